"""numba's compiled math kernels (backends/numpy_engine/jit.py) against llvmpipe itself, bit for
bit.

tests/numpy/test_jit_kernels.py compares the kernels with LlvmpipeMath's NumPy reference, which
tests/gl/test_llvmpipe_math.py compares with the driver; this closes the loop directly: the
cases of test_llvmpipe_math.py whose runtime function is a built-in the kernels compute (sin,
cos, tan, exp2, exp, log2, log, pow, and the Mesa lowerings atan, atan(y, x), asin, acos),
evaluated by a runtime with `--jit on`. Each case is one
call per block of 65,536 lanes (llvmpipe_reference.blocked): the first block holds the uniform
arguments and is the kernel's; the second holds the spread magnitudes and the edges, and where those
include a NaN or a huge angle the kernel declines it to NumPy. Needs numba (`jit_kernels`:
skipped without it on a developer machine, a failure on CI) and Mesa 22.3's llvmpipe.
"""

from __future__ import annotations

import numpy as np
import pytest
from image_bits import assert_same_lanes
from llvmpipe_eval import evaluate
from test_llvmpipe_math import EXACT, NA, NB, NT, RT

from glslcheck.backends.numpy_engine import jit
from glslcheck.backends.numpy_engine.runtime import Runtime

KERNEL_BUILTINS = ("sin", "cos", "tan", "exp2", "exp", "log2", "log", "pow", "atan", "asin", "acos")
CASES = [
    c for c in EXACT if getattr(c[1], "__self__", None) is RT and c[1].__name__ in KERNEL_BUILTINS
]
# asin and acos are one call, which the kernel declines when a lane is outside [-1, 1] or NaN (the
# cases' spread and edges): their arguments inside [-1, 1] again, which the kernel must take
TAKEN = [(e, f, a[np.abs(a) <= 1], b) for e, f, a, b in CASES if f.__name__ in ("asin", "acos")]


@pytest.mark.parametrize(
    "case,taken",
    [(c, False) for c in CASES] + [(c, True) for c in TAKEN],
    ids=[f"{c[0]}-{i}" for i, c in enumerate(CASES + TAKEN)],
)
def test_kernels_are_bit_exact_with_llvmpipe(llvmpipe, jit_kernels, monkeypatch, case, taken):
    expr, fn, a, b = case
    monkeypatch.setenv("GLSLCHECK_JIT", "on")
    calls, declined = [], []
    real = jit.compiled

    def counting(name, run, fma, kernels):
        fn = real(name, lambda *args: declined.append(name) or run(*args), fma, kernels)
        return lambda *args: calls.append(name) or fn(*args)

    monkeypatch.setattr(jit, "compiled", counting)
    rt = Runtime("float32")
    ours_fn = getattr(rt, fn.__name__)
    got = evaluate(llvmpipe, expr, a, b)
    with rt.errstate():
        ours = np.asarray(ours_fn(a) if b is None else ours_fn(a, b))
    assert calls, "the kernels were not called"
    assert not (taken and declined), "the kernel declined arguments inside [-1, 1]"
    names = ("the kernels", "llvmpipe")
    assert_same_lanes(ours, got, (a, b), what=expr, names=names, mode="values_any_nan")


def test_mix_kernel_is_bit_exact_with_llvmpipe(llvmpipe, jit_kernels, monkeypatch):
    """mix(a, b, c) with its weight known only at run time (nir_lower_flrp's x + t*(y - x)),
    weights in [-0.5, 1.5]: the compiled fast form, which must take the call, against the
    driver. (A weight of exactly 0 or 1 is a select only where NIR sees a b2f: the runtime's
    per-lane guess for transpiled code, which a texture read is not; the kernel's selects are
    checked against the NumPy form in tests/numpy/test_jit_kernels.py.)"""
    monkeypatch.setenv("GLSLCHECK_JIT", "on")
    t = NT[(NT != 0) & (NT != 1)]
    a, b = NA[: t.size], NB[: t.size]
    got = evaluate(llvmpipe, "mix(a, b, c)", a, b, t)
    rt = Runtime("float32")
    with rt.errstate():
        ours = rt.mix(a, b, t)
    assert [f.__name__ for f in rt.lp._kernels.values()] == ["call"]  # jit.compiled's
    names = ("the kernels", "llvmpipe")
    assert_same_lanes(ours, got, (a, b, t), what="mix(a, b, c)", names=names, mode="values_any_nan")
