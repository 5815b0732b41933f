"""The compiled engine: a checked GLSL program as per-pixel scalar functions compiled by numba
(codegen.py writes them, scalar.py is their runtime, engine.py loads and renders); lanes.py
rewrites them to run blocks of 8 or 16 pixels in lockstep with the branch-free math of
lanes_math.py (a program starts per pixel and moves to 8 lanes once that pays: engine.TieredProgram;
GLSLCHECK_COMPILED_LANES=0, 8 or 16 fixes the mode), lanes_rt.py is that rewrite's own runtime.

Importing this package imports neither numba nor llvmlite: engine.py imports numba when a
program is loaded (numba is the optional extra `glslcheck[jit]`).
"""
