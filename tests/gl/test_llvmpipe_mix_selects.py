"""Which `mix` weights llvmpipe turns into a select, and both CPU engines with it, bit for bit.

nir_opt_algebraic's ``('~flrp', a, b, ('b2f', 'c@1')) -> ('bcsel', c, b, a)`` (Mesa 22.3)
makes a `mix` a select where NIR sees its weight as a bool converted to float, before
nir_lower_flrp: the dropped side is ignored, NaN included. Any other weight is interpolated,
``x + w*(y - x)``, in every lane, a weight of exactly 0 or 1 included (where that is not y, or
a NaN on the dropped side stays). nir_fold.b2f_weight decides the form from the source.

Each weight is rendered by the driver as (W, X, Y), then as ``mix(X, Y, W)`` with X large and Y
small (``X + (Y - X)`` rounds: the select and the sum differ) and with X a NaN: the driver's
result is checked against the select and the sum computed here in float32 from its own W, X
and Y, and the NumPy backend's and the compiled engine's renders of the same shaders against
the driver's bits. Written for llvmpipe of Mesa 22.3 (the `llvmpipe` fixture skips elsewhere).
"""

from __future__ import annotations

import numpy as np
import pytest

from glslcheck.verification.verify import compile_backend

HEAD = """
float pick(float v) { return step(0.0, v); }
float pickWrites(float v, out float o) {
    o = v;
    for (int i = 0; i < 3; i++) { o += 1.0; }
    float h = float(v > 0.0);
    return h;
}
float mixp(float x, float y, float w) { return mix(x, y, w); }
vec3 mixv(vec3 x, vec3 y, vec3 w) { return mix(x, y, w); }
void mainImage(out vec4 c, in vec2 p) {
    float d = sin(p.x * 0.37 + p.y * 1.13);
    float e = cos(p.x * 0.71 - p.y * 0.53);
    float X = NANX 300.0 * fract(p.x * 0.1371 + p.y * 0.0917) + 1000.0;
    float Y = fract(p.y * 0.311 + p.x * 0.057) * 0.37;
    float W = WEIGHT;
    c = OUT;
}
"""
MIX = "vec4(mix(X, Y, W), 0.0, 0.0, 1.0)"
VIA_PARAM = "vec4(mixp(X, Y, W), 0.0, 0.0, 1.0)"
VIA_VEC3 = "vec4(mixv(vec3(X), vec3(Y), vec3(W)).y, 0.0, 0.0, 1.0)"

# name -> (weight, the mix's expression, selects): what the driver does, checked below
FORMS = {
    "step": ("step(d, 0.0)", MIX, True),
    "float_of_bool": ("float(d > 0.0)", MIX, True),
    "conditional_one_zero": ("(d > 0.0 ? 1.0 : 0.0)", MIX, True),
    "conditional_zero_one": ("(d > 0.0 ? 0.0 : 1.0)", MIX, True),
    "product_of_steps": ("step(d, 0.0) * step(e, 0.0)", MIX, True),
    "min_of_steps": ("min(step(d, 0.0), step(e, 0.0))", MIX, True),
    "max_of_steps": ("max(step(d, 0.0), step(e, 0.0))", MIX, True),
    "abs_of_step": ("abs(step(d, 0.0))", MIX, True),
    "clamped_step": ("clamp(step(d, 0.0), 0.0, 1.0)", MIX, True),
    "step_by_constants_of_product_one": ("step(d, 0.0) * 2.0 * 0.5", MIX, True),
    "one_minus_one_minus_step": ("1.0 - (1.0 - step(d, 0.0))", MIX, True),
    "component_of_a_vector_step": ("step(vec2(d), vec2(0.0)).x", MIX, True),
    "function_returning_step": ("pick(d)", MIX, True),
    "function_with_out_parameter_and_loop": ("0.0; float o; W = pickWrites(d, o)", MIX, True),
    "local_of_step": ("0.0; float w = step(d, 0.0); w = w * step(e, 0.0); W = w", MIX, True),
    "parameter_passed_a_step": ("step(d, 0.0)", VIA_PARAM, True),
    "vector_of_a_step": ("step(d, 0.0)", VIA_VEC3, True),
    # written in the call: the NumPy backend selects on the compares themselves (mix_b2f)
    "step_in_the_call": ("step(d, 0.0)", "vec4(mix(X, Y, step(d, 0.0)), 0.0, 0.0, 1.0)", True),
    "step_and_bool_in_the_call": (
        "step(d, 0.0) * float(e > 0.0)",
        "vec4(mix(X, Y, step(d, 0.0) * float(e > 0.0)), 0.0, 0.0, 1.0)",
        True,
    ),
    "one_minus_step": ("1.0 - step(d, 0.0)", MIX, False),
    "one_minus_float_of_bool": ("1.0 - float(d > 0.0)", MIX, False),
    "sum_of_steps": ("step(d, 0.0) + step(e, 0.0)", MIX, False),
    "product_with_one_minus_step": ("(1.0 - step(d, 0.0)) * step(e, 0.0)", MIX, False),
    "parameter_passed_one_minus_step": ("1.0 - step(d, 0.0)", VIA_PARAM, False),
    "saturated_clamp": ("clamp(1e6 * d, 0.0, 1.0)", MIX, False),
    "floor": ("floor(d + 1.0)", MIX, False),
    "sign": ("max(sign(d), 0.0)", MIX, False),
    "saturated_smoothstep": ("smoothstep(-1e-6, 1e-6, d)", MIX, False),
}
SIZE = (64, 64)


def _text(name: str, nan: bool, out: str | None = None) -> str:
    weight, mix, _ = FORMS[name]
    text = HEAD.replace("WEIGHT", weight).replace("NANX", "sqrt(-1.0 - abs(d)) +" if nan else "")
    return text.replace("OUT", out or mix)


def _render(make_shader, text: str, backend: str) -> np.ndarray:
    got = compile_backend(make_shader(text), backend).render(size=SIZE, frame=0)
    return np.asarray(got, np.float32).reshape(-1, 4)


def _same(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return (a.view(np.int32) == b.view(np.int32)) | (np.isnan(a) & np.isnan(b))


@pytest.mark.parametrize("name", sorted(FORMS))
def test_llvmpipe_selects_on_a_b2f_weight_only(llvmpipe, make_shader, name):
    """The driver gives the select on every pixel for the b2f forms and the sum for the others,
    and the shader tells the two apart (else the check proves nothing)."""
    selects = FORMS[name][2]
    w, x, y, _ = _render(make_shader, _text(name, False, "vec4(W, X, Y, 1.0)"), "gl").T
    assert ((w == 0) | (w == 1)).mean() > 0.5  # (mostly 0 or 1: where the forms differ)
    select, summed = np.where(w == 1, y, x), x + w * (y - x)
    tells = select != summed
    assert tells.sum() > 100
    got = _render(make_shader, _text(name, False), "gl")[:, 0]
    assert (got == (select if selects else summed)).all()
    got_nan = _render(make_shader, _text(name, True), "gl")[:, 0]
    ones = w == 1  # (x is NaN: y there if it selects, NaN if it interpolates)
    assert (got_nan[ones] == y[ones]).all() if selects else np.isnan(got_nan[ones]).all()


@pytest.mark.parametrize("nan", [False, True], ids=["finite", "nan_dropped"])
@pytest.mark.parametrize("name", sorted(FORMS))
def test_numpy_mix_as_llvmpipe(llvmpipe, make_shader, name, nan):
    text = _text(name, nan)
    assert _same(_render(make_shader, text, "numpy"), _render(make_shader, text, "gl")).all()


@pytest.mark.parametrize("nan", [False, True], ids=["finite", "nan_dropped"])
@pytest.mark.parametrize("name", sorted(FORMS))
def test_compiled_mix_as_llvmpipe(llvmpipe, numba, make_shader, name, nan):
    text = _text(name, nan)
    assert _same(_render(make_shader, text, "compiled"), _render(make_shader, text, "gl")).all()


VECTORS = {  # a vec3 mix of a constant x whose components differ: a formula per component
    "mixed_constant_one_minus_step": ("1.0 - step(d, 0.0)", (0.0, 0.5, 1.0)),
    "signed_constant_clamp": ("clamp(2.0 * d, 0.0, 1.0)", (1.0, -1.0, 3.0)),
}


def _vector_text(name: str, out: str) -> str:
    weight, x = VECTORS[name]
    vec = f"vec3({', '.join(str(v) for v in x)})"
    return HEAD.replace("WEIGHT", weight).replace("NANX", "").replace("OUT", out.format(x=vec))


@pytest.mark.parametrize("name", sorted(VECTORS))
def test_llvmpipe_lowers_a_vector_mix_per_component(llvmpipe, make_shader, name):
    """Each component is ``x*(1-w) + y*w`` (its flrp shares t and y with the other two: strict),
    where ``x + w*(y - x)`` differs on some pixels of each component not 0 in x."""
    w, _, y, _ = _render(make_shader, _vector_text(name, "vec4(W, 0.0, Y, 1.0)"), "gl").T
    got = _render(make_shader, _vector_text(name, "vec4(mix({x}, vec3(Y), W), 1.0)"), "gl")
    x = np.array(VECTORS[name][1], np.float32)
    for c in range(3):
        strict = x[c] * (np.float32(1.0) - w) + y * w
        assert (got[:, c] == strict).all(), c
        if x[c] != 0.0:
            assert (got[:, c] != x[c] + w * (y - x[c])).sum() > 100, c


@pytest.mark.parametrize("backend", ["numpy", "compiled"])
@pytest.mark.parametrize("name", sorted(VECTORS))
def test_engines_lower_a_vector_mix_as_llvmpipe(llvmpipe, make_shader, request, name, backend):
    if backend == "compiled":
        request.getfixturevalue("numba")
    text = _vector_text(name, "vec4(mix({x}, vec3(Y), W), 1.0)")
    assert _same(_render(make_shader, text, backend), _render(make_shader, text, "gl")).all()
