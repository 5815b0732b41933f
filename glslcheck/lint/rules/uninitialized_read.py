"""A local or global variable may be read before it is assigned a value.

## What it does
Follows each function's statements in order and reports the first read of a local variable
declared without an initializer when some path reaches the read without an assignment: an
`if` without `else` (or with one arm only assigning), a loop body (which may run zero times), a
`?:` or `&&`/`||` arm, a `switch` case. An assignment to a part (`v.x = ..`, `a[i] = ..`)
counts as an assignment, and so does passing the variable as an `out` argument
(`traceScene(ray, position, normal)`); an `inout` argument is a read; a loop whose condition is
always true (`while (true)`) is left only by its `break`s. One finding per variable.

A global declared without an initializer (`float edge;` at file scope, not `const` or a
uniform) is followed the same way from mainImage across the functions it calls: a function
that assigns the global on every path counts as assigning it at its call, and a read in a
callee that some path from mainImage reaches before any assignment is reported there. The
analysis is the checker's (`glslcheck.semantics.analysis.undefined`): `check` warns at the same
reads, and `verify` names the pixels they change.

This is a note, not a deduction: WebGL implementations zero-initialise variables, so the
shader may look right; GLSL ES 3.00 itself leaves the value undefined.

## Why is this bad?
GLSL ES 3.00 (section 4.3): a local variable without an initializer has an undefined value,
and globals without one "enter main() with undefined values". What it reads depends on the
driver: the shader may work in one browser and show garbage in another (llvmpipe folds a
global that one path sets to 1.0 to that constant on every path). It is also usually a logic
error (a branch that forgot to set the value).

## Example
```glsl
float kS;
if (kD > 0.0) kS = pow(max(dot(viewDir, reflected), 0.0), alpha);
color += kS * specularColor;
```

## Use instead
```glsl
float kS = 0.0; // no highlight where the light does not reach
if (kD > 0.0) kS = pow(max(dot(viewDir, reflected), 0.0), alpha);
color += kS * specularColor;
```
"""

from __future__ import annotations

from ...base.diagnostics import Diagnostic
from ...semantics.analysis import global_reads, program_facts, reached_through, unassigned_reads

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

    from ..engine import LintContext

NAME = "uninitialized-read"
PENALTY = 0
SEVERITY = "note"
NEEDS = "ast"


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    model = ctx.model
    if model is None:
        return
    for fn in program_facts(model).in_file(ctx.path):
        for u in unassigned_reads(model, fn.definition):
            if u.kind != "uninitialized-local":
                continue
            name = u.node.name
            yield Diagnostic(
                f"'{name}' may be read before it is assigned a value "
                f"(declared at line {u.origin.loc.line} without an initializer)",
                u.loc,
                help=u.help,
            )
    for u in global_reads(model):
        if u.loc.path == ctx.path:
            yield Diagnostic(
                f"the global '{u.node.name}' may be read before it is assigned a value "
                f"(declared at line {u.origin.loc.line} without an initializer"
                f"{reached_through(model.entry, u.via)})",
                u.loc,
                help=u.help,
            )
