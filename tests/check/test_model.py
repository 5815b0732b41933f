"""The Model API the linter and the NumPy transpiler consume (glslcheck.semantics)."""

from __future__ import annotations

import pytest

from glslcheck.cli.main import main
from glslcheck.frontend import syntax as A
from glslcheck.frontend.parser import parse_shader
from glslcheck.language import builtin_functions as B
from glslcheck.language import glsl_types as T
from glslcheck.semantics import CheckError, Constructor, Model, Symbol, check

SRC = """\
struct Ray { vec3 origin; vec3 direction; };
const int N = 2 * 3;
const vec3 UP = vec3(0.0, 1.0, 0.0);
float x = 1.0;

float shade(in Ray r, out float hit)
{
    float x = r.direction.y;   // shadows the global x
    hit = x > 0.0 ? 1.0 : 0.0;
    return x * float(N);
}

float unused(float a) { return a; }

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    Ray r = Ray(vec3(0.0), normalize(vec3(fragCoord / iResolution.xy, 1.0)));
    float hit;
    float s = shade(r, hit);
    float arr[N];
    fragColor = vec4(UP.xy, s, arr.length());
}
"""


@pytest.fixture
def model(make_shader) -> Model:
    shader = make_shader(SRC)
    return check(parse_shader(shader, "Image"), "Image")


def nodes(model: Model, cls, **attrs):
    return [
        n
        for n in model.ast.walk()
        if isinstance(n, cls) and all(getattr(n, k) == v for k, v in attrs.items())
    ]


def test_every_expression_has_a_type(model):
    for n in model.ast.walk():
        if isinstance(n, A.Expr):
            assert isinstance(model.type_of(n), T.Type)
    call = nodes(model, A.Call, callee="normalize")[0]
    assert model.type_of(call) == T.VEC3
    swz = nodes(model, A.Field, name="xy")[0]
    assert model.type_of(swz) == T.VEC2
    assert model.is_swizzle(swz) and model.swizzle_indices(swz) == (0, 1)
    member = nodes(model, A.Field, name="direction")[0]
    assert not model.is_swizzle(member) and model.type_of(member) == T.VEC3


def test_symbols_and_unique_names(model):
    xs = [model.symbol_of(n) for n in nodes(model, A.Identifier, name="x")]
    local = xs[0]
    assert local.kind == "local" and local.function.name == "shade"
    glob = next(g for g in model.globals if g.name == "x")
    assert glob.kind == "global" and glob.unique_name == "x"
    assert local.unique_name != glob.unique_name and local.unique_name.startswith("x_")
    decl = nodes(model, A.Declarator, name="x")
    assert {model.symbol_of(d).kind for d in decl} == {"global", "local"}
    param = model.symbol_of(nodes(model, A.Identifier, name="hit")[0])
    assert param.kind == "param" and param.qualifier == "out"
    res = model.symbol_of(nodes(model, A.Identifier, name="iResolution")[0])
    assert res.kind == "uniform" and res.type == T.VEC3


def test_call_targets(model):
    shade = nodes(model, A.Call, callee="shade")[0]
    target = model.call_target(shade)
    assert isinstance(target, Symbol) and target.kind == "function" and target.type == T.FLOAT
    assert target.params[1][1:] == (T.FLOAT, "out")
    norm = model.call_target(nodes(model, A.Call, callee="normalize")[0])
    assert isinstance(norm, B.Overload) and norm.returns == T.VEC3
    ctor = model.call_target(nodes(model, A.Call, callee="Ray")[0])
    assert isinstance(ctor, Constructor) and ctor.type is model.structs["Ray"]


def test_constants(model):
    n_ident = nodes(model, A.Identifier, name="N")[0]
    assert model.const_value(n_ident) == 6
    up = nodes(model, A.Identifier, name="UP")[0]
    assert model.const_value(up) == (0.0, 1.0, 0.0)
    length = nodes(model, A.MethodCall, name="length")[0]
    assert model.const_value(length) == 6
    arr = next(model.symbol_of(d) for d in nodes(model, A.Declarator, name="arr"))
    assert arr.type == T.ArrayType(T.FLOAT, 6)
    assert model.const_value(nodes(model, A.Identifier, name="fragCoord")[0]) is None


def test_program_facts(model):
    assert model.entry.name == "mainImage"
    names = [f.name for f in model.reachable_functions()]
    assert names == ["shade", "mainImage"]  # callees first, 'unused' not reachable
    assert set(model.functions) == {"shade", "unused", "mainImage"}
    main_calls = [t for _, t in model.calls_from(model.entry)]
    assert main_calls[0].name == "normalize" and main_calls[1] is model.functions["shade"][0]
    assert model.uniforms_read() == {"iResolution"}
    assert model.diagnostics == []


def test_errors_raise_or_collect(make_shader):
    shader = make_shader(
        "void mainImage(out vec4 c, in vec2 f)\n{\n    float x = 1;\n    c = vec4(x);\n}\n"
    )
    result = parse_shader(shader, "Image")
    with pytest.raises(CheckError) as e:
        check(result, "Image")
    d = e.value.diagnostics[0]
    assert "write 1.0" in d.message and d.loc.line == 3 and d.rule == "type"
    m = check(result, "Image", collect=True)
    assert [x.loc.line for x in m.errors] == [3]


def test_common_tab_uniform(make_shader):
    shader = make_shader(
        "void mainImage(out vec4 c, in vec2 f) { c = vec4(t()); }\n",
        common="float t() { return iTime + iDate.x; }\n",
    )
    image = check(parse_shader(shader, "Image"), "Image", collect=True)
    assert [d.loc.path for d in image.errors] == ["Common.glsl"]
    assert "without iTime; pass it as a parameter from mainImage" in image.errors[0].message
    alone = check(parse_shader(shader, "Common"), "Common", collect=True)
    assert [d.message for d in alone.errors] == [d.message for d in image.errors]


def test_warnings_do_not_fail(make_shader):
    shader = make_shader("void mainImage(in vec4 c, in vec2 f) { }\n")  # 'in' fragColor: a warning
    m = check(parse_shader(shader, "Image"), "Image")
    assert [d.severity for d in m.diagnostics] == ["warning"]


def test_cli_exit_codes(tmp_path, capsys):
    good = tmp_path / "good" / "Image.glsl"
    good.parent.mkdir()
    good.write_text("void mainImage(out vec4 c, in vec2 f) { c = vec4(1.0); }\n")
    bad = tmp_path / "bad.glsl"
    bad.write_text("void mainImage(out vec4 c, in vec2 f)\n{\n    c = vec4(1.0) * 2;\n}\n")
    assert main(["check", str(good)]) == 0
    assert main(["check", str(bad)]) == 1
    err = capsys.readouterr().err
    assert f"{bad}:3:" in err and "write 2.0" in err and "^" in err and "help:" in err
    assert main(["check", str(tmp_path / "missing.glsl")]) == 2


def test_listed_nodes_are_the_walks(model, make_shader):
    """`Model.nodes()` and `body_nodes()` (the lists the checker, hazards and lint rules read
    instead of walking again, to save time) hold exactly what `walk()` yields, in its order: the
    program's, and each function body's (a slice of the program's list), here and in a program
    with prototypes, globals between functions, nested loops and a Common tab before it."""

    def same(m):
        assert m.nodes() == list(m.ast.walk())
        assert all(a is b for a, b in zip(m.nodes(), m.ast.walk()))
        definitions = [d for d in m.ast.decls if isinstance(d, A.FunctionDefinition)]
        assert len(definitions) >= 3
        for d in definitions:
            listed = m.body_nodes(d)
            assert [id(n) for n in listed] == [id(n) for n in d.body.walk()]
            assert m.body_nodes(d) is listed  # sliced once

    same(model)
    src = """\
float f(float a);
const float K[2] = float[2](1.0, 2.0);
float g(float a) { for (int i = 0; i < 2; i++) { for (int j = 0; j < i; j++) { a += K[j]; } } \
    return a; }
uniform float extra;
float f(float a) { return g(a) * extra; }
void mainImage(out vec4 c, in vec2 p) { c = vec4(f(p.x)); }
"""
    shader = make_shader(src, common="float h(float v) { return v * 2.0; }\n")
    same(check(parse_shader(shader, "Image"), "Image"))
    # a definition that is not one of the program's own: walked, not sliced
    other = model.ast.decls[-1]
    fresh = check(parse_shader(make_shader(SRC), "Image"), "Image")
    assert [id(n) for n in fresh.body_nodes(other)] == [id(n) for n in other.body.walk()]
