"""The backends by name, and the public Python API: compile a Shadertoy shader for a backend and
render frames.

    import glslcheck
    prog = glslcheck.compile("lab_shaders/07_final")   # or backend="numpy", "gl", "webgl",
                                                       # "compiled"
    img = prog.render(size=(800, 450), time=0.0, frame=0, mouse=(0, 0, 0, 0), date=None,
                      precision="float32", samples=1)
    # img: float32 numpy array (height, width, 4), top row first, values as the shader wrote them
    #      (not clamped); the Image pass has alpha 1, discarded pixels are (0, 0, 0, 0).

`path` is a tab file, a folder of tabs (see glslcheck/shadertoy/sources.py) or an already loaded
`Shader`. `compile` raises GlslError (with file:line:col diagnostics) when the shader does not
parse, check or compile, InputError when the path cannot be read, and GLUnavailable (an
InputError) for backend="gl" without an OpenGL context (WebGLUnavailable for backend="webgl"
without headless Chromium: glslcheck/backends/webgl; InputError for backend="compiled" without
numba).

`render` also takes `time_delta` (iTimeDelta, default 1/60) and `frame_rate` (iFrameRate,
default 60), as the GL backend does. `precision` is the float type inside the shader:
"float32" (GLSL highp, the default), "float16" (mediump emulation) or "float64" (a reference);
a backend renders in its record's `precisions` only (GL, WebGL and the compiled engine: "float32").
`samples` = k*k renders a k x k grid of sub-pixel positions per pixel and averages them (the same
grid on every backend). With backend="numpy", `render(..., stats=True)` counts the lanes that ran
each function, branch and loop body; `prog.format_stats()` prints them.

The default, backend="auto" (backends/tiered.py), renders with the NumPy backend and moves a
shader's frames to the compiled engine once they have cost what compiling it is expected to,
where the two give the same bits; it takes every option the NumPy backend takes.

`names()` lists the backends without importing any of them; `get(name)` imports the one asked for
and returns its Backend record (glslcheck/backends/interface.py).
"""

from __future__ import annotations

import importlib
import os

from ..shadertoy.sources import Shader, load_shader
from .interface import Backend, Program

# name -> the module that declares its Backend record (as BACKEND), in the order choices list them
BACKENDS = {
    "auto": "glslcheck.backends.tiered",
    "numpy": "glslcheck.backends.numpy_engine.backend",
    "gl": "glslcheck.backends.gl.backend",
    "webgl": "glslcheck.backends.webgl.backend",
    "compiled": "glslcheck.backends.compiled_engine.backend",
}
# what render, verify, report, bench and grade run unless told: the CPU program they check
# (the NumPy backend, then the compiled engine where that gives the same bits: tiered.py)
DEFAULT = "auto"
REFERENCE_DRIVER = "gl"  # the real driver verify compares with by default and bench times against


def names() -> tuple[str, ...]:
    """Every backend's name, the default ("auto") first."""
    return tuple(BACKENDS)


def get(name: str) -> Backend:
    """The Backend record of `name`; ValueError naming the backends there are."""
    if name not in BACKENDS:
        raise ValueError(f"backend must be one of {', '.join(BACKENDS)}, not {name!r}")
    return importlib.import_module(BACKENDS[name]).BACKEND


def backend_program(shader: Shader, backend: Backend, output: str = "Image"):
    """The backend's own program for the `output` pass of a loaded shader: one pass compiled by
    the backend, or the passes of a shader with buffers or channels run frame after frame
    (backends/multipass.py)."""
    from ..shadertoy.channels import needs_passes

    if backend.multipass and (output != "Image" or needs_passes(shader)):
        from .multipass import MultipassProgram

        return MultipassProgram(shader, backend, output)
    return backend.compile_pass(shader, "Image")


def compile(
    path: str | os.PathLike | Shader, backend: str = "auto", output: str = "Image"
) -> Program:  # noqa: A001
    """Load, check and compile a shader for `backend` (one of `names()`). A shader with Buffer
    tabs, a channels.json or iChannel reads runs its passes frame after frame
    (backends/multipass.py); `output` chooses the pass `render` returns ("Buffer A", ...)."""
    record = get(backend)
    record.require()
    if output != "Image" and not record.multipass:
        from ..base.diagnostics import InputError

        raise InputError(
            f"error: --backend {record.name} renders the Image pass only, not {output!r}"
        )
    shader = path if isinstance(path, Shader) else load_shader(path)
    return Program(shader, record, backend_program(shader, record, output))
