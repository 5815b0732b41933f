"""Compiled kernels for the llvmpipe math emulation, used when they pay.

llvmpipe_reference.LlvmpipeMath's sin, cos, tan, exp2, log2 and pow are 30-70 NumPy operations a
call. A raymarcher makes tens of thousands of such calls a frame on the few hundred lanes a march
loop keeps after compaction, and there the calls are all overhead; on a whole tile each operation
is a pass over memory. backends/numpy_engine/jit_kernels.py makes the same float32 steps in one
compiled loop (numba), which LLVM vectorises: 10-40x less CPU a call at 143 lanes, 7-18x at
3,600, 6-9x on a 48,000-lane tile (pow the least; docs/performance.md, "The llvmpipe
math emulation"). The frames are the same bits with and without them (tests/numpy/test_jit_*.py).

numba is an optional extra (``pip install 'glslcheck[jit]'``); without it nothing changes. It is
not free: ``import numba`` and loading the kernels' machine code from numba's cache take
0.7-2 s of wall time; compiling them the first time, before there is a cache, 6-10 s. So the
kernels are loaded the way a tiered JIT promotes a function:

- ``--jit auto`` (the default; ``$GLSLCHECK_JIT``): the process counts the time its calls of
  the emulation take on the NumPy path, and loads the kernels once that time exceeds what
  loading them costs: the wall time the last load took in this cache (recorded beside it), or
  :data:`COLD_SECONDS` before there was one. From then on those calls go to the kernels. A
  render that would gain less than the load costs never pays it (a lab scene spends well under
  a second there); one that spends much more gains nearly all of the difference, and never
  loses more than the load (the rule of renting skis until their price is spent). The count is
  per process, over every render it makes (a `verify` of many shaders, the frames of a
  `bench`). A render worker process (--parallel processes) counts its own calls too and
  loads on its own rule within a frame; it reports what it counted with each frame, the parent
  adds the workers' counts up, and once they exceed the threshold times the number of workers
  (each worker pays its own load, in parallel), or once the parent has loaded the kernels
  itself, every worker loads them before its next frame's first tile (:func:`decided`,
  :func:`add_counted`) instead of counting to its own threshold again.
- A first load compiles the kernels (6-10 s) and records that it did: the next process's
  threshold is then the time importing numba took plus :data:`WARM_KERNELS_SECONDS` (what a
  load from the cache costs), not the compile; its load records the real figure.
- ``--jit on``: load them when the first render makes its math functions (an error if numba
  is missing); ``--jit off``: never, numba is not imported.

numba's cache goes to ``$NUMBA_CACHE_DIR`` when the user set it, else to
``$XDG_CACHE_HOME/glslcheck/numba`` (``~/.cache/glslcheck/numba``): set before numba is
imported, so nothing is written into site-packages or the source tree.

The hook: llvmpipe_reference.LlvmpipeMath._kernel passes each NumPy function it makes through
:func:`dispatch`, which returns it unchanged (off, numba missing, a function without kernel) or
wrapped; LlvmpipeMath.builtin does the same for the Runtime's own float32 lowerings of atan,
atan(y, x), asin and acos (Mesa's: 12-40 NumPy operations a call; the kernels take 8-30x less
CPU a call, docs/performance.md), whose NumPy time counts towards auto's threshold too. A call the
kernel declines (edge arguments that give NaN, see jit_kernels) goes to the NumPy function: the same
bits either way.
"""

from __future__ import annotations

import json
import math
import os
import sys
import threading
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from ...base import config
from ...base.diagnostics import InputError
from ..cpu_core import numba_cache
from ..cpu_core.numba_cache import cache_dir, use_cache_dir  # noqa: F401  (jit.cache_dir, jit.use_cache_dir)

COLD_SECONDS = (
    10.0  # the load cost assumed before one was measured in this cache (a first compile: 6-10 s)
)
WARM_KERNELS_SECONDS = (
    1.0  # loading the kernels' machine code from the cache, numba imported (0.5-0.9 s measured)
)
_RECORD = "glslcheck-jit.json"  # in the cache directory: the last load's wall time

_F32 = np.dtype(np.float32)
_ONE_LANE = np.zeros(1, np.float32)  # explog's y where it reads none
# LlvmpipeMath's algorithm name -> (jit_kernels function, its `which`)
_KERNELS = {
    "_sin": ("trig", 0),
    "_cos": ("trig", 1),
    "_tan": ("trig", 2),
    "_exp2": ("explog", 0),
    "_log2": ("explog", 1),
    "_pow": ("explog", 2),
    # Runtime's own lowerings (LlvmpipeMath.builtin): atan(y, x) is "_atan2"
    "_atan": ("arc", 0),
    "_asin": ("arc", 1),
    "_acos": ("arc", 2),
    "_atan2": ("arc", 3),
    "_mix": ("mix", 0),
}
_KINDS = sorted({kind for kind, _ in _KERNELS.values()})  # jit_kernels' compiled functions


def mode() -> str:
    """``$GLSLCHECK_JIT`` (set by --jit), else ``"auto"``."""
    return config.jit()


def available() -> bool:
    """Whether numba is installed (without importing it)."""
    if _STATE.available is None:
        _STATE.available = numba_cache.installed()
    return _STATE.available


class _State:
    """The process's view of the kernels: loaded or not, and the time counted towards loading."""

    def __init__(self) -> None:
        self.lock = threading.Lock()
        self.available: bool | None = None
        self.kernels: Any = None  # the jit_kernels module once loaded
        self.failed: str | None = None  # why loading failed (then never tried again)
        self.spent = (
            0.0  # seconds of the emulation's NumPy calls (auto); `+=` from tile threads may
        )
        # lose an update now and then, which only delays the switch by a call
        self.threshold: float | None = None
        self.load_seconds: float | None = None
        self.pays = False  # the render workers' counts (add_counted) passed their threshold
        self.reported = 0.0  # in a worker: the part of `spent` already reported (counted())
        self.workers_spent = 0.0  # in the parent: what the workers reported


_STATE = _State()


def _stamp() -> list:
    """What the recorded load time depends on: numba's version and the kernels' source."""
    from importlib.metadata import version

    st = os.stat(os.path.join(os.path.dirname(__file__), "jit_kernels.py"))
    return [version("numba"), st.st_mtime_ns, st.st_size]


def threshold() -> float:
    """Seconds of the emulation's calls on NumPy after which auto loads the kernels: the last
    load's wall time in this cache, else :data:`COLD_SECONDS`."""
    if _STATE.threshold is None:
        seconds = COLD_SECONDS
        try:
            with open(os.path.join(cache_dir(), _RECORD)) as f:
                record = json.load(f)
            if record.get("stamp") == _stamp():
                seconds = float(record["seconds"])
                if record.get("compiled"):  # that load compiled them; this one reads the cache
                    seconds = min(seconds, float(record["numba"]) + WARM_KERNELS_SECONDS)
        except (OSError, ValueError, KeyError, TypeError):
            pass
        _STATE.threshold = seconds
    return _STATE.threshold


def load(required: bool = False) -> Any:
    """The jit_kernels module, imported (numba's cache directory set first) on the first call;
    None when numba is missing or fails (a warning, once), an InputError then if ``required``."""
    with _STATE.lock:
        if _STATE.kernels is None and _STATE.failed is None:
            if not available():
                _STATE.failed = "numba is not installed (pip install 'glslcheck[jit]')"
            else:
                _import()
        if _STATE.kernels is None and required:
            raise InputError(f"error: --jit on: {_STATE.failed}")
        return _STATE.kernels


def _import() -> None:
    t0 = time.perf_counter()
    try:
        path = use_cache_dir()
        from numba.core import config  # noqa: F401  (imports numba: its time is t_numba)

        t_numba = time.perf_counter() - t0
        from . import jit_kernels

        compiled_now = any(
            getattr(jit_kernels, k).stats.cache_misses for k in _KINDS
        )  # not from the cache
    except Exception as e:  # an incompatible numba, a compile error: the NumPy path stays
        _STATE.failed = f"numba's kernels failed to load ({type(e).__name__}: {e})"
        print(f"glslcheck: warning: {_STATE.failed}; using NumPy", file=sys.stderr)
        return
    _STATE.load_seconds = time.perf_counter() - t0
    _STATE.kernels = jit_kernels
    try:  # the next process's threshold
        os.makedirs(path, exist_ok=True)
        tmp = os.path.join(path, f"{_RECORD}.{os.getpid()}")
        with open(tmp, "w") as f:
            json.dump(
                {
                    "seconds": round(_STATE.load_seconds, 3),
                    "stamp": _stamp(),
                    "compiled": compiled_now,
                    "numba": round(t_numba, 3),
                },
                f,
            )
        os.replace(tmp, os.path.join(path, _RECORD))
    except OSError:
        pass


def dispatch(name: str, run: Callable[..., np.ndarray], fma: bool) -> Callable[..., np.ndarray]:
    """LlvmpipeMath's NumPy function ``run`` of the algorithm ``name`` (``"_sin"``, ...), or a
    function that takes the compiled kernel instead where :func:`mode` and the rule above say so
    (same arguments, same bits)."""
    m = mode()
    if m == "off" or name not in _KERNELS:
        return run
    if m == "on":
        return compiled(name, run, fma, load(required=True))
    if not available():
        return run
    fast = None
    state = _STATE
    clock = time.perf_counter

    def auto(*args: np.ndarray) -> np.ndarray:
        nonlocal fast
        if fast is not None:
            return fast(*args)
        if state.kernels is not None:
            fast = compiled(name, run, fma, state.kernels)
            return fast(*args)
        if state.failed is not None:
            return run(*args)
        if state.pays:  # the render workers' counts say so (in the parent, rendering itself now)
            load()
            return auto(*args)
        t0 = clock()
        r = run(*args)
        state.spent += clock() - t0
        if state.spent > (state.threshold or threshold()):
            load()
        return r

    return auto


def decided() -> bool:
    """Whether this process's rule has chosen the kernels (loaded, or the workers' counts pay
    for them): a render worker told so loads them before its frame (workers.py)."""
    return _STATE.kernels is not None or _STATE.pays


def counted() -> float:
    """In a render worker: the seconds of NumPy math counted since the last call (reported to
    the parent with each frame)."""
    spent = _STATE.spent
    new, _STATE.reported = spent - _STATE.reported, spent
    return new


def add_counted(seconds: float, workers: int) -> None:
    """In the parent: ``seconds`` counted by its ``workers`` render workers during a frame.
    Once their sum exceeds the threshold times the number of workers (the load each of them
    pays, in parallel), the kernels pay for all of them (:func:`decided`)."""
    state = _STATE
    state.workers_spent += seconds
    if (
        not state.pays
        and state.workers_spent > threshold() * max(workers, 1)
        and mode() == "auto"
        and available()
    ):
        state.pays = True


def compiled(
    name: str, run: Callable[..., np.ndarray], fma: bool, kernels: Any
) -> Callable[..., np.ndarray]:
    """``run`` with its calls on float32 arrays made by the kernel (``run`` where it declines)."""
    kind, which = _KERNELS[name]
    kernel = getattr(kernels, kind)

    take: Callable[..., bool]  # (out, the arguments) -> whether the kernel computed them
    if kind == "trig":

        def take_trig(out: np.ndarray, a: np.ndarray) -> bool:
            return kernel(a, out, fma, which)

        take = take_trig
    elif kind == "mix":

        def take_mix(out: np.ndarray, x: np.ndarray, y: np.ndarray, a: np.ndarray) -> bool:
            return kernel(x, y, a, out)

        return _rows_call(run, take_mix)
    else:  # explog, arc: exp2, log2, atan, asin and acos read no y

        def take_xy(out: np.ndarray, x: np.ndarray, y: np.ndarray = _ONE_LANE) -> bool:
            return kernel(x, y, out, fma, which)

        take = take_xy

    def call(x: np.ndarray, *rest: np.ndarray) -> np.ndarray:
        if not rest:
            if x.dtype is not _F32:
                return run(x)
            out = np.empty(x.size, _F32)
            if take(out, _flat(x)):
                return out if x.ndim == 1 else out.reshape(x.shape)
            return run(x)
        args = (x, *rest)  # pow, atan2, mix: broadcast
        for v in args:
            if v.dtype is not _F32:
                return run(*args)
        shape, n = _shape(args)
        out = np.empty(n, _F32)
        if take(out, *(_flat(v if v.size in (1, n) else np.broadcast_to(v, shape)) for v in args)):
            return out if len(shape) == 1 else out.reshape(shape)
        return run(*args)

    return call


def _rows_call(
    run: Callable[..., np.ndarray], take: Callable[..., bool]
) -> Callable[..., np.ndarray]:
    """``run`` made by ``take`` (mix's kernel) on (rows, lanes) matrices: each argument's rows
    (its components) and lanes are the result's or one, so that a vec3 constant of shape
    (3, 1) or a float against vec3 lanes is read in place, not copied to the broadcast shape
    (which cost 10x the kernel)."""

    def call(*args: np.ndarray) -> np.ndarray:
        for v in args:
            if v.dtype is not _F32:
                return run(*args)
        shape, n = _shape(args)
        if n == 0:
            return run(*args)
        cols = shape[-1] if shape else 1
        rows = n // cols
        out = np.empty((rows, cols), _F32)
        if take(out, *(_rows(v, shape, rows, cols) for v in args)):
            return out.reshape(shape)
        return run(*args)

    return call


def _rows(v: np.ndarray, shape: tuple[int, ...], rows: int, cols: int) -> np.ndarray:
    """``v`` as a contiguous, writable (rows or 1, cols or 1) matrix reading as ``v`` broadcast
    to ``shape`` read as (rows, cols); a copy at the broadcast shape where its leading axes
    broadcast otherwise."""
    vs = v.shape
    c = vs[-1] if vs else 1
    lead = v.size // c if c else 0
    if not (c in (cols, 1) and (lead == 1 or (lead == rows and vs[:-1] == shape[:-1]))):
        v, lead, c = np.broadcast_to(v, shape), rows, cols
    flags = v.flags
    if not (flags.c_contiguous and flags.writeable):
        v = np.array(v, _F32, order="C")
    return v.reshape(lead, c)


def _flat(v: np.ndarray) -> np.ndarray:
    """``v``'s lanes as the kernels take them: one contiguous row (a copy of a strided view or
    of a read-only array, a uniform input: the kernels are compiled for writable arrays only)."""
    flags = v.flags
    if flags.c_contiguous and flags.writeable:
        return v if v.ndim == 1 else v.reshape(-1)
    return np.array(v, _F32, order="C").reshape(-1)


def _shape(args: tuple[np.ndarray, ...]) -> tuple[tuple[int, ...], int]:
    """The broadcast shape of ``args`` and its size (the usual cases, equal shapes and one-element
    operands, without np.broadcast_shapes)."""
    shape = args[0].shape
    for v in args[1:]:
        vs = v.shape
        if vs == shape or (v.size == 1 and v.ndim <= len(shape)):
            continue
        if math.prod(shape) == 1 and len(shape) <= v.ndim:
            shape = vs
            continue
        shape = np.broadcast_shapes(*(a.shape for a in args))
        break
    return shape, math.prod(shape)
