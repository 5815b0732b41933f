"""Verifying the CPU renderer: render one shader with the NumPy backend and with OpenGL
(Mesa llvmpipe) at the same inputs, frame by frame, and compare the two images.

This module owns the frame schedule (which times, frame numbers and rates a run covers), the
pairing of the two backends, and the option parsers the `verify` command uses for sizes, time
lists and mouse positions. The verdict itself (metrics, tolerance model, diff image) belongs to
`glslcheck.compare`; each frame's outcome is a `compare.Comparison`.

Library API:

    comparisons = verify("lab_shaders/07_final", size=(320, 180), times=[0.0, 1.7])
    all(c.match for c in comparisons)
    for r in verify_frames(shader, frames=10, fps=30): r.spec.time, r.comparison.psnr_db

Inputs fed to both backends (identical on both sides): iResolution from `size`, iTime and
iFrame from the schedule, iMouse, iDate (`date`, default the fixed 2026-01-01 00:00), and
iTimeDelta = 1/fps, iFrameRate = fps when both backends accept them. `precision` selects the
NumPy backend's float mode (float32 = highp, float16 = mediump emulation, float64 = reference);
the GL side is always what the driver runs (highp = float32), so float16/float64 measure the
error of that mode against the real GPU. `samples` (a perfect square) supersamples both sides
on the same sub-pixel grid.

The schedule (`frame_specs`):

- nothing given: one frame at iTime = 0, iFrame = `frame` (0).
- `time=T` or `times=[...]`: one frame per time, each with iFrame = `frame`.
- `frames=N`: N consecutive frames from iFrame = `frame`: iFrame = frame + i and
  iTime = iFrame / fps (the clock of a player running at `fps`, default 60).
"""

from __future__ import annotations

import inspect
import logging
import math
import os
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Iterator, Sequence

import numpy as np

from .compare import Comparison, compare
from .diagnostics import InputError
from .shadertoy import DEFAULT_SIZE
from .sources import Shader, load_shader

BACKENDS = ("numpy", "gl")
ALL_BACKENDS = ("numpy", "gl", "webgl")  # webgl: headless Chromium (glslcheck/webgl_backend)
PRECISIONS = ("float32", "float16", "float64")
DEFAULT_FPS = 60.0


# ---------------------------------------------------------------------------------------------
# Option parsers (usable as argparse `type=`: they raise ValueError with a readable message).


# The largest image glslcheck renders: 4096x4096 pixels. Its float32 RGBA image alone is
# 256 MiB; verify holds two of them (NumPy and GL) plus the comparison's arrays. 16384x16384
# (4 GiB per image) ran out of memory with a traceback.
MAX_PIXELS = 4096 * 4096


def check_pixels(w: int, h: int, text: str) -> None:
    """ValueError when w*h is above MAX_PIXELS."""
    if w * h > MAX_PIXELS:
        raise ValueError(f"a size of at most {MAX_PIXELS:,} pixels (e.g. 4096x4096), not {text!r} "
                         f"({w * h:,} pixels, {w * h * 16 / 2**30:.1f} GiB per float image)")


def parse_size(text: str) -> tuple[int, int]:
    """'320x180' -> (320, 180); both at least 1 and at most 16384, at most MAX_PIXELS in all."""
    parts = text.lower().replace("*", "x").split("x")
    try:
        if len(parts) != 2:
            raise ValueError
        w, h = int(parts[0]), int(parts[1])
    except ValueError:
        raise ValueError(f"a size is WIDTHxHEIGHT in pixels, e.g. 320x180, not {text!r}") from None
    if not (1 <= w <= 16384 and 1 <= h <= 16384):
        raise ValueError(f"a size must be between 1x1 and 16384x16384, not {text!r}")
    check_pixels(w, h, text)
    return w, h


def parse_floats(text: str, count: int | None = None, what: str = "value") -> tuple[float, ...]:
    """'0,0.5,1' -> (0.0, 0.5, 1.0); finite numbers only; exactly `count` of them if given."""
    items = [t.strip() for t in text.split(",")]
    try:
        values = tuple(float(t) for t in items)
    except ValueError:
        raise ValueError(f"{what} must be comma-separated numbers, not {text!r}") from None
    if not all(math.isfinite(v) for v in values):
        raise ValueError(f"{what} must be finite numbers, not {text!r}")
    if count is not None and len(values) != count:
        raise ValueError(f"{what} needs {count} comma-separated numbers, not {text!r}")
    return values


def parse_time(text: str) -> float:
    return parse_floats(text, 1, "a time")[0]


def parse_times(text: str) -> tuple[float, ...]:
    return parse_floats(text, None, "--times")


def parse_mouse(text: str) -> tuple[float, float, float, float]:
    """'X,Y,Z,W' -> iMouse (pixels; signs of Z and W as on Shadertoy)."""
    return parse_floats(text, 4, "--mouse")  # type: ignore[return-value]


def parse_samples(text: str) -> int:
    """A perfect square >= 1 (the k*k sub-pixel grid both backends use)."""
    try:
        n = int(text)
    except ValueError:
        raise ValueError(f"--samples must be an integer, not {text!r}") from None
    k = math.isqrt(n) if n >= 1 else 0
    if k < 1 or k * k != n or n > 256:
        raise ValueError(f"--samples must be a perfect square from 1 to 256 (1, 4, 9, 16, ...), not {text!r}")
    return n


def parse_count(text: str) -> int:
    try:
        n = int(text)
    except ValueError:
        raise ValueError(f"expected a whole number, not {text!r}") from None
    if n < 0:
        raise ValueError(f"expected a number >= 0, not {text!r}")
    return n


def parse_fps(text: str) -> float:
    fps = parse_floats(text, 1, "--fps")[0]
    if fps <= 0:
        raise ValueError(f"--fps must be positive, not {text!r}")
    return fps


# ---------------------------------------------------------------------------------------------
# The frame schedule.


@dataclass(frozen=True, slots=True)
class FrameSpec:
    """The per-frame inputs: iTime, iFrame, iTimeDelta, iFrameRate."""

    time: float = 0.0
    frame: int = 0
    time_delta: float = 1.0 / DEFAULT_FPS
    frame_rate: float = DEFAULT_FPS


def frame_specs(
    time: float | None = None,
    times: Sequence[float] | None = None,
    frames: int | None = None,
    fps: float | None = None,
    frame: int | None = None,
) -> list[FrameSpec]:
    """The frames one run renders (see the module docstring); ValueError on conflicting options."""
    given = [name for name, v in (("time", time), ("times", times), ("frames", frames)) if v is not None]
    if len(given) > 1:
        raise ValueError(f"give only one of --{', --'.join(given)}")
    rate = DEFAULT_FPS if fps is None else float(fps)
    if not rate > 0:
        raise ValueError(f"fps must be positive, not {fps}")
    start = 0 if frame is None else int(frame)
    delta = 1.0 / rate
    if frames is not None:
        if frames < 1:
            raise ValueError("frames must be at least 1")
        return [FrameSpec((start + i) / rate, start + i, delta, rate) for i in range(frames)]
    if times is not None:
        if not len(times):
            raise ValueError("times is empty")
        return [FrameSpec(float(t), start, delta, rate) for t in times]
    return [FrameSpec(0.0 if time is None else float(time), start, delta, rate)]


# ---------------------------------------------------------------------------------------------
# Backends.


def compile_backend(shader: Shader, backend: str):
    """A compiled program of `backend` ("numpy", "gl" or "webgl") with a `render(size=..., ...)` method.

    GlslError (exit 1) when the shader does not compile, GLUnavailable (exit 2) without a GL
    context, WebGLUnavailable (exit 2) without headless Chromium, InputError (exit 2) when the
    NumPy backend is not installed in this build.
    """
    if backend == "gl":
        from .gl_backend import compile_gl

        return compile_gl(shader)
    if backend == "webgl":
        from .webgl_backend import compile_webgl

        return compile_webgl(shader)
    if backend == "numpy":
        try:
            from . import api
        except ImportError:
            api = None
        if api is not None and hasattr(api, "compile"):
            return api.compile(shader, backend="numpy")
        try:
            from .numpy_backend.program import compile_numpy
        except ImportError as e:
            raise InputError(f"error: the NumPy backend is not available in this build ({e})") from None
        return compile_numpy(shader)
    raise ValueError(f"unknown backend {backend!r}; expected one of {', '.join(ALL_BACKENDS)}")


def _accepted(program) -> set[str] | None:
    """The keyword arguments `program.render` takes (None: it takes **kwargs)."""
    params = inspect.signature(program.render).parameters.values()
    if any(p.kind is p.VAR_KEYWORD for p in params):
        return None
    return {p.name for p in params}


class _Pair:
    """Two compiled programs rendered with the same inputs.

    Inputs that only one backend understands are not fed to either side (iTimeDelta and
    iFrameRate then keep their defaults on both), so the two always see the same uniforms;
    `precision` is the exception: it goes to each backend that takes it (the GL side has none:
    the driver is float32).
    """

    def __init__(self, programs: Sequence):
        self.programs = list(programs)
        accepted = [_accepted(p) for p in self.programs]
        common = None
        for a in accepted:
            if a is not None:
                common = a if common is None else common & a
        self._common = common
        self._accepted = accepted

    def render(self, spec: FrameSpec, size, mouse, date, precision, samples) -> list[np.ndarray]:
        shared = {"size": size, "time": spec.time, "frame": spec.frame, "mouse": mouse, "date": date,
                  "samples": samples, "time_delta": spec.time_delta, "frame_rate": spec.frame_rate}
        images = []
        for program, accepted in zip(self.programs, self._accepted):
            kwargs = {k: v for k, v in shared.items() if self._common is None or k in self._common}
            if accepted is None or "precision" in accepted:
                kwargs["precision"] = precision
            images.append(program.render(**kwargs))
        return images


# ---------------------------------------------------------------------------------------------
# Verification.


@dataclass(eq=False)
class FrameResult:
    """One verified frame: which shader, which inputs, the comparison, and (if kept) both images."""

    shader: str
    spec: FrameSpec
    size: tuple[int, int]
    comparison: Comparison
    numpy_image: np.ndarray | None = None
    gl_image: np.ndarray | None = None

    @property
    def match(self) -> bool:
        return self.comparison.match


def _as_shader(shader) -> Shader:
    if isinstance(shader, Shader):
        return shader
    if isinstance(shader, (str, os.PathLike)):
        return load_shader(shader)
    raise TypeError(f"expected a Shader or a path, not {type(shader).__name__}")


def verify_frames(
    shader,
    *,
    size: tuple[int, int] = DEFAULT_SIZE,
    sizes: Sequence[tuple[int, int]] | None = None,
    time: float | None = None,
    times: Sequence[float] | None = None,
    frames: int | None = None,
    fps: float | None = None,
    frame: int | None = None,
    mouse: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0),
    date=None,
    precision: str = "float32",
    samples: int = 1,
    backends: tuple[str, str] = BACKENDS,
    programs: Sequence | None = None,
    keep_images: bool = False,
    compare_options: dict | None = None,
    progress: "Progress | None" = None,
) -> Iterator[FrameResult]:
    """Render and compare frame by frame, every size times every frame of the schedule.

    `shader` is a `Shader` or a path. `backends` names the two sides (first = the one under
    test, reported as "numpy"); `programs` gives already compiled programs instead. Both are
    compiled before the first frame, so a GLSL error or a missing GL context surfaces at once.
    """
    if precision not in PRECISIONS:
        raise ValueError(f"precision must be one of {', '.join(PRECISIONS)}, not {precision!r}")
    specs = frame_specs(time, times, frames, fps, frame)
    size_list = [tuple(s) for s in (sizes or [size])]
    shader = _as_shader(shader)
    if programs is None:
        # GL/WebGL first: a missing context or browser is reported before a slower NumPy transpile.
        by_name = {b: compile_backend(shader, b) for b in sorted(backends, key=lambda b: b == "numpy")}
        programs = [by_name[b] for b in backends]
    emulate_driver(programs)
    pair = _Pair(programs)
    name = shader.root or (shader.image.path if shader.image else "<shader>")
    for w_h in size_list:
        for spec in specs:
            numpy_img, gl_img = pair.render(spec, w_h, tuple(mouse), date, precision, samples)
            comparison = compare(numpy_img, gl_img, **(compare_options or {}))
            if progress is not None:
                progress.step(f"{name} t={spec.time:g}")
            yield FrameResult(name, spec, (int(w_h[0]), int(w_h[1])), comparison,
                              numpy_img if keep_images else None, gl_img if keep_images else None)


def emulate_driver(programs: Sequence) -> None:
    """Have every program that emulates a driver (the NumPy side) compute what the measured
    driver (the GL side) does where GLSL leaves a value undefined and the CPU decides
    (glslcheck/driver_profile.py). A driver that follows no known model is reported on stderr,
    and the NumPy side keeps its prediction for this machine."""
    programs = [getattr(p, "impl", p) for p in programs]  # api.Program wraps a backend's program
    models = {p.float_to_uint_model for p in programs if hasattr(p, "float_to_uint_model")}
    if not models:
        return
    model = models.pop() if len(models) == 1 else None
    if model is None:
        logging.getLogger("glslcheck").warning(
            "note: the GL driver's uint(x) of negative, NaN or huge x follows no model glslcheck "
            "knows (glslcheck/driver_profile.py); pixels that depend on such conversions may differ")
        return
    for p in programs:
        if hasattr(p, "emulate_float_to_uint"):
            p.emulate_float_to_uint(model)


def verify(shader, **options) -> list[Comparison]:
    """The comparisons of every frame `verify_frames(shader, **options)` renders, in order."""
    return [r.comparison for r in verify_frames(shader, **options)]


def diff_paths(path: str | os.PathLike, count: int) -> list[Path]:
    """`diff.png` for one frame; `diff-0.png`, `diff-1.png`, ... for several."""
    p = Path(path)
    if count == 1:
        return [p]
    suffix = p.suffix or ".png"
    stem = p.name[: -len(p.suffix)] if p.suffix else p.name
    return [p.with_name(f"{stem}-{i}{suffix}") for i in range(count)]


# ---------------------------------------------------------------------------------------------
# Progress bar (stderr; no dependency).


class Progress:
    """A one-line progress bar redrawn with '\\r': `[#####.....] 5/10 label`.

    Disabled (a no-op) when `enabled` is False. `finish()` ends the line.
    """

    WIDTH = 24

    def __init__(self, total: int, stream=None, enabled: bool = True):
        self.total = max(int(total), 1)
        self.done = 0
        self.stream = stream if stream is not None else sys.stderr
        self.enabled = enabled
        self._drawn = False

    def step(self, label: str = "") -> None:
        self.done += 1
        if not self.enabled:
            return
        filled = self.WIDTH * min(self.done, self.total) // self.total
        bar = "#" * filled + "." * (self.WIDTH - filled)
        line = f"\rverify [{bar}] {self.done}/{self.total} {label}"
        self.stream.write(line[:120].ljust(80))
        self.stream.flush()
        self._drawn = True

    def finish(self) -> None:
        if self.enabled and self._drawn:
            self.stream.write("\n")
            self.stream.flush()
            self._drawn = False

