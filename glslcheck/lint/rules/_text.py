"""Text helpers the lint rules share for messages and suggested rewrites (not a rule: no NAME,
not in the table). The analysis they report on lives in glslcheck/analysis."""

from __future__ import annotations

from ...frontend import syntax as A
from ...frontend.printer import to_glsl
from ...semantics.analysis import builtin_call, numbers, program_facts
from ...semantics.model import Model

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator
    from typing import Any

    from ...semantics.analysis import FunctionFacts

COMPARISONS = ("<", "<=", ">", ">=")
FLIPPED = {"<": ">", "<=": ">=", ">": "<", ">=": "<="}  # a op b  <=>  b FLIPPED[op] a


def negative_reason(fn: FunctionFacts, e: A.Expr) -> str | None:
    """Why `e` can be negative (`FunctionFacts.negative_witness`) as the rules say it: the reason,
    followed by `: <source> (line N)` when its source lies outside `e`; None: it cannot."""
    why = fn.negative_witness(e)
    if why is None:
        return None
    reason, source = why
    return (
        reason if fn.contains(e, source) else f"{reason}: {text(source)} (line {source.loc.line})"
    )


def _compared(fn, e) -> tuple[Any, str] | None:
    """(the other side, the operator read with `e` on the left) when `e` is a side of a
    comparison or an argument of step(), the comparison it makes (`step(edge, x)` is
    `x >= edge`); else None."""
    up = fn.parent.get(id(e))
    if type(up) is A.Binary and up.op in COMPARISONS:
        return (up.right, up.op) if up.left is e else (up.left, FLIPPED[up.op])
    if type(up) is A.Call and len(up.args) == 2 and builtin_call(fn.model, up, "step"):
        return (up.args[0], ">=") if up.args[1] is e else (up.args[1], "<=")
    return None


def compared_values(
    model: Model, path: str, *names: str
) -> Iterator[tuple[A.Call, A.Expr, str, str]]:
    """Every call of one of the built-in functions `names` computed only to be compared, in the
    file `path`: a side of a comparison or of a step(), directly (`length(v) < r`, `step(r,
    length(v))`), through a local that holds it and is written nowhere else, every read of which
    is such a side (`float d = length(v); ... step(r, d)`), or returned by a user function every
    call of which is only compared so (`float mag(vec3 c) { return sqrt(...); } ... if (mag(c)
    > x)`). (The call, the other side of its first comparison, the operator read with the
    call on the left, how: "" directly, "local", or the name of the function returning it.)"""
    for fn in program_facts(model).in_file(path):
        for node in fn.nodes:
            if type(node) is A.Call and builtin_call(model, node, *names):
                found = _only_compared(fn, node, True)
                if found is not None:
                    yield (node, *found)


def _only_compared(fn, e, through_calls: bool) -> tuple[Any, str, str] | None:
    """(the other side of the first comparison, the operator, how) when the value of `e` is only
    ever compared (see compared_values); None otherwise. `through_calls`: a returned value may
    be compared by the function's callers."""
    direct = _compared(fn, e)
    if direct is not None:
        return (*direct, "")
    up = fn.parent.get(id(e))
    if type(up) is A.Return and through_calls:
        return _compared_by_callers(fn)
    sym = None
    if type(up) is A.Declarator and up.init is e:
        sym = fn.model.symbol_of(up)
    elif type(up) is A.Assignment and up.op == "=" and up.value is e:
        if type(up.target) is A.Identifier:
            sym = fn.model.symbol_of(up.target)
    if sym is None or sym.kind != "local":
        return None
    if [w.node for w in fn.writes_to(sym) if w.kind != "decl"] != [up]:
        return None
    target = up.target if type(up) is A.Assignment else None
    reads = [
        n
        for n in fn.nodes
        if type(n) is A.Identifier and n is not target and fn.model.symbol_of(n) is sym
    ]
    first = None  # (nothing read: the unused-variable rule's)
    for r in reads:
        side = _compared(fn, r)
        if side is not None:
            found: tuple[Any, str, str] | None = (*side, "local")
        elif through_calls and type(fn.parent.get(id(r))) is A.Return:
            found = _compared_by_callers(fn)
        else:
            return None
        if found is None:
            return None
        first = first or found
    return first


def _compared_by_callers(fn) -> tuple[Any, str, str] | None:
    """(other side, operator, the function's name) of its first call when every call of the
    user function `fn` is only compared, directly or through a local; None otherwise."""
    if fn.symbol is None or fn.symbol.name == "mainImage":
        return None
    sites = program_facts(fn.model).call_sites(fn.symbol)
    first = None
    for caller, call in sites:
        found = _only_compared(caller, call, False)
        if found is None:
            return None
        first = first or found
    return None if first is None else (first[0], first[1], fn.symbol.name)


def kept(via: str, other: A.Expr) -> str:
    """How compared_values' value reaches its comparison, for a message: "" when directly."""
    if via == "local":
        return ", its value kept in a local that is only compared"
    if via:
        return (
            f", returned by {via}() whose every call is only compared (as at line {other.loc.line})"
        )
    return ""


def text(e: Any) -> str:
    """GLSL text of an expression, shortened for a message."""
    s = to_glsl(e)
    return s if len(s) <= 60 else s[:57] + "..."


def at_lines(nodes: Any) -> str:
    """`line 4`, or `lines 4, 9 and 12`: where the nodes are, for a message."""
    lines = sorted({n.loc.line for n in nodes})
    if len(lines) == 1:
        return f"line {lines[0]}"
    return "lines " + ", ".join(map(str, lines[:-1])) + f" and {lines[-1]}"


def is_atom(e: Any) -> bool:
    """A name, a literal, or a field/swizzle/element of one: printed inside a larger expression
    it needs no parentheses. (Not the NumPy transpiler's `is_plain_read`, which asks whether a value
    is read without computing anything per lane.)"""
    while type(e) in (A.Field, A.Index):
        e = e.base
    return type(e) in (A.Identifier, A.FloatLiteral, A.IntLiteral, A.BoolLiteral)


def wrap(e: Any) -> str:
    """GLSL text of `e`, in parentheses unless it is an atom or a call."""
    return text(e) if is_atom(e) or type(e) is A.Call else f"({text(e)})"


def squared(model: Model, e: Any) -> str:
    """`r * r` for an expression, or the folded square of a constant bound."""
    nums = numbers(model.const_value(e))
    if len(nums) == 1:
        v = nums[0] * nums[0]
        s = repr(v) if v != int(v) or abs(v) >= 1e16 else f"{int(v)}.0"
        return s if len(s) < 12 else f"{v:g}"
    w = wrap(e)
    return f"{w} * {w}"


def squared_bound(ctx: Any, fn: Any, bound: A.Expr) -> tuple[str, bool] | None:
    """The text of a comparison's bound squared, for a fix, and whether the bound is known to be
    >= 0 (squaring both sides keeps the comparison only then): the folded square of a constant
    (None for a negative one), `r * r` for a name or field `r`; None for any other bound (its
    square written out would compute it twice)."""
    from ..fixes.build import node_text

    nums = numbers(ctx.model.const_value(bound))
    if len(nums) == 1:
        return (squared(ctx.model, bound), True) if nums[0] >= 0 else None
    r = node_text(ctx, bound)
    if r is None or not is_atom(bound) or len(nums) > 1:
        return None
    lo = fn.value_range(bound)[0]
    return f"{r} * {r}", lo is not None and lo >= 0
