"""Settings from the environment are checked: a value outside what glslcheck supports is an
error that names the variable (exit 2), never minutes of work or a traceback later."""

from __future__ import annotations

import pytest

from glslcheck.backends.compiled_engine.engine import lanes_width
from glslcheck.backends.webgl.browser import call_timeout
from glslcheck.base.diagnostics import InputError


@pytest.mark.parametrize("value", ["3", "-7", "1000000", "8.0", "eight"])
def test_compiled_lanes_outside_the_supported_widths(monkeypatch, value):
    monkeypatch.setenv("GLSLCHECK_COMPILED_LANES", value)
    with pytest.raises(
        InputError, match=f"GLSLCHECK_COMPILED_LANES must be auto, 0 .* not {value!r}"
    ):
        lanes_width()


@pytest.mark.parametrize("value,width", [("0", 0), ("8", 8), (" 16 ", 16), ("auto", 0), ("", 0)])
def test_compiled_lanes_supported(monkeypatch, value, width):
    monkeypatch.setenv("GLSLCHECK_COMPILED_LANES", value)
    assert lanes_width() == width


@pytest.mark.parametrize("value", ["inf", "nan", "-1", "0", "1e9"])
def test_webgl_timeout_outside_its_range(monkeypatch, value):
    monkeypatch.setenv("GLSLCHECK_WEBGL_TIMEOUT", value)
    with pytest.raises(InputError, match="GLSLCHECK_WEBGL_TIMEOUT must be a number of seconds"):
        call_timeout()


def test_webgl_timeout_in_range(monkeypatch):
    monkeypatch.setenv("GLSLCHECK_WEBGL_TIMEOUT", "86400")
    assert call_timeout() == 86400.0
