"""Where a shader asks for mediump or lowp float arithmetic, and what verify says about it.

llvmpipe (Mesa 22.3) lowers GLSL ES precision qualifiers to float16: Mesa's GLSL compiler
(glsl/lower_precision.cpp, on because llvmpipe reports PIPE_SHADER_CAP_FP16) marks each
expression whose operands are all mediump or lowp (variables, lookups on a lowp sampler, calls
of functions declared mediump; a constant takes its partner's precision) and computes it in
float16, with f2fmp conversions at the edges and constants rounded to float16. What is lowered
in the end also depends on NIR's later passes, which glslcheck cannot pin: measured with
tools/measure_mediump.py (moderngl EGL, `#version 300 es`, `precision mediump
float;`, mediump x and y computed from gl_FragCoord):

- `x - y * 1.7`, `fract(x * 3.7)`, `mix(x, y, 0.3)`, `x * y + x`, `dot`, `length`: float16
  with round to nearest after every operation (2048 of 2048 equal to NumPy's float16);
  `x * 1000.0 * 100.0` is inf (past 65504); `fract(sin(x) * 43758.5453)` differs from highp
  by up to 35 times its value;
- `x + y`, `x * y`, `x / y`, `sqrt(x)`, `sin(x)`, `exp2(y)`, `inversesqrt(x)` alone: float32,
  equal to highp in every pixel (one operation on two variables is not lowered);
- `pow(x, 1.3)`: float16-like, within 0.4% of highp but not NumPy's float16 of the float32 pow.

The NumPy backend computes every float in float32 (highp). So verify does not emulate this: it
compares such a shader's pixels with verification/compare.py's usual tolerance (2/255 per channel)
and says why they may differ (`notes`): float16 rounds to 11 significant bits (2^-11 relative per
operation, 0.0005 on a colour of 1, inside the tolerance), but overflows past 65504 and turns a
hash such as `fract(sin(x) * 43758.5453)` into other values, which the tolerance rightly does
not absorb. Declaring `precision highp float;` compares like with like. A lookup's own lowp
result (Shadertoy's samplers are lowp) is emulated (backends/numpy_engine/textures.py); arithmetic
on it directly (`0.5 * texture(...)`) is float16 on llvmpipe too, and here for `+ - * /` over
lookups and constants (backends/cpu_core/nir_fold/lower_precision.py `float16_tree`);
built-in calls on it stay float32, within the same 2^-11 per operation, and are not flagged (nearly
every textured shader has them).
"""

from __future__ import annotations

import re

_COMMENTS = re.compile(r"//[^\n]*|/\*.*?\*/", re.S)
_FLOAT_TYPES = r"(?:float|vec[234]|mat[234](?:x[234])?)"
_MEDIUMP = re.compile(
    r"\bprecision\s+(mediump|lowp)\s+float\b|\b(mediump|lowp)\s+" + _FLOAT_TYPES + r"\b"
)


def mediump_declarations(shader) -> list[tuple[str, int, str]]:
    """(file, line, the declaration's words) of each `precision mediump|lowp float` and each
    mediump or lowp float-typed declaration in the shader's own texts (comments left out)."""
    found = []
    for src in shader.sources():
        text = _COMMENTS.sub(lambda m: "\n" * m.group(0).count("\n"), src.text)
        for m in _MEDIUMP.finditer(text):
            found.append(
                (src.path, text.count("\n", 0, m.start()) + 1, " ".join(m.group(0).split()))
            )
    return found


def mediump_notes(shader) -> tuple[str, ...]:
    """verify's note for a shader with mediump/lowp float arithmetic (empty without any)."""
    found = mediump_declarations(shader)
    if not found:
        return ()
    path, line, words = found[0]
    more = f" (and {len(found) - 1} more)" if len(found) > 1 else ""
    return (
        f"{path}:{line}: `{words}`{more}: llvmpipe computes mediump/lowp float arithmetic in "
        "float16, glslcheck's NumPy backend in float32; pixels are compared with the usual "
        "tolerance (2/255), which float16's rounding (2^-11 relative per operation) stays "
        "inside, but a float16 overflow past 65504 or a hash such as fract(sin(x) * 43758.5453) "
        "differs; declare `precision highp float;` to compare like with like "
        "(glslcheck/semantics/mediump.py)",
    )
