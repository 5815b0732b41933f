"""Statements after a `return`, `break`, `continue` or `discard` in the same block never run.

## What it does
Reports the statements of a block that follow a `return`, `break`, `continue` or `discard` of
that block: control never reaches them. One finding per block, at its first unreachable
statement, naming the jump and the lines that never run. A jump inside a nested block (`if (hit)
{ return c; }`) leaves the code after that block reachable and is not reported; neither are
comments and empty statements. Returns after a `return` that each carry a comment on their line
(`return fade(loc); // cross fade`) are outputs kept to switch between and are not reported; a
bare one (the starter's `return vec4(0.5);` left under the student's return) is.

It is a possible deduction: the compiler drops code that never runs, so the cost is to the reader
(and to the student, whose code after the jump does not do what it seems to).

## Why is this bad?
The course's coding standards: "Use the most efficient methods (-1 per inefficient/unnecessary
practices)". Code left after an early `return` (a second light, a final color no one sees) is
unnecessary code: a leftover of testing one part at a time.

## Example
```glsl
vec3 lit = ambient + diffuse;
return vec4(lit, 1.0);
vec3 second = shade(lightTwo, p, n); // never runs
```

## Use instead
```glsl
vec3 lit = ambient + diffuse + shade(lightTwo, p, n);
return vec4(lit, 1.0);
```
"""

from __future__ import annotations

from ...base.diagnostics import Diagnostic
from ...frontend import syntax as A
from ...semantics.analysis import program_facts

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

    from ..engine import LintContext

NAME = "unreachable-code"
PENALTY = 1
STANDARD = "efficiency"
SEVERITY = "warning"
CERTAINTY = "possible"
NEEDS = "ast"

_JUMPS = {A.Return: "return", A.Break: "break", A.Continue: "continue", A.Discard: "discard"}


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    noted = {c.end_line for c in ctx.comments if not c.block}  # lines ending in a // comment
    for fn in program_facts(ctx.model).in_file(ctx.path):
        for block in fn.nodes:
            if type(block) is not A.Compound or fn.is_dead(block):
                continue  # a dead block inside dead code is part of the outer finding
            jump = next((s for s in block.stmts if type(s) in _JUMPS), None)
            if jump is None:
                continue
            after = block.stmts[block.stmts.index(jump) + 1 :]
            after = [s for s in after if not (type(s) is A.ExpressionStatement and s.expr is None)]
            if not after or all(type(s) is A.Return and s.loc.line in noted for s in after):
                continue  # returns each named by a comment: other outputs kept to switch between
            first, last = after[0].loc.line, max(s.loc.end_line or s.loc.line for s in after)
            lines = f"line {first}" if first == last else f"lines {first}-{last}"
            yield Diagnostic(
                f"the code after the '{_JUMPS[type(jump)]}' at line {jump.loc.line} never runs"
                f" ({lines})",
                after[0].loc,
                help="remove it, or move it before the jump if it was meant to run",
            )
