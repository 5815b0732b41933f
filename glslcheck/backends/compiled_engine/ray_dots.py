"""A ray's constant components merged into a callee's dot product (cpu_core/nir_fold/ray_dots.py),
written by the compiled engine as the NumPy backend does (numpy_engine/transpile/ray_dots.py):
a function whose dot products see a ray takes a flag, the ray's rsq and one constant per
component (0.0 where not constant); a root's ``normalize(v)`` keeps its rsq's temporary."""

from __future__ import annotations

from typing import Any

from ...frontend import syntax as A
from ...semantics.model import Symbol
from ..cpu_core.nir_fold.ray_dots import ray_call, ray_dot, ray_fn, ray_roots
from .values import Val

_HIDDEN = ["_rf", "_rq", "_rk0", "_rk1", "_rk2"]


def ray_param_names(cg: Any, fn: Symbol) -> list[str]:
    """The hidden parameters of a function whose dot products see a ray."""
    return list(_HIDDEN) if ray_fn(cg.fold_context(), fn) is not None else []


def ray_call_args(cg: Any, call: A.Call, fn: Symbol) -> list[str]:
    """The hidden arguments of a call of `fn`: the caller's own (in the first pass of the loop
    that writes the ray after the call), a root's, or a false flag and zeros."""
    ctx = cg.fold_context()
    if ray_fn(ctx, fn) is None:
        return []
    zero = cg.cf(0.0)
    none = ["False"] + [zero] * 4
    rc = ray_call(ctx, call)
    if rc is None:
        return none
    if rc.root is None:
        if rc.loop is None:
            return list(_HIDDEN)
        return [f"(_rf and {cg.fn.sum_index[id(rc.loop)]} == 0)"] + _HIDDEN[1:]
    kept = cg.fn.ray_roots.get(id(rc.root))
    if kept is None or kept[1] > cg.indent:
        return none
    return ["True", kept[0]] + [zero if k is None else cg.cf(k) for k in rc.ks]


def _root_of(cg: Any, e: A.Call) -> Symbol | None:
    """The ray root local `e` (a ``normalize``) initialises, or None."""
    return ray_roots(cg.fold_context()).get(id(e))


def ray_normalize(cg: Any, e: A.Call, args: list[Val], rtype: Any) -> Val | None:
    """``normalize(v)`` initialising a ray root: as geometric's, its rsq's temporary kept for
    the call; else None."""
    if cg.fn is None or cg.fn.sym is None:
        return None
    sym = _root_of(cg, e)
    if sym is None:
        return None
    parts = [cg.atom(p) for p in args[0].parts]
    d = cg.tmp(f"(F32(1.0) / np.sqrt({cg.dot_text(parts, parts)}))")
    cg.fn.ray_roots[id(sym)] = (d, cg.indent)
    return Val(rtype, [f"({p} * {d})" for p in parts])


def ray_dot_val(cg: Any, e: A.Call, args: list[Val], written: Val) -> Val:
    """A dot product that sees the caller's ray: ``(x[i] * k[i]) * rq`` where the caller's
    component i is the constant k[i] (not 0.0), the `written` products elsewhere, summed right
    to left, where the flag is set; `written` otherwise."""
    found = ray_dot(cg.fold_context(), e)
    if found is None or len(args[0].parts) != 3:
        return written
    r, x = found
    xs = [cg.atom(p) for p in args[x].parts]
    ps = [cg.atom(p) for p in args[r].parts]
    plain = cg.fmul(
        Val(args[x].t, xs, args[x].const, args[x].uni),
        Val(args[r].t, ps, args[r].const, args[r].uni),
        args[x].t,
    ).parts
    terms = [
        f"((({xi} * _rk{i}) * _rq) if _rk{i} != F32(0.0) else {pi})"
        for i, (xi, pi) in enumerate(zip(xs, plain))
    ]
    text = terms[-1]
    for t in terms[-2::-1]:
        text = f"({t} + {text})"
    return Val(written.t, [f"({text} if _rf else {written.parts[0]})"])
