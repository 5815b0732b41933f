"""normalize() of a vector whose length the function computes again after it.

## What it does
Reports `normalize(v)` (or a user function that returns its argument normalized) when the
length of `v` is computed again after it in the same function: `length(v)`, `distance(a, b)`
for `v = a - b` or `b - a`, `dot(v, v)` (its square) or `sqrt` of v's squared components
written out, evaluated after it (every path to the measure goes through the normalize, a
measure in a branch too: on that path the length is computed twice, and computed first it is
computed once on every path) with no write to `v`'s variables in between. Vectors are compared
by value, as `normalize-known-length` compares them (a local variable stands for the value
assigned to it on every path; `v` and `-v` have the same length).

A length computed before the normalize is `normalize-known-length`: there the fix divides by
the length at hand; here the length has to be computed first.

## Why is this bad?
The course's coding standards: "Use the most efficient methods (-1 per inefficient/unnecessary
practices)". `normalize(v)` computes the length of `v` (a dot product and a reciprocal square
root); computing it again for the distance does that work twice. Compute the length once and
divide by it: one square root gives both the unit vector and the distance.

## Example
```glsl
vec3 L = normalize(light - p);
float d = distance(light, p);
```

## Use instead
```glsl
vec3 toLight = light - p;
float d = length(toLight); // computed once: the distance, and the unit vector below
vec3 L = toLight / d;
```
"""

from __future__ import annotations

from ...base.diagnostics import Diagnostic
from ...semantics.analysis import program_facts
from .normalize_known_length import measured, measured_lengths, normalize_calls

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

    from ..engine import LintContext

NAME = "length-computed-twice"
PENALTY = 1
STANDARD = "efficiency"
SEVERITY = "warning"
NEEDS = "ast"


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    for fn in program_facts(ctx.model).in_file(ctx.path):
        calls = normalize_calls(fn)
        if not calls:
            continue
        known = measured_lengths(fn)
        for call in sorted(calls, key=lambda c: fn.enter[id(c)]):
            found = measured(fn, call, known, after=True)
            if found is not None:
                message, fix, _ = found  # the length comes after: no rewrite in place
                yield Diagnostic(message, call.loc, help=fix)
