"""glslcheck check PATH...: parse and type-check shaders (GLSL ES 3.00 and Shadertoy rules).

Each PATH is a tab file or a folder of tabs (see glslcheck/shadertoy/sources.py). Every pass is
checked as Shadertoy compiles it: the Common tab alone (only iDate and iSampleRate declared), then
Common followed by each pass tab (Image, Buffer A..D). An error in the Common tab is reported once.
With --webgl each of those programs is also compiled by WebGL 2 in headless Chromium (ANGLE,
the compiler Shadertoy's page uses) and ANGLE's errors are reported in the user's tab and line
(rule webgl-compile, messages starting "WebGL:"); a program ANGLE rejects counts as an error.
Exit 0 when every program is clean (warnings allowed), 1 on errors, 2 on usage or I/O errors.
"""

from __future__ import annotations

import sys

from ...base.diagnostics import GlslError, format_text
from ...shadertoy.sources import find_shaders
from ...shadertoy.wrapper import PASS_TABS

_CHECKED_TABS = (*PASS_TABS, "GLSL")


def add_arguments(p) -> None:
    p.add_argument("paths", nargs="+", metavar="PATH", help="tab files or folders of tab files")
    p.add_argument("-q", "--quiet", action="store_true", help="print only errors and warnings")
    p.add_argument("--no-warnings", action="store_true", help="do not print warnings")
    p.add_argument(
        "--webgl",
        action="store_true",
        help="also compile each program with WebGL 2 in headless Chromium (ANGLE) and report its "
        "errors",
    )


def passes(shader) -> list[str]:
    """Common alone first (when present), then every pass tab present."""
    out = ["Common"] if "Common" in shader.tabs else []
    return out + [t for t in _CHECKED_TABS if t in shader.tabs]


def run(args) -> int:
    from ...frontend.parser import parse_shader
    from ...semantics import check

    shaders = find_shaders(args.paths)
    failed = 0
    count = 0
    for shader in shaders:
        seen: set[tuple] = set()
        for tab in passes(shader):
            count += 1
            try:
                result = parse_shader(shader, tab)
                diagnostics = check(result, tab, collect=True).diagnostics
            except GlslError as e:
                diagnostics = e.diagnostics
            if args.webgl:  # ANGLE's verdict on the same program (glslcheck/webgl_backend)
                from ...backends.webgl import webgl_diagnostics

                diagnostics = list(diagnostics) + webgl_diagnostics(shader, tab)
            errors = 0
            for d in diagnostics:
                key = (str(d.loc), d.message, d.severity)
                if key in seen:
                    errors += d.severity == "error"
                    continue
                seen.add(key)
                if d.severity == "error":
                    errors += 1
                elif args.no_warnings:
                    continue
                print(format_text(d), file=sys.stderr)
            failed += bool(errors)
    if not args.quiet:
        ok = count - failed
        print(
            f"checked {count} program{'s' if count != 1 else ''}: {ok} clean"
            + (f", {failed} with errors" if failed else ""),
            file=sys.stderr,
        )
    return 1 if failed else 0
