"""Constants merged into the value a variable holds in each copy of a loop NIR unrolls.

NIR unrolls a loop of a constant count with a small body (loop_unroll.py) and runs its algebraic
rules on the copies again: a read of a variable at the top of the body is, in the first copy,
the value the variable had before the loop and, in every later copy, the value the body's last
write gave it (SSA: no phi is left). Where that value is ``y * #b`` (``y + #b``), a product by
(a sum with) a constant at the read merges with it, ``#a * (b * #c) -> (a*c) * b`` and ``#a +
(b + #c) -> (a + c) + b`` (constant_merge.py; no "used once" condition), the constants folded in
float32: ``float a = p.y * 0.013; for (int i = 0; i < 3; i++) a = sin(a * 1.01) * 0.7;`` is
``sin(p.y * (0.013*1.01))`` in the first copy and ``sin(s * (0.7*1.01))`` in the later ones;
``a *= 1.01`` and ``a += 1.01`` are such a read, and ``a * float(i) * 1.01`` is one once the
copy's ``float(i)`` is a constant (measured: tests/gl/test_llvmpipe_loop_copies.py). A sum
through a variable assigned again merges the same way outside a loop (constant_merge.py follows
a sum only into a never-written local; a product through ssa_values.product_parts).

The value's y is kept in a temporary where the write computes it (ssa_values.keep_factor, for
the reads :func:`reaching_values` names); the read takes the copy's code by the loop's pass
count (repeated_sums.indexed_loop counts it where :func:`merging_loop` says so)."""

from __future__ import annotations

from typing import Any

from ....frontend import syntax as A
from ....semantics.model import Symbol
from ..facts import induction_variable
from .components import component_locals
from .loop_unroll import nir_unrolls
from .queries import (
    SUMS,
    constant_value,
    current_function,
    function_facts,
    has_matrix,
    is_constant,
    is_varying,
    reaching_value,
)

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..fold_protocols import FoldEmitter, FoldEngine

_LEAVES = (A.Break, A.Continue, A.Return, A.Discard, A.For, A.While, A.DoWhile)


def reaching_values(tr: FoldEngine, ident: A.Identifier) -> tuple[Any, list[Any]] | None:
    """(None, [value]) for a read the last whole write reaches alone (queries.reaching_value);
    (loop, [value before the loop or None, value of the body's last write]) for a read at the
    top of the body of a loop NIR unrolls whole (no early exit, no loop inside), which no write
    in the body precedes and whose last write in the body runs on every pass; else None."""
    value = reaching_value(tr, ident)
    if value is not None:
        return None, [value]
    sym = tr.model.symbol_of(ident)
    if sym is None or sym.kind not in ("local", "param") or tr.fn is None:
        return None
    facts = function_facts(tr)
    if not facts.ok or id(ident) not in facts.enter:
        return None
    loops = facts.enclosing_loops(ident)
    loop = loops[-1] if loops else None
    if not isinstance(loop, A.For) or not facts.contains(loop.body, ident):
        return None
    inner = facts.region[id(loop.body)]
    read_at = facts.enter[id(ident)]
    writes = [w for w in facts.writes_to(sym) if facts.contains(loop, w.node)]
    if not writes or facts.region[id(ident)] != inner or any(w.pos < read_at for w in writes):
        return None
    last = writes[-1]
    if last.kind not in ("=", "init") or last.value is None or facts.region[id(last.node)] != inner:
        return None
    if not _whole_copies(tr, loop):
        return None
    before = [w for w in facts.writes_to(sym) if w.pos < facts.enter[id(loop)]]
    first = None
    if before and before[-1].kind in ("=", "init") and before[-1].value is not None:
        w = before[-1]
        if facts.dominates(w.node, loop) and not facts.written_between(w.node, loop, [sym]):
            first = w.value
    return loop, [first, last.value]


def _whole_copies(tr: FoldEngine, loop: A.For) -> bool:
    """NIR unrolls `loop` and every copy runs its whole body."""
    if not nir_unrolls(tr, loop):
        return False
    return not any(isinstance(n, _LEAVES) for n in loop.body.walk())


def merging_loop(tr: FoldEngine, loop: Any) -> bool:
    """Some read in the unrolled `loop` merges a constant in one copy and not in another (or
    with other constants): the engines count its passes."""
    cache = tr.fold_state.copy_loops
    if id(loop) not in cache:
        cache[id(loop)] = isinstance(loop, A.For) and any(
            isinstance(n, (A.Binary, A.Assignment)) and (_copies(tr, n) or (None,))[0] is loop
            for n in loop.body.walk()
        )
    return cache[id(loop)]


def _operands(tr: FoldEngine, e: Any) -> tuple[str, Any, Any, Any] | None:
    """(op, #k, the read x, g) of ``x op #k`` (``#k op x``; ``-`` with k on the right), of a
    compound ``x op= #k`` (g None), or of ``(x op g) op #k`` (either order in both, not ``-``)
    with g a constant in each copy of a loop NIR unrolls (:func:`copy_constant`); else None."""
    if isinstance(e, A.Assignment):
        if e.op not in ("*=", "+=", "-=") or not is_constant(tr, e.value):
            return None
        return e.op[0], e.value, e.target, None
    if not isinstance(e, A.Binary) or e.op not in ("*", "+", "-"):
        return None
    if e.op == "-" and not is_constant(tr, e.right):
        return None
    k_node, x_node = (e.right, e.left) if is_constant(tr, e.right) else (e.left, e.right)
    if not is_constant(tr, k_node) or is_constant(tr, x_node):
        return None
    if isinstance(x_node, A.Binary) and x_node.op == e.op and e.op != "-":
        for g, b in ((x_node.right, x_node.left), (x_node.left, x_node.right)):
            if copy_constant(tr, g) and not is_constant(tr, b) and not copy_constant(tr, b):
                if tr.type_of(x_node) != tr.type_of(b) or has_matrix(tr, b, g) or _merges(tr, b):
                    return None  # (b's own constant would merge too: not copied)
                return e.op, k_node, b, g
    return e.op, k_node, x_node, None


def _merges(tr: FoldEngine, b: Any) -> bool:
    """b is a product (sum) with a constant operand, which NIR would merge into further."""
    return (
        isinstance(b, A.Binary)
        and b.op in ("*", "+", "-")
        and (is_constant(tr, b.left) or is_constant(tr, b.right))
    )


def copy_constant(tr: FoldEngine, node: Any) -> bool:
    """`node` is computed from the induction variables of loops NIR unrolls around it (in their
    bodies) and constants only: a constant in each copy (``float(i)``), which the copy's
    algebraic rules merge like one."""
    if tr.fn is None or is_constant(tr, node) or tr.has_effects(node):
        return False
    facts = function_facts(tr)
    if not facts.ok or id(node) not in facts.enter:
        return False
    inductions = {
        id(induction_variable(lp, tr.model))
        for lp in facts.enclosing_loops(node)
        if isinstance(lp, A.For) and facts.contains(lp.body, node) and nir_unrolls(tr, lp)
    }
    seen = False
    for n in node.walk():
        if isinstance(n, A.Call) and isinstance(tr.model.call_target(n), Symbol):
            return False  # (a user function: not followed)
        if isinstance(n, A.Identifier):
            sym = tr.model.symbol_of(n)
            if sym is not None and id(sym) in inductions:
                seen = True
            elif not is_constant(tr, n):
                return False
    return seen


def _copies(tr: FoldEngine, e: Any) -> tuple[Any, list[Any]] | None:
    """(loop, the values of the read operand of ``x op #k`` or ``x op= #k`` per copy) where
    one merges."""
    ops = _operands(tr, e) if tr.fn is not None else None
    if ops is None or not isinstance(ops[2], A.Identifier):
        return None
    op, _, x_node, _ = ops
    t = tr.type_of(x_node)
    if t is None or t.base != "float" or t.is_matrix or tr.type_of(e) != t:
        return None
    found = reaching_values(tr, x_node)
    if found is None or (found[0] is None and op == "*"):
        return None  # (a product in straight line: constant_merge.py, ssa_values.product_parts)
    if not any(_parts(tr, op, v, t) is not None for v in found[1]):
        return None
    return found


def merged_copies(tr: FoldEmitter, e: Any, mask: str | None, old: Any = None) -> Any:
    """``x * #k`` (``x + #k``, ``x - #k``, or a compound ``x op= #k`` whose `old` is x's code)
    with the constant merged into the value x holds in each copy of an unrolled loop
    (:func:`reaching_values`), as written in a copy where it does not merge or y was not kept;
    a sum through a variable assigned again the same way; ``(x op g) op #k`` with g a copy's
    constant as ``x op (g op k)``, k merged on into x's value likewise."""
    ops = _operands(tr, e) if tr.fn is not None else None
    if ops is None:
        return None
    op, k_node, x_node, g = ops
    t = tr.type_of(e)
    if t is None or t.base != "float" or t.is_matrix:
        return None
    found = _copies(tr, e)
    sym = tr.model.symbol_of(x_node) if isinstance(x_node, A.Identifier) else None
    if found is not None and not any(_held(tr, op, v, t, sym) for v in found[1]):
        found = None  # (no copy's y kept: as written)
    if found is None and g is None:
        return None
    tk = tr.expr(k_node, mask)
    inner = x_node if g is None else e.left if is_constant(tr, e.right) else e.right
    tx = old if old is not None else tr.expr(inner, mask)
    x_left = isinstance(e, A.Assignment) or inner is e.left
    if op == "*":
        xt, kt = tr.type_of(inner), tr.type_of(k_node)
        written = (
            tr.binary_values("*", xt, kt, tx, tk)
            if x_left
            else tr.binary_values("*", kt, xt, tk, tx)
        )
    else:
        written = tr.ieee(op, tx, tk) if x_left else tr.ieee(op, tk, tx)
    if g is not None:
        tk = tr.ieee(op, tr.expr(g, mask), tk)  # (folded in float32 in the copy)
    codes = [None]
    if found is not None:
        codes = [_merged(tr, op, tk, v, t, mask, sym) for v in found[1]]
    if g is not None:
        tb = tr.expr(x_node, mask)
        plain = tr.binary_values("*", t, t, tb, tk) if op == "*" else tr.ieee("+", tk, tb)
    elif all(c is None for c in codes):
        return None
    else:
        plain = written
    codes = [plain if c is None else c for c in codes]
    if found is None or found[0] is None:
        return tr.llvmpipe(codes[0], written)
    return tr.llvmpipe(tr.by_copy(found[0], codes[0], codes[1]), written)


def _parts(tr: FoldEngine, op: str, value: Any, t: Any) -> tuple[Any, Any, str, str] | None:
    """(b, #c, c's sign, b's sign) of a value ``b * #c`` (or ``b +- #c``, ``#c +- b`` for a sum)
    that a constant of `op` merges into; None for another value."""
    if not isinstance(value, A.Binary) or value.op not in (("*",) if op == "*" else SUMS):
        return None
    if tr.has_effects(value) or tr.type_of(value) != t:
        return None
    left, right = value.left, value.right
    if is_constant(tr, right) and not is_constant(tr, left):
        b, c, c_sign, b_sign = left, right, value.op, "+"
    elif is_constant(tr, left) and not is_constant(tr, right):
        b, c, c_sign, b_sign = right, left, "+", value.op
    else:
        return None
    if has_matrix(tr, b, c) or not is_varying(tr, b) or tr.type_of(b) != t:
        return None
    if (
        isinstance(b, A.Binary)
        and b.op in (("*",) if op == "*" else SUMS)
        and (is_constant(tr, b.left) or is_constant(tr, b.right))
    ):
        return None  # NIR would merge further into b: not copied (as constant_merge.py)
    return b, c, c_sign, b_sign


def _merged(
    tr: FoldEmitter, op: str, tk: Any, value: Any, t: Any, mask: str | None, sym: Any
) -> Any:
    """The code of ``x op #k`` with x's `value` merged (its y kept by ssa_values.keep_factor in
    this Python function, or to be kept there at the end of the previous pass, or for a product
    by components.py's record of the write), else None."""
    parts = _parts(tr, op, value, t) if value is not None else None
    if parts is None:
        return None
    _, c_node, c_sign, b_sign = parts
    kept = tr.fold_state.kept.get(id(value)) or tr.fold_state.kept_slots.get(id(value))
    if kept is None and op == "*" and t.is_scalar:
        return _merged_record(tr, tk, value, t, sym)
    if kept is None or kept[1] is not tr.lines:
        return None
    tb, tc = kept[0], tr.expr(c_node, mask)
    if op == "*":
        return tr.binary_values("*", t, t, tb, tr.ieee("*", tk, tc))
    k = tr.negate(tk) if op == "-" else tk
    c = tr.negate(tc) if c_sign == "-" else tc
    return tr.ieee(b_sign, tr.ieee("+", k, c), tb)


def _held(tr: FoldEngine, op: str, value: Any, t: Any, sym: Any) -> bool:
    """:func:`_merged` can merge into `value` here: its y kept (or to be kept) in this Python
    function, or components.py's record of it."""
    if value is None or _parts(tr, op, value, t) is None:
        return False
    kept = tr.fold_state.kept.get(id(value)) or tr.fold_state.kept_slots.get(id(value))
    if kept is not None:
        return kept[1] is tr.lines
    return op == "*" and t.is_scalar and _record(tr, value, sym) is not None


def _record(tr: FoldEngine, value: Any, sym: Any) -> Any:
    """components.py's (y, constants) of component 0 of the write of `sym` whose value is
    `value`, kept in this Python function; else None."""
    write = next((w for w in function_facts(tr).writes_to(sym) if w.value is value), None)
    record = tr.fold_state.components.get(id(write.node)) if write is not None else None
    if record is None or record[0] is not tr.lines:
        return None
    return record[1].get(0)


def _merged_record(tr: FoldEmitter, tk: Any, value: Any, t: Any, sym: Any) -> Any:
    """``x * #k`` where components.py kept x's value ``y * #c`` (a local it follows: one written
    by ``*=`` or in part), read through its record of the write: ``y * (k*c)``."""
    record = _record(tr, value, sym)
    if record is None:
        return None
    y, cs = record
    if len(cs) != 1:
        return None  # (more constants: merged in an order not measured in a loop's copies)
    c = tr.const_float(cs[0]) if isinstance(cs[0], (int, float)) else cs[0]
    return tr.binary_values("*", t, t, y, tr.ieee("*", tk, c))


def merged_value(tr: FoldEngine, value: Any) -> bool:
    """`value` (the whole new value of a write) is one a constant merges into at some read of
    the current function, in a copy of an unrolled loop or, for a sum, in straight line
    (:func:`merged_copies`): its y is worth keeping."""
    return id(value) in _merged_values(tr)[0]


def later_values(tr: FoldEngine, loop: Any) -> list[tuple[Any, Any]]:
    """(value, its variable) of the writes in `loop`'s body whose value a later copy merges a
    constant into: the engines hold its y in a temporary made before the loop (so the first
    pass defines it, and a loop that moves lanes moves it too), which :func:`kept_in_slot`
    fills."""
    return _merged_values(tr)[1].get(id(loop), [])


def kept_in_slot(tr: FoldEmitter, e: A.Binary, mask: str | None) -> Any:
    """The code of a write's value ``y * #c`` (``y +- #c``) that a later copy of its loop merges
    a constant into (:func:`later_values`), as written, y stored in the temporary made before
    the loop; None for any other expression. Tried before every other rule: the later copy's
    read was emitted with that temporary, so y must be stored whatever else applies."""
    slot = tr.fold_state.kept_slots.get(id(e))
    if slot is None or slot[1] is not tr.lines:
        return None
    t = tr.type_of(e)
    parts = _parts(tr, tr.fold_state.slot_ops[id(e)], e, t)
    assert parts is not None  # (later_values took it for such a value)
    y, c_node, _, _ = parts
    ty = tr.store(slot[0], tr.expr(y, mask))
    tc = tr.expr(c_node, mask)
    tr.fold_state.kept[id(e)] = (ty, tr.lines)
    if e.op == "*":
        ct = tr.type_of(c_node)
        left = y is e.left
        return (
            tr.binary_values("*", t, ct, ty, tc) if left else tr.binary_values("*", ct, t, tc, ty)
        )
    return tr.ieee(e.op, ty, tc) if y is e.left else tr.ieee(e.op, tc, ty)


def _slot_filled(tr: FoldEngine, op: str, value: Any, sym: Any) -> bool:
    """The engines emit `value` through the rules' dispatch, where :func:`kept_in_slot` stores
    its y: not a write components.py computes per component, nor a step of a ``+=`` chain
    (repeated_sums.py: ``x = x + #c``)."""
    if id(sym) in component_locals(tr):
        return False
    y = _parts(tr, op, value, tr.type_of(value))
    return y is not None and not (op != "*" and isinstance(y[0], A.Identifier))


def _merged_values(tr: FoldEngine) -> tuple[set[int], dict[int, list[tuple[Any, Any]]]]:
    cache = tr.fold_state.copy_values
    key = id(current_function(tr).sym)
    if key not in cache:
        out: set[int] = set()
        later: dict[int, list[tuple[Any, Any]]] = {}
        for n in current_function(tr).sym.node.body.walk():
            found = _copies(tr, n) if isinstance(n, (A.Binary, A.Assignment)) else None
            if found is None:
                continue
            op, _, x_node, _ = _operands(tr, n)  # type: ignore[misc]  # (_copies found them)
            t = tr.type_of(x_node)
            for i, v in enumerate(found[1]):
                if _parts(tr, op, v, t) is None or id(v) in out:
                    continue
                out.add(id(v))
                sym = tr.model.symbol_of(x_node)
                if found[0] is not None and i == 1 and _slot_filled(tr, op, v, sym):
                    later.setdefault(id(found[0]), []).append((v, sym))
                    tr.fold_state.slot_ops[id(v)] = op
        cache[key] = out, later
    return cache[key]


def nonzero_constant(tr: FoldEngine, node: Any) -> bool:
    """A constant none of whose components is zero (``x + 0.0`` is x to NIR: added_zero.py)."""
    value = constant_value(tr, node)
    return value is not None and all(v != 0.0 for v in value)
