"""The llvmpipe math emulation's fast path: the same float32 steps in fewer NumPy calls.

llvmpipe_reference.LlvmpipeMath repeats gallivm's sin/cos/exp2/log2/pow (lp_bld_arit.c) step by step
and handles every input: subnormals flushed (DAZ), +-Inf, NaN, out-of-range conversions, the edges
of log2. A raymarcher calls it tens of thousands of times a frame on a few hundred lanes (a
march loop compacted to the lanes still marching), where each of its 40-70 NumPy calls costs
more than the arithmetic. The kernels here make the same float32 operations, in the same order
with the same roundings, for the common case only, and say so first:

- one or two reductions over the argument's bits decide whether every lane is in the range
  where the edge handling changes nothing (no NaN, Inf, subnormal or out-of-range conversion;
  for log2 every x normal and positive; exp2 clamps only when some |x| > 126; pow takes x = +-0
  too). Otherwise a kernel returns None and the caller takes the reference path;
- the fused multiply-adds (``llvm.fmuladd``, fused on an FMA CPU) are made in float64 rows of
  one buffer (the product of two float32 values is exact there, the sum rounded once) and
  rounded to float32; a float64 sum that is exactly a float32 midpoint is the only case where
  that double rounding can differ from the fused one (see llvmpipe_reference.fma32), and one test
  over the whole buffer at the end finds it: the lanes where one is are then computed again by the
  reference (rare on random arguments, a few lanes of a frame where values are short
  fractions: colours of 0.5, exact powers of two);
- the two Horner chains of a polynomial (even and odd coefficients), and sin/cos's two
  polynomials, are evaluated as the two rows of one array: elementwise, so the same bits in
  half the calls.

LlvmpipeMath uses the kernels up to 4096 lanes a call (llvmpipe_reference.DEFER_LANES): on whole
tiles their float64 rows cost as much as the calls they save.

Every kernel is checked bit for bit against the reference on millions of inputs, specials
included (tests/numpy/test_llvmpipe_fast_kernels.py). Without FMA a fused step is a float32
multiply then add, as llvmpipe does there.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..llvmpipe_math import coefficients as co

F32, F64, I32, U32, I64 = np.float32, np.float64, np.int32, np.uint32, np.int64
_SIG64 = (F64, F64, F64)  # a ufunc's float64 loop for float32 operands (cheaper than dtype=)


def _c(v: Any, dtype: Any) -> np.ndarray:
    """A constant operand as a 0-d array: NumPy resolves it faster than a NumPy scalar (about
    half the time of an integer operation on a few hundred lanes)."""
    return np.array(v, dtype)


_LOW29 = _c(0x1FFFFFFF, I64)  # the float64 bits rounding to float32 drops
_MID29 = _c(0x10000000, I64)  # ... when they are exactly half a float32 step
_ABS = _c(0x7FFFFFFF, I32)
_MIN_NORMAL_BITS = co.MIN_NORMAL_BITS
_INT_MIN = _c(-(2**31), I32)
_I1, _I2, _I4, _NOT1 = (_c(v, I32) for v in (1, 2, 4, ~1))
_U29 = _c(29, U32)

# gallivm's constants: llvmpipe_math.coefficients
_SIN_MAX_BITS = co.SIN_MAX_BITS
_FOPI = _c(co.FOUR_OVER_PI, F32)
_DP = tuple(_c(v, F32) for v in co.DP)
_SC = co.SIN_COS
_ZERO, _HALF, _ONE, _MINUS_ONE = (_c(v, F32) for v in (0.0, 0.5, 1.0, -1.0))

# exp2: |x| <= 126 (bits 0x42FC0000): neither clamp (128, -126.99999) applies
_EXP2_MAX_BITS = 0x42FC0000
_EXP2_HI, _EXP2_LO = _c(co.EXP2_HI, F32), _c(co.EXP2_LO, F32)
_EXP2 = co.EXP2
_EXP2_C1 = np.array([[_EXP2[5]], [_EXP2[4]]], F32)  # odd and even chain: first coefficients
_EXP2_C2 = np.array([[_EXP2[3]], [_EXP2[2]]], F32)
_EXP2_C3 = np.array([[_EXP2[1]], [_EXP2[0]]], F32)
_B127, _I23 = _c(127, I32), _c(23, I32)

_LOG2 = co.LOG2
_LOG2_C1 = np.array([[_LOG2[4]], [_LOG2[3]]], F32)  # even and odd chain
_LOG2_C2 = np.array([[_LOG2[2]], [_LOG2[1]]], F32)
_LOG2_C0 = _c(_LOG2[0], F32)
_MANT = _c(0x007FFFFF, I32)
_ONE_BITS = _c(0x3F800000, I32)
_INF_BITS = co.INF_BITS


class _Fused:
    """``llvm.fmuladd`` for one kernel call: with FMA, each product and sum in float64 rows of
    one buffer, rounded to float32 at once, the rows checked for midpoints by :meth:`midpoints`;
    without FMA a float32 multiply then add."""

    __slots__ = ("fma", "buf", "used")

    def __init__(self, fma: bool, rows: int, n: int) -> None:
        self.fma = fma
        self.buf = np.empty((rows, n), F64) if fma else None
        self.used = 0

    def mad(self, a: Any, b: Any, c: Any, rows: int = 1) -> np.ndarray:
        """``a*b + c``, the result ``rows`` rows (a stacked evaluation) or one."""
        if not self.fma:
            return np.add(np.multiply(a, b, dtype=F32), c, dtype=F32)
        k = self.used
        buf = self.buf
        assert buf is not None  # made with fma
        s = buf[k] if rows == 1 else buf[k : k + rows]
        self.used = k + rows
        # (NumPy's stubs take a signature as strings only; its dtypes are accepted too)
        np.multiply(a, b, out=s, signature=_SIG64)  # type: ignore[arg-type]
        np.add(s, c, out=s)
        return s.astype(F32)

    def midpoints(self) -> np.ndarray | None:
        """None when no float64 sum is a float32 midpoint (each rounding equals the fused
        one), else the lanes where one is (the rows are overwritten by the test)."""
        if not self.used or self.buf is None:  # (no buffer: nothing used)
            return None
        low = self.buf[: self.used].view(I64)
        np.bitwise_and(low, _LOW29, out=low)
        mid = low == _MID29
        if not mid.any():
            return None
        return mid.any(axis=0)


def _fix(r: np.ndarray, bad: np.ndarray | None, ref: Any, *args: np.ndarray) -> np.ndarray | None:
    """``r`` (flat) with the lanes ``bad`` (a float32 midpoint in a fused step, where the
    double rounding may differ) recomputed by ``ref``, the reference algorithm, on those lanes
    of the flat ``args`` alone: every step is elementwise, so the same bits as the whole call.
    None (decline) without ``ref``."""
    if bad is None:
        return r
    if ref is None:
        return None
    at = np.flatnonzero(bad)
    r[at] = ref(*(a[at] for a in args))
    return r


def _flat(x: np.ndarray) -> np.ndarray:
    return x if x.ndim == 1 else x.reshape(-1)


def _normal_or_zero(xi: np.ndarray) -> bool:
    """Given |x|'s bits ``xi`` whose minimum is below FLT_MIN's: whether all such are zeros
    (no subnormal; DAZ would make them zeros, which they are)."""
    return not ((xi != 0) & (xi < _MIN_NORMAL_BITS)).any()


def sin_cos(a: np.ndarray, fma: bool, cos: bool, ref: Any = None) -> np.ndarray | None:
    """LlvmpipeMath._sin/_cos for |x| < 2**29, finite; None otherwise. ``ref``: the reference
    for the lanes of a float32 midpoint (:func:`_fix`)."""
    shape = a.shape
    a = _flat(a)
    ai = a.view(I32)
    xi = ai & _ABS
    hi = int(xi.max())
    if hi >= _SIN_MAX_BITS:
        return None  # Inf, NaN or a conversion that could overflow
    if xi.min() < _MIN_NORMAL_BITS and not _normal_or_zero(xi):
        return None  # subnormals: the reference flushes them
    x_abs = xi.view(F32)
    j_add = (x_abs * _FOPI).astype(I32)  # in range: truncates as cvttps2dq
    j_add += _I1
    j = j_add & _NOT1
    y_2 = j.astype(F32)
    # the bound on j for the exact forms of DP1 and DP2 (see LlvmpipeMath._sin_cos_reduced):
    # from the largest |x| (conservative: the float32 product rounds at most to the next
    # float, so 2 more cover it); an exact step fused or not gives the same bits
    j_max = int(float(np.int32(hi).view(F32)) * 1.2732396) + 3
    f = _Fused(fma, 8, a.size)
    x_1 = (y_2 * _DP[0] + x_abs) if j_max < 2**16 else f.mad(y_2, _DP[0], x_abs)
    x_2 = (y_2 * _DP[1] + x_1) if j_max < 2**13 else f.mad(y_2, _DP[1], x_1)
    x_3 = f.mad(y_2, _DP[2], x_2)
    z = x_3 * x_3
    both = f.mad(f.mad(z, _SC[0], _SC[1], rows=2), z, _SC[2], rows=2)
    both *= z
    y_10 = both[0]
    y_10 *= z
    y_10 -= z * _HALF
    y_10 += _ONE
    y2_9 = f.mad(both[1], x_3, x_3)
    bad = f.midpoints() if fma else None
    if cos:
        j -= _I2  # emm2_2 (wraps, as psubd)
        sign = ((_I4 & ~j).view(U32) << _U29).view(I32)
    else:
        sign = (ai ^ (j_add.view(U32) << _U29).view(I32)) & _INT_MIN
    y = np.where(j & _I2, y_10, y2_9)
    yi = y.view(I32)
    yi ^= sign
    if j_max >= 2**16:
        # lp_build_clamp. Below, x_1 is exact (Sterbenz), so |x_3| < 0.8, y2_9 is about
        # sin(x_3) and y_10 = 1 + (a - z/2) with 0 <= a < z/2: both within [-1, 1] already
        np.fmin(y, _ONE, out=y)
        np.fmax(y, _MINUS_ONE, out=y)
    fixed = _fix(y, bad, ref, a)
    return None if fixed is None else fixed.reshape(shape)


def exp2(x: np.ndarray, fma: bool, ref: Any = None) -> np.ndarray | None:
    """LlvmpipeMath._exp2 without NaN or subnormals; None otherwise (``ref``: see
    :func:`sin_cos`)."""
    r = _exp2(x, fma)
    return None if r is None else _reshape(_fix(r[0], r[1], ref, _flat(x)), x.shape)


def _reshape(r: np.ndarray | None, shape: tuple[int, ...]) -> np.ndarray | None:
    return None if r is None else r.reshape(shape)


def _exp2(x: np.ndarray, fma: bool) -> tuple[np.ndarray, np.ndarray | None] | None:
    """exp2 of the flattened ``x`` and the lanes of a midpoint (or None), or None (declined)."""
    x = _flat(x)
    xi = x.view(I32) & _ABS
    hi = xi.max()
    if hi > _EXP2_MAX_BITS:
        if hi > _INF_BITS:
            return None  # NaN
        x = np.minimum(x, _EXP2_HI)  # minps, maxps: at most +-Inf here
        np.maximum(x, _EXP2_LO, out=x)
    if xi.min() < _MIN_NORMAL_BITS and not _normal_or_zero(xi):
        return None
    ipart = np.floor(x)
    fpart = x - ipart
    e = ipart.astype(I32)
    e += _B127
    e <<= _I23  # (ipart + 127) << 23: a normal float's exponent field here
    f = _Fused(fma, 5, x.size)
    x2 = fpart * fpart
    r = f.mad(f.mad(x2, _EXP2_C1, _EXP2_C2, rows=2), x2, _EXP2_C3, rows=2)  # odd, even chains
    p = f.mad(r[0], fpart, r[1])
    return np.multiply(e.view(F32), p, out=p), (f.midpoints() if fma else None)


def log2(x: np.ndarray, fma: bool, ref: Any = None) -> np.ndarray | None:
    """LlvmpipeMath._log2 for every x normal, positive and finite (where its edges change
    nothing); None otherwise (``ref``: see :func:`sin_cos`)."""
    r = _log2(x, fma)
    return None if r is None else _reshape(_fix(r[0], r[1], ref, _flat(x)), x.shape)


def _log2(x: np.ndarray, fma: bool) -> tuple[np.ndarray, np.ndarray | None] | None:
    """log2 of the flattened ``x`` and the lanes of a midpoint (or None), or None (declined)."""
    x = _flat(x)
    i = x.view(I32)
    if i.min() < _MIN_NORMAL_BITS or i.max() >= _INF_BITS:
        return None
    logexp = i >> _I23  # the sign bit is clear
    logexp -= _B127
    mi = i & _MANT
    mi |= _ONE_BITS
    mant = mi.view(F32)
    y = mant - _ONE
    y /= mant + _ONE
    w = y * y
    f = _Fused(fma, 5, x.size)
    x2 = w * w
    r = f.mad(x2, _LOG2_C1, _LOG2_C2, rows=2)  # even, odd chains
    even = f.mad(x2, r[0], _LOG2_C0)
    p = f.mad(r[1], w, even)
    res = f.mad(y, p, logexp.astype(F32))
    return res, (f.midpoints() if fma else None)


def pow(x: np.ndarray, y: np.ndarray, fma: bool, ref: Any = None) -> np.ndarray | None:
    """LlvmpipeMath._pow: exp2(log2(x) * y), then 0 where x is +-0 (or subnormal, or NaN:
    declined here). Lanes of x == 0 are computed as x = 1 and then set to 0, which is what the
    reference gives them whatever the rest yields (every step is elementwise); None where a
    kernel declines (``ref``: see :func:`sin_cos`, here of both arguments)."""
    lg = _log2(x, fma)
    zero = None
    if lg is None:
        zero = x == _ZERO
        if not zero.any():
            return None
        lg = _log2(np.where(zero, _ONE, x), fma)
        if lg is None:
            return None
    lg2, bad_x = lg
    t = lg2.reshape(x.shape) * y
    e = _exp2(t, fma)
    if e is None:
        return None
    r, bad = e
    r = r.reshape(t.shape)
    if zero is not None:
        np.copyto(r, _ZERO, where=zero)
    if bad_x is not None:
        bad_x = np.broadcast_to(bad_x.reshape(x.shape), t.shape).reshape(-1)
        bad = bad_x if bad is None else bad | bad_x
    if bad is None:
        return r
    if ref is None:
        return None
    flat = _fix(r.reshape(-1), bad, ref, *(np.broadcast_to(v, t.shape).reshape(-1) for v in (x, y)))
    return None if flat is None else flat.reshape(t.shape)
