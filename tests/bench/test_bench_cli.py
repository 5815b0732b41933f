"""`glslcheck bench` on the command line at a tiny size: exact JSON, the table, the plot file,
exit codes 0/1/2 and the progress bar. Renders for real (GL and NumPy); no timing is asserted."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from glslcheck.cli.main import main
from glslcheck.verification.bench import JSON_KEYS

ROOT = Path(__file__).resolve().parents[2]
PART = str(ROOT / "lab_shaders" / "02_point_light")
TINY = ["--size", "16x10", "--runs", "1", "--no-progress"]


@pytest.fixture(scope="module")
def json_run(tmp_path_factory, gl):
    """One real run shared by the tests that only read its output (it renders 24 frames)."""
    import contextlib
    import io

    # The `gl` fixture (tests/conftest.py) skips on a developer machine without EGL, fails in CI.
    plot = tmp_path_factory.mktemp("bench") / "plot.png"
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        code = main(["bench", PART, *TINY, "--format", "json", "--plot", str(plot)])
    return code, json.loads(out.getvalue()), plot


def test_json_exact_keys_and_twelve_rows(json_run):
    code, obj, _ = json_run
    assert code == 0
    assert list(obj) == ["rows"]
    rows = obj["rows"]
    assert len(rows) == 12
    assert all(tuple(r) == JSON_KEYS for r in rows)
    assert {(r["backend"], r["precision"]) for r in rows} == {
        ("gl", "float32"),
        ("auto", "float16"),
        ("auto", "float32"),
        ("auto", "float64"),
    }
    assert sorted({r["samples"] for r in rows}) == [1, 4, 16]
    # the default CPU program: float16 and float64 are the NumPy backend's alone
    assert {r["engine"] for r in rows if r["precision"] != "float32"} == {"numpy"}
    assert {r["engine"] for r in rows if r["backend"] == "gl"} == {"gl"}


def test_reference_row_error_zero_and_ratio_column(json_run):
    rows = json_run[1]["rows"]
    (ref,) = [
        r for r in rows if (r["backend"], r["precision"], r["samples"]) == ("auto", "float64", 16)
    ]
    assert (
        ref["max_abs_error"] == 0 and ref["mean_abs_error"] == 0 and ref["pixels_over_1_255"] == 0
    )
    assert ref["psnr_db"] is None
    (gl1,) = [r for r in rows if r["backend"] == "gl" and r["samples"] == 1]
    assert gl1["ratio_to_gl"] == 1.0
    assert all(r["ratio_to_gl"] > 0 and r["median_ms"] > 0 for r in rows)


def test_plot_file_written(json_run):
    from PIL import Image

    with Image.open(json_run[2]) as im:
        assert im.format == "PNG"


def test_text_table(gl, capsys):
    assert main(["bench", PART, *TINY]) == 0
    out = capsys.readouterr().out
    assert "x GL@1" in out and "16x10" in out and "PSNR dB" in out
    lines = [
        line for line in out.splitlines() if line.startswith(("  gl x", "  f16", "  f32", "  f64"))
    ]
    assert len(lines) == 12
    assert any(
        line.startswith("  f64 x16") and " inf " in line and line.endswith("*") for line in lines
    )


def test_progress_bar_on_stderr(gl, capsys):
    assert (
        main(["bench", PART, "--size", "8x6", "--runs", "1", "--progress", "--format", "json"]) == 0
    )
    err = capsys.readouterr().err
    assert "bench [" in err and "24/24" in err


def test_shader_error_exit_1_others_still_measured(gl, capsys, tmp_path):
    bad = tmp_path / "bad.glsl"
    bad.write_text("void mainImage(out vec4 c, in vec2 f) { c = vec4(undefined_name); }\n")
    assert main(["bench", str(bad), PART, *TINY, "--format", "json"]) == 1
    captured = capsys.readouterr()
    assert "bad.glsl:1:" in captured.err
    assert len(json.loads(captured.out)["rows"]) == 12


@pytest.mark.parametrize(
    "argv",
    [
        ["--runs", "0"],
        ["--size", "16"],
        ["--format", "csv"],
        ["--time", "soon"],
    ],
)
def test_usage_errors_exit_2(argv, capsys):
    assert main(["bench", PART, *argv]) == 2


def test_missing_file_exit_2(capsys, tmp_path):
    assert main(["bench", str(tmp_path / "nope.glsl"), *TINY]) == 2


def test_no_gl_context_exit_2(monkeypatch, capsys):
    import glslcheck.backends.gl.program as gb
    from glslcheck.backends.gl import GLUnavailable

    def unavailable(*a, **k):
        raise GLUnavailable("error: cannot create an OpenGL context with EGL (test)")

    monkeypatch.setattr(gb, "compile_gl", unavailable)
    assert main(["bench", PART, *TINY]) == 2
    assert "OpenGL context" in capsys.readouterr().err


def test_unwritable_plot_exit_2(gl, capsys, tmp_path):
    assert (
        main(
            [
                "bench",
                PART,
                "--size",
                "8x6",
                "--runs",
                "1",
                "--no-progress",
                "--plot",
                str(tmp_path / "no" / "such" / "dir.png"),
            ]
        )
        == 2
    )
