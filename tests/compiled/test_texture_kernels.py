"""The compiled engine's one-pixel texture sampling (backends/compiled_engine/texture_kernels.py)
against the NumPy backend's (textures.py), bit for bit, on every path: nearest, linear and
mipmap filters, clamp and repeat on power-of-two and other sizes, texel offsets, explicit,
implicit and gradient LODs, lowp and exact results, texelFetch in and out of range,
textureSize at every level, and unbound channels. Coordinates include huge, infinite and NaN
values (what a lockstep lane that a branch left out may hold)."""

from __future__ import annotations

import numpy as np
import pytest
from texture_kernel_helpers import bits, packed, reference

from glslcheck.shadertoy.channels import ChannelInput

F = np.float32
# the reference computes NaN and infinite coordinates as NumPy arrays, which warn about them
pytestmark = pytest.mark.filterwarnings("ignore::RuntimeWarning")


def _channels(rng, size, filter, wrap, lowp):
    w, h = size
    texels = (rng.standard_normal((h, w, 4)) * 3).astype(F)
    texels[0, 0, 0] = F(1e5)  # past float16's range: lowp gives 65504
    texels[-1, -1, 1] = F(3e-6)  # a float16 subnormal
    return ChannelInput(texels, filter, wrap, lowp)


def _coords(rng, n):
    u = rng.uniform(-2.5, 2.5, n).astype(F)
    special = np.array([0, 1, -0.0, 0.5, 1e30, -1e30, np.inf, -np.inf, np.nan, 3e9, 1.2e7], F)
    u[: len(special)] = special
    return u


CASES = [
    ((16, 8), f, w, lowp)
    for f in ("nearest", "linear", "mipmap")
    for w in ("clamp", "repeat")
    for lowp in (True, False)
] + [((12, 10), f, w, True) for f in ("nearest", "linear", "mipmap") for w in ("clamp", "repeat")]


@pytest.mark.parametrize("size,filter,wrap,lowp", CASES)
def test_sample_agrees_bit_for_bit(numba, size, filter, wrap, lowp):
    from glslcheck.backends.compiled_engine import texture_kernels as tk

    rng = np.random.default_rng(hash((size, filter, wrap, lowp)) % 2**32)
    s = _channels(rng, size, filter, wrap, lowp)
    uf, ui, tm = packed(s, 1)
    ref = reference()
    n = 600
    u, v = _coords(rng, n), rng.permutation(_coords(rng, n))
    lods = rng.uniform(-1.5, 6.5, n).astype(F)
    lods[:7] = [0.0, 1.0, 2.0, np.inf, -np.inf, 40.0, np.nan]  # NaN: level 0, unblended
    for offset in ((0, 0), (1, -2)):
        want_plain = ref._sample(s, np.stack([u, v]), offset)
        want_lod = ref.textureLodOffset(s, np.stack([u, v]), lods, offset)
        got_plain = np.array(
            [
                tk.tex_sample(uf, ui, tm, 1, u[i], v[i], offset[0], offset[1], False, F(0))
                for i in range(n)
            ]
        ).T
        got_lod = np.array(
            [
                tk.tex_sample(uf, ui, tm, 1, u[i], v[i], offset[0], offset[1], True, lods[i])
                for i in range(n)
            ]
        ).T
        assert (bits(got_plain) == bits(want_plain)).all()
        assert (bits(got_lod) == bits(want_lod)).all()


@pytest.mark.parametrize("size", [(16, 8), (12, 10)])
def test_implicit_and_gradient_lod_agree(numba, size):
    """The implicit LOD of a tile's quads (the differences from each quad's bottom-left pixel,
    taken here by index) and textureGrad's, as the NumPy backend computes them."""
    from glslcheck.backends.compiled_engine import texture_kernels as tk

    rng = np.random.default_rng(7)
    s = _channels(rng, size, "mipmap", "repeat", True)
    uf, ui, tm = packed(s, 1)
    ref = reference()
    tw, th = 8, 6
    scale = np.float32(2.0) ** rng.uniform(-3, 8, tw * th).astype(F)
    p = (rng.uniform(0, 1, (2, tw * th)) * scale).astype(F)
    want = ref._implicit_lod(s, p, tw)
    for k in range(tw * th):
        y, x = divmod(k, tw)
        bl = (y & ~1) * tw + (x & ~1)
        dx = p[:, bl + 1] - p[:, bl]
        dy = p[:, bl + tw] - p[:, bl]
        got = tk.tex_lod(ui, tm, 1, dx[0], dx[1], dy[0], dy[1], False)
        assert bits(got) == bits(want[k])
    g = (rng.standard_normal((4, 200)) * 0.05).astype(F)
    g[:, :3] = [[np.inf, 0, np.nan], [0, 0, 1], [1e30, 0, 0], [0, 0, 0]]
    want_grad = ref.textureGrad(s, g[:2] * 9, g[:2], g[2:])
    for k in range(200):
        lod = tk.tex_lod(ui, tm, 1, g[0, k], g[1, k], g[2, k], g[3, k], True)
        got = tk.tex_sample(uf, ui, tm, 1, g[0, k] * 9, g[1, k] * 9, 0, 0, True, lod)
        assert (bits(got) == bits(want_grad[:, k])).all()


@pytest.mark.parametrize("lowp", [True, False])
def test_texel_fetch_size_and_unbound_agree(numba, lowp):
    from glslcheck.backends.compiled_engine import texture_kernels as tk

    rng = np.random.default_rng(3)
    s = _channels(rng, (12, 10), "mipmap", "clamp", lowp)
    s.texels[2, 3] = [np.inf, -np.inf, np.nan, -2.0]  # out of range these read 0 * t
    uf, ui, tm = packed(s, 1)
    ref = reference()
    xy = rng.integers(-3, 15, (2, 300)).astype(np.int32)
    xy[:, :2] = [[3, 3], [2, 2]]
    lod = rng.integers(0, 2, 300).astype(np.int32)
    want = ref.texelFetch(s, xy, lod)
    got = np.array([tk.tex_fetch(uf, ui, tm, 1, xy[0, i], xy[1, i], lod[i]) for i in range(300)]).T
    assert (bits(got) == bits(want)).all()
    for level in (-1, 0, 1, 3, 5, 31, 32, 40):
        assert tuple(tk.tex_size(ui, tm, 1, level)) == tuple(
            ref.textureSize(s, np.int32(level)).tolist()
        )
        assert tuple(tk.tex_size(ui, tm, 0, level)) == tuple(
            ref.textureSize(None, np.int32(level)).tolist()
        )
    unbound = ref.texture(None, np.zeros((2, 1), F))[:, 0]
    assert (
        bits(tk.tex_sample(uf, ui, tm, 0, F(0.5), F(0.5), 0, 0, False, F(0))) == bits(unbound)
    ).all()
    assert (bits(tk.tex_fetch(uf, ui, tm, 2, 0, 0, 0)) == bits(unbound)).all()
    assert tk.tex_lowp(ui, tm, 1) == ref.lowp_arith(s) and tk.tex_lowp(ui, tm, 0)


def test_half_rounds_as_numpy_float16(numba):
    """half() against NumPy's float32 -> float16 conversion, on the float16 grid's ties, its
    subnormals, its overflow edge and random values, and float16 arithmetic through it."""
    from glslcheck.backends.compiled_engine import texture_kernels as tk

    rng = np.random.default_rng(5)
    h = np.arange(0, 0x7C01, dtype=np.uint16).view(np.float16).astype(F)  # every finite float16
    mids = (h[:-1] + (h[1:] - h[:-1]) * F(0.5)).astype(F)
    xs = np.concatenate([h, mids, np.nextafter(mids, F(0)), np.nextafter(mids, F(1e9))])
    xs = np.concatenate([xs, -xs, rng.standard_normal(4000).astype(F) * 1e3, [np.inf, -np.inf]])
    want = xs.astype(np.float16).astype(F)
    got = np.array([tk.half(x) for x in xs], F)
    assert (got.view(np.uint32) == want.view(np.uint32)).all()
    a, b = rng.standard_normal((2, 3000)).astype(np.float16) * np.float16(40)
    for op in (np.add, np.subtract, np.multiply, np.divide):
        want = op(a, b).astype(F)
        got = np.array([tk.half(op(x, y)) for x, y in zip(a.astype(F), b.astype(F))], F)
        assert (bits(got) == bits(want)).all()


def test_lod_split_agrees_bit_for_bit(numba):
    """The one rule both engines split a LOD by (textures.lod_split and its one-lane form):
    the lower level and the fraction, clamped to the levels; NaN reads level 0 unblended."""
    from glslcheck.backends.compiled_engine import texture_kernels as tk
    from glslcheck.backends.numpy_engine.textures import lod_split

    rng = np.random.default_rng(11)
    lods = rng.uniform(-3, 9, 500).astype(F)
    special = [0, -0.0, 1, 2.5, 5, 5.5, 6, 7, 1e30, -1e30, np.inf, -np.inf, np.nan, 1e-45]
    lods[: len(special)] = special
    for count in (1, 2, 6):
        level, frac = lod_split(lods, lods.shape, count)
        got = [tk.lod_split(lod, count) for lod in lods]
        assert [int(k) for k, _ in got] == level.tolist()
        assert (bits([f for _, f in got]) == bits(frac)).all()
        assert level.min() >= 0 and level.max() <= count - 1
    assert (level[12], frac[12]) == (0, 0)  # NaN
