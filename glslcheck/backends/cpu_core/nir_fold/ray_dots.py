"""A ray's constant component merged into a dot product with a constant, through calls.

Mesa inlines every call before its algebraic rules run, so a camera ray's constant component
meets a callee's constant in ``#a * (b * #c) -> (a*c) * b`` (constant_merge.py's rule, no
"used once" condition). The path tracer's shape (p03-fdS3zw): the camera's axes fold to
constants, so ``rd = normalize(v)`` has ``rd.z = 3.0 * rsq`` (v.z the constant 3.0, rsq
``inversesqrt(dot(v, v))``); ``traceEyePath(ro, rd)`` passes the constant ro and rd on, in the
first copy of its unrolled loop, to ``intersect`` and ``iSphere(ro, rd, sph)`` with sph
constant, whose ``dot(ro - sph.xyz, rd)`` multiplies rd.z by the constant -9.0: Mesa computes
``-27.0 * rsq`` (measured: tests/gl/test_llvmpipe_sphere_hits.py). The engines write a callee
once for every call, so they pass it two hidden arguments: the ray's rsq and its constant
components (None where the call's ray or constants do not reach it as such, and the callee
computes as written).

:func:`ray_fn`: the functions whose ``dot`` sees such a ray (a `in` vec3 parameter the function
never writes, times a vector computed from constants and parameters whose arguments must be
constants), directly or through the calls that pass the ray on. :func:`ray_call`: where a call
gives one the hidden arguments: its own (the caller's parameter passed on, in the first copy of
an unrolled loop when the loop writes it after the call), or a root (a never-written local
``normalize(v)`` with a nonzero constant component, the needed arguments constants there).
Only the products of the constant components move (``dot`` summed right to left, as
Runtime.dot); rd.x and rd.y stay ``v.x * rsq`` (the ray read elsewhere too)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ....frontend import syntax as A
from ....semantics.analysis import param_directions
from ....semantics.model import Symbol
from .loop_unroll import nir_unrolls
from .queries import asked_in, written_symbols

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..fold_protocols import FoldEngine

F32 = np.float32


@dataclass(frozen=True)
class RayFn:
    """A function some ``dot`` of which sees a ray: its parameter `ray`, the parameters whose
    arguments must be constants (`needs`) and the float globals that must hold constants
    where the root call is made (`globals`, ids)."""

    ray: int
    needs: tuple[int, ...]
    globals: tuple[int, ...]


@dataclass(frozen=True)
class RayCall:
    """A call's hidden arguments: the caller's own (`loop` the loop in whose first copy only,
    or None), or a root's (`root` the local ray, `ks` its constant components, None where not
    constant)."""

    loop: Any = None
    root: Symbol | None = None
    ks: tuple[float | None, ...] = ()


def current_definition(tr: FoldEngine) -> Symbol | None:
    """The user function the engine is emitting (None in a global initializer)."""
    sym = tr.fn.sym if tr.fn is not None else None
    return sym if sym is not None and isinstance(sym.node, A.FunctionDefinition) else None


def ray_roots(tr: FoldEngine) -> dict[int, Symbol]:
    """The locals of the current function some call passes as a ray root, by the id of the
    normalize() that initialises each (in the order the calls name them); memoized."""
    fn = current_definition(tr)
    if fn is None:
        return {}
    key = ("roots", id(fn))
    memo = tr.fold_state.ray_fns
    if key not in memo:
        found: dict[int, Symbol] = {}
        for n in fn.node.body.walk():
            if isinstance(n, A.Call) and isinstance(tr.model.call_target(n), Symbol):
                rc = ray_call(tr, n)
                if rc is not None and rc.root is not None:
                    found[id(rc.root.node.init)] = rc.root
        memo[key] = found
    return memo[key]


def ray_fn(tr: FoldEngine, fn: Symbol) -> RayFn | None:
    """The ray `fn`'s dot products see (the module's doc) where some root call's ray reaches
    it (the lowest such parameter), or None."""
    live = _live(tr)
    rays = [r for r in _candidates(tr, fn) if (id(fn), r) in live]
    return _candidates(tr, fn)[min(rays)] if rays else None


def _candidates(tr: FoldEngine, fn: Symbol) -> dict[int, RayFn]:
    """Each parameter of `fn` some dot product would see as a ray, and its RayFn."""
    memo = tr.fold_state.ray_fns
    key = ("candidates", id(fn))
    if key not in memo:
        memo[key] = {}  # (GLSL has no recursion: a guard only)
        with asked_in(tr, fn):
            memo[key] = _ray_fns(tr, fn)
    return memo[key]


def _live(tr: FoldEngine) -> set[tuple[int, int]]:
    """(function, parameter) of the candidates a root call's ray reaches, through the calls
    that pass it on."""
    memo = tr.fold_state.ray_fns
    if "live" in memo:
        return memo["live"]
    memo["live"] = set()
    fns: dict[int, Symbol] = {}
    todo = [tr.model.entry] if tr.model.entry is not None else []
    while todo:
        f = todo.pop()
        if f is None or id(f) in fns:
            continue
        fns[id(f)] = f
        todo += [
            t
            for n in f.node.body.walk()
            if isinstance(n, A.Call) and isinstance(t := tr.model.call_target(n), Symbol)
        ]
    live: set[tuple[int, int]] = set()
    edges: dict[tuple[int, int], list[tuple[int, int]]] = {}
    for f in fns.values():
        for n in f.node.body.walk():
            g = tr.model.call_target(n) if isinstance(n, A.Call) else None
            if not isinstance(g, Symbol) or g is f:
                continue
            for r, cand in _candidates(tr, g).items():
                with asked_in(tr, f):
                    if _root_call(tr, f, n, cand) is not None:
                        live.add((id(g), r))
                    q = _param_index(tr, f, n.args[r])
                    if q is not None and q in _candidates(tr, f):
                        edges.setdefault((id(f), q), []).append((id(g), r))
    todo2 = list(live)
    while todo2:
        k = todo2.pop()
        for nxt in edges.get(k, []):
            if nxt not in live:
                live.add(nxt)
                todo2.append(nxt)
    memo["live"] = live
    return live


def _param_index(tr: FoldEngine, fn: Symbol, node: Any) -> int | None:
    sym = tr.model.symbol_of(node) if isinstance(node, A.Identifier) else None
    if sym is None or sym.kind != "param":
        return None
    for i, p in enumerate(fn.node.proto.params):
        if tr.model.symbol_of(p) is sym:
            return i
    return None


def _ray_fns(tr: FoldEngine, fn: Symbol) -> dict[int, RayFn]:
    dirs = param_directions(fn)
    written = written_symbols(tr)
    syms = [tr.model.symbol_of(p) for p in fn.node.proto.params]

    def ray_param(node: Any) -> int | None:
        i = _param_index(tr, fn, node)
        if i is None or dirs[i] != "in" or str(syms[i].type) != "vec3":
            return None
        return i

    found: dict[int, tuple[set[int], set[int]]] = {}
    for n in fn.node.body.walk():
        if not isinstance(n, A.Call):
            continue
        target = tr.model.call_target(n)
        if n.callee == "dot" and not isinstance(target, Symbol) and len(n.args) == 2:
            for r_node, x_node in ((n.args[1], n.args[0]), (n.args[0], n.args[1])):
                r = ray_param(r_node)
                if r is None or id(syms[r]) in written:
                    continue
                needs = _constant_params(tr, fn, x_node, written, 0)
                if needs is not None and r not in needs:
                    found.setdefault(r, (set(), set()))[0].update(needs)
                    break
        elif isinstance(target, Symbol) and target is not fn:
            for g in _candidates(tr, target).values():
                r = ray_param(n.args[g.ray])
                if r is None or _unchanged(tr, fn, syms[r], n) is False:
                    continue
                passed = _passed_needs(tr, fn, n, g, written)
                if passed is not None:
                    entry = found.setdefault(r, (set(), set()))
                    entry[0].update(passed[0])
                    entry[1].update(passed[1] | set(g.globals))
    return {r: RayFn(r, tuple(sorted(a)), tuple(sorted(b))) for r, (a, b) in found.items()}


def _passed_needs(
    tr: FoldEngine, fn: Symbol, call: A.Call, g: RayFn, written: set[int]
) -> tuple[set[int], set[int]] | None:
    """The parameters of `fn` and the globals the arguments of `call` that `g` needs constant
    come from, or None where one is neither a constant nor such a parameter."""
    params: set[int] = set()
    globals_: set[int] = set()
    for j in g.needs:
        a = call.args[j]
        if tr.model.const_value(a) is not None:
            continue
        sym = tr.model.symbol_of(a) if isinstance(a, A.Identifier) else None
        q = _param_index(tr, fn, a)
        if q is not None and param_directions(fn)[q] == "in":
            if _unchanged(tr, fn, sym, call) is False:
                return None
            params.add(q)
        elif sym is not None and sym.kind == "global" and sym.const_value is not None:
            continue
        elif sym is not None and sym.kind == "global" and str(sym.type).startswith("vec"):
            globals_.add(id(sym))
        else:
            return None
    return params, globals_


def _constant_params(
    tr: FoldEngine, fn: Symbol, e: Any, written: set[int], depth: int
) -> set[int] | None:
    """The `in` parameters of `fn` that `e` reads, where it computes a float vector of them
    and constants only (``+ - * /``, negation, swizzles, never-written locals), else None."""
    if depth > 8:
        return None
    if tr.model.const_value(e) is not None:
        return set()
    if isinstance(e, A.Field):
        return _constant_params(tr, fn, e.base, written, depth + 1)
    if isinstance(e, A.Unary) and e.op == "-":
        return _constant_params(tr, fn, e.operand, written, depth + 1)
    if isinstance(e, A.Binary) and e.op in ("+", "-", "*", "/"):
        a = _constant_params(tr, fn, e.left, written, depth + 1)
        b = _constant_params(tr, fn, e.right, written, depth + 1)
        return None if a is None or b is None else a | b
    if not isinstance(e, A.Identifier):
        return None
    sym = tr.model.symbol_of(e)
    if sym is None or id(sym) in written or sym.type.base != "float":
        return None
    if sym.kind == "param":
        i = _param_index(tr, fn, e)
        return {i} if i is not None and param_directions(fn)[i] == "in" else None
    if sym.kind == "global" and sym.const_value is not None:
        return set()
    init = sym.node.init if isinstance(sym.node, A.Declarator) else None
    if sym.kind != "local" or init is None:
        return None
    return _constant_params(tr, fn, init, written, depth + 1)


def _unchanged(tr: FoldEngine, fn: Symbol, sym: Symbol | None, call: A.Call) -> Any:
    """True where `fn` never writes parameter `sym`; the loop where `call` is a top-level
    statement's of the body of a loop NIR unrolls, itself a top-level statement of `fn`, and
    only that body writes `sym`, after the call (so the first copy reads the argument); else
    False."""
    if sym is None:
        return False
    if id(sym) not in written_symbols(tr):
        return True
    body = fn.node.body.stmts
    for loop in body:
        if not isinstance(loop, A.For) or not isinstance(loop.body, A.Compound):
            continue
        stmts = loop.body.stmts
        at = next((k for k, st in enumerate(stmts) if any(n is call for n in st.walk())), None)
        if at is None:
            continue
        if not nir_unrolls(tr, loop) or any(_writes(tr, st, sym) for st in body if st is not loop):
            return False
        if any(_writes(tr, st, sym) for st in stmts[: at + 1]) or _writes(tr, loop.init, sym):
            return False
        return loop
    return False


def _writes(tr: FoldEngine, node: Any, sym: Symbol) -> bool:
    if node is None:
        return False
    for n in node.walk():
        target = None
        if isinstance(n, A.Assignment):
            target = n.target
        elif isinstance(n, (A.Unary, A.Postfix)) and n.op in ("++", "--"):
            target = n.operand
        elif isinstance(n, A.Call) and isinstance(t := tr.model.call_target(n), Symbol):
            for a, d in zip(n.args, param_directions(t)):
                if d != "in" and _root(tr, a) is sym:
                    return True
        if target is not None and _root(tr, target) is sym:
            return True
    return False


def _root(tr: FoldEngine, x: Any) -> Symbol | None:
    while isinstance(x, (A.Field, A.Index)):
        x = x.base
    return tr.model.symbol_of(x) if isinstance(x, A.Identifier) else None


def ray_call(tr: FoldEngine, call: A.Call) -> RayCall | None:
    """The hidden arguments a call of a :func:`ray_fn` function gets in the current function
    (the module's doc), or None (the callee computes as written)."""
    fn = current_definition(tr)
    target = tr.model.call_target(call)
    if fn is None or not isinstance(target, Symbol):
        return None
    g = ray_fn(tr, target)
    if g is None:
        return None
    own = ray_fn(tr, fn)
    if own is not None and _param_index(tr, fn, call.args[g.ray]) == own.ray:
        with asked_in(tr, fn):
            written = written_symbols(tr)
            unchanged = _unchanged(tr, fn, _root(tr, call.args[g.ray]), call)
            passed = _passed_needs(tr, fn, call, g, written)
        if unchanged is False or passed is None or not passed[0] <= set(own.needs):
            return None
        return RayCall(loop=None if unchanged is True else unchanged)
    return _root_call(tr, fn, call, g)


def _root_call(tr: FoldEngine, fn: Symbol, call: A.Call, g: RayFn) -> RayCall | None:
    """A root: the ray argument a never-written local ``normalize(v)`` with a nonzero
    constant component, each needed argument a constant there, each needed global a
    constant where the call is made."""
    written = written_symbols(tr)
    a = call.args[g.ray]
    sym = tr.model.symbol_of(a) if isinstance(a, A.Identifier) else None
    if sym is None or sym.kind != "local" or id(sym) in written:
        return None
    init = sym.node.init if isinstance(sym.node, A.Declarator) else None
    if not (isinstance(init, A.Call) and init.callee == "normalize" and len(init.args) == 1):
        return None
    if isinstance(tr.model.call_target(init), Symbol):
        return None
    ks = _components(tr, init.args[0], written, 0)
    if ks is None or len(ks) != 3 or not any(k is not None and k != 0.0 for k in ks):
        return None
    for j in g.needs:
        vals = _components(tr, call.args[j], written, 0)
        if vals is None or any(v is None for v in vals):
            return None
    for k in g.globals:
        if not _constant_global_at(tr, fn, k, call):
            return None
    return RayCall(root=sym, ks=tuple(None if k == 0.0 else k for k in ks))


def _constant_global_at(tr: FoldEngine, fn: Symbol, key: int, call: A.Call) -> bool:
    """Global `key` holds a constant where `call` is made: an earlier statement of the block
    that holds the call's statement calls a straight-line function that writes the constant
    (call_fold's evaluation), nothing after it and before the call writes the global, and
    nothing the called function runs writes it."""
    target = tr.model.call_target(call)
    if key in tr.facts.global_effects(target)[1]:
        return False
    from ..call_fold import writes_constants

    holders = [
        (b.stmts, k)
        for b in fn.node.body.walk()
        if isinstance(b, A.Compound)
        for k, st in enumerate(b.stmts)
        if any(n is call for n in st.walk())
    ]
    if not holders:
        return False
    stmts, at = holders[-1]  # (the innermost block: walk visits a block before its own)
    for st in reversed(stmts[:at]):
        calls = [
            n
            for n in st.walk()
            if isinstance(n, A.Call) and isinstance(tr.model.call_target(n), Symbol)
        ]
        if (
            isinstance(st, A.ExpressionStatement)
            and isinstance(st.expr, A.Call)
            and calls == [st.expr]
        ):
            if key in tr.facts.global_effects(tr.model.call_target(st.expr))[1]:
                return writes_constants(tr, st.expr, key)  # type: ignore[arg-type]
        if any(key in tr.facts.global_effects(tr.model.call_target(c))[1] for c in calls):
            return False
        if any(
            (g := _root(tr, n.target)) is not None and id(g) == key
            for n in st.walk()
            if isinstance(n, A.Assignment)
        ):
            return False
    return False


def _components(tr: FoldEngine, e: Any, written: set[int], depth: int) -> list[float | None] | None:
    """Each component of float expression `e` as NIR's constant folding sees it: a float32
    constant, or None (a run-time value); ``x * 0.0`` is 0.0 and ``x + 0.0`` is x (Mesa's
    inexact rules). None where `e`'s shape is not followed."""
    if depth > 16:
        return None
    t = tr.type_of(e)
    if t is None or t.base != "float" or not (t.is_scalar or t.is_vector):
        return None
    n = 1 if t.is_scalar else t.size
    cv = tr.model.const_value(e)
    if cv is not None:
        from ..fold_eval import Refuse, flat_terms

        try:
            vals = flat_terms(cv)
        except Refuse:
            return None
        return [float(F32(v)) for v in vals] if len(vals) == n else None
    unknown: list[float | None] = [None] * n
    if isinstance(e, A.Identifier):
        sym = tr.model.symbol_of(e)
        init = sym.node.init if sym is not None and isinstance(sym.node, A.Declarator) else None
        if sym is None or sym.kind != "local" or id(sym) in written or init is None:
            return unknown
        return _components(tr, init, written, depth + 1) or unknown
    if isinstance(e, A.Field):
        base = _components(tr, e.base, written, depth + 1)
        idx = [max(s.find(c) for s in ("xyzw", "rgba", "stpq")) for c in e.name]
        if base is None or min(idx) < 0:
            return unknown
        return [base[i] if i < len(base) else None for i in idx]
    if isinstance(e, A.Unary) and e.op == "-":
        a = _components(tr, e.operand, written, depth + 1)
        return unknown if a is None else [None if v is None else -v for v in a]
    if isinstance(e, A.Binary) and e.op in ("+", "-", "*"):
        a = _components(tr, e.left, written, depth + 1)
        b = _components(tr, e.right, written, depth + 1)
        if a is None or b is None:
            return unknown
        a, b = (a * n if len(a) == 1 else a), (b * n if len(b) == 1 else b)
        return [_fold(e.op, x, y) for x, y in zip(a, b)]
    if isinstance(e, A.Call) and not isinstance(tr.model.call_target(e), Symbol):
        if e.constructor and t.is_vector:
            parts: list[float | None] = []
            for arg in e.args:
                parts += _components(tr, arg, written, depth + 1) or [None] * _width(tr, arg)
            return parts * n if len(parts) == 1 else (parts if len(parts) == n else unknown)
        args = [_components(tr, a, written, depth + 1) for a in e.args]
        if e.callee == "normalize" and args[0] is not None and len(args[0]) == n:
            x = args[0]
            if all(v is not None for v in x):
                v = np.asarray(x, F32)
                d = v[n - 1] * v[n - 1]
                for i in range(n - 2, -1, -1):
                    d = F32(v[i] * v[i] + d)
                r = F32(1.0) / np.sqrt(F32(d))
                return [float(F32(c * r)) for c in v]
            return [0.0 if c == 0.0 else None for c in x]  # (0 * rsq)
        if e.callee == "cross" and all(a is not None and len(a) == 3 for a in args):
            p, q = args
            if all(v is not None for v in p + q):  # type: ignore[operator]
                a3, b3 = np.asarray(p, F32), np.asarray(q, F32)
                return [
                    float(F32(a3[1] * b3[2] - a3[2] * b3[1])),
                    float(F32(a3[2] * b3[0] - a3[0] * b3[2])),
                    float(F32(a3[0] * b3[1] - a3[1] * b3[0])),
                ]
    return unknown


def _width(tr: FoldEngine, e: Any) -> int:
    t = tr.type_of(e)
    return 1 if t is None or t.is_scalar else t.size


def _fold(op: str, x: float | None, y: float | None) -> float | None:
    if x is not None and y is not None:
        a, b = F32(x), F32(y)
        return float(a + b if op == "+" else a - b if op == "-" else a * b)
    if op == "*" and (x == 0.0 or y == 0.0):
        return 0.0  # (``a * 0.0 -> 0.0``)
    if op == "+" and x == 0.0:
        return y
    if op in "+-" and y == 0.0:
        return x
    return None


def ray_loop(tr: FoldEngine, loop: Any) -> bool:
    """Some call in `loop` passes the current function's ray on in the first copy only: the
    engines count the loop's passes."""
    fn = current_definition(tr)
    if fn is None or not isinstance(loop, A.For):
        return False
    if ray_fn(tr, fn) is None:
        return False
    for n in loop.body.walk():
        if isinstance(n, A.Call) and isinstance(tr.model.call_target(n), Symbol):
            rc = ray_call(tr, n)
            if rc is not None and rc.loop is loop:
                return True
    return False


def ray_dot(tr: FoldEngine, call: A.Call) -> tuple[int, int] | None:
    """(the index of the ray's argument, of the other's) of a ``dot`` of the current function
    that :func:`ray_fn` found: it merges the caller's constant components where the hidden
    arguments are given; else None."""
    fn = current_definition(tr)
    if fn is None or call.callee != "dot" or isinstance(tr.model.call_target(call), Symbol):
        return None
    own = ray_fn(tr, fn)
    if own is None or len(call.args) != 2:
        return None
    written = written_symbols(tr)
    for r, x in ((1, 0), (0, 1)):
        if _param_index(tr, fn, call.args[r]) == own.ray:
            needs = _constant_params(tr, fn, call.args[x], written, 0)
            if needs is not None and set(needs) <= set(own.needs) and own.ray not in needs:
                return r, x
    return None
