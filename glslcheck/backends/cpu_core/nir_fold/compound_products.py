"""A constant sunk through a compound product: ``x *= b; ... x * #c`` is ``(a * #c) * b``.

``('~fmul', ('fmul(is_used_once)', a, b), '#c') -> (a * #c) * b`` applies to the SSA value
``x *= b`` makes when the product by the constant is its only read (gargantua's ``coverage *=
saturate(..); coverage = saturate(coverage * 0.7)``). The ``*=`` keeps its factors in
temporaries (:func:`kept_product`) for the read (:func:`sunk_through_compound`). Copied one
level deep only (:func:`_sink_reads` says where)."""

from __future__ import annotations

from typing import Any

from ....frontend import syntax as A
from ....frontend.printer import to_glsl
from ....semantics.model import Symbol
from .inlined_results import final_return
from .queries import (
    FunctionStandin,
    current_function,
    function_facts,
    has_matrix,
    is_constant,
    is_product,
)

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..fold_protocols import FoldEmitter, FoldEngine


def kept_product(tr: FoldEmitter, node: A.Assignment, mask: str | None, old: Any) -> Any:
    """``x *= b`` read once, by a product by a constant: its factors kept for
    :func:`sunk_through_compound` (None: the write as usual)."""
    if not isinstance(node.target, A.Identifier) or id(node) not in _sink_reads(tr).values():
        return None
    t = tr.type_of(node.target)
    ta, tb = tr.tmp(old), tr.tmp(tr.expr(node.value, mask))
    tr.fold_state.kept_products[id(node)] = (tr.lines, ta, tb)
    return tr.binary_values("*", t, tr.type_of(node.value), ta, tb)


def sunk_through_compound(tr: FoldEmitter, e: A.Binary, mask: str | None) -> Any:
    """``x * #c`` where x's value is ``a * b`` from ``x *= b``, read only here: ``(a * #c) * b``
    (``('~fmul', ('fmul(is_used_once)', a, b), '#c') -> (a * #c) * b``, the product used once
    in SSA): gargantua's ``coverage *= saturate(..); coverage = saturate(coverage * 0.7)``.
    Copied one level deep only: where a is itself a product NIR sees as used once the constant
    sinks on (not copied, left as written), so a must not be one (a sum, a built-in, or a
    call of a user function repeated with the same arguments in the function: CSE shares
    its value, as gargantua's second ``pcurve(radialGradient, 4.0, 0.9)``)."""
    if (
        isinstance(tr.fn, FunctionStandin)
        or getattr(current_function(tr).sym, "node", None) is None
    ):
        return None  # (a global's initializer)
    w_id = _sink_reads(tr).get(id(e))
    kept = tr.fold_state.kept_products.get(w_id) if w_id is not None else None
    if kept is None or kept[0] is not tr.lines:
        return None
    k = e.right if is_constant(tr, e.right) else e.left
    tk = tr.expr(k, mask)
    written = tr.binary_values(
        "*", tr.type_of(e.left), tr.type_of(e.right), *tr.exprs([e.left, e.right], mask)
    )
    t = tr.type_of(e)
    sunk = tr.binary_values(
        "*", t, t, tr.binary_values("*", t, tr.type_of(k), kept[1], tk), kept[2]
    )
    return tr.llvmpipe(sunk, written)


def _returns_product(tr: FoldEngine, call: A.Call) -> bool:
    """The user function called returns a product (its last statement ``return a * b``), or
    its result is not known here."""
    target = tr.model.call_target(call)
    assert isinstance(target, Symbol)  # asked for calls of user functions
    last = final_return(target)
    return last is None or is_product(tr, last.value)


def _sink_reads(tr: FoldEngine) -> dict[int, int]:
    """id(``x * #c``) -> id(``x *= b``) for the products :func:`sunk_through_compound`
    rewrites: b not constant, x's value read only by that product, the value x had before
    the ``*=`` not a product NIR would sink into (see there)."""
    cache = tr.fold_state.sink_reads
    key = id(current_function(tr).sym)
    if key in cache:
        return cache[key]
    out: dict[int, int] = {}
    facts = function_facts(tr)
    calls: dict[str, int] = {}
    for n in current_function(tr).sym.node.body.walk():
        if isinstance(n, A.Call) and isinstance(tr.model.call_target(n), Symbol):
            calls[to_glsl(n)] = calls.get(to_glsl(n), 0) + 1
    reads: dict[int, list[Any]] = {}
    targets = {
        id(n.target)
        for n in current_function(tr).sym.node.body.walk()
        if isinstance(n, A.Assignment) and n.op == "="
    }
    for n in current_function(tr).sym.node.body.walk():
        if (
            isinstance(n, A.Identifier)
            and tr.model.symbol_of(n) is not None
            and id(n) not in targets
        ):
            reads.setdefault(id(tr.model.symbol_of(n)), []).append(n)
    for n in current_function(tr).sym.node.body.walk() if facts.ok else ():
        if not (
            isinstance(n, A.Binary)
            and n.op == "*"
            and tr.type_of(n).base == "float"
            and not has_matrix(tr, n.left, n.right)
        ):
            continue
        x = n.left if is_constant(tr, n.right) else n.right if is_constant(tr, n.left) else None
        if not isinstance(x, A.Identifier) or is_constant(tr, x) or id(x) not in facts.enter:
            continue
        sym = tr.model.symbol_of(x)
        before = [w for w in facts.writes_to(sym) if w.pos < facts.enter[id(x)]]
        w = before[-1] if before else None
        if (
            w is None
            or not isinstance(w.node, A.Assignment)
            or w.node.op != "*="
            or is_constant(tr, w.node.value)
            or not isinstance(w.node.target, A.Identifier)
            or tr.type_of(w.node.target) != tr.type_of(x)
            or not facts.dominates(w.node, x)
            or facts.written_between(w.node, x, [sym])
        ):
            continue
        later = [w2.pos for w2 in facts.writes_to(sym) if w2.pos > w.pos]
        end = min(later) if later else None
        users = [
            r
            for r in reads.get(id(sym), ())
            if id(r) in facts.enter
            and facts.enter[id(r)] > w.pos
            and (end is None or facts.enter[id(r)] < end)
            and r is not w.node.target
        ]
        if users != [x] or facts.enclosing_loops(x) != facts.enclosing_loops(w.node):
            continue
        prev = [v for v in facts.writes_to(sym) if v.pos < facts.enter[id(w.node.target)]]
        a = prev[-1].value if prev and prev[-1].kind in ("=", "init") else None
        if (
            a is None
            or is_product(tr, a)
            or (
                isinstance(a, A.Call)
                and isinstance(tr.model.call_target(a), Symbol)
                and calls.get(to_glsl(a), 0) < 2
                and _returns_product(tr, a)
            )
        ):
            continue
        out[id(n)] = id(w.node)
    cache[key] = out
    return out
