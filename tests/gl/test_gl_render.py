"""Rendering with the GL driver: orientation, pixel centres, alpha, float framebuffer,
supersampling."""

import datetime

import numpy as np
import pytest

from glslcheck.backends.gl import compile_gl, render_shader
from glslcheck.shadertoy.wrapper import sample_offsets


def _render(make_shader, body, **kw):
    image = "void mainImage(out vec4 c, in vec2 p) {\n" + body + "\n}\n"
    return compile_gl(make_shader(image)).render(**kw)


def test_shape_dtype_and_top_row_first(gl, make_shader):
    img = _render(make_shader, "c = vec4(p.y / iResolution.y);", size=(8, 6))
    assert img.shape == (6, 8, 4) and img.dtype == np.float32
    assert img[0, 0, 0] == pytest.approx(5.5 / 6)  # top row: fragCoord.y = height - 0.5
    assert img[-1, 0, 0] == pytest.approx(0.5 / 6)  # bottom row
    assert np.all(np.diff(img[:, 0, 0]) < 0)


def test_fragcoord_is_the_pixel_centre(gl, make_shader):
    img = _render(make_shader, "c = vec4(p, 0.0, 1.0);", size=(5, 3))
    assert np.array_equal(img[0, :, 0], np.arange(5) + 0.5)
    assert np.array_equal(img[:, 0, 1], np.array([2.5, 1.5, 0.5], np.float32))


def test_alpha_is_forced_to_one(gl, make_shader):
    img = _render(make_shader, "c = vec4(0.2, 0.4, 0.6, 0.25);", size=(4, 4))
    assert np.all(img[..., 3] == 1.0)


def test_values_are_unquantised_and_unclamped(gl, make_shader):
    img = _render(make_shader, "c = vec4(0.123456, 3.5, -2.25, 1.0);", size=(3, 2))
    assert np.all(img[..., 0] == np.float32(0.123456))
    assert np.all(img[..., 1] == 3.5)
    assert np.all(img[..., 2] == -2.25)


def test_inputs_reach_the_shader(gl, make_shader):
    body = (
        "c = vec4(iTime + float(iFrame), iMouse.x + iMouse.w, "
        "iDate.x + iDate.y + iDate.z + iDate.w + iSampleRate, 0.0);"
    )
    img = _render(make_shader, body, size=(2, 2), time=1.5, frame=3, mouse=(10, 20, 30, -4))
    assert tuple(img[0, 0, :3]) == (4.5, 6.0, 2026.0 + 0 + 1 + 0 + 44100.0)
    when = datetime.datetime(2024, 3, 5, 1, 2, 3)
    img = _render(make_shader, "c = iDate;", size=(1, 1), date=when)
    assert tuple(img[0, 0, :3]) == (2024.0, 2.0, 5.0)  # alpha is forced to 1
    body = "c = vec4(iTimeDelta, iFrameRate, iChannelTime[3] + iChannelResolution[2].x, 0.0);"
    img = _render(make_shader, body, size=(1, 1), time_delta=0.5, frame_rate=30.0)
    assert tuple(img[0, 0, :3]) == (0.5, 30.0, 0.0)


def test_unused_uniforms_are_skipped(gl, make_shader):
    img = _render(make_shader, "c = vec4(0.5);", size=(2, 2))
    assert np.all(img[..., :3] == 0.5)


def test_unbound_channel_reads_opaque_black(gl, make_shader):
    img = _render(
        make_shader,
        "c = texture(iChannel0, p / iResolution.xy) + vec4(0.0, 0.0, 0.0, 0.0);",
        size=(2, 2),
    )
    assert np.all(img[..., :3] == 0.0)


def test_uninitialised_variables_read_zero_as_in_webgl(gl, make_shader):
    img = _render(
        make_shader, "float u; vec4 z;\n c = vec4(u, z.x, z.w, 1.0) + vec4(0.25);", size=(2, 2)
    )
    assert np.all(img[..., :3] == 0.25)


def test_samples_average_a_regular_grid(gl, make_shader):
    # (fract(x) - 0.5)^2 is 0 at the pixel centre; at offsets +-0.25 it is 0.0625.
    body = "vec2 f = fract(p) - 0.5; c = vec4(f.x * f.x, p.y, f.y * f.y, 1.0);"
    one = _render(make_shader, body, size=(4, 2))
    four = _render(make_shader, body, size=(4, 2), samples=4)
    assert np.all(one[..., 0] == 0.0)
    assert np.allclose(four[..., 0], 0.0625) and np.allclose(four[..., 2], 0.0625)
    assert np.allclose(four[..., 1], one[..., 1])  # linear in p: the average is the centre value
    assert sample_offsets(4) == [(-0.25, -0.25), (0.25, -0.25), (-0.25, 0.25), (0.25, 0.25)]


def test_samples_must_be_a_perfect_square(gl, make_shader):
    with pytest.raises(ValueError):
        _render(make_shader, "c = vec4(1.0);", size=(2, 2), samples=3)


def test_render_shader_in_one_call(gl, make_shader):
    img = render_shader(
        make_shader("void mainImage(out vec4 c, in vec2 p) { c = vec4(1.0); }\n"), size=(3, 3)
    )
    assert img.shape == (3, 3, 4)


def test_buffer_pass_keeps_alpha(gl, make_shader):
    shader = make_shader(
        Buffer_A="void mainImage(out vec4 c, in vec2 p) { c = vec4(0.5, 0.5, 0.5, 0.25); }\n"
    )
    img = compile_gl(shader, tab="Buffer A").render(size=(2, 2))
    assert np.all(img[..., 3] == 0.25)
