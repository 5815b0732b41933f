"""Mesa's rules across a user function's result, rendered by llvmpipe and by both CPU engines.

Mesa inlines every function before nir_opt_algebraic, so its rules see the value a call
returns: in iq's sphere-grid fbm, ``length(f - c) - hash(i + c)*hash(i + c)*0.7`` is
``(h*0.7)*h`` on llvmpipe, h the ``fract`` hash returns (the two calls one value after CSE).
nir_fold/inlined_results.py says which functions count as the value they return.

Written for llvmpipe of the emulated Mesa (the `llvmpipe` fixture of tests/conftest.py skips
elsewhere, naming the driver)."""

from __future__ import annotations

import pytest

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
    renders_as_llvmpipe, make_shader, backend, time
):
    """``(g(x) * g(y)) * #c`` is ``(g(x) * #c) * g(y)`` where g, inlined, returns an opaque
    value, in both engines (the compiled engine asks the same plan: rewrite_binary). Measured
    without it at iTime 1.3: 2285, 1568 and 1854 of the 14,400 pixels differed from llvmpipe
    in x, y and z, in both engines."""
    renders_as_llvmpipe(make_shader(INLINED_RESULTS), backend, name="INLINED_RESULTS", time=time)


# constants a vector constructor passes into a call: nested (vec3(vec2(x, y), 2.5)), flat, and
# a vec2, each multiplied in the callee by a constant beside the constant component
CONSTRUCTED_ARGUMENTS = """float g3(vec3 p) { return fract(p.x * 0.7 * p.z + p.y); }
float g2(vec2 p) { return fract(p.x * p.y * 0.3); }
void mainImage(out vec4 c, in vec2 f) {
    float x = fract(f.x * 0.0137 + f.y * 0.173) * 20.0 + iTime;
    float y = sin(f.y * 0.05);
    c = vec4(g3(vec3(vec2(x, y), 2.5)), g3(vec3(x, y, 1.3)), g2(vec2(x, 1.7)), 1.0);
}"""


@pytest.mark.parametrize("backend", ["numpy", "compiled"])
@pytest.mark.parametrize("time", [0.0, 1.3])
def test_constants_of_a_constructor_argument_merge_in_the_callee(
    renders_as_llvmpipe, make_shader, backend, time
):
    """``g3(vec3(vec2(x, y), 2.5))`` whose body computes ``p.x * 0.7 * p.z`` is ``x * (0.7 *
    2.5)`` after inlining (transpile/call_fold.py: a constructor's constant arguments are
    constant components, as a local's are). Measured without it at iTime 1.3: 6252, 5766 and
    4566 of the 14,400 pixels differed from llvmpipe in x, y and z, in both engines."""
    renders_as_llvmpipe(
        make_shader(CONSTRUCTED_ARGUMENTS), backend, name="CONSTRUCTED_ARGUMENTS", time=time
    )


# iq's sdBase with simplex cells: the hashes stored in locals first (r0, r1), then squared;
# r1 * r0 and r0 * r1, one value to NIR's CSE, each multiplied by a constant
STORED_RESULTS = """float hash(vec3 p) {
    p = 17.0 * fract(p * 0.3183099 + vec3(0.11, 0.17, 0.13));
    return fract(p.x * p.y * p.z * (p.x + p.y + p.z));
}
void mainImage(out vec4 c, in vec2 f) {
    vec3 q = vec3(f * 0.37, iTime * 3.1 + f.x * 0.13);
    vec3 i = floor(q), fr = fract(q);
    float r0 = hash(i), r1 = hash(i + 1.0);
    c = vec4(length(fr) - r0 * r0 * 0.55, length(fr - 1.0) - r1 * r0 * 0.55,
             fr.z + r0 * r1 * 2.5, 1.0);
}"""


@pytest.mark.parametrize("backend", ["numpy", "compiled"])
@pytest.mark.parametrize("time", [0.0, 1.3])
def test_a_local_holding_a_user_function_result_is_that_value(
    renders_as_llvmpipe, make_shader, backend, time
):
    """``float r0 = hash(i);`` never written again stands for hash's ``fract`` as a local
    initialised by ``fract(...)`` does (queries.stable_init), so ``(r0 * r0) * 0.55`` is
    ``(r0 * 0.55) * r0``; ``r1 * r0`` and ``r0 * r1`` are one value used twice, which no
    constant sinks into (queries.node_shapes). Measured at iTime 1.3, of the 14,400 pixels
    per channel, in both engines: without the local seen through, 964 differed from llvmpipe
    in x; with it but the two products counted apart, 728 in y and 232 in z."""
    renders_as_llvmpipe(make_shader(STORED_RESULTS), backend, name="STORED_RESULTS", time=time)
