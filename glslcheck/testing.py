"""Rendering-equivalence tests for shader authors and course autograders: a pytest plugin.

Installed with the package (entry point `glslcheck.testing` in the `pytest11` group), so a test
suite only asks for the `shader_check` fixture:

    def test_part3_renders_like_the_reference(shader_check):
        shader_check.assert_renders_like("student/part3", "reference/part3", times=[0, 1.7, 5.3])

    def test_part3_is_sound(shader_check):
        shader_check.assert_no_nan("student/part3", times=[0, 1.7, 5.3])
        shader_check.assert_animates("student/part3", times=[0, 1.7])
        shader_check.assert_matches_png("student/part3", "expected/part3.png", time=1.7)

A shader is a folder of Shadertoy tab files, a tab file, or a loaded `Shader`. Each assertion
renders at `size` (default the fixture's, 320x180; `--glslcheck-size WxH` sets it for the run)
with `backend` (default "numpy", the CPU renderer; `--glslcheck-backend gl` uses the OpenGL
driver) and fails (`RenderMismatch`, an AssertionError) with the numbers and the path of a diff
image written under the test's own `tmp_path` (the plain functions below write under a fresh
temporary folder instead).

The tolerances are glslcheck's own scale (glslcheck/verification/grade/closeness.py,
docs/grading.md): `tolerance="same"` (default) is `glslcheck verify`'s match, differences the
display cannot show or sub-pixel edge shifts; `"close"` also passes a PSNR of at least 30 dB
(the same scene with a parameter changed); a number is the lowest PSNR in dB that passes.
Against a PNG the render is compared as the screen shows it (8-bit): the PNG's own rounding is
half a display step, inside verify's 2/255.

Without pytest the functions work the same (`from glslcheck.testing import assert_no_nan`).
"""

from __future__ import annotations

import math
import os
import tempfile
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import pytest

from .base.images import load_image, quantise, save_image, save_rgb
from .shadertoy.sources import Shader, load_shader
from .verification.compare import DEFAULT_ABS_TOL, NAN_COLOUR, Comparison, compare, diff_colours
from .verification.grade.closeness import CLOSE_PSNR_DB
from .verification.verify import compile_backend

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from typing import Any

DEFAULT_SIZE = (320, 180)


class RenderMismatch(AssertionError):
    """An assertion of this module failed; the message has the numbers and the image paths."""


def _shader(shader) -> Shader:
    return shader if isinstance(shader, Shader) else load_shader(shader)


def _name(shader) -> str:
    if isinstance(shader, Shader):
        return shader.root or (shader.image.path if shader.image else "<shader>")
    return str(shader)


def _min_psnr(tolerance) -> float | None:
    """None for "same" (verify's match); the lowest passing PSNR otherwise."""
    if tolerance == "same":
        return None
    if tolerance == "close":
        return CLOSE_PSNR_DB
    if isinstance(tolerance, (int, float)) and not isinstance(tolerance, bool):
        if math.isfinite(tolerance):
            return float(tolerance)
    raise ValueError(f"tolerance must be 'same', 'close' or a PSNR in dB, not {tolerance!r}")


def _passes(c: Comparison, min_psnr: float | None) -> bool:
    if c.match:
        return True
    return min_psnr is not None and c.nan_mismatched_pixels == 0 and c.psnr_db >= min_psnr


def _psnr(c: Comparison) -> str:
    return "inf" if math.isinf(c.psnr_db) else f"{c.psnr_db:.1f} dB"


def _numbers(c: Comparison, ours: str, theirs: str) -> str:
    pixels = c.size[0] * c.size[1]
    over = c.mismatched_pixels + c.edge_pixels
    text = (
        f"PSNR {_psnr(c)}, max abs error {c.max_abs_error:.4g}, mean abs error "
        f"{c.mean_abs_error:.4g}, {over} of {pixels} pixels ({100.0 * over / pixels:.2f}%) off by "
        f"more than 2/255 ({c.mismatched_pixels} mismatched, budget {int(c.mismatch_budget)}; "
        f"{c.edge_pixels} at edges, budget {int(c.edge_budget)})"
    )
    if c.nan_mismatched_pixels:
        text += f", {c.nan_mismatched_pixels} pixels NaN/Inf in one image only"
    if c.worst:
        w = c.worst[0]
        show = ", ".join(f"{v:.4g}" for v in w.numpy[:3])
        other = ", ".join(f"{v:.4g}" for v in w.gl[:3])
        text += (
            f"; worst at pixel ({w.x}, {w.y}) from the top left: "
            f"{ours} ({show}), {theirs} ({other})"
        )
    return text


class ShaderCheck:
    """The assertions, with the size, backend and diff folder they use (the `shader_check`
    fixture's object; `ShaderCheck()` outside pytest)."""

    def __init__(self, size=DEFAULT_SIZE, backend: str = "numpy", diff_dir=None):
        self.size = (int(size[0]), int(size[1]))
        self.backend = backend
        self._diff_dir = Path(diff_dir) if diff_dir is not None else None
        # compile_backend's programs: a backend's Program, or a driver's own (no common type)
        self._programs: dict[tuple, Any] = {}

    @property
    def diff_dir(self) -> Path:
        if self._diff_dir is None:
            self._diff_dir = Path(tempfile.mkdtemp(prefix="glslcheck-diff-"))
        self._diff_dir.mkdir(parents=True, exist_ok=True)
        return self._diff_dir

    def _diff_path(self, shader, what: str) -> Path:
        stem = "".join(
            ch if ch.isalnum() or ch in "-_." else "_" for ch in Path(_name(shader)).name
        )
        return self.diff_dir / f"{stem or 'shader'}-{what}.png"

    def render(self, shader, time: float = 0.0, size=None, backend: str | None = None):
        """The float RGBA render (top row first) of `shader` at iTime `time`."""
        backend = backend or self.backend
        key = (id(shader) if isinstance(shader, Shader) else os.path.realpath(shader), backend)
        program = self._programs.get(key)
        if program is None:
            program = self._programs[key] = compile_backend(_shader(shader), backend)
        return program.render(size=tuple(size or self.size), time=float(time))

    def assert_renders_like(
        self,
        shader,
        reference,
        times: Sequence[float] = (0.0,),
        tolerance="same",
        size=None,
        backend: str | None = None,
    ) -> list[Comparison]:
        """`shader` renders like `reference` at every time, within `tolerance`; the comparisons."""
        __tracebackhide__ = True
        min_psnr = _min_psnr(tolerance)
        out = []
        for t in times:
            ours = self.render(shader, t, size, backend)
            theirs = self.render(reference, t, size, backend)
            c = compare(ours, theirs)
            out.append(c)
            if not _passes(c, min_psnr):
                path = self._diff_path(shader, f"vs-reference-t{t:g}")
                save_rgb(diff_colours(c), path, "diff image")
                need = "verify's match" if min_psnr is None else f"PSNR >= {min_psnr:g} dB"
                raise RenderMismatch(
                    f"{_name(shader)} does not render like {_name(reference)} at iTime {t:g} "
                    f"(tolerance {tolerance!r}: {need}): "
                    + _numbers(c, "shader", "reference")
                    + f"; diff image: {path}"
                )
        return out

    def assert_matches_png(
        self, shader, png, time: float = 0.0, tolerance="same", backend: str | None = None
    ) -> Comparison:
        """`shader` at iTime `time`, rendered at the PNG's size, looks like the PNG."""
        __tracebackhide__ = True
        expected = load_image(png)
        h, w = expected.shape[:2]
        ours = self.render(shader, time, (w, h), backend)
        c = compare(quantise(ours), expected)  # both as the screen shows them
        if not _passes(c, _min_psnr(tolerance)):
            path = self._diff_path(shader, f"vs-png-t{time:g}")
            save_rgb(diff_colours(c), path, "diff image")
            rendered = self._diff_path(shader, f"render-t{time:g}")
            save_image(ours, rendered)
            raise RenderMismatch(
                f"{_name(shader)} at iTime {time:g} does not look like {png} "
                f"(tolerance {tolerance!r}): "
                + _numbers(c, "render", "png")
                + f"; diff image: {path}; the render: {rendered}"
            )
        return c

    def assert_no_nan(
        self, shader, times: Sequence[float] = (0.0,), size=None, backend: str | None = None
    ) -> None:
        """No NaN or Inf in any colour channel of any pixel, at every time."""
        __tracebackhide__ = True
        for t in times:
            img = self.render(shader, t, size, backend)
            bad = (~np.isfinite(img[..., :3])).any(axis=-1)
            if bad.any():
                ys, xs = np.nonzero(bad)
                rgb = quantise(img[..., :3])
                rgb[bad] = NAN_COLOUR
                path = self._diff_path(shader, f"nan-t{t:g}")
                save_rgb(rgb, path, "NaN map")
                w, h = img.shape[1], img.shape[0]
                raise RenderMismatch(
                    f"{_name(shader)} has {int(bad.sum())} NaN/Inf pixels of {w * h} at iTime "
                    f"{t:g} ({w}x{h}), in x {xs.min()}..{xs.max()}, y {ys.min()}..{ys.max()} from "
                    f"the top left, first at ({xs[0]}, {ys[0]}); where they come from: glslcheck "
                    f"probe {_name(shader)} --nan --time {t:g} --size {w}x{h}; "
                    f"the pixels in magenta: {path}"
                )

    def assert_animates(
        self, shader, times: Sequence[float] = (0.0, 1.0), size=None, backend: str | None = None
    ) -> None:
        """The frames at `times` are not all the same picture: some pixel of some frame differs
        from the first frame's by more than verify's display tolerance (2/255)."""
        __tracebackhide__ = True
        if len(times) < 2:
            raise ValueError("assert_animates needs at least two times")
        first = self.render(shader, times[0], size, backend)
        largest, at = 0.0, times[1]
        for t in times[1:]:
            c = compare(self.render(shader, t, size, backend), first)
            if c.max_abs_error > DEFAULT_ABS_TOL:
                return
            if c.max_abs_error >= largest:
                largest, at = c.max_abs_error, t
        path = self._diff_path(shader, "animation")
        save_rgb(diff_colours(compare(self.render(shader, at, size, backend), first)), path)
        raise RenderMismatch(
            f"{_name(shader)} does not animate: the frames at iTime "
            f"{', '.join(f'{t:g}' for t in times)} differ from the first by at most "
            f"{largest:.4g} (a visible change is over 2/255 = {DEFAULT_ABS_TOL:.4g}); "
            f"diff image: {path} (iTime {at:g} against {times[0]:g})"
        )


_DEFAULT = ShaderCheck()


def assert_renders_like(shader, reference, times=(0.0,), tolerance="same", size=None, backend=None):
    __tracebackhide__ = True
    return _DEFAULT.assert_renders_like(shader, reference, times, tolerance, size, backend)


def assert_matches_png(shader, png, time=0.0, tolerance="same", backend=None):
    __tracebackhide__ = True
    return _DEFAULT.assert_matches_png(shader, png, time, tolerance, backend)


def assert_no_nan(shader, times=(0.0,), size=None, backend=None):
    __tracebackhide__ = True
    return _DEFAULT.assert_no_nan(shader, times, size, backend)


def assert_animates(shader, times=(0.0, 1.0), size=None, backend=None):
    __tracebackhide__ = True
    return _DEFAULT.assert_animates(shader, times, size, backend)


# ---------------------------------------------------------------------------------------------
# The pytest plugin.


def pytest_addoption(parser) -> None:
    group = parser.getgroup("glslcheck", "rendering-equivalence tests (glslcheck.testing)")
    group.addoption(
        "--glslcheck-size",
        default=None,
        metavar="WxH",
        help="render size of the shader_check fixture (default 320x180)",
    )
    group.addoption(
        "--glslcheck-backend",
        default=None,
        choices=("numpy", "compiled", "gl", "webgl"),
        help="what renders for the shader_check fixture (default numpy: the CPU renderer)",
    )


@pytest.fixture
def shader_check(request, tmp_path) -> ShaderCheck:
    """The assertions of glslcheck.testing, diff images under this test's tmp_path."""
    from .base.limits import parse_size

    text = request.config.getoption("glslcheck_size", None)
    try:
        size = parse_size(text) if text else DEFAULT_SIZE
    except ValueError as e:
        raise pytest.UsageError(f"--glslcheck-size: {e}") from None
    backend = request.config.getoption("glslcheck_backend", None) or "numpy"
    return ShaderCheck(size, backend, tmp_path / "glslcheck")
