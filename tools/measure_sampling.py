"""Measure how the GL driver (Mesa llvmpipe here) samples textures; not a test.

Run `python tools/measure_sampling.py`. It prints what
glslcheck/backends/numpy_engine/textures.py copies: (1) lowp/mediump sampler2D results are float32
with the low 13 mantissa bits cleared (highp: exact); (2) linear filtering of an RGBA32F texture
uses float32 weights (4096 distinct, exact weights across a 2-texel texture), and how far
textures.py's bilinear order is from the driver's on random texels; (3) the implicit LOD of
LINEAR_MIPMAP_LINEAR: levels filled with their own index make the result equal the LOD, compared
with 0.5 * fast_log2(max |d|^2) per quad; (4) arithmetic whose operands are all lowp/mediump (a
lookup's result, a lowp or mediump variable, constants) runs in float16 with round to nearest: past
65504 it is inf.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from glslcheck.backends.gl import get_context, renderer_name  # noqa: E402
from glslcheck.backends.gl.program import VERTEX_SHADER, _bind_channel  # noqa: E402
from glslcheck.backends.numpy_engine.textures import _bilinear, _fast_log2, _quad_corner_diff  # noqa: E402
from glslcheck.shadertoy.channels import ChannelInput  # noqa: E402


def run(ctx, body: str, channel: ChannelInput, size, prec: str = "") -> np.ndarray:
    fs = (
        "#version 300 es\nprecision highp float;\nprecision highp int;\n"
        + prec
        + "uniform sampler2D t;\nout vec4 o;\nvoid main() {\n    vec2 f = gl_FragCoord.xy;\n"
        + body
        + "\n}\n"
    )
    prog = ctx.program(vertex_shader=VERTEX_SHADER, fragment_shader=fs)
    tex = _bind_channel(ctx, 0, channel)
    out = ctx.texture(size, 4, dtype="f4")
    fbo = ctx.framebuffer([out])
    fbo.use()
    fbo.clear()
    ctx.vertex_array(prog, []).render(vertices=3)
    img = np.frombuffer(fbo.read(components=4, dtype="f4"), np.float32).reshape(size[1], size[0], 4)
    for o in (fbo, out, tex, prog):
        o.release()
    return img  # row 0 = bottom


def main() -> None:
    ctx = get_context()
    print(f"driver: {renderer_name()}")
    rng = np.random.default_rng(1)
    vals = (rng.normal(size=(16, 16, 4)) * 100).astype(np.float32)
    chan = ChannelInput(vals, "nearest", "clamp")
    trunc = (vals.view(np.uint32) & np.uint32(0xFFFFE000)).view(np.float32)
    for prec in ("", "precision mediump sampler2D;\n", "precision highp sampler2D;\n"):
        got = run(ctx, "o = texelFetch(t, ivec2(f), 0);", chan, (16, 16), prec)
        print(
            f"sampler precision {prec.strip() or '(default: lowp)'}: truncated to 10 mantissa bits "
            f"{np.array_equal(got, trunc)}, exact {np.array_equal(got, vals)}"
        )

    two = np.zeros((1, 2, 4), np.float32)
    two[0, 1] = 1.0
    n = 4096
    got = run(
        ctx,
        f"o = texture(t, vec2(0.25 + 0.5 * f.x / {n}.0, 0.5));",
        ChannelInput(two, "linear", "clamp"),
        (n, 1),
        "precision highp sampler2D;\n",
    )[0, :, 0]
    x = np.float32(0.25) + np.float32(0.5) * (
        (np.arange(n) + 0.5).astype(np.float32) / np.float32(n)
    )
    print(
        f"linear weights: {len(np.unique(got))} distinct over {n} pixels, "
        "max error against float32 "
        f"weights {np.abs(got - (x * 2 - 0.5)).max():.3g}"
    )

    w, h = 64, 36
    tex = rng.normal(size=(5, 7, 4)).astype(np.float32)
    fx, fy = np.meshgrid(
        (np.arange(w) + 0.5).astype(np.float32), (np.arange(h) + 0.5).astype(np.float32)
    )
    u = (fx + np.float32(0.123)) / np.float32(w) * np.float32(1.3) - np.float32(0.15)
    v = (fy + np.float32(0.123)) / np.float32(h) * np.float32(1.3) - np.float32(0.15)
    for wrap in ("clamp", "repeat"):
        body = f"vec2 uv = (f + 0.123) / vec2({w}.0, {h}.0) * 1.3 - 0.15; o = texture(t, uv);"
        got = run(
            ctx, body, ChannelInput(tex, "linear", wrap), (w, h), "precision highp sampler2D;\n"
        )
        ours = _bilinear(tex, u, v, (0, 0), wrap)
        print(
            f"bilinear ({wrap}) against textures.py: {int((got != ours).sum())} of {got.size} "
            "values differ, "
            f"max {np.abs(got - ours).max():.3g} (texels |x| <= {np.abs(tex).max():.2f})"
        )

    levels = 7
    flat = ChannelInput(np.zeros((64, 64, 4), np.float32), "mipmap", "clamp")
    flat._levels = [
        np.full((max(1, 64 >> k), max(1, 64 >> k), 4), float(k), np.float32) for k in range(levels)
    ]
    w, h = 64, 32
    body = (
        "float s = exp2(f.x / 10.0 - 1.0) * (1.0 + 0.3 * f.y / 32.0);"
        "vec2 uv = vec2(f.x * s, f.y * s * 0.7 + f.x * 0.2 * s) / 64.0; o = texture(t, uv);"
    )
    got = run(ctx, body, flat, (w, h), "precision highp sampler2D;\n")[..., 0]
    fx, fy = np.meshgrid(
        (np.arange(w) + 0.5).astype(np.float32), (np.arange(h) + 0.5).astype(np.float32)
    )
    s = np.exp2(fx / np.float32(10) - np.float32(1)) * (
        np.float32(1) + np.float32(0.3) * fy / np.float32(32)
    )
    uv = np.stack([fx * s, fy * s * np.float32(0.7) + fx * np.float32(0.2) * s]) / np.float32(64)
    scaled = (uv * np.float32(64)).reshape(2, -1)
    dx, dy = _quad_corner_diff(scaled, w, 1), _quad_corner_diff(scaled, w, 0)
    lod = np.clip(
        np.float32(0.5) * _fast_log2(np.maximum((dx * dx).sum(0), (dy * dy).sum(0))), 0, levels - 1
    )
    print(
        "implicit LOD per quad, 0.5 * fast_log2(max |d|^2): max error "
        f"{np.abs(lod.reshape(h, w) - got).max():.3g} of a level"
    )

    # (4) arithmetic on lowp/mediump operands only (lookup results, lowp/mediump variables): float16
    w, h = 32, 16
    fx, fy = np.meshgrid(
        (np.arange(w) + 0.5).astype(np.float32), (np.arange(h) + 0.5).astype(np.float32)
    )
    x = (fx / np.float32(7) + fy / np.float32(3)).astype(np.float16)  # RNE to float16
    got = run(
        ctx,
        "mediump float x = f.x / 7.0 + f.y / 3.0; o = vec4(x * 3.3, x + 0.123, x * 1000.0 * 100.0, "
        "1.0 / (x * 1000.0 + 1e6));",
        chan,
        (w, h),
    )
    f16 = [x * np.float16(3.3), x + np.float16(0.123)]
    print(
        "mediump variable arithmetic as float16 (round to nearest): "
        + ", ".join(
            f"{int((got[..., i] != m.astype(np.float32)).sum())} of {m.size} differ"
            for i, m in enumerate(f16)
        )
        + f"; x * 1e5 (over 65504): {np.isinf(got[..., 2]).mean():.0%} inf; "
        "1 / (x * 1000 + 1e6) (the sum past "
        f"float16's range): {(got[..., 3] == 0).mean():.0%} zero"
    )
    w = h = 16
    texel = trunc.astype(
        np.float16
    )  # the lookup's 10-bit result is exact in float16 where in range
    got = run(ctx, "o = texelFetch(t, ivec2(f), 0) * 3.14159265;", chan, (w, h))
    ok = np.abs(trunc) < 60000 / 3.2
    model = (texel * np.float16(3.14159265)).astype(np.float32)
    print(
        "lookup * 3.14159265 without a highp operand: float16 product "
        f"{int((got != model)[ok].sum())} of "
        f"{int(ok.sum())} in-range values differ; float32 product "
        f"{int((got != trunc * np.float32(3.14159265))[ok].sum())}"
    )


if __name__ == "__main__":
    main()
