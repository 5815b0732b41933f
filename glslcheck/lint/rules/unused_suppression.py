"""A `glslcheck: ignore[...]` comment that silences nothing, or that the linter cannot read.

## What it does
Reports a suppression comment
* whose rule had no finding on that line (`ignore[...]`) or in the file (`ignore-file[...]`),
* that names no rule (a typo such as `ignore[missing-coment]`), or
* that is not a directive glslcheck knows (`glslcheck: skip[...]`, `ignore` without rule names).

A suppression for a rule that did not run (left out by `--select`/`--ignore` or configuration,
or an AST rule on a file without a parse tree) is not reported: it may well be needed.
Silence this rule itself with `glslcheck: ignore-file[unused-suppression]`.

## Why is this bad?
A stale suppression hides the next real finding on its line, and a misspelt one silently
suppresses nothing while looking as if it did.

## Example
```glsl
// add the ambient term
col += ambient; // glslcheck: ignore[missing-comment]
```

## Use instead
```glsl
// add the ambient term
col += ambient;
```
"""

from __future__ import annotations

from ...base.diagnostics import Diagnostic

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

    from ..engine import LintContext

NAME = "unused-suppression"
PENALTY = 0
SEVERITY = "note"
NEEDS = "suppressions"


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    for s in ctx.suppressions:
        if s.problem is not None:
            yield Diagnostic(
                f"glslcheck cannot read this directive: {s.problem}",
                s.loc,
                help="write `glslcheck: ignore[rule-name]` or `glslcheck: ignore-file[rule-name]`",
            )
            continue
        where = "in this file" if s.file_wide else "on this line"
        for name in s.names:
            if name not in ctx.known_rules:
                import difflib  # only for a misspelt name: not at every start-up

                close = difflib.get_close_matches(name, sorted(ctx.known_rules), n=1)
                hint = f"did you mean `{close[0]}`? " if close else ""
                yield Diagnostic(
                    f"the suppression names `{name}`, which is no glslcheck rule",
                    s.loc,
                    help=f"{hint}`glslcheck rule --all` lists the rules",
                )
            elif name in ctx.rules_run and name not in s.used:
                yield Diagnostic(
                    f"unused suppression: `{name}` has no finding {where}",
                    s.loc,
                    help="remove the suppression",
                )
