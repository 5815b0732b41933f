"""pow() of a base that can be negative: undefined in GLSL, NaN on most GPUs.

## What it does
Reports `pow(x, y)` when the base `x` can be shown to be possibly negative: it is (or is a
variable last assigned, on every path, from) a dot product of two different vectors, a
difference, a negation, `sin`/`cos`/`tan`, a `reflect`/`refract`/`cross` result or a negative
constant, and is not made non-negative by `max(.., >= 0)`, `clamp(.., >= 0, ..)`, `abs`,
`dot(v, v)`, `length`, `sqrt`, `exp`, `x * x`, `smoothstep`, `step`, `fract` or a uniform such as
`iTime`. The analysis is conservative: a parameter or a user function's result of unknown sign
is not reported. A dot product of two different vectors is taken to be a cosine in [-1, 1], so
`pow(1.0 - max(dot(n, v), 0.0), 5.0)` is accepted. A call `pow-small-exponent` reports
(`pow(x - c, 2.0)`) is left to it, its rewrite (`v * v`) being defined for every base, unless
the base is negative for being a dot product: a cosine wants its clamp whatever the exponent.

## Why is this bad?
GLSL ES 3.00 (section 8.2): "pow: Results are undefined if x < 0". GPUs compute
`exp2(y * log2(x))`, which is NaN for a negative `x`: black or flickering pixels where the
surface faces away from the light. The Lab 4 specular term needs the clamped coefficient
("we have a similar clamped coefficient"); the course's standards also ask for correct,
thoughtful code ("Use the most efficient methods (-1 per inefficient/unnecessary practices)").

## Example
```glsl
float specular = pow(dot(viewDir, reflected), alpha);
```

## Use instead
```glsl
float specular = pow(max(dot(viewDir, reflected), 0.0), alpha);
```
"""

from __future__ import annotations

from ...base.diagnostics import Diagnostic
from ...frontend import syntax as A
from ...semantics.analysis import builtin_calls
from ._text import negative_reason, text
from .pow_small_exponent import small_exponent

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

    from ..engine import LintContext

NAME = "pow-negative-base"
PENALTY = 1
STANDARD = "efficiency"
SEVERITY = "warning"
NEEDS = "ast"


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    model = ctx.model
    if model is None:  # (no semantic model: no function has facts)
        return
    for fn, node in builtin_calls(model, ctx.path, "pow", arity=2):
        base = node.args[0]
        if small_exponent(fn, node) is not None and not _cosine(fn, base):
            continue  # pow-small-exponent's rewrite (`v * v`) is the fix: defined for every base
        why = negative_reason(fn, base)
        if why is not None:
            yield Diagnostic(
                f"the base of pow() can be negative ({why}); pow() is undefined there",
                base.loc,
                help=f"clamp the base first: pow(max({text(base)}, 0.0), {text(node.args[1])})",
            )


def _cosine(fn, base) -> bool:
    """Whether `base` can be negative for being a dot product (a cosine meant to be clamped):
    multiplying it by itself still gives a value for the side facing away."""
    why = fn.negative_witness(base)
    source = why[1] if why is not None else None
    return type(source) is A.Call and source.callee == "dot"
