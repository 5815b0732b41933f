"""The Shadertoy wrapper text and its line map (glslcheck/shadertoy/wrapper.py); no GL needed."""

import pytest

from glslcheck.base.diagnostics import InputError
from glslcheck.shadertoy.sources import Shader, Source
from glslcheck.shadertoy.wrapper import UNIFORMS, build_common_only, build_program

COMMON = "float twice(float x) {\n    return 2.0 * x;\n}\n"
IMAGE = "void mainImage(out vec4 c, in vec2 p) {\n    c = vec4(twice(p.x));\n}\n"


def test_prelude_is_shadertoys(make_shader):
    text = build_program(make_shader(IMAGE)).text
    lines = text.splitlines()
    assert lines[:7] == [
        "#version 300 es",
        "#ifdef GL_ES",
        "precision highp float;",
        "precision highp int;",
        "precision mediump sampler3D;",
        "#endif",
        "#define HW_PERFORMANCE 1",
    ]
    for u in UNIFORMS:
        assert u.declaration in lines
    assert "uniform sampler2D iChannel3;" in lines
    assert "uniform float     iChannelTime[4];" in lines
    assert "out vec4 shadertoy_out_color;" in lines
    assert "    shadertoy_out_color = vec4(color.xyz, 1.0);" in lines
    assert "    mainImage(color, gl_FragCoord.xy);" in lines


def test_common_and_image_lines_map_back(make_shader):
    program = build_program(make_shader(IMAGE, COMMON))
    lines = program.text.split("\n")
    for path, text in (("Common.glsl", COMMON), ("Image.glsl", IMAGE)):
        for n, line in enumerate(text.splitlines(), 1):
            at = program.program_line(path, n)
            assert lines[at - 1] == line
            assert program.locate(at) == (path, n)
    assert program.locate(1) is None  # #version
    assert program.locate(program.line_count) is None  # closing brace of main()
    assert program.text.index(COMMON) < program.text.index(IMAGE)


def test_text_without_final_newline_keeps_lines_apart(make_shader):
    program = build_program(make_shader(IMAGE.rstrip("\n"), COMMON.rstrip("\n")))
    assert "}\nvoid mainImage" in program.text
    assert program.locate(program.program_line("Image.glsl", 3)) == ("Image.glsl", 3)


def test_samples_offset_goes_in_the_footer_only(make_shader):
    plain = build_program(make_shader(IMAGE, COMMON))
    offset = build_program(make_shader(IMAGE, COMMON), samples_offset=True)
    assert offset.segments == plain.segments  # user lines do not move
    assert "uniform vec2 glslcheck_offset;" in offset.text
    assert "mainImage(color, gl_FragCoord.xy + glslcheck_offset);" in offset.text
    assert "glslcheck_offset" not in plain.text


def test_buffer_pass_keeps_alpha(make_shader):
    program = build_program(make_shader(IMAGE, Buffer_A=IMAGE), "Buffer A")
    assert "shadertoy_out_color = color;" in program.text


def test_common_alone_declares_only_idate_and_isamplerate(make_shader):
    program = build_common_only(make_shader(IMAGE, COMMON))
    assert "iDate;" in program.text and "iSampleRate;" in program.text
    assert "iTime" not in program.text and "iResolution" not in program.text
    assert "void main() {}" in program.text
    at = program.program_line("Common.glsl", 2)
    assert program.locate(at) == ("Common.glsl", 2)


def test_plain_glsl_is_taken_as_it_is():
    text = "#version 300 es\nprecision highp float;\nout vec4 o;\nvoid main() { o = vec4(1.0); }\n"
    shader = Shader({"GLSL": Source("plain.frag", text, "GLSL")}, root="plain.frag")
    program = build_program(shader)
    assert program.text == text
    assert program.locate(4) == ("plain.frag", 4)
    with pytest.raises(InputError):
        build_program(shader, samples_offset=True)


def test_sound_tab_is_refused(make_shader):
    with pytest.raises(InputError):
        build_program(
            make_shader(IMAGE, Sound="vec2 mainSound(int s, float t) { return vec2(0); }"), "Sound"
        )
