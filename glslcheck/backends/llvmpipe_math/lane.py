"""llvmpipe's math on one float32 lane, as numba functions that callers inline.

The steps every CPU emulation of gallivm's sin/cos/tan/exp2/log2 (lp_bld_arit.c) and of Mesa's
atan/asin/acos lowerings shares, in float32 with llvmpipe's roundings:

- bit helpers (:func:`bits`, :func:`from_bits`, :func:`select`), the fused multiply-add
  (:func:`mad`: ``llvm.fmuladd``, fused on an FMA CPU as LLVM's ``llvm.fma.f32``, else a float32
  multiply then add) and DAZ (:func:`daz`: a subnormal operand reads as a zero of its sign);
- sin/cos's Cody-Waite reduction and polynomials, the exp2 and log2 polynomials;
- whole one-lane algorithms for the arguments each documents: :func:`trig` (|x| < 2**29),
  :func:`exp2` (not NaN), :func:`log2` (positive, zero or subnormal), :func:`arc`.

Used by backends/numpy_engine/jit_kernels.py (loops over arrays), backends/compiled_engine/
scalar.py (per pixel) and lanes_math.py (branch-free, W pixels in lockstep). Every function is
``inline="always"`` (numba copies it into its caller, which is compiled with ``cache=True``), and
those the lockstep code calls compute both sides of a choice and pick one by :func:`select`
(no branch: LLVM packs W copies into SIMD instructions). numba compiles without fast-math, so
nothing is contracted or reordered.

Importing this module imports numba: its callers point numba's cache first
(cpu_core/numba_cache.use_cache_dir).
"""

from __future__ import annotations

import numba
import numpy as np
from llvmlite import ir
from numba.core import types
from numba.extending import intrinsic

from . import coefficients as co

F32 = np.float32
U32 = np.uint32
OPTIONS = dict(
    cache=True, nogil=True, error_model="numpy"
)  # error_model: x / 0 is IEEE, no exception
INLINE = dict(inline="always", **OPTIONS)
ONE, MINUS_ONE, HALF, ZERO = F32(1.0), F32(-1.0), F32(0.5), F32(0.0)
INF = F32(np.inf)
HALF_PI = F32(np.pi / 2)
FOUR_OVER_PI = F32(co.FOUR_OVER_PI)
EXP2_HI, EXP2_LO = F32(co.EXP2_HI), F32(co.EXP2_LO)
ABS_BITS, MIN_NORMAL_BITS, INF_BITS, SIN_MAX_BITS = (
    co.ABS_BITS,
    co.MIN_NORMAL_BITS,
    co.INF_BITS,
    co.SIN_MAX_BITS,
)
SIGN_BIT = U32(0x80000000)
ASIN_P0, ASIN_P1 = (F32(v) for v in co.ASIN_P)
ACOS_P0, ACOS_P1 = (F32(v) for v in co.ACOS_P)
_DP0, _DP1, _DP2 = (F32(v) for v in co.DP)
# SIN_COS[row, 0] the cosine's polynomial (y_6), SIN_COS[row, 1] the sine's (y2_6)
_C0, _C1, _C2 = (F32(co.SIN_COS[r, 0, 0]) for r in range(3))
_S0, _S1, _S2 = (F32(co.SIN_COS[r, 1, 0]) for r in range(3))
_E0, _E1, _E2, _E3, _E4, _E5 = (F32(v) for v in co.EXP2)
_L0, _L1, _L2, _L3, _L4 = (F32(v) for v in co.LOG2)
_A0, _A1, _A2, _A3, _A4, _A5 = (F32(v) for v in co.ATAN)
_MINUS_TWO, _ATAN2_SCALE, _ATAN2_BIG = F32(-2.0), F32(co.ATAN2_SCALE), F32(co.ATAN2_BIG)
_ASIN_C1 = F32(F32(np.pi / 4) - ONE)  # M_PI_4f - 1.0f, rounded twice as in C


# ---------------------------------------------------------------- bits, select, fused multiply-add
@intrinsic
def fmaf(typingctx, a, b, c):
    """float32 ``a*b + c`` rounded once: LLVM's llvm.fma.f32 (vfmadd on an FMA CPU, a correctly
    rounded libm fmaf elsewhere)."""
    sig = types.float32(types.float32, types.float32, types.float32)

    def codegen(context, builder, signature, args):
        f = ir.FloatType()
        fn = builder.module.declare_intrinsic("llvm.fma", [f], fnty=ir.FunctionType(f, [f, f, f]))
        return builder.call(fn, args)

    return sig, codegen


@intrinsic
def bits(typingctx, x):
    """The bits of float32 ``x`` as uint32."""

    def codegen(context, builder, signature, args):
        return builder.bitcast(args[0], ir.IntType(32))

    return types.uint32(types.float32), codegen


@intrinsic
def from_bits(typingctx, u):
    """The float32 whose bits are uint32 ``u``."""

    def codegen(context, builder, signature, args):
        return builder.bitcast(args[0], ir.FloatType())

    return types.float32(types.uint32), codegen


@intrinsic
def select(typingctx, c, a, b):
    """``a`` where the bool ``c`` holds, else ``b``: LLVM's ``select`` (both computed; a blend of
    two registers once vectorised). ``a`` and ``b`` have one type."""
    if not isinstance(c, types.Boolean) or a != b:
        return None

    def codegen(context, builder, signature, args):
        return builder.select(args[0], args[1], args[2])

    return a(c, a, b), codegen


@numba.njit(**INLINE)
def mad(a, b, c, fma):
    """``llvm.fmuladd`` of float32 scalars, as LlvmpipeMath.mad."""
    if fma:
        return fmaf(a, b, c)
    return F32(F32(a * b) + c)


@numba.njit(**INLINE)
def daz(x):
    """A subnormal x as a zero of its sign (MXCSR.DAZ), as llvmpipe_reference.daz, by a select."""
    b = bits(x)
    return from_bits(select((b & U32(ABS_BITS)) < U32(MIN_NORMAL_BITS), U32(b & SIGN_BIT), b))


@numba.njit(**INLINE)
def fmin(a, b):
    """IEEE minNum as np.fmin: a NaN operand gives the other (a NaN a gives b), equal operands
    (+0 and -0 too) the second. ``a < b`` picked by select is one vminps; the NaN terms are two
    compares."""
    return select((a < b) | ((b != b) & (a == a)), a, b)


@numba.njit(**INLINE)
def fmax(a, b):
    """IEEE maxNum as np.fmax (see :func:`fmin`)."""
    return select((a > b) | ((b != b) & (a == a)), a, b)


@numba.njit(**INLINE)
def sign(v):
    """Runtime.sign of a float32: 1, -1, else +0 (zeros and NaN)."""
    return select(v > ZERO, ONE, select(v < ZERO, MINUS_ONE, ZERO))


# ---------------------------------------------------------------- sin, cos, tan
@numba.njit(**INLINE)
def sin_cos_polynomials(y_2, x_abs, fma):
    """lp_build_sin_or_cos's shared middle: |x| reduced by j * pi/4 (``y_2`` = float32(j), three
    fused Cody-Waite steps), then the cosine's polynomial y_10 and the sine's y2_9 of it."""
    x_1 = mad(y_2, _DP0, x_abs, fma)
    x_2 = mad(y_2, _DP1, x_1, fma)
    x_3 = mad(y_2, _DP2, x_2, fma)
    z = F32(x_3 * x_3)
    y_6 = F32(mad(mad(z, _C0, _C1, fma), z, _C2, fma) * z)
    y2_6 = F32(mad(mad(z, _S0, _S1, fma), z, _S2, fma) * z)
    y_10 = F32(F32(F32(y_6 * z) - F32(z * HALF)) + ONE)
    y2_9 = mad(y2_6, x_3, x_3, fma)
    return y_10, y2_9


@numba.njit(**INLINE)
def trig(a, fma, which):
    """LlvmpipeMath._sin (``which`` 0), _cos (1) or _tan (2, sin over cos of one reduction) of
    one float32 lane ``a``, |a| < 2**29 and finite (:func:`trig_in_range`, the caller's check)."""
    ai = np.int64(bits(a))
    x_abs = daz(from_bits(np.uint32(ai & ABS_BITS)))
    j_add = np.int64(np.int32(F32(x_abs * FOUR_OVER_PI))) + 1  # in range: cvttps2dq truncates so
    j = j_add & ~np.int64(1)
    y_10, y2_9 = sin_cos_polynomials(F32(j), x_abs, fma)
    s = ZERO
    c = ZERO
    if (
        which != 1
    ):  # sin: bit 1 of j picks the polynomial; the sign bit is x's flipped by bit 2 of j_add
        s = y2_9 if (j & 2) == 0 else y_10
        if ((ai >> 31) ^ (j_add >> 2)) & 1:
            s = -s
        s = min(max(s, MINUS_ONE), ONE)  # lp_build_clamp (no NaN here)
    if which != 0:  # cos: the same of j - 2, the sign bit set where its bit 2 is clear
        j2 = j - 2
        c = y2_9 if (j2 & 2) == 0 else y_10
        if (j2 >> 2) & 1 == 0:
            c = -c
        c = min(max(c, MINUS_ONE), ONE)
    return s if which == 0 else c if which == 1 else F32(s / c)


@numba.njit(**INLINE)
def trig_in_range(a):
    """True where :func:`trig` computes LlvmpipeMath's result for ``a``: |a| < 2**29 and
    finite (a NaN or an Inf has larger bits)."""
    return (np.int64(bits(a)) & ABS_BITS) < SIN_MAX_BITS


# ---------------------------------------------------------------- exp2, log2
@numba.njit(**INLINE)
def exp2_polynomial(fpart, fma):
    """lp_build_exp2_polynomial of the fraction ``fpart`` in [0, 1): odd and even Horner chains
    in fpart**2, then ``mad(odd, fpart, even)``."""
    x2 = F32(fpart * fpart)
    odd = mad(x2, mad(x2, _E5, _E3, fma), _E1, fma)
    even = mad(x2, mad(x2, _E4, _E2, fma), _E0, fma)
    return mad(odd, fpart, even, fma)


@numba.njit(**INLINE)
def exp2(x, fma):
    """LlvmpipeMath._exp2 of one lane, x not NaN: clamp, 2**floor(x) from the exponent bits
    times the degree-5 polynomial of the fraction."""
    x = min(max(daz(x), EXP2_LO), EXP2_HI)
    ipart = F32(np.floor(x))
    p = exp2_polynomial(F32(x - ipart), fma)
    return F32(from_bits(np.uint32((np.int64(ipart) + 127) << 23)) * p)


@numba.njit(**INLINE)
def log2_of_parts(mant, logexp, fma):
    """lp_build_log2's formula: ``logexp + y * P(y*y)``, y = (m-1)/(m+1) of the mantissa ``mant``
    in [1, 2) (odd and even Horner chains in y**4)."""
    y = F32(F32(mant - ONE) / F32(mant + ONE))
    w = F32(y * y)
    x2 = F32(w * w)
    even = mad(x2, mad(x2, _L4, _L2, fma), _L0, fma)
    odd = mad(x2, _L3, _L1, fma)
    return mad(y, mad(odd, w, even, fma), logexp, fma)


@numba.njit(**INLINE)
def log2(x, fma):
    """LlvmpipeMath._log2 of one lane, x positive (or a zero, or subnormal) and not NaN: the
    exponent plus y * P(y*y), y = (m-1)/(m+1); -Inf for a zero after DAZ, +Inf for +Inf."""
    b = np.int64(bits(x))
    if (b & ABS_BITS) < MIN_NORMAL_BITS:
        return -INF
    if b == INF_BITS:
        return INF
    logexp = F32(((b & INF_BITS) >> 23) - 127)
    mant = from_bits(np.uint32((b & 0x007FFFFF) | 0x3F800000))
    return log2_of_parts(mant, logexp, fma)


# ---------------------------------------------------------------- atan, atan2, asin, acos
# Runtime._nir_atan, Runtime.atan's two-argument form and Runtime._asin_expr (Mesa's own
# lowerings, not gallivm's: plain float32 operations, no fused step), step by step
@numba.njit(**INLINE)
def atan(v):
    """Runtime._nir_atan of one lane ``v`` (already read with DAZ): never a NaN."""
    a = abs(v)
    x = daz(F32(fmin(a, ONE) / fmax(a, ONE)))
    x2 = F32(x * x)
    t = F32(x * _A0)
    p = F32(x * x2)
    t = F32(t + F32(p * _A1))
    p = F32(p * x2)
    t = F32(t + F32(p * _A2))
    p = F32(p * x2)
    t = F32(t + F32(p * _A3))
    p = F32(p * x2)
    t = F32(t + F32(p * _A4))
    t = daz(F32(t + F32(F32(p * _A5) * x2)))  # x^11's term reassociated, as in _nir_atan
    t = select(ONE < a, F32(F32(F32(t * _MINUS_TWO) + HALF_PI) + t), t)
    return F32(t * sign(v))


@numba.njit(**INLINE)
def atan2(y, x):
    """Runtime.atan(y, x) of one lane: y over x scaled, the half-plane flipped, atan of the
    quotient (atan(0, 0) = 3*pi/4, as llvmpipe's lowering)."""
    y = daz(y)
    x = daz(x)
    flip = ZERO >= x
    ax = abs(x)
    s = select(flip, ax, y)
    t = select(flip, y, ax)
    scale = select(abs(t) >= _ATAN2_BIG, _ATAN2_SCALE, ONE)
    rcp = F32(ONE / F32(t * scale))
    tan = select(ax == abs(y), ONE, daz(F32(abs(F32(s * scale)) * abs(rcp))))
    arc = F32(F32(select(flip, ONE, ZERO) * HALF_PI) + atan(tan))
    return select(fmin(y, rcp) < ZERO, -arc, arc)


@numba.njit(**INLINE)
def asin_expr(x, p0, p1):
    """Runtime._asin_expr of one lane, |x| <= 1 (else NaN: the caller's check); asin with
    (ASIN_P0, ASIN_P1), acos's part with (ACOS_P0, ACOS_P1)."""
    a = abs(x)
    poly = F32(HALF_PI + F32(a * F32(_ASIN_C1 + F32(a * F32(p0 + F32(a * p1))))))
    return F32(sign(x) * F32(HALF_PI - F32(np.sqrt(F32(ONE - a)) * poly)))


@numba.njit(**INLINE)
def arc(x, y, which):
    """atan (``which`` 0), asin (1), acos (2) of ``x``, or atan2 (3) of ``y`` = ``x`` and ``x`` =
    ``y``."""
    if which == 0:
        return atan(daz(x))
    if which == 1:
        return asin_expr(daz(x), ASIN_P0, ASIN_P1)
    if which == 2:
        return F32(HALF_PI - asin_expr(daz(x), ACOS_P0, ACOS_P1))
    return atan2(x, y)
