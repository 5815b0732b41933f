"""The llvmpipe math emulation as compiled loops (numba): one pass over the lanes per call.

runtime.LlvmpipeMath makes gallivm's sin/cos/exp2/log2/pow (lp_bld_arit.c) as 30-70 NumPy
operations; on the few hundred lanes of a compacted march loop each costs more than its
arithmetic. These kernels make the same float32 operations, in the same order with the same
roundings, lane by lane in one compiled loop without a branch out of it, which LLVM
vectorises (10-40x less CPU a call at 143 lanes, 6-9x on a whole tile: docs/performance.md,
"Compiled math kernels").

Imported only by backends/numpy_engine/jit.py, which sets numba's cache directory first and decides
when loading them pays (importing numba and loading the machine code from numba's cache take
seconds); nothing else in glslcheck imports numba.

- A fused multiply-add (``llvm.fmuladd``, fused on an FMA CPU) is LLVM's own ``llvm.fma.f32``
  (:func:`_fma`): one rounding, as vfmadd, which runtime._fma32 emulates in float64; without
  FMA it is a float32 multiply then add, as llvmpipe does there. numba compiles without
  fast-math, so nothing else is contracted or reordered.
- DAZ: a subnormal operand of these algorithms reads as a zero of its sign, as in
  LlvmpipeMath (runtime._daz).
- Each kernel first scans its arguments and returns False, writing nothing useful, where some
  lane would give a NaN (the bits of a NaN LLVM makes here need not be the ones NumPy's
  reference writes) or leave the range where the reference's integer conversions cannot
  overflow (sin/cos/tan: |x| >= 2**29); the caller then takes the NumPy path. Every other
  edge (+-0, subnormals, +-Inf where the result is finite or an infinity) is computed here.

:func:`arc` makes the Runtime's own lowerings of atan, atan(y, x), asin and acos (Mesa's, no
fused step) the same way.

Bit for bit against LlvmpipeMath's and the Runtime's reference, both FMA modes:
tests/numpy/test_jit_kernels.py; against llvmpipe itself: tests/gl/test_jit_llvmpipe.py.
"""

from __future__ import annotations

from .numba_cache import use_cache_dir

use_cache_dir()  # numba's cache directory first (here and for scalar.py and lanes_math.py, which import this)

import numba  # noqa: E402
import numpy as np  # noqa: E402
from llvmlite import ir  # noqa: E402
from numba.core import types  # noqa: E402
from numba.extending import intrinsic  # noqa: E402

from . import llvmpipe_fast as lf  # noqa: E402

F32 = np.float32
_OPTS = dict(cache=True, nogil=True, error_model="numpy")  # error_model: x / 0 is IEEE, no exception
_ONE, _MONE, _HALF, _ZERO = F32(1.0), F32(-1.0), F32(0.5), F32(0.0)
_FOPI = F32(lf.FOUR_OVER_PI)
_DP0, _DP1, _DP2 = (F32(v) for v in lf.DP)
# SIN_COS[row, 0] the cosine's polynomial (y_6), SIN_COS[row, 1] the sine's (y2_6)
_C0, _C1, _C2 = (F32(lf.SIN_COS[r, 0, 0]) for r in range(3))
_S0, _S1, _S2 = (F32(lf.SIN_COS[r, 1, 0]) for r in range(3))
_E0, _E1, _E2, _E3, _E4, _E5 = (F32(v) for v in lf.EXP2)
_L0, _L1, _L2, _L3, _L4 = (F32(v) for v in lf.LOG2)
_EXP2_HI, _EXP2_LO = F32(128.0), F32(-126.99999)
_INF = F32(np.inf)
_ABS = 0x7FFFFFFF
_MIN_NORMAL_BITS = 0x00800000
_INF_BITS = 0x7F800000
_SIN_MAX_BITS = 0x4E000000  # |x| < 2**29: j = int(|x| * 4/pi) + 1 stays far from int32 overflow


@intrinsic
def _fma(typingctx, a, b, c):
    """float32 ``a*b + c`` rounded once: LLVM's llvm.fma.f32 (vfmadd on an FMA CPU, a correctly
    rounded libm fmaf elsewhere)."""
    sig = types.float32(types.float32, types.float32, types.float32)

    def codegen(context, builder, signature, args):
        f = ir.FloatType()
        fn = builder.module.declare_intrinsic("llvm.fma", [f], fnty=ir.FunctionType(f, [f, f, f]))
        return builder.call(fn, args)
    return sig, codegen


@intrinsic
def _bits(typingctx, x):
    """The bits of float32 ``x`` as uint32."""
    def codegen(context, builder, signature, args):
        return builder.bitcast(args[0], ir.IntType(32))
    return types.uint32(types.float32), codegen


@intrinsic
def _float(typingctx, u):
    """The float32 whose bits are uint32 ``u``."""
    def codegen(context, builder, signature, args):
        return builder.bitcast(args[0], ir.FloatType())
    return types.float32(types.uint32), codegen


@numba.njit(inline="always", **_OPTS)
def _mad(a, b, c, fma):
    """``llvm.fmuladd`` of float32 scalars, as LlvmpipeMath.mad."""
    if fma:
        return _fma(a, b, c)
    return F32(F32(a * b) + c)


@numba.njit(inline="always", **_OPTS)
def _daz(x):
    """A subnormal x as a zero of its sign (MXCSR.DAZ), as runtime._daz."""
    if (np.int64(_bits(x)) & _ABS) < _MIN_NORMAL_BITS:
        return _float(_bits(x) & np.uint32(0x80000000))
    return x


@numba.njit(inline="always", **_OPTS)
def _trig(a, fma, which):
    """LlvmpipeMath._sin (``which`` 0), _cos (1) or _tan (2, sin over cos of one reduction) of
    one float32 lane ``a``, |a| < 2**29 and finite (the caller's check)."""
    ai = np.int64(_bits(a))
    x_abs = _daz(_float(np.uint32(ai & _ABS)))
    j_add = np.int64(np.int32(F32(x_abs * _FOPI))) + 1  # in range: cvttps2dq truncates so
    j = j_add & ~np.int64(1)
    y_2 = F32(j)
    x_1 = _mad(y_2, _DP0, x_abs, fma)
    x_2 = _mad(y_2, _DP1, x_1, fma)
    x_3 = _mad(y_2, _DP2, x_2, fma)
    z = F32(x_3 * x_3)
    y_6 = F32(_mad(_mad(z, _C0, _C1, fma), z, _C2, fma) * z)
    y2_6 = F32(_mad(_mad(z, _S0, _S1, fma), z, _S2, fma) * z)
    y_10 = F32(F32(F32(y_6 * z) - F32(z * _HALF)) + _ONE)
    y2_9 = _mad(y2_6, x_3, x_3, fma)
    s = _ZERO
    c = _ZERO
    if which != 1:  # sin: bit 1 of j picks the polynomial; the sign bit is x's flipped by bit 2 of j_add
        s = y2_9 if (j & 2) == 0 else y_10
        if ((ai >> 31) ^ (j_add >> 2)) & 1:
            s = -s
        s = min(max(s, _MONE), _ONE)  # lp_build_clamp (no NaN here)
    if which != 0:  # cos: the same of j - 2, the sign bit set where its bit 2 is clear
        j2 = j - 2
        c = y2_9 if (j2 & 2) == 0 else y_10
        if (j2 >> 2) & 1 == 0:
            c = -c
        c = min(max(c, _MONE), _ONE)
    return s if which == 0 else c if which == 1 else F32(s / c)


@numba.njit(inline="always", **_OPTS)
def trig_in_range(a):
    """True where :func:`_trig` computes LlvmpipeMath's result for ``a``: |a| < 2**29 and
    finite (a NaN or an Inf has larger bits)."""
    return (np.int64(_bits(a)) & _ABS) < _SIN_MAX_BITS


@numba.njit("boolean(float32[::1], float32[::1], boolean, int64)", **_OPTS)
def trig(a, out, fma, which):
    """:func:`_trig` of every lane of ``a`` into ``out`` (same size); False (declined) where some
    |x| >= 2**29 or is not finite."""
    n = a.size
    for k in range(n):
        if not trig_in_range(a[k]):
            return False
    for k in range(n):
        out[k] = _trig(a[k], fma, which)
    return True


@numba.njit(inline="always", **_OPTS)
def _exp2(x, fma):
    """LlvmpipeMath._exp2 of one lane, x not NaN: clamp, 2**floor(x) from the exponent bits
    times the degree-5 polynomial of the fraction."""
    x = min(max(_daz(x), _EXP2_LO), _EXP2_HI)
    ipart = F32(np.floor(x))
    fpart = F32(x - ipart)
    x2 = F32(fpart * fpart)
    odd = _mad(x2, _mad(x2, _E5, _E3, fma), _E1, fma)
    even = _mad(x2, _mad(x2, _E4, _E2, fma), _E0, fma)
    p = _mad(odd, fpart, even, fma)
    return F32(_float(np.uint32((np.int64(ipart) + 127) << 23)) * p)


@numba.njit(inline="always", **_OPTS)
def _log2(x, fma):
    """LlvmpipeMath._log2 of one lane, x positive (or a zero, or subnormal) and not NaN: the
    exponent plus y * P(y*y), y = (m-1)/(m+1); -Inf for a zero after DAZ, +Inf for +Inf."""
    b = np.int64(_bits(x))
    if (b & _ABS) < _MIN_NORMAL_BITS:
        return -_INF
    if b == _INF_BITS:
        return _INF
    logexp = F32(((b & _INF_BITS) >> 23) - 127)
    mant = _float(np.uint32((b & 0x007FFFFF) | 0x3F800000))
    y = F32(F32(mant - _ONE) / F32(mant + _ONE))
    w = F32(y * y)
    x2 = F32(w * w)
    even = _mad(x2, _mad(x2, _L4, _L2, fma), _L0, fma)
    odd = _mad(x2, _L3, _L1, fma)
    return _mad(y, _mad(odd, w, even, fma), logexp, fma)


@numba.njit("boolean(float32[::1], float32[::1], float32[::1], boolean, int64)", **_OPTS)
def explog(x, y, out, fma, which):
    """LlvmpipeMath._exp2 (``which`` 0), _log2 (1) of ``x``, or _pow (2) of ``x`` and ``y``, into
    ``out``; x and y have out's size or one element (broadcast). False (declined) where some
    lane's result would be a NaN: exp2 of NaN, log2 of a negative number or NaN, pow where
    log2(x) * y is NaN (x < 0; 0 * Inf)."""
    n = out.size
    nx = x.size
    ny = y.size
    for k in range(nx):
        b = np.int64(_bits(x[k]))
        if (b & _ABS) > _INF_BITS:
            if which != 2:
                return False  # NaN (pow: x NaN gives 0, below)
        elif which != 0 and b >= 0x80000000 and (b & _ABS) >= _MIN_NORMAL_BITS:
            return False  # a negative number: log2 is NaN
    if which == 0:
        for k in range(n):
            out[k] = _exp2(x[k], fma)
    elif which == 1:
        for k in range(n):
            out[k] = _log2(x[k], fma)
    else:  # no exit from this loop, so that LLVM can vectorise it: a NaN is noted and told at the end
        nan = False
        for k in range(n):
            xk = x[k if nx > 1 else 0]
            zero = (np.int64(_bits(xk)) & _ABS) < _MIN_NORMAL_BITS or xk != xk  # x == 0 after DAZ, or NaN
            t = F32(_log2(_ONE if zero else xk, fma) * y[k if ny > 1 else 0])
            nan |= t != t and not zero
            r = _exp2(_ZERO if t != t else t, fma)
            out[k] = _ZERO if zero else r
        return not nan
    return True


# ---------------------------------------------------------------- atan, atan2, asin, acos
# Runtime._nir_atan, Runtime.atan's two-argument form and Runtime._asin_expr (Mesa's own
# lowerings, not gallivm's: plain float32 operations, no fused step), step by step per lane
_HALF_PI = F32(np.pi / 2)
_A0, _A1, _A2, _A3, _A4, _A5 = (F32(v) for v in (0.9999793128310355, -0.3326756418091246, 0.1938924977115610,
                                                  -0.1173503194786851, 0.0536813784310406, -0.0121323213173444))
_MTWO, _QUARTER, _BIG = F32(-2.0), F32(0.25), F32(1e18)
_ASIN_C1 = F32(F32(np.pi / 4) - _ONE)  # M_PI_4f - 1.0f, rounded twice as in C
_ASIN_P = (F32(0.086566724), F32(-0.03102955))  # asin's p0, p1
_ACOS_P = (F32(0.08132463), F32(-0.02363318))


@numba.njit(inline="always", **_OPTS)
def _fmin(a, b):
    """np.fmin of float32 scalars: a NaN operand yields the other; of equal operands the second."""
    if a != a:
        return b
    if b != b:
        return a
    return a if a < b else b


@numba.njit(inline="always", **_OPTS)
def _fmax(a, b):
    """np.fmax of float32 scalars: a NaN operand yields the other; of equal operands (+0 and -0
    too) the second, as np.fmax."""
    if a != a:
        return b
    if b != b:
        return a
    return a if a > b else b


@numba.njit(inline="always", **_OPTS)
def _sign(v):
    """Runtime.sign of a float32: 1, -1, else +0 (zeros and NaN)."""
    return _ONE if v > _ZERO else _MONE if v < _ZERO else _ZERO


@numba.njit(inline="always", **_OPTS)
def _atan(v):
    """Runtime._nir_atan of one lane ``v`` (already read with DAZ): never a NaN."""
    a = abs(v)
    x = _daz(F32(_fmin(a, _ONE) / _fmax(a, _ONE)))
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
    t = _daz(F32(t + F32(F32(p * _A5) * x2)))  # x^11's term reassociated, as in _nir_atan
    if _ONE < a:
        t = F32(F32(F32(t * _MTWO) + _HALF_PI) + t)
    return F32(t * _sign(v))


@numba.njit(inline="always", **_OPTS)
def _atan2(y, x):
    """Runtime.atan(y, x) of one lane: y over x scaled, the half-plane flipped, atan of the
    quotient (atan(0, 0) = 3*pi/4, as llvmpipe's lowering)."""
    y = _daz(y)
    x = _daz(x)
    flip = _ZERO >= x
    ax = abs(x)
    s = ax if flip else y
    t = y if flip else ax
    scale = _QUARTER if abs(t) >= _BIG else _ONE
    rcp = F32(_ONE / F32(t * scale))
    tan = _ONE if ax == abs(y) else _daz(F32(abs(F32(s * scale)) * abs(rcp)))
    arc = F32(F32(F32(1.0 if flip else 0.0) * _HALF_PI) + _atan(tan))
    return -arc if _fmin(y, rcp) < _ZERO else arc


@numba.njit(inline="always", **_OPTS)
def _asin_expr(x, p0, p1):
    """Runtime._asin_expr of one lane, |x| <= 1 (else NaN: the caller's check)."""
    a = abs(x)
    poly = F32(_HALF_PI + F32(a * F32(_ASIN_C1 + F32(a * F32(p0 + F32(a * p1))))))
    return F32(_sign(x) * F32(_HALF_PI - F32(np.sqrt(F32(_ONE - a)) * poly)))


@numba.njit(inline="always", **_OPTS)
def _arc(x, y, which):
    """atan (``which`` 0), asin (1), acos (2) of ``x``, or atan2 (3) of ``y`` = ``x`` and ``x`` = ``y``."""
    if which == 0:
        return _atan(_daz(x))
    if which == 1:
        return _asin_expr(_daz(x), _ASIN_P[0], _ASIN_P[1])
    if which == 2:
        return F32(_HALF_PI - _asin_expr(_daz(x), _ACOS_P[0], _ACOS_P[1]))
    return _atan2(x, y)


@numba.njit("boolean(float32[::1], float32[::1], float32[::1], boolean, int64)", **_OPTS)
def arc(x, y, out, fma, which):
    """Runtime.atan (``which`` 0), asin (1), acos (2) of ``x``, or atan (3) of ``x`` over ``y``
    (GLSL's atan(y, x) with its y first), into ``out``; x and y have out's size or one element,
    as for :func:`explog`. ``fma`` is unused (the same signature as explog: none of these has a
    fused step). False (declined) for asin or acos where some |x| > 1 or x is NaN (the result
    would be a NaN); atan and atan2 never give one."""
    n = out.size
    nx = x.size
    ny = y.size
    if which == 1 or which == 2:
        for k in range(nx):
            if not abs(x[k]) <= _ONE:
                return False
    for k in range(n):
        out[k] = _arc(x[k if nx > 1 else 0], y[k if ny > 1 else 0], which)
    return True


# ---------------------------------------------------------------- mix
@numba.njit("boolean(float32[:, ::1], float32[:, ::1], float32[:, ::1], float32[:, ::1])", **_OPTS)
def mix(x, y, a, out):
    """Runtime.mix's "fast" form (nir_lower_flrp's ``x + a*(y - x)``, a weight of exactly 1 or 0
    a select of y or x) into ``out``, of shape (components, lanes); x, y and a have out's
    number of rows or one, and its number of columns or one (broadcast, as a vec3 constant of
    shape (3, 1) or a float weight against vec3 lanes: nothing is copied to broadcast). False
    (declined) where an arithmetic lane gives a NaN (its bits are NumPy's to choose; a NaN that
    is selected is copied, the same bits)."""
    rows, cols = out.shape
    nan = False
    for i in range(rows):
        xi = i if x.shape[0] > 1 else 0
        yi = i if y.shape[0] > 1 else 0
        ai = i if a.shape[0] > 1 else 0
        for k in range(cols):
            xk = x[xi, k if x.shape[1] > 1 else 0]
            yk = y[yi, k if y.shape[1] > 1 else 0]
            ak = a[ai, k if a.shape[1] > 1 else 0]
            t = F32(xk + F32(ak * F32(yk - xk)))  # computed in every lane, then selected: no branch,
            one = ak == _ONE  # so that LLVM vectorises the loop
            zero = ak == _ZERO
            nan |= (t != t) & ~one & ~zero
            out[i, k] = yk if one else xk if zero else t
    return not nan
