"""The scalar runtime of the compiled engine: one GLSL operation on one pixel's values, as
numba functions the generated module calls (inlined by LLVM).

Each function computes, for one lane, exactly what glslcheck/backends/numpy_engine/runtime.py
computes for every lane (its docstring is the reference for every rule quoted here): IEEE float32
arithmetic, llvmpipe's integer division and remainder, shift counts mod 32, float-to-int
conversions through x86's cvttps2dq, IEEE minNum/maxNum for min/max, and gallivm's
sin/cos/tan/exp2/log2/pow, for which backends/llvmpipe_math/lane.py has the one-lane algorithms
(`trig`, `exp2`, `log2`): they are called here for the arguments they take, and the rest
(|x| >= 2**29 for the trigonometric functions, NaN, negative logarithms) is computed by the
functions below, step by step as LlvmpipeMath does.

Imported only by the generated modules (backends/compiled_engine/engine.py loads them); importing it
points numba's cache directory, then imports numba.
"""

from __future__ import annotations

from ..cpu_core.numba_cache import use_cache_dir

use_cache_dir()  # numba's cache directory first

import numba  # noqa: E402
import numpy as np  # noqa: E402

from ..llvmpipe_math import lane  # noqa: E402
from ..llvmpipe_math.lane import bits, from_bits, sin_cos_polynomials  # noqa: E402

F32 = np.float32
I32 = np.int32
U32 = np.uint32
_J = dict(inline="never", cache=True, nogil=True, error_model="numpy")
_ZERO, _ONE, _MONE, _TWO, _THREE, _HALF = (
    F32(0.0),
    F32(1.0),
    F32(-1.0),
    F32(2.0),
    F32(3.0),
    F32(0.5),
)
_NAN = F32(np.nan)
_INF = F32(np.inf)
_INT_MIN = I32(-(2**31))
_LOG2E = F32(1.4426950408889634)
_LN2 = F32(0.6931471805599453)
_FLT_MIN_BITS = 0x00800000


def njit(fn):
    return numba.njit(**_J)(fn)


# -- float basics ----------------------------------------------------------------------------
@numba.njit(inline="always", **lane.OPTIONS)
def fmin(a, b):
    """``min`` of floats: IEEE minNum, a NaN operand gives the other (np.fmin; for equal operands,
    +0 and -0 included, the second). Branches here, which one pixel at a time runs faster than
    lane.fmin's select (lanes_math.py uses that)."""
    if a != a:
        return b
    if b != b:
        return a
    return a if a < b else b


@numba.njit(inline="always", **lane.OPTIONS)
def fmax(a, b):
    """``max`` of floats: IEEE maxNum as np.fmax (see :func:`fmin`)."""
    if a != a:
        return b
    if b != b:
        return a
    return a if a > b else b


@njit
def clamp(x, lo, hi):
    """``min(max(x, lo), hi)`` (NaN x gives lo)."""
    return fmin(fmax(x, lo), hi)


@njit
def sign(x):
    """1, -1 or 0; sign(-0.0) = +0.0, sign(NaN) = 0."""
    if x > _ZERO:
        return _ONE
    if x < _ZERO:
        return _MONE
    return _ZERO


@njit
def fract(x):
    return F32(x - np.floor(x))


@njit
def mod(x, y):
    """``x - y * floor(x / y)`` in float32."""
    return F32(x - F32(y * np.floor(F32(x / y))))


@njit
def step(edge, x):
    return _ONE if x >= edge else _ZERO


@njit
def smoothstep(e0, e1, x):
    t = clamp(F32(F32(x - e0) / F32(e1 - e0)), _ZERO, _ONE)
    return F32(t * F32(t * F32(_THREE - F32(_TWO * t))))


@njit
def smoothstep_scaled(e0, e1, x, k):
    """k * smoothstep(e0, e1, x) in Mesa's order, (t*k) * (t*(3-2t)) (Runtime.smoothstep_scaled);
    k is a constant with no zero component (nir_fold.smoothstep_products)."""
    t = clamp(F32(F32(x - e0) / F32(e1 - e0)), _ZERO, _ONE)
    return F32(F32(t * k) * F32(t * F32(_THREE - F32(_TWO * t))))


@njit
def inversesqrt(x):
    return F32(_ONE / np.sqrt(x))


@njit
def daz(x):
    """A subnormal float32 as a zero of its sign (llvmpipe's DAZ, lane.daz)."""
    return lane.daz(x)


@njit
def mix_fast(x, y, a):
    """nir_lower_flrp's ``x + a*(y-x)`` in every lane, a weight of 0 or 1 included (Runtime.mix,
    form "fast"; the "select" form is builtin_calls.mix_call's)."""
    return F32(x + F32(a * F32(y - x)))


# -- ints ------------------------------------------------------------------------------------
@njit
def idiv(a, b):
    """int ``/``: truncation; x / 0 = 0; INT_MIN / -1 = INT_MIN (llvmpipe)."""
    if b == 0:
        return I32(0)
    a64 = np.int64(a)
    b64 = np.int64(b)
    q = abs(a64) // abs(b64)
    if (a64 < 0) != (b64 < 0):
        q = -q
    return I32(q)


@njit
def udiv(a, b):
    """uint ``/``: x / 0 = 0xFFFFFFFF."""
    if b == 0:
        return U32(0xFFFFFFFF)
    return U32(a // b)


@njit
def irem(a, b):
    """int ``%`` at run time: the unsigned remainder of the bit patterns; x % 0 = -1."""
    au = U32(a)
    bu = U32(b)
    if bu == 0:
        return I32(-1)
    return I32(U32(au % bu))


@njit
def urem(a, b):
    if b == 0:
        return U32(0xFFFFFFFF)
    return U32(a % b)


@njit
def irem_const(a, b):
    """int ``%`` folded by Mesa (both operands constant): the C remainder; x % 0 = -1."""
    if b == 0:
        return I32(-1)
    a64 = np.int64(a)
    b64 = np.int64(b)
    r = abs(a64) % abs(b64)
    return I32(-r if a64 < 0 else r)


@njit
def ishl(a, n):
    """int ``<<`` on the unsigned bits, count mod 32."""
    return I32(U32(U32(a) << U32(np.int64(n) & 31)))


@njit
def ishr(a, n):
    """int ``>>``: arithmetic, count mod 32."""
    return I32(a >> I32(np.int64(n) & 31))


@njit
def ushl(a, n):
    return U32(a << U32(np.int64(n) & 31))


@njit
def ushr(a, n):
    return U32(a >> U32(np.int64(n) & 31))


@njit
def iabs(a):
    return I32(abs(np.int64(a)))  # abs(INT_MIN) wraps to INT_MIN


@njit
def isign(a):
    return I32(1) if a > 0 else (I32(-1) if a < 0 else I32(0))


# -- conversions -----------------------------------------------------------------------------
@njit
def to_int(x):
    """``int(float)``: truncation; NaN, +-Inf and out of range give INT_MIN (cvttps2dq)."""
    t = np.trunc(np.float64(x))
    if t >= -2147483648.0 and t < 2147483648.0:
        return I32(np.int64(t))
    return _INT_MIN


@njit
def _cvtt_bits(t):
    if t >= -2147483648.0 and t < 2147483648.0:
        return U32(I32(np.int64(t)))
    return U32(0x80000000)


@njit
def to_uint_sse(x):
    """``uint(float)`` as llvmpipe on an x86 CPU without AVX-512 (driver_profile._sse)."""
    xd = np.float64(x)
    if xd >= 2147483648.0:
        return U32(_cvtt_bits(np.trunc(xd - 2147483648.0)) | U32(0x80000000))
    return _cvtt_bits(np.trunc(xd))


@njit
def to_uint_avx512(x):
    t = np.trunc(np.float64(x))
    if t >= 0.0 and t < 4294967296.0:
        return U32(np.int64(t))
    return U32(0xFFFFFFFF)


@njit
def to_uint_arm64(x):
    xd = np.float64(x)
    if xd != xd:
        return U32(0)
    t = np.trunc(xd)
    if t <= 0.0:
        return U32(0)
    if t >= 4294967295.0:
        return U32(0xFFFFFFFF)
    return U32(np.int64(t))


@njit
def float_bits_to_int(x):
    return I32(bits(x))


@njit
def float_bits_to_uint(x):
    return bits(x)


@njit
def int_bits_to_float(i):
    return from_bits(U32(i))


@njit
def uint_bits_to_float(u):
    return from_bits(u)


# -- llvmpipe's transcendentals --------------------------------------------------------------
@njit
def _wrap(v):
    """int64 -> int32 with two's-complement wrap-around (paddd/psubd)."""
    return np.int64(I32(v))


@njit
def _trig_any(a, fma, which):
    """LlvmpipeMath._sin_cos_reduced/_sin_cos_result for a finite |a| >= 2**29, where the
    conversion may give INT_MIN and the integer steps wrap (lane.trig covers the rest)."""
    ai = np.int64(I32(bits(a)))
    x_abs = lane.daz(from_bits(U32(ai & 0x7FFFFFFF)))
    p = np.float64(F32(x_abs * lane.FOUR_OVER_PI))
    j0 = (
        np.int64(I32(np.int64(p)))
        if (p >= -2147483648.0 and p < 2147483648.0)
        else np.int64(-(2**31))
    )
    emm2_add = _wrap(j0 + 1)
    emm2_and = emm2_add & ~np.int64(1)
    y_10, y2_9 = sin_cos_polynomials(F32(emm2_and), x_abs, fma)
    s = _ZERO
    c = _ZERO
    if which != 1:
        s = y2_9 if (emm2_and & 2) == 0 else y_10
        if ((ai >> 31) ^ (emm2_add >> 2)) & 1:
            s = -s
        s = fmax(fmin(s, _ONE), _MONE)
    if which != 0:
        j2 = _wrap(emm2_and - 2)
        c = y2_9 if (j2 & 2) == 0 else y_10
        if (j2 >> 2) & 1 == 0:
            c = -c
        c = fmax(fmin(c, _ONE), _MONE)
    return s if which == 0 else c if which == 1 else F32(s / c)


@njit
def _trig_call(a, fma, which):
    if lane.trig_in_range(a):
        return lane.trig(a, fma, which)
    if (np.int64(bits(a)) & 0x7FFFFFFF) >= 0x7F800000:
        return _NAN  # NaN or Inf
    return _trig_any(a, fma, which)


@njit
def sin(a, fma):
    return _trig_call(a, fma, 0)


@njit
def cos(a, fma):
    return _trig_call(a, fma, 1)


@njit
def tan(a, fma):
    return _trig_call(a, fma, 2)


@njit
def exp2(x, fma):
    if x != x:
        return _NAN
    return lane.exp2(x, fma)


@njit
def log2(x, fma):
    """lp_build_log2_safe: NaN for x < 0 (after DAZ) and NaN, -Inf for 0, +Inf for +Inf."""
    if x != x:
        return _NAN
    b = np.int64(bits(x))
    if b >= 0x80000000 and (b & 0x7FFFFFFF) >= _FLT_MIN_BITS:
        return _NAN
    return lane.log2(x, fma)


@njit
def pow(x, y, fma):
    """lp_build_pow: exp2(log2(x) * y), 0 where x is 0 after DAZ or NaN (y read with DAZ)."""
    if x != x or (np.int64(bits(x)) & 0x7FFFFFFF) < _FLT_MIN_BITS:
        return _ZERO
    t = F32(log2(x, fma) * lane.daz(y))
    if t != t:
        return _NAN
    return lane.exp2(t, fma)


@njit
def pow_zero(x):
    """``pow(x, +0.0)`` as Mesa rewrites it: 1, but 0 for x == 0 or NaN."""
    return _ZERO if (x == _ZERO or x != x) else _ONE


@njit
def exp(x, fma):
    return exp2(F32(lane.daz(x) * _LOG2E), fma)


@njit
def log(x, fma):
    return F32(log2(x, fma) * _LN2)


# asin, acos, atan and atan(y, x) as Runtime computes them (Mesa's lowerings): llvmpipe_math.lane's
# one-lane functions, which numpy_engine/jit_kernels' `arc` kernel runs over lanes
@njit
def asin(x):
    return lane.arc(x, x, 1)


@njit
def acos(x):
    return lane.arc(x, x, 2)


@njit
def atan(y):
    return lane.arc(y, y, 0)


@njit
def atan2(y, x):
    """Runtime.atan(y, x): Mesa's nir_atan2 (atan(0, 0) = 3*pi/4)."""
    return lane.arc(y, x, 3)


@njit
def sinh(x, fma):
    return F32(_HALF * F32(exp(x, fma) - exp(-x, fma)))


@njit
def cosh(x, fma):
    return F32(_HALF * F32(exp(x, fma) + exp(-x, fma)))


@njit
def tanh(x, fma):
    x = clamp(x, F32(-10.0), F32(10.0))
    e1 = exp(x, fma)
    e2 = exp(-x, fma)
    return F32(F32(e1 - e2) / F32(e1 + e2))


@njit
def asinh(x, fma):
    return F32(sign(x) * log(F32(abs(x) + np.sqrt(F32(F32(x * x) + _ONE))), fma))


@njit
def acosh(x, fma):
    return log(F32(x + np.sqrt(F32(F32(x * x) - _ONE))), fma)


@njit
def atanh(x, fma):
    return F32(_HALF * log(F32(F32(_ONE + x) / F32(_ONE - x)), fma))


@njit
def index(i, n):
    """An array index clamped to [0, n-1] (runtime.Runtime._clamp_index)."""
    return min(max(np.int64(i), 0), n - 1)


@njit
def round_even(x):
    return np.rint(x)


# -- arrays (loops, not slices: numba compiles a slice assignment's broadcasting machinery
#    into every module that uses one, seconds each; these are compiled once and cached) --------
@njit
def acopy(a):
    """A copy of array a (GLSL arrays are values)."""
    out = np.empty(a.size, a.dtype)
    for k in range(a.size):
        out[k] = a[k]
    return out


@njit
def aslice(a, off, n):
    """A copy of a[off:off+n]."""
    out = np.empty(n, a.dtype)
    for k in range(n):
        out[k] = a[off + k]
    return out


@njit
def aset(dst, off, src):
    """dst[off:off+len(src)] = src."""
    for k in range(src.size):
        dst[off + k] = src[k]
    return 0


@njit
def pow_special(y):
    """An exponent Mesa rewrites: 0, 1, 2 or 4, not -0.0 (Runtime.pow, _POW_REWRITTEN)."""
    return (y == _ZERO and bits(y) == 0) or y == _ONE or y == _TWO or y == F32(4.0)


@njit
def pow_uniform(x, y, special, zeros, fma):
    """Runtime.pow with a lane-uniform exponent y: when every component is special
    (`pow_special`), Runtime.pow_const's rewrite (all zeros: 1 everywhere); else the run-time
    pow."""
    if special:
        if zeros:
            return _ONE
        if y == _ONE:
            return x
        if y == _TWO:
            return F32(x * x)
        if y == F32(4.0):
            sq = F32(x * x)
            return F32(sq * sq)
        return pow_zero(x)
    return pow(x, y, fma)


# llvmpipe's loop limiter (gallivm lp_exec_endloop, LP_MAX_TGSI_LOOP_ITERATIONS), as the NumPy
# backend's LaneHelpers.tick counts it: one budget of passes per invocation, shared by every loop,
# in lc[0] (the engine sets it per pixel, or per block in lockstep: 65,535 when verifying, else
# more than any frame can spend); each pass costs 1 when it ends, and lc[lid] is set when the
# budget stopped loop lid.
@numba.njit(inline="always", **lane.OPTIONS)
def tick(lc, n):
    """At the top of pass n, where pass n - 1 ended and costs 1: True when no budget is left
    (the loop stops)."""
    if n == 1:
        return False
    lc[0] -= 1
    return lc[0] <= 0


@numba.njit(inline="always", **lane.OPTIONS)
def limited(lc, lid):
    """The budget stopped loop lid with the pixel still in it."""
    lc[lid] = 1
    return 0


@numba.njit(inline="always", **lane.OPTIONS)
def tick_end(lc):
    """The pass that left a loop (its condition, a break, a return) costs 1."""
    lc[0] -= 1
    return 0


@njit
def loops_limited(lt, lc):
    """Flag in lt (shared by a frame's bands) the loops the budget stopped in lc (one band's)."""
    for k in range(1, lc.size):
        if lc[k]:
            lt[k] = 1
    return 0


class LoopCapError(Exception):
    """A loop of the generated code ran more than transpile.LOOP_CAP passes; args[0] is its id
    (the module's LOOPS gives its file, line and column)."""
