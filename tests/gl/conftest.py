"""Fixtures of the GL tests: `gl` and `llvmpipe` are in tests/conftest.py (the texture tests
in tests/channels compare bit for bit with llvmpipe too); `renders_as_llvmpipe` compares a CPU
engine's render with the driver's, bit for bit (tests/image_bits.py)."""

from __future__ import annotations

import image_bits
import pytest


@pytest.fixture
def renders_as_llvmpipe(llvmpipe, request):
    """renders_as_llvmpipe(shader, backend="numpy", *, name=None, size=(160, 90), **inputs)
    asserts that `backend`'s float32 image of `shader` (a Shader, or a folder) is llvmpipe's bit
    for bit (a NaN the same NaN, -0.0 not +0.0), both rendered with the same `inputs` (time,
    frame, mouse...). "compiled" is the compiled engine as `--backend compiled` picks it, and
    asks for the `numba` fixture (skipped without numba, a failure on CI). The message names
    `name` (by default the test's id), the frame, the differing pixels per channel and the first
    one; the rendered images are returned as (cpu, llvmpipe)."""

    def check(shader, backend="numpy", *, name=None, size=image_bits.SIZE, **inputs):
        if backend == "compiled":
            request.getfixturevalue("numba")
        want = image_bits.render(shader, "gl", size=size, **inputs)
        got = image_bits.render(shader, backend, size=size, **inputs)
        what = f"{name or request.node.name} at {image_bits.frame_text(size, **inputs)}"
        image_bits.assert_same(got, want, what=what, names=(backend, "llvmpipe"))
        return got, want

    return check
