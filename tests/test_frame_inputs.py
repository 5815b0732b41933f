"""One frame's inputs are declared once (shadertoy.FrameInputs) and every backend's render takes
them through `@frame_inputs`: the signature each shows (which verify reads to know what a
backend takes) is FrameInputs' fields, then the backend's own options."""

from __future__ import annotations

import dataclasses
import inspect

import pytest

from glslcheck.backends.gl.program import GLProgram
from glslcheck.backends.interface import Program
from glslcheck.backends.numpy_engine.program import NumpyProgram, compile_numpy
from glslcheck.backends.webgl.program import WebGLProgram
from glslcheck.shadertoy.frame_inputs import FrameInputs
from glslcheck.shadertoy.wrapper import frame_uniforms
from glslcheck.verification.verify import _accepted

FIELDS = [(f.name, f.default) for f in dataclasses.fields(FrameInputs)]
SHADER = "void mainImage(out vec4 o, in vec2 f) { o = vec4(f / iResolution.xy, iTime, 1.0); }"


@pytest.mark.parametrize(
    "cls, options",
    [
        (NumpyProgram, ["precision", "stats", "channels"]),
        (GLProgram, ["channels"]),
        (WebGLProgram, ["channels"]),
        (Program, ["precision", "stats"]),
    ],
)
def test_every_render_takes_the_frame_inputs_then_its_options(cls, options):
    params = list(inspect.signature(cls.__new__(cls).render).parameters.values())
    assert [(p.name, p.default) for p in params[: len(FIELDS)]] == FIELDS
    assert [p.name for p in params[len(FIELDS) :]] == options
    assert _accepted(cls.__new__(cls)) == {name for name, _ in FIELDS} | set(options)


def test_the_inputs_reach_the_render_and_are_checked(make_shader):
    prog = compile_numpy(make_shader(SHADER))
    img = prog.render((4, 2), 0.75, precision="float64")  # positional as before: size, time
    assert img.shape == (2, 4, 4) and (img[..., 2] == 0.75).all()
    with pytest.raises(ValueError, match="size must be at least 1x1, not 0x2"):
        prog.render(size=(0, 2))
    with pytest.raises(ValueError, match="samples must be a perfect square"):
        prog.render(samples=3)
    with pytest.raises(TypeError, match="unexpected keyword argument 'colour'"):
        prog.render(colour=1)


def test_frame_inputs_give_the_frames_uniforms():
    inputs = FrameInputs(
        size=(7, 3), time=2.5, frame=4, mouse=(1, 2, 3, 4), time_delta=0.5, frame_rate=2.0
    )
    assert inputs.uniforms() == frame_uniforms(7, 3, 2.5, 4, (1, 2, 3, 4), None, 0.5, 2.0)
    assert FrameInputs(**inputs.keywords()) == inputs
    assert FrameInputs(samples=4).offsets == [
        (-0.25, -0.25),
        (0.25, -0.25),
        (-0.25, 0.25),
        (0.25, 0.25),
    ]
