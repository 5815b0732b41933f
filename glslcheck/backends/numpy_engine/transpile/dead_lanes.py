"""Values a select throws away: computed only on the lanes that keep them.

`mix(x, y, w)` with a bool weight, or in the float32 "select" form (nir_fold.mix_form: a weight
NIR sees as a bool converted to float, ``step()``), is a select in the runtime's copy of
llvmpipe: the other side is ignored, NaN included (`Runtime.mix_reads` says which lanes read
which side, from the one predicate the runtime's mix itself uses; docs/performance.md
"07_final's dead lanes"); so is a `?:` without side effects, by its
condition (np.where, Mesa's bcsel). A branchless shader computes a value for
every pixel and keeps it only where such a weight selects it: 07_final lights every pixel and
then keeps the background with `mix(background, color, hit)`, so the lighting of the pixels
that hit nothing is dead work.

`plan` finds, in one block, the statements whose values only such a select reads and moves them
to just before it, into a region that runs on the lanes whose weight reads that side
(`Statements.dead_lane_region`: compacted when few lanes do, skipped when none does). A
statement moves when

* it declares locals with initializers, each never written again and read only by statements
  that move with it or by the select's argument itself (a plain variable, read nowhere else);
* evaluating it has no side effect: no assignment or ++/--, no out or inout argument, no user
  function that writes a global or may discard (reading globals is fine);
* nothing it reads is written by the statements it moves past (locals; globals when one of
  them may write a global), and, when it runs a loop, none of them runs a loop (llvmpipe's
  loop limiter counts passes in program order);
* the weight is a varying local that the select's own statement does not write;
* the statements moved are worth a region: a loop, or REGION_NODES syntax nodes.

Exact, not approximate: the moved values are the same in every lane that reads them, and a lane
that does not read them selects the other side whatever they hold, so every pixel keeps the
bits of the program as written. What lanes outside the
current mask hold is observable through derivatives only, so a program that takes derivatives
(or implicit-LOD texture lookups) is left as it is; so are the traced module (tracing.py, which
reports what every lane computes) and the "vary" module of undefined values.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ....frontend import syntax as A
from ....semantics.analysis import builtin_call
from ....semantics.model import Symbol
from ...cpu_core import nir_fold

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from .state import TranspilerState

STATEMENTS = (A.ExpressionStatement, A.DeclarationStatement, A.Return)  # where a select may be
# A region without a loop pays from this many syntax nodes (its callees' bodies counted): the
# ones of 8-62 nodes in the lab and the hold-out shaders (a normalize, two small calls, a few
# `?:`) saved nothing at 400x225 (03_lambert_color 9.3-9.5 -> 10.3-10.4 ms a frame, the others
# within the noise of a loaded machine); with the lights' loop, 158-178 nodes, 07_final's
# frame lost a third
REGION_NODES = 96


@dataclass(frozen=True)
class Move:
    """Statements computed only on the lanes where a select reads its argument `side` (0: x or
    the `?:`'s else, 1: y or its then), emitted just before the statement that holds it."""

    stmts: tuple[Any, ...]  # in their order in the block
    weight: A.Identifier  # the mix's weight, or the `?:`'s condition
    side: int
    form: str | None  # rt.mix's form: "fast", or None for a bool weight
    declared: tuple[tuple[Symbol, A.Declarator], ...]  # the locals they declare


@dataclass
class Plan:
    at: dict[int, list[Move]]  # id(statement holding the select) -> the moves emitted before it
    moved: set[int]  # ids of the statements moved


NO_PLAN = Plan({}, set())


def plan(tr: TranspilerState, stmts: list[Any]) -> Plan:
    """The moves of one block (see the module docstring); NO_PLAN when there is none."""
    fs = tr.fn
    if (
        fs is None
        or fs.uni is None
        or fs.switch_depth
        or fs.no_compact
        or tr.facts.uses_derivs
        or tr.undefined != "zero"
        or tr.watched is not None
        or len(stmts) < 2
    ):
        return NO_PLAN
    result = Plan({}, set())
    for k, s in enumerate(stmts):
        if not isinstance(s, STATEMENTS):
            continue
        for sel in (n for n in s.walk() if _is_select(tr, n)):
            found = _selected_side(tr, s, sel)
            if found is None:
                continue
            weight, form, sides = found
            for side, arg in sides:
                move = _move(tr, stmts, k, weight, arg, side, form, result.moved)
                if move is not None:
                    result.at.setdefault(id(s), []).append(move)
                    result.moved.update(id(m) for m in move.stmts)
    return result if result.moved else NO_PLAN


def _is_select(tr: TranspilerState, n: Any) -> bool:
    """A `mix` call, or a `?:` without side effects (np.where: a select in every lane)."""
    if isinstance(n, A.Ternary):
        return not (tr.has_effects(n.then) or tr.has_effects(n.else_))
    return builtin_call(tr.model, n, "mix") and len(n.args) == 3


def _selected_side(
    tr: TranspilerState, s: Any, sel: Any
) -> tuple[Any, str | None, list[tuple[int, Any]]] | None:
    """(the weight, rt.mix's form, the (side, argument) pairs worth a look) when `sel` selects
    in some lanes by a varying local that `s` does not write; else None."""
    fs = tr.fn
    assert fs is not None and fs.uni is not None  # (plan checked)
    w = sel.cond if isinstance(sel, A.Ternary) else sel.args[2]
    sym = tr.model.symbol_of(w) if isinstance(w, A.Identifier) else None
    if sym is None or sym.kind not in ("local", "param") or fs.uni.is_uniform(w):
        return None
    if any(v is sym for n in s.walk() for v in tr.facts.written_variables(n)):
        return None
    base = tr.type_of(w).base
    if base == "bool":
        form = None
    elif base == "float" and nir_fold.mix_form(tr, sel) == "select":
        form = "select"
    else:
        return None
    pairs = (
        [(1, sel.then), (0, sel.else_)]
        if isinstance(sel, A.Ternary)
        else [
            (1, sel.args[1]),
            (0, sel.args[0]),
        ]
    )
    sides = [(i, a) for i, a in pairs if isinstance(a, A.Identifier)]
    return (w, form, sides) if sides else None


def _move(
    tr: TranspilerState,
    stmts: list[Any],
    k: int,
    weight: A.Identifier,
    arg: A.Identifier,
    side: int,
    form: str | None,
    taken: set[int],
) -> Move | None:
    """The statements before stmts[k] that compute only the select's argument `arg` (the
    backward slice of its variable, within the block), when moving them is exact and pays."""
    y = tr.model.symbol_of(arg)
    reads = read_counts(tr)
    if y is None or y.kind != "local" or reads.get(id(y)) != 1:
        return None
    writes = tr.facts.write_counts()
    inside: dict[int, int] = {id(y): 1}  # reads by the select and the statements moving
    chosen: list[int] = []
    for j in range(k - 1, -1, -1):
        s = stmts[j]
        if id(s) in taken:
            continue
        declared = _declared(tr, s)
        if not declared or any(
            writes.get(id(sym), 0) or reads.get(id(sym), 0) != inside.get(id(sym), -1)
            for sym, _ in declared
        ):
            continue
        between = [stmts[i] for i in range(j + 1, k) if i not in chosen]
        if not _pure(tr, s) or not _movable_past(tr, s, between):
            continue
        chosen.append(j)
        for n in s.walk():
            if isinstance(n, A.Identifier) and (sym := tr.model.symbol_of(n)) is not None:
                inside[id(sym)] = inside.get(id(sym), 0) + 1
    if not chosen:
        return None
    moved = tuple(stmts[j] for j in sorted(chosen))
    if not _worth_a_region(tr, moved):
        return None
    return Move(moved, weight, side, form, tuple(d for s in moved for d in _declared(tr, s)))


def _worth_a_region(tr: TranspilerState, moved: tuple[Any, ...]) -> bool:
    """The lanes a region leaves out save more than it costs (the weight's lanes, the gather
    and the scatter, about what a few vector operations on every lane cost): it runs a loop, or
    REGION_NODES syntax nodes or more, counting the bodies of the functions it calls."""
    if any(_runs_loop(tr, s) for s in moved):
        return True
    count = 0
    seen: set[int] = set()
    todo = list(moved)
    while todo:
        for n in todo.pop().walk():
            count += 1
            tgt = tr.model.call_target(n) if isinstance(n, A.Call) else None
            if isinstance(tgt, Symbol) and id(tgt) not in seen:
                seen.add(id(tgt))
                todo.append(tgt.node.body)
        if count >= REGION_NODES:
            return True
    return False


def _declared(tr: TranspilerState, s: Any) -> list[tuple[Symbol, A.Declarator]]:
    """The locals a declaration statement declares, each with an initializer; [] otherwise."""
    if not isinstance(s, A.DeclarationStatement) or not isinstance(s.decl, A.VariableDeclaration):
        return []
    out = []
    for dec in s.decl.declarators:
        sym = tr.model.symbol_of(dec)
        if sym is None or dec.init is None or sym.kind != "local":
            return []
        out.append((sym, dec))
    return out


def _pure(tr: TranspilerState, s: Any) -> bool:
    """Evaluating the statement's initializers writes nothing but the locals it declares."""
    for n in s.walk():
        if isinstance(n, (A.Assignment, A.Sequence, A.Discard)):
            return False
        if isinstance(n, (A.Unary, A.Postfix)) and n.op in ("++", "--"):
            return False
        if isinstance(n, A.Call):
            if tr.facts.written_variables(n):
                return False  # (an out or inout argument)
            tgt = tr.model.call_target(n)
            if isinstance(tgt, Symbol) and (
                tr.facts.writes_globals(tgt) or id(tgt) in tr.facts.may_discard
            ):
                return False
    return True


def _movable_past(tr: TranspilerState, s: Any, between: list[Any]) -> bool:
    """Nothing `s` reads is written by `between`, and its loops keep their place among theirs."""
    if not between:
        return True
    read: set[int] = set()
    lane_state = False  # reads a global some function writes
    for n in s.walk():
        if isinstance(n, A.Identifier) and (sym := tr.model.symbol_of(n)) is not None:
            read.add(id(sym))
            lane_state |= id(sym) in tr.facts.written_globals
        elif isinstance(n, A.Call):
            tgt = tr.model.call_target(n)
            lane_state |= isinstance(tgt, Symbol) and id(tgt) in tr.facts.reads_lane_state
    loops = _runs_loop(tr, s)
    for b in between:
        for n in b.walk():
            if any(id(sym) in read for sym in tr.facts.written_variables(n)):
                return False
            if lane_state and _writes_global(tr, n):
                return False
        if loops and _runs_loop(tr, b):
            return False
    return True


def _writes_global(tr: TranspilerState, n: Any) -> bool:
    if any(sym.kind == "global" for sym in tr.facts.written_variables(n)):
        return True
    tgt = tr.model.call_target(n) if isinstance(n, A.Call) else None
    return isinstance(tgt, Symbol) and tr.facts.writes_globals(tgt)


def _runs_loop(tr: TranspilerState, node: Any, seen: set[int] | None = None) -> bool:
    """A loop in `node` or in a function it calls."""
    seen = set() if seen is None else seen
    for n in node.walk():
        if isinstance(n, (A.For, A.While, A.DoWhile)):
            return True
        tgt = tr.model.call_target(n) if isinstance(n, A.Call) else None
        if isinstance(tgt, Symbol) and id(tgt) not in seen:
            seen.add(id(tgt))
            if _runs_loop(tr, tgt.node.body, seen):
                return True
    return False


def read_counts(tr: TranspilerState) -> dict[int, int]:
    """id(symbol) -> how many identifiers in the current function's body name it (its reads,
    for a local that is only written by its declaration)."""
    fs = tr.fn
    assert fs is not None  # (plan checked)
    memo = tr.dead_lane_reads
    key = id(fs.sym)
    if key not in memo:
        counts: dict[int, int] = {}
        for n in fs.sym.node.body.walk():
            if isinstance(n, A.Identifier) and (sym := tr.model.symbol_of(n)) is not None:
                counts[id(sym)] = counts.get(id(sym), 0) + 1
        memo[key] = counts
    return memo[key]
