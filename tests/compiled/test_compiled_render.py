"""The compiled engine (glslcheck/compiled_backend) against the NumPy backend, bit for bit.

Each shader is rendered by both engines at a small size and the images compared exactly (a NaN
equals a NaN: the engines need not make the same NaN payload, and the image keeps it). The
constructs each have their own small shader, pixels spread over hard inputs (zero-length
normalize, pow of negatives, huge and tiny magnitudes, int overflow, NaN and Inf), so one
wrong rule shows as differing pixels.

Compiling is slow (numba: seconds per module, cold); every program is compiled once per
session (`compiled`, module-scoped cache below) and numba's cache keeps the machine code for
the next run. numba is the optional `jit` extra: without it these tests are skipped on a
developer machine and FAIL on CI (the `numba` fixture, tests/compiled/conftest.py).
"""

from __future__ import annotations

import os

import numpy as np
import pytest
from image_bits import assert_same, assert_same_frames, frame_text

import glslcheck
from glslcheck.base.diagnostics import GlslError

SIZE = (40, 24)
MOUSE = (10.0, 7.0, 3.0, -2.0)
LAB = os.path.join(os.path.dirname(__file__), "..", "..", "lab_shaders")
# a sample of the lab shaders (all of them: benchmarks/bench_compiled.py, which reports the
# agreement of every lab and real shader): one of each structure
LAB_SAMPLE = (
    "01_spheres_procedural",
    "03_lambert_attenuation",
    "05_blinn_phong",
    "07_final",
    "bonus_gooch_shading",
    "bonus_spot_lights",
)


def _compare(shader, time: float = 1.3) -> None:
    """The compiled engine's render of `shader` (a Shader or a path) is the NumPy backend's, as
    numbers (a NaN any NaN: the engines need not make the same payload)."""
    from glslcheck.backends.compiled_engine.engine import compile_compiled

    inputs = dict(size=SIZE, time=time, mouse=MOUSE)
    got = compile_compiled(shader).render(**inputs)
    want = glslcheck.compile(shader, backend="numpy").render(**inputs)
    what = f"{getattr(shader, 'root', shader)} at {frame_text(**inputs)}"
    assert_same(got, want, what=what, names=("compiled", "numpy"), mode="values_any_nan")


@pytest.mark.parametrize("name", LAB_SAMPLE)
def test_lab_shader_bit_for_bit(numba, name):
    _compare(os.path.join(LAB, name))


# -- constructs, each in its own shader -----------------------------------------------------------
CONSTRUCTS = {
    "functions_out_inout": """
void split(in vec2 p, out float a, inout vec3 acc, out ivec2 cell) {
    a = p.x * 0.5;
    acc += vec3(p, a);
    cell = ivec2(floor(p * 4.0));
    p = vec2(0.0);  // a copy: the caller's value stays
}
float twice(float x) { return x + x; }
void mainImage(out vec4 c, in vec2 f) {
    vec2 uv = f / iResolution.xy;
    float a;
    vec3 acc = vec3(1.0);
    ivec2 cell;
    split(uv, a, acc, cell);
    split(uv.yx, a, acc, cell);
    c = vec4(acc * twice(a), float(cell.x * 7 + cell.y) / 50.0);
}""",
    "control_flow": """
int side = 0;
bool bump() { side += 1; return side > 2; }
vec2 pick(float x) { if (x > 0.5) { return vec2(1.0, x); } else if (x > 0.2) { return vec2(x, \
    2.0); } }  // x <= 0.2: 0
float march(vec2 p) {
    float t = 0.0;
    for (int i = 0; i < 64; i++) {
        float d = length(p - vec2(0.5)) - 0.2 - t * 0.1;
        if (i == 3) continue;
        if (d < 0.01) return t;
        t += d * 0.5;
        if (t > 2.0) break;
    }
    int k = 0;
    while (k < 5) { k++; if (k == 4) break; }
    do { t += 0.01; k--; } while (k > 0);
    return -t;
}
void mainImage(out vec4 c, in vec2 f) {
    vec2 uv = f / iResolution.xy;
    float m = march(uv);
    bool b = uv.x > 0.5 && bump();      // bump only where uv.x > 0.5
    bool o = uv.y > 0.5 || bump();
    float s = uv.x < 0.3 ? (uv.y < 0.5 ? 1.0 : 2.0) : float(side);
    c = vec4(m, b ? 1.0 : 0.0, o ? s : -s, float(side) + pick(uv.x).x - pick(uv.y).y);
}""",
    # two returns in a loop: the lanes right of the middle leave by the second (on the third
    # pass) long before the others reach the first (on the eleventh); a lane that returned
    # keeps its value when another lane later returns by a write above it in the text
    "returns_in_a_loop": """
float steps(vec2 p) {
    float t = 0.0;
    for (int i = 0; i < 32; i++) {
        float d = p.x < 0.5 ? 1.0 - 0.1 * float(i) : 1.0;
        if (d < 0.05) return t;
        t += p.x < 0.5 ? d * 0.1 : d;
        if (t > 2.5) return -1.0 - t;
    }
    return -9.0;
}
void mainImage(out vec4 c, in vec2 f) {
    vec2 uv = f / iResolution.xy;
    c = vec4(steps(uv), steps(uv.yx), uv);
}""",
    # ternaries whose sides are pure become selects (codegen._speculable): the side not taken
    # is computed too, so it must do nothing (x / 0 on it); sides with calls, side effects,
    # int division or assignments keep their branch
    "ternary_selects": """
int side = 0;
float bump(float v) { side += 1; return v + float(side); }
void mainImage(out vec4 c, in vec2 f) {
    vec2 uv = f / iResolution.xy;
    float x = floor(uv.x * 8.0), y = floor(uv.y * 6.0);
    float idx = 0.0;
    idx = y == 2.0 ? (x <= 3.0 ? 40960.0 : 42.0) : idx;
    idx = x < y ? 3.0 : idx;
    idx = x > 1.0 && x < 6.0 && y > 1.0 ? idx + 0.5 : idx;
    float q = uv.y - 0.5;
    float r = q != 0.0 ? uv.x / q : -7.0;          // uv.x / 0.0 on the side not taken
    vec3 col = uv.x > 0.5 ? vec3(uv, q) : vec3(q, r, idx);
    bool flip = uv.y < 0.25 ? uv.x > 0.3 : !(uv.x > 0.6);
    float b = uv.x > 0.7 ? bump(uv.y) : uv.y;      // bump only where taken
    int i = int(x) - 3;
    int d = i != 0 ? 100 / i : -1;
    float a = 0.0;
    float w = uv.y > 0.5 ? (a = 2.0) : (a = 3.0);
    c = vec4(col * (flip ? 0.5 : 1.0) + idx * 0.001, b + float(side) * 0.01 + float(d) * 0.1 + a \
        + w);
}""",
    "structs_arrays": """
struct Light { vec3 pos; float power; bool on; };
struct Hit { float t; Light l; };
Light lights[3];
const float W[4] = float[4](0.1, 0.2, 0.3, 0.4);
Hit best(vec2 p) {
    Hit h = Hit(1e9, lights[0]);
    for (int i = 0; i < 3; i++) {
        float d = distance(vec3(p, 0.0), lights[i].pos);
        if (lights[i].on && d < h.t) { h.t = d; h.l = lights[i]; }
    }
    return h;
}
void mainImage(out vec4 c, in vec2 f) {
    vec2 uv = f / iResolution.xy;
    lights[0] = Light(vec3(0.2, 0.3, 0.0), 1.0, true);
    lights[1] = Light(vec3(0.8, 0.6, 0.1), 2.0, uv.x > 0.2);
    lights[2].pos = vec3(0.5);
    lights[2].power = 3.0;
    lights[2].on = true;
    Hit h = best(uv);
    int k = int(uv.x * 9.0) - 2;  // -2..6: clamped indices at both ends
    float arr[5];
    arr[int(uv.y * 5.0)] = 1.0;
    Light copy[3] = lights;
    copy[0].power = 9.0;
    c = vec4(h.t, h.l.power + W[k] + arr[2], copy[0].power + lights[0].power, float(h.l.on));
}""",
    "swizzles_matrices": """
void mainImage(out vec4 c, in vec2 f) {
    vec2 uv = f / iResolution.xy;
    vec4 v = vec4(uv, uv.yx * 2.0);
    v.xz = v.zx;
    v.wy += vec2(0.25, -0.5);
    vec3 w = v.zyx;
    w.y = w[int(uv.x * 3.0)];
    mat3 m = mat3(cos(uv.x), sin(uv.x), 0.0, -sin(uv.x), cos(uv.x), 0.0, 0.0, 0.0, 1.0);
    mat2 r = mat2(uv.x, uv.y, -uv.y, uv.x * 3.0);
    vec3 a = m * w;
    vec3 b = w * m;
    mat3 mm = m * transpose(m) * 2.0;
    m[1] = vec3(1.0, 2.0, 3.0);
    m[int(uv.y * 3.0)][1] = 5.0;
    vec2 q = inverse(r) * uv + r[1];
    c = vec4(a.x + b.y, mm[0][0] + mm[2].z + determinant(mat3(m)) * 0.01, q * 0.1 + determinant(r));
}""",
    "int_uint": """
void mainImage(out vec4 c, in vec2 f) {
    int x = int(f.x) - 20;
    int y = int(f.y) - 12;
    int big = 2147483647 + x;               // wraps
    int d = y != 0 ? x / y : x / (y + 0);   // x / 0 is 0 on llvmpipe
    int r = x % 7;                          // negatives: llvmpipe's unsigned remainder
    int s = (x << (y + 30)) ^ (big >> 3);   // counts mod 32
    uint u = uint(x) * 2654435761u;
    u ^= u >> 15u;
    uint ud = u / uint(max(y, 0)) + u % 5u;
    int m = -2147483647 - 1;
    int n = m / -1 + abs(m) + int(-3.99) + int(3.99);
    float big_f = float(x) * 1e9;
    ivec3 iv = ivec3(big_f, 1e20 * float(y), f.x) / ivec3(2, 3, max(y, 1));
    c = vec4(float(d + r) * 0.1, float(s & 1023), float(ud % 1000u) / 1000.0,
             float(n + iv.x + iv.y + iv.z + int(uint(big_f))) * 1e-9);
}""",
    "builtins_hard_cases": """
// s(): a NaN or an Inf as a number, so one NaN term does not hide the others of its sum
float s(float v) { return isnan(v) ? 1234.5 : (isinf(v) ? sign(v) * 4321.0 : v); }
float s3(vec3 v) { return s(v.x) + s(v.y) * 3.0 + s(v.z) * 7.0; }
void mainImage(out vec4 c, in vec2 f) {
    vec2 uv = f / iResolution.xy - 0.5;
    float x = uv.x * 40.0;
    if (uv.y > 2.0) x = 0.0;  // x written again: \
        Mesa's constant merging through it (nir_fold) stays out
    vec3 z = vec3(uv.y > 0.3 ? 0.0 : uv.x, 0.0, 0.0);
    vec3 n = normalize(z);                              // NaN for the zero vector
    float p = pow(x, uv.y * 3.0);                        // negative base: NaN
    float p2 = s(pow(x, 2.0)) + s(pow(-abs(x), 4.0)) + s(pow(x, 0.0)) + s(pow(1.0, x));  // \
        Mesa's rewrites
    float huge = s(sin(x * 1e8)) + s(cos(x * 1e12)) + s(tan(x * 3e9)) + s(sin(x)) + s(cos(x * 7.0));
    float tiny = s(exp2(x * 10.0)) + s(log2(abs(x) * 1e-39)) + s(exp(x - x * 6.0)) + s(log(x)) + \
        s(log2(x));
    float inf = 1.0 / uv.x;                              // +-Inf, NaN for 0/0
    float q = inf * 0.0 + 0.0 * uv.x;                    // 0 * Inf: NaN, unless folded
    vec3 mixes = mix(vec3(1.0), vec3(0.0, 2.0, x), uv.x) + mix(z, n, step(0.0, uv.y));
    float a = s(atan(uv.y, uv.x)) + s(atan(x)) * 3.0 + s(asin(uv.y * 3.0)) * 5.0 + s(acos(uv.x)) \
        * 7.0
            + s(atan(0.0, uv.y)) * 11.0 + s(atan(x, 0.0)) * 13.0;
    float h = s(sinh(x)) + s(cosh(uv.y)) * 3.0 + s(tanh(x * 10.0)) * 5.0 + s(asinh(x)) * 7.0
            + s(acosh(x)) * 11.0 + s(atanh(uv.y * 3.0)) * 13.0;
    float m = s(mod(x, uv.y)) + s(fract(-x)) + s(sign(uv.x)) + s(smoothstep(0.1, -0.1, uv.y))
            + s(clamp(x, -1.0, inversesqrt(uv.y))) + s(min(inf, x)) + s(max(q, 1.0)) + s(round(x))
            + s(roundEven(x)) + s(trunc(x)) + s(ceil(x)) + s(floor(x)) + s(degrees(x)) + \
                s(radians(x));
    vec3 g = reflect(n, vec3(0.0, 1.0, 0.0)) + refract(vec3(uv, -1.0), vec3(0.0, 0.0, 1.0), 1.5 + \
        uv.x)
           + cross(vec3(uv, 1.0), z) + faceforward(vec3(1.0), vec3(uv, 0.5), vec3(0.0, 1.0, 0.0));
    float bits = s(intBitsToFloat(floatBitsToInt(x) ^ 1)) + \
        s(uintBitsToFloat(floatBitsToUint(uv.y) + 7u));
    bvec3 bv = lessThan(vec3(x), vec3(0.0, 1.0, 2.0));
    float rel = float(any(bv)) + float(all(not(bv))) + float(isnan(p)) + float(isinf(inf));
    c = vec4(s3(n) + s(p) + p2 + huge * 17.0, tiny + s(q) + a * 19.0 + h * 23.0,
             m + s3(mixes) + s3(g) * 29.0 + s(dot(g, mixes)),
             bits + rel + s(length(uv)) + s(distance(uv, vec2(0.1))));
}""",
    "globals_and_constants": """
float counter = 1.5;
const vec3 K = vec3(0.0, 1.0, 2.0);
vec2 last;
void touch(float v) { counter += v; last = vec2(counter, v); }
vec3 tone(vec3 albedo) { return K + 0.5 * albedo; }  // a constant zero on the left (Mesa drops it)
void mainImage(out vec4 c, in vec2 f) {
    vec2 uv = f / iResolution.xy;
    touch(uv.x);
    if (uv.y > 0.5) touch(1.0);
    vec3 nan3 = vec3(0.0) / vec3(uv.x - uv.x);
    vec3 folded = nan3 * K;                 // NaN times a constant zero is 0 (Mesa folds it)
    float negz = -0.0 * uv.x + 0.0;        // x + 0.0 keeps the sign of -0.0
    vec3 left = tone(vec3(uv, -0.0 * uv.y));  // K.x = 0.0 + x: the right side, -0.0 kept
    negz += 1.0 / left.z + (0.0 - uv.x);
    c = vec4(counter + left.x * 3.0, last.y + folded.x, folded.y + 1.0 / negz, iTime + iMouse.x + \
        iDate.w * 0.0
             + iResolution.x + float(iFrame));
}""",
}


@pytest.mark.parametrize("name", sorted(CONSTRUCTS))
def test_construct_bit_for_bit(numba, make_shader, name):
    shader = make_shader(CONSTRUCTS[name])
    # none of Mesa's reassociations, which the NumPy backend copies and this engine does not
    # (backends/cpu_core/nir_fold/ emits each as `(<Mesa's order> if rt.lp else
    # <written>)`): these shaders test the engine's own rules (the reassociations:
    # test_mesa_reassociation_...)
    assert "if rt.lp else" not in glslcheck.compile(shader, backend="numpy").source
    _compare(shader)


def _statement_code(source: str, glsl: str) -> list[str]:
    """The generated lines of the statement whose source comment holds glsl."""
    lines = source.splitlines()
    start = next(
        i for i, line in enumerate(lines) if line.strip().startswith("# line") and glsl in line
    )
    end = next(i for i in range(start + 1, len(lines)) if lines[i].strip().startswith("# line"))
    return [line.strip() for line in lines[start + 1 : end]]


def test_pure_ternaries_are_selects(make_shader):
    """The ternary_selects construct's pure ternaries are written as selects, the others keep
    their branch (the bits: test_construct_bit_for_bit)."""
    from glslcheck.backends.compiled_engine.engine import generate

    source, _ = generate(make_shader(CONSTRUCTS["ternary_selects"]), lanes=0)
    for glsl in (
        "(x <= 3.0 ? 40960.0 : 42.0)",
        "x < y ? 3.0",
        "idx + 0.5 : idx",
        "uv.x / q : -7.0",
        "vec3(uv, q) : vec3(q, r, idx)",
        "uv.x > 0.3 : !(uv.x > 0.6)",
    ):
        code = _statement_code(source, glsl)
        assert not any(line.startswith("if ") for line in code), (glsl, code)
        assert any("lsel(" in line for line in code), (glsl, code)
    for glsl in ("bump(uv.y) : uv.y", "100 / i : -1", "(a = 2.0) : (a = 3.0)"):
        code = _statement_code(source, glsl)
        assert any(line.startswith("if ") for line in code), (glsl, code)


def test_mesa_reassociation_bit_for_bit(numba, make_shader):
    """`x * 3.1` with `float x = uv.x * 40.0` never written again is `uv.x * (3.1*40.0)` on
    llvmpipe (nir_opt_algebraic merges the constants through the SSA value): nir_fold's
    constant_merge decides it for both engines, and the compiled engine computes the merged
    product (its module multiplies the two constants) to the NumPy backend's bits."""
    from glslcheck.backends.compiled_engine.engine import compile_compiled, generate

    shader = make_shader(
        "void mainImage(out vec4 c, in vec2 f) {\n float x = (f.x / iResolution.x - 0.5) * 40.0;"
        "\n c = vec4(exp2(x * 3.1), 1.0, 1.0, 1.0); }"
    )
    assert "(F_3p1 * F_40p0)" in generate(shader)[0]
    got = compile_compiled(shader).render(size=SIZE)
    want = glslcheck.compile(shader, backend="numpy").render(size=SIZE)
    assert_same(got, want, what=f"{SIZE[0]}x{SIZE[1]}, iTime 0", names=("compiled", "numpy"))


def test_constants_merged_through_a_negation_bit_for_bit(numba, make_shader):
    """``-x * #c`` with x's value ``y * #k`` is ``-(y * (k*c))`` on llvmpipe (NIR moves the
    negation out of the product: nir_fold.constant_merge, measured in
    tests/gl/test_llvmpipe_lowering.py): through a local, a parenthesized product, a local
    holding the negation, a vector, on either side."""
    shader = make_shader(
        "void mainImage(out vec4 c, in vec2 p) {\n float a = fract(p.x * 0.1371 + p.y * 0.0917),"
        " b = sin(p.y * 0.917 + p.x * 0.0311);\n float x = a * 0.85;\n"
        " vec3 w = -(vec3(a, b, a - b) * 2.1);\n c = vec4(-x * 0.6, (0.45 * w).y + (w * 0.3).z,"
        " -(b * 1.3) * 0.7, 1.0); }"
    )
    assert "if rt.lp else" in glslcheck.compile(shader, backend="numpy").source
    _compare(shader)


def test_uniform_products_merged_at_every_frame(numba, make_shader):
    """``float time = iTime * 0.85; sin(time * 0.2)`` is ``sin(iTime * (0.2*0.85))`` on
    llvmpipe (constant_merge through the SSA value, as above, here of a uniform: one lane in the
    NumPy backend, one scalar a block in lockstep). The merged and the written product round
    apart at some iTime values only, so one frame proves little: every frame of 4 s of
    animation, per pixel and in lockstep, bit for bit against the NumPy backend."""
    from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate

    shader = make_shader(
        "void mainImage(out vec4 c, in vec2 f) {\n float time = iTime * 0.85;\n"
        " c = vec4(sin(time * 0.2), cos(time * 0.28) * 0.4, -time * 0.6, f.x * time * 0.5); }"
    )
    times = [k / 60 for k in range(240)]
    numpy = glslcheck.compile(shader, backend="numpy")
    want = np.stack([numpy.render(size=(8, 1), time=t) for t in times])
    for lanes in (0, 8):
        prog = CompiledProgram(*generate(shader, lanes=lanes))
        got = np.stack([prog.render(size=(8, 1), time=t) for t in times])
        assert_same_frames(got, want, times, what="8x1", names=(f"lanes {lanes}", "numpy"))


REPEATED_SUMS = """float rnd(inout float seed) { seed += 0.1; return seed; }
vec2 hash2(inout float seed) { return vec2(seed += 0.1, seed += 0.1); }
void mainImage(out vec4 c, in vec2 p) {
    float s0 = fract(p.x * 0.1371 + p.y * 0.0917) * 40.0, seed = s0;
    seed += 0.1; seed += 0.1; seed += 0.1;
    float a = fract(sin(seed) * 43758.5453);
    vec2 v = vec2(seed += 0.1, seed += 0.1);
    seed = seed + 0.1; seed -= 0.1; seed += 0.2;
    vec3 w = vec3(s0); w += 0.047; w += vec3(1.802, 0.5, 0.25); w -= 1.423;
    for (int i = 0; i < iFrame + 2; i++) { seed += 0.1; seed += 0.1; }
    float b = seed;
    if (s0 > 20.0) { seed += 0.1; seed += 0.7; } seed += 0.1;
    rnd(seed); rnd(seed);
    vec2 h = hash2(seed); h += hash2(seed);
    seed += 2.329; float r = 0.0;
    for (int i = 0; i < 4; i++) { r += rnd(seed); }
    c = vec4(a + v.y + h.x, b + w.y + h.y, seed + w.x + r, rnd(seed));
}"""


def test_repeated_sums_bit_for_bit(numba, make_shader):
    """``seed += 0.1`` written again and again: NIR's merged constants
    (nir_fold.repeated_sums, measured on llvmpipe: tests/gl/test_llvmpipe_repeated_sums.py) in
    both engines, in a straight line, a constructor, mixed forms, vectors, a loop, a branch,
    through calls (inout parameters, a constructor's in the callee) and an unrolled loop."""
    shader = make_shader(REPEATED_SUMS)
    assert "if rt.lp else" in glslcheck.compile(shader, backend="numpy").source
    _compare(shader, time=0.0)


ARMS_BY_BLOCK = """vec2 hash2(inout float seed) {
    return fract(sin(vec2(seed += 0.1, seed += 0.1)) * vec2(43758.5453123, 22578.1459123));
}
float trace(inout float seed, bool u) {
    float acc = 0.0;
    for (int j = 0; j < 3; ++j) {
        if (u) { acc += hash2(seed).x; } else { acc += hash2(seed).y; }
    }
    return acc;
}
void mainImage(out vec4 c, in vec2 f) {
    float seed = f.x * 0.0217 + f.y * 0.0731;
    hash2(seed);
    float acc = trace(seed, f.x < 16.0);
    c = vec4(seed, acc, 0.0, 1.0);
}"""


def test_seed_chains_in_arms_bit_for_bit(numba, make_shader):
    """A seed's chain into the arms of an ``if`` in an unrolled loop: the first pass reads the
    caller's constants, the later ones their own (nir_fold.repeated_sums.later_entry, chosen
    by the pass count in both arms); per pixel and in lockstep, whose blocks of 8 pixels here
    take one arm only (a compare hoisted in one arm is not read in the other)."""
    from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate

    shader = make_shader(ARMS_BY_BLOCK)
    want = glslcheck.compile(shader, backend="numpy").render(size=SIZE, time=0.0)
    for lanes in (0, 8):
        got = CompiledProgram(*generate(shader, lanes=lanes)).render(size=SIZE, time=0.0)
        assert_same(got, want, what=f"lanes {lanes}", names=("compiled", "numpy"))


RETURNED_SUMS = """float fbm(vec3 p) {
    float f;
    f = 0.5 * sin(p.x); p = p * 2.02;
    f += 0.25 * sin(p.y);
    float n = sin(p.z * 3.5);
    f += 0.03 * n * n;
    return f;
}
vec2 waves(vec2 p) {
    vec2 w = sin(p * 1.7);
    w -= 0.125 * cos(p.yx * 3.1);
    w += 0.0625 * sin(p * 5.3);
    return w;
}
float terrain(vec3 pos) {
    float h = 1.0 - smoothstep(1.0, 3.0, pos.y);
    return pos.y * 0.1 + (fbm(pos * vec3(0.8, 1.0, 0.8)) - 0.4) * h;
}
void mainImage(out vec4 c, in vec2 f) {
    vec3 p = vec3(f / iResolution.xy, 0.5) * 3.0;
    vec2 w = waves(p.xy * 4.0) + vec2(0.3, -0.7);
    c = vec4(terrain(p), w, fbm(p.zyx));
}"""


def test_returned_sums_bit_for_bit(numba, make_shader):
    """``fbm(x) - 0.4`` of a function returning ``f = a; f += b; ...``: NIR inlines it and sinks
    the constant into the sum (nir_fold.sunk_return, both engines from that rule), a float and
    a vec2 sum, a ``-=`` term, and a call without a constant beside."""
    shader = make_shader(RETURNED_SUMS)
    source = glslcheck.compile(shader, backend="numpy").source
    assert "_k is None" in source  # (the NumPy backend sinks the constants: the rule applies)
    _compare(shader, time=0.0)


FUSED_AFTER_CALL = """vec3 rotate(vec3 p, float x, float y, float z) {
    mat3 matx = mat3(1.0, 0.0, 0.0, 0.0, cos(x), sin(x), 0.0, -sin(x), cos(x));
    mat3 maty = mat3(cos(y), 0.0, -sin(y), 0.0, 1.0, 0.0, sin(y), 0.0, cos(y));
    mat3 matz = mat3(cos(z), sin(z), 0.0, -sin(z), cos(z), 0.0, 0.0, 0.0, 1.0);
    p = matx * p;
    p = matz * p;
    p = maty * p;
    return p;
}
void turn(inout vec3 dir, inout vec3 pos) {
    vec2 m = iMouse.xy / iResolution.xy;
    vec3 angle = vec3(m.y * 0.05 + 0.05, 1.0 + m.x, -0.45);
    dir = rotate(dir, angle.x, angle.y, angle.z);
    pos = rotate(pos, angle.x, angle.y, angle.z);
}
void mainImage(out vec4 c, in vec2 f) {
    vec2 uv = f / iResolution.xy;
    vec3 dir = normalize(vec3(uv * 2.0 - 1.0, 6.0));
    vec3 pos = vec3(0.0, -0.0, -10.0);
    pos.x += 0.35 * 3.0 - 1.5;
    turn(dir, pos);
    float dither = fract(sin(dot(uv, vec2(12.9898, 78.223))) * 43758.5453) * 2.0;
    vec3 ray = pos + dir * dither * 15.0 / 200.0;
    c = vec4(ray, 1.0);
}"""


def test_fused_after_folded_call_bit_for_bit(numba, make_shader):
    """``pos + e`` where a call folded per call site left ``p1 + p2`` in pos's components:
    llvmpipe's ffma fusing and splitting makes it ``(p1 + e) + p2`` (nir_fold.fused_plan
    decides for both engines; gargantua's camera)."""
    import re

    shader = make_shader(FUSED_AFTER_CALL)
    source = glslcheck.compile(shader, backend="numpy").source
    assert re.search(r"\(\(_t\d+ \+ _t\d+\[0\]\) \+ _t\d+\)", source)  # (the rule applies)
    _compare(shader, time=0.0)


PRODUCT_SUMS = """vec2 G = vec2(0.6 * 1.5 + 0.25 * 2.0 + 1.85, 1.25);
void mainImage(out vec4 c, in vec2 p) {
    float u = fract(p.x * 0.1371 + p.y * 0.0917) * 40.0, v = fract(p.x * 0.0371 + p.y * 0.917);
    float k = p.x * 0.0123 + p.y * 0.457;
    vec2 q = p / 7.0; q.x *= iResolution.x / iResolution.y;
    vec2 w = p * 0.0123 + p.yx * 0.457 + iTime;
    c = vec4(p.x * 0.0123 + p.y * 0.457 + fract(1.12 * iTime) + (u * v - p.y * 0.457 - iTime),
             iTime + (u * v + u * p.y) + (k + iTime),
             q.x + q.y * 3.43 + fract(1.12 * iTime) + w.y,
             u * v + p.x * 0.37 + p.y * 0.457 + iTime + G.x * G.y);
}"""


def test_product_sums_bit_for_bit(numba, make_shader):
    """``(p1 + p2) + e`` is ``(p1 + e) + p2`` on llvmpipe where e is no product
    (nir_fold.product_sums, measured in tests/gl/test_llvmpipe_product_sums.py): a uniform, a
    uniform expression, a difference, e first, a factorable sum, a local, a component ``*=``
    wrote, a vector, and three products kept (a global's initializer is left as written); per
    pixel and in lockstep against the NumPy backend, over frames where the orders round
    apart."""
    from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate

    shader = make_shader(PRODUCT_SUMS)
    assert "if rt.lp else" in glslcheck.compile(shader, backend="numpy").source
    times = [0.3 + k / 7 for k in range(12)]
    numpy = glslcheck.compile(shader, backend="numpy")
    want = np.stack([numpy.render(size=SIZE, time=t) for t in times])
    for lanes in (0, 8):
        prog = CompiledProgram(*generate(shader, lanes=lanes))
        got = np.stack([prog.render(size=SIZE, time=t) for t in times])
        what = f"{SIZE[0]}x{SIZE[1]}"
        assert_same_frames(got, want, times, what=what, names=(f"lanes {lanes}", "numpy"))


PATH_TRACERS = os.path.join(os.path.dirname(__file__), "..", "gl", "path_tracers")


@pytest.mark.parametrize(
    "name", sorted(f[:-5] for f in os.listdir(PATH_TRACERS) if f.endswith(".glsl"))
)
def test_path_tracers_bit_for_bit(numba, name):
    """A seed advanced through calls and an unrolled bounce loop (a global, an inout
    parameter): the chain's constants from one plan in both engines
    (tests/gl/test_llvmpipe_path_tracers.py verifies them against llvmpipe), and the lockstep
    rewrite takes the loop's pass count."""
    from glslcheck.backends.compiled_engine.engine import generate
    from glslcheck.shadertoy.sources import load_shader

    path = os.path.join(PATH_TRACERS, f"{name}.glsl")
    assert "LANES_FALLBACK" not in generate(load_shader(path), lanes=8)[0]
    _compare(path)


@pytest.mark.parametrize(
    "text, what",
    [
        (
            "void mainImage(out vec4 c, in vec2 f) { c = vec4(float(packHalf2x16(f))); }",
            "packHalf2x16",
        ),
    ],
)
def test_unsupported_is_a_located_error(numba, make_shader, text, what):
    from glslcheck.backends.compiled_engine.engine import compile_compiled

    with pytest.raises(GlslError) as info:
        compile_compiled(make_shader(text))
    message = str(info.value)
    assert what in message and "not supported by the compiled engine yet" in message
    assert info.value.diagnostics[0].loc.line == 1


def test_runaway_loop_is_a_located_error(numba, make_shader):
    from glslcheck.backends.compiled_engine.engine import compile_compiled

    text = (
        "void mainImage(out vec4 c, in vec2 f) {\n float t = 0.0;\n while (f.x > 0.0) { t += "
        "1.0; }\n c = vec4(t); }"
    )
    prog = compile_compiled(make_shader(text))
    with pytest.raises(GlslError, match="loop ran more than") as info:
        prog.render(size=(2, 2))
    loc = info.value.diagnostics[0].loc
    assert (loc.path, loc.line, loc.column) == ("Image.glsl", 3, 2)


GLOBAL_COUNTERS = os.path.join(os.path.dirname(__file__), "..", "gl", "global_counters")


@pytest.mark.parametrize(
    "name", sorted(n[:-5] for n in os.listdir(GLOBAL_COUNTERS) if n.endswith(".glsl"))
)
def test_global_counters_bit_for_bit(numba, name):
    """Globals changed in the functions mainImage calls (compared with llvmpipe in
    tests/gl/test_llvmpipe_global_counters.py)."""
    _compare(os.path.join(GLOBAL_COUNTERS, f"{name}.glsl"))
