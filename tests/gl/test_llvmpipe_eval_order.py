"""Reads and writes in one expression, in the order llvmpipe gives them: a call, a constructor
or a `?:` is computed where it stands, before a later operand's call writes what it reads; a
plain read (a variable, a component, an element, an operator of them) sees that write.

Mesa's GLSL front end emits calls (built-ins too) and constructors as instructions as it meets
them and leaves variable reads in trees that the consuming instruction evaluates
(cpu_core/eval_order.py). So in `vec4(LB(seed), bump(seed), LB(seed), 1.0)`, with
`bump(inout float s)`, the first LB hashes the old seed; in `vec4(seed, bump(seed), ...)` the
first component is the new one. Each shape below reads a variable both ways around a call that
writes it (an inout or out argument, a global the callee writes, a component or element of a
vector or array); the NumPy backend and the compiled engine (one pixel a call and lockstep)
must give the driver's image bit for bit. Written for llvmpipe of Mesa 22.3 (the `llvmpipe`
fixture skips elsewhere)."""

from __future__ import annotations

import pytest

HEAD = """float id(float x) { return x; }
float id2(float a, float b) { return a; }
float LB(float x) { return float(floatBitsToUint(x) & 255u) / 255.0; }
float bump(inout float s) { s += 0.25; return 0.5; }
float setv(out float s) { s = 0.75; return 0.5; }
float first(inout float a, float b) { float r = a; a = 0.0; return r + b; }
float gs;
float bumpg() { gs += 0.25; return 0.5; }
float bumpv(inout vec2 v) { v += 0.25; return 0.5; }
float bumpa(inout float a[2]) { a[0] += 0.25; return 0.5; }
void mainImage(out vec4 c, in vec2 p) {
    float seed = fract(p.x * 0.0123 + p.y * 0.457);
    gs = seed;
    vec2 v = vec2(seed, 0.1);
    float a[2] = float[2](seed, 0.2);
"""

# name -> the rest of mainImage; every shape writes what it read to c
SHAPES = {
    "user_calls_in_a_constructor": "c = vec4(LB(seed), bump(seed), LB(seed), 1.0);",
    "plain_reads_in_a_constructor": "c = vec4(seed, bump(seed), seed, 1.0);",
    "a_builtin_call": "c = vec4(abs(seed), bump(seed), seed, 1.0);",
    "a_nested_constructor": "c = vec4(vec2(seed, 1.0), bump(seed), seed);",
    "a_splat_and_an_array_constructor": (
        "c = vec4(vec2(seed).x, float[2](seed, 0.0)[0], bump(seed), seed);"
    ),
    "binary_operands": (
        "float x = id(seed) + bump(seed); c = vec4(x, seed + bump(seed), seed, 1.0);"
    ),
    "nested_calls": "c = vec4(id2(id(seed), bump(seed)), id2(seed, bump(seed)), seed, 1.0);",
    "an_operator_around_a_call": "c = vec4(LB(seed) + seed, bump(seed), seed, 1.0);",
    "an_out_argument": "c = vec4(id(seed), setv(seed), seed, 1.0);",
    "an_inout_argument_read_at_the_call": "c = vec4(first(seed, bump(seed)), seed, 0.0, 1.0);",
    "a_global_the_callee_writes": "c = vec4(id(gs), bumpg(), gs, gs + bumpg());",
    "components": (
        "float x = vec2(id(v.x), bumpv(v)).x; c = vec4(x, v.x, vec2(v.y, bumpv(v)).x, 1.0);"
    ),
    "array_elements": "c = vec4(id(a[0]), bumpa(a), a[0], id(a[1]));",
    "a_ternary": "c = vec4(seed > 0.5 ? seed : -seed, bump(seed), seed, 1.0);",
    # x * 1.0 + 0.0 is x to NIR (added_zero.py): still an operator tree, read after the call
    "an_added_zero": "c = vec4(seed * 1.0 + 0.0, bump(seed), seed, 1.0);",
}

ENGINES = [("numpy", None), ("compiled", "0"), ("compiled", "8")]


@pytest.mark.parametrize("backend,lanes", ENGINES, ids=["numpy", "compiled", "lockstep"])
@pytest.mark.parametrize("name", list(SHAPES))
def test_reads_and_writes_in_one_expression_as_llvmpipe(
    renders_as_llvmpipe, monkeypatch, tmp_path, name, backend, lanes
):
    if lanes is not None:
        monkeypatch.setenv("GLSLCHECK_COMPILED_LANES", lanes)
    path = tmp_path / f"{name}.glsl"
    path.write_text(HEAD + "    " + SHAPES[name] + "\n}\n")
    renders_as_llvmpipe(path, backend, time=1.7)
