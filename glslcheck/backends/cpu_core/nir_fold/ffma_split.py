"""A sum of two products returned through a folded call: ``(p1 + p2) + e`` is ``(p1 + e) + p2``.

The reassociation of product_sums.py (nir_opt_algebraic's add chains: the bits are those of
``(p1 + e) + p2`` rounded step by step, no fused multiply-add) where the sum comes out of a call
folded per call site (cpu_core/call_fold.py) and is read once: gargantua's ``raypos = eyepos +
eyevec*dither*far/200`` after RotateCamera, measured in 576 of 576 pixels. A sum written in the
shader, ``(a*b + c*d) + e``, is product_sums.py's."""

from __future__ import annotations

from ....frontend import syntax as A
from ..call_fold import product_sums
from .queries import call_write, current_function, function_facts

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from typing import Any

    from ..fold_protocols import FoldEngine


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
