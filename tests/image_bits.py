"""Two float32 images (or arrays of lanes) compared bit for bit, and a message that says where
and how they differ.

The GL tests render a shader on a CPU engine and on llvmpipe and compare the images as int32
bit patterns (a NaN must be the same NaN, -0.0 is not +0.0); the compiled engine's tests compare
it with the NumPy backend, or its lockstep module with its per-pixel one. When the images differ,
the assertion names the shader and the frame, counts the differing pixels per channel and shows
the first one (from the top left, as `glslcheck probe --pixel` takes it) in both images, values
and bits: what a developer needs to start probing. The math tests compare lanes (a built-in's
results on many arguments) the same way: the first differing lanes with their arguments.

Imported by basename (tests/ is on sys.path through tests/conftest.py), as tests/gl's
llvmpipe_eval.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from glslcheck.shadertoy.sources import Shader, load_shader
from glslcheck.verification.verify import compile_backend

SIZE = (160, 90)  # the GL tests' frame: 14,400 pixels, a few seconds on llvmpipe
CHANNELS = "rgba"
# How two images must agree:
#   "bits": every bit (a NaN the same NaN, -0.0 not +0.0);
#   "bits_any_nan": every bit, but a NaN equals any NaN (engines need not make the same payload);
#   "values_any_nan": equal as numbers (-0.0 equals +0.0), a NaN equals any NaN.
MODES = ("bits", "bits_any_nan", "values_any_nan")
UNIFORM_NAMES = {"time": "iTime", "frame": "iFrame", "mouse": "iMouse", "samples": "samples"}


def render(shader: Shader | str | Path, backend: str, *, size=SIZE, **inputs) -> np.ndarray:
    """`backend`'s float32 image of `shader` (a Shader, or a folder or file load_shader reads),
    (height, width, 4), row 0 the top; `inputs` as `render` takes them (time, frame, mouse...)."""
    if not isinstance(shader, Shader):
        shader = load_shader(shader)
    return np.asarray(compile_backend(shader, backend).render(size=size, **inputs), np.float32)


def same(got: np.ndarray, want: np.ndarray, mode: str = "bits") -> np.ndarray:
    """Per element, whether `got` and `want` agree as `mode` (MODES) says."""
    if mode not in MODES:
        raise ValueError(f"mode {mode!r}, not one of {MODES}")
    got, want = np.asarray(got, np.float32), np.asarray(want, np.float32)
    if got.shape != want.shape:
        raise AssertionError(f"the images' shapes differ: {got.shape} and {want.shape}")
    if mode == "values_any_nan":
        equal = got == want
    else:
        equal = got.view(np.int32) == want.view(np.int32)
    if mode != "bits":
        equal |= np.isnan(got) & np.isnan(want)
    return equal


def differing_pixels(got: np.ndarray, want: np.ndarray, mode: str = "bits") -> int:
    """How many pixels (any channel) of two (..., 4) images differ."""
    return int((~same(got, want, mode).all(axis=-1)).sum())


def frame_text(size=None, **inputs) -> str:
    """``160x90, iTime 1.3, iFrame 0``: the frame a render saw (iTime 0 when not given)."""
    parts = [f"{size[0]}x{size[1]}"] if size is not None else []
    if "time" not in inputs:
        parts.append("iTime 0")
    for key, value in inputs.items():
        parts.append(
            f"{UNIFORM_NAMES.get(key, key)} {value:g}"
            if isinstance(value, float)
            else f"{UNIFORM_NAMES.get(key, key)} {value}"
        )
    return ", ".join(parts)


def _pixel(image: np.ndarray, row: int, col: int) -> str:
    values = image[row, col]
    shown = ", ".join(f"{v:.9g}" for v in values.tolist())
    bits = " ".join(f"{b:08x}" for b in values.view(np.uint32).tolist())
    return f"({shown}) [{bits}]"


def mismatch(
    got: np.ndarray, want: np.ndarray, *, what: str, names=("got", "want"), mode: str = "bits"
) -> str | None:
    """None where two (height, width, 4) images agree as `mode` says; else what a developer
    reads: `what` (the shader and the frame), the differing pixels per channel, and the first
    one from the top left in both images."""
    equal = same(got, want, mode)
    if equal.all():
        return None
    got, want = np.asarray(got, np.float32), np.asarray(want, np.float32)
    height, width = got.shape[:2]
    per_channel = ", ".join(f"{c} {n}" for c, n in zip(CHANNELS, (~equal).reshape(-1, 4).sum(0)))
    rows, cols = np.nonzero(~equal.all(axis=-1))
    row, col = int(rows[0]), int(cols[0])
    a, b = names
    return (
        f"{what}: {a} differs from {b} ({mode}) in {rows.size} of {height * width} pixels "
        f"(per channel: {per_channel}); the first at pixel {col},{row} from the top left "
        f"(fragCoord {col + 0.5}, {height - row - 0.5}): {a} {_pixel(got, row, col)}, "
        f"{b} {_pixel(want, row, col)}"
    )


def assert_same(
    got: np.ndarray, want: np.ndarray, *, what: str, names=("got", "want"), mode: str = "bits"
) -> None:
    """Assert that two (height, width, 4) float32 images agree as `mode` says (MODES), with
    :func:`mismatch`'s message."""
    message = mismatch(got, want, what=what, names=names, mode=mode)
    assert message is None, message


def assert_same_frames(
    got: np.ndarray, want: np.ndarray, times, *, what: str, names=("got", "want"), mode="bits"
) -> None:
    """Assert that renders of one frame a time (axis 0, at iTime `times`) agree as `mode` says:
    the message counts the differing frames per channel and names the first one's iTime."""
    equal = same(got, want, mode).reshape(len(times), -1, 4)
    frames = ~equal.all(axis=1)
    if frames.any():
        first = int(np.argmax(frames.any(axis=1)))
        per_channel = ", ".join(f"{c} {n}" for c, n in zip(CHANNELS, frames.sum(axis=0)))
        a, b = names
        raise AssertionError(
            f"{what}: {a} differs from {b} ({mode}) in {int(frames.any(axis=1).sum())} of "
            f"{len(times)} frames (per channel: {per_channel}); the first at iTime "
            f"{times[first]:.9g}"
        )


def _shown(values: np.ndarray, at: np.ndarray) -> str:
    values = np.asarray(values, np.float32).reshape(-1)[at]
    bits = values.view(np.uint32)
    return (
        "[" + ", ".join(f"{v:.9g} ({b:08x})" for v, b in zip(values.tolist(), bits.tolist())) + "]"
    )


def assert_same_lanes(
    got, want, args=(), *, what: str, names=("got", "want"), mode: str = "bits", shown: int = 5
) -> None:
    """Assert that two arrays of float32 results (lanes; any shape, compared element by element)
    agree as `mode` says (MODES); the message counts the differing lanes and shows the first
    `shown` of them: each argument of `args` there (broadcast to the results' shape) and both
    results, values and bits."""
    equal = same(got, want, mode).reshape(-1)
    if equal.all():
        return
    bad = np.flatnonzero(~equal)
    at = bad[:shown]
    shape = np.shape(got)
    arguments = []
    for k, arg in enumerate(args):
        if arg is None:
            continue
        try:
            arguments.append(f"argument {k} {_shown(np.broadcast_to(arg, shape), at)}")
        except ValueError:  # not of the results' shape: not shown
            continue
    a, b = names
    raise AssertionError(
        f"{what}: {a} differs from {b} ({mode}) in {bad.size} of {equal.size} lanes; the first "
        f"at lanes {at.tolist()}: "
        + "; ".join(arguments + [f"{a} {_shown(got, at)}", f"{b} {_shown(want, at)}"])
    )
