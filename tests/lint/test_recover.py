"""Syntax-error recovery (glslcheck/lint/recover.py): which text is dropped, and that every kept
line stays where it was."""

from __future__ import annotations

from glslcheck.base.diagnostics import Location
from glslcheck.lint.recover import declarations, drop_declaration
from glslcheck.shadertoy.sources import Source

TEXT = """// a comment { with a brace
#define BODY { return 1.0; }
float f(in float x)
{
    return x * 2.0
}
struct S { float a; };
float g = 1.0;
void mainImage(out vec4 c, in vec2 p) { c = vec4(f(p.x)); }
"""


def test_declarations_skip_comments_and_directives():
    found = [TEXT[a:b].split("\n")[0] for a, b, _ in declarations(TEXT)]
    assert found == [
        "float f(in float x)",
        "struct S { float a; };",
        "float g = 1.0;",
        "void mainImage(out vec4 c, in vec2 p) { c = vec4(f(p.x)); }",
    ]


def test_a_body_error_keeps_the_prototype_and_every_line():
    units = [Source("Image.glsl", TEXT)]
    new, region = drop_declaration(units, Location("Image.glsl", 6, 1), [])
    assert region == ("Image.glsl", 3, 6, "f")
    lines = new[0].text.split("\n")
    assert len(lines) == len(TEXT.split("\n"))
    assert lines[2] == "float f(in float x)" and lines[3].strip() == ";" and lines[4].strip() == ""
    assert lines[8] == TEXT.split("\n")[8]  # mainImage untouched


def test_a_second_error_in_the_same_declaration_blanks_it_whole():
    units = [Source("Image.glsl", TEXT)]
    new, region = drop_declaration(units, Location("Image.glsl", 3, 7), [("Image.glsl", 3, 6, "f")])
    assert region[:3] == ("Image.glsl", 3, 6)
    assert new[0].text.split("\n")[2].strip() == ""


def test_an_unclosed_function_is_blanked_to_the_end_and_other_files_are_not_touched():
    units = [Source("Image.glsl", "float g = 1.0;\nvoid f() { if (x) { }\n")]
    new, region = drop_declaration(units, Location("Image.glsl", 2, 12), [])
    assert (
        region == ("Image.glsl", 2, 3, "f") and new[0].text == "float g = 1.0;\n" + " " * 21 + "\n"
    )
    assert drop_declaration(units, Location("Other.glsl", 1, 1), [])[1] is None


def test_a_dropped_declaration_whose_text_is_no_regular_expression(tmp_path, capsys):
    """Found by the fuzzer (seed 16, inputs 28811 and 29258): a dropped declaration that names no
    function is remembered by its first line, `float g = (1.0 +;`, and that text went into a
    regular expression unescaped: `re.error` and a traceback instead of the compile errors."""
    from glslcheck.cli.main import main

    path = tmp_path / "Image.glsl"
    path.write_text(
        "// Image.glsl\nfloat g = (1.0 +;\nfloat f(float x);\n"
        "void mainImage(out vec4 c, in vec2 p) {\n    c = vec4(f(p.x));\n}\n"
    )
    assert main(["lint", str(path)]) == 1
    out = capsys.readouterr().out
    assert "Image.glsl:2:17: compile-error expected an expression" in out
    assert (
        "Image.glsl:5:14: compile-error 'float f(float)' is declared but has no definition" in out
    )


RESERVED = """// sample: one texel of the background (sample is also this comment's word)
vec3 sample(in vec2 uv) { return vec3(uv, iTime); }
void mainImage(out vec4 c, in vec2 f) { c = vec4(sample(f / iResolution.xy), 1.0); }
"""


def test_a_reserved_word_as_a_name_is_spelt_another_way_in_the_code_only():
    from glslcheck.lint.recover import rename_reserved

    units = [Source("Image.glsl", RESERVED)]
    new, name = rename_reserved(units, Location("Image.glsl", 2, 6))
    assert name == "Sample"
    assert new[0].text == RESERVED.replace("vec3 sample(", "vec3 Sample(").replace(
        "vec4(sample(", "vec4(Sample("
    )
    taken = [Source("Image.glsl", RESERVED + "float Sample = 1.0;\n")]
    assert rename_reserved(taken, Location("Image.glsl", 2, 6))[1] == "sAmple"
    assert rename_reserved(units, Location("Image.glsl", 2, 1)) is None  # `vec3`: no such word


def test_a_reserved_word_as_a_name_leaves_every_rule_running(tmp_path):
    """One compile error, with a note of the name the rest is read as, and the findings of the
    function it names: no rule is left out of it."""
    from glslcheck.lint.engine import lint_paths
    from glslcheck.lint.report import summary_line

    path = tmp_path / "Image.glsl"
    path.write_text(RESERVED)
    result = lint_paths([str(path)])
    findings = [f for f in result.findings if f.rule != "missing-comment"]
    errors = [f for f in findings if f.rule == "compile-error"]
    assert [(f.loc.line, f.loc.column, f.severity) for f in errors] == [(2, 6, "error")]
    assert "'sample' is a reserved word" in errors[0].message
    assert [n.message for n in errors[0].notes] == [
        "the rest of the file is linted with it read as 'Sample'"
    ]
    uniforms = [f for f in findings if f.rule == "uniform-outside-mainimage"]
    assert [(f.loc.line, f.loc.column) for f in uniforms] == [(2, 43)]
    summary = summary_line(result)
    assert "1 compile error, not counted" in summary and "not fully linted" not in summary
