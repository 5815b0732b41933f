"""Cube map sampling over lanes, as llvmpipe does it: face selection, face coordinates, seamless
bilinear filtering across the faces' edges and corners, and the implicit LOD of a cube map.

The rules are Mesa 22.3's gallivm (lp_bld_sample.c: lp_build_cube_lookup, lp_build_cube_new_coords,
lp_build_rho; lp_bld_sample_soa.c: lp_build_sample_image_linear with seamless_cube_map, which
Shadertoy's WebGL 2 and the GL verifier's context enable), measured against the driver in
tests/gl/test_cube_maps.py: docs/llvmpipe.md, "Cube maps". textures.TextureFunctions calls
these for a channel whose `ChannelInput.cube` is set (`_sample_cube`, `_implicit_lod`);
compiled_engine/texture_kernels.py has the one-pixel numba forms of the same functions
(tests/compiled/test_cube_kernels.py runs both).

Faces are numbered as OpenGL's: 0 +X, 1 -X, 2 +Y, 3 -Y, 4 +Z, 5 -Z; a face's texels are
`levels[k][face, y, x]`.
"""

from __future__ import annotations

import numpy as np

from ..llvmpipe_math.cube_faces import NEXT_FACE, NEXT_X, NEXT_Y

_SIGN = np.uint32(0x80000000)
_HALF = np.float32(0.5)
_THIRD = np.float32(1.0 / 3.0)


def _bits(v: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(v, dtype=np.float32).view(np.uint32)


def _from_bits(b: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(b, dtype=np.uint32).view(np.float32)


def max_x86(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """lp_build_max as llvmpipe emits it on x86 (maxps): a > b ? a : b, so b where either is NaN
    (the face choice here, and every rho of textures.py)."""
    return np.where(a > b, a, b)


def cube_select(x, y, z):
    """lp_build_cube_lookup's face choice: (face 0..5, major axis value ma, minor s, minor t):
    x when |x| > |y|, then z when |z| >= max(|x|, |y|) (x86 maxps: |y| where either is NaN);
    the minors mirrored by ma's sign bit (an exclusive or, exact: -r, -t; s, r; s, -t for the
    x, y, z faces)."""
    return cube_select_minors(x, y, z, x, y, z)


def cube_coords(x, y, z, derivs: bool = False):
    """(face, s, t): the face's coordinates in [0, 1], minor * |0.5 / ma| + 0.5 (a product and a
    sum, each rounded). The factor is 0.5 / |ma| (lp_build_cube_imapos) for a lookup without
    derivatives, |0.5 * (1 / ma)| for one that computes them (`derivs`: an implicit LOD)."""
    face, ma, sc, tc = cube_select(x, y, z)
    with np.errstate(divide="ignore", invalid="ignore"):
        ima = np.abs(_HALF * (np.float32(1) / ma)) if derivs else _HALF / np.abs(ma)
    return face, sc * ima + _HALF, tc * ima + _HALF


def cube_rho(x, y, z, size: int, ddx, ddy, explicit: bool = False):
    """rho^2 of a cube lookup with derivatives, per pixel (lp_build_cube_lookup with
    derivatives, then lp_build_rho; Mesa 22.3 gives a cube map one LOD per pixel, measured): the
    direction's derivatives along x and y, `ddx` and `ddy` (3 components each: the fine
    differences across the pixel's quad, gallivm's ddx and ddy, for an implicit LOD; the
    shader's for textureGrad) carried onto the pixel's face,
    d.s = (d.sc - (d.ma * (1 / ma)) * sc) * (0.5 * (1 / ma)) and the same for t, then
    max((n d.s)^2 + (n d.t)^2 along x, along y) with x86 maxps, n the face size. `explicit`:
    an infinite or NaN rho^2 reads 0, as lp_build_rho does for given derivatives."""
    x, y, z = (np.asarray(v, dtype=np.float32) for v in (x, y, z))
    _, ma, sc, tc = cube_select(x, y, z)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        ima = np.float32(1) / ma
        imahalf = _HALF * ima
        n = np.float32(size)
        out = []
        for d in (ddx, ddy):
            _, dma, dsc, dtc = cube_select_minors(x, y, z, *d)
            dmadivma = dma * ima
            ds = n * ((dsc - dmadivma * sc) * imahalf)
            dt = n * ((dtc - dmadivma * tc) * imahalf)
            out.append(ds * ds + dt * dt)
        rho2 = max_x86(out[0], out[1])
    return np.where(np.isfinite(rho2), rho2, np.float32(0)) if explicit else rho2


def cube_select_minors(x, y, z, dx, dy, dz):
    """The face of direction (x, y, z) chosen as `cube_select` does, applied to another vector
    (dx, dy, dz), its derivative: (face, its major component, its mirrored minors)."""
    x, y, z = (np.asarray(v, dtype=np.float32) for v in (x, y, z))
    ax, ay, az = np.abs(x), np.abs(y), np.abs(z)
    xsel = ax > ay
    zsel = az >= max_x86(ax, ay)
    ma = np.where(zsel, z, np.where(xsel, x, y))
    sign = _bits(ma) & _SIGN
    dx, dy, dz = (np.asarray(v, dtype=np.float32) for v in (dx, dy, dz))
    dma = np.where(zsel, dz, np.where(xsel, dx, dy))
    bx, by, bz = _bits(dx), _bits(dy), _bits(dz)
    sc = np.where(zsel, bx ^ sign, np.where(xsel, bz ^ _SIGN ^ sign, bx))
    tc = np.where(zsel | xsel, by ^ _SIGN, bz ^ sign)
    face = np.where(zsel, 4, np.where(xsel, 0, 2)) + (sign >> np.uint32(31)).astype(np.int64)
    return face, dma, _from_bits(sc), _from_bits(tc)


def _axis(c: np.ndarray, n: int):
    """One axis of lp_build_sample_image_linear's seamless path: max(c, 0) (a NaN gives 0),
    * n - 0.5, floor and weight; the integer by x86's conversion (huge: INT_MIN)."""
    x = np.fmax(c, np.float32(0)) * np.float32(n) - _HALF
    fl = np.floor(x)
    ok = fl < np.float32(2.0**31)
    i0 = np.where(ok, np.where(ok, fl, 0).astype(np.int64), -(2**31))
    return i0, x - fl


def _remap(face, fall, other, n_max):
    """Face and (x, y) of the texels falling off in direction `fall` (0..3), `other` the
    coordinate along the other axis (lp_build_cube_new_coords)."""
    nf = NEXT_FACE[fall][face]
    cx, cy = NEXT_X[fall][face], NEXT_Y[fall][face]
    return nf, cx[..., 0] * n_max + cx[..., 1] * other, cy[..., 0] * n_max + cy[..., 1] * other


def cube_texel_indices(face, s, t, n: int):
    """The four texels of a seamless bilinear lookup at face coordinates (s, t) of a level of
    size n: ((face, y, x) of texel 00, 01, 10, 11), the weights (fx, fy) and the fall-off masks
    (x < 0, x > n - 1, y < 0, y > n - 1). A texel off an edge is read from the adjacent face;
    at a corner, where it falls off both, it is read through its x edge, and weighted 0
    (`cube_bilinear`)."""
    x0, fx = _axis(s, n)
    y0, fy = _axis(t, n)
    x1, y1 = x0 + 1, y0 + 1
    m = n - 1
    off = (x0 < 0, x1 > m, y0 < 0, y1 > m)
    y0c, y1c = np.maximum(y0, 0), np.minimum(y1, m)
    out = []
    for xs, ys, xfall, yfall in (
        (x0, y0c, 0, 2),
        (x1, y0c, 1, 2),
        (x0, y1c, 0, 3),
        (x1, y1c, 1, 3),
    ):
        f, nx, ny = _remap(face, xfall, ys, m)
        zf, xi, yi = (
            np.where(off[xfall], f, face),
            np.where(off[xfall], nx, xs),
            np.where(off[xfall], ny, ys),
        )
        ysel = off[yfall] & ~off[xfall]
        f, nx, ny = _remap(face, yfall, xs, m)
        out.append((np.where(ysel, f, zf), np.where(ysel, ny, yi), np.where(ysel, nx, xi)))
    return out, fx, fy, off


def cube_bilinear(level: np.ndarray, face, s, t, lerp) -> np.ndarray:
    """One level's seamless bilinear filter, (lanes, 4): lerp(lerp(00, 01, fx), lerp(10, 11,
    fx), fy) with llvmpipe's fused `lerp`; where a texel falls off a corner, the weights
    w = (1 - fx)(1 - fy), fx(1 - fy), (1 - fx)fy, fx fy with a third of the corner's added to
    each of the other three, and the sum w00 c00 + w01 c01 + w10 c10 + w11 c11 (products and
    sums rounded one by one)."""
    n = level.shape[1]
    idx, fx, fy, off = cube_texel_indices(face, s, t, n)
    c = [level[f, y, x] for f, y, x in idx]
    fxe, fye = fx[..., None], fy[..., None]
    out = lerp(lerp(c[0], c[1], fxe), lerp(c[2], c[3], fxe), fye)
    corner = [off[0] & off[2], off[1] & off[2], off[0] & off[3], off[1] & off[3]]
    any_corner = corner[0] | corner[1] | corner[2] | corner[3]
    if any_corner.any():
        one = np.float32(1)
        wx0, wy0 = one - fx, one - fy
        w = [wx0 * wy0, fx * wy0, wx0 * fy, fx * fy]
        cw = np.zeros_like(fx)
        for k in range(4):
            cw = np.where(corner[k], w[k], cw)
        cw = cw * _THIRD
        w = [np.where(corner[k], np.float32(0), w[k] + cw)[..., None] for k in range(4)]
        acc = w[0] * c[0]
        for k in range(1, 4):
            acc = w[k] * c[k] + acc
        out = np.where(any_corner[..., None], acc, out)
    return out
