"""A square root is computed only to be compared with a bound.

## What it does
Reports `sqrt(x)` computed only to be an operand of `<`, `<=`, `>` or `>=`: directly, through
a local that holds it and is only compared, or returned by a function every call of which is
only compared (`float brightness(vec3 c) { return sqrt(dot(c, c)); }` read only as
`brightness(c) > 0.5`). The fix, for a direct comparison, squares both sides.

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

from ..fixes import Fix, Fixable
from ..fixes.build import facts_of, fit, node_text, precedence, replace
from ._text import compared_values, kept, squared, squared_bound, text

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

    from ...base.diagnostics import Diagnostic
    from ..engine import LintContext

NAME = "sqrt-comparison"
PENALTY = 1
STANDARD = "efficiency"
SEVERITY = "warning"
NEEDS = "ast"


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    model = ctx.model
    if model is None:  # (no semantic model: no function has facts)
        return
    for side, other, op, via in compared_values(model, ctx.path, "sqrt"):
        x, bound = text(side.args[0]), squared(model, other)
        yield Fixable(
            f"sqrt() is compared with a bound{kept(via, other)}: compare its argument with the "
            "squared bound",
            side.loc,
            help=f"write {x} {op} {bound} (for a bound >= 0)",
            fix=None if via else _fix(ctx, side, other),
        )


def _fix(ctx: LintContext, side, other) -> Fix | None:
    """`x < r * r` for `sqrt(x) < r`: the same comparison when x >= 0 (else sqrt is NaN and
    every comparison false) and r >= 0."""
    fn = facts_of(ctx, side)
    bound = squared_bound(ctx, fn, other) if fn is not None else None
    x = side.args[0]
    x_text = node_text(ctx, x)
    if bound is None or x_text is None:
        return None
    bound_text, nonneg = bound
    lo = fn.value_range(x)[0]
    x_nonneg = lo is not None and lo >= 0
    why = []
    if not nonneg:
        why.append(f"the bound '{text(other)}' may be negative")
    if not x_nonneg:
        why.append(f"'{text(x)}' may be negative, where sqrt() is NaN and the comparison false")
    return Fix(
        f"compare {text(x)} with {bound_text}",
        ctx.path,
        (
            replace(side, fit(fn, side, x_text, precedence(x))),
            replace(other, fit(fn, other, bound_text, 14 if "*" in bound_text else 17)),
        ),
        "unsafe" if why else "safe",
        " and ".join(why),
    )
