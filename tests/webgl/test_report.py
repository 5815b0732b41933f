"""`glslcheck report`: one self-contained page, opened in the real browser without errors; the
probe's NaN origins where a render has NaN pixels; bench's accuracy/time table and plot."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from glslcheck.cli.main import main
from glslcheck.verification.report import build_report, load_in_browser

SIZE = (64, 36)


def _bad_shader(tmp_path):
    folder = tmp_path / "bad"
    folder.mkdir()
    (folder / "Image.glsl").write_text(
        "void mainImage(out vec4 fragColor, in vec2 fragCoord)\n{\n"
        "    float webgl_k = 1.0;\n    fragColor = vec4(webgl_k);\n}\n"
    )
    return folder


def _nan_shader(tmp_path):
    """The left half of the image is NaN: sqrt of a negative on line 4."""
    folder = tmp_path / "nan"
    folder.mkdir()
    (folder / "Image.glsl").write_text(
        "void mainImage(out vec4 fragColor, in vec2 fragCoord)\n{\n"
        "    vec2 uv = fragCoord / iResolution.xy;\n"
        "    float r = sqrt(uv.x - 0.5);\n"
        "    fragColor = vec4(r, uv.y, 0.25, 1.0);\n}\n"
    )
    return folder


def test_page_is_self_contained_and_complete(tmp_path, webgl, gl):
    page = build_report(
        ["lab_shaders/07_final", _bad_shader(tmp_path)], size=SIZE, time=1.7, bench=None
    )
    good, bad = page.shaders
    assert good.ok and not bad.ok and not page.ok
    # the default CPU program first (one frame: the NumPy backend's), then the drivers
    assert set(good.renders) == {"auto", "gl", "webgl"} and not bad.renders
    assert good.engines == {"auto": "numpy", "gl": "gl", "webgl": "webgl"}
    assert [(a, b) for a, b, _, _ in good.pairs] == [
        ("auto", "gl"),
        ("auto", "webgl"),
        ("gl", "webgl"),
    ]
    text = page.html
    # No network at view time: every image inline, no external stylesheet, script or link.
    assert not re.search(r"""(src|href)=["'](?!data:|#)""", text)
    assert text.count('src="data:image/png;base64,') == 3 + 3  # three renders, three heat maps
    # The finding sits under its line, in the user's file.
    assert (
        "reserved by WebGL" in text
        and "WebGL: &#x27;webgl_k&#x27; : reserved built-in name" in text
    )
    assert '<span class="ln">3</span>' in text
    assert "<b>numpy vs gl</b>" in text and "by the NumPy backend</figcaption>" in text


def test_nan_origins_are_on_the_page(tmp_path, gl):
    page = build_report([_nan_shader(tmp_path)], size=SIZE, backends=("numpy", "gl"), bench=None)
    (r,) = page.shaders
    # Counted from the render itself, not from the probe: x < 32 of 64 columns, every row.
    nan_pixels = int(np.isnan(r.renders["numpy"]).any(axis=-1).sum())
    assert nan_pixels == 32 * 36 and r.nonfinite["numpy"] == nan_pixels
    (origin,) = r.nan.origins
    assert (Path(origin.file).name, origin.line, origin.column, origin.pixels) == (
        "Image.glsl",
        4,
        15,
        nan_pixels,
    )
    text = page.html
    assert "NaN and Inf pixels: where they came from" in text
    row = re.search(
        r"<tr><td><code>([^<]*)</code></td><td>([^<]*)</td><td><code>([^<]*)</code></td>"
        r'<td class="num">(\d+)</td>',
        text,
    )
    assert row and row.group(1).endswith("Image.glsl:4:15") and row.group(2) == "sqrt of a negative"
    assert row.group(3) == "sqrt(uv.x - 0.5)" and int(row.group(4)) == nan_pixels
    # ... and under line 4 of the listing, and the map of those pixels
    assert re.search(
        r'<span class="ln">4</span>[^\n]*?</span><span class="note nan">\s*\^ note \[nan-origin\] '
        r"sqrt of a negative",
        text,
    )
    assert 'alt="NaN/Inf pixels of the NumPy render"' in text
    # A shader without NaN pixels has no such section.
    clean = build_report(
        ["lab_shaders/01_spheres_procedural"], size=SIZE, backends=("numpy",), bench=None
    )
    assert clean.shaders[0].nan is None and "where they came from" not in clean.html


def test_accuracy_time_table_and_plot(tmp_path, gl):
    page = build_report(
        ["lab_shaders/07_final"], size=SIZE, backends=("numpy", "gl"), bench=(32, 18), bench_runs=1
    )
    (r,) = page.shaders
    labels = [x.config.label for x in r.bench]
    assert labels == ["gl x1", "gl x4", "gl x16"] + [
        f"f{p} x{n}" for p in (16, 32, 64) for n in (1, 4, 16)
    ]
    by = {x.config.label: x for x in r.bench}
    # The reference is NumPy float64 at 16 samples: error 0 against itself; GL x1 is the time unit.
    assert by["f64 x16"].mean_abs_error == 0 and by["gl x1"].ratio_to_gl == 1.0
    assert by["gl x1"].mean_abs_error > by["gl x16"].mean_abs_error  # supersampling converges
    table = re.search(r'<table class="bench">(.*?)</table>', page.html).group(1)
    cells = [
        re.findall(r"<td[^>]*>([^<]*)</td>", tr)
        for tr in re.findall(r"<tr[^>]*>(.*?)</tr>", table)[1:]
    ]
    assert [c[0] for c in cells] == labels
    for c, x in zip(cells, r.bench):  # the page shows the code's numbers
        assert float(c[4]) == round(x.median_ms, 1) and float(c[5]) == round(x.ratio_to_gl, 2)
        assert float(c[7]) == float(f"{x.mean_abs_error:.3g}") and int(c[9]) == x.pixels_over_1_255
        assert (c[10] == "*") == x.pareto
    assert "glslcheck bench --size 32x18 --runs 1 --time 0</code>" in page.html
    assert 'alt="render time against error" src="data:image/png;base64,' in page.html
    # Without GL there is no unit for the times: the page says so instead of a table.
    from glslcheck.verification.report import ShaderReport, _bench

    r2 = ShaderReport("x", r.shader, unavailable={"gl": "no OpenGL context"})
    _bench(r2, (32, 18), 1, 0.0)
    assert not r2.bench and r2.bench_note == "not measured: GL is not available (no OpenGL context)"


def test_page_opens_in_chromium_without_errors(tmp_path, webgl, gl):
    out = tmp_path / "report.html"
    assert (
        main(
            [
                "report",
                "lab_shaders/07_final",
                str(_nan_shader(tmp_path)),
                "-o",
                str(out),
                "--size",
                "64x36",
                "--bench-size",
                "32x18",
                "--bench-runs",
                "1",
            ]
        )
        == 0
    )
    text = out.read_text()
    assert (
        text.count('<table class="bench">') == 2
        and text.count('alt="render time against error"') == 2
    )
    assert "webgl x16" in text and "sqrt of a negative" in text
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
    assert (
        main(
            [
                "report",
                "lab_shaders/01_spheres_procedural",
                "--no-webgl",
                "--no-bench",
                "-o",
                str(out),
                "--size",
                "32x18",
            ]
        )
        == 0
    )
    text = out.read_text()
    assert (
        "WebGL (ANGLE" not in text and text.count("data:image/png") == 3
    )  # numpy, gl, one heat map
    assert "check: glslcheck;" in text  # and ANGLE was not asked
