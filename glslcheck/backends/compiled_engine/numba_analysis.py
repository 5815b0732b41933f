"""numba's analyses of a function's IR that it recomputes after its rewrites, with the same
results in less time: variable liveness (`analysis.compute_live_map`) on bit sets, and the
definition of every used name in each scope (`ir_utils.fixup_var_define_in_scope`) once per scope.

numba recomputes the liveness of a whole function after each pass that may have rewritten its
IR (`PostProcessor`, a few hundred times for a large module). Its `compute_live_map` runs two
fix points over Python sets of names: the names defined or used in every block that reaches a
block (`def_reach`), then the names live at each block's entry. A lockstep function has W names
for every per-pixel scalar and hundreds of blocks, so every union copies sets of thousands of
names: blocks x names per sweep, most of the time of numba's liveness on the largest modules.
`compute_live_map` here is the same two fix points in the same block order, each set a Python
int with one bit per name (a union is an OR of machine words). Both are least fix points of
monotone updates from the same start, so they are the same sets whatever the order of the
updates; the result is converted back to numba's sets of names.

numba's `fixup_var_define_in_scope` checks every used name against the scope of every block:
blocks x names, though the blocks of a function share one scope (or a few). Here each scope is
checked once, in the order of its first block: numba's later visits of the same scope find every
name defined and change nothing.

tests/compiled/test_numba_analysis.py compares both with numba's on lockstep modules.
`replace()` puts them in place of numba's (numba_patches.install: once, and only on the numba
versions they were checked against: `CHECKED`).
"""

from __future__ import annotations

from collections import defaultdict
from typing import Any

import numpy as np

from .numba_swaps import swap

CHECKED = ("0.68.",)  # the numba versions whose functions these mirror


class _Bits:
    """Sets of names as ints: bit i is the i-th name seen."""

    def __init__(self, sets: list) -> None:
        index: dict[str, int] = {}
        for names in sets:
            for n in names:
                index.setdefault(n, len(index))
        self.index = index
        self.names = list(index)
        self.nbytes = (len(index) + 7) // 8

    def of(self, names: Any) -> int:
        if not names:
            return 0
        flags = np.zeros(self.nbytes * 8, np.uint8)
        flags[[self.index[n] for n in names]] = 1
        return int.from_bytes(np.packbits(flags, bitorder="little").tobytes(), "little")

    def names_of(self, bits: int) -> set:
        if not bits:
            return set()
        raw = np.frombuffer(bits.to_bytes(self.nbytes, "little"), np.uint8)
        names = self.names
        return {names[i] for i in np.flatnonzero(np.unpackbits(raw, bitorder="little"))}


def _fix_point(sweep: Any, dct: dict) -> None:
    """Run sweep(dct) until a sweep changes nothing (numba's `fix_point`: sets only grow)."""
    while True:
        before = dict(dct)
        sweep(dct)
        if dct == before:
            return


def compute_live_map(cfg: Any, blocks: dict, var_use_map: dict, var_def_map: dict) -> dict:
    """The names that must be alive at the entry of each block (numba's compute_live_map)."""
    topo_order = cfg.topo_order()
    bits = _Bits([*var_use_map.values(), *var_def_map.values()])
    use = {k: bits.of(v) for k, v in var_use_map.items()}
    defs = {k: bits.of(v) for k, v in var_def_map.items()}

    def def_reach(dct: dict) -> None:
        # the names defined or used in a block or in any block that reaches it
        for offset in topo_order:
            dct[offset] |= defs[offset] | use[offset]
            for out_blk, _ in cfg.successors(offset):
                dct[out_blk] |= dct[offset]

    def liveness(dct: dict) -> None:
        # a use pushed back to the predecessors that reach it and do not define it
        for offset in reversed(topo_order):
            live = dct[offset]
            for inc_blk, _ in cfg.predecessors(offset):
                dct[inc_blk] |= live & def_reach_map[inc_blk] & ~defs[inc_blk]

    live_map = {offset: use[offset] for offset in blocks.keys()}
    def_reach_map: dict = defaultdict(int)
    _fix_point(def_reach, def_reach_map)
    _fix_point(liveness, live_map)
    return {offset: bits.names_of(v) for offset, v in live_map.items()}


def fixup_var_define_in_scope(blocks: dict) -> None:
    """Define every name the blocks use in each of their scopes (numba's
    fixup_var_define_in_scope, each scope once)."""
    used_var = {}
    for blk in blocks.values():
        for inst in blk.body:
            for var in inst.list_vars():
                used_var[var] = inst
    seen: set[int] = set()
    for blk in blocks.values():
        scope = blk.scope
        if id(scope) in seen:
            continue
        seen.add(id(scope))
        localvars = scope.localvars
        for var in used_var:
            if var.name not in localvars:
                localvars.define(var.name, var)


def replace() -> bool:
    """Put both in the place of numba's; False when this numba lacks either."""
    from numba.core import analysis, ir_utils, untyped_passes

    names = (
        (analysis, "compute_live_map", compute_live_map),
        (ir_utils, "fixup_var_define_in_scope", fixup_var_define_in_scope),
    )
    if not all(hasattr(m, n) for m, n, _ in names):
        return False
    # numba's modules that call them by a name of their own (`from ... import`), and the
    # modules that own them (postproc.VariableLifetime calls analysis.compute_live_map)
    users = (analysis, ir_utils, untyped_passes)
    for home, name, mine in names:
        numba_own = getattr(home, name)
        for m in users:
            if getattr(m, name, None) is numba_own:
                swap(m, name, mine)
    return True
