"""glslcheck: parse, check, lint, render on the CPU and verify Shadertoy GLSL ES 3.00."""

__version__ = "0.1.0"
