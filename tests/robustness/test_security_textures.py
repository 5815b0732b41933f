"""Textures come only from the shader's folder and only from regular files, and a hostile image
is an error at the binding, never a traceback or a hang."""

from __future__ import annotations

import json
import os
import struct
import subprocess
import sys
import zlib
from pathlib import Path

import pytest

IMAGE = "void mainImage(out vec4 c, in vec2 p) {\n    c = texture(iChannel0, p / 8.0);\n}\n"


def _png(width: int, height: int, rows: bytes) -> bytes:
    def chunk(kind: bytes, data: bytes) -> bytes:
        return (
            struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
        )

    header = struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)  # 8-bit grey
    return (
        b"\x89PNG\r\n\x1a\n"
        + chunk(b"IHDR", header)
        + chunk(b"IDAT", zlib.compress(rows))
        + chunk(b"IEND", b"")
    )


def _shader(folder: Path, texture: str) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "Image.glsl").write_text(IMAGE)
    (folder / "channels.json").write_text(
        json.dumps({"Image": {"iChannel0": {"texture": texture}}})
    )
    return folder


def _render(folder: Path, tmp_path: Path) -> subprocess.CompletedProcess:
    return subprocess.run(
        [
            sys.executable,
            "-m",
            "glslcheck",
            "render",
            str(folder),
            "--size",
            "8x8",
            "-o",
            str(tmp_path / "out.png"),
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )


def test_a_texture_outside_the_shader_folder_is_refused(tmp_path):
    secret = tmp_path / "secret.png"
    secret.write_bytes(_png(2, 2, b"\x00\x01\x02" * 2))
    folder = tmp_path / "shader"
    (folder / "inside").mkdir(parents=True)
    (folder / "inside" / "link.png").symlink_to(secret)
    for name in (str(secret), "../secret.png", "inside/../../secret.png", "inside/link.png"):
        done = _render(_shader(folder, name), tmp_path)
        assert done.returncode == 2, (name, done.stderr)
        assert (
            f"{name!r} is outside the shader's folder" in done.stderr
            and "Traceback" not in done.stderr
        )
        assert not (tmp_path / "out.png").exists()


def test_a_texture_inside_the_folder_still_renders(tmp_path):
    folder = tmp_path / "shader"
    (folder / "media").mkdir(parents=True)
    (folder / "media" / "tex.png").write_bytes(_png(2, 2, b"\x00\x10\x20" * 2))
    done = _render(_shader(folder, "media/tex.png"), tmp_path)
    assert done.returncode == 0, done.stderr


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="named pipes are a POSIX notion")
def test_a_fifo_as_a_texture_does_not_hang(tmp_path):
    folder = tmp_path / "shader"
    folder.mkdir()
    os.mkfifo(folder / "pipe.png")
    done = _render(_shader(folder, "pipe.png"), tmp_path)
    assert done.returncode == 2 and "pipe.png' is not a regular file" in done.stderr


@pytest.mark.parametrize(
    "name, data",
    [
        ("bomb.png", _png(30000, 30000, b"\x00" * 31)),  # 900 M pixels announced, a few bytes sent
        ("cut.png", _png(4, 4, b"\x00\x01\x02\x03\x04" * 4)[:-30]),
        ("damaged.tif", b"II*\x00\x08\x00\x00\x00\xff\xff" + b"\x00" * 40),
    ],
)
def test_a_hostile_image_is_an_error_at_its_binding(tmp_path, name, data):
    folder = tmp_path / "shader"
    folder.mkdir()
    (folder / name).write_bytes(data)
    done = _render(_shader(folder, name), tmp_path)
    assert done.returncode == 2, done.stderr
    assert '"Image"."iChannel0"."texture": cannot read the image' in done.stderr
    assert "Traceback" not in done.stderr
