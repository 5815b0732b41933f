"""A constant sunk into a smoothstep: ``#k * smoothstep(e0, e1, x)`` is ``(t*k) * (t*(3 - 2t))``.

Mesa lowers smoothstep to ``t * (t * (3 - 2t))``, t = ``clamp((x - e0) / (e1 - e0), 0, 1)``: a
product, which nir_opt_algebraic's ``(a * b) * #c -> (a * #c) * b`` (sink.py) rewrites where
that product is used once, a = t (an fsat: opaque to every other rule). Used more than once
(the same call written twice, which CSE merges, or a local read twice) it stays whole.
Measured: tests/gl/test_llvmpipe_lowering.py."""

from __future__ import annotations

from typing import Any

from ....frontend import syntax as A
from .queries import (
    constant_value,
    current_function,
    is_builtin,
    is_constant,
    read_once,
    stable_init,
    use_counts,
    used_once,
    written_symbols,
)

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..fold_protocols import FoldEmitter, FoldEngine


def scaled_smoothstep(tr: FoldEmitter, e: A.Binary, mask: str | None) -> Any:
    """The code of ``e`` = ``#k * smoothstep(..)`` (either order) in Mesa's order, else None."""
    if e.op != "*":
        return None
    for call, k in ((e.right, e.left), (e.left, e.right)):
        if not is_constant(tr, k) or is_constant(tr, call) or not _smoothstep_value(tr, call):
            continue
        if not _product_used_once(tr, e):
            return None
        found = _smoothstep_once(tr, call)
        if found is None:
            continue
        if 0 in (constant_value(tr, k) or [0]):
            return None  # (x * 0.0 is folded to 0 first: Runtime.fmul)
        t, tk = tr.type_of(e), tr.type_of(k)
        if tr.type_of(call) != t or not (tk == t or tk.is_scalar):
            return None  # (a vector constant times a scalar smoothstep: not measured)
        e0, e1, x, kk, whole = tr.exprs([*found.args, k, call], mask)
        pair = (kk, whole) if k is e.left else (whole, kk)
        written = tr.binary_values("*", tr.type_of(e.left), tr.type_of(e.right), *pair)
        return tr.llvmpipe(tr.runtime("smoothstep_scaled", e0, e1, x, kk), written)
    return None


def _smoothstep_value(tr: FoldEngine, node: Any) -> bool:
    """``node`` is a smoothstep call or a local it initialises (the cheap test, made first)."""
    if isinstance(node, A.Identifier):
        sym = tr.model.symbol_of(node)
        node = sym.node.init if sym is not None and isinstance(sym.node, A.Declarator) else None
    return isinstance(node, A.Call) and node.callee == "smoothstep"


def _smoothstep_once(tr: FoldEngine, node: Any) -> A.Call | None:
    """The built-in smoothstep call whose value ``node`` is, where NIR sees its product used
    once here: the call as an operand, or a never-written local it initialises read only here,
    and no other call with the same arguments in the function (CSE would merge them)."""
    call = node
    if isinstance(node, A.Identifier):
        call = stable_init(tr, node) if read_once(tr, node) else None
    elif id(node) not in use_counts(tr)[2]:
        return None  # (not an operand: a local's initializer feeds every read of it)
    if not (isinstance(call, A.Call) and call.callee == "smoothstep" and is_builtin(tr, call)):
        return None
    if tr.has_effects(call):
        return None
    shapes = use_counts(tr)[0]
    shape = shapes.get(id(call))
    body = current_function(tr).sym.node.body
    copies = sum(1 for n in body.walk() if isinstance(n, A.Call) and shapes.get(id(n)) == shape)
    return call if copies == 1 else None


def _product_used_once(tr: FoldEngine, e: A.Binary) -> bool:
    """The product ``e`` feeds one instruction: an operand used once, or the initializer of a
    never-written local read at one place (measured: ``float r = 24.0 * smoothstep(..)`` read
    twice keeps the written order on llvmpipe, read once it does not)."""
    if used_once(tr, e):
        return True
    body = current_function(tr).sym.node.body
    for n in body.walk():
        if isinstance(n, A.Declarator) and n.init is e:
            sym = tr.model.symbol_of(n)
            if sym is None or id(sym) in written_symbols(tr):
                return False
            idents = (x for x in body.walk() if isinstance(x, A.Identifier))
            read = next((x for x in idents if tr.model.symbol_of(x) is sym), None)
            return read is not None and read_once(tr, read)
    return False
