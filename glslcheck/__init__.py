"""glslcheck: parse, check, lint, render on the CPU and verify Shadertoy GLSL ES 3.00."""

from .base.version import __version__  # noqa: F401


def compile(*args, **kwargs):  # noqa: A001 - the public entry point, `glslcheck.compile(path)`
    """Compile a shader for rendering; see glslcheck.backends.registry (imported lazily to keep
    startup cheap)."""
    from .backends.registry import compile as _compile

    return _compile(*args, **kwargs)
