"""Constants merged across an operand: ``#a * (b * #c) -> (a*c) * b``, ``#a + (b + #c) -> (a + c) +
b``.

nir_opt_algebraic folds the two constants into one (in float32) with no "used once" condition,
so the rule reaches through any SSA value, here a never-written local: ``vec2 uv = q * 1.2;
... uv * 0.2`` is ``q * 0.24`` on llvmpipe. Subtraction is addition of the negation. NIR moves
a negation out of a product (``-x * #c -> -(x * #c)``), so the constants merge through it:
``float time = iTime * 0.85; ... -time * 0.6`` is ``-(iTime * 0.51)``. A float
``dot`` is a multiply to Mesa (:func:`_scalar_dot`), and ``dot(vecN(s), #K)`` a product by the
constants' sum (dot_constants.py), so a constant merges into those too."""

from __future__ import annotations

from typing import Any

from ....frontend import syntax as A
from ....language.glsl_types import FLOAT
from .dot_constants import broadcast_dot_parts
from .queries import (
    SUMS,
    has_matrix,
    is_builtin,
    is_constant,
    is_varying,
    reaching_value,
    stable_init,
)
from .ssa_values import product_parts

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..fold_protocols import FoldEmitter


def merge_constants(tr: FoldEmitter, e: A.Binary, mask: str | None) -> Any:
    """``#a * (b * #c) -> (a*c) * b`` and ``#a + (b + #c) -> (a + c) + b`` (no "used once"
    condition: they reach through any SSA value, here a never-written local such as
    ``vec2 uv = q * 1.2; ... uv * 0.2``, which is ``q * 0.24`` on llvmpipe: 1.2*0.2 is folded
    in float32). Subtraction is addition of the negation."""
    if e.op == "-" and not is_constant(tr, e.right):
        return None
    k_node, x_node = (e.right, e.left) if is_constant(tr, e.right) else (e.left, e.right)
    if not is_constant(tr, k_node) or is_constant(tr, x_node):
        return None
    # -x * #c: NIR's fmul(fneg(x), c) -> fneg(fmul(x, c)), then x's constants merge with c
    negated = e.op == "*" and _is_negation(x_node)
    inner: Any = x_node.operand if isinstance(x_node, A.Unary) and negated else x_node
    kept = None
    if isinstance(inner, A.Identifier):
        parts: tuple[Any, ...] | None = product_parts(tr, inner) if e.op == "*" else None
        kept = (
            parts[2] if parts is not None else None
        )  # (y's value kept: :func:`ssa_values.keep_factor`)
        inner = reaching_value(tr, inner) if kept is not None else stable_init(tr, inner)
        if e.op == "*" and kept is None and not negated and _is_negation(inner):
            negated, inner = True, inner.operand  # a local holding -x
    ops = ("*",) if e.op == "*" else SUMS
    factored = (
        broadcast_dot_parts(tr, inner) if e.op == "*" and kept is None and not negated else None
    )
    if (
        factored is not None and tr.type_of(k_node).is_scalar
    ):  # s * sum(K) by broadcast_dot, then merged
        tk, tx = tr.exprs([k_node, x_node], mask)
        written = (
            tr.binary_values("*", FLOAT, FLOAT, tx, tk)
            if x_node is e.left
            else tr.binary_values("*", FLOAT, FLOAT, tk, tx)
        )
        merged = tr.ieee("*", tk, tr.const_float(factored[1]))
        rewritten = tr.binary_values("*", FLOAT, FLOAT, tr.expr(factored[0], mask), merged)
        return tr.llvmpipe(rewritten, written)
    parts = _scalar_dot(tr, inner) if e.op == "*" else None
    if parts is None:
        if not isinstance(inner, A.Binary):
            return None
        parts = (inner.op, inner.left, inner.right)
    op, left, right = parts
    if op not in ops or tr.has_effects(inner):
        return None
    if is_constant(tr, right) and not is_constant(tr, left):
        b_node, c_node, c_sign, b_sign = left, right, op, "+"
    elif is_constant(tr, left) and not is_constant(tr, right):
        b_node, c_node, c_sign, b_sign = right, left, "+", op
    else:
        return None
    if tr.type_of(inner) != tr.type_of(x_node) or not is_varying(tr, b_node):
        return None  # (all constant after propagation: NIR folds it left to right)
    if has_matrix(tr, b_node, c_node):
        return None  # m * v is no elementwise product: NIR lowers it to columns first
    b_inner = stable_init(tr, b_node) if isinstance(b_node, A.Identifier) else b_node
    if (
        isinstance(b_inner, A.Binary)
        and b_inner.op in ops
        and (is_constant(tr, b_inner.left) or is_constant(tr, b_inner.right))
        and not has_matrix(tr, b_inner.left, b_inner.right)
    ):
        return None  # NIR would merge further into b: not copied (m * v is a sum of columns)
    if kept is not None:
        tk, tc, tx = tr.exprs([k_node, c_node, x_node], mask)
        tb = kept
    else:
        tk, tc, tb, tx = tr.exprs([k_node, c_node, b_node, x_node], mask)
    t = tr.type_of(e)
    if e.op == "*":
        rewritten = tr.binary_values("*", t, t, tb, tr.ieee("*", tk, tc))
        if negated:
            rewritten = tr.negate(rewritten)
        written = (
            tr.binary_values("*", t, t, tx, tk)
            if x_node is e.left
            else tr.binary_values("*", t, t, tk, tx)
        )
    else:
        k = tr.negate(tk) if e.op == "-" else tk
        c = tr.negate(tc) if c_sign == "-" else tc
        rewritten = tr.ieee(b_sign, tr.ieee("+", k, c), tb)
        written = tr.ieee(e.op, tx, tk) if x_node is e.left else tr.ieee(e.op, tk, tx)
    return tr.llvmpipe(rewritten, written)


def _is_negation(node: Any) -> bool:
    return isinstance(node, A.Unary) and node.op == "-"


def _scalar_dot(tr: FoldEmitter, node: Any) -> tuple[str, Any, Any] | None:
    """``("*", a, b)`` for ``dot(a, b)`` of two floats: Mesa's built-in is a multiply there
    (builtin_functions.cpp ``_dot``: ``ir_binop_mul`` for one component), so NIR merges a
    constant into it as into ``a * b`` (a hash's ``dot(n, 123.456) * 789.123`` is ``n *
    (123.456*789.123)``, measured); None for anything else."""
    if not (
        isinstance(node, A.Call)
        and node.callee == "dot"
        and len(node.args) == 2
        and is_builtin(tr, node)
    ):
        return None
    if not all(tr.type_of(a).is_scalar and tr.type_of(a).base == "float" for a in node.args):
        return None
    return "*", node.args[0], node.args[1]
