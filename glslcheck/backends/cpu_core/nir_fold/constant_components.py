"""A vector's constant component in NIR's constant rules: NIR splits vectors into components, so
a component a vector constructor gives a constant is a constant in every operation on it.

A path tracer's camera, ``vec3 orig = vec3(off, -6.0); vec3 w = normalize(orig);``: w's z is
``-6.0 * rsq(dot(orig, orig))`` to NIR, so ``7.0 * w`` merges the two constants in z
(``#a * (b * #c) -> (a*c) * b``, constant_merge.py's rule) into ``-42.0 * rsq``; and the ray
``((ll + s*h) + t*v) - orig`` adds the constant 6.0 in z, which sinks down the chain of sums
(``(a + b) + #c -> (a + #c) + b``, each sum used once: sink.py's rule) into ll's ``-6.0 - ...``
and cancels it (``#a + (b + #c) -> (a + c) + b``, the zero dropped). The engines compute a
vector operation whole, so the rules that look for a constant operand do not see these.

:func:`component_constants` evaluates each component of a float ``+``, ``-`` or ``*`` as NIR
sees it (:class:`_Term`: through never-written locals, swizzles, vector constructors,
``normalize`` and scalar operands broadcast), applies those three rules where a constant
component takes part, and, where one did, computes the changed components in Mesa's order
(the others as written). Measured: tests/gl/test_llvmpipe_constant_components.py."""

from __future__ import annotations

from typing import Any

import numpy as np

from ....frontend import syntax as A
from .queries import (
    constant_value,
    current_function,
    has_matrix,
    is_builtin,
    is_constant,
    one_copy,
    stable_init,
    used_once,
)

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..fold_protocols import FoldEmitter, FoldEngine

_DEPTH = 24  # terms looked into below an operation (a chain of sums of a camera is ~8 deep)


class _Term:
    """One component's value: a constant ("k"), a value computed as written ("leaf"), or a
    sum, product or negation of terms. `src` (node, component): the code of an unchanged term
    is that component of the node's code; `comp`: a constant a vector constructor gave a
    component (or one merged from such); `once`: a sum or product feeding one instruction."""

    __slots__ = ("op", "args", "value", "src", "comp", "once", "changed")

    def __init__(
        self,
        op: str,
        args: tuple[_Term, ...] = (),
        value: float = 0.0,
        src: tuple[Any, int] | None = None,
        comp: bool = False,
        once: bool = False,
        changed: bool = False,
    ) -> None:
        self.op, self.args, self.value, self.src = op, args, value, src
        self.comp, self.once, self.changed = comp, once, changed


def _k(v: float, comp: bool, src: tuple[Any, int] | None = None) -> _Term:
    return _Term("k", value=float(np.float32(v)), comp=comp, src=src)


def _f32(op: str, a: float, b: float) -> float:
    x, y = np.float32(a), np.float32(b)
    return float(x + y if op == "+" else x * y)


def _size(t: Any) -> int:
    return t.size if t.is_vector else 1


class _Eval:
    """The terms of one expression's components, and the rules applied to them."""

    def __init__(self, tr: FoldEngine) -> None:
        self.tr = tr

    def term(self, node: Any, i: int, once: bool, depth: int = 0) -> _Term:
        tr = self.tr
        t = tr.type_of(node)
        leaf = _Term("leaf", src=(node, i))
        if t.base != "float" or not (t.is_scalar or t.is_vector) or depth > _DEPTH:
            return leaf
        if is_constant(tr, node):
            values = constant_value(tr, node)
            if values is None or not values:
                return leaf
            return _k(values[i] if len(values) > 1 else values[0], False, (node, i))
        if tr.has_effects(node):
            return leaf
        if isinstance(node, A.Identifier):
            init = stable_init(tr, node)
            if init is None or tr.type_of(init) != t:
                return leaf
            # (a local read twice still takes the constant: measured, the camera's ``ll``)
            inner = self.term(init, i, one_copy(tr, init), depth + 1)
            if inner.op == "leaf":
                return leaf
            inner.src = (node, i)
            return inner
        if isinstance(node, A.Field) and tr.model.is_swizzle(node):
            base_t = tr.type_of(node.base)
            if base_t.is_scalar:
                return leaf
            j = tr.model.swizzle_indices(node)[i]
            inner = self.term(node.base, j, once, depth + 1)
            if inner.op == "leaf":
                return leaf
            inner.src = (node, i)
            return inner
        if isinstance(node, A.Call) and node.constructor and t.is_vector:
            parts: list[tuple[Any, int]] = []
            for a in node.args:
                at = tr.type_of(a)
                if at.base != "float" or not (at.is_scalar or at.is_vector):
                    return leaf
                parts.extend((a, j) for j in range(_size(at)))
            if len(parts) == 1:
                parts = parts * t.size  # (one scalar: every component)
            if len(parts) < t.size:
                return leaf
            a, j = parts[i]
            inner = self.term(a, j, once, depth + 1)
            if inner.op == "k":
                inner.comp = True  # (the constructor is no constant: is_constant said so)
            if inner.op == "leaf":
                return leaf
            inner.src = (node, i)
            return inner
        if (
            isinstance(node, A.Call)
            and node.callee == "normalize"
            and len(node.args) == 1
            and is_builtin(tr, node)
            and t.is_vector
        ):
            x = self.term(node.args[0], i, True, depth + 1)  # (x * rsq: x's component used there)
            rsq = _Term("rsq", src=(node.args[0], -1))
            return _Term("*", (x, rsq), src=(node, i), once=once)
        if isinstance(node, A.Unary) and node.op == "-":
            x = self.term(node.operand, i, True, depth + 1)
            if x.op == "k":
                return _k(-x.value, x.comp, (node, i))
            return _Term("neg", (x,), src=(node, i), once=once)
        if (
            isinstance(node, A.Binary)
            and node.op in ("+", "-", "*")
            and not has_matrix(tr, node.left, node.right)
        ):
            left, right = (
                self.term(
                    side, i if tr.type_of(side).is_vector else 0, used_once(tr, side), depth + 1
                )
                for side in (node.left, node.right)
            )
            if node.op == "-":  # (a - b is a + -b to NIR)
                right = _k(-right.value, right.comp) if right.op == "k" else _Term("neg", (right,))
            return _Term("*" if node.op == "*" else "+", (left, right), src=(node, i), once=once)
        return leaf

    def rules(self, x: _Term) -> _Term:
        """x with NIR's constant rules applied where a constant component takes part, its
        operands first (nir_opt_algebraic reaches a value's operands before the value)."""
        if x.op in ("k", "leaf", "rsq"):
            return x
        args = tuple(self.rules(a) for a in x.args)
        if any(a is not b for a, b in zip(args, x.args)):
            x = _Term(x.op, args, src=x.src, once=x.once, changed=any(a.changed for a in args))
        if x.op == "neg":
            return x
        return self.merged(x)

    def merged(self, x: _Term) -> _Term:
        a, b = x.args
        if a.op == "k" and b.op != "k":
            a, b = b, a
        if b.op != "k" or a.op == "k":
            return x  # (two constants: folded as written)
        if x.op == "*" and a.op == "neg":
            # -y * #c -> -(y * #c), then y's constants merge with c
            inner = self.merged(_Term("*", (a.args[0], b), once=True))
            return _Term("neg", (inner,), changed=True) if inner.changed else x
        # #a * (b * #c) -> (a*c) * b, #a + (b + #c) -> (a + c) + b: no "used once" condition
        if a.op == x.op:
            y, c = a.args
            if y.op == "k" and c.op != "k":
                y, c = c, y
            if c.op == "k" and y.op != "k" and (b.comp or c.comp):
                k = _k(_f32(x.op, b.value, c.value), True)
                if x.op == "+" and k.value == 0.0:
                    return _changed(y)  # (fadd(a, 0.0) -> a)
                return self.merged(_Term(x.op, (y, k), once=x.once, changed=True))
        # (a + b) + #c -> (a + #c) + b, both sums used once, a and b no constant; a product b
        # stays whole (the rule with is_fmul first)
        if x.op == "+" and b.comp and x.once and a.op == "+" and a.once:
            p, q = a.args
            if p.op != "k" and q.op != "k":
                if q.op != "*" and p.op == "*":
                    p, q = q, p
                inner = self.merged(_Term("+", (p, b), once=True, changed=True))
                return _Term("+", (inner, q), once=x.once, changed=True)
        return x


def _changed(x: _Term) -> _Term:
    return _Term(x.op, x.args, x.value, None, x.comp, x.once, True) if not x.changed else x


def component_constants(tr: FoldEmitter, e: A.Binary, mask: str | None) -> Any:
    """The code of a float ``+``, ``-`` or ``*`` whose components NIR's constant rules change
    where a vector constructor's constant component takes part, each changed component in
    Mesa's order (llvmpipe mode); None where no such rule applies."""
    t = tr.type_of(e)
    if not (t.is_scalar or t.is_vector) or has_matrix(tr, e.left, e.right) or tr.has_effects(e):
        return None  # (a leaf with effects would be computed twice)
    if not _constructor_reached(tr, e):
        return None  # (no vector constructor in reach: nothing for this rule)
    ev = _Eval(tr)
    once = used_once(tr, e) or _stored_once(tr, e)
    terms = [ev.rules(ev.term(e, i, once)) for i in range(_size(t))]
    if not any(x.changed for x in terms):
        return None
    lt, rt_ = tr.type_of(e.left), tr.type_of(e.right)
    tl, tr_ = tr.exprs([e.left, e.right], mask)
    written = tr.tmp(tr.binary_values(e.op, lt, rt_, tl, tr_))
    codes: dict[int, Any] = {}
    parts = [
        _code(tr, x, mask, codes) if x.changed else _component(tr, written, i, t)
        for i, x in enumerate(terms)
    ]
    rewritten = parts[0] if t.is_scalar else tr.vector(parts)
    return tr.llvmpipe(rewritten, written)


def _code(tr: FoldEmitter, x: _Term, mask: str | None, codes: dict[int, Any]) -> Any:
    """The code of a term: an unchanged one as its node's component, else its operations."""
    if x.op == "k":
        return tr.const_float(x.value)
    if x.op == "rsq":
        node = x.src[0] if x.src is not None else None
        v = _node_code(tr, node, mask, codes)
        return tr.runtime("inversesqrt", tr.runtime("dot", v, v))
    if not x.changed and x.src is not None:
        node, i = x.src
        return _component(tr, _node_code(tr, node, mask, codes), i, tr.type_of(node))
    if x.op == "neg":
        return tr.negate(_code(tr, x.args[0], mask, codes))
    a, b = (_code(tr, y, mask, codes) for y in x.args)
    return tr.ieee(x.op, a, b)


def _node_code(tr: FoldEmitter, node: Any, mask: str | None, codes: dict[int, Any]) -> Any:
    if id(node) not in codes:
        codes[id(node)] = tr.tmp(tr.expr(node, mask))
    return codes[id(node)]


def _component(tr: FoldEmitter, code: Any, i: int, t: Any) -> Any:
    return tr.component(code, i) if t.is_vector else code


def _constructor_reached(tr: FoldEngine, e: Any, depth: int = 0) -> bool:
    """A vector constructor that is no constant is in e or in the initializer of a
    never-written local it reads (memoized per node)."""
    memo = tr.fold_state.constant_components
    if id(e) in memo:
        return memo[id(e)]
    found = False
    for n in e.walk():
        if isinstance(n, A.Call) and n.constructor and not is_constant(tr, n):
            found = True
        elif isinstance(n, A.Identifier) and depth < 8:
            init = stable_init(tr, n)
            found = init is not None and _constructor_reached(tr, init, depth + 1)
        if found:
            break
    memo[id(e)] = found
    return found


def _stored_once(tr: FoldEngine, e: Any) -> bool:
    """e is the initializer of a local read at one place (to NIR its value feeds one
    instruction per component)."""
    cache = tr.fold_state.component_inits
    key = id(current_function(tr).sym)
    if key not in cache:
        cache[key] = {
            id(n.init): n
            for n in current_function(tr).sym.node.body.walk()
            if isinstance(n, A.Declarator) and n.init is not None
        }
    decl = cache[key].get(id(e))
    if decl is None:
        return False
    sym = tr.model.symbol_of(decl)
    reads = [
        n
        for n in current_function(tr).sym.node.body.walk()
        if isinstance(n, A.Identifier) and tr.model.symbol_of(n) is sym
    ]
    return len(reads) == 1
