"""sqrt() or inversesqrt() of a value that can be negative.

## What it does
Reports `sqrt(x)` and `inversesqrt(x)` when `x` can be shown to be possibly negative, with the
same conservative analysis as `pow-negative-base`: a dot product of two different vectors, a
difference (a discriminant `b * b - c`), a negation, `sin`/`cos`, ... not guarded by
`max(.., 0.0)`, `abs`, `dot(v, v)` and the like. Values of unknown sign (parameters) are not
reported.

This is a note, not a deduction: the code may test the sign elsewhere (`if (disc < 0.0) return`),
which this rule does not follow.

## Why is this bad?
GLSL ES 3.00 (section 8.2): "sqrt: Results are undefined if x < 0"; "inversesqrt: Results
are undefined if x <= 0". GPUs return NaN, which spreads through every later computation of
the pixel.

## Example
```glsl
float disc = halfB * halfB - c;
float t = -halfB - sqrt(disc);
```

## Use instead
```glsl
float disc = halfB * halfB - c;
float t = -halfB - sqrt(max(disc, 0.0)); // the miss is masked with step(0.0, disc)
```
"""

from __future__ import annotations

from ...base.diagnostics import Diagnostic
from ...semantics.analysis import builtin_calls
from ._text import negative_reason, text

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

    from ..engine import LintContext

NAME = "unguarded-sqrt"
PENALTY = 0
SEVERITY = "note"
NEEDS = "ast"


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    model = ctx.model
    if model is None:  # (no semantic model: no function has facts)
        return
    for fn, node in builtin_calls(model, ctx.path, "sqrt", "inversesqrt", arity=1):
        arg = node.args[0]
        why = negative_reason(fn, arg)
        if why is not None:
            yield Diagnostic(
                f"the argument of {node.callee}() can be negative ({why})",
                arg.loc,
                help=f"guard it: {node.callee}(max({text(arg)}, 0.0)), "
                "and mask the result where it was negative",
            )
