"""The file does not compile: an error Shadertoy would show, reported before any lint finding.

## What it does
Reports every syntax and type error of the linted file (the errors `glslcheck check` prints,
as the Shadertoy pass the file belongs to compiles it), first, before every other finding.

Linting goes on past them: a syntax error takes out only the top-level declaration it is in (a
function keeps its prototype, so its callers still check), a type error only the function it is
in. The rules that read names and scopes (`uniform-outside-mainimage`) still read that
function; the rules that need types skip it, and one note per rule says which functions it could
not run in. `unused-variable` and `unused-function` read the whole program and do not run on a
program with errors. A word GLSL reserves used as a name (`vec3 sample(...)`) takes out nothing:
the rest of the file is read with it spelt another way (a note says how), and every rule runs.

A compile error is not a coding-standard deduction: it costs no points here (a shader that does
not compile costs far more). The exit status is 1, as for any finding.

## Why is this bad?
Shadertoy shows a black image and the error; the course's assignments must run ("correct and
stable final product that runs as expected"). Code pasted from Shadertoy mid-edit, or a
submission whose last change was never compiled, is the commonest cause.

## Example
```glsl
vec4 shade(in vec3 n)
{
    vec3 color = normalz * 0.5 + 0.5;   // 'normalz' is not declared
}                                       // and no return statement
```

## Use instead
```glsl
vec4 shade(in vec3 n)
{
    vec3 color = n * 0.5 + 0.5;
    return vec4(color, 1.0);
}
```
"""

from __future__ import annotations

from ...base.diagnostics import Diagnostic

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

    from ..engine import LintContext

NAME = "compile-error"
PENALTY = 0
SEVERITY = "error"
NEEDS = "text"  # the engine hands every file its program's errors (ctx.compile_errors)


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    for error in ctx.compile_errors:
        yield Diagnostic(
            error.message,
            error.loc,
            help=error.help
            or "Shadertoy does not compile this: fix it first (`glslcheck check` prints the same "
            "error)",
            notes=list(error.notes),
        )
