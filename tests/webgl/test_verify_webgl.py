"""`verify --against webgl`: NumPy against WebGL, driver-dependent pixels set apart; and it can
fail."""

from __future__ import annotations

import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from glslcheck.cli.main import main
from glslcheck.verification.drivers import closest_driver, driver_verdict, verify_against_webgl
from glslcheck.verification.verify import compile_backend

ROOT = Path(__file__).resolve().parents[2]
LAB = sorted(p for p in (ROOT / "lab_shaders").iterdir() if p.is_dir())
SIZE = (160, 90)


@pytest.mark.parametrize("path", LAB, ids=lambda p: p.name)
def test_every_lab_shader_matches_webgl(path, webgl, gl):
    (result,) = verify_against_webgl(path, size=SIZE, time=1.7)
    assert result.match, result.comparison.summary()
    # The two drivers' own differences are reported, never hidden: the verdict only differs from
    # the plain comparison where GL and WebGL disagree.
    if result.driver_pixels == 0:
        assert result.comparison is result.plain


def test_an_injected_difference_fails(webgl, gl, make_shader):
    # The NumPy side renders a shader whose colour differs by 0.05 in a 30x20 block (600 pixels,
    # over the mismatch budget of 14 at 160x90); neither driver has that colour, so the
    # driver-aware verdict must fail it.
    base = "void mainImage(out vec4 c, in vec2 f) { c = vec4(f / iResolution.xy, 0.5, 1.0);%s }"
    right = make_shader(base % "")
    wrong = make_shader(base % " if (f.x < 30.0 && f.y < 20.0) c.b += 0.05;")
    programs = (
        compile_backend(wrong, "numpy"),
        compile_backend(right, "webgl"),
        compile_backend(right, "gl"),
    )
    (result,) = verify_against_webgl(right, size=SIZE, programs=programs)
    assert not result.match
    assert result.comparison.mismatched_pixels == 600
    assert result.driver_pixels == 0


def test_the_closer_driver_is_taken_only_where_drivers_differ():
    numpy_img = np.zeros((1, 3, 4), np.float32)
    webgl_img = np.full((1, 3, 4), 0.5, np.float32)
    gl_img = np.zeros((1, 3, 4), np.float32)
    mask = np.array([[True, False, True]])
    out = closest_driver(numpy_img, webgl_img, gl_img, mask)
    assert out[0, :, 0].tolist() == [0.0, 0.5, 0.0]
    gl_img[0, 2] = np.nan  # NaN is never the closer value to a number
    assert closest_driver(numpy_img, webgl_img, gl_img, mask)[0, 2, 0] == 0.5
    nan_numpy = numpy_img.copy()
    nan_numpy[0, 2] = np.nan  # but NaN in NumPy and GL alike is no difference (compare's rule)
    assert np.isnan(closest_driver(nan_numpy, webgl_img, gl_img, mask)[0, 2, 0])
    verdict, plain, drivers = driver_verdict(
        numpy_img[..., :3], webgl_img[..., :3], gl_img[..., :3]
    )
    assert not plain.match and drivers.nan_numpy == 1


def test_cli_against_webgl(capsys, webgl, gl):
    assert main(["verify", "lab_shaders/07_final", "--against", "webgl", "--size", "160x90"]) == 0
    out = capsys.readouterr().out
    assert (
        "driver-dependent" in out
        and "NaN/Inf pixels   numpy 0, webgl 0" in out
        and "-> match" in out
    )
    assert (
        main(
            [
                "verify",
                "lab_shaders/01_spheres_procedural",
                "--backends",
                "gl,webgl",
                "--size",
                "16x9",
            ]
        )
        == 0
    )
    assert "gl 0, webgl 0" in capsys.readouterr().out
    assert (
        main(["verify", "lab_shaders/07_final", "--against", "webgl", "--backends", "gl,webgl"])
        == 2
    )


def test_render_backend_webgl(tmp_path, webgl):
    out = tmp_path / "w.npy"
    assert (
        main(
            [
                "render",
                "lab_shaders/07_final",
                "--backend",
                "webgl",
                "--size",
                "16x9",
                "-o",
                str(out),
            ]
        )
        == 0
    )
    img = np.load(out)
    assert img.shape == (9, 16, 4) and (img[..., 3] == 1.0).all()
    assert (
        main(
            [
                "render",
                "lab_shaders/07_final",
                "--backend",
                "webgl",
                "--precision",
                "float16",
                "-o",
                str(tmp_path / "x.png"),
            ]
        )
        == 2
    )


def _descendants(pid: int) -> set[int]:
    children: dict[int, list[int]] = {}
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        children.setdefault(int(fields[1]), []).append(int(stat.parent.name))
    out, todo = set(), [pid]
    while todo:
        for c in children.get(todo.pop(), []):
            out.add(c)
            todo.append(c)
    return out


def test_no_browser_outlives_its_process(webgl):
    # A child process starts the browser, prints the pids of its descendants (driver + Chromium's
    # processes) and exits normally: atexit must end every one of them.
    code = (
        f"import os, sys; sys.path.insert(0, {str(ROOT)!r})\n"
        "from tests.webgl.test_verify_webgl import _descendants\n"
        "from glslcheck.backends.webgl import get_browser\n"
        "get_browser(); print(' '.join(map(str, _descendants(os.getpid()))))\n"
    )
    proc = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=300, cwd=ROOT
    )
    assert proc.returncode == 0, proc.stderr
    pids = [int(p) for p in proc.stdout.split()]
    assert len(pids) >= 2  # Playwright's driver and at least the browser process
    # Processes end asynchronously once told to: give them a few seconds, not forever.
    deadline = time.monotonic() + 10.0
    while (alive := [p for p in pids if _running(p)]) and time.monotonic() < deadline:
        time.sleep(0.2)
    assert not alive, f"still running after exit: {alive}"


def _running(pid: int) -> bool:
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False
