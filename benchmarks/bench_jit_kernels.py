"""numba's compiled kernels of the llvmpipe math (backends/numpy_engine/jit_kernels.py) against the
NumPy emulation they replace: their cost, their bits, their speed per call.

    python benchmarks/bench_jit_kernels.py [--lanes 143,3600,16000,48000] [--check N] [--repeat N]

Needs the optional extra (`pip install -e '.[jit]'`; `make setup` installs it). It prints

1. the cost of the kernels, wall time of fresh processes: ``import numba`` (against a bare
   ``import numpy``), and ``jit.load()`` (numba imported, the kernels compiled or read from
   numba's cache) with an empty cache directory (the first use on a machine) and again with
   that directory filled (every later process);
2. bit for bit: ``jit.compiled`` of each function against LlvmpipeMath's reference on
   ``--check`` arguments (every scale, multiples of 1/8, zeros), with and without FMA; the count
   of lanes that differ must be 0 (tests/numpy/test_jit_kernels.py checks specials too);
3. CPU time per call, best of ``--repeat`` in turns: the LlvmpipeMath public method as a render
   calls it, with ``--jit off`` (NumPy: llvmpipe_fast's kernels up to 4096 lanes, the reference
   above) and ``--jit on`` (the compiled kernel); ratio = off / on. The lane counts: a
   compacted march loop (143), a small tile or loop (3600), a larger one (16000), a whole
   48,000-lane tile.

Parts 2 and 3 also take the Runtime's own lowerings with kernels (``RUNTIME``: atan, atan(y, x),
asin, acos, mix's fast form), through the Runtime method a render calls, against the Runtime's
NumPy lowering.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)
sys.path.insert(0, HERE)

from bench_render import _best  # noqa: E402

from glslcheck.backends.numpy_engine import jit  # noqa: E402
from glslcheck.backends.numpy_engine.llvmpipe_reference import HOST_FMA, LlvmpipeMath, blocked  # noqa: E402
from glslcheck.backends.numpy_engine.runtime import Runtime  # noqa: E402

F32 = np.float32
FUNCTIONS = ("_sin", "_cos", "_tan", "_exp2", "_log2", "_pow")
# the Runtime's own lowerings: kernel name -> (the Runtime method as a render calls it, its NumPy
# lowering, the number of arguments)
RUNTIME = {
    "_atan": (lambda rt: rt.atan, lambda rt: rt._atan, 1),
    "_atan2": (lambda rt: rt.atan, lambda rt: rt._atan, 2),
    "_asin": (lambda rt: rt.asin, lambda rt: rt._asin, 1),
    "_acos": (lambda rt: rt.acos, lambda rt: rt._acos, 1),
    "_mix": (lambda rt: lambda x, y, a: rt.mix(x, y, a, "fast"), lambda rt: rt._mix_fast, 3),
}


def _runtime_arguments(n: int, rng: np.random.Generator, name: str) -> tuple[np.ndarray, ...]:
    """atan: every scale; asin, acos: [-1, 1]; mix: values and weights in [-0.5, 1.5], a fifth
    of them exactly 0 or 1."""
    if name in ("_asin", "_acos"):
        return (rng.uniform(-1, 1, n).astype(F32),)
    if name == "_mix":
        a = rng.uniform(-0.5, 1.5, n).astype(F32)
        a[rng.random(n) < 0.2] = rng.choice(np.array([0, 1], F32))
        return rng.uniform(-50, 50, n).astype(F32), rng.uniform(-50, 50, n).astype(F32), a
    return tuple(
        (rng.uniform(-1, 1, n) * 10.0 ** rng.uniform(-6, 6, n)).astype(F32)
        for _ in range(RUNTIME[name][2])
    )


def _public(lp: LlvmpipeMath, name: str):
    """The method a render calls (through the runtime's dispatch to the kernels or NumPy)."""
    return {
        "_sin": lambda a: lp.sin_or_cos(a, cos=False),
        "_cos": lambda a: lp.sin_or_cos(a, cos=True),
        "_tan": lp.tan,
        "_exp2": lp.exp2,
        "_log2": lp.log2,
        "_pow": lp.pow,
    }[name]


def _arguments(n: int, rng: np.random.Generator, name: str) -> tuple[np.ndarray, ...]:
    """Every scale: uniform magnitudes over decades, multiples of 1/8, zeros."""
    hi = {"_exp2": 2, "_pow": 3, "_log2": 30}.get(name, 5)
    v = (rng.uniform(-1, 1, n) * 10.0 ** rng.uniform(-6, hi, n)).astype(F32)
    eighths = rng.random(n) < 0.2
    v[eighths] = (np.round(v[eighths] * 8) / 8).astype(F32)
    v[rng.random(n) < 0.01] = 0.0
    if name in ("_log2", "_pow"):
        v = np.abs(v)
    return (v, rng.uniform(-4, 40, n).astype(F32)) if name == "_pow" else (v,)


def _compare(name: str, ref, args: tuple[np.ndarray, ...], fma: bool, kernels) -> str:
    """``jit.compiled`` of ``name`` against ``ref`` on ``args`` in calls of 4096 lanes: the
    lanes, those the kernel took, and those whose bits differ."""
    declined = []
    fn = jit.compiled(name, lambda *a: declined.append(1) or ref(*a), fma, kernels)
    n = args[0].size
    differ = taken = 0
    with np.errstate(all="ignore"):
        for i in range(0, n, 4096):
            part = tuple(a[i : i + 4096] for a in args)
            before = len(declined)
            got, want = fn(*part), ref(*part)
            taken += part[0].size if len(declined) == before else 0
            differ += int((got.view(np.int32) != want.view(np.int32)).sum())
    return f"{name[1:]:5s} FMA {fma!s:5s}: {n:,} lanes, {taken:,} by the kernel, {differ} differ"


def check(n: int) -> None:
    rng = np.random.default_rng(18)
    kernels = jit.load(required=True)
    for fma in (True, False):
        lp = LlvmpipeMath(fma)
        for name in FUNCTIONS:

            def ref(*a, _f=getattr(lp, name)):
                return blocked(_f, *a)

            print("   " + _compare(name, ref, _arguments(n, rng, name), fma, kernels))
        rt = Runtime("float32", fma=fma)
        for name, (_, ref, _) in RUNTIME.items():
            print("   " + _compare(name, ref(rt), _runtime_arguments(n, rng, name), fma, kernels))


def _per_call(name: str, n: int, fns: dict, call: tuple[np.ndarray, ...], repeat: int) -> str:
    """CPU time per call of ``fns["off"]`` and ``fns["on"]``, best of ``repeat`` three times in
    turns."""
    t = {m: float("inf") for m in fns}
    for _ in range(3):
        for m, fn in fns.items():
            t[m] = min(t[m], _best(lambda: fn(*call), repeat, time.process_time))
    return (
        f"{name[1:]:5s} {n:6d} lanes: off {t['off'] * 1e6:8.1f} us   on {t['on'] * 1e6:8.1f} us"
        f"   {t['off'] / t['on']:6.1f}x"
    )


def _seconds(code: str, env: dict) -> float:
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-c", code], check=True, cwd=ROOT, env=env)
    return time.perf_counter() - t0


def costs() -> None:
    env = dict(os.environ, PYTHONPATH=ROOT)
    base = min(_seconds("import numpy", env) for _ in range(3))
    imp = min(_seconds("import numpy, numba", env) for _ in range(3))
    print(
        f"   import numpy {base * 1000:.0f} ms; import numpy, numba {imp * 1000:.0f} ms "
        f"(+{(imp - base) * 1000:.0f} ms)"
    )
    load = (
        "import time; t = time.perf_counter(); from glslcheck.backends.numpy_engine import jit; "
        "jit.load(True); "
        "print(f'{(time.perf_counter() - t) * 1000:.0f} ms', end='')"
    )
    with tempfile.TemporaryDirectory() as cache:
        env["NUMBA_CACHE_DIR"] = cache
        for what in ("empty cache (compiles)", "from numba's cache"):
            print(f"   jit.load(), {what}: ", end="", flush=True)
            _seconds(load, env)
            print()


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--lanes", default="143,3600,16000,48000")
    ap.add_argument("--check", type=int, default=1_000_000)
    ap.add_argument("--repeat", type=int, default=15)
    args = ap.parse_args()
    import numba

    print(
        f"numba {numba.__version__}, NumPy {np.__version__}, FMA {HOST_FMA}; load "
        f"{' '.join(f'{v:.1f}' for v in os.getloadavg())}"
    )
    print("1. cost of the kernels (fresh processes, wall time)")
    costs()
    print("2. bit for bit against LlvmpipeMath's reference")
    check(args.check)
    print(
        f"3. CPU time per call, best of {args.repeat} in turns (the public method; "
        "ratio = off / on)"
    )
    rng = np.random.default_rng(7)
    math, runtimes = {}, {}
    for mode in ("off", "on"):
        os.environ["GLSLCHECK_JIT"] = mode
        math[mode] = lp = LlvmpipeMath(HOST_FMA)
        for name in FUNCTIONS:  # the mode is read when the runtime makes each function
            lp._kernel(name)
        runtimes[mode] = rt = Runtime("float32")
        for name, (public, _, _) in RUNTIME.items():
            public(rt)(*_runtime_arguments(4, rng, name))
    del os.environ["GLSLCHECK_JIT"]
    for n in (int(v) for v in args.lanes.split(",")):
        for name in FUNCTIONS:
            a = rng.uniform(-50, 50, n).astype(F32)
            call = (
                (a,)
                if name in ("_sin", "_cos", "_tan")
                else (np.abs(a) * F32(0.02),)
                if name != "_pow"
                else (rng.uniform(0, 1, n).astype(F32), np.array([F32(32.0)]))
            )
            print(
                "   "
                + _per_call(
                    name, n, {m: _public(lp, name) for m, lp in math.items()}, call, args.repeat
                )
            )
        for name, (public, _, _) in RUNTIME.items():
            call = _runtime_arguments(n, rng, name)
            print(
                "   "
                + _per_call(
                    name, n, {m: public(rt) for m, rt in runtimes.items()}, call, args.repeat
                )
            )
    print(f"load at the end {' '.join(f'{v:.1f}' for v in os.getloadavg())}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
