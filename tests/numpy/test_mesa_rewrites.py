"""Mesa's compile-time rewrites of `pow` and llvmpipe's atan of NaN, copied by the NumPy backend.

Mesa rewrites `pow(x, c)` for a constant exponent component c of 1.0, 2.0, 4.0 (x, x*x,
(x*x)*(x*x)) and +0.0 (1, but 0 for x == 0 or NaN), and `pow(1.0, y)` to 1; other exponents
(0.5, 3.0, 8.0, -0.0, ...) keep the run-time `exp2(y*log2(x))`. llvmpipe's atan multiplies by
fsign(x), so atan(NaN) = 0 and atan(-0) = +0. The GL tests render the same expressions with a
uniform base and a literal exponent and compare every pixel with the NumPy render.
"""

from __future__ import annotations

import math

import numpy as np

from glslcheck.backends.numpy_engine.program import compile_numpy
from glslcheck.backends.numpy_engine.runtime import Runtime
from glslcheck.backends.numpy_engine.transpile import transpile_shader
from glslcheck.frontend import syntax as A

NAN = float("nan")
INF = float("inf")
RT = Runtime("float32")


def _f(*xs: float) -> np.ndarray:
    return np.array(xs, dtype=np.float32)


def _same(a: np.ndarray, b: np.ndarray) -> bool:
    """Equal values, NaN equal to NaN (signs of zero ignored)."""
    a, b = np.asarray(a, np.float32), np.asarray(b, np.float32)
    return a.shape == b.shape and bool(np.all((a == b) | (np.isnan(a) & np.isnan(b))))


def test_pow_const_products():
    x = _f(-0.5, -2.0, 0.0, NAN, -INF, 3.0)
    assert _same(RT.pow_const(x, 1.0), x)
    assert _same(RT.pow_const(x, 2.0), _f(0.25, 4.0, 0.0, NAN, INF, 9.0))
    assert _same(RT.pow_const(x, 4.0), _f(0.0625, 16.0, 0.0, NAN, INF, 81.0))
    assert _same(RT.pow_const(x, 0.0), _f(1.0, 1.0, 0.0, 0.0, 1.0, 1.0))
    # not rewritten: the run-time formula (NaN for x < 0, 0 for x == 0 or NaN)
    for c in (-0.0, 0.5, 3.0, 8.0, -1.0):
        assert _same(RT.pow_const(x, c), RT.pow(x, RT.const_float(c)))
    assert RT.pow_const(x, 2.0).dtype == np.float32
    assert Runtime("float16").pow_const(_f(-0.5).astype(np.float16), 2.0).dtype == np.float16


def test_pow_in_one_buffer_equals_the_formula():
    """`pow` computes in place and skips the x == 0 test for a positive scalar exponent
    (exp2(y * log2(0)) is already 0 then): the values must equal the plain formula
    exp2(y * log2(x)), 0 for x == 0 or NaN, for every exponent kind, shape and precision."""
    xs = [-0.5, -2.0, 0.0, -0.0, NAN, -INF, INF, 1.0, 3.0, 1e-40, 0.999, 1e30]
    # float32 evaluates llvmpipe's own exp2/log2 (checked against the driver bit for bit in
    # tests/numpy/test_llvmpipe_math_gl.py); the NumPy formula is the other precisions'.
    for prec in ("float16", "float64"):
        rt = Runtime(prec)
        x = np.asarray(xs, dtype=rt.F)
        for y in (48.0, 1.0 / 2.2, 1e-30, 1e30, 3.0, 0.0, -0.0, -1.0, -1e30, NAN, INF, -INF):
            yv = rt.const_float(y)
            with np.errstate(all="ignore"):
                want = np.where((x == 0) | np.isnan(x), rt.F(0), np.exp2(yv * np.log2(x)))
                assert _same(rt.pow(x, yv), want), (prec, y)  # lanes ** uniform
                assert _same(rt.pow(x[:, None].repeat(2, 1), yv), np.stack([want, want], 1))  # vec2
                ys = np.full(x.shape, yv)
                assert _same(rt.pow(x, ys), want), (prec, y)  # lanes ** lanes
                assert _same(
                    rt.pow(x[4:5], ys),
                    np.where(np.isnan(x[4]) | (x[4] == 0), rt.F(0), np.exp2(ys * np.log2(x[4]))),
                ), (prec, y)
            assert rt.pow(x, yv).dtype == rt.F


def test_pow_const_vector_exponent_is_per_component():
    x = np.full((3, 2), -0.5, dtype=np.float32)
    got = RT.pow_const(x, (2.0, 3.0, 0.0))
    assert got.shape == (3, 2)
    assert (
        _same(got[0], _f(0.25, 0.25)) and np.all(np.isnan(got[1])) and _same(got[2], _f(1.0, 1.0))
    )
    assert _same(RT.pow_const(x, (4.0, 4.0, 4.0)), np.full((3, 2), 0.0625, np.float32))
    assert _same(RT.pow_one(_f(INF, NAN, 2.0)), _f(1.0, 1.0, 1.0))


def test_atan_of_nan_is_zero():
    assert _same(RT.atan(_f(NAN, -0.0, 0.0)), _f(0.0, 0.0, 0.0))
    assert math.copysign(1.0, float(RT.atan(_f(-0.0))[0])) == 1.0  # +0, as fsign(-0) = 0
    y = _f(NAN, NAN, NAN, 1.0, -1.0, NAN)
    x = _f(1.0, -1.0, NAN, NAN, NAN, -INF)
    got = RT.atan(y, x)
    assert _same(got, _f(0.0, math.pi / 2, 0.0, 0.0, -0.0, math.pi / 2))
    # ordinary arguments are unchanged
    v = _f(-3.0, -0.5, 0.25, 2.0, 1e10)
    assert np.allclose(RT.atan(v), np.arctan(v), rtol=0, atol=1e-5)  # the polynomial: ~1e-6


def test_transpiler_emits_the_rewrites(make_shader):
    code = transpile_shader(
        make_shader(
            "const float E = 4.0;\n"
            "void mainImage(out vec4 o, in vec2 f) {\n"
            "    float x = -f.x;\n"
            "    o = vec4(pow(x, 2.0), pow(x, E), pow(x, 3.0), pow(1.0, x))\n"
            "      + pow(vec4(x), vec4(1.0, 0.0, 0.5, 2.0)) + pow(2.0, x) + pow(vec2(2.0), "
            "vec2(x)).x;\n"
            "}\n"
        )
    )
    code = code if isinstance(code, str) else str(code)
    assert "rt.pow_const(v_x, 2.0)" in code
    assert "rt.pow_const(v_x, 4.0)" in code
    assert "rt.pow(v_x, " in code  # 3.0: not rewritten
    assert "rt.pow_one(v_x)" in code
    assert "rt.exp2(v_x)" in code and "rt.exp2(rt.vec(2, v_x))" in code  # fpow(2.0, a) -> fexp2(a)
    assert "(1.0, 0.0, 0.5, 2.0))" in code


_REWRITE_SHADER = """
uniform float a_unused;
void mainImage(out vec4 o, in vec2 f) {
    // x: -2 .. 2 across the image, with 0 on one column; NaN, +-Inf on the last columns
    float x = (f.x - 8.5) / 4.0;
    if (f.x > 17.0) x = 0.0 / 0.0;
    if (f.x > 18.0) x = -1.0 / 0.0;
    float row = floor(f.y);
    if (row == 0.0) o = vec4(pow(x, 2.0), pow(x, 1.0), pow(x, 4.0), pow(x, 0.0));
    else if (row == 1.0) o = vec4(pow(vec3(x), vec3(2.0, 3.0, 0.0)), pow(x, 3.0));
    else if (row == 2.0) o = vec4(pow(x, 0.5), pow(x, -0.0), pow(1.0, x), pow(x, 8.0));
    else o = vec4(atan(x), atan(x, -1.0), atan(1.0, x), atan(x, x));
}
"""


def test_rewrites_match_llvmpipe(gl, make_shader):
    from glslcheck.backends.gl import compile_gl

    shader = make_shader(_REWRITE_SHADER.replace("uniform float a_unused;\n", ""))
    size = (20, 4)
    ours = compile_numpy(shader).render(size=size)
    theirs = compile_gl(shader).render(size=size)
    nan_ours, nan_theirs = np.isnan(ours), np.isnan(theirs)
    assert np.array_equal(nan_ours, nan_theirs)
    ok = nan_ours | (ours == theirs) | np.isclose(ours, theirs, rtol=1e-5, atol=1e-6)
    assert ok.all(), np.argwhere(~ok)
    # the rewritten products are exact (no exp2/log2 approximation on either side)
    exact = ours[-1, :, :3]  # row 0 (bottom row): pow(x, 2.0), pow(x, 1.0), pow(x, 4.0)
    assert np.array_equal(exact[~np.isnan(exact)], theirs[-1, :, :3][~np.isnan(exact)])


def test_nir_fold_shapes_are_equal_exactly_where_the_glsl_text_is():
    # nir_fold.queries.used_once counts copies of a value by shape (hash-consing, linear) instead of
    # printing every subtree (quadratic in a long chain): both must mean the same thing.
    from pathlib import Path

    from glslcheck.backends.cpu_core.nir_fold.queries import node_shapes
    from glslcheck.frontend.parser import parse_shader
    from glslcheck.frontend.printer import to_glsl
    from glslcheck.shadertoy.sources import find_shaders

    root = Path(__file__).resolve().parents[2]
    checked = 0
    for shader in find_shaders([str(root / "lab_shaders"), str(root / "tests" / "corpus")]):
        for tab in shader.tabs:
            if tab == "Common":
                continue
            ast = parse_shader(shader, tab).ast
            shapes = node_shapes(ast)
            by_text: dict[str, set[int]] = {}
            for node in ast.walk():
                if isinstance(node, (A.Expr,)):
                    by_text.setdefault(to_glsl(node), set()).add(shapes[id(node)])
                    checked += 1
            assert all(len(s) == 1 for s in by_text.values())  # one text: one shape
            texts_of: dict[int, set[str]] = {}
            for text, s in by_text.items():
                texts_of.setdefault(next(iter(s)), set()).add(text)
            assert all(len(t) == 1 for t in texts_of.values())  # one shape: one text
    assert checked > 5000


def test_each_engine_reads_families_of_the_one_table_of_binary_rewrites():
    """The families an engine names are the table's (a misspelt one would silently drop its
    rewrites), and the NumPy transpiler writes exactly the families the table has no rule for."""
    from glslcheck.backends.compiled_engine.fold_values import COPIED
    from glslcheck.backends.cpu_core.nir_fold.dispatch import BINARY_RULES, FAMILIES
    from glslcheck.backends.numpy_engine.transpile.binary_rules import OWN

    assert COPIED <= FAMILIES
    assert set(OWN) == {family for family, rule, _ in BINARY_RULES if rule is None}


def test_nir_fold_on_a_chain_of_thousands_of_terms_is_linear(make_shader, monkeypatch):
    # 3,000 terms: printing every partial sum was 4.5 million node prints (142 s). Counted, not
    # timed: the GLSL text nir_fold prints stays within a small multiple of the source's size.
    import importlib
    import pkgutil

    from glslcheck.backends.cpu_core import nir_fold
    from glslcheck.frontend.printer import to_glsl as real

    printed = [0]

    def counting(node):
        text = real(node)
        printed[0] += len(text)
        return text

    for found in pkgutil.iter_modules(nir_fold.__path__):  # each module that prints binds to_glsl
        module = importlib.import_module(f"{nir_fold.__name__}.{found.name}")
        if hasattr(module, "to_glsl"):
            monkeypatch.setattr(module, "to_glsl", counting)
    body = " + ".join(f"sin(x * {k % 13}.0)" for k in range(3000))
    source = (
        "void mainImage(out vec4 o, in vec2 f) {\n    float x = f.x;\n"
        f"    x = {body};\n    o = vec4(x);\n}}\n"
    )
    transpile_shader(make_shader(source), "Image")
    assert printed[0] < 10 * len(source), printed[0]
