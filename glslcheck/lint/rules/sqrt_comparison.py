"""A square root is computed only to be compared with a bound.

## What it does
Reports `sqrt(x)` used directly as an operand of `<`, `<=`, `>` or `>=`.

## Why is this bad?
The course's coding standards: "Use the most efficient methods (-1 per inefficient/unnecessary
practices) ... Use inefficient functions and methods sparingly and out of necessity (including
but not limited to conditionals, square roots, etc.)". For a non-negative bound,
`sqrt(x) < r` is `x < r * r`: one multiply instead of a square root.

## Example
```glsl
if (sqrt(distSq) < radius) hit = 1.0;
```

## Use instead
```glsl
if (distSq < radius * radius) hit = 1.0;
```
"""

from __future__ import annotations

from ...base.diagnostics import Diagnostic
from ._text import compared_calls, squared, text

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

    from ..engine import LintContext

NAME = "sqrt-comparison"
PENALTY = 1
SEVERITY = "warning"
NEEDS = "ast"


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    model = ctx.model
    if model is None:  # (no semantic model: no function has facts)
        return
    for side, other, op in compared_calls(model, ctx.path, "sqrt"):
        x, bound = text(side.args[0]), squared(model, other)
        yield Diagnostic(
            "sqrt() is compared with a bound: compare its argument with the squared bound",
            side.loc,
            help=f"write {x} {op} {bound} (for a bound >= 0)",
        )
