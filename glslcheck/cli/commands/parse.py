"""glslcheck parse PATH... [--print] [--ast]: parse shaders and report syntax errors.

Each PATH is a tab file or a folder of tabs (see glslcheck/shadertoy/sources.py). Every pass is
parsed as Shadertoy compiles it: the Common tab followed by the pass's tab. Exit 0 when all parse,
1 on syntax errors, 2 on usage or I/O errors.
"""

from __future__ import annotations

import sys

from ...base.diagnostics import GlslError, format_text
from ...shadertoy.sources import find_shaders


def add_arguments(p) -> None:
    p.add_argument("paths", nargs="+", metavar="PATH", help="tab files or folders of tab files")
    p.add_argument(
        "--print", dest="print_", action="store_true", help="print each program back as GLSL"
    )
    p.add_argument(
        "--ast", action="store_true", help="print each program's syntax tree with locations"
    )
    p.add_argument("-q", "--quiet", action="store_true", help="print only errors")


def passes(shader):
    """The passes of a shader: each tab but Common (which rides along), or Common alone."""
    tabs = [t for t in shader.tabs if t != "Common"]
    return tabs or ["Common"]


def run(args) -> int:
    from ...frontend.parser import parse_shader
    from ...frontend.printer import to_glsl
    from ...frontend.syntax import format_tree

    shaders = find_shaders(args.paths)
    failed = 0
    count = 0
    for shader in shaders:
        for tab in passes(shader):
            count += 1
            try:
                result = parse_shader(shader, tab)
            except GlslError as e:
                failed += 1
                for d in e.diagnostics:
                    print(format_text(d), file=sys.stderr)
                continue
            if args.print_:
                print(to_glsl(result.ast), end="")
            if args.ast:
                print(format_tree(result.ast))
    if not args.quiet:
        ok = count - failed
        print(
            f"parsed {ok} of {count} program{'s' if count != 1 else ''}"
            + (f", {failed} with errors" if failed else ""),
            file=sys.stderr,
        )
    return 1 if failed else 0
