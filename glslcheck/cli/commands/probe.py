"""glslcheck probe SHADER (--pixel X,Y | --frag-coord FX,FY | --nan) [--size WxH] [--time T]
[--frame N] [--mouse X,Y,Z,W] [--date Y,M,D,S] [--format text|json]: what one pixel computed, or
where every NaN came from.

--pixel X,Y (from the top left, as verify prints pixels; --frag-coord FX,FY gives fragCoord
instead) prints every statement the pixel executed, in order: file:line and the source line,
the values assigned (float32, as the render computes them, then the float64 shadow -- the same
program run in float64 on the same pixel -- and how many bits of it the float32 value keeps),
the branches taken, each loop iteration (a long loop shows its first and last few), function
calls with their arguments and return values, discard, and the final fragColor. JSON:
{"pixel": [x, y], "frag_coord": [fx, fy], "color": [r, g, b, a], "steps": [{"file", "line",
"code", "kind": "assign|branch|loop|call|return|discard|undefined", "name", "value", "value64",
"bits"}],
"first_nan": {"file", "line", "column", "code", "operation"} | null}. Names and values by kind:
assign: the variable and its whole value after the write; branch: "if", "if/else" or "switch"
with the condition or selector, "break", "continue"; loop: "for start", "for iteration" with its
number, "for end" with the iteration count (also "while", "do"); call: the function with its
arguments by parameter name; return: the function and the returned value. Vectors are lists,
matrices lists of columns, structs objects; non-finite floats are "nan", "inf" and "-inf"; bits
is null where there is no float to compare or no float64 step to pair with. undefined: where a
value GLSL leaves undefined enters (an out parameter on entry, a local declared without an
initializer, an operation on constants outside its range; `glslcheck check` warns at its read)
with the value this render gives it (WebGL's), and the keys "undefined" (the kind) and
"read_line" (the line of its read).

--nan renders the frame and groups every NaN or Inf pixel by the operation where its first NaN
or Inf appeared (file:line:col, the expression, what made it: 0/0, sqrt or log of a negative,
normalize of a zero vector, inversesqrt(0), pow of a negative base, overflow, ...), with the
pixel count, the bounding box and a help line. When the program reads undefined values, the
frame is rendered again with other values at those reads: the pixels whose colour changes
depend on them, counted per origin ("undefined_pixels") and followed by the reads. JSON:
{"nan_pixels", "inf_pixels", "origins": [{"file", "line", "column", "code", "operation",
"pixels", "box": [x0, y0, x1, y1], "undefined_pixels"}], "undefined_reads": [{"file", "line",
"column", "kind"}] (empty unless some NaN/Inf pixel depends on one)}.

probe runs on the NumPy backend only, whatever render's default: its step trace and NaN origins
come from the NumPy backend's traced module, which the compiled engine has no counterpart of
(the two render the same bits where the default CPU program moves, so the values are the
render's). The uniform options are render's. Exit 0 (1 with --nan when some pixel is NaN or
Inf), 1 on a shader error, 2 on usage or I/O errors.
"""

from __future__ import annotations

import argparse
import json
import math

from ...base import limits
from ...base.diagnostics import InputError
from . import args as cli_args


def _pixel(text: str) -> tuple[int, int]:
    try:
        x, y = (int(v) for v in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"--pixel takes X,Y (whole numbers from the top left), not {text!r}"
        ) from None
    return x, y


def add_arguments(p) -> None:
    p.add_argument("path", metavar="SHADER", help="a tab file or a folder of tab files")
    what = p.add_mutually_exclusive_group(required=True)
    what.add_argument(
        "--pixel", type=_pixel, metavar="X,Y", help="the pixel to trace, from the top left"
    )
    what.add_argument(
        "--frag-coord",
        type=cli_args.arg(lambda t: limits.parse_floats(t, 2, "--frag-coord")),
        metavar="FX,FY",
        help="the fragCoord to trace (origin at the bottom left, pixel centres at .5)",
    )
    what.add_argument(
        "--nan", action="store_true", help="find where the frame's NaN and Inf pixels came from"
    )
    cli_args.add_uniform_arguments(p)
    p.add_argument("--format", choices=("text", "json"), default="text", help="default text")


def run(args) -> int:
    from ...verification.probe import Inputs, Probe, format_nan, format_pixel

    inputs = Inputs(
        size=args.size, time=args.time, frame=args.frame, mouse=args.mouse, date=args.date
    )
    probe = Probe(args.path)
    if args.nan:
        nan_report = probe.nan_origins(inputs)
        print(
            json.dumps(nan_report.to_json())
            if args.format == "json"
            else format_nan(nan_report, args.path, inputs)
        )
        return 1 if nan_report.nan_pixels or nan_report.inf_pixels else 0
    if args.frag_coord is not None:
        fx, fy = args.frag_coord
        w, h = args.size
        if not (0 <= fx < w and 0 <= fy < h) or not all(math.isfinite(v) for v in (fx, fy)):
            raise InputError(f"error: --frag-coord {fx:g},{fy:g} is outside the {w}x{h} image")
        report = probe.pixel(None, None, inputs, frag_coord=(fx, fy))
    else:
        x, y = args.pixel
        report = probe.pixel(x, y, inputs)
    print(
        json.dumps(report.to_json())
        if args.format == "json"
        else format_pixel(report, args.path, inputs)
    )
    return 0


def nan_hint(path: str, nan_pixels: int, size: tuple[int, int], time: float) -> str:
    """The line `render` and `verify` print for an image with NaN pixels."""
    opts = (f" --size {size[0]}x{size[1]}" if tuple(size) != (800, 450) else "") + (
        f" --time {time:g}" if time else ""
    )
    return (
        f"{nan_pixels} pixel{'s are' if nan_pixels != 1 else ' is'} NaN: "
        f"`glslcheck probe {path} --nan{opts}` "
        "shows where they came from"
    )
