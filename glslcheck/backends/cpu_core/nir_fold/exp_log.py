"""``exp`` and ``log`` as the products Mesa lowers them to: ``exp(x)`` is ``exp2(x * log2(e))``
and ``log(x)`` is ``log2(x) * ln(2)`` (glsl_to_nir, the constants rounded to float32), so
nir_opt_algebraic's product rules reach into them:

- ``exp(x * #k)`` is ``exp2(x * (k * log2(e)))``, the two constants folded in float32
  (``('~fmul', '#a', ('fmul', 'b(is_not_const)', '#c'))``: a smooth minimum's ``exp(-k*a)``);
- ``exp(a * b)``, the product used once, is ``exp2((a * log2(e)) * b)``
  (``('~fmul(is_used_once)', ('fmul(is_used_once)', a, b), '#c') -> (a*c) * b``);
- ``log(x) * #k`` is ``log2(x) * (ln(2) * k)``.

Measured bit for bit on llvmpipe (tests/gl/test_llvmpipe_lowering.py): the written order differs
on 2790, 1956 and 3960 of 14,400 pixels. Both engines take these decisions from here
(:func:`exp_product` from their calls of ``exp``, :func:`log_scaled` from dispatch.py)."""

from __future__ import annotations

from typing import Any

from ....frontend import syntax as A
from ....language.glsl_types import FLOAT
from .queries import is_builtin, is_constant, is_product, used_once
from .ssa_values import product_parts

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..fold_protocols import FoldEmitter

LOG2E = 1.4426950408889634  # M_LOG2E: exp(x) = exp2(x * M_LOG2E)
LN2 = 0.6931471805599453  # 1 / M_LOG2E: log(x) = log2(x) * (1 / M_LOG2E)


def exp_product(tr: FoldEmitter, call: A.Call, args: list[Any], mask: str | None) -> Any:
    """``exp`` of a product (its argument's codes: `args`) in Mesa's order, else None."""
    if len(call.args) != 1 or tr.fn is None or tr.type_of(call).base != "float":
        return None
    arg = call.args[0]
    if not isinstance(arg, A.Binary) or not is_product(tr, arg) or tr.has_effects(arg):
        return None
    a, b = arg.left, arg.right
    t, ta, tb = tr.type_of(arg), tr.type_of(a), tr.type_of(b)
    if any(x != t and not x.is_scalar for x in (ta, tb)):
        return None
    ka, kb = is_constant(tr, a), is_constant(tr, b)
    if any(_scaled(tr, x) for x, k in ((a, ka), (b, kb)) if not k):
        return None  # (more constants NIR would merge first: not copied)
    code_a, code_b = tr.exprs([a, b], mask)
    l2e = tr.const_float(LOG2E)
    if ka != kb:  # x * (k * log2(e)), the constants folded
        (x, tx), (k, tk) = ((code_b, tb), (code_a, ta)) if ka else ((code_a, ta), (code_b, tb))
        rewritten = tr.binary_values("*", tx, tk, x, tr.binary_values("*", tk, FLOAT, k, l2e))
    elif not ka and used_once(tr, arg):  # (a * log2(e)) * b
        rewritten = tr.binary_values(
            "*", ta, tb, tr.binary_values("*", ta, FLOAT, code_a, l2e), code_b
        )
    else:
        return None
    return tr.llvmpipe(tr.runtime("exp2", rewritten), tr.runtime("exp", args[0]))


def _scaled(tr: FoldEmitter, x: Any) -> bool:
    """x is itself a product or quotient by a constant, or a variable holding one (a negation
    is looked through: NIR moves it out of the products, which changes no bits)."""
    if isinstance(x, A.Unary):
        return x.op != "-" or _scaled(tr, x.operand)
    if isinstance(x, A.Binary) and x.op in ("*", "/"):
        return is_constant(tr, x.left) or is_constant(tr, x.right)
    return isinstance(x, A.Identifier) and product_parts(tr, x) is not None


def log_scaled(tr: FoldEmitter, e: A.Binary, mask: str | None) -> Any:
    """``log(x) * #k`` (either order) as ``log2(x) * (ln(2) * k)``, else None."""
    if e.op != "*":
        return None
    for call, k in ((e.left, e.right), (e.right, e.left)):
        if (
            isinstance(call, A.Call)
            and call.callee == "log"
            and is_builtin(tr, call)
            and is_constant(tr, k)
            and not is_constant(tr, call)
            and not tr.has_effects(call.args[0])
        ):
            break
    else:
        return None
    tc, tk = tr.type_of(call), tr.type_of(k)
    if tc != tr.type_of(e) or tk != tc and not tk.is_scalar:
        return None
    code_l, code_r = tr.exprs([e.left, e.right], mask)
    x = tr.expr(call.args[0], mask)
    code_k = code_r if k is e.right else code_l
    merged = tr.binary_values("*", FLOAT, tk, tr.const_float(LN2), code_k)
    rewritten = tr.binary_values("*", tc, tk, tr.runtime("log2", x), merged)
    return tr.llvmpipe(
        rewritten, tr.binary_values("*", tr.type_of(e.left), tr.type_of(e.right), code_l, code_r)
    )
