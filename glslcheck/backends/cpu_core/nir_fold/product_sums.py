"""A term added to a sum of two products joins the first product: ``(p1 + p2) + e`` is
``(p1 + e) + p2``.

nir_opt_algebraic reassociates add chains "for more MAD/FMA-friendly code" (Mesa 22.3,
src/compiler/nir/nir_opt_algebraic.py): ``~fadd(fadd(is_used_once)(a(is_fmul), b(is_fmul)),
c(is_not_fmul)) -> fadd(fadd(a, c), b)``, where is_fmul and is_not_fmul look through an fneg.
The search tries the written operand order first, so ``a`` is the first product written, and
``e`` may stand on either side of the sum. A path tracer's seed ``p.x*c1 + p.y*c2 + iTime`` is
so ``(p.x*c1 + iTime) + p.y*c2`` on llvmpipe. Measured on llvmpipe (160x90, 14,400 values each,
tests/gl/test_llvmpipe_product_sums.py):

- e any value that is no product: a uniform, ``fract(1.12*iTime)``, a non-uniform opaque
  value, a sum, a quotient, a negated value; ``p1 - p2``, ``(p1 + p2) - e``, ``e + (p1 + p2)``
  and a sum held in a local read once likewise; vectors per component, a scalar e too;
- a factorable sum ``u*v + u*q`` takes e before it is factored: the rule rewrites the outer
  addition, which NIR visits first;
- kept as written: e a product (``iTime*iTime``, ``z*0.5``, ``-(z*w)``), a term of the sum no
  product (``p.x + p.y*c2 + e``, ``p.x/3.0 + ...``), three products (``(p1 + p2) + p3``'s
  sum is no sum of two products), a sum used twice, ``e - (p1 + p2)`` (an fneg of the sum).

A constant e is the sink's (sink.py: the same order), so this rule leaves it out."""

from __future__ import annotations

from typing import Any

from ....frontend import syntax as A
from .queries import (
    SUMS,
    current_function,
    function_facts,
    is_constant,
    is_fmul,
    is_opaque,
    one_copy,
    reaching_value,
    read_once,
    stable_init,
    used_once,
)

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..fold_protocols import FoldEmitter, FoldEngine


def product_sum(tr: FoldEmitter, e: A.Binary, mask: str | None) -> Any:
    """``(p1 + p2) + e`` (or ``- e``, or ``e + (p1 + p2)``, ``p1 - p2`` inside) as
    ``(p1 + e) + p2`` under llvmpipe; None where the rule does not apply."""
    match = product_sum_parts(tr, e)
    if match is None:
        return None
    p1, p2, inner_op, other = match
    tp1, tp2, to, tl, trr = tr.exprs([p1, p2, other, e.left, e.right], mask)
    first = tr.ieee("-" if e.op == "-" else "+", tp1, to)
    return tr.llvmpipe(tr.ieee(inner_op, first, tp2), tr.ieee(e.op, tl, trr))


def product_sum_parts(tr: FoldEngine, e: A.Binary) -> tuple[Any, Any, str, Any] | None:
    """(p1, p2, the sum's operator, e) when ``e`` is a sum the rule rewrites, else None."""
    if e.op not in SUMS or tr.has_effects(e):
        return None
    if getattr(current_function(tr).sym.node, "body", None) is None:
        return None  # (a global's initializer: computed as written)
    t = tr.type_of(e)
    if t.base != "float" or t.is_matrix:
        return None
    sides = [(e.left, e.right)] + ([(e.right, e.left)] if e.op == "+" else [])
    for s, other in sides:  # (the written order first, as nir_search tries it)
        inner = _sum_value(tr, s)
        if inner is None or tr.type_of(s) != t:
            continue
        p1, p2 = inner.left, inner.right
        if not all(tr.type_of(p) == t and _fmul(tr, p) for p in (p1, p2)):
            continue
        if tr.type_of(other) != t and not tr.type_of(other).is_scalar:
            continue
        if is_constant(tr, other) or not _not_fmul(tr, other):
            return None
        return p1, p2, inner.op, other
    return None


def _sum_value(tr: FoldEngine, x: Any) -> A.Binary | None:
    """The sum (``+`` or ``-``) x is to NIR and that only this addition reads: written here, or
    the value of a local read only here (its initializer or the assignment reaching here)."""
    inner = x
    if isinstance(x, A.Identifier):
        if not read_once(tr, x):
            return None
        init = stable_init(tr, x) or reaching_value(tr, x, unchanged=True)
        if init is None or not one_copy(tr, init):
            return None
        inner = init
    if not (isinstance(inner, A.Binary) and inner.op in SUMS):
        return None  # (a sum NIR would factor still is one: it reaches the outer sum first)
    return inner if inner is not x or used_once(tr, x) else None


def _fmul(tr: FoldEngine, node: Any) -> bool:
    """A product to NIR (queries.is_fmul, also a negated one or a component ``*=`` wrote); a
    product by 1.0, -1.0 or 0.0 is left out (NIR folds it away)."""
    while isinstance(node, A.Unary) and node.op == "-":
        node = node.operand
    if isinstance(node, A.Binary) and node.op == "*":
        for k in (node.left, node.right):
            v = tr.model.const_value(k)
            if v is not None and _trivial(v):
                return False
    return is_fmul(tr, node) or _multiplied(tr, node)


def _trivial(v: Any) -> bool:
    try:
        return float(v) in (0.0, 1.0, -1.0)
    except (TypeError, ValueError):
        return True  # (a vector constant: not copied)


def _multiplied(tr: FoldEngine, node: Any) -> bool:
    """A local, or the component of one, whose value here is what ``x *= y`` (y no matrix)
    wrote into that very variable or component, on every path, nothing written since
    (``p.x *= iResolution.x / iResolution.y; ... p.x``)."""
    target_name = None
    base = node
    if isinstance(node, A.Field) and tr.model.is_swizzle(node):
        base, target_name = node.base, node.name
    sym = tr.model.symbol_of(base) if isinstance(base, A.Identifier) else None
    if sym is None or sym.kind not in ("local", "param") or tr.fn is None:
        return False
    facts = function_facts(tr)
    if not facts.ok or id(base) not in facts.enter:
        return False
    before = [w for w in facts.writes_to(sym) if w.pos < facts.enter[id(base)]]
    if not before:
        return False
    w = before[-1].node
    if not (isinstance(w, A.Assignment) and w.op == "*="):
        return False
    if tr.type_of(w.value).is_matrix or tr.type_of(w.target).is_matrix:
        return False
    wt = w.target
    if isinstance(wt, A.Field) and tr.model.is_swizzle(wt):
        if not (isinstance(wt.base, A.Identifier) and target_name is not None):
            return False
        if set(target_name) - set(wt.name) or len(set(wt.name)) != len(wt.name):
            return False  # (a component the write left as it was)
    elif not isinstance(wt, A.Identifier):
        return False
    return facts.dominates(w, base) and not facts.written_between(w, base, [sym])


def _not_fmul(tr: FoldEngine, node: Any) -> bool:
    """A value NIR holds as no product when it reaches the outer addition: opaque (a uniform, a
    built-in's result, ...), a sum (one NIR factors is visited after: measured), a quotient, or
    the negation of one; or a local holding such a value."""
    while isinstance(node, A.Unary) and node.op == "-":
        node = node.operand
    if _fmul(tr, node):
        return False
    if is_opaque(tr, node):
        return True
    value = node
    if isinstance(node, A.Identifier):
        value = stable_init(tr, node) or reaching_value(tr, node)
        if value is None:
            return False
        if is_opaque(tr, value):
            return True
    if not isinstance(value, A.Binary) or tr.type_of(value).is_matrix:
        return False
    return value.op in ("+", "-", "/")  # (a sum NIR factors later is still one here)
