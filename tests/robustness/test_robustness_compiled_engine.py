"""Robustness: the compiled engine honours the frame budget and Ctrl-C.

Its frames run in numba's machine code, which never returns to the interpreter until the frame
is done: a shader of three nested loops of 99,999 passes would run for as long as it is left.
The calling thread only waits, so `--frame-budget` ends the frame with a located error (exit 1),
SIGINT ends the command with "interrupted" (exit 2); the process exits at once although numba's
threads cannot be stopped. `verify --backends compiled,gl` stops the loops as llvmpipe does.
Every run here shares one numba cache (numba's compile takes seconds: the first run compiles,
the others load).
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

NESTED = """void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    float s = 0.0;
    for (int i = 0; i < 99999; i++) {
        for (int j = 0; j < 99999; j++) {
            for (int k = 0; k < 99999; k++) {
                s += sin(float(i + j + k));
            }
        }
    }
    fragColor = vec4(s, 0.0, 0.0, 1.0);
}
"""
TIMEOUT = 90  # seconds a run may take before the test fails (a cold compile takes a few)
BUDGET = 2.0


@pytest.fixture(scope="module")
def setup(tmp_path_factory, numba) -> tuple[Path, dict]:
    folder = tmp_path_factory.mktemp("nested")
    shader = folder / "Image.glsl"
    shader.write_text(NESTED)
    cache = folder / "numba"
    cache.mkdir(mode=0o700)
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache), GLSLCHECK_COMPILED_LANES="0")
    env.pop("GLSLCHECK_FRAME_SECONDS", None)
    return shader, env


def _glslcheck(*args: str) -> list[str]:
    return [sys.executable, "-m", "glslcheck", *args]


# glslcheck with Python's Ctrl-C handler even when this test runs where SIGINT is ignored (a
# shell's background job), which a child would inherit
INTERRUPTIBLE = (
    "import runpy, signal; signal.signal(signal.SIGINT, signal.default_int_handler); "
    "runpy.run_module('glslcheck', run_name='__main__')"
)


def test_the_frame_budget_ends_a_compiled_frame(setup, tmp_path):
    shader, env = setup
    t0 = time.monotonic()
    done = subprocess.run(
        _glslcheck(
            "render",
            str(shader),
            "--backend",
            "compiled",
            "--size",
            "16x8",
            "--frame-budget",
            str(BUDGET),
            "-o",
            str(tmp_path / "out.png"),
        ),
        env=env,
        capture_output=True,
        text=True,
        timeout=TIMEOUT,
        check=False,
    )
    elapsed = time.monotonic() - t0
    assert done.returncode == 1, done.stderr
    assert f"{shader}:1:1: error: the frame was still rendering after {BUDGET:g} s" in done.stderr
    assert "--frame-budget SECONDS" in done.stderr and "Traceback" not in done.stderr
    assert elapsed < TIMEOUT / 3, elapsed
    assert not (tmp_path / "out.png").exists()


def test_ctrl_c_ends_a_compiled_frame(setup, tmp_path):
    shader, env = setup
    warm = _glslcheck(
        "render",
        str(shader),
        "--backend",
        "compiled",
        "--size",
        "1x1",
        "--frame-budget",
        "1",
        "-o",
        str(tmp_path / "warm.png"),
    )
    subprocess.run(warm, env=env, capture_output=True, timeout=TIMEOUT, check=False)
    proc = subprocess.Popen(
        [
            sys.executable,
            "-c",
            INTERRUPTIBLE,
            "render",
            str(shader),
            "--backend",
            "compiled",
            "--size",
            "16x8",
            "-o",
            str(tmp_path / "out.png"),
        ],
        env=env,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        time.sleep(5)  # the module loads from the cache warmed above: the frame is running by now
        assert proc.poll() is None, proc.communicate()[1]
        t0 = time.monotonic()
        proc.send_signal(signal.SIGINT)
        err = proc.communicate(timeout=TIMEOUT)[1]
        elapsed = time.monotonic() - t0
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert proc.returncode == 2, err
    assert err.strip() == "glslcheck: interrupted"
    assert elapsed < 5, elapsed


def test_verify_compiled_against_gl_stops_loops_as_llvmpipe(setup, gl):
    """verify makes the compiled engine stop loops as llvmpipe does (65,535 passes a pixel, as
    the NumPy side): the frame that runs for ever in `render` answers at once, and matches."""
    shader, env = setup
    t0 = time.monotonic()
    done = subprocess.run(
        _glslcheck(
            "verify",
            str(shader),
            "--backends",
            "compiled,gl",
            "--size",
            "16x8",
            "--frame-budget",
            str(BUDGET * 10),
        ),
        env=env,
        capture_output=True,
        text=True,
        timeout=TIMEOUT,
        check=False,
    )
    elapsed = time.monotonic() - t0
    assert done.returncode == 0, done.stdout + done.stderr
    assert "verify: match" in done.stdout
    for line in (4, 5, 6):
        assert f"Image.glsl:{line}: this loop reached llvmpipe's limit" in done.stdout
    assert elapsed < TIMEOUT / 3, elapsed
