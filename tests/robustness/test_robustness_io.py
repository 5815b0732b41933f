"""Hostile and unlucky input and output files: special files as input, symlink loops,
output names no writer knows, a full disk, Ctrl-C while an output is written. Each ends in exit 2
with a message naming the path, never a hang, a traceback or a damaged file."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from glslcheck.base import images
from glslcheck.base.images import GifWriter, save_image
from glslcheck.cli.main import main

SHADER = "void mainImage(out vec4 c, in vec2 p) { c = vec4(p / iResolution.xy, 0.5, 1.0); }\n"


def _glslcheck(*args: str, timeout: float = 60, **kwargs) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "glslcheck", *args],
        capture_output=True,
        text=True,
        timeout=timeout,
        **kwargs,
    )


@pytest.fixture
def shader(tmp_path: Path) -> Path:
    path = tmp_path / "Image.glsl"
    path.write_text(SHADER)
    return path


def test_a_fifo_is_refused_at_once(tmp_path: Path):
    fifo = tmp_path / "Image.glsl"
    os.mkfifo(fifo)
    for command in ("check", "lint", "render"):
        proc = _glslcheck(
            command, str(fifo), timeout=60
        )  # it blocked forever: the timeout fails it
        assert proc.returncode == 2, proc.stderr
        assert f"{fifo}: error: is a FIFO (named pipe), not a regular file" in proc.stderr


def test_dev_zero_is_refused_not_read():
    proc = _glslcheck("check", "/dev/zero", timeout=60)  # it read 3.7 GB before
    assert proc.returncode == 2
    assert "/dev/zero: error: is a character device, not a regular file" in proc.stderr


def test_reading_stops_at_the_cap_whatever_the_size_says(tmp_path: Path, monkeypatch):
    from glslcheck.shadertoy import sources

    big = tmp_path / "Image.glsl"
    big.write_bytes(b"// x\n" * 100)
    monkeypatch.setattr(sources, "MAX_FILE_BYTES", 64)
    with pytest.raises(sources.InputError, match="up to 64 bytes"):
        sources.read_source(big)


def test_a_symlink_loop_says_what_it_is(tmp_path: Path):
    (tmp_path / "a.glsl").symlink_to(tmp_path / "b.glsl")
    (tmp_path / "b.glsl").symlink_to(tmp_path / "a.glsl")
    for command in ("check", "lint"):
        proc = _glslcheck(command, str(tmp_path / "a.glsl"))
        assert proc.returncode == 2
        assert "loop of symbolic links" in proc.stderr and "no such file" not in proc.stderr


def test_verify_diff_without_an_extension_is_refused_before_rendering(
    shader: Path, tmp_path: Path, capsys
):
    assert main(["verify", str(shader), "--diff", str(tmp_path / "bad")]) == 2
    err = capsys.readouterr().err
    assert f"{tmp_path / 'bad'}: error: the diff image must be a .png file" in err


def test_bench_plot_with_an_unknown_extension_is_refused_before_measuring(
    shader: Path, tmp_path: Path, capsys
):
    assert main(["bench", str(shader), "--plot", str(tmp_path / "x.xyz")]) == 2
    assert "x.xyz: error: the plot must be a .png file" in capsys.readouterr().err


def test_lint_to_a_full_disk(shader: Path):
    with open("/dev/full", "w") as full:
        proc = subprocess.run(
            [sys.executable, "-m", "glslcheck", "lint", str(shader)],
            stdout=full,
            stderr=subprocess.PIPE,
            text=True,
            timeout=60,
        )
    assert proc.returncode == 2
    assert "cannot write to standard output (No space left on device)" in proc.stderr
    assert "Traceback" not in proc.stderr and "Exception ignored" not in proc.stderr


def _leftovers(folder: Path) -> list[str]:
    return [p.name for p in folder.iterdir() if p.name.startswith(".")]


def test_ctrl_c_while_a_gif_is_written_leaves_the_old_file(
    shader: Path, tmp_path: Path, monkeypatch, capsys
):
    gif = tmp_path / "anim.gif"
    gif.write_bytes(b"the old animation")
    real_add = GifWriter.add

    def add(self, img):
        if self.frames == 2:
            raise KeyboardInterrupt
        real_add(self, img)

    monkeypatch.setattr(GifWriter, "add", add)
    assert main(["render", str(shader), "-o", str(gif), "--frames", "4", "--size", "16x8"]) == 2
    assert "interrupted" in capsys.readouterr().err
    assert gif.read_bytes() == b"the old animation"
    assert _leftovers(tmp_path) == []


def test_a_failed_image_write_leaves_the_old_file(tmp_path: Path, monkeypatch):
    from PIL import Image

    png = tmp_path / "out.png"
    png.write_bytes(b"the old image")

    def failing_save(self, fp, format=None, **params):
        Path(fp).write_bytes(b"half an image")
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(Image.Image, "save", failing_save)
    with pytest.raises(images.InputError, match="cannot write the image .No space left on device"):
        save_image(np.zeros((4, 4, 4), np.float32), png)
    assert png.read_bytes() == b"the old image"
    assert _leftovers(tmp_path) == []


def test_render_writes_an_image_atomically(shader: Path, tmp_path: Path):
    png = tmp_path / "out.png"
    png.write_bytes(b"old")
    assert main(["render", str(shader), "-o", str(png), "--size", "8x4"]) == 0
    assert png.read_bytes().startswith(b"\x89PNG")
    assert _leftovers(tmp_path) == []
    assert oct(png.stat().st_mode & 0o777) == oct(
        0o666 & ~_umask()
    )  # as any new file, not mkstemp's 0600


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def test_gif_frames_are_written_as_they_come(tmp_path: Path):
    """render --frames streams: each frame is on disk before the next is rendered."""
    rng = np.random.default_rng(1)
    sizes = []
    with GifWriter(tmp_path / "anim.gif", fps=30) as gif:
        tmp = next(p for p in tmp_path.iterdir() if p.name.startswith(".anim.gif"))
        for _ in range(4):
            gif.add(rng.random((64, 96, 4)).astype(np.float32))  # noise: about 6 KB per frame
            gif._file.flush()
            sizes.append(tmp.stat().st_size)
    assert all(b > a for a, b in zip(sizes, sizes[1:])), sizes
    from PIL import Image

    with Image.open(tmp_path / "anim.gif") as im:
        assert im.n_frames == 4


def test_gif_frames_decode_as_pillow_writes_them(tmp_path: Path):
    """The frame-by-frame writer gives the same pictures as Pillow's own save_all."""
    from PIL import Image

    rng = np.random.default_rng(2)
    frames = [rng.random((20, 30, 4)).astype(np.float32) for _ in range(3)]
    frames[1][:] = 0.25
    with GifWriter(tmp_path / "ours.gif", fps=25) as gif:
        for f in frames:
            gif.add(f)
    pil = [Image.fromarray(images.quantise(f[..., :3]), "RGB") for f in frames]
    pil[0].save(tmp_path / "pillow.gif", save_all=True, append_images=pil[1:], duration=40, loop=0)
    with Image.open(tmp_path / "ours.gif") as a, Image.open(tmp_path / "pillow.gif") as b:
        assert a.n_frames == b.n_frames == 3 and a.info["loop"] == 0
        for i in range(3):
            a.seek(i)
            b.seek(i)
            assert a.info["duration"] == b.info["duration"] == 40
            assert np.array_equal(np.asarray(a.convert("RGB")), np.asarray(b.convert("RGB")))


def test_an_output_that_is_not_a_regular_file_is_written_not_replaced(tmp_path: Path):
    fifo = tmp_path / "out.npy"
    os.mkfifo(fifo)
    import threading

    got = []
    reader = threading.Thread(target=lambda: got.append(open(fifo, "rb").read()))
    reader.start()
    save_image(np.zeros((2, 2, 4), np.float32), fifo)
    reader.join(timeout=30)
    assert got and got[0].startswith(b"\x93NUMPY")
    assert fifo.is_fifo()  # still the FIFO: nothing was renamed over it (as /dev/null must stay)


def test_an_output_symlink_is_written_through_and_keeps_the_mode(tmp_path: Path):
    real = tmp_path / "real.png"
    real.write_bytes(b"old")
    real.chmod(0o640)
    link = tmp_path / "link.png"
    link.symlink_to(real)
    save_image(np.zeros((2, 2, 4), np.float32), link)
    assert link.is_symlink() and real.read_bytes().startswith(b"\x89PNG")
    assert real.stat().st_mode & 0o777 == 0o640
