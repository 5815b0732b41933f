"""Globals a shader's functions change with ``+=``, ``-=``, ``*=``, ``++`` and ``--``
(tests/gl/global_counters: called once, twice, in loops, from another function, initialized
or not, from a constant or a varying start), rendered by llvmpipe and by both CPU engines bit
for bit.

The entry point has no caller: its globals start at their constant initializers, and it takes
no chain arguments (nir_fold.chain_params), which a counter advanced in a function it calls
once asked of it. Mesa inlines every call and so knows a global's value where the entry point
never set it from a varying one: ``x * gCount + gScale`` after ``bump(); bump();`` is
``x * 4.5 + -0.5`` to NIR, whose constants the rules then merge into ``x``'s products; the
engines fold such a call with the globals' known values (cpu_core/call_fold.py,
``known_globals``). Written for llvmpipe of Mesa 22.3 (the `llvmpipe` fixture skips
elsewhere); the compiled engine per pixel and in lockstep (its `lanes`)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from glslcheck.shadertoy.sources import load_shader
from glslcheck.verification.verify import compile_backend

HERE = Path(__file__).resolve().parent / "global_counters"
CASES = sorted(p.stem for p in HERE.glob("*.glsl"))


def _bits(name: str, backend: str) -> np.ndarray:
    shader = load_shader(HERE / f"{name}.glsl")
    got = compile_backend(shader, backend).render(size=(160, 90), frame=0)
    return np.asarray(got, np.float32).view(np.int32)


@pytest.mark.parametrize("name", CASES)
def test_numpy_renders_global_counters_as_llvmpipe(llvmpipe, name):
    assert (_bits(name, "numpy") == _bits(name, "gl")).all()


@pytest.mark.parametrize("lanes", [0, 8])
@pytest.mark.parametrize("name", CASES)
def test_compiled_renders_global_counters_as_llvmpipe(llvmpipe, numba, name, lanes):
    from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate

    shader = load_shader(HERE / f"{name}.glsl")
    got = CompiledProgram(*generate(shader, lanes=lanes)).render(size=(160, 90), frame=0)
    assert (np.asarray(got, np.float32).view(np.int32) == _bits(name, "gl")).all()
