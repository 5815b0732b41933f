"""glslcheck report SHADER... [-o report.html] [--size WxH] [--time T] [--no-webgl]
[--bench-size WxH] [--bench-runs N] [--no-bench]: one self-contained HTML page: the source with
the check and lint findings under their lines, the render of each backend side by side (NumPy,
GL = Mesa llvmpipe, WebGL = ANGLE on SwiftShader in headless Chromium), the difference heat map
of every pair with verify's numbers and verdict, the NaN/Inf pixels' origins (probe --nan) where
a render has any, and bench's accuracy/time table and plot at a small size.

Each SHADER is a tab file or a folder of tabs; several shaders (e.g. lab_shaders/) get an index
at the top. Inline CSS, images as data URIs: the page needs no network. A backend that cannot run
here is named with the reason; the page is still written (see glslcheck/verification/report.py).

Exit 0 when the page is written and every shader is clean and matches, 1 when a shader has
errors or a mismatch (the page says which), 2 on usage or I/O errors.
"""

from __future__ import annotations

import sys

from ...base import limits
from . import args as cli_args


def _parse_bench_runs(text: str) -> int:
    return limits.in_range(
        limits.whole_number(text, "--bench-runs"), 1, limits.MAX_RUNS, "--bench-runs", text
    )


def add_arguments(p) -> None:
    p.add_argument("paths", nargs="+", metavar="SHADER", help="tab files or folders of tab files")
    p.add_argument(
        "-o", "--output", default="report.html", metavar="HTML", help="default report.html"
    )
    p.add_argument(
        "--size",
        type=cli_args.arg(limits.parse_size),
        default=(320, 180),
        metavar="WxH",
        help="render size in pixels (default 320x180)",
    )
    p.add_argument(
        "--time",
        type=cli_args.arg(limits.parse_time),
        default=0.0,
        metavar="T",
        help="iTime in seconds (default 0)",
    )
    p.add_argument(
        "--no-webgl", action="store_true", help="leave out the WebGL backend (headless Chromium)"
    )
    p.add_argument(
        "--bench-size",
        type=cli_args.arg(limits.parse_size),
        default=(64, 36),
        metavar="WxH",
        help="render size of the accuracy/time table (glslcheck bench; default 64x36)",
    )
    p.add_argument(
        "--bench-runs",
        type=cli_args.arg(_parse_bench_runs),
        default=3,
        metavar="N",
        help="timed rounds of the table, median taken (default 3)",
    )
    p.add_argument(
        "--no-bench", action="store_true", help="leave out the accuracy/time table and plot"
    )


def run(args) -> int:
    from ...base.images import atomic_write, check_output
    from ...verification.report import DEFAULT_BACKENDS, build_report

    check_output(args.output, (".html", ".htm"), "report (an HTML page)")
    backends = tuple(b for b in DEFAULT_BACKENDS if not (args.no_webgl and b == "webgl"))
    page = build_report(
        args.paths,
        size=args.size,
        time=args.time,
        backends=backends,
        bench=None if args.no_bench else args.bench_size,
        bench_runs=args.bench_runs,
    )
    # a file name's undecodable bytes show as `\\udcXX` in the page
    with (
        atomic_write(args.output, "report") as tmp,
        open(tmp, "w", encoding="utf-8", errors="backslashreplace") as f,
    ):
        f.write(page.html)
    bad = [r.name for r in page.shaders if not r.ok]
    print(
        f"{args.output}: {len(page.shaders)} shader{'s' * (len(page.shaders) != 1)}"
        + (f", {len(bad)} with problems: {', '.join(bad)}" if bad else ", all clean and matching"),
        file=sys.stderr,
    )
    return 1 if bad else 0
