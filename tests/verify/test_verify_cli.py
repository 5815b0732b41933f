"""`glslcheck verify` on the command line: JSON keys, exit codes 0/1/2, --diff, progress bar."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from glslcheck.cli.main import main
from glslcheck.verification.verify import BACKENDS, JSON_KEYS

ROOT = Path(__file__).resolve().parents[2]
PART = str(ROOT / "lab_shaders" / "02_point_light")
SMALL = ["--size", "64x36"]


def test_match_exit_0_and_exact_json_keys(gl, capsys):
    assert main(["verify", PART, *SMALL, "--format", "json"]) == 0
    obj = json.loads(capsys.readouterr().out)
    assert isinstance(obj, dict) and tuple(obj) == JSON_KEYS
    assert obj["match"] is True and obj["size"] == [64, 36]
    assert obj["engine"] == "numpy"  # one quick frame: the default CPU program's first engine


def test_several_frames_give_a_list_of_exact_objects(gl, capsys):
    assert main(["verify", PART, *SMALL, "--times", "0,1.7", "--format", "json"]) == 0
    objs = json.loads(capsys.readouterr().out)
    assert isinstance(objs, list) and len(objs) == 2
    assert all(tuple(o) == JSON_KEYS for o in objs)
    assert (
        main(["verify", PART, PART, *SMALL, "--frames", "2", "--fps", "30", "--format", "json"])
        == 0
    )
    assert len(json.loads(capsys.readouterr().out)) == 4


def test_text_table_and_verdict(gl, capsys):
    assert main(["verify", PART, *SMALL, "--time", "1.7"]) == 0
    out = capsys.readouterr().out
    assert "iTime 1.7" in out and "max abs error" in out and "PSNR" in out and "NaN/Inf" in out
    assert out.strip().splitlines()[-1] == "verify: match (1 frame)"


def test_mismatch_exit_1_text_and_diff(gl, capsys, tmp_path, monkeypatch):
    import glslcheck.verification.verify as v

    real = v.compile_backend

    class Tampered:
        def __init__(self, prog):
            self.prog = prog

        def render(self, **kw):
            img = self.prog.render(**kw).copy()
            img[10:20, 10:30, 0] = 5.0 - img[10:20, 10:30, 0]
            return img

    monkeypatch.setattr(
        v, "compile_backend", lambda s, b: Tampered(real(s, b)) if b == BACKENDS[0] else real(s, b)
    )
    diff = tmp_path / "diff.png"
    assert main(["verify", PART, *SMALL, "--diff", str(diff)]) == 1
    out = capsys.readouterr().out
    assert "MISMATCH" in out and "fragCoord" in out and "differences in" in out
    from PIL import Image

    with Image.open(diff) as im:
        assert im.size == (64, 36)
    assert (
        main(["verify", PART, *SMALL, "--times", "0,1", "--diff", str(diff), "--format", "json"])
        == 1
    )
    assert (tmp_path / "diff-0.png").is_file() and (tmp_path / "diff-1.png").is_file()
    assert [o["match"] for o in json.loads(capsys.readouterr().out)] == [False, False]


def test_diff_written_on_match_too(gl, tmp_path, capsys):
    diff = tmp_path / "d.png"
    assert main(["verify", PART, *SMALL, "--diff", str(diff)]) == 0
    assert diff.is_file()


def test_glsl_error_exit_1_with_location(gl, tmp_path, capsys):
    bad = tmp_path / "Image.glsl"
    bad.write_text("void mainImage(out vec4 c, in vec2 p)\n{\n    c = vec4(undefinedThing);\n}\n")
    assert main(["verify", str(bad), *SMALL]) == 1
    err = capsys.readouterr().err
    assert f"{bad}:3:" in err


@pytest.mark.parametrize(
    "argv",
    [
        ["verify", "no/such/shader.glsl"],
        ["verify", PART, "--size", "64by36"],
        ["verify", PART, "--time", "1", "--times", "0,1"],
        ["verify", PART, "--mouse", "1,2,3"],
        ["verify", PART, "--samples", "3"],
        ["verify", PART, "--precision", "float8"],
    ],
)
def test_usage_and_io_errors_exit_2(argv, capsys):
    with pytest.raises(SystemExit) as e:
        raise SystemExit(main(argv))
    assert e.value.code == 2


def test_no_gl_context_exit_2_with_advice(monkeypatch, capsys):
    import glslcheck.backends.gl.program as program
    from glslcheck.backends.gl.context import ADVICE, GLUnavailable

    def unavailable():
        raise GLUnavailable(f"error: cannot create an OpenGL context with EGL (test); {ADVICE}")

    monkeypatch.setattr(program, "get_context", unavailable)
    assert main(["verify", PART, *SMALL]) == 2
    assert "apt-get install" in capsys.readouterr().err


def test_progress_bar_on_stderr(gl, capsys):
    assert main(["verify", PART, *SMALL, "--frames", "3", "--progress"]) == 0
    err = capsys.readouterr().err
    assert "verify [" in err and "3/3" in err
    assert main(["verify", PART, *SMALL, "--frames", "3", "--no-progress"]) == 0
    assert "verify [" not in capsys.readouterr().err
