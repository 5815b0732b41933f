"""The interface every backend offers: its `Backend` record (what it supports, what it needs, how
it compiles one pass) and `Program`, the compiled shader `glslcheck.compile` returns.

Each backend package declares its record in its `backend.py` (numpy_engine, compiled_engine, gl,
webgl); glslcheck/backends/registry.py names them and imports a record only when it is asked for.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from ..base.precision import check_precision
from ..shadertoy.frame_inputs import FrameInputs, frame_inputs
from ..shadertoy.sources import Shader

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    import numpy as np


def _nothing_to_check() -> None:
    """A backend that needs nothing beyond glslcheck's own requirements."""


@dataclass(frozen=True, slots=True)
class Backend:
    """One backend: its name, what it supports and needs, and how it compiles a pass.

    `compile_pass(shader, tab)` compiles one pass ("Image", "Buffer A", ...) of a loaded Shader
    into the backend's own program, whose `render(size=..., ...)` gives float32 (height, width, 4)
    images. `program_text(program)` is the text that program runs (Python or GLSL).
    """

    name: str
    title: str  # how a page names it: "GL (Mesa llvmpipe)"
    called: str  # how a sentence names it: "the compiled engine"
    precisions: tuple[str, ...]  # the float types inside the shader it renders in
    multipass: bool  # Buffer A-D and channels.json (backends/multipass.py)
    lane_stats: bool  # render(stats=True) counts the lanes of each branch
    driver: (
        bool  # a real driver renders: its float is the driver's highp and render takes no precision
    )
    needs: str  # what it needs beyond glslcheck's own requirements ("" for nothing)
    compile_pass: Callable[[Shader, str], Any]
    program_text: Callable[[Any], str]
    # InputError (exit 2) with the install line when a package it imports is missing; checked
    # before a shader is read
    require: Callable[[], None] = _nothing_to_check
    # InputError (exit 2) when this machine cannot run it now (no OpenGL context, no browser)
    check_ready: Callable[[], None] = _nothing_to_check


class Program:
    """A compiled shader: `render(...)` gives float32 (height, width, 4) images."""

    def __init__(self, shader: Shader, backend: Backend, impl: Any) -> None:
        self.shader = shader
        self.backend = backend
        self.impl = impl

    @frame_inputs
    def render(
        self, inputs: FrameInputs, precision: str = "float32", stats: bool = False
    ) -> np.ndarray:
        """One frame; see glslcheck/backends/registry.py (the arguments: `shadertoy.FrameInputs`,
        then `precision` and `stats`)."""
        check_precision(precision)
        common = inputs.keywords()
        if self.backend.driver:
            if precision != "float32":
                raise ValueError(
                    f"the {self.backend.name.upper()} backend renders in float32 only "
                    "(the driver's highp)"
                )
            if stats:
                raise ValueError("stats=True needs backend='numpy'")
            return self.impl.render(**common)
        return self.impl.render(**common, precision=precision, stats=stats)

    def format_stats(self) -> str:
        if not self.backend.lane_stats:
            raise ValueError("lane statistics exist for backend='numpy' only")
        return self.impl.format_stats()

    @property
    def engine(self) -> str:
        """The engine that rendered the last frame: the default CPU program's "numpy",
        "compiled pixel" or "compiled lanes8" (backends/tiered.py), the compiled engine's
        "compiled pixel" or "compiled lanes8", else the backend's name."""
        engine = getattr(self.impl, "engine", None)
        if isinstance(engine, str):
            return engine
        mode = getattr(self.impl, "mode", None)
        return f"{self.backend.name} {mode}" if isinstance(mode, str) else self.backend.name

    @property
    def source(self) -> str:
        """The generated Python module (NumPy and compiled engines) or the GLSL program (GL,
        WebGL)."""
        return self.backend.program_text(self.impl)

    def __repr__(self) -> str:
        return f"<glslcheck.Program {self.shader.root!r} backend={self.backend.name}>"
