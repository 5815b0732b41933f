"""Products by constants merged per vector component, through component writes: NIR's SSA per
component.

NIR splits vectors into components, so a component written as ``y * #c`` (or a whole local so
written) merges with a later ``*=`` or ``*`` by a constant, also through a copy ``q = r +
0.0``, the constants folded right to left (nir_opt_algebraic visits the last instruction
first): gargantua's ``radialCoords.z = distFromDisc * 1.5; radialCoords *= 0.95;`` is
``distFromDisc * (1.5*0.95)`` (:func:`component_write`, :func:`merge_components`). A
component's ``+= e`` undone by a later ``-= e`` is its value before (``('~fadd', ('fneg', a),
('fadd', a, b)) -> b``, :func:`_cancelled_sum`)."""

from __future__ import annotations

from typing import Any

from ....frontend import syntax as A
from ....frontend.printer import to_glsl
from ....language.glsl_types import FLOAT
from ....semantics.analysis import param_directions
from .compound_products import kept_product
from .queries import (
    FunctionStandin,
    constant_value,
    current_function,
    function_facts,
    has_matrix,
    is_constant,
)

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ....semantics.model import Symbol
    from ..fold_protocols import FoldEmitter, FoldEngine


def component_write(tr: FoldEmitter, node: Any, mask: str | None, old: Any = None) -> Any:
    """The code of the value a write gives a local, component by component as NIR sees it,
    or None (the write as usual). ``node``: a declarator with an initializer, or an assignment
    ``=`` / ``*=`` (``old``: the code of the target's value before a ``*=``).

    NIR splits a vector into its components (SSA per component), so a component's last write
    is what a later product by a constant reads, and ``#a * (b * #c) -> (a*c) * b`` merges the
    two constants: gargantua's ``radialCoords.z = distFromDisc * 1.5; radialCoords *= 0.95;``
    is ``distFromDisc * (1.5*0.95)`` on llvmpipe, and ``rc = radialCoords + 0.0; ... rc * 3.0``
    (``x + 0.0`` is x) merges a third constant. For a local that is written in part (a
    component, or a compound assignment) and read in such a product, directly or through a
    copy, each write keeps, per component, the factor y and the constants c1, c2, ... of its
    value ``y * c1 * c2 ...`` (y in a temporary: :func:`_chain`), and a later ``*`` by a
    constant (:func:`merge_components`) or ``*=`` reads them through the write that last gave
    that component its value (:func:`_component_record`). The constants are folded in float32
    left to right, as NIR merges the inner product first."""
    if tr.fn is None or isinstance(tr.fn, FunctionStandin):
        return None
    if isinstance(node, A.Assignment) and node.op in ("+=", "-="):
        assert old is not None  # given with every assignment
        return _cancelled_sum(tr, node, mask, old)
    if isinstance(node, A.Declarator):
        sym, comps, value = tr.model.symbol_of(node), None, node.init
    elif node.op in ("=", "*="):
        sym, comps = _target_components(tr, node.target)
        value = node.value
    else:
        return None
    if (
        sym is None
        or id(sym) not in _component_locals(tr)
        or value is None
        or _writes_locals(tr, value)
    ):
        return None
    facts = function_facts(tr)
    if id(node) not in facts.enter:
        return None  # (a node of an inlined body)
    compound = isinstance(node, A.Assignment) and node.op == "*="
    if compound and not is_constant(tr, value):
        assert old is not None
        return kept_product(tr, node, mask, old)
    if compound and has_matrix(tr, value):
        return None
    kept = compound and any(cs for _, cs in _chain(tr, node.target, mask, keep=False)[0])
    if not kept and not _read_later(tr, facts, sym, node):
        return None  # (no product by a constant reads what this write would keep)
    if compound:
        assert old is not None
        t = tr.type_of(node.target)
        entries, old = _times(
            tr, _chain(tr, node.target, mask, keep=True)[0], old, value, _size(t), mask, True
        )
        written = tr.binary_values("*", t, tr.type_of(value), old, tr.expr(value, mask))
    else:
        entries, written = _chain(tr, value, mask, keep=True)
    n = len(entries)
    comps = comps if comps is not None else tuple(range(n))
    if len(comps) != n:
        return None
    records = tr.fold_state.components
    records[id(node)] = (tr.lines, {c: (y, cs) for c, (y, cs) in zip(comps, entries) if cs})
    return _merged_code(tr, entries, written)


def merge_components(tr: FoldEmitter, e: A.Binary, mask: str | None) -> Any:
    """``x * #k`` with x (or a swizzle of it) a local whose components :func:`component_write`
    kept, when a component's constants merge: each component ``y * (c*...*k)`` (llvmpipe
    mode), else as written."""
    if e.op != "*" or has_matrix(tr, e.left, e.right):
        return None
    k, x = (e.left, e.right) if is_constant(tr, e.left) else (e.right, e.left)
    if not is_constant(tr, k) or is_constant(tr, x) or _local_root(tr, x) is None:
        return None
    if isinstance(tr.fn, FunctionStandin) or id(_local_root(tr, x)) not in _component_locals(tr):
        return None
    entries, written = _chain(tr, e, mask, keep=False)
    if not any(len(cs) > 1 for _, cs in entries):
        return None
    return _merged_code(tr, entries, written)


def _merged_code(tr: FoldEmitter, entries: list[tuple[Any, list[Any]]], written: Any) -> Any:
    if not any(len(cs) > 1 for _, cs in entries):
        return written
    parts = []
    for y, cs in entries:
        cs = [tr.const_float(c) if isinstance(c, (int, float)) else c for c in cs]
        c = cs[-1] if cs else None
        for inner in reversed(cs[:-1]):
            c = tr.ieee("*", inner, c)  # (nir_opt_algebraic visits the last instruction first)
        parts.append(y if c is None else tr.binary_values("*", FLOAT, FLOAT, y, c))
    merged = parts[0] if len(parts) == 1 else tr.vector(parts)
    return tr.llvmpipe(merged, written)


def _chain(
    tr: FoldEmitter, node: Any, mask: str | None, keep: bool
) -> tuple[list[tuple[Any, list[Any]]], Any]:
    """([(y, [c1, c2, ...]) per component], the code of the value as written): the value of
    each component is ``y * c1 * c2 ...`` to NIR, y's code and the constants' codes.
    Followed: products by constants, swizzles, ``x + 0.0`` (x to NIR) and reads of a local
    (the components its reaching writes kept); anything else is y itself, no constant. With
    `keep`, a y that has constants is a temporary (it must outlive later writes)."""
    n = _size(tr.type_of(node))
    if isinstance(node, A.Binary) and node.op == "*" and not has_matrix(tr, node.left, node.right):
        k_left = is_constant(tr, node.left)
        k, x = (node.left, node.right) if k_left else (node.right, node.left)
        if is_constant(tr, k) and not is_constant(tr, x):
            inner, wx = _chain(tr, x, mask, keep)
            entries, wx = _times(tr, inner, wx, k, n, mask, keep)
            tk = tr.expr(k, mask)
            lt, rt_ = tr.type_of(node.left), tr.type_of(node.right)
            written = (
                tr.binary_values("*", lt, rt_, tk, wx)
                if k_left
                else tr.binary_values("*", lt, rt_, wx, tk)
            )
            return entries, written
    if (
        isinstance(node, A.Binary)
        and node.op == "+"
        and _zero(tr, node.right)
        and tr.type_of(node.left) == tr.type_of(node)
    ):
        inner, wx = _chain(tr, node.left, mask, keep)
        return inner, tr.runtime("fadd", wx, tr.expr(node.right, mask))
    if (
        isinstance(node, A.Field)
        and tr.model.is_swizzle(node)
        and not tr.type_of(node.base).is_scalar
    ):
        inner, wb = _chain(tr, node.base, mask, keep)
        idx = tr.model.swizzle_indices(node)
        return [inner[i] for i in idx], (
            tr.component(wb, idx[0]) if len(idx) == 1 else tr.swizzle(wb, tuple(idx))
        )
    code = tr.expr(node, mask)
    found: list[tuple[Any, list[Any]] | None] = [None] * n
    if isinstance(node, A.Identifier) and tr.type_of(node).base == "float":
        found = [_component_record(tr, node, i) for i in range(n)]
    return [f if f else (_component(tr, code, i, n), []) for i, f in enumerate(found)], code


def _times(
    tr: FoldEmitter,
    entries: list[tuple[Any, list[Any]]],
    code: Any,
    k: Any,
    n: int,
    mask: str | None,
    keep: bool,
) -> tuple[list[tuple[Any, list[Any]]], Any]:
    """Each component's entry times the constant k (a scalar, or a vector: its component), and
    the code of the factor (a temporary with `keep` when a component is the factor itself)."""
    if keep and any(not cs for _, cs in entries):
        code = tr.tmp(code)
        entries = [
            (y, cs) if cs else (_component(tr, code, i, len(entries)), [])
            for i, (y, cs) in enumerate(entries)
        ]
    if len(entries) == 1 and n > 1:
        entries = entries * n  # (a scalar times a vector constant)
    if tr.type_of(k).is_scalar:
        ks: list[Any] = [tr.expr(k, mask)] * n
    else:
        values = constant_value(tr, k)
        assert values is not None  # `k` was tested as a constant
        ks = list(values)  # (values: named by _merged_code only if it uses them)
    return [(y, cs + [kc]) for (y, cs), kc in zip(entries, ks)], code


def _component(tr: FoldEmitter, code: Any, i: int, n: int) -> Any:
    return code if n == 1 else tr.component(code, i)


def _size(t: Any) -> int:
    return t.size if t.is_vector else 1


def _zero(tr: FoldEngine, node: Any) -> bool:
    """A float constant +0.0 (``fadd(a, 0.0) -> a``)."""
    import math

    v = tr.model.const_value(node)
    return isinstance(v, float) and v == 0.0 and math.copysign(1.0, v) > 0


def _local_root(tr: FoldEngine, node: Any) -> Any:
    """The local or parameter a read names, through swizzles and ``+ 0.0``; else None."""
    while True:
        if isinstance(node, A.Field) and tr.model.is_swizzle(node):
            node = node.base
        elif isinstance(node, A.Binary) and node.op == "+" and _zero(tr, node.right):
            node = node.left
        else:
            break
    if isinstance(node, A.Identifier):
        s = tr.model.symbol_of(node)
        if s is not None and s.kind in ("local", "param") and tr.type_of(node).base == "float":
            return s
    return None


def _target_components(tr: FoldEngine, target: Any) -> tuple[Any, tuple[int, ...] | None]:
    """(the local an assignment writes, the components it writes: None for all) for a target
    that is a local or one swizzle of it; else (None, None)."""
    if isinstance(target, A.Identifier):
        return tr.model.symbol_of(target), None
    if (
        isinstance(target, A.Field)
        and isinstance(target.base, A.Identifier)
        and tr.model.is_swizzle(target)
        and not tr.type_of(target.base).is_scalar
    ):
        return tr.model.symbol_of(target.base), tuple(tr.model.swizzle_indices(target))
    return None, None


def component_locals(tr: FoldEngine) -> set[int]:
    """ids of the locals whose writes :func:`component_write` computes (loop_copies.py asks)."""
    return _component_locals(tr)


def _component_locals(tr: FoldEngine) -> set[int]:
    """ids of the float locals of the current function :func:`component_write` follows: written
    in part (a component, a compound assignment) and read in a product by a constant (or by
    ``*=`` one), directly or through a copy into such a local."""
    cache = tr.fold_state.component_locals
    key = id(current_function(tr).sym)
    if key in cache:
        return cache[key]
    facts = function_facts(tr)
    if not facts.ok:
        cache[key] = set()
        return cache[key]
    partly = {
        key_ for key_, ws in facts.writes.items() if any(w.kind in ("part", "op") for w in ws)
    }
    reads: dict[int, list[Any]] = {}  # id(symbol) -> the nodes that read it so
    copies: list[tuple[Any, Any, Any]] = []
    for n in current_function(tr).sym.node.body.walk():
        if isinstance(n, A.Binary) and n.op == "*":
            for a, b in ((n.left, n.right), (n.right, n.left)):
                s = _local_root(tr, b) if is_constant(tr, a) and not is_constant(tr, b) else None
                if s is not None:
                    reads.setdefault(id(s), []).append(n)
        elif isinstance(n, A.Assignment) and n.op == "*=" and is_constant(tr, n.value):
            s = _target_components(tr, n.target)[0]
            if s is not None:
                reads.setdefault(id(s), []).append(n)
        elif isinstance(n, A.Assignment) and n.op == "=" and isinstance(n.target, A.Identifier):
            copies.append((tr.model.symbol_of(n.target), _local_root(tr, n.value), n))
        elif isinstance(n, A.Declarator) and n.init is not None:
            copies.append((tr.model.symbol_of(n), _local_root(tr, n.init), n))
    grew = True
    while grew:
        grew = False
        for t, s, n in copies:
            if t is not None and s is not None and id(t) in reads and n not in reads.get(id(s), ()):
                reads.setdefault(id(s), []).append(n)
                grew = True
    tr.fold_state.component_reads[key] = reads
    cache[key] = set(reads) & partly
    return cache[key]


def _cancelled_sum(tr: FoldEmitter, node: A.Assignment, mask: str | None, old: Any) -> Any:
    """``x.y += e; ... x.y -= e`` (either order, e the same text, its variables not written in
    between): x.y is its value before the ``+=`` to NIR (``('~fadd', ('fneg', a), ('fadd', a,
    b)) -> b``), with the constants :func:`component_write` kept for it (gargantua's ``rc.y +=
    iTime * speed; ... rc.y -= iTime * speed; ... rc * 6.0``). Each such write keeps the
    component's value before it (a temporary) for a later write that cancels it."""
    if tr.fn is None or isinstance(tr.fn, FunctionStandin):
        return None
    sym, comps = _target_components(tr, node.target)
    value = node.value
    if (
        sym is None
        or id(sym) not in _component_locals(tr)
        or _writes_locals(tr, value)
        or has_matrix(tr, value)
    ):
        return None
    facts = function_facts(tr)
    if id(node) not in facts.enter or tr.type_of(node.target).base != "float":
        return None
    target = node.target  # a local or one swizzle of it (_target_components)
    assert isinstance(target, (A.Identifier, A.Field))
    ident = target if isinstance(target, A.Identifier) else target.base
    assert isinstance(ident, A.Identifier)
    comps = comps if comps is not None else tuple(range(_size(tr.type_of(node.target))))
    undo = tr.fold_state.undo
    records = tr.fold_state.components
    before: (
        list[Any] | None
    ) = []  # per component: (code, record) of its value before the write this one cancels
    for c in comps:
        w = _component_source(tr, ident, c)
        kept = undo.get(id(w.node)) if w is not None else None
        if (
            kept is None
            or kept[0] is not tr.lines
            or c not in kept[1]
            or w.node.op == node.op
            or to_glsl(w.node.value) != to_glsl(value)
            or tr.type_of(w.node.value) != tr.type_of(value)
        ):
            before = None
            break
        read = [tr.model.symbol_of(n) for n in value.walk() if isinstance(n, A.Identifier)]
        if facts.written_between(w.node, node, [r for r in read if r is not None]):
            before = None
            break
        assert before is not None  # (set to None only on the way out of the loop)
        before.append(kept[1][c])
    if before is None and not _cancelled_later(tr, facts, sym, node):
        return None
    n = len(comps)
    t_old = tr.tmp(old)
    undo[id(node)] = (
        tr.lines,
        {
            c: (_component(tr, t_old, j, n), _component_record(tr, ident, c))
            for j, c in enumerate(comps)
        },
    )
    written = tr.binary_values(
        node.op[0], tr.type_of(node.target), tr.type_of(value), t_old, tr.expr(value, mask)
    )
    if before is None:
        return written
    records[id(node)] = (tr.lines, {c: rec for c, (_, rec) in zip(comps, before) if rec})
    lp = before[0][0] if n == 1 else tr.vector([code for code, _ in before])
    return tr.llvmpipe(lp, written)


def _cancelled_later(tr: FoldEngine, facts: Any, sym: Symbol, node: A.Assignment) -> bool:
    """A later compound assignment of ``sym`` subtracts what ``node`` adds (or adds what it
    subtracts), the same text: :func:`_cancelled_sum` may need the value before ``node``."""
    text, end = to_glsl(node.value), facts.exit[id(node)]
    return any(
        isinstance(w.node, A.Assignment)
        and w.node.op in ("+=", "-=")
        and w.node.op != node.op
        and w.pos > end
        and to_glsl(w.node.value) == text
        for w in facts.writes_to(sym)
    )


def _component_record(tr: FoldEngine, ident: A.Identifier, i: int) -> tuple[Any, list[Any]] | None:
    """(y, constants) :func:`component_write` kept for component i of the local read here (from
    :func:`_component_source`'s write)."""
    last = _component_source(tr, ident, i)
    kept = tr.fold_state.components.get(id(last.node)) if last is not None else None
    if kept is None or kept[0] is not tr.lines:
        return None  # (not kept, or kept in another Python function: an outlined part)
    return kept[1].get(i)


def _component_source(tr: FoldEngine, ident: A.Identifier, i: int) -> Any:
    """The write (analysis.dataflow.Write) that last gave component i of the local read here its
    value: it runs before this read on every path, and nothing writes the component in between
    (loops around the read included); else None."""
    sym = tr.model.symbol_of(ident)
    if sym is None or sym.kind not in ("local", "param"):
        return None
    facts = function_facts(tr)
    if not facts.ok or id(ident) not in facts.enter:
        return None
    at = facts.enter[id(ident)]
    writes = facts.writes_to(sym)
    last = None
    for w in writes:
        if w.pos < at and _writes_component(tr, w, i):
            last = w
    if last is None or not facts.dominates(last.node, ident):
        return None
    loops_w = {id(lp) for lp in facts.enclosing_loops(last.node)}
    for loop in facts.enclosing_loops(ident):
        if id(loop) not in loops_w:
            lo, hi = facts.enter[id(loop)], facts.exit[id(loop)]
            if any(lo <= w.pos <= hi and _writes_component(tr, w, i) for w in writes):
                return None
    return last


def _writes_locals(tr: FoldEngine, value: Any) -> bool:
    """The expression writes a variable (an assignment, ++/--, an out argument): a user call
    that only reads its arguments is computed once, as written, so it may stay."""
    for n in value.walk():
        if (
            isinstance(n, (A.Assignment, A.Sequence))
            or isinstance(n, (A.Unary, A.Postfix))
            and n.op in ("++", "--")
        ):
            return True
        if isinstance(n, A.Call) and any(
            d != "in" for d in param_directions(tr.model.call_target(n))
        ):
            return True
    return False


def _read_later(tr: FoldEngine, facts: Any, sym: Symbol, node: Any) -> bool:
    """A product by a constant (or a copy into a local read so) reads ``sym`` after ``node``
    (one before it, in a loop, is not reached by this write: :func:`_component_record`)."""
    end = facts.exit[id(node)]
    return any(facts.enter.get(id(r), -1) > end for r in _component_reads(tr).get(id(sym), ()))


def _component_reads(tr: FoldEngine) -> dict[int, list[Any]]:
    _component_locals(tr)
    return tr.fold_state.component_reads[id(current_function(tr).sym)]


def _writes_component(tr: FoldEngine, w: Any, i: int) -> bool:
    if isinstance(w.node, A.Assignment):
        comps = _target_components(tr, w.node.target)[1]
        if comps is not None:
            return i in comps
    return True
