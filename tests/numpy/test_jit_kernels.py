"""numba's compiled kernels (numpy_backend/jit_kernels.py) against LlvmpipeMath's step-by-step
algorithms, bit for bit, with and without FMA.

Through `jit.compiled`, the function runtime.LlvmpipeMath calls once the kernels are on: on about
1,500,000 lanes per function and FMA choice, in calls of 1 to 49,152 lanes (a tile), with the arguments of
tests/numpy/test_llvmpipe_fast_kernels.py (every scale, log-spread down to FLT_MIN, exact
multiples of 1/8, where the fused steps' float64 sums land on float32 midpoints; specials mixed
in: +-0, subnormals, +-Inf, NaN, huge). A call the kernel takes must give the reference's bits
exactly; a call it declines (a NaN would come out, or |x| >= 2**29 for sin/cos/tan) goes to the
NumPy function, which must be asked for it. Skipped without numba on a developer machine, a
failure on CI (the `jit_kernels` fixture).
"""

from __future__ import annotations

import numpy as np
import pytest
from test_llvmpipe_fast_kernels import KERNELS as FAST_KERNELS
from test_llvmpipe_fast_kernels import RNG, SPECIALS, _bits, _sample

from glslcheck.numpy_backend import jit
from glslcheck.numpy_backend.runtime import LlvmpipeMath, _blocked

F32 = np.float32
KERNELS = dict(FAST_KERNELS, _tan=(-3, 9.5, False))  # (scale exponents, positive only)


def _compiled(name: str, lp: LlvmpipeMath, kernels, declined: list):
    """The kernel as LlvmpipeMath calls it, its NumPy path the reference (counting declines)."""
    def run(*args):
        declined.append(args[0].size)
        return _blocked(getattr(lp, name), *args)
    return jit.compiled(name, run, lp.fma, kernels)


def _args(name: str, n: int, specials: bool) -> tuple[np.ndarray, ...]:
    lo, hi, positive = KERNELS[name]
    args = (_sample(n, lo, hi, positive, specials),)
    if name == "_pow":
        args += (_sample(n, -2, 1.5, False, specials),)
    return args


@pytest.mark.parametrize("fma", [True, False])
@pytest.mark.parametrize("name", sorted(KERNELS))
def test_kernel_equals_reference(jit_kernels, name, fma):
    lp = LlvmpipeMath(fma)
    declined: list = []
    fn = _compiled(name, lp, jit_kernels, declined)
    lanes = taken = 0
    with np.errstate(all="ignore"):
        while lanes < 1_500_000:
            n = int(RNG.choice([1, 3, 7, 143, 900, 5000, 16000, 49152]))
            args = _args(name, n, RNG.random() < 1 / 3)
            want = _blocked(getattr(lp, name), *args)
            before = len(declined)
            got = fn(*args)
            lanes += n
            assert got.dtype == np.float32 and got.shape == want.shape
            if len(declined) == before:  # the kernel's lanes: every bit, no NaN among them
                taken += n
                bad = np.flatnonzero(got.view(np.int32) != want.view(np.int32))
            else:
                bad = np.flatnonzero(_bits(got) != _bits(want))
            assert bad.size == 0, (name, fma, n, [a[bad[:5]] for a in args], got[bad[:5]], want[bad[:5]])
    assert taken > lanes // 2, (name, fma, taken, lanes)


@pytest.mark.parametrize("name", sorted(KERNELS))
def test_specials_one_by_one(jit_kernels, name):
    """Each special alone and beside ordinary lanes, in either argument of pow, both FMA
    choices; the specials a kernel computes (zeros, subnormals, infinities) to the bit, the
    rest declined to NumPy (which gives the reference's NaN)."""
    for fma in (True, False):
        lp = LlvmpipeMath(fma)
        fn = _compiled(name, lp, jit_kernels, [])
        with np.errstate(all="ignore"):
            for s in SPECIALS:
                for x in (np.array([s], F32), np.array([0.25, s, 3.0], F32)):
                    cases = [(x,)] if name != "_pow" else [(np.abs(x), np.full_like(x, 2.5)),
                                                          (np.full_like(x, 2.5), x), (x, np.full_like(x, -1.5))]
                    for a in cases:
                        want = _blocked(getattr(lp, name), *a)
                        assert np.array_equal(_bits(fn(*a)), _bits(want)), (name, fma, a)


def test_shapes_and_layouts(jit_kernels):
    """What LlvmpipeMath passes: vectors (3, n), a one-lane exponent against lanes and lanes
    against a one-lane base, a vector of one-lane components, a strided view; the result has
    the broadcast shape and the reference's bits."""
    lp = LlvmpipeMath(True)
    x = RNG.uniform(0.01, 40.0, (3, 500)).astype(F32)
    cases = {"_sin": [(x,), (x[:, ::2],), (x[:, :1],)],
             "_pow": [(x, x[:, :1]), (x, F32(2.5) * np.ones((1,), F32)), (x[:1, :1], x), (x[0], x[1]),
                      (x[:, ::3], x[:, ::3])]}
    for name, calls in cases.items():
        fn = _compiled(name, lp, jit_kernels, declined := [])
        for args in calls:
            want = _blocked(getattr(lp, name), *args)
            got = fn(*args)
            assert got.shape == want.shape and np.array_equal(got.view(np.int32), want.view(np.int32))
        assert not declined


def test_other_dtypes_stay_on_numpy(jit_kernels):
    lp = LlvmpipeMath(True)
    fn = _compiled("_exp2", lp, jit_kernels, declined := [])
    fn(np.zeros(50_000, F32))
    fn(np.zeros(8, np.float64))
    assert declined == [8]
