"""No command writes over a file it reads: an output named like one of the shader's tabs,
its channels.json or a texture is refused (exit 2) and the file stays as it was."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
from PIL import Image

IMAGE = "void mainImage(out vec4 c, in vec2 p) {\n    c = texture(iChannel0, p / 8.0);\n}\n"


def _glslcheck(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "glslcheck", *args],
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=300,
    )


def _shader(tmp_path: Path) -> Path:
    folder = tmp_path / "shader"
    folder.mkdir()
    (folder / "Image.glsl").write_text(IMAGE)
    Image.fromarray(np.full((2, 2, 4), 200, np.uint8)).save(folder / "tex.png")
    (folder / "channels.json").write_text(
        json.dumps({"Image": {"iChannel0": {"texture": "tex.png"}}})
    )
    return folder


def _contents(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())}


def test_render_transpile_and_verify_never_overwrite_what_they_read(tmp_path):
    folder = _shader(tmp_path)
    before = _contents(folder)
    cases = [
        ("render", "shader", "-o", "shader/tex.png", "--size", "8x8"),
        ("transpile", "shader/Image.glsl", "-o", "shader/Image.glsl"),
        ("transpile", "shader", "-o", "shader/channels.json"),
        ("verify", "shader", "--size", "8x8", "--diff", "shader/tex.png"),
    ]
    for case in cases:
        done = _glslcheck(*case, cwd=tmp_path)
        assert done.returncode == 2, (case, done.stderr)
        assert "which the shader is read from; name another file" in done.stderr, (
            case,
            done.stderr,
        )
        assert _contents(folder) == before, case


def test_an_output_beside_the_inputs_is_written(tmp_path):
    _shader(tmp_path)
    done = _glslcheck("render", "shader", "-o", "shader/out.png", "--size", "8x8", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "shader" / "out.png").is_file()
