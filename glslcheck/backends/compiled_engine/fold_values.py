"""Mesa's rewrites (the NumPy backend's nir_fold) computed by the compiled engine: the rules decide,
this module gives them the compiled engine's values to build Mesa's order from.

A rule of backends/cpu_core/nir_fold builds its rewrite from the operations of
fold_protocols.FoldEmitter (operands, products and sums as the engine writes them, IEEE operations,
negation) and never spells one itself; the NumPy Transpiler answers with Python text over lane
arrays, :class:`FoldValues` with Codegen's `Val`s. So a rule changes both engines at once, and
both compute the same float32 operations in the same order.

What the NumPy backend holds as one lane matters to the bits (Runtime.fmul takes a value the
same in every lane, computed, for a constant, and folds ``x * 0.0`` to 0): a value here carries
`Val.one` (one lane there: a uniform input, a constant, a value of the uniformity analysis) and
`Val.uni` (one lane and computed: taken there for a constant), as the arrays there are."""

from __future__ import annotations

import math
from typing import Any

from ...language import glsl_types as T
from ...semantics.consteval import f32
from ..cpu_core import nir_fold
from ..cpu_core.call_fold import fold_plan, opaque_calls, record_sums
from ..cpu_core.fold_eval import holder_leaf, term_fields
from ..cpu_core.nir_fold import FoldContext
from ..cpu_core.nir_fold.repeated_sums import chain_params
from .builtin_calls import componentwise_text, geometric
from .values import Val, not_yet

# the families of nir_fold.BINARY_RULES this engine computes (built from FoldEmitter's operations)
COPIED = frozenset(
    {
        "matrix",
        "product_sums",
        "factoring",
        "exp_log",
        "constant_merge",
        "constant_components",
        "components",
        "compound",
        "sink",
        "ssa_values",
    }
)


class FoldValues(FoldContext):
    """nir_fold's context for the compiled engine, with the operations its rules emit through
    (fold_protocols.FoldEmitter): every value is a `Val` of the Codegen being generated."""

    def __init__(self, cg: Any) -> None:  # (a Codegen, which imports this module)
        super().__init__(cg.model, cg.facts)
        self.cg = cg

    @property
    def lines(self) -> Any:
        """The function being generated (each variant anew): a value a rule kept is read there."""
        return self.cg.fn

    def expr(self, e: Any, mask: str | None = None) -> Val:
        v = self.cg.expr(e)
        v.one = self.cg.one_lane(e)
        return v

    def exprs(self, items: list[Any], mask: str | None = None) -> list[Val]:
        return [self.expr(e, mask) for e in items]

    def const_float(self, v: float, v32: float | None = None) -> Val:
        x = v32 if v32 is not None else f32(v)
        return Val(T.FLOAT, [self.cg.cf(x)], [x], uni=True, one=True)

    def binary_values(self, op: str, lt: Any, rtp: Any, left: Val, right: Val) -> Val:
        """`left op right` as the NumPy Transpiler's binary_values computes it: a float product
        is Runtime.fmul (Codegen.fmul; a matrix product by shape), a sum the operator."""
        rtype = T.binary_result(op, lt, rtp)
        assert not isinstance(rtype, str), rtype  # (the rules combine operands of checked types)
        cg = self.cg
        if op == "*" and (lt.is_matrix or rtp.is_matrix) and not (lt.is_scalar or rtp.is_scalar):
            v = cg.linear_product(left, right, rtype)
        elif op == "*":
            v = cg.fmul(left, right, rtype)
        else:
            v = cg.componentwise(left, right, rtype, lambda a, b, i: f"({a} {op} {b})")
        return _computed(v, left, right)

    def ieee(self, op: str, left: Val, right: Val) -> Val:
        rtype = T.binary_result(op, left.t, right.t)
        assert not isinstance(rtype, str), rtype
        v = self.cg.componentwise(left, right, rtype, lambda a, b, i: f"({a} {op} {b})")
        return _computed(v, left, right)

    def negate(self, value: Val) -> Val:
        return Val(value.t, [f"(-{p})" for p in value.parts], None, value.one, value.one)

    def llvmpipe(self, rewritten: Val, written: Val) -> Val:
        """Mesa's order: the compiled engine computes llvmpipe's float32 only."""
        return rewritten

    def store(self, target: Val, value: Val) -> Val:
        """value into the temporaries of `target` (made before a loop: Codegen.enter_unrolled)."""
        for name, part in zip(target.parts, value.parts):
            self.cg.emit(f"{name} = {part}")
        return Val(target.t, target.parts, None, value.uni, value.one)

    def by_copy(self, loop: Any, first: Val, later: Val) -> Val:
        """`first` in the first pass of a loop NIR unrolls, `later` in the others (its pass
        count: Codegen.enter_unrolled)."""
        assert self.cg.fn is not None  # (generating a function)
        ix = self.cg.fn.sum_index[id(loop)]
        parts = [f"({a} if {ix} == 0 else {b})" for a, b in zip(first.parts, later.parts)]
        one = first.one and later.one
        return Val(first.t, parts, None, first.uni and later.uni, one)

    def tmp(self, value: Val) -> Val:
        """value in temporaries that later writes leave alone (a rule reads them after the
        variable they came from is written again: a variable's name is copied too)."""
        parts = [
            p if p.startswith(("F_", "I_", "U_", "_t")) else self.cg.tmp_fresh(p)
            for p in value.parts
        ]
        return Val(value.t, parts, value.const, value.uni, value.one)

    def component(self, value: Val, i: int) -> Val:
        const = [value.const[i]] if value.const is not None else None
        return Val(T.SCALARS[value.t.base], [value.parts[i]], const, value.uni, value.one)

    def vector(self, parts: list[Val]) -> Val:
        one = all(p.one for p in parts)  # (Runtime.vec: a new array)
        return Val(T.vector("float", len(parts)), [p.parts[0] for p in parts], None, one, one)

    def leaves(self, value: Val, t: Any) -> list[str]:
        return [self.cg.atom(p) for p in value.parts]

    def swizzle(self, value: Val, idx: tuple[int, ...]) -> Val:
        """Runtime.swizzle: a view where the components are evenly spaced (a uniform input's
        stays read-only: no constant), else a new array."""
        step = idx[1] - idx[0] if len(idx) > 1 else 1
        view = step > 0 and all(b - a == step for a, b in zip(idx, idx[1:]))
        uni = value.uni if view else value.one
        const = [value.const[i] for i in idx] if value.const is not None else None
        t = T.vector(value.t.base, len(idx))
        return Val(t, [value.parts[i] for i in idx], const, uni, value.one)

    def runtime(self, name: str, *args: Val) -> Val:
        """The Runtime's operation `name` (runtime_operators.py, runtime_transcendental.py), as
        the NumPy backend computes it: `dot` (Runtime.dot, products summed right to left),
        `dot_add` (the constant in the innermost sum), `inversesqrt`, `fadd` (a constant zero
        added keeps the other operand), `exp`, `exp2`, `log2`."""
        cg = self.cg
        if name == "fadd":
            a, b = args
            rtype = T.binary_result("+", a.t, b.t)
            assert not isinstance(rtype, str), rtype
            return _computed(cg.fadd("+", a, b, rtype), a, b)
        if name == "dot":
            u, v = args
            return _computed(geometric(cg, "dot", [u, v], T.FLOAT), u, v)
        if name == "dot_add":
            u, v, k = args
            u = Val(u.t, [cg.atom(p) for p in u.parts], u.const, u.uni, u.one)
            v = Val(v.t, [cg.atom(p) for p in v.parts], v.const, v.uni, v.one)
            prods = cg.fmul(u, v, u.t if len(u.parts) >= len(v.parts) else v.t).parts
            text = f"({prods[-1]} + {k.parts[0]})"
            for p in reversed(prods[:-1]):
                text = f"({p} + {text})"
            return _computed(_computed(Val(T.FLOAT, [text]), u, v), k, k)
        if name == "inversesqrt":
            (x,) = args
            return _computed(Val(x.t, [f"inversesqrt({p})" for p in x.parts]), x, x)
        if name in ("exp", "exp2", "log2"):  # (nir_fold.exp_log: the lowered forms)
            (x,) = args
            return _computed(Val(x.t, [componentwise_text(cg, name, p) for p in x.parts]), x, x)
        if name == "smoothstep_scaled":  # (nir_fold.smoothstep_products)
            return _smoothstep_scaled(cg, *args)
        raise ValueError(f"no Runtime operation {name!r} here")


def _smoothstep_scaled(cg: Any, e0: Val, e1: Val, x: Val, k: Val) -> Val:
    """Runtime.smoothstep_scaled per component (scalar edges and constants broadcast)."""
    n = len(x.parts)
    e0s, e1s, ks = ([v.parts[i if len(v.parts) > 1 else 0] for i in range(n)] for v in (e0, e1, k))
    parts = [f"smoothstep_scaled({a}, {b}, {c}, {d})" for a, b, c, d in zip(e0s, e1s, x.parts, ks)]
    return Val(x.t, parts)


def _computed(v: Val, left: Val, right: Val) -> Val:
    """v, the result of an operation on left and right, flagged as the NumPy backend's array of
    it is: one lane when both operands are, and then a computed value (a constant to fmul)."""
    one = left.one and right.one
    return Val(v.t, v.parts, None, one, one)


def folded_call(cg: Any, call: Any, fn: Any) -> Val | None:
    """The call `call` of user function `fn` with constants propagated into it as NIR does,
    where the NumPy backend's cpu_core/call_fold.py decides so (fold_plan: the terms of its
    out parameters and its result), computed from those terms as the Transpiler emits them
    (call_fold._emit_call); None: the call as usual."""

    fold = cg.fold_context()
    plan = fold_plan(fold, call, fn, None, lambda f: bool(chain_params(fold, f)))
    if plan is None:
        return None
    env, params, result, holders = plan
    held = {i: (fold.tmp(cg.expr(a)).parts, cg.type_of(a)) for i, a in holders}
    # (its terms read the globals' known values: its writes, unless they are made by the
    # callee's calls in the folded code: cpu_core.call_fold.opaque_calls)
    if fold.facts.writes_globals(fn) and not opaque_calls(call, holders):
        fold.fold_state.call_fold_off = True
        try:
            cg.user_call(call, fn)
        finally:
            fold.fold_state.call_fold_off = False
    memo: dict[int, str] = {}

    def code(term: Any) -> str:
        if id(term) in memo:
            return memo[id(term)]
        op, args, value, text = term_fields(term)
        if op == "k" and value is not None:
            c = cg.cf(value)
        elif op == "x":
            leaf = holder_leaf(text)
            if leaf is None:
                c = text  # (a value the engine computed: a uniform the callee reads)
            else:
                parts, t = held[leaf[0]]
                idx = leaf[1]
                c = parts[idx[0] * t.rows + idx[1] if len(idx) == 2 else idx[0] if idx else 0]
        else:
            xs = [code(x) for x in args]
            if op == "neg":
                c = cg.tmp(f"(-{xs[0]})")
            elif op == "call":
                c = cg.tmp(_runtime_text(cg, text, xs))
            elif op in ("+", "-", "*", "/") and len(xs) == 2:
                c = cg.tmp(f"({xs[0]} {op} {xs[1]})")
            else:
                raise not_yet(f"a folded call's term {op!r}", call)
        memo[id(term)] = c
        return c

    for a, p, (_, _, d) in zip(call.args, params, fn.params):
        if d != "in":
            cg.write(cg.lvalue(a), [code(x) for x in env[id(p)]])
            record_sums(fold, call, a, env[id(p)], memo)  # (for nir_fold.fused_plan)
    return Val(fn.type, [code(x) for x in result])


def fused_sum(cg: Any, e: Any) -> Val | None:
    """``x + e`` where x holds the sums of products a folded call wrote and llvmpipe's ffma
    fusing and splitting reassociates them (nir_fold.fused_plan decides): ``(p1 + e) + p2``
    per such component, as the NumPy backend's ffma_split computes it; None: the sum as usual."""

    fold = cg.fold_context()
    plan = nir_fold.fused_plan(fold, e)
    if plan is None:
        return None
    x, other, sums = plan
    tx, to = cg.type_of(x), cg.type_of(other)
    left, right = cg.expr(e.left), cg.expr(e.right)
    xv, ov = (left, right) if x is e.left else (right, left)
    oparts = [cg.tmp_fresh(p) for p in ov.parts]  # (read after x's value, as there)
    parts = []
    for i, s in enumerate(sums):
        oi = oparts[i] if to.is_vector else oparts[0]
        xi = xv.parts[i] if tx.is_vector else xv.parts[0]
        parts.append(f"(({s[0]} + {oi}) + {s[1]})" if s is not None else f"({xi} + {oi})")
    return Val(tx, parts)


def _runtime_text(cg: Any, method: str, xs: list[str]) -> str:
    """A call term's Runtime method (call_fold: `pow`, ``pow_const({}, c)``, a component-wise
    built-in) of one component, as this engine computes it."""
    if method == "pow":
        return f"pow({xs[0]}, {xs[1]}, FMA)"
    if method.startswith("pow_const("):
        c = float(method[len("pow_const({}, ") : -1])  # (Runtime.pow_const's exponents)
        if c == 1.0:
            return xs[0]
        if c == 2.0:
            return f"({xs[0]} * {xs[0]})"
        if c == 4.0:
            sq = cg.tmp(f"({xs[0]} * {xs[0]})")
            return f"({sq} * {sq})"
        if c == 0.0 and math.copysign(1.0, c) > 0:
            return f"pow_zero({xs[0]})"
        return f"pow({xs[0]}, {cg.cf(c)}, FMA)"
    text = componentwise_text(cg, method, xs[0]) if len(xs) == 1 else None
    if text is None:
        raise ValueError(f"no Runtime method {method!r} here")
    return text
