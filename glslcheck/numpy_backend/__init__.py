"""NumPy backend: the GLSL-to-Python transpiler and the runtime its output calls (``runtime``)."""
