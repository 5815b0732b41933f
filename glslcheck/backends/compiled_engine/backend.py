"""The compiled engine's Backend record: float32, every pass (Buffers and channels), numba
needed."""

from __future__ import annotations

from ..interface import Backend


def _compile_pass(shader, tab: str):
    from .engine import compile_compiled

    return compile_compiled(shader, tab=tab)


def _require() -> None:
    from .engine import require_numba

    require_numba()


BACKEND = Backend(
    name="compiled",
    title="compiled engine (numba)",
    called="the compiled engine",
    precisions=("float32",),
    multipass=True,
    lane_stats=False,
    driver=False,
    needs="numba",
    compile_pass=_compile_pass,
    program_text=lambda program: program.source,
    require=_require,
    check_ready=_require,
)
