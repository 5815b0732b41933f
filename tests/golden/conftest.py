"""Golden-image switches: `UPDATE_GOLDEN=1 pytest tests/golden` (or `pytest tests/golden
--update-golden`) re-renders every golden PNG with the GL backend instead of comparing.

The pytest option only exists when pytest loads this file at start-up, i.e. when tests/golden
(or a file in it) is on the command line; the environment variable works from anywhere.
"""

from __future__ import annotations

import os

import pytest


def pytest_addoption(parser):
    parser.addoption(
        "--update-golden",
        action="store_true",
        default=False,
        help="re-render the golden images of tests/golden with the GL backend",
    )


@pytest.fixture(scope="session")
def update_golden(request) -> bool:
    try:
        option = bool(request.config.getoption("--update-golden"))
    except ValueError:  # the option was not registered (this conftest loaded late)
        option = False
    return option or os.environ.get("UPDATE_GOLDEN", "") not in ("", "0")
