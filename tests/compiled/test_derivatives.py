"""dFdx, dFdy and fwidth in the compiled engine: lockstep blocks of 2x2 quads (lanes.py
quad_lanes) against the NumPy backend, bit for bit.

The NumPy backend's derivatives are llvmpipe's (fine, quads from even x and y, helper pixels
past an odd edge; verified against GL in tests/real_verify), so the compiled engine must give
its bits. The per-pixel engine cannot compute a derivative (one pixel a call): a shader with one
renders in lockstep from its first frame, and a fixed per-pixel mode is a located error.
Sizes: even (40x24) and odd on both axes (41x23: a helper column and a helper row), at 8 and 16
lanes (quads of 4 and 8 columns: 41 is a multiple of neither, so a block lies past the edge).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from image_bits import assert_same, frame_text

import glslcheck
from glslcheck.base.diagnostics import GlslError

MOUSE = (10.0, 7.0, 3.0, -2.0)

DERIVATIVES = {
    # the plain cases: linear and non-linear values, vectors, a uniform (0), x = dFdx(x)
    "plain": """
void mainImage(out vec4 c, in vec2 f) {
    vec2 uv = f / iResolution.xy;
    vec2 d = dFdx(uv * uv) * 1000.0 + dFdy(sin(uv * 9.0)) * 100.0;
    float t = dFdx(iTime) + dFdy(iTime * 3.0);            // uniform: 0
    float s = uv.x * uv.y * 50.0;
    s = dFdx(s) + fwidth(s);                              // the \
        quad's lanes read before any is written
    vec3 w = fwidth(vec3(uv, uv.x * uv.y * 7.0)) * 40.0;
    c = vec4(d, s + t, 1.0) + vec4(w, 0.0);
}""",
    # Inigo Quilez's filtered checkers (h41-raymarch of the hold-out corpus), reached under
    # divergent branches in a called function: the quad's other lanes compute it too
    "branch_checkers": """
float checkersGradBox(in vec2 p) {
    vec2 w = fwidth(p) + 0.001;
    vec2 i = 2.0 * (abs(fract((p - 0.5 * w) * 0.5) - 0.5) - abs(fract((p + 0.5 * w) * 0.5) - \
        0.5)) / w;
    return 0.5 - 0.5 * i.x * i.y;
}
void mainImage(out vec4 c, in vec2 f) {
    vec2 uv = (2.0 * f - iResolution.xy) / iResolution.y;
    vec3 col = vec3(0.2);
    float m = uv.y < 0.0 ? 1.0 : 2.0;
    if (length(uv) < 1.2) {
        vec2 pos = uv / max(abs(uv.y), 0.05) * 3.0;
        col = vec3(0.6, 0.3, 0.1);
        if (m < 1.5) {
            float k = checkersGradBox(pos + iTime);
            col = 0.3 + k * vec3(0.6);
        }
    }
    c = vec4(col, 1.0);
}""",
    # derivatives of values a divergent loop and an early return computed (IQ's checkers2D of
    # the tuned corpus: max of |dFdx| and |dFdy|)
    "after_divergent_loop": """
float march(vec2 p) {
    float t = 0.0;
    for (int i = 0; i < 40; i++) {
        float d = length(p - vec2(0.3, 0.2)) - 0.25 - t * 0.05;
        if (d < 0.001) break;
        t += d * 0.7;
        if (t > 3.0) return -1.0;
    }
    return t;
}
void mainImage(out vec4 c, in vec2 f) {
    vec2 uv = f / iResolution.xy;
    float t = march(uv);
    vec2 p = uv * (3.0 + t);
    vec2 w = max(abs(dFdx(p)), abs(dFdy(p))) + 0.01;
    c = vec4(w * 10.0, t, 1.0);
}""",
    # a local declared and written after a divergent early return, its derivative read there:
    # a returned neighbour holds the value it computed (gargantua's GasDisc, radialCoords)
    "local_after_early_return": """
float disc(vec2 p) {
    float c = sin(p.x * 7.0) + cos(p.y * 5.0);
    if (c < 0.2) return c;
    vec3 r;
    r.x = p.x * 3.1 + c;
    r.y = p.y * 2.3 - c * c;
    r *= 0.95;
    return dFdx(r.x) * 10.0 + dFdy(r.y) * 5.0;
}
void mainImage(out vec4 c, in vec2 f) {
    vec2 uv = f / iResolution.xy;
    c = vec4(disc(uv * 3.0), disc(uv.yx * 2.0 + 1.0), 0.0, 1.0);
}""",
}


# a local written again at its declaration's level inside a branch (`q.x -= 0.05`), read by a
# neighbour's derivative in a nested branch: the lanes outside the branch hold the value computed
# in every lane (llvmpipe's SSA value, the NumPy backend's free write), not the value before the
# write (surfer_boy's eye: `q.x -= eyeOff`, then `atan` of it under `if (m < 0.0)`)
DERIVATIVES["write_at_declaration_level"] = """
vec3 shade(vec2 uv, float id) {
    vec3 col = vec3(0.1);
    if (id < 1.5) {
        col = vec3(uv, 0.0);
    } else if (id < 2.5) {
        vec2 q = abs(uv * 2.0 - 1.0);
        q.x -= 0.05;
        vec2 r = q - vec2(0.3, 0.1);
        float m = length(r) - 0.4;
        if (m < 0.0) {
            float an = r.y * r.x + 1.5;
            col = vec3(dFdx(an), dFdy(an), an);
        }
    }
    return col;
}
void mainImage(out vec4 c, in vec2 f) {
    vec2 uv = f / iResolution.xy;
    vec3 col = vec3(0.0);
    if (uv.y > 0.1) {
        col = shade(uv, f.y > 13.0 ? 2.0 : 1.0);  // a quad row of each size is split here
    }
    c = vec4(col, 1.0);
}"""


# a call's result in the lanes a mask leaves out, read by a neighbour's derivative: a lane that
# returned holds the value of the last pass it ran the call in, in a loop NIR keeps (40 steps),
# zero in one it unrolls (4) (llvmpipe's register for returns merged after inlining:
# nir_fold.register_call; tests/gl's test_a_result_returned_from_a_branch_keeps_its_old_value_...)
KEPT_RETURNS = (
    Path(__file__).resolve().parents[1] / "gl" / "shaders" / "kept_returns.glsl"
).read_text()
DERIVATIVES["register_in_kept_loop"] = KEPT_RETURNS.replace("STEPS", "40")
DERIVATIVES["register_in_unrolled_loop"] = KEPT_RETURNS.replace("STEPS", "4")
# a loop of 6 passes whose body costs too much for NIR to unroll keeps the register
# (nir_fold.loop_unroll.nir_unrolls; tests/gl's test_the_register_is_kept_in_a_short_loop_...)
DERIVATIVES["register_in_short_kept_loop"] = (
    KEPT_RETURNS.replace("STEPS", "6")
    .replace("float acc = 0.0;", "float acc = 0.0, a = p.y * 0.013;")
    .replace(
        "float(i) * 0.37));",
        "float(i) * 0.37));\n" + "".join(f"a = sin(a * 1.01 + {k + 1}.0);\n" for k in range(24)),
    )
    .replace("c = vec4(acc, 0.0, 0.0, 1.0);", "c = vec4(acc, a, 0.0, 1.0);")
)
# an array returned from a branch, one element of it read by a neighbour's derivative (its
# return slots, one per element, hold zero where no return wrote them: lanes_rt.lzero)
DERIVATIVES["array_returned_from_a_branch"] = """
float[8] pick(float x) {
    float r[8];
    for (int i = 0; i < 8; i++) { r[i] = sin(x * float(i)); }
    if (x > 0.5) { return r; }
    r[int(x * 7.0)] = 2.0 * x;
    return r;
}
void mainImage(out vec4 c, in vec2 f) {
    vec2 uv = f / iResolution.xy;
    float a = 0.0;
    if (uv.y > 0.3) {
        float[8] r = pick(uv.x);
        a = dFdx(r[1]) * 40.0 + r[int(uv.y * 7.0)];
    }
    c = vec4(a, uv, 1.0);
}"""


def _compiled(shader, lanes: int, size, time: float = 1.3) -> np.ndarray:
    from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate

    source, path = generate(shader, lanes=lanes)
    assert "QUADS = True" in source and f"LANES = {lanes}" in source, source[-300:]
    return CompiledProgram(source, path).render(size=size, time=time, mouse=MOUSE)


@pytest.mark.parametrize("size", [(40, 24), (41, 23)])
@pytest.mark.parametrize("lanes", [8, 16])
@pytest.mark.parametrize("name", sorted(DERIVATIVES))
def test_derivatives_bit_for_bit(numba, make_shader, name, lanes, size):
    shader = make_shader(DERIVATIVES[name])
    got = _compiled(shader, lanes, size)
    want = glslcheck.compile(shader, backend="numpy").render(size=size, time=1.3, mouse=MOUSE)
    what = f"{name} at {frame_text(size, time=1.3, mouse=MOUSE)}"
    assert_same(got, want, what=what, names=(f"lanes {lanes}", "numpy"), mode="bits_any_nan")
    # not trivially equal: the derivatives are not all zero
    assert np.ptp(want[..., :3]) > 0.0


def test_derivatives_start_in_lockstep(numba, make_shader, monkeypatch):
    """The default program of a shader with derivatives is the lockstep module from the first
    frame (no per-pixel tier); GLSLCHECK_COMPILED_LANES=0 is a located error, not a traceback."""
    from glslcheck.backends.compiled_engine.engine import (
        CompiledProgram,
        compile_compiled,
        generate,
    )

    shader = make_shader(DERIVATIVES["plain"])
    monkeypatch.delenv("GLSLCHECK_COMPILED_LANES", raising=False)
    prog = compile_compiled(shader)
    assert isinstance(prog, CompiledProgram) and "QUADS = True" in prog.source
    with pytest.raises(GlslError) as err:
        generate(shader, lanes=0)
    d = err.value.diagnostics[0]
    assert "derivatives only with pixels in lockstep" in d.message and (
        d.loc.line,
        d.loc.column,
    ) == (4, 14), (d.message, d.loc)
    monkeypatch.setenv("GLSLCHECK_COMPILED_LANES", "0")
    with pytest.raises(GlslError, match="derivatives only with pixels in lockstep"):
        generate(shader)


def test_quad_lanes():
    """Lane k's pair: lanes 0..3 the lower row, 4..7 the upper (8 lanes)."""
    from glslcheck.backends.compiled_engine.lanes_render import quad_lanes

    assert [quad_lanes("dfdx", k, 8) for k in range(8)] == [
        (1, 0),
        (1, 0),
        (3, 2),
        (3, 2),
        (5, 4),
        (5, 4),
        (7, 6),
        (7, 6),
    ]
    assert [quad_lanes("dfdy", k, 8) for k in range(8)] == [(4, 0), (5, 1), (6, 2), (7, 3)] * 2


SWITCH_LOCAL = """
void mainImage(out vec4 c, in vec2 f) {
    vec2 uv = f / iResolution.xy;
    vec3 col = vec3(0.0);
    switch (int(f.y) % 3) {
        case 0:
            col = vec3(uv, 1.0);
            break;
        case 1:
            vec2 q = uv * 3.0;
            q.x += sin(uv.y * 5.0);
            col = vec3(dFdx(q.x), dFdy(q.x), q.y) * 10.0;
            break;
        default:
            col = vec3(0.5);
    }
    c = vec4(col, 1.0);
}"""


def test_a_local_declared_in_a_switch_is_refused_with_derivatives(make_shader):
    """A neighbour's derivative reads such a local in the lanes another case runs: llvmpipe
    computes it in every lane, the NumPy backend writes it under the case's mask (`glslcheck
    verify`: MISMATCH), so the compiled engine refuses it at its declaration rather than give
    either's bits; without derivatives it runs."""
    from glslcheck.backends.compiled_engine.engine import generate

    with pytest.raises(GlslError) as err:
        generate(make_shader(SWITCH_LOCAL), lanes=8)
    d = err.value.diagnostics[0]
    line = SWITCH_LOCAL.split("\n").index("            vec2 q = uv * 3.0;") + 1
    assert "a local declared in a switch" in d.message and d.loc.line == line, (d.message, d.loc)
    plain = SWITCH_LOCAL.replace("dFdx(q.x), dFdy(q.x)", "q.x, q.x")
    source, _ = generate(make_shader(plain), lanes=8)
    assert "QUADS = True" not in source
