"""glslcheck render SHADER [-o out.png|out.npy|anim.gif] [--size WxH] [--time T] [--frame N]
[--mouse X,Y,Z,W] [--date Y,M,D,S] [--precision float16|float32|float64] [--samples N]
[--backend numpy|gl|webgl] [--stats] [--frames N --fps F]: render a shader's Image tab.

The NumPy backend (default) renders on the CPU; --backend gl uses the OpenGL driver (Mesa
llvmpipe); --backend webgl renders as Shadertoy's page does, with WebGL 2 in headless Chromium
(ANGLE on SwiftShader). Inputs: iResolution from --size (default 800x450), iTime --time (0), iFrame --frame
(0), iMouse --mouse, iDate --date (year, month 0-11, day, seconds; default 2026-01-01 00:00),
iTimeDelta 1/60 and iFrameRate 60 (with --frames: 1/F and F). fragCoord is the pixel centre with
the origin at the bottom left; the image's first row is its top. Alpha is 1, as on Shadertoy.

Output: .png (values clamped to [0, 1], *255 + 0.5 rounded down), .npy (the float32 array,
unclamped) or, with --frames N, a .gif animation of N frames at --fps F (iTime = i / F,
iFrame = --frame + i) with a progress bar on stderr. --stats prints how many lanes (pixels)
ran each function, branch and loop body (NumPy backend).

Exit 0 when rendered, 1 on a shader error (file:line:col on stderr), 2 on usage or I/O errors.
"""

from __future__ import annotations

import argparse
import math
import sys

from ..diagnostics import InputError


def _floats(text: str, count: int, what: str) -> tuple[float, ...]:
    try:
        values = tuple(float(v) for v in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"{what} takes {count} numbers separated by commas, not {text!r}") from None
    if len(values) != count or not all(math.isfinite(v) for v in values):
        raise argparse.ArgumentTypeError(f"{what} takes {count} finite numbers separated by commas, not {text!r}")
    return values


def size_arg(text: str) -> tuple[int, int]:
    parts = text.lower().split("x")
    try:
        w, h = (int(p) for p in parts)
    except ValueError:
        raise argparse.ArgumentTypeError(f"--size takes WIDTHxHEIGHT, e.g. 800x450, not {text!r}") from None
    if not (1 <= w <= 16384 and 1 <= h <= 16384):
        raise argparse.ArgumentTypeError(f"--size must be between 1x1 and 16384x16384, not {text!r}")
    from ..verify import check_pixels

    try:
        check_pixels(w, h, text)
    except ValueError as e:
        raise argparse.ArgumentTypeError(f"--size takes {e}") from None
    return w, h


def _positive_int(text: str) -> int:
    try:
        v = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number, not {text!r}") from None
    if v < 1:
        raise argparse.ArgumentTypeError(f"expected a number of at least 1, not {text!r}")
    return v


def _samples(text: str) -> int:
    v = _positive_int(text)
    if math.isqrt(v) ** 2 != v:
        raise argparse.ArgumentTypeError(f"--samples must be a perfect square (1, 4, 9, 16, ...), not {v}")
    return v


def _number(text: str) -> float:
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, not {text!r}") from None
    if not math.isfinite(v):
        raise argparse.ArgumentTypeError(f"expected a finite number, not {text!r}")
    return v


def add_arguments(p) -> None:
    p.add_argument("path", metavar="SHADER", help="a tab file or a folder of tab files")
    p.add_argument("-o", "--output", default="out.png", metavar="FILE",
                   help="out.png, out.npy, or anim.gif with --frames (default out.png)")
    p.add_argument("--size", type=size_arg, default=(800, 450), metavar="WxH", help="default 800x450")
    p.add_argument("--time", type=_number, default=0.0, metavar="T", help="iTime in seconds (default 0)")
    p.add_argument("--frame", type=int, default=0, metavar="N", help="iFrame (default 0)")
    p.add_argument("--mouse", type=lambda t: _floats(t, 4, "--mouse"), default=(0.0, 0.0, 0.0, 0.0),
                   metavar="X,Y,Z,W", help="iMouse (default 0,0,0,0)")
    p.add_argument("--date", type=lambda t: _floats(t, 4, "--date"), default=None, metavar="Y,M,D,S",
                   help="iDate: year, month 0-11, day, seconds since midnight (default 2026,0,1,0)")
    p.add_argument("--precision", choices=("float16", "float32", "float64"), default="float32",
                   help="float type inside the shader (NumPy backend; default float32 = highp)")
    p.add_argument("--samples", type=_samples, default=1, metavar="N", help="samples per pixel, a square (default 1)")
    p.add_argument("--backend", choices=("numpy", "gl", "webgl"), default="numpy", help="default numpy")
    p.add_argument("--stats", action="store_true", help="print the lanes that ran each function and branch")
    p.add_argument("--frames", type=_positive_int, default=None, metavar="N", help="render an animation of N frames")
    p.add_argument("--fps", type=_number, default=60.0, metavar="F", help="frames per second of --frames (default 60)")


def run(args) -> int:
    from .. import api
    from ..numpy_backend.program import save_image

    out = args.output
    lower = out.lower()
    if args.frames is None and not lower.endswith((".png", ".npy")):
        raise InputError(f"{out}: error: the output must end in .png or .npy (or .gif with --frames)")
    if args.frames is not None and not lower.endswith(".gif"):
        raise InputError(f"{out}: error: --frames writes a .gif animation; name the output *.gif")
    if args.fps <= 0:
        raise InputError("error: --fps must be positive")
    if args.stats and args.backend != "numpy":
        raise InputError("error: --stats needs --backend numpy")
    if args.backend != "numpy" and args.precision != "float32":
        raise InputError(f"error: the {args.backend.upper()} backend renders in float32 only; "
                         "drop --precision or use --backend numpy")
    prog = api.compile(args.path, backend=args.backend)
    common = dict(size=args.size, mouse=args.mouse, date=args.date, precision=args.precision, samples=args.samples)
    if args.frames is None:
        img = prog.render(time=args.time, frame=args.frame, stats=args.stats, **common)
        try:
            save_image(img, out)
        except OSError as e:
            raise InputError(f"{out}: error: cannot write the image ({e.strerror or e})") from None
        if args.stats:
            print(prog.format_stats())
        return 0
    return _animation(prog, args, common)


def _animation(prog, args, common) -> int:
    import numpy as np
    from PIL import Image

    frames = []
    n = args.frames
    show = sys.stderr.isatty() or n > 1
    for i in range(n):
        t = args.time + i / args.fps
        img = prog.render(time=t, frame=args.frame + i, time_delta=1.0 / args.fps, frame_rate=args.fps,
                          stats=args.stats, **common)
        with np.errstate(invalid="ignore"):
            q = np.floor(np.clip(np.nan_to_num(img[..., :3], nan=0.0), 0.0, 1.0) * 255.0 + 0.5).astype(np.uint8)
        frames.append(Image.fromarray(q, "RGB"))
        if show:
            filled = 24 * (i + 1) // n
            sys.stderr.write(f"\rrender [{'#' * filled}{'.' * (24 - filled)}] {i + 1}/{n} t={t:.3f}s")
            sys.stderr.flush()
    if show:
        sys.stderr.write("\n")
    try:
        frames[0].save(args.output, save_all=True, append_images=frames[1:], duration=max(int(round(1000 / args.fps)), 10),
                       loop=0)
    except OSError as e:
        raise InputError(f"{args.output}: error: cannot write the animation ({e.strerror or e})") from None
    if args.stats:
        print(prog.format_stats())
    return 0
