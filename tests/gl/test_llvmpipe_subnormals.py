"""A subnormal product of two per-pixel values, scaled back up by a division, rendered by
llvmpipe and by both CPU engines bit for bit.

llvmpipe runs its shaders with MXCSR.FTZ (gallivm's lp_build_fpstate_set_denorms_zero): a
product below FLT_MIN is a zero of its sign there, and dividing it by a small value leaves it
zero, where IEEE arithmetic keeps the subnormal and the quotient is a normal number. A path
tracer's Blinn term ``pow(a, 100.0) * G / (4.0 * cos_o * cos_i)`` is such a chain: the tiny
product divided by a small negative cosine is a tiny negative colour on the CPU, and the
``pow(colour, 1.0 / 2.2)`` after it NaN, where llvmpipe gives 0. The shader writes the
quotient and its three operands; :func:`test_llvmpipe_flushes_the_subnormal_product` checks
from those operands that the driver's quotient is the flushed one, and that IEEE's differs
on some pixels (else the comparison proves nothing). Written for llvmpipe of Mesa 22.3 (the
`llvmpipe` fixture skips elsewhere).
"""

from __future__ import annotations

import numpy as np
import pytest
from image_bits import SIZE, assert_same, render

F = np.float32
FLT_MIN = np.finfo(F).tiny
# a and b from 2^-70 down to 2^-80 each: a * b from 2^-140 (subnormal) up to 2^-120 (normal);
# d near 2^-80, so that the quotient of every product is a normal number
SHADER = """void mainImage(out vec4 c, in vec2 p) {
    float u = fract(p.x * 0.1371 + p.y * 0.0917), v = fract(p.x * 0.0371 + p.y * 0.917);
    float a = exp2(-70.0 - 10.0 * u), b = -exp2(-70.0 - 10.0 * v), d = exp2(-80.0 - u);
    c = vec4(a * b / d, a, b, d);
}"""


def _flushed(x: np.ndarray) -> np.ndarray:
    """x with its subnormals as zeros of their sign (x86 FTZ)."""
    return np.where(np.abs(x) < FLT_MIN, np.copysign(F(0.0), x), x).astype(F)


def test_llvmpipe_flushes_the_subnormal_product(llvmpipe, make_shader):
    img = render(make_shader(SHADER), "gl", time=0.0, frame=0).reshape(-1, 4)
    q, a, b, d = (img[:, k] for k in range(4))
    with np.errstate(under="ignore"):
        ieee = (a * b) / d
    flushed = _flushed(a * b) / d
    assert_same(q, flushed, what="a * b / d", names=("llvmpipe", "flushed"))
    assert np.count_nonzero(ieee != flushed) > SIZE[0] * SIZE[1] // 10


def test_numpy_flushes_the_subnormal_product(renders_as_llvmpipe, make_shader):
    renders_as_llvmpipe(make_shader(SHADER), time=0.0, frame=0)


@pytest.mark.parametrize("lanes", [0, 8])
def test_compiled_flushes_the_subnormal_product(llvmpipe, numba, make_shader, lanes):
    """The compiled engine per pixel and in lockstep (its `lanes`), against the driver."""
    from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate

    shader = make_shader(SHADER)
    want = render(shader, "gl", time=0.0, frame=0)
    got = CompiledProgram(*generate(shader, lanes=lanes)).render(size=SIZE, time=0.0, frame=0)
    assert_same(got, want, what=f"lanes {lanes}", names=("compiled", "llvmpipe"))
