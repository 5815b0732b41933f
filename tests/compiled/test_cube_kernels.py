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

from glslcheck.shadertoy.channels import ChannelInput

F = np.float32
pytestmark = pytest.mark.filterwarnings("ignore::RuntimeWarning")


class _Ref:
    F = np.float32
    lp = object()


def _reference():
    from glslcheck.backends.numpy_engine.textures import TextureFunctions

    return type("Ref", (_Ref, TextureFunctions), {})()


def _bits(a):
    a = np.asarray(a, F)
    return np.where(np.isnan(a), np.uint32(0x7FC00000), a.view(np.uint32))


def _cube(rng, n, filter, lowp):
    texels = (rng.standard_normal((6, n, n, 4)) * 3).astype(F)
    texels[2, 0, 0, 0] = F(1e5)  # past float16's range: lowp gives 65504
    return ChannelInput(texels, filter, "clamp", lowp, cube=True)


def _packed(channel):
    from glslcheck.backends.numpy_engine import texture_kernels as tk

    floats, meta = tk.pack([None, None, channel], 3)
    uf = np.concatenate([np.zeros(3, F), floats])
    ui = np.concatenate([np.zeros(5, np.int32), meta])
    return uf, ui, 5


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
    from glslcheck.backends.numpy_engine import texture_kernels as tk

    rng = np.random.default_rng(n * 7 + len(filter) + lowp)
    s = _cube(rng, n, filter, lowp)
    uf, ui, tm = _packed(s)
    ref = _reference()
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
        bad = (_bits(got) != _bits(want)).any(0)
        assert not bad.any(), f"{int(bad.sum())} lanes differ, first {d[:, bad][:, 0]}"
    plain = ref._sample(s, d)
    got = np.array(
        [tk.tex_sample_cube(uf, ui, tm, 2, *d[:, i], False, F(0), False) for i in range(count)]
    ).T
    assert (_bits(got) == _bits(plain)).all()


def test_cube_rho_and_lod_agree(numba):
    from glslcheck.backends.numpy_engine import cube_maps
    from glslcheck.backends.numpy_engine import texture_kernels as tk

    rng = np.random.default_rng(5)
    count = 600
    d = _directions(rng, count)
    ddx = (rng.standard_normal((3, count)) * 0.05).astype(F)
    ddy = (rng.standard_normal((3, count)) * 0.05).astype(F)
    ddx[:, :3] = [[np.inf, 0, np.nan], [0, 0, 1], [1e30, 0, 0]]
    diffs = {1: ddx, 0: ddy}
    k = {"i": 0}

    def fine_diff(v, axis):  # the reference reads the derivatives of x, y, z in turn
        out = diffs[axis][k["i"] % 3]
        k["i"] += 1
        return out

    want = cube_maps.cube_rho(d[0], d[1], d[2], 8, fine_diff)
    s = _cube(rng, 8, "mipmap", True)
    uf, ui, tm = _packed(s)
    for i in range(count):
        got = tk.cube_rho(d[0, i], d[1, i], d[2, i], 8, *ddx[:, i], *ddy[:, i])
        assert _bits(got) == _bits(want[i]), (i, d[:, i])
        lod = tk.tex_lod_cube(ui, tm, 2, *d[:, i], *ddx[:, i], *ddy[:, i])
        want_lod = F(0.5) * _reference_fast_log2(want[i])
        assert _bits(lod) == _bits(want_lod)


def _reference_fast_log2(x):
    from glslcheck.backends.numpy_engine.textures import _fast_log2

    return _fast_log2(np.array([x], F))[0]


def test_cube_size_and_unbound_agree(numba):
    from glslcheck.backends.numpy_engine import texture_kernels as tk

    rng = np.random.default_rng(2)
    s = _cube(rng, 8, "mipmap", True)
    uf, ui, tm = _packed(s)
    ref = _reference()
    for lod in range(5):
        assert tk.tex_size(ui, tm, 2, lod) == tuple(ref.textureSize(s, lod))
    assert tk.tex_sample_cube(uf, ui, tm, 0, F(1), F(0), F(0), False, F(0), False) == (0, 0, 0, 1)
