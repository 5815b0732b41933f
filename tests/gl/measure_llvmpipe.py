"""Measure what the GL driver (Mesa llvmpipe here) returns for GLSL's undefined and edge cases.

Not a test: run `python tests/gl/measure_llvmpipe.py` to regenerate llvmpipe_measurements.md
(the NumPy backend copies these values). Each case is evaluated twice: with literal operands,
which Mesa's compiler folds at compile time, and with operands from uniforms, which llvmpipe
computes at run time; the two can differ. Also times an 800x450 render of a simple shader.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from glslcheck.gl_backend import compile_gl, get_context, renderer_name  # noqa: E402
from glslcheck.gl_backend.program import VERTEX_SHADER  # noqa: E402
from glslcheck.sources import Shader, Source  # noqa: E402

# (case, literal expression, run-time expression, uniform values, what GLSL ES 3.00 says)
CASES = [
    ("pow(-2.0, 2.0)", "pow(-2.0, 2.0)", "pow(fa, fb)", dict(fa=-2.0, fb=2.0), "undefined (x < 0)"),
    ("pow(0.0, 0.0)", "pow(0.0, 0.0)", "pow(fa, fb)", dict(fa=0.0, fb=0.0), "undefined (x = 0, y <= 0)"),
    ("normalize(vec3(0)).x", "normalize(vec3(0.0)).x", "normalize(vec3(fa)).x", dict(fa=0.0), "x / length(x) = 0/0"),
    ("sqrt(-1.0)", "sqrt(-1.0)", "sqrt(fa)", dict(fa=-1.0), "undefined (x < 0)"),
    ("log(0.0)", "log(0.0)", "log(fa)", dict(fa=0.0), "undefined (x <= 0)"),
    ("inversesqrt(0.0)", "inversesqrt(0.0)", "inversesqrt(fa)", dict(fa=0.0), "undefined (x <= 0)"),
    ("smoothstep(1.0, 1.0, 0.5)", "smoothstep(1.0, 1.0, 0.5)", "smoothstep(fa, fb, fc)", dict(fa=1.0, fb=1.0, fc=0.5), "undefined (edge0 >= edge1)"),
    ("smoothstep(1.0, 1.0, 1.0)", "smoothstep(1.0, 1.0, 1.0)", "smoothstep(fa, fb, fc)", dict(fa=1.0, fb=1.0, fc=1.0), "undefined (edge0 >= edge1)"),
    ("mod(-7.5, 2.0)", "mod(-7.5, 2.0)", "mod(fa, fb)", dict(fa=-7.5, fb=2.0), "x - y*floor(x/y) = 0.5"),
    ("int(-7) / 2", "float(int(-7) / 2)", "float(ia / ib)", dict(ia=-7, ib=2), "truncation toward zero: -3"),
    ("-7 % 2 (int)", "float(-7 % 2)", "float(ia % ib)", dict(ia=-7, ib=2), "undefined (negative operand)"),
    ("clamp(0.5, 1.0, 0.0)", "clamp(0.5, 1.0, 0.0)", "clamp(fa, fb, fc)", dict(fa=0.5, fb=1.0, fc=0.0), "undefined (minVal > maxVal); formula min(max(x,lo),hi) = 0"),
    ("int(3.99)", "float(int(3.99))", "float(int(fa))", dict(fa=3.99), "truncation: 3"),
    ("int(-3.99)", "float(int(-3.99))", "float(int(fa))", dict(fa=-3.99), "truncation: -3"),
    ("round(2.5)", "round(2.5)", "round(fa)", dict(fa=2.5), ".5 direction implementation-defined (2 or 3)"),
    ("round(-2.5)", "round(-2.5)", "round(fa)", dict(fa=-2.5), ".5 direction implementation-defined (-2 or -3)"),
    ("roundEven(2.5)", "roundEven(2.5)", "roundEven(fa)", dict(fa=2.5), "2 (to even)"),
    ("2147483647 + 1 (int)", "float(2147483647 + 1)", "float(ia + ib)", dict(ia=2147483647, ib=1), "wraps: -2147483648"),
    ("1e38 * 10.0", "1e38 * 10.0", "fa * fb", dict(fa=1e38, fb=10.0), "overflow: +Inf (IEEE highp)"),
    ("atan(0.0, 0.0)", "atan(0.0, 0.0)", "atan(fa, fb)", dict(fa=0.0, fb=0.0), "undefined (x = y = 0)"),
    ("fract(-0.25)", "fract(-0.25)", "fract(fa)", dict(fa=-0.25), "x - floor(x) = 0.75"),
    ("sign(-0.0)", "sign(-0.0)", "sign(fa)", dict(fa=-0.0), "0.0 (sign of zero unspecified)"),
]

FRAGMENT = """#version 300 es
precision highp float;
precision highp int;
uniform float fa, fb, fc;
uniform int ia, ib;
out vec4 o;
void main() {
    o = vec4(float(%s), 0.0, 0.0, 1.0);
}
"""


def evaluate(ctx, expr: str, values: dict) -> float:
    prog = ctx.program(vertex_shader=VERTEX_SHADER, fragment_shader=FRAGMENT % expr)
    for name, value in values.items():
        if name in prog:
            prog[name].value = value
    tex = ctx.texture((1, 1), 4, dtype="f4")
    fbo = ctx.framebuffer([tex])
    fbo.use()
    ctx.vertex_array(prog, []).render(vertices=3)
    value = np.frombuffer(fbo.read(components=4, dtype="f4"), np.float32)[0]
    fbo.release()
    tex.release()
    return float(value)


def show(x: float) -> str:
    if np.isnan(x):
        return "NaN"
    if np.isinf(x):
        return "+Inf" if x > 0 else "-Inf"
    if x == 0:
        return "-0.0" if np.signbit(x) else "0.0"
    return repr(float(np.float32(x)))


def render_time() -> float:
    image = ("void mainImage(out vec4 c, in vec2 p) {\n    vec2 uv = p / iResolution.xy;\n"
             "    c = vec4(0.5 + 0.5 * cos(iTime + uv.xyx + vec3(0.0, 2.0, 4.0)), 1.0);\n}\n")
    gl = compile_gl(Shader({"Image": Source("Image.glsl", image, "Image")}))
    gl.render()
    runs = 20
    start = time.perf_counter()
    for i in range(runs):
        gl.render(time=i / 60)
    return (time.perf_counter() - start) / runs


def main() -> None:
    ctx = get_context()
    rows = []
    for case, literal, runtime, values, spec in CASES:
        rows.append((case, spec, show(evaluate(ctx, literal, {})), show(evaluate(ctx, runtime, values))))
    seconds = render_time()
    lines = [
        "# What Mesa llvmpipe returns for GLSL ES 3.00 edge cases",
        "",
        f"Measured with `{renderer_name()}`, GL {ctx.version_code}, by `tests/gl/measure_llvmpipe.py`",
        "(regenerate with `python tests/gl/measure_llvmpipe.py`). Values were read back from an RGBA32F",
        "framebuffer, so they are exact float32 (integer results were converted with `float()`).",
        "`literal` uses constant operands, which Mesa's compiler folds at compile time; `run time` takes",
        "the same operands from uniforms, so llvmpipe computes them while shading. A shader's operands",
        "are nearly always run-time values: copy the run-time column, and note where the two differ.",
        "",
        "| case | GLSL ES 3.00 says | llvmpipe, literal (folded) | llvmpipe, run time |",
        "|---|---|---|---|",
    ]
    lines += [f"| `{c}` | {s} | {lit} | {rt} |" for c, s, lit, rt in rows]
    lines += [
        "",
        f"Render time: a simple 800x450 Shadertoy shader (the default new-shader colour cycle) takes "
        f"{seconds * 1000:.1f} ms per frame on llvmpipe, including the float framebuffer read-back.",
        "",
    ]
    out = Path(__file__).with_name("llvmpipe_measurements.md")
    out.write_text("\n".join(lines))
    print("\n".join(lines))


if __name__ == "__main__":
    main()
