"""numba's compiled kernels (backends/numpy_engine/jit_kernels.py) against LlvmpipeMath's
step-by-step algorithms, bit for bit, with and without FMA.

Through `jit.compiled`, the function llvmpipe_reference.LlvmpipeMath calls once the kernels are on:
on about 1,500,000 lanes per function and FMA choice, in calls of 1 to 49,152 lanes (a tile), with
the arguments of tests/numpy/test_llvmpipe_fast_kernels.py (every scale, log-spread down to FLT_MIN,
exact multiples of 1/8, where the fused steps' float64 sums land on float32 midpoints; specials
mixed in: +-0, subnormals, +-Inf, NaN, huge). A call the kernel takes must give the reference's bits
exactly; a call it declines (a NaN would come out, or |x| >= 2**29 for sin/cos/tan) goes to the
NumPy function, which must be asked for it. Skipped without numba on a developer machine, a
failure on CI (the `jit_kernels` fixture).
"""

from __future__ import annotations

import numpy as np
import pytest
from image_bits import assert_same_lanes
from test_llvmpipe_fast_kernels import KERNELS as FAST_KERNELS
from test_llvmpipe_fast_kernels import RNG, SPECIALS, _sample

from glslcheck.backends.numpy_engine import jit
from glslcheck.backends.numpy_engine.llvmpipe_reference import LlvmpipeMath, blocked
from glslcheck.backends.numpy_engine.runtime import Runtime

F32 = np.float32
NAMES = ("the kernel", "the reference")
KERNELS = dict(FAST_KERNELS, _tan=(-3, 9.5, False))  # (scale exponents, positive only)


def _compiled(name: str, lp: LlvmpipeMath, kernels, declined: list):
    """The kernel as LlvmpipeMath calls it, its NumPy path the reference (counting declines)."""

    def run(*args):
        declined.append(args[0].size)
        return blocked(getattr(lp, name), *args)

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
            want = blocked(getattr(lp, name), *args)
            before = len(declined)
            got = fn(*args)
            lanes += n
            assert got.dtype == np.float32 and got.shape == want.shape
            mode = "bits_any_nan"
            if len(declined) == before:  # the kernel's lanes: every bit, no NaN among them
                taken += n
                mode = "bits"
            what = f"{name}, fma {fma}, a call of {n} lanes"
            assert_same_lanes(got, want, args, what=what, names=NAMES, mode=mode)
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
                    cases = (
                        [(x,)]
                        if name != "_pow"
                        else [
                            (np.abs(x), np.full_like(x, 2.5)),
                            (np.full_like(x, 2.5), x),
                            (x, np.full_like(x, -1.5)),
                        ]
                    )
                    for a in cases:
                        want = blocked(getattr(lp, name), *a)
                        what = f"{name}, fma {fma}, special {s!r}"
                        got = fn(*a)
                        assert_same_lanes(got, want, a, what=what, names=NAMES, mode="bits_any_nan")


def test_shapes_and_layouts(jit_kernels):
    """What LlvmpipeMath passes: vectors (3, n), a one-lane exponent against lanes and lanes
    against a one-lane base, a vector of one-lane components, a strided view; the result has
    the broadcast shape and the reference's bits."""
    lp = LlvmpipeMath(True)
    x = RNG.uniform(0.01, 40.0, (3, 500)).astype(F32)
    cases = {
        "_sin": [(x,), (x[:, ::2],), (x[:, :1],)],
        "_pow": [
            (x, x[:, :1]),
            (x, F32(2.5) * np.ones((1,), F32)),
            (x[:1, :1], x),
            (x[0], x[1]),
            (x[:, ::3], x[:, ::3]),
        ],
    }
    for name, calls in cases.items():
        fn = _compiled(name, lp, jit_kernels, declined := [])
        for args in calls:
            want = blocked(getattr(lp, name), *args)
            got = fn(*args)
            assert got.shape == want.shape and np.array_equal(
                got.view(np.int32), want.view(np.int32)
            )
        assert not declined


def test_other_dtypes_stay_on_numpy(jit_kernels):
    lp = LlvmpipeMath(True)
    fn = _compiled("_exp2", lp, jit_kernels, declined := [])
    fn(np.zeros(50_000, F32))
    fn(np.zeros(8, np.float64))
    assert declined == [8]


# Runtime's own lowerings (LlvmpipeMath.builtin): name -> (Runtime method, its reference, arguments
# (scale exponents, positive only) per argument). asin/acos: mostly inside [-1, 1], some outside
ARC = {
    "_atan": ("atan", "_atan", [(-38, 38, False)]),
    "_atan2": ("atan", "_atan", [(-38, 38, False)] * 2),
    "_asin": ("asin", "_asin", [(-1, 0.05, False)]),
    "_acos": ("acos", "_acos", [(-1, 0.05, False)]),
}


def _arc_args(name: str, n: int, specials: bool) -> tuple[np.ndarray, ...]:
    args = tuple(_sample(n, *spec, specials) for spec in ARC[name][2])
    if name == "_atan2" and RNG.random() < 0.25:  # equal magnitudes (the quotient taken as 1)
        args = (args[0], args[0] * RNG.choice(np.array([-1, 1], F32), n))
    return args


@pytest.mark.parametrize("fma", [True, False])
@pytest.mark.parametrize("name", sorted(ARC))
def test_arc_kernels_equal_reference(jit_kernels, name, fma):
    """atan, atan2, asin, acos: about 1,500,000 lanes per function and FMA choice (none of them
    has a fused step; a kernel that read `fma` wrongly would show here), the Runtime's NumPy
    lowering the reference. asin/acos decline a call with a lane outside [-1, 1] or NaN (a NaN
    result); atan and atan2 take every call."""
    rt = Runtime("float32", fma=fma)
    method, ref, _ = ARC[name]
    declined: list = []

    def run(*args):
        declined.append(args[0].size)
        return getattr(rt, ref)(*args)

    fn = jit.compiled(name, run, fma, jit_kernels)
    lanes = taken = 0
    with np.errstate(all="ignore"):
        while lanes < 1_500_000:
            n = int(RNG.choice([1, 3, 7, 143, 900, 5000, 16000, 49152]))
            args = _arc_args(name, n, RNG.random() < 1 / 3)
            want = getattr(rt, ref)(*args)
            before = len(declined)
            got = fn(*args)
            lanes += n
            assert got.dtype == np.float32 and got.shape == want.shape
            mode = "bits_any_nan"
            if len(declined) == before:
                taken += n
                mode = "bits"
            else:
                assert name in ("_asin", "_acos"), name
            what = f"{name}, fma {fma}, a call of {n} lanes"
            assert_same_lanes(got, want, args, what=what, names=NAMES, mode=mode)
    assert taken > lanes // 2, (name, fma, taken, lanes)


@pytest.mark.parametrize("name", sorted(ARC))
def test_arc_specials(jit_kernels, name):
    """Every pair of specials (+-0, subnormals, FLT_MIN, +-Inf, NaN, +-FLT_MAX, +-1, ...) for
    atan2, each special alone and beside ordinary lanes for the others, through the Runtime
    method with --jit on: the reference's bits (NaN as one pattern)."""
    rt = Runtime("float32")
    method, ref, _ = ARC[name]
    fn = jit.compiled(name, getattr(rt, ref), rt.lp.fma, jit_kernels)
    with np.errstate(all="ignore"):
        if name == "_atan2":
            y, x = (v.reshape(-1).copy() for v in np.meshgrid(SPECIALS, SPECIALS))
            cases = [(y, x), (y[:1], x), (y, x[:1])]
        else:
            cases = [(np.array([s], F32),) for s in SPECIALS] + [
                (np.array([0.25, s, -0.75], F32),) for s in SPECIALS
            ]
        for args in cases:
            want = getattr(rt, ref)(*args)
            got = fn(*args)
            assert_same_lanes(got, want, args, what=name, names=NAMES, mode="bits_any_nan")


def test_arc_dispatch_in_runtime(jit_kernels, monkeypatch):
    """With --jit on, Runtime.atan/asin/acos call the kernels (vectors, a one-lane argument
    against lanes) and give the bits of --jit off."""
    x = RNG.uniform(-3, 3, (3, 700)).astype(F32)
    u = RNG.uniform(-1, 1, (2, 700)).astype(F32)
    calls = {"atan": [(x,), (x, x[:, :1]), (x[:1, :1], x)], "asin": [(u,)], "acos": [(u[:, ::2],)]}
    got = {}
    for mode in ("on", "off"):
        monkeypatch.setenv("GLSLCHECK_JIT", mode)
        rt = Runtime("float32")
        got[mode] = [getattr(rt, m)(*a) for m, args in calls.items() for a in args]
        assert bool(rt.lp._kernels) and all(
            (f.__name__ == "call") == (mode == "on") for f in rt.lp._kernels.values()
        )
    for on, off in zip(got["on"], got["off"]):
        assert on.shape == off.shape and np.array_equal(on.view(np.int32), off.view(np.int32))


def _weights(n: int) -> np.ndarray:
    """mix's weights: in [0, 1], some exactly 0 or 1 (NIR's selects), some outside, some special."""
    a = RNG.uniform(-0.5, 1.5, n).astype(F32)
    pick = RNG.random(n)
    a[pick < 0.2] = F32(0.0)
    a[(pick >= 0.2) & (pick < 0.4)] = F32(1.0)
    if RNG.random() < 0.2:  # whole calls of selects only
        a = (RNG.random(n) < 0.5).astype(F32)
    if RNG.random() < 1 / 3:
        a[RNG.integers(0, n, max(1, n // 50))] = RNG.choice(SPECIALS, max(1, n // 50))
    return a


@pytest.mark.parametrize("fma", [True, False])
def test_mix_kernel_equals_reference(jit_kernels, fma):
    """mix's fast form, x + a*(y - x) in every lane: about 1,500,000 lanes per FMA
    choice in calls of 1 to 49,152 lanes, same shapes and the broadcasts the transpiler makes
    (vec3 x, y and a float a; a one-lane x or y; vec3 constants of shape (3, 1), read-only
    ones, strided views), specials among x, y and a; a call with an arithmetic NaN is declined
    (and only then)."""
    rt = Runtime("float32", fma=fma)
    declined: list = []

    def run(*args):
        declined.append(args[0].size)
        return rt._mix_fast(*args)

    fn = jit.compiled("_mix", run, fma, jit_kernels)
    lanes = taken = 0
    with np.errstate(all="ignore"):
        while lanes < 1_500_000:
            n = int(RNG.choice([1, 3, 7, 143, 900, 5000, 16000, 49152]))
            specials = RNG.random() < 1 / 3
            x, y = (_sample(n, -3, 5, False, specials) for _ in range(2))
            a = _weights(n)
            shape = RNG.integers(0, 7)
            if shape == 1:  # vec3 x, y; float a
                x, y = x.reshape(1, n).repeat(3, 0) * F32(0.5), np.stack([y, -y, y * F32(3)])
            elif shape == 2:
                x = x[:1]
            elif shape == 3:
                y = y[:1]
            elif shape == 4:  # vec3 constants (3, 1), a float weight per lane
                x, y = x[:3].reshape(-1, 1).copy(), y[:3].reshape(-1, 1).copy()
            elif shape == 5:  # a vec3 constant against vec3 lanes; a strided weight
                x, y = x[:3].reshape(-1, 1).copy(), np.stack([y, y * F32(0.25), -y])
                a = np.stack([a, a])[1]
            elif shape == 6:  # vec3 lanes, a read-only (uniform) constant, a one-lane weight
                x, y = np.stack([x, -x, x]), y[:3].reshape(-1, 1).copy()
                y.flags.writeable = False
                a = a[:1]
            want = rt._mix_fast(x, y, a)
            before = len(declined)
            got = fn(x, y, a)
            lanes += want.size
            assert got.dtype == np.float32 and got.shape == want.shape
            mode = "bits_any_nan"
            if len(declined) == before:
                taken += want.size
                mode = "bits"
            else:
                assert np.isnan(want).any()
            what = f"mix, fma {fma}, shape {shape}, {n} lanes"
            assert_same_lanes(got, want, (x, y, a), what=what, names=NAMES, mode=mode)
    assert taken > lanes // 2, (fma, taken, lanes)


def test_mix_in_runtime(jit_kernels, monkeypatch):
    """Runtime.mix's fast form with --jit on calls the kernel and gives the bits of --jit off;
    the other forms (strict, one, a bool weight) do not reach it."""
    x, y = RNG.uniform(-3, 3, (2, 3, 600)).astype(F32)
    a = _weights(600)
    got = {}
    for mode in ("on", "off"):
        monkeypatch.setenv("GLSLCHECK_JIT", mode)
        rt = Runtime("float32")
        got[mode] = [
            rt.mix(x, y, a, "fast"),
            rt.mix(x[0], y[0], a, "fast"),
            rt.mix(x, y, a[:1], "fast"),
            rt.mix(x, y, a, "strict"),
            rt.mix(x, y, a > 0.5),
        ]
        assert list(rt.lp._kernels) == ["_mix"]
    for on, off in zip(got["on"], got["off"]):
        assert on.shape == off.shape and np.array_equal(on.view(np.int32), off.view(np.int32))
