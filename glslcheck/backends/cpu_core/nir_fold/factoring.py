"""Factoring: ``('~fadd', ('fmul', a, b), ('fmul', a, c)) -> a * (b + c)``.

``a*b + c*a`` is ``a * (b + c)`` on llvmpipe, one rounding fewer. NIR sees through SSA values,
so a product stored in a local that is never written again counts too (``vec2 uv = 50.0 * f;
... uv.x + uv.y`` is ``50.0 * (f.x + f.y)``), and so does a variable assigned again whose value
ssa_values.keep_factor kept (``p = 17.0*fract(q); ... p.x + p.y``, iq's hash). The factored sum
is a product itself, so a third term factors again: ``(a*b + a*c) + a*d`` is ``a * ((b + c) +
d)`` (measured: ``p.x + p.y + p.z`` of that hash). Copied where the new sum is not rewritten
further (each term opaque or constant, not all constant; three terms at most, none constant:
GLSL IR rebalances a longer chain first): :func:`factor`, :func:`factor_parts`."""

from __future__ import annotations

from typing import Any

from ....frontend import syntax as A
from ....frontend.printer import to_glsl
from .queries import is_constant, is_opaque, is_product, stable_init
from .ssa_values import product_parts

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..fold_protocols import FoldEmitter, FoldEngine


class _Kept:
    """A factor whose value ssa_values.keep_factor kept in a temporary (`code`): y of ``x = y *
    #c``, or its component `comp`; `node` is y's expression."""

    def __init__(self, code: Any, node: Any, comp: int | None) -> None:
        self.code, self.node, self.comp = code, node, comp


class _Sum:
    """The factor ``b + c`` of a sum NIR factored first (``a*b + a*c`` is ``a * (b + c)``)."""

    def __init__(self, left: Any, right: Any) -> None:
        self.left, self.right = left, right


def factor(tr: FoldEmitter, e: A.Binary, mask: str | None) -> Any:
    """``a*b + a*c`` (either operand order, products possibly stored in never-written locals,
    or a sum factored first) as ``a * (b + c)``."""
    parts = factor_parts(tr, e)
    if parts is None:
        return None
    shared, b, c = parts
    t = tr.type_of(e)
    ts, tb, tc = (_code(tr, x, mask) for x in (shared, b, c))
    tl, trr = tr.exprs([e.left, e.right], mask)
    rewritten = tr.binary_values("*", t, t, ts, tr.ieee("+", tb, tc))  # float, no matrix: fmul
    return tr.llvmpipe(rewritten, tr.ieee("+", tl, trr))


def factor_parts(tr: FoldEngine, e: Any, nested: bool = True) -> tuple[Any, Any, Any] | None:
    """(a, b, c) when the sum ``e`` is ``a*b + a*c`` as :func:`factor` rewrites it, else None
    (`nested`: a term may itself be such a sum of two opaque terms)."""
    if not (isinstance(e, A.Binary) and e.op == "+"):
        return None
    left, right = _factors(tr, e.left, nested), _factors(tr, e.right, nested)
    if left is None or right is None or sorted(left[0]) == sorted(right[0]):
        return None  # (x*y + x*y is CSE'd to p + p first)
    for i in (0, 1):
        for j in (0, 1):
            if left[0][i] == right[0][j]:
                shared, b, c = left[1][i], left[1][1 - i], right[1][1 - j]
                break
        else:
            continue
        break
    else:
        return None
    if isinstance(b, _Sum) or isinstance(c, _Sum):
        other = c if isinstance(b, _Sum) else b
        if isinstance(other, _Sum) or not _opaque_term(tr, other):
            return None  # (four terms, or a constant the new sum would take: not copied)
        return shared, b, c
    rest = [_node(x) for x in (b, c)]
    if not all(is_opaque(tr, x) or is_constant(tr, x) for x in rest) or all(
        is_constant(tr, x) for x in rest
    ):
        return None  # b + c would be rewritten further (or folded): not copied
    return shared, b, c


def _node(x: Any) -> Any:
    """The expression of a factor (a node, a (node, component) pair or a kept value)."""
    if isinstance(x, _Kept):
        return x.node
    return x[0] if isinstance(x, tuple) else x


def _opaque_term(tr: FoldEngine, x: Any) -> bool:
    return not isinstance(x, _Sum) and is_opaque(tr, _node(x)) and not is_constant(tr, _node(x))


def _factors(
    tr: FoldEngine, node: Any, nested: bool = False
) -> tuple[tuple[str, str], tuple[Any, Any]] | None:
    """The two factors of a product ``node`` (their GLSL texts, and nodes, (node, component)
    pairs or kept values), looking through a never-written local defined as a product, a
    variable whose product value was kept, and (`nested`) a sum that factors into a product;
    None otherwise."""
    if is_product(tr, node):
        if tr.type_of(node.left) != tr.type_of(node.right) and not (
            tr.type_of(node.left).is_scalar or tr.type_of(node.right).is_scalar
        ):
            return None
        return (to_glsl(node.left), to_glsl(node.right)), (node.left, node.right)
    if nested and isinstance(node, A.Binary) and node.op == "+":
        parts = factor_parts(tr, node, nested=False)
        if parts is None or not all(_opaque_term(tr, x) for x in parts[1:]):
            return None
        return (_text(parts[0]), f"<sum {id(node)}>"), (parts[0], _Sum(parts[1], parts[2]))
    comp = None
    if isinstance(node, A.Field) and isinstance(node.base, A.Identifier) and len(node.name) == 1:
        comp = "xyzwrgbastpq".index(node.name) % 4 if node.name in "xyzwrgbastpq" else None
        if comp is None:
            return None
        node = node.base
    if not isinstance(node, A.Identifier):
        return None
    init, kept = stable_init(tr, node), None
    if init is None:
        value = product_parts(tr, node)  # (y, #c, y's temporary) of a value kept for this read
        if value is None or value[2] is None:
            return None
        kept, factors = value, (value[0], value[1])
    elif not is_product(tr, init):
        return None
    else:
        factors = (init.left, init.right)
    whole = tr.type_of(node)
    items: list[tuple[Any, str]] = []
    for f in factors:
        ft = tr.type_of(f)
        if comp is not None and not ft.is_scalar:
            item: Any = (f, comp)
        elif comp is None and not ft == whole and not ft.is_scalar:
            return None
        else:
            item = f
        if kept is not None and f is kept[0]:
            item = _Kept(kept[2], f, comp if not ft.is_scalar else None)
        items.append((item, _text(item)))
    return (items[0][1], items[1][1]), (items[0][0], items[1][0])


def _text(x: Any) -> str:
    """The GLSL text a factor is matched by (a kept value by its temporary)."""
    if isinstance(x, _Kept):
        return f"<kept {x.code}>" + ("" if x.comp is None else f"[{x.comp}]")
    if isinstance(x, tuple):
        return f"({to_glsl(x[0])})[{x[1]}]"
    return to_glsl(x)


def _code(tr: FoldEmitter, x: Any, mask: str | None) -> Any:
    if isinstance(x, _Sum):
        return tr.ieee("+", _code(tr, x.left, mask), _code(tr, x.right, mask))
    if isinstance(x, _Kept):
        return x.code if x.comp is None else tr.component(x.code, x.comp)
    if isinstance(x, tuple):
        node, comp = x
        return tr.component(tr.expr(node, mask), comp)
    return tr.expr(x, mask)
