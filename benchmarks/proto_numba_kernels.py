"""Prototype, not used by glslcheck: llvmpipe's sin and pow compiled into one numba kernel each,
measured against the NumPy emulation (runtime.LlvmpipeMath) it would replace.

    python -m venv --system-site-packages /tmp/nb && /tmp/nb/bin/pip install numba
    PYTHONPATH=. /tmp/nb/bin/python benchmarks/proto_numba_kernels.py [--lanes 143,3600,48000] [--check N]

numba is NOT a dependency of glslcheck (issue 18 asks for the figures first): run this with an
interpreter that has it. It prints

1. the cost of having numba at all: ``import numba`` (a fresh subprocess, against a bare
   ``import numpy``), and the first call of each kernel (LLVM compiles it then; ``cache=True``
   keeps the machine code in __pycache__ for the next process, timed in a second subprocess);
2. bit for bit: each kernel against LlvmpipeMath's reference (``_sin``, ``_pow``; FMA as this
   CPU has it) on ``--check`` random arguments over every scale the kernels take, exact
   multiples of 1/8 (where fused multiply-add midpoints are common) and zeros; the count of
   lanes that differ must be 0;
3. time per call, numba against the NumPy kernels (``LlvmpipeMath.sin_or_cos`` / ``pow``, the
   fast path up to 4096 lanes and the reference above), on the lane counts a call has after
   compaction and on one render tile; CPU time, best of N, in turns. Ratio = NumPy / numba.

The kernels take the common range only (|x| < 2**29 and finite for sin; pow: x normal or zero,
positive, finite, and an exponent that keeps log2(x) * y finite) and say so by returning False,
as llvmpipe_fast's kernels do: the caller then takes the NumPy reference. A fused
multiply-add is computed as runtime._fma32 does: the float64 product is exact, the sum rounds
once, and a sum that is exactly a float32 midpoint is corrected by TwoSum (here per lane, in
the loop).
"""

from __future__ import annotations

import argparse
import math
import os
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)
sys.path.insert(0, HERE)

import numba  # noqa: E402
from bench_render import _best  # noqa: E402

from glslcheck.numpy_backend import llvmpipe_fast as lf  # noqa: E402
from glslcheck.numpy_backend.runtime import HOST_FMA, LlvmpipeMath  # noqa: E402

F32 = np.float32
_FOPI = F32(lf.FOUR_OVER_PI)
_DP0, _DP1, _DP2 = (F32(v) for v in lf.DP)
_SC = [[F32(lf.SIN_COS[r, c, 0]) for c in range(2)] for r in range(3)]
_C0, _S0, _C1, _S1, _C2, _S2 = _SC[0][0], _SC[0][1], _SC[1][0], _SC[1][1], _SC[2][0], _SC[2][1]
_HALF, _ONE, _MONE = F32(0.5), F32(1.0), F32(-1.0)
_E = tuple(F32(v) for v in lf.EXP2)
_L = tuple(F32(v) for v in lf.LOG2)
_TWO25 = 2.0 ** 25


@numba.njit(cache=True, inline="always")
def _mad(a, b, c, fma, buf):
    """``llvm.fmuladd`` of float32 scalars, as runtime._fma32 / LlvmpipeMath.mad. ``buf``: a
    float64 array of one element, the bits of the sum read through it (LLVM makes that a
    register move)."""
    if not fma:
        return F32(F32(a * b) + c)
    ps = np.float64(a) * np.float64(b)
    cs = np.float64(c)
    s = ps + cs
    buf[0] = s
    if (buf.view(np.int64)[0] & 0x1FFFFFFF) == 0x10000000:  # a float32 midpoint
        bb = s - ps
        err = (ps - (s - bb)) + (cs - bb)
        if err != 0.0:  # nextafter(s, towards err): s is no power of two here
            m, e = math.frexp(s)
            s = s + math.copysign(math.ldexp(1.0, e - 53), err)
    return F32(s)


@numba.njit(cache=True)
def sin_kernel(a, out, fma):
    """LlvmpipeMath._sin on float32 ``a`` (flat) into ``out``; False (out unset) outside
    |x| < 2**29, finite."""
    ai = a.view(np.int32)
    for k in range(a.size):
        if (ai[k] & 0x7FFFFFFF) >= 0x4E000000:
            return False
    oi = out.view(np.int32)
    buf = np.empty(1, np.float64)
    for k in range(a.size):
        bits = ai[k] & 0x7FFFFFFF
        x_abs = F32(0.0) if bits < 0x00800000 else abs(a[k])  # DAZ
        j_add = np.int32(x_abs * _FOPI) + np.int32(1)
        j = j_add & np.int32(-2)
        y_2 = F32(j)
        x_1 = _mad(y_2, _DP0, x_abs, fma, buf)
        x_2 = _mad(y_2, _DP1, x_1, fma, buf)
        x_3 = _mad(y_2, _DP2, x_2, fma, buf)
        z = F32(x_3 * x_3)
        c6 = F32(_mad(_mad(z, _C0, _C1, fma, buf), z, _C2, fma, buf) * z)
        s6 = F32(_mad(_mad(z, _S0, _S1, fma, buf), z, _S2, fma, buf) * z)
        y_10 = F32(F32(F32(c6 * z) - F32(z * _HALF)) + _ONE)
        y2_9 = _mad(s6, x_3, x_3, fma, buf)
        sign = (ai[k] ^ (j_add << 29)) & np.int32(-2147483648)
        y = y2_9 if (j & 2) == 0 else y_10
        out[k] = y
        oi[k] ^= sign
        v = out[k]
        if not v <= _ONE:  # fmin(y, 1) as minps: NaN -> 1
            v = _ONE
        if not v >= _MONE:
            v = _MONE
        out[k] = v
    return True


@numba.njit(cache=True, inline="always")
def _exp2_one(x, fma, buf):
    if abs(x) < F32(1.17549435e-38):  # DAZ: a subnormal is a zero of its sign
        x = F32(math.copysign(0.0, x))
    ipart = F32(math.floor(x))
    fpart = F32(x - ipart)
    e = np.int32(ipart) + np.int32(127)
    x2 = F32(fpart * fpart)
    odd = _mad(_mad(x2, _E[5], _E[3], fma, buf), x2, _E[1], fma, buf)
    even = _mad(_mad(x2, _E[4], _E[2], fma, buf), x2, _E[0], fma, buf)
    p = _mad(odd, fpart, even, fma, buf)
    bits = buf.view(np.int32)  # (buf's first four bytes: its float64 is not needed here)
    bits[0] = e << 23
    return F32(buf.view(np.float32)[0] * p)


@numba.njit(cache=True)
def pow_kernel(x, y, out, fma):
    """LlvmpipeMath._pow on float32 ``x`` and ``y`` (flat, same size, or y of size 1) into
    ``out``; False where some lane leaves the common range (see the module docstring)."""
    xi = x.view(np.int32)
    ny = y.size
    for k in range(x.size):
        b = xi[k]
        if b != 0 and (b < 0x00800000 or b >= 0x7F800000):
            return False  # negative, subnormal, Inf or NaN (-0.0 has b < 0 too)
    m1 = np.empty(1, np.float32)
    buf = np.empty(1, np.float64)
    for k in range(x.size):
        b = xi[k]
        if b == 0:
            out[k] = F32(0.0)
            continue
        logexp = F32((b >> 23) - 127)
        m1.view(np.int32)[0] = (b & 0x007FFFFF) | 0x3F800000
        mant = m1[0]
        yy = F32(F32(mant - _ONE) / F32(mant + _ONE))
        w = F32(yy * yy)
        x2 = F32(w * w)
        even = _mad(_mad(x2, _L[4], _L[2], fma, buf), x2, _L[0], fma, buf)
        odd = _mad(x2, _L[3], _L[1], fma, buf)
        p = _mad(odd, w, even, fma, buf)
        lg = _mad(yy, p, logexp, fma, buf)
        t = F32(lg * y[k if ny > 1 else 0])
        if not abs(t) <= F32(126.0):
            if t != t:
                return False
            t = min(max(t, F32(-126.99999)), F32(128.0))
        out[k] = _exp2_one(t, fma, buf)
    return True


def numba_sin(a: np.ndarray, ref: LlvmpipeMath) -> np.ndarray:
    flat = np.ascontiguousarray(a).reshape(-1)
    out = np.empty_like(flat)
    if not sin_kernel(flat, out, ref.fma):
        return ref.sin_or_cos(a, cos=False)
    return out.reshape(a.shape)


def numba_pow(x: np.ndarray, y: np.ndarray, ref: LlvmpipeMath) -> np.ndarray:
    xf, yf = np.ascontiguousarray(x).reshape(-1), np.ascontiguousarray(y).reshape(-1)
    out = np.empty_like(xf)
    if not pow_kernel(xf, yf, out, ref.fma):
        return ref.pow(x, y)
    return out.reshape(x.shape)


def _arguments(n: int, rng: np.random.Generator, kind: str) -> np.ndarray:
    """Every scale: uniform magnitudes over decades, multiples of 1/8, zeros."""
    scale = 10.0 ** rng.uniform(-6, 5 if kind == "sin" else 3, n)
    v = (rng.uniform(-1, 1, n) * scale).astype(F32)
    eighths = rng.random(n) < 0.2
    v[eighths] = (np.round(v[eighths] * 8) / 8).astype(F32)
    v[rng.random(n) < 0.01] = 0.0
    return v if kind == "sin" else np.abs(v)


def check(n: int, lm: LlvmpipeMath) -> None:
    rng = np.random.default_rng(18)
    a = _arguments(n, rng, "sin")
    got, want = numba_sin(a, lm), lm._sin(a)
    print(f"   sin: {n:,} lanes, {int((got.view(np.int32) != want.view(np.int32)).sum())} differ")
    x = _arguments(n, rng, "pow")
    for y in (np.array([F32(8.0)]), rng.uniform(-4, 40, n).astype(F32)):
        got = numba_pow(x, y, lm)
        want = lm._pow(x, y if y.size == n else y)
        diff = int((got.view(np.int32) != want.view(np.int32)).sum())
        print(f"   pow ({'one exponent' if y.size == 1 else 'per-lane exponents'}): {n:,} lanes, {diff} differ")


def _subprocess_seconds(code: str) -> float:
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-c", code], check=True, cwd=ROOT,
                   env=dict(os.environ, PYTHONPATH=ROOT))
    return time.perf_counter() - t0


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--lanes", default="143,3600,48000")
    ap.add_argument("--check", type=int, default=2_000_000)
    ap.add_argument("--repeat", type=int, default=15)
    args = ap.parse_args()
    lm = LlvmpipeMath(HOST_FMA)
    print(f"numba {numba.__version__}, NumPy {np.__version__}, FMA {HOST_FMA}; load "
          f"{' '.join(f'{v:.1f}' for v in os.getloadavg())}")
    print("1. cost of numba (fresh processes, wall time)")
    base = min(_subprocess_seconds("import numpy") for _ in range(3))
    imp = min(_subprocess_seconds("import numpy, numba") for _ in range(3))
    print(f"   import numpy {base * 1000:.0f} ms; import numpy, numba {imp * 1000:.0f} ms (+{(imp - base) * 1000:.0f} ms)")
    first = ("import numpy as np, time; t = time.perf_counter(); "
             "import benchmarks.proto_numba_kernels as p; from glslcheck.numpy_backend.runtime import LlvmpipeMath; "
             "lm = LlvmpipeMath(); p.numba_sin(np.ones(8, np.float32), lm); "
             "p.numba_pow(np.ones(8, np.float32), np.ones(1, np.float32), lm); "
             "print(f'   module import + first call of both kernels: {(time.perf_counter() - t) * 1000:.0f} ms')")
    for name in os.listdir(os.path.join(HERE, "__pycache__")) if os.path.isdir(os.path.join(HERE, "__pycache__")) else ():
        if name.startswith("proto_numba_kernels") and name.endswith((".nbi", ".nbc")):
            os.remove(os.path.join(HERE, "__pycache__", name))
    print("   compiling (no cache):", flush=True)
    _subprocess_seconds(first)
    print("   from numba's on-disk cache:", flush=True)
    _subprocess_seconds(first)
    print("2. bit for bit against LlvmpipeMath's reference")
    check(args.check, lm)
    print(f"3. CPU time per call, best of {args.repeat} (NumPy = LlvmpipeMath's public method, fast path up to "
          "4096 lanes)")
    rng = np.random.default_rng(7)
    for n in (int(v) for v in args.lanes.split(",")):
        a = rng.uniform(-50, 50, n).astype(F32)
        x = rng.uniform(0, 1, n).astype(F32)
        y = np.array([F32(32.0)])
        for name, fast, slow in (("sin", lambda: numba_sin(a, lm), lambda: lm.sin_or_cos(a, cos=False)),
                                 ("pow", lambda: numba_pow(x, y, lm), lambda: lm.pow(x, y))):
            tn = tf = float("inf")
            for _ in range(3):  # in turns
                tf = min(tf, _best(fast, args.repeat, time.process_time))
                tn = min(tn, _best(slow, args.repeat, time.process_time))
            print(f"   {name} {n:6d} lanes: NumPy {tn * 1e6:8.1f} us   numba {tf * 1e6:7.1f} us   {tn / tf:6.1f}x")
    print(f"load at the end {' '.join(f'{v:.1f}' for v in os.getloadavg())}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
