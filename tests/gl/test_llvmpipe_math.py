"""The NumPy runtime's float32 built-ins against llvmpipe, bit for bit, on many inputs.

llvmpipe evaluates sin, cos, exp2, log2 (and tan, pow, exp, log, the hyperbolic functions built
on them) with its own polynomials (gallivm lp_bld_arit.c), asin/acos with Mesa's GLSL formula
and atan with NIR's polynomial (after nir_opt_algebraic's reassociation of its last term);
`Runtime("float32")` repeats them step by step (see `LlvmpipeMath` in
glslcheck/backends/numpy_engine/runtime.py). Each case renders a few hundred thousand inputs at once
(uniform grid, random, subnormal, huge, +-0, +-Inf, NaN) and compares every bit.

CPU dependence: the steps llvmpipe builds with `llvm.fmuladd` are fused on a CPU with FMA and
not fused without; `Runtime()` follows this machine (`HOST_FMA`), and a test checks that the
other choice is measurably different, so a wrong detection cannot pass.

Written for llvmpipe of Mesa 22.3: the bit-exact tests take the `llvmpipe` fixture
(tests/conftest.py), which fails naming that release on another driver.
"""

from __future__ import annotations

import numpy as np
import pytest
from image_bits import assert_same_lanes
from llvmpipe_eval import evaluate, ulp_distance

from glslcheck.backends.numpy_engine.llvmpipe_reference import HOST_FMA
from glslcheck.backends.numpy_engine.runtime import Runtime

RT = Runtime("float32")
RNG = np.random.default_rng(20261201)
EDGES = np.array(
    [
        0.0,
        -0.0,
        1.0,
        -1.0,
        0.5,
        2.0,
        np.inf,
        -np.inf,
        np.nan,
        1e-40,
        -1e-40,
        1e-45,
        1.17549435e-38,
        3e38,
        -3e38,
        1e10,
        -1e10,
        2.0**31,
        1e30,
        128.0,
        129.0,
        -127.0,
        -126.99999,
        127.99999,
        0.7853982,
        1.5707964,
        3.1415927,
        6.2831855,
    ],
    dtype=np.float32,
)


def _inputs(lo: float, hi: float, n: int = 100_000) -> np.ndarray:
    """Uniform in [lo, hi], then magnitudes spread over the whole float32 range, then EDGES."""
    spread = RNG.standard_normal(n // 4) * 10.0 ** RNG.uniform(-44, 38, n // 4)
    return np.concatenate([RNG.uniform(lo, hi, n), spread, EDGES]).astype(np.float32)


X = _inputs(-50.0, 50.0)
Y = RNG.permutation(X)
POS = np.abs(_inputs(0.0, 20.0))
UNIT = _inputs(-1.0, 1.0)
# the lanes compared as numbers, a NaN equal to any NaN: ulp_distance 0
NAMES = ("Runtime", "llvmpipe")

# (GLSL expression of a and b, runtime function, inputs a, inputs b)
EXACT = [
    ("sin(a)", RT.sin, X, None),
    ("cos(a)", RT.cos, X, None),
    ("sin(a)", RT.sin, X * np.float32(1e4), None),  # large arguments: cos(1e10) == 1 there
    ("cos(a)", RT.cos, X * np.float32(1e6), None),
    ("tan(a)", RT.tan, X, None),
    ("exp2(a)", RT.exp2, X * np.float32(3.0), None),
    ("exp(a)", RT.exp, X, None),
    ("log2(a)", RT.log2, POS, None),
    ("log2(a)", RT.log2, X, None),  # negative, zero, NaN edges
    ("log(a)", RT.log, POS, None),
    ("pow(a, b)", RT.pow, POS, Y * np.float32(0.2)),
    ("pow(a, b)", RT.pow, X, Y),
    # a constant base of 2: nir_opt_algebraic's fpow(2.0, a) -> fexp2(a), which the transpiler
    # copies (pow_rewrite); the driver's pow(2.0, a) must be our exp2 bit for bit
    ("pow(2.0, a)", RT.exp2, X * np.float32(3.0), None),
    ("pow(vec2(2.0), vec2(a, b)).y", lambda a, b: RT.exp2(b), X, Y * np.float32(3.0)),
    # literal exponents: 1, 2, 4 are products (pow_const), 0.5 and 3 stay exp2(y * log2(x))
    # (products of |a| < 1e-9 are subnormal: plain multiplies keep them where llvmpipe flushes
    # them, see NORMAL below, so those are left out)
    ("pow(a, 2.0)", lambda a: RT.pow_const(a, 2.0), X[~(np.abs(X) < 1e-9) | (X == 0)], None),
    ("pow(a, 4.0)", lambda a: RT.pow_const(a, 4.0), X[~(np.abs(X) < 1e-9) | (X == 0)], None),
    ("pow(a, 0.5)", lambda a: RT.pow(a, np.float32(0.5)), POS, None),
    ("pow(a, 3.0)", lambda a: RT.pow(a, np.float32(3.0)), X, None),
    ("asin(a)", RT.asin, UNIT, None),
    ("acos(a)", RT.acos, UNIT, None),
    ("sinh(a)", RT.sinh, X, None),
    ("cosh(a)", RT.cosh, X, None),
    ("tanh(a)", RT.tanh, X, None),
    ("asinh(a)", RT.asinh, X, None),
    ("acosh(a)", RT.acosh, POS + np.float32(1.0), None),
    ("atanh(a)", RT.atanh, UNIT, None),
    ("atan(a)", RT.atan, X, None),
    ("atan(a, b)", RT.atan, X, Y),
    ("atan(a, b)", RT.atan, UNIT, RNG.permutation(UNIT)),
    (
        "atan(a)",
        RT.atan,
        np.linspace(0.75, 1.4, 100_000, dtype=np.float32),
        None,
    ),  # x^11 reassociated
    (
        "fract(sin(a) * 43758.5453)",
        lambda a: RT.fract(RT.mul(RT.sin(a), RT.const_float(43758.5453))),
        X,
        None,
    ),
]


@pytest.mark.parametrize("case", EXACT, ids=[f"{c[0]}-{i}" for i, c in enumerate(EXACT)])
def test_builtin_is_bit_exact_with_llvmpipe(llvmpipe, case):
    expr, fn, a, b = case
    got = evaluate(llvmpipe, expr, a, b)
    with RT.errstate():
        ours = np.asarray(fn(a) if b is None else fn(a, b))
    assert ours.dtype == np.float32
    assert_same_lanes(ours, got, (a, b), what=expr, names=NAMES, mode="values_any_nan")


# Normal operands only: plain arithmetic keeps subnormal operands and results where llvmpipe
# flushes them (DAZ/FTZ, documented in tests/hard_cases/README.md), so those are left out here.
NA, NB, NC = (RNG.uniform(-50.0, 50.0, 100_000).astype(np.float32) for _ in range(3))
NT = RNG.uniform(-0.5, 1.5, 100_000).astype(np.float32)
NORMAL = [
    ("sqrt(abs(a))", lambda a, b, c: RT.sqrt(np.abs(a))),
    ("inversesqrt(abs(a))", lambda a, b, c: RT.inversesqrt(np.abs(a))),
    ("length(vec3(a, b, c))", lambda a, b, c: RT.length(np.stack([a, b, c]))),
    (
        "distance(vec2(a, b), vec2(c, a))",
        lambda a, b, c: RT.distance(np.stack([a, b]), np.stack([c, a])),
    ),
    ("normalize(vec3(a, b, c)).y", lambda a, b, c: RT.normalize(np.stack([a, b, c]))[1]),
    ("mod(a, b)", lambda a, b, c: RT.mod(a, b)),
    ("fract(a)", lambda a, b, c: RT.fract(a)),
    ("smoothstep(a, b, c)", lambda a, b, c: RT.smoothstep(a, b, c)),
    # nir_lower_flrp without FFMA, weight known only at run time: x + t*(y - x)
    ("mix(a, b, c)", lambda a, b, c: RT.mix(a, b, c)),
]


@pytest.mark.parametrize("case", NORMAL, ids=[c[0] for c in NORMAL])
def test_builtin_on_normal_operands_is_bit_exact_with_llvmpipe(llvmpipe, case):
    expr, fn = case
    c = NT if expr.startswith("mix") else NC
    got = evaluate(llvmpipe, expr, NA, NB, c)
    with RT.errstate():
        ours = np.asarray(fn(NA, NB, c), np.float32)
    what = f"{expr} on normal operands"
    assert_same_lanes(ours, got, (NA, NB, c), what=what, names=NAMES, mode="values_any_nan")


def test_fma_choice_follows_this_cpu(llvmpipe):
    """Runtime() fuses llvm.fmuladd exactly when this CPU does: the other choice differs from
    the driver on some inputs (about 1% of sin arguments), the detected one on none."""
    got = evaluate(llvmpipe, "sin(a)", X)
    other = Runtime("float32", fma=not HOST_FMA)
    with RT.errstate():
        assert np.count_nonzero(ulp_distance(RT.sin(X), got)) == 0
        assert np.count_nonzero(ulp_distance(other.sin(X), got)) > 100


def test_float64_mode_keeps_numpy_math():
    """precision="float64" is the accuracy reference: libm, not llvmpipe's polynomials."""
    rt = Runtime("float64")
    x = np.linspace(-10, 10, 101)
    np.testing.assert_array_equal(rt.sin(x), np.sin(x))
    np.testing.assert_array_equal(rt.exp2(x), np.exp2(x))
    np.testing.assert_array_equal(rt.log2(np.abs(x)), np.log2(np.abs(x)))


def test_pack_snorm_of_nan_is_minus_one(gl):
    """llvmpipe clamps with max-then-min (IEEE maxNum): packSnorm2x16 of NaN is -32767 (0x8001),
    as for -1.0; packUnorm2x16 of NaN is 0."""
    a = np.array([0.0, 0.0, 0.0], np.float32)
    b = np.array([0.0, 1.0, 0.0], np.float32)
    c = np.array([0.5, -2.0, 0.25], np.float32)
    got = evaluate(
        gl,
        "",
        a,
        b,
        c,
        stmt="float n = a / b; o = ivec4(int(packSnorm2x16(vec2(n, c))),"
        " int(packSnorm2x16(vec2(c, n))), int(packUnorm2x16(vec2(n, c))), 0);",
    )
    with RT.errstate():
        n = a / b
        ours = np.stack(
            [
                RT.packSnorm2x16(np.stack([n, c])),
                RT.packSnorm2x16(np.stack([c, n])),
                RT.packUnorm2x16(np.stack([n, c])),
            ],
            1,
        ).view(np.int32)
    np.testing.assert_array_equal(ours, got[:, :3])
