"""The per-call cuts for the slowest real shaders (fewer NumPy calls per frame) change no pixel and
do cut the calls: a built-in call repeated in one expression is computed once (`Expressions.
repeated_calls`), int and uint operators are NumPy's, swizzles are views or `take`, `dot` makes
its products in one call.

Each shader is rendered with the generated code of today and with the common-subexpression step
turned off (the code before it); the images must be bit-identical, and the call counts show the
step did its work.
"""

from __future__ import annotations

import itertools

import numpy as np

from glslcheck.backends.numpy_engine.program import compile_numpy
from glslcheck.backends.numpy_engine.runtime import Runtime
from glslcheck.backends.numpy_engine.transpile import transpile_shader
from glslcheck.backends.numpy_engine.transpile.expressions import Expressions

# A rotation by a per-pixel angle (the pattern of most raymarchers), the same call inside a
# `&&` and both sides of a `?:` (parts under masks of their own), and repeats separated by a
# side effect, which must not be shared: `sin(x) + sin(x += 1.0)` is two different sines.
ROTATE = """
float twice(float x) {
    float y = sin(x) + sin((x += 1.0));
    return y + x;
}
void mainImage(out vec4 o, in vec2 f) {
    float a = f.x * 0.37 + f.y * 0.11;
    vec2 q = mat2(cos(a), -sin(a), sin(a), cos(a)) * vec2(f.y * 0.1, 1.0);
    bool pos = f.x > 3.0 && sin(a) * sin(a) > 0.25;
    float t = pos ? cos(a) * cos(a) : sin(a) - cos(a);
    o = vec4(q, t + twice(a), 1.0);
}
"""


def _render_counting(make_shader, monkeypatch, cse: bool):
    monkeypatch.setattr(Expressions, "CSE_CALLS", cse)
    prog = compile_numpy(make_shader(ROTATE))
    prog.threads = 1
    rt = prog.module()["rt"]
    counts = {"sin": 0, "cos": 0}
    for name in counts:
        real = getattr(rt, name)

        def counted(x, _real=real, _name=name):
            counts[_name] += 1
            return _real(x)

        monkeypatch.setattr(rt, name, counted)
    return prog.render(size=(8, 6), time=0.0), counts


def test_a_repeated_builtin_call_is_computed_once_with_the_same_pixels(make_shader, monkeypatch):
    img, counts = _render_counting(make_shader, monkeypatch, cse=True)
    before, counts_before = _render_counting(make_shader, monkeypatch, cse=False)
    assert np.array_equal(img, before) and np.isfinite(img).all()
    # one tile: mainImage's rotation 2 cos + 2 sin, the `&&` sin(a) * sin(a) 2 sin, the `?:`
    # cos(a) * cos(a) 2 cos and sin(a) - cos(a); twice() 2 sin (a side effect between them).
    # Once each: the rotation's, the `&&`'s (its own), the `?:`'s (both sides are computed on
    # every lane and selected: they share cos(a)); twice() keeps both
    assert counts_before == {"sin": 2 + 2 + 1 + 2, "cos": 2 + 2 + 1}
    assert counts == {"sin": 1 + 1 + 1 + 2, "cos": 1 + 1}


def test_repeated_calls_are_not_shared_across_a_side_effect(make_shader):
    code = transpile_shader(make_shader(ROTATE)).source
    body = code.split("def f_twice")[1].split("def ")[0]
    assert body.count("rt.sin(") == 2  # sin(x) and sin(x += 1.0): both computed
    main = code.split("def f_mainImage")[1]
    assert "rt.mat(2, 2, _t" in main  # the rotation reads its temporaries


def test_the_tracing_transpiler_keeps_every_call(make_shader):
    from glslcheck.backends.numpy_engine.tracing import TraceTranspiler

    assert TraceTranspiler.CSE_CALLS is False  # each call is traced where it runs


XORSHIFT = """
void mainImage(out vec4 o, in vec2 f) {
    uint s = uint(f.x) * 747796405u + uint(f.y) * 2891336453u + 1u;
    s ^= s << 13;
    s ^= s >> 17;
    s ^= s << 5;
    int i = int(f.x) - 3;
    int j = (i >> 1) + (i & 6) - (i | 1) * (i ^ 5);
    o = vec4(float(s & 0xffffu) / 65535.0, float(s >> 16) / 65535.0, float(j) + float(i < 0 == s \
        > 7u) * 100.0, 1.0);
}
"""


def test_int_and_uint_operators_compute_what_glsl_defines(make_shader):
    code = transpile_shader(make_shader(XORSHIFT)).source
    assert "(v_s << C_u_13)" in code and "(v_s >> C_u_17)" in code and "rt.shl" not in code
    prog = compile_numpy(make_shader(XORSHIFT))
    w, h = 6, 4
    img = prog.render(size=(w, h), time=0.0)
    m = 0xFFFFFFFF
    for y, x in itertools.product(range(h), range(w)):
        s = (x * 747796405 + y * 2891336453 + 1) & m
        s ^= (s << 13) & m
        s ^= s >> 17
        s ^= (s << 5) & m
        i = x - 3
        j = (i >> 1) + (i & 6) - (i | 1) * (i ^ 5)
        want = [
            np.float32(s & 0xFFFF) / np.float32(65535.0),
            np.float32(s >> 16) / np.float32(65535.0),
            j + 100.0 * ((i < 0) == (s > 7)),
            1.0,
        ]  # (a Shadertoy shader's alpha is 1)
        assert img[h - 1 - y, x].tolist() == [float(v) for v in want], (x, y)


def test_swizzles_read_the_same_components_as_a_list_index():
    rt = Runtime("float32")
    v = np.arange(4 * 5, dtype=np.float32).reshape(4, 5)
    uniform = v.copy()
    uniform.flags.writeable = False  # a uniform input
    for n in (2, 3, 4):
        for idx in itertools.product(range(4), repeat=n):
            sw = "".join("xyzw"[i] for i in idx)
            for a in (v, uniform):
                r = rt.swizzle(a, sw)
                assert np.array_equal(r, v[list(idx)]) and r.dtype == v.dtype, sw
                # a uniform's swizzle other than a prefix stays a writable copy, which
                # Runtime._const reads as "may be a constant", as before views
                if a is uniform and idx != tuple(range(n)):
                    assert r.flags.writeable, sw


def test_dot_is_the_sum_from_the_right_of_rounded_products():
    rt = Runtime("float32")
    rng = np.random.default_rng(7)
    for n in (2, 3, 4):
        a = (rng.standard_normal((n, 1000)) * 10.0 ** rng.integers(-3, 4, (n, 1000))).astype(
            np.float32
        )
        b = (rng.standard_normal((n, 1000)) * 10.0 ** rng.integers(-3, 4, (n, 1000))).astype(
            np.float32
        )
        want = a[n - 1] * b[n - 1]
        for i in range(n - 2, -1, -1):
            want = a[i] * b[i] + want
        assert np.array_equal(rt.dot(a, b), want)
        assert np.array_equal(rt.dot(a, b[:, :1]), rt.dot(a, np.repeat(b[:, :1], 1000, axis=1)))
