"""llvmpipe_fast's kernels against LlvmpipeMath's step-by-step algorithms, bit for bit.

The kernels (glslcheck/backends/numpy_engine/llvmpipe_fast.py) are the same float32 steps in fewer
NumPy calls, for arguments in the common range; elsewhere they decline (return None) and the
reference path runs. Compared here on about two million lanes per kernel and FMA choice:
arguments at every scale the kernels accept (uniform, log-spread down to FLT_MIN, exact
multiples of 1/8, the edges of their ranges) with specials mixed in at random (+-0, subnormals,
+-Inf, NaN, huge), and through the public methods, which must equal the reference whether or
not a kernel declines. (tests/gl/test_llvmpipe_math.py compares the public methods with the
driver itself.)
"""

from __future__ import annotations

import numpy as np
import pytest
from image_bits import assert_same_lanes

from glslcheck.backends.numpy_engine import llvmpipe_fast
from glslcheck.backends.numpy_engine.llvmpipe_reference import LlvmpipeMath, blocked

RNG = np.random.default_rng(1818)
F32 = np.float32
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
        -1.17549435e-38,
        np.inf,
        -np.inf,
        np.nan,
        3.4028235e38,
        -3.4028235e38,
        2.0**29,
        -(2.0**29),
        5.3687085e8,
        1.6e9,
        2.0**31,
        126.0,
        -126.0,
        126.00001,
        127.99999,
        128.0,
        129.0,
        -126.99999,
        -127.0,
        1.0,
        -1.0,
    ],
    F32,
)
NAMES = ("the fast path", "the reference")
ANY_NAN = "bits_any_nan"  # every NaN as one pattern (the sign of a NaN means nothing in GLSL)
# (kernel name, exponent range of the arguments' scale, positive only)
KERNELS = {
    "_sin": (-3, 9.5, False),
    "_cos": (-3, 9.5, False),
    "_exp2": (-3, 2.5, False),
    "_log2": (-38, 38, True),
    "_pow": (-3, 5, True),
}


def _sample(n: int, lo: float, hi: float, positive: bool, specials: bool) -> np.ndarray:
    """n float32 arguments of one kind at a random scale 10**[lo, hi]: uniform, log-spread
    magnitudes (down to the smallest normal), or exact multiples of 1/8 (their products and
    sums are short: the float64 midpoints of the fused steps happen there)."""
    scale = 10.0 ** RNG.uniform(lo, hi)
    kind = RNG.integers(0, 3)
    if kind == 0:
        x = RNG.uniform(-scale, scale, n)
    elif kind == 1:
        x = RNG.choice([-1.0, 1.0], n) * 10.0 ** RNG.uniform(-37.9, max(np.log10(scale), -37.8), n)
    else:
        s = min(scale, 1e15)
        x = RNG.integers(-int(s * 8), int(s * 8) + 1, n) / 8.0
    x = x.astype(F32)
    if specials:
        k = min(n, 1 + RNG.integers(0, 3))
        x[RNG.choice(n, k, replace=False)] = RNG.choice(SPECIALS, k)
    return np.abs(x) if positive else x


def _kernel(name: str, fma: bool, ref=None):
    """The kernel; ``ref`` recomputes the lanes of a float32 midpoint (without it the kernel
    declines there)."""
    return {
        "_sin": lambda a: llvmpipe_fast.sin_cos(a, fma, False, ref),
        "_cos": lambda a: llvmpipe_fast.sin_cos(a, fma, True, ref),
        "_exp2": lambda a: llvmpipe_fast.exp2(a, fma, ref),
        "_log2": lambda a: llvmpipe_fast.log2(a, fma, ref),
        "_pow": lambda a, b: llvmpipe_fast.pow(a, b, fma, ref),
    }[name]


def _public(lp: LlvmpipeMath, name: str):
    return {
        "_sin": lambda a: lp.sin_or_cos(a, cos=False),
        "_cos": lambda a: lp.sin_or_cos(a, cos=True),
        "_exp2": lp.exp2,
        "_log2": lp.log2,
        "_pow": lp.pow,
    }[name]


@pytest.mark.parametrize("fma", [True, False])
@pytest.mark.parametrize("name", sorted(KERNELS))
def test_kernel_equals_reference(name, fma):
    """About two million lanes in calls of 1 to 20,000 lanes; a third of the calls carry a
    few specials (most of those decline). Every call a kernel takes must give the
    reference's bits, and most calls must be taken (else the test compares nothing)."""
    lp = LlvmpipeMath(fma)
    lo, hi, positive = KERNELS[name]
    kernel, public = _kernel(name, fma, lp._fast(name)), _public(lp, name)
    taken = lanes = 0
    with np.errstate(all="ignore"):
        while lanes < 2_000_000:
            n = int(RNG.choice([1, 3, 7, 143, 900, 5000, 20000]))
            specials = RNG.random() < 1 / 3
            args = (_sample(n, lo, hi, positive, specials),)
            if name == "_pow":
                args += (_sample(n, -2, 1.5, False, specials),)
            want = blocked(getattr(lp, name), *args)
            got = kernel(*args)
            if got is None:  # declined: the public method takes the reference path
                got = public(*args)
            else:
                taken += n
            lanes += n
            assert got.dtype == np.float32 and got.shape == want.shape
            what = f"{name}, fma {fma}, a call of {n} lanes"
            assert_same_lanes(got, want, args, what=what, names=NAMES, mode=ANY_NAN)
    assert taken > lanes // 3, (name, fma, taken, lanes)


@pytest.mark.parametrize("name", sorted(KERNELS))
def test_specials_one_by_one(name):
    """Each special alone and beside ordinary lanes, in every argument position, through the
    public method (kernel or reference) against the reference, both FMA choices."""
    for fma in (True, False):
        lp = LlvmpipeMath(fma)
        with np.errstate(all="ignore"):
            for s in SPECIALS:
                for x in (np.array([s], F32), np.array([0.25, s, 3.0], F32)):
                    args = (x,) if name != "_pow" else (np.abs(x), np.full_like(x, 2.5))
                    if name == "_pow":
                        args = [args, (np.full_like(x, 2.5), x)]
                    else:
                        args = [args]
                    for a in args:
                        want = blocked(getattr(lp, name), *a)
                        got = _public(lp, name)(*a)
                        what = f"{name}, fma {fma}, special {s!r}"
                        assert_same_lanes(got, want, a, what=what, names=NAMES, mode=ANY_NAN)


def test_fused_rows_find_a_midpoint():
    """1 * (1 + 2**-23) + 2**-24 is a float32 midpoint of its float64 sum: `_Fused.midpoints`
    must see it, in its lane (in a later row too); 1 * 1.5 + 0.25 is not."""
    v = np.array([1.0, 1.0, 1.0], F32)
    c = np.array([0.25, 2**-24, 0.25], F32)
    f = llvmpipe_fast._Fused(True, 2, 3)
    f.mad(v, F32(1.5), F32(0.25))
    f.mad(v, F32(1 + 2**-23), c)
    assert f.midpoints().tolist() == [False, True, False]
    f = llvmpipe_fast._Fused(True, 2, 3)
    f.mad(v, F32(1.5), F32(0.25))
    assert f.midpoints() is None


def test_midpoint_lanes_get_the_reference(monkeypatch):
    """Lanes flagged as midpoints are recomputed by the reference on those lanes alone
    (without one the kernel declines): checked by flagging every third lane of a call and
    giving a reference that negates its result, which must then show in exactly those lanes;
    the public method's result is the reference's bit for bit."""
    real = llvmpipe_fast._Fused.midpoints

    def every_third(self):
        real(self)
        return np.arange(self.buf.shape[1]) % 3 == 0

    monkeypatch.setattr(llvmpipe_fast._Fused, "midpoints", every_third)
    x = RNG.uniform(0.5, 50.0, 300).astype(F32).reshape(3, 100)
    flagged = (np.arange(300) % 3 == 0).reshape(3, 100)
    lp = LlvmpipeMath(True)
    with np.errstate(all="ignore"):
        for name in sorted(KERNELS):
            args = (x,) if name != "_pow" else (x, x[:1] * F32(0.01))  # pow: y broadcast
            want = blocked(getattr(lp, name), *args)
            assert _kernel(name, True)(*args) is None
            calls = []

            def negated_ref(*a, _name=name):
                calls.append(a[0].size)
                return -getattr(lp, _name)(*a)

            got = _kernel(name, True, negated_ref)(*args)
            assert calls == [100]
            negated = np.where(flagged, -want, want)
            what = f"{name}, every third lane flagged"
            assert_same_lanes(got, negated, args, what=what, names=NAMES, mode=ANY_NAN)
            got = _public(lp, name)(*args)
            assert_same_lanes(got, want, args, what=what, names=NAMES, mode=ANY_NAN)
