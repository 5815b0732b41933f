"""Compiling a shader to its NumPy module and rendering its frames: scheduling, caches, budgets,
stats.

This module owns what happens around one frame: the frame cache for shaders that do not
animate, the uniform values, globals and frame values every tile shares (`FrameSpec`), the
order and the workers of the tiles (worker processes, workers.py, or a thread pool), the
frame's budgets, time (config.FRAME_SECONDS, `tiles.Budget`) and memory (MEMORY_FRACTION,
tiles sized to the shader's per-lane state, `NumpyProgram._fit_memory`), and the lane
statistics. What runs inside a tile
(the namespace of the generated code, `State`, `LaneHelpers`, `render_tile`) is tiles.py's, shared
with the worker processes; the imports go one way: program -> workers -> tiles.

Library API:

    prog = compile_numpy(shader)            # parse + check + transpile; GlslError on errors
    img = prog.render(size=(800, 450), time=0.0, frame=0, mouse=(0, 0, 0, 0), date=None,
                      time_delta=1/60, frame_rate=60.0, samples=1, precision="float32")
    # img: float32 (height, width, 4), top row first; the GL backend's render() signature plus
    # `precision` ("float16" | "float32" | "float64", the float dtype used inside the shader)
    prog.last_stats                         # lanes per function/branch/loop of the last render
    prog.parallel = "auto"                  # or "processes" / "threads" (env GLSLCHECK_PARALLEL)
    prog.compaction = Compaction(min_lanes=16)  # when sparse regions run on gathered lanes
    module = load_module("shader.py")       # a module written by `glslcheck transpile`

A frame is cut into tiles (`frame.frame_tiles`); `os.cpu_count()` worker processes or threads
of one process-wide pool render them. Threads share the GIL, which NumPy releases only inside
each operation: a tile runs hundreds of short ones, so two threads gain little (nothing on a
sparse scene). Processes do not share it but cost a few tenths of a second to start, so
`parallel="auto"` uses threads until a program has rendered for PROCESSES_AFTER seconds in
this process (or a pool is already up). Tiles write their rows straight into the top-first
image (with threads also into the frame cache's copy, whose buffers are reused; worker
processes write a shared file that the caller and the cache map without copying it). Peak
memory is a few tiles' temporaries per worker plus the output image and its cached copy.
"""

from __future__ import annotations

import os
import sys
import threading
import time as _time
from collections import OrderedDict
from collections.abc import Sequence
from concurrent.futures import FIRST_EXCEPTION, ThreadPoolExecutor, wait
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import numpy as np

from ...base import config
from ...base.diagnostics import Diagnostic, GlslError, Location
from ...shadertoy.frame_inputs import FrameInputs, frame_inputs
from ...shadertoy.wrapper import DEFAULT_SIZE, UNIFORMS_BY_NAME
from ..driver_profile import host_model
from . import workers
from .runtime import Runtime
from .tiles import (
    MIN_TILE_LANES,
    Budget,
    Cancelled,
    Compaction,
    FrameSpec,
    LaneHelpers,
    State,
    execute_module,
    frame_tiles,
    render_tile,
)
from .transpile import SMALL_STATE, transpile_shader

CACHE_FRAMES = 8
_CPUS = os.cpu_count()
CACHE_BYTES = (
    256 * 2**20
)  # and at most this much of them (a 3840x2160 frame is 127 MiB), the newest always kept
PROCESSES_AFTER = (
    1.0  # seconds a program renders in this process before "auto" starts worker processes
)
# The whole-frame budget: a frame that is still rendering after this many seconds stops with an
# error at the loop (or function) it was in, whatever each loop's own cap (LOOP_CAP iterations
# per loop execution: loops nested two deep may still run 10**10 times). Checked at every region
# entry and loop iteration (`LaneHelpers.count`); environment variable GLSLCHECK_FRAME_SECONDS, or
# `NumpyProgram.frame_seconds`.
# The memory budget: the tiles rendering at once (one per thread or worker) hold at most this
# fraction of the machine's memory, or of the address space `ulimit -v` leaves this process;
# environment variable GLSLCHECK_MEMORY_MB. A tile's lanes times the shader's per-lane state
# (estimated by the transpiler, `transpile.lane_state`) must fit: large local arrays get smaller
# tiles, and a shader whose 2x2 tile does not fit is refused with an error at its largest variable.
MEMORY_FRACTION = 0.5
# Uniforms that change from frame to frame; a shader that reads none of them renders one image
# for a whole animation.
ANIMATED_UNIFORMS = ("iTime", "iFrame", "iTimeDelta", "iDate", "iMouse", "iFrameRate")


def memory_budget() -> int:
    """Bytes the tiles rendering at once may hold: GLSLCHECK_MEMORY_MB, else MEMORY_FRACTION of
    the machine's memory or of the address space left under `ulimit -v`, whichever is less."""
    given = config.memory_mb()
    if given is not None:
        return int(given * 2**20)
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
    """The frame budget in seconds: GLSLCHECK_FRAME_SECONDS, else config.FRAME_SECONDS. The variable
    takes the range `--frame-budget` takes (base/limits.py, the one home of both limits)."""
    return config.frame_seconds()


def uniform_value(rt: Runtime, name: str, value: Any) -> Any:
    """`value` of the Shadertoy uniform `name` as the runtime holds it (a sampler: its
    ChannelInput)."""
    u = UNIFORMS_BY_NAME[name]
    t = u.glsl_type
    if t.startswith("sampler"):
        return (
            value if not isinstance(value, int) else None
        )  # a channels.ChannelInput; None: unbound

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
            del self.spare[: -self.SPARE_FRAMES]

    def clear(self) -> None:
        for image in list(self.values())[-self.SPARE_FRAMES :]:
            self.recycle(image)
        super().clear()


_POOLS: dict[int, ThreadPoolExecutor] = {}
_POOLS_LOCK = threading.Lock()


def tile_pool(threads: int) -> ThreadPoolExecutor:
    """A process-wide pool of `threads` tile workers (made once, not per render)."""
    with _POOLS_LOCK:
        pool = _POOLS.get(threads)
        if pool is None:
            pool = _POOLS[threads] = ThreadPoolExecutor(
                max_workers=threads, thread_name_prefix="glslcheck-tile"
            )
        return pool


class _FrameKey(NamedTuple):
    """What decides a frame's pixels (the frame cache's key): size, samples, precision, stats,
    llvmpipe's loop limit and the values of the uniforms the shader reads."""

    width: int
    height: int
    samples: int
    precision: str
    stats: bool
    loop_limit: int | None
    uniforms: tuple


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

    engine = "numpy"  # the engine that renders its frames (Program.engine; not a field)

    source: str
    meta: dict
    filename: str
    threads: int | None = None
    last_stats: list[RegionStat] = field(default_factory=list)
    # "threads", "processes" (worker processes, see workers.py) or "auto": processes once the
    # program has rendered for PROCESSES_AFTER seconds in this process
    parallel: str = field(default_factory=config.parallel)
    last_parallel: str = ""  # how the last frame was rendered: "processes", "threads", "one thread"
    # llvmpipe's loop limiter (LaneHelpers.tick): None = loops run until they end (a runaway loop is
    # an error after LOOP_CAP passes); 65535 = stop as llvmpipe does (verify sets it)
    loop_limit: int | None = None
    frame_seconds: float | None = (
        None  # the frame budget; None: GLSLCHECK_FRAME_SECONDS or FRAME_SECONDS
    )
    compaction: Compaction = (
        Compaction()
    )  # when a sparse region runs on a gathered copy of its lanes
    _render_seconds: float = field(default=0.0, repr=False)
    _keys: dict = field(default_factory=dict, repr=False)
    _modules: dict = field(default_factory=dict, repr=False)
    _cache: _FrameCache = field(default_factory=lambda: _FrameCache(), repr=False)
    _specs: OrderedDict = field(default_factory=OrderedDict, repr=False)  # frame key -> FrameSpec
    _tile_order: OrderedDict = field(
        default_factory=OrderedDict, repr=False
    )  # tiles -> indices, slowest first
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
        """Compute ``uint(x)`` of out-of-range floats as `model` does
        (glslcheck/backends/driver_profile.py; by default this machine's prediction): verify sets
        the model it measured on the driver."""
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
            found |= {
                tuple(x.loops.get(lid, ("<shader>", 0, 0))[:2]) for lid in getattr(x, "limited", ())
            }
            getattr(x, "limited", set()).clear()
        return sorted(found)

    def module(self, precision: str = "float32") -> dict:
        with self._lock:
            if precision not in self._modules:
                self._modules[precision] = execute_module(
                    self.source, self.filename, self.meta, precision, self._code
                )
            return self._modules[precision]

    @frame_inputs
    def render(
        self, inputs: FrameInputs, precision: str = "float32", stats: bool = False, channels=None
    ) -> np.ndarray:
        """Render one frame: float32 (height, width, 4), row 0 = top of the image, unclamped.

        Arguments as `GLProgram.render` (`shadertoy.FrameInputs`, then `channels`: the inputs of
        iChannel0..3, glslcheck.shadertoy.channels.ChannelInput or None); `precision` is the float
        dtype inside the shader. Discarded pixels are (0, 0, 0, 0), the GL backend's clear
        colour."""
        ns = self.module(precision)
        values = inputs.uniforms()
        if (
            channels is not None
        ):  # each ChannelInput's repr is unique: a new input is a new frame key
            from ...shadertoy.channels import channel_uniforms

            values.update(channel_uniforms(channels))
        key = _FrameKey(
            inputs.width,
            inputs.height,
            inputs.samples,
            precision,
            stats,
            self.loop_limit,
            tuple((u, repr(values.get(u, UNIFORMS_BY_NAME[u].default))) for u in self.uniforms),
        )
        if not stats:
            hit = self._cached(key)
            if hit is not None:
                return hit
        spec = self._frame_spec(key, ns, values, inputs.offsets)
        image, cached, all_stats = self._schedule(ns, spec, precision)
        self._store(key, cached, all_stats)
        return image

    def _cached(self, key: _FrameKey) -> np.ndarray | None:
        """A copy of the frame cache's image for `key` (the caller may write it), or None."""
        with self._lock:
            hit = self._cache.get(key)
            if hit is None:
                return None
            self._cache.move_to_end(key)
            return hit.copy()

    def _frame_spec(self, key: _FrameKey, ns: dict, values: dict, offsets: list) -> FrameSpec:
        """The frame's FrameSpec: uniform values and globals (run once, on one lane), the same
        for every frame with this key and compaction, so kept for the last CACHE_FRAMES keys."""
        spec_key = (key, self.compaction)
        with self._lock:
            spec = self._specs.get(spec_key)
        if spec is not None:
            return spec
        rt = ns["rt"]
        base = {
            f"u_{u}": uniform_value(rt, u, values.get(u, UNIFORMS_BY_NAME[u].default))
            for u in self.uniforms
        }
        base["loop_limit"] = self.loop_limit
        proto = State(
            **base, lanes=1, width=1, stats=None, discard=LaneHelpers.NO, parent=None, budget=None
        )
        with rt.errstate():
            ns["init_globals"](proto)
        base.update({k: v for k, v in proto.__dict__.items() if k.startswith("g_")})
        spec = FrameSpec(
            key.width,
            key.height,
            base,
            offsets,
            "S.frag_coord4" in self.source,
            key.stats,
            self.compaction,
        )
        with self._lock:
            self._specs[spec_key] = spec
            while len(self._specs) > CACHE_FRAMES:
                self._specs.popitem(last=False)
        return spec

    def _schedule(
        self, ns: dict, spec: FrameSpec, precision: str
    ) -> tuple[np.ndarray, np.ndarray | None, list[dict]]:
        """Render the frame's tiles within its time and memory budgets, on worker processes or
        threads: (the caller's image, the frame cache's copy (None with stats), per-tile stats).
        The tiles that took longest in the last frame of this size go first, so that the workers
        finish together (the order changes no pixel: each tile writes its own rows)."""
        budget = Budget(self.frame_seconds if self.frame_seconds is not None else frame_seconds())
        tile_lanes, threads = self._fit_memory(precision, self.threads or _CPUS or 1)
        tiles = frame_tiles(spec.width, spec.height, tile_lanes)
        with self._lock:
            order = self._tile_order.get(tiles)
        run_tiles = [tiles[i] for i in order] if order is not None else tiles
        all_stats: list[dict] = []
        seconds: dict[tuple, float] = {}  # tile -> seconds it took
        image = cached = None
        started = _time.perf_counter()
        if self._use_processes(threads, tiles):
            try:
                # the image and the cache's read-only view share the pixels (copy-on-write)
                image, cached, all_stats, seconds = workers.render(
                    self._key(precision),
                    self.source,
                    self.filename,
                    self.meta,
                    precision,
                    spec,
                    run_tiles,
                    threads,
                    budget,
                )
                self.last_parallel = "processes"
            except workers.Unavailable:
                image, all_stats = None, []  # the pool is gone for this process: threads below
        if image is None:
            image = np.empty((spec.height, spec.width, 4), dtype=np.float32)  # top row first
            # the frame cache's copy, written by each tile while its rows are still in the CPU cache
            if not spec.stats:
                with self._lock:
                    cached = self._cache.buffer(image.shape)
            budget.start()
            try:
                seconds = self._render_threads(
                    ns, spec, run_tiles, image, cached, threads, all_stats, budget
                )
            finally:
                budget.finish()
        if len(seconds) == len(tiles):
            cost = [seconds[t] for t in tiles]
            with self._lock:
                self._tile_order[tiles] = sorted(range(len(tiles)), key=lambda i: -cost[i])
                while len(self._tile_order) > CACHE_FRAMES:
                    self._tile_order.popitem(last=False)
        self._render_seconds += _time.perf_counter() - started
        return image, cached, all_stats

    def _store(self, key: _FrameKey, cached: np.ndarray | None, all_stats: list[dict]) -> None:
        """After a frame: its lane statistics in `last_stats` (a frame with stats is not
        cached), else its copy in the frame cache, bounded by CACHE_FRAMES and CACHE_BYTES."""
        if key.stats:
            total: dict[int, int] = {}
            for st in all_stats:
                for k, v in st.items():
                    total[k] = total.get(k, 0) + v
            regions = self.meta.get("regions", {})
            self.last_stats = []
            for k in sorted(regions):
                kind, function, path, line = regions[k]
                self.last_stats.append(RegionStat(kind, function, path, line, total.get(k, 0)))
            return
        with self._lock:
            self._cache[key] = cached
            while len(self._cache) > CACHE_FRAMES or (
                len(self._cache) > 1 and sum(v.nbytes for v in self._cache.values()) > CACHE_BYTES
            ):
                self._cache.recycle(self._cache.popitem(last=False)[1])

    def _render_threads(
        self, ns, spec, tiles, image, cached, threads, all_stats, budget=None
    ) -> dict:
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
            futures = [tile_pool(threads).submit(run, t) for t in tiles]
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
            errors = [e for f in futures if not f.cancelled() and (e := f.exception()) is not None]
            if errors:  # the tile's own error, not the Cancelled of the tiles it stopped
                raise next((e for e in errors if not isinstance(e, Cancelled)), errors[0])
        else:
            for t in tiles:
                run(t)
        return seconds

    def _fit_memory(self, precision: str, threads: int) -> tuple[int, int]:
        """(at most this many lanes per tile, tiles at once) that keep the tiles' state within
        `memory_budget()`: fewer lanes per tile, then one tile at a time; a located GlslError when
        even one 2x2 tile does not fit."""
        per_lane, loc = lane_bytes(self.meta, precision)
        limit = memory_budget()
        lanes = limit // (threads * per_lane)
        if lanes < MIN_TILE_LANES:
            threads = 1
            lanes = limit // per_lane
        if lanes < MIN_TILE_LANES:
            raise GlslError(
                Diagnostic(
                    f"this shader needs about {_megabytes(per_lane)} per pixel on the CPU (its "
                    "largest variable is "
                    "declared here): even a 2x2 tile would take "
                    f"{_megabytes(MIN_TILE_LANES * per_lane)}, more than "
                    f"the memory budget of {_megabytes(limit)}",
                    loc or Location(self.meta.get("source", "<shader>"), 1, 1),
                    rule="numpy-memory-budget",
                    help="use smaller arrays, or render with --backend gl; "
                    "GLSLCHECK_MEMORY_MB sets the budget "
                    f"(default {MEMORY_FRACTION:.0%} of the machine's memory)",
                )
            )
        return lanes, threads  # frame_tiles makes tiles of at most TILE_LANES

    def _use_processes(self, threads: int, tiles: Sequence) -> bool:
        """Worker processes for frames of several tiles when asked to, or ("auto") once this
        program has spent PROCESSES_AFTER seconds rendering here or a pool is already up:
        starting the workers costs a few tenths of a second, which one small frame would not
        repay."""
        mode = self.parallel
        if mode not in ("auto", "threads", "processes"):
            raise ValueError(f"parallel must be 'auto', 'threads' or 'processes', not {mode!r}")
        if mode == "threads" or threads < 2 or len(tiles) < 2:
            return False
        if not workers.available():
            return False
        return mode == "processes" or workers.running() or self._render_seconds >= PROCESSES_AFTER

    def _key(self, precision: str) -> str:
        key = self._keys.get(precision)
        if key is None:
            key = self._keys[precision] = workers.program_key(self.source, self.meta, precision)
        return key

    def format_stats(self) -> str:
        """The lanes that ran each function, branch and loop body in the last render."""
        rows = [f"{'lanes':>12}  {'what':<10} {'function':<20} where"]
        for r in self.last_stats:
            rows.append(f"{r.lanes:>12,}  {r.kind:<10} {r.function:<20} {r.path}:{r.line}")
        return "\n".join(rows)


def compile_numpy(
    shader,
    tab: str | None = None,
    undefined: str = "zero",
    undefined_sites: tuple[int, ...] | None = None,
) -> NumpyProgram:
    """Parse, check and transpile a shader's Image tab (or plain GLSL file, or Buffer `tab`);
    `undefined="vary"` draws a new value at each undefined read (of the origins
    `undefined_sites` only, when given: transpile.Transpiler)."""
    t = transpile_shader(shader, tab, undefined=undefined, undefined_sites=undefined_sites)
    prog = NumpyProgram(t.source, t.meta, t.filename, _code=t.code)
    prog.module("float32")  # a broken module fails here, not in the middle of a render
    return prog


def program_from_source(source: str, filename: str = "<glslcheck-numpy module>") -> NumpyProgram:
    """A NumpyProgram from the text of a generated module (reads its SHADER_META)."""
    import ast as pyast

    tree = pyast.parse(source)
    meta = None
    for node in tree.body:
        if isinstance(node, pyast.Assign) and any(
            getattr(t, "id", None) == "SHADER_META" for t in node.targets
        ):
            meta = pyast.literal_eval(node.value)
    if meta is None:
        raise ValueError(
            f"{filename}: not a module generated by glslcheck transpile (no SHADER_META)"
        )
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
    return {"rt": rt, "X": LaneHelpers(meta, rt)}


def run_standalone(ns: dict) -> None:
    """`python shader.py [-o out.png|out.npy] [--size WxH] [--time T] [--frame N] [--precision
    P]`."""
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
    from ...base.images import save_image

    save_image(img, args.output)
