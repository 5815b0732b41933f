"""Constants sunk into a sum or a product used once: ``(a + b) + #c -> (a + #c) + b``.

nir_opt_algebraic moves a constant inward where both operations are used once (a and b not
constant): first the variant that keeps a product ``b`` whole (``is_fmul``), so ``(a*b + c) +
K`` is ``(c + K) + a*b``; subtraction is addition of the negation; the new sum is matched
again, so the constant sinks down a chain of sums, also through a local read once
(:func:`_sink_sum`: iq's noise). The same for products, ``(a * b) * #c -> (a * #c) * b``, also
past a broadcast operand, where a factor is a variable a folded call wrote as a sum
(:func:`_settled`), a never-written product by a constant or ``1.0 / y`` (:func:`_scaled`), the
constant possibly a never-written local (:func:`_local_constant`): gargantua's ``eyevec *
dither * far`` is ``(eyevec * far) * dither``; a factor ``normalize(x)`` read once takes the
constant on into x (:func:`_normalized_once`). ``dot(u, v) + #c`` puts the constant in the dot
product's innermost addition, ``u.x*v.x + (u.y*v.y + (u.z*v.z + #c))`` (``rt.dot_add``), a
squared length too (squared_lengths.py). Not copied: chains GLSL IR rebalances first
(:func:`_rebalanced`)."""

from __future__ import annotations

from typing import Any

from ....frontend import syntax as A
from ..call_fold import out_roots
from ..call_sites import local_initializer
from .factoring import factor_parts
from .queries import (
    SUMS,
    call_write,
    current_function,
    function_facts,
    has_matrix,
    is_builtin,
    is_constant,
    is_fmul,
    is_opaque,
    one_copy,
    reaching_value,
    read_once,
    stable_init,
    used_once,
    written_symbols,
)
from .squared_lengths import merged_argument, shared_dot, squared_length

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..fold_protocols import FoldEmitter, FoldEngine


def sink_constant(tr: FoldEmitter, e: A.Binary, mask: str | None) -> Any:
    """Constants sunk into a sum (:func:`_sink_sum`), a two-term product, or a dot product."""
    inner, k, k_left = e.left, e.right, False
    if (
        is_constant(tr, inner)
        and not is_constant(tr, k)
        or e.op == "*"
        and _local_constant(tr, inner)
    ):
        inner, k, k_left = e.right, e.left, True
    if not (is_constant(tr, k) or e.op == "*" and _local_constant(tr, k)) or is_constant(tr, inner):
        return None
    if tr.type_of(k) != tr.type_of(e) and not tr.type_of(k).is_scalar:
        return None  # (a scalar constant added to or multiplying a vector: each component)
    if not used_once(tr, e):
        return None
    if k_left and e.op == "-":
        return None  # #c - (a + b): the negation sits between the two sums
    if e.op in SUMS:
        return _sink_sum(tr, e, inner, k, mask)
    if not (used_once(tr, inner) and isinstance(inner, A.Binary) and inner.op == "*"):
        return None
    a, b = inner.left, inner.right
    if has_matrix(tr, a, b):
        return None  # a matrix product is not reassociated as numbers are
    if not (
        (
            is_opaque(tr, a)
            or _settled(tr, a)
            or _advanced(tr, a)
            or _normalized_once(tr, a) is not None
        )
        and (is_opaque(tr, b) or _settled(tr, b) or _advanced(tr, b) or _scaled(tr, b))
    ):
        return None  # an operand NIR would look into further: not copied
    t, ty = tr.type_of(e), [tr.type_of(x) for x in (a, b, k)]
    if any(x != t and not x.is_scalar for x in ty):
        return None
    ta, tb, tk = tr.exprs([a, b, k], mask)
    prod = lambda x, y, tx, ty: tr.binary_values("*", tx, ty, x, y)  # noqa: E731
    ab, ak = tr.type_of(inner), (ty[0] if ty[0] == t else ty[2])  # (types of a*b, a*#c)
    written = (
        prod(prod(ta, tb, ty[0], ty[1]), tk, ab, ty[2])
        if not k_left
        else prod(tk, prod(ta, tb, ty[0], ty[1]), ty[2], ab)
    )
    x = _normalized_once(tr, a)
    if (
        x is not None
    ):  # a = x * inversesqrt(dot(x, x)) to NIR, used once: the constant sinks into it
        tx = tr.tmp(tr.expr(x, mask))
        scaled = prod(tx, tk, ty[0], ty[2])
        rsq = tr.runtime("inversesqrt", tr.runtime("dot", tx, tx))
        ta_k = prod(scaled, rsq, ty[0], tr.type_of(k))
        return tr.llvmpipe(prod(ta_k, tb, ak, ty[1]), written)
    return tr.llvmpipe(prod(prod(ta, tk, ty[0], ty[2]), tb, ak, ty[1]), written)


def _local_constant(tr: FoldEngine, node: Any) -> bool:
    """A never-written local initialised by a constant expression (``float warpAmount = 5.0;``):
    a constant to NIR (GLSL IR's constant propagation), counted as one by the product sink."""
    sym = tr.model.symbol_of(node) if isinstance(node, A.Identifier) else None
    init = local_initializer(sym)
    if init is None:
        return False
    return tr.model.const_value(init) is not None and id(sym) not in written_symbols(tr)


def _normalized_once(tr: FoldEngine, node: Any) -> Any:
    """x when ``node`` reads a never-written local initialised as ``normalize(x)`` (x a vector)
    and read only here: NIR sees ``x * frsq(dot(x, x))`` used once, and a constant multiplying
    it sinks on to x: ``(normalize(x) * b) * #c`` is ``((x * #c) * inversesqrt(dot(x, x))) * b``
    (measured: gargantua's WarpSpace, ``singularityVector * warpFactor * warpAmount``, 1 of
    43,200 values off on a copy of the function, 8 with the constant beside normalize's
    result); else None."""
    sym = tr.model.symbol_of(node) if isinstance(node, A.Identifier) else None
    if (
        sym is None
        or sym.kind != "local"
        or not isinstance(sym.node, A.Declarator)
        or id(sym) in written_symbols(tr)
    ):
        return None
    init = sym.node.init
    if not (
        isinstance(init, A.Call)
        and init.callee == "normalize"
        and is_builtin(tr, init)
        and tr.type_of(init.args[0]).is_vector
        and not tr.has_effects(init)
    ):
        return None
    reads = [
        n
        for n in current_function(tr).sym.node.body.walk()
        if isinstance(n, A.Identifier) and tr.model.symbol_of(n) is sym
    ]
    return init.args[0] if reads == [node] else None


def _settled(tr: FoldEmitter, node: Any) -> bool:
    """A variable whose value here is what a call of a user function wrote into it (an out or
    inout argument, nothing written since), where that value is, to NIR after inlining, a sum
    or a built-in's result in every component (cpu_core/call_fold.out_roots: gargantua's
    eyevec after RotateCamera): no algebraic rule looks into it as a factor."""
    w = call_write(tr, node)
    if w is None:
        return False
    roots = out_roots(tr, w.node, tr.model.symbol_of(node))
    return roots is not None and roots <= {"+", "call"}


def _advanced(tr: FoldEngine, node: Any) -> bool:
    """A local (or a component of one) whose value here is what a ``+=`` or ``-=`` of a value
    that is not a constant wrote (on every path, nothing written since): to NIR a sum, which no
    algebraic rule looks into as a factor (measured: a path hash's ``p2 += dot(...)`` then
    ``p2.x * p2.y * #K`` is ``(p2.x * #K) * p2.y``)."""
    while isinstance(node, A.Field) and tr.model.is_swizzle(node):
        node = node.base
    sym = tr.model.symbol_of(node) if isinstance(node, A.Identifier) else None
    if sym is None or sym.kind not in ("local", "param") or tr.fn is None:
        return False
    facts = function_facts(tr)
    if not facts.ok or id(node) not in facts.enter:
        return False
    before = [w for w in facts.writes_to(sym) if w.pos < facts.enter[id(node)]]
    if not before or before[-1].kind != "op":
        return False
    w = before[-1].node
    return (
        isinstance(w, A.Assignment)
        and w.op in ("+=", "-=")
        and not is_constant(tr, w.value)
        and facts.dominates(w, node)
        and not facts.written_between(w, node, [sym])
    )


def _scaled(tr: FoldEngine, node: Any) -> bool:
    """A never-written local initialised as a product by a constant (``float dither = rand(uv)
    * 2.0``) or a constant divided by a value (``1.0 / (...)``): beside ``(a * dither) * #c``
    NIR leaves it whole, measured (gargantua: ``((eyevec * dither) * 15.0) / 200.0`` is
    ``((eyevec * 15.0) * dither) / 200.0``; WarpSpace's warpFactor likewise)."""
    sym = tr.model.symbol_of(node) if isinstance(node, A.Identifier) else None
    if (
        sym is None
        or sym.kind != "local"
        or not isinstance(sym.node, A.Declarator)
        or id(sym) in written_symbols(tr)
    ):
        return False
    init = sym.node.init  # (its value, whatever calls compute it: a user function's result too)
    if (
        isinstance(init, A.Binary)
        and init.op == "/"
        and is_constant(tr, init.left)
        and not is_constant(tr, init.right)
    ):
        return tr.type_of(init).is_scalar  # (1.0 / y, gargantua's warpFactor: measured the same)
    return (
        isinstance(init, A.Binary)
        and init.op == "*"
        and not has_matrix(tr, init.left, init.right)
        and is_constant(tr, init.left) != is_constant(tr, init.right)
    )


def _sink_sum(tr: FoldEmitter, e: A.Binary, inner: Any, k: Any, mask: str | None) -> Any:
    """``(a + b) + #c -> (a + #c) + b`` as nir_opt_algebraic applies it: first the variant that
    keeps a product ``b`` whole (``is_fmul``, so the constant joins the other term), else the
    constant joins ``a``; the new sum ``a + #c`` is matched again, so the constant sinks down
    a chain of sums each used once: ``uv = (p.xy + K*p.z) + f.xy; uv + 0.5`` is
    ``((p.xy + 0.5) + K*p.z) + f.xy`` (iq's noise). A sum may be the initializer of a
    never-written local read once (to NIR the same SSA value, used once). Not copied (None):
    a chain GLSL IR rebalances first (:func:`_rebalanced`), a ``dot`` other than
    ``dot(oc, oc)`` (:func:`_stable_vector`), a term that is none of opaque, product, sum."""
    if (
        isinstance(inner, A.Call)
        and inner.callee == "dot"
        and is_builtin(tr, inner)
        and all(_stable_vector(tr, x) for x in inner.args)
    ):
        u, v, kk = tr.exprs([*inner.args, k], mask)
        signed = tr.negate(kk) if e.op == "-" else kk
        written = tr.ieee(e.op, tr.runtime("dot", u, v), kk)
        return tr.llvmpipe(tr.runtime("dot_add", u, v, signed), written)
    squared = squared_length(tr, inner)
    if squared is not None:
        u, kk, written = tr.exprs([squared, k, inner], mask)
        signed = tr.negate(kk) if e.op == "-" else kk
        if shared_dot(tr, squared, inner) and not merged_argument(tr, squared):
            # (dot(x, x) used twice after CSE: the constant stays outside)
            rewritten = tr.ieee(e.op, tr.runtime("dot", u, u), kk)
            return tr.llvmpipe(rewritten, tr.ieee(e.op, written, kk))
        return tr.llvmpipe(tr.runtime("dot_add", u, u, signed), tr.ieee(e.op, written, kk))
    plan = _sum_plan(tr, inner, tr.type_of(e), 0)
    if plan is None or plan[0] != "sum" or _rebalanced(tr, e):
        return None
    leaves: list[Any] = []
    _plan_leaves(plan, leaves)
    codes = tr.exprs([*leaves, e.left, e.right, k], mask)
    tk = tr.negate(codes[-1]) if e.op == "-" else codes[-1]
    rewritten = _plan_code(tr, plan, iter(codes), tk)
    return tr.llvmpipe(rewritten, tr.ieee(e.op, codes[-3], codes[-2]))


def _sum_plan(tr: FoldEngine, x: Any, t: Any, depth: int) -> tuple | None:
    """Where a constant added to ``x`` goes: ("leaf", x) when x is a term it stays beside,
    ("sum", receiver plan, other term, operator, receiver on the left) when x is a sum used
    once, None where the rewrite is not copied."""
    if tr.type_of(x) != t or tr.has_effects(x):
        return None  # (a broadcast operand: keep it simple)
    inner = x
    if isinstance(x, A.Identifier) and read_once(tr, x):
        init = stable_init(tr, x) or reaching_value(tr, x, unchanged=True)
        inner = init if init is not None and one_copy(tr, init) else x
    elif not used_once(tr, x):
        inner = None
    if not (isinstance(inner, A.Binary) and inner.op in SUMS) or depth > 16:
        return ("leaf", x) if known_term(tr, x) else None
    a, b = inner.left, inner.right
    if any(is_constant(tr, y) or has_matrix(tr, y) or tr.type_of(y) != t for y in (a, b)):
        return None
    if not all(known_term(tr, y) for y in (a, b)):
        return None  # a term NIR looks into (a call inlined, a mix, ...): not copied
    if factor_parts(tr, inner) is not None:
        return ("leaf", x)  # factored first (a*b + a*c -> a*(b + c)): a product, no sum
    if is_fmul(tr, b) or not is_fmul(tr, a):
        recv = _sum_plan(tr, a, t, depth + 1)
        return None if recv is None else ("sum", recv, b, inner.op, True)
    if inner.op == "-":
        return ("sum", ("neg", b), a, "+", False)  # fneg(b) + #c: no sum to sink into
    recv = _sum_plan(tr, b, t, depth + 1)
    return None if recv is None else ("sum", recv, a, "+", False)


def _plan_leaves(plan: tuple, out: list[Any]) -> None:
    """The nodes of a :func:`_sum_plan` in the order :func:`_plan_code` reads their codes."""
    if plan[0] == "sum":
        _plan_leaves(plan[1], out)
        out.append(plan[2])
    else:
        out.append(plan[1])


def _plan_code(tr: FoldEmitter, plan: tuple, codes: Any, k: Any) -> Any:
    if plan[0] == "leaf":
        return tr.ieee("+", next(codes), k)
    if plan[0] == "neg":
        return tr.ieee("+", tr.negate(next(codes)), k)
    recv = _plan_code(tr, plan[1], codes, k)
    other = next(codes)
    return tr.ieee(plan[3], recv, other) if plan[4] else tr.ieee("+", recv, other)


def known_term(tr: FoldEngine, node: Any) -> bool:
    """A term whose kind to NIR is known: opaque, a product (:func:`queries.is_fmul`), a sum, or a
    selection (``c ? x : y``, a bcsel: no product), written or the value of a local here."""
    if is_opaque(tr, node) or is_fmul(tr, node) or _sum(tr, node):
        return True
    if isinstance(node, A.Identifier):
        node = stable_init(tr, node) or reaching_value(tr, node)
    if not isinstance(node, A.Ternary):
        return False
    x, y = node.then, node.else_  # (c ? a*b : a*d is a * (c ? b : d) to NIR: not copied)
    return not (isinstance(x, A.Binary) and isinstance(y, A.Binary) and x.op == y.op)


def _sum(tr: FoldEngine, node: Any) -> bool:
    """A sum or difference (no product: :func:`queries.is_fmul` tells which term keeps the
    constant)."""
    return isinstance(node, A.Binary) and node.op in SUMS


def _rebalanced(tr: FoldEngine, e: A.Binary) -> bool:
    """GLSL IR's do_rebalance_tree balances an expression tree of three or more additions of
    the same type whose leaves are variables (at most one constant) before NIR sees it:
    ``(a + b + c) + K`` reaches NIR as ``(a + b) + (c + K)`` (measured)."""
    stack: list[A.Expr] = [e]
    ops, constants = 0, 0
    while stack:
        n = stack.pop()
        if isinstance(n, A.Binary):
            if n.op != "+" or tr.type_of(n) != tr.type_of(e):
                return False
            ops += 1
            stack += [n.left, n.right]
        elif is_constant(tr, n):
            constants += 1
        elif not (
            isinstance(n, A.Identifier) or (isinstance(n, A.Field) and tr.model.is_swizzle(n))
        ):
            return False
    return ops >= 3 and constants <= 1


def _stable_vector(tr: FoldEngine, node: Any) -> bool:
    """A never-written vector local initialised as the difference of two opaque vectors
    (``vec3 oc = ro - center``: measured). A vector built from scalars is left out: there
    llvmpipe's bits follow neither order (other rules, such as ``sqrt(x) * sqrt(x) -> x``,
    reach into the components)."""
    init = stable_init(tr, node) if isinstance(node, A.Identifier) else None
    if not (isinstance(init, A.Binary) and init.op == "-"):
        return False
    return all(
        is_opaque(tr, x)
        or (
            isinstance(x, A.Call)
            and x.constructor
            and len(x.args) > 1
            and all(is_opaque(tr, a) for a in x.args)
        )
        for x in (init.left, init.right)
    )
