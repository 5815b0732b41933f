"""glslcheck verify SHADER... [--size WxH] [--time T | --times T,T,... | --frames N [--fps F]]
[--frame N] [--mouse X,Y,Z,W] [--precision float32|float16|float64] [--samples N]
[--diff diff.png] [--format text|json] [--against gl|webgl]: render on the CPU and with OpenGL
and compare.

Each SHADER is a tab file or a folder of tabs (see glslcheck/shadertoy/sources.py). Its Image tab is
rendered by the default CPU program and by the OpenGL driver (Mesa llvmpipe) with the same
uniforms. The default CPU program is the NumPy backend, whose frames move to the compiled engine
once they have cost its compile, where that gives the same bits (glslcheck/backends/tiered.py);
the text names the side under test after the engine of each frame ("numpy", or "compiled" for a
frame of the compiled engine). The two float images are compared
and the two float images are compared by the tolerance model of glslcheck/verification/compare.py:
max and mean abs error, PSNR, pixels over tolerance ("mismatched"), edge pixels (differences a
sub-pixel shift explains), NaN/Inf counts in each image, and where the differences lie (bounding box
and worst pixels, with fragCoord).

--against webgl compares with WebGL 2 in headless Chromium (ANGLE on SwiftShader, as Shadertoy's
page renders; glslcheck/webgl_backend). Each frame is also rendered with GL: a pixel where the two
drivers differ depends on the driver, and there NumPy need only match the closer of the two
("driver-dependent" in the report; glslcheck/verification/drivers.py). `--backends gl,webgl`
compares the two drivers with each other; `--backends compiled,gl` verifies the compiled engine
(glslcheck/compiled_backend: float32, numba needed, exit 2 with the pip line without it).

Frames: one at iTime 0 by default; --time T; --times 0,0.5,1 (one frame each, iFrame = --frame);
--frames N with --fps F (iFrame = --frame + i, iTime = iFrame / F, iTimeDelta = 1/F; Buffer A-D
carried from frame to frame, see glslcheck/shadertoy/channels.py). Several
frames show a progress bar on stderr when it is a terminal (--progress forces it).

--format json prints exactly {"match", "verdict", "size", "max_abs_error", "mean_abs_error",
"psnr_db", "mismatched_pixels", "edge_pixels", "nan_numpy", "nan_gl", "unstable_pixels",
"unstable_lines", "undefined_pixels", "undefined_lines", "driver", "engine"} for one frame
(psnr_db is null for identical images; verdict is "match", "match-unstable", "undefined" or
"mismatch"; unstable pixels are those where both float32 renders are far from the float64
reference, see verification/compare.py; unstable_lines names the statements where they lose
precision, traced by glslcheck probe on a sample of them; undefined pixels are those over
tolerance whose colour depends on a value the shader leaves undefined (an out parameter, a
local or a global read before it is written, an operation on constants outside its range:
`glslcheck check` warns at each), found by rendering the NumPy side with other values at those reads
(verification/verify.py, UndefinedSide); they are counted apart from the mismatches, and the
verdict is "undefined" (match false, exit 1: the shader is at fault, not the renderer) when they
are the only difference; undefined_lines is [{"file", "line", "column", "code", "kind",
"pixels"}] of the reads, kind one of out-parameter, out-parameter-unwritten (at the return that
leaves it so), uninitialized-local, uninitialized-global, division-by-zero, shift-out-of-range,
conversion-out-of-range, domain; driver is {"renderer", "mesa", "emulated"} of the GL side,
emulated false when the NumPy backend's bit-exact emulation was copied from another driver than
this one, llvmpipe of Mesa 22.3: a mismatch then also says so in the text output, since it may
be the driver's; engine is the engine that rendered the side under test: "numpy", "compiled
pixel" or "compiled lanes8" for the default CPU program), or a JSON list of such objects, in
order (shader by shader, then frame by frame), when more than one frame is verified. --diff
diff.png writes the heat map of the differences (diff-0.png, diff-1.png, ... for several
frames).

Exit 0 when every frame matches, 1 on a mismatch, undefined pixels or a GLSL error (diagnostics
as file:line:col on stderr), 2 on usage or I/O errors, or when no OpenGL context can be created.
"""

from __future__ import annotations

import argparse
import json
import math
import sys

from ...backends import registry
from ...base import limits
from ...base.diagnostics import GlslError, InputError, format_text
from ...base.images import check_output
from ...base.precision import PRECISIONS
from ...shadertoy.sources import find_shaders
from ...verification.verify import (
    BACKENDS,
    DEFAULT_FPS,
    FrameResult,
    Progress,
    diff_paths,
    frame_specs,
    verify_frames,
)
from . import args as cli_args

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator


def _backends(text: str) -> tuple[str, str]:
    names = tuple(t.strip() for t in text.split(","))
    if len(names) != 2 or not all(n in registry.names() for n in names):
        raise ValueError(
            f"--backends takes two of {', '.join(registry.names())} separated by a comma, "
            f"not {text!r}"
        )
    return names


def add_arguments(p) -> None:
    p.add_argument("paths", nargs="+", metavar="SHADER", help="tab files or folders of tab files")
    p.add_argument(
        "--size",
        type=cli_args.arg(limits.parse_size),
        default=(800, 450),
        metavar="WxH",
        help="render size in pixels (default 800x450)",
    )
    when = p.add_mutually_exclusive_group()
    when.add_argument(
        "--time",
        type=cli_args.arg(limits.parse_time),
        metavar="T",
        help="iTime in seconds (default 0)",
    )
    when.add_argument(
        "--times",
        type=cli_args.arg(limits.parse_times),
        metavar="T,T,...",
        help="verify one frame per time",
    )
    when.add_argument(
        "--frames",
        type=cli_args.arg(limits.parse_frames),
        metavar="N",
        help="verify N consecutive frames at --fps",
    )
    p.add_argument(
        "--fps",
        type=cli_args.arg(limits.parse_fps),
        default=None,
        metavar="F",
        help="frames per second: iFrameRate, iTimeDelta = 1/F and the --frames clock (default "
        f"{DEFAULT_FPS:g})",
    )
    p.add_argument(
        "--frame",
        type=cli_args.arg(limits.parse_frame),
        default=0,
        metavar="N",
        help="iFrame (with --frames: the first frame) (default 0)",
    )
    p.add_argument(
        "--mouse",
        type=cli_args.arg(limits.parse_mouse),
        default=(0.0, 0.0, 0.0, 0.0),
        metavar="X,Y,Z,W",
        help="iMouse in pixels (default 0,0,0,0)",
    )
    p.add_argument(
        "--date",
        type=cli_args.arg(limits.parse_date),
        default=None,
        metavar="Y,M,D,S",
        help="iDate: year, month 0-11, day, seconds since midnight (default 2026,0,1,0)",
    )
    p.add_argument(
        "--precision",
        choices=PRECISIONS,
        default="float32",
        help="float mode of the NumPy backend; OpenGL is always highp float32 (default float32)",
    )
    p.add_argument(
        "--samples",
        type=cli_args.arg(limits.parse_samples),
        default=1,
        metavar="N",
        help="samples per pixel on both sides, a perfect square (default 1)",
    )
    p.add_argument(
        "--diff",
        metavar="PNG",
        help="write the difference heat map (diff-<i>.png for several frames)",
    )
    p.add_argument(
        "--format", choices=("text", "json"), default="text", help="output format (default text)"
    )
    p.add_argument(
        "--progress",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="progress bar on stderr for several frames (default: when stderr is a terminal)",
    )
    p.add_argument(
        "--against",
        choices=("gl", "webgl"),
        default=None,
        help="the reference NumPy is compared with: gl (Mesa llvmpipe, default) or webgl "
        "(headless Chromium, ANGLE on SwiftShader)",
    )
    p.add_argument(
        "--backends",
        type=cli_args.arg(_backends),
        default=None,
        metavar="A,B",
        help="compare two other backends, e.g. gl,webgl (the drivers with each other)",
    )


def _frame_count(args) -> int:
    if args.frames is not None:
        return args.frames
    if args.times is not None:
        return len(args.times)
    return 1


def run(args) -> int:
    if args.diff:
        check_output(args.diff, (".png",), "diff image")
    try:
        limits.check_schedule(args.frame, args.frames, args.fps or DEFAULT_FPS)
        frame_specs(args.time, args.times, args.frames, args.fps, args.frame)  # conflicting options
    except ValueError as e:
        raise InputError(f"glslcheck verify: error: {e}") from None
    if args.against and args.backends:
        raise InputError("glslcheck verify: error: give --against or --backends, not both")
    args.backends = args.backends or ((BACKENDS[0], args.against) if args.against else BACKENDS)
    for (
        name
    ) in args.backends:  # a driver's side is always its highp; an engine of ours renders as told
        backend = registry.get(name)
        if not backend.driver and args.precision not in backend.precisions:
            raise InputError(
                f"glslcheck verify: error: {backend.called} renders in "
                f"{' and '.join(backend.precisions)} only; drop --precision"
            )
    shaders = find_shaders(args.paths)
    total = len(shaders) * _frame_count(args)
    if args.diff:
        cli_args.refuse_to_overwrite_inputs(diff_paths(args.diff, total), shaders, "diff image")
    show = args.progress if args.progress is not None else (total > 1 and sys.stderr.isatty())
    progress = Progress(total, sys.stderr, enabled=bool(show) and total > 1)

    results = []
    glsl_errors = 0
    paths = iter(diff_paths(args.diff, total)) if args.diff else None
    try:
        for index, shader in enumerate(shaders):
            try:
                options = dict(
                    size=args.size,
                    time=args.time,
                    times=args.times,
                    frames=args.frames,
                    fps=args.fps,
                    frame=args.frame,
                    mouse=args.mouse,
                    date=args.date,
                    precision=args.precision,
                    samples=args.samples,
                    progress=progress,
                )
                frames: Iterator[FrameResult]
                if args.against == "webgl":  # NumPy vs WebGL, driver-dependent pixels apart
                    from ...verification.drivers import verify_against_webgl

                    frames = verify_against_webgl(shader, **options)
                else:
                    frames = verify_frames(shader, backends=args.backends, **options)
                for result in frames:
                    _keep(result, paths)
                    results.append(result)
            except GlslError as e:
                progress.finish()
                glsl_errors += 1
                for d in e.diagnostics:
                    print(format_text(d), file=sys.stderr)
                progress.done = (index + 1) * _frame_count(args)
    finally:
        progress.finish()

    if args.format == "json":
        objects = [r.to_json() for r in results]
        if len(objects) == 1:
            print(json.dumps(objects[0]))
        elif objects or not glsl_errors:
            print(json.dumps(objects))
    else:
        _print_text(results, args, glsl_errors)
    if glsl_errors or not all(r.match for r in results):
        return 1
    return 0


def _keep(result, diff_paths) -> None:
    """Write a frame's diff image at once (numbered over the frames asked for, as --diff says),
    then drop its per-pixel maps: a run of many frames keeps only their summaries."""
    if diff_paths is not None:
        from ...verification.compare import write_diff_png

        write_diff_png(
            result.comparison, next(diff_paths)
        )  # atomic; InputError (exit 2) on failure
    c = result.comparison
    c.error_map = c.edge_mask = c.nan_mask = None


def _print_text(results, args, glsl_errors: int) -> None:
    out = sys.stdout
    for result in results:
        names = side_names(args.backends, result.engine)
        out.write(format_frame(result, args.precision, args.samples, names=names))
    failed = sum(r.comparison.verdict == "mismatch" for r in results)
    undefined = sum(r.comparison.verdict == "undefined" for r in results)
    n = len(results)
    frames = f"{n} frame{'s' if n != 1 else ''}"
    if failed or undefined:
        parts = [f"MISMATCH in {failed}"] if failed else []
        parts += [f"undefined in the shader in {undefined}"] if undefined else []
        line = f"verify: {', '.join(parts)} of {frames}"
    elif n:
        line = f"verify: match ({frames})"
    else:
        line = "verify: nothing verified"
    if glsl_errors:
        line += f"; {glsl_errors} shader{'s' if glsl_errors != 1 else ''} with GLSL errors"
    out.write(line + "\n")


def side_names(backends: tuple[str, str], engine: str) -> tuple[str, str]:
    """How the text names the two sides of a frame: the default CPU program ("auto") after the
    engine that rendered it, "numpy" or "compiled"."""
    a, b = backends
    if a == "auto":
        a = engine.split()[0] if engine else "numpy"
    return a, b


def _num(v: float) -> str:
    return "inf" if math.isinf(v) else f"{v:.4g}"


def format_frame(
    result,
    precision: str = "float32",
    samples: int = 1,
    worst: int = 3,
    names: tuple[str, str] = BACKENDS,
) -> str:
    """The short text table of one frame; `names` label the two sides (default numpy, gl)."""
    a, b = names
    c = result.comparison
    s = result.spec
    w, h = result.size
    extra = ""
    if precision != "float32":
        extra += f"  {precision}"
    if samples != 1:
        extra += f"  {samples} samples"
    lines = [f"{result.shader}  {w}x{h}  iTime {s.time:g}  iFrame {s.frame}{extra}"]
    psnr = "inf" if math.isinf(c.psnr_db) else f"{c.psnr_db:.1f} dB"
    lines.append(
        f"  max abs error    {_num(c.max_abs_error):<10}  mean {c.mean_abs_error:.3g}  PSNR {psnr}"
    )
    lines.append(
        f"  mismatched       {c.mismatched_pixels:<10}  budget {int(c.mismatch_budget)}"
        f"  (over {c.abs_tol * 255:.0f}/255)"
    )
    lines.append(f"  edge pixels      {c.edge_pixels:<10}  budget {int(c.edge_budget)}")
    lines.append(
        f"  NaN/Inf pixels   {a} {c.nan_numpy}, {b} {c.nan_gl}"
        + (f", {c.nan_mismatched_pixels} in one image only" if c.nan_mismatched_pixels else "")
    )
    if c.nan_numpy:
        from .probe import nan_hint

        lines.append(f"  note: {nan_hint(result.shader, c.nan_numpy, result.size, s.time)}")
    drivers = getattr(result, "drivers", None)
    if drivers is not None:  # verify --against webgl (glslcheck/verification/drivers.py)
        plain = result.plain
        lines.append(
            f"  driver-dependent {result.driver_pixels:<10}  pixels where gl and webgl differ; "
            f"there {a} need match only the closer driver"
        )
        lines.append(
            f"  {a} vs {b} alone {plain.mismatched_pixels} mismatched, {plain.edge_pixels} edge, "
            f"max abs error {_num(plain.max_abs_error)}"
        )
    if c.bbox is not None:
        x0, y0, x1, y1 = c.bbox
        lines.append(
            f"  differences in   x {x0}..{x1 - 1}, y {y0}..{y1 - 1} (from the top left); "
            f"fragCoord x {x0 + 0.5}..{x1 - 0.5}, y {h - y1 + 0.5}..{h - y0 - 0.5}"
        )
    for p in c.worst[:worst]:
        lines.append(
            f"  {p.kind:<8} pixel ({p.x}, {p.y}) fragCoord ({p.frag_coord[0]}, {p.frag_coord[1]}): "
            f"{a} {_rgb(p.numpy)} {b} {_rgb(p.gl)}"
        )
    if c.unstable_pixels:
        lines.append(
            f"  unstable pixels  {c.unstable_pixels:<10}  both float32 renders far from the "
            "float64 reference (not counted)"
        )
    lines.extend(f"  note: {n}" for n in getattr(result, "notes", ()))
    for u in c.unstable_lines[:3]:
        lines.append(
            f"  precision lost   {u['file']}:{u['line']} `{u['code']}` keeps {u['bits']} of 24 "
            f"bits (~{u['pixels']} unstable pixels)"
        )
    if c.undefined_pixels:
        lines.append(
            f"  undefined        {c.undefined_pixels:<10}  pixels whose colour depends on a value "
            "the shader leaves undefined (not counted)"
        )
    for u in c.undefined_lines[:3]:
        count = f"{u['pixels']} pixels" if u["pixels"] is not None else "pixels not counted"
        lines.append(
            f"  undefined read   {u['file']}:{u['line']}:{u['column']} `{u['code']}` "
            f"({UNDEFINED_KINDS.get(u['kind'], u['kind'])}; {count})"
        )
    if c.verdict == "undefined":
        first = c.undefined_lines[0] if c.undefined_lines else None
        where = f" (line {first['line']}: `glslcheck check` says why)" if first else ""
        lines.append(
            "  -> UNDEFINED IN THE SHADER: the renders differ only where it reads undefined "
            f"values{where}"
        )
    elif c.match and c.unstable_pixels:
        where = (
            f": line {c.unstable_lines[0]['line']} `{c.unstable_lines[0]['code']}` keeps "
            f"{c.unstable_lines[0]['bits']} of 24 bits"
            if c.unstable_lines
            else ""
        )
        lines.append(f"  -> match, except {c.unstable_pixels} unstable pixels{where}")
    else:
        lines.append("  -> match" if c.match else "  -> MISMATCH")
    return "\n".join(lines) + "\n"


UNDEFINED_KINDS = {
    "out-parameter": "an out parameter read before it is written",
    "out-parameter-unwritten": "an out parameter a path leaves unwritten",
    "uninitialized-local": "a local read before it is assigned",
    "uninitialized-global": "a global read before it is assigned",
    "division-by-zero": "division by zero (integer, or float by a constant)",
    "shift-out-of-range": "a shift out of range",
    "conversion-out-of-range": "a conversion out of range",
    "domain": "a built-in outside its domain",
}


def _rgb(values) -> str:
    return "(" + ", ".join(f"{v:.4g}" for v in values[:3]) + ")"
