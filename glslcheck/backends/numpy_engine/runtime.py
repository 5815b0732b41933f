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

Numeric semantics: where GLSL ES 3.00 leaves a result undefined or unordered, the runtime
computes what llvmpipe does (measured; tests/numpy/test_runtime_gl.py repeats the cases): the
table of cases, the formulas, transcendentals, constant folding, subnormals and derivatives
are in docs/llvmpipe.md.
"""

from __future__ import annotations

import numpy as np

from ...base.precision import check_precision
from ..driver_profile import FLOAT_TO_UINT, host_model
from .llvmpipe_reference import HOST_FMA, LlvmpipeMath
from .runtime_common import CommonFunctions
from .runtime_operators import ArithmeticOps
from .runtime_transcendental import TranscendentalFunctions
from .runtime_values import ValueOps, where
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
        self._last_weight = (None, None)  # (b2f weight, weight == 1): mix's select
        self._2 = F(2.0)
        self._3 = F(3.0)
        self._half = F(0.5)

    # NumPy's own ufuncs, which the transpiler calls where it knows every operand is an array
    # of one float dtype (GLSL float operands always are): the built-in's exact operation,
    # without a Python frame and the operand coercions of the methods below (`min_`, `abs`...)
    # on every call. A ufunc is no descriptor, so `rt.np_fmin` is np.fmin itself.
    np_where = staticmethod(where)  # `c ? a : b` of one array each (select: also structs)
    np_fmin = np.fmin  # min: a NaN operand yields the other (IEEE minNum, as llvmpipe; min_)
    np_fmax = np.fmax
    np_abs = np.abs
    np_sqrt = np.sqrt
    np_floor = np.floor
    np_ceil = np.ceil
    np_trunc = np.trunc
