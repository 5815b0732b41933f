"""glslcheck transpile SHADER [-o shader.py]: write the NumPy Python module of a shader.

The module has one Python function per GLSL function reachable from mainImage, each statement
preceded by a `# line N: <GLSL>` comment, and runs on its own with NumPy and glslcheck's
runtime: `python shader.py -o out.png --size 800x450 --time 1.5`. Without -o the module is
printed on stdout. Exit 0 when written, 1 on a shader error (or a construct the NumPy backend
does not support yet, such as texture lookups), 2 on usage or I/O errors.
"""

from __future__ import annotations

import sys


def add_arguments(p) -> None:
    p.add_argument("path", metavar="SHADER", help="a tab file or a folder of tab files")
    p.add_argument(
        "-o",
        "--output",
        default=None,
        metavar="FILE",
        help="write the module here (default: stdout)",
    )


def run(args) -> int:
    from ...backends.numpy_engine.transpile import transpile_shader
    from ...shadertoy.sources import load_shader

    shader = load_shader(args.path)
    result = transpile_shader(shader)
    if args.output is None:
        sys.stdout.write(result.source)
        return 0
    from ...base.images import atomic_write
    from .args import refuse_to_overwrite_inputs

    refuse_to_overwrite_inputs([args.output], [shader], "module")
    with atomic_write(
        args.output, "module"
    ) as tmp:  # InputError (exit 2) when it cannot be written
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(result.source)
    return 0
