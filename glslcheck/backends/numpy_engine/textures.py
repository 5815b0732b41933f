"""Texture sampling on the CPU: the GLSL ES 3.00 lookup built-ins over lanes, as llvmpipe does them.

This module owns the ES 3.00 lookups on a sampler2D for the NumPy backend: `texture`,
`textureLod`, `textureGrad`, `textureOffset`, their `Proj` and `Offset` combinations,
`texelFetch`, `texelFetchOffset` and `textureSize`; and `texture`, `textureLod`, `textureGrad`
and `textureSize` on a samplerCube (a cube map channel: the face math is cube_maps.py's).
`Runtime` inherits them (`TextureFunctions`), so generated code calls
`rt.texture(S.u_iChannel0, uv, S.width)`.
A sampler value is a `glslcheck.shadertoy.channels.ChannelInput` (texels float32 (height, width, 4),
row 0 = texture coordinate t near 0, i.e. the bottom as OpenGL uploads it) or None (unbound: GL's
incomplete texture, which reads (0, 0, 0, 1) and has size 0).

What llvmpipe does (nearest and linear filtering, wraps, lowp results and their float16
arithmetic, mipmap LOD selection), measured with tools/measure_sampling.py and copied
here bit for bit: docs/llvmpipe.md, "Texture sampling".
"""

from __future__ import annotations

from typing import Any

import numpy as np

from . import cube_maps

_LOWP_MASK = np.uint32(0xFFFFE000)  # keep sign, exponent and the top 10 mantissa bits


def _truncate_lowp(v: np.ndarray) -> np.ndarray:
    """llvmpipe's lowp/mediump sampler result: the float32 converted to float16 rounding towards
    zero (gallivm's float-to-half conversion) and back: the mantissa cut to 10 bits, a finite
    magnitude past 65504 gives 65504 (not inf), below 2^-14 a multiple of 2^-24 (subnormal,
    truncated); inf and NaN stay (measured with texelFetch: 1e5 -> 65504, 5e37 -> 65504,
    1e-5 -> 9.954e-6, 3e-8 -> 0)."""
    v = np.ascontiguousarray(v, dtype=np.float32)
    out = (v.view(np.uint32) & _LOWP_MASK).view(np.float32)
    a = np.abs(v)
    if (a < np.float32(2.0**-14)).any() or (np.isfinite(a) & (a > np.float32(65504))).any():
        sub = np.copysign(np.floor(a * np.float32(2.0**24)) * np.float32(2.0**-24), v)
        out = np.where(a < np.float32(2.0**-14), sub, out)
        out = np.where(
            np.isfinite(a) & (a > np.float32(65504)), np.copysign(np.float32(65504), v), out
        )
    return out.astype(np.float32, copy=False)


def _lerp(a: np.ndarray, b: np.ndarray, w: np.ndarray) -> np.ndarray:
    """llvmpipe's lp_build_lerp on floats: fmuladd(w, b - a, a), which LLVM fuses into one FMA
    on x86-64 (measured: bit for bit equal). NumPy has no fma: the product of two float32 values
    is exact in float64, the float64 sum is then rounded to float32 (a second rounding that can
    differ from a single one only when the exact sum needs more than 53 bits and lies within
    2^-29 ulp of a float32 tie: not seen in the measurements)."""
    d = (b - a).astype(np.float64)
    return (np.asarray(w, np.float64) * d + a.astype(np.float64)).astype(np.float32)


_INT_MIN = -(2**31)


def _to_int32(x: np.ndarray) -> np.ndarray:
    """x86's cvttps2dq (LLVM's fptosi there): truncation towards zero; a NaN or a value outside
    int32 gives INT_MIN (0x80000000). Kept in int64 (the wraps below only read low bits or
    clamp)."""
    ok = (x >= np.float32(-(2.0**31))) & (x < np.float32(2.0**31))
    if ok.all():  # the usual case: one conversion (astype truncates towards zero)
        return x.astype(np.int64)
    return np.where(ok, np.trunc(np.where(ok, x, 0)), _INT_MIN).astype(np.int64)


def _ifloor_fract(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """lp_build_ifloor_fract with SSE4.1: floor as a float, the weight x - floor(x), the integer
    by _to_int32 (so a huge or infinite x has weight 0 or NaN and integer INT_MIN)."""
    fl = np.floor(x)
    return _to_int32(fl), x - fl


def _fract_safe(u: np.ndarray) -> np.ndarray:
    """lp_build_fract_safe: u - floor(u), kept below 1 (min with 1 - 2^-24; a NaN, from an
    infinite u, gives the second operand too)."""
    return np.where(
        u - np.floor(u) < np.float32(1 - 2.0**-24), u - np.floor(u), np.float32(1 - 2.0**-24)
    )


def _axis_nearest(u: np.ndarray, n: int, pot: bool, wrap: str, off) -> np.ndarray:
    """lp_build_sample_wrap_nearest along one axis: the texel index for coordinate u, size n
    (`pot`: level 0's size on this axis is a power of two, llvmpipe's static pot_width/height)."""
    nf = np.float32(n)
    if wrap != "repeat":  # CLAMP_TO_EDGE: itrunc(u * n + offset), clamped as an integer
        return np.clip(_to_int32(u * nf + np.asarray(off).astype(np.float32)), 0, n - 1)
    if pot:  # ifloor(u * n) + offset, & (n - 1)
        return (_to_int32(np.floor(u * nf)) + off) & (n - 1)
    if np.any(off):  # the offset in normalised units, before the repeat
        u = u + np.asarray(off).astype(np.float32) / nf
    return _to_int32(_fract_safe(u) * nf)


def _axis_linear(u: np.ndarray, n: int, pot: bool, wrap: str, off):
    """lp_build_sample_wrap_linear along one axis: the two texel indices and the weight."""
    nf, half = np.float32(n), np.float32(0.5)
    if wrap != "repeat":  # CLAMP_TO_EDGE: min(u * n + offset, n) (NaN: n), - 0.5, max(0): no
        # integer overflow for huge or infinite coordinates
        x = np.maximum(np.fmin(u * nf + np.asarray(off).astype(np.float32), nf) - half, 0)
        i0, w = _ifloor_fract(x)
        return i0, np.minimum(i0 + 1, n - 1), w
    if pot:  # u * n - 0.5 (+ offset), ifloor_fract, & (n - 1): huge coordinates read texels 0, 1
        i0, w = _ifloor_fract(u * nf - half + np.asarray(off).astype(np.float32))
        return i0 & (n - 1), (i0 + 1) & (n - 1), w
    if np.any(off):  # lp_build_coord_repeat_npot_linear, the offset in normalised units first
        u = u + np.asarray(off).astype(np.float32) / nf
    x = (u - np.floor(u)) * nf - half
    i0, w = _ifloor_fract(x)
    i0 = np.where(~(x >= 0), n - 1, i0)  # an unordered compare: NaN too
    return i0, np.where(i0 != n - 1, i0 + 1, 0), w


def _pot(t: np.ndarray) -> tuple[bool, bool]:
    """Whether the texture's width and height (level 0) are powers of two."""
    h, w = t.shape[:2]
    return (w & (w - 1)) == 0, (h & (h - 1)) == 0


def _nearest(t: np.ndarray, u, v, offset, wrap: str, pot=None) -> np.ndarray:
    h, w = t.shape[:2]
    pot = _pot(t) if pot is None else pot
    return t[
        _axis_nearest(v, h, pot[1], wrap, offset[1]), _axis_nearest(u, w, pot[0], wrap, offset[0])
    ]


def _bilinear(t: np.ndarray, u, v, offset, wrap: str, pot=None) -> np.ndarray:
    """One level's bilinear filter (see the module docstring for the measured agreement).
    `pot`: level 0's (width, height) power-of-two flags (default: this level's)."""
    h, w = t.shape[:2]
    pot = _pot(t) if pot is None else pot
    xa, xb, fx = _axis_linear(u, w, pot[0], wrap, offset[0])
    ya, yb, fy = _axis_linear(v, h, pot[1], wrap, offset[1])
    fx, fy = fx[..., None], fy[..., None]
    a, b, c, d = t[ya, xa], t[ya, xb], t[yb, xa], t[yb, xb]
    return _lerp(_lerp(a, b, fx), _lerp(c, d, fx), fy)


def _offset(offset) -> tuple:
    off = np.asarray(offset).astype(np.int64)
    return off[0], off[1]


def _project(p) -> np.ndarray:
    p = np.asarray(p, dtype=np.float32)
    return p[:2] / p[-1]


def _fast_log2(x: np.ndarray) -> np.ndarray:
    """Mesa's lp_build_fast_log2 on the float32 bits: (exponent field - 127 - 1) + the mantissa
    with the exponent of 1.0 (in [1, 2)). No special cases: 0 gives -127, +inf 128 and a NaN
    about 128.5, which the LOD clamp turns into the first and the last level."""
    bits = np.ascontiguousarray(x, dtype=np.float32).view(np.uint32)
    exponent = ((bits >> np.uint32(23)) & np.uint32(0xFF)).astype(np.int32) - 128
    mantissa = ((bits & np.uint32(0x007FFFFF)) | np.uint32(0x3F800000)).view(np.float32)
    return exponent.astype(np.float32) + mantissa


def lod_split(lod, shape: tuple, count: int) -> tuple[np.ndarray, np.ndarray]:
    """A mipmap LOD per lane as lp_build_linear_mip_levels splits it: (the lower level, an int
    array, and the blend fraction lod - floor(lod)) of the LOD clamped to the `count` levels; a
    NaN LOD reads the first level, unblended (llvmpipe's integer conversion of it, clamped).
    texture_kernels.lod_split is its one-lane form."""
    lod = np.broadcast_to(np.asarray(lod, dtype=np.float32), shape)
    lod = np.clip(np.where(np.isnan(lod), np.float32(0), lod), np.float32(0), np.float32(count - 1))
    lo = np.floor(lod)
    return lo.astype(np.int64), lod - lo


def _mipmapped(level, count: int, lod, shape: tuple) -> np.ndarray:
    """A lookup between mipmap levels, (lanes..., 4): `level(k, sel)` filters level k at the
    lanes `sel` (None: every lane); the lanes go by their lower level (lod_split), each read
    there and blended with the next level by the fraction (the fused lerp). lp_build_sample_mipmap
    reads the upper level only when some lane's fraction is above 0, so an integer LOD reads
    one level (an infinite texel one level up makes no 0 * inf = NaN); here the lanes that share
    a lower level decide together (texture_kernels.py: each pixel alone)."""
    lo, frac = lod_split(lod, shape, count)
    frac = frac[..., None]

    def two_levels(k, sel, fr):
        a = level(k, sel)
        if k + 1 < count and (fr > 0).any():
            a = _lerp(a, level(k + 1, sel), fr)
        return a

    ks = np.unique(lo)
    if len(ks) == 1:  # one level for every lane (textureLod(s, p, 0.0)): no selection
        return two_levels(int(ks[0]), None, frac)
    out = np.empty(shape + (4,), dtype=np.float32)
    for k in ks:
        sel = lo == k
        out[sel] = two_levels(int(k), sel, frac[sel])
    return out


def _quad_corner_diff(v: np.ndarray, width: int, axis: int) -> np.ndarray:
    """Per 2x2 quad of a `width`-wide tile (lanes row by row from the bottom): the difference
    between the quad's bottom-left pixel and its right (axis 1) or upper (axis 0) neighbour,
    repeated over the quad. An odd last column or row pairs with its left or lower neighbour."""
    n = v.shape[-1]
    img: np.ndarray = v.reshape(v.shape[:-1] + (n // width, width))
    other = 1 - axis
    size: int = img.shape[-2 + axis]
    if size < 2:
        return np.zeros_like(v)
    take = lambda a, sl, ax: a[(Ellipsis, sl, slice(None)) if ax == 0 else (Ellipsis, sl)]  # noqa: E731
    base = take(take(img, slice(0, None, 2), axis), slice(0, None, 2), other)
    step = take(take(img, slice(1, None, 2), axis), slice(0, None, 2), other)
    if step.shape != base.shape:  # odd size: the last pixel pairs with the one before it
        last = take(take(img, slice(size - 1, size), axis), slice(0, None, 2), other) - take(
            take(img, slice(size - 2, size - 1), axis), slice(0, None, 2), other
        )
        d = np.concatenate(
            [step - take(base, slice(0, step.shape[-2 + axis]), axis), last],
            axis=img.ndim - 2 + axis,
        )
    else:
        d = step - base
    d = np.repeat(np.repeat(d, 2, axis=img.ndim - 2), 2, axis=img.ndim - 1)
    d = d[..., : img.shape[-2], : img.shape[-1]]
    return np.ascontiguousarray(d).reshape(v.shape)


class TextureFunctions:
    """The texture lookup built-ins; mixed into `Runtime` (which provides `F` and `_f`)."""

    F: Any
    lp: Any
    _quad_diff: Any  # Runtime's fine derivative (runtime_common.py)

    def _tex_result(self, s, texels: np.ndarray) -> np.ndarray:
        """(4, lanes) in the runtime's float type, truncated as a lowp sampler returns it."""
        out = np.moveaxis(texels, -1, 0)
        if s.lowp:
            out = _truncate_lowp(out)
        return np.ascontiguousarray(out, dtype=self.F)

    def lowp_arith(self, *samplers) -> bool:
        """Whether arithmetic on these samplers' lookups is float16, as on llvmpipe: float32 mode
        (llvmpipe's) and lowp samplers (an unbound channel is lowp too).
        transpile/float16.lowp_tree."""
        return self.lp is not None and all(s is None or s.lowp for s in samplers)

    def lowp_constant(self, s, x) -> np.ndarray:
        """A lookup's constant argument as llvmpipe passes it to a lowp sampler: rounded to
        float16 (to nearest, past 65504 an infinity) in float32 mode
        (nir_fold.lower_precision.float16_lookup_args)."""
        if not self.lowp_arith(s):
            return x
        with np.errstate(over="ignore"):
            return np.asarray(x, np.float32).astype(np.float16).astype(self.F)

    @staticmethod
    def half(x) -> np.ndarray:
        """A float16 operand of transpile/float16.lowp_tree's code (rounded to nearest; a
        lookup's lowp result is already a float16 value)."""
        return np.asarray(x, dtype=np.float16)

    def lowp_full(self, x: np.ndarray) -> np.ndarray:
        """The float16 result of such a tree as the render's float type (exact)."""
        return np.asarray(x, dtype=self.F)

    def _unbound(self, lanes: int) -> np.ndarray:
        out = np.zeros((4, lanes), dtype=self.F)
        out[3] = 1.0
        return out

    def _sample(self, s, p: np.ndarray, offset=(0, 0), lod=None, implicit=False) -> np.ndarray:
        """Filter `s` at texture coordinates p (2, lanes) float32, `offset` texels added to the
        texel coordinates (textureOffset) before the wrap. `lod` (lanes,) selects the mipmap
        levels of a "mipmap" channel (None: level 0); other filters read level 0 only. A cube
        map's p is its direction (3, lanes); `implicit`: its LOD came from derivatives."""
        p = np.asarray(p, dtype=np.float32)
        if s is None:
            return self._unbound(p.shape[-1])
        if s.cube:
            return self._tex_result(s, self._sample_cube(s, p, lod, implicit))
        u, v = p[0], p[1]
        if s.filter == "nearest":
            return self._tex_result(s, _nearest(s.texels, u, v, offset, s.wrap))
        if s.filter == "linear" or lod is None:
            return self._tex_result(s, _bilinear(s.texels, u, v, offset, s.wrap))
        levels = s.levels()
        pot = _pot(levels[0])
        shape = np.broadcast_shapes(u.shape, v.shape, np.shape(lod))
        u, v = np.broadcast_to(u, shape), np.broadcast_to(v, shape)

        def level(k, sel):  # level k's bilinear result at the lanes `sel` (None: all)
            us, vs = (u, v) if sel is None else (u[sel], v[sel])
            return _bilinear(levels[k], us, vs, offset, s.wrap, pot)

        return self._tex_result(s, _mipmapped(level, len(levels), lod, shape))

    @staticmethod
    def _sample_cube(s, d: np.ndarray, lod, implicit: bool) -> np.ndarray:
        """A cube map lookup in direction d (3, lanes): the face and its coordinates, then
        nearest (clamped to the face) or the seamless bilinear filter of one level, or of two
        blended by the LOD's fraction (`_mipmapped`). `implicit`: the LOD came from derivatives
        (implicit or textureGrad's), whose lookup computes the face coordinates another way."""
        face, u, v = cube_maps.cube_coords(d[0], d[1], d[2], implicit and lod is not None)
        if s.filter == "nearest":
            n = s.texels.shape[1]
            x = _axis_nearest(u, n, True, "clamp", 0)
            return s.texels[face, _axis_nearest(v, n, True, "clamp", 0), x]
        if s.filter == "linear" or lod is None:
            return cube_maps.cube_bilinear(s.texels, face, u, v, _lerp)
        levels = s.levels()
        shape = np.broadcast_shapes(u.shape, np.shape(lod))
        face, u, v = (np.broadcast_to(a, shape) for a in (face, u, v))

        def level(k, sel):  # level k's seamless bilinear result at the lanes `sel` (None: all)
            f, us, vs = (face, u, v) if sel is None else (face[sel], u[sel], v[sel])
            return cube_maps.cube_bilinear(levels[k], f, us, vs, _lerp)

        return _mipmapped(level, len(levels), lod, shape)

    def _implicit_lod(self, s, p: np.ndarray, width: int | None, bias=None):
        """llvmpipe's LOD of a 2x2 quad (measured, tools/measure_sampling.py): the
        derivatives of the scaled coordinates between the quad's bottom-left pixel and its right
        and upper neighbours, lod = 0.5 * fast_log2(max(dx.dx, dy.dy)) with fast_log2 the
        piecewise-linear exponent + (mantissa - 1), the same for the four pixels. A cube map's
        LOD is per pixel (cube_maps.cube_rho, measured: tests/gl/test_cube_maps.py)."""
        if s is None or s.filter != "mipmap" or width is None:
            return None
        h, w = s.texels.shape[-3:-1]
        p = np.asarray(p, dtype=np.float32)
        if p.shape[-1] == 1:
            rho2 = np.zeros(1, np.float32)
        elif s.cube:  # per pixel: its fine derivatives (dFdx, dFdy) carried onto its face
            ddx, ddy = ([self._quad_diff(c, width, axis) for c in p] for axis in (1, 0))
            rho2 = cube_maps.cube_rho(p[0], p[1], p[2], w, ddx, ddy)
        else:  # the coordinates' differences, then scaled by the size (not the scaled coordinates')
            size = np.array([w, h], dtype=np.float32)[:, None]
            dx = _quad_corner_diff(p, width, 1) * size
            dy = _quad_corner_diff(p, width, 0) * size
            rho2 = cube_maps.max_x86(dx[0] * dx[0] + dx[1] * dx[1], dy[0] * dy[0] + dy[1] * dy[1])
        lod = np.float32(0.5) * _fast_log2(rho2)
        if bias is not None:
            lod = lod + np.asarray(bias, dtype=np.float32)
        return lod

    @staticmethod
    def _coords(p: Any) -> np.ndarray:
        return np.asarray(p, dtype=np.float32)

    # -- the built-ins (spec 8.8); `width` (the tile width) is for the implicit LOD of mipmaps
    def texture(self, s, p, bias=None, width=None) -> np.ndarray:
        """texture(sampler2D, vec2[, float bias]) with the channel's filter and wrap. Without
        mipmaps the LOD (and so the bias) only chooses between the magnification and
        minification filters, which glslcheck always sets alike."""
        p = self._coords(p)
        return self._sample(s, p, lod=self._implicit_lod(s, p, width, bias), implicit=True)

    def textureLod(self, s, p, lod) -> np.ndarray:
        return self.textureLodOffset(s, p, lod, (0, 0))

    def textureLodOffset(self, s, p, lod, offset) -> np.ndarray:
        mip = s is not None and s.filter == "mipmap"
        return self._sample(s, self._coords(p), _offset(offset), lod if mip else None)

    def textureGrad(self, s, p, dpdx, dpdy) -> np.ndarray:
        """textureGrad(sampler2D, vec2, vec2, vec2) as textureGradOffset; on a samplerCube
        (vec3s) the given derivatives of the direction are carried onto its face as the
        implicit LOD carries its own (cube_maps.cube_rho)."""
        if s is None or not s.cube:
            return self.textureGradOffset(s, p, dpdx, dpdy, (0, 0))
        p = self._coords(p)
        if s.filter != "mipmap":
            return self._sample(s, p)
        p, ddx, ddy = np.broadcast_arrays(p, *(np.asarray(g, np.float32) for g in (dpdx, dpdy)))
        rho2 = cube_maps.cube_rho(p[0], p[1], p[2], s.texels.shape[-2], ddx, ddy, explicit=True)
        return self._sample(s, p, lod=np.float32(0.5) * _fast_log2(rho2), implicit=True)

    def textureGradOffset(self, s, p, dpdx, dpdy, offset) -> np.ndarray:
        """The LOD from the given gradients, by the implicit LOD's formula (`_implicit_lod`)."""
        p = self._coords(p)
        if s is None or s.filter != "mipmap":
            return self._sample(s, p, _offset(offset))
        h, w = s.texels.shape[:2]
        size = np.array([w, h], dtype=np.float32).reshape(2, *([1] * (np.ndim(dpdx) - 1)))
        dx, dy = np.asarray(dpdx, np.float32) * size, np.asarray(dpdy, np.float32) * size
        rho2 = cube_maps.max_x86(dx[0] * dx[0] + dx[1] * dx[1], dy[0] * dy[0] + dy[1] * dy[1])
        rho2 = np.where(
            np.isfinite(rho2), rho2, np.float32(0)
        )  # lp_build_rho: explicit derivatives only
        return self._sample(s, p, _offset(offset), np.float32(0.5) * _fast_log2(rho2))

    # the projective forms: coordinates p.xy / p.z (vec3) or p.xy / p.w (vec4), then as above
    def textureProjOffset(self, s, p, offset, bias=None, width=None) -> np.ndarray:
        return self.textureOffset(s, _project(p), offset, bias, width)

    def textureProjLod(self, s, p, lod) -> np.ndarray:
        return self.textureLod(s, _project(p), lod)

    def textureProjLodOffset(self, s, p, lod, offset) -> np.ndarray:
        return self.textureLodOffset(s, _project(p), lod, offset)

    def textureProjGrad(self, s, p, dpdx, dpdy) -> np.ndarray:
        return self.textureGrad(s, _project(p), dpdx, dpdy)

    def textureProjGradOffset(self, s, p, dpdx, dpdy, offset) -> np.ndarray:
        return self.textureGradOffset(s, _project(p), dpdx, dpdy, offset)

    def textureProj(self, s, p, bias=None, width=None) -> np.ndarray:
        """textureProj(sampler2D, vec3 | vec4): coordinates p.xy / p.z (vec3) or / p.w (vec4)."""
        return self.texture(s, _project(p), bias, width)

    def textureOffset(self, s, p, offset, bias=None, width=None) -> np.ndarray:
        """The (constant) texel offset is added to the integer texel coordinates, before the
        wrap."""
        p = self._coords(p)
        return self._sample(s, p, _offset(offset), self._implicit_lod(s, p, width, bias))

    def texelFetch(self, s, p, lod, *rest) -> np.ndarray:
        """The texel at integer coordinates; out of range (undefined in ES 3.00) reads 0."""
        p = np.asarray(p)
        lanes = p.shape[-1]
        if s is None:
            return self._unbound(lanes)
        h, w = s.texels.shape[:2]
        x, y = p[0].astype(np.int64), p[1].astype(np.int64)
        level = np.broadcast_to(np.asarray(lod), x.shape)
        inside = (x >= 0) & (x < w) & (y >= 0) & (y < h) & (level == 0)
        texels = s.texels[np.clip(y, 0, h - 1), np.clip(x, 0, w - 1)] * inside[..., None]
        return self._tex_result(s, texels)

    def texelFetchOffset(self, s, p, lod, offset) -> np.ndarray:
        return self.texelFetch(s, np.asarray(p) + np.asarray(offset), lod)

    @staticmethod
    def textureSize(s, lod) -> np.ndarray:
        """ivec2 of level `lod`: max(1, size >> lod); (0, 0) when unbound."""
        lod = np.asarray(lod, dtype=np.int32)
        if s is None:
            return np.zeros((2,) + lod.shape, dtype=np.int32)
        h, w = s.texels.shape[-3:-1]
        return np.stack(
            [np.maximum(np.int32(w) >> lod, 1), np.maximum(np.int32(h) >> lod, 1)]
        ).astype(np.int32)
