"""NumPy renders against the GL driver (Mesa llvmpipe): the corpus, masks, calls, indexing,
precision and supersampling.

Tolerance: `glslcheck.verification.compare.compare`, the project's one tolerance model (2/255 per
channel after clamping, scattered/edge budgets; argued in verification/compare.py). Our float32
arithmetic follows llvmpipe operation by operation (no FMA, the same formulas for the built-ins, see
runtime.py), so smooth shading agrees to ~1e-3 at worst (exp2/log2/pow ULPs through a lighting
chain); the budget for edge pixels covers silhouettes where one float32 rounding flips a comparison.
Tests of exact integer/bool logic (`_exact`) demand bit equality instead.
"""

from __future__ import annotations

import glob
import os

import numpy as np
import pytest

from glslcheck.backends.numpy_engine import program as P
from glslcheck.backends.numpy_engine import tiles as F
from glslcheck.shadertoy.sources import load_shader
from glslcheck.verification.compare import compare

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CORPUS = sorted(
    glob.glob(os.path.join(ROOT, "tests", "corpus", "*.glsl"))
    + glob.glob(os.path.join(ROOT, "tests", "corpus", "*.frag"))
)
LABS = sorted(p for p in glob.glob(os.path.join(ROOT, "lab_shaders", "*")) if os.path.isdir(p))


def _image(body: str, helpers: str = "") -> str:
    return helpers + "\nvoid mainImage(out vec4 fragColor, in vec2 fragCoord) {\n" + body + "\n}\n"


def _both(gl, shader, **kw):
    from glslcheck.backends.gl import compile_gl

    a = P.compile_numpy(shader).render(**kw)
    b = compile_gl(shader, gl).render(**kw)
    return a, b


def _match(gl, shader, **kw):
    a, b = _both(gl, shader, **kw)
    c = compare(a, b)
    assert c.match, c.summary() if hasattr(c, "summary") else (c.max_abs_error, c.mismatched_pixels)
    return a, b


def _exact(gl, shader, **kw):
    a, b = _both(gl, shader, **kw)
    np.testing.assert_array_equal(a, b)
    return a


def _load(path):
    # Every corpus and lab shader must transpile: a failure here is a failure, not a skip.
    shader = load_shader(path)
    return shader, P.compile_numpy(shader)


# -- the corpus and the lab ----------------------------------------------------------------


@pytest.mark.parametrize("path", CORPUS + LABS, ids=lambda p: os.path.relpath(p, ROOT))
def test_corpus_matches_gl(gl, path):
    from glslcheck.backends.gl import compile_gl

    shader, prog = _load(path)
    # A corpus program the driver rejects is a failure: check accepted it, so the two disagree.
    glprog = compile_gl(shader, gl)
    for size, time in (((96, 54), 0.0), ((97, 31), 1.7)):
        a = prog.render(size=size, time=time, frame=3)
        b = glprog.render(size=size, time=time, frame=3)
        c = compare(a, b)
        assert c.match, (path, size, c.max_abs_error, c.mismatched_pixels, c.edge_pixels)


@pytest.mark.parametrize("path", CORPUS + LABS, ids=lambda p: os.path.relpath(p, ROOT))
def test_corpus_same_with_and_without_compaction(path):
    shader, prog = _load(path)
    ref = prog.render(size=(160, 90), time=0.5)
    prog = P.compile_numpy(shader)
    prog.compaction = F.Compaction(min_lanes=1)
    again = prog.render(size=(160, 90), time=0.5)
    np.testing.assert_array_equal(ref, again)


# -- orientation and the footer --------------------------------------------------------------


def test_shape_orientation_alpha(make_shader):
    img = P.compile_numpy(
        make_shader(_image("fragColor = vec4(fragCoord, fragCoord.y / iResolution.y, 0.25);"))
    ).render(size=(5, 3))
    assert img.shape == (3, 5, 4) and img.dtype == np.float32
    assert np.array_equal(img[0, :, 0], np.arange(5) + 0.5)
    assert np.array_equal(img[:, 0, 1], [2.5, 1.5, 0.5])
    assert np.all(img[..., 3] == 1.0)


def test_inputs_match_gl(gl, make_shader):
    body = (
        "fragColor = vec4(iTime + float(iFrame), iMouse.x + iMouse.w + iTimeDelta, "
        "iDate.x + iDate.y + iDate.z + iDate.w + iFrameRate, iChannelTime[1]);"
    )
    _exact(gl, make_shader(_image(body)), size=(3, 2), time=1.25, frame=7, mouse=(10, 20, 30, -4))


# -- masks -------------------------------------------------------------------------------------


def test_divergent_if_else(gl, make_shader):
    body = """
    vec3 c = vec3(0.0);
    if (fragCoord.x < 20.0) { c.r = 1.0; if (fragCoord.y > 10.0) c.g += 0.5; else { c.b = 0.25; } }
    else if (fragCoord.x < 40.0) c = vec3(0.5);
    else { c.g = fragCoord.y / 64.0; }
    fragColor = vec4(c, 1.0);"""
    _exact(gl, make_shader(_image(body)), size=(64, 32))


def test_loops_with_lane_dependent_break_and_continue(gl, make_shader):
    body = """
    float acc = 0.0;
    int n = int(fragCoord.x) % 13;
    for (int i = 0; i < 20; i++) {
        if (i == n) break;
        if (i % 3 == 1) continue;
        acc += 1.0;
    }
    int k = 0;
    while (true) { k++; if (k > int(fragCoord.y)) break; }
    int j = 0;
    do { j += 2; if (j == 6) continue; acc += 0.01; } while (j < int(fragCoord.x) % 7);
    fragColor = vec4(acc / 20.0, float(k) / 64.0, float(j) / 16.0, 1.0);"""
    _exact(gl, make_shader(_image(body)), size=(64, 48))


def test_early_return(gl, make_shader):
    helpers = """
    float f(float x) {
        if (x < 10.0) return 0.1;
        for (int i = 0; i < 10; i++) { if (float(i) * 5.0 > x) return float(i) / 10.0; }
        return 1.0;
    }
    void g(inout vec3 c, float x) { if (x > 30.0) return; c.r = 0.5; }"""
    body = "vec3 c = vec3(0.0); g(c, fragCoord.x); c.g = f(fragCoord.x); fragColor = vec4(c, 1.0);"
    _exact(gl, make_shader(_image(body, helpers)), size=(64, 8))


def test_switch_fall_through(gl, make_shader):
    body = """
    int k = int(fragCoord.x) % 6;
    vec3 c = vec3(0.0);
    switch (k) {
        case 0: c.r += 0.25;
        case 1: c.g += 0.5; break;
        default: c.b = 1.0;
        case 3: c.r += 0.125; break;
        case 4: { c = vec3(0.75); if (fragCoord.y > 2.0) break; c.g = 0.0; }
    }
    fragColor = vec4(c, 1.0);"""
    _exact(gl, make_shader(_image(body)), size=(12, 4))


def test_continue_in_a_switch_skips_the_later_cases(gl, make_shader):
    body = """
    float acc = 0.0;
    for (int i = 0; i < 5; i++) {
        switch ((int(fragCoord.x) + i) % 4) {
            case 1: acc += 0.125; continue;
            case 2: if (fragCoord.y > 1.0) { acc += 0.5; continue; }
            case 3: acc -= 0.0625;
        }
        acc += 0.25;
    }
    fragColor = vec4(acc, 0.0, 0.0, 1.0);"""
    _exact(gl, make_shader(_image(body)), size=(8, 4))


def test_a_discard_of_every_lane_keeps_the_clear_colour(gl, make_shader):
    """Under a uniform condition in mainImage (or a function it calls with every lane), where
    the discard mask is the entry's full mask."""
    helpers = "void kill() { if (iTime > 2.0) discard; }"
    body = "if (iTime > 1.0) discard; kill(); fragColor = vec4(0.5, 0.25, 1.0, 1.0);"
    shader = make_shader(_image(body, helpers))
    for t in (0.5, 1.5, 2.5):
        img = _exact(gl, shader, size=(8, 4), time=t)
        assert np.all(img[..., 3] == (1.0 if t < 1.0 else 0.0))


def test_discard_keeps_the_clear_colour(gl, make_shader):
    helpers = "void kill(float x) { if (x > 5.0) discard; }"
    body = (
        "if (fragCoord.y < 2.0) discard; kill(fragCoord.x); fragColor = vec4(0.5, 0.25, 1.0, 1.0);"
    )
    img = _exact(gl, make_shader(_image(body, helpers)), size=(8, 4))
    assert np.all(img[-2:] == 0.0) and np.all(img[:2, 5:] == 0.0) and np.all(img[:2, :5, 3] == 1.0)


def test_short_circuit_and_ternary_side_effects(gl, make_shader):
    helpers = "float g; bool bump(float v) { g += v; return v > 3.0; }"
    body = """
    g = 0.0;
    bool a = fragCoord.x > 4.0 && bump(fragCoord.x);
    bool b = fragCoord.x < 2.0 || bump(1.0);
    float t = fragCoord.y > 1.0 ? (g += 10.0) : (g -= 1.0);
    fragColor = vec4(g / 40.0, float(a), float(b), t / 40.0);"""
    _exact(gl, make_shader(_image(body, helpers)), size=(8, 3))


# -- calls, structs, arrays --------------------------------------------------------------------


def test_out_inout_copy_semantics(gl, make_shader):
    helpers = """
    void f(inout float a, out float b, float c) { a += c; b = a * 2.0; c = 100.0; }
    void z(out vec2 v) { v.x += 1.0; }
    float arr[3];"""
    body = """
    float p = 1.0, q = 5.0;
    f(p, q, p);
    int i = 0;
    arr[0] = fragCoord.x;
    f(arr[i++], arr[i], 3.0);
    fragColor = vec4(p + q, arr[0] + arr[1] * 0.01, float(i), 1.0);"""
    _exact(gl, make_shader(_image(body, helpers)), size=(4, 2))


def test_out_parameters_start_at_zero(make_shader):
    # WebGL zero-initialises out parameters; Mesa's glsl_zero_init does not cover them, so this
    # is checked by value.
    helpers = "void z(out vec2 v, out int n) { v.x += 1.0; n++; }"
    body = "vec2 w = vec2(7.0); int n = 5; z(w, n); fragColor = vec4(w, float(n), 1.0);"
    img = P.compile_numpy(make_shader(_image(body, helpers))).render(size=(2, 1))
    assert img[0, 0].tolist() == [1.0, 0.0, 1.0, 1.0]


def test_structs_and_dynamic_indexing(gl, make_shader):
    helpers = """
    struct Light { vec3 pos; float k[2]; };
    Light lights[3];"""
    body = """
    for (int i = 0; i < 3; i++) { lights[i].pos = vec3(float(i)); lights[i].k[1] = float(i) * 0.5; }
    int j = int(fragCoord.x) % 3;
    Light l = lights[j];
    l.pos.y += 0.25;
    lights[j].k[0] = l.pos.y;
    mat3 m = mat3(1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0);
    vec3 col = m[j];
    col[j] *= 2.0;
    fragColor = vec4(l.pos.y + lights[j].k[0] + l.k[1], col.x / 10.0, col[int(fragCoord.y) % 3] / \
        20.0, 1.0);"""
    _exact(gl, make_shader(_image(body, helpers)), size=(6, 3))


def test_out_of_range_dynamic_index_is_clamped(make_shader):
    # WebGL (ANGLE) clamps; desktop drivers leave it undefined, so this is checked by value.
    body = """
    float a[4] = float[4](1.0, 2.0, 3.0, 4.0);
    int i = int(fragCoord.x) - 2;
    vec3 v = vec3(10.0, 20.0, 30.0);
    a[i + 1] += 100.0;
    fragColor = vec4(a[i], v[i], a[0] + a[3], 1.0);"""
    img = P.compile_numpy(make_shader(_image(body))).render(size=(8, 1))
    i = np.arange(8) - 2
    a0 = np.where(i + 1 <= 0, 101.0, 1.0)
    a3 = np.where(i + 1 >= 3, 104.0, 4.0)
    expect_a = np.array([[1, 2, 3, 4]] * 8, float)
    expect_a[np.arange(8), np.clip(i + 1, 0, 3)] += 100.0
    np.testing.assert_array_equal(img[0, :, 0], expect_a[np.arange(8), np.clip(i, 0, 3)])
    np.testing.assert_array_equal(img[0, :, 1], np.array([10, 20, 30])[np.clip(i, 0, 2)])
    np.testing.assert_array_equal(img[0, :, 2], a0 + a3)


# -- precision and supersampling -------------------------------------------------------------


def test_precision_modes_use_their_dtypes(make_shader):
    prog = P.compile_numpy(
        make_shader(
            _image(
                # u is 1 at run time but no constant: Mesa would reassociate (1.0 + t) - 1.0 into t
                "float e = 1.0 / 1024.0; float t = iTime * 1e-8; float u = iResolution.x / "
                "iResolution.x;"
                "fragColor = vec4((1.0 + e * 0.4 - 1.0) * 1024.0, (1.0 + t - u) * 1e8, 0.0, 1.0);"
            )
        )
    )
    seen = {}
    for precision in ("float16", "float32", "float64"):
        ns = prog.module(precision)
        seen[precision] = ns["rt"].F
        img = prog.render(size=(1, 1), time=1.0, precision=precision)
        assert img.dtype == np.float32
        seen[precision + "-img"] = img[0, 0, :2]
    assert (
        seen["float16"] is np.float16
        and seen["float32"] is np.float32
        and seen["float64"] is np.float64
    )
    assert seen["float16-img"][0] == 0.0  # 1 + 0.0004 rounds to 1 in half precision
    assert seen["float32-img"][0] == pytest.approx(0.4, abs=1e-3) and seen["float32-img"][1] == 0.0
    assert seen["float64-img"][1] == pytest.approx(1.0, abs=1e-6)


def test_samples_4_matches_gl(gl, make_shader):
    body = (
        "float d = length(fragCoord - iResolution.xy * 0.5) - 9.3; fragColor = vec4(step(0.0, "
        "d), fract(fragCoord * 0.37), 1.0);"
    )
    a, b = _match(gl, make_shader(_image(body)), size=(32, 24), samples=4)
    one = P.compile_numpy(make_shader(_image(body))).render(size=(32, 24))
    assert not np.array_equal(a, one)  # the edge really is antialiased


def test_tiles_and_odd_sizes(gl, make_shader, monkeypatch):
    monkeypatch.setattr(F, "TILE_WIDTH", 16)
    monkeypatch.setattr(F, "TILE_HEIGHT", 8)
    body = (
        "vec2 uv = fragCoord / iResolution.xy; fragColor = vec4(uv, "
        "dFdx(uv.x * uv.x) * 100.0, 1.0);"
    )
    _match(gl, make_shader(_image(body)), size=(37, 19))
