"""The public Python API: compile a Shadertoy shader for a backend and render frames.

    import glslcheck
    prog = glslcheck.compile("lab_shaders/07_final", backend="numpy")   # or "gl", "webgl"
    img = prog.render(size=(800, 450), time=0.0, frame=0, mouse=(0, 0, 0, 0), date=None,
                      precision="float32", samples=1)
    # img: float32 numpy array (height, width, 4), top row first, values as the shader wrote them
    #      (not clamped); the Image pass has alpha 1, discarded pixels are (0, 0, 0, 0).

`path` is a tab file, a folder of tabs (see glslcheck/shadertoy/sources.py) or an already loaded
`Shader`. `compile` raises GlslError (with file:line:col diagnostics) when the shader does not
parse, check or compile, InputError when the path cannot be read, and GLUnavailable (an
InputError) for backend="gl" without an OpenGL context (WebGLUnavailable for backend="webgl"
without headless Chromium: glslcheck/webgl_backend).

`render` also takes `time_delta` (iTimeDelta, default 1/60) and `frame_rate` (iFrameRate,
default 60), as the GL backend does. `precision` is the float type inside the shader:
"float32" (GLSL highp, the default), "float16" (mediump emulation) or "float64" (a reference);
the GL backend only has "float32". `samples` = k*k renders a k x k grid of sub-pixel positions
per pixel and averages them (the same grid on both backends). With backend="numpy",
`render(..., stats=True)` counts the lanes that ran each function, branch and loop body;
`prog.format_stats()` prints them.
"""

from __future__ import annotations

import os
from typing import Any

import numpy as np

from ..base.precision import check_precision
from ..shadertoy.frame_inputs import FrameInputs, frame_inputs
from ..shadertoy.sources import Shader, load_shader

BACKENDS = ("numpy", "gl", "webgl")


class Program:
    """A compiled shader: `render(...)` gives float32 (height, width, 4) images."""

    def __init__(self, shader: Shader, backend: str, impl: Any) -> None:
        self.shader = shader
        self.backend = backend
        self.impl = impl

    @frame_inputs
    def render(self, inputs: FrameInputs, precision: str = "float32", stats: bool = False) -> np.ndarray:
        """One frame; see the module docstring (the arguments: `shadertoy.FrameInputs`, then
        `precision` and `stats`)."""
        check_precision(precision)
        common = inputs.keywords()
        if self.backend in ("gl", "webgl"):
            if precision != "float32":
                raise ValueError(f"the {self.backend.upper()} backend renders in float32 only (the driver's highp)")
            if stats:
                raise ValueError("stats=True needs backend='numpy'")
            return self.impl.render(**common)
        return self.impl.render(**common, precision=precision, stats=stats)

    def format_stats(self) -> str:
        if self.backend != "numpy":
            raise ValueError("lane statistics exist for backend='numpy' only")
        return self.impl.format_stats()

    @property
    def source(self) -> str:
        """The generated Python module (backend='numpy') or the GLSL program (backend='gl')."""
        return self.impl.source if self.backend == "numpy" else self.impl.program.text

    def __repr__(self) -> str:
        return f"<glslcheck.Program {self.shader.root!r} backend={self.backend}>"


def compile(path: str | os.PathLike | Shader, backend: str = "numpy", output: str = "Image") -> Program:  # noqa: A001
    """Load, check and compile a shader for `backend` ("numpy" or "gl"). A shader with Buffer
    tabs, a channels.json or iChannel reads runs its passes frame after frame (shadertoy/channels.py);
    `output` chooses the pass `render` returns ("Buffer A", ...)."""
    if backend not in BACKENDS:
        raise ValueError(f"backend must be one of {', '.join(BACKENDS)}, not {backend!r}")
    shader = path if isinstance(path, Shader) else load_shader(path)
    from ..shadertoy.channels import MultipassProgram, needs_passes

    if output != "Image" or needs_passes(shader):
        return Program(shader, backend, MultipassProgram(shader, backend, output))
    if backend == "gl":
        from .gl import compile_gl

        return Program(shader, "gl", compile_gl(shader))
    if backend == "webgl":
        from .webgl import compile_webgl

        return Program(shader, "webgl", compile_webgl(shader))
    from .numpy_engine.program import compile_numpy

    return Program(shader, "numpy", compile_numpy(shader))
