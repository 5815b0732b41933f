"""Mesa's rewrites of float arithmetic, rendered by llvmpipe and by the NumPy backend bit for bit.

GLSL ES 3.00 has no `precise`, so Mesa reassociates: `mix` becomes one of four formulas
(nir_lower_flrp: which one depends on the operands the compiler knows and on the other `mix`
calls), and nir_opt_algebraic factors `a*b + a*c` and sinks constants into sums, products and
dot products. `glslcheck/backends/cpu_core/nir_fold/` and `Runtime.mix` repeat the
rewrites in float32 mode. Each shader below computes its operands with opaque built-ins (fract, sin,
sqrt, floor: values NIR does not look into) over 160x90 pixels. Without the rewrites (written order,
strict mix everywhere) these channels differ from llvmpipe (measured): constants_sunk 680, 4718
and 5163 pixels in its first three, factoring 979, 6694, 6556, mix_constant_operands 1169 and
2074 (second and third), mix_forms 5623 (first), mix_shared_operands 3261 (third),
constants_merged 3600, 3200, 2165 (first three), constants_sunk_further 30, 4667, 1103,
constants_merged_through_assignments 5035, 7837, 9300, constants_sunk_beside_a_selection 3498, 6900,
1538; the other channels pin forms that give the same bits here.

Written for llvmpipe of Mesa 22.3 (the `llvmpipe` fixture of tests/conftest.py fails naming
that release on another driver).
"""

from __future__ import annotations

from pathlib import Path

import image_bits
import numpy as np
import pytest

from glslcheck.verification.verify import compile_backend

OPERANDS = """
    float a = fract(p.x * 0.1371 + p.y * 0.0917), b = sin(p.y * 0.917 + p.x * 0.0311);
    float d = fract(p.x * 0.01377 + p.y * 0.0311), t = fract(p.x * 0.0173 + p.y * 0.0071);
    float e = sqrt(p.x), f = floor(p.y * 0.3);
"""
CASES = {
    # run-time weight: x + t*(y - x); constant weight: x*(1 - t) + y*t; x = +-1: (x -+ t) + y*t
    "mix_forms": "c = vec4(mix(a, b, t), mix(a, b, 0.37), mix(1.0, d, t), mix(-1.0, e, t));",
    # y = 1 -> strict; constant x and y of similar size -> fast; 1e-6 and 1 are not similar
    "mix_constant_operands": "c = vec4(mix(a, 1.0, t), mix(0.3, 1.0, t), mix(1.0, 0.7, t), "
    "mix(1e-6, 1.0, t));",
    # another mix with the same weight and x (or y): strict for both
    "mix_shared_operands": "c = vec4(mix(a, b, t), mix(a, d, t), mix(e, f, t), mix(d, b, "
    "t + 0.5));",
    # (a + b) + K -> (a + K) + b; (e*f + b) - K -> (b - K) + e*f; (a*b)*K -> (a*K)*b;
    # dot(o, o) - K -> o.x*o.x + (o.y*o.y + (o.z*o.z - K))
    "constants_sunk": """vec3 o = vec3(e, b, d) - vec3(d, e, b);
        c = vec4((a + b) + 2.7182817, (e * f + b) - 2.7182817, (a * b) * 2.7182817, dot(o, o) - \
            2.7182817);""",
    # a*b + c*a -> a*(b + c), also through a local product (a hash of a real shader)
    "factoring": """vec2 uv = 50.0 * fract(p / 3.14159265);
        c = vec4(fract(uv.x * uv.y * (uv.x + uv.y)), a * b + d * a, e * 1.37 + e * b, 2.7182817 * \
            (a * b));""",
    # (a + b) + K with longer terms: K sinks down a chain of sums used once, also through a
    # local read once (a sum stored, or assigned before: iq's noise, `uv + 0.5` with
    # uv = (p.xy + K2*p.z) + f.xy and f = f*f*(3 - 2f)), beside products of any factors
    "constants_sunk_further": """vec3 x3 = vec3(a * 20.0, b * 30.0, d * 7.0), fl = floor(x3), fr \
        = fract(x3);
        fr = fr*fr*(3.0 - 2.0*fr);
        vec2 uv = (fl.xy + vec2(37.0, 17.0)*fl.z) + fr.xy;
        float v = fl.y - fr.y*(b + 1.0);
        c = vec4(((uv + 0.5) / 256.0).x, (v - 2.7182817) * e, a*b*d + e + 1.37, 1.0);""",
    # beside a selection (a bcsel: no product), through locals: (u + f*a) + K -> (u + K) + f*a
    "constants_sunk_beside_a_selection": """float u = d > 0.5 ? a*b : e; float v = u + f*a; float \
        w = t > 0.3 ? e : b;
        c = vec4(v + 0.9, (w - d*e) - 1.7, (a > 0.5 ? a : d) + e*t + 2.3, 1.0);""",
    # a product by a constant seen through a variable assigned again (SSA): #M * (y * #c) ->
    # (M*c) * y for a constant matrix (iq's fbm: p = m*p*2.02; p = m*p*2.03), and
    # (y * #c) * #k -> y * (c*k)
    "constants_merged_through_assignments": """const mat3 m = mat3(0.0, 0.8, 0.6, -0.8, 0.36, \
        -0.48, -0.6, -0.48, 0.64);
        vec3 r = vec3(a, b, d);
        r = m*r*2.02;
        r = m*r*2.03;
        vec3 w = r * 3.5;
        c = vec4(r.x, w.y, (m*r*2.01).z, 1.0);""",
    # #a * (b * #c) -> (a*c) * b and #a + (b + #c) -> (a + c) + b, also through a local
    "constants_merged": """vec2 uv = (2.0 * p - iResolution.xy) / min(iResolution.x, \
        iResolution.y) * 1.2;
        vec2 w = uv * 0.2; float q = b + 0.37;
        c = vec4(w, (q - 1.3) * 1.0, 2.5 - (q + 1.7));""",
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_numpy_rewrites_as_mesa(renders_as_llvmpipe, make_shader, name):
    shader = make_shader("void mainImage(out vec4 c, in vec2 p) {" + OPERANDS + CASES[name] + "}")
    renders_as_llvmpipe(shader, name=name)


def test_float64_reference_keeps_the_written_order(make_shader):
    """The rewrites are float32 (llvmpipe) only: the float64 render computes the source's order,
    so it differs from the float32 render by float32 rounding only."""
    shader = make_shader(
        "void mainImage(out vec4 c, in vec2 p) {" + OPERANDS + CASES["constants_sunk"] + "}"
    )
    prog = compile_backend(shader, "numpy")
    f32 = np.asarray(prog.render(size=(32, 16)), np.float64)
    f64 = np.asarray(prog.render(size=(32, 16), precision="float64"), np.float64)
    assert np.allclose(f32, f64, rtol=1e-5, atol=1e-3)


def test_a_matrix_product_is_not_reassociated_as_numbers(gl, make_shader):
    """`m * p * 2.02` with a constant matrix (the fbm of the real shader Elevated): the constant
    merge once read it as the elementwise `p * (2.02 * m)`, a wrong value of the wrong shape
    (a traceback in mix). NIR lowers m * p to columns before any reassociation; the rounding of
    those column sums is not what this test is about, so it compares to GL within 4 ULP-scale
    units of the values (|q| < 20 here: 1e-5 absolute)."""
    shader = make_shader("""const mat2 m2 = mat2(0.8, 0.6, -0.6, 0.8);
void mainImage(out vec4 c, in vec2 p) {
    vec2 q = fract(p * 0.0173);
    q = m2 * q * 2.02;
    q = m2 * q * 2.03;
    c = vec4(q, mix(vec3(0.2), vec3(0.9), q.x * 0.1));
}""")
    got_gl = np.asarray(compile_backend(shader, "gl").render(size=(64, 36)))
    got_np = np.asarray(compile_backend(shader, "numpy").render(size=(64, 36)))
    np.testing.assert_allclose(got_np, got_gl, rtol=0, atol=1e-5)


ZERO_ADDS = """float add(float x, float k) { return x + k; }
void origin(out vec2 o) { o = vec2(0.0, 1.0); }
vec2 along(vec2 o, float t, vec2 d) { return o + t * d; }
void mainImage(out vec4 c, in vec2 p) {
    float a = fract(p.x * 0.1371 + p.y * 0.0917);
    float z = -floor(a), zp = floor(a);    // -0.0 and +0.0, opaque to the compiler
    vec2 o;
    origin(o);
    vec2 r = vec2(0.0, 1.0) + vec2(z, a);  // per component: x keeps -0.0, y adds 1
    c = vec4(1.0 / (z + 0.0) + 1.0 / add(z, 0.0),
             1.0 / r.x + r.y,
             1.0 / (0.0 - zp) + 1.0 / along(o, z, vec2(1.0, 2.0)).x,
             1.0);
}"""


def test_an_added_constant_zero_keeps_the_sign_of_zero(renders_as_llvmpipe, make_shader):
    """nir_opt_algebraic drops ``x + 0.0`` (and ``0.0 - x`` is ``-x``: llvmpipe lowers fsub to
    fadd of fneg), also when the zero reaches the addition through a function argument or an
    out parameter (NIR inlines first): 1/x is then -inf where IEEE gives +inf. Each channel
    mixes a literal case with one through a function; with IEEE additions all 14,400 pixels
    of each channel differed from llvmpipe (measured). The float64 reference keeps IEEE."""
    shader = make_shader(ZERO_ADDS)
    _, got_gl = renders_as_llvmpipe(shader, name="ZERO_ADDS")
    assert (got_gl[..., 0] == -np.inf).all()  # the case the test is about, not an accident
    f64 = np.asarray(compile_backend(shader, "numpy").render(size=(8, 4), precision="float64"))
    assert (f64[..., 0] == np.inf).all() and (f64[..., 2] == np.inf).all()


MERGED_DOTS = """float hash(vec2 v) { return fract(15465.1327854 * sin(dot(v, vec2(173.93422, \
    102.5165)))); }
void mainImage(out vec4 c, in vec2 p) {
    vec2 uv = (2.0 * p - iResolution.xy) / min(iResolution.x, iResolution.y) * 1.2;
    vec3 r = fract(vec3(p.x, p.y, p.x + p.y) * 0.013);
    c = vec4(fract(dot(uv * 0.2, vec2(173.93422, 102.5165)) * 7.1),
             fract(dot(r * 2.1 * 0.7, vec3(17.1, 29.3, 41.7))), hash(uv * 0.2) + hash(uv), 1.0);
}"""


def test_constants_merge_into_a_dot_product_also_through_an_inlined_argument(
    renders_as_llvmpipe, make_shader
):
    """dot(v, #K) with v a product by constants: ``dot(uv * 0.2, K)``, uv = q * 1.2 read
    several times, is ``dot(q, (K * 0.2) * 1.2)``; ``r * 2.1 * 0.7`` (one expression: GLSL IR
    folds 2.1 * 0.7 first) gives ``dot(r, K * (2.1 * 0.7))``; the third channel reaches uv * 0.2
    through the parameter of an inlined hash (a real shader's star field, tests/real_verify
    23-2d). Without the dot rule 9,560 and 4,180 pixels of the first two channels differed from
    llvmpipe, without the inlining 11,820 of the third (measured)."""
    renders_as_llvmpipe(make_shader(MERGED_DOTS), name="MERGED_DOTS")


ONE_VALUE_DOTS = """float hash(vec2 co) { return fract(sin(dot(co.xy, vec2(12.9898, 78.233))) * \
    43758.5453); }
void mainImage(out vec4 c, in vec2 p) {
    float a = fract(p.x * 0.1371 + p.y * 0.0917), q = floor(p.x) / 61.0 + floor(p.y) * 0.0173;
    c = vec4(fract(sin(dot(a, 123.456) * 789.123)),
             fract(dot(vec2(q), vec2(12.9898, 78.233)) * 43.7) + fract(dot(vec4(a), vec4(12.9898, \
                 78.233, 37.719, 4.581))),
             hash(vec2(q)) + fract(dot(vec3(a), vec3(0.1, 0.2, 0.7)) * 4373.1), 1.0);
}"""


def test_a_dot_product_of_one_value_is_a_product(renders_as_llvmpipe, make_shader):
    """Mesa's ``dot`` of two floats is a multiply, so a constant merges into it: ``dot(a, #b) *
    #c`` is ``a * (b*c)``; ``dot(vecN(s), #K)`` is ``s * (K[0] + (K[1] + ...))`` (the component
    products factored, the constants summed right to left), also with a constant factor merged
    into that sum and through the parameter of an inlined hash (``co.xy`` of ``vec2(q)``). Hashes
    of two real shaders not tuned on (tests/real_verify/holdout.json h12, h14). Without the
    rules the first three channels differed from llvmpipe in 3,669, 9,677 and 3,460 pixels
    (measured; the third's through the inlining)."""
    renders_as_llvmpipe(make_shader(ONE_VALUE_DOTS), name="ONE_VALUE_DOTS")


GLOBAL_CONSTANTS = """float PI = 3.14159265;  // globals that are not const but never written: \
    constants to Mesa
float SCALE = 0.37;
void mainImage(out vec4 c, in vec2 p) {
    vec2 uv = 50.0 * fract(p / PI);
    float q = fract(p.x * 0.0173 + p.y * 0.0071);
    c = vec4(fract(uv.x * uv.y * (uv.x + uv.y)), fract((q * SCALE) * 1234.5),
             fract(dot(uv * SCALE, vec2(12.9898, 78.233))), 1.0);
}"""


def test_a_global_initialised_by_a_constant_and_never_written_is_a_constant(
    renders_as_llvmpipe, make_shader
):
    """GLSL IR propagates such a global as a constant before NIR's rewrites, so they apply as
    for a `const` (factoring through uv, constants merged in a product and in a dot product).
    Read as a variable, the three channels differed from llvmpipe in 979, 4,543 and 3,181
    pixels (measured; the first is the hash of a real shader, tests/real_verify 33)."""
    renders_as_llvmpipe(make_shader(GLOBAL_CONSTANTS), name="GLOBAL_CONSTANTS")


SSA_VALUES = (
    "void mainImage(out vec4 c, in vec2 p) {"
    + OPERANDS
    + CASES["constants_sunk_further"]
    + CASES["constants_merged_through_assignments"].replace("c = vec4(", "c += vec4(")
    + "}"
)


RETURNED_SUMS = """float h(vec3 x) { return fract(sin(x.x * 1.7 + x.y * 3.1) * 43.7 + x.z); }
float fbm(vec3 p) { float f; f = 0.5*h(p); f += 0.25*h(p + 1.0); f += 0.125*h(p + 2.0); return f; }
float wave(vec3 p) { float f = fract(p.x * 3.1); f -= 0.5*fract(p.y * 1.7); f += p.z * 0.3; \
    return f; }
void mainImage(out vec4 c, in vec2 q) {
    vec3 p = vec3(fract(q.x * 0.1371 + q.y * 0.0917), sin(q.y * 0.917 + q.x * 0.0311), fract(q.x \
        * 0.01377 + q.y * 0.0311));
    c = vec4(fbm(p) - 0.4, wave(p) + 1.3, 0.7 + fbm(p.zxy), 1.0);
}"""


def test_a_constant_added_to_a_result_sinks_into_the_sum_the_function_returns(
    renders_as_llvmpipe, make_shader
):
    """NIR inlines every function, so ``fbm(p) - 0.4`` with fbm returning ``f`` built as
    ``f = 0.5*h(p); f += ...`` is ``((0.5*h(p) - 0.4) + 0.25*h(..)) + ...`` on llvmpipe (iq's
    terrain ``displacement(x) - 0.4``, the real shader volcanic). Measured: 299, 4398 and 1293
    pixels of the three channels differed from llvmpipe without it."""
    renders_as_llvmpipe(make_shader(RETURNED_SUMS), name="RETURNED_SUMS")
    renders_as_llvmpipe(make_shader(RETURNED_SUMS_SHARED), name="RETURNED_SUMS_SHARED")


# the same sum computed for another call (same argument; for a vector function, any other call:
# equal components) is merged by CSE after inlining, used twice: the constant stays outside.
# Sunk anyway (measured): 80, 1 and 246 pixels of the three channels differed.
RETURNED_SUMS_SHARED = (
    RETURNED_SUMS.split("void mainImage")[0]
    + """
vec3 fbm3(vec3 p) { vec3 f = 0.5*fract(p*7.0); f += 0.25*fract(p*3.0); return f; }
void mainImage(out vec4 c, in vec2 q) {
    vec3 p = vec3(fract(q.x * 0.1371 + q.y * 0.0917), sin(q.y * 0.917 + q.x * 0.0311), fract(q.x \
        * 0.01377 + q.y * 0.0311));
    float d = fbm(p);
    vec3 a = (fbm3(p) - vec3(0.3, 0.2, 0.1)) * 1.5, b = fbm3(p.zxy) * 2.0;
    c = vec4(fbm(p) - 0.4 + d * 2.0, a.x + b.y, a.z + b.x, 1.0);
}"""
)


# gargantua's camera (tests/real_channels, Buffer A): a position with constant components and a
# constant angle passed into rotate()'s matrix products, two calls deep; and a constant
# component reaching a compound assignment through a call (elephant's `p.y -= 2.4`)
CALL_CONSTANTS = """vec3 rotate(vec3 p, float x, float y, float z) {
    mat3 matx = mat3(1.0, 0.0, 0.0, 0.0, cos(x), sin(x), 0.0, -sin(x), cos(x));
    mat3 maty = mat3(cos(y), 0.0, -sin(y), 0.0, 1.0, 0.0, sin(y), 0.0, cos(y));
    mat3 matz = mat3(cos(z), sin(z), 0.0, -sin(z), cos(z), 0.0, 0.0, 0.0, 1.0);
    p = matx * p;
    p = matz * p;
    p = maty * p;
    return p;
}
void camera(inout vec3 dir, inout vec3 pos, float ax, float ay) {
    vec3 angle = vec3(ax * 0.05 + 0.05, 1.0 + ay, -0.45);
    dir = rotate(dir, angle.x, angle.y, angle.z);
    pos = rotate(pos, angle.x, angle.y, angle.z);
}
float lift(vec3 ro, float t, vec3 rd) { vec3 p = ro + t * rd; p.y -= 2.4; return p.y * 3.7; }
void mainImage(out vec4 c, in vec2 q) {
    float ax = fract(q.x * 0.1371 + q.y * 0.0917), ay = sin(q.y * 0.917 + q.x * 0.0311);
    vec3 dir = normalize(vec3(q * 0.01, 6.0));
    vec3 pos = vec3(0.0, -0.0, -10.0);
    pos.x += fract(q.y * 0.0173) * 3.0 - 1.5;
    camera(dir, pos, ax, ay);
    vec3 ro = vec3(ax, 1.6, ay);
    c = vec4(pos, lift(ro, fract(q.x * 0.01377 + q.y * 0.0311), dir));
}"""
# gargantua's first ray step, pos read once after the call: eyepos + eyevec * dither * far / 200
CALL_CONSTANTS_STEP = (
    CALL_CONSTANTS.split("    vec3 ro =")[0]
    + """    float dither = fract(q.x * 0.01377 + q.y * 0.0311) * 2.0;
    const float far = 15.0;
    c = vec4(pos + dir * dither * far / 200.0, 1.0);
}"""
)


def test_constants_propagated_into_a_call_per_component(renders_as_llvmpipe, make_shader):
    """NIR inlines every function, scalarises, then folds: pos = (x, -0.0, -10.0) passed inout
    through camera() into rotate() with the constant angle -0.45 is ``sin(-0.45)*x +
    (cos(-0.45)*10)*sin(ax)`` in y (``#a * (b * #c)`` across two calls: the real shader
    gargantua; transpile/call_fold.py). Measured without it: 463, 6711 and 364 of the 14,400
    pixels of pos's three channels differed from llvmpipe. The fourth channel, lift()'s
    ``(1.6 + t*rd.y) - 2.4`` folded to ``(1.6 - 2.4) + t*rd.y`` through a component written
    by a compound assignment, gives llvmpipe's bits either way here (no pixel differed)."""
    renders_as_llvmpipe(make_shader(CALL_CONSTANTS), name="CALL_CONSTANTS")


SCALED_ARGUMENTS = """float hash11(float p) { vec3 p3 = fract(vec3(p) * 443.8975); p3 += dot(p3, \
    p3.yzx + 19.19); return fract((p3.x + p3.y) * p3.z); }
float scaled(vec2 q) { vec2 r = fract(q * 7.31); return dot(r, vec2(3.7, 1.3)); }
void mainImage(out vec4 c, in vec2 p) {
    float a = fract(p.x * 0.1371 + p.y * 0.0917), fi = floor(p.x) + 160.0 * floor(p.y);
    c = vec4(hash11(fi * 0.017), hash11(a * 2.3), scaled(p * 0.37), 1.0);
}"""


def test_a_product_by_a_constant_passed_into_a_call_merges_with_its_constants(
    renders_as_llvmpipe, make_shader
):
    """An argument ``y * #c`` is that product in each component of the parameter after inlining,
    so the callee's constants merge into it (``fract(vec3(p) * 443.8975)`` of ``p = fi * 0.017``
    is ``fract(fi * (0.017*443.8975))``), and a dot product whose products share a value is
    factored (``dot(p3, p3.yzx + 19.19)`` of three equal components is ``a * (b + (b + b))``):
    Dave Hoskins' hash11 in NebulaSmoke (tests/real_verify/holdout.json h40; call_fold.py).
    Without the product arguments 9,013, 8,948 and 7,680 pixels of the three channels differed
    from llvmpipe, without the factoring 6,040 and 6,166 of the first two (measured)."""
    renders_as_llvmpipe(make_shader(SCALED_ARGUMENTS), name="SCALED_ARGUMENTS")


HASHES_WITHOUT_SINE = """float hash11(float p) { vec3 p3 = fract(vec3(p) * .1031); p3 += dot(p3, \
    p3.yzx + 33.33); return fract((p3.x + p3.y) * p3.z); }
float hash12(vec2 p) { vec3 p3 = fract(vec3(p.xyx) * .1031); p3 += dot(p3, p3.yzx + 33.33); \
    return fract((p3.x + p3.y) * p3.z); }
float hash13(vec3 p3) { p3 = fract(p3 * .1031); p3 += dot(p3, p3.zyx + 31.32); return fract((p3.x \
    + p3.y) * p3.z); }
void mainImage(out vec4 c, in vec2 p) {
    float q = fract(p.x * 0.01371 + p.y * 0.0917) * 50.0;
    c = vec4(hash11(p.x + 160.0 * p.y) + hash11(q), hash12(p), hash13(vec3(p, p.x * 0.7 + 3.0)), \
        1.0);
}"""


def test_a_dot_product_whose_products_share_a_value_is_factored(renders_as_llvmpipe, make_shader):
    """Dave Hoskins' hashes without sine, as written on Shadertoy: hash11's ``vec3(p)`` has three
    equal components and hash12's ``vec3(p.xyx)`` two, so two products of ``dot(p3, p3.yzx +
    33.33)`` share a value and NIR factors them (``a*b + a*c -> a * (b + c)``; call_fold.py
    folds such a call even without constant arguments); ``hash11(q)`` of a never-written ``q =
    ... * 50.0`` also merges 50.0 into the hash's constant. hash13 has no shared product (a
    check that nothing else moves). Without the factoring 7,588 and 2,007 pixels of the first two
    channels differed from llvmpipe, without the merge through q 4,629 of the first (measured)."""
    renders_as_llvmpipe(make_shader(HASHES_WITHOUT_SINE), name="HASHES_WITHOUT_SINE")


def test_a_scaled_local_whose_operand_changes_before_the_call_is_not_evaluated_again(
    renders_as_llvmpipe, make_shader
):
    """q = s.m * 0.5 and then s.m = 2.0 before hash11(q): the product is not q's value at the
    call, so it is not merged (it was read again there, and a struct member's write raised a
    KeyError in the scan for writes: a real textured shader, tests/real_channels ice_primitives)."""
    renders_as_llvmpipe(
        make_shader(
            SCALED_ARGUMENTS.split("float scaled")[0]
            + """struct S { float m; };
void mainImage(out vec4 c, in vec2 p) {
    S s = S(fract(p.x * 0.1371 + p.y * 0.0917));
    float q = s.m * 0.5;
    s.m = 2.0;
    c = vec4(hash11(q), s.m, 0.0, 1.0);
}"""
        )
    )


def test_a_sum_returned_through_a_folded_call_fuses_with_its_next_addition(
    renders_as_llvmpipe, make_shader
):
    """gargantua's first ray step, ``pos + dir * dither * far / 200.0`` with pos folded by the
    call (each component ``p1 + p2`` of two products) and read only there: llvmpipe fuses and
    splits again, ``(p1 + step) + p2`` (nir_fold.ffma_split.fused_after_call), and ``(dir * dither)
    * 15.0`` is ``(dir * 15.0) * dither`` (the product sink past a broadcast operand: dir is what
    the call wrote, dither a product by a constant). Measured: 3832, 4665 and 3901 pixels
    differed from llvmpipe with the call folded alone, 4127, 8716 and 4021 without any of it."""
    renders_as_llvmpipe(make_shader(CALL_CONSTANTS_STEP), name="CALL_CONSTANTS_STEP")


ADVANCED_HASH = """vec3 hash31(float q) {  // spqr's camera path hash (fbm set f04)
    vec3 p2 = fract(q * vec3(5.3983, 5.4427, 6.9371));
    p2 += dot(p2.zxy, p2.xyz + vec3(21.5351, 14.3137, 15.3219));
    return fract(vec3(p2.x * p2.y * 95.4337, p2.y * p2.z * 97.597, p2.z * p2.x * 93.8365));
}
void mainImage(out vec4 c, in vec2 p) {
    c = vec4(hash31(p.x * 0.731 + p.y * 91.3 + floor(iTime)), 1.0);
}
"""


def test_a_constant_sinks_into_a_product_of_components_of_a_sum(renders_as_llvmpipe, make_shader):
    """``p2.x * p2.y * #K`` with p2 last written by ``p2 += dot(...)`` (to NIR a sum, which no
    rule looks into as a factor) is ``(p2.x * #K) * p2.y`` (nir_fold.sink.product_sink); the
    hash amplifies the ulp to a visible difference."""
    renders_as_llvmpipe(make_shader(ADVANCED_HASH), name="ADVANCED_HASH")


SQUARED_LENGTHS = """float warp(vec3 r) {
    vec3 origin = vec3(0.0);
    float d = distance(r, origin);
    return 1.0 / (pow(d, 2.0) + 0.000001);
}
float glow(vec3 r) { return (pow(length(r), 2.0) - 0.37) * 1.5; }
float steer(vec3 r) {  // gargantua's WarpSpace: normalize() shares the dot product
    vec3 origin = vec3(0.0);
    float d = distance(r, origin);
    vec3 v = normalize(origin - r);
    return v.x / (pow(d, 2.0) + 0.000001);
}
void mainImage(out vec4 c, in vec2 q) {
    vec3 r = vec3(sin(q.x * 0.37), fract(q.y * 0.013), sqrt(q.x)) * 3.0 - 1.0;
    c = vec4(warp(r), glow(r.yzx), steer(r.zxy), 1.0);
}"""


def test_a_squared_length_plus_a_constant_is_a_dot_product(renders_as_llvmpipe, make_shader):
    """``pow(distance(r, vec3(0.0)), 2.0) + K`` (gargantua's WarpSpace) is ``dot(r, r) + K`` on
    llvmpipe: fpow(a, 2.0) -> a*a, sqrt(a)*sqrt(a) -> a, and K joins the dot product's
    innermost addition, unless another length/normalize/dot of r shares that dot product
    (steer(): K stays outside; nir_fold.squared_lengths.squared_length). Measured without the rule:
    6048, 6791 and 6168 of the 14,400 pixels differed from llvmpipe; with K always sunk, 477 of
    steer()'s."""
    renders_as_llvmpipe(make_shader(SQUARED_LENGTHS), name="SQUARED_LENGTHS")


NORMALIZED_STEPS = """void warp(inout vec3 e, inout vec3 r) {  // gargantua's WarpSpace
    vec3 origin = vec3(0.0);
    float d = distance(r, origin);
    float wf = 1.0 / (pow(d, 2.0) + 0.000001);
    vec3 sv = normalize(origin - r);
    float wa = 5.0;
    e = e + sv * wf * wa / float(200);
}
void mainImage(out vec4 c, in vec2 q) {
    vec3 r = vec3(sin(q.x * 0.37), fract(q.y * 0.013), sqrt(q.x)) * 3.0 - 1.0;
    vec3 e = normalize(vec3(fract(q.x * 0.0173), sin(q.y * 0.31), 0.5));
    warp(e, r);
    c = vec4(e, 1.0);
}"""


def test_a_constant_sinks_into_a_normalize_used_once(renders_as_llvmpipe, make_shader):
    """``(sv * wf) * wa`` with sv = normalize(x) read once, wf = 1.0 / (...) and the local
    constant wa = 5.0: NIR sees sv as ``x * frsq(dot(x, x))``, and the constant sinks twice,
    ``((x * 5.0) * inversesqrt(dot(x, x))) * wf`` (nir_fold.sink._normalized_once). Measured
    without it: 5, 0 and 3 of the 14,400 pixels differed from llvmpipe (1 ulp; gargantua's
    second ray step)."""
    renders_as_llvmpipe(make_shader(NORMALIZED_STEPS), name="NORMALIZED_STEPS")


def _warp_after(steps: str) -> str:
    """NORMALIZED_STEPS's warp called where r's value merges several writes (a phi to NIR)."""
    head = NORMALIZED_STEPS.split("    warp(e, r);")[0]
    return head + steps + "\n    c = vec4(e, 1.0);\n}"


@pytest.mark.parametrize(
    "steps",
    [
        "    for (int i = 0; i < int(iTime * 0.0) + 4; i++) { warp(e, r); r += e * 0.075; }",
        "    if (q.y > 40.0) { r = r * 1.5 + sin(r.zxy) * cos(r) + exp(r.yzx) * 0.1 + log(abs(r) "
        "+ 1.0); }\n"
        "    warp(e, r);",
    ],
    ids=["loop", "branch"],
)
def test_a_constant_joins_a_shared_dot_product_of_a_merged_value(
    renders_as_llvmpipe, make_shader, steps
):
    """The same warp, its r written in the loop around the call (gargantua's ray steps) or in a
    branch before it: the constant joins the dot product's innermost addition although
    normalize() shares it (nir_fold.squared_lengths.merged_argument). Measured with it kept outside:
    3 and 1 of the 14,400 pixels differed from llvmpipe (x); NORMALIZED_STEPS itself: 0 outside, 1
    sunk."""
    renders_as_llvmpipe(make_shader(_warp_after(steps)))


CONSTANT_POWERS = """float pcurve(float x, float a, float b) {  // gargantua's GasDisc
    float k = pow(a + b, a + b) / (pow(a, a) * pow(b, b));
    return k * pow(x, a) * pow(1.0 - x, b);
}
void mainImage(out vec4 c, in vec2 q) {
    float x = fract(q.x * 0.0173 + q.y * 0.00731);
    c = vec4(pcurve(x, 4.0, 0.9), pcurve(0.5, 4.0, 0.9), pcurve(x, 2.5, 1.5), 1.0);
}"""


def test_powers_of_constants_propagated_into_a_call_are_folded(renders_as_llvmpipe, make_shader):
    """``pcurve(x, 4.0, 0.9)``: after inlining, Mesa folds ``pow`` of the constant arguments
    with the host's powf (correctly rounded), and ``k * pow(x, 4.0)``, pow(x, 4.0) being
    ``(x*x)*(x*x)`` used once, is ``((x*x) * k) * (x*x)`` (fold_eval.Evaluator.pow / mul).
    Measured without the fold: 14,400 and 14,400 of the 14,400 pixels differed in
    x and y (2-6 ulps); z, no exponent 4.0, already agreed."""
    renders_as_llvmpipe(make_shader(CONSTANT_POWERS), name="CONSTANT_POWERS")


_RADIAL = """void mainImage(out vec4 c, in vec2 p) {  // gargantua's GasDisc
    float a = fract(p.x * 0.1371 + p.y * 0.0917), b = sin(p.y * 0.917 + p.x * 0.0311);
    float d = fract(p.x * 0.01377 + p.y * 0.0311), e = sqrt(p.x) * (iTime + 1.0);
    vec3 r;
    r.x = a * 1.7 + 0.55;
    r.y = sin(b * 3.7) * 1.5;
    r.z = d * 1.3;
    r *= 0.95;
    vec3 q = r + 0.0;
"""
COMPONENT_WRITES = (
    _RADIAL
    + """    q.y += e;
    vec3 s = q * 3.1;
    r.y += e * 0.5;
    float h = b * 1.37;
    h *= 0.73;
    c = vec4(h, s.z, (r.yx * vec2(0.15, 0.27)).y, 1.0);
}"""
)


def test_constants_merge_through_the_last_write_of_each_component(renders_as_llvmpipe, make_shader):
    """NIR sees each component's last write (SSA after splitting vectors into components), so a
    product by a constant written to a component, or to a whole local, merges with a later
    ``*=`` or ``*`` by a constant, also through a copy (``q = r + 0.0`` is r):
    ``h = b * 1.37; h *= 0.73`` is ``b * (1.37*0.73)``; s.z is ``d * (1.3*(0.95*3.1))`` (the
    constants folded right to left: nir_opt_algebraic visits the last instruction first);
    ``(r.yx * vec2(0.15, 0.27)).y`` is ``(a*1.7 + 0.55) * (0.95*0.27)`` (nir_fold.component_write,
    _merge_components). Measured without it: 4772, 6413 and 3607 of the 14,400 pixels
    differed from llvmpipe (with the constants folded left to right, s.z: 11,111)."""
    renders_as_llvmpipe(make_shader(COMPONENT_WRITES), name="COMPONENT_WRITES")


CANCELLED_SUMS = (
    _RADIAL
    + """    q.y += e;
    vec3 s = q * 3.1;
    q.y -= e;
    vec3 u = q * 6.1;
    q.y += e;
    q.y -= e;
    c = vec4(s.y, u.y, (q * 12.7).y, 1.0);
}"""
)


def test_a_sum_cancelled_by_its_difference_is_the_value_before_it(renders_as_llvmpipe, make_shader):
    """``q.y += e; ... q.y -= e`` is q.y as it was to NIR (``('~fadd', ('fneg', a), ('fadd', a,
    b)) -> b``), so a later product by a constant merges with the constants q.y had:
    u.y is ``sin(..) * (1.5*(0.95*6.1))`` (nir_fold.components._cancelled_sum). Measured without it:
    13,446 and 13,377 of the 14,400 pixels differed from llvmpipe (u.y and the last, after
    a second cancelled pair); s.y (no cancellation) pins the sum read between."""
    renders_as_llvmpipe(make_shader(CANCELLED_SUMS), name="CANCELLED_SUMS", time=0.7)


NEGATED_PRODUCTS = """void mainImage(out vec4 c, in vec2 p) {
    float a = fract(p.x * 0.1371 + p.y * 0.0917), b = sin(p.y * 0.917 + p.x * 0.0311);
    float x = a * 0.85;
    vec3 w = -(vec3(a, b, a - b) * 2.1);
    c = vec4(-x * 0.6, (0.45 * w).y + (w * 0.3).z, clamp(-(b * 1.3) * 0.7, 0.0, 1.0), 1.0);
}"""


def test_constants_merge_through_a_negation(renders_as_llvmpipe, make_shader):
    """NIR moves a negation out of a product (``fmul(fneg(a), b) -> fneg(fmul(a, b))``), so
    ``-x * #c`` with x's value ``y * #k`` is ``-(y * (k*c))``: through a local, a parenthesized
    product, a local holding the negation, on either side, inside clamp
    (nir_fold.constant_merge). Measured without it: 5780, 5371 and 2331 of the 14,400 pixels
    differed from llvmpipe."""
    renders_as_llvmpipe(make_shader(NEGATED_PRODUCTS), name="NEGATED_PRODUCTS")


def test_a_negated_product_of_itime_merges_at_every_frame(llvmpipe, make_shader):
    """The same merge on a uniform (57-2d's ``float time = iTime*0.85; ... -time*0.6``): the
    merged and the written product round apart at some iTime values only, so 4 s of frames at
    60 fps, one pixel each. Measured without it: 88 and 72 of the 240 frames differed from
    llvmpipe (the negated channels); ``sin(time * 0.2)`` pins the merge without a negation."""
    shader = make_shader(
        "void mainImage(out vec4 c, in vec2 f) {\n float time = iTime * 0.85;\n"
        " c = vec4(sin(time * 0.2), -time * 0.6, 0.37 * -(iTime * 1.3), 1.0); }"
    )
    gl, numpy = compile_backend(shader, "gl"), compile_backend(shader, "numpy")
    times = [k / 60 for k in range(240)]
    want = np.stack([np.asarray(gl.render(size=(1, 1), time=t), np.float32) for t in times])
    got = np.stack([np.asarray(numpy.render(size=(1, 1), time=t), np.float32) for t in times])
    image_bits.assert_same_frames(
        got, want, times, what="iTime * 0.85 negated, 1x1", names=("numpy", "llvmpipe")
    )


# gargantua's atan2 (returns from inside branches, after atan()) called in a loop of STEPS passes
# (tests/compiled/test_derivatives.py reads it too)
KEPT_RETURNS = (Path(__file__).resolve().parent / "shaders" / "kept_returns.glsl").read_text()


@pytest.mark.parametrize("steps", ["40", "4"])
def test_a_result_returned_from_a_branch_keeps_its_old_value_in_lanes_left_out(
    renders_as_llvmpipe, make_shader, steps
):
    """A neighbour that returned early still has atan2's result in a derivative: llvmpipe's
    register for the merged returns, stored under the exec mask, so its value of the last
    iteration that lane called it in a loop NIR keeps (40 steps), zero in a loop it unrolls
    (4 steps: each copy its own register) (nir_fold.register_call, tiles.LaneHelpers.reg).
    Measured: 40 steps, zero in those lanes: 10,218 of the 14,400 pixels differed from
    llvmpipe; 4 steps, the register kept across iterations: 917."""
    renders_as_llvmpipe(make_shader(KEPT_RETURNS.replace("STEPS", steps)), name="KEPT_RETURNS")


def kept_returns_with_steps(steps: int, lines: int) -> str:
    """KEPT_RETURNS whose loop runs `steps` passes, with `lines` more lines of a sin step in its
    body (3 instructions each for NIR's unroll cost, loop_unroll.py), their value in green."""
    body = " ".join(f"a = sin(a * 1.01 + {k + 1}.0);" for k in range(lines))
    text = KEPT_RETURNS.replace("float acc = 0.0;", "float acc = 0.0, a = p.y * 0.013;")
    text = text.replace("float(i) * 0.37));", "float(i) * 0.37));\n        " + body)
    text = text.replace("c = vec4(acc, 0.0, 0.0, 1.0);", "c = vec4(acc, a, 0.0, 1.0);")
    return text.replace("STEPS", str(steps))


@pytest.mark.parametrize("backend", ["numpy", "compiled"])
@pytest.mark.parametrize(
    "steps, lines",
    [(6, 0), (6, 24), (8, 0)],
    ids=["cheap_body_unrolled", "costly_body_kept", "three_atans_kept_at_8"],
)
def test_the_register_is_kept_in_a_short_loop_nir_does_not_unroll(
    renders_as_llvmpipe, make_shader, steps, lines, backend
):
    """Six passes, within NIR's 32: with the plain body NIR unrolls the loop (zero in the lanes
    that returned), with 24 sin lines more the body costs too much to unroll and the lanes keep
    the value of their last call (loop_unroll.nir_unrolls decides for register_call, in both
    engines); the plain body is kept at 8 passes, for the cost of its three atan calls.
    Measured: taking every loop of at most 32 passes as unrolled put 1,522 and 2,134 of the
    14,400 pixels of the kept loops off (each engine); the register kept in the cheap one put
    1,522 off. Where llvmpipe's limit lies, found with these shaders: 7 passes of the plain body
    unrolled, 8 kept; 4 passes with 30 sin lines unrolled, 31 kept (a body cost of 116 to 118;
    loop_unroll.py counts 112, so it takes 31 lines for unrolled)."""
    renders_as_llvmpipe(make_shader(kept_returns_with_steps(steps, lines)), backend)


SUNK_THROUGH_COMPOUNDS = """float saturate(float x) { return clamp(x, 0.0, 1.0); }
float pcurve(float x, float a, float b) {
    float k = pow(a + b, a + b) / (pow(a, a) * pow(b, b));
    return k * pow(x, a) * pow(1.0 - x, b);
}
void mainImage(out vec4 c, in vec2 p) {  // gargantua's GasDisc
    float x = fract(p.x * 0.0173 + p.y * 0.00731), d = fract(p.y * 0.0131 + p.x * 0.0037);
    float coverage = pcurve(x, 4.0, 0.9);
    coverage *= saturate(1.0 - d);
    coverage = saturate(coverage * 0.7);
    coverage *= pcurve(x, 4.0, 0.9);
    float s = sin(x * 5.1);
    s *= d;
    c = vec4(coverage, s * 0.37, 1.0, 1.0);
}"""


def test_a_constant_sinks_into_a_compound_product_read_once(renders_as_llvmpipe, make_shader):
    """``x *= b; ... x * #c`` with x's new value read only there is ``(a * #c) * b`` (a: x
    before), the product used once in SSA (nir_fold.compound_products.sunk_through_compound); copied
    one level: a is a sin() here, and the pcurve() value that CSE shares with the second identical
    call. Measured without it: 4537 and 5121 of the 14,400 pixels differed from llvmpipe."""
    renders_as_llvmpipe(make_shader(SUNK_THROUGH_COMPOUNDS), name="SUNK_THROUGH_COMPOUNDS")


def test_a_product_in_a_global_initializer_is_no_local_write(make_shader):
    """The per-component rules read the current function's writes; a global's initializer has
    none (it stopped transpiling with an AttributeError: a regression caught on the lab)."""
    shader = make_shader(
        "float TAU = 3.14159 * 2.0;\n"
        "void mainImage(out vec4 c, in vec2 p) { c = vec4(TAU * 0.1 * p.x, 0.0, 0.0, 1.0); }"
    )
    got = np.asarray(compile_backend(shader, "numpy").render(size=(4, 2)))
    assert np.allclose(
        got[0, :, 0], np.float32(6.28318) * np.float32(0.1) * (np.arange(4) + 0.5), rtol=1e-6
    )


def without_rule(monkeypatch, name, value):
    """Patch `name` in every module of the nir_fold package, and of the NumPy transpiler that
    writes its rewrites, that binds it: the module that defines it, each module that imports it
    (`from .queries import ...` binds a name of its own there) and the package, whose names the
    transpiler reads."""
    import importlib
    import pkgutil

    from glslcheck.backends.cpu_core import nir_fold

    transpile = importlib.import_module("glslcheck.backends.numpy_engine.transpile")
    modules = [nir_fold] + [
        importlib.import_module(f"{package.__name__}.{m.name}")
        for package in (nir_fold, transpile)
        for m in pkgutil.iter_modules(package.__path__)
    ]
    bound = [m for m in modules if hasattr(m, name)]
    assert bound, name
    for module in bound:
        monkeypatch.setattr(module, name, value)


@pytest.mark.parametrize(
    "text",
    [
        ZERO_ADDS,
        MERGED_DOTS,
        ONE_VALUE_DOTS,
        SCALED_ARGUMENTS,
        HASHES_WITHOUT_SINE,
        GLOBAL_CONSTANTS,
        SSA_VALUES,
        RETURNED_SUMS,
        CALL_CONSTANTS,
        CALL_CONSTANTS_STEP,
        SQUARED_LENGTHS,
        NORMALIZED_STEPS,
        CONSTANT_POWERS,
        COMPONENT_WRITES,
        CANCELLED_SUMS,
        SUNK_THROUGH_COMPOUNDS,
        KEPT_RETURNS.replace("STEPS", "40"),
    ],
    ids=[
        "zero_adds",
        "merged_dots",
        "one_value_dots",
        "scaled_arguments",
        "hashes_without_sine",
        "globals",
        "ssa_values",
        "returned_sums",
        "call_constants",
        "call_constants_step",
        "squared_lengths",
        "normalized_steps",
        "constant_powers",
        "component_writes",
        "cancelled_sums",
        "sunk_through_compounds",
        "kept_returns",
    ],
)
def test_float64_reference_is_the_same_without_these_rewrites(make_shader, monkeypatch, text):
    """The rewrites and the inlining above are float32 (llvmpipe) only: the float64 render is
    bit for bit the one of the code generated without them."""
    from glslcheck.backends.cpu_core.nir_fold import dot_constants
    from glslcheck.backends.numpy_engine.transpile import functions

    shader = make_shader(text)
    with_them = np.asarray(
        compile_backend(shader, "numpy").render(size=(32, 18), precision="float64")
    )
    monkeypatch.setattr(functions, "worth_inlining", lambda *a: False)
    monkeypatch.setattr(functions, "folded_call", lambda *a: None)
    without_rule(monkeypatch, "merged_dot", lambda *a: None)
    without_rule(monkeypatch, "broadcast_dot", lambda *a: None)
    without_rule(monkeypatch, "dot_operand", dot_constants.constant_product)
    without_rule(monkeypatch, "zero_add", lambda *a: None)
    without_rule(monkeypatch, "constant_global", lambda *a: False)
    without_rule(monkeypatch, "component_write", lambda *a: None)
    without_rule(monkeypatch, "_cancelled_sum", lambda *a: None)
    without_rule(monkeypatch, "sunk_through_compound", lambda *a: None)
    without_rule(monkeypatch, "register_call", lambda *a: False)
    for name in (
        "broadcast_dot_parts",
        "_scalar_dot",
        "_sink_sum",
        "keep_factor",
        "merge_into_matrix",
        "sunk_return",
        "fused_after_call",
        "squared_length",
        "sink_constant",
        "merge_components",
    ):
        without_rule(monkeypatch, name, lambda *a: None)
    without = np.asarray(
        compile_backend(make_shader(text), "numpy").render(size=(32, 18), precision="float64")
    )
    assert with_them.view(np.int64).tolist() == without.view(np.int64).tolist()


# A lattice hash of the kind iq's sphere fbm uses: the parameter assigned a product by a
# constant, then its components summed (NIR factors the first two terms, then the third into
# that product); the same through a never-written local, grouped both ways, in a product.
FACTORED_TWICE = """float cellHash(vec3 p) {
    p = 17.0 * fract(p * 0.3183099 + vec3(0.11, 0.17, 0.13));
    return fract(p.x * p.y * p.z * (p.x + p.y + p.z));
}
void mainImage(out vec4 c, in vec2 p) {
    vec3 s = 23.0 * fract(vec3(p.x * 0.1371, p.y * 0.0917, p.x * 0.0311 + p.y * 0.0173));
    c = vec4(cellHash(vec3(p / iResolution.y, iTime + 0.3)), s.x + s.y + s.z,
             s.x * s.y * s.z * (s.x + (s.y + s.z)), 1.0);
}"""


def test_a_sum_of_three_products_by_one_constant_is_factored_twice(
    renders_as_llvmpipe, make_shader
):
    """``k*x + k*y + k*z`` is ``k * ((x + y) + z)`` on llvmpipe: the first factoring makes a
    product, which factors with the third term again (nir_fold.factoring, a _Sum factor), also
    where the products are the components of a parameter assigned again (ssa_values keeps
    the factor). Measured without it: 5428, 3421 and 2819 of the 14,400 pixels differed from
    llvmpipe in the three channels."""
    renders_as_llvmpipe(make_shader(FACTORED_TWICE), name="FACTORED_TWICE")


def test_the_compiled_engine_factors_a_sum_of_three_products_as_llvmpipe(
    renders_as_llvmpipe, numba, make_shader
):
    """The compiled engine takes the factoring from the same plan (rewrite_binary)."""
    renders_as_llvmpipe(make_shader(FACTORED_TWICE), "compiled", name="FACTORED_TWICE")


# exp and log are Mesa's products by log2(e) and ln(2): a smooth minimum's exp(-k*a) with the
# constant passed in, exp of a product of two values, a log scaled by a constant.
EXP_LOG_PRODUCTS = """float smoothMin(float a, float b, float k) {
    return -log(exp(-k * a) + exp(-k * b)) / k;
}
void mainImage(out vec4 c, in vec2 f) {
    vec2 p = f / iResolution.y * 2.0 - 1.0 + iTime;
    float q = fract(p.x * 7.31) + 0.1;
    c = vec4(smoothMin(p.x, p.y, 1.56), exp(p.x * p.y), log(q) * 1.56, 1.0);
}"""


@pytest.mark.parametrize("backend", ["numpy", "compiled"])
def test_exp_and_log_are_products_by_constants_to_nir(renders_as_llvmpipe, make_shader, backend):
    """``exp(x * #k)`` is ``exp2(x * (k*log2(e)))``, ``exp(a*b)`` is ``exp2((a*log2(e)) * b)``,
    ``log(x) * #k`` is ``log2(x) * (ln(2)*k)`` (nir_fold.exp_log), in both engines. Measured
    without it: 1819, 1956 and 3960 of the 14,400 pixels differed from llvmpipe per channel."""
    renders_as_llvmpipe(make_shader(EXP_LOG_PRODUCTS), backend, name="EXP_LOG_PRODUCTS")
