"""The NumPy runtime's float32 built-ins against llvmpipe, bit for bit, on many inputs.

llvmpipe evaluates sin, cos, exp2, log2 (and tan, pow, exp, log, the hyperbolic functions built
on them) with its own polynomials (gallivm lp_bld_arit.c), asin/acos with Mesa's GLSL formula
and atan with NIR's polynomial; `Runtime("float32")` repeats them step by step (see
`LlvmpipeMath` in glslcheck/numpy_backend/runtime.py). Each case renders a few hundred thousand
inputs at once (uniform grid, random, subnormal, huge, +-0, +-Inf, NaN) and compares every bit.

CPU dependence: the steps llvmpipe builds with `llvm.fmuladd` are fused on a CPU with FMA and
not fused without; `Runtime()` follows this machine (`HOST_FMA`), and a test checks that the
other choice is measurably different, so a wrong detection cannot pass.
"""

from __future__ import annotations

import numpy as np
import pytest

from glslcheck.numpy_backend.runtime import HOST_FMA, Runtime
from llvmpipe_eval import evaluate, ulp_distance

RT = Runtime("float32")
RNG = np.random.default_rng(20261201)
EDGES = np.array([0.0, -0.0, 1.0, -1.0, 0.5, 2.0, np.inf, -np.inf, np.nan, 1e-40, -1e-40, 1e-45,
                  1.17549435e-38, 3e38, -3e38, 1e10, -1e10, 2.0**31, 1e30, 128.0, 129.0, -127.0,
                  -126.99999, 127.99999, 0.7853982, 1.5707964, 3.1415927, 6.2831855],
                 dtype=np.float32)


def _inputs(lo: float, hi: float, n: int = 100_000) -> np.ndarray:
    """Uniform in [lo, hi], then magnitudes spread over the whole float32 range, then EDGES."""
    spread = RNG.standard_normal(n // 4) * 10.0 ** RNG.uniform(-44, 38, n // 4)
    return np.concatenate([RNG.uniform(lo, hi, n), spread, EDGES]).astype(np.float32)


X = _inputs(-50.0, 50.0)
Y = RNG.permutation(X)
POS = np.abs(_inputs(0.0, 20.0))
UNIT = _inputs(-1.0, 1.0)

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
    ("asin(a)", RT.asin, UNIT, None),
    ("acos(a)", RT.acos, UNIT, None),
    ("sinh(a)", RT.sinh, X, None),
    ("cosh(a)", RT.cosh, X, None),
    ("tanh(a)", RT.tanh, X, None),
    ("asinh(a)", RT.asinh, X, None),
    ("acosh(a)", RT.acosh, POS + np.float32(1.0), None),
    ("atanh(a)", RT.atanh, UNIT, None),
    ("fract(sin(a) * 43758.5453)", lambda a: RT.fract(RT.mul(RT.sin(a), RT.const_float(43758.5453))),
     X, None),
]


@pytest.mark.parametrize("case", EXACT, ids=[f"{c[0]}-{i}" for i, c in enumerate(EXACT)])
def test_builtin_is_bit_exact_with_llvmpipe(gl, case):
    expr, fn, a, b = case
    got = evaluate(gl, expr, a, b)
    with RT.errstate():
        ours = np.asarray(fn(a) if b is None else fn(a, b))
    assert ours.dtype == np.float32
    u = ulp_distance(ours, got)
    bad = np.flatnonzero(u)
    assert bad.size == 0, (expr, bad.size, a[bad[:5]], got[bad[:5]], ours[bad[:5]])


def test_atan_within_one_ulp_of_llvmpipe(gl):
    # Mesa 22.3's nir_atan: six power terms summed left to right. Known residue: 1 ULP on
    # ~0.2% of arguments with 0.85 < |x| < 1.2 (the order LLVM/NIR really uses there is not
    # found yet); measured 0.007% of these inputs differ, none by more than 1 ULP.
    for expr, ours, a, b in (("atan(a)", RT.atan(X), X, None), ("atan(a, b)", RT.atan(X, Y), X, Y)):
        got = evaluate(gl, expr, a, b)
        u = ulp_distance(ours, got)
        assert u.max() <= 1 and np.mean(u == 0) >= 0.999, (expr, int(u.max()), float(np.mean(u == 0)))


def test_fma_choice_follows_this_cpu(gl):
    """Runtime() fuses llvm.fmuladd exactly when this CPU does: the other choice differs from
    the driver on some inputs (about 1% of sin arguments), the detected one on none."""
    got = evaluate(gl, "sin(a)", X)
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
    got = evaluate(gl, "", a, b, c, stmt="float n = a / b; o = ivec4(int(packSnorm2x16(vec2(n, c))),"
                   " int(packSnorm2x16(vec2(c, n))), int(packUnorm2x16(vec2(n, c))), 0);")
    with RT.errstate():
        n = a / b
        ours = np.stack([RT.packSnorm2x16(np.stack([n, c])), RT.packSnorm2x16(np.stack([c, n])),
                         RT.packUnorm2x16(np.stack([n, c]))], 1).view(np.int32)
    np.testing.assert_array_equal(ours, got[:, :3])
