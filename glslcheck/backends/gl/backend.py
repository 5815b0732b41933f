"""The OpenGL backend's Backend record: the driver's float32, Buffer passes, an OpenGL context."""

from __future__ import annotations

from ..interface import Backend


def _compile_pass(shader, tab: str):
    from .program import compile_gl

    return compile_gl(shader, tab=tab)


def _check_ready() -> None:
    from .context import get_context

    get_context()


BACKEND = Backend(
    name="gl",
    title="GL (Mesa llvmpipe)",
    called="the GL backend",
    precisions=("float32",),
    multipass=True,
    lane_stats=False,
    driver=True,
    needs="an OpenGL context",
    compile_pass=_compile_pass,
    program_text=lambda program: program.program.text,
    check_ready=_check_ready,
)
