"""Cube map sampling: the compiled engine's one-pixel kernels (texture_kernels.py, tex_sample_cube
and its helpers) against the NumPy backend's lanes (cube_maps.py through textures.py), bit for
bit on every path: the face choice and its ties, both coordinate forms, texels off each edge
and corner of each face at every level size down to 1x1, nearest, linear and mipmap filters
with explicit and implicit LODs, lowp and exact results, and unbound channels. Directions
include zero, huge, infinite and NaN components (what a lockstep lane a branch left out may
hold). The driver's values are the other test's (tests/gl/test_cube_maps.py)."""

from __future__ import annotations

import numpy as np
import pytest
from texture_kernel_helpers import bits, packed, reference

from glslcheck.shadertoy.channels import ChannelInput

F = np.float32
pytestmark = pytest.mark.filterwarnings("ignore::RuntimeWarning")


def _cube(rng, n, filter, lowp):
    texels = (rng.standard_normal((6, n, n, 4)) * 3).astype(F)
    texels[2, 0, 0, 0] = F(1e5)  # past float16's range: lowp gives 65504
    return ChannelInput(texels, filter, "clamp", lowp, cube=True)


def _directions(rng, n):
    """Random directions, most near the faces' edges and corners (|minor| close to |major|),
    ties, signed zeros and special values."""
    d = rng.uniform(-1, 1, (3, n)).astype(F)
    major = rng.integers(0, 3, n)
    sign = np.where(rng.random(n) < 0.5, F(-1), F(1))
    near = (1 - rng.uniform(0, 0.3, (3, n)) ** 3).astype(F) * np.where(
        rng.random((3, n)) < 0.5, F(-1), F(1)
    )
    d = np.where(rng.random((3, n)) < 0.6, near, d)
    d[major, np.arange(n)] = sign * rng.uniform(0.5, 3, n).astype(F)
    special = [
        (1, 1, 0.3),
        (-1, 1, 1),
        (0.5, -0.5, -0.5),
        (0, 0, 0),
        (-0.0, -0.0, -0.0),
        (1e30, 2, 3),
        (np.inf, 1, 0),
        (-np.inf, np.inf, 0),
        (np.nan, 1, 0),
        (1, np.nan, 2),
        (3e-39, -2e-39, 1e-45),
        (2e-39, 1e-39, 0),  # 1 / ma overflows where 0.5 / |ma| does not
    ]
    d[:, : len(special)] = np.array(special, F).T
    return d


CASES = [
    (n, f, lowp)
    for n in (8, 6, 1)
    for f in ("nearest", "linear", "mipmap")
    for lowp in (True, False)
]


@pytest.mark.parametrize("n,filter,lowp", CASES)
def test_cube_sample_agrees_bit_for_bit(numba, n, filter, lowp):
    from glslcheck.backends.compiled_engine import texture_kernels as tk

    rng = np.random.default_rng(n * 7 + len(filter) + lowp)
    s = _cube(rng, n, filter, lowp)
    uf, ui, tm = packed(s, 2)
    ref = reference()
    count = 800
    d = _directions(rng, count)
    lods = rng.uniform(-1.5, 5.5, count).astype(F)
    lods[:7] = [0.0, 1.0, 2.0, np.inf, -np.inf, 40.0, np.nan]
    for implicit in (False, True):
        lod = lods if filter == "mipmap" else None
        want = ref._sample(s, d, lod=lod, implicit=implicit)
        got = np.array(
            [
                tk.tex_sample_cube(
                    uf, ui, tm, 2, d[0, i], d[1, i], d[2, i], lod is not None, lods[i], implicit
                )
                for i in range(count)
            ]
        ).T
        bad = (bits(got) != bits(want)).any(0)
        assert not bad.any(), f"{int(bad.sum())} lanes differ, first {d[:, bad][:, 0]}"
    plain = ref._sample(s, d)
    got = np.array(
        [tk.tex_sample_cube(uf, ui, tm, 2, *d[:, i], False, F(0), False) for i in range(count)]
    ).T
    assert (bits(got) == bits(plain)).all()


def _derivatives(rng, count):
    """Random derivatives of a direction along x and y, with infinite, NaN, huge and zero ones."""
    ddx = (rng.standard_normal((3, count)) * 0.05).astype(F)
    ddy = (rng.standard_normal((3, count)) * 0.05).astype(F)
    ddx[:, :4] = [[np.inf, 0, np.nan, 0], [0, 0, 1, 0], [1e30, 0, 0, 0]]
    ddy[:, 3] = 0
    scale = np.exp2(rng.uniform(-12, 8, count)).astype(F)  # LODs below, on and above the levels
    return ddx * scale, ddy * scale


@pytest.mark.parametrize("explicit", [False, True])
def test_cube_rho_and_lod_agree(numba, explicit):
    """rho^2 and the LOD from derivatives: the fine differences of an implicit LOD, or
    textureGrad's given ones (an infinite or NaN rho^2 read as 0)."""
    from glslcheck.backends.compiled_engine import texture_kernels as tk
    from glslcheck.backends.numpy_engine import cube_maps

    rng = np.random.default_rng(5)
    count = 600
    d = _directions(rng, count)
    ddx, ddy = _derivatives(rng, count)
    want = cube_maps.cube_rho(d[0], d[1], d[2], 8, ddx, ddy, explicit)
    s = _cube(rng, 8, "mipmap", True)
    uf, ui, tm = packed(s, 2)
    for i in range(count):
        got = tk.cube_rho(d[0, i], d[1, i], d[2, i], 8, *ddx[:, i], *ddy[:, i])
        if explicit and not np.isfinite(got):
            got = F(0)
        assert bits(got) == bits(want[i]), (i, d[:, i])
        lod = tk.tex_lod_cube(ui, tm, 2, *d[:, i], *ddx[:, i], *ddy[:, i], explicit)
        assert bits(lod) == bits(F(0.5) * _reference_fast_log2(want[i]))
    assert not explicit or np.isfinite(want).all()


@pytest.mark.parametrize("n,filter,lowp", CASES)
def test_cube_texture_grad_agrees_bit_for_bit(numba, n, filter, lowp):
    """textureGrad on a cube map: the NumPy backend's lanes against the compiled engine's call
    (tex_lod_cube of the given derivatives, then tex_sample_cube), every filter and size."""
    from glslcheck.backends.compiled_engine import texture_kernels as tk

    rng = np.random.default_rng(n * 5 + len(filter) + lowp)
    s = _cube(rng, n, filter, lowp)
    uf, ui, tm = packed(s, 2)
    count = 800
    d = _directions(rng, count)
    ddx, ddy = _derivatives(rng, count)
    want = reference().textureGrad(s, d, ddx, ddy)
    got = np.array(
        [
            tk.tex_sample_cube(
                uf,
                ui,
                tm,
                2,
                *d[:, i],
                True,
                tk.tex_lod_cube(ui, tm, 2, *d[:, i], *ddx[:, i], *ddy[:, i], True),
                True,
            )
            for i in range(count)
        ]
    ).T
    bad = (bits(got) != bits(want)).any(0)
    assert not bad.any(), f"{int(bad.sum())} lanes differ, first {d[:, bad][:, 0]}"


def _reference_fast_log2(x):
    from glslcheck.backends.numpy_engine.textures import _fast_log2

    return _fast_log2(np.array([x], F))[0]


def test_cube_size_and_unbound_agree(numba):
    from glslcheck.backends.compiled_engine import texture_kernels as tk

    rng = np.random.default_rng(2)
    s = _cube(rng, 8, "mipmap", True)
    uf, ui, tm = packed(s, 2)
    ref = reference()
    for lod in range(5):
        assert tk.tex_size(ui, tm, 2, lod) == tuple(ref.textureSize(s, lod))
    assert tk.tex_sample_cube(uf, ui, tm, 0, F(1), F(0), F(0), False, F(0), False) == (0, 0, 0, 1)
