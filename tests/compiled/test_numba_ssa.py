"""numba_ssa's SSA reconstruction and phi removal against numba's own passes: the same IR, on the
functions of lockstep modules (the construct shaders, whose divergent loops, breaks and returns
make phi nodes, and lab shaders)."""

from __future__ import annotations

import copy
import os
import types

import pytest
from test_compiled_render import CONSTRUCTS, LAB


def _dump(blocks: dict) -> dict:
    return {label: [str(s) for s in b.body] for label, b in blocks.items()}


def _functions(source: str) -> list:
    """The Python functions of a generated module (what numba's passes see)."""
    ns: dict = {"__name__": "glslcheck_test_module"}
    # (numba's cache needs a file; nothing is compiled here)
    exec(compile(source.replace("cache=True", "cache=False"), "<lockstep>", "exec"), ns)
    return [v.py_func for v in ns.values() if getattr(v, "py_func", None) is not None]


def _check(source: str) -> tuple[int, int]:
    """Both passes on every function of the module, numba's and numba_ssa's, on copies of the same
    IR: (functions with re-assigned names, phi nodes stripped)."""
    from numba.core import ir
    from numba.core.compiler import run_frontend

    from glslcheck.backends.compiled_engine import numba_ssa

    if not numba_ssa.install():  # (numba's own passes run there: nothing of ours to check)
        pytest.skip(f"numba_ssa is not installed on numba other than {numba_ssa.CHECKED}")
    ref_ssa, ref_strip = numba_ssa.numba_passes()
    fixed = phis = 0
    for fn in _functions(source):
        blocks = run_frontend(fn).blocks
        want = ref_ssa(copy.deepcopy(blocks))
        got = numba_ssa.run_ssa(copy.deepcopy(blocks))
        assert _dump(got) == _dump(want), fn.__name__
        fixed += want is not blocks
        n = sum(
            isinstance(s, ir.Assign) and isinstance(s.value, ir.Expr) and s.value.op == "phi"
            for b in want.values()
            for s in b.body
        )
        phis += n
        loc = next(iter(want.values())).loc
        a = types.SimpleNamespace(blocks=copy.deepcopy(want), loc=loc)
        b = types.SimpleNamespace(blocks=copy.deepcopy(want), loc=loc)
        ref_strip(None, a)
        numba_ssa.strip_phi_nodes(None, b)
        assert _dump(b.blocks) == _dump(a.blocks), fn.__name__
    return fixed, phis


@pytest.mark.parametrize("name", sorted(CONSTRUCTS))
def test_constructs_same_ir_as_numba(numba, make_shader, name):
    from glslcheck.backends.compiled_engine.engine import generate

    source, _ = generate(make_shader(CONSTRUCTS[name]), lanes=8)
    _check(source)


@pytest.mark.parametrize("name", ["07_final", "bonus_spot_lights"])
def test_lab_same_ir_as_numba(numba, name):
    from glslcheck.backends.compiled_engine.engine import generate
    from glslcheck.shadertoy.sources import load_shader

    source, _ = generate(load_shader(os.path.join(LAB, name)), lanes=8)
    fixed, phis = _check(source)
    assert fixed and phis  # (the comparison saw both passes at work)


def test_block_with_a_name_assigned_twice(numba):
    """A block that assigns a name twice (not SSA form) takes numba's walk: the exported value
    goes after the last assignment."""
    from numba.core import ir
    from numba.core.compiler import run_frontend

    from glslcheck.backends.compiled_engine import numba_ssa

    def f(a):
        x = a + 1
        y = x * 2
        return y

    blocks = run_frontend(f).blocks
    (label,) = blocks
    scope = blocks[label].scope
    loc = blocks[label].loc
    body = blocks[label].body
    x, y = scope.get_exact("x"), scope.get_exact("y")
    # x written a second time (`x = y` after y's assignment), and a phi of this block (a loop to
    # itself) fed by x from this block
    at = next(i for i, s in enumerate(body) if isinstance(s, ir.Assign) and s.target.name == "y")
    body.insert(at + 1, ir.Assign(target=x, value=y, loc=loc))
    target = scope.redefine("z", loc)
    phi = ir.Expr.phi(loc=loc)
    phi.incoming_values.append(x)
    phi.incoming_blocks.append(label)
    body.insert(0, ir.Assign(target=target, value=phi, loc=loc))
    if not numba_ssa.install():
        pytest.skip(f"numba_ssa is not installed on numba other than {numba_ssa.CHECKED}")
    _, ref_strip = numba_ssa.numba_passes()
    a = types.SimpleNamespace(blocks=copy.deepcopy(blocks), loc=loc)
    b = types.SimpleNamespace(blocks=copy.deepcopy(blocks), loc=loc)
    ref_strip(None, a)
    numba_ssa.strip_phi_nodes(None, b)
    assert _dump(b.blocks) == _dump(a.blocks)
    text = _dump(b.blocks)[label]
    writes = [i for i, t in enumerate(text) if t.startswith("x = ")]
    assert len(writes) == 2 and text.index(f"{target.name} = x") == writes[-1] + 1
