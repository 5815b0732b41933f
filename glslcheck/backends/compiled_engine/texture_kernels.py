"""Texture sampling for one pixel, as numba functions: the compiled engine's lookups.

The same rules as numpy_engine/textures.py (the NumPy backend's lookups over lanes, and the
reference: what llvmpipe does, measured, docs/llvmpipe.md "Texture sampling"), written for one
lane: every function here is the one-lane form of the function of the same name there, the same
float32 operations in the same order (the lerp through float64 as `_lerp` does), so both agree
bit for bit (tests/compiled/test_texture_kernels.py runs both on every path). One difference:
where a mipmap LOD lies exactly on a level, textures.py blends in the next level when some other
lane of the same level has a fraction above 0 (lerp by 0, which changes nothing unless the two
levels' texels differ by an infinity or a NaN); here each pixel decides for itself. Both split a
LOD into a level and a fraction with `lod_split`'s rule.

The texels of the bound channels live in the float uniform array `uf` and their description in
the int one `ui` (`pack` writes both; the generated module passes them as it passes the other
uniforms): at `ui[tm + META * channel]` the words below, then each level's offset into `uf`,
width and height. The texels of a level are row by row from the bottom, RGBA; a cube map's
level is its six faces one after the other (+X, -X, +Y, -Y, +Z, -Z), each of width x height.

Cube maps: `tex_sample_cube`, `tex_lod_cube` and their helpers are the one-lane forms of
numpy_engine/cube_maps.py's functions of the same names (both read their tables, NEXT_FACE,
NEXT_X, NEXT_Y, from llvmpipe_math/cube_faces.py); tests/compiled/test_cube_kernels.py runs
both on every path.
"""

from __future__ import annotations

from ..cpu_core.numba_cache import use_cache_dir

use_cache_dir()  # numba's cache directory first

import numba  # noqa: E402
import numpy as np  # noqa: E402

from ..llvmpipe_math.cube_faces import NEXT_FACE, NEXT_X, NEXT_Y  # noqa: E402
from ..llvmpipe_math.lane import bits, from_bits  # noqa: E402

F32 = np.float32
I32 = np.int32
# a channel's words in ui: bound, filter, wrap, lowp, level count, level-0 power-of-two flags,
# cube map
BOUND, FILTER, WRAP, LOWP, LEVELS, POT_W, POT_H, CUBE = range(8)
LEVEL0 = 8  # then (offset, width, height) per level
MAX_LEVELS = 32  # a 2^31-texel side has 32 levels
META = LEVEL0 + 3 * MAX_LEVELS
FILTERS = {"nearest": 0, "linear": 1, "mipmap": 2}
_J = dict(cache=True, nogil=True, error_model="numpy")
_INT_MIN = -(2**31)
_HALF = F32(0.5)
_ONE_BELOW = F32(1 - 2.0**-24)
_LOWP_MASK = np.uint32(0xFFFFE000)
_MIN_NORMAL16 = F32(2.0**-14)
_MAX16 = F32(65504)
_SUB16 = F32(2.0**24)
_SUB16_INV = F32(2.0**-24)
_HALF_INF = F32(65520)  # the midpoint between float16's largest value and 2^16
_INF = F32(np.inf)


@numba.njit(inline="always", **_J)
def _to_int32(x):
    """textures._to_int32: truncation towards zero; NaN or outside int32 gives INT_MIN."""
    if x >= F32(-(2.0**31)) and x < F32(2.0**31):
        return np.int64(np.trunc(x))
    return np.int64(_INT_MIN)


@numba.njit(inline="always", **_J)
def _fract_safe(u):
    f = u - np.floor(u)
    return f if f < _ONE_BELOW else _ONE_BELOW


@numba.njit(inline="always", **_J)
def _axis_nearest(u, n, pot, repeat, off):
    """textures._axis_nearest for one lane."""
    nf = F32(n)
    if not repeat:
        i = _to_int32(u * nf + F32(off))
        return min(max(i, 0), n - 1)
    if pot:
        return (_to_int32(np.floor(u * nf)) + off) & (n - 1)
    if off != 0:
        u = u + F32(off) / nf
    return min(_to_int32(_fract_safe(u) * nf), n - 1)  # (below n: the fraction is below 1)


@numba.njit(inline="always", **_J)
def _axis_linear(u, n, pot, repeat, off):
    """textures._axis_linear for one lane: (i0, i1, weight)."""
    nf = F32(n)
    if not repeat:
        a = u * nf + F32(off)
        a = a if a < nf else nf  # np.fmin: a NaN gives n
        x = a - _HALF
        x = x if x > F32(0) else F32(0)
        fl = np.floor(x)
        i0 = _to_int32(fl)
        return i0, min(i0 + 1, n - 1), x - fl
    if pot:
        x = u * nf - _HALF + F32(off)
        fl = np.floor(x)
        i0 = _to_int32(fl)
        return i0 & (n - 1), (i0 + 1) & (n - 1), x - fl
    if off != 0:
        u = u + F32(off) / nf
    x = (u - np.floor(u)) * nf - _HALF
    fl = np.floor(x)
    i0 = _to_int32(fl)
    if not (x >= F32(0)):
        i0 = np.int64(n - 1)
    i1 = i0 + 1 if i0 != n - 1 else np.int64(0)
    return i0, i1, x - fl


@numba.njit(inline="always", **_J)
def _lerp(a, b, w):
    """textures._lerp: fmuladd(w, b - a, a) through float64 (one rounding to float32)."""
    return F32(np.float64(w) * np.float64(b - a) + np.float64(a))


@numba.njit(**_J)
def _truncate_lowp(v):
    """textures._truncate_lowp for one value."""
    a = np.abs(v)
    if a < _MIN_NORMAL16:
        return np.copysign(np.floor(a * _SUB16) * _SUB16_INV, v)
    if np.isfinite(a) and a > _MAX16:
        return np.copysign(_MAX16, v)
    return from_bits(bits(v) & _LOWP_MASK)


@numba.njit(inline="always", **_J)
def _texel(uf, at, w, x, y):
    k = at + (y * w + x) * 4
    return uf[k], uf[k + 1], uf[k + 2], uf[k + 3]


@numba.njit(inline="always", **_J)
def _level(ui, m, k):
    """(offset into uf, width, height) of level k of the channel at ui[m]."""
    j = m + LEVEL0 + 3 * k
    return np.int64(ui[j]), np.int64(ui[j + 1]), np.int64(ui[j + 2])


@numba.njit(**_J)
def _nearest(uf, ui, m, u, v, ox, oy):
    at, w, h = _level(ui, m, 0)
    repeat = ui[m + WRAP] != 0
    x = _axis_nearest(u, w, ui[m + POT_W] != 0, repeat, ox)
    y = _axis_nearest(v, h, ui[m + POT_H] != 0, repeat, oy)
    return _texel(uf, at, w, x, y)


@numba.njit(**_J)
def _bilinear(uf, ui, m, k, u, v, ox, oy):
    """textures._bilinear of level k (the wraps chosen by level 0's power-of-two sizes)."""
    at, w, h = _level(ui, m, k)
    repeat = ui[m + WRAP] != 0
    xa, xb, fx = _axis_linear(u, w, ui[m + POT_W] != 0, repeat, ox)
    ya, yb, fy = _axis_linear(v, h, ui[m + POT_H] != 0, repeat, oy)
    a0, a1, a2, a3 = _texel(uf, at, w, xa, ya)
    b0, b1, b2, b3 = _texel(uf, at, w, xb, ya)
    c0, c1, c2, c3 = _texel(uf, at, w, xa, yb)
    d0, d1, d2, d3 = _texel(uf, at, w, xb, yb)
    return (
        _lerp(_lerp(a0, b0, fx), _lerp(c0, d0, fx), fy),
        _lerp(_lerp(a1, b1, fx), _lerp(c1, d1, fx), fy),
        _lerp(_lerp(a2, b2, fx), _lerp(c2, d2, fx), fy),
        _lerp(_lerp(a3, b3, fx), _lerp(c3, d3, fx), fy),
    )


@numba.njit(**_J)
def _result(ui, m, r, g, b, a):
    """textures.TextureFunctions._tex_result: lowp channels truncated."""
    if ui[m + LOWP] != 0:
        return _truncate_lowp(r), _truncate_lowp(g), _truncate_lowp(b), _truncate_lowp(a)
    return r, g, b, a


@numba.njit(inline="always", **_J)
def lod_split(lod, count):
    """textures.lod_split for one lane: (the lower level, the blend fraction) of `lod` clamped
    to the `count` levels; a NaN LOD reads level 0, unblended."""
    if lod != lod:
        return np.int64(0), F32(0)
    top = F32(count - 1)
    c = lod if lod > F32(0) else F32(0)
    c = c if c < top else top
    lo = np.floor(c)
    return np.int64(lo), c - lo


@numba.njit(**_J)
def tex_sample(uf, ui, tm, ch, u, v, ox, oy, has_lod, lod):
    """textures.TextureFunctions._sample: the channel's filter and wrap at (u, v), texel offset
    (ox, oy); `lod` (when has_lod) chooses the levels of a mipmap channel, else level 0."""
    m = tm + META * ch
    if ui[m + BOUND] == 0:
        return F32(0), F32(0), F32(0), F32(1)
    f = ui[m + FILTER]
    if f == 0:
        r, g, b, a = _nearest(uf, ui, m, u, v, ox, oy)
        return _result(ui, m, r, g, b, a)
    if f == 1 or not has_lod:
        r, g, b, a = _bilinear(uf, ui, m, 0, u, v, ox, oy)
        return _result(ui, m, r, g, b, a)
    k, frac = lod_split(lod, ui[m + LEVELS])
    r, g, b, a = _bilinear(uf, ui, m, k, u, v, ox, oy)
    if k + 1 < ui[m + LEVELS] and frac > F32(0):
        r1, g1, b1, a1 = _bilinear(uf, ui, m, k + 1, u, v, ox, oy)
        r, g, b, a = _lerp(r, r1, frac), _lerp(g, g1, frac), _lerp(b, b1, frac), _lerp(a, a1, frac)
    return _result(ui, m, r, g, b, a)


@numba.njit(inline="always", **_J)
def _fast_log2(x):
    """textures._fast_log2 for one value."""
    b = bits(x)
    exponent = I32((b >> np.uint32(23)) & np.uint32(0xFF)) - I32(128)
    mantissa = from_bits((b & np.uint32(0x007FFFFF)) | np.uint32(0x3F800000))
    return F32(exponent) + mantissa


@numba.njit(**_J)
def tex_lod(ui, tm, ch, dxu, dxv, dyu, dyv, explicit):
    """The LOD of a mipmap lookup from the coordinates' differences (dxu, dxv) along x and
    (dyu, dyv) along y: textures.TextureFunctions._implicit_lod (the quad's differences), or
    textureGradOffset's (`explicit`: the given gradients, an infinite or NaN rho read as 0)."""
    m = tm + META * ch
    w, h = F32(ui[m + LEVEL0 + 1]), F32(ui[m + LEVEL0 + 2])
    x0, x1, y0, y1 = dxu * w, dxv * h, dyu * w, dyv * h
    p, q = x0 * x0 + x1 * x1, y0 * y0 + y1 * y1
    rho2 = p if p > q else q  # maxps: q where either is NaN
    if explicit and not np.isfinite(rho2):
        rho2 = F32(0)
    return _HALF * _fast_log2(rho2)


@numba.njit(**_J)
def tex_mipmapped(ui, tm, ch):
    """Whether the channel is bound with mipmap filtering (its lookups read a LOD)."""
    m = tm + META * ch
    return ui[m + BOUND] != 0 and ui[m + FILTER] == 2


@numba.njit(**_J)
def tex_fetch(uf, ui, tm, ch, x, y, lod):
    """textures.TextureFunctions.texelFetch: the texel at (x, y) of level 0; out of range (or
    another level) the clamped texel times 0."""
    m = tm + META * ch
    if ui[m + BOUND] == 0:
        return F32(0), F32(0), F32(0), F32(1)
    at, w, h = _level(ui, m, 0)
    xi, yi = np.int64(x), np.int64(y)
    inside = F32(1) if (0 <= xi < w and 0 <= yi < h and lod == 0) else F32(0)
    r, g, b, a = _texel(uf, at, w, min(max(xi, 0), w - 1), min(max(yi, 0), h - 1))
    return _result(ui, m, r * inside, g * inside, b * inside, a * inside)


@numba.njit(**_J)
def tex_size(ui, tm, ch, lod):
    """textures.TextureFunctions.textureSize: max(1, size >> lod) (a shift of 32 or more, or a
    negative one, gives 0, as NumPy's); (0, 0) unbound."""
    m = tm + META * ch
    if ui[m + BOUND] == 0:
        return I32(0), I32(0)
    w, h = np.int64(ui[m + LEVEL0 + 1]), np.int64(ui[m + LEVEL0 + 2])
    s = np.int64(lod)
    if 0 <= s < 32:
        a, b = w >> s, h >> s
        return I32(a if a > 1 else 1), I32(b if b > 1 else 1)
    return I32(1), I32(1)


@numba.njit(**_J)
def tex_lowp(ui, tm, ch):
    """textures.TextureFunctions.lowp_arith for one channel: its lookups are lowp (or unbound)."""
    m = tm + META * ch
    return ui[m + BOUND] == 0 or ui[m + LOWP] != 0


@numba.njit(**_J)
def lowp_const(ui, tm, ch, x):
    """textures.TextureFunctions.lowp_constant for one value: a lookup's constant argument
    rounded to float16 (`half`) where the channel is lowp."""
    return half(x) if tex_lowp(ui, tm, ch) else x


@numba.njit(**_J)  # (not inlined into numba's IR: a lockstep module calls it hundreds of times)
def half(x):
    """TextureFunctions.half for one value: float32 x rounded to the nearest float16 (ties to
    even; 65520 and past give an infinity), as a float32. An operation of two such values in
    float32 rounded again by `half` is the float16 operation (NumPy's float16 arithmetic does
    the same: a float32 result has more than twice float16's precision)."""
    a = np.abs(x)
    if not (a < _HALF_INF):
        return x if a != a else np.copysign(_INF, x)
    if a < _MIN_NORMAL16:  # float16 subnormals: multiples of 2^-24
        return np.copysign(np.rint(a * _SUB16) * _SUB16_INV, x)
    b = bits(x)
    b = (b + np.uint32(0xFFF) + ((b >> np.uint32(13)) & np.uint32(1))) & np.uint32(0xFFFFE000)
    return from_bits(b)


def pack(channels, uf_base: int) -> tuple[np.ndarray, np.ndarray]:
    """(float tail, int tail) describing iChannel0..3 (`channels`: ChannelInput or None each):
    the texels of every level, at uf offsets from `uf_base`, and META words per channel."""
    meta = np.zeros(4 * META, np.int32)
    parts: list[np.ndarray] = []
    at = uf_base
    for c, s in enumerate(list(channels)[:4]):
        if s is None:
            continue
        m = META * c
        levels = s.levels() if s.filter == "mipmap" else [s.texels]
        h, w = levels[0].shape[-3:-1]
        meta[m + BOUND] = 1
        meta[m + FILTER] = FILTERS[s.filter]
        meta[m + WRAP] = s.wrap == "repeat"
        meta[m + LOWP] = bool(s.lowp)
        meta[m + LEVELS] = len(levels)
        meta[m + POT_W] = (w & (w - 1)) == 0
        meta[m + POT_H] = (h & (h - 1)) == 0
        meta[m + CUBE] = bool(s.cube)
        for k, t in enumerate(levels):
            j = m + LEVEL0 + 3 * k
            meta[j], meta[j + 1], meta[j + 2] = at, t.shape[-2], t.shape[-3]
            parts.append(np.ascontiguousarray(t, np.float32).reshape(-1))
            at += parts[-1].size
    floats = np.concatenate(parts) if parts else np.zeros(0, np.float32)
    return floats, meta


# -- cube maps (cube_maps.py's functions, one lane) --------------------------------------------
_SIGN = np.uint32(0x80000000)
_THIRD = F32(1.0 / 3.0)
_NEXT_FACE = NEXT_FACE.astype(np.int64)
_NEXT_X = NEXT_X.astype(np.int64)
_NEXT_Y = NEXT_Y.astype(np.int64)


@numba.njit(inline="always", **_J)
def _max_x86(a, b):
    return a if a > b else b


@numba.njit(**_J)
def cube_select_minors(x, y, z, dx, dy, dz):
    """cube_maps.cube_select_minors for one lane: (face, major component of d, its minors)."""
    ax, ay, az = np.abs(x), np.abs(y), np.abs(z)
    xsel = ax > ay
    zsel = az >= _max_x86(ax, ay)
    if zsel:
        ma, dma, face = z, dz, np.int64(4)
    elif xsel:
        ma, dma, face = x, dx, np.int64(0)
    else:
        ma, dma, face = y, dy, np.int64(2)
    sign = bits(ma) & _SIGN
    if zsel:
        sc, tc = bits(dx) ^ sign, bits(dy) ^ _SIGN
    elif xsel:
        sc, tc = bits(dz) ^ _SIGN ^ sign, bits(dy) ^ _SIGN
    else:
        sc, tc = bits(dx), bits(dz) ^ sign
    return face + np.int64(sign >> np.uint32(31)), dma, from_bits(sc), from_bits(tc)


@numba.njit(**_J)
def cube_coords(x, y, z, derivs):
    """cube_maps.cube_coords for one lane: (face, s, t)."""
    face, ma, sc, tc = cube_select_minors(x, y, z, x, y, z)
    ima = np.abs(_HALF * (F32(1) / ma)) if derivs else _HALF / np.abs(ma)
    return face, sc * ima + _HALF, tc * ima + _HALF


@numba.njit(inline="always", **_J)
def _face_rho2(x, y, z, sc, tc, ima, n, dx, dy, dz):
    """(n d.s)^2 + (n d.t)^2 of one derivative (dx, dy, dz) of direction (x, y, z) carried
    onto its face (cube_maps.cube_rho's formula)."""
    _, dma, dsc, dtc = cube_select_minors(x, y, z, dx, dy, dz)
    q = dma * ima
    imahalf = _HALF * ima
    ds, dt = n * ((dsc - q * sc) * imahalf), n * ((dtc - q * tc) * imahalf)
    return ds * ds + dt * dt


@numba.njit(**_J)
def cube_rho(x, y, z, size, dxx, dxy, dxz, dyx, dyy, dyz):
    """cube_maps.cube_rho for one lane, given the direction's derivatives along x and y."""
    _, ma, sc, tc = cube_select_minors(x, y, z, x, y, z)
    ima = F32(1) / ma
    n = F32(size)
    rx = _face_rho2(x, y, z, sc, tc, ima, n, dxx, dxy, dxz)
    return _max_x86(rx, _face_rho2(x, y, z, sc, tc, ima, n, dyx, dyy, dyz))


@numba.njit(inline="always", **_J)
def _cube_axis(c, n):
    """cube_maps._axis for one lane: (i0, weight)."""
    c = c if c > F32(0) else F32(0)  # np.fmax(c, 0): a NaN gives 0
    x = c * F32(n) - _HALF
    fl = np.floor(x)
    i0 = np.int64(fl) if fl < F32(2.0**31) else np.int64(_INT_MIN)
    return i0, x - fl


@numba.njit(inline="always", **_J)
def _cube_remap(face, fall, other, n_max):
    """cube_maps._remap for one lane."""
    return (
        _NEXT_FACE[fall, face],
        _NEXT_X[fall, face, 0] * n_max + _NEXT_X[fall, face, 1] * other,
        _NEXT_Y[fall, face, 0] * n_max + _NEXT_Y[fall, face, 1] * other,
    )


@numba.njit(inline="always", **_J)
def _cube_texel(face, xs, ys, xfall, yfall, offx, offy, n_max):
    """One texel of cube_maps.cube_texel_indices: (face, y, x) of the texel at (xs, ys), read
    across the x edge when it falls off there, else across the y edge."""
    if offx:
        f, x, y = _cube_remap(face, xfall, ys, n_max)
        return f, y, x
    if offy:
        f, x, y = _cube_remap(face, yfall, xs, n_max)
        return f, y, x
    return face, ys, xs


@numba.njit(**_J)
def cube_bilinear(uf, at, n, face, s, t):
    """cube_maps.cube_bilinear for one lane, on the level of size n whose faces start at uf[at]:
    the seamless bilinear filter, corners weighted as llvmpipe weights them."""
    x0, fx = _cube_axis(s, n)
    y0, fy = _cube_axis(t, n)
    x1, y1 = x0 + 1, y0 + 1
    m = np.int64(n - 1)
    o0, o1, o2, o3 = x0 < 0, x1 > m, y0 < 0, y1 > m
    y0c, y1c = max(y0, np.int64(0)), min(y1, m)
    fa, ya, xa = _cube_texel(face, x0, y0c, 0, 2, o0, o2, m)
    fb, yb, xb = _cube_texel(face, x1, y0c, 1, 2, o1, o2, m)
    fc, yc, xc = _cube_texel(face, x0, y1c, 0, 3, o0, o3, m)
    fd, yd, xd = _cube_texel(face, x1, y1c, 1, 3, o1, o3, m)
    side = n * n
    a0, a1, a2, a3 = _texel(uf, at + fa * side * 4, n, xa, ya)
    b0, b1, b2, b3 = _texel(uf, at + fb * side * 4, n, xb, yb)
    c0, c1, c2, c3 = _texel(uf, at + fc * side * 4, n, xc, yc)
    d0, d1, d2, d3 = _texel(uf, at + fd * side * 4, n, xd, yd)
    k00, k01, k10, k11 = o0 and o2, o1 and o2, o0 and o3, o1 and o3
    if not (k00 or k01 or k10 or k11):
        return (
            _lerp(_lerp(a0, b0, fx), _lerp(c0, d0, fx), fy),
            _lerp(_lerp(a1, b1, fx), _lerp(c1, d1, fx), fy),
            _lerp(_lerp(a2, b2, fx), _lerp(c2, d2, fx), fy),
            _lerp(_lerp(a3, b3, fx), _lerp(c3, d3, fx), fy),
        )
    wx0, wy0 = F32(1) - fx, F32(1) - fy
    w00, w01, w10, w11 = wx0 * wy0, fx * wy0, wx0 * fy, fx * fy
    cw = F32(0)
    if k00:
        cw = w00
    if k01:
        cw = w01
    if k10:
        cw = w10
    if k11:
        cw = w11
    cw = cw * _THIRD
    w00 = F32(0) if k00 else w00 + cw
    w01 = F32(0) if k01 else w01 + cw
    w10 = F32(0) if k10 else w10 + cw
    w11 = F32(0) if k11 else w11 + cw
    return (
        w11 * d0 + (w10 * c0 + (w01 * b0 + w00 * a0)),
        w11 * d1 + (w10 * c1 + (w01 * b1 + w00 * a1)),
        w11 * d2 + (w10 * c2 + (w01 * b2 + w00 * a2)),
        w11 * d3 + (w10 * c3 + (w01 * b3 + w00 * a3)),
    )


@numba.njit(**_J)
def tex_sample_cube(uf, ui, tm, ch, x, y, z, has_lod, lod, implicit):
    """textures.TextureFunctions._sample_cube for one lane: direction (x, y, z); `lod` (when
    has_lod) chooses a mipmap channel's levels, `implicit`: it came from derivatives."""
    m = tm + META * ch
    if ui[m + BOUND] == 0:
        return F32(0), F32(0), F32(0), F32(1)
    f = ui[m + FILTER]
    face, s, t = cube_coords(x, y, z, implicit and has_lod and f == 2)
    at, n, _ = _level(ui, m, 0)
    if f == 0:
        xi = _axis_nearest(s, n, True, False, 0)
        yi = _axis_nearest(t, n, True, False, 0)
        r, g, b, a = _texel(uf, at + face * n * n * 4, n, xi, yi)
        return _result(ui, m, r, g, b, a)
    if f == 1 or not has_lod:
        r, g, b, a = cube_bilinear(uf, at, n, face, s, t)
        return _result(ui, m, r, g, b, a)
    k, frac = lod_split(lod, ui[m + LEVELS])
    at, n, _ = _level(ui, m, k)
    r, g, b, a = cube_bilinear(uf, at, n, face, s, t)
    if k + 1 < ui[m + LEVELS] and frac > F32(0):
        at, n, _ = _level(ui, m, k + 1)
        r1, g1, b1, a1 = cube_bilinear(uf, at, n, face, s, t)
        r, g, b, a = _lerp(r, r1, frac), _lerp(g, g1, frac), _lerp(b, b1, frac), _lerp(a, a1, frac)
    return _result(ui, m, r, g, b, a)


@numba.njit(**_J)
def tex_lod_cube(ui, tm, ch, x, y, z, dxx, dxy, dxz, dyx, dyy, dyz, explicit):
    """The LOD of a cube map lookup for one lane from the direction's derivatives along x and
    y carried onto its face (cube_rho), 0.5 * fast_log2: textures.TextureFunctions._implicit_lod
    (its fine derivatives), or textureGrad's (`explicit`: the given ones, an infinite or NaN
    rho^2 read as 0)."""
    m = tm + META * ch
    n = ui[m + LEVEL0 + 1]
    rho2 = cube_rho(x, y, z, n, dxx, dxy, dxz, dyx, dyy, dyz)
    if explicit and not np.isfinite(rho2):
        rho2 = F32(0)
    return _HALF * _fast_log2(rho2)
