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

from typing import TYPE_CHECKING, Iterator

from ... import ast as A
from ...analysis import builtin_call, program_facts
from ...diagnostics import Diagnostic
from ._text import COMPARISONS, FLIPPED, squared, text

if TYPE_CHECKING:
    from ..engine import LintContext

NAME = "sqrt-comparison"
PENALTY = 1
SEVERITY = "warning"
NEEDS = "ast"


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    model = ctx.model
    for fn in program_facts(ctx.model).in_file(ctx.path):
        for node in fn.nodes:
            if type(node) is not A.Binary or node.op not in COMPARISONS:
                continue
            for side, other in ((node.left, node.right), (node.right, node.left)):
                op = node.op if side is node.left else FLIPPED[node.op]
                if not builtin_call(model, side, "sqrt"):
                    continue
                x, bound = text(side.args[0]), squared(model, other)
                yield Diagnostic(
                    "sqrt() is compared with a bound: compare its argument with the squared bound",
                    side.loc,
                    help=f"write {x} {op} {bound} (for a bound >= 0)",
                )
