"""numba's SSA reconstruction (its ReconstructSSA pass) and phi removal (PreLowerStripPhis) in
time proportional to what they change, with the same IR out.

numba's `ssa._run_ssa` fixes one re-assigned name (a "violator") at a time, and each fix walks
every statement of the function twice, and looks a use's reaching definition up by a linear
search of its block: time grows with violators x statements. A lockstep function writes W names
for every per-pixel scalar, so both grow W-fold (lanes.py): the pass was most of the compile of
the largest lockstep functions. `run_ssa` is the same algorithm, driven by numba's own handlers
(`_FreshVarHandler`, `_FixSSAVars`) in the same order, but each fix visits only the statements
that name the violator (every other statement is returned unchanged by both handlers), and a
statement's position comes from an index instead of a search. Same fresh names, same phi nodes in
the same order, same statements: tests/compiled/test_numba_ssa.py compares the two on the
lockstep modules of the lab shaders.

numba's phi removal puts each phi's incoming value at the end of its incoming block, after the
last assignment to that value, which it finds by walking the block for each phi: phis x
statements again. `strip_phi_nodes` finds it from a map of the block's assignments when every
name is assigned once in the block (SSA form: the usual case; numba's walk decides otherwise).

`replace()` puts both in place of numba's (numba_patches.install: once, and only on the numba
versions they were checked against, whose internals they call: `CHECKED`).
"""

from __future__ import annotations

from collections import defaultdict
from typing import Any

from .numba_swaps import swap

CHECKED = ("0.68.",)  # the numba versions whose ssa.py this mirrors


class _BlockView:
    """What the fix of one violator reads of a block: its length, its location, and the
    positions of the statements that name the violator (by identity, as numba's search)."""

    __slots__ = ("body", "loc", "pos")

    def __init__(self, body: list, loc: Any, pos: dict) -> None:
        self.body = body
        self.loc = loc
        self.pos = pos


def _fix_handler(ssa: Any, cache: Any) -> Any:
    class FixByIndex(ssa._FixSSAVars):
        def _stmt_index(self, defstmt: Any, block: Any, stop: int = -1) -> int:
            # numba's: the first i in range(len(body))[:stop] with body[i] is defstmt, else len
            n = len(block.body)
            i = block.pos.get(id(defstmt))
            if i is not None and i < len(range(n)[:stop]):
                return i
            return n

    return FixByIndex(cache)


def run_ssa(blocks: dict) -> dict:
    """numba's ssa._run_ssa(blocks), the same result."""
    from numba.core import errors, ir, ssa
    from numba.core.analysis import compute_cfg_from_blocks

    if not blocks:
        return {}
    cfg = compute_cfg_from_blocks(blocks)
    df_plus = ssa._iterated_domfronts(cfg)
    violators = ssa._find_defs_violators(blocks, cfg)
    cache = ssa._CacheListVars()
    if not violators:
        return blocks
    wanted = set(violators)
    bodies = {label: list(blk.body) for label, blk in blocks.items()}
    # per block, the positions of the statements naming each violator (defined or used): the
    # only ones a fix of that name changes (phi nodes put in front shift them: `shift`)
    where: dict[Any, dict[str, list[int]]] = {}
    for label, body in bodies.items():
        at: dict[str, list[int]] = defaultdict(list)
        for i, stmt in enumerate(body):
            for name in {v.name for v in stmt.list_vars()} & wanted:
                at[name].append(i)
        where[label] = at
    shift = dict.fromkeys(bodies, 0)
    scope = ssa._get_scope(blocks)
    fresh = ssa._FreshVarHandler()
    fix = _fix_handler(ssa, cache)
    for varname in violators:
        defmap: dict = defaultdict(list)
        states: dict[str, Any] = dict(scope=scope, varname=varname, defmap=defmap)
        for label, body in bodies.items():
            states["label"] = label
            s = shift[label]
            for i in where[label].get(varname, ()):
                stmt = body[s + i]
                if isinstance(stmt, ir.Assign):
                    body[s + i] = fresh.on_assign(states, stmt)
                else:
                    body[s + i] = fresh.on_other(states, stmt)
        phimap: dict = defaultdict(list)
        states = dict(
            scope=scope,
            varname=varname,
            defmap=defmap,
            phimap=phimap,
            cfg=cfg,
            phi_locations=ssa._compute_phi_locations(df_plus, defmap),
        )
        for label, body in bodies.items():
            at_var = where[label].get(varname)
            if not at_var:
                continue
            s = shift[label]
            states["label"] = label
            states["block"] = _BlockView(
                body, blocks[label].loc, {id(body[s + i]): s + i for i in at_var}
            )
            out = []
            for i in at_var:
                stmt = body[s + i]
                if isinstance(stmt, ir.Assign):
                    out.append(fix.on_assign(states, stmt))
                else:
                    out.append(fix.on_other(states, stmt))
            for i, stmt in zip(at_var, out):
                body[s + i] = stmt
        for label, philist in phimap.items():
            bodies[label][:0] = philist
            shift[label] += len(philist)
    newblocks = {}
    for label, blk in blocks.items():
        nb = ir.Block(scope=blk.scope, loc=blk.loc)
        nb.body = bodies[label]
        newblocks[label] = nb
    if compute_cfg_from_blocks(newblocks) != cfg:
        raise errors.CompilerError("CFG mutated in SSA pass")
    return newblocks


def _strip_block(block: Any, phis: set, exports: list, null: Any) -> Any:
    """One block of numba's PreLowerStripPhis._strip_phi_nodes: the block without its phis,
    with the incoming values it exports after the last assignment to them in the block (a Var
    equals another of its name), else first. From a map of the block's assignments when each
    name is assigned once there; else numba's walk of the block for each export."""
    from copy import copy

    from numba.core import ir

    new = copy(block)
    new.body = [stmt for stmt in block.body if stmt not in phis]
    exports = [
        (target, null() if rhs is ir.UNDEFINED else rhs) for target, rhs in exports
    ]  # (numba makes the null before the walk: it is assigned nowhere)
    defined: dict[str, Any] = {}
    names = [s.target.name for s in new.body if isinstance(s, ir.Assign)]
    names += [target.name for target, _ in exports]
    if len(set(names)) < len(names):
        for target, rhs in exports:
            assign = ir.Assign(target=target, value=rhs, loc=rhs.loc)
            assignments = [s for s in new.find_insts(ir.Assign) if s.target == rhs]
            if assignments:
                new.insert_after(assign, assignments[-1])
            else:
                new.prepend(assign)
        return new
    for stmt in new.body:
        if isinstance(stmt, ir.Assign):
            defined[stmt.target.name] = stmt
    after: dict[int, list] = defaultdict(list)  # the statements put right after one, latest first
    front: list = []
    for target, rhs in exports:
        assign = ir.Assign(target=target, value=rhs, loc=rhs.loc)
        anchor = defined.get(rhs.name) if isinstance(rhs, ir.Var) else None
        if anchor is not None:
            after[id(anchor)].insert(0, assign)
        else:
            front.insert(0, assign)
        defined[target.name] = assign
    out: list = []

    def put(stmt: Any) -> None:
        out.append(stmt)
        for s in after.get(id(stmt), ()):
            put(s)

    for stmt in front + new.body:
        put(stmt)
    new.body = out
    return new


def strip_phi_nodes(self: Any, func_ir: Any) -> Any:
    """numba's PreLowerStripPhis._strip_phi_nodes(func_ir), the same result."""
    from numba.core import ir

    exporters: dict = defaultdict(list)
    phis = set()
    for block in func_ir.blocks.values():
        for assign in block.find_insts(ir.Assign):
            if isinstance(assign.value, ir.Expr) and assign.value.op == "phi":
                phis.add(assign)
                phi = assign.value
                for ib, iv in zip(phi.incoming_blocks, phi.incoming_values):
                    exporters[ib].append((assign.target, iv))
    func_ir.blocks = {
        label: _strip_block(block, phis, exporters[label], lambda: ir.Expr.null(loc=func_ir.loc))
        for label, block in func_ir.blocks.items()
    }
    return func_ir


def replace() -> bool:
    """Put run_ssa and strip_phi_nodes in the place of numba's ssa._run_ssa and
    PreLowerStripPhis._strip_phi_nodes; False when this numba lacks what they call."""
    from numba.core import ssa, typed_passes

    ok = all(
        hasattr(ssa, n)
        for n in (
            "_run_ssa",
            "_iterated_domfronts",
            "_find_defs_violators",
            "_CacheListVars",
            "_get_scope",
            "_FreshVarHandler",
            "_FixSSAVars",
            "_compute_phi_locations",
        )
    )
    strip = getattr(typed_passes, "PreLowerStripPhis", None)
    ok = ok and strip is not None and hasattr(strip, "_strip_phi_nodes")
    if ok and strip is not None:
        swap(ssa, "_run_ssa", run_ssa)
        swap(strip, "_strip_phi_nodes", strip_phi_nodes)
    return ok
