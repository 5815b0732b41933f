"""`glslcheck render --backend compiled`: the image, the exit codes and the messages."""

from __future__ import annotations

import numpy as np

from glslcheck.cli.main import main

IMAGE = (
    "void mainImage(out vec4 fragColor, in vec2 fragCoord) {\n"
    "    fragColor = vec4(fragCoord.x / iResolution.x, sin(iTime), -1.0, 0.2);\n}\n"
)


def test_render_writes_the_numpy_backends_image(numba, tmp_path):
    path = tmp_path / "Image.glsl"
    path.write_text(IMAGE)
    assert (
        main(
            [
                "render",
                str(path),
                "-o",
                str(tmp_path / "c.npy"),
                "--size",
                "6x3",
                "--time",
                "0.7",
                "--backend",
                "compiled",
            ]
        )
        == 0
    )
    assert (
        main(["render", str(path), "-o", str(tmp_path / "n.npy"), "--size", "6x3", "--time", "0.7"])
        == 0
    )
    got, want = np.load(tmp_path / "c.npy"), np.load(tmp_path / "n.npy")
    assert got.shape == (3, 6, 4) and got.tobytes() == want.tobytes()


def test_unsupported_construct_exits_1_at_its_line(numba, tmp_path, capsys):
    path = tmp_path / "Image.glsl"
    path.write_text(
        "void mainImage(out vec4 c, in vec2 f) {\n    c = vec4(1.0);\n    c.x = "
        "float(packHalf2x16(f));\n}\n"
    )
    assert main(["render", str(path), "-o", str(tmp_path / "c.png"), "--backend", "compiled"]) == 1
    err = capsys.readouterr().err
    assert f"{path}:3:" in err and "not supported by the compiled engine yet" in err
    assert "Traceback" not in err and not (tmp_path / "c.png").exists()


def test_buffer_passes_render_and_unbound_channels_are_located(numba, tmp_path, capsys):
    """A multipass shader renders on the compiled engine (any pass, through the one multipass
    driver) with the NumPy backend's bits; a channel read but not bound is the same located
    error on both."""
    import json

    import numpy as np

    (tmp_path / "Image.glsl").write_text(
        "void mainImage(out vec4 c, in vec2 f) {\n    c = texture(iChannel0, f / 9.0);\n}\n"
    )
    (tmp_path / "Buffer A.glsl").write_text(
        "void mainImage(out vec4 c, in vec2 f) { c = vec4(f * 0.1, iTime, 0.5); }\n"
    )
    args = ["render", str(tmp_path), "--size", "6x3", "--backend"]
    assert main([*args, "compiled", "-o", str(tmp_path / "c.png")]) == 1
    err = capsys.readouterr().err
    assert "Image.glsl:2:" in err and "iChannel0 is read but not bound" in err
    assert "Traceback" not in err and not (tmp_path / "c.png").exists()
    (tmp_path / "channels.json").write_text(
        json.dumps({"Image": {"iChannel0": {"buffer": "Buffer A"}}})
    )
    for backend in ("compiled", "numpy"):
        for tab in ("Image", "Buffer A"):
            out = str(tmp_path / f"{backend}-{tab}.npy")
            assert main([*args, backend, "--pass", tab, "-o", out]) == 0
    for tab in ("Image", "Buffer A"):
        got = np.load(tmp_path / f"compiled-{tab}.npy")
        assert got.tobytes() == np.load(tmp_path / f"numpy-{tab}.npy").tobytes()


def test_without_numba_exit_2_with_the_pip_line(tmp_path, capsys, monkeypatch):
    from glslcheck.backends.compiled_engine import engine

    monkeypatch.setattr(engine, "available", lambda: False)
    path = tmp_path / "Image.glsl"
    path.write_text(IMAGE)
    assert main(["render", str(path), "-o", str(tmp_path / "c.png"), "--backend", "compiled"]) == 2
    err = capsys.readouterr().err
    assert "pip install 'glslcheck[jit]'" in err and "Traceback" not in err


def test_bench_compiled_prints_its_figures(numba, gl):
    """benchmarks/bench_compiled.py, one quick round (timings are not asserted: see its
    docstring)."""
    import subprocess
    import sys
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    done = subprocess.run(
        [
            sys.executable,
            str(root / "benchmarks" / "bench_compiled.py"),
            "--lab-only",
            "--only",
            "07_final",
            "--size",
            "16x9",
            "--numpy-size",
            "16x9",
            "--repeat",
            "1",
        ],
        cwd=root,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert done.returncode == 0 and "Traceback" not in done.stderr, done.stderr[-2000:]
    for line in (
        "07_final",
        "geometric mean (CPU)",
        "geometric mean (wall)",
        "verify against GL: 1 of 1 match",
        "bit-identical to the NumPy render: 1 of 1",
        "load average at end",
    ):
        assert line in done.stdout, done.stdout


def test_bench_times_the_compiled_engine_beside_numpy(numba, gl, tmp_path, capsys):
    """`bench --backend compiled`: three more rows (1, 4, 16 samples) whose images are the NumPy
    float32 rows' bit for bit on this shader (test_render_writes_the_numpy_backends_image), so
    their errors against the reference are the same numbers."""
    import json

    path = tmp_path / "Image.glsl"
    path.write_text(IMAGE)
    assert (
        main(
            [
                "bench",
                str(path),
                "--size",
                "6x3",
                "--runs",
                "1",
                "--time",
                "0.7",
                "--format",
                "json",
                "--backend",
                "compiled",
            ]
        )
        == 0
    )
    rows = json.loads(capsys.readouterr().out)["rows"]
    compiled = {r["samples"]: r for r in rows if r["backend"] == "compiled"}
    numpy32 = {
        r["samples"]: r for r in rows if r["backend"] == "auto" and r["precision"] == "float32"
    }
    assert sorted(compiled) == [1, 4, 16] and len(rows) == 15
    for n, r in compiled.items():
        assert r["precision"] == "float32" and r["median_ms"] > 0
        assert (r["max_abs_error"], r["mean_abs_error"]) == (
            numpy32[n]["max_abs_error"],
            numpy32[n]["mean_abs_error"],
        )


def test_bench_compiled_unsupported_construct_exits_1_at_its_line(numba, gl, tmp_path, capsys):
    path = tmp_path / "Image.glsl"
    path.write_text(
        "void mainImage(out vec4 c, in vec2 f) {\n    c = vec4(1.0);\n    c.x = "
        "float(packHalf2x16(f));\n}\n"
    )
    assert main(["bench", str(path), "--size", "4x2", "--runs", "1", "--backend", "compiled"]) == 1
    err = capsys.readouterr().err
    assert (
        f"{path}:3:" in err
        and "not supported by the compiled engine yet" in err
        and "Traceback" not in err
    )


def test_bench_compiled_without_numba_exits_2_before_measuring(tmp_path, capsys, monkeypatch):
    from glslcheck.backends.compiled_engine import engine

    monkeypatch.setattr(engine, "available", lambda: False)
    path = tmp_path / "Image.glsl"
    path.write_text(IMAGE)
    assert (
        main(
            [
                "bench",
                str(path),
                "--size",
                "4x2",
                "--runs",
                "1",
                "--plot",
                str(tmp_path / "p.png"),
                "--backend",
                "compiled",
            ]
        )
        == 2
    )
    err = capsys.readouterr().err
    assert "pip install 'glslcheck[jit]'" in err and "Traceback" not in err
    assert not (tmp_path / "p.png").exists()


def test_verify_backends_compiled_gl_matches(numba, gl, tmp_path, capsys):
    """`verify --backends compiled,gl`: the compiled engine as the CPU side, against llvmpipe."""
    import json

    path = tmp_path / "Image.glsl"
    path.write_text(IMAGE)
    assert (
        main(
            [
                "verify",
                str(path),
                "--size",
                "16x9",
                "--time",
                "0.7",
                "--format",
                "json",
                "--backends",
                "compiled,gl",
            ]
        )
        == 0
    )
    frame = json.loads(capsys.readouterr().out)  # one frame: one object
    assert frame["match"] is True and frame["verdict"] == "match"


def test_verify_compiled_errors(gl, tmp_path, capsys, monkeypatch):
    """Unsupported construct: exit 1 at its line; --precision other than float32: exit 2; no
    numba: exit 2."""
    from glslcheck.backends.compiled_engine import engine

    path = tmp_path / "Image.glsl"
    path.write_text(IMAGE)
    assert (
        main(
            [
                "verify",
                str(path),
                "--size",
                "4x2",
                "--precision",
                "float64",
                "--backends",
                "compiled,gl",
            ]
        )
        == 2
    )
    assert "float32 only" in capsys.readouterr().err
    if engine.available():
        bad = tmp_path / "Bad.glsl"
        bad.write_text(
            "void mainImage(out vec4 c, in vec2 f) {\n    c = vec4(1.0);\n    c.x = "
            "float(packHalf2x16(f));\n}\n"
        )
        assert main(["verify", str(bad), "--size", "4x2", "--backends", "compiled,gl"]) == 1
        err = capsys.readouterr().err
        assert (
            f"{bad}:3:" in err
            and "not supported by the compiled engine yet" in err
            and "Traceback" not in err
        )
    monkeypatch.setattr(engine, "available", lambda: False)
    assert main(["verify", str(path), "--size", "4x2", "--backends", "compiled,gl"]) == 2
    err = capsys.readouterr().err
    assert "pip install 'glslcheck[jit]'" in err and "Traceback" not in err
