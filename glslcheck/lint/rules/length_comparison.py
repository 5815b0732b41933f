"""A length or distance is computed only to be compared with a bound.

## What it does
Reports `length(v)` or `distance(a, b)` used directly as an operand of `<`, `<=`, `>` or `>=`.

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

from ...base.diagnostics import Diagnostic
from ._text import compared_calls, squared, text

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

    from ..engine import LintContext

NAME = "length-comparison"
PENALTY = 1
SEVERITY = "warning"
NEEDS = "ast"


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    model = ctx.model
    if model is None:  # (no semantic model: no function has facts)
        return
    for side, other, op in compared_calls(model, ctx.path, "length", "distance"):
        bound = squared(model, other)
        if side.callee == "length":
            v = text(side.args[0])
            fix = f"compare dot(v, v) with the squared bound: with v = {v}, dot(v, v) {op} {bound}"
        else:
            a, b = text(side.args[0]), text(side.args[1])
            fix = f"compare the squared distance: with d = {a} - {b}, dot(d, d) {op} {bound}"
        yield Diagnostic(
            f"{side.callee}() is compared with a bound: its square root is not needed",
            side.loc,
            help=fix,
        )
