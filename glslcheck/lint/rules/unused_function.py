"""A function is never called from mainImage, directly or through other functions.

## What it does
Reports each user function defined in the file that is not reachable from the entry point
(`mainImage`, or `main` in a plain GLSL file) through calls. A Common tab is checked together
with the Image tab; when the shader has other passes too (Buffer A..D), Common's functions are
not reported (another pass may call them).

This is a note, not a deduction.

## Why is this bad?
Dead code: a leftover of an earlier part of the lab, or a function that was meant to be used
(a forgotten light, a bonus effect that never shows). Every function must also be commented,
so an unused one costs comments for nothing.

## Example
```glsl
vec3 lambert(in vec3 n, in vec3 l) { return vec3(max(dot(n, l), 0.0)); } // old version
vec3 blinnPhong(in vec3 n, in vec3 l, in vec3 v) { /* ... */ }
// mainImage calls only blinnPhong
```

## Use instead
```glsl
vec3 blinnPhong(in vec3 n, in vec3 l, in vec3 v) { /* ... */ }
```
"""

from __future__ import annotations

from ...base.diagnostics import Diagnostic
from ...semantics.analysis import program_facts
from .unused_variable import common_shared

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

    from ..engine import LintContext

NAME = "unused-function"
PENALTY = 0
SEVERITY = "note"
NEEDS = "ast"
READS = "program"  # a call in code that does not compile may be missing


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    model = ctx.model
    if model is None:
        return
    if model.entry is None or common_shared(ctx):
        return
    reachable = {id(s) for s in model.reachable_functions()}
    for fn in program_facts(ctx.model).in_file(ctx.path):
        sym = fn.symbol
        if sym is None or id(sym) in reachable or sym is model.entry:
            continue
        proto = fn.definition.proto
        yield Diagnostic(
            f"the function '{proto.name}' is never called from {model.entry.name}",
            proto.name_loc if proto.name_loc.line else proto.loc,
            help=f"remove '{proto.name}', or call it where its result was meant to be used",
        )
