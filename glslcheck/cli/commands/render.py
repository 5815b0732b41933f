"""glslcheck render SHADER [-o out.png|out.npy|anim.gif] [--size WxH] [--time T] [--frame N]
[--mouse X,Y,Z,W] [--date Y,M,D,S] [--precision float16|float32|float64] [--samples N]
[--backend auto|numpy|gl|webgl|compiled] [--stats] [--frames N --fps F] [--pass TAB]: render a
shader's Image tab (or, with --pass "Buffer A", a buffer). Buffers and channels.json: see
glslcheck/shadertoy/channels.py; --frame N of a multipass shader runs frames 0..N.

By default (--backend auto) the NumPy backend renders on the CPU and hands the frames to the
compiled engine once they have cost its compile and it gives the same bits, faster
(glslcheck/backends/tiered.py); --backend numpy keeps the NumPy backend; --backend gl uses the
OpenGL driver (Mesa llvmpipe); --backend webgl renders as Shadertoy's page does, with WebGL 2 in
headless Chromium (ANGLE on SwiftShader); --backend compiled compiles each pixel's program with
numba (the extra glslcheck[jit]; an Image tab without channels, float32:
glslcheck/compiled_backend). Inputs: iResolution from --size (default 800x450), iTime --time
(0), iFrame --frame (0), iMouse --mouse, iDate --date (year, month 0-11, day, seconds; default
2026-01-01 00:00), iTimeDelta 1/60 and iFrameRate 60 (with --frames: 1/F and F). fragCoord is
the pixel centre with the origin at the bottom left; the image's first row is its top. Alpha is
1, as on Shadertoy.

Output: .png (values clamped to [0, 1], *255 + 0.5 rounded down), .npy (the float32 array,
unclamped) or, with --frames N, a .gif animation of N frames at --fps F (iTime = --time + i / F,
iFrame = --frame + i) with a progress bar on stderr; its frames are written as they are rendered.
Every output is written to a temporary file and renamed into place, so a failure or Ctrl-C
leaves an existing file as it was. --stats prints how many lanes (pixels) ran each function,
branch and loop body (NumPy backend). The limits of every value: glslcheck/base/limits.py.

Exit 0 when rendered, 1 on a shader error (file:line:col on stderr), 2 on usage or I/O errors.
"""

from __future__ import annotations

import sys

from ...backends import registry
from ...base import limits
from ...base.diagnostics import InputError
from ...base.precision import PRECISIONS
from . import args as cli_args


def add_arguments(p) -> None:
    p.add_argument("path", metavar="SHADER", help="a tab file or a folder of tab files")
    p.add_argument(
        "-o",
        "--output",
        default="out.png",
        metavar="FILE",
        help="out.png, out.npy, or anim.gif with --frames (default out.png)",
    )
    cli_args.add_uniform_arguments(p)
    p.add_argument(
        "--precision",
        choices=PRECISIONS,
        default="float32",
        help="float type inside the shader (NumPy backend; default float32 = highp)",
    )
    p.add_argument(
        "--samples",
        type=cli_args.arg(limits.parse_samples),
        default=1,
        metavar="N",
        help="samples per pixel, a square (default 1)",
    )
    p.add_argument(
        "--backend",
        choices=registry.names(),
        default="auto",
        help="default auto: the NumPy engine, then the compiled engine once that pays and gives "
        "the same bits (backends/tiered.py); numpy; compiled: by numba, per pixel, then 8 pixels "
        "in lockstep once that pays",
    )
    p.add_argument(
        "--stats", action="store_true", help="print the lanes that ran each function and branch"
    )
    p.add_argument(
        "--frames",
        type=cli_args.arg(limits.parse_frames),
        default=None,
        metavar="N",
        help="render an animation of N frames",
    )
    p.add_argument(
        "--fps",
        type=cli_args.arg(limits.parse_fps),
        default=60.0,
        metavar="F",
        help="frames per second of --frames (default 60)",
    )
    p.add_argument(
        "--pass",
        dest="pass_name",
        default="Image",
        metavar="TAB",
        help='the pass to write, e.g. "Buffer A" (default Image; buffers run frames 0..N, '
        "shadertoy/channels.py)",
    )


def run(args) -> int:
    from ...base.images import IMAGE_SUFFIXES, check_output, save_image

    out = args.output
    if args.frames is None:
        check_output(out, IMAGE_SUFFIXES, "output (or a .gif with --frames)")
    else:
        check_output(out, (".gif",), "output of --frames (an animation)")
    try:
        limits.check_schedule(args.frame, args.frames, args.fps, args.time)
    except ValueError as e:
        raise InputError(f"glslcheck render: error: {e}") from None
    backend = registry.get(args.backend)
    if args.stats and not backend.lane_stats:
        raise InputError("error: --stats needs --backend numpy")
    if args.precision not in backend.precisions:
        raise InputError(
            f"error: the {args.backend.upper()} backend renders in float32 only; "
            "drop --precision or use --backend numpy"
        )
    prog = registry.compile(args.path, backend=args.backend, output=args.pass_name)
    cli_args.refuse_to_overwrite_inputs([out], [prog.shader], "output")
    common = dict(
        size=args.size,
        mouse=args.mouse,
        date=args.date,
        precision=args.precision,
        samples=args.samples,
    )
    if args.frames is None:
        img = prog.render(time=args.time, frame=args.frame, stats=args.stats, **common)
        save_image(img, out)  # atomic: an error or Ctrl-C leaves an existing file as it was
        if args.stats:
            print(prog.format_stats())
        _nan_note(img, args)
        return 0
    return _animation(prog, args, common)


def _nan_note(img, args) -> None:
    import numpy as np

    nan = int(np.isnan(img).any(axis=-1).sum())
    if nan:
        from .probe import nan_hint

        print(
            f"{args.path}: note: {nan_hint(args.path, nan, args.size, args.time)}", file=sys.stderr
        )


def _animation(prog, args, common) -> int:
    """Render and write the frames one at a time (GifWriter): memory does not grow with --frames."""
    from ...base.images import GifWriter

    n = args.frames
    show = sys.stderr.isatty() or n > 1
    with GifWriter(args.output, args.fps) as gif:
        for i in range(n):
            t = args.time + i / args.fps
            img = prog.render(
                time=t,
                frame=args.frame + i,
                time_delta=1.0 / args.fps,
                frame_rate=args.fps,
                stats=args.stats,
                **common,
            )
            gif.add(img)
            if show:
                filled = 24 * (i + 1) // n
                sys.stderr.write(
                    f"\rrender [{'#' * filled}{'.' * (24 - filled)}] {i + 1}/{n} t={t:.3f}s"
                )
                sys.stderr.flush()
        if show:
            sys.stderr.write("\n")
    if args.stats:
        print(prog.format_stats())
    return 0
