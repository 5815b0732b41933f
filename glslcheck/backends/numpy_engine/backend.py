"""The NumPy engine's Backend record: every precision, Buffer passes and lane statistics."""

from __future__ import annotations

from ..interface import Backend


def _compile_pass(shader, tab: str):
    from .program import compile_numpy

    return compile_numpy(shader, tab if tab != "Image" else None)


BACKEND = Backend(
    name="numpy",
    title="NumPy (CPU)",
    called="the NumPy backend",
    precisions=("float16", "float32", "float64"),
    multipass=True,
    lane_stats=True,
    driver=False,
    needs="",
    compile_pass=_compile_pass,
    program_text=lambda program: program.source,
)
