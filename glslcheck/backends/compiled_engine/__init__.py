"""The compiled engine: a checked GLSL program as per-pixel scalar functions compiled by numba
(codegen.py writes them, scalar.py is their runtime, engine.py loads and renders); lanes.py
rewrites them to run blocks of 8 or 16 pixels in lockstep with the branch-free math of
lanes_math.py (a program starts per pixel and moves to 8 lanes once that pays: engine.TieredProgram;
GLSLCHECK_COMPILED_LANES=0, 8 or 16 fixes the mode), lanes_rt.py is that rewrite's own runtime.

Importing this package imports neither numba nor llvmlite: engine.py imports numba when a
program is loaded (numba is the optional extra `glslcheck[jit]`).
"""

from __future__ import annotations

from typing import Any


def compile_program(path: Any, pass_name: str = "Image", threads: int | None = None) -> Any:
    """`render --backend compiled`: an api.Program rendering `path`'s Image tab per pixel.
    InputError (exit 2) without numba, with the pip line; GlslError (exit 1) for a construct
    or a multipass shader the engine does not support yet."""
    from .engine import compile_compiled, require_numba

    require_numba()
    if pass_name != "Image":
        from ...base.diagnostics import InputError

        raise InputError(f"error: --backend compiled renders the Image pass only, not {pass_name!r}")
    return compile_compiled(path, threads)
