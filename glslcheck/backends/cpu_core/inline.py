"""Calls inlined as Mesa inlines them, where one of Mesa's rewrites then reaches through an
argument into the caller's expression.

Mesa compiles a program by inlining every function (GLSL IR's do_function_inlining, then NIR)
before its algebraic passes run, so a rewrite that merges constants sees an argument's
expression inside the callee's body. The real shader that shows it (a star field's hash):

    float random(in vec2 v) { return fract(15465.1327854 * sin(dot(v, vec2(173.93422, 102.5165))));
    }
    ... vec2 uv = (2.0 * fragCoord - res) / min(res.x, res.y) * 1.2;  ... random(uv * 0.2) ...

llvmpipe computes ``dot(q, (K * 0.2) * 1.2)`` with q the division, the constants merged in
float32 (nir_fold.merged_dot); the written order differs in the last bits of the sine's
argument, and a hash amplifies them (a star where llvmpipe has none). The NumPy backend writes a
function once for every call, so its body cannot see ``uv * 0.2``. Here such a call is
inlined: the callee's return expression is generated at the call site, each parameter read as
its argument's value, and nir_fold's look-through (`nir_fold.queries.stable_init`) sees the
argument.

Only where it pays: the callee is a single ``return <expression>;`` with ``in`` parameters it
never writes, no calls of user functions and no ``mix`` (whose lowering depends on the other
``mix`` calls of the function), the arguments have no side effects, and some argument is a
product by a constant (through never-written locals) that the callee passes to a ``dot`` with
a constant. The same values are computed either way; only the float32 rewrites differ, so the
float64 reference is unchanged. Other calls stay Python calls.
"""

from __future__ import annotations

from typing import Any

from ...frontend import syntax as A
from ...language import builtin_functions as B
from ...semantics.model import Symbol

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from .fold_protocols import FoldEmitter, FoldEngine


def bound_argument(tr: FoldEngine, sym: Symbol) -> Any:
    """The argument node of an inlined call a parameter symbol stands for, else None."""
    for frame in reversed(tr.fold_state.inline_frames):
        if id(sym) in frame["params"]:
            return frame["params"][id(sym)][1]
    return None


def bound_code(tr: FoldEngine, sym: Symbol) -> Any:
    """The value (the engine's: FoldEmitter) of the argument an inlined parameter reads, else
    None."""
    for frame in reversed(tr.fold_state.inline_frames):
        if id(sym) in frame["params"]:
            return frame["params"][id(sym)][0]
    return None


def inline_owner(tr: FoldEngine, sym: Symbol | None) -> Any:
    """The inlined function a parameter symbol belongs to, else None."""
    for frame in reversed(tr.fold_state.inline_frames):
        if id(sym) in frame["params"]:
            return frame["fn"]
    return None


def _body_expression(tr: FoldEngine, fn: Symbol) -> Any:
    """The expression of `fn`'s body when it may be inlined (see the module doc), else None."""
    memo = tr.fold_state.inline_bodies
    if id(fn) in memo:
        return memo[id(fn)]
    value = None
    stmts = fn.node.body.stmts
    if (
        len(stmts) == 1
        and isinstance(stmts[0], A.Return)
        and stmts[0].value is not None
        and all(d == "in" for _, _, d in fn.params)
    ):
        value = stmts[0].value
        for n in value.walk():
            if isinstance(n, A.Call) and (
                isinstance(tr.model.call_target(n), Symbol) or n.callee == "mix"
            ):
                value = None
                break
            if isinstance(n, (A.Assignment, A.Unary, A.Postfix)) and (
                isinstance(n, A.Assignment) or n.op in ("++", "--")
            ):
                value = None  # (a parameter written: not a plain read of the argument)
                break
        if value is not None and any(tr.model.symbol_of(p) is None for p in fn.node.proto.params):
            value = None  # (an unnamed parameter)
    memo[id(fn)] = value
    return value


def worth_inlining(tr: FoldEngine, call: A.Call, fn: Symbol, constant_product: Any) -> bool:
    """Some argument is a product by a constant or a ``vecN(s)`` (`constant_product(tr, node)`:
    nir_fold.dot_operand, passed in so this module does not import nir_fold, which imports it)
    that the callee hands to a ``dot`` with a constant (nir_fold.merged_dot then merges the
    constants, nir_fold.broadcast_dot factors s out), and inlining is allowed."""
    if tr.fn is None or tr.fold_state.inline_frames or any(tr.has_effects(a) for a in call.args):
        return False  # (one level: a call inside an inlined body stays a call)
    value = _body_expression(tr, fn)
    if value is None:
        return False
    products = set()
    for p, arg in zip(fn.node.proto.params, call.args):
        if constant_product(tr, arg):
            products.add(id(tr.model.symbol_of(p)))
    if not products:
        return False
    for n in value.walk():
        if (
            isinstance(n, A.Call)
            and n.callee == "dot"
            and len(n.args) == 2
            and isinstance(tr.model.call_target(n), B.Overload)
        ):
            for a, b in ((n.args[0], n.args[1]), (n.args[1], n.args[0])):
                if isinstance(a, A.Field) and tr.model.is_swizzle(a):
                    a = a.base  # (`co.xy` of a vec2(s) is vec2(s): nir_fold.broadcast_dot)
                if (
                    isinstance(a, A.Identifier)
                    and id(tr.model.symbol_of(a)) in products
                    and tr.model.const_value(b) is not None
                ):
                    return True
    return False


def inline_call(tr: FoldEmitter, call: A.Call, fn: Symbol, mask: str | None) -> Any:
    """The callee's return expression at the call site, its parameters read as the arguments'
    values (each argument evaluated once, left to right, before the body as a call does)."""
    from .facts import is_plain_read

    params: dict[int, tuple[Any, Any]] = {}
    for p, arg in zip(fn.node.proto.params, call.args):
        code = tr.expr(arg, mask)
        if not is_plain_read(arg):
            code = tr.tmp(code)
        params[id(tr.model.symbol_of(p))] = (code, arg)
    frames = tr.fold_state.inline_frames
    frames.append({"fn": fn, "params": params})
    value = _body_expression(tr, fn)
    # the tracing transpiler (backends/numpy_engine/tracing.py, glslcheck probe) records a
    # function's return value: inlined, the expression is part of the caller's statement, not a
    # return
    watched = getattr(tr, "watched", None)  # (the Transpiler's; the compiled engine traces none)
    watch = watched.pop(id(value), None) if watched is not None else None
    try:
        return tr.expr(value, mask)
    finally:
        frames.pop()
        if watch is not None and watched is not None:  # (a watch came from tr.watched)
            watched[id(value)] = watch
