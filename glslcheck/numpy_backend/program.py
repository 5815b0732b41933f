"""Compiling a shader to its NumPy module and rendering it: tiles, lanes, masks, compaction, stats.

This module owns what happens around the generated code (`transpile.py`): executing the module
in a restricted namespace (`__builtins__` empty; only `rt`, the runtime, and `X`, the lane
helpers below, are visible), the per-invocation state `State` (uniforms, globals, discard mask,
statistics), splitting the image into tiles rendered by worker processes or a thread pool,
supersampling, the frame cache for shaders that do not animate, the error for a runaway
loop, and the frame's budgets: time (FRAME_SECONDS, `Budget`) and memory (MEMORY_FRACTION,
tiles sized to the shader's per-lane state, `NumpyProgram._fit_memory`).

Library API:

    prog = compile_numpy(shader)            # parse + check + transpile; GlslError on errors
    img = prog.render(size=(800, 450), time=0.0, frame=0, mouse=(0, 0, 0, 0), date=None,
                      time_delta=1/60, frame_rate=60.0, samples=1, precision="float32")
    # img: float32 (height, width, 4), top row first; the GL backend's render() signature plus
    # `precision` ("float16" | "float32" | "float64", the float dtype used inside the shader)
    prog.last_stats                         # lanes per function/branch/loop of the last render
    prog.parallel = "auto"                  # or "processes" / "threads" (env GLSLCHECK_PARALLEL)
    module = load_module("shader.py")       # a module written by `glslcheck transpile`

Tiles: bands of about TILE_LANES pixels (up to TILE_WIDTH wide) keep a shader's temporaries
small (a few hundred kB each); tiles start at even x and y, so derivative quads (2x2, see the runtime) never
straddle two tiles (`frame_tiles`; `render_tile` renders one). `os.cpu_count()` worker
processes (workers.py) or threads of one process-wide pool render them. Threads share the GIL,
which NumPy releases only inside each operation: a tile runs hundreds of short ones, so two
threads gain little (nothing on a sparse scene). Processes do not share it but cost a few
tenths of a second to start, so `parallel="auto"` uses threads until a program has rendered
for PROCESSES_AFTER seconds in this process (or a pool is already up). Tiles write their rows
straight into the top-first image (with threads also into the frame cache's copy, whose
buffers are reused; worker processes write a shared file that the caller and the cache map
without copying it). Peak memory is a few tiles' temporaries per worker plus the output image
and its cached copy.

Fixed costs per tile are kept off the lanes: a tile's fragment coordinates are made once and kept
read-only for later frames (gl_FragCoord only when the code reads it; `_fragments`), uniform
(1,) masks combine without full-lane
arrays, and a compacted view (`Lanes.gather`) gathers globals and fragment coordinates only
when the region first reads them.
"""

from __future__ import annotations

import functools
import linecache
import math
import os
import sys
import threading
import time as _time
from collections import OrderedDict
from concurrent.futures import FIRST_EXCEPTION, ThreadPoolExecutor, wait
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..diagnostics import Diagnostic, GlslError, InputError, Location
from ..driver_profile import host_model
from ..shadertoy import DEFAULT_SIZE, UNIFORMS_BY_NAME, frame_uniforms, sample_offsets
from .runtime import Runtime, Struct
from .transpile import SMALL_STATE

TILE_LANES = 49152  # lanes per tile: fewer calls in compacted regions; full-lane work measured flat 24k-49k
TILE_WIDTH = 1024  # widest tile; wide bands keep rows contiguous in the output image
TILE_HEIGHT = None  # None: TILE_LANES // tile width (rounded to even); set both to force a tile size
COMPACT_FRACTION = 0.5  # compact a region when fewer than this fraction of the lanes take it
COMPACT_MIN_LANES = 1024  # below this many lanes gathering costs more than it saves
CACHE_FRAMES = 8
_CPUS = os.cpu_count()
CACHE_BYTES = 256 * 2**20  # and at most this much of them (a 3840x2160 frame is 127 MiB), the newest always kept
PROCESSES_AFTER = 1.0  # seconds a program renders in this process before "auto" starts worker processes
# The whole-frame budget: a frame that is still rendering after this many seconds stops with an
# error at the loop (or function) it was in, whatever each loop's own cap (LOOP_CAP iterations
# per loop execution: loops nested two deep may still run 10**10 times). Checked at every region
# entry and loop iteration (`Lanes.count`); environment variable GLSLCHECK_FRAME_SECONDS, or
# `NumpyProgram.frame_seconds`.
FRAME_SECONDS = 300.0
# The memory budget: the tiles rendering at once (one per thread or worker) hold at most this
# fraction of the machine's memory, or of the address space `ulimit -v` leaves this process;
# environment variable GLSLCHECK_MEMORY_MB. A tile's lanes times the shader's per-lane state
# (estimated by the transpiler, `transpile.lane_state`) must fit: large local arrays get smaller
# tiles, and a shader whose 2x2 tile does not fit is refused with an error at its largest variable.
MEMORY_FRACTION = 0.5
MIN_TILE_LANES = 4  # one 2x2 derivative quad
# Uniforms that change from frame to frame; a shader that reads none of them renders one image
# for a whole animation.
ANIMATED_UNIFORMS = ("iTime", "iFrame", "iTimeDelta", "iDate", "iMouse", "iFrameRate")


# ---------------------------------------------------------------------------------------------
# Per-invocation state and the lane helpers the generated code calls as `X.<name>`
# ---------------------------------------------------------------------------------------------


class Budget:
    """When a frame must stop: at `deadline` (`time.monotonic()`, one clock for every process of
    the machine, so worker processes get it in their message) or once `cancelled` (Ctrl-C in
    the caller, or an error in another tile). The generated code's `X.count` reads one flag,
    `stop`, which a timer thread sets at the deadline (reading the clock there instead cost
    more than the rest of `X.count`). Picklable (without its timer)."""

    def __init__(self, seconds: float) -> None:
        self.seconds = seconds
        self.deadline = _time.monotonic() + seconds
        self.cancelled = False
        self.stop = False
        self._timer: threading.Timer | None = None

    def __getstate__(self) -> dict:
        return {**self.__dict__, "_timer": None}

    def cancel(self) -> None:
        self.cancelled = self.stop = True

    def start(self) -> "Budget":
        """Arm the deadline in this process (until `finish`)."""
        self._timer = threading.Timer(max(0.0, self.deadline - _time.monotonic()), self._expire)
        self._timer.daemon = True
        self._timer.start()
        return self

    def _expire(self) -> None:
        self.stop = True

    def finish(self) -> None:
        if self._timer is not None:
            self._timer.cancel()
            self._timer = None


class Cancelled(Exception):
    """A tile stopped because its frame was cancelled (the frame's own error is raised)."""


def memory_budget() -> int:
    """Bytes the tiles rendering at once may hold: GLSLCHECK_MEMORY_MB, else MEMORY_FRACTION of
    the machine's memory or of the address space left under `ulimit -v`, whichever is less."""
    text = os.environ.get("GLSLCHECK_MEMORY_MB", "").strip()
    if text:
        try:
            value = float(text)
        except ValueError:
            value = math.nan
        if not 0 < value < math.inf:
            raise InputError(f"error: GLSLCHECK_MEMORY_MB must be a positive number of megabytes, not {text!r}")
        return int(value * 2**20)
    avail = 2**40  # unknown: no limit from the machine
    try:
        avail = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError, AttributeError):
        pass
    try:
        import resource

        soft = resource.getrlimit(resource.RLIMIT_AS)[0]
        if soft != resource.RLIM_INFINITY:
            with open("/proc/self/statm") as f:  # the address space in use now (Linux)
                used = int(f.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
            avail = min(avail, max(0, soft - used))
    except (ImportError, OSError, ValueError):
        pass
    return int(MEMORY_FRACTION * avail)


def lane_bytes(meta: dict, precision: str) -> tuple[int, Location | None]:
    """(estimated bytes of one lane's state, where its largest variable is declared)."""
    state = meta.get("lane_state")
    scalars = state[0] if state else SMALL_STATE
    loc = Location(state[1], state[2], state[3]) if state else None
    return scalars * (8 if precision == "float64" else 4), loc


def _megabytes(n: int) -> str:
    return f"{n / 2**20:,.0f} MB" if n >= 2**20 else f"{n / 2**10:,.0f} kB"


def frame_seconds() -> float:
    """The frame budget in seconds: GLSLCHECK_FRAME_SECONDS, else FRAME_SECONDS."""
    text = os.environ.get("GLSLCHECK_FRAME_SECONDS", "").strip()
    try:
        value = float(text) if text else FRAME_SECONDS
    except ValueError:
        value = math.nan
    if not 0 < value < math.inf:
        raise InputError(f"error: GLSLCHECK_FRAME_SECONDS must be a positive number of seconds, not {text!r}")
    return value


class State:
    """What one tile's invocation carries: `lanes`, `width` (tile width, for derivatives),
    `frag_coord` (vec2 lanes), `frag_coord4` (gl_FragCoord), `discard` (mask), uniforms
    `u_<name>`, globals `g_<name>`, `stats` (region id -> lanes, shared), `parent` (when this
    is a compacted view of another state), `budget` (the frame's `Budget`; None: no limit)."""

    budget: Budget | None = None

    passes = None  # [passes left] of llvmpipe's loop limiter when emulated (Lanes.tick), else None

    def __init__(self, **values: Any) -> None:
        self.__dict__.update(values)

    def __getattr__(self, name: str) -> Any:
        # a compacted view gathers globals and fragment coordinates on first use only
        lazy = self.__dict__.get("lazy")
        if lazy is None or name not in lazy:
            raise AttributeError(name)
        lazy.discard(name)
        parent = self.parent
        g = Lanes._take(getattr(parent, name), self.idx, parent.lanes)
        self.__dict__[name] = g
        self.gathered[name] = g
        return g


@dataclass
class _Gathered:
    values: tuple
    originals: tuple


class Lanes:
    """Mask and compaction helpers. A mask is None (all lanes of the current lane set) or a bool
    array of shape (1,) or (lanes,)."""

    NO = np.zeros(1, dtype=np.bool_)

    def __init__(self, meta: dict, rt: Runtime | None = None) -> None:
        self.meta = meta
        self.loops = meta.get("loops", {})
        self.rt = rt
        self.limited: set[int] = set()  # loops llvmpipe's pass budget stopped (see tick)

    def put(self, old, new, m):
        """`rt.assign(old, new, m)` that skips the select when the mask is uniform."""
        if m is not None and m.shape[-1] == 1:
            if not m[0]:
                return old
            m = None
        return self.rt.assign(old, new, m)

    # masks ------------------------------------------------------------------------------------
    # A mask of shape (1,) is uniform: all of the current lanes or none. Combining it with
    # another mask returns one of the operands instead of computing a full-lane array.
    @staticmethod
    def and_(a, b):
        if a is None:
            return b
        if b is None:
            return a
        if a.shape[-1] == 1:
            return b if a[0] else a
        if b.shape[-1] == 1:
            return a if b[0] else b
        return a & b

    @staticmethod
    def or_(a, b):
        if a is None or b is None:
            return None
        if a.shape[-1] == 1:
            return a if a[0] else b
        if b.shape[-1] == 1:
            return b if b[0] else a
        return a | b

    def andnot(self, a, b):
        if b is None:
            return self.NO
        if b.shape[-1] == 1:
            return self.NO if b[0] else a
        nb = ~b
        if a is None:
            return nb
        if a.shape[-1] == 1:
            return nb if a[0] else a
        return a & nb

    def refresh(self, m, live, *drop):
        m = self.and_(m, live)
        for d in drop:
            m = self.andnot(m, d)
        return m

    @staticmethod
    def not_(m):
        return None if m is None else ~m

    @staticmethod
    def live(m) -> bool:
        return m is None or bool(m.any())

    @staticmethod
    def every(c) -> bool:
        """True when every lane of a bool value is true (inactive lanes included: a cheap,
        conservative test that lets a select skip computing its other side)."""
        return bool(c.all())

    @staticmethod
    def true(c) -> bool:
        """A uniform condition's value (shape (1,) by construction of the uniformity analysis)."""
        if c.shape[-1] != 1:
            raise AssertionError("internal error: a condition judged uniform varies across lanes")
        return bool(c.reshape(-1)[0])

    # statistics, budget and loops ---------------------------------------------------------------
    def count(self, S, rid: int, m) -> None:
        """Called on entering each function, branch and loop iteration: stops the frame when it
        is over its budget or cancelled, and counts the lanes when statistics are on."""
        b = S.budget
        if b is not None and b.stop:
            self.over_budget(b, rid)
        st = S.stats
        if st is None:
            return
        n = S.lanes if m is None else (int(np.count_nonzero(m)) if m.shape[-1] != 1 else (S.lanes if m[0] else 0))
        st[rid] = st.get(rid, 0) + n

    def tick(self, S, lid: int, n: int) -> bool:
        """llvmpipe's loop limiter, when the program renders with `loop_limit` (gallivm
        lp_exec_endloop, LP_MAX_TGSI_LOOP_ITERATIONS = 65535): one pass budget per invocation shared
        by every loop; each pass of a loop costs 1 (the pass that ends it on its condition too:
        llvmpipe masks the lanes out and runs to the loop's end), and a loop goes round again
        only while the budget is positive. Called at the top of pass `n` of loop `lid`: the
        check belongs to the end of pass n - 1. Matches llvmpipe's pass counts exactly:
        `for (i < 70000)` runs 65,535 times; two loops of 40,000 run 40,000 and 25,534; a loop
        entered with no budget left runs once; 100 x 1,000 nested runs 65,405 inner passes.
        The budget is per tile here and per 8-lane group there: for loops whose pass count
        differs between pixels it can bite at a slightly different pass. True when the loop
        must stop (recorded in `limited`)."""
        passes = S.passes
        if passes is None:
            return False
        if n > 1 and passes[0] <= 0:
            self.limited.add(lid)
            return True
        passes[0] -= 1
        return False

    def over_budget(self, budget: Budget, rid: int) -> None:
        if budget.cancelled:
            raise Cancelled()
        kind, function, path, line = self.meta.get("regions", {}).get(rid, ("", "", "<shader>", 0))
        _, _, col = self.loops.get(rid, (path, line, 1))
        where = "this loop" if kind == "loop" else f"this {kind}" if kind in ("if", "else", "case") else f"'{function}'"
        raise GlslError(Diagnostic(
            f"the frame was still rendering after {budget.seconds:g} s on the CPU, in {where}; the NumPy "
            "renderer stops it (a GPU would hang or reset)", Location(path, line, col), rule="numpy-frame-budget",
            help="bound the loops' iteration counts (nested loops multiply) and the arrays' sizes; "
                 "--frame-budget SECONDS (or GLSLCHECK_FRAME_SECONDS) sets the budget"))

    def runaway(self, lid: int) -> None:
        path, line, col = self.loops.get(lid, ("<shader>", 0, 0))
        cap = self.meta.get("loop_cap", 0)
        raise GlslError(Diagnostic(
            f"this loop did not end after {cap:,} iterations; the NumPy renderer stops it (a GPU would "
            "hang or reset)", Location(path, line, col), rule="numpy-runaway-loop",
            help="check the loop's condition and step; give it a constant upper bound"))

    # compaction -------------------------------------------------------------------------------
    @staticmethod
    def sparse(S, m):
        """Active lane indices when compacting pays off, else None."""
        if m is None or S.lanes < COMPACT_MIN_LANES or m.shape[-1] != S.lanes:
            return None
        idx = np.flatnonzero(m)
        if len(idx) >= COMPACT_FRACTION * S.lanes:
            return None
        return idx

    @staticmethod
    def _take(v, idx, lanes):
        if isinstance(v, np.ndarray):
            if v.ndim and v.shape[-1] == lanes and lanes != 1:
                return np.take(v, idx, axis=-1)  # several times faster than v[..., idx]
            return v
        if isinstance(v, Struct):
            return v.map(lambda x: Lanes._take(x, idx, lanes))
        return v

    @staticmethod
    def _put(old, new, idx, lanes):
        if new is old:
            return old
        if isinstance(new, Struct):
            return Struct(new.type_name, {k: Lanes._put(old[k], new[k], idx, lanes) for k in new.fields})
        if new is None:  # a mask meaning "every lane of the compacted set"
            new = np.ones(len(idx), dtype=np.bool_)
        if not isinstance(new, np.ndarray):
            return new
        if old is None:  # a mask that was "every lane"
            old = np.ones(lanes, dtype=np.bool_)
        base = np.broadcast_to(old, np.broadcast_shapes(old.shape[:-1], new.shape[:-1]) + (lanes,))
        out = np.array(base, dtype=old.dtype, copy=True)
        if out.ndim == 1:
            out[idx] = new
            return out
        # one row at a time: 2.5x faster than out[..., idx] = new on (3, lanes)
        rows = out.reshape(-1, lanes)
        news = np.broadcast_to(new, out.shape[:-1] + (len(idx),)).reshape(-1, len(idx))
        for r in range(rows.shape[0]):
            rows[r][idx] = news[r]
        return out

    _LANE_FIELDS = ("discard", "frag_coord", "frag_coord4")

    def gather(self, S, idx, values: tuple):
        """A compacted view of S (and of `values`) on the lanes `idx`. Globals and fragment
        coordinates are gathered when the region first reads them (`State.__getattr__`)."""
        lanes = S.lanes
        fields = {}
        lazy = set(S.__dict__.get("lazy") or ())  # fields S itself has not gathered yet
        for k, v in S.__dict__.items():
            if k.startswith("g_") or k in self._LANE_FIELDS:
                if isinstance(v, np.ndarray) and (v.shape[-1] == 1 or lanes == 1):
                    fields[k] = v  # uniform: the same array serves the compacted lanes
                else:
                    lazy.add(k)
            elif k not in ("lazy", "gathered", "idx"):
                fields[k] = v
        child = State(**fields)
        child.parent = S
        child.lanes = len(idx)
        child.idx = idx
        child.lazy = lazy
        child.gathered = {k: fields[k] for k in fields if k.startswith("g_") or k in self._LANE_FIELDS}
        gathered = tuple(self._take(v, idx, lanes) for v in values)
        return child, _Gathered(gathered, values)

    def scatter(self, S, idx, rec: _Gathered, values: tuple):
        parent = S.parent
        lanes = parent.lanes
        for k, g in S.gathered.items():
            v = S.__dict__[k]
            if v is not g:
                setattr(parent, k, self._put(getattr(parent, k), v, idx, lanes))
        for k, v in S.__dict__.items():  # globals written in the region before any read of them
            if k.startswith("g_") and k not in S.gathered:
                if k in S.lazy or hasattr(parent, k):
                    setattr(parent, k, self._put(getattr(parent, k), v, idx, lanes))
                else:
                    setattr(parent, k, v)
        out = tuple(self._put(o, v, idx, lanes) if v is not g else o
                    for o, g, v in zip(rec.originals, rec.values, values))
        return parent, out

    def push(self, stack: list, S, m, values: tuple):
        idx = self.sparse(S, m)
        child, rec = self.gather(S, idx, values)
        stack.append((idx, rec))
        return child, rec.values

    def unwind(self, stack: list, S, values: tuple):
        while stack:
            idx, rec = stack.pop()
            S, values = self.scatter(S, idx, rec, values)
        return S, values


# ---------------------------------------------------------------------------------------------
# Executing generated modules
# ---------------------------------------------------------------------------------------------


def execute_module(source: str, filename: str, meta: dict, precision: str = "float32", code: Any = None) -> dict:
    """Run generated code in a namespace that holds nothing but the runtime and the helpers.

    The source is registered in `linecache` under `filename`, so tracebacks and debuggers show
    the generated lines (each with its GLSL line in a comment)."""
    linecache.cache[filename] = (len(source), None, source.splitlines(True), filename)
    if code is None:
        code = compile(source, filename, "exec")
    ns: dict[str, Any] = {"__builtins__": {}, "__name__": "glslcheck_shader", "rt": None, "X": None}
    ns["rt"] = rt = Runtime(precision, meta.get("float_to_uint"))
    rt.fold_constants = True  # Mesa's folding of constants (Runtime.fmul); uniforms are read-only
    ns["X"] = Lanes(meta, rt)
    with np.errstate(all="ignore"):  # constants may overflow in float16, as on a mediump GPU
        exec(code, ns)  # noqa: S102 - generated from a checked AST; every GLSL name is mangled
    return ns


def _uniform_value(rt: Runtime, name: str, value: Any) -> Any:
    u = UNIFORMS_BY_NAME[name]
    t = u.glsl_type
    if t.startswith("sampler"):
        return value if not isinstance(value, int) else None  # a channels.ChannelInput; None: unbound

    def one(v):
        if t == "float":
            return rt.const_float(float(v))
        if t == "int":
            return rt.const_int(int(v))
        n = int(t[-1])
        return rt.vec(n, *[rt.const_float(float(x)) for x in v])

    value = rt.array(*[one(v) for v in value]) if u.array_size else one(value)
    value.flags.writeable = False  # an input, not a constant: Runtime.fmul does not fold it
    return value


class _FrameCache(OrderedDict):
    """The frame cache (key -> image). Its images are never handed out (a hit returns a copy).
    With threads, each is a copy the tiles write beside the caller's image, and the buffers of
    dropped entries are kept (at most SPARE_FRAMES) for the next frames' copies: a fresh buffer
    costs page faults on first write, about as much as the copy itself. With worker processes,
    each is a read-only view of the frame's shared file (workers.py), no copy at all."""

    SPARE_FRAMES = 2

    def __init__(self) -> None:
        super().__init__()
        self.spare: list[np.ndarray] = []

    def buffer(self, shape: tuple[int, ...]) -> np.ndarray:
        for i, b in enumerate(self.spare):
            if b.shape == shape:
                return self.spare.pop(i)
        return np.empty(shape, dtype=np.float32)

    def recycle(self, image: np.ndarray) -> None:
        if image.base is None:  # not a worker frame file's view: dropping that frees the file
            self.spare.append(image)
            del self.spare[:-self.SPARE_FRAMES]

    def clear(self) -> None:
        for image in list(self.values())[-self.SPARE_FRAMES:]:
            self.recycle(image)
        super().clear()


@dataclass
class FrameSpec:
    """What every tile of one frame needs; picklable (it travels to worker processes)."""

    width: int
    height: int
    base: dict  # u_<uniform> and g_<global> values, the same for every pixel
    offsets: list  # sub-pixel sample offsets
    need4: bool  # the code reads gl_FragCoord: build it
    stats: bool  # count the lanes of each region
    compaction: tuple  # (COMPACT_FRACTION, COMPACT_MIN_LANES) of the caller, for workers


def frame_tiles(width: int, height: int, lanes: int | None = None) -> tuple[tuple[int, int, int, int], ...]:
    """(x0, y0, w, h) of each tile, y0 from the bottom; tiles start at even x and y, so 2x2
    derivative quads never straddle two tiles. `lanes`: at most this many per tile (memory)."""
    tile_lanes = TILE_LANES if lanes is None else max(MIN_TILE_LANES, min(TILE_LANES, lanes))
    return _frame_tiles(width, height, TILE_WIDTH, TILE_HEIGHT, tile_lanes)


@functools.lru_cache(maxsize=64)
def _frame_tiles(width: int, height: int, tile_width: int, tile_height: int | None,
                 tile_lanes: int) -> tuple[tuple[int, int, int, int], ...]:
    tw = min(tile_width, width, max(2, tile_lanes // 4 * 2))  # narrower than a 2-row band of lanes
    tw += tw % 2 if tw < width else 0
    th = tile_height or max(2, (tile_lanes // tw) // 2 * 2)
    return tuple((x0, y0, min(tw, width - x0), min(th, height - y0))  # a tuple: the cache shares it
                 for y0 in range(0, height, th) for x0 in range(0, width, tw))


# Fragment coordinates of tiles already rendered, read-only, by (tile, dtype, sample offset,
# gl_FragCoord wanted): building them again was 5% of a frame of the four-sphere scene. Kept up
# to FRAG_CACHE_LANES lanes (a 1920x1080 frame twice over; past that they are made per tile).
FRAG_CACHE_LANES = 2 * 1920 * 1080
_FRAGS: dict = {}
_FRAG_LANES = [0]
_GRIDS: dict = {}  # (w, h) -> pixel-centre offsets (float64) of a tile shape; a frame has few shapes


def _fragments(rt, tile, dx: float, dy: float, need4: bool):
    """gl_FragCoord.xy (2, lanes) and, when the code reads it, gl_FragCoord (4, lanes)."""
    key = (tile, rt.F, dx, dy, need4)
    got = _FRAGS.get(key)
    if got is not None:
        return got
    x0, y0, tw, th = tile
    lanes = tw * th
    grid = _GRIDS.get((tw, th))
    if grid is None:
        grid = _GRIDS[(tw, th)] = (np.tile(np.arange(tw) + 0.5, th), np.repeat(np.arange(th) + 0.5, tw))
    gx, gy = grid
    frag = np.empty((2, lanes), dtype=rt.F)
    np.add(gx, x0, out=frag[0], casting="unsafe")  # one rounding of x + 0.5 to F
    np.add(gy, y0, out=frag[1], casting="unsafe")
    frag4 = None
    if need4:  # gl_FragCoord: the pixel centre, whatever the sample
        frag4 = np.empty((4, lanes), dtype=rt.F)
        frag4[:2] = frag
        frag4[2] = 0.5
        frag4[3] = 1.0
        frag4.flags.writeable = False
    if dx or dy:  # then the sample's offset, rounded to F again
        frag[0] += rt.F(dx)
        frag[1] += rt.F(dy)
    frag.flags.writeable = False  # shared by every frame: generated code never writes inputs
    got = (frag, frag4)
    if _FRAG_LANES[0] + lanes <= FRAG_CACHE_LANES:
        _FRAGS[key] = got
        _FRAG_LANES[0] += lanes
    return got


def render_tile(ns: dict, spec: FrameSpec, tile: tuple[int, int, int, int], image: np.ndarray,
                cached: np.ndarray | None = None, budget: Budget | None = None) -> dict | None:
    """Run the shader on one tile and write its rows into `image` (and `cached`); returns the
    tile's lane counts per region when `spec.stats`, else None. `budget`: the frame's."""
    rt = ns["rt"]
    x0, y0, tw, th = tile
    lanes = tw * th
    samples = len(spec.offsets)
    acc = None
    st: dict | None = {} if spec.stats else None
    for dx, dy in spec.offsets:
        frag, frag4 = _fragments(rt, tile, dx if samples > 1 else 0.0, dy if samples > 1 else 0.0,
                                 spec.need4)
        limit = spec.base.get("loop_limit")
        S = State(**spec.base, lanes=lanes, width=tw, frag_coord=frag, discard=Lanes.NO, stats=st,
                  parent=None, budget=budget, passes=None if limit is None else [limit])
        if spec.need4:
            S.frag_coord4 = frag4
        with rt.errstate():
            try:
                color = ns["shade"](S)  # RGB (a Shadertoy shader: alpha is 1) or RGBA (plain GLSL)
            except RecursionError as e:  # a chain of calls nested about a thousand deep
                raise _too_deep(ns, e) from None
            if S.discard is not Lanes.NO or samples > 1:
                if len(color) == 3:
                    color = np.concatenate([np.broadcast_to(color, (3, lanes)), np.ones((1, lanes), color.dtype)])
                color = np.broadcast_to(color, (4, lanes))
                if S.discard is not Lanes.NO:
                    color = np.where(np.broadcast_to(S.discard, (lanes,)), 0.0, color)
                if samples > 1:
                    color = color.astype(np.float64)
            color = np.broadcast_to(color, (len(color), lanes))
        acc = color if acc is None else acc + color
    if samples > 1:
        acc = acc / samples
    # tile row 0 is the bottom one (y0); the image's row 0 is the top of the picture
    rows = slice(spec.height - y0 - th, spec.height - y0)
    if acc.strides[-1] == 0:
        # the same colour in every pixel (a background tile): whole rows of it, one pass; the
        # reshape is a view, since the 4 channels of a row's pixels are contiguous
        pixel = np.append(acc[:, 0], [1.0]) if len(acc) == 3 else acc[:, 0]
        image[rows, x0:x0 + tw].reshape(th, tw * 4)[...] = np.tile(pixel.astype(np.float32), tw)
    else:
        dst = image[rows, x0:x0 + tw][::-1]
        for c in range(len(acc)):  # one channel at a time: 2.5x faster than one transposed copy
            dst[..., c] = acc[c].reshape(th, tw)
        if len(acc) == 3:
            dst[..., 3] = 1.0
    if cached is not None:
        cached[rows, x0:x0 + tw] = image[rows, x0:x0 + tw]
    return st


def _too_deep(ns: dict, e: RecursionError) -> GlslError:
    """A located error for Python's recursion limit reached by the generated code: at the GLSL
    line of the innermost generated frame (GLSL has no recursion: a long chain of calls)."""
    from .transpile import _glsl_location, too_complex

    path = ns.get("SHADER_META", {}).get("source", "<shader>")
    loc = Location(path, 1, 1)
    tb = e.__traceback__
    while tb is not None:
        code = tb.tb_frame.f_code
        if tb.tb_frame.f_globals is ns and code.co_filename in linecache.cache:
            loc = _glsl_location("".join(linecache.cache[code.co_filename][2]), tb.tb_lineno, path)
        tb = tb.tb_next
    return too_complex("its function calls are nested too deeply for Python", loc)


_POOLS: dict[int, ThreadPoolExecutor] = {}
_POOLS_LOCK = threading.Lock()


def _pool(threads: int) -> ThreadPoolExecutor:
    """A process-wide pool of `threads` tile workers (made once, not per render)."""
    with _POOLS_LOCK:
        pool = _POOLS.get(threads)
        if pool is None:
            pool = _POOLS[threads] = ThreadPoolExecutor(max_workers=threads, thread_name_prefix="glslcheck-tile")
        return pool


@dataclass
class RegionStat:
    kind: str
    function: str
    path: str
    line: int
    lanes: int


@dataclass(eq=False)
class NumpyProgram:
    """A shader transpiled to Python; render it as often as needed (thread-safe)."""

    source: str
    meta: dict
    filename: str
    threads: int | None = None
    last_stats: list[RegionStat] = field(default_factory=list)
    # "threads", "processes" (worker processes, see workers.py) or "auto": processes once the
    # program has rendered for PROCESSES_AFTER seconds in this process
    parallel: str = field(default_factory=lambda: os.environ.get("GLSLCHECK_PARALLEL", "auto"))
    last_parallel: str = ""  # how the last frame was rendered: "processes", "threads", "one thread"
    # llvmpipe's loop limiter (Lanes.tick): None = loops run until they end (a runaway loop is an
    # error after LOOP_CAP passes); 65535 = stop as llvmpipe does (verify sets it)
    loop_limit: int | None = None
    frame_seconds: float | None = None  # the frame budget; None: GLSLCHECK_FRAME_SECONDS or FRAME_SECONDS
    _render_seconds: float = field(default=0.0, repr=False)
    _keys: dict = field(default_factory=dict, repr=False)
    _modules: dict = field(default_factory=dict, repr=False)
    _cache: OrderedDict = field(default_factory=lambda: _FrameCache(), repr=False)
    _specs: OrderedDict = field(default_factory=OrderedDict, repr=False)  # frame key -> FrameSpec
    _tile_order: OrderedDict = field(default_factory=OrderedDict, repr=False)  # tiles -> indices, slowest first
    _lock: Any = field(default_factory=threading.Lock, repr=False)
    _code: Any = field(default=None, repr=False)  # the compiled module, when the transpiler made it

    @property
    def uniforms(self) -> list[str]:
        """The Shadertoy uniforms the generated code reads (the others are never computed)."""
        return list(self.meta.get("uniforms", []))

    @property
    def animated(self) -> bool:
        return any(u in ANIMATED_UNIFORMS for u in self.uniforms)

    def emulate_float_to_uint(self, model: str) -> None:
        """Compute ``uint(x)`` of out-of-range floats as `model` does (glslcheck/driver_profile.py;
        by default this machine's prediction): verify sets the model it measured on the driver."""
        with self._lock:
            if self.meta.get("float_to_uint", host_model()) != model:
                self.meta = {**self.meta, "float_to_uint": model}
                self._modules.clear()
                self._keys.clear()
                self._cache.clear()
                self._specs.clear()

    def limited_loops(self) -> list[tuple[str, int]]:
        """(file, line) of the loops llvmpipe's limiter stopped in this process's renders since
        the last call (worker processes keep their own record)."""
        found = set()
        for ns in self._modules.values():
            x = ns.get("X")
            found |= {tuple(x.loops.get(lid, ("<shader>", 0, 0))[:2]) for lid in getattr(x, "limited", ())}
            getattr(x, "limited", set()).clear()
        return sorted(found)

    def module(self, precision: str = "float32") -> dict:
        with self._lock:
            if precision not in self._modules:
                self._modules[precision] = execute_module(self.source, self.filename, self.meta, precision, self._code)
            return self._modules[precision]

    def render(
        self,
        size: tuple[int, int] = DEFAULT_SIZE,
        time: float = 0.0,
        frame: int = 0,
        mouse: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0),
        date=None,
        time_delta: float = 1.0 / 60.0,
        frame_rate: float = 60.0,
        samples: int = 1,
        precision: str = "float32",
        stats: bool = False,
        channels=None,
    ) -> np.ndarray:
        """Render one frame: float32 (height, width, 4), row 0 = top of the image, unclamped.

        Arguments as `GLProgram.render`; `precision` is the float dtype inside the shader.
        `channels`: the inputs of iChannel0..3 (glslcheck.channels.ChannelInput or None).
        Discarded pixels are (0, 0, 0, 0), the GL backend's clear colour."""
        width, height = int(size[0]), int(size[1])
        if width < 1 or height < 1:
            raise ValueError(f"size must be at least 1x1, not {width}x{height}")
        offsets = sample_offsets(samples)
        ns = self.module(precision)
        rt = ns["rt"]
        values = frame_uniforms(width, height, time, frame, mouse, date, time_delta, frame_rate)
        if channels is not None:  # each ChannelInput's repr is unique: a new input is a new frame key
            from ..channels import channel_uniforms

            values.update(channel_uniforms(channels))
        used = self.uniforms
        key = (width, height, samples, precision, stats, self.loop_limit,
               tuple((u, repr(values.get(u, UNIFORMS_BY_NAME[u].default))) for u in used))
        if not stats:
            with self._lock:
                hit = self._cache.get(key)
                if hit is not None:
                    self._cache.move_to_end(key)
                    return hit.copy()
        spec_key = (key, COMPACT_FRACTION, COMPACT_MIN_LANES)
        with self._lock:
            spec = self._specs.get(spec_key)
        if spec is None:  # uniform values and globals: the same for every frame with this key
            base = {f"u_{u}": _uniform_value(rt, u, values.get(u, UNIFORMS_BY_NAME[u].default)) for u in used}
            base["loop_limit"] = self.loop_limit
            proto = State(**base, lanes=1, width=1, stats=None, discard=Lanes.NO, parent=None, budget=None)
            with rt.errstate():
                ns["init_globals"](proto)
            globals_ = {k: v for k, v in proto.__dict__.items() if k.startswith("g_")}
            base.update(globals_)
            spec = FrameSpec(width, height, base, offsets, "S.frag_coord4" in self.source, stats,
                             (COMPACT_FRACTION, COMPACT_MIN_LANES))
            with self._lock:
                self._specs[spec_key] = spec
                while len(self._specs) > CACHE_FRAMES:
                    self._specs.popitem(last=False)
        budget = Budget(self.frame_seconds if self.frame_seconds is not None else frame_seconds())
        threads = self.threads or _CPUS or 1
        tile_lanes, threads = self._fit_memory(precision, threads)
        tiles = frame_tiles(width, height, tile_lanes)
        # the tiles that took longest in the last frame of this size go first, so that the
        # workers finish together (the order changes no pixel: each tile writes its own rows)
        with self._lock:
            order = self._tile_order.get(tiles)
        run_tiles = [tiles[i] for i in order] if order is not None else tiles
        all_stats: list[dict] = []
        seconds: dict[tuple, float] = {}  # tile -> seconds it took
        image = cached = None
        started = _time.perf_counter()
        if self._use_processes(threads, tiles):
            from . import workers

            try:
                # the image and the cache's read-only view share the pixels (copy-on-write)
                image, cached, all_stats, seconds = workers.render(
                    self._key(precision), self.source, self.filename, self.meta, precision, spec,
                    run_tiles, threads, budget)
                self.last_parallel = "processes"
            except workers.Unavailable:
                image, all_stats = None, []  # the pool is gone for this process: threads below
        if image is None:
            image = np.empty((height, width, 4), dtype=np.float32)  # top row first
            # the frame cache's copy, written by each tile while its rows are still in the CPU cache
            if not stats:
                with self._lock:
                    cached = self._cache.buffer(image.shape)
            budget.start()
            try:
                seconds = self._render_threads(ns, spec, run_tiles, image, cached, threads, all_stats, budget)
            finally:
                budget.finish()
        if len(seconds) == len(tiles):
            cost = [seconds[t] for t in tiles]
            with self._lock:
                self._tile_order[tiles] = sorted(range(len(tiles)), key=lambda i: -cost[i])
                while len(self._tile_order) > CACHE_FRAMES:
                    self._tile_order.popitem(last=False)
        self._render_seconds += _time.perf_counter() - started
        out = image
        if stats:
            total: dict[int, int] = {}
            for st in all_stats:
                for k, v in st.items():
                    total[k] = total.get(k, 0) + v
            regions = self.meta.get("regions", {})
            self.last_stats = [RegionStat(*regions[k], total.get(k, 0)) for k in sorted(regions)]
        else:
            with self._lock:
                self._cache[key] = cached
                while len(self._cache) > CACHE_FRAMES or (
                        len(self._cache) > 1 and sum(v.nbytes for v in self._cache.values()) > CACHE_BYTES):
                    self._cache.recycle(self._cache.popitem(last=False)[1])
        return out

    def _render_threads(self, ns, spec, tiles, image, cached, threads, all_stats, budget=None) -> dict:
        """Render `tiles` on this process's threads: {tile: seconds it took}. On an error or
        Ctrl-C the budget is cancelled, so the tiles still running stop at their next region."""
        self.last_parallel = "threads" if threads > 1 and len(tiles) > 1 else "one thread"
        seconds: dict = {}

        def run(tile):
            t0 = _time.perf_counter()
            try:
                st = render_tile(ns, spec, tile, image, cached, budget)
            except BaseException:
                if budget is not None:  # the other tiles stop at their next region
                    budget.cancel()
                raise
            seconds[tile] = _time.perf_counter() - t0
            if st is not None:
                all_stats.append(st)

        if threads > 1 and len(tiles) > 1:
            futures = [_pool(threads).submit(run, t) for t in tiles]
            pending = set(futures)
            try:
                while pending:  # waits of 0.1 s: Ctrl-C is seen between them on every platform
                    done, pending = wait(pending, timeout=0.1, return_when=FIRST_EXCEPTION)
                    if any(f.exception() is not None for f in done):
                        break
            except BaseException:
                if budget is not None:
                    budget.cancel()
                raise
            finally:
                for f in futures:  # after an error: drop the tiles not started yet ...
                    f.cancel()
                for f in futures:  # ... and let the running ones finish before returning
                    if not f.cancelled():
                        f.exception()
            errors = [f.exception() for f in futures if not f.cancelled() and f.exception() is not None]
            if errors:  # the tile's own error, not the Cancelled of the tiles it stopped
                raise next((e for e in errors if not isinstance(e, Cancelled)), errors[0])
        else:
            for t in tiles:
                run(t)
        return seconds

    def _fit_memory(self, precision: str, threads: int) -> tuple[int, int]:
        """(lanes per tile, tiles at once) that keep the tiles' state within `memory_budget()`:
        fewer lanes per tile, then one tile at a time; a located GlslError when even one 2x2
        tile does not fit."""
        per_lane, loc = lane_bytes(self.meta, precision)
        limit = memory_budget()
        lanes = limit // (threads * per_lane)
        if lanes < MIN_TILE_LANES:
            threads = 1
            lanes = limit // per_lane
        if lanes < MIN_TILE_LANES:
            raise GlslError(Diagnostic(
                f"this shader needs about {_megabytes(per_lane)} per pixel on the CPU (its largest variable is "
                f"declared here): even a 2x2 tile would take {_megabytes(MIN_TILE_LANES * per_lane)}, more than "
                f"the memory budget of {_megabytes(limit)}", loc or Location(self.meta.get("source", "<shader>"), 1, 1),
                rule="numpy-memory-budget",
                help="use smaller arrays, or render with --backend gl; GLSLCHECK_MEMORY_MB sets the budget "
                     f"(default {MEMORY_FRACTION:.0%} of the machine's memory)"))
        return min(TILE_LANES, lanes), threads

    def _use_processes(self, threads: int, tiles: list) -> bool:
        """Worker processes for frames of several tiles when asked to, or ("auto") once this
        program has spent PROCESSES_AFTER seconds rendering here or a pool is already up:
        starting the workers costs a few tenths of a second, which one small frame would not
        repay."""
        mode = self.parallel
        if mode not in ("auto", "threads", "processes"):
            raise ValueError(f"parallel must be 'auto', 'threads' or 'processes', not {mode!r}")
        if mode == "threads" or threads < 2 or len(tiles) < 2:
            return False
        from . import workers

        if not workers.available():
            return False
        return mode == "processes" or workers.running() or self._render_seconds >= PROCESSES_AFTER

    def _key(self, precision: str) -> str:
        key = self._keys.get(precision)
        if key is None:
            from .workers import program_key

            key = self._keys[precision] = program_key(self.source, self.meta, precision)
        return key

    def format_stats(self) -> str:
        """The lanes that ran each function, branch and loop body in the last render."""
        rows = [f"{'lanes':>12}  {'what':<10} {'function':<20} where"]
        for r in self.last_stats:
            rows.append(f"{r.lanes:>12,}  {r.kind:<10} {r.function:<20} {r.path}:{r.line}")
        return "\n".join(rows)


def compile_numpy(shader, tab: str | None = None) -> NumpyProgram:
    """Parse, check and transpile a shader's Image tab (or plain GLSL file, or Buffer `tab`)."""
    from .transpile import transpile_shader

    t = transpile_shader(shader, tab)
    prog = NumpyProgram(t.source, t.meta, t.filename, _code=t.code)
    prog.module("float32")  # a broken module fails here, not in the middle of a render
    return prog


def program_from_source(source: str, filename: str = "<glslcheck-numpy module>") -> NumpyProgram:
    """A NumpyProgram from the text of a generated module (reads its SHADER_META)."""
    import ast as pyast

    tree = pyast.parse(source)
    meta = None
    for node in tree.body:
        if isinstance(node, pyast.Assign) and any(getattr(t, "id", None) == "SHADER_META" for t in node.targets):
            meta = pyast.literal_eval(node.value)
    if meta is None:
        raise ValueError(f"{filename}: not a module generated by glslcheck transpile (no SHADER_META)")
    return NumpyProgram(source, meta, filename)


def load_module(path: str) -> NumpyProgram:
    """A module written by `glslcheck transpile`, ready to render."""
    with open(path, encoding="utf-8") as f:
        return program_from_source(f.read(), os.path.abspath(path))


def standalone_globals(meta: dict) -> dict:
    """What a generated module needs when run as a script (`python shader.py`)."""
    precision = "float32"
    argv = sys.argv[1:]
    if "--precision" in argv:
        precision = argv[argv.index("--precision") + 1]
    rt = Runtime(precision, meta.get("float_to_uint"))
    rt.fold_constants = True
    return {"rt": rt, "X": Lanes(meta, rt)}


def run_standalone(ns: dict) -> None:
    """`python shader.py [-o out.png|out.npy] [--size WxH] [--time T] [--frame N] [--precision P]`."""
    import argparse

    p = argparse.ArgumentParser(description="Render this transpiled shader with NumPy.")
    p.add_argument("-o", "--output", default="out.png")
    p.add_argument("--size", default=f"{DEFAULT_SIZE[0]}x{DEFAULT_SIZE[1]}")
    p.add_argument("--time", type=float, default=0.0)
    p.add_argument("--frame", type=int, default=0)
    p.add_argument("--precision", default="float32")
    args = p.parse_args()
    with open(ns["__file__"], encoding="utf-8") as f:
        prog = program_from_source(f.read(), os.path.abspath(ns["__file__"]))
    w, h = (int(v) for v in args.size.lower().split("x"))
    img = prog.render(size=(w, h), time=args.time, frame=args.frame, precision=args.precision)
    from ..images import save_image

    save_image(img, args.output)
