"""The command-line options every command shares, as argparse sees them: `arg(parse_x)` wraps one
of the validators of glslcheck/base/limits.py (the one home of the limits) as an argparse `type=`
so that its ValueError message becomes a usage error (exit 2); the uniform options of render and
probe and the frame budget are declared here once; `environment` hands options to the NumPy
programs a command makes.
"""

from __future__ import annotations

import argparse
import contextlib
import os
from collections.abc import Callable

from ...base.diagnostics import InputError
from ...base.limits import (
    MAX_FRAME_SECONDS,
    MIN_FRAME_SECONDS,
    parse_date,
    parse_frame,
    parse_frame_budget,
    parse_mouse,
    parse_size,
    parse_time,
)


def arg(parse: Callable[[str], object]) -> Callable[[str], object]:
    """`parse` as an argparse type: its ValueError message becomes a usage error (exit 2)."""

    def convert(text: str):
        try:
            return parse(text)
        except ValueError as e:
            raise argparse.ArgumentTypeError(str(e)) from None

    convert.__name__ = parse.__name__.replace("parse_", "")
    return convert


def add_uniform_arguments(p: argparse.ArgumentParser) -> None:
    """The uniform options (--size --time --frame --mouse --date) of `glslcheck render` and
    `glslcheck probe`."""
    p.add_argument(
        "--size", type=arg(parse_size), default=(800, 450), metavar="WxH", help="default 800x450"
    )
    p.add_argument(
        "--time",
        type=arg(parse_time),
        default=0.0,
        metavar="T",
        help="iTime in seconds (default 0)",
    )
    p.add_argument(
        "--frame", type=arg(parse_frame), default=0, metavar="N", help="iFrame (default 0)"
    )
    p.add_argument(
        "--mouse",
        type=arg(parse_mouse),
        default=(0.0, 0.0, 0.0, 0.0),
        metavar="X,Y,Z,W",
        help="iMouse (default 0,0,0,0)",
    )
    p.add_argument(
        "--date",
        type=arg(parse_date),
        default=None,
        metavar="Y,M,D,S",
        help="iDate: year, month 0-11, day, seconds since midnight (default 2026,0,1,0)",
    )


def add_frame_budget(p: argparse.ArgumentParser) -> None:
    """`--frame-budget SECONDS` on a command that renders with the NumPy backend."""
    p.add_argument(
        "--frame-budget",
        type=arg(parse_frame_budget),
        default=None,
        metavar="SECONDS",
        help="stop a NumPy frame still rendering after SECONDS with an error at the loop it was in "
        f"({MIN_FRAME_SECONDS:g} to {MAX_FRAME_SECONDS:g}; default: "
        "$GLSLCHECK_FRAME_SECONDS or 300)",
    )


@contextlib.contextmanager
def environment(**values: str | None):
    """The environment variables `values` (those not None) set while the block runs, then as
    they were: options the NumPy programs made by a command read from the environment
    (--parallel: GLSLCHECK_PARALLEL, --frame-budget: GLSLCHECK_FRAME_SECONDS), and main() may
    run again in the same process."""
    before = {name: os.environ.get(name) for name, value in values.items() if value is not None}
    os.environ.update({name: value for name, value in values.items() if value is not None})
    try:
        yield
    finally:
        for name, value in before.items():
            if value is None:
                os.environ.pop(name, None)
            else:
                os.environ[name] = value


def refuse_to_overwrite_inputs(outputs, shaders, what: str) -> None:
    """InputError when one of `outputs` is a file one of `shaders` is read from (a tab,
    channels.json, a texture): a command never writes over what it reads."""
    from ...shadertoy.channels import input_files

    inputs = {os.path.realpath(path): path for shader in shaders for path in input_files(shader)}
    for output in outputs:
        path = inputs.get(os.path.realpath(output))
        if path is not None:
            raise InputError(
                f"{output}: error: the {what} would overwrite {path}, which the shader is read "
                f"from; name another file"
            )
