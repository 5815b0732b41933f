"""numba_ssa's SSA reconstruction and phi removal against numba's own passes: the same IR, on the
functions of lockstep modules (the construct shaders, whose divergent loops, breaks and returns
make phi nodes, and lab shaders)."""

from __future__ import annotations

import copy
import os
import types

import pytest
from test_compiled_render import CONSTRUCTS, LAB

from glslcheck.backends.compiled_engine import numba_swaps


def _dump(blocks: dict) -> dict:
    return {label: [str(s) for s in b.body] for label, b in blocks.items()}


def _check(functions: list[tuple[str, dict]]) -> tuple[int, int]:
    """Both passes on every function of a module (lockstep_ir's), numba's and numba_ssa's, on
    copies of the same IR: (functions with re-assigned names, phi nodes stripped)."""
    from numba.core import ir, ssa, typed_passes

    from glslcheck.backends.compiled_engine import numba_patches, numba_ssa

    if not numba_patches.install(numba_ssa):  # (numba's own passes run there: nothing to check)
        pytest.skip(f"numba_ssa is not installed on numba other than {numba_ssa.CHECKED}")
    ref_ssa = numba_swaps.original(ssa, "_run_ssa")
    ref_strip = numba_swaps.original(typed_passes.PreLowerStripPhis, "_strip_phi_nodes")
    fixed = phis = 0
    for name, blocks in functions:
        want = ref_ssa(copy.deepcopy(blocks))
        got = numba_ssa.run_ssa(copy.deepcopy(blocks))
        assert _dump(got) == _dump(want), name
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
        assert _dump(b.blocks) == _dump(a.blocks), name
    return fixed, phis


@pytest.mark.parametrize("name", sorted(CONSTRUCTS))
def test_constructs_same_ir_as_numba(lockstep_ir, make_shader, name):
    _check(lockstep_ir(make_shader(CONSTRUCTS[name])))


@pytest.mark.parametrize("name", ["07_final", "bonus_spot_lights"])
def test_lab_same_ir_as_numba(lockstep_ir, name):
    from glslcheck.shadertoy.sources import load_shader

    fixed, phis = _check(lockstep_ir(load_shader(os.path.join(LAB, name))))
    assert fixed and phis  # (the comparison saw both passes at work)


def test_block_with_a_name_assigned_twice(numba):
    """A block that assigns a name twice (not SSA form) takes numba's walk: the exported value
    goes after the last assignment."""
    from numba.core import ir, typed_passes
    from numba.core.compiler import run_frontend

    from glslcheck.backends.compiled_engine import numba_patches, numba_ssa

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
    if not numba_patches.install(numba_ssa):
        pytest.skip(f"numba_ssa is not installed on numba other than {numba_ssa.CHECKED}")
    ref_strip = numba_swaps.original(typed_passes.PreLowerStripPhis, "_strip_phi_nodes")
    a = types.SimpleNamespace(blocks=copy.deepcopy(blocks), loc=loc)
    b = types.SimpleNamespace(blocks=copy.deepcopy(blocks), loc=loc)
    ref_strip(None, a)
    numba_ssa.strip_phi_nodes(None, b)
    assert _dump(b.blocks) == _dump(a.blocks)
    text = _dump(b.blocks)[label]
    writes = [i for i, t in enumerate(text) if t.startswith("x = ")]
    assert len(writes) == 2 and text.index(f"{target.name} = x") == writes[-1] + 1
