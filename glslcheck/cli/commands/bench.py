"""glslcheck bench SHADER... [--size WxH] [--runs N] [--time T] [--format text|json]
[--plot out.png] [--webgl] [--backend compiled]: render time against error for GL and the CPU
precision modes.

For each SHADER (a tab file or a folder of tabs) the Image tab is rendered 12 ways: by the
OpenGL driver (Mesa llvmpipe, highp = float32) and by the default CPU program at float16, float32
and float64, each at 1, 4 and 16 samples per pixel (the NumPy backend, whose float32 frames move
to the compiled engine once they have cost its compile, where that gives the same bits:
glslcheck/backends/tiered.py; the table's backend column and the JSON's engine say which engine
rendered the timed rounds) (--webgl adds WebGL 2 in headless Chromium at
each, in the plot's purple; --backend compiled adds the compiled engine, glslcheck/compiled_backend,
at each, in brown: it needs numba, the extra glslcheck[jit], exit 2 with the pip line without
it). Each is timed (median of --runs rounds after a warm-up render; the rounds go round-robin
over the configurations so machine load falls on all alike) and compared with the reference, NumPy
float64 at 16 samples per pixel.

Error is over RGB as the screen shows it (NaN as 0, +Inf as 1, clamped to [0, 1]; NaN/Inf in
one image only counts as 1): max and mean absolute error, PSNR, and the pixels where some
channel differs by more than 1/255 (one 8-bit display step). "x GL@1" (ratio_to_gl) is a
configuration's time over the time of GL at 1 sample of the same shader in the same run.
The text table marks the Pareto front (no configuration both faster and closer, by mean
error); --plot draws time against mean error on log axes, one panel per shader, with the front.

--format json prints exactly {"rows": [{"shader", "backend", "precision", "samples",
"median_ms", "ratio_to_gl", "max_abs_error", "mean_abs_error", "psnr_db",
"pixels_over_1_255", "engine"}, ...]} (psnr_db null when infinite, i.e. for the reference itself;
backend "auto" for the default CPU program; engine "numpy", "compiled pixel", "compiled lanes8",
"numpy then compiled lanes8" when it moved during the rounds, or the backend's name).
A progress bar runs on stderr when it is a terminal (--progress forces it).

Exit 0 when every shader was measured, 1 when a shader has GLSL errors (the others are still
measured), 2 on usage or I/O errors, or when no OpenGL context can be created.
"""

from __future__ import annotations

import argparse
import json
import sys

from ...backends import registry
from ...base import limits
from ...base.diagnostics import GlslError, format_text
from ...base.images import check_output
from ...shadertoy.sources import find_shaders
from ...verification.bench import (
    DEFAULT_RUNS,
    DEFAULT_SIZE,
    bench_shader,
    configurations,
    format_table,
    write_plot,
)
from ...verification.verify import Progress
from . import args as cli_args


class _BenchProgress(Progress):
    """verify's progress bar, named 'bench'."""

    NAME = "bench"


def add_arguments(p) -> None:
    p.add_argument("paths", nargs="+", metavar="SHADER", help="tab files or folders of tab files")
    w, h = DEFAULT_SIZE
    p.add_argument(
        "--size",
        type=cli_args.arg(limits.parse_size),
        default=DEFAULT_SIZE,
        metavar="WxH",
        help=f"render size in pixels (default {w}x{h})",
    )
    p.add_argument(
        "--runs",
        type=cli_args.arg(limits.parse_runs),
        default=DEFAULT_RUNS,
        metavar="N",
        help="timed renders per configuration after one warm-up; "
        f"the median is reported (default {DEFAULT_RUNS})",
    )
    p.add_argument(
        "--time",
        type=cli_args.arg(limits.parse_time),
        default=0.0,
        metavar="T",
        help="iTime in seconds (default 0)",
    )
    p.add_argument(
        "--format", choices=("text", "json"), default="text", help="output format (default text)"
    )
    p.add_argument("--plot", metavar="PNG", help="write the time-against-error plot")
    p.add_argument(
        "--webgl",
        action="store_true",
        help="also time WebGL 2 in headless Chromium (ANGLE on SwiftShader) at each sample count",
    )
    p.add_argument(
        "--backend",
        choices=("compiled",),
        action="append",
        default=[],
        help="also time this engine at each sample count: compiled (per pixel, by numba)",
    )
    p.add_argument(
        "--progress",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="progress bar on stderr (default: when stderr is a terminal)",
    )


def run(args) -> int:
    if args.plot:
        check_output(args.plot, (".png",), "plot")  # before the minutes of measuring, not after
    compiled = "compiled" in args.backend
    for name in args.backend:
        registry.get(
            name
        ).require()  # InputError (exit 2) with the install line, before anything is measured
    shaders = find_shaders(args.paths)
    per_shader = len(configurations(webgl=args.webgl, compiled=compiled)) * (args.runs + 1)
    show = args.progress if args.progress is not None else sys.stderr.isatty()
    progress = _BenchProgress(len(shaders) * per_shader, sys.stderr, enabled=bool(show))

    rows = []
    glsl_errors = 0
    try:
        for index, shader in enumerate(shaders):
            try:
                rows += bench_shader(
                    shader,
                    size=args.size,
                    runs=args.runs,
                    time=args.time,
                    step=progress.step,
                    webgl=args.webgl,
                    compiled=compiled,
                )
            except GlslError as e:
                progress.finish()
                glsl_errors += 1
                for d in e.diagnostics:
                    print(format_text(d), file=sys.stderr)
                progress.done = (index + 1) * per_shader
    finally:
        progress.finish()

    if args.plot and rows:
        write_plot(
            rows, args.plot, title=_plot_title(args)
        )  # atomic; InputError (exit 2) on failure

    if args.format == "json":
        print(json.dumps({"rows": [r.to_json() for r in rows]}))
    elif rows:
        sys.stdout.write(format_table(rows, args.size, args.runs, args.time))
    return 1 if glsl_errors else 0


def _plot_title(args) -> str:
    w, h = args.size
    return (
        f"render time against error at {w}x{h}, iTime {args.time:g} "
        f"(reference: NumPy float64, 16 samples; median of {args.runs})"
    )
