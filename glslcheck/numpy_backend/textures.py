"""Texture sampling on the CPU: the GLSL ES 3.00 lookup built-ins over lanes, as llvmpipe does them.

This module owns `texture`, `textureLod`, `textureGrad`, `textureProj`, `textureOffset`,
`texelFetch`, `texelFetchOffset` and `textureSize` for the NumPy backend. `Runtime` inherits
them (`TextureFunctions`), so generated code calls `rt.texture(S.u_iChannel0, uv, S.width)`.
A sampler value is a `glslcheck.channels.ChannelInput` (texels float32 (height, width, 4), row
0 = texture coordinate t near 0, i.e. the bottom as OpenGL uploads it) or None (unbound: GL's
incomplete texture, which reads (0, 0, 0, 1) and has size 0).

What llvmpipe does, measured with tests/channels/measure_sampling.py (Mesa 22.3.6, LLVM 15):

- nearest: texel floor(u * width) (float32 product), then the wrap; bit for bit equal.
- linear on float textures: float32 weights (not 8-bit fixed point: a 2x1 texture 0..1 gave
  4096 distinct, exact weights over 4096 pixels). The weight x = u * width - 0.5, x0 = floor(x),
  w = x - x0, and lerp a + w * (b - a) along x then y. llvmpipe's generated code orders or fuses
  a few of these float32 operations differently: the results differ in the last bits (at most
  1.3e-6 absolute on texel values around 3, measured on a 7x5 texture of normal random values),
  never by 1/255 of anything, which compare.py's tolerance (an absolute tolerance in 1/255
  steps) accepts; tests compare linear filtering with a tolerance of 4e-6 * max |texel|.
- precision: Shadertoy's prelude declares `precision mediump sampler3D` only, so the iChannel
  uniforms it declares are lowp sampler2D (the ES 3.00 fragment default), and llvmpipe honours
  it: every lookup result (after filtering) has its float32 mantissa truncated to 10 bits (the
  low 13 bits cleared; pi reads 3.140625). A `precision highp sampler2D;` in the user's tab comes
  after the uniforms' declarations and changes nothing (measured). The lookups here truncate the
  same way (`ChannelInput.lowp`). Not emulated: GLSL's precision propagation, by which an
  expression whose operands are all lowp (`texture(...) * 2.0`) is lowp and llvmpipe truncates
  its result again; a lookup stored in a (highp) variable first is exact on both backends.
- mipmap filtering (llvmpipe's per-quad LOD and "brilinear" blend) is not emulated: a channel
  with filter "mipmap" is refused by the NumPy backend before rendering (see channels.py).
"""

from __future__ import annotations

from typing import Any

import numpy as np

_LOWP_MASK = np.uint32(0xFFFFE000)  # keep sign, exponent and the top 10 mantissa bits


def _truncate_lowp(v: np.ndarray) -> np.ndarray:
    """llvmpipe's lowp/mediump sampler result: float32 with the mantissa cut to 10 bits."""
    v = np.ascontiguousarray(v, dtype=np.float32)
    return (v.view(np.uint32) & _LOWP_MASK).view(np.float32)


def _wrap(i: np.ndarray, n: int, wrap: str) -> np.ndarray:
    return np.mod(i, n) if wrap == "repeat" else np.clip(i, 0, n - 1)


class TextureFunctions:
    """The texture lookup built-ins; mixed into `Runtime` (which provides `F` and `_f`)."""

    F: Any

    def _tex_result(self, s, texels: np.ndarray) -> np.ndarray:
        """(4, lanes) in the runtime's float type, truncated as a lowp sampler returns it."""
        out = np.moveaxis(texels, -1, 0)
        if s.lowp:
            out = _truncate_lowp(out)
        return np.ascontiguousarray(out, dtype=self.F)

    def _unbound(self, lanes: int) -> np.ndarray:
        out = np.zeros((4, lanes), dtype=self.F)
        out[3] = 1.0
        return out

    def _sample(self, s, p: np.ndarray, offset=(0, 0)) -> np.ndarray:
        """Filter level 0 of `s` at texture coordinates p (2, lanes) float32, `offset` texels
        added to the texel coordinates (textureOffset) before the wrap."""
        p = np.asarray(p, dtype=np.float32)
        if s is None:
            return self._unbound(p.shape[-1])
        h, w = s.texels.shape[:2]
        u, v = p[0], p[1]
        if s.filter == "nearest":
            ix = _wrap(np.floor(u * np.float32(w)).astype(np.int64) + offset[0], w, s.wrap)
            iy = _wrap(np.floor(v * np.float32(h)).astype(np.int64) + offset[1], h, s.wrap)
            return self._tex_result(s, s.texels[iy, ix])
        if s.filter != "linear":
            raise ValueError(f"the NumPy backend does not emulate {s.filter!r} filtering")
        if s.wrap == "repeat":  # the closest of the orders measured (see the module docstring)
            u = u - np.floor(u)
            v = v - np.floor(v)
        x = u * np.float32(w) - np.float32(0.5)
        y = v * np.float32(h) - np.float32(0.5)
        x0, y0 = np.floor(x), np.floor(y)
        fx, fy = (x - x0)[..., None], (y - y0)[..., None]
        x0, y0 = x0.astype(np.int64) + offset[0], y0.astype(np.int64) + offset[1]
        xa, xb = _wrap(x0, w, s.wrap), _wrap(x0 + 1, w, s.wrap)
        ya, yb = _wrap(y0, h, s.wrap), _wrap(y0 + 1, h, s.wrap)
        t = s.texels
        a, b, c, d = t[ya, xa], t[ya, xb], t[yb, xa], t[yb, xb]
        lo = a + fx * (b - a)
        hi = c + fx * (d - c)
        return self._tex_result(s, lo + fy * (hi - lo))

    @staticmethod
    def _coords(p: Any) -> np.ndarray:
        return np.asarray(p, dtype=np.float32)

    # -- the built-ins (spec 8.8); `width` (the tile width) is for the implicit LOD of mipmaps
    def texture(self, s, p, *rest) -> np.ndarray:
        """texture(sampler2D, vec2[, float bias]): level 0 with the channel's filter and wrap.
        Without mipmaps the LOD (and so the bias) only chooses between the magnification and
        minification filters, which glslcheck always sets alike."""
        return self._sample(s, self._coords(p))

    def textureLod(self, s, p, lod, *rest) -> np.ndarray:
        return self._sample(s, self._coords(p))

    def textureGrad(self, s, p, dpdx, dpdy, *rest) -> np.ndarray:
        return self._sample(s, self._coords(p))

    def textureProj(self, s, p, *rest) -> np.ndarray:
        """textureProj(sampler2D, vec3 | vec4): coordinates p.xy / p.z (vec3) or / p.w (vec4)."""
        p = self._coords(p)
        return self._sample(s, p[:2] / p[-1])

    def textureOffset(self, s, p, offset, *rest) -> np.ndarray:
        """The (constant) texel offset is added to the integer texel coordinates, before the wrap."""
        off = np.asarray(offset).astype(np.int64)
        return self._sample(s, self._coords(p), (off[0], off[1]))

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
        h, w = s.texels.shape[:2]
        return np.stack([np.maximum(np.int32(w) >> lod, 1), np.maximum(np.int32(h) >> lod, 1)]).astype(np.int32)
