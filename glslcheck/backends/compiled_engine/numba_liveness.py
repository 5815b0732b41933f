"""numba's variable liveness (`analysis.compute_live_map`) on bit sets, with the same sets out.

numba recomputes the liveness of a whole function after each pass that may have rewritten its
IR (`PostProcessor`, a few hundred times for a large module). Its `compute_live_map` runs two
fix points over Python sets of names: the names defined or used in every block that reaches a
block (`def_reach`), then the names live at each block's entry. A lockstep function has W names
for every per-pixel scalar and hundreds of blocks, so every union copies sets of thousands of
names: blocks x names per sweep, most of the time of numba's liveness on the largest modules.

`compute_live_map` here is the same two fix points in the same block order, each set a Python
int with one bit per name (a union is an OR of machine words). Both are least fix points of
monotone updates from the same start, so they are the same sets whatever the order of the
updates; the result is converted back to numba's sets of names (tests/compiled/
test_numba_liveness.py compares it with numba's on lockstep modules).

`install()` puts it in place of numba's (once; only for the numba versions it was checked
against: `CHECKED`).
"""

from __future__ import annotations

import threading
from collections import defaultdict
from typing import Any

import numpy as np

CHECKED = ("0.68.",)  # the numba versions whose analysis.compute_live_map this mirrors
_STATE: dict[str, Any] = {}
_LOCK = threading.Lock()


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


def install() -> bool:
    """Put compute_live_map in the place of numba's (once); False when this numba is not one it
    was checked against (numba's own then runs)."""
    with _LOCK:
        if "installed" not in _STATE:
            _STATE["installed"] = _install()
        return _STATE["installed"]


def _install() -> bool:
    from numba import __version__
    from numba.core import analysis, ir_utils

    if not __version__.startswith(CHECKED) or not hasattr(analysis, "compute_live_map"):
        return False
    _STATE["numba"] = analysis.compute_live_map
    analysis.compute_live_map = compute_live_map  # (postproc.VariableLifetime looks it up here)
    if getattr(ir_utils, "compute_live_map", None) is _STATE["numba"]:
        ir_utils.compute_live_map = compute_live_map  # (its own import of the name)
    return True


def numba_compute_live_map() -> Any:
    """numba's own analysis.compute_live_map (the reference this is checked against)."""
    from numba.core import analysis

    return _STATE.get("numba", analysis.compute_live_map)
