"""numba_analysis against numba's own functions on the functions of lockstep modules (the construct
shaders, whose divergent loops, breaks and returns make loops and joins in numba's control flow
graph, and lab shaders): the same sets of names live at each block's entry (compute_live_map), as
numba's frontend writes the IR and after its SSA pass (phi nodes, renamed versions), and the same
names defined in each scope (fixup_var_define_in_scope)."""

from __future__ import annotations

import copy
import os

import pytest
from test_compiled_render import CONSTRUCTS, LAB

from glslcheck.backends.compiled_engine import numba_swaps


def _check(functions: list[tuple[str, dict]]) -> int:
    """Both live maps and both scope fix-ups of every function of a module (lockstep_ir's),
    before and after SSA: the blocks with names live at their entry."""
    from numba.core import analysis, ssa

    from glslcheck.backends.compiled_engine import numba_analysis, numba_patches

    if not numba_patches.install(numba_analysis):
        pytest.skip(f"numba_analysis is not installed on numba other than {numba_analysis.CHECKED}")
    ref = numba_swaps.original(analysis, "compute_live_map")
    live = 0
    for name, frontend in functions:
        for blocks in (frontend, ssa._run_ssa(copy.deepcopy(frontend))):
            cfg = analysis.compute_cfg_from_blocks(blocks)
            usedefs = analysis.compute_use_defs(blocks)
            want = ref(cfg, blocks, usedefs.usemap, usedefs.defmap)
            got = numba_analysis.compute_live_map(cfg, blocks, usedefs.usemap, usedefs.defmap)
            assert list(got) == list(want), name
            assert got == want, name
            live += sum(bool(v) for v in want.values())
            _check_scopes(blocks)
    return live


def _check_scopes(blocks: dict) -> None:
    """numba's and numba_analysis's fixup_var_define_in_scope on copies of blocks whose second half
    has a scope of its own, empty: the same names, in the same order, in every scope."""
    from numba.core import ir, ir_utils

    from glslcheck.backends.compiled_engine import numba_analysis

    ref = numba_swaps.original(ir_utils, "fixup_var_define_in_scope")
    out = []
    for fixup in (ref, numba_analysis.fixup_var_define_in_scope):
        copied = copy.deepcopy(blocks)
        first = next(iter(copied.values()))
        own = ir.Scope(parent=first.scope.parent, loc=first.loc)
        for blk in list(copied.values())[len(copied) // 2 :]:
            blk.scope = own
        fixup(copied)
        scopes = {id(b.scope): b.scope for b in copied.values()}.values()
        out.append([list(s.localvars._con) for s in scopes])
    assert out[0] == out[1]
    assert len(blocks) < 2 or out[0][-1]  # (the empty scope received the names used)


@pytest.mark.parametrize("name", sorted(CONSTRUCTS))
def test_constructs_same_live_map_as_numba(lockstep_ir, make_shader, name):
    _check(lockstep_ir(make_shader(CONSTRUCTS[name])))


@pytest.mark.parametrize("name", ["07_final", "bonus_spot_lights"])
def test_lab_same_live_map_as_numba(lockstep_ir, name):
    from glslcheck.shadertoy.sources import load_shader

    live = _check(lockstep_ir(load_shader(os.path.join(LAB, name))))
    assert live  # (names live across blocks: the fix points were at work)


def test_loop_and_unreachable_block(numba):
    """A loop (a block that is its own predecessor's successor) and a block no path reaches."""
    from numba.core import analysis, ir
    from numba.core.compiler import run_frontend

    from glslcheck.backends.compiled_engine import numba_analysis, numba_patches

    def f(n):
        s = 0.0
        t = 1.0
        i = 0
        while i < n:
            if i > 3:
                s += t
            t = t * 0.5
            i += 1
        return s

    blocks = run_frontend(f).blocks
    loc = next(iter(blocks.values())).loc
    scope = next(iter(blocks.values())).scope
    dead = ir.Block(scope, loc)  # reads s and t, jumps into the loop; nothing jumps to it
    dead.append(ir.Assign(scope.get_exact("t"), scope.get_exact("s"), loc))
    dead.append(ir.Jump(min(blocks), loc))
    blocks[max(blocks) + 100] = dead
    if not numba_patches.install(numba_analysis):
        pytest.skip(f"numba_analysis is not installed on numba other than {numba_analysis.CHECKED}")
    ref = numba_swaps.original(analysis, "compute_live_map")
    cfg = analysis.compute_cfg_from_blocks(blocks)
    usedefs = analysis.compute_use_defs(blocks)
    want = ref(cfg, blocks, usedefs.usemap, usedefs.defmap)
    got = numba_analysis.compute_live_map(cfg, blocks, usedefs.usemap, usedefs.defmap)
    assert got == want and list(got) == list(want)
    assert any("s" in v and "t" in v for v in want.values())  # carried around the loop
