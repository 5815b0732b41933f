"""Constants merged into a dot product with a constant, and a dot product of a broadcast vector.

NIR lowers ``dot`` to component products summed right to left, then its reassociations merge
constants into them: ``dot(x * #c, #K)`` is ``dot(x, K * c)``, tree by tree in the order GLSL
IR and NIR fold them (:func:`merged_dot`), also through the parameter of a call inlined for it
(cpu_core/inline.py: Mesa inlines every function before these passes, and asks
:func:`dot_operand` which calls to inline); ``dot(vecN(s), #K)`` is ``s * (K[0] + (K[1] +
...))`` by the factoring ``a*b + a*c -> a * (b + c)`` (:func:`broadcast_dot`: a hash's
``dot(vec2(index), vec2(12.9898, 78.233))``)."""

from __future__ import annotations

from typing import Any

from ....frontend import syntax as A
from ....language.glsl_types import FLOAT
from .queries import (
    constant_value,
    has_matrix,
    is_builtin,
    is_constant,
    is_varying,
    read_once,
    stable_init,
)

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..fold_protocols import FoldEmitter, FoldEngine


def merged_dot(tr: FoldEmitter, call: A.Call, args: list[Any], mask: str | None) -> Any:
    """``dot(v, #K)`` where v is a chain of products by constants, ``(x * #c1) * #c2``, also
    through never-written locals and inlined parameters (:func:`queries.stable_init`).

    Two compilers merge the constants, in this order (measured bit for bit, Mesa 22.3):
    GLSL IR first folds the constants of one expression tree (``r * 2.1 * 0.7`` is
    ``r * (2.1*0.7)``; its tree grafting puts a variable written once and read once, such as an
    inlined argument, into the tree that reads it); then NIR lowers the dot product to
    component products and its reassociation ``('~fmul', '#a', ('fmul', 'b(is_not_const)',
    '#c')) -> ('fmul', ('fmul', a, c), b)`` (nir_opt_algebraic.py) merges K with each tree's
    constant, the outer tree first. So ``vec2 uv = q * 1.2`` read twice and ``dot(uv * 0.2, K)``
    is ``dot(q, (K * 0.2) * 1.2)`` (``K * (0.2 * 1.2)`` differs in 70% of the pixels), and
    ``dot(r * 2.1 * 0.7, K)`` is ``dot(r, K * (2.1 * 0.7))``. Float32 only, like every rule."""
    if len(call.args) != 2 or tr.fn is None or tr.type_of(call).base != "float":
        return None
    u, w = call.args
    if is_constant(tr, w) and not is_constant(tr, u):
        v, k, v_first = u, w, True
    elif is_constant(tr, u) and not is_constant(tr, w):
        v, k, v_first = w, u, False
    else:
        return None
    x, trees = _product_chain(tr, v)
    if not trees or not is_varying(tr, x) or tr.type_of(x) != tr.type_of(v) or tr.has_effects(x):
        return None
    built = stable_init(tr, x) if isinstance(x, A.Identifier) else x
    if isinstance(built, A.Call) and built.constructor:
        return None  # NIR merges further into each component (vec3(p * 0.37, ...)): not copied
    t = tr.type_of(v)
    tx, tk = tr.exprs([x, k], mask)
    merged = tk
    for tree in trees:
        codes = tr.exprs(tree[::-1], mask)  # GLSL IR folds the tree's constants inner first
        folded = codes[0]
        for c in codes[1:]:
            folded = tr.binary_values("*", t, t, folded, c)
        merged = tr.binary_values("*", t, t, merged, folded)
    rewritten = tr.runtime("dot", tx, merged) if v_first else tr.runtime("dot", merged, tx)
    return tr.llvmpipe(rewritten, tr.runtime("dot", args[0], args[1]))


def broadcast_dot(tr: FoldEmitter, call: A.Call, args: list[Any], mask: str | None) -> Any:
    """``dot(vecN(s), #K)`` (s a float, also through a never-written local or an inlined
    parameter, :func:`queries.stable_init`) is ``s * (K[0] + (K[1] + ...))`` on llvmpipe: the dot
    product lowered to ``s*K[0] + (s*K[1] + ...)`` (summed right to left), NIR's factoring
    ``('~fadd', ('fmul', a, b), ('fmul', a, c)) -> a * (b + c)`` leaves one product by the
    constants' float32 sum (measured bit for bit for vec2, vec3, vec4: a hash's
    ``dot(vec2(index), vec2(12.9898, 78.233))``; the sum left to right differs for vec4)."""
    parts = broadcast_dot_parts(tr, call)
    if parts is None:
        return None
    x, total = parts
    rewritten = tr.binary_values("*", FLOAT, FLOAT, tr.expr(x, mask), tr.const_float(total))
    return tr.llvmpipe(rewritten, tr.runtime("dot", args[0], args[1]))


def broadcast_dot_parts(tr: FoldEngine, call: Any) -> tuple[Any, float] | None:
    """(s, the float32 sum of K right to left) for a call ``dot(vecN(s), #K)``, else None."""
    if not (
        isinstance(call, A.Call)
        and call.callee == "dot"
        and len(call.args) == 2
        and is_builtin(tr, call)
    ):
        return None
    if tr.fn is None or tr.type_of(call).base != "float" or tr.has_effects(call):
        return None
    for v, k in ((call.args[0], call.args[1]), (call.args[1], call.args[0])):
        x = _broadcast(tr, v)
        ks = constant_value(tr, k) if x is not None else None
        if ks is None or len(ks) != tr.type_of(v).size or not is_varying(tr, x):
            continue
        import numpy as np

        total = np.float32(ks[-1])
        for c in reversed(ks[:-1]):
            total = np.float32(np.float32(c) + total)
        return (x, float(total)) if np.isfinite(total) else None
    return None


def dot_operand(tr: FoldEngine, node: Any) -> bool:
    """``node`` is an operand the rules of a ``dot`` with a constant rewrite: a product by a
    constant (:func:`constant_product`, for :func:`merged_dot`) or ``vecN(s)`` (for
    :func:`broadcast_dot`); cpu_core/inline.py inlines a call that passes one to such a dot."""
    return constant_product(tr, node) or tr.fn is not None and _broadcast(tr, node) is not None


def _broadcast(tr: FoldEngine, v: Any) -> Any:
    """The float s of a vector ``vecN(s)`` (also a never-written local or inlined parameter
    so built, or a swizzle of one), else None."""
    if isinstance(v, A.Field) and tr.model.is_swizzle(v):
        v = v.base
    built = stable_init(tr, v) if isinstance(v, A.Identifier) else v
    if not (isinstance(built, A.Call) and built.constructor and len(built.args) == 1):
        return None
    s = built.args[0]
    t = tr.type_of(built)
    if not (
        t.is_vector
        and t.base == "float"
        and tr.type_of(s).is_scalar
        and tr.type_of(s).base == "float"
    ):
        return None
    return None if tr.has_effects(s) else s


def _product_chain(tr: FoldEngine, v: Any) -> tuple[Any, list[list[Any]]]:
    """(x, trees) for ``v = (x * #c2) * #c1``: the constant factors grouped by the GLSL IR
    expression tree they sit in, outer tree and outer factor first. A never-written local read
    once (or an inlined parameter, read once in its function) is grafted into the tree that
    reads it; another one starts a new tree. ([] when v is no such product.)"""
    trees: list[list[Any]] = [[]]
    node = v
    for _ in range(16):
        inner = node
        while isinstance(inner, A.Identifier):
            init = stable_init(tr, inner)
            if init is None:
                break
            if not read_once(tr, inner) and trees[-1]:
                trees.append([])
            inner = init
        if not (isinstance(inner, A.Binary) and inner.op == "*") or has_matrix(
            tr, inner.left, inner.right
        ):
            break
        if tr.type_of(inner) != tr.type_of(v) or tr.has_effects(inner):
            break
        if is_constant(tr, inner.right) and not is_constant(tr, inner.left):
            trees[-1].append(inner.right)
            node = inner.left
        elif is_constant(tr, inner.left) and not is_constant(tr, inner.right):
            trees[-1].append(inner.left)
            node = inner.right
        else:
            break
    return node, [tree for tree in trees if tree]


def constant_product(tr: FoldEngine, node: Any) -> bool:
    """``node`` is, or is a never-written local initialised by, a product of a constant and a
    value that is not constant (the start of :func:`_product_chain`)."""
    if tr.fn is None or tr.has_effects(node):
        return False
    _, trees = _product_chain(tr, node)
    return bool(trees)
