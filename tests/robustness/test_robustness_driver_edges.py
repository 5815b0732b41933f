"""`check` agrees with the drivers on the edges, and warns about the undefined
behaviour on which the NumPy backend and a GPU may disagree.

Each rejected case was accepted by `check` and rejected by Mesa; the test compiles it with the
driver too (the `gl` fixture), so the pair cannot drift apart silently.
"""

from __future__ import annotations

import pytest

from glslcheck.base.diagnostics import GlslError
from glslcheck.cli.main import main
from glslcheck.frontend.parser import parse_shader
from glslcheck.semantics import check
from glslcheck.shadertoy.sources import load_shader

HEADER = "// a shader\n"


def _diagnostics(tmp_path, text: str, name: str = "Image.glsl"):
    path = tmp_path / name
    path.write_text(text)
    shader = load_shader(path)
    tab = next(iter(shader.tabs))
    try:
        return check(parse_shader(shader, tab), tab, collect=True).diagnostics
    except GlslError as e:
        return e.diagnostics


def _errors(tmp_path, text: str):
    return [d for d in _diagnostics(tmp_path, text) if d.severity == "error"]


def _warnings(tmp_path, text: str, name: str = "Image.glsl"):
    return [d for d in _diagnostics(tmp_path, text, name) if d.severity == "warning"]


def _driver_rejects(tmp_path, text: str) -> bool:
    from glslcheck.backends.gl import compile_gl

    path = tmp_path / "driver" / "Image.glsl"
    path.parent.mkdir(exist_ok=True)
    path.write_text(text)
    try:
        compile_gl(load_shader(path))
    except GlslError:
        return True
    return False


MAIN = "void mainImage(out vec4 fragColor, in vec2 fragCoord) { fragColor = vec4(1.0); }\n"

REJECTED = {
    "identifier-1025": (
        "float " + "a" * 1025 + " = 1.0;\n" + MAIN,
        2,
        7,
        "an identifier of 1025 characters; GLSL ES 3.00 allows at most 1024",
    ),
    "unnamed-mainImage-parameter": (
        "void mainImage(out vec4 fragColor, in vec2) { fragColor = vec4(1.0); }\n",
        2,
        36,
        "a parameter of a function definition needs a name",
    ),
    "unnamed-parameter": (
        "float f(float) { return 1.0; }\n" + MAIN.replace("vec4(1.0)", "vec4(f(1.0))"),
        2,
        9,
        "a parameter of a function definition needs a name",
    ),
    "invariant-all": (
        "#pragma STDGL invariant(all)\n" + MAIN,
        2,
        1,
        "#pragma STDGL invariant(all) cannot be used in a fragment shader",
    ),
}


@pytest.mark.parametrize("case", sorted(REJECTED))
def test_check_rejects_what_mesa_rejects(case, tmp_path, gl):
    body, line, column, message = REJECTED[case]
    errors = _errors(tmp_path, HEADER + body)
    assert errors, case
    assert (errors[0].loc.line, errors[0].loc.column) == (line, column)
    assert errors[0].message.startswith(message)
    assert _driver_rejects(tmp_path, HEADER + body), "the driver accepts it now: revisit the rule"


ACCEPTED = {
    "identifier-1024": "float " + "a" * 1024 + " = 1.0;\n" + MAIN,
    "unnamed-prototype-parameter": "float f(float);\nfloat f(float x) { return x; }\n"
    + MAIN.replace("vec4(1.0)", "vec4(f(1.0))"),
    # GLSL ES 3.00 section 3.4: #line takes constant integer expressions; a hex literal is one.
    "line-hex": "#line 0x10\n" + MAIN,
    "line-octal-with-source": "#line 010 0x2\n" + MAIN,
    "other-pragma": "#pragma optimize(off)\n" + MAIN,
}


@pytest.mark.parametrize("case", sorted(ACCEPTED))
def test_check_accepts_what_mesa_accepts(case, tmp_path, gl):
    assert _errors(tmp_path, HEADER + ACCEPTED[case]) == []
    assert not _driver_rejects(tmp_path, HEADER + ACCEPTED[case])


def test_plain_glsl_declaring_iresolution_gets_the_real_values(tmp_path, gl, capsys):
    shader = tmp_path / "plain.frag"
    shader.write_text(
        "#version 300 es\nprecision highp float;\nuniform vec3 iResolution;\nuniform float iTime;\n"
        "out vec4 o;\nvoid main() { o = vec4(gl_FragCoord.xy / iResolution.xy, iTime, 1.0); }\n"
    )
    assert main(["verify", str(shader), "--size", "8x4", "--time", "0.5", "--format", "json"]) == 0
    assert '"match": true' in capsys.readouterr().out
    out = tmp_path / "numpy.npy"
    assert main(["render", str(shader), "--size", "8x4", "--time", "0.5", "-o", str(out)]) == 0
    import numpy as np

    img = np.load(out)
    assert img[0, 0, :3].tolist() == pytest.approx(
        [0.5 / 8, 3.5 / 4, 0.5]
    )  # top left: fragCoord (0.5, 3.5)


def test_plain_glsl_uniform_of_another_type_stays_zero_on_both(tmp_path, gl, capsys):
    shader = tmp_path / "plain.frag"
    shader.write_text(
        "#version 300 es\nprecision highp float;\nuniform vec2 iResolution;\nout vec4 o;\n"
        "void main() { o = vec4(iResolution, 0.25, 1.0); }\n"
    )
    assert (
        main(["verify", str(shader), "--size", "4x4", "--format", "json"]) == 0
    )  # was a struct.error traceback
    assert '"match": true' in capsys.readouterr().out


INDEX_CASES = {
    # (body of mainImage after `float s = 0.0;`, warned?)
    "counting-loop": ("for (int i = 0; i < 4; i++) s += a[i];", False),
    "counting-down": ("for (int i = 3; i >= 0; i--) s += a[i];", False),
    "step-two": ("for (int i = 0; i < 4; i += 2) s += a[i + 1];", False),
    "modulo": ("for (int i = 0; i < 9; i++) s += a[i % 4];", False),
    "clamp": ("s += a[clamp(int(fragCoord.x), 0, 3)];", False),
    "mask": ("s += a[int(fragCoord.x) & 3];", False),
    "min-max": ("s += a[max(min(int(fragCoord.x), 3), 0)];", False),
    "from-a-float": ("s += a[int(fragCoord.x)];", True),
    "loop-one-too-far": ("for (int i = 0; i <= 4; i++) s += a[i];", True),
    "offset-past-the-end": ("for (int i = 0; i < 4; i++) s += a[i + 1];", True),
    "loop-variable-changed-in-body": (
        "for (int i = 0; i < 4; i++) { s += a[i]; i += int(s); }",
        True,
    ),
    "vector": ("vec3 v = vec3(s); s += v[int(fragCoord.y)];", True),
}


@pytest.mark.parametrize("case", sorted(INDEX_CASES))
def test_dynamic_index_warning(case, tmp_path):
    body, warned = INDEX_CASES[case]
    text = (
        HEADER + "float a[4] = float[4](0.1, 0.2, 0.3, 0.4);\n"
        "void mainImage(out vec4 fragColor, in vec2 fragCoord) {\n    float s = 0.0;\n    "
        + body
        + "\n    fragColor = vec4(s);\n}\n"
    )
    warnings = [w for w in _warnings(tmp_path, text) if "index" in w.message]
    assert bool(warnings) == warned, [w.message for w in warnings]
    if warned:
        assert warnings[0].loc.line == 5 and "undefined behaviour" in warnings[0].message


OUTPUT_CASES = {
    "always": ("fragColor = vec4(1.0);", None),
    "rgb-is-enough-in-image": ("fragColor.rgb = vec3(1.0);", None),
    "both-arms": (
        "if (fragCoord.x > 1.0) fragColor = vec4(1.0); else fragColor = vec4(0.0);",
        None,
    ),
    "return-early-after-writing": (
        "fragColor = vec4(0.0);\n    if (fragCoord.x > 1.0) return;\n    fragColor = vec4(1.0);",
        None,
    ),
    "discard": ("if (fragCoord.x > 1.0) discard;\n    fragColor = vec4(1.0);", None),
    "out-argument": ("paint(fragColor);", None),
    "one-arm": ("if (fragCoord.x > 1.0) fragColor = vec4(1.0);", "every path"),
    "early-return": ("if (fragCoord.x > 1.0) return;\n    fragColor = vec4(1.0);", "this path"),
    "only-in-a-loop": (
        "for (int i = 0; i < int(fragCoord.x); i++) fragColor = vec4(1.0);",
        "every path",
    ),
    "only-red": ("fragColor.r = 1.0;", "every path"),
    "never": ("float x = 1.0;", "every path"),
}


@pytest.mark.parametrize("case", sorted(OUTPUT_CASES))
def test_unwritten_output_warning(case, tmp_path):
    body, expected = OUTPUT_CASES[case]
    text = (
        HEADER + "void paint(out vec4 c) { c = vec4(0.5); }\n"
        "void mainImage(out vec4 fragColor, in vec2 fragCoord) {\n    " + body + "\n}\n"
    )
    warnings = [w for w in _warnings(tmp_path, text) if "not written" in w.message]
    if expected is None:
        assert warnings == []
    else:
        assert len(warnings) == 1 and expected in warnings[0].message
        assert warnings[0].loc.path.endswith("Image.glsl")


def test_a_buffer_tab_needs_alpha_too(tmp_path):
    text = (
        HEADER
        + "void mainImage(out vec4 fragColor, in vec2 fragCoord) { fragColor.rgb = vec3(1.0); }\n"
    )
    assert [w for w in _warnings(tmp_path, text, "Buffer A.glsl") if "not written" in w.message]
    assert not [w for w in _warnings(tmp_path, text, "Image.glsl") if "not written" in w.message]


def test_check_prints_the_warnings_and_still_passes(tmp_path, capsys):
    shader = tmp_path / "Image.glsl"
    shader.write_text(
        HEADER + "void mainImage(out vec4 fragColor, in vec2 fragCoord) {\n"
        "    if (fragCoord.x > 1.0) return;\n    fragColor = vec4(1.0);\n}\n"
    )
    assert main(["check", str(shader)]) == 0
    err = capsys.readouterr().err
    assert f"{shader}:3:28: warning: 'fragColor' is not written on this path" in err
