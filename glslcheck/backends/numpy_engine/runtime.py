"""The NumPy runtime that transpiled GLSL ES 3.00 shaders call.

This module owns the representation of GLSL values over many pixels ("lanes") and every
GLSL ES 3.00 operator and built-in function (spec chapter 5 and chapter 8, texture lookups
excepted) with the numeric behaviour of the reference GPU, Mesa llvmpipe (Mesa 22.3.6,
LLVM 15). The transpiler emits readable Python such as::

    rt = Runtime("float32")
    with rt.errstate():
        n = rt.normalize(rt.sub(p, c))
        k = rt.max_(rt.dot(n, l), rt.const_float(0.0))

Representation
==============

A GLSL value evaluated over ``L`` lanes is a NumPy array whose LAST axis is the lane axis.
The lane axis has size ``L`` or size 1; size 1 means "the same in every lane" (uniforms,
constants) and broadcasts against any lane count. The number of dimensions tells the
GLSL shape apart, so a value never needs a type tag:

==================  =======================  =============================================
GLSL type           array shape              notes
==================  =======================  =============================================
float/int/uint/bool ``(L,)``                 1-D: a scalar
vecK / ivecK ...    ``(K, L)``               ``v[i]`` is component i (a scalar)
matCxR              ``(C, R, L)``            column-major: ``m[c]`` is column c, a vecR
T[M] (array)        ``(M,) + shape(T)``      stacked with a leading array axis
struct              :class:`Struct`          named fields, each a value as above
S[M] (array of s.)  :class:`Struct`          struct-of-arrays: every field has leading M
==================  =======================  =============================================

Element dtypes: ``float`` is the runtime's float dtype (:attr:`Runtime.F`), ``int`` is
``np.int32``, ``uint`` is ``np.uint32``, ``bool`` is ``np.bool_``.

Because scalars are 1-D and vectors 2-D, NumPy broadcasting *is* GLSL's scalar-vector and
scalar-matrix broadcasting: ``add(s, v)`` with ``s.shape == (L,)`` and ``v.shape == (3, L)``
just works. Component-wise vector/matrix operations are plain ufuncs; the linear-algebra
products have their own functions (:meth:`Runtime.mat_mul_vec`, :meth:`Runtime.vec_mul_mat`,
:meth:`Runtime.mat_mul_mat`) because the transpiler knows the static types.

Value semantics. The runtime never writes into an array it was given: every function returns
a new array (or, where the result equals an input, the input itself). GLSL assignment of
arrays and structs copies; with immutable arrays a Python assignment that shares the array is
already a copy. Masked writes (:meth:`Runtime.assign`, :meth:`Runtime.assign_swizzle`,
:meth:`Runtime.assign_index`, :meth:`Runtime.assign_field`) return the new value; the
transpiler rebinds the variable: ``x = rt.assign(x, new, mask)``.

Masks. Divergent control flow is executed for all lanes; a mask is a bool array of shape
``(L,)`` or ``(1,)`` (or ``None`` meaning "all lanes") and a masked write keeps the old value
in inactive lanes. A masked write always returns the full broadcast lane count.

Constants. Python numbers accepted by the runtime are converted to the type of the other
operand, but the transpiler should create literals with :meth:`Runtime.const_float`,
:meth:`Runtime.const_int`, :meth:`Runtime.const_uint`, :meth:`Runtime.const_bool`
(arrays of shape ``(1,)``) so the dtype is explicit.

Precision
=========

``Runtime("float32")`` (default) is highp: IEEE binary32, every operation rounded to float32.
``Runtime("float16")`` emulates mediump: values are stored as float16 and NumPy evaluates each
float16 operation in float32 and rounds the result to float16 (one rounding per GLSL
operation, like a GPU with 16-bit ALUs; ints stay 32-bit, as on every desktop GPU).
``Runtime("float64")`` is a reference mode for measuring error. Every function keeps floats in
the active dtype: internal constants are created in that dtype, so a float32 input never
comes back float64 and float16 stays float16. ``floatBitsToInt`` & co. always reinterpret
float32 bits (GLSL defines them on highp floats); in float16 mode the result of
``intBitsToFloat`` is rounded to float16.

Warnings. Division by zero, NaN and overflow are ordinary results on a GPU; the caller wraps
the whole render in ``with rt.errstate():`` (``np.errstate(all="ignore")``) instead of each
call paying for it.

Numeric semantics (measured on llvmpipe)
========================================

Measured by rendering 1x1 ``#version 300 es`` fragment shaders with uniform inputs (so the
GLSL compiler cannot constant-fold) into an RGBA32I target, reading bits back exactly
(``tests/numpy/test_runtime_gl.py`` repeats all of these). "spec" is GLSL ES 3.00.

=================================  =====================  =================  ================
case                               spec                   llvmpipe           ours
=================================  =====================  =================  ================
pow(-2, 2)                         undefined (x < 0)      NaN                NaN
pow(0, 0), pow(0, -1), pow(0, y)   undefined (x=0, y<=0)  0 (any y)          0
pow(NaN, y)                        NaN                    0                  0
pow(inf, 0), pow(1, inf)           NaN (0*inf)            NaN                NaN
pow(-0.5, 2.0) (literal exponent)  undefined (x < 0)      0.25 (x*x)         0.25 ``pow_const``
pow(x, 1.0 | 4.0 | 0.0), x < 0     undefined              x, x^4, 1          same ``pow_const``
pow(NaN, 0.0), pow(0, 0.0)         undefined              0                  0
pow(x<0, 3.0 | 0.5 | -0.0 | 8.0)   undefined              NaN (no rewrite)   NaN
pow(1.0, inf) (literal base 1)     NaN                    1                  1  ``pow_one``
normalize(vec3(0))                 0/0                    NaN                NaN
normalize(float 0.0)               0/0                    0 (= sign(x))      0
sqrt(-1)                           undefined              NaN                NaN
log(0), log2(0)                    undefined              -inf               -inf
log(-1)                            undefined              NaN                NaN
inversesqrt(0)                     undefined              +inf               +inf
smoothstep(1, 1, x)                undefined              0 (x<=1), 1 (x>1)  same (formula)
smoothstep(2, 1, 1.5)              undefined              0.5                0.5 (formula)
mod(-7.5, 2)                       x - y*floor(x/y)       0.5                0.5
mod(1, 0), mod(inf, 1)             formula                NaN                NaN
int(-7) / 2                        -3 (truncation)        -3                 -3
int / 0 (any sign)                 undefined              0                  0
INT_MIN / -1                       undefined              INT_MIN            INT_MIN
uint / 0u, uint % 0u               undefined              0xFFFFFFFF         0xFFFFFFFF
-7 % 2 (run time)                  undefined (negative)   1 (!)              1   ``rem``
7 % -2, -7 % -3 (run time)         undefined              7, -7              same
-7 % 2 (constant-folded)           undefined              -1 (C remainder)   -1  ``rem_const``
x % 0 (int)                        undefined              -1                 -1
2147483647 + 1                     wraps                  INT_MIN            INT_MIN
1 << 32, 1 << 33, -8 >> 33         undefined (>= 32)      1, 2, -4 (n & 31)  same
clamp(0.5, 1, 0)                   min(max(x,lo),hi)      0                  0
clamp(NaN, 0, 1)                   undefined              0                  0
min/max(NaN, 1), (1, NaN)          undefined              1 (IEEE fmin/fmax) 1
int(3.99), int(-3.99)              trunc                  3, -3              3, -3
int(NaN), int(+-inf), int(+-3e9)   undefined              INT_MIN            INT_MIN
uint(-1.0), uint(NaN), uint(5e9)   undefined              the CPU decides    the driver's model
uint(-0.5)                         undefined              0 (trunc)          0
round(2.5), round(-2.5), round(.5) impl.-defined .5 dir.  2, -2, 0 (even)    even
roundEven(2.5), roundEven(-2.5)    2, -2                  2, -2              2, -2
1e38 * 10                          inf                    +inf               +inf
0 * inf, 0/0                       NaN                    NaN                NaN
atan(0, 0), atan(0, -0)            undefined              3*pi/4 (2.3561912) 3*pi/4
atan(-0, -1)                       -pi                    -pi                -pi
atan(inf, inf)                     pi/4                   0.78539485         nir formula
atan(NaN), atan(-0)                NaN, -0                0, +0 (fsign)      0, +0
atan(NaN, 1), atan(1, NaN)         NaN                    0, 0               0, 0
atan(NaN, -1), atan(NaN, -inf)     NaN                    pi/2               pi/2
fract(-0.25), fract(-1e-9)         x - floor(x)           0.75, 1.0          0.75, 1.0
fract(inf)                         NaN                    NaN                NaN
sign(-0.0), sign(NaN)              0                      +0, 0              +0, 0
step(0, NaN)                       undefined              0                  0
tanh(+-100)                        +-1                    +-1                +-1
sinh(100), cosh(100)               inf                    inf                inf
asin(2), acos(2), acosh(0.5)       undefined              NaN                NaN
atanh(1)                           undefined              +inf               +inf
packUnorm2x16(NaN)                 undefined              0                  0
packSnorm2x16(NaN)                 undefined              -32767 (0x8001)    -32767
mix(NaN, y, 1.0) (constant 1.0)    NaN                    y (folded)         y  ``fmul``
NaN * vec3(1, 0, 0) (constant)     NaN everywhere         (NaN, 0, 0)        same ``fmul``
cos(1e10), sin(1e10)               cos, sin               1, -1 (clamped)    1, -1
=================================  =====================  =================  ================

Literal operands (the rows marked ``pow_const`` / ``pow_one``, measured with a uniform base
and a literal exponent): Mesa's compiler rewrites ``pow`` before run time when an exponent
component is 1.0, 2.0, 4.0 or +0.0 (vector exponents per component), and ``pow(1.0, y)`` to 1;
the transpiler emits those forms when the checker folds the operand to a constant. Mesa also
propagates constants through plain local variables, which the transpiler does not follow.

Formulas (each matched bit-for-bit on 65536 random inputs unless a ULP figure is given):
no fused multiply-add is formed for GLSL arithmetic (``a*b+c`` rounds twice); ``x/y`` (also by
a constant) and ``sqrt`` are correctly rounded; ``inversesqrt(x) = 1/sqrt(x)``;
``length = sqrt(dot)``; ``dot`` sums RIGHT to left (``x0*y0 + (x1*y1 + x2*y2)``, 60,000 random
vec3/vec4 pairs; Mesa's factoring of products that share an operand, ``dot(v, v.zxy)``, is not
copied); ``mat * vec`` sums its columns left to right; ``normalize(v) = v *
inversesqrt(dot(v, v))``; ``mix = x*(1-a) + y*a``; ``smoothstep: t*(t*(3-2t))``;
``cross = a.yzx*b.zxy - a.zxy*b.yzx``; ``mod`` as the spec.

Transcendentals, float32 (:class:`LlvmpipeMath`, bit-exact with llvmpipe on ~125,000 inputs
each, subnormal, huge (cos(1e10) = 1) and non-finite ones included:
``tests/gl/test_llvmpipe_math.py``): ``sin``/``cos`` are gallivm's ``lp_build_sin_or_cos``
(Cephes sinf/cosf: Cody-Waite reduction by pi/4, two polynomials, clamp to [-1, 1]; Mesa
src/gallium/auxiliary/gallivm/lp_bld_arit.c), ``tan = sin/cos``; ``exp2`` is ``lp_build_exp2``
(clamp to [-126.99999, 128], 2**floor times a degree-5 polynomial), ``log2`` is
``lp_build_log2_safe`` (exponent + odd polynomial in (m-1)/(m+1)), ``pow = exp2(log2(x)*y)``
with 0 where x == 0 or NaN (``lp_build_pow``), ``exp(x) = exp2(x*log2(e))``,
``log(x) = log2(x)*ln(2)`` (``lp_build_exp``, ``lp_build_log_safe``); ``sinh cosh tanh asinh
acosh atanh``: Mesa's GLSL formulas over those (``tanh(NaN) = -1``: its clamp(x, -10, 10)
takes NaN to -10); ``asin``/``acos``: Mesa's GLSL formula ``sign(x)*(pi/2 - sqrt(1-|x|)*(pi/2
+ |x|*(pi/4-1 + |x|*(p0 + |x|*p1))))`` with float32 constants (builtin_functions.cpp);
``atan``/``atan(y, x)``: Mesa 22.3's ``nir_atan``/``nir_atan2`` (nir_builtin_builder.c: six
power terms summed left to right, the last one reassociated by nir_opt_algebraic), bit-exact;
``mix``: the formula nir_lower_flrp picks for the call (:meth:`Runtime.mix`); Mesa's
reassociations of sums and products: :mod:`nir_fold`. CPU dependence: gallivm builds these polynomials with
``llvm.fmuladd``, fused on a CPU with FMA (Haswell and later; this machine: AVX2 + FMA, no
AVX-512) and not fused without: :data:`HOST_FMA` follows this CPU, ``Runtime(fma=...)`` picks
either; the two differ on ~1% of sin arguments. AVX-512 should not change these results (the
same IEEE operations, wider; not measured: no AVX-512 machine here). ``precision="float64"``
keeps NumPy's libm: it is the accuracy reference, not an emulation.

Mesa's compiler folds constants (``fold_constants``, on for transpiled shaders, see
:meth:`Runtime.fmul`): ``x * 0.0`` is 0 when the zero is a compile-time constant, even for
x = NaN or Inf, per component (``NaN * vec3(1, 0, 0)`` is (NaN, 0, 0); ``dot(vec3(NaN, 1, 2),
vec3(0, 1, 1))`` is 3; ``mix(NaN, y, 1.0)`` is y); two constants multiply out (0 * inf =
NaN); ``x + 0.0`` is x and ``0.0 - x`` is -x, keeping the sign of a zero (:meth:`Runtime.fadd`,
float32 only); ``pow`` with a constant exponent 0, 1, 2 or 4 is rewritten (0 gives 1 there). A value
counts as constant when it is the same in every lane and is not a uniform input (uniforms are
read-only arrays): a value computed from uniforms that happens to be 0 is taken for a constant
too, the one approximation.

Subnormals: llvmpipe runs with x86 FTZ/DAZ (lp_build_fpstate_set_denorms_zero), so subnormal
inputs and results are zero there (``atan(0, 1e-45)`` is 3*pi/4 on llvmpipe). The built-ins
above flush their operands and the intermediate results that can be subnormal
(:func:`daz`); plain GLSL arithmetic keeps subnormals here (flushing every result would cost
a pass per operation): ``1e-20 * 1e-20`` is 0 there and 1e-40 here, which only shows when a
later product scales it back up.

Derivatives (measured): llvmpipe computes FINE derivatives on 2x2 quads whose lower-left
pixel has even x and even y (gl_FragCoord space): ``dFdx`` at (x, y) is
``v(x|1, y) - v(x&~1, y)`` -- different in the two rows of a quad -- and ``dFdy`` is
``v(x, y|1) - v(x, y&~1)``; ``fwidth = |dFdx| + |dFdy|``. See :meth:`Runtime.dFdx`.
"""

from __future__ import annotations

import numpy as np

from ...base.precision import check_precision
from ..driver_profile import FLOAT_TO_UINT, host_model
from .llvmpipe_reference import HOST_FMA, LlvmpipeMath
from .runtime_common import CommonFunctions
from .runtime_operators import ArithmeticOps
from .runtime_transcendental import TranscendentalFunctions
from .runtime_values import ValueOps
from .textures import TextureFunctions


class Runtime(ValueOps, ArithmeticOps, TranscendentalFunctions, CommonFunctions, TextureFunctions):
    """GLSL ES 3.00 operators and built-ins over lane arrays, in one float precision.

    ``Runtime(precision)`` with precision ``"float32"`` (highp, default), ``"float16"``
    (mediump emulation) or ``"float64"`` (reference). Instantiate once per render.
    """

    def __init__(
        self, precision: str = "float32", float_to_uint: str | None = None, fma: bool | None = None
    ) -> None:
        self.F = np.dtype(check_precision(precision)).type  # "float32" is np.float32's name
        self.precision = precision
        # how uint(x) treats negatives, NaN and x >= 2**32 (undefined; the CPU decides on
        # llvmpipe): a model of glslcheck/backends/driver_profile.py, by default this machine's
        self.float_to_uint = float_to_uint or host_model()
        if self.float_to_uint not in FLOAT_TO_UINT:
            raise ValueError(f"float_to_uint must be one of {sorted(FLOAT_TO_UINT)}")
        F = self.F
        # float32 (highp) evaluates sin/cos/exp2/log2/pow with llvmpipe's own algorithms;
        # float16 and float64 keep NumPy's (float64 is the accuracy reference).
        self.lp = LlvmpipeMath(HOST_FMA if fma is None else fma) if F is np.float32 else None
        # Mesa's constant folding (fmul, dot, mix, pow): on for transpiled shaders, whose
        # uniform inputs are read-only arrays (see fmul); off for direct calls, which get IEEE.
        self.fold_constants = False
        self._dtype = np.dtype(F)  # `x.dtype is self._dtype`: the fast test in _f
        self._0 = F(0.0)
        self._1 = F(1.0)
        self._2 = F(2.0)
        self._3 = F(3.0)
        self._half = F(0.5)

    # NumPy's own ufuncs, which the transpiler calls where it knows every operand is an array
    # of one float dtype (GLSL float operands always are): the built-in's exact operation,
    # without a Python frame and the operand coercions of the methods below (`min_`, `abs`...)
    # on every call. A ufunc is no descriptor, so `rt.np_fmin` is np.fmin itself.
    np_where = staticmethod(np.where)  # `c ? a : b` of one array each (select: also structs)
    np_fmin = np.fmin  # min: a NaN operand yields the other (IEEE minNum, as llvmpipe; min_)
    np_fmax = np.fmax
    np_abs = np.abs
    np_sqrt = np.sqrt
    np_floor = np.floor
    np_ceil = np.ceil
    np_trunc = np.trunc
