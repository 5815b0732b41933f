"""A constant added to a call's result, sunk into the ``+=`` chain the function returns.

NIR inlines every function, so ``displacement(x) - 0.4`` (iq's terrain) over ``f = 0.5*noise(p);
f += 0.25*noise(q); ... return f;`` is a sum the constant sinks into as sink.py sinks it:
``((0.5*noise(p) - 0.4) + 0.25*noise(q)) + ...`` on llvmpipe. Such a function
(:func:`sunk_return`) takes one more argument, the constant or None, passed by the call of
:func:`sunk_call`, keeps its terms in temporaries and adds the constant where NIR puts it
(:func:`sunk_order`); each engine writes these (the NumPy backend:
numpy_engine/transpile/returned_sums.py; the sum's text: cpu_core/common.sum_in_order)."""

from __future__ import annotations

from typing import Any, NamedTuple

from ....frontend import syntax as A
from ....semantics.model import Symbol
from .inlined_results import final_return
from .queries import (
    SUMS,
    asked_in,
    current_function,
    function_facts,
    is_fmul,
    is_opaque,
    use_counts,
    used_once,
)
from .sink import known_term

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..fold_protocols import FoldEngine


def sunk_return(tr: FoldEngine, fn: Symbol) -> list[tuple[Any, Any, str]] | None:
    """The sum a user function returns when a caller adds a constant to its result and NIR,
    which inlines every function, would sink that constant into it (:func:`sink._sink_sum`):
    ``float f; f = 0.5*noise(p); f += 0.25*noise(q); ... return f;`` called as
    ``displacement(x) - 0.4`` (iq's terrain) is ``((0.5*noise(p) - 0.4) + 0.25*noise(q)) + ...``
    on llvmpipe. Only the plain shape: the function's last statement returns a float local
    that nothing else reads, written by statements of the function's body (no branch, no loop)
    as ``f = a`` (or an initializer) then ``f += t`` / ``f -= t``; no out parameter, no other
    return. The terms [(write, value, operator)], else None. Such a function takes one more
    argument, the constant (None: add nothing), its terms are kept in temporaries and its
    return reads them (module doc)."""
    cache = tr.fold_state.sunk_returns
    if id(fn) not in cache:
        cache[id(fn)] = None
        if id(fn) in _sink_calls(tr) and all(d == "in" for _, _, d in fn.params):
            with asked_in(tr, fn):
                cache[id(fn)] = _return_chain(tr, fn)
    return cache[id(fn)]


def _sink_calls(tr: FoldEngine) -> set[int]:
    """ids of the user functions some call of which has a constant added to its result."""
    found = tr.fold_state.sink_calls
    if found is None:
        found = tr.fold_state.sink_calls = set()
        for sym in tr.model.reachable_functions():
            for n in sym.node.body.walk():
                if isinstance(n, A.Binary) and n.op in SUMS:
                    for call, k in ((n.left, n.right), (n.right, n.left)):
                        target = tr.model.call_target(call) if isinstance(call, A.Call) else None
                        if isinstance(target, Symbol) and tr.model.const_value(k) is not None:
                            found.add(id(target))
    return found


def _return_chain(tr: FoldEngine, fn: Symbol) -> list[tuple[Any, Any, str]] | None:
    last = final_return(fn)
    if last is None or not isinstance(last.value, A.Identifier):
        return None
    body = fn.node.body.stmts
    ret = last.value
    sym = tr.model.symbol_of(ret)
    if (
        sym is None
        or sym.kind != "local"
        or tr.type_of(ret).base != "float"
        or tr.type_of(ret).is_matrix
    ):
        return None
    for n in fn.node.body.walk():
        if (
            isinstance(n, A.Discard)
            or isinstance(n, A.Call)
            and id(tr.model.call_target(n)) in tr.facts.may_discard
        ):
            return None  # (an early exit: the return would not be the function's last statement)
    top = {id(st.expr) for st in body if isinstance(st, A.ExpressionStatement)}
    top |= {
        id(d)
        for st in body
        if isinstance(st, A.DeclarationStatement) and isinstance(st.decl, A.VariableDeclaration)
        for d in st.decl.declarators
    }
    writes = [w for w in function_facts(tr).writes_to(sym) if w.kind != "decl"]
    if len(writes) < 2 or writes[0].kind not in ("=", "init") or writes[0].value is None:
        return None
    chain = [(writes[0].node, writes[0].value, "+")]
    for w in writes[1:]:
        if not (isinstance(w.node, A.Assignment) and w.node.op in ("+=", "-=")):
            return None
        chain.append((w.node, w.node.value, w.node.op[0]))
    targets = {id(w.node.target) for w in writes if isinstance(w.node, A.Assignment)}
    for n in fn.node.body.walk():
        if (
            isinstance(n, A.Identifier)
            and tr.model.symbol_of(n) is sym
            and n is not ret
            and id(n) not in targets
        ):
            return None  # (f read elsewhere: an intermediate sum used twice)
    if any(id(w) not in top or tr.type_of(v) != tr.type_of(ret) for w, v, _ in chain):
        return None
    first = chain[0][1]
    if not (is_opaque(tr, first) or is_fmul(tr, first)):
        return None  # a sum would take the constant further
    if not all(known_term(tr, v) for _, v, _ in chain[1:]):
        return None
    if isinstance(first, A.Call) and isinstance(tr.model.call_target(first), Symbol):
        return None  # (a user function's result: what NIR sees in it is not followed)
    return chain


def sunk_call(tr: FoldEngine, e: A.Binary) -> tuple[A.Call, Any, bool] | None:
    """``f(...) +- #c`` where f has a :func:`sunk_return`: (the call, the constant, whether it
    is subtracted), else None. Not where the function computes the same sum for another call
    of this function (same arguments, or any other call of a vector function: NIR scalarises,
    then CSE merges equal components): that sum is used twice there, and the constant stays
    outside (measured). Calls in other functions are not compared: a copy CSE merges across
    functions is not detected."""
    if e.op not in SUMS:
        return None
    call, k = (e.left, e.right) if isinstance(e.left, A.Call) else (e.right, e.left)
    target = tr.model.call_target(call) if isinstance(call, A.Call) else None
    if (
        not isinstance(call, A.Call)
        or not isinstance(target, Symbol)
        or tr.model.const_value(k) is None
        or tr.type_of(k) != tr.type_of(e)
        or call is e.right
        and e.op == "-"
        or sunk_return(tr, target) is None
    ):
        return None
    if not (used_once(tr, e) and used_once(tr, call)):
        return None
    shapes = use_counts(tr)[0]
    others = [
        n
        for n in current_function(tr).sym.node.body.walk()
        if isinstance(n, A.Call) and n is not call and tr.model.call_target(n) is target
    ]
    if (
        any(shapes.get(id(n)) == shapes.get(id(call)) for n in others)
        or others
        and tr.type_of(call).is_vector
    ):
        return None  # NIR's CSE merges the inlined copies (per component for a vector): used twice
    return call, k, e.op == "-"


class SunkOrder(NamedTuple):
    """The order NIR adds a :func:`sunk_return` chain ``t0 op1 t1 op2 t2 ...`` in when a caller's
    constant k sinks into it: first ``t[joined] + k`` (``-t[joined] + k`` where `negated`), then
    each (operator, term index) of `then`, left to right."""

    joined: int
    negated: bool
    then: tuple[tuple[str, int], ...]


def sunk_order(tr: FoldEngine, chain: list[tuple[Any, Any, str]]) -> SunkOrder:
    """Where the constant sinks into a :func:`sunk_return` chain: beside the first term, or,
    when only the first term is a product, beside the second (negated for a ``-=``), the first
    added after it."""
    (_, a, _), (_, t1, op1) = chain[0], chain[1]
    later = tuple((op, i) for i, (_, _, op) in enumerate(chain[2:], 2))
    if is_fmul(tr, t1) or not is_fmul(tr, a):
        return SunkOrder(0, False, ((op1, 1), *later))
    return SunkOrder(1, op1 == "-", (("+", 0), *later))
