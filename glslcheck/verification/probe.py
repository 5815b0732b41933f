"""Probing a shader: what one pixel computed, statement by statement, and where NaN/Inf pixels came
from.

Library API (the `glslcheck probe` command and verify's unstable pixels call it):

    p = Probe("lab_shaders/07_final")                # parse + check + the traced module
    inputs = Inputs(size=(800, 450), time=0.0)       # the uniforms, as `render` takes them
    report = p.pixel(400, 225, inputs)               # x, y from the top left (as verify prints)
    report = p.pixel(None, None, inputs, frag_coord=(400.5, 224.5))
    report.steps, report.color, report.first_nan     # Step list, RGBA, Origin or None
    nan = p.nan_origins(inputs)                      # NanReport: every NaN/Inf pixel by origin
    step = first_unstable(p, 400, 225, inputs)       # first Step whose float32 value keeps
                                                     # fewer than 16 bits of its float64 shadow

The steps come from the traced module (backends/numpy_engine/tracing.py) run on the probed pixel's
lane (its 2x2 quad when the shader takes derivatives) twice: in float32, the render's precision, and
in float64, the shadow. The two runs are paired step by step (`pairs`: where they part, `difflib`
realigns the rest, the float64 run having taken another branch or run another number of
iterations; an unpaired step has no shadow). `bits`: how many significant bits of the float64
shadow the float32 value keeps, min(24, floor(-log2(|v32 - v64| / |v64|))) with |.| the largest
component (a vector or matrix is judged as a whole: a component that is tiny next to the others does
not count), 24 when equal.
"""

from __future__ import annotations

import difflib
import math
import os
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..backends.numpy_engine.runtime_values import Struct
from ..backends.numpy_engine.tracing import (
    HELP,
    OPERATIONS,
    LaneTracer,
    PixelTracer,
    Site,
    TraceTranspiler,
)
from ..base.diagnostics import GlslError, InputError, source_line
from ..semantics.analysis import STOPS, stop_notes, undefined_reads

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..backends.numpy_engine.program import NumpyProgram

# first_unstable: a value keeping fewer bits than this has lost more than a third of float32's 24
UNSTABLE_BITS = 16
BITS_KINDS = ("assign", "return", "call")  # the steps whose values are compared with their shadow
FIRST_ITERATIONS, LAST_ITERATIONS = (
    3,
    2,
)  # a longer loop prints these iterations and folds the others


@dataclass
class Inputs:
    """The uniforms of one frame, as `glslcheck render` takes them."""

    size: tuple[int, int] = (800, 450)
    time: float = 0.0
    frame: int = 0
    mouse: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)
    date: Any = None

    def values(self) -> dict:
        from ..shadertoy.wrapper import frame_uniforms

        return frame_uniforms(*self.size, self.time, self.frame, self.mouse, self.date)


@dataclass
class Step:
    """One statement the pixel executed: where, what kind (assign, branch, loop, call, return,
    discard), a name (variable, function, `if`, ...), the float32 value, the float64 shadow
    (None when unpaired) and the bits the value keeps (None for non-float values)."""

    file: str
    line: int
    column: int
    code: str
    kind: str
    name: str
    value: Any
    value64: Any = None
    bits: int | None = None
    depth: int = 0
    what: str = ""  # loop markers: start, iteration, end
    count: int = 0
    why: str = ""  # an undefined value's step: the kind of read (semantics.analysis.undefined)
    read_line: int = 0  # ... and the line it is read at

    def to_json(self) -> dict:
        return {
            "file": self.file,
            "line": self.line,
            "code": self.code,
            "kind": self.kind,
            "name": self.name,
            "value": to_py(self.value, True),
            "value64": to_py(self.value64, False),
            "bits": self.bits,
            **({"undefined": self.why, "read_line": self.read_line} if self.why else {}),
        }


@dataclass
class Origin:
    """Where a first NaN or Inf appeared: the operation's location and GLSL text, what made it,
    and (for --nan) the pixels it reached with their bounding box (x0, y0, x1, y1 from the top
    left)."""

    file: str | None
    line: int | None
    column: int | None
    code: str
    operation: str
    source: str = ""  # the whole source line
    pixels: int = 0
    box: tuple[int, int, int, int] = (0, 0, 0, 0)
    # of `pixels`, those whose colour changes with the shader's undefined values (--nan)
    undefined_pixels: int = 0

    @property
    def help(self) -> str:
        return HELP.get(self.operation, "")

    def to_json(self, with_pixels: bool = True) -> dict:
        out: dict[str, Any] = {
            "file": self.file,
            "line": self.line,
            "column": self.column,
            "code": self.code,
            "operation": self.operation,
        }
        if with_pixels:
            out.update(
                pixels=self.pixels, box=list(self.box), undefined_pixels=self.undefined_pixels
            )
        return out


@dataclass
class PixelReport:
    pixel: tuple[int, int]
    frag_coord: tuple[float, float]
    color: tuple[float, ...]  # RGBA
    steps: list[Step]
    first_nan: Origin | None
    truncated: int = 0  # steps past the recording limit

    def to_json(self) -> dict:
        return {
            "pixel": list(self.pixel),
            "frag_coord": list(self.frag_coord),
            "color": [_float(c, True) for c in self.color],
            "steps": [s.to_json() for s in self.steps],
            "first_nan": self.first_nan.to_json(False) if self.first_nan else None,
        }


@dataclass
class NanReport:
    nan_pixels: int
    inf_pixels: int
    origins: list[Origin] = field(default_factory=list)
    # the program's undefined reads when some NaN/Inf pixel depends on them:
    # {"file", "line", "column", "kind"} (semantics.analysis.undefined)
    undefined_reads: list[dict] = field(default_factory=list)

    def to_json(self) -> dict:
        return {
            "nan_pixels": self.nan_pixels,
            "inf_pixels": self.inf_pixels,
            "origins": [o.to_json() for o in self.origins],
            "undefined_reads": list(self.undefined_reads),
        }


class Probe:
    """A shader compiled for probing: its traced module (float32 and float64) and, for --nan,
    its normal module."""

    def __init__(self, shader: Any) -> None:
        from ..backends.numpy_engine.transpile import check_program
        from ..frontend.parser import parse_shader
        from ..shadertoy.sources import Shader, load_shader

        self.shader = shader if isinstance(shader, Shader) else load_shader(shader)
        from ..shadertoy.channels import needs_passes

        if needs_passes(self.shader):  # its iChannels would read unbound textures: say so instead
            from ..base.diagnostics import InputError

            raise InputError(
                f"{self.shader.root}: error: probe does not support buffers and channels yet "
                "(glslcheck/shadertoy/channels.py); render or verify it instead"
            )
        tab = (
            "Image"
            if "Image" in self.shader.tabs
            else ("GLSL" if "GLSL" in self.shader.tabs else "Image")
        )
        self.model = check_program(parse_shader(self.shader, tab))
        src = self.shader.tabs.get(tab)
        self.path = src.path if src is not None else self.shader.root
        tr = TraceTranspiler(self.model, self.path)
        self.source, self.meta = tr.module()
        self.sites: list[Site] = tr.sites
        self.filename = f"<glslcheck-probe {self.path}>"
        self._modules: dict[str, dict] = {}
        self._program: NumpyProgram | None = None
        self._tracers = _PerThread()

    def module(self, precision: str) -> dict:
        from ..backends.numpy_engine.tiles import execute_module

        if precision not in self._modules:
            self._modules[precision] = execute_module(
                self.source, self.filename, self.meta, precision
            )
        return self._modules[precision]

    def program(self):
        """The normal (untraced) NumpyProgram, for the frame --nan scans."""
        if self._program is None:
            from ..backends.numpy_engine.program import NumpyProgram
            from ..backends.numpy_engine.transpile import transpile

            t = transpile(self.model, self.path)
            self._program = NumpyProgram(t.source, t.meta, t.filename)
        return self._program

    # -- running lanes ---------------------------------------------------------------------------
    def run(
        self, precision: str, inputs: Inputs, frags: np.ndarray, width: int, tracer: LaneTracer
    ) -> np.ndarray:
        """RGBA (4, lanes) of the traced module on fragment coordinates `frags` (2, lanes),
        lanes in rows of `width` (for derivatives), with `tracer` as T."""
        from ..backends.numpy_engine.program import frame_seconds, uniform_value
        from ..backends.numpy_engine.tiles import Budget, LaneHelpers, State
        from ..shadertoy.wrapper import UNIFORMS_BY_NAME

        ns = self.module(precision)
        rt = ns["rt"]
        ns["T"] = self._tracers
        self._tracers.local.tracer = tracer
        values = inputs.values()
        uniforms = {
            f"u_{u}": uniform_value(rt, u, values.get(u, UNIFORMS_BY_NAME[u].default))
            for u in self.meta["uniforms"]
        }
        lanes = frags.shape[-1]
        with rt.errstate():
            proto = State(
                **uniforms, lanes=1, width=1, stats=None, discard=LaneHelpers.NO, parent=None
            )
            ns["init_globals"](proto)
            frag = frags.astype(rt.F)
            S = State(**proto.__dict__)
            S.lanes, S.width, S.frag_coord = lanes, width, frag
            if "S.frag_coord4" in self.source:
                S.frag_coord4 = np.concatenate(
                    [frag, np.full((1, lanes), 0.5, rt.F), np.ones((1, lanes), rt.F)]
                )
            S.budget = Budget(frame_seconds()).start()  # a runaway trace stops as a frame does
            try:
                with self.undefined_notes():
                    color = ns["shade"](S)
            finally:
                S.budget.finish()
            color = np.broadcast_to(color, (len(color), lanes)).astype(np.float64)
            if len(color) == 3:
                color = np.concatenate([color, np.ones((1, lanes))])
            return np.where(np.broadcast_to(S.discard, (lanes,)), 0.0, color)

    def undefined_mask(self, inputs: Inputs, image: np.ndarray) -> np.ndarray | None:
        """bool (h, w): the pixels of `image` (this frame's render) whose colour changes when
        the shader's undefined values do (verify's taint: the module that draws them anew,
        compare.depends_on_undefined); None when the program has no undefined reads."""
        from ..semantics.analysis import origins

        found = list(origins(self.model).values())
        if not found:
            return None
        from ..backends.numpy_engine.program import NumpyProgram
        from ..backends.numpy_engine.transpile import transpile
        from .compare import depends_on_undefined

        t = transpile(self.model, self.path, undefined="vary")
        varied = NumpyProgram(t.source, t.meta, t.filename).render(
            size=inputs.size,
            time=inputs.time,
            frame=inputs.frame,
            mouse=inputs.mouse,
            date=inputs.date,
        )
        self.undefined_found = found
        return depends_on_undefined(image, varied)

    @contextmanager
    def undefined_notes(self) -> Iterator[None]:
        """A loop that never ends (or a frame over its budget) in a program that reads undefined
        values: its error also names those reads, which may be why (a `while (true)` waiting
        for a random point whose seed is an out parameter ends on one driver, not with zeros)."""
        try:
            yield
        except GlslError as e:
            reads = undefined_reads(self.model)
            for d in e.diagnostics:
                if d.rule in STOPS and reads:
                    d.notes.extend(stop_notes(reads, d.rule))
            raise

    # -- one pixel -------------------------------------------------------------------------------
    def pixel(
        self,
        x: int | None,
        y: int | None,
        inputs: Inputs,
        frag_coord: tuple[float, float] | None = None,
    ) -> PixelReport:
        """Every step pixel (x, y) (from the top left) executed, or the pixel at `frag_coord`."""
        (x, y), (fx, fy), color, t32, t64 = self.traces(x, y, inputs, frag_coord)
        lane = t32.lane
        steps = self._steps(t32, t64)
        first = (
            self.origin(int(t32.origin[lane]), int(t32.operation[lane]))
            if t32.origin[lane] >= 0
            else None
        )
        return PixelReport(
            (x, y),
            (fx, fy),
            tuple(float(np.float32(c)) for c in color),
            steps,
            first,
            t32.truncated,
        )

    def traces(
        self,
        x: int | None,
        y: int | None,
        inputs: Inputs,
        frag_coord: tuple[float, float] | None = None,
        stop_bits: int | None = None,
    ):
        """The float32 and float64 runs of pixel (x, y) (or `frag_coord`): ((x, y), (fx, fy),
        RGBA of the float32 run, its PixelTracer, the float64 one's). With `stop_bits` the
        float64 run goes first and the float32 run stops at its first step that keeps fewer
        bits of its shadow while both follow the same path (_ShadowedTracer; RGBA None then)."""
        w, h = inputs.size
        if frag_coord is None:
            assert x is not None and y is not None, "a pixel or a fragment coordinate"
            if not (0 <= x < w and 0 <= y < h):
                raise InputError(
                    f"error: the pixel {x},{y} is outside the {w}x{h} image "
                    f"(x 0..{w - 1}, y 0..{h - 1} from the top left)"
                )
            frag_coord = (x + 0.5, h - 1 - y + 0.5)
        fx, fy = (float(v) for v in frag_coord)
        x, y = int(math.floor(fx)), h - 1 - int(math.floor(fy))
        if self.meta.get("uses_derivatives"):  # the pixel's 2x2 quad, as llvmpipe shades it
            qx, qy = int(math.floor(fx)) & ~1, int(math.floor(fy)) & ~1
            frags = np.array(
                [[qx + 0.5, qx + 1.5, qx + 0.5, qx + 1.5], [qy + 0.5, qy + 0.5, qy + 1.5, qy + 1.5]]
            )
            lane = (int(math.floor(fy)) - qy) * 2 + (int(math.floor(fx)) - qx)
            frags[:, lane] = (fx, fy)
            width = 2
        else:
            frags, lane, width = np.array([[fx], [fy]]), 0, 1
        t64 = PixelTracer(frags.shape[1], self.sites, lane)
        color: np.ndarray | None
        if stop_bits is None:
            t32 = PixelTracer(frags.shape[1], self.sites, lane)
            color = self.run("float32", inputs, frags, width, t32)[:, lane]
            self.run("float64", inputs, frags, width, t64)
            return (x, y), (fx, fy), color, t32, t64
        self.run("float64", inputs, frags, width, t64)
        t32 = _ShadowedTracer(frags.shape[1], self.sites, lane, t64.records, stop_bits)
        try:
            color = self.run("float32", inputs, frags, width, t32)[:, lane]
        except _Departed:
            color = None
        return (x, y), (fx, fy), color, t32, t64

    def origin(self, site: int, operation: int) -> Origin:
        s = self.sites[site]
        return Origin(s.path, s.line, s.column, s.expr or s.code, OPERATIONS[operation], s.code)

    def _steps(self, t32: PixelTracer, t64: PixelTracer) -> list[Step]:
        r32, r64 = t32.records, t64.records
        pair = dict(pairs(r32, r64))
        steps = []
        for i, r in enumerate(r32):
            s = self.sites[r.site]
            v64 = r64[pair[i]].value if i in pair else None
            value = r.value
            if s.kind == "call":
                value = dict(zip(s.params, r.value))
                v64 = dict(zip(s.params, v64)) if v64 is not None else None
            elif s.kind == "loop":
                value = v64 = r.count if r.what != "start" else None
            bits = bits_kept(value, v64) if s.kind in BITS_KINDS and v64 is not None else None
            steps.append(
                Step(
                    s.path,
                    s.line,
                    s.column,
                    s.code,
                    s.kind,
                    _step_name(s, r.what),
                    value,
                    v64,
                    bits,
                    r.depth,
                    r.what,
                    r.count,
                    s.why,
                    s.read_line,
                )
            )
        return steps

    # -- NaN origins over a frame ------------------------------------------------------------------
    def nan_origins(self, inputs: Inputs) -> NanReport:
        """Render the frame, then run the traced module on its NaN/Inf pixels and group them by
        where their first NaN or Inf appeared."""
        from ..backends.numpy_engine.program import tile_pool
        from ..backends.numpy_engine.tiles import TILE_LANES

        w, h = inputs.size
        with self.undefined_notes():
            img = self.program().render(
                size=inputs.size,
                time=inputs.time,
                frame=inputs.frame,
                mouse=inputs.mouse,
                date=inputs.date,
            )
        nan = np.isnan(img).any(axis=-1)
        inf = np.isinf(img).any(axis=-1) & ~nan
        report = NanReport(int(nan.sum()), int(inf.sum()))
        ys, xs = np.nonzero(nan | inf)  # rows from the top
        if not len(xs):
            return report
        undefined = self.undefined_mask(inputs, img)
        fx, fy = xs.astype(np.int64), (h - 1 - ys).astype(np.int64)
        if self.meta.get("uses_derivatives"):  # whole quads, stacked in a 2-wide strip
            quads = np.unique(np.stack([fy & ~1, fx & ~1], axis=1), axis=0)
            qy, qx = quads[:, 0], quads[:, 1]
            lx = np.stack([qx, qx + 1, qx, qx + 1], axis=1).reshape(-1)
            ly = np.stack([qy, qy, qy + 1, qy + 1], axis=1).reshape(-1)
            width, chunk = 2, TILE_LANES // 4 * 4
        else:
            lx, ly, width, chunk = fx, fy, 1, TILE_LANES
        origin = np.full(len(lx), -1, np.int64)
        operation = np.full(len(lx), -1, np.int64)

        def scan(start: int) -> None:
            sl = slice(start, start + chunk)
            frags = np.stack([lx[sl] + 0.5, ly[sl] + 0.5])
            t = LaneTracer(frags.shape[1], self.sites)
            self.run("float32", inputs, frags, width if width == 2 else frags.shape[1], t)
            origin[sl], operation[sl] = t.origin, t.operation

        self.module("float32")  # executed once, before the threads share it
        starts = range(0, len(lx), chunk)
        threads = os.cpu_count() or 1
        if threads > 1 and len(starts) > 1:
            for f in [tile_pool(threads).submit(scan, s) for s in starts]:
                f.result()
        else:
            for s in starts:
                scan(s)
        if (
            width == 2
        ):  # from quad lanes back to the NaN/Inf pixels (a quad's other pixels may be fine)
            q = np.searchsorted(
                quads[:, 0] * (w + 2) + quads[:, 1], (fy & ~1) * (w + 2) + (fx & ~1)
            )
            idx = 4 * q + 2 * (fy & 1) + (fx & 1)
            origin, operation = origin[idx], operation[idx]
        keys = (origin + 1) * len(OPERATIONS) + operation
        for key in np.unique(keys):
            m = keys == key
            o, op = int(key // len(OPERATIONS)) - 1, int(key % len(OPERATIONS))
            if o >= 0:
                org = self.origin(o, op)
            else:
                org = Origin(None, None, None, "", "unknown (no traced operation made it)")
            org.pixels = int(m.sum())
            org.box = (int(xs[m].min()), int(ys[m].min()), int(xs[m].max()), int(ys[m].max()))
            if undefined is not None:
                org.undefined_pixels = int(undefined[ys[m], xs[m]].sum())
            report.origins.append(org)
        report.origins.sort(key=lambda o: (-o.pixels, o.file or "", o.line or 0, o.column or 0))
        if any(o.undefined_pixels for o in report.origins):
            report.undefined_reads = [
                {"file": u.loc.path, "line": u.loc.line, "column": u.loc.column, "kind": u.kind}
                for u in self.undefined_found
            ]
        return report


class _PerThread:
    """The modules' `T`: the tracer of the calling thread (--nan scans chunks on threads)."""

    def __init__(self) -> None:
        self.local = threading.local()

    def __getattr__(self, name: str) -> Any:
        return getattr(self.local.tracer, name)


def _key(r: Any) -> tuple:
    return (r.site, r.depth, r.what)


def pairs(r32: list, r64: list, realign: int | None = None) -> Iterator[tuple[int, int]]:
    """(i, j): record r32[i] paired with its shadow r64[j], in order of i. While both runs follow
    the same path (the same site, depth and loop marker step by step) step i is paired with step
    i; where they part, `difflib` realigns the two rest of the runs (the float64 run took another
    branch or ran another number of iterations; an unpaired step has no shadow). `realign`: the
    longest rest realigned (difflib's time grows about quadratically with it); past it the
    pairs stop at the parting. (difflib over the whole runs, longest block first, could pair a
    loop step with another iteration's shadow even where the runs never parted before: a
    31-pathtrace pixel blamed `vec2 f = vec2(float(i), float(j)) / ...` for 0 bits that way.)"""
    n = min(len(r32), len(r64))
    i = 0
    while i < n and _key(r32[i]) == _key(r64[i]):
        yield i, i
        i += 1
    if i == n or (realign is not None and max(len(r32), len(r64)) - i > realign):
        return
    sm = difflib.SequenceMatcher(
        None, [_key(r) for r in r32[i:]], [_key(r) for r in r64[i:]], autojunk=False
    )
    for a, b, size in sm.get_matching_blocks():
        for k in range(size):
            yield i + a + k, i + b + k


# first_unstable: the longest rest of a run realigned where the float32 and float64 runs part
# before any value departs; past it the pixel gives no answer (a path tracer's bounces take
# thousands of steps, and difflib took seconds per pixel on them)
REALIGN_STEPS = 2_000


def first_unstable(
    probe: Probe,
    x: int,
    y: int,
    inputs: Inputs,
    min_bits: int = UNSTABLE_BITS,
    realign: int | None = REALIGN_STEPS,
) -> Step | None:
    """The first statement of pixel (x, y) (from the top left) whose float32 value keeps fewer
    than `min_bits` bits of its float64 shadow (Step: file, line, code, bits), or None: the steps
    `probe.pixel` reports, compared in order and only up to the first that departs. Where the
    two runs part before any value departs, at most `realign` steps are realigned (None: all)."""
    _, _, _, t32, t64 = probe.traces(x, y, inputs, stop_bits=min_bits)
    return first_unstable_traced(probe, t32, t64, min_bits, realign)


def first_unstable_traced(
    probe: Probe,
    t32: PixelTracer,
    t64: PixelTracer,
    min_bits: int = UNSTABLE_BITS,
    realign: int | None = REALIGN_STEPS,
) -> Step | None:
    """first_unstable on the two runs of a pixel (Probe.traces; a _ShadowedTracer has compared
    the steps up to where the runs part already)."""
    r32, r64 = t32.records, t64.records
    checked = getattr(t32, "checked", 0)
    for i, j in pairs(r32, r64, realign):
        if i < checked:
            continue
        site = probe.sites[r32[i].site]
        value, v64, bits = _compared(site, r32[i], r64[j])
        if bits is not None and bits < min_bits:
            r = r32[i]
            return Step(
                site.path,
                site.line,
                site.column,
                site.code,
                site.kind,
                _step_name(site, r.what),
                value,
                v64,
                bits,
                r.depth,
                r.what,
                r.count,
            )
    return None


def _compared(site: Site, r: Any, r64: Any) -> tuple[Any, Any, int | None]:
    """A step's float32 value, its float64 shadow (a call's arguments by name) and the bits kept
    (None for steps not compared)."""
    value, v64 = r.value, r64.value
    if site.kind not in BITS_KINDS or v64 is None:
        return value, v64, None
    if site.kind == "call":
        value, v64 = dict(zip(site.params, value)), dict(zip(site.params, v64))
    return value, v64, bits_kept(value, v64)


class _Departed(Exception):
    """The float32 run's step departed from its shadow: the run stops (_ShadowedTracer)."""


class _ShadowedTracer(PixelTracer):
    """The float32 run's PixelTracer for first_unstable: while its steps follow the float64 run's
    (`shadow`, the same site, depth and loop marker), each is compared with its shadow as it is
    recorded (`checked` counts them) and the run stops at the first that keeps fewer than
    `min_bits` bits; the rest of a pixel's run costs nothing then."""

    def __init__(
        self, lanes: int, sites: list[Site], lane: int, shadow: list, min_bits: int
    ) -> None:
        super().__init__(lanes, sites, lane)
        self.shadow, self.min_bits = shadow, min_bits
        self.checked = 0

    def _record(self, rec: Any) -> None:
        super()._record(rec)
        k = self.checked
        if k != len(self.records) - 1 or k >= len(self.shadow) or _key(self.shadow[k]) != _key(rec):
            return  # parted (or past the recording limit): first_unstable_traced realigns
        bits = _compared(self.sites[rec.site], rec, self.shadow[k])[2]
        if bits is not None and bits < self.min_bits:
            raise _Departed
        self.checked = k + 1


# ---------------------------------------------------------------------------------------------
# Values: bits kept, JSON, text
# ---------------------------------------------------------------------------------------------


def _leaves(v: Any) -> list[Any]:
    if isinstance(v, Struct):
        return [x for f in v.fields.values() for x in _leaves(f)]
    if isinstance(v, dict):
        return [x for f in v.values() for x in _leaves(f)]
    if isinstance(v, (list, tuple)):
        return [x for f in v for x in _leaves(f)]
    return [v]


_TINY32 = float(np.finfo(np.float32).tiny)


def bits_kept(v32: Any, v64: Any) -> int | None:
    """Significant bits of v64 that v32 keeps (module docstring); None when there is no float.
    Each float leaf (a scalar, vector or matrix, a struct's or a call's member) is judged as a
    whole, all leaves at once in one flat array."""
    a_all, b_all = _leaves(v32), _leaves(v64)
    if len(a_all) != len(b_all):
        return None
    pa, pb, sizes = [], [], []
    for a, b in zip(a_all, b_all):
        a, b = np.asarray(a), np.asarray(b)
        if a.dtype.kind == "f" and a.shape == b.shape:
            pa.append(a.reshape(-1))
            pb.append(b.reshape(-1))
            sizes.append(a.size)
    if not pa:
        return None
    out = 24 if 0 in sizes else None  # an empty leaf: nothing differs
    keep = [k for k, n in enumerate(sizes) if n]
    if not keep:
        return out
    sizes = [sizes[k] for k in keep]
    a = np.concatenate([pa[k] for k in keep]).astype(np.float64)
    b = np.concatenate([pb[k] for k in keep]).astype(np.float64)
    starts = np.cumsum([0] + sizes[:-1])
    with np.errstate(invalid="ignore", over="ignore"):
        # a shadow below float32's smallest normal (2^-126) is zero in float32 (GPUs flush it)
        b = np.where(np.abs(b) < _TINY32, 0.0, b)
        a = np.where(np.abs(a) < _TINY32, 0.0, a)
        fin_a, fin_b = np.isfinite(a), np.isfinite(b)
        fin = fin_a & fin_b
        same = np.logical_and.reduceat((a == b) | (np.isnan(a) & np.isnan(b)), starts)
        finite_a = np.logical_and.reduceat(fin_a, starts)
        finite = np.logical_and.reduceat(fin, starts)
        err = np.maximum.reduceat(np.where(fin, np.abs(a - b), 0.0), starts)
        scale = np.maximum.reduceat(np.where(fin, np.abs(b), 0.0), starts)
    for k in range(len(sizes)):
        if same[k] and not finite_a[k]:
            continue  # NaN or Inf in both: no bits to count
        if same[k]:
            bits = 24
        elif not finite[k]:
            bits = 0
        else:
            e, sc = float(err[k]), float(scale[k])
            bits = 0 if sc == 0.0 or e >= sc else min(24, int(math.floor(-math.log2(e / sc))))
        out = bits if out is None else min(out, bits)
    return out


def _float(x: Any, f32: bool) -> float | str:
    x = float(x)
    if math.isnan(x):
        return "nan"
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return float(str(np.float32(x))) if f32 else x


def to_py(v: Any, f32: bool) -> Any:
    """A JSON value: floats as numbers ("nan", "inf", "-inf" as strings), vectors as lists,
    matrices as lists of columns, structs as objects."""
    if v is None:
        return None
    if isinstance(v, Struct):
        return {k[2:] if k.startswith("m_") else k: to_py(x, f32) for k, x in v.fields.items()}
    if isinstance(v, dict):
        return {k: to_py(x, f32) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [to_py(x, f32) for x in v]
    if isinstance(v, str):
        return v
    a = np.asarray(
        v
    )  # also Python and NumPy scalars (np.float64 is a float: NaN must become "nan")
    if a.ndim:
        return [to_py(x, f32) for x in a]
    if a.dtype.kind == "f":
        return _float(a, f32)
    if a.dtype.kind == "b":
        return bool(a)
    return int(a) if a.dtype.kind in "iu" else a.item()


def fmt(v: Any, f32: bool = True) -> str:
    """A value as GLSL-like text: 0.70710677, (1, 0.5, 0), true, {origin: (...), ...}, [..]."""
    p = to_py(v, f32)
    return _fmt(p, f32, top=True)


def _fmt(p: Any, f32: bool, top: bool = False) -> str:
    if isinstance(p, dict):
        return "{" + ", ".join(f"{k}: {_fmt(x, f32)}" for k, x in p.items()) + "}"
    if isinstance(p, list):
        return "(" + ", ".join(_fmt(x, f32) for x in p) + ")"
    if isinstance(p, bool):
        return "true" if p else "false"
    if isinstance(p, float):
        return f"{p:.8g}" if f32 else f"{p:.12g}"
    return str(p)


def _step_name(s: Site, what: str) -> str:
    return f"{s.name} {what}" if s.kind == "loop" else s.name


def format_pixel(report: PixelReport, shader: str, inputs: Inputs) -> str:
    """The text `glslcheck probe --pixel` prints."""
    x, y = report.pixel
    fx, fy = report.frag_coord
    w, h = inputs.size
    out = [
        f"{shader}: pixel {x},{y} from the top left (fragCoord {fx:g}, {fy:g}) of {w}x{h}, "
        f"iTime {inputs.time:g}",
        "each step: file:line, the source line, then what it did; float values in float32, then "
        "[the float64 shadow (when it differs), bits of it kept]",
        "",
    ]
    _format_steps(report.steps, 0, len(report.steps), out, [None], 0)
    if report.truncated:
        out.append(f"... {report.truncated:,} more steps not recorded")
    out.append("")
    out.append(f"fragColor = {fmt(list(report.color))}")
    if report.first_nan is not None:
        o = report.first_nan
        out.append(f"first NaN/Inf: {o.file}:{o.line}:{o.column}: {o.operation}: {o.code}")
        if o.help:
            out.append(f"  help: {o.help}")
    return "\n".join(out)


def _describe(s: Step) -> str:
    shadow = ""
    if s.bits is not None:  # the shadow only where it tells something the float32 value does not
        shadow = (
            f"   [{s.bits} bits]"
            if s.bits == 24
            else f"   [f64 {fmt(s.value64, False)}, {s.bits} bits]"
        )
    if s.kind == "assign":
        return f"{s.name} = {fmt(s.value)}{shadow}"
    if s.kind == "return":
        return f"return {fmt(s.value)}{shadow}"
    if s.kind == "call":
        args = ", ".join(f"{k}={fmt(v)}" for k, v in s.value.items())
        return f"call {s.name}({args})" + (f"   [{s.bits} bits]" if s.bits is not None else "")
    if s.kind == "branch":
        if s.name in ("if", "if/else"):
            if s.value:
                return "if: true, the then branch runs"
            return (
                "if: false, the else branch runs"
                if s.name == "if/else"
                else "if: false, the then branch is skipped"
            )
        if s.name == "switch":
            return f"switch on {fmt(s.value)}"
        return s.name
    if s.kind == "discard":
        return "discard: the pixel is dropped"
    if s.kind == "undefined":
        what = UNDEFINED_ENTRIES.get(s.why, "a value GLSL leaves undefined")
        return (
            f"{s.name} = {fmt(s.value)}: UNDEFINED in the shader, {what} (read at line "
            f"{s.read_line}); this render gives it WebGL's value, a GPU may give it any: "
            "what follows from it depends on the driver (`glslcheck check` warns at the read)"
        )
    return s.name


# what enters at an undefined value's site (Step.why: semantics.analysis.undefined's kinds)
UNDEFINED_ENTRIES = {
    "out-parameter": "an out parameter's value on entry",
    "out-parameter-unwritten": "an out parameter a path returns without writing",
    "uninitialized-local": "a local declared without an initializer",
    "uninitialized-global": "a global declared without an initializer, on entry to main",
    "division-by-zero": "an integer division, or a float one by a constant, by zero",
    "shift-out-of-range": "a shift out of range",
    "conversion-out-of-range": "a conversion out of range",
    "domain": "a built-in outside its domain",
}


def _format_steps(steps: list[Step], i: int, j: int, out: list[str], last: list, nest: int) -> None:
    k = i
    while k < j:
        s = steps[k]
        if s.kind == "loop" and s.what == "start":
            end = next(
                (
                    m
                    for m in range(k + 1, j)
                    if steps[m].kind == "loop"
                    and steps[m].what == "end"
                    and steps[m].file == s.file
                    and steps[m].line == s.line
                    and steps[m].depth == s.depth
                ),
                j,
            )
            starts = [
                m
                for m in range(k + 1, end)
                if steps[m].kind == "loop"
                and steps[m].what == "iteration"
                and steps[m].line == s.line
                and steps[m].file == s.file
                and steps[m].depth == s.depth
            ]
            _line(s, out, last, nest, f"{s.name.split()[0]} loop starts")
            bounds = list(zip(starts, starts[1:] + [end]))
            shown = bounds if len(bounds) <= FIRST_ITERATIONS + LAST_ITERATIONS + 1 else None
            for n, (a, b) in enumerate(bounds):
                if shown is None and FIRST_ITERATIONS <= n < len(bounds) - LAST_ITERATIONS:
                    if n == FIRST_ITERATIONS:
                        hidden = bounds[FIRST_ITERATIONS : len(bounds) - LAST_ITERATIONS]
                        nsteps = hidden[-1][1] - hidden[0][0]
                        out.append(
                            "    " * (s.depth + nest + 1) + f"... iterations {n + 1} to "
                            f"{len(bounds) - LAST_ITERATIONS} folded ({len(hidden)} iterations, "
                            f"{nsteps} steps) ..."
                        )
                        last[0] = None
                    continue
                out.append("    " * (s.depth + nest + 1) + f"iteration {n + 1}")
                _format_steps(steps, a + 1, b, out, last, nest + 1)
            if end < j:
                _line(steps[end], out, last, nest, f"loop ends after {steps[end].count} iterations")
            k = end + 1
            continue
        _line(s, out, last, nest, _describe(s))
        k += 1


def _line(s: Step, out: list[str], last: list, nest: int, text: str) -> None:
    pad = "    " * (s.depth + nest)
    where = (s.file, s.line)
    if last[0] != where:
        out.append(f"{pad}{_short(s.file)}:{s.line}: {s.code}")
        last[0] = where
    out.append(f"{pad}    {text}")


def _short(path: str) -> str:
    try:
        rel = os.path.relpath(path)
    except ValueError:
        return path
    return rel if not rel.startswith("..") else path


def format_nan(report: NanReport, shader: str, inputs: Inputs) -> str:
    """The text `glslcheck probe --nan` prints."""
    w, h = inputs.size
    out = [
        f"{shader}: {w}x{h}, iTime {inputs.time:g}: {_count(report.nan_pixels, 'NaN pixel')}, "
        f"{_count(report.inf_pixels, 'Inf pixel')}"
    ]
    for o in report.origins:
        x0, y0, x1, y1 = o.box
        where = f"{_short(o.file)}:{o.line}:{o.column}: " if o.file else ""
        out.append("")
        out.append(
            f"{where}{o.operation} in `{o.code}`: the first NaN/Inf of "
            f"{_count(o.pixels, 'pixel')}, "
            f"in {x0},{y0} .. {x1},{y1} (from the top left)"
        )
        if o.file:
            assert o.line is not None and o.column is not None  # a located origin
            text = source_line(o.file, o.line) or ""
            out.append(f"    {text.rstrip()}")
            out.append(
                "    "
                + "".join(c if c == "\t" else " " for c in text[: max(o.column - 1, 0)])
                + "^"
            )
        if o.help:
            out.append(f"  help: {o.help}")
        if o.undefined_pixels:
            out.append(
                f"  note: {o.undefined_pixels} of these pixels change when the shader's "
                "undefined values do: that NaN/Inf is the shader's undefined behaviour (below)"
            )
    for u in report.undefined_reads[:4]:
        what = UNDEFINED_ENTRIES.get(u["kind"], "a value GLSL leaves undefined")
        out.append(
            f"{_short(u['file'])}:{u['line']}:{u['column']}: note: undefined in the shader: {what} "
            "(`glslcheck check` says more)"
        )
    if not report.origins:
        out.append("no pixel is NaN or Inf")
    return "\n".join(out)


def _count(n: int, what: str) -> str:
    return f"{n} {what}{'s' if n != 1 else ''}"
