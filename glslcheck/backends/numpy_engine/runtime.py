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
(:func:`_daz`); plain GLSL arithmetic keeps subnormals here (flushing every result would cost
a pass per operation): ``1e-20 * 1e-20`` is 0 there and 1e-40 here, which only shows when a
later product scales it back up.

Derivatives (measured): llvmpipe computes FINE derivatives on 2x2 quads whose lower-left
pixel has even x and even y (gl_FragCoord space): ``dFdx`` at (x, y) is
``v(x|1, y) - v(x&~1, y)`` -- different in the two rows of a quad -- and ``dFdy`` is
``v(x, y|1) - v(x, y&~1)``; ``fwidth = |dFdx| + |dFdy|``. See :meth:`Runtime.dFdx`.
"""

from __future__ import annotations

import math
from typing import Any, Iterable

import numpy as np

from ..driver_profile import FLOAT_TO_UINT, float_to_uint, host_fma, host_model
from ...base.precision import check_precision
from . import jit, llvmpipe_fast
from .textures import TextureFunctions

__all__ = ["Runtime", "Struct", "GLSLRuntimeError"]

I32 = np.int32
U32 = np.uint32
BOOL = np.bool_
INT_MIN = -(2**31)

_SWIZZLE_SETS = ("xyzw", "rgba", "stpq")
_SWIZZLE_CACHE: dict[str, tuple[int, ...]] = {}


class GLSLRuntimeError(RuntimeError):
    """A construct the runtime cannot evaluate (for example a texture lookup)."""


def swizzle_indices(sw: str) -> tuple[int, ...]:
    """Component indices of a swizzle string (``"xzy"`` -> ``(0, 2, 1)``); any of xyzw/rgba/stpq."""
    got = _SWIZZLE_CACHE.get(sw)
    if got is None:
        for letters in _SWIZZLE_SETS:
            if all(ch in letters for ch in sw):
                got = tuple(letters.index(ch) for ch in sw)
                break
        else:
            raise ValueError(f"bad swizzle {sw!r}")
        _SWIZZLE_CACHE[sw] = got
    return got


class Struct:
    """A GLSL struct value: a type name and an ordered set of named fields.

    Fields are read as attributes (``s.pos``) or with ``s["pos"]``. A Struct is never modified
    in place by the runtime; :meth:`Runtime.assign_field` returns a new one. An array of structs
    is a Struct whose fields carry a leading array axis (struct-of-arrays).
    """

    __slots__ = ("_name", "_fields")

    def __init__(self, _name: str, _fields: dict[str, Any] | None = None, **fields: Any) -> None:
        object.__setattr__(self, "_name", _name)
        d = dict(_fields or {})
        d.update(fields)
        object.__setattr__(self, "_fields", d)

    def __getattr__(self, key: str) -> Any:
        try:
            return self._fields[key]
        except KeyError:
            raise AttributeError(key) from None

    def __getitem__(self, key: str) -> Any:
        return self._fields[key]

    def __setattr__(self, key: str, value: Any) -> None:
        raise AttributeError("Struct values are immutable; use Runtime.assign_field")

    def __reduce__(self):  # pickled by value (globals travel to render worker processes)
        return (Struct, (self._name, self._fields))

    def replace(self, **changes: Any) -> "Struct":
        d = dict(self._fields)
        d.update(changes)
        return Struct(self._name, d)

    def map(self, fn) -> "Struct":
        return Struct(self._name, {k: fn(v) for k, v in self._fields.items()})

    @property
    def type_name(self) -> str:
        return self._name

    @property
    def fields(self) -> dict[str, Any]:
        return dict(self._fields)

    def __repr__(self) -> str:
        inner = ", ".join(f"{k}={v!r}" for k, v in self._fields.items())
        return f"{self._name}({inner})"


def _lanes_of(*values: Any) -> int:
    n = 1
    for v in values:
        if isinstance(v, np.ndarray) and v.ndim:
            m = v.shape[-1]
            if m != 1:
                if n != 1 and n != m:
                    raise ValueError(f"lane counts differ: {n} vs {m}")
                n = m
        elif isinstance(v, Struct):
            n = max(n, _lanes_of(*v._fields.values()))
    return n


_CONVERTERS = {"float": "to_float", "int": "to_int", "uint": "to_uint", "bool": "to_bool"}


# ---------------------------------------------------------------------------------------------
# llvmpipe's own float32 algorithms (gallivm), step by step.
#
# Mesa 22.3.6 compiles GLSL sin, cos, exp2, log2 (and pow, exp, log built on them) to LLVM IR
# with the code in src/gallium/auxiliary/gallivm/lp_bld_arit.c; the functions below repeat
# each IR instruction in float32 so the NumPy backend gets the same bits (measured bit for bit
# on 400,000 inputs each, subnormals, +-0, +-Inf, NaN and |x| up to 3e38 included:
# tests/numpy/test_llvmpipe_math_gl.py). CPU dependence, recorded where it arises:
#
# - ``lp_build_mad``/``lp_build_fmuladd`` emit ``llvm.fmuladd``, which LLVM fuses into one
#   rounding on a CPU with FMA (x86 FMA3: Haswell and later) and evaluates as a multiply and
#   an add elsewhere. :data:`HOST_FMA` reads the CPU flags; ``Runtime(fma=...)`` overrides.
#   GLSL's own ``a*b + c`` is never fused (llvmpipe does not set NIR's fuse_ffma): only the
#   steps inside these built-ins are.
# - llvmpipe runs shaders with MXCSR DAZ|FTZ (lp_build_fpstate_set_denorms_zero): subnormal
#   operands count as zero inside these algorithms (:func:`_daz`).
# - out-of-range float->int conversions inside them (``cvttps2dq``) give INT_MIN on every x86
#   CPU (SSE2 and AVX-512 alike): that is what makes cos(1e10) = 1 there.


HOST_FMA = host_fma()
_F32 = np.float32
_POW_REWRITTEN = (0.0, 1.0, 2.0, 4.0)  # exponents Mesa's compiler rewrites (Runtime.pow_const)
_FLT_MIN = _F32(1.17549435e-38)


_BLOCK = 65536  # lanes per pass inside LlvmpipeMath (a render tile, 49152 lanes, is one block)
# up to this many lanes a call checks its fused multiply-adds for midpoints once at the end
# (LlvmpipeMath._fast); above, keeping every float64 sum alive costs more than the checks it saves
_DEFER_LANES = 4096


def _daz(x: np.ndarray) -> np.ndarray:
    """Subnormals as zero (same sign), as an x86 operand with MXCSR.DAZ set. Returns ``x``
    itself when no |x| < FLT_MIN (zeros included) is present: the usual case, one test."""
    tiny = np.abs(x) < _FLT_MIN
    if not tiny.any():
        return x
    return np.where(tiny, np.copysign(_F32(0.0), x), x)


_LOW29 = np.int64(0x1FFFFFFF)  # NumPy scalars: a Python int operand costs a type resolution per call
_MID29 = np.int64(0x10000000)


def _fma_sum(a: Any, b: Any, c: Any) -> np.ndarray:
    """float64 ``a*b + c`` of float32 operands (the product exact, the sum rounded once), in a
    new buffer. ``a.astype`` then in-place steps: half the cost of ``np.multiply(a, b,
    dtype=np.float64)`` on a few hundred lanes, the same bits."""
    b_shape = getattr(b, "shape", ())  # (np.shape/np.ndim cost microseconds on a scalar)
    if type(a) is np.ndarray and (b_shape == a.shape or not b_shape):
        s = a.astype(np.float64)
        np.multiply(s, b, out=s)
    else:
        s = np.multiply(a, b, dtype=np.float64)
    c_shape = getattr(c, "shape", ())
    if c_shape == s.shape or not c_shape or np.broadcast_shapes(c_shape, s.shape) == s.shape:
        np.add(s, c, out=s)
    else:
        s = np.add(s, c, dtype=np.float64)
    return s


def _fma32(a: Any, b: Any, c: Any) -> np.ndarray:
    """float32 ``a*b + c`` with ONE rounding, like vfmadd. The float64 product of two float32
    values is exact; the float64 sum rounds once more, which can change the float32 result
    only when it lands exactly on a float32 midpoint (low 29 mantissa bits 1000...0) after an
    inexact addition. Those few elements get the exact error (TwoSum) and are moved one float64
    step towards it, so rounding to float32 is the correctly rounded fused result. (The sum is
    made in the product's buffer, which then holds the midpoint test; the operands of the rare
    midpoints are re-read and their float64 sum made again, the same bits.)"""
    s = _fma_sum(a, b, c)
    r = s.astype(_F32)
    low = np.bitwise_and(s.view(np.int64), _LOW29, out=s.view(np.int64))
    mid = low == _MID29
    if mid.any():
        at = np.nonzero(mid)
        ps = np.multiply(np.broadcast_to(a, r.shape)[at], np.broadcast_to(b, r.shape)[at], dtype=np.float64)
        cs = np.broadcast_to(c, r.shape)[at].astype(np.float64)
        ss = ps + cs
        bb = ss - ps
        err = (ps - (ss - bb)) + (cs - bb)  # TwoSum: ss + err == ps + cs exactly
        r[at] = np.where(err != 0, np.nextafter(ss, np.where(err > 0, np.inf, -np.inf)), ss)
    return r


_TWO31 = _F32(2.0**31)


def _cvtt(x: np.ndarray) -> np.ndarray:
    """x86 ``cvttps2dq`` of float32 ``x``: truncate to int32; NaN and out-of-range give INT_MIN.
    In range (|x| < 2**31; -2**31 itself gives INT_MIN either way) NumPy's cast truncates the
    same; only the other lanes are replaced (by -2**31) before it."""
    ok = np.abs(x) < _TWO31
    if not ok.all():
        x = np.where(ok, x, -_TWO31)
    return x.astype(I32)


def _blocked(fn: Any, *args: np.ndarray) -> np.ndarray:
    """``fn(*args)`` (float32 in, float32 out, elementwise) evaluated on blocks of
    :data:`_BLOCK` lanes of the broadcast arguments: the two dozen temporaries of a built-in
    on a million lanes (8 MB each in float64) are then tile-sized and recycled by the allocator
    instead of being faulted in anew at every step (3-5x less CPU time at 1,000,000 lanes).
    Same bits as one call (every step is elementwise). 0-d arguments run as 1-lane arrays."""
    if len(args) == 1 and type(args[0]) is np.ndarray and args[0].ndim and args[0].size <= _BLOCK:
        return fn(args[0])  # the usual call: one lane array of a tile or less
    args = tuple(np.asarray(v) for v in args)
    shape = args[0].shape if len(args) == 1 else np.broadcast_shapes(*(v.shape for v in args))
    if not shape:
        return fn(*(v.reshape(1) for v in args)).reshape(())
    n = math.prod(shape)
    if n <= _BLOCK:
        return fn(*(v if v.ndim else v.reshape(1) for v in args))
    flat = [v.reshape(-1) if v.shape == shape else v.reshape(()) if v.size == 1
            else np.broadcast_to(v, shape).reshape(-1) for v in args]
    out = np.empty(n, _F32)
    for i in range(0, n, _BLOCK):
        out[i:i + _BLOCK] = fn(*(v[i:i + _BLOCK] if v.ndim else v for v in flat))
    return out.reshape(shape)


def _keeps_shape(r: np.ndarray, v: np.ndarray) -> bool:
    """Whether broadcasting ``v`` against ``r`` leaves ``r``'s shape (so ``r`` can take the
    result in place): the usual cases by their shapes, the rest by np.broadcast_shapes (which
    costs a few microseconds a call)."""
    rs, vs = r.shape, v.shape
    if rs == vs or (v.ndim <= r.ndim and (v.size == 1 or rs[r.ndim - v.ndim:] == vs)):
        return True
    return rs == np.broadcast_shapes(rs, vs)


class LlvmpipeMath:
    """gallivm's float32 sin/cos/exp2/log2/pow (lp_bld_arit.c, Mesa 22.3), with or without
    FMA. All inputs and results are float32 arrays. The public methods split large arrays
    into blocks (:func:`_blocked`); the ``_``-prefixed ones are the algorithms, step by step."""

    # gallivm's coefficients, kept in llvmpipe_fast (their one home): the exp2 and log2
    # polynomials, and the cosine's (y_6) and sine's (y2_6) polynomials of lp_build_sin_or_cos
    EXP2, LOG2, SIN_COS = llvmpipe_fast.EXP2, llvmpipe_fast.LOG2, llvmpipe_fast.SIN_COS

    def __init__(self, fma: bool = HOST_FMA) -> None:
        self.fma = fma
        self._kernels: dict[str, Any] = {}

    def mad(self, a: Any, b: Any, c: Any, exact: bool = False) -> np.ndarray:
        """``llvm.fmuladd``: fused on an FMA CPU, else a*b then + c. ``exact``: the caller
        knows every float32 product a*b is exact, so fused and unfused agree."""
        if self.fma and not exact:
            return _fma32(a, b, c)
        return np.add(np.multiply(a, b, dtype=_F32), c, dtype=_F32)

    def _fast(self, name: str) -> Any:
        """The algorithm ``name`` (``"_exp2"``, ...) with its fused multiply-adds checked for
        float32 midpoints once at the end instead of after each one (:class:`_DeferredFma`):
        three NumPy calls fewer per fused step, which is most of the cost on the few hundred
        lanes a call has after compaction. When a float64 sum is a midpoint anywhere (rare), the
        call is made again on the reference path, which corrects each one: the same bits
        either way. Without FMA there is nothing to defer."""
        ref = getattr(self, name)
        if not self.fma:
            return ref

        def run(*args: np.ndarray) -> np.ndarray:
            if args[0].size > _DEFER_LANES:
                return ref(*args)
            d = _DeferredFma()
            r = getattr(d, name)(*args)
            return ref(*args) if d.midpoint() else r
        return run

    def _kernel(self, name: str) -> Any:
        """The algorithm ``name`` as llvmpipe_fast's kernel (the same steps in fewer NumPy
        calls, for arguments in the common range), else, where the kernel declines (edge
        arguments), :meth:`_fast`, which also recomputes the lanes of a float32 midpoint in
        the kernel: the same bits either way. Up to :data:`_DEFER_LANES` lanes: on larger
        arrays (whole tiles) the kernel's float64 rows cost as much as the calls they save
        (measured alternately in one process: 1.5-1.8x faster at 143 lanes, 1.2-1.5x at
        3600, even at 16000-48000 for sin and exp2, pow slower there). Made once
        per name (a hot path: one call per tile, loop iteration and march step)."""
        run = self._kernels.get(name)
        if run is None:
            fast, slow, fma = _FAST_KERNELS.get(name), self._fast(name), self.fma

            def run(*args: np.ndarray) -> np.ndarray:
                if max(a.size for a in args) > _DEFER_LANES:
                    return slow(*args)
                r = fast(*args, fma, slow)  # slow: also for the lanes of a float32 midpoint
                return slow(*args) if r is None else r
            # compiled kernels (numba) where jit.py's rule says they pay; else run itself
            self._kernels[name] = run = jit.dispatch(name, run if fast else slow, fma)
        return run

    def builtin(self, name: str, ref: Any) -> Any:
        """Runtime's own float32 lowering ``ref`` of the built-in ``name`` (``"_atan"``,
        ``"_atan2"``, ``"_asin"``, ``"_acos"``: Mesa's, a dozen to forty NumPy operations a call)
        as jit.dispatch gives it: the compiled kernel where jit.py's rule says it pays, else
        ``ref``. Made once per name."""
        run = self._kernels.get(name)
        if run is None:
            self._kernels[name] = run = jit.dispatch(name, ref, self.fma)
        return run

    def polynomial(self, x: np.ndarray, coeffs: tuple[float, ...]) -> np.ndarray:
        """``lp_build_polynomial``: even and odd coefficients in x*x separately (each by
        Horner with mad), then ``mad(odd, x, even)``."""
        x2 = x * x
        even = odd = None
        for i in range(len(coeffs) - 1, -1, -1):
            c = _F32(coeffs[i])
            if i % 2 == 0:
                even = c if even is None else self.mad(x2, even, c)
            else:
                odd = c if odd is None else self.mad(x2, odd, c)
        return self.mad(odd, x, even)

    # ------------------------------------------------------------------ sin, cos
    def sin_or_cos(self, a: np.ndarray, cos: bool) -> np.ndarray:
        """``lp_build_sin_or_cos``: Cephes sinf/cosf as in sse_mathfun: j = (int(|x|*4/pi) + 1)
        & ~1, three-part Cody-Waite reduction by pi/4 (DP1..DP3), one of two polynomials, sign
        by integer bit tricks, clamped to [-1, 1] with minps/maxps (a NaN from an overflowed
        reduction becomes +1), and NaN for non-finite input. For |x| >= 2**31 * pi/4 the
        conversion gives INT_MIN, so the "reduced" argument is huge and the result is a
        clamped +-1 (cos(1e10) = 1, sin(1e10) = -1)."""
        return _blocked(self._kernel("_cos" if cos else "_sin"), a)

    def tan(self, a: np.ndarray) -> np.ndarray:
        """``sin(x) / cos(x)`` (Mesa's GLSL tan), both from one reduction and one evaluation
        of each polynomial: the two share everything but the final selection and sign."""
        return _blocked(self._kernel("_tan"), a)

    def _sin(self, a: np.ndarray) -> np.ndarray:
        return self._sin_cos_result(a, self._sin_cos_reduced(a), cos=False)

    def _cos(self, a: np.ndarray) -> np.ndarray:
        return self._sin_cos_result(a, self._sin_cos_reduced(a), cos=True)

    def _tan(self, a: np.ndarray) -> np.ndarray:
        reduced = self._sin_cos_reduced(a)
        return self._sin_cos_result(a, reduced, cos=False) / self._sin_cos_result(a, reduced, cos=True)

    def _sin_cos_reduced(self, a: np.ndarray) -> tuple[np.ndarray, ...]:
        """The part sin and cos share: |x| (DAZ), j = emm2_add & ~1, the reduced argument
        x_3 and both polynomials of it (y_10 the cosine one, y2_9 the sine one)."""
        ai = a.view(I32)
        x_abs = _daz((ai & I32(0x7FFFFFFF)).view(_F32))
        emm2_add = _cvtt(x_abs * _F32(llvmpipe_fast.FOUR_OVER_PI))
        emm2_add += I32(1)  # wraps at INT_MAX, as paddd
        emm2_and = emm2_add & I32(~1)
        y_2 = emm2_and.astype(_F32)
        # DP1 has 8 significant bits and DP2 11: times an integer j < 2**16 (resp. 2**13, so
        # |x| < ~51000, resp. ~6400) the float32 product is exact and the fused multiply-add
        # rounds like a multiply then an add (the cheap form). INT_MIN reads as 2**31 here.
        j_max = int(emm2_and.view(U32).max(initial=0))
        x_1 = self.mad(y_2, _F32(llvmpipe_fast.DP[0]), x_abs, exact=j_max < 2**16)
        x_2 = self.mad(y_2, _F32(llvmpipe_fast.DP[1]), x_1, exact=j_max < 2**13)
        x_3 = self.mad(y_2, _F32(llvmpipe_fast.DP[2]), x_2)
        z = x_3 * x_3
        # both polynomials have the form mad(mad(z, p0, p1), z, p2) * z: on few lanes evaluated
        # as one (2, lanes) array, row 0 the cosine's coefficients and row 1 the sine's
        # (elementwise, so the same bits as two calls, in half the NumPy calls); on a tile two
        # arrays of one row each are faster (measured: 1.2x the time with the stacked form)
        p = self.SIN_COS
        if z.size <= _DEFER_LANES:  # (flat: the argument may be a vector, e.g. of shape (3, 1))
            zf = z.reshape(-1)
            both = self.mad(self.mad(zf, p[0], p[1]), zf, p[2])
            both *= zf
            both = [row.reshape(z.shape) for row in both]
        else:
            both = [self.mad(self.mad(z, p[0, i, 0], p[1, i, 0]), z, p[2, i, 0]) * z for i in (0, 1)]
        y_10 = both[0]  # y_6 * z
        y_10 *= z
        y_10 -= z * _F32(0.5)
        y_10 += _F32(1.0)  # ((y_6*z)*z - z*0.5) + 1.0
        y2_9 = self.mad(both[1], x_3, x_3)  # y2_6 = both[1]
        return ai, emm2_add, emm2_and, y_10, y2_9

    @staticmethod
    def _sin_cos_result(a: np.ndarray, reduced: tuple[np.ndarray, ...], cos: bool) -> np.ndarray:
        """From :meth:`_sin_cos_reduced`: the sign (sin: the argument's sign flipped by bit 2
        of j; cos: bit 2 of j - 2, inverted), the polynomial picked by bit 1 of j (cos: of j - 2), the
        clamp and NaN for non-finite input. ``fmin(y, 1)``/``fmax(., -1)`` are minps/maxps
        here: a NaN y becomes 1 in both."""
        ai, emm2_add, emm2_and, y_10, y2_9 = reduced
        if cos:
            emm2_2 = emm2_and - I32(2)  # wraps, as psubd
            sign_bit = ((I32(4) & ~emm2_2).view(U32) << U32(29)).view(I32)
        else:
            emm2_2 = emm2_and
            sign_bit = (ai ^ (emm2_add.view(U32) << U32(29)).view(I32)) & I32(INT_MIN)
        # y = (emm2_2 & 2) == 0 ? y2_9 : y_10, as a bit select: np.where on a mask that
        # changes from lane to lane costs several times these four integer passes
        keep = ((emm2_2 & I32(2)) >> 1) - I32(1)  # all ones where bit 1 is clear
        yi = y2_9.view(I32) ^ y_10.view(I32)
        yi &= keep
        yi ^= y_10.view(I32)
        yi ^= sign_bit
        y = yi.view(_F32)
        np.fmin(y, _F32(1.0), out=y)  # lp_build_clamp
        np.fmax(y, _F32(-1.0), out=y)
        finite = np.isfinite(a)
        if not finite.all():
            y[~finite] = _F32(np.nan)
        return y

    # ------------------------------------------------------------------ exp2, log2, pow
    def exp2(self, x: np.ndarray) -> np.ndarray:
        """``lp_build_exp2``: clamp to [-126.99999, 128] (NaN passes), split floor/fraction,
        2**ipart from the exponent bits times a degree-5 polynomial of the fraction."""
        return _blocked(self._kernel("_exp2"), x)

    def log2(self, x: np.ndarray) -> np.ndarray:
        """``lp_build_log2_safe``: exponent + y*P(y*y) with y = (m-1)/(m+1) for the mantissa m
        in [1, 2); then +Inf for +Inf, -Inf for 0 (subnormals too), NaN for x < 0. The edge
        masks are unordered compares, so NaN input hits all three and ends NaN."""
        return _blocked(self._kernel("_log2"), x)

    def pow(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """``lp_build_pow``: exp2(log2_safe(x) * y), then 0 where x == 0 (an unordered compare:
        NaN x gives 0 too; so do subnormal x)."""
        return _blocked(self._kernel("_pow"), x, y)

    def _exp2(self, x: np.ndarray) -> np.ndarray:
        # minps(128, x) then maxps(-126.99999, .): a NaN x passes both, as in np.minimum/maximum
        x = np.minimum(_daz(x), _F32(128.0))
        np.maximum(x, _F32(-126.99999), out=x)
        ipart = np.floor(x)
        fpart = x - ipart
        # (ipart + 127) << 23 in uint32: the int32 wrap-around of paddd/pslld, bit for bit
        expipart = ((_cvtt(ipart).view(U32) + U32(127)) << U32(23)).view(_F32)
        return np.multiply(expipart, self.polynomial(fpart, self.EXP2), out=expipart)

    def _log2(self, x: np.ndarray) -> np.ndarray:
        i = x.view(I32)
        logexp = (((i & I32(0x7F800000)) >> 23) - I32(127)).astype(_F32)
        mant = ((i & I32(0x007FFFFF)) | I32(0x3F800000)).view(_F32)
        y = (mant - _F32(1.0)) / (mant + _F32(1.0))
        res = self.mad(y, self.polynomial(y * y, self.LOG2), logexp)
        if ((x >= _FLT_MIN) & (x < _F32(np.inf))).all():
            return res  # every x normal, positive and finite: no edge applies
        xd = _daz(x)
        nan = np.isnan(x)
        res = np.where((xd < _F32(0.0)) | nan, _F32(np.nan),
                       np.where(xd == _F32(0.0), _F32(-np.inf),
                                np.where(x == _F32(np.inf), _F32(np.inf), res)))
        return res

    def _pow(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        r = self._exp2(self._log2(x) * y)
        zero = ~(np.abs(x) >= _FLT_MIN)  # x == 0 after DAZ, or NaN
        if zero.any():
            r = np.where(zero, _F32(0.0), r)
        return r


_FAST_KERNELS = {  # LlvmpipeMath._kernel: name -> kernel(*args, fma, ref), None where it declines
    "_sin": lambda a, fma, ref: llvmpipe_fast.sin_cos(a, fma, False, ref),
    "_cos": lambda a, fma, ref: llvmpipe_fast.sin_cos(a, fma, True, ref),
    "_exp2": llvmpipe_fast.exp2,
    "_log2": llvmpipe_fast.log2,
    "_pow": llvmpipe_fast.pow,
}


class _DeferredFma(LlvmpipeMath):
    """An FMA LlvmpipeMath for ONE call (a fresh instance per call: render threads share the
    runtime) whose fused multiply-adds round the float64 sum to float32 at once and keep the
    sum; :meth:`midpoint` then tells whether any sum is a float32 midpoint, the only case where
    that rounding differs from the fused one (see :func:`_fma32`)."""

    def __init__(self) -> None:
        super().__init__(fma=True)
        self.sums: list[np.ndarray] = []

    def mad(self, a: Any, b: Any, c: Any, exact: bool = False) -> np.ndarray:
        if exact:
            return np.add(np.multiply(a, b, dtype=_F32), c, dtype=_F32)
        s = _fma_sum(a, b, c)
        self.sums.append(s)
        return s.astype(_F32)

    def midpoint(self) -> bool:
        """Whether any kept float64 sum has low 29 mantissa bits 1000...0 (the sums are
        this instance's own buffers, overwritten by the test)."""
        if not self.sums:
            return False
        flat = np.concatenate([s.reshape(-1) for s in self.sums])
        low = np.bitwise_and(flat.view(np.int64), _LOW29, out=flat.view(np.int64))
        return bool((low == _MID29).any())


class Runtime(TextureFunctions):  # texture lookups: textures.py
    """GLSL ES 3.00 operators and built-ins over lane arrays, in one float precision.

    ``Runtime(precision)`` with precision ``"float32"`` (highp, default), ``"float16"``
    (mediump emulation) or ``"float64"`` (reference). Instantiate once per render.
    """

    def __init__(self, precision: str = "float32", float_to_uint: str | None = None,
                 fma: bool | None = None) -> None:
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

    # ------------------------------------------------------------------ plumbing
    @staticmethod
    def errstate():
        """Context manager silencing NumPy floating-point warnings for a whole render."""
        return np.errstate(all="ignore")

    def c(self, x: float) -> Any:
        """A float constant as a 0-d scalar of the active dtype (for internal formulas)."""
        return self.F(x)

    def _f(self, x: Any) -> np.ndarray:
        """Coerce to a float array of the active dtype (no copy when already right)."""
        if isinstance(x, np.ndarray):
            if x.dtype is self._dtype or x.dtype == self._dtype:
                return x
            if x.dtype == BOOL:
                return x.astype(self.F)
            return x.astype(self.F)
        return np.asarray(x, dtype=self.F)

    @staticmethod
    def _like(x: Any, ref: Any) -> Any:
        """Python number -> array of ref's dtype (arrays are returned unchanged)."""
        if isinstance(x, np.ndarray):
            return x
        if isinstance(ref, np.ndarray):
            return np.asarray(x, dtype=ref.dtype)
        if isinstance(x, bool):
            return np.asarray(x, dtype=BOOL)
        if isinstance(x, int):
            return np.asarray(x, dtype=I32)
        return np.asarray(x)

    def _pair(self, a: Any, b: Any) -> tuple[np.ndarray, np.ndarray]:
        if not isinstance(a, np.ndarray):
            a = self._like(a, b) if isinstance(b, np.ndarray) else self._num(a)
        if not isinstance(b, np.ndarray):
            b = self._like(b, a)
        return a, b

    def _num(self, x: Any) -> np.ndarray:
        if isinstance(x, (bool, np.bool_)):
            return np.asarray(x, dtype=BOOL)
        if isinstance(x, (int, np.integer)):
            return np.asarray(x, dtype=I32)
        return np.asarray(x, dtype=self.F)

    # ------------------------------------------------------------------ constants
    def const_float(self, x: float) -> np.ndarray:
        """A float literal, uniform over lanes: shape (1,), active float dtype."""
        return np.array([x], dtype=self.F)

    f = const_float

    @staticmethod
    def const_int(x: int) -> np.ndarray:
        """An int literal, shape (1,), int32 (values wrap to 32 bits like GLSL)."""
        return np.array([x], dtype=np.int64).astype(I32)

    @staticmethod
    def const_uint(x: int) -> np.ndarray:
        """A uint literal, shape (1,), uint32."""
        return np.array([int(x) & 0xFFFFFFFF], dtype=U32)

    @staticmethod
    def const_bool(x: bool) -> np.ndarray:
        """A bool literal, shape (1,)."""
        return np.array([bool(x)], dtype=BOOL)

    def zeros(self, shape: tuple[int, ...] = (), kind: str = "float", lanes: int = 1) -> np.ndarray:
        """A zero value (WebGL zero-initialises every variable) of GLSL shape ``shape``.

        ``kind`` is float/int/uint/bool; ``shape`` is ``()`` scalar, ``(K,)`` vector,
        ``(C, R)`` matrix, with any leading array axes.
        """
        return np.zeros(tuple(shape) + (lanes,), dtype=self.dtype_of(kind))

    def dtype_of(self, kind: str):
        return {"float": self.F, "int": I32, "uint": U32, "bool": BOOL}[kind]

    def broadcast_lanes(self, x: Any, lanes: int) -> Any:
        """``x`` with its lane axis expanded to ``lanes``: always a fresh, writable array."""
        if isinstance(x, Struct):
            return x.map(lambda v: self.broadcast_lanes(v, lanes))
        x = self._num(x) if not isinstance(x, np.ndarray) else x
        if x.ndim == 0:
            x = x.reshape(1)
        out = np.empty(x.shape[:-1] + (lanes,), dtype=x.dtype)
        out[...] = x  # always a fresh writable array: callers may write into it
        return out

    # ------------------------------------------------------------------ conversions
    def to_float(self, x: Any) -> np.ndarray:
        """``float(x)``/``vecK(x)`` conversion: bool -> 0/1, int/uint rounded to nearest."""
        return self._f(x)

    @staticmethod
    def _float_to_i64(x: np.ndarray) -> np.ndarray:
        return np.trunc(x.astype(np.float64))

    def to_int(self, x: Any) -> np.ndarray:
        """``int(x)``: float truncates toward zero; NaN, +-inf and values outside the int32
        range give INT_MIN (llvmpipe/x86 ``cvttps2dq``); uint reinterprets the bits; bool 0/1."""
        x = self._num(x) if not isinstance(x, np.ndarray) else x
        k = x.dtype.kind
        if k == "i":
            return x if x.dtype == I32 else x.astype(I32)
        if k == "u":
            return x.astype(U32).view(I32)
        if k == "b":
            return x.astype(I32)
        t = self._float_to_i64(x)
        ok = (t >= -(2.0**31)) & (t < 2.0**31)
        return np.where(ok, t, INT_MIN).astype(np.int64).astype(I32)

    def to_uint(self, x: Any) -> np.ndarray:
        """``uint(x)``: float truncates; negatives, NaN and values past 2**32 are undefined and
        follow the runtime's ``float_to_uint`` model (glslcheck/backends/driver_profile.py: what llvmpipe
        computes on this kind of CPU); int reinterprets the bits; bool 0/1."""
        x = self._num(x) if not isinstance(x, np.ndarray) else x
        k = x.dtype.kind
        if k == "u":
            return x if x.dtype == U32 else x.astype(U32)
        if k == "i":
            return x.astype(I32).view(U32)
        if k == "b":
            return x.astype(U32)
        return float_to_uint(x, self.float_to_uint)

    def to_bool(self, x: Any) -> np.ndarray:
        """``bool(x)``: x != 0 (NaN -> true)."""
        x = self._num(x) if not isinstance(x, np.ndarray) else x
        if x.dtype == BOOL:
            return x
        return x != 0

    def convert(self, x: Any, kind: str) -> np.ndarray:
        """Convert to ``kind`` in {"float", "int", "uint", "bool"}."""
        if kind == "float":  # the common case, without building bound methods per call
            return self._f(x)
        return getattr(self, _CONVERTERS[kind])(x)

    # ------------------------------------------------------------------ constructors
    def _components(self, args: Iterable[Any], kind: str) -> list[np.ndarray]:
        comps: list[np.ndarray] = []
        for a in args:
            a = self._num(a) if not isinstance(a, np.ndarray) else a
            a = self.convert(a, kind)
            if a.ndim <= 1:
                comps.append(a.reshape(-1) if a.ndim == 0 else a)
            elif a.ndim == 2:
                comps.extend(a)
            elif a.ndim == 3:
                for col in a:
                    comps.extend(col)
            else:
                raise ValueError(f"cannot take components of an array of shape {a.shape}")
        return comps

    @staticmethod
    def _stack(comps: list[np.ndarray]) -> np.ndarray:
        lanes = _lanes_of(*comps)
        out = np.empty((len(comps), lanes), dtype=comps[0].dtype)
        for i, c in enumerate(comps):
            out[i] = c
        return out

    def _vec(self, k: int, args: tuple, kind: str) -> np.ndarray:
        comps = self._components(args, kind)
        if len(comps) == 1:
            comps = comps * k
        if len(comps) < k:
            raise ValueError(f"vec{k} constructor needs {k} components, got {len(comps)}")
        return self._stack(comps[:k])

    def vec(self, k: int, *args: Any) -> np.ndarray:
        """``vecK(...)``: one scalar splats; otherwise the components of all arguments
        (scalars, vectors, matrices column-major) in order, converted to float."""
        if len(args) == k:  # k float scalars (`vec3(p.x + e, p.y, p.z)`): what _vec makes of
            dt = self._dtype  # them, without converting each one
            for a in args:
                if not (isinstance(a, np.ndarray) and a.ndim == 1 and a.dtype == dt):
                    break
            else:
                return self._stack(list(args))
        return self._vec(k, args, "float")

    def ivec(self, k: int, *args: Any) -> np.ndarray:
        return self._vec(k, args, "int")

    def uvec(self, k: int, *args: Any) -> np.ndarray:
        return self._vec(k, args, "uint")

    def bvec(self, k: int, *args: Any) -> np.ndarray:
        return self._vec(k, args, "bool")

    def mat(self, c: int, r: int, *args: Any) -> np.ndarray:
        """``matCxR(...)``: a scalar gives scalar*identity; a matrix copies the overlapping
        part and fills the rest from the identity; otherwise C*R components column-major."""
        if len(args) == 1:
            a = args[0]
            a = self._num(a) if not isinstance(a, np.ndarray) else a
            if a.ndim <= 1:
                s = self._f(a).reshape(-1)
                out = np.zeros((c, r, s.shape[-1]), dtype=self.F)
                for i in range(min(c, r)):
                    out[i, i] = s
                return out
            if a.ndim == 3:
                a = self._f(a)
                out = np.zeros((c, r, a.shape[-1]), dtype=self.F)
                for i in range(min(c, r)):
                    out[i, i] = self._1
                cc, rr = min(c, a.shape[0]), min(r, a.shape[1])
                out[:cc, :rr] = a[:cc, :rr]
                return out
        comps = self._components(args, "float")
        if len(comps) < c * r:
            raise ValueError(f"mat{c}x{r} constructor needs {c * r} components, got {len(comps)}")
        return self._stack(comps[: c * r]).reshape(c, r, -1)

    def array(self, *elements: Any) -> Any:
        """``T[](e0, e1, ...)``: stack elements on a new leading axis (Structs field-wise)."""
        if isinstance(elements[0], Struct):
            s0 = elements[0]
            return Struct(s0._name, {k: self.array(*(e._fields[k] for e in elements))
                                     for k in s0._fields})
        els = [self._num(e) if not isinstance(e, np.ndarray) else e for e in elements]
        lanes = _lanes_of(*els)
        shape = els[0].shape[:-1] + (lanes,) if els[0].ndim else (lanes,)
        out = np.empty((len(els),) + shape, dtype=els[0].dtype)
        for i, e in enumerate(els):
            out[i] = e
        return out

    @staticmethod
    def struct(name: str, **fields: Any) -> Struct:
        """A struct value (constructor ``S(a, b)`` -> ``rt.struct("S", a=..., b=...)``)."""
        return Struct(name, fields)

    # ------------------------------------------------------------------ access
    @staticmethod
    def swizzle(v: np.ndarray, sw: str) -> np.ndarray:
        """Read ``v.sw``: one letter gives a scalar (L,), several a vector (len, L).
        Also applies to scalars (``f.xxx``) when ``v`` is 1-D."""
        idx = swizzle_indices(sw)
        if v.ndim == 1:
            return v if len(idx) == 1 else np.stack([v] * len(idx))
        if len(idx) == 1:
            return v[idx[0]]
        step = idx[1] - idx[0]
        if step and v.flags.writeable and idx == tuple(range(idx[0], idx[0] + step * len(idx), step)):
            # evenly spaced (.xy, .xz, .zyx, .yz): a view, as the prefixes always were, 20x cheaper
            # than indexing with a list. A read-only value (a uniform) keeps the copy, which
            # Runtime._const takes for a constant, as before
            return v[idx[0]:(idx[-1] + step if idx[-1] + step >= 0 else None):step]
        if idx == tuple(range(len(idx))):
            return v[: len(idx)]
        return v.take(idx, axis=0)  # (.xzy, .xxy: ndarray.take costs a third of indexing with a list)

    @staticmethod
    def _mask_lanes(mask: Any) -> Any:
        if mask is None:
            return None
        if isinstance(mask, np.ndarray) and mask.dtype != BOOL:
            mask = mask.astype(BOOL)
        return mask

    def assign(self, old: Any, new: Any, mask: Any = None) -> Any:
        """``old = new`` in lanes where ``mask`` is true (None: all lanes). Works for every
        value kind including Structs; the result has the broadcast lane count and old's dtype."""
        if isinstance(old, Struct):
            return Struct(old._name, {k: self.assign(v, new._fields[k], mask)
                                      for k, v in old._fields.items()})
        new = self._like(new, old)
        if mask is None:
            return new if new.dtype == old.dtype else new.astype(old.dtype)
        if new is old and isinstance(mask, np.ndarray) and old.ndim and old.shape[-1] == mask.shape[-1]:
            return old  # (a struct field neither side wrote: already per lane, nothing to select.
            # A one-lane value still broadcasts: it would count as a constant in fmul)
        mask = self._mask_lanes(mask)
        out = np.where(mask, new, old)
        return out if out.dtype == old.dtype else out.astype(old.dtype)

    def assign_swizzle(self, old: np.ndarray, sw: str, new: Any, mask: Any = None) -> np.ndarray:
        """``old.sw = new`` under ``mask`` (``new`` is a scalar for one letter, else a vector)."""
        idx = swizzle_indices(sw)
        new = self._like(new, old)
        lanes = _lanes_of(old, new, mask)
        out = self.broadcast_lanes(old, lanes)
        mask = self._mask_lanes(mask)
        if len(idx) == 1:
            comps = [new]
        else:
            comps = [new[i] for i in range(len(idx))]
        for i, c in zip(idx, comps):
            out[i] = c if mask is None else np.where(mask, c, out[i])
        return out

    def _clamp_index(self, idx: Any, size: int) -> Any:
        if isinstance(idx, (int, np.integer)):
            return min(max(int(idx), 0), size - 1)
        idx = np.asarray(idx)
        if idx.size == 1:
            return min(max(int(idx.reshape(-1)[0]), 0), size - 1)
        return np.clip(idx.astype(np.intp), 0, size - 1)

    def index(self, arr: Any, idx: Any) -> Any:
        """``arr[idx]`` for arrays (leading axis), vectors (component) and matrices (column).

        ``idx`` is a Python int or an int array of lanes; out-of-range indices are clamped to
        ``[0, size-1]`` per lane (ANGLE/WebGL behaviour)."""
        if isinstance(arr, Struct):
            return arr.map(lambda v: self.index(v, idx))
        size = arr.shape[0]
        if (arr.shape[-1] == 1 and isinstance(idx, np.ndarray) and idx.ndim == 1 and idx.shape[0] > 1
                and arr.ndim > 1):
            # a uniform array (a constant table) read at lane-varying indices: one gather that
            # clamps as it reads (mode="clip"), contiguous with the lane axis last
            table = arr[..., 0]
            table = table.transpose(tuple(range(1, table.ndim)) + (0,))
            return np.take(table, idx, axis=-1, mode="clip")
        i = self._clamp_index(idx, size)
        if isinstance(i, int):
            return arr[i]
        lanes = _lanes_of(arr, i)
        if size <= 4:  # a few selects beat fancy indexing for vectors and matrices
            out = arr[0]
            for k in range(1, size):
                out = np.where(i == k, arr[k], out)
            return np.broadcast_to(out, out.shape[:-1] + (lanes,)) if out.shape[-1] != lanes else out
        a = np.broadcast_to(arr, arr.shape[:-1] + (lanes,))
        i = np.broadcast_to(i, (lanes,))
        picked = a[(i, Ellipsis, np.arange(lanes))]  # shape (lanes, ...)
        return np.ascontiguousarray(np.moveaxis(picked, 0, -1))

    def assign_index(self, old: Any, idx: Any, new: Any, mask: Any = None) -> Any:
        """``old[idx] = new`` under ``mask`` with per-lane clamped ``idx``; returns the new value."""
        if isinstance(old, Struct):
            return Struct(old._name, {k: self.assign_index(v, idx, new._fields[k], mask)
                                      for k, v in old._fields.items()})
        new = self._like(new, old)
        size = old.shape[0]
        i = self._clamp_index(idx, size)
        mask = self._mask_lanes(mask)
        lanes = _lanes_of(old, new, mask, i if not isinstance(i, int) else None)
        out = self.broadcast_lanes(old, lanes)
        if isinstance(i, int):
            out[i] = new if mask is None else np.where(mask, new, out[i])
            return out
        if size > 4:  # one scatter, not a pass per element (float a[100000]: 100,000 passes)
            ln = np.arange(lanes)
            i = np.broadcast_to(i, (lanes,))
            new = np.broadcast_to(new, out.shape[1:])
            if mask is not None:
                on = np.broadcast_to(mask, (lanes,))
                ln, i, new = ln[on], i[on], new[..., on]
            out[(i, Ellipsis, ln)] = np.moveaxis(new, -1, 0)
            return out
        for k in range(size):
            sel = i == k
            if mask is not None:
                sel = sel & mask
            out[k] = np.where(sel, new, out[k])
        return out

    def assign_field(self, old: Struct, name: str, new: Any, mask: Any = None) -> Struct:
        """``s.name = new`` under ``mask``; returns a new Struct."""
        return old.replace(**{name: self.assign(old._fields[name], new, mask)})

    @staticmethod
    def field(s: Struct, name: str) -> Any:
        return s._fields[name]

    @staticmethod
    def select(cond: Any, a: Any, b: Any) -> Any:
        """``cond ? a : b`` evaluated for all lanes (Structs field-wise)."""
        if isinstance(a, Struct):
            return Struct(a._name, {k: Runtime.select(cond, v, b._fields[k])
                                    for k, v in a._fields.items()})
        return np.where(cond, a, b)

    def any_lane(self, mask: Any) -> bool:
        """True when some lane of a bool value is true (for skipping dead branches/loops)."""
        return bool(np.any(mask))

    # ------------------------------------------------------------------ arithmetic
    def add(self, a: Any, b: Any) -> np.ndarray:
        a, b = self._pair(a, b)
        return np.add(a, b)

    def sub(self, a: Any, b: Any) -> np.ndarray:
        a, b = self._pair(a, b)
        return np.subtract(a, b)

    def mul(self, a: Any, b: Any) -> np.ndarray:
        """Component-wise ``*`` (scalar*x, vec*vec, mat*scalar). Use ``mat_mul_*`` for the
        linear-algebra products."""
        a, b = self._pair(a, b)
        return np.multiply(a, b)

    def fmul(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """Float ``a * b`` as Mesa compiles it: NIR folds ``x * 0.0`` to ``0.0`` when the zero is
        a compile-time constant (nir_opt_algebraic's inexact ``fmul(a, 0.0) -> 0.0``), so NaN or
        Inf times a constant zero component is 0 on llvmpipe (measured: ``v * vec3(1, 0, 0)``
        keeps NaN only in x; ``mix(NaN, y, 1.0)`` is y). Here a lane-uniform operand (the same
        value in every lane: a constant, or a value built from constants) with zero components
        gives 0 there. Approximation: a uniform input that happens to be 0 (iTime at t = 0)
        also folds, where llvmpipe would give NaN for a NaN or Inf other operand; uniforms
        read directly (read-only arrays, and their swizzles) do not. Only with
        ``fold_constants`` (set for transpiled shaders)."""
        r = a * b
        if self.fold_constants:
            # _const_zero of (a, b) or of (b, a): one operand constant, the other not (a hot
            # path: both tests made once)
            ca, cb = self._const(a), self._const(b)
            if ca != cb:
                z = a if ca else b
                if z.size <= 16 and np.count_nonzero(z) != z.size:  # (z.all() costs 4x that)
                    r = np.where(z == 0, self._0, r)
        return r

    def fadd(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """Float ``a + b`` as Mesa 22.3 compiles it for llvmpipe: nir_opt_algebraic drops an
        addition of a constant zero, ``(('fadd(is_only_used_as_float)', 'a@32', 0.0), a)``
        (GL does not ask to preserve signed zeros), so ``x + 0.0`` keeps a -0.0 that IEEE
        addition turns into +0.0 (then ``1.0 / x`` is -inf, not +inf). NIR matches each
        component after scalarising, and sees constants through inlined function arguments
        and out parameters, as `fmul`'s constant zero does here: an operand that is
        lane-uniform and not a uniform input (`_const`) counts as a constant. Measured bit for
        bit against llvmpipe in tests/gl/test_llvmpipe_lowering.py. float32 (llvmpipe) mode
        only: float64, the accuracy reference, adds as IEEE does."""
        r = a + b
        if self.lp is not None and self.fold_constants:
            for z, other in ((a, b), (b, a)):
                if self._const_zero(z, other):
                    r = np.where(z == 0, other, r)
        return r

    def fsub(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """Float ``a - b`` as Mesa compiles it: llvmpipe asks for ``lower_fsub``, so it is
        ``fadd(a, fneg(b))`` and `fadd`'s rule applies: ``0.0 - x`` is ``-x`` (-0.0 for x = +0,
        measured), ``x - 0.0`` is x. float32 (llvmpipe) mode only, as `fadd`."""
        r = a - b
        if self.lp is not None and self.fold_constants:
            if self._const_zero(a, b):
                r = np.where(a == 0, -b, r)
            if self._const_zero(b, a):
                r = np.where(b == 0, a, r)
        return r

    @staticmethod
    def _const(z: np.ndarray) -> bool:
        """z may be a compile-time constant: lane-uniform and not a uniform input (read-only)."""
        return z.ndim > 0 and z.shape[-1] == 1 and z.flags.writeable

    def _const_zero(self, z: np.ndarray, other: np.ndarray) -> bool:
        """Mesa folds z * other to 0 where z is a constant zero and other is not a constant
        (two constants are multiplied out at compile time, IEEE: 0 * inf = NaN)."""
        return (self.fold_constants and self._const(z) and z.size <= 16 and not self._const(other)
                and np.count_nonzero(z) != z.size)

    def div(self, a: Any, b: Any) -> np.ndarray:
        """``/``: float IEEE division; int truncates toward zero (x/0 = 0, INT_MIN/-1 =
        INT_MIN); uint x/0 = 0xFFFFFFFF (llvmpipe)."""
        a, b = self._pair(a, b)
        k = a.dtype.kind
        if k == "f":
            return np.divide(a, b)
        if k == "i":
            a64, b64 = a.astype(np.int64), b.astype(np.int64)
            bz = b64 == 0
            q = np.abs(a64) // np.where(bz, 1, np.abs(b64))
            q = np.where((a64 < 0) != (b64 < 0), -q, q)
            return np.where(bz, 0, q).astype(I32)
        bz = b == 0
        q = a // np.where(bz, U32(1), b)
        return np.where(bz, U32(0xFFFFFFFF), q).astype(U32)

    def rem(self, a: Any, b: Any) -> np.ndarray:
        """``%`` as llvmpipe evaluates it at run time: the UNSIGNED remainder of the 32-bit
        patterns, also for int (so -7 % 2 == 1, 7 % -2 == 7); x % 0 == 0xFFFFFFFF (-1).
        GLSL leaves negative operands undefined; non-negative operands give the C result."""
        a, b = self._pair(a, b)
        au = a.view(U32) if a.dtype == I32 else a
        bu = b.view(U32) if b.dtype == I32 else b
        bz = bu == 0
        r = np.where(bz, U32(0xFFFFFFFF), au % np.where(bz, U32(1), bu)).astype(U32)
        return r.view(I32) if a.dtype == I32 else r

    def rem_const(self, a: Any, b: Any) -> np.ndarray:
        """``%`` as Mesa's compiler folds it when both operands are compile-time constants
        (after its constant propagation): the C remainder (sign of the dividend), -7 % 2 == -1."""
        a, b = self._pair(a, b)
        if a.dtype == U32:
            return self.rem(a, b)
        a64, b64 = a.astype(np.int64), b.astype(np.int64)
        bz = b64 == 0
        r = np.fmod(a64, np.where(bz, 1, b64))
        return np.where(bz, -1, r).astype(I32)

    def neg(self, a: Any) -> np.ndarray:
        a = self._num(a) if not isinstance(a, np.ndarray) else a
        return np.negative(a)

    def pos(self, a: Any) -> Any:
        return a

    def inc(self, a: np.ndarray) -> np.ndarray:
        """``a + 1`` in a's type (for ++/--; the transpiler handles pre/post order)."""
        return np.add(a, np.asarray(1, dtype=a.dtype))

    def dec(self, a: np.ndarray) -> np.ndarray:
        return np.subtract(a, np.asarray(1, dtype=a.dtype))

    # integer bit operations -------------------------------------------------------
    @staticmethod
    def _shift_count(a: np.ndarray, b: Any) -> np.ndarray:
        b = np.asarray(b)
        if b.size == 1:  # a uniform count, usually a constant (xorshift's << 13): no array steps
            return np.array(int(b.reshape(-1)[0]) & 31, a.dtype).reshape(b.shape)
        return (b.astype(np.int64) & 31).astype(a.dtype)

    def shl(self, a: Any, b: Any) -> np.ndarray:
        """``a << b``; the count is taken mod 32 (llvmpipe: 1 << 32 == 1, 1 << -1 == INT_MIN)."""
        a = self._num(a) if not isinstance(a, np.ndarray) else a
        n = self._shift_count(a, b)
        if a.dtype == I32:
            return np.left_shift(a.view(U32), n.view(U32)).view(I32)
        return np.left_shift(a, n)

    def shr(self, a: Any, b: Any) -> np.ndarray:
        """``a >> b``: arithmetic for int, logical for uint; the count is taken mod 32."""
        a = self._num(a) if not isinstance(a, np.ndarray) else a
        return np.right_shift(a, self._shift_count(a, b))

    def bit_and(self, a: Any, b: Any) -> np.ndarray:
        a, b = self._pair(a, b)
        return np.bitwise_and(a, b)

    def bit_or(self, a: Any, b: Any) -> np.ndarray:
        a, b = self._pair(a, b)
        return np.bitwise_or(a, b)

    def bit_xor(self, a: Any, b: Any) -> np.ndarray:
        a, b = self._pair(a, b)
        return np.bitwise_xor(a, b)

    def bit_not(self, a: Any) -> np.ndarray:
        a = self._num(a) if not isinstance(a, np.ndarray) else a
        return np.invert(a)

    # comparisons and logic -------------------------------------------------------
    def lt(self, a: Any, b: Any) -> np.ndarray:
        a, b = self._pair(a, b)
        return np.less(a, b)

    def le(self, a: Any, b: Any) -> np.ndarray:
        a, b = self._pair(a, b)
        return np.less_equal(a, b)

    def gt(self, a: Any, b: Any) -> np.ndarray:
        a, b = self._pair(a, b)
        return np.greater(a, b)

    def ge(self, a: Any, b: Any) -> np.ndarray:
        a, b = self._pair(a, b)
        return np.greater_equal(a, b)

    def eq(self, a: Any, b: Any) -> np.ndarray:
        """Scalar ``==`` (NaN == NaN is false). For vectors/matrices/arrays/structs use
        :meth:`equal_all`."""
        a, b = self._pair(a, b)
        return np.equal(a, b)

    def ne(self, a: Any, b: Any) -> np.ndarray:
        a, b = self._pair(a, b)
        return np.not_equal(a, b)

    def equal_all(self, a: Any, b: Any) -> np.ndarray:
        """Aggregate ``==`` on any value (vector, matrix, array, struct): one bool per lane."""
        if isinstance(a, Struct):
            res = None
            for k, v in a._fields.items():
                e = self.equal_all(v, b._fields[k])
                res = e if res is None else res & e
            return res
        a, b = self._pair(a, b)
        e = np.equal(a, b)
        if e.ndim > 1:
            e = e.reshape(-1, e.shape[-1]).all(axis=0)
        return e

    def nequal_all(self, a: Any, b: Any) -> np.ndarray:
        return ~self.equal_all(a, b)

    @staticmethod
    def and_(a: Any, b: Any) -> np.ndarray:
        """``&&`` with both operands evaluated (the transpiler masks side effects)."""
        return np.logical_and(a, b)

    @staticmethod
    def or_(a: Any, b: Any) -> np.ndarray:
        return np.logical_or(a, b)

    @staticmethod
    def xor_(a: Any, b: Any) -> np.ndarray:
        """``^^``."""
        return np.not_equal(np.asarray(a, dtype=BOOL), np.asarray(b, dtype=BOOL))

    @staticmethod
    def not_(a: Any) -> np.ndarray:
        """``!`` on bool and the built-in ``not(bvec)``."""
        return np.logical_not(a)

    # ------------------------------------------------------------------ linear algebra
    def dot(self, a: Any, b: Any) -> np.ndarray:
        """Sum of products RIGHT to left, each rounded (no FMA), as llvmpipe:
        ``x0*y0 + (x1*y1 + (x2*y2 + x3*y3))`` (measured bit-exact on 60,000 random vec3/vec4
        pairs, constant or not; left to right matches only 56-76%). Mesa's factoring of products
        that share an operand (``dot(v, v.zxy)``: a*c + b*a -> a*(c + b)) is not copied."""
        a, b = self._f(a), self._f(b)
        if a.ndim == 1 and b.ndim == 1:
            return self.fmul(a, b)
        n = a.shape[0]
        ca, cb = self._const(a), self._const(b)  # (_const_zero of (a, b) and of (b, a), each test once)
        if self.fold_constants and ca != cb and (a if ca else b).size <= 16 and (
                np.count_nonzero(a if ca else b) != (a if ca else b).size):
            # a constant zero component drops its product (NIR folds x * 0.0 to 0.0), so a NaN
            # there does not reach the sum: dot(vec3(NaN, 1, 2), vec3(0, 1, 1)) = 3 on llvmpipe
            s = self.fmul(a[n - 1], b[n - 1])
            for i in range(n - 2, -1, -1):
                s = self.fmul(a[i], b[i]) + s
            return s
        # every product in one call (each rounded, as one at a time), then the sum from the
        # right, in place (t + s == s + t): n ufunc calls instead of 2n - 1
        p = np.multiply(a, b)
        if n == 1:
            return p[0]
        s = np.add(p[n - 1], p[n - 2])
        for i in range(n - 3, -1, -1):
            s += p[i]
        return s

    def dot_add(self, a: Any, b: Any, k: Any) -> np.ndarray:
        """``dot(a, b) + k`` for a constant ``k`` as Mesa compiles it (nir_fold): the constant
        joins the innermost addition, ``x0*y0 + (x1*y1 + (x2*y2 + k))``."""
        a, b = self._f(a), self._f(b)
        if a.ndim == 1 and b.ndim == 1:
            return self.fmul(a, b) + self._f(k)
        n = max(a.shape[0], b.shape[0])
        a, b = (np.broadcast_to(v, (n,) + v.shape[1:]) if v.ndim == 1 else v for v in (a, b))
        s = self.fmul(a[n - 1], b[n - 1]) + self._f(k)
        for i in range(n - 2, -1, -1):
            s = self.fmul(a[i], b[i]) + s
        return s

    def mat_mul_vec(self, m: np.ndarray, v: np.ndarray) -> np.ndarray:
        """``m * v``: matCxR (C,R,L) times vecC (C,L) -> vecR (R,L); sum of m[c]*v[c] in c order."""
        m, v = self._f(m), self._f(v)
        s = np.multiply(m[0], v[0])
        for c in range(1, m.shape[0]):
            s = np.add(s, np.multiply(m[c], v[c]))
        return s

    def vec_mul_mat(self, v: np.ndarray, m: np.ndarray) -> np.ndarray:
        """``v * m``: vecR (R,L) times matCxR (C,R,L) -> vecC; component c is dot(v, m[c])."""
        m, v = self._f(m), self._f(v)
        return self._stack([self.dot(v, m[c]) for c in range(m.shape[0])])

    def mat_mul_mat(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """``a * b``: matKxR (K,R,L) times matCxK (C,K,L) -> matCxR; column c is a * b[c]."""
        a, b = self._f(a), self._f(b)
        cols = [self.mat_mul_vec(a, b[c]) for c in range(b.shape[0])]
        lanes = _lanes_of(*cols)
        out = np.empty((len(cols), a.shape[1], lanes), dtype=self.F)
        for i, col in enumerate(cols):
            out[i] = col
        return out

    def matrixCompMult(self, a: Any, b: Any) -> np.ndarray:
        return np.multiply(self._f(a), self._f(b))

    def outerProduct(self, c: np.ndarray, r: np.ndarray) -> np.ndarray:
        """``outerProduct(c, r)``: matrix with r.length() columns, m[i][j] = c[j] * r[i]."""
        c, r = self._f(c), self._f(r)
        return np.multiply(c[None, :, :], r[:, None, :])

    @staticmethod
    def transpose(m: np.ndarray) -> np.ndarray:
        return np.ascontiguousarray(np.swapaxes(m, 0, 1))

    def determinant(self, m: np.ndarray) -> np.ndarray:
        """Cofactor expansion along the first column, as Mesa's GLSL built-in."""
        m = self._f(m)
        n = m.shape[0]
        if n == 2:
            return m[0][0] * m[1][1] - m[1][0] * m[0][1]
        if n == 3:
            return (m[0][0] * (m[1][1] * m[2][2] - m[2][1] * m[1][2])
                    - m[1][0] * (m[0][1] * m[2][2] - m[2][1] * m[0][2])
                    + m[2][0] * (m[0][1] * m[1][2] - m[1][1] * m[0][2]))
        # 4x4: Mesa's _determinant_mat4 (2x2 sub-determinants of the lower rows)
        SubFactor00 = m[2][2] * m[3][3] - m[3][2] * m[2][3]
        SubFactor01 = m[2][1] * m[3][3] - m[3][1] * m[2][3]
        SubFactor02 = m[2][1] * m[3][2] - m[3][1] * m[2][2]
        SubFactor03 = m[2][0] * m[3][3] - m[3][0] * m[2][3]
        SubFactor04 = m[2][0] * m[3][2] - m[3][0] * m[2][2]
        SubFactor05 = m[2][0] * m[3][1] - m[3][0] * m[2][1]
        c0 = m[1][1] * SubFactor00 - m[1][2] * SubFactor01 + m[1][3] * SubFactor02
        c1 = -(m[1][0] * SubFactor00 - m[1][2] * SubFactor03 + m[1][3] * SubFactor04)
        c2 = m[1][0] * SubFactor01 - m[1][1] * SubFactor03 + m[1][3] * SubFactor05
        c3 = -(m[1][0] * SubFactor02 - m[1][1] * SubFactor04 + m[1][2] * SubFactor05)
        return m[0][0] * c0 + m[0][1] * c1 + m[0][2] * c2 + m[0][3] * c3

    def inverse(self, m: np.ndarray) -> np.ndarray:
        """Adjugate divided by the determinant (singular -> inf/NaN, as on the GPU)."""
        m = self._f(m)
        n = m.shape[0]
        if n == 2:
            det = self.determinant(m)
            adj = np.empty_like(np.broadcast_to(m, m.shape))
            adj[0][0], adj[0][1] = m[1][1], -m[0][1]
            adj[1][0], adj[1][1] = -m[1][0], m[0][0]
            return adj / det
        # general cofactor formula: inv[c][r] = cof(r, c) / det, cof on the transposed
        lanes = m.shape[-1]
        adj = np.empty((n, n, lanes), dtype=self.F)
        idx = list(range(n))
        for c in range(n):
            for r in range(n):
                cols = [i for i in idx if i != r]
                rows = [j for j in idx if j != c]
                sub = m[np.ix_(cols, rows)]
                minor = self.determinant(sub)
                adj[c][r] = minor if (r + c) % 2 == 0 else -minor
        det = self.determinant(m)
        return adj / det

    # ------------------------------------------------------------------ angle & trig
    def radians(self, x: Any) -> np.ndarray:
        return self._f(x) * self.F(math.pi / 180.0)

    def degrees(self, x: Any) -> np.ndarray:
        return self._f(x) * self.F(180.0 / math.pi)

    def sin(self, x: Any) -> np.ndarray:
        if self.lp is not None:
            return self.lp.sin_or_cos(self._f(x), cos=False)
        return np.sin(self._f(x))

    def cos(self, x: Any) -> np.ndarray:
        if self.lp is not None:
            return self.lp.sin_or_cos(self._f(x), cos=True)
        return np.cos(self._f(x))

    def tan(self, x: Any) -> np.ndarray:
        if self.lp is not None:
            return self.lp.tan(self._f(x))
        return np.tan(self._f(x))

    def _asin_expr(self, x: np.ndarray, p0: float, p1: float) -> np.ndarray:
        """Mesa's GLSL built-in (builtin_functions.cpp ``asin_expr``); its constants are float
        literals, so ``M_PI_4f - 1.0f`` is rounded to float32 twice, as in C."""
        F = self.F
        a = np.abs(x)
        c1 = F(F(math.pi / 4) - F(1.0))
        poly = F(math.pi / 2) + a * (c1 + a * (F(p0) + a * F(p1)))
        return self.sign(x) * (F(math.pi / 2) - np.sqrt(self._1 - a) * poly)

    def asin(self, x: Any) -> np.ndarray:
        """Mesa's polynomial asin (|x| > 1 -> NaN through sqrt)."""
        if self.lp is not None:  # compiled (jit.py) where that pays; the same bits
            return self.lp.builtin("_asin", self._asin)(self._f(x))
        return self._asin(x)

    def _asin(self, x: Any) -> np.ndarray:
        return self._asin_expr(self._daz(x), 0.086566724, -0.03102955)

    def acos(self, x: Any) -> np.ndarray:
        if self.lp is not None:
            return self.lp.builtin("_acos", self._acos)(self._f(x))
        return self._acos(x)

    def _acos(self, x: Any) -> np.ndarray:
        return self.F(math.pi / 2) - self._asin_expr(self._daz(x), 0.08132463, -0.02363318)

    # nir_atan's odd polynomial x*c0 + x^3*c1 + ... + x^11*c5 (Mesa 22.3 nir_builtin_builder.c)
    _ATAN_COEFFS = (0.9999793128310355, -0.3326756418091246, 0.1938924977115610,
                    -0.1173503194786851, 0.0536813784310406, -0.0121323213173444)

    def _daz(self, x: Any) -> np.ndarray:
        """Subnormal operands read as zero in float32 (llvmpipe's DAZ); other modes unchanged."""
        x = self._f(x)
        return _daz(x) if self.lp is not None else x

    def _nir_atan(self, v: np.ndarray) -> np.ndarray:
        """Mesa 22.3 ``nir_atan``: x = min(|v|, 1) / max(|v|, 1); the six terms x^(2k+1)*c_k
        (x^3 = x^2*x, x^5 = x^3*x^2, ...) summed left to right; for |v| > 1 the fixup
        ``(t*-2 + pi/2) + t``; then times ``fsign(v)`` (fsign(NaN) = fsign(-0) = 0 on llvmpipe,
        so atan(NaN) = 0 and atan(-0) = +0). The last term is not ``(x^9*x^2)*c5``:
        nir_opt_algebraic's constant reassociation ``(a*b)*#c -> (a*#c)*b`` (a*b used once,
        the rule :mod:`nir_fold` describes) makes it ``(x^9*c5)*x^2``. Bit-exact with llvmpipe
        (measured: tests/gl/test_llvmpipe_math.py)."""
        F = self.F
        a = np.abs(v)
        x = self._daz(np.fmin(a, self._1) / np.fmax(a, self._1))  # FTZ of the quotient
        x2 = x * x
        p = x
        t = x * F(self._ATAN_COEFFS[0])
        for k, cf in enumerate(self._ATAN_COEFFS[1:], 1):
            if k == len(self._ATAN_COEFFS) - 1 and self.lp is not None:
                t = t + (p * F(cf)) * x2  # x^11 is used once only: reassociated
                break
            p = p * x2
            t = t + p * F(cf)
        t = self._daz(t)  # FTZ: a subnormal sum (|v| < 1.2e-38 / 0.99998) is 0 there
        t = np.where(self._1 < a, (t * F(-2.0) + F(math.pi / 2)) + t, t)
        return t * self.sign(v)

    def atan(self, y: Any, x: Any = None) -> np.ndarray:
        """``atan(y_over_x)`` and ``atan(y, x)`` following Mesa's NIR lowering (atan(0, 0) is
        3*pi/4 on llvmpipe: the lowering pretends 0/0 = 1 on the left half-plane)."""
        if self.lp is not None:  # compiled (jit.py) where that pays; the same bits
            if x is None:
                return self.lp.builtin("_atan", self._atan)(self._f(y))
            return self.lp.builtin("_atan2", self._atan)(self._f(y), self._f(x))
        return self._atan(y, x)

    def _atan(self, y: Any, x: Any = None) -> np.ndarray:
        if x is None:
            return self._nir_atan(self._daz(y))
        F = self.F
        y, x = self._daz(y), self._daz(x)
        flip = self._0 >= x
        ax = np.abs(x)
        s = np.where(flip, ax, y)
        t = np.where(flip, y, ax)
        scale = np.where(np.abs(t) >= F(1e18), F(0.25), self._1)
        rcp = self._1 / (t * scale)
        abs_s_over_t = self._daz(np.abs(s * scale) * np.abs(rcp))  # FTZ of the product
        tan = np.where(ax == np.abs(y), self._1, abs_s_over_t)
        arc = flip.astype(F) * F(math.pi / 2) + self._nir_atan(tan)
        return np.where(np.fmin(y, rcp) < self._0, -arc, arc)

    def sinh(self, x: Any) -> np.ndarray:
        x = self._f(x)
        return self._half * (self.exp(x) - self.exp(-x))

    def cosh(self, x: Any) -> np.ndarray:
        x = self._f(x)
        return self._half * (self.exp(x) + self.exp(-x))

    def tanh(self, x: Any) -> np.ndarray:
        """(e^x - e^-x)/(e^x + e^-x) with x clamped to [-10, 10] by GLSL clamp (llvmpipe:
        tanh(100) = 1; tanh(NaN) = -1, since clamp(NaN, -10, 10) = -10)."""
        x = self.clamp(self._f(x), self.F(-10.0), self.F(10.0))
        e1, e2 = self.exp(x), self.exp(-x)
        return (e1 - e2) / (e1 + e2)

    def asinh(self, x: Any) -> np.ndarray:
        x = self._f(x)
        return self.sign(x) * self.log(np.abs(x) + np.sqrt(x * x + self._1))

    def acosh(self, x: Any) -> np.ndarray:
        x = self._f(x)
        return self.log(x + np.sqrt(x * x - self._1))

    def atanh(self, x: Any) -> np.ndarray:
        x = self._f(x)
        return self._half * self.log((self._1 + x) / (self._1 - x))

    # ------------------------------------------------------------------ exponential
    def pow(self, x: Any, y: Any) -> np.ndarray:
        """``exp2(y * log2(x))`` with llvmpipe's edges: x < 0 -> NaN; x == 0 or x NaN -> 0
        (for every y, including 0, negative and NaN)."""
        x, y = self._f(x), self._f(y)
        if (self.fold_constants and y.ndim and y.shape[-1] == 1 and y.size <= 4 and y.flags.writeable
                and all(float(v) in _POW_REWRITTEN for v in y.reshape(-1))  # (np.isin: 0.2 ms a call)
                and not np.signbit(y).any()):
            # an exponent the same in every lane (a constant after Mesa's propagation) of 0, 1,
            # 2 or 4: Mesa rewrites pow there (pow_const); as fmul, a uniform input equal to
            # one of these is taken for a constant too
            c = tuple(float(v) for v in y.reshape(-1))
            if not any(c):  # NIR's fpow(a, 0.0) -> 1.0 (measured: pow(0, e) = 1 for a zeroed e)
                return np.ones(np.broadcast_shapes(x.shape, y.shape), dtype=self.F)
            return self.pow_const(x, c if y.ndim > 1 else c[0])
        if self.lp is not None:
            return self.lp.pow(x, _daz(y))
        r = np.log2(x)
        one_y = y.size == 1
        if one_y and r.ndim:  # one buffer for every step
            np.multiply(y, r, out=r)
            np.exp2(r, out=r)
        else:
            r = np.exp2(y * r)
        yv = float(y.reshape(-1)[0]) if one_y else 0.0
        if 0.0 < yv < math.inf:
            zero = np.isnan(x)  # exp2(y * log2(0)) = exp2(-inf) is already 0 for y > 0
        else:
            zero = (x == self._0) | np.isnan(x)
        if r.ndim and zero.shape == r.shape:
            np.copyto(r, self._0, where=zero)
            return r
        return np.where(zero, self._0, r)

    def pow_const(self, x: Any, c: Any) -> np.ndarray:
        """``pow(x, c)`` with a compile-time constant exponent ``c`` (a Python float, or a tuple
        of floats for a vector), compiled as Mesa compiles it: per component, an exponent of
        1.0 is ``x``, 2.0 is ``x*x``, 4.0 is ``(x*x)*(x*x)`` (so pow(-0.5, 2.0) = 0.25 where
        the run-time formula gives NaN), +0.0 is 1 except 0 for x == 0 or NaN (``log2(x) * 0``
        folded to 0, then llvmpipe's x == 0 select); any other exponent (-0.0, 0.5, 3.0, ...)
        is the run-time :meth:`pow`."""
        x = self._f(x)
        if isinstance(c, tuple):
            if len(set(c)) == 1 and len({math.copysign(1.0, v) for v in c}) == 1:
                return self.pow_const(x, c[0])
            return np.stack([self.pow_const(x[i], v) for i, v in enumerate(c)])
        if c == 1.0:
            return x
        if c == 2.0:
            return x * x
        if c == 4.0:
            sq = x * x
            return sq * sq
        if c == 0.0 and math.copysign(1.0, c) > 0:
            return np.where((x == self._0) | np.isnan(x), self._0, self._1)
        return self.pow(x, self.F(c))

    def pow_one(self, y: Any) -> np.ndarray:
        """``pow(1.0, y)`` with a constant base of all ones: Mesa's GLSL compiler returns the
        constant 1 (the run-time formula gives NaN for y = +-inf or NaN)."""
        return np.ones_like(self._f(y))

    def exp(self, x: Any) -> np.ndarray:
        """``exp2(x * log2(e))`` (lp_build_exp; a subnormal x is 0 in the product, DAZ)."""
        return self.exp2(self._daz(x) * self.F(1.4426950408889634))

    def log(self, x: Any) -> np.ndarray:
        """``log2(x) * ln(2)`` (lp_build_log_safe)."""
        return self.log2(x) * self.F(0.6931471805599453)

    def exp2(self, x: Any) -> np.ndarray:
        if self.lp is not None:
            return self.lp.exp2(self._f(x))
        return np.exp2(self._f(x))

    def log2(self, x: Any) -> np.ndarray:
        if self.lp is not None:
            return self.lp.log2(self._f(x))
        return np.log2(self._f(x))

    def sqrt(self, x: Any) -> np.ndarray:
        return np.sqrt(self._f(x))

    def inversesqrt(self, x: Any) -> np.ndarray:
        return self._1 / np.sqrt(self._f(x))

    # ------------------------------------------------------------------ common
    def abs(self, x: Any) -> np.ndarray:
        """abs for float and int (abs(INT_MIN) == INT_MIN)."""
        x = self._num(x) if not isinstance(x, np.ndarray) else x
        return np.abs(x)

    def sign(self, x: Any) -> np.ndarray:
        """1, -1 or 0 (sign(-0.0) == +0.0, sign(NaN) == 0, as llvmpipe); int too."""
        x = self._num(x) if not isinstance(x, np.ndarray) else x
        if x.dtype.kind == "i":
            return np.sign(x)
        one = x.dtype.type(1)
        return np.where(x > 0, one, np.where(x < 0, -one, x.dtype.type(0)))

    def floor(self, x: Any) -> np.ndarray:
        return np.floor(self._f(x))

    def ceil(self, x: Any) -> np.ndarray:
        return np.ceil(self._f(x))

    def trunc(self, x: Any) -> np.ndarray:
        return np.trunc(self._f(x))

    def round(self, x: Any) -> np.ndarray:
        """Half-way cases go to even on llvmpipe (round(2.5) == 2, round(-2.5) == -2)."""
        return np.rint(self._f(x))

    def roundEven(self, x: Any) -> np.ndarray:
        return np.rint(self._f(x))

    def fract(self, x: Any) -> np.ndarray:
        x = self._f(x)
        return x - np.floor(x)

    def mod(self, x: Any, y: Any) -> np.ndarray:
        """``x - y * floor(x / y)`` in the float dtype (not np.mod/np.fmod)."""
        x, y = self._f(x), self._f(y)
        return x - y * np.floor(x / y)

    def modf(self, x: Any) -> tuple[np.ndarray, np.ndarray]:
        """Returns ``(fractional part, integer part)``, both with the sign of x; the
        transpiler assigns the second to the ``out`` argument."""
        x = self._f(x)
        i = np.trunc(x)
        return x - i, i

    def min_(self, a: Any, b: Any) -> np.ndarray:
        """``min``; a NaN operand yields the other operand (IEEE minNum, as llvmpipe)."""
        a, b = self._pair(a, b)
        return np.fmin(a, b) if a.dtype.kind == "f" else np.minimum(a, b)

    def max_(self, a: Any, b: Any) -> np.ndarray:
        a, b = self._pair(a, b)
        return np.fmax(a, b) if a.dtype.kind == "f" else np.maximum(a, b)

    def clamp(self, x: Any, lo: Any, hi: Any) -> np.ndarray:
        """``min(max(x, lo), hi)`` exactly (lo > hi gives hi; NaN x gives lo)."""
        return self.min_(self.max_(x, lo), hi)

    def mix(self, x: Any, y: Any, a: Any, form: str | None = None) -> np.ndarray:
        """``x*(1-a) + y*a``; with a bool ``a`` selects y where a is true.

        In float32 (llvmpipe) mode, ``form`` is the formula Mesa's nir_lower_flrp picks for this
        call (llvmpipe has no FFMA; :func:`nir_fold.mix_form` decides from the operands the
        compiler knows): ``"strict"`` ``x*(1-a) + y*a`` (a constant ``a``, or ``y`` = +-1),
        ``"fast"`` ``x + a*(y-x)`` (run-time ``a``: measured bit for bit), ``"one"`` /
        ``"minus_one"`` ``(x - a) + y*a`` / ``(x + a) + y*a`` for a constant ``x`` of +1 / -1.
        None: :meth:`_flrp_form` guesses it from the operands. float64 and float16 keep the GLSL
        formula."""
        if isinstance(a, np.ndarray) and a.dtype == BOOL:
            x, y = self._pair(x, y)
            return np.where(a, y, x)
        x, y, a = self._f(x), self._f(y), self._f(a)
        if self.lp is not None:
            if form is None:
                form = self._flrp_form(x, y, a)
            if form == "fast":  # compiled (jit.py) where that pays; the same bits
                return self.lp.builtin("_mix", self._mix_fast)(x, y, a)
            if form in ("one", "minus_one"):
                r = (x - a) if form == "one" else (x + a)
                return r + y * a
        r = self.fmul(x, self._1 - a)  # a constant a of 0 or 1 drops the other side (fmul)
        t = self.fmul(y, a)
        if r.shape == t.shape and r.ndim:  # the sum in r's buffer
            return np.add(r, t, out=r)
        return r + t

    def _mix_fast(self, x: np.ndarray, y: np.ndarray, a: np.ndarray) -> np.ndarray:
        """mix's "fast" form in float32: ``x + a*(y - x)``. A lane whose weight is exactly 0 or
        1 is taken for NIR's b2f(c) (step(), 1.0 - step(), float(bool), their products: the lab
        shaders' branchless selects): ``flrp(x, y, b2f(c))`` is ``bcsel(c, y, x)`` in
        nir_opt_algebraic, before the lowering. Per lane, so a one-pixel probe run agrees with
        the render. Where every lane is such a select (a branchless shader's whole tile), the
        arithmetic is skipped: the same values, a third of the passes."""
        one, zero = a == self._1, a == self._0
        n_one, n_zero = np.count_nonzero(one), np.count_nonzero(zero)
        if n_one + n_zero == a.size:
            return np.where(one, y, x)
        r = np.subtract(y, x)
        r = np.multiply(a, r, out=r if _keeps_shape(r, a) else None)
        r = np.add(x, r, out=r if _keeps_shape(r, x) else None)
        if n_one:  # r is a new array of the broadcast shape here
            np.copyto(r, y, where=one)
        if n_zero:
            np.copyto(r, x, where=zero)
        return r

    def _flrp_form(self, x: np.ndarray, y: np.ndarray, a: np.ndarray) -> str:
        """The lowering ``convert_flrp_instruction`` (Mesa nir_lower_flrp.c; llvmpipe sets
        lower_ffma32, so no FMA form) picks for ``mix(x, y, a)``, in its order: x and y both
        constants whose exponents differ by at most 11 -> fast; x a constant of all +1 / -1 ->
        one / minus_one; y a constant of all +1 or all -1 -> strict; a constant -> strict; else
        fast. For direct calls only: transpiled code passes the form :func:`nir_fold.mix_hint`
        decides from the source (this run-time guess depends on the lane count). "Constant" is :meth:`_const` (lane-uniform and not a uniform input, as for
        :meth:`fmul`) with ``fold_constants``; direct calls count a lane-uniform ``a`` only.
        Approximation: a value computed from uniforms only (``sin(iTime)``) counts as a
        constant here, where Mesa sees a run-time value."""
        if not self.fold_constants:
            return "strict" if a.ndim == 0 or a.shape[-1] == 1 else "fast"
        cx, cy = self._const(x) and x.size <= 16, self._const(y) and y.size <= 16
        if cx and cy:
            ex, ey = np.frexp(np.broadcast_arrays(x, y)[0])[1], np.frexp(np.broadcast_arrays(y, x)[0])[1]
            if (np.abs(ex - ey) <= 11).all():
                return "fast"
        if cx and (x == self._1).all():
            return "one"
        if cx and (x == -self._1).all():
            return "minus_one"
        if cy and ((y == self._1).all() or (y == -self._1).all()):
            return "strict"
        return "strict" if self._const(a) else "fast"

    def step(self, edge: Any, x: Any) -> np.ndarray:
        """0 where x < edge else 1; NaN gives 0 (llvmpipe computes x >= edge)."""
        edge, x = self._f(edge), self._f(x)
        return (x >= edge).astype(self.F)

    def smoothstep(self, e0: Any, e1: Any, x: Any) -> np.ndarray:
        """t = clamp((x-e0)/(e1-e0), 0, 1); t*(t*(3-2t)). Equal edges follow the formula
        (0/0 = NaN clamps to 0), as llvmpipe."""
        e0, e1, x = self._f(e0), self._f(e1), self._f(x)
        t = self.clamp((x - e0) / (e1 - e0), self._0, self._1)
        return t * (t * (self._3 - self._2 * t))

    @staticmethod
    def isnan(x: np.ndarray) -> np.ndarray:
        return np.isnan(x)

    @staticmethod
    def isinf(x: np.ndarray) -> np.ndarray:
        return np.isinf(x)

    def floatBitsToInt(self, x: Any) -> np.ndarray:
        return self._f(x).astype(np.float32).view(I32)

    def floatBitsToUint(self, x: Any) -> np.ndarray:
        return self._f(x).astype(np.float32).view(U32)

    def intBitsToFloat(self, x: Any) -> np.ndarray:
        x = np.asarray(x, dtype=I32) if not isinstance(x, np.ndarray) else x
        f = x.astype(I32).view(np.float32)
        return f if self.F is np.float32 else f.astype(self.F)

    def uintBitsToFloat(self, x: Any) -> np.ndarray:
        x = np.asarray(x, dtype=U32) if not isinstance(x, np.ndarray) else x
        f = x.astype(U32).view(np.float32)
        return f if self.F is np.float32 else f.astype(self.F)

    # ------------------------------------------------------------------ packing
    @staticmethod
    def _pack16(lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
        return (lo.astype(U32) & U32(0xFFFF)) | (hi.astype(U32) << U32(16))

    def packSnorm2x16(self, v: np.ndarray) -> np.ndarray:
        """round(clamp(c, -1, 1) * 32767) per component (round half to even). NaN gives -32767
        (0x8001) as on llvmpipe, whose clamp is max-then-min with IEEE maxNum: max(NaN, -1) is
        -1 (measured)."""
        v = self._f(v).astype(np.float32)
        q = np.rint(np.nan_to_num(np.clip(v, -1.0, 1.0), nan=-1.0) * np.float32(32767.0))
        q = q.astype(np.int32).astype(np.int16).view(np.uint16)
        return self._pack16(q[0], q[1])

    def unpackSnorm2x16(self, p: Any) -> np.ndarray:
        p = np.asarray(p).astype(U32)
        lo = (p & U32(0xFFFF)).astype(np.uint16).view(np.int16)
        hi = (p >> U32(16)).astype(np.uint16).view(np.int16)
        v = np.stack([lo, hi]).astype(np.float32) / np.float32(32767.0)
        return np.clip(v, -1.0, 1.0).astype(self.F)

    def packUnorm2x16(self, v: np.ndarray) -> np.ndarray:
        v = self._f(v).astype(np.float32)
        q = np.rint(np.nan_to_num(np.clip(v, 0.0, 1.0), nan=0.0) * np.float32(65535.0))
        q = q.astype(np.uint32)
        return self._pack16(q[0], q[1])

    def unpackUnorm2x16(self, p: Any) -> np.ndarray:
        p = np.asarray(p).astype(U32)
        v = np.stack([p & U32(0xFFFF), p >> U32(16)]).astype(np.float32) / np.float32(65535.0)
        return v.astype(self.F)

    def packHalf2x16(self, v: np.ndarray) -> np.ndarray:
        h = self._f(v).astype(np.float32).astype(np.float16).view(np.uint16)
        return self._pack16(h[0], h[1])

    def unpackHalf2x16(self, p: Any) -> np.ndarray:
        p = np.asarray(p).astype(U32)
        h = np.stack([p & U32(0xFFFF), p >> U32(16)]).astype(np.uint16).view(np.float16)
        return h.astype(self.F)

    # ------------------------------------------------------------------ geometric
    def length(self, x: Any) -> np.ndarray:
        x = self._f(x)
        if x.ndim == 1:
            return np.abs(x)
        d = self.dot(x, x)
        return np.sqrt(d, out=d)

    def distance(self, a: Any, b: Any) -> np.ndarray:
        return self.length(self.sub(self._f(a), self._f(b)))

    def cross(self, a: Any, b: Any) -> np.ndarray:
        a, b = self._f(a), self._f(b)
        return self._stack([a[1] * b[2] - a[2] * b[1],
                            a[2] * b[0] - a[0] * b[2],
                            a[0] * b[1] - a[1] * b[0]])

    def normalize(self, x: Any) -> np.ndarray:
        """``x * inversesqrt(dot(x, x))`` (zero vector -> NaN); a float normalizes to sign(x)."""
        x = self._f(x)
        if x.ndim == 1:
            return self.sign(x)
        d = self.dot(x, x)  # a fresh array: sqrt and the reciprocal reuse it
        np.sqrt(d, out=d)
        np.divide(self._1, d, out=d)
        return x * d

    def faceforward(self, n: Any, i: Any, nref: Any) -> np.ndarray:
        n = self._f(n)
        return np.where(self.dot(nref, i) < self._0, n, -n)

    def reflect(self, i: Any, n: Any) -> np.ndarray:
        i, n = self._f(i), self._f(n)
        return i - self._2 * (self.dot(n, i) * n)

    def refract(self, i: Any, n: Any, eta: Any) -> np.ndarray:
        i, n, eta = self._f(i), self._f(n), self._f(eta)
        d = self.dot(n, i)
        k = self._1 - eta * eta * (self._1 - d * d)
        r = eta * i - (eta * d + np.sqrt(k)) * n
        return np.where(k < self._0, self._0, r)

    # ------------------------------------------------------------------ vector relational
    def lessThan(self, a: Any, b: Any) -> np.ndarray:
        return self.lt(a, b)

    def lessThanEqual(self, a: Any, b: Any) -> np.ndarray:
        return self.le(a, b)

    def greaterThan(self, a: Any, b: Any) -> np.ndarray:
        return self.gt(a, b)

    def greaterThanEqual(self, a: Any, b: Any) -> np.ndarray:
        return self.ge(a, b)

    def equal(self, a: Any, b: Any) -> np.ndarray:
        return self.eq(a, b)

    def notEqual(self, a: Any, b: Any) -> np.ndarray:
        return self.ne(a, b)

    @staticmethod
    def any(v: np.ndarray) -> np.ndarray:
        return np.any(v, axis=0)

    @staticmethod
    def all(v: np.ndarray) -> np.ndarray:
        return np.all(v, axis=0)

    @staticmethod
    def not_vec(v: np.ndarray) -> np.ndarray:
        """The built-in ``not(bvec)`` (``not`` is a Python keyword)."""
        return np.logical_not(v)

    # ------------------------------------------------------------------ derivatives
    def _quad_diff(self, v: Any, width: int, axis: int) -> np.ndarray:
        v = self._f(v)
        if v.shape[-1] == 1:
            return np.zeros_like(v)
        n = v.shape[-1]
        if n % width:
            raise ValueError(f"lane count {n} is not a multiple of the tile width {width}")
        height = n // width
        img = v.reshape(v.shape[:-1] + (height, width))
        ax = img.ndim - 2 + axis  # axis 1: x (columns), axis 0: y (rows)
        size = img.shape[ax]
        even = [slice(None)] * img.ndim
        odd = [slice(None)] * img.ndim
        even[ax] = slice(0, size - 1, 2)
        odd[ax] = slice(1, size, 2)
        d = img[tuple(odd)] - img[tuple(even)]
        out = np.repeat(d, 2, axis=ax)
        if size % 2:  # odd size: the last row/column reuses its left/lower neighbour pair
            last = [slice(None)] * img.ndim
            last[ax] = slice(size - 1, size)
            prev = [slice(None)] * img.ndim
            prev[ax] = slice(size - 2, size - 1)
            if size > 1:
                tail = img[tuple(last)] - img[tuple(prev)]
            else:
                tail = np.zeros_like(img[tuple(last)])
            out = np.concatenate([out, tail], axis=ax)
        return out.reshape(v.shape)

    def dFdx(self, v: Any, width: int) -> np.ndarray:
        """Fine x-derivative as llvmpipe: lanes are the rows of a ``width``-wide tile,
        lane = y*width + x with y counted from the bottom (gl_FragCoord order), 2x2 quads start
        at even x and y. ``dFdx(x, y) = v(x|1, y) - v(x&~1, y)``. Tiles of a shader that uses
        derivatives are rendered with llvmpipe's helper column/row at an odd edge (program.py
        `render_tile`), so quads are whole; an odd width seen here anyway (the probe's strips)
        uses the difference to its left neighbour. Lane-uniform values have zero derivative."""
        return self._quad_diff(v, width, 1)

    def dFdy(self, v: Any, width: int) -> np.ndarray:
        """Fine y-derivative: ``v(x, y|1) - v(x, y&~1)``; see :meth:`dFdx`."""
        return self._quad_diff(v, width, 0)

    def fwidth(self, v: Any, width: int) -> np.ndarray:
        return np.abs(self.dFdx(v, width)) + np.abs(self.dFdy(v, width))

    # ------------------------------------------------------------------ unsupported
    @staticmethod
    def texture_unsupported(name: str, line: int | None = None) -> None:
        """Raise for texture lookups, which the NumPy backend does not evaluate."""
        where = f" (line {line})" if line is not None else ""
        raise GLSLRuntimeError(f"{name}{where}: texture lookups are not supported by the NumPy backend")
