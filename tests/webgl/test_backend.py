"""The WebGL backend renders what Shadertoy's page renders, and maps ANGLE's errors to the user's
lines."""

from __future__ import annotations

import os
import subprocess
import sys

import numpy as np
import pytest

from glslcheck.backends.webgl import compile_webgl, get_browser
from glslcheck.base.diagnostics import GlslError

SIZE = (160, 90)  # small: the machine is shared

W, H = SIZE


def test_uniforms_reach_the_shader_as_shadertoy_sets_them(webgl, make_shader):
    # One uniform per pixel column range; every value is exact in float32, so equality is fair.
    shader = make_shader("""
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    int column = int(fragCoord.x) / 10;
    vec4 v = vec4(0.0);
    if (column == 0) v = vec4(iResolution, iTime);
    else if (column == 1) v = iMouse;
    else if (column == 2) v = iDate;
    else if (column == 3) v = vec4(float(iFrame), iTimeDelta, iFrameRate, iSampleRate);
    else if (column == 4) v = vec4(iChannelTime[0], iChannelTime[3], iChannelResolution[0].x, \
        iChannelResolution[3].z);
    else if (column == 5) v = texture(iChannel0, vec2(0.5));
    fragColor = v;
}
""")
    img = compile_webgl(shader).render(
        size=SIZE,
        time=1.5,
        frame=7,
        mouse=(10.0, 20.0, -3.0, 4.0),
        date=(2024.0, 5.0, 17.0, 3600.5),
        time_delta=0.25,
        frame_rate=4.0,
    )
    assert img.shape == (H, W, 4) and img.dtype == np.float32
    row = img[H // 2]
    # The Image pass forces alpha to 1 (Shadertoy's footer), so only xyz carries the values.
    assert row[0, :3].tolist() == [W, H, 1.0]
    assert row[15, :3].tolist() == [10.0, 20.0, -3.0]
    assert row[25, :3].tolist() == [2024.0, 5.0, 17.0]
    assert row[35, :3].tolist() == [7.0, 0.25, 4.0]
    assert row[45, :3].tolist() == [0.0, 0.0, 0.0]
    assert row[55].tolist() == [0.0, 0.0, 0.0, 1.0]  # an unbound channel samples as (0, 0, 0, 1)
    assert (img[..., 3] == 1.0).all()


def test_float_target_is_read_back_unclamped_and_unquantised(webgl, make_shader):
    shader = make_shader("void mainImage(out vec4 c, in vec2 f) { c = vec4(f.x, -f.y, 0.3, 0.0); }")
    img = compile_webgl(shader).render(size=SIZE)
    x = np.arange(W, dtype=np.float32) + 0.5
    y = np.arange(H, dtype=np.float32)[::-1] + 0.5  # row 0 is the top: fragCoord.y = H - 0.5
    assert (img[..., 0] == x[None, :]).all()
    assert (img[..., 1] == -y[:, None]).all()
    # An 8-bit target would give 77/255 = 0.30196 here; the float target gives float32(0.3).
    assert (img[..., 2] == np.float32(0.3)).all()


def test_buffer_tab_keeps_alpha(webgl, make_shader):
    shader = make_shader(
        "void mainImage(out vec4 c, in vec2 f) { c = vec4(0.0); }",
        Buffer_A="void mainImage(out vec4 c, in vec2 f) { c = vec4(0.25, 0.5, 0.75, 0.125); }",
    )
    img = compile_webgl(shader, tab="Buffer A").render(size=(8, 4))
    assert (img == np.float32([0.25, 0.5, 0.75, 0.125])).all()


def test_supersampling_uses_the_gl_backends_grid(webgl, make_shader):
    # The average of fragCoord over the 2x2 grid is the pixel centre again; its x*x is not.
    shader = make_shader(
        "void mainImage(out vec4 c, in vec2 f) { c = vec4(f.x, f.x * f.x, 0.0, 1.0); }"
    )
    img = compile_webgl(shader).render(size=(16, 2), samples=4)
    x = np.arange(16, dtype=np.float64) + 0.5
    assert np.allclose(img[0, :, 0], x, atol=1e-6)
    # mean of (x -+ 0.25)^2 = x^2 + 0.0625: the offsets are +-1/4 pixel, as
    # shadertoy.wrapper.sample_offsets
    assert np.allclose(img[0, :, 1], x * x + 0.0625, rtol=1e-6)


def test_one_browser_serves_every_shader(webgl, make_shader):
    a = compile_webgl(make_shader("void mainImage(out vec4 c, in vec2 f) { c = vec4(1.0); }"))
    b = compile_webgl(make_shader("void mainImage(out vec4 c, in vec2 f) { c = vec4(0.5); }"))
    assert a.browser is b.browser is get_browser() is webgl
    assert a.render(size=(2, 2))[0, 0, 0] == 1.0 and b.render(size=(2, 2))[0, 0, 0] == 0.5


def test_angle_errors_point_into_the_users_tab_and_line(webgl, make_shader):
    shader = make_shader(
        "void mainImage(out vec4 c, in vec2 f)\n{\n    float k = 1;\n    c = vec4(k);\n}\n",
        common="float helper(float x)\n{\n    return x;\n}\n",
    )
    with pytest.raises(GlslError) as e:
        compile_webgl(shader)
    d = e.value.diagnostics[0]
    assert d.rule == "webgl-compile" and d.message.startswith("WebGL: ")
    assert "cannot convert from 'const int' to 'highp float'" in d.message
    # line 3 of Image.glsl (after the prelude and the 4 lines of Common), at the quoted '='
    assert (d.loc.path, d.loc.line, d.loc.column) == ("Image.glsl", 3, 13)


def test_angle_error_in_common_points_into_common(webgl, make_shader):
    shader = make_shader(
        "void mainImage(out vec4 c, in vec2 f) { c = vec4(helper(1.0)); }\n",
        common="float helper(float x)\n{\n    return x + undefinedThing;\n}\n",
    )
    with pytest.raises(GlslError) as e:
        compile_webgl(shader)
    locs = {(d.loc.path, d.loc.line) for d in e.value.diagnostics if d.loc}
    assert ("Common.glsl", 3) in locs


ENDLESS = """
import sys
from glslcheck.base.diagnostics import GlslError, register_source
from glslcheck.shadertoy.sources import Shader, Source
from glslcheck.backends.webgl import compile_webgl, get_browser

text = ("void mainImage(out vec4 c, in vec2 f)\\n{\\n    float s = 0.0;\\n"
        "    for (int i = 0; i < 2000000000; i++) { s += sin(float(i) + f.x); }\\n"
        "    c = vec4(s);\\n}\\n")
register_source("Image.glsl", text)
shader = Shader(root="<test>")
shader.tabs["Image"] = Source("Image.glsl", text, "Image")
first = get_browser()
try:
    compile_webgl(shader).render(size=(2, 2))
except GlslError as e:
    d = e.diagnostics[0]
    print(d.loc, d.message)
# the next use starts a new browser, which works
print(first.closed, get_browser() is not first, get_browser().call("info")["renderer"][:5])
"""


def test_an_endless_loop_times_out_and_the_next_render_gets_a_new_browser(webgl):
    # In a child process: a timeout ends the browser it happens in (here not the session's), and
    # Playwright's sync API allows one browser driver per thread.
    env = dict(os.environ, GLSLCHECK_WEBGL_TIMEOUT="3")
    proc = subprocess.run(
        [sys.executable, "-c", ENDLESS], capture_output=True, text=True, timeout=300, env=env
    )
    assert proc.returncode == 0, proc.stderr
    first, second = proc.stdout.splitlines()
    assert first.startswith(
        "Image.glsl:1:6 WebGL: the Image program ran for more than 3 s in the browser"
    )
    assert second == "True True ANGLE"


def test_a_missing_browser_is_an_input_error_with_advice(webgl, monkeypatch, capsys):
    from glslcheck.backends.webgl import Browser, WebGLUnavailable
    from glslcheck.cli.main import main

    monkeypatch.setenv("GLSLCHECK_CHROMIUM", "/nonexistent/chromium")
    with pytest.raises(WebGLUnavailable) as e:
        Browser()
    assert "apt-get install chromium" in str(e.value) and "glslcheck[webgl]" in str(e.value)
    monkeypatch.delenv("GLSLCHECK_CHROMIUM")
    monkeypatch.setenv("GLSLCHECK_WEBGL_TIMEOUT", "-1")
    assert main(["check", "lab_shaders/07_final", "--webgl"]) == 2
    assert (
        "GLSLCHECK_WEBGL_TIMEOUT must be a number of seconds from 0 to 86400"
        in capsys.readouterr().err
    )
