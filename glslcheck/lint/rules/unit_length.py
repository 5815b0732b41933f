"""The length of a vector that is already of unit length.

## What it does
Reports `length(u)` and `dot(u, u)` (also inside `sqrt(dot(u, u))`) where `u` is the result of
`normalize`, written there or held in a local variable
that the normalize's value reaches on every path with no other write in between, or another
value of unit length (`_unit_vectors.py`: a helper returning a normalize, `reflect()` of a unit
vector about a unit normal). That length
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
from ._unit_vectors import held, unit_source

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
            unit = unit_source(fn, v)
            if unit is None:
                continue
            square = n.callee == "dot"
            yield Diagnostic(
                f"'{text(n)}' is the {'squared ' if square else ''}length of a unit vector"
                f"{held(v, unit)}: it is 1.0 wherever the normalize is defined",
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
