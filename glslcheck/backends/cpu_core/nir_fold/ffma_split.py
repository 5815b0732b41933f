"""A sum of two products returned through a folded call: ``(p1 + p2) + e`` is ``(p1 + e) + p2``.

llvmpipe fuses ``p1 + p2`` into an ffma (nir_opt_algebraic_late, fuse_ffma32), moves e into its
addend, ``ffma(a, b, ffma(c, d, e))``, and splits each ffma again (lower_ffma32), so the sum
is reassociated where the written code kept it apart: gargantua's ``raypos = eyepos +
eyevec*dither*far/200`` after RotateCamera, measured in 576 of 576 pixels. Copied where the
sum comes out of a call folded per call site (cpu_core/call_fold.py) and is read once;
inside one written expression, ``(a*b + c*d) + e``, measured the same but not copied."""

from __future__ import annotations

from ....frontend import syntax as A
from ..call_fold import product_sums
from .queries import call_write, current_function, function_facts

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from typing import Any

    from ..fold_protocols import FoldEngine, LineWriter


def fused_plan(tr: FoldEngine, e: A.Binary) -> tuple[Any, Any, list] | None:
    """``x + e`` where x's value, written by a call folded per call site
    (cpu_core/call_fold.py), is ``p1 + p2`` in a component, two products, and this is x's
    only read: (x, e, per component of x the codes of (p1, p2) or None), else None."""
    if e.op != "+":
        return None
    for x, other in ((e.left, e.right), (e.right, e.left)):
        w = call_write(tr, x)
        if w is None:
            continue
        sums = product_sums(tr, w.node, tr.model.symbol_of(x))
        tx, to = tr.type_of(x), tr.type_of(other)
        if (
            sums is None
            or not any(sums)
            or to.base != "float"
            or to.is_matrix
            or tx.is_matrix
            or to != tx
            and not to.is_scalar
            or tr.has_effects(other)
        ):
            continue
        reads = [
            n
            for n in current_function(tr).sym.node.body.walk()
            if isinstance(n, A.Identifier)
            and tr.model.symbol_of(n) is tr.model.symbol_of(x)
            and function_facts(tr).enter.get(id(n), -1) > function_facts(tr).exit[id(w.node)]
        ]
        if reads != [x]:
            return None  # (x read again: the sum is used twice)
        return x, other, sums
    return None


def fused_after_call(tr: LineWriter, e: A.Binary, mask: str | None) -> str | None:
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
