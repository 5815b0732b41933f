"""LlvmpipeMath's fast path (fused multiply-adds checked for float32 midpoints once per call,
`LlvmpipeMath._fast`) against its reference path (each one checked and corrected, `fma32`),
bit for bit, on random arguments with every kind of special: +-0, subnormals, +-Inf, NaN, huge
magnitudes, exact integers and halves. Both FMA choices, and lane counts on both sides of
`_DEFER_LANES` (the fast path only defers up to there)."""

from __future__ import annotations

import numpy as np
import pytest
from image_bits import assert_same_lanes

from glslcheck.backends.numpy_engine import llvmpipe_reference
from glslcheck.backends.numpy_engine.llvmpipe_reference import DeferredFma, LlvmpipeMath, blocked

RNG = np.random.default_rng(18)
SPECIALS = np.array(
    [
        0.0,
        -0.0,
        1e-45,
        -1e-45,
        1e-40,
        -1e-40,
        1.1754942e-38,
        1.17549435e-38,
        np.inf,
        -np.inf,
        np.nan,
        -np.nan,
        3.4028235e38,
        -3.4028235e38,
        1e10,
        -1e10,
        2.0**31,
        -(2.0**31),
        1.0,
        -1.0,
        0.5,
        2.0,
        128.0,
        -127.0,
        -126.99999,
        129.0,
        0.7853982,
        1.5707964,
        3.1415927,
        6.2831855,
        51471.0,
        6433.0,
    ],
    np.float32,
)
# both paths make NaN the same way, but the sign of a NaN carries no meaning in GLSL: every NaN
# is one pattern
ANY_NAN = "bits_any_nan"


def _sample(n: int) -> np.ndarray:
    """n float32 values: a third uniform in [-100, 100], a third spread over every magnitude
    (subnormal to huge, both signs), a third exact multiples of 1/8 and raw bit patterns;
    the specials placed at random positions."""
    k = n // 3
    spread = RNG.standard_normal(k) * 10.0 ** RNG.uniform(-45, 38.5, k)
    bits = (
        RNG.integers(-(2**31), 2**31, n - 2 * k, dtype=np.int64).astype(np.int32).view(np.float32)
    )
    bits[::2] = RNG.integers(-800, 800, bits[::2].size) / 8.0
    with np.errstate(all="ignore"):
        x = np.concatenate([RNG.uniform(-100, 100, k), spread, bits]).astype(np.float32)
    x[RNG.choice(n, SPECIALS.size, replace=False)] = SPECIALS
    return x


@pytest.mark.parametrize("fma", [True, False])
@pytest.mark.parametrize(
    "shape", [(40,), (300,), (llvmpipe_reference.DEFER_LANES,), (20_000,), (3, 1), (4, 50)]
)
def test_fast_path_equals_reference(fma, shape):
    """Lane arrays of each size, and vectors (components first: (3, 1) is a vec3 of one lane)."""
    lp = LlvmpipeMath(fma)
    n = int(np.prod(shape))
    x, y = _sample(max(n, 40))[:n].reshape(shape), _sample(max(n, 40))[:n].reshape(shape)
    with np.errstate(all="ignore"):
        for name, args in (
            ("_sin", (x,)),
            ("_cos", (x,)),
            ("_tan", (x,)),
            ("_exp2", (x,)),
            ("_exp2", (x * np.float32(1e-2),)),
            ("_log2", (x,)),
            ("_log2", (np.abs(x),)),
            ("_pow", (np.abs(x), y * np.float32(1e-2))),
            ("_pow", (x, y)),
        ):
            public = {
                "_sin": lambda a: lp.sin_or_cos(a, cos=False),
                "_cos": lambda a: lp.sin_or_cos(a, cos=True),
                "_tan": lp.tan,
                "_exp2": lp.exp2,
                "_log2": lp.log2,
                "_pow": lp.pow,
            }[name]
            want = blocked(getattr(lp, name), *args)
            got = public(*args)
            assert got.dtype == np.float32
            what = f"{name}, fma {fma}, {n} lanes"
            names = ("the public method", "the reference")
            assert_same_lanes(got, want, args, what=what, names=names, mode=ANY_NAN)


def test_deferred_check_finds_a_midpoint_and_the_call_falls_back():
    """1 * (1 + 2**-23) + 2**-24 is a float32 midpoint: the deferred check must see it (and
    the fused rounding, ties-to-even here, is the reference's)."""
    d = DeferredFma()
    one = np.ones(3, np.float32)
    d.mad(one, np.float32(1 + 2**-23), np.float32(2**-24))
    assert d.midpoint()
    d = DeferredFma()
    d.mad(one, np.float32(1.5), np.float32(0.25))
    assert not d.midpoint()
    # a fast-path call whose check fires returns the reference result
    calls = []

    class Spy(LlvmpipeMath):
        def _exp2(self, x):
            calls.append(type(self).__name__)
            return super()._exp2(x)

    orig = DeferredFma.midpoint
    try:
        DeferredFma.midpoint = lambda self: True
        x = _sample(50)
        with np.errstate(all="ignore"):
            got = Spy(True).exp2(x)
            want = blocked(LlvmpipeMath(True)._exp2, x)
    finally:
        DeferredFma.midpoint = orig
    assert calls == ["Spy"]  # the deferred run is DeferredFma's own; the fallback is Spy's
    assert_same_lanes(got, want, (x,), what="exp2, a midpoint check that fires", mode=ANY_NAN)


@pytest.mark.parametrize("kinds", ["zeros", "subnormals", "both", "neither"])
def test_daz_flushes_subnormals_only(kinds: str) -> None:
    """daz against the definition read off the bits (exponent field 0: zero or subnormal, made
    a zero of the same sign); an array without a subnormal comes back as itself."""
    x = RNG.uniform(-4.0, 4.0, 1000).astype(np.float32)
    if kinds in ("zeros", "both"):
        x[::7] = 0.0
        x[3::7] = -0.0
    if kinds in ("subnormals", "both"):
        x[5::11] = np.float32(1e-40)
        x[6::11] = np.float32(-3e-42)
    bits = x.view(np.uint32)
    expected = np.where((bits & 0x7F800000) == 0, bits & 0x80000000, bits).astype(np.uint32)
    r = llvmpipe_reference.daz(x)
    np.testing.assert_array_equal(r.view(np.uint32), expected)
    assert (r is x) == (kinds in ("zeros", "neither"))


def test_daz_of_scalars_and_0d_arrays() -> None:
    """A NumPy scalar and a 0-d array (uniform operands) flush as a one-lane array does."""
    for v in (0.0, -0.0, 1e-40, -1e-40, 2.0):
        lane = llvmpipe_reference.daz(np.array([v], np.float32))
        for x in (np.float32(v), np.array(v, np.float32)):
            r = np.asarray(llvmpipe_reference.daz(x))
            assert r.shape == () and r.view(np.uint32) == lane.view(np.uint32)[0], (v, type(x))
