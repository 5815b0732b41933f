"""Arithmetic on lowp lookups in float16, as Mesa's lower_precision.cpp makes it on llvmpipe.

Not a rewrite of the order but of the type: Shadertoy's iChannels are lowp samplers, and Mesa's
GLSL compiler runs an operation whose operands are all lowp or mediump in float16. Copied for
trees of ``+ - * /`` over lookups and literal constants, ``pow(x, 2.0)`` among them as ``x * x``
(``fpow(a, 2.0) -> a * a``) with a constant factor sunk into it, ``(x * #k) * x``
(:func:`float16_tree`, :func:`_square`): elephant's terrain height, ``2.1 + 0.1*textureLod(..).x``,
is 2.130859375 on llvmpipe where float32 gives 2.1319335."""

from __future__ import annotations

from typing import Any, Protocol

from ....frontend import syntax as A
from ..common import TEXTURE_FUNCTIONS
from .queries import constant_value, is_builtin

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Callable

    from ..fold_protocols import FoldEngine

LOWP_OPS = ("+", "-", "*", "/")


def float16_lookup_args(tr: FoldEngine, e: A.Call) -> list[int]:
    """The arguments of lookup `e` that reach a lowp sampler rounded to float16 on llvmpipe:
    its float ones (coordinate, LOD, bias, derivatives) that Mesa folds to a constant, whose
    value float16 does not hold exactly (the others need no rounding). Measured
    (tests/gl/test_cube_maps.py, tests/channels/test_channels.py): `textureLod(s, p, 1.3)` reads
    LOD 1.2998047 (float16 to nearest), a literal, a constant expression, a `const` or a
    never-written global or local alike, on sampler2D and samplerCube; a value computed from a
    highp one is not rounded; a projective coordinate is rounded before its division. Copied
    where queries.constant_value sees the constant (not Mesa's folds of `x * 0.0` or of a
    variable written again)."""
    import numpy as np

    out = []
    for i, a in enumerate(e.args[1:], 1):
        t = tr.type_of(a)
        if t.base != "float" or t.is_matrix or t.is_array:
            continue
        values = constant_value(tr, a)
        if values is None:
            continue
        with np.errstate(over="ignore"):
            half = np.asarray(values, np.float32).astype(np.float16).astype(np.float32)
        if not np.array_equal(half, np.asarray(values, np.float32)):
            out.append(i)
    return out


def float16_tree(tr: FoldEngine, e: A.Binary) -> tuple[set[int], list[Any]] | None:
    """When llvmpipe computes ``e`` in float16 (a tree of ``+ - * /`` and negation over lookups
    on an iChannel and literal constants, at least one lookup): the ids of the tree's operation
    nodes and its lookups' sampler operands, else None. Each engine writes the tree with
    :func:`float16_code` (the NumPy backend: numpy_engine/transpile/float16.py)."""
    if e.op not in LOWP_OPS:
        return None
    memo = tr.fold_state.lowp
    if _lowp_kind(tr, e, memo) != "low" or tr.has_effects(e):
        return None
    nodes: list[Any] = []
    samplers: list[Any] = []
    _lowp_parts(e, memo, nodes, samplers)
    return {id(n) for n in nodes}, samplers


def _lowp_kind(tr: FoldEngine, node: Any, memo: dict[int, Any]) -> str | None:
    """ "const" (a literal constant), "lookup" (an iChannel lookup, swizzled or not), "low" (an
    operation float16 on llvmpipe) or None (float32) for a node of such a tree (memoised)."""
    key = id(node)
    if key not in memo:
        memo[key] = _lowp_kind_of(tr, node, memo)
    return memo[key]


def _lowp_kind_of(tr: FoldEngine, node: Any, memo: dict[int, Any]) -> str | None:
    if isinstance(node, (A.FloatLiteral, A.IntLiteral)):
        return "const"
    if isinstance(node, A.Identifier):
        return None  # (a `const` variable or a never-written global is highp: measured,
        # `const float K = 0.1; K * texture(..).x` is float32 on llvmpipe)
    kids = list(node.children())
    if tr.model.const_value(node) is not None:
        # literals only; a zero is left to the float32 forms (Mesa drops `x + 0.0` and
        # `x * 0.0`, a NaN operand too)
        if not all(_lowp_kind(tr, k, memo) == "const" for k in kids) or not all(
            constant_value(tr, node) or [0.0]
        ):
            return None
        return "const"
    t = tr.type_of(node)
    if t.base != "float" or t.is_matrix or t.is_array:
        return None
    if isinstance(node, A.Field):
        return "lookup" if _lowp_kind(tr, node.base, memo) == "lookup" else None
    if isinstance(node, A.Call) and _square(tr, node):
        return "low" if _lowp_kind(tr, node.args[0], memo) in ("low", "lookup") else None
    if isinstance(node, A.Call):
        sampler = node.args[0] if node.args else None
        sym = tr.model.symbol_of(sampler) if isinstance(sampler, A.Identifier) else None
        if (
            getattr(tr.model.call_target(node), "name", None) not in TEXTURE_FUNCTIONS
            or sym is None
            or sym.kind != "uniform"
            or str(tr.type_of(sampler)) not in ("sampler2D", "samplerCube")
        ):
            return None
        return "lookup"
    if isinstance(node, A.Unary) and node.op == "-":
        return "low" if _lowp_kind(tr, node.operand, memo) in ("low", "lookup") else None
    if isinstance(node, A.Binary) and node.op in LOWP_OPS:
        kinds = {_lowp_kind(tr, node.left, memo), _lowp_kind(tr, node.right, memo)}
        return None if None in kinds or kinds == {"const"} else "low"
    return None


def _square(tr: FoldEngine, node: A.Call) -> bool:
    """``pow(x, 2.0)`` (a vector of 2.0 too) of the built-in: x * x to NIR (``fpow(a, 2.0) ->
    a * a``), in float16 for a float16 x (gargantua's ``pow(texture(..).rgb, vec3(2.0)) * 4.0``)."""
    return (
        node.callee == "pow"
        and len(node.args) == 2
        and is_builtin(tr, node)
        and set(constant_value(tr, node.args[1]) or [0.0]) == {2.0}
    )


def _lowp_parts(node: Any, memo: dict[int, Any], nodes: list[Any], samplers: list[Any]) -> None:
    """The operation nodes of a float16 tree and the samplers its lookups read."""
    kind = memo.get(id(node))
    if kind == "low":
        nodes.append(node)
        kids = (
            (node.operand,)
            if isinstance(node, A.Unary)
            else node.args[:1]
            if isinstance(node, A.Call)
            else (node.left, node.right)
        )
        for k in kids:
            _lowp_parts(k, memo, nodes, samplers)
    elif kind == "lookup":
        while isinstance(node, A.Field):
            node = node.base
        samplers.append(node.args[0])


class Float16Emitter(Protocol):
    """How an engine writes the values of a float16 tree (:func:`float16_code`): the NumPy
    backend as expressions over float16 arrays (numpy_engine/transpile/float16.py), the
    compiled engine as float32 components rounded after each operation
    (compiled_engine/texture_calls.py)."""

    def leaf(self, node: Any) -> Any: ...  # a leaf's value rounded to float16
    def negate(self, x: Any) -> Any: ...
    def op(self, op: str, a: Any, b: Any) -> Any: ...  # one float16 operation
    # a value computed once (`build` runs inside) and read twice: (first read, second read)
    def shared(self, build: Callable[[], Any]) -> tuple[Any, Any]: ...


def float16_code(model: Any, node: Any, ops: set[int], em: Float16Emitter) -> Any:
    """The operations of a float16 tree found by :func:`_lowp_kind` (`ops`: the ids of its
    operation nodes), in llvmpipe's order, written by `em`: leaves rounded to float16, ``pow(x,
    2.0)`` as ``x * x``, ``(x*x) * #k`` with the square used once as ``(x * #k) * x`` (NIR's
    ``(a*b)*#c -> (a*#c)*b``), every other operation as written."""
    if id(node) not in ops:
        return em.leaf(node)
    if isinstance(node, A.Unary):
        return em.negate(float16_code(model, node.operand, ops, em))
    if isinstance(node, A.Call):  # pow(x, 2.0): x * x, x computed once
        return em.op("*", *em.shared(lambda: float16_code(model, node.args[0], ops, em)))
    square, k = (
        (node.left, node.right) if isinstance(node.left, A.Call) else (node.right, node.left)
    )
    if (
        node.op == "*"
        and isinstance(square, A.Call)
        and id(square) in ops
        and model.const_value(k) is not None
    ):
        x, again = em.shared(lambda: float16_code(model, square.args[0], ops, em))
        return em.op("*", em.op("*", x, float16_code(model, k, ops, em)), again)
    left = float16_code(model, node.left, ops, em)
    return em.op(node.op, left, float16_code(model, node.right, ops, em))
