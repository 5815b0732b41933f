"""The WebGL 2 backend's Backend record: the driver's float32, Buffer passes, headless Chromium."""

from __future__ import annotations

from ..interface import Backend


def _compile_pass(shader, tab: str):
    from .program import compile_webgl

    return compile_webgl(shader, tab=tab)


def _check_ready() -> None:
    from .browser import get_browser

    get_browser()


BACKEND = Backend(
    name="webgl",
    title="WebGL (ANGLE, SwiftShader)",
    called="the WebGL backend",
    precisions=("float32",),
    multipass=True,
    lane_stats=False,
    driver=True,
    needs="headless Chromium",
    compile_pass=_compile_pass,
    program_text=lambda program: program.program.text,
    check_ready=_check_ready,
)
