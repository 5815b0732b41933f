"""The OpenGL context: one headless EGL context (Mesa llvmpipe on a machine without a GPU) per
process.

WebGL, which Shadertoy runs on, initialises every variable to zero; desktop Mesa leaves them
undefined, and llvmpipe really does return garbage for an uninitialised local. Mesa's driconf
option `glsl_zero_init` gives WebGL's behaviour, and an environment variable of the same name
overrides it; we set it (unless the user already did) before the driver loads. Mesa announces
the override on stderr ("ATTENTION: default value of option glsl_zero_init overridden by
environment."); that one line is filtered, everything else the driver prints is passed on.
"""

from __future__ import annotations

import os
import sys
import tempfile

from ...base.diagnostics import InputError

ADVICE = (
    "install the Debian packages libegl1 libegl-mesa0 libgl1-mesa-dri "
    "(sudo apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri)"
)
# The lowest GL version whose drivers compile `#version 300 es` (GL_ARB_ES3_compatibility is core in
# 4.3).
REQUIRED_GL_VERSION = 330

_context = None


class GLUnavailable(InputError):
    """No OpenGL context could be created (an environment problem: exit 2, never a traceback)."""


def _quietly(fn):
    """Call fn() with C-level stderr captured; re-print all but Mesa's driconf override notice."""
    sys.stderr.flush()
    saved = os.dup(2)
    with tempfile.TemporaryFile() as tmp:
        os.dup2(tmp.fileno(), 2)
        try:
            return fn()
        finally:
            os.dup2(saved, 2)
            os.close(saved)
            tmp.seek(0)
            for line in tmp.read().decode("utf-8", "replace").splitlines(keepends=True):
                if "overridden by environment" not in line:
                    sys.stderr.write(line)


def create_context():
    """A new standalone moderngl context on EGL; GLUnavailable with install advice if that fails."""
    try:
        import moderngl
    except ImportError as e:  # pragma: no cover - moderngl is a dependency
        raise GLUnavailable(
            f"error: moderngl is not installed ({e}); pip install moderngl"
        ) from None
    os.environ.setdefault("glsl_zero_init", "true")
    try:
        ctx = _quietly(
            # (moderngl's stubs type each **setting as a dict; a string is what it takes)
            lambda: moderngl.create_context(standalone=True, backend="egl")  # type: ignore[arg-type]
        )
    except Exception as e:  # moderngl/glcontext raise plain Exception subclasses
        raise GLUnavailable(
            f"error: cannot create an OpenGL context with EGL ({e}); {ADVICE}"
        ) from None
    if ctx.version_code < REQUIRED_GL_VERSION:
        version = ctx.version_code
        ctx.release()
        raise GLUnavailable(
            f"error: the OpenGL context is version {version}, glslcheck needs "
            f"{REQUIRED_GL_VERSION} or later; {ADVICE}"
        )
    return ctx


def get_context():
    """The process-wide context, created on first use and reused afterwards."""
    global _context
    if _context is None:
        _context = create_context()
    return _context


def renderer_name() -> str:
    """The driver's GL_RENDERER string, e.g. 'llvmpipe (LLVM 15.0.6, 256 bits)'."""
    return get_context().info["GL_RENDERER"]


_gl_functions: dict[str, object] = {}


def gl_function(name: str, *argtypes):
    """A GL entry point moderngl does not wrap (glTexSubImage2D on a cube face's mipmap level),
    through EGL's eglGetProcAddress, as the context's own loader finds them; it acts on the
    current context, the process-wide one."""
    fn = _gl_functions.get(name)
    if fn is None:
        import ctypes

        egl = ctypes.CDLL("libEGL.so.1")
        egl.eglGetProcAddress.restype = ctypes.c_void_p
        egl.eglGetProcAddress.argtypes = [ctypes.c_char_p]
        address = egl.eglGetProcAddress(name.encode())
        if not address:
            raise GLUnavailable(f"error: the GL driver has no {name}; {ADVICE}")
        fn = ctypes.CFUNCTYPE(None, *argtypes)(address)
        _gl_functions[name] = fn
    return fn
