"""Hypothesis property tests: runtime built-ins against float64 / exact-integer references."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from glslcheck.backends.numpy_engine.runtime import Runtime

RT = Runtime("float32")
f32 = np.float32
i32 = st.integers(min_value=-(2**31), max_value=2**31 - 1)
# llvmpipe flushes subnormals to zero (x86 FTZ/DAZ), NumPy does not: see the runtime docstring.
finite = st.floats(min_value=-1e6, max_value=1e6, allow_nan=False, width=32, allow_subnormal=False)
SET = settings(max_examples=300, deadline=None)


def arr(x, dtype=np.float32):
    return np.array([x], dtype=dtype)


def ulp_distance(a: float, b: float) -> int:
    ai = int(np.array([a], f32).view(np.int32)[0])
    bi = int(np.array([b], f32).view(np.int32)[0])
    ai = -(2**31) - ai if ai < 0 else ai
    bi = -(2**31) - bi if bi < 0 else bi
    return abs(ai - bi)


def wrap32(x: int) -> int:
    return (x + 2**31) % 2**32 - 2**31


# ---------------------------------------------------------------- integers: exact
@SET
@given(i32, i32)
def test_int_arithmetic_wraps(a, b):
    A, B = arr(a, np.int32), arr(b, np.int32)
    assert int(RT.add(A, B)[0]) == wrap32(a + b)
    assert int(RT.sub(A, B)[0]) == wrap32(a - b)
    assert int(RT.mul(A, B)[0]) == wrap32(a * b)


@SET
@given(i32, i32)
def test_int_division_truncates_toward_zero(a, b):
    got = int(RT.div(arr(a, np.int32), arr(b, np.int32))[0])
    if b == 0:
        assert got == 0
    else:
        q = abs(a) // abs(b)
        assert got == wrap32(q if (a < 0) == (b < 0) else -q)


@SET
@given(i32, i32)
def test_int_remainder_forms(a, b):
    got = int(RT.rem(arr(a, np.int32), arr(b, np.int32))[0])
    ua, ub = a & 0xFFFFFFFF, b & 0xFFFFFFFF
    assert got == wrap32(0xFFFFFFFF if ub == 0 else ua % ub)
    if a >= 0 and b > 0:  # where GLSL defines %, both forms are the C remainder
        assert got == a % b == int(RT.rem_const(arr(a, np.int32), arr(b, np.int32))[0])
    if b != 0:
        c = int(RT.rem_const(arr(a, np.int32), arr(b, np.int32))[0])
        assert c == wrap32(int(math.fmod(a, b)))


@SET
@given(i32, st.integers(min_value=-64, max_value=64))
def test_shifts_take_count_mod_32(a, n):
    A, N = arr(a, np.int32), arr(n, np.int32)
    k = n & 31
    assert int(RT.shl(A, N)[0]) == wrap32(a << k)
    assert int(RT.shr(A, N)[0]) == a >> k  # Python >> is arithmetic
    ua = a & 0xFFFFFFFF
    assert int(RT.shr(arr(ua, np.uint32), N)[0]) == ua >> k


@SET
@given(st.floats(width=32, allow_nan=True, allow_infinity=True))
def test_float_to_int_truncates_or_int_min(x):
    got = int(RT.to_int(arr(x))[0])
    if math.isnan(x) or math.isinf(x) or not (-(2**31) <= math.trunc(x) < 2**31):
        assert got == -(2**31)
    else:
        assert got == math.trunc(x)


# ---------------------------------------------------------------- floats against float64
# Bound 0: a single IEEE operation (or a fixed sequence of them) that NumPy performs in float32
# with round-to-nearest, compared with the same sequence in float64 rounded after each step.
@SET
@given(finite, finite)
def test_mod_is_the_spec_formula_in_float32(x, y):
    if y == 0:
        return
    with np.errstate(all="ignore"):
        q = f32(f32(x) / f32(y))
    expect = f32(f32(x) - f32(f32(y) * np.floor(q)))
    with RT.errstate():
        got = RT.mod(arr(x), arr(y))[0]
    assert got == expect or (np.isnan(got) and np.isnan(expect))


@SET
@given(
    st.floats(min_value=0.0, max_value=1.0000000150474662e30, width=32, allow_subnormal=False),
    finite,
)
def test_sqrt_and_division_correctly_rounded(x, y):
    # IEEE sqrt and division are correctly rounded: float32(float64 result) is the exact answer
    # (float64 has > 2*24+2 bits, so the double rounding is innocuous).
    assert RT.sqrt(arr(x))[0] == f32(math.sqrt(x))
    if y != 0:
        with np.errstate(all="ignore"):  # overflow to inf is a valid result
            assert RT.div(arr(x), arr(y))[0] == f32(np.float64(f32(x)) / np.float64(f32(y)))


@SET
@given(st.floats(min_value=-100, max_value=100, width=32))
def test_sin_cos_absolute_error(x):
    # float32 sin/cos are llvmpipe's Cephes polynomials (bit-exact with the driver, see
    # tests/numpy/test_llvmpipe_math_gl.py): three-part Cody-Waite reduction by pi/4, whose
    # error grows with |x| (~|x| * 2**-48), plus the degree-7/8 polynomials' 6e-8. Measured max
    # over 2,000,001 points of [-100, 100]: 7.7e-8, with and without FMA; bound 1e-7.
    assert abs(float(RT.sin(arr(x))[0]) - math.sin(x)) <= 1e-7
    assert abs(float(RT.cos(arr(x))[0]) - math.cos(x)) <= 1e-7


@SET
@given(st.floats(min_value=-100, max_value=100, width=32))
def test_exp2_relative_error(x):
    # llvmpipe's exp2: exact 2**floor(x) times a degree-5 minimax polynomial of the fraction
    # (relative error ~3e-7 = 4.3 float32 ULP, measured max over 2,000,001 points); bound 5 ULP.
    assert abs(float(RT.exp2(arr(x))[0]) / 2.0**x - 1.0) <= 5 * 2.0**-24


@SET
@given(
    st.floats(min_value=-1e4, max_value=1e4, width=32, allow_subnormal=False),
    st.floats(min_value=-1e4, max_value=1e4, width=32, allow_subnormal=False),
)
def test_atan2_absolute_error(y, x):
    # Mesa's degree-11 odd polynomial for atan on [0, 1] has max error ~1e-5 rad (its
    # coefficients are a minimax fit to ~6e-6); range reduction adds a few float32 ULPs of
    # pi/2 (1.2e-7 each). atan(0, 0) is 3*pi/4 by construction, not atan2's 0.
    with RT.errstate():
        got = float(RT.atan(arr(y), arr(x))[0])
    if x == 0 and y == 0:
        return
    assert abs(got - math.atan2(y, x)) < 1e-5


@SET
@given(st.floats(min_value=-1, max_value=1, width=32))
def test_asin_acos_absolute_error(x):
    # Abramowitz & Stegun 4.4.45-style approximation: |error| <= 2e-4 rad for the polynomial
    # (asin uses slightly different coefficients, measured max 4e-4 against libm).
    assert abs(float(RT.asin(arr(x))[0]) - math.asin(x)) < 5e-4
    assert abs(float(RT.acos(arr(x))[0]) - math.acos(x)) < 5e-4


@SET
@given(st.lists(st.floats(min_value=-1e3, max_value=1e3, width=32), min_size=2, max_size=4))
def test_dot_length_normalize_error_bounds(c):
    v = np.array(c, dtype=f32).reshape(-1, 1)
    exact = sum(float(a) * float(a) for a in c)
    got = float(RT.dot(v, v)[0])
    # a left-to-right sum of n rounded products of non-negative terms: relative error
    # <= (2n-1) * 2^-24 (each product and each addition rounds once).
    assert abs(got - exact) <= (2 * len(c)) * 2.0**-24 * exact + 1e-30
    if exact > 1e-6:
        n = RT.normalize(v)
        ln = math.sqrt(sum(float(a) ** 2 for a in n[:, 0]))
        # dot + sqrt + reciprocal + one product each: a handful of ULPs around 1.0
        assert abs(ln - 1.0) < 8 * 2.0**-24 * 2 + 2 * len(c) * 2.0**-24


@SET
@given(finite, finite, st.floats(min_value=0, max_value=1, width=32))
def test_mix_clamp_smoothstep_formulas(x, y, a):
    X, Y, A = arr(x), arr(y), arr(a)
    assert RT.mix(X, Y, A)[0] == f32(f32(f32(x) * f32(f32(1) - f32(a))) + f32(f32(y) * f32(a)))
    lo, hi = min(x, y), max(x, y)
    assert RT.clamp(A, arr(lo), arr(hi))[0] == min(max(f32(a), f32(lo)), f32(hi))
    s = float(RT.smoothstep(arr(0.0), arr(1.0), A)[0])
    assert abs(s - a * a * (3 - 2 * a)) < 4 * 2.0**-24 * 3


@SET
@given(
    st.sampled_from(["float16", "float32", "float64"]),
    st.lists(st.floats(min_value=-10, max_value=10, width=16), min_size=1, max_size=5),
    st.sampled_from(
        [
            "sin",
            "exp",
            "sqrt",
            "fract",
            "floor",
            "sign",
            "normalize",
            "tanh",
            "atan",
            "asin",
            "round",
            "inversesqrt",
            "log2",
        ]
    ),
)
def test_dtype_is_preserved(precision, values, name):
    rt = Runtime(precision)
    x = np.array(values, dtype=rt.F)
    with rt.errstate():
        out = getattr(rt, name)(x)
        assert out.dtype == rt.F
        assert rt.add(rt.mul(x, 2.5), rt.f(1.0)).dtype == rt.F
        assert rt.pow(x, rt.f(2.0)).dtype == rt.F
