"""glslangValidator as the reference compiler (glslcheck/semantics/glslang.py)."""

from glslcheck.semantics.glslang import parse_output, validate, validate_shader
from glslcheck.shadertoy.wrapper import build_program

GOOD = (
    "#version 300 es\nprecision highp float;\nout vec4 o;\nvoid main() {\n    o = vec4(1.0);\n}\n"
)


def test_accepts_a_valid_program(glslang):
    result = validate(GOOD)
    assert result.ok and result.messages == []


def test_rejects_implicit_int_to_float(glslang):
    result = validate(GOOD.replace("o = vec4(1.0);", "float x = 1;\n    o = vec4(x);"))
    assert not result.ok
    assert result.messages[0][0] == 5 and "cannot convert" in result.messages[0][1]
    assert all("compilation terminated" not in m for _, m in result.messages)


def test_rejects_a_syntax_error(glslang):
    result = validate(GOOD.replace("vec4(1.0);", "vec4(1.0)"))
    assert not result.ok and result.messages[0][0] == 6


def test_shadertoy_wrapper_compiles(glslang, make_shader):
    shader = make_shader(
        "void mainImage(out vec4 c, in vec2 p) { c = vec4(p / iResolution.xy, iTime, 1.0); }\n"
    )
    assert validate(build_program(shader).text).ok
    assert validate_shader(shader) == []


def test_errors_map_to_the_users_files(glslang, make_shader):
    common = "float twice(float x) {\n    return 2.0 * x;\n}\nfloat bad() { return iTime; }\n"
    image = (
        "void mainImage(out vec4 c, in vec2 p) {\n    int n = 1.5;\n    c = vec4(twice(p.x));\n}\n"
    )
    diags = validate_shader(make_shader(image, common))
    where = [(d.loc.path, d.loc.line) for d in diags]
    # iTime is not declared when Shadertoy compiles Common alone; it is reported once.
    assert where.count(("Common.glsl", 4)) == 1
    assert ("Image.glsl", 2) in where
    assert all(d.rule == "glslang" for d in diags)


def test_parse_output():
    raw = (
        "x.frag\nERROR: 0:5: '=' :  cannot convert from ' const int' to ' temp highp float'\n"
        "ERROR: 0:5: '' : compilation terminated \nWARNING: 0:2: 'x' : something\n"
        "ERROR: 2 compilation errors.  No code generated.\n"
    )
    errors, warnings = parse_output(raw)
    assert errors == [(5, "'=' : cannot convert from 'const int' to 'temp highp float'")]
    assert warnings == [(2, "'x' : something")]
