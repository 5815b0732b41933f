"""One frame's tiles on the CPU: what runs the generated code, shared by this process and the
workers.

This module owns everything a tile needs, whether it renders on one of the caller's threads
(program.py) or in a worker process (workers.py); both import it, and neither imports the
other's internals:

- `execute_module`: a generated module run in a restricted namespace (`__builtins__` empty;
  only `rt`, the runtime, and `X`, its `LaneHelpers`, are visible);
- `State`: what one tile's invocation carries (uniforms, globals, discard mask, statistics,
  the frame's `Budget`);
- `LaneHelpers`: the masks, the compaction of sparse regions (`LaneHelpers.gather` /
  `scatter`), the lane statistics, llvmpipe's loop limiter and the errors for a runaway loop or
  an exhausted budget;
- `FrameSpec`: what every tile of one frame needs (uniform values and globals, sample offsets,
  the `Compaction` settings), picklable to travel to the workers;
- `frame_tiles` and `render_tile`: the image cut into tiles, and one tile rendered into its rows.

Tiles: bands of about TILE_LANES pixels (up to TILE_WIDTH wide) keep a shader's temporaries
small (a few hundred kB each); tiles start at even x and y, so derivative quads (2x2, see the
runtime) never straddle two tiles. A tile's fragment coordinates are made once and kept
read-only for later frames (gl_FragCoord only when the code reads it; `_fragments`), uniform
(1,) masks combine without full-lane arrays, and a compacted view (`LaneHelpers.gather`) gathers
globals and fragment coordinates only when the region first reads them.
"""

from __future__ import annotations

import functools
import linecache
import threading
import time as _time
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...base.diagnostics import Diagnostic, GlslError, Location
from .lane_memo import MemoMath
from .runtime import Runtime
from .runtime_values import Struct, lanes_of
from .transpile import glsl_location, too_complex

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up

TILE_LANES = (
    49152  # lanes per tile: fewer calls in compacted regions; full-lane work measured flat 24k-49k
)
TILE_WIDTH = 1024  # widest tile; wide bands keep rows contiguous in the output image
TILE_HEIGHT = (
    None  # None: TILE_LANES // tile width (rounded to even); set both to force a tile size
)
MIN_TILE_LANES = 4  # one 2x2 derivative quad


@dataclass(frozen=True)
class Compaction:
    """When a varying region runs on a gathered copy of the lanes that take it
    (`LaneHelpers.sparse`) instead of masked on all of them: a frame's setting
    (`FrameSpec.compaction`, from `NumpyProgram.compaction`), carried by each tile's `State`."""

    fraction: float = 0.5  # compact a region when fewer than this fraction of the lanes take it
    min_lanes: int = 1024  # below this many lanes gathering costs more than it saves
    # the same for a loop's live lanes, checked at every pass. Gathered once, the short arrays
    # serve every later pass, so compacting earlier could pay off; measured at 0.75 and 0.9
    # (docs/performance.md) it moved no real shader beyond the noise of a shared
    # machine and added gathers to a Mandelbrot loop whose lanes leave a few at a time
    loop_fraction: float = 0.5
    # the same for a dead-lane region (transpile/dead_lanes.py), which holds a loop, a call or
    # enough arithmetic that its lanes left out cost more than the gather: on 07_final at
    # 800x450 (three tiles of 50-55% hit lanes) one-thread frames of 42 ms at 0.5, 35-38 ms
    # at 0.75, 0.9 and 1.01 alike (docs/performance.md)
    select_fraction: float = 0.75


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

    def start(self) -> Budget:
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


class State:
    """What one tile's invocation carries: `lanes`, `width` (tile width, for derivatives),
    `frag_coord` (vec2 lanes), `frag_coord4` (gl_FragCoord), `discard` (mask), uniforms
    `u_<name>`, globals `g_<name>`, `stats` (region id -> lanes, shared), `parent` (when this
    is a compacted view of another state), `budget` (the frame's `Budget`; None: no limit),
    `compaction` (the frame's `Compaction`)."""

    budget: Budget | None = None
    compaction = Compaction()

    passes = (
        None  # [passes left] of llvmpipe's loop limiter when emulated (LaneHelpers.tick), else None
    )
    frame_values: dict | None = None  # the frame's values (`LaneHelpers.frame`); None: none kept

    if TYPE_CHECKING:  # a compacted view's own fields (`compact`), and gl_FragCoord
        parent: State
        lanes: int
        idx: np.ndarray
        lazy: set[str]
        gathered: dict[str, Any]
        frag_coord4: Any
        width: int
        frag_coord: Any

    def __init__(self, **values: Any) -> None:
        self.__dict__.update(values)

    def __getattr__(self, name: str) -> Any:
        # a compacted view gathers globals and fragment coordinates on first use only
        lazy = self.__dict__.get("lazy")
        if lazy is None or name not in lazy:
            raise AttributeError(name)
        lazy.discard(name)
        parent = self.parent
        g = LaneHelpers._take(getattr(parent, name), self.idx, parent.lanes)
        self.__dict__[name] = g
        self.gathered[name] = g
        return g


@dataclass
class _Gathered:
    values: tuple
    originals: tuple


class LaneHelpers:
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
        assert self.rt is not None  # (helpers of a render have its runtime)
        return self.rt.assign(old, new, m)

    def reg(self, S, name: str, new, m):
        """``new`` (a call's result under the mask m) with the lanes m leaves out holding what
        they held the last time this call site ran for them (zero before), kept on S as the
        lane field `name`: llvmpipe's register for a value merged across control flow (a
        function's return from inside a branch, after inlining), stored under the exec mask,
        so a neighbour's derivative reads the old value there (transpile/functions.py)."""
        assert self.rt is not None  # (helpers of a render have its runtime)
        if not self.rt.lp:
            return new  # (llvmpipe's, float32 renders only: the float64 reference keeps zero there)
        old = getattr(S, name, None)  # (a `g_` field: gathered and scattered as a global)
        if old is None or np.shape(old) != np.shape(new):
            old = np.zeros_like(new)
        out = self.put(old, new, m)
        setattr(S, name, out)
        return out

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
    def reads(S, m, lanes):
        """The lanes of m a dead-lane region runs on (transpile/dead_lanes.py): those of
        `lanes` (where the select reads its values; None: every lane). All of m under
        llvmpipe's loop limiter, whose pass budget the region's loops spend as before."""
        if lanes is None or S.passes is not None:
            return m
        return LaneHelpers.and_(m, lanes)

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

    # values computed once a frame (transpile/frame_values.py) ----------------------------------
    @staticmethod
    def frame(S, key: int):
        """The values the statements `key` computed in an earlier tile of this frame, or None
        (not yet, or no table kept: then the tile computes them)."""
        table = S.frame_values
        return None if table is None else table.get(key)

    @staticmethod
    def keep(S, key: int, values: tuple) -> None:
        """Keep what the statements `key` computed for the frame's later tiles: one-lane values
        only (a value of several lanes would be this tile's, a broken promise of the
        transpiler's, so nothing is kept and every tile computes its own)."""
        table = S.frame_values
        if table is not None and lanes_of(*values) == 1:
            table[key] = values

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
        n = (
            S.lanes
            if m is None
            else (int(np.count_nonzero(m)) if m.shape[-1] != 1 else (S.lanes if m[0] else 0))
        )
        st[rid] = st.get(rid, 0) + n

    def tick(self, S, n: int) -> bool:
        """llvmpipe's loop limiter, when the program renders with `loop_limit` (gallivm
        lp_exec_endloop, LP_MAX_TGSI_LOOP_ITERATIONS = 65535): one pass budget per invocation
        shared by every loop; each pass of a loop costs 1 when it ends, and the loop goes round
        again only while the budget is positive. Called at the top of pass `n`, where pass
        n - 1 ended: True when the loop must stop (`stop` records it). The pass that ends a
        loop on its condition costs 1 too (`spend`: llvmpipe masks the lanes out and runs to
        the loop's end); a break or a return ends the pass it is in. Matches llvmpipe's pass
        counts exactly: `for (i < 70000)` runs 65,535 times; two loops of 40,000 run 40,000 and
        25,534; a loop entered with no budget left runs once; three nested loops of 99,999 run
        1, 1 and 65,535 passes (an outer pass is paid when it ends, after its inner loop).
        The budget is per tile here and per 8-lane group there: for loops whose pass count
        differs between pixels it can bite at a slightly different pass."""
        passes = S.passes
        if passes is None or n == 1:
            return False
        passes[0] -= 1
        return passes[0] <= 0

    @staticmethod
    def spend(S) -> None:
        """The pass whose condition ends the loop: it costs 1 (see `tick`)."""
        if S.passes is not None:
            S.passes[0] -= 1

    def stop(self, lid: int, live) -> None:
        """The limiter stopped loop `lid`: recorded when some lane was still in it."""
        if self.live(live):
            self.limited.add(lid)

    def over_budget(self, budget: Budget, rid: int) -> None:
        if budget.cancelled:
            raise Cancelled()
        kind, function, path, line = self.meta.get("regions", {}).get(rid, ("", "", "<shader>", 0))
        _, _, col = self.loops.get(rid, (path, line, 1))
        where = (
            "this loop"
            if kind == "loop"
            else f"this {kind}"
            if kind in ("if", "else", "case")
            else f"'{function}'"
        )
        raise GlslError(
            Diagnostic(
                f"the frame was still rendering after {budget.seconds:g} s on the CPU, "
                f"in {where}; the NumPy "
                "renderer stops it (a GPU would hang or reset)",
                Location(path, line, col),
                rule="numpy-frame-budget",
                help="bound the loops' iteration counts (nested loops multiply) and the arrays' "
                "sizes; --frame-budget SECONDS (or GLSLCHECK_FRAME_SECONDS) sets the budget",
            )
        )

    def runaway(self, lid: int) -> None:
        path, line, col = self.loops.get(lid, ("<shader>", 0, 0))
        cap = self.meta.get("loop_cap", 0)
        raise GlslError(
            Diagnostic(
                f"this loop did not end after {cap:,} iterations; the NumPy renderer stops it (a "
                "GPU would hang or reset)",
                Location(path, line, col),
                rule="numpy-runaway-loop",
                help="check the loop's condition and step; give it a constant upper bound",
            )
        )

    # undefined values ---------------------------------------------------------------------------
    # The value a module transpiled with undefined="vary" gives an undefined read: the n-th drawn
    # in the tile (counted on its uncompacted state, so the same tile draws the same values),
    # spread over (0.1, 0.9) for floats by the golden ratio's multiples, 1..7 for integers, true
    # for bools: never zero or false, WebGL's value, and different from one draw to the next, as
    # a register's leftover is, so a loop waiting for a random point inside a sphere ends.
    GOLDEN = 0.6180339887498949

    def undefined(self, S, zero):
        root = S
        while root.__dict__.get("parent") is not None:
            root = root.parent
        n = root.__dict__.get("undefined_draws", 0) + 1
        root.undefined_draws = n
        f = 0.1 + 0.8 * ((n * self.GOLDEN) % 1.0)
        return self._filled(zero, f, 1 + n % 7)

    def _filled(self, zero, f: float, i: int):
        if hasattr(zero, "map"):  # a struct (runtime_values.Struct): each field
            return zero.map(lambda v: self._filled(v, f, i))
        kind = zero.dtype.kind
        return np.full_like(zero, f if kind == "f" else (True if kind == "b" else i))

    # compaction -------------------------------------------------------------------------------
    @staticmethod
    def sparse(S, m, fraction: float | None = None):
        """Active lane indices when compacting pays off (fewer than ``fraction``, by default
        the region's `Compaction.fraction`, of the lanes are active), else None."""
        c = S.compaction
        if m is None or S.lanes < c.min_lanes or m.shape[-1] != S.lanes:
            return None
        if np.count_nonzero(m) >= (c.fraction if fraction is None else fraction) * S.lanes:
            return None  # (counted first: no index array on the passes that do not compact)
        return np.flatnonzero(m)

    @staticmethod
    def select_sparse(S, m):
        """`sparse` for a dead-lane region (`Compaction.select_fraction`)."""
        return LaneHelpers.sparse(S, m, S.compaction.select_fraction)

    @staticmethod
    def loop_sparse(S, m):
        """`sparse` for a loop's live lanes, at the top of each pass
        (`Compaction.loop_fraction`)."""
        return LaneHelpers.sparse(S, m, S.compaction.loop_fraction)

    @staticmethod
    def _take(v, idx, lanes):
        if isinstance(v, np.ndarray):
            if v.ndim and v.shape[-1] == lanes and lanes != 1:
                return np.take(v, idx, axis=-1)  # several times faster than v[..., idx]
            return v
        if isinstance(v, Struct):
            return v.map(lambda x: LaneHelpers._take(x, idx, lanes))
        return v

    @staticmethod
    def _put(old, new, idx, lanes):
        if new is old:
            return old
        if isinstance(new, Struct):
            return Struct(
                new.type_name, {k: LaneHelpers._put(old[k], new[k], idx, lanes) for k in new.fields}
            )
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
        child.gathered = {
            k: fields[k] for k in fields if k.startswith("g_") or k in self._LANE_FIELDS
        }
        gathered = tuple(self._take(v, idx, lanes) for v in values)
        return child, _Gathered(gathered, values)

    def scatter(self, S, idx, rec: _Gathered, values: tuple, uniform: int = 0):
        """The region's end: S's parent back, with what the region wrote put into the lanes
        `idx` (`values`: the region's variables, in the order gathered; fewer when the region
        leaves the last ones dead). The last `uniform` of `values` are variables every write of
        which in the region was free (backends/cpu_core/uniformity.py): one value for all lanes
        stays that, not an array of them."""
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
        first_uniform = len(values) - uniform
        out = tuple(
            o
            if v is g
            else v
            if k >= first_uniform and lanes_of(v) == 1
            else self._put(o, v, idx, lanes)
            for k, (o, g, v) in enumerate(zip(rec.originals, rec.values, values))
        )
        return parent, out

    def push(self, stack: list, S, m, values: tuple):
        idx = self.loop_sparse(S, m)
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


def execute_module(
    source: str, filename: str, meta: dict, precision: str = "float32", code: Any = None
) -> dict:
    """Run generated code in a namespace that holds nothing but the runtime and the helpers.

    The source is registered in `linecache` under `filename`, so tracebacks and debuggers show
    the generated lines (each with its GLSL line in a comment)."""
    linecache.cache[filename] = (len(source), None, source.splitlines(True), filename)
    if code is None:
        code = compile(source, filename, "exec")
    ns: dict[str, Any] = {"__builtins__": {}, "__name__": "glslcheck_shader", "rt": None, "X": None}
    ns["rt"] = rt = Runtime(precision, meta.get("float_to_uint"))
    rt.fold_constants = True  # Mesa's folding of constants (Runtime.fmul); uniforms are read-only
    rt.lp = (
        MemoMath(rt.lp) if rt.lp is not None else None
    )  # uniform inputs: computed once (lane_memo.py)
    ns["X"] = LaneHelpers(meta, rt)
    with np.errstate(all="ignore"):  # constants may overflow in float16, as on a mediump GPU
        exec(code, ns)  # noqa: S102 - generated from a checked AST; every GLSL name is mangled
    return ns


# ---------------------------------------------------------------------------------------------
# A frame's tiles
# ---------------------------------------------------------------------------------------------


@dataclass
class FrameSpec:
    """What every tile of one frame needs; picklable (it travels to worker processes)."""

    width: int
    height: int
    base: dict  # u_<uniform> and g_<global> values, the same for every pixel
    offsets: list  # sub-pixel sample offsets
    need4: bool  # the code reads gl_FragCoord: build it
    stats: bool  # count the lanes of each region
    compaction: Compaction = Compaction()  # the program's setting, the same in every worker
    # the values computed once a frame (LaneHelpers.frame), filled by the first tile that needs
    # each; a worker process fills its own copy
    values: dict = field(default_factory=dict)

    def __getstate__(self) -> dict:
        # a worker computes its own: an unpickled array is writable, and Runtime.fmul tells a
        # uniform input (read-only) from a constant by that flag
        return {**self.__dict__, "values": {}}


def frame_tiles(
    width: int, height: int, lanes: int | None = None
) -> tuple[tuple[int, int, int, int], ...]:
    """(x0, y0, w, h) of each tile, y0 from the bottom; tiles start at even x and y, so 2x2
    derivative quads never straddle two tiles. `lanes`: at most this many per tile (memory)."""
    tile_lanes = TILE_LANES if lanes is None else max(MIN_TILE_LANES, min(TILE_LANES, lanes))
    return _frame_tiles(width, height, TILE_WIDTH, TILE_HEIGHT, tile_lanes)


@functools.lru_cache(maxsize=64)
def _frame_tiles(
    width: int, height: int, tile_width: int, tile_height: int | None, tile_lanes: int
) -> tuple[tuple[int, int, int, int], ...]:
    tw = min(tile_width, width, max(2, tile_lanes // 4 * 2))  # narrower than a 2-row band of lanes
    tw += tw % 2 if tw < width else 0
    th = tile_height or max(2, (tile_lanes // tw) // 2 * 2)
    return tuple(
        (x0, y0, min(tw, width - x0), min(th, height - y0))  # a tuple: the cache shares it
        for y0 in range(0, height, th)
        for x0 in range(0, width, tw)
    )


# Fragment coordinates of tiles already rendered, read-only, by (tile, dtype, sample offset,
# gl_FragCoord wanted): building them again was 5% of a frame of the four-sphere scene. Kept up
# to FRAG_CACHE_LANES lanes (a 1920x1080 frame twice over; past that they are made per tile).
FRAG_CACHE_LANES = 2 * 1920 * 1080
_FRAGS: dict = {}
_FRAG_LANES = [0]
# (w, h) -> pixel-centre offsets (float64) of a tile shape; a frame has few shapes
_GRIDS: dict = {}


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
        grid = _GRIDS[(tw, th)] = (
            np.tile(np.arange(tw) + 0.5, th),
            np.repeat(np.arange(th) + 0.5, tw),
        )
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


def render_tile(
    ns: dict,
    spec: FrameSpec,
    tile: tuple[int, int, int, int],
    image: np.ndarray,
    cached: np.ndarray | None = None,
    budget: Budget | None = None,
) -> dict | None:
    """Run the shader on one tile and write its rows into `image` (and `cached`); returns the
    tile's lane counts per region when `spec.stats`, else None. `budget`: the frame's."""
    rt = ns["rt"]
    x0, y0, tw, th = tile
    # A GPU shades whole 2x2 quads: at an odd right or top edge the quad's other pixels are
    # helper invocations outside the viewport, which derivatives (and implicit mipmap LODs) read
    # (llvmpipe, measured on a real shader at 16x9). A shader that uses derivatives gets the same
    # helper column/row here; they are rendered and dropped.
    ew, eh = (tw + tw % 2, th + th % 2) if ns["X"].meta.get("uses_derivatives") else (tw, th)
    lanes = ew * eh
    samples = len(spec.offsets)
    acc = None
    st: dict | None = {} if spec.stats else None
    for dx, dy in spec.offsets:
        frag, frag4 = _fragments(
            rt,
            tile if (ew, eh) == (tw, th) else (x0, y0, ew, eh),
            dx if samples > 1 else 0.0,
            dy if samples > 1 else 0.0,
            spec.need4,
        )
        limit = spec.base.get("loop_limit")
        S = State(
            **spec.base,
            lanes=lanes,
            width=ew,
            frag_coord=frag,
            discard=LaneHelpers.NO,
            stats=st,
            parent=None,
            budget=budget,
            passes=None if limit is None else [limit],
            compaction=spec.compaction,
            # none kept where a tile counts what the statements do: lane statistics, llvmpipe's
            # pass budget per invocation
            frame_values=spec.values if limit is None and not spec.stats else None,
        )
        if spec.need4:
            S.frag_coord4 = frag4
        with rt.errstate():
            try:
                color = ns["shade"](S)  # RGB (a Shadertoy shader: alpha is 1) or RGBA (plain GLSL)
            except RecursionError as e:  # a chain of calls nested about a thousand deep
                raise _too_deep(ns, e) from None
            if S.discard is not LaneHelpers.NO or samples > 1:
                if len(color) == 3:
                    color = np.concatenate(
                        [np.broadcast_to(color, (3, lanes)), np.ones((1, lanes), color.dtype)]
                    )
                color = np.broadcast_to(color, (4, lanes))
                if S.discard is not LaneHelpers.NO:
                    # a mask of None is every lane (a discard under the entry's full mask)
                    every = S.discard is None
                    color = np.where(np.broadcast_to(every or S.discard, (lanes,)), 0.0, color)
                if samples > 1:
                    color = color.astype(np.float64)
            color = np.broadcast_to(color, (len(color), lanes))
        acc = color if acc is None else acc + color
    assert acc is not None  # (at least one sample)
    if samples > 1:
        acc = acc / samples
    # tile row 0 is the bottom one (y0); the image's row 0 is the top of the picture
    rows = slice(spec.height - y0 - th, spec.height - y0)
    if acc.strides[-1] == 0:
        # the same colour in every pixel (a background tile): whole rows of it, one pass; the
        # reshape is a view, since the 4 channels of a row's pixels are contiguous
        pixel = np.append(acc[:, 0], [1.0]) if len(acc) == 3 else acc[:, 0]
        image[rows, x0 : x0 + tw].reshape(th, tw * 4)[...] = np.tile(pixel.astype(np.float32), tw)
    else:
        dst = image[rows, x0 : x0 + tw][::-1]
        for c in range(len(acc)):  # one channel at a time: 2.5x faster than one transposed copy
            dst[..., c] = acc[c].reshape(eh, ew)[:th, :tw]
        if len(acc) == 3:
            dst[..., 3] = 1.0
    if cached is not None:
        cached[rows, x0 : x0 + tw] = image[rows, x0 : x0 + tw]
    return st


def _too_deep(ns: dict, e: RecursionError) -> GlslError:
    """A located error for Python's recursion limit reached by the generated code: at the GLSL
    line of the innermost generated frame (GLSL has no recursion: a long chain of calls)."""
    path = ns.get("SHADER_META", {}).get("source", "<shader>")
    loc = Location(path, 1, 1)
    tb = e.__traceback__
    while tb is not None:
        code = tb.tb_frame.f_code
        if tb.tb_frame.f_globals is ns and code.co_filename in linecache.cache:
            loc = glsl_location("".join(linecache.getlines(code.co_filename)), tb.tb_lineno, path)
        tb = tb.tb_next
    return too_complex("its function calls are nested too deeply for Python", loc)
