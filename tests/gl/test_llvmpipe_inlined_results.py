"""Mesa's rules across a user function's result, rendered by llvmpipe and by both CPU engines.

Mesa inlines every function before nir_opt_algebraic, so its rules see the value a call
returns: in iq's sphere-grid fbm, ``length(f - c) - hash(i + c)*hash(i + c)*0.7`` is
``(h*0.7)*h`` on llvmpipe, h the ``fract`` hash returns (the two calls one value after CSE).
nir_fold/inlined_results.py says which functions count as the value they return.

Written for llvmpipe of the emulated Mesa (the `llvmpipe` fixture of tests/conftest.py skips
elsewhere, naming the driver)."""

from __future__ import annotations

import numpy as np
import pytest

from glslcheck.verification.verify import compile_backend

# x: iq's sdBase (a hash returning a fract, its square by a constant, two lattice corners);
# y: two calls with different arguments; z: a function that returns a local, a sine
INLINED_RESULTS = """float hash(vec3 p) {
    p = 17.0 * fract(p * 0.3183099 + vec3(0.11, 0.17, 0.13));
    return fract(p.x * p.y * p.z * (p.x + p.y + p.z));
}
float noise2(vec2 p) { return fract(sin(dot(p, vec2(12.9898, 78.233))) * 43758.5453); }
float cell(vec2 p) {
    float r = sin(dot(floor(p), vec2(127.1, 311.7)));
    return r;
}
void mainImage(out vec4 c, in vec2 f) {
    vec3 q = vec3(f * 0.37, iTime * 3.1 + f.x * 0.13);
    vec3 i = floor(q), fr = fract(q);
    const vec3 a = vec3(0, 1, 1), b = vec3(1, 0, 1);
    c = vec4(min(length(fr - a) - hash(i + a) * hash(i + a) * 0.7,
                 length(fr - b) - hash(i + b) * hash(i + b) * 0.7),
             fr.x - noise2(f) * noise2(f * 1.1) * 0.7,
             fr.y + cell(q.xy) * cell(q.xy) * 0.55, 1.0);
}"""


@pytest.mark.parametrize("backend", ["numpy", "compiled"])
@pytest.mark.parametrize("time", [0.0, 1.3])
def test_a_constant_sinks_into_a_product_of_user_function_results(
    llvmpipe, make_shader, request, backend, time
):
    """``(g(x) * g(y)) * #c`` is ``(g(x) * #c) * g(y)`` where g, inlined, returns an opaque
    value, in both engines (the compiled engine asks the same plan: copied_binary). Measured
    without it at iTime 1.3: 2285, 1568 and 1854 of the 14,400 pixels differed from llvmpipe
    in x, y and z, in both engines."""
    if backend == "compiled":
        request.getfixturevalue("numba")
    shader = make_shader(INLINED_RESULTS)
    got_gl = np.asarray(compile_backend(shader, "gl").render(size=(160, 90), time=time), np.float32)
    got = np.asarray(compile_backend(shader, backend).render(size=(160, 90), time=time), np.float32)
    same = got.view(np.int32) == got_gl.view(np.int32)
    assert same.all(), (~same).reshape(-1, 4).sum(0).tolist()
