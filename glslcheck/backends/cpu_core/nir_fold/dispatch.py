"""Which of nir_fold's rules rewrites a binary expression: the first one that applies gives the
code.

The NumPy transpiler tries them all (numpy_engine/transpile/binary_rules.py), in this order: the
float16 tree of lowp lookups (lower_precision.py: its type decides every operation in it); a
value whose y a later copy of an unrolled loop reads from a temporary
(loop_copies.kept_in_slot); for an expression with side effects, a constant added to a call's
result (returned_sums.py), then, where its only effects are calls of user functions that are
opaque values once inlined (queries.inlined_calls_only, inlined_results.py), the rules below as
for any value; for a matrix operand, only constants merged into the matrix (ssa_values.py); for
a sum, factoring (factoring.py) then the ffma split (ffma_split.py); then a log scaled by a
constant (exp_log.py), constants merged (loop_copies.py, constant_merge.py, components.py,
compound_products.py) or sunk (smoothstep_products.py, sink.py); last, a product by a constant
kept through a variable assigned again (ssa_values.py).

:func:`copied_binary` is the same order for an engine that computes some families only (the
compiled engine: compiled_engine/fold_values.COPIED, the families built from
fold_protocols.FoldEmitter's operations)."""

from __future__ import annotations

from ....frontend import syntax as A
from .components import merge_components
from .compound_products import sunk_through_compound
from .constant_merge import merge_constants
from .exp_log import log_scaled
from .factoring import factor
from .loop_copies import kept_in_slot, merged_copies
from .queries import inlined_calls_only
from .sink import sink_constant
from .smoothstep_products import scaled_smoothstep
from .ssa_values import keep_factor, merge_into_matrix

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from typing import Any

    from ..fold_protocols import FoldEmitter


def copied_binary(tr: FoldEmitter, e: A.Binary, mask: str | None, copied: frozenset[str]) -> Any:
    """The rules of the module doc for an engine that computes the families `copied` only:
    those, in the same order; None where none of them rewrites ``e``."""
    if e.op not in ("+", "-", "*") or tr.fn is None or tr.type_of(e).base != "float":
        return None
    kept = kept_in_slot(tr, e, mask) if "constant_merge" in copied else None
    if kept is not None:
        return kept
    if tr.has_effects(e) and not inlined_calls_only(tr, e):
        return None
    if tr.type_of(e.left).is_matrix or tr.type_of(e.right).is_matrix:
        return merge_into_matrix(tr, e, mask) if "matrix" in copied else None
    if e.op == "+" and "factoring" in copied:
        folded = factor(tr, e, mask)
        if folded is not None:
            return folded
    if "exp_log" in copied:
        folded = log_scaled(tr, e, mask)
        if folded is not None:
            return folded
    if "constant_merge" in copied:
        folded = merged_copies(tr, e, mask)
        if folded is None:
            folded = merge_constants(tr, e, mask)
        if folded is not None:
            return folded
    folded = merge_components(tr, e, mask) if "components" in copied else None
    if folded is None and "compound" in copied:
        folded = sunk_through_compound(tr, e, mask)
    if folded is not None:
        return folded
    folded = None
    if "sink" in copied:
        folded = scaled_smoothstep(tr, e, mask)
        if folded is None:
            folded = sink_constant(tr, e, mask)
    if folded is None and "ssa_values" in copied:
        folded = keep_factor(tr, e, mask)
    return folded
