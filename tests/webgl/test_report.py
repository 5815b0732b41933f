"""`glslcheck report`: one self-contained page, opened in the real browser without errors."""

from __future__ import annotations

import re

import numpy as np

from glslcheck.cli import main
from glslcheck.report import build_report, load_in_browser

SIZE = (64, 36)


def _bad_shader(tmp_path):
    folder = tmp_path / "bad"
    folder.mkdir()
    (folder / "Image.glsl").write_text("void mainImage(out vec4 fragColor, in vec2 fragCoord)\n{\n"
                                       "    float webgl_k = 1.0;\n    fragColor = vec4(webgl_k);\n}\n")
    return folder


def test_page_is_self_contained_and_complete(tmp_path, webgl, gl):
    page = build_report(["lab_shaders/07_final", _bad_shader(tmp_path)], size=SIZE, time=1.7)
    good, bad = page.shaders
    assert good.ok and not bad.ok and not page.ok
    assert set(good.renders) == {"numpy", "gl", "webgl"} and not bad.renders
    assert [(a, b) for a, b, _, _ in good.pairs] == [("numpy", "gl"), ("numpy", "webgl"), ("gl", "webgl")]
    text = page.html
    # No network at view time: every image inline, no external stylesheet, script or link.
    assert not re.search(r"""(src|href)=["'](?!data:|#)""", text)
    assert text.count('src="data:image/png;base64,') == 3 + 3  # three renders, three heat maps
    # The finding sits under its line, in the user's file.
    assert "reserved by WebGL" in text and "WebGL: &#x27;webgl_k&#x27; : reserved built-in name" in text
    assert '<span class="ln">3</span>' in text


def test_page_opens_in_chromium_without_errors(tmp_path, webgl, gl):
    out = tmp_path / "report.html"
    assert main(["report", "lab_shaders/07_final", "-o", str(out), "--size", "64x36"]) == 0
    shot = tmp_path / "report.png"
    assert load_in_browser(out, screenshot=shot, height=900) == []
    from PIL import Image

    with Image.open(shot) as im:
        pixels = np.asarray(im.convert("RGB"), dtype=np.float64)
    assert pixels.shape[:2] == (900, 1280)
    # Something was drawn: the renders' blues and the badges' greens, not a blank page.
    assert pixels.std() > 20
    assert main(["report", "lab_shaders/07_final", "-o", str(tmp_path / "x.txt")]) == 2


def test_report_names_a_missing_backend(tmp_path, gl):
    out = tmp_path / "r.html"
    assert main(["report", "lab_shaders/01_spheres_procedural", "--no-webgl", "-o", str(out), "--size", "32x18"]) == 0
    text = out.read_text()
    assert "WebGL (ANGLE" not in text and text.count("data:image/png") == 3  # numpy, gl, one heat map
    assert "check: glslcheck;" in text  # and ANGLE was not asked
