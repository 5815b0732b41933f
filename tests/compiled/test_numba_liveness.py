"""numba_liveness's live map against numba's own compute_live_map: the same sets of names at each
block's entry, on the functions of lockstep modules (the construct shaders, whose divergent loops,
breaks and returns make loops and joins in numba's control flow graph, and lab shaders), as numba's
frontend writes them and after its SSA pass (phi nodes, renamed versions)."""

from __future__ import annotations

import copy
import os

import pytest
from test_compiled_render import CONSTRUCTS, LAB
from test_numba_ssa import _functions


def _check(source: str) -> int:
    """Both live maps of every function of the module, before and after SSA: the blocks with
    names live at their entry."""
    from numba.core import analysis, ssa
    from numba.core.compiler import run_frontend

    from glslcheck.backends.compiled_engine import numba_liveness

    if not numba_liveness.install():
        pytest.skip(f"numba_liveness is not installed on numba other than {numba_liveness.CHECKED}")
    ref = numba_liveness.numba_compute_live_map()
    live = 0
    for fn in _functions(source):
        frontend = run_frontend(fn).blocks
        for blocks in (frontend, ssa._run_ssa(copy.deepcopy(frontend))):
            cfg = analysis.compute_cfg_from_blocks(blocks)
            usedefs = analysis.compute_use_defs(blocks)
            want = ref(cfg, blocks, usedefs.usemap, usedefs.defmap)
            got = numba_liveness.compute_live_map(cfg, blocks, usedefs.usemap, usedefs.defmap)
            assert list(got) == list(want), fn.__name__
            assert got == want, fn.__name__
            live += sum(bool(v) for v in want.values())
    return live


@pytest.mark.parametrize("name", sorted(CONSTRUCTS))
def test_constructs_same_live_map_as_numba(numba, make_shader, name):
    from glslcheck.backends.compiled_engine.engine import generate

    source, _ = generate(make_shader(CONSTRUCTS[name]), lanes=8)
    _check(source)


@pytest.mark.parametrize("name", ["07_final", "bonus_spot_lights"])
def test_lab_same_live_map_as_numba(numba, name):
    from glslcheck.backends.compiled_engine.engine import generate
    from glslcheck.shadertoy.sources import load_shader

    source, _ = generate(load_shader(os.path.join(LAB, name)), lanes=8)
    assert _check(source)  # (names live across blocks: the fix points were at work)


def test_loop_and_unreachable_block(numba):
    """A loop (a block that is its own predecessor's successor) and a block no path reaches."""
    from numba.core import analysis, ir
    from numba.core.compiler import run_frontend

    from glslcheck.backends.compiled_engine import numba_liveness

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
    if not numba_liveness.install():
        pytest.skip(f"numba_liveness is not installed on numba other than {numba_liveness.CHECKED}")
    ref = numba_liveness.numba_compute_live_map()
    cfg = analysis.compute_cfg_from_blocks(blocks)
    usedefs = analysis.compute_use_defs(blocks)
    want = ref(cfg, blocks, usedefs.usemap, usedefs.defmap)
    got = numba_liveness.compute_live_map(cfg, blocks, usedefs.usemap, usedefs.defmap)
    assert got == want and list(got) == list(want)
    assert any("s" in v and "t" in v for v in want.values())  # carried around the loop
