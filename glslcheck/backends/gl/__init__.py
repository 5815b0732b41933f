"""The OpenGL backend: Shadertoy shaders rendered by the real driver (Mesa llvmpipe headless).

This package owns the GL side of `verify`: creating a context (`context.py`), compiling the
Shadertoy program and rendering it into a float framebuffer (`program.py`). The wrapper text
itself comes from `glslcheck.shadertoy.wrapper`.

Library API (the `render` / `verify` commands call only this):

    ctx = get_context()                    # process-wide; GLUnavailable (exit 2) with advice
    gl = compile_gl(shader)                # GlslError with user file:line on a driver error
    img = gl.render(size=(800, 450), time=0.0, frame=0, mouse=(0, 0, 0, 0), date=None,
                    time_delta=1/60, frame_rate=60.0, samples=1)
    # img: float32 (height, width, 4), top row first, unclamped RGBA32F values
    img = render_shader(shader, size=(400, 225))   # compile + render in one call
"""

from ..driver_log import driver_diagnostics, parse_driver_log
from .context import GLUnavailable, create_context, get_context, renderer_name
from .program import GLProgram, compile_gl, render_shader

__all__ = [
    "GLProgram",
    "GLUnavailable",
    "compile_gl",
    "create_context",
    "driver_diagnostics",
    "get_context",
    "parse_driver_log",
    "render_shader",
    "renderer_name",
]
