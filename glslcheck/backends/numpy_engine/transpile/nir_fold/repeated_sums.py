"""A variable advanced by constants: ``seed += 0.1`` written again and again (path tracers'
random numbers).

NIR is SSA: ``seed += 0.1; seed += 0.1; seed += 0.1`` is ``((s0 + 0.1) + 0.1) + 0.1``, and
``('~fadd', '#a', ('fadd', 'b(is_not_const)', '#c')) -> (a + c) + b`` folds each new constant
into the sum before it, in float32, left to right: ``s0 + ((0.1 + 0.1) + 0.1)`` (measured on
llvmpipe, tests/gl/test_llvmpipe_repeated_sums.py). The chain runs while each step's previous
write reaches it alone (analysis.dataflow: it runs before on every path, nothing writes the
variable in between), so it restarts at a loop top and stops at the join after a branch that
writes the variable (a phi to NIR). The generated code has one variable per GLSL one, so the
value before the chain is kept in a temporary (:func:`repeated_sum`)."""

from __future__ import annotations

from typing import Any

from .....frontend import syntax as A
from .queries import current_function, function_facts, is_constant, is_varying

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..state import FoldEngine, TranspilerState


def sum_step(tr: FoldEngine, e: Any) -> tuple[str, Any, Any, bool] | None:
    """(sign, the constant, the previous step or None, whether a later step continues this
    one and its value before must be kept) for a step ``x += #c`` (``x -= #c``, ``x = x +
    #c``, ``x = #c + x``, ``x = x - #c``); None for any other write. Emits nothing: both CPU
    engines ask it."""
    step = _step(tr, e)
    if step is None:
        return None
    prev = _previous_step(tr, e)
    kept = prev is None and id(e) in _chained(tr) and _varying_start(tr, e)
    return step[0], step[1], prev, kept


def repeated_sum(tr: TranspilerState, e: A.Assignment, mask: str | None, old: str) -> str | None:
    """The code of the new value of a step (:func:`sum_step`) whose previous write is a step
    too: ``base + (c1 + c2 ...)`` in llvmpipe mode, the written ``old + c`` otherwise; None
    for any other write. The first step of a chain keeps the value before it (`old`) in a
    temporary and returns None."""
    step = sum_step(tr, e)
    if step is None:
        return None
    sign, k_node, prev, kept = step
    tk = tr.expr(k_node, mask)
    k = f"(-{tk})" if sign == "-" else tk
    chains = tr.fold_state.sum_chains
    known = chains.get(id(prev)) if prev is not None else None
    if known is None or known[2] is not tr.lines:
        if kept:
            chains[id(e)] = (tr.tmp(old), k, tr.lines)
        return None
    base, merged, _ = known
    merged = f"({merged} + {k})"
    chains[id(e)] = (base, merged, tr.lines)
    t = tr.type_of(e.target)
    written = tr.binary_values(sign, t, tr.type_of(k_node), old, tk)
    return f"(({base} + {merged}) if rt.lp else {written})"


def _step(tr: FoldEngine, e: Any) -> tuple[str, Any] | None:
    """("+" or "-", the constant) when `e` adds a float constant to a whole local or parameter
    and stores the sum back in it; else None."""
    if not isinstance(e, A.Assignment) or not isinstance(e.target, A.Identifier):
        return None
    sym = tr.model.symbol_of(e.target)
    t = tr.type_of(e.target)
    if sym is None or sym.kind not in ("local", "param") or t.base != "float" or t.is_matrix:
        return None
    if e.op in ("+=", "-="):
        sign, k_node = e.op[0], e.value
    elif e.op == "=" and isinstance(e.value, A.Binary) and e.value.op in ("+", "-"):
        left, right = e.value.left, e.value.right
        if _reads(tr, left, sym) and is_constant(tr, right):
            sign, k_node = e.value.op, right
        elif e.value.op == "+" and _reads(tr, right, sym) and is_constant(tr, left):
            sign, k_node = "+", left
        else:
            return None
    else:
        return None
    kt = tr.type_of(k_node)
    if not is_constant(tr, k_node) or kt.base != "float" or not (kt.is_scalar or kt == t):
        return None
    return sign, k_node


def _reads(tr: FoldEngine, node: Any, sym: Any) -> bool:
    return isinstance(node, A.Identifier) and tr.model.symbol_of(node) is sym


def _previous_step(tr: FoldEngine, e: A.Assignment) -> Any:
    """The step whose value alone reaches `e` (NIR sees it as e's operand), else None."""
    facts = function_facts(tr)
    if not facts.ok or id(e) not in facts.enter:
        return None  # (a node of an inlined body: another function's)
    sym = tr.model.symbol_of(e.target)
    before = [w for w in facts.writes_to(sym) if w.pos < facts.enter[id(e)]]
    if not before:
        return None
    w = before[-1]
    if _step(tr, w.node) is None or not facts.dominates(w.node, e):
        return None
    if facts.written_between(w.node, e, [sym]):
        return None
    return w.node


def _chained(tr: FoldEngine) -> set[int]:
    """ids of the steps of the current function that a later step continues."""
    cache = tr.fold_state.sum_chained
    key = id(current_function(tr).sym)
    if key not in cache:
        out: set[int] = set()
        body = current_function(tr).sym.node.body
        for n in body.walk():
            if isinstance(n, A.Assignment) and _step(tr, n) is not None:
                prev = _previous_step(tr, n)
                if prev is not None:
                    out.add(id(prev))
        cache[key] = out
    return cache[key]


def _varying_start(tr: FoldEngine, e: A.Assignment) -> bool:
    """The value before the chain is no constant to NIR (``b(is_not_const)``: a constant is
    folded step by step instead)."""
    facts = function_facts(tr)
    sym = tr.model.symbol_of(e.target)
    before = [w for w in facts.writes_to(sym) if w.pos < facts.enter[id(e)]]
    if not before:
        return sym.kind == "param"
    w = before[-1]
    if w.kind in ("=", "init") and w.value is not None and facts.dominates(w.node, e):
        return is_varying(tr, w.value)
    return True
