"""Which of nir_fold's rules rewrites a binary expression: the first one that applies gives the
code, tried in Mesa's order, which :data:`BINARY_RULES` states once for both engines.

The order: the float16 tree of lowp lookups (lower_precision.py: its type decides every
operation in it); a value whose y a later copy of an unrolled loop reads from a temporary
(loop_copies.kept_in_slot); for an expression with side effects, a constant added to a call's
result (returned_sums.py), then, where its only effects are calls of user functions that are
opaque values once inlined (queries.inlined_calls_only, inlined_results.py), the rules below as
for any value; for a matrix operand, only constants merged into the matrix (ssa_values.py); for
a sum or difference, a term joining the first of two products it is added to (product_sums.py:
NIR rewrites the outer addition before the inner one is factored); for a sum, factoring
(factoring.py) then the ffma split (ffma_split.py); then a vector constructor's constant
component in the constant rules (constant_components.py), a log scaled by a constant
(exp_log.py), constants merged (loop_copies.py, constant_merge.py, components.py,
compound_products.py) or sunk (smoothstep_products.py, sink.py); last, a product by a constant
kept through a variable assigned again (ssa_values.py).

:func:`rewrite_binary` walks the table for an engine: the families it computes (the NumPy
transpiler all of them, numpy_engine/transpile/binary_rules.py; the compiled engine those
built from fold_protocols.FoldEmitter's operations, compiled_engine/fold_values.COPIED), and its
own writers of the families whose code it writes itself (the table has no rule for those)."""

from __future__ import annotations

from ....frontend import syntax as A
from .components import merge_components
from .compound_products import sunk_through_compound
from .constant_components import component_constants
from .constant_merge import merge_constants
from .exp_log import log_scaled
from .factoring import factor
from .loop_copies import kept_in_slot, merged_copies
from .lower_precision import LOWP_OPS
from .product_sums import product_sum
from .queries import SUMS, inlined_calls_only
from .sink import sink_constant
from .smoothstep_products import scaled_smoothstep
from .ssa_values import keep_factor, merge_into_matrix

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Callable, Mapping
    from typing import Any

    from ..fold_protocols import FoldEmitter

    Rule = Callable[..., Any]  # (the engine, the expression, its mask) -> the code, or None

# (family, rule, where it is tried), in Mesa's order; None: a family each engine writes itself.
# where: "lowp" any operator of LOWP_OPS, before the tests below; "first" a float +, - or * of a
# function; "effects" one with side effects; "matrix" one with a matrix operand (nothing after);
# "sums" a + or -, "sum" a +, before "any": every other float +, - or *.
BINARY_RULES: tuple[tuple[str, Rule | None, str], ...] = (
    ("lower_precision", None, "lowp"),  # the float16 tree (its type decides every operation)
    ("constant_merge", kept_in_slot, "first"),  # y read from a later copy's temporary
    ("returned_sums", None, "effects"),  # a constant sunk into a call's returned sum
    ("matrix", merge_into_matrix, "matrix"),
    ("product_sums", product_sum, "sums"),
    ("factoring", factor, "sum"),
    ("ffma_split", None, "sum"),  # a sum of two products a folded call returns, a term added
    ("constant_components", component_constants, "any"),
    ("exp_log", log_scaled, "any"),
    ("constant_merge", merged_copies, "any"),
    ("constant_merge", merge_constants, "any"),
    ("components", merge_components, "any"),
    ("compound", sunk_through_compound, "any"),
    ("sink", scaled_smoothstep, "any"),
    ("sink", sink_constant, "any"),
    ("ssa_values", keep_factor, "any"),
)
FAMILIES = frozenset(family for family, _, _ in BINARY_RULES)


def rewrite_binary(
    tr: FoldEmitter,
    e: A.Binary,
    mask: str | None,
    families: frozenset[str],
    own: Mapping[str, Rule] | None = None,
) -> Any:
    """The code of the first rule of :data:`BINARY_RULES` that rewrites ``e``, among the
    `families` an engine computes (`own`: its writers of those the table has no rule for); None
    where none does."""

    def tried(where: str) -> Any:
        for family, rule, at in BINARY_RULES:
            if at == where and family in families:
                write = rule if rule is not None else (own or {}).get(family)
                folded = write(tr, e, mask) if write is not None else None
                if folded is not None:
                    return folded
        return None

    folded = tried("lowp") if e.op in LOWP_OPS else None
    if folded is not None:
        return folded
    if e.op not in ("+", "-", "*") or tr.fn is None or tr.type_of(e).base != "float":
        return None
    folded = tried("first")
    if folded is not None:
        return folded
    if tr.has_effects(e):
        folded = tried("effects")
        if folded is not None or not inlined_calls_only(tr, e):
            return folded
    if tr.type_of(e.left).is_matrix or tr.type_of(e.right).is_matrix:
        return tried("matrix")
    folded = tried("sums") if e.op in SUMS else None
    if folded is None and e.op == "+":
        folded = tried("sum")
    return folded if folded is not None else tried("any")
