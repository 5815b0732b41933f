"""An `out` parameter is read before the function writes it.

## What it does
Reports the first read of an `out` parameter that some path through the function reaches
before an assignment to it: `float rand(out float seed) { ... sin(seed) ...; seed++; }`. The
paths are `uninitialized-read`'s (an `if` without `else`, a loop body that may not run, a `?:`
or `&&`/`||` arm, a `switch` case); an assignment to a part (`p.x = ..`) and passing the
parameter as another call's `out` argument count as writes, `+=`, `++` and an `inout` argument
as reads. One finding per parameter. The analysis is the checker's
(`glslcheck.semantics.analysis.undefined`): `check` warns at the same read, and `verify` names
the pixels it changes as undefined in the shader rather than a renderer's fault.

This is a course rule: the rubric's standard "Use the most efficient methods (-1 per
inefficient/unnecessary practices) ... implement optimized and thoughtful shader code" is broken
by code whose result depends on a value the program never set, and the rubric's "correct and
stable final product" is what it costs: the shader's noise, and whether its loops end, change
from one driver to the next. A TA marks it as a correctness bug wherever it is seen.

## Why is this bad?
GLSL ES 3.00 (section 6.1.1): an `out` parameter is copied out when the function returns, never
in; on entry its value is undefined, whatever the caller's variable holds. WebGL passes zero,
a desktop driver whatever its register held: a random-number helper that reads its `out` seed
returns the same number on every call in the browser (a `while (true)` loop waiting for a
random point inside the unit sphere then never ends) and something else on the desktop.

## Example
```glsl
// next random number in [0, 1) from the running seed
float rand(out float seed)
{
    float r = fract(sin(seed) * 43758.5453);
    seed++;
    return r;
}
```

## Use instead
```glsl
// next random number in [0, 1) from the running seed (read and advanced: inout)
float rand(inout float seed)
{
    float r = fract(sin(seed) * 43758.5453);
    seed++;
    return r;
}
```
"""

from __future__ import annotations

from ...base.diagnostics import Diagnostic
from ...semantics.analysis import program_facts, unassigned_reads

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

    from ..engine import LintContext

NAME = "out-parameter-read"
PENALTY = 1
STANDARD = "correctness"
SEVERITY = "warning"
NEEDS = "ast"


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    model = ctx.model
    if model is None:
        return
    for fn in program_facts(model).in_file(ctx.path):
        for u in unassigned_reads(model, fn.definition):
            if u.kind != "out-parameter":
                continue
            name = u.node.name
            yield Diagnostic(
                f"the out parameter '{name}' is read before it is written: its value on entry "
                "is undefined (an out parameter is not copied in), so the result depends on the "
                "driver; unnecessary and incorrect code",
                u.loc,
                help=f"declare it 'inout {name}' if the caller's value is meant to come in, "
                "or write it before reading it",
            )
