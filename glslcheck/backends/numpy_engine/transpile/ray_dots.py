"""A ray's constant components merged into a callee's dot product (cpu_core/nir_fold/ray_dots.py),
written by the NumPy transpiler: a function whose dot products see a ray takes two more
arguments, the ray's rsq (lanes) and its constant components (a tuple, None where not
constant); a root's ``normalize(v)`` keeps v in a temporary, and the dot computes the merged
products in llvmpipe mode where both are given."""

from __future__ import annotations

from ....frontend import syntax as A
from ....semantics.model import Symbol
from ...cpu_core.nir_fold.ray_dots import ray_call, ray_dot, ray_fn, ray_roots

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from .state import TranspilerState


def ray_param_names(tr: TranspilerState, fn: Symbol) -> list[str]:
    """The hidden parameters of a function whose dot products see a ray: its rsq, its
    constant components."""
    return ["_rq", "_rk"] if ray_fn(tr, fn) is not None else []


def ray_call_args(tr: TranspilerState, call: A.Call, fn: Symbol) -> list[str]:
    """The hidden arguments of a call of `fn`: the caller's own (in the first pass of the loop
    that writes the ray after the call), a root's rsq and constants, or None and None."""
    if ray_fn(tr, fn) is None:
        return []
    rc = ray_call(tr, call)
    if rc is None:
        return ["None", "None"]
    if rc.root is None:
        if rc.loop is None:
            return ["_rq", "_rk"]
        return [f"(_rq if {tr.fold_state.sum_index[id(rc.loop)]} == 0 else None)", "_rk"]
    kept = tr.fold_state.ray_fns.get(("root", id(rc.root)))
    if kept is None or kept[1] is not tr.lines:
        return ["None", "None"]
    v = kept[0]
    ks = ", ".join("None" if k is None else repr(k) for k in rc.ks)
    return [f"(rt.inversesqrt(rt.dot({v}, {v})) if rt.lp else None)", f"({ks},)"]


def _roots(tr: TranspilerState) -> list[Symbol]:
    """The locals of the current function some call passes as a ray root."""
    return list(ray_roots(tr).values())


def ray_normalize(tr: TranspilerState, e: A.Call, mask: str | None) -> str | None:
    """``normalize(v)`` initialising a ray root: v kept in a temporary (its rsq is computed
    from it at the call), else None."""
    for sym in _roots(tr):
        if sym.node.init is e:
            v = tr.tmp(tr.expr(e.args[0], mask))
            tr.fold_state.ray_fns[("root", id(sym))] = (v, tr.lines)
            return f"rt.normalize({v})"
    return None


def ray_dot_code(tr: TranspilerState, e: A.Call, args: list[str], other: str | None) -> str | None:
    """A dot product that sees the caller's ray: the merged products where the hidden
    arguments are given (Runtime.ray_dot), else `other` (another rule's code) or the written
    dot."""
    if tr.fn is None or tr.fn.sym is None:
        return None
    found = ray_dot(tr, e)
    if found is None:
        return None
    r, x = found
    written = other if other is not None else f"rt.dot({args[0]}, {args[1]})"
    return f"({written} if _rq is None else rt.ray_dot({args[x]}, {args[r]}, _rq, _rk))"
