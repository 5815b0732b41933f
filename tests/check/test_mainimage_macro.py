"""Code-golf Shadertoy: `mainImage` written as a macro that Shadertoy's wrapper call expands.

Shadertoy compiles its `main()` wrapper after the user's code, so `#define mainImage(O, U) ...`
turns the wrapper's `mainImage(color, gl_FragCoord.xy);` into the user's code. The preprocessor
models that call as the entry function (frontend/preprocess/driver.py `_wrapper_call`); the checker,
the NumPy backend and the GL backend (which compiles the real wrapper) then run the same program."""

from __future__ import annotations

import pytest

from glslcheck.frontend.parser import parse_shader
from glslcheck.semantics import CheckError, check
from glslcheck.verification.verify import verify

GOLF = "#define mainImage(O, U) O = vec4(U / iResolution.xy, 0.5 + 0.5 * sin(iTime), 1.0)\n"
GOLF_LOOP = (
    "// three channels, one statement per channel\n"
    "#define R iResolution.xy\n"
    "#define mainImage(O, U) for (int i = 0; i < 3; i++) O[i] = 0.5 + 0.5 * sin(float(i) + iTime "
    "+ U.x / R.x)\n"
)


@pytest.mark.parametrize("text", [GOLF, GOLF_LOOP], ids=["expression", "loop"])
def test_a_mainimage_macro_checks(make_shader, text):
    model = check(parse_shader(make_shader(text)), "Image")
    assert model.entry is not None and model.entry.name == "mainImage"


def test_an_error_in_the_macro_points_at_the_macro(make_shader):
    shader = make_shader("// golf\n#define mainImage(O, U) O = vec4(U, missingName, 1.0)\n")
    with pytest.raises(CheckError) as e:
        check(parse_shader(shader), "Image")
    (d,) = e.value.diagnostics
    assert d.loc.line == 2 and "missingName" in d.message


def test_a_mainimage_macro_in_common(make_shader):
    # the Image pass (Common, then Image, then the wrapper) expands it; Common compiled alone
    # has no wrapper call, so there it is only a macro
    # (a macro body in Common reading iTime would be taken for Common code: not modelled)
    shader = make_shader(
        "// the image is Common's macro\n",
        common="#define mainImage(O, U) O = vec4(U * 0.01, 0.5, 1.0)\n",
    )
    assert check(parse_shader(shader, "Image"), "Image").entry.name == "mainImage"
    common = check(parse_shader(shader, "Common"), "Common", collect=True)
    assert common.entry is None and not common.errors


@pytest.mark.parametrize("text", [GOLF, GOLF_LOOP], ids=["expression", "loop"])
def test_the_same_program_renders_on_both_backends(gl, make_shader, text):
    for c in verify(make_shader(text), size=(48, 27), times=(0.0, 1.3)):
        assert c.match, c.summary()
