"""A value only a select reads, computed by the NumPy backend on the lanes that keep it
(transpile/dead_lanes.py), against llvmpipe, which computes it on every pixel: the same bits,
with NaN on the side the select throws away. The weights are NIR's b2f (step, float(bool) and
their products), which nir_opt_algebraic turns into a select whatever the other side holds."""

from __future__ import annotations

import numpy as np
import pytest

from glslcheck.backends.numpy_engine.transpile import transpile_shader
from glslcheck.verification.verify import compile_backend

SCENE = """
vec3 shade(vec3 p, vec3 n) {
    vec3 c = vec3(0.0);
    for (int i = 0; i < 4; ++i) {
        vec3 l = normalize(vec3(float(i) - 1.5, 1.0, 0.5) - p);
        c += pow(max(dot(n, l), 0.0), 16.0) * vec3(0.3, 0.25, 0.2);
    }
    return c;
}
void mainImage(out vec4 o, in vec2 f) {
    vec2 uv = (f + f - iResolution.xy) / iResolution.y;
    float d = 1.0 - dot(uv, uv) * 4.0;
    float hit = WEIGHT;
    vec3 n = vec3(uv, sqrt(max(d, 0.0)));
    vec3 bg = vec3(0.1, 0.2, 0.3) * (uv.y + 1.0);
    vec3 color = shade(n, -normalize(vec3(uv, -2.0))) + vec3(sqrt(d));
    bool lit = hit > 0.5;
    o = vec4(SELECT, 1.0);
}
"""


@pytest.mark.parametrize(
    ("weight", "select"),
    [
        ("step(0.0, d)", "mix(bg, color, hit)"),  # color is NaN wherever the weight is 0
        ("float(d >= 0.0)", "mix(bg, color, hit)"),
        ("step(0.0, d) * step(d, 2.0)", "mix(bg, color, hit)"),  # 07_final's hitSphere
        ("step(0.0, d)", "lit ? color : bg"),  # a conditional: Mesa's bcsel
    ],
)
def test_numpy_computes_a_selected_value_on_its_lanes_as_llvmpipe_everywhere(
    llvmpipe, make_shader, weight, select
):
    shader = make_shader(SCENE.replace("WEIGHT", weight).replace("SELECT", select))
    assert "rt.mix_reads(" in transpile_shader(shader).source
    got_gl = np.asarray(compile_backend(shader, "gl").render(size=(160, 90), frame=0), np.float32)
    got_np = np.asarray(
        compile_backend(shader, "numpy").render(size=(160, 90), frame=0), np.float32
    )
    assert np.isfinite(got_gl).all()  # (the NaN side was thrown away by the driver too)
    assert np.array_equal(got_np.view(np.int32), got_gl.view(np.int32))
