"""Verifying the CPU renderer: render one shader with the default CPU program (the NumPy
backend, whose frames move to the compiled engine where that gives the same bits:
backends/tiered.py) and with OpenGL (Mesa llvmpipe) at the same inputs, frame by frame, and
compare the two images. Each frame's result names the engine that rendered it.

This module owns the frame schedule (which times, frame numbers and rates a run covers) and the
pairing of the two backends; the values a user gives and their limits are in
`glslcheck.base.limits`, shared by every command. The verdict itself (metrics, tolerance model, diff
image) belongs to `glslcheck.verification.compare`; each frame's outcome is a `compare.Comparison`.

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
import os
import sys
from collections import abc
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..backends import registry
from ..base.diagnostics import GlslError
from ..base.precision import check_precision
from ..semantics.mediump import mediump_notes
from ..shadertoy.sources import Shader, load_shader
from ..shadertoy.wrapper import DEFAULT_SIZE
from .compare import JSON_KEYS as COMPARISON_KEYS
from .compare import Comparison, compare, depends_on_undefined

BACKENDS = ("auto", "gl")  # the default pair: the side under test, then its reference
DEFAULT_FPS = 60.0
# a verified frame in JSON: its comparison, then the engine that rendered the side under test
JSON_KEYS = (*COMPARISON_KEYS, "engine")


# ---------------------------------------------------------------------------------------------
# The frame schedule.


@dataclass(frozen=True, slots=True)
class FrameSpec:
    """The per-frame inputs: iTime, iFrame, iTimeDelta, iFrameRate."""

    time: float = 0.0
    frame: int = 0
    time_delta: float = 1.0 / DEFAULT_FPS
    frame_rate: float = DEFAULT_FPS


@dataclass(frozen=True, slots=True)
class Frames(abc.Sequence):
    """`length` consecutive frames from iFrame `start` at `rate`, made one at a time when asked
    for (`--frames 100000000` holds no list of 10^8 frames)."""

    start: int
    length: int
    rate: float

    def __len__(self) -> int:
        return self.length

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[j] for j in range(*i.indices(self.length))]
        if i < 0:
            i += self.length
        if not 0 <= i < self.length:
            raise IndexError(i)
        n = self.start + i
        return FrameSpec(n / self.rate, n, 1.0 / self.rate, self.rate)


def frame_specs(
    time: float | None = None,
    times: Sequence[float] | None = None,
    frames: int | None = None,
    fps: float | None = None,
    frame: int | None = None,
) -> Sequence[FrameSpec]:
    """The frames one run renders (see the module docstring); ValueError on conflicting options.
    `frames=N` gives a lazy sequence (`Frames`), the others a list."""
    given = [
        name for name, v in (("time", time), ("times", times), ("frames", frames)) if v is not None
    ]
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
        return Frames(start, int(frames), rate)
    if times is not None:
        if not len(times):
            raise ValueError("times is empty")
        return [FrameSpec(float(t), start, delta, rate) for t in times]
    return [FrameSpec(0.0 if time is None else float(time), start, delta, rate)]


# ---------------------------------------------------------------------------------------------
# Backends.


def compile_backend(shader: Shader, backend: str):
    """A compiled program of `backend` (one of `registry.names()`) with a `render(size=..., ...)`
    method.

    A driver's side is the backend's own program, whose render takes no precision: verify feeds
    `precision` to each side that takes it (`_Pair`). GlslError (exit 1) when the shader does not
    compile, GLUnavailable (exit 2) without a GL context, WebGLUnavailable (exit 2) without
    headless Chromium, InputError (exit 2) without numba for the compiled engine.
    """
    program = registry.compile(shader, backend=backend)
    return program.impl if program.backend.driver else program


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

    def inputs(self, spec: FrameSpec, size, mouse, date, precision, samples) -> dict:
        """The keyword arguments a NumPy program renders this frame with, as the pair's."""
        shared = {
            "size": size,
            "time": spec.time,
            "frame": spec.frame,
            "mouse": mouse,
            "date": date,
            "samples": samples,
            "time_delta": spec.time_delta,
            "frame_rate": spec.frame_rate,
        }
        kwargs = {k: v for k, v in shared.items() if self._common is None or k in self._common}
        return {**kwargs, "precision": precision}

    def render(
        self, spec: FrameSpec, size, mouse, date, precision, samples, only_first: bool = False
    ) -> list[np.ndarray]:
        shared = {
            "size": size,
            "time": spec.time,
            "frame": spec.frame,
            "mouse": mouse,
            "date": date,
            "samples": samples,
            "time_delta": spec.time_delta,
            "frame_rate": spec.frame_rate,
        }
        images = []
        for program, accepted in zip(
            self.programs[:1] if only_first else self.programs, self._accepted
        ):
            kwargs = {k: v for k, v in shared.items() if self._common is None or k in self._common}
            if accepted is None or "precision" in accepted:
                kwargs["precision"] = precision
            images.append(program.render(**kwargs))
        return images

    def reference(self, spec: FrameSpec, size, mouse, date, samples) -> np.ndarray | None:
        """The float64 render of the program under test (None when it has no precision)."""
        accepted = self._accepted[0]
        if accepted is not None and "precision" not in accepted:
            return None
        backend = getattr(self.programs[0], "backend", None)
        if backend is not None and "float64" not in backend.precisions:
            return None
        return self.render(spec, size, mouse, date, "float64", samples, only_first=True)[0]


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
    notes: tuple[str, ...] = ()  # what the report should say besides the metrics
    # the engine that rendered the side under test (Program.engine: "numpy", "compiled lanes8",
    # "gl", ...)
    engine: str = ""

    @property
    def match(self) -> bool:
        return self.comparison.match

    def to_json(self) -> dict:
        """Exactly JSON_KEYS: the comparison's keys and "engine"."""
        return {**self.comparison.to_json(), "engine": self.engine}


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
    progress: Progress | None = None,
) -> Iterator[FrameResult]:
    """Render and compare frame by frame, every size times every frame of the schedule.

    `shader` is a `Shader` or a path. `backends` names the two sides (first = the one under
    test, reported as "numpy"); `programs` gives already compiled programs instead. Both are
    compiled before the first frame, so a GLSL error or a missing GL context surfaces at once.
    """
    check_precision(precision)
    specs = frame_specs(time, times, frames, fps, frame)
    size_list = [tuple(s) for s in (sizes or [size])]
    shader = _as_shader(shader)
    records = {b: registry.get(b) for b in backends}
    if programs is None:
        # drivers first: a missing context or browser is reported before a slower transpile
        ours = next((b for b in backends if not records[b].driver), None)
        by_name = {}
        for b in sorted(backends, key=lambda b: not records[b].driver):
            try:
                by_name[b] = compile_backend(shader, b)
            except GlslError as driver_error:
                if not records[b].driver or ours is None:
                    raise
                # our own front end's diagnostics are clearer than the driver's cascade (and
                # carry fix-its, e.g. iGlobalTime -> iTime): report them when it also fails
                try:
                    compile_backend(shader, ours)
                except GlslError as own:
                    raise own from None
                raise driver_error
        programs = [by_name[b] for b in backends]
    emulate_driver(programs)
    driver, driver_note = gl_driver(programs)
    for p in programs:
        llvmpipe_loop_limit(p)
    pair = _Pair(programs)
    name = shader.root or (shader.image.path if shader.image else "<shader>")
    # a side that can emulate float16 computes mediump in float32 here (semantics/mediump.py)
    mediump = (
        mediump_notes(shader) if any("float16" in r.precisions for r in records.values()) else ()
    )
    # the default CPU program's frames are the NumPy backend's bits (backends/tiered.py)
    undefined = UndefinedSide(shader, programs, records[backends[0]].name in ("numpy", "auto"))
    for w_h in size_list:
        for spec in specs:
            with undefined.explains_stops():
                numpy_img, gl_img = pair.render(spec, w_h, tuple(mouse), date, precision, samples)
            comparison = compare(numpy_img, gl_img, **(compare_options or {}))
            if not comparison.match:
                # unstable pixels: only worth a float64 render when the frame fails
                # (verification/compare.py), and the taint of undefined values likewise
                ref = (
                    pair.reference(spec, w_h, tuple(mouse), date, samples)
                    if precision == "float32"
                    else None
                )
                render = pair.inputs(spec, w_h, tuple(mouse), date, precision, samples)
                undef = undefined.mask(render, numpy_img)
                if ref is not None or undef is not None:
                    comparison = compare(
                        numpy_img,
                        gl_img,
                        reference=ref,
                        undefined=undef,
                        **(compare_options or {}),
                    )
                    if comparison.unstable_pixels:
                        comparison.unstable_lines = unstable_lines(
                            shader, comparison, w_h, spec, tuple(mouse), date
                        )
                    # compare sets the mask of the pixels it counts
                    if comparison.undefined_pixels and comparison.undefined_mask is not None:
                        comparison.undefined_lines = undefined.lines(
                            render, comparison.undefined_mask
                        )
            if progress is not None:
                progress.step(f"{name} t={spec.time:g}")
            comparison.driver = driver
            notes = (
                tuple(
                    f"{path}:{line}: this loop reached llvmpipe's limit of {LLVMPIPE_LOOP_LIMIT:,} "
                    "loop passes per pixel and was stopped on both sides (a GPU runs it to the end)"
                    for path, line in limited_loops(programs[0])
                )
                + mediump
            )
            if driver_note is not None and not comparison.match:
                notes += (driver_note,)
            yield FrameResult(
                name,
                spec,
                (int(w_h[0]), int(w_h[1])),
                comparison,
                numpy_img if keep_images else None,
                gl_img if keep_images else None,
                notes,
                engine_of(programs[0], records[backends[0]].name),
            )


class UndefinedSide:
    """Which pixels of a frame depend on the shader's undefined reads (semantics.analysis.undefined:
    out parameters, locals and globals read before written, operations on constants outside
    their range), and which reads. The taint is differential: the NumPy backend renders the
    frame with WebGL's values at those reads (zeros, its normal module) and with values drawn
    anew at each (`undefined="vary"`, backends/numpy_engine/transpile); a pixel whose colour
    differs between the two depends on an undefined value (compare.depends_on_undefined).
    Nothing else differs between the renders, so a pixel found is certain; a pixel both values
    colour alike is left to the other counts, which keeps a renderer's bug from hiding here.
    With several reads, each of the first MAX_SITES gets a render of its own that varies it
    alone: the pixels it changes are its count in `lines`.

    Renders happen only for a frame that fails and a program with undefined reads; a shader of
    several passes (buffers, channels) is not tainted: its undefined pixels stay mismatches."""

    MAX_SITES = 4

    def __init__(self, shader: Shader, programs: Sequence, numpy_under_test: bool) -> None:
        self.shader = shader
        self._found: list | None = None  # the reads, found when a frame first fails
        self._programs: dict = {}
        self._numpy_under_test = numpy_under_test  # its render is the zeros' render
        # the NumPy renders stop loops where the program under test does (llvmpipe's limit
        # against GL, none against WebGL), so that only the undefined values differ
        under_test = getattr(programs[0], "impl", programs[0])
        self._loop_limit = getattr(under_test, "loop_limit", LLVMPIPE_LOOP_LIMIT)
        self._float_to_uint = next(
            (
                p.meta["float_to_uint"]
                for p in (getattr(q, "impl", q) for q in programs)
                if isinstance(getattr(p, "meta", None), dict) and "float_to_uint" in p.meta
            ),
            None,
        )

    @property
    def sites(self) -> list:
        """The program's undefined reads, one per origin (semantics.analysis.origins), in
        source order; none for a shader of several passes."""
        if self._found is None:
            from ..frontend.parser import parse_shader
            from ..semantics import check
            from ..semantics.analysis import origins
            from ..shadertoy.channels import needs_passes

            self._found = []
            shader = self.shader
            tab = (
                "Image"
                if "Image" in shader.tabs
                else ("GLSL" if "GLSL" in shader.tabs else "Image")
            )
            if not needs_passes(shader):
                try:
                    self._found = list(origins(check(parse_shader(shader, tab))).values())
                except GlslError:
                    pass
        return self._found

    @contextmanager
    def explains_stops(self) -> Iterator[None]:
        """A render stopped by a runaway loop or the frame budget: its error also names the
        program's undefined reads (semantics.analysis.stop_notes), which may be why."""
        from ..semantics.analysis import STOPS, stop_notes

        try:
            yield
        except GlslError as e:
            for d in e.diagnostics:
                if d.rule in STOPS and self.sites:
                    d.notes.extend(stop_notes(self.sites, d.rule))
            raise

    def _program(self, mode: str, sites: tuple[int, ...] | None = None):
        key = (mode, sites)
        prog = self._programs.get(key)
        if prog is None:
            from ..backends.numpy_engine.program import compile_numpy

            prog = compile_numpy(self.shader, undefined=mode, undefined_sites=sites)
            prog.loop_limit = self._loop_limit
            if self._float_to_uint is not None:
                prog.emulate_float_to_uint(self._float_to_uint)
            self._programs[key] = prog
        return prog

    def mask(self, inputs: dict, image: np.ndarray) -> np.ndarray | None:
        """bool (h, w) of the pixels that depend on an undefined read (None: no reads to taint).
        `image` is the render under test, used as the zeros' render when it is the NumPy one."""
        if not self.sites:
            return None
        zero = image if self._numpy_under_test else self._program("zero").render(**inputs)
        self._zero = zero
        return depends_on_undefined(zero, self._program("vary").render(**inputs))

    def lines(self, inputs: dict, undefined: np.ndarray) -> list[dict]:
        """{"file", "line", "column", "code", "kind", "pixels"} of each undefined read whose
        variation changes some of the `undefined` pixels (the over-tolerance ones), most pixels
        first; "pixels" is null for the reads past MAX_SITES (not rendered apart)."""
        from ..base.diagnostics import source_line

        counts: list[int | None] = []
        if len(self.sites) == 1:
            counts = [int(undefined.sum())]
        else:
            for k in range(len(self.sites)):
                if k >= self.MAX_SITES:
                    counts.append(None)
                    continue
                alone = self._program("vary", (k,)).render(**inputs)
                counts.append(int((depends_on_undefined(self._zero, alone) & undefined).sum()))
        out = []
        for u, n in zip(self.sites, counts):
            if n == 0:
                continue
            out.append(
                {
                    "file": u.loc.path,
                    "line": u.loc.line,
                    "column": u.loc.column,
                    "code": (source_line(u.loc.path, u.loc.line) or "").strip(),
                    "kind": u.kind,
                    "pixels": n,
                }
            )
        return sorted(out, key=lambda d: (-(d["pixels"] or 0), d["file"], d["line"]))


UNSTABLE_PROBES = 24  # unstable pixels traced per frame to name the lines that lose precision
# ... and the steps (float64 runs, and float32 runs up to their first departure) they may trace
# per frame: about 0.1 ms of CPU each, so ~20 s; a path tracer's pixel runs ~9,000 steps
UNSTABLE_STEPS = 200_000


def unstable_lines(
    shader: Shader, comparison: Comparison, size, spec: FrameSpec, mouse, date
) -> list[dict]:
    """Where the unstable pixels lose their precision: up to UNSTABLE_PROBES of them, spread over
    the image, are traced by `glslcheck probe` (float32 beside its float64 shadow) and each is
    attributed to its first statement that keeps fewer than probe.UNSTABLE_BITS bits. Pixels are
    traced in an order that keeps the traced ones spread over the image, until UNSTABLE_STEPS
    steps have run (at least one pixel). Entries {"file", "line", "code", "bits", "pixels",
    "sampled"}, most pixels first; "pixels" extrapolates the traced share to all unstable pixels,
    "bits" is the fewest kept at that line and "sampled" the number of pixels traced."""
    from .probe import UNSTABLE_BITS, Inputs, Probe, first_unstable_traced

    mask = comparison.unstable_mask
    if mask is None or not mask.any():
        return []
    ys, xs = np.nonzero(mask)
    picks = np.unique(np.linspace(0, len(xs) - 1, min(UNSTABLE_PROBES, len(xs))).astype(int))
    try:
        probe = Probe(shader)
    # attribution is a hint: a shader probe cannot trace keeps its count
    except Exception:  # noqa: BLE001
        return []
    inputs = Inputs(
        size=(int(size[0]), int(size[1])), time=spec.time, frame=spec.frame, mouse=mouse, date=date
    )
    found: dict[tuple, list] = {}
    sampled = steps = 0
    for i in picks[_spread(len(picks))]:
        if steps >= UNSTABLE_STEPS:
            break
        t32, t64 = probe.traces(int(xs[i]), int(ys[i]), inputs, stop_bits=UNSTABLE_BITS)[3:]
        steps += len(t32.records) + t32.truncated + len(t64.records) + t64.truncated
        sampled += 1
        step = first_unstable_traced(probe, t32, t64)
        if step is not None:
            entry = found.setdefault((step.file, step.line, step.code.strip()), [0, step.bits])
            entry[0] += 1
            entry[1] = min(entry[1], step.bits)
    scale = len(xs) / sampled
    lines = [
        {
            "file": f,
            "line": ln,
            "code": code,
            "bits": int(bits),
            "pixels": int(round(n * scale)),
            "sampled": sampled,
        }
        for (f, ln, code), (n, bits) in found.items()
    ]
    return sorted(lines, key=lambda d: (-d["pixels"], d["file"], d["line"]))


def _spread(n: int) -> list[int]:
    """0..n-1 in bit-reversed order (0, n/2, n/4, 3n/4, ...): every prefix is spread over the
    range."""
    bits = max(1, (n - 1).bit_length())
    order = [int(f"{k:0{bits}b}"[::-1], 2) for k in range(1 << bits)]
    return [k for k in order if k < n]


# llvmpipe stops every loop once an invocation has made 65,535 loop passes in all
# (gallivm's LP_MAX_TGSI_LOOP_ITERATIONS, one budget shared by all loops); a 70,000-pass loop
# that adds 1/70000 gives 0.9367 there. The NumPy side emulates it when verifying.
LLVMPIPE_LOOP_LIMIT = 65535


def llvmpipe_loop_limit(program) -> None:
    """Make a NumPy program stop loops as llvmpipe does (see NumpyProgram.loop_limit)."""
    impl = getattr(program, "impl", program)
    if hasattr(impl, "loop_limit"):
        impl.loop_limit = LLVMPIPE_LOOP_LIMIT


def limited_loops(program) -> list[tuple[str, int]]:
    """(file, line) of loops the emulated limit stopped, for the verify report."""
    impl = getattr(program, "impl", program)
    return impl.limited_loops() if hasattr(impl, "limited_loops") else []


def emulate_driver(programs: Sequence) -> None:
    """Have every program that emulates a driver (the NumPy side) compute what the measured
    driver (the GL side) does where GLSL leaves a value undefined and the CPU decides
    (glslcheck/backends/driver_profile.py). A driver that follows no known model is reported on
    stderr, and the NumPy side keeps its prediction for this machine."""
    programs = [getattr(p, "impl", p) for p in programs]  # a Program wraps a backend's program
    models = {p.float_to_uint_model for p in programs if hasattr(p, "float_to_uint_model")}
    if not models:
        return
    model = models.pop() if len(models) == 1 else None
    if model is None:
        logging.getLogger("glslcheck").warning(
            "note: the GL driver's uint(x) of negative, NaN or huge x follows no model glslcheck "
            "knows (glslcheck/backends/driver_profile.py); pixels that depend on such "
            "conversions may differ"
        )
        return
    for p in programs:
        if hasattr(p, "emulate_float_to_uint"):
            p.emulate_float_to_uint(model)


def gl_driver(programs: Sequence) -> tuple[dict | None, str | None]:
    """The GL side's {"renderer", "mesa", "emulated"} (None when no side is a GL driver), and
    the note verify prints with a mismatch when the NumPy backend's bit-exact emulation was
    copied from another driver (driver_profile.emulation_note), else None."""
    from ..backends.driver_profile import driver_name, emulation_note, is_emulated

    for p in programs[1:]:
        ctx = getattr(getattr(p, "impl", p), "ctx", None)
        if ctx is not None and hasattr(ctx, "info"):
            renderer, mesa = driver_name(ctx)
            return {
                "renderer": renderer,
                "mesa": mesa,
                "emulated": is_emulated(renderer, mesa),
            }, emulation_note(ctx)
    return None, None


def engine_of(program, name: str) -> str:
    """The engine that rendered `program`'s last frame (Program.engine), else `name`."""
    engine = getattr(program, "engine", None)
    return engine if isinstance(engine, str) else name


def verify(shader, **options) -> list[Comparison]:
    """The comparisons of every frame `verify_frames(shader, **options)` renders, in order."""
    return [r.comparison for r in verify_frames(shader, **options)]


def diff_paths(path: str | os.PathLike, count: int) -> Iterator[Path]:
    """`diff.png` for one frame; `diff-0.png`, `diff-1.png`, ... for several (made as needed)."""
    p = Path(path)
    if count == 1:
        yield p
        return
    suffix = p.suffix or ".png"
    stem = p.name[: -len(p.suffix)] if p.suffix else p.name
    for i in range(count):
        yield p.with_name(f"{stem}-{i}{suffix}")


# ---------------------------------------------------------------------------------------------
# Progress bar (stderr; no dependency).


class Progress:
    """A one-line progress bar redrawn with '\\r': `verify [#####.....] 5/10 label`.

    Disabled (a no-op) when `enabled` is False. `finish()` ends the line. `NAME` starts the line
    (bench's bar is a subclass with its own).
    """

    WIDTH = 24
    NAME = "verify"

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
        line = f"\r{self.NAME} [{bar}] {self.done}/{self.total} {label}"
        self.stream.write(line[:120].ljust(80))
        self.stream.flush()
        self._drawn = True

    def finish(self) -> None:
        if self.enabled and self._drawn:
            self.stream.write("\n")
            self.stream.flush()
            self._drawn = False
