"""An added constant zero dropped: nir_opt_algebraic's ``fadd(a, 0.0) -> a``.

IEEE addition makes ``-0.0 + 0.0`` +0.0; NIR drops the addition and keeps the -0.0 (``1.0 / x``
is then -inf). NIR applies it after inlining every
function, so the zero may come through an argument or an out parameter (found by
cpu_core/constant_flow.py); the runtime (`Runtime.fadd`) checks the value. The compiled engine
asks the same question (compiled_engine/expressions.py `zero_add`)."""

from __future__ import annotations

from ....frontend import syntax as A
from ..constant_flow import constant_flow
from .queries import SUMS

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..fold_protocols import FoldEngine


def zero_add(tr: FoldEngine, e: A.Binary) -> bool:
    """A float ``+`` / ``-`` whose operand may be a constant zero once Mesa has inlined the
    function: the engines compute it as ``Runtime.fadd`` / ``fsub`` do, else as the plain
    operator.

    Mesa 22.3's nir_opt_algebraic drops ``fadd(a, 0.0)`` (``('fadd(is_only_used_as_float)',
    'a@32', 0.0) -> a``; llvmpipe lowers ``a - b`` to ``fadd(a, fneg(b))``), which keeps the
    sign of a -0.0 that IEEE addition would make +0.0. NIR applies it after inlining every
    function, so the zero may come through an argument or an out parameter, not only a
    literal: `cpu_core.constant_flow` finds the operands that may be one, and the runtime
    (`Runtime.fadd`) checks the value they hold. Elsewhere, the common case, the operator
    stays a NumPy operator without a Python call."""
    if e.op not in SUMS or tr.fn is None:
        return False
    if any(tr.type_of(x).base != "float" for x in (e, e.left, e.right)):
        return False
    flow = constant_flow(tr)
    return flow.may_be_zero_constant(e.left) or flow.may_be_zero_constant(e.right)
