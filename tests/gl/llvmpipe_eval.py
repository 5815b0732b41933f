"""Evaluate one GLSL float expression on the live driver for many inputs at once.

`evaluate(ctx, "sin(a)", a)` renders a fragment shader over a grid with one pixel per input;
the operands `a`, `b`, `c` are read from highp R32F textures (`precision highp sampler2D`, or
Mesa clamps them to half range) with texelFetch, so the compiler cannot fold them, and the
result comes back as `floatBitsToInt` in an RGBA32I target: every bit, NaN and -0 included.
Shared by the GL cross-check tests and by tools/measure_llvmpipe.py.
"""

from __future__ import annotations

import numpy as np

VERTEX = "#version 300 es\nin vec2 p; void main(){ gl_Position = vec4(p, 0.0, 1.0); }"
FRAGMENT = """#version 300 es
precision highp float;
precision highp int;
precision highp sampler2D;
uniform sampler2D A, B, C;
%s
out ivec4 o;
void main() {
    ivec2 q = ivec2(gl_FragCoord.xy);
    float a = texelFetch(A, q, 0).x;
    float b = texelFetch(B, q, 0).x;
    float c = texelFetch(C, q, 0).x;
    o = ivec4(0);
    %s
}
"""
WIDTH = 1024


def evaluate(
    ctx, expr: str, a, b=None, c=None, decl: str = "", stmt: str | None = None
) -> np.ndarray:
    """float32 results of `expr` (over float operands a, b, c) per input, in input order.

    `stmt` replaces the default `o.x = floatBitsToInt(<expr>);` (it may set o.x..o.w);
    the result is then the int32 array of shape (n, 4)."""
    a = np.asarray(a, np.float32).ravel()
    n = a.size
    w = min(n, WIDTH)
    h = -(-n // w)

    def pad(x) -> bytes:
        x = (
            np.zeros(n, np.float32)
            if x is None
            else np.broadcast_to(np.asarray(x, np.float32).ravel(), (n,))
        )
        return np.concatenate([x, np.zeros(w * h - n, np.float32)]).tobytes()

    textures = [ctx.texture((w, h), 1, pad(x), dtype="f4") for x in (a, b, c)]
    body = stmt if stmt is not None else f"o.x = floatBitsToInt({expr});"
    prog = ctx.program(vertex_shader=VERTEX, fragment_shader=FRAGMENT % (decl, body))
    for unit, name in enumerate("ABC"):
        if name in prog:
            prog[name].value = unit
            textures[unit].use(unit)
    vbo = ctx.buffer(np.array([-1, -1, 3, -1, -1, 3], dtype="f4").tobytes())
    vao = ctx.simple_vertex_array(prog, vbo, "p")
    target = ctx.texture((w, h), 4, dtype="i4")
    fbo = ctx.framebuffer([target])
    fbo.use()
    fbo.viewport = (0, 0, w, h)
    vao.render()
    out = np.frombuffer(fbo.read(components=4, dtype="i4"), dtype="<i4").reshape(-1, 4)[:n].copy()
    for obj in [vao, vbo, fbo, target, prog] + textures:
        obj.release()
    return out if stmt is not None else out[:, 0].view(np.float32)


def ulp_distance(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Float32 ULP distance per element (0 where both are NaN; -0 and +0 are 0 apart)."""
    xi = np.asarray(x, np.float32).view(np.int32).astype(np.int64)
    yi = np.asarray(y, np.float32).view(np.int32).astype(np.int64)
    xi = np.where(xi < 0, -(2**31) - xi, xi)
    yi = np.where(yi < 0, -(2**31) - yi, yi)
    d = np.abs(xi - yi)
    return np.where(np.isnan(x) & np.isnan(y), 0, d)
