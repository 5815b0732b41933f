"""Vectors known to be of unit length where they are read (shared by normalize-known-length,
which reports normalizing one again, and unit-length, which reports measuring one).

A value is of unit length when it is a normalize() call, a call of a user function each of
whose returns is one (`estimateNormal(p)` returning `normalize(...)`), reflect() of one about
another (the reflection keeps the incident vector's length when the normal is of unit length),
a negation of one, or a local that holds one where it is read (assigned on every path, not
written since). Wherever the normalize is defined: not for a zero vector.
"""

from __future__ import annotations

from ...frontend import syntax as A
from ...semantics.analysis import builtin_call, program_facts
from ...semantics.model import Symbol
from ._text import text

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from typing import Any

_DEPTH = 8  # locals, negations and calls followed (GLSL has no recursion)


def unit_source(fn, v, depth: int = 0) -> Any:
    """The expression that makes `v` of unit length (the module's doc): `v` itself, or the
    value a local `v` holds where it is read; None when its length is not known to be 1."""
    if depth > _DEPTH:
        return None
    model = fn.model
    t = type(v)
    if t is A.Identifier:
        sym = model.symbol_of(v)
        if sym is None or sym.kind != "local":
            return None
        value = fn.reaching_value(v, sym)
        return None if value is None else unit_source(fn, value, depth + 1)
    if t is A.Unary and v.op == "-":
        return v if unit_source(fn, v.operand, depth + 1) is not None else None
    if t is not A.Call:
        return None
    if builtin_call(model, v, "normalize"):
        return v
    if builtin_call(model, v, "reflect") and len(v.args) == 2:
        both = all(unit_source(fn, a, depth + 1) is not None for a in v.args)
        return v if both else None
    target = model.call_target(v)
    d = getattr(target, "node", None)
    if not isinstance(target, Symbol) or not isinstance(d, A.FunctionDefinition) or d.body is None:
        return None
    callee = program_facts(model).fn(d)
    returns = [n for n in callee.nodes if type(n) is A.Return and not callee.is_dead(n)]
    if returns and all(
        r.value is not None and unit_source(callee, r.value, depth + 1) is not None for r in returns
    ):
        return v
    return None


def held(v, unit) -> str:
    """` ('v' holds normalize(...), line 7)` when a local `v` holds the unit value, else ``."""
    if _callee(unit) == "reflect":
        why = " (a unit vector reflected about a unit normal)"
    elif type(unit) is A.Call and _callee(unit) != "normalize":
        why = f" ({unit.callee}() returns a normalized vector)"
    else:
        why = ""
    if v is unit or type(v) is not A.Identifier:
        return why
    return f" ('{v.name}' holds {text(unit)}, line {unit.loc.line}){why}"


def _callee(e) -> str:
    """The name a call calls (a built-in or a user function), else ``."""
    return e.callee if type(e) is A.Call else ""


def normalized_again(fn, call: A.Call) -> tuple[str, str] | None:
    """(message, help) when the normalize() `call` normalizes a vector already of unit
    length."""
    if not builtin_call(fn.model, call, "normalize") or len(call.args) != 1:
        return None
    v = call.args[0]
    unit = unit_source(fn, v)
    if unit is None:
        return None
    return (
        f"'{text(call)}' normalizes a vector already of unit length{held(v, unit)}: it gives "
        f"back {text(v)}",
        f"write {text(v)}: its length is already 1",
    )
