"""The compiled engine: a checked GLSL program as per-pixel scalar functions compiled by numba
(codegen.py writes them, scalar.py is their runtime, engine.py loads and renders).

Importing this package imports neither numba nor llvmlite: engine.py imports numba when a
program is loaded (numba is the optional extra `glslcheck[jit]`).
"""
