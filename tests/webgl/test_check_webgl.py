"""`check --webgl` and the WebGL rules of our checker (glslcheck/semantics/webgl_rules.py).

Each fixture in tests/webgl/invalid is something ANGLE (Shadertoy's browser) rejects although
glslangValidator accepts it (tools/webgl_agreement.py found them; Mesa accepts most of them and
rejects a struct defined in a parameter's type and `#pragma STDGL invariant(all)`, so those two
are not WebGL's own rules but are kept here, where glslang's rejection is not required). Same
format as tests/check/invalid: `// expect: <part of our message>` and `// ERROR` on the line. For
each, our checker must reject it there, ANGLE must too, on the same line (so the rule is not our
invention), and glslangValidator must accept it (else it belongs in tests/check/invalid).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from glslcheck.backends.webgl import webgl_diagnostics
from glslcheck.base.diagnostics import register_source
from glslcheck.cli.main import main
from glslcheck.semantics.agreement import glslang_errors, our_errors
from glslcheck.shadertoy.sources import Shader, Source

HERE = Path(__file__).parent / "invalid"
FIXTURES = sorted(HERE.glob("*.glsl"))


def load(path: Path) -> tuple[Shader, str, int]:
    text = path.read_text(encoding="utf-8")
    lines = text.splitlines()
    expect = lines[0].removeprefix("// expect: ").strip()
    line = next(i + 1 for i, t in enumerate(lines) if t.rstrip().endswith("// ERROR"))
    shader = Shader(root=str(path))
    register_source(str(path), text)
    shader.tabs["Image"] = Source(str(path), text, "Image")
    return shader, expect, line


def test_fixtures_exist():
    assert len(FIXTURES) >= 6


@pytest.mark.parametrize("path", FIXTURES, ids=lambda p: p.stem)
def test_we_reject_what_angle_rejects(path, webgl):
    shader, expect, line = load(path)
    ours = [d for d in our_errors(shader) if expect in d.message]
    assert ours and ours[0].loc.line == line, (
        f"{path.name}: {[(str(d.loc), d.message) for d in our_errors(shader)]}"
    )
    angle = webgl_diagnostics(shader, "Image")
    assert any(
        d.loc is not None and d.loc.path == str(path) and d.loc.line == line for d in angle
    ), f"{path.name}: ANGLE said {[(str(d.loc), d.message) for d in angle]}"


@pytest.mark.parametrize("path", FIXTURES, ids=lambda p: p.stem)
def test_glslang_accepts_them(path, glslang):
    shader, _expect, _line = load(path)
    assert not glslang_errors(shader), (
        f"{path.name}: glslangValidator rejects it: move it to tests/check/invalid"
    )


def test_double_underscore_is_an_error_in_a_tab_and_a_warning_in_a_plain_file(
    tmp_path, capsys, make_shader
):
    from glslcheck.frontend.parser import parse_shader
    from glslcheck.semantics import check

    shader = make_shader(
        "const float light__power = 2.0;\n"
        "void mainImage(out vec4 c, in vec2 f) { c = vec4(light__power); }\n"
    )
    ours = check(parse_shader(shader, "Image"), "Image", collect=True).diagnostics
    assert [(d.severity, d.loc.line) for d in ours] == [("error", 1)]
    assert (
        "Shadertoy's browser rejects it" in ours[0].message
        and ours[0].help == "rename it, for example to 'light_power'"
    )
    path = (
        tmp_path / "plain.frag"
    )  # a plain GLSL ES file need not run in WebGL: the spec allows the name
    path.write_text(
        "#version 300 es\nprecision highp float;\nout vec4 o;\nfloat a__b = 1.0;\n"
        "void main() { o = vec4(a__b); }\n"
    )
    assert main(["check", str(path)]) == 0
    assert (
        f"{path}:4:7: warning: 'a__b': names containing '__' are reserved"
        in capsys.readouterr().err
    )


def test_plain_glsl_gets_warnings_not_errors(tmp_path, capsys):
    path = tmp_path / "plain.frag"
    path.write_text(
        "#version 300 es\nprecision highp float;\nout vec4 o;\nfloat webgl_k = 1.0;\n"
        "void main() { o = vec4(webgl_k); }\n"
    )
    assert main(["check", str(path)]) == 0
    assert (
        "warning: 'webgl_k': names starting with 'webgl_' are reserved by WebGL"
        in capsys.readouterr().err
    )


def test_check_webgl_reports_angle_in_the_users_line(tmp_path, capsys, webgl):
    folder = tmp_path / "shader"
    folder.mkdir()
    (folder / "Common.glsl").write_text("float helper(float x)\n{\n    return x;\n}\n")
    # An int assigned to a float: ANGLE's message must come out at Image.glsl line 3, at the '='.
    (folder / "Image.glsl").write_text(
        "void mainImage(out vec4 c, in vec2 f)\n{\n    float k = 1;\n    c = vec4(helper(k));\n}\n"
    )
    assert main(["check", str(folder), "--webgl"]) == 1
    err = capsys.readouterr().err
    assert (
        f"{folder / 'Image.glsl'}:3:13: error: WebGL: '=' : cannot convert from 'const int' to "
        "'highp float'" in err
    )
    assert main(["check", "lab_shaders/07_final", "--webgl"]) == 0


# GLSL ES 3.00 section 4.3.3: a call of a built-in function (other than a texture lookup) whose
# arguments are constant expressions is a constant expression, so a const may be initialised by
# one. glslangValidator folds only some built-ins and rejects the bit casts ("global const
# initializers must be constant"); ANGLE, Shadertoy's compiler, folds them: check follows the
# spec and ANGLE.
BIT_CAST_CONSTS = (
    "const float largest = intBitsToFloat(2139095039);\n"
    "const int oneBits = floatBitsToInt(1.0);\n"
    "const float half_ = uintBitsToFloat(0x3F000000u);\n"
    "void mainImage(out vec4 c, in vec2 f) { c = vec4(largest, float(oneBits), half_, 1.0); }\n"
)


def _tab(text: str) -> Shader:
    shader = Shader(root="bit-cast-consts")
    register_source("Image.glsl", text)
    shader.tabs["Image"] = Source("Image.glsl", text, "Image")
    return shader


def test_const_initialised_by_a_built_in_on_constants_is_accepted(webgl):
    shader = _tab(BIT_CAST_CONSTS)
    assert our_errors(shader) == []
    angle = [d for d in webgl_diagnostics(shader, "Image") if d.severity == "error"]
    assert angle == [], [(str(d.loc), d.message) for d in angle]


def test_glslang_rejects_the_bit_cast_consts(glslang):
    """The difference is glslang's: if it starts folding the bit casts, this documents nothing."""
    assert glslang_errors(_tab(BIT_CAST_CONSTS))
