"""Branch-free one-lane math for pixels run in lockstep: scalar.py's functions without a branch
or a call, so that W inlined copies of one, side by side in a W-lane tuple
``(f(a[0]), f(a[1]), ..., f(a[W-1]))``, become W-wide SIMD instructions (LLVM's SLP vectoriser).

Every function here has the name, the signature and, for every input, the result bits of
scalar.py's function of that name (NaN, +-0, +-Inf, subnormals, |x| >= 2**29, both ``fma``
modes: tests/compiled/test_lanes_math.py). What differs is only how it is computed:

- every ``if`` and ``x if c else y`` of scalar.py is a ``select`` (LLVM's, llvmpipe_math.lane): both
  sides are computed, then one is picked, lane by lane (a blend of two registers);
- sin/cos/tan compute lane.trig's steps for every argument with scalar._trig_any's
  int32 wrap-around, which is the same bits where _trig applies (|x| < 2**29) and scalar's
  answer for larger |x|; a NaN or an infinity gives scalar's NaN by a last select. So no rare
  path is left for a caller to hoist;
- int ``/`` and ``%`` are float64 divisions truncated (x86 has no packed integer divide): for
  32-bit operands the float64 quotient truncates to the integer quotient exactly (the rounding
  error, below |q| * 2**-53 < 2**-22 / |b|, is smaller than a quotient's distance to the next
  integer, at least 1 / |b|), and the remainder a - q*b is exact in float64;
- float to int conversions are float32/float64 to int32 (``cvttps2dq``/``cvttpd2dq``) with the
  out-of-range lanes selected away; a uint beyond 2**31 goes through ``t - 2**31`` and the top
  bit (AVX2 has no packed float-to-uint32).

**Contract for the lockstep caller** (compiled_backend's generated code):

- ``from glslcheck.backends.compiled_engine.lanes_math import *`` after scalar's import replaces the
  functions listed in :data:`REWRITTEN`; :data:`AS_IS` lists scalar.py's functions that already
  vectorise as they are (the test checks both lists against the machine code).
- ``fma`` must be a compile-time constant where it is used (the generated module's global
  ``FMA``, frozen by numba): a run-time bool is a branch in every copy.
- numba's SLP vectoriser is off by default: ``numba.core.config.SLP_VECTORIZE = 1`` (or
  ``NUMBA_SLP_VECTORIZE=1`` in the environment) before the module is compiled; without it the
  functions are still correct, one lane at a time.
- The public functions are numba ``inline="never"``, as scalar.py's, and LLVM's inliner inlines
  each of the W calls (the test checks that no call is left): numba's own ``inline="always"``
  would copy and re-type a function's IR at every call site, 27 s instead of 1.5 s to compile
  one W = 8 tuple of sin (load 5). Their helpers (``_trig_lane``, ``_exp2_finite``, ...) are
  numba-inlined into them once.
- Each public function has ONE signature (:data:`_SIGS`: float32 arguments, int32/uint32 for
  the integer ones, a bool ``fma``) and is compiled when this module is imported, with the SLP
  vectoriser off whatever the caller's setting (:func:`njit`): about 13 s the first time on a
  machine, then numba's cache (importing numba included, ~1 s of CPU). A function compiled with
  SLP on packs its own one-lane pairs first, which the caller cannot repack (:func:`njit`'s
  docstring). scalar.py's functions (those in :data:`AS_IS` too) are compiled lazily, with
  whatever setting the caller's compile has: the same applies to them (smoothstep's
  ``x - e0`` and ``e1 - e0`` are such a pair), so the lockstep engine should compile scalar.py
  with SLP off as well (the W-lane test here compiles them in a fresh process with it on, and
  they pass, but that is the order of one test, not a guarantee).
- Nothing here needs a hoisted rare-case test (an any-lane check before the W calls): every
  function is straight-line for every input, |x| >= 2**29, NaN and infinities included.

What this does not change: integer division stays float64 (4 lanes a ymm register: vdivpd),
and a caller's loads with a signed index keep numba's wrap-around select per lane, which stops
the packing of the loads themselves (docs/performance.md, "Lane math").
"""

from __future__ import annotations

from ..cpu_core.numba_cache import use_cache_dir

use_cache_dir()  # numba's cache directory first

import numba  # noqa: E402
import numpy as np  # noqa: E402

from ..llvmpipe_math import lane  # noqa: E402
from ..llvmpipe_math.lane import ACOS_P0, ACOS_P1, ASIN_P0, ASIN_P1, bits, from_bits, select  # noqa: E402

F32 = np.float32
F64 = np.float64
I32 = np.int32
U32 = np.uint32
_J = dict(inline="never", cache=True, nogil=True, error_model="numpy")
_ZERO, _ONE, _MONE, _TWO, _THREE, _HALF, _FOUR = (
    F32(v) for v in (0.0, 1.0, -1.0, 2.0, 3.0, 0.5, 4.0)
)
_NAN = F32(np.nan)
_INF = F32(np.inf)
_INT_MIN = I32(-(2**31))
_ABS = 0x7FFFFFFF
_SIGN = U32(0x80000000)
_MIN_NORMAL_BITS = 0x00800000
_INF_BITS = 0x7F800000
_TWO31 = F64(2.0**31)
_TWO31F = F32(2.0**31)
_LOG2E = F32(1.4426950408889634)
_LN2 = F32(0.6931471805599453)


_F, _I, _U = "float32", "int32", "uint32"
_SIGS = {  # name: (result, arguments); the types the generated code passes (fma: its FMA global)
    **{n: (_F, "float32, float32") for n in ("fmin", "fmax", "atan2")},
    **{n: (_F, "float32, float32, float32") for n in ("clamp", "mix_fast")},
    **{n: (_F, "float32") for n in ("daz", "sign", "pow_zero", "asin", "acos", "atan")},
    **{
        n: (_F, "float32, boolean")
        for n in (
            "sin",
            "cos",
            "tan",
            "exp2",
            "log2",
            "exp",
            "log",
            "sinh",
            "cosh",
            "tanh",
            "asinh",
            "acosh",
            "atanh",
        )
    },
    "pow": (_F, "float32, float32, boolean"),
    "pow_uniform": (_F, "float32, float32, boolean, boolean, boolean"),
    **{n: (_I, "int32, int32") for n in ("idiv", "irem", "irem_const")},
    **{n: (_U, "uint32, uint32") for n in ("udiv", "urem")},
    "to_int": (_I, "float32"),
    **{n: (_U, "float32") for n in ("to_uint_sse", "to_uint_avx512", "to_uint_arm64")},
}


def njit(fn):
    """A public function, compiled now for its one signature (numba's cache keeps it) with the SLP
    vectoriser OFF: LLVM inlines this one-lane code W times into a lockstep caller and packs the
    W copies there. Compiled with SLP on, a function's own isomorphic pairs are packed first (sinh's
    exp(x) and exp(-x), atan2's y and x, tan's sine and cosine picks: two-wide vectors), which the
    caller cannot unpack: 1.0x-0.5x of one lane at a time instead of 4-16x."""
    from numba.core import config

    result, args = _SIGS[fn.__name__]
    old = config.SLP_VECTORIZE
    config.SLP_VECTORIZE = 0
    try:
        return numba.njit(f"{result}({args})", **_J)(fn)
    finally:
        config.SLP_VECTORIZE = old


def _inline(fn):
    """A helper: inlined into the public functions by numba (once, when they compile)."""
    return numba.njit(**{**_J, "inline": "always"})(fn)


# -- float basics ----------------------------------------------------------------------------
@njit
def fmin(a, b):
    """IEEE minNum as np.fmin (lane.fmin: a select, one vminps and two compares)."""
    return lane.fmin(a, b)


@njit
def fmax(a, b):
    """IEEE maxNum as np.fmax (lane.fmax)."""
    return lane.fmax(a, b)


@njit
def clamp(x, lo, hi):
    return fmin(fmax(x, lo), hi)


@njit
def daz(x):
    return lane.daz(x)


@njit
def sign(x):
    return lane.sign(x)


@njit
def mix_fast(x, y, a):
    """``x + a*(y-x)`` in every lane (scalar.mix_fast)."""
    return F32(x + F32(a * F32(y - x)))


# -- ints ------------------------------------------------------------------------------------
@_inline
def _u32_of(t):
    """The uint32 of a float64 integer t in [0, 2**32): through int32 (cvttpd2dq), top bit back."""
    return U32(U32(I32(t - _TWO31)) ^ _SIGN)


@njit
def idiv(a, b):
    """int ``/``: truncation; x / 0 = 0; INT_MIN / -1 = INT_MIN (scalar.idiv)."""
    zero = b == 0
    q = np.trunc(F64(a) / select(zero, F64(1.0), F64(b)))  # exact (module docstring)
    q = select(q >= _TWO31, F64(-_TWO31), q)  # INT_MIN / -1 wraps
    return select(zero, I32(0), I32(q))


@njit
def udiv(a, b):
    """uint ``/``: x / 0 = 0xFFFFFFFF."""
    zero = b == 0
    q = np.trunc(F64(a) / select(zero, F64(1.0), F64(b)))
    return select(zero, U32(0xFFFFFFFF), _u32_of(q))


@_inline
def _urem64(au, bu):
    """The remainder of uint32 bit patterns as a float64 (bu not 0): exact."""
    ad = F64(au)
    bd = F64(bu)
    return ad - np.trunc(ad / bd) * bd


@njit
def irem(a, b):
    """int ``%`` at run time: the unsigned remainder of the bit patterns; x % 0 = -1."""
    bu = U32(b)
    zero = bu == 0
    r = _urem64(U32(a), select(zero, U32(1), bu))
    return select(zero, I32(-1), I32(_u32_of(r)))


@njit
def urem(a, b):
    zero = b == 0
    r = _urem64(a, select(zero, U32(1), U32(b)))
    return select(zero, U32(0xFFFFFFFF), _u32_of(r))


@njit
def irem_const(a, b):
    """int ``%`` folded by Mesa: the C remainder (the sign of a); x % 0 = -1."""
    zero = b == 0
    ad = F64(a)
    bd = select(zero, F64(1.0), F64(b))
    r = ad - np.trunc(ad / bd) * bd  # exact; INT_MIN % -1 is 0
    return select(zero, I32(-1), I32(r))


# -- conversions -----------------------------------------------------------------------------
@njit
def to_int(x):
    """``int(float)``: truncation; NaN, +-Inf and out of range give INT_MIN (cvttps2dq). A
    float32 truncates into [-2**31, 2**31) exactly when it lies in that range."""
    return select((x >= -_TWO31F) & (x < _TWO31F), I32(x), _INT_MIN)


@_inline
def _cvtt_bits(t):
    return select((t >= -_TWO31) & (t < _TWO31), U32(I32(t)), _SIGN)


@njit
def to_uint_sse(x):
    """``uint(float)`` as llvmpipe on an x86 CPU without AVX-512 (scalar.to_uint_sse)."""
    xd = F64(x)
    big = xd >= _TWO31
    bits = _cvtt_bits(np.trunc(select(big, xd - _TWO31, xd)))
    return select(big, U32(bits | _SIGN), bits)


@njit
def to_uint_avx512(x):
    t = np.trunc(F64(x))
    return select(
        (t >= 0.0) & (t < 4294967296.0), _u32_of(select(t >= 0.0, t, F64(0.0))), U32(0xFFFFFFFF)
    )


@njit
def to_uint_arm64(x):
    t = np.trunc(F64(x))
    inner = _u32_of(select((t > 0.0) & (t < 4294967295.0), t, F64(0.0)))
    r = select(t >= 4294967295.0, U32(0xFFFFFFFF), inner)
    return select((t <= 0.0) | (t != t), U32(0), r)


# -- llvmpipe's transcendentals --------------------------------------------------------------
@_inline
def _pick(flag, a, b):
    """``a`` where bit 0 of the int ``flag`` is clear, else ``b``, by a bit mask."""
    m = U32(-(I32(flag) & I32(1)))
    return from_bits(U32(bits(a) ^ U32(U32(bits(a) ^ bits(b)) & m)))


@_inline
def _negate_if(flag, x):
    """``-x`` where bit 0 of the int ``flag`` is set: the sign bit flipped by a bit mask."""
    return from_bits(U32(bits(x) ^ U32(U32(I32(flag) & I32(1)) << U32(31))))


@_inline
def _trig_lane(a, fma, which):
    """scalar._trig_call without a branch: scalar._trig_any's steps (lane.trig's where
    |a| < 2**29) in int32 arithmetic, the polynomial and sign picked by selects, NaN for a NaN or
    an infinite ``a``."""
    ai = I32(bits(a))
    x_abs = lane.daz(from_bits(U32(bits(a) & U32(_ABS))))
    p = F32(x_abs * lane.FOUR_OVER_PI)  # >= 0, or NaN
    j0 = select(p < _TWO31F, I32(p), _INT_MIN)  # cvttps2dq
    emm2_add = I32(j0 + I32(1))
    emm2_and = I32(emm2_add & I32(-2))
    y_10, y2_9 = lane.sin_cos_polynomials(F32(emm2_and), x_abs, fma)
    s = _ZERO
    c = _ZERO
    if which != 1:  # a constant: folded
        s = _pick(emm2_and >> 1, y2_9, y_10)
        s = _negate_if(I32(ai >> 31) ^ I32(emm2_add >> 2), s)
        s = fmax(fmin(s, _ONE), _MONE)
    if which != 0:
        j2 = I32(emm2_and - I32(2))
        c = _pick(emm2_and >> 1, y_10, y2_9)  # bit 1 of j2 = j - 2 is bit 1 of the even j flipped
        c = _negate_if(I32(j2 >> 2) ^ I32(1), c)
        c = fmax(fmin(c, _ONE), _MONE)
    bad = (bits(a) & U32(_ABS)) >= U32(_INF_BITS)  # NaN or Inf: scalar's NaN
    if which == 2:  # the NaN selected before the division: a select of a division's result
        return F32(select(bad, _NAN, s) / select(bad, _ONE, c))  # becomes a branch (LLVM)
    return select(bad, _NAN, s if which == 0 else c)


@njit
def sin(a, fma):
    return _trig_lane(a, fma, 0)


@njit
def cos(a, fma):
    return _trig_lane(a, fma, 1)


@njit
def tan(a, fma):
    return _trig_lane(a, fma, 2)


@_inline
def _exp2_finite(x, fma):
    """lane.exp2 of a non-NaN x, its clamp and DAZ by selects."""
    x = lane.daz(x)
    x = select(x < lane.EXP2_LO, lane.EXP2_LO, x)
    x = select(x > lane.EXP2_HI, lane.EXP2_HI, x)
    ipart = F32(np.floor(x))
    p = lane.exp2_polynomial(F32(x - ipart), fma)
    return F32(from_bits(U32(I32(I32(I32(ipart) + I32(127)) << I32(23)))) * p)


@njit
def exp2(x, fma):
    nan = x != x
    return select(nan, _NAN, _exp2_finite(select(nan, _ZERO, x), fma))


@njit
def log2(x, fma):
    """lp_build_log2_safe (scalar.log2): NaN for NaN and x < 0 after DAZ, -Inf for a zero after
    DAZ, +Inf for +Inf, else lane.log2's exponent plus y * P(y*y)."""
    b = bits(x)
    mag = b & U32(_ABS)
    tiny = mag < U32(_MIN_NORMAL_BITS)
    nan = (x != x) | ((b >= _SIGN) & (mag >= U32(_MIN_NORMAL_BITS)))
    inf = b == U32(_INF_BITS)
    b = select(tiny | nan | inf, U32(0x3F800000), b)  # 1.0: the formula on a harmless value
    logexp = F32(I32(I32(b >> U32(23)) - I32(127)))  # b's sign bit is clear
    mant = from_bits(U32((b & U32(0x007FFFFF)) | U32(0x3F800000)))
    r = lane.log2_of_parts(mant, logexp, fma)
    r = select(inf, _INF, select(tiny, -_INF, r))
    return select(nan, _NAN, r)


@njit
def pow(x, y, fma):
    """lp_build_pow (scalar.pow): exp2(log2(x) * y), 0 where x is 0 after DAZ or NaN."""
    zero = (x != x) | ((bits(x) & U32(_ABS)) < U32(_MIN_NORMAL_BITS))
    t = F32(log2(x, fma) * lane.daz(y))
    nan = t != t
    r = select(nan, _NAN, _exp2_finite(select(nan, _ZERO, t), fma))
    return select(zero, _ZERO, r)


@njit
def pow_zero(x):
    return select((x == _ZERO) | (x != x), _ZERO, _ONE)


@njit
def exp(x, fma):
    return exp2(F32(lane.daz(x) * _LOG2E), fma)


@njit
def log(x, fma):
    return F32(log2(x, fma) * _LN2)


@njit
def pow_uniform(x, y, special, zeros, fma):
    """scalar.pow_uniform by selects: both Runtime.pow_const's rewrite (y one of the special
    exponents, picked by selects) and the run-time pow are computed, and ``special`` and
    ``zeros`` pick one. They are lane-uniform, but the generated code passes them as run-time
    values (``pow(x, shininess)`` with a uniform parameter): an ``if`` on them, in each of the W
    inlined copies, cut the W lanes into W pairs of blocks that the SLP vectoriser, which packs
    within one block, left scalar: a large share of the CPU time of a shader that calls pow on
    every pixel. Where they are constants, LLVM folds the selects and the unused side."""
    sq = F32(x * x)
    rewrite = select(
        y == _ONE, x, select(y == _TWO, sq, select(y == _FOUR, F32(sq * sq), pow_zero(x)))
    )
    return select(special, select(zeros, _ONE, rewrite), pow(x, y, fma))


# -- Mesa's atan, atan(y, x), asin, acos: llvmpipe_math.lane's (selects already) ---------------
@njit
def atan(y):
    return lane.atan(lane.daz(y))


@njit
def atan2(y, x):
    """Runtime.atan(y, x): Mesa's nir_atan2 (atan(0, 0) = 3*pi/4)."""
    return lane.atan2(y, x)


@njit
def asin(x):
    return lane.asin_expr(lane.daz(x), ASIN_P0, ASIN_P1)


@njit
def acos(x):
    return F32(lane.HALF_PI - lane.asin_expr(lane.daz(x), ACOS_P0, ACOS_P1))


# -- hyperbolic: scalar.py's formulas over the branch-free exp and log -----------------------
@njit
def sinh(x, fma):
    return F32(_HALF * F32(exp(x, fma) - exp(-x, fma)))


@njit
def cosh(x, fma):
    return F32(_HALF * F32(exp(x, fma) + exp(-x, fma)))


@njit
def tanh(x, fma):
    x = select(x > F32(-10.0), x, F32(-10.0))  # clamp(x, -10, 10), NaN gives -10: two compares
    x = select(x < F32(10.0), x, F32(10.0))  # (the NaN terms of fmin/fmax cannot apply)
    e1 = exp(x, fma)
    e2 = exp(-x, fma)
    return F32(F32(e1 - e2) / F32(e1 + e2))


@njit
def asinh(x, fma):
    return F32(lane.sign(x) * log(F32(abs(x) + np.sqrt(F32(F32(x * x) + _ONE))), fma))


@njit
def acosh(x, fma):
    return log(F32(x + np.sqrt(F32(F32(x * x) - _ONE))), fma)


@njit
def atanh(x, fma):
    return F32(_HALF * log(F32(F32(_ONE + x) / F32(_ONE - x)), fma))


# scalar.py's functions this module replaces, and those that vectorise as they are (no branch
# left after LLVM's simplification; tests/compiled/test_lanes_math.py checks both lists)
REWRITTEN = (
    "fmin",
    "fmax",
    "clamp",
    "sign",
    "daz",
    "mix_fast",
    "idiv",
    "udiv",
    "irem",
    "urem",
    "irem_const",
    "to_int",
    "to_uint_sse",
    "to_uint_avx512",
    "to_uint_arm64",
    "sin",
    "cos",
    "tan",
    "exp2",
    "log2",
    "pow",
    "pow_zero",
    "exp",
    "log",
    "pow_uniform",
    "asin",
    "acos",
    "atan",
    "atan2",
    "sinh",
    "cosh",
    "tanh",
    "asinh",
    "acosh",
    "atanh",
)
AS_IS = (
    "fract",
    "mod",
    "step",
    "smoothstep",
    "smoothstep_scaled",
    "inversesqrt",
    "ishl",
    "ishr",
    "ushl",
    "ushr",
    "iabs",
    "isign",
    "float_bits_to_int",
    "float_bits_to_uint",
    "int_bits_to_float",
    "uint_bits_to_float",
    "round_even",
)
__all__ = list(REWRITTEN)
