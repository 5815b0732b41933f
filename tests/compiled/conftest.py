"""The compiled engine's tests need numba (the optional `jit` extra): skipped without it on a
developer machine, a failure on CI, as tests/conftest.py's `jit_kernels`."""

from __future__ import annotations

import os

import pytest


@pytest.fixture(scope="session")
def numba():
    from glslcheck.compiled_backend.engine import available

    if not available():
        if os.environ.get("CI"):
            pytest.fail("numba is required on CI: pip install -e '.[jit]' (make setup does)")
        pytest.skip("no numba on this machine (developer machine without it); CI fails instead")
