"""Driver compile errors become diagnostics at the user's file:line (glslcheck/gl_backend)."""

import pytest

from glslcheck.backends.gl import compile_gl, parse_driver_log
from glslcheck.base.diagnostics import GlslError

COMMON = (
    "float twice(float x) {\n    return 2.0 * x;\n}\n\nfloat broken() {\n    return "
    "undefined_name;\n}\n"
)
IMAGE = "void mainImage(out vec4 c, in vec2 p) {\n    c = vec4(twice(p.x));\n}\n"


def _errors(shader):
    with pytest.raises(GlslError) as info:
        compile_gl(shader)
    return info.value.diagnostics


def test_error_in_image_is_reported_at_its_line(gl, make_shader):
    image = (
        "void mainImage(out vec4 c, in vec2 p) {\n    vec3 col = vec3(1.0);\n\n    c = "
        "vec4(col, nope);\n}\n"
    )
    diags = _errors(make_shader(image, "float twice(float x) { return x; }\n"))
    assert {(d.loc.path, d.loc.line) for d in diags} == {
        ("Image.glsl", 4)
    }  # Mesa adds follow-up errors
    d = diags[0]
    assert "nope" in d.message
    assert d.loc.column == image.splitlines()[3].index("nope") + 1


def test_error_in_common_is_reported_at_its_line(gl, make_shader):
    diags = _errors(make_shader(IMAGE, COMMON))
    assert {(d.loc.path, d.loc.line) for d in diags} == {("Common.glsl", 6)}
    assert "undefined_name" in diags[0].message


def test_es_rules_are_enforced(gl, make_shader):
    # Desktop GLSL 3.30 converts int to float implicitly; GLSL ES 3.00 does not.
    image = "void mainImage(out vec4 c, in vec2 p) {\n    float x = 1;\n    c = vec4(x);\n}\n"
    [d] = _errors(make_shader(image))
    assert (d.loc.path, d.loc.line, d.loc.column) == ("Image.glsl", 2, 5)


def test_missing_mainimage_points_at_the_tab_file(gl, make_shader):
    # The error is in the wrapper's call; with no mainImage in the tab it lands on the tab's 1:1.
    [d] = _errors(make_shader("void mainImag(out vec4 c, in vec2 p) { c = vec4(1.0); }\n"))
    assert (d.loc.line, d.loc.column) == (1, 1) and "mainImage" in d.message and d.help


def test_driver_log_formats():
    log = (
        "GLSL Compiler failed\n\nfragment_shader\n===============\n0:42(5): error: "
        "`y' undeclared\n0:3(1): warning: meh\n"
    )
    assert parse_driver_log(log) == [(42, 5, "error", "`y' undeclared"), (3, 1, "warning", "meh")]
    assert parse_driver_log("ERROR: 0:7: 'x' : undeclared identifier") == [
        (7, None, "error", "'x' : undeclared identifier")
    ]
