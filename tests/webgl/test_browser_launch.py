"""An installed Chromium that fails to start (here: under an address-space limit, which it cannot
start under) is reported as a failed start with its cause, never as a missing Chromium."""

from __future__ import annotations

import os
import resource
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
LIMIT = 4_000_000 * 1024  # bytes: `ulimit -v 4000000`, enough for everything glslcheck does


def _limited():
    resource.setrlimit(resource.RLIMIT_AS, (LIMIT, LIMIT))


def test_chromium_under_an_address_space_limit_is_a_failed_start_not_a_missing_browser(webgl):
    from glslcheck.backends.webgl import chromium_path

    executable = chromium_path()
    done = subprocess.run(
        [sys.executable, "-m", "glslcheck", "check", "lab_shaders/07_final", "--webgl"],
        cwd=ROOT,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
        capture_output=True,
        text=True,
        timeout=300,
        preexec_fn=_limited,
    )
    if done.returncode == 0:
        pytest.skip("this Chromium starts under the limit")
    assert done.returncode == 2 and "Traceback" not in done.stderr, done.stderr
    assert f"headless Chromium ({executable}) failed to start: " in done.stderr
    assert f"address-space limit (ulimit -v {LIMIT // 1024})" in done.stderr
    assert "install" not in done.stderr and "no Chromium" not in done.stderr
