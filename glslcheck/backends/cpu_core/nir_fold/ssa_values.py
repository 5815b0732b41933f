"""A product by a constant seen through a variable assigned again: NIR's SSA values.

NIR sees SSA values: a variable assigned again still stands for the value it was given, so
``p = m*p*2.02; p = m*p*2.03`` (iq's fbm) is ``(m*2.02) * (m*p)`` for a constant matrix m,
merged by ``('~fmul', '#a', ('fmul', 'b(is_not_const)', '#c'))`` after NIR lowers the matrix
product to columns (:func:`merge_into_matrix`), and ``(y * #c) * #k`` is ``y * (c*k)`` through
such a variable too. The generated code has one variable per GLSL one, so the value y had is
kept in a temporary for the later read (:func:`keep_factor`, :func:`product_parts`)."""

from __future__ import annotations

from typing import Any

from ....frontend import syntax as A
from .loop_copies import merged_value, nonzero_constant
from .queries import (
    current_function,
    function_facts,
    has_matrix,
    is_constant,
    is_fmul,
    is_varying,
    reaching_value,
    stable_init,
    written_symbols,
)

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..fold_protocols import FoldEmitter, FoldEngine


def keep_factor(tr: FoldEmitter, e: A.Binary, mask: str | None) -> Any:
    """``x = y * #c`` where x is read later in a product by a constant: the code of the
    product, y's value kept in a temporary for that read (:func:`product_parts`). NIR sees
    through x to y however often x is assigned (``p = m*p*2.02; p = m*p*2.03;`` in an fbm:
    the second is ``(m*2.02) * (m*p)``, SSA); the generated code has one variable per GLSL
    one, so the value y had is kept here, in float32 and float64 mode alike (the same
    values: only llvmpipe mode reads the temporary). The same for ``x = y +- #c`` and for
    the value before a loop NIR unrolls that its first copy reads (loop_copies.merged_value;
    a value a later copy reads: loop_copies.kept_in_slot)."""
    if (
        e.op not in ("*", "+", "-")
        or tr.type_of(e.left) != tr.type_of(e.right)
        and not (tr.type_of(e.left).is_scalar or tr.type_of(e.right).is_scalar)
    ):
        return None
    k_left = is_constant(tr, e.left)
    y, k = (e.right, e.left) if k_left else (e.left, e.right)
    if not is_constant(tr, k) or is_constant(tr, y) or tr.type_of(y) != tr.type_of(e):
        return None
    if e.op != "*" and (
        not nonzero_constant(tr, k) or isinstance(y, A.Identifier) or tr.type_of(e).is_matrix
    ):
        return None  # (a sum: `x = x + #c` is repeated_sums.py's; `x + 0.0` is x to NIR)
    plain = isinstance(y, (A.Identifier, A.Field, A.Index))  # (merged in a loop's copies too)
    if not (isinstance(y, (A.Binary, A.Call)) or plain) or is_fmul(tr, y) and product_parts(tr, y):
        return None  # (a longer chain: not copied)
    w = _write_of(tr, e)
    if w is None or id(w.symbol) not in written_symbols(tr):
        return None  # (a variable written once: its initializer is read again instead)
    # (a plain read is kept for a product by a constant only: the terms of a sum factor whole)
    reads = _merge_reads(tr, products=plain).get(id(w.symbol), ()) if e.op == "*" else ()
    if not (any(reaching_value(tr, r) is e for r in reads) or merged_value(tr, e)):
        return None  # (no product by (sum with) a constant reads this value)
    ty = tr.tmp(tr.expr(y, mask))
    tk = tr.expr(k, mask)
    tr.fold_state.kept[id(e)] = (ty, tr.lines)
    t = tr.type_of(e)
    if e.op != "*":
        return tr.ieee(e.op, tk, ty) if k_left else tr.ieee(e.op, ty, tk)
    return tr.binary_values("*", t, t, tk, ty) if k_left else tr.binary_values("*", t, t, ty, tk)


def _write_of(tr: FoldEngine, value: Any) -> Any:
    """The write (analysis.dataflow.Write) of a local whose whole new value is ``value``."""
    facts = function_facts(tr)
    if not facts.ok:
        return None
    index = tr.fold_state.writes
    key = id(current_function(tr).sym)
    if key not in index:
        index[key] = {
            id(w.value): w
            for ws in facts.writes.values()
            for w in ws
            if w.kind in ("=", "init")
            and w.value is not None
            and w.symbol.kind in ("local", "param")
        }
    return index[key].get(id(value))


def _merge_reads(tr: FoldEngine, products: bool = False) -> dict[int, list[A.Identifier]]:
    """id(symbol) -> the reads of it as a factor of a product by a constant, or (it or one of
    its components) as a term of a sum (factoring.py factors ``x.x + x.y``; not with
    `products`), in the current function."""
    cache = tr.fold_state.merge_reads
    key = (id(current_function(tr).sym), products)
    if key not in cache:
        out: dict[int, list[A.Identifier]] = {}
        for n in current_function(tr).sym.node.body.walk():
            if not isinstance(n, A.Binary):
                continue
            for a, b in ((n.left, n.right), (n.right, n.left)):
                if n.op == "+" and products:
                    continue
                if n.op == "+" and isinstance(b, A.Field) and len(b.name) == 1:
                    b = b.base
                elif not (n.op == "*" and is_constant(tr, a) or n.op == "+"):
                    continue
                if isinstance(b, A.Identifier) and tr.model.symbol_of(b) is not None:
                    out.setdefault(id(tr.model.symbol_of(b)), []).append(b)
        cache[key] = out
    return cache[key]


def product_parts(tr: FoldEngine, node: Any) -> tuple[Any, Any, Any] | None:
    """(y, #c, code) when the value of the variable ``node`` is ``y * #c`` to NIR: a
    never-written local's initializer (code None: y is computed again here), or the
    assignment reaching this read when :func:`keep_factor` kept y (code: its temporary, in the
    Python function being written, `tr.lines`)."""
    if not isinstance(node, A.Identifier):
        return None
    init, code = stable_init(tr, node), None
    if init is None:
        init = reaching_value(tr, node)
        kept = tr.fold_state.kept.get(id(init))
        if kept is None or kept[1] is not tr.lines:
            return None  # (not kept, or kept in another Python function: an outlined part)
        code = kept[0]
    if not (isinstance(init, A.Binary) and init.op == "*") or has_matrix(tr, init.left, init.right):
        return None
    if is_constant(tr, init.right) and not is_constant(tr, init.left):
        return init.left, init.right, code
    if is_constant(tr, init.left) and not is_constant(tr, init.right):
        return init.right, init.left, code
    return None


def merge_into_matrix(tr: FoldEmitter, e: A.Binary, mask: str | None) -> Any:
    """``#M * v`` with v a vector whose value is ``y * #c`` (c a scalar): NIR lowers the
    product to columns, ``M[j][i] * (y[j] * c)``, and merges each constant, ``(M[j][i]*c) *
    y[j]`` (``('~fmul', '#a', ('fmul', 'b(is_not_const)', '#c'))``): ``(M * c) * y``, M * c
    folded in float32 (measured: ``p = m*p*2.02; p = m*p*2.03`` of iq's fbm)."""
    if e.op != "*" or not (tr.type_of(e.left).is_matrix and tr.type_of(e.right).is_vector):
        return None
    if tr.model.const_value(e.left) is None and not is_constant(tr, e.left):
        return None
    parts = product_parts(tr, e.right)
    if (
        parts is None
        or not tr.type_of(parts[1]).is_scalar
        or tr.type_of(parts[0]) != tr.type_of(e.right)
    ):
        return None
    y, c, code = parts
    if code is None and (not is_varying(tr, y) or tr.has_effects(y)):
        return None
    tm, tc, tv = tr.exprs([e.left, c, e.right], mask)
    ty = code if code is not None else tr.expr(y, mask)
    mt, vt = tr.type_of(e.left), tr.type_of(e.right)
    merged = tr.binary_values("*", mt, tr.type_of(c), tm, tc)
    rewritten = tr.binary_values("*", mt, vt, merged, ty)
    return tr.llvmpipe(rewritten, tr.binary_values("*", mt, vt, tm, tv))
