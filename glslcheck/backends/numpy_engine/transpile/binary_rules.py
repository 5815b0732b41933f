"""Which of nir_fold's rules rewrites a binary expression in the NumPy transpiler's code, tried in
Mesa's order (cpu_core/nir_fold/dispatch.py states it; `copied_binary` there is the same order
for the families both engines compute), with the rewrites the transpiler writes itself: the
float16 tree of lowp lookups (float16.py), a constant sunk into a call's returned sum
(returned_sums.py) and a sum returned through a folded call split as llvmpipe's ffma
(:func:`fused_after_call`)."""

from __future__ import annotations

from ....frontend import syntax as A
from ...cpu_core.nir_fold.components import merge_components
from ...cpu_core.nir_fold.compound_products import sunk_through_compound
from ...cpu_core.nir_fold.constant_merge import merge_constants
from ...cpu_core.nir_fold.exp_log import log_scaled
from ...cpu_core.nir_fold.factoring import factor
from ...cpu_core.nir_fold.ffma_split import fused_plan
from ...cpu_core.nir_fold.loop_copies import kept_in_slot, merged_copies
from ...cpu_core.nir_fold.lower_precision import LOWP_OPS
from ...cpu_core.nir_fold.queries import inlined_calls_only
from ...cpu_core.nir_fold.sink import sink_constant
from ...cpu_core.nir_fold.smoothstep_products import scaled_smoothstep
from ...cpu_core.nir_fold.ssa_values import keep_factor, merge_into_matrix
from .float16 import lowp_tree
from .returned_sums import sink_into_call

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from .state import TranspilerState


def binary(tr: TranspilerState, e: A.Binary, mask: str | None) -> str | None:
    """The generated code of ``e`` when one of the package's rules rewrites it, else None."""
    low = lowp_tree(tr, e, mask) if e.op in LOWP_OPS else None
    if low is not None:
        return low
    if e.op not in ("+", "-", "*") or tr.fn is None:
        return None
    if tr.type_of(e).base != "float":
        return None
    kept = kept_in_slot(tr, e, mask)  # (a later copy of a loop reads y from a temporary)
    if kept is not None:
        return kept
    if tr.has_effects(e):
        folded = sink_into_call(tr, e, mask)
        if folded is not None or not inlined_calls_only(tr, e):
            return folded
    if tr.type_of(e.left).is_matrix or tr.type_of(e.right).is_matrix:
        return merge_into_matrix(tr, e, mask)
    if e.op == "+":
        folded = factor(tr, e, mask)
        if folded is None:
            folded = fused_after_call(tr, e, mask)
        if folded is not None:
            return folded
    folded = log_scaled(tr, e, mask)
    if folded is None:
        folded = merged_copies(tr, e, mask)
    if folded is None:
        folded = merge_constants(tr, e, mask)
    if folded is not None:
        return folded
    folded = merge_components(tr, e, mask)
    if folded is None:
        folded = sunk_through_compound(tr, e, mask)
    if folded is not None:
        return folded
    folded = scaled_smoothstep(tr, e, mask)
    if folded is None:
        folded = sink_constant(tr, e, mask)
    return folded if folded is not None else keep_factor(tr, e, mask)


def fused_after_call(tr: TranspilerState, e: A.Binary, mask: str | None) -> str | None:
    """``(p1 + e) + p2`` for ``x + e`` of a :func:`fused_plan`, else None. llvmpipe fuses
    ``p1 + p2`` into ``ffma(p2's factors, p1)`` (nir_opt_algebraic_late, fuse_ffma32),
    ``ffma(a, b, fmul(c, d)) + e`` becomes ``ffma(a, b, ffma(c, d, e))``, and lower_ffma32
    splits each ffma into a product and a sum (measured: gargantua's ``raypos = eyepos +
    eyevec*dither*far/200`` after RotateCamera, 576 of 576 pixels; ``(a*e + b*h) + d`` is
    ``(a*e + d) + b*h`` in every pixel, while ``(a*e + b) + d`` keeps its order). In the
    written code, inside one expression, not copied here."""
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
