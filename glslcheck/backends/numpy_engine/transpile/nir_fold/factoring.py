"""Factoring: ``('~fadd', ('fmul', a, b), ('fmul', a, c)) -> a * (b + c)``.

``a*b + c*a`` is ``a * (b + c)`` on llvmpipe, one rounding fewer. NIR sees through SSA values,
so a product stored in a local that is never written again counts too (``vec2 uv = 50.0 * f;
... uv.x + uv.y`` is ``50.0 * (f.x + f.y)``). Copied where b + c is not rewritten further (each
opaque or constant, not both constant): :func:`factor`, :func:`factor_parts`."""

from __future__ import annotations

from typing import Any

from .....frontend import syntax as A
from .....frontend.printer import to_glsl
from .queries import is_constant, is_opaque, is_product, stable_init

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..state import FoldEmitter, FoldEngine


def factor(tr: FoldEmitter, e: A.Binary, mask: str | None) -> Any:
    """``a*b + a*c`` (either operand order, products possibly stored in never-written locals)
    as ``a * (b + c)``."""
    parts = factor_parts(tr, e)
    if parts is None:
        return None
    shared, b, c = parts
    t = tr.type_of(e)
    ts, tb, tc = (_code(tr, x, mask) for x in (shared, b, c))
    tl, trr = tr.exprs([e.left, e.right], mask)
    rewritten = tr.binary_values("*", t, t, ts, tr.ieee("+", tb, tc))  # float, no matrix: fmul
    return tr.llvmpipe(rewritten, tr.ieee("+", tl, trr))


def factor_parts(tr: FoldEngine, e: Any) -> tuple[Any, Any, Any] | None:
    """(a, b, c) when the sum ``e`` is ``a*b + a*c`` as :func:`factor` rewrites it, else None."""
    if not (isinstance(e, A.Binary) and e.op == "+"):
        return None
    left, right = _factors(tr, e.left), _factors(tr, e.right)
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
    rest = [x[0] if isinstance(x, tuple) else x for x in (b, c)]
    if not all(is_opaque(tr, x) or is_constant(tr, x) for x in rest) or all(
        is_constant(tr, x) for x in rest
    ):
        return None  # b + c would be rewritten further (or folded): not copied
    return shared, b, c


def _factors(tr: FoldEngine, node: Any) -> tuple[tuple[str, str], tuple[Any, Any]] | None:
    """The two factors of a product ``node`` (their GLSL texts, and nodes or (node, component)
    pairs), looking through a never-written local defined as a product; None otherwise."""
    if is_product(tr, node):
        if tr.type_of(node.left) != tr.type_of(node.right) and not (
            tr.type_of(node.left).is_scalar or tr.type_of(node.right).is_scalar
        ):
            return None
        return (to_glsl(node.left), to_glsl(node.right)), (node.left, node.right)
    comp = None
    if isinstance(node, A.Field) and isinstance(node.base, A.Identifier) and len(node.name) == 1:
        comp = "xyzwrgbastpq".index(node.name) % 4 if node.name in "xyzwrgbastpq" else None
        if comp is None:
            return None
        node = node.base
    if not isinstance(node, A.Identifier):
        return None
    init = stable_init(tr, node)
    if init is None or not is_product(tr, init):
        return None
    parts = []
    for f in (init.left, init.right):
        ft = tr.type_of(f)
        if comp is not None and not ft.is_scalar:
            parts.append(((f, comp), f"({to_glsl(f)})[{comp}]"))
        elif comp is None and not ft == tr.type_of(init) and not ft.is_scalar:
            return None
        else:
            parts.append((f, to_glsl(f)))
    return (parts[0][1], parts[1][1]), (parts[0][0], parts[1][0])


def _code(tr: FoldEmitter, x: Any, mask: str | None) -> Any:
    if isinstance(x, tuple):
        node, comp = x
        return tr.component(tr.expr(node, mask), comp)
    return tr.expr(x, mask)
