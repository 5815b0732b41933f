"""Branch-free lane math (backends/compiled_engine/lanes_math.py) in W-lane tuples against
scalar.py's functions one lane at a time: CPU nanoseconds per lane, in one process, the same
arguments.

    python benchmarks/bench_lanes_math.py [--only sin,cos] [--lanes 65536] [--repeat 7]

For each function and two kinds of arguments, it times four numba loops over the same array:

- ``scalar``: scalar.py's function, one lane an iteration (each pixel of today's per-pixel
  engine runs its functions one at a time);
- ``one``: lanes_math's function the same way (the branch-free code without SIMD: what the
  branches cost or save alone);
- ``W8``/``W16``: lanes_math's function in the lockstep engine's form, a tuple of W calls a
  block, numba's SLP vectoriser on (``config.SLP_VECTORIZE``), FMA a compile-time constant.

LLVM's loop vectoriser is off in all four (in a shader, a block's W lanes are what is packed;
there is no loop over an array of arguments to vectorise across iterations).

Arguments: ``coherent`` (sorted, as neighbouring pixels: a branch on a quadrant or a sign is
predicted) and ``random`` (the same range shuffled: hashes, random ray directions). Figures are
the best of ``--repeat`` runs, the thread's CPU time, with the load average printed before and
after (the machine is shared); the ratios compare columns of one run. The compile time of each
W8 loop (seconds; scalar.py's function and lanes_math's in the same W8 tuple) is printed too:
what a lockstep module pays per call site (lanes_math's functions themselves are compiled, or
loaded from numba's cache, when it is imported). For scalar.py's functions that lanes_math keeps
(lanes_math.AS_IS) the ``one``/``W`` columns run scalar.py's function.
"""

from __future__ import annotations

import argparse
import os
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "tests", "compiled"))

from test_lanes_math import DTYPES, SPECS  # noqa: E402 (the functions' argument kinds)

# the range of each function's arguments (as shaders pass them), by name; floats not listed: +-100
RANGES = {
    "exp2": (-20, 20),
    "exp": (-15, 15),
    "log2": (1e-3, 1e3),
    "log": (1e-3, 1e3),
    "pow": (1e-3, 100),
    "asin": (-1, 1),
    "acos": (-1, 1),
    "atanh": (-0.99, 0.99),
    "acosh": (1, 100),
    "sinh": (-10, 10),
    "cosh": (-10, 10),
    "tanh": (-10, 10),
    "smoothstep": (-1, 2),
    "mix_fast": (-1, 2),
    "inversesqrt": (1e-3, 100),
    "to_uint_sse": (0, 4e9),
    "to_uint_avx512": (0, 4e9),
    "to_uint_arm64": (-10, 4e9),
    "to_int": (-3e9, 3e9),
}


def _load() -> str:
    return " ".join(f"{v:.2f}" for v in os.getloadavg())


def arguments(name: str, n: int, coherent: bool, rng) -> list[np.ndarray]:
    kinds = SPECS[name][0]
    cols = []
    for k, kind in enumerate(kinds):
        if kind == "f":
            lo, hi = RANGES.get(name, (-100, 100))
            if name == "pow" and k == 1:
                lo, hi = -4, 4
            v = np.linspace(lo, hi, n) if coherent else rng.uniform(lo, hi, n)
        elif name.endswith(("shl", "shr")) and k == 1:
            v = np.arange(n) % 32 if coherent else rng.integers(0, 32, n)
        else:
            v = np.arange(n) - n // 2 if coherent else rng.integers(-(2**31), 2**31, n)
            if k == 1:
                v = np.where(v == 0, 7, v if coherent else v % 1000 + 1)
        cols.append(
            np.asarray(v).astype(np.int64 if kind != "f" else np.float64).astype(DTYPES[kind])
        )
    return cols


def _lanes_loop(f, nargs: int, width: int, fma: bool | None):
    """A numba loop: W-tuples of ``f`` a block (width > 1), or one lane an iteration."""
    import numba

    xs = [f"x{k}" for k in range(nargs)]
    tail = ", FMA" if fma is not None else ""
    if width == 1:
        body = (
            "    for k in range(out.size):\n        out[k] = "
            f"f({', '.join(x + '[k]' for x in xs)}{tail})\n"
        )
    else:
        body = f"    for b in range(out.size // {width}):\n        i = np.uint64(b * {width})\n"
        for x in xs:
            body += (
                f"        {x}_ = ("
                + ", ".join(f"{x}[i + np.uint64({j})]" for j in range(width))
                + ",)\n"
            )
        body += (
            "        r = ("
            + ", ".join(f"f({', '.join(f'{x}_[{j}]' for x in xs)}{tail})" for j in range(width))
            + ",)\n"
        )
        body += "".join(f"        out[i + np.uint64({j})] = r[{j}]\n" for j in range(width))
    g = {"f": f, "np": np, "FMA": fma}
    exec(f"def k({', '.join(xs)}, out):\n{body}", g)
    return numba.njit(error_model="numpy")(g["k"])


def _compiled(f, args, out, width, fma, slp):
    """The loop compiled (timed, cold: numba compiles at the first call) and run once; the
    vectorisers as given while it compiles."""
    from numba.core import config

    kernel = _lanes_loop(f, len(args), width, fma)
    old = config.SLP_VECTORIZE, config.LOOP_VECTORIZE
    config.SLP_VECTORIZE, config.LOOP_VECTORIZE = int(slp), 0
    try:
        started = time.perf_counter()
        kernel(*args, out)
        return kernel, time.perf_counter() - started
    finally:
        config.SLP_VECTORIZE, config.LOOP_VECTORIZE = old


def _best(kernel, args, out, repeat: int) -> float:
    best = float("inf")
    for _ in range(repeat):
        started = time.thread_time()
        kernel(*args, out)
        best = min(best, time.thread_time() - started)
    return best * 1e9 / out.size


def main() -> None:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--only", default="", help="comma-separated function names (default: all)")
    ap.add_argument("--lanes", type=int, default=1 << 16)
    ap.add_argument("--repeat", type=int, default=7)
    opts = ap.parse_args()

    from glslcheck.backends.compiled_engine import lanes_math, scalar
    from glslcheck.backends.numpy_engine.llvmpipe_reference import HOST_FMA

    names = [n for n in opts.only.split(",") if n] or list(lanes_math.REWRITTEN + lanes_math.AS_IS)
    names = [n for n in names if n in SPECS]
    print(
        f"load average at the start: {_load()}; {opts.lanes} lanes, best of {opts.repeat}, "
        f"FMA {HOST_FMA}"
    )
    print(
        f"{'function':18s} {'args':8s} {'scalar':>8s} {'one':>8s} {'W8':>8s} {'W16':>8s}   "
        f"{'scalar/W8':>9s} {'scalar/W16':>10s} {'scalar/one':>10s}   compile W8 s (scalar, lanes)"
    )
    rng = np.random.default_rng(18)
    ratios = []
    for name in names:
        kinds, out_kind, takes_fma = SPECS[name]
        fma = bool(HOST_FMA) if takes_fma else None
        mine = getattr(lanes_math, name) if name in lanes_math.REWRITTEN else getattr(scalar, name)
        for coherent in (True, False):
            args = arguments(name, opts.lanes, coherent, rng)
            out = np.empty(opts.lanes, DTYPES[out_kind])
            ks, ts8 = _compiled(getattr(scalar, name), args, out, 1, fma, False)
            k1, _ = _compiled(mine, args, out, 1, fma, False)
            k8, tl8 = _compiled(mine, args, out, 8, fma, True)
            k16, _ = _compiled(mine, args, out, 16, fma, True)
            if coherent:  # the compile figure: scalar's W8 tuple, lanes_math's W8 tuple
                _, ts8 = _compiled(getattr(scalar, name), args, out, 8, fma, True)
            t = [_best(k, args, out, opts.repeat) for k in (ks, k1, k8, k16)]
            ratios.append((name, coherent, t[0] / t[2], t[0] / t[3]))
            label = "coherent" if coherent else "random"
            comp = f"{ts8:5.1f} {tl8:5.1f}" if coherent else ""
            print(
                f"{name:18s} {label:8s} {t[0]:8.2f} {t[1]:8.2f} {t[2]:8.2f} {t[3]:8.2f}   "
                f"{t[0] / t[2]:9.2f} {t[0] / t[3]:10.2f} {t[0] / t[1]:10.2f}   {comp}",
                flush=True,
            )
    for coherent in (True, False):
        r8 = [r[2] for r in ratios if r[1] == coherent]
        r16 = [r[3] for r in ratios if r[1] == coherent]
        if r8:
            print(
                f"geometric mean scalar/W8 {np.exp(np.mean(np.log(r8))):.2f}, scalar/W16 "
                f"{np.exp(np.mean(np.log(r16))):.2f} ({'coherent' if coherent else 'random'} "
                "arguments)"
            )
    print(f"load average at the end: {_load()}")


if __name__ == "__main__":
    main()
