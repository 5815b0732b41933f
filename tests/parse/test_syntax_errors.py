"""Broken programs: each is rejected with a message in words at the right line and column,
and glslangValidator (the reference compiler) rejects the same program wrapped as Shadertoy
wraps it."""

from __future__ import annotations

import pytest

from glslcheck.base.diagnostics import GlslError
from glslcheck.frontend.parser import parse_units
from glslcheck.shadertoy.sources import Shader, Source

# (name, source, line, column, message substring). Lines and columns are 1-based in the
# user's text; each case says why the position is the right one.
CASES = [
    # The ';' belongs right after `1.0` (line 2, col 16), not at the next line's token.
    (
        "missing-semicolon-declaration",
        "void mainImage(out vec4 c, in vec2 f) {\n    float x = 1.0\n    float y = 2.0;\n    c = "
        "vec4(x + y);\n}\n",
        2,
        18,
        "expected ';' after this declaration",
    ),
    (
        "missing-semicolon-statement",
        "void mainImage(out vec4 c, in vec2 f) {\n    c = vec4(1.0)\n}\n",
        2,
        18,
        "expected ';' after this statement",
    ),
    (
        "missing-semicolon-return",
        "float f() {\n    return 1.0\n}\nvoid mainImage(out vec4 c, in vec2 f) { c = vec4(f()); "
        "}\n",
        2,
        15,
        "expected ';' after this return statement",
    ),
    # An unclosed block points at the '{' that opened it.
    (
        "unclosed-brace",
        "void mainImage(out vec4 c, in vec2 f)\n{\n    if (f.x > 1.0) {\n        c = "
        "vec4(1.0);\n    \n}\n",
        2,
        1,
        "this '{' is never closed",
    ),
    (
        "missing-operand",
        "void mainImage(out vec4 c, in vec2 f) {\n    float x = (1.0 + );\n    c = vec4(x);\n}\n",
        2,
        22,
        "expected an expression",
    ),
    (
        "reserved-word-input",
        "void mainImage(out vec4 c, in vec2 f) {\n    float input = 1.0;\n    c = "
        "vec4(input);\n}\n",
        2,
        11,
        "'input' is a reserved word",
    ),
    (
        "reserved-word-output-param",
        "float g(float output) { return output; }\nvoid mainImage(out vec4 c, "
        "in vec2 f) { c = vec4(g(1.0)); }\n",
        1,
        15,
        "'output' is a reserved word",
    ),
    (
        "non-ascii-identifier",
        "void mainImage(out vec4 c, in vec2 f) {\n    float caf\u00e9 = 1.0;\n    c = "
        "vec4(1.0);\n}\n",
        2,
        14,
        "GLSL source is ASCII outside comments",
    ),
    (
        "missing-close-paren",
        "void mainImage(out vec4 c, in vec2 f) {\n    if (f.x > 1.0 { c = vec4(1.0); }\n}\n",
        2,
        19,
        "expected",
    ),
    (
        "else-without-if",
        "void mainImage(out vec4 c, in vec2 f) {\n    c = vec4(1.0);\n    else c = vec4(0.0);\n}\n",
        3,
        5,
        "'else'",
    ),
    (
        "bad-octal",
        "void mainImage(out vec4 c, in vec2 f) {\n    int x = 09;\n    c = vec4(float(x));\n}\n",
        2,
        13,
        "not a valid octal number",
    ),
    (
        "integer-too-large",
        "void mainImage(out vec4 c, in vec2 f) {\n    uint x = 5000000000u;\n    c = "
        "vec4(float(x));\n}\n",
        2,
        14,
        "does not fit in 32 bits",
    ),
    (
        "stray-character",
        "void mainImage(out vec4 c, in vec2 f) {\n    c = vec4(1.0) @ 2.0;\n}\n",
        2,
        19,
        "unexpected character '@'",
    ),
    (
        "string-literal",
        'void mainImage(out vec4 c, in vec2 f) {\n    c = "red";\n}\n',
        2,
        9,
        "no string",
    ),
    (
        "extra-close-brace",
        "void mainImage(out vec4 c, in vec2 f) {\n    c = vec4(1.0);\n}\n}\n",
        4,
        1,
        "'}'",
    ),
    (
        "two-types",
        "void mainImage(out vec4 c, in vec2 f) {\n    float float x = 1.0;\n    c = "
        "vec4(1.0);\n}\n",
        2,
        11,
        "'float' is a keyword and cannot be used as a name",
    ),
    (
        "struct-member-semicolon",
        "struct L {\n    vec3 p\n    vec3 c;\n};\nvoid mainImage(out vec4 c, "
        "in vec2 f) { c = vec4(1.0); }\n",
        2,
        11,
        "expected ';'",
    ),
    (
        "unknown-type-name",
        "void mainImage(out vec4 c, in vec2 f) {\n    Light l;\n    c = vec4(1.0);\n}\n",
        2,
        11,
        "unexpected name 'l' after 'Light'",
    ),
    (
        "nul-byte",
        "void mainImage(out vec4 c, in vec2 f) {\n    c = vec4(1.0);\x00\n}\n",
        2,
        19,
        "NUL byte",
    ),
    (
        "unclosed-paren-at-eof",
        "void mainImage(out vec4 c, in vec2 f) {\n    c = vec4(1.0,\n",
        2,
        13,
        "this '(' is never closed",
    ),
    (
        "missing-semicolon-after-struct",
        "struct L { vec3 p; }\nvoid mainImage(out vec4 c, in vec2 f) { c = vec4(1.0); }\n",
        1,
        21,
        "expected ';' after this declaration",
    ),
]


def _error(text: str):
    with pytest.raises(GlslError) as info:
        parse_units([Source("Image.glsl", text)])
    (d,) = info.value.diagnostics
    return d


@pytest.mark.parametrize("name,text,line,col,message", CASES, ids=[c[0] for c in CASES])
def test_syntax_error_position_and_message(name, text, line, col, message):
    d = _error(text)
    assert message in d.message, d.message
    assert (d.loc.path, d.loc.line, d.loc.column) == ("Image.glsl", line, col), (d.message, d.loc)


@pytest.mark.parametrize("name,text,line,col,message", CASES, ids=[c[0] for c in CASES])
def test_glslang_rejects_too(name, text, line, col, message, glslang):
    from glslcheck.semantics.glslang import validate
    from glslcheck.shadertoy.wrapper import build_program

    shader = Shader(tabs={"Image": Source("Image.glsl", text)}, root="Image.glsl")
    result = validate(build_program(shader).text)
    assert not result.ok, f"glslangValidator accepted {name}"
