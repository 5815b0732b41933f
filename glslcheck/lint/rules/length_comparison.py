"""A length or distance is computed only to be compared with a bound.

## What it does
Reports `length(v)` or `distance(a, b)` used as an operand of `<`, `<=`, `>` or `>=` or of
`step()` (`step(r, length(v))` compares `length(v) >= r`), directly or through a local it
initializes that is never written again and only ever compared (`float d = length(center -
uv); return 1.0 - step(radius, d);`). The fix, for a direct comparison, squares both sides.

## Why is this bad?
The course's coding standards: "Use the most efficient methods (-1 per inefficient/unnecessary
practices)", and the Lab 4 hint for the in-circle test: "'length' is inefficient and requires
prior calculation of some other metric using 2D Pythagorean theorem". `length` is a square root
of a dot product; both sides of a comparison of non-negative numbers can be squared, so the
square root is not needed: `length(v) < r` is `dot(v, v) < r * r`.

## Example
```glsl
vec2 dp = coord - center;
if (length(dp) <= radius) inCircle = 1.0;
```

## Use instead
```glsl
vec2 dp = coord - center;
float distSq = dot(dp, dp);          // reused below for the sphere's z
if (distSq <= radius * radius) inCircle = 1.0;
```
"""

from __future__ import annotations

from ..fixes import Fix, Fixable
from ..fixes.build import declare_before, facts_of, fit, name_hint, node_text, operand_text, replace
from ._text import compared_values, is_atom, kept, squared, squared_bound, text

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

    from ...base.diagnostics import Diagnostic
    from ..engine import LintContext

NAME = "length-comparison"
PENALTY = 1
STANDARD = "efficiency"
SEVERITY = "warning"
NEEDS = "ast"


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    model = ctx.model
    if model is None:  # (no semantic model: no function has facts)
        return
    for side, other, op, via in compared_values(model, ctx.path, "length", "distance"):
        bound = squared(model, other)
        if side.callee == "length":
            v = text(side.args[0])
            fix = f"compare dot(v, v) with the squared bound: with v = {v}, dot(v, v) {op} {bound}"
        else:
            a, b = text(side.args[0]), text(side.args[1])
            fix = f"compare the squared distance: with d = {a} - {b}, dot(d, d) {op} {bound}"
        yield Fixable(
            f"{side.callee}() is compared with a bound{kept(via, other)}: its square root is not "
            "needed",
            side.loc,
            help=fix,
            fix=None if via else _fix(ctx, side, other),
        )


def _fix(ctx: LintContext, side, other) -> Fix | None:
    """`dot(v, v) < r * r` for `length(v) < r` (v in a local first when it is not a name; for
    `distance(a, b)` the local is `a - b`): the same comparison when the bound is >= 0."""
    fn = facts_of(ctx, side)
    bound = squared_bound(ctx, fn, other) if fn is not None else None
    if bound is None:
        return None
    bound_text, nonneg = bound
    edits = []
    v = side.args[0]
    if side.callee == "length" and is_atom(v):
        name = node_text(ctx, v)
    else:
        if side.callee == "length":
            value, hint = node_text(ctx, v), name_hint(v)
        else:
            a, b = operand_text(ctx, side.args[0], 13), operand_text(ctx, side.args[1], 14)
            value = None if a is None or b is None else f"{a} - {b}"
            to = name_hint(side.args[1])
            hint = name_hint(side.args[0]) + "To" + to[0].upper() + to[1:]
        if value is None:
            return None
        found = declare_before(ctx, fn, side, fn.model.type_of(v), value, hint)
        if found is None:
            return None
        name, insert = found
        edits.append(insert)
    if name is None:
        return None
    edits.append(replace(side, f"dot({name}, {name})"))
    edits.append(replace(other, fit(fn, other, bound_text, 14 if "*" in bound_text else 17)))
    return Fix(
        f"compare dot({name}, {name}) with {bound_text}",
        ctx.path,
        tuple(edits),
        "safe" if nonneg else "unsafe",
        ""
        if nonneg
        else f"squaring keeps the comparison only for a bound >= 0, and "
        f"'{text(other)}' may be negative",
    )
