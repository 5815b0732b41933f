"""Fixtures of the compiled engine's tests: `numba` is in tests/conftest.py (the folder's tests
are marked `numba` and `slow` there); `lockstep_ir` gives numba's IR of a generated module, for
the tests that compare numba_ssa and numba_analysis with numba's own passes."""

from __future__ import annotations

import pytest


@pytest.fixture
def lockstep_ir(numba):
    """lockstep_ir(shader, lanes=8) -> [(name, blocks)]: each function of `shader`'s generated
    module (lockstep with `lanes` lanes, per pixel with 0) as numba's frontend writes its IR,
    before any pass of numba's or ours: what numba_ssa and numba_analysis are given."""

    def functions(shader, lanes: int = 8) -> list[tuple[str, dict]]:
        from numba.core.compiler import run_frontend

        from glslcheck.backends.compiled_engine.engine import generate

        source, _ = generate(shader, lanes=lanes)
        ns: dict = {"__name__": "glslcheck_test_module"}
        # (numba's cache needs a file; nothing is compiled here)
        exec(compile(source.replace("cache=True", "cache=False"), "<lockstep>", "exec"), ns)
        jitted = [v.py_func for v in ns.values() if getattr(v, "py_func", None) is not None]
        return [(fn.__name__, run_frontend(fn).blocks) for fn in jitted]

    return functions
