"""The NumPy transpiler's reading of nir_fold's table of binary rewrites
(cpu_core/nir_fold/dispatch.py: Mesa's order, shared with the compiled engine): every family,
with the rewrites the transpiler writes itself: the float16 tree of lowp lookups (float16.py),
a constant sunk into a call's returned sum (returned_sums.py) and a sum of two products returned
through a folded call with a term added (:func:`fused_after_call`)."""

from __future__ import annotations

from ....frontend import syntax as A
from ...cpu_core.nir_fold.dispatch import FAMILIES, rewrite_binary
from ...cpu_core.nir_fold.ffma_split import fused_plan
from .float16 import lowp_tree
from .returned_sums import sink_into_call

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from .state import TranspilerState


def binary(tr: TranspilerState, e: A.Binary, mask: str | None) -> str | None:
    """The generated code of ``e`` when one of the rules rewrites it, else None."""
    return rewrite_binary(tr, e, mask, FAMILIES, OWN)


def fused_after_call(tr: TranspilerState, e: A.Binary, mask: str | None) -> str | None:
    """``(p1 + e) + p2`` for ``x + e`` of a :func:`fused_plan`, else None: nir_opt_algebraic's
    reassociation of add chains (nir_fold/product_sums.py) where a folded call left ``p1 + p2``
    in x (measured: gargantua's ``raypos = eyepos + eyevec*dither*far/200`` after
    RotateCamera, 576 of 576 pixels; ``(a*e + b*h) + d`` is ``(a*e + d) + b*h`` in every
    pixel, while ``(a*e + b) + d`` keeps its order). A sum written in one expression is
    product_sums.py's, from the shared table."""
    plan = fused_plan(tr, e)
    if plan is None:
        return None
    x, other, sums = plan
    tx, to = tr.type_of(x), tr.type_of(other)
    tl, trr = tr.exprs([e.left, e.right], mask)
    if other is e.right:
        trr = to_code = tr.tmp(trr)
    else:
        tl = to_code = tr.tmp(tl)
    tx_code = tl if x is e.left else trr
    parts = []
    for i, s in enumerate(sums):
        oi = f"{to_code}[{i}]" if to.is_vector else to_code
        xi = f"{tx_code}[{i}]" if tx.is_vector else tx_code
        parts.append(f"(({s[0]} + {oi}) + {s[1]})" if s is not None else f"({xi} + {oi})")
    rewritten = parts[0] if tx.is_scalar else f"rt.vec({tx.size}, {', '.join(parts)})"
    return (
        f"({rewritten} if rt.lp else "
        f"{tr.binary_values('+', tr.type_of(e.left), tr.type_of(e.right), tl, trr)})"
    )


# the families of dispatch.BINARY_RULES whose code this transpiler writes itself
OWN = {
    "lower_precision": lowp_tree,
    "returned_sums": sink_into_call,
    "ffma_split": fused_after_call,
}
