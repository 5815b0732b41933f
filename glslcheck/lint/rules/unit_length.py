"""The length of a vector that is already of unit length.

## What it does
Reports `length(u)` and `dot(u, u)` (also inside `sqrt(dot(u, u))`) where `u` is the result of
`normalize`, written there or held in a local variable
that the normalize's value reaches on every path with no other write in between. That length
is 1 (wherever the normalize is defined: not for a zero vector): a square root computed for a
value known in advance, and often a bug (the distance to the
light was meant: `length(light - p)`, not the length of the normalized vector).

## Why is this bad?
The course's coding standards: "Use the most efficient methods (-1 per inefficient/unnecessary
practices) ... Use inefficient functions and methods sparingly and out of necessity (including
but not limited to conditionals, square roots, etc.)". The length of a unit vector is 1.0.

## Example
```glsl
vec3 lightVec = normalize(light.center - position);
float d = length(lightVec);
```

## Use instead
```glsl
vec3 toLight = light.center - position;
float d = length(toLight); // the distance to the light
vec3 lightVec = toLight / d;
```
"""

from __future__ import annotations

from ...base.diagnostics import Diagnostic
from ...frontend import syntax as A
from ...semantics.analysis import builtin_call, program_facts
from ._text import text

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator
    from typing import Any

    from ..engine import LintContext

NAME = "unit-length"
PENALTY = 1
STANDARD = "efficiency"
SEVERITY = "warning"
NEEDS = "ast"


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    for fn in program_facts(ctx.model).in_file(ctx.path):
        for n in fn.nodes:
            if type(n) is not A.Call:
                continue
            v = _measured(fn, n)
            if v is None:
                continue
            unit = _unit(fn, v)
            if unit is None:
                continue
            held = ""
            if v is not unit:
                held = f" ('{v.name}' holds {text(unit)}, line {unit.loc.line})"
            square = n.callee == "dot"
            yield Diagnostic(
                f"'{text(n)}' is the {'squared ' if square else ''}length of a normalized "
                f"vector{held}: it is 1.0 wherever the normalize is defined",
                n.loc,
                help="write 1.0, or measure the vector before normalizing it if its length was "
                "meant (the distance to a light: length(light - p))",
            )


def _measured(fn, n: A.Call) -> Any:
    """The vector a call measures: length(u), dot(u, u) (in `sqrt(dot(u, u))` too); else
    None."""
    model = fn.model
    if builtin_call(model, n, "length") and len(n.args) == 1:
        return n.args[0]
    if builtin_call(model, n, "dot") and len(n.args) == 2:
        if fn.key(n.args[0]) == fn.key(n.args[1]) and fn.is_pure(n.args[0]):
            return n.args[0]
    return None


def _unit(fn, v) -> A.Call | None:
    """The normalize call `v` is, or that a local `v` holds where it is read, else None."""
    model = fn.model
    if type(v) is A.Identifier:
        sym = model.symbol_of(v)
        if sym is None or sym.kind != "local":
            return None
        v = fn.reaching_value(v, sym)
    if builtin_call(model, v, "normalize"):
        return v
    return None
