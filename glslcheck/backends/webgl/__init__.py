"""The WebGL 2 backend: Shadertoy shaders rendered and compiled where Shadertoy really runs,
in a browser (headless Chromium, ANGLE over SwiftShader).

This package owns the browser (`browser.py`: one per process, driven by Playwright), the page
code (`harness.js`: the WebGL2 context, Shadertoy's vertex stage, the RGBA32F target) and the
Python side of compiling and rendering (`program.py`). The wrapper text comes from
`glslcheck.shadertoy.wrapper`, as for the GL backend.

Library API (`render --backend webgl`, `verify --against webgl`, `check --webgl` call only this):

    webgl = compile_webgl(shader)            # GlslError with user file:line on an ANGLE error
    img = webgl.render(size=(160, 90), time=0.0, samples=1)   # as GLProgram.render
    webgl_diagnostics(shader, "Image")      # ANGLE's errors, [] when it compiles
    get_browser().info["renderer"]           # 'ANGLE (Google, Vulkan 1.3.0 (SwiftShader ...'
    close_browser()                          # also at exit
"""

from .browser import (
    Browser,
    WebGLUnavailable,
    browser_started,
    chromium_path,
    close_browser,
    get_browser,
)
from .program import (
    WebGLProgram,
    angle_diagnostics,
    compile_webgl,
    render_shader,
    webgl_diagnostics,
)

__all__ = [
    "Browser",
    "WebGLProgram",
    "WebGLUnavailable",
    "angle_diagnostics",
    "browser_started",
    "chromium_path",
    "close_browser",
    "compile_webgl",
    "get_browser",
    "render_shader",
    "webgl_diagnostics",
]
