"""Fixtures of the WebGL tests: one headless Chromium for the whole session.

`webgl` is the process-wide browser (glslcheck.backends.webgl.get_browser), started once and
closed when the session ends. Without Chromium or Playwright the tests that need it are skipped
on a developer machine (and say so) but FAIL on CI (any non-empty `CI`), as tests/conftest.py
does for OpenGL.
"""

from __future__ import annotations

import os

import pytest


@pytest.fixture(scope="session")
def webgl():
    from glslcheck.backends.webgl import WebGLUnavailable, close_browser, get_browser

    try:
        browser = get_browser()
    except WebGLUnavailable as e:
        if os.environ.get("CI"):
            pytest.fail(f"headless Chromium with WebGL 2 is required on CI: {e}")
        pytest.skip(f"no headless Chromium with WebGL 2 on this machine ({e}); CI fails instead")
    yield browser
    close_browser()
