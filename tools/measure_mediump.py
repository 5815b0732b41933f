"""Measure how the GL driver (Mesa llvmpipe here) computes mediump float arithmetic; not a test.

Run `python tools/measure_mediump.py`. For each expression it renders a
`#version 300 es` shader with `precision mediump float;` and mediump variables x, y computed from
gl_FragCoord, and prints how many of the 2048 results equal NumPy's float16 evaluation (inputs
rounded to float16, every operation rounded to nearest) and how many equal the same shader with
`precision highp float;`. What it found is in glslcheck/semantics/mediump.py's docstring.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from glslcheck.backends.gl import get_context, renderer_name  # noqa: E402
from glslcheck.backends.gl.program import VERTEX_SHADER  # noqa: E402

W, H = 64, 32
h, f32 = np.float16, np.float32
# name: (GLSL, NumPy float16 model over x, y as float16 arrays)
EXPRESSIONS = {
    "x + y": lambda x, y: x + y,
    "x * y": lambda x, y: x * y,
    "x / y": lambda x, y: x / y,
    "sqrt(x)": lambda x, y: np.sqrt(x),
    "sin(x)": lambda x, y: np.sin(x.astype(f32)).astype(h),
    "exp2(y)": lambda x, y: np.exp2(y.astype(f32)).astype(h),
    "inversesqrt(x)": lambda x, y: (h(1) / np.sqrt(x)).astype(h),
    "pow(x, 1.3)": lambda x, y: np.power(x.astype(f32), f32(1.3)).astype(h),
    "x - y * 1.7": lambda x, y: x - y * h(1.7),
    "fract(x * 3.7)": lambda x, y: x * h(3.7) - np.floor(x * h(3.7)),
    "mix(x, y, 0.3)": lambda x, y: x * (h(1) - h(0.3)) + y * h(0.3),
    "x * y + x": lambda x, y: x * y + x,
    "dot(vec2(x, y), vec2(y, x))": lambda x, y: x * y + y * x,
    "length(vec2(x, y))": lambda x, y: np.sqrt(x * x + y * y),
    "x * 1000.0 * 100.0": lambda x, y: x * h(1000) * h(100),
    "fract(sin(x) * 43758.5453)": lambda x, y: (lambda s: s - np.floor(s))(
        np.sin(x.astype(f32)).astype(h) * h(43758.5453)
    ),
}


def render(ctx, expr: str, precision: str) -> np.ndarray:
    fs = (
        f"#version 300 es\nprecision {precision} float;\nout highp vec4 o;\nvoid main() {{\n"
        "    highp vec2 f = gl_FragCoord.xy;\n"
        f"    {precision} float x = f.x / 7.0 + f.y / 3.0;\n"
        f"    {precision} float y = f.x * 0.37 - f.y / 11.0 + 0.3;\n"
        f"    o = vec4({expr}, 0.0, 0.0, 1.0);\n}}\n"
    )
    prog = ctx.program(vertex_shader=VERTEX_SHADER, fragment_shader=fs)
    out = ctx.texture((W, H), 4, dtype="f4")
    fbo = ctx.framebuffer([out])
    fbo.use()
    fbo.clear()
    ctx.vertex_array(prog, []).render(vertices=3)
    img = np.frombuffer(fbo.read(components=4, dtype="f4"), np.float32).reshape(H, W, 4)[..., 0]
    for o in (fbo, out, prog):
        o.release()
    return img


def main() -> None:
    ctx = get_context()
    print(f"driver: {renderer_name()}")
    fx, fy = np.meshgrid((np.arange(W) + 0.5).astype(f32), (np.arange(H) + 0.5).astype(f32))
    x = (fx / f32(7) + fy / f32(3)).astype(h)
    y = (fx * f32(0.37) - fy / f32(11) + f32(0.3)).astype(h)
    for expr, model in EXPRESSIONS.items():
        got, high = render(ctx, expr, "mediump"), render(ctx, expr, "highp")
        with np.errstate(all="ignore"):
            ours = model(x, y).astype(f32)
            rel = np.nanmax(np.abs(got - high) / np.maximum(np.abs(high), 1e-30))
        print(
            f"{expr:30s} equal to float16: {int((ours == got).sum()):4d}/{got.size}, to highp: "
            f"{int((got == high).sum()):4d}/{got.size}, max relative difference from highp "
            f"{rel:.3g}, inf {int(np.isinf(got).sum())}"
        )


if __name__ == "__main__":
    main()
