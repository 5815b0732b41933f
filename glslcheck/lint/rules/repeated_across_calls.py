"""A helper computes the same value in each of several calls that pass it the same arguments.

## What it does
Reports a value a helper function computes from its `in` parameters alone (an expression worth
reusing, as `repeated-expression` means it, that takes a square root, a transcendental function
or a division: `normalize(eye - position)`, `pow(k, shininess)`, `(p - c) / r`, or a user
function that does (a dot product is too cheap to pass around); pure, reading only parameters
the helper never writes (and uniforms), computed on every call: not in a branch or a loop of the
helper, and not the value the helper returns, which makes the calls themselves the repeated
value) when a function calls the helper two or more times, each call on every path to the next,
with the same arguments for those parameters and nothing they read written in between: the
lighting helper called once per light computes the view vector once per light, from the same eye
and surface point. One finding per value, at the value, naming the calls.
Calls that pass the same value for every argument are not reported here: the call itself is
then the repeated value (`repeated-expression`'s, for a pure function).
A call in a loop that gives the helper the same arguments on every iteration is
`loop-invariant`'s.

## Why is this bad?
The course's coding standards: "Use the most efficient methods (-1 per inefficient/unnecessary
practices)"; Lab 4 part 6 sums over lights, and part 7 asks to "remove redundant operations".
Work that does not depend on the light is done once per light instead of once per pixel.

## Example
```glsl
vec3 shade(in Light light, in vec3 p, in vec3 n, in vec3 eye)
{
    vec3 view = normalize(eye - p);
    ...
}
color = shade(light1, p, n, eye) + shade(light2, p, n, eye);
```

## Use instead
```glsl
vec3 shade(in Light light, in vec3 p, in vec3 n, in vec3 view)
{
    ...
}
vec3 view = normalize(eye - p); // the same for every light
color = shade(light1, p, n, view) + shade(light2, p, n, view);
```
"""

from __future__ import annotations

from ...base.diagnostics import Diagnostic
from ...semantics.analysis import program_facts
from ._helper_values import call_sites, helper_values, same_arguments
from ._text import text

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

    from ..engine import LintContext

NAME = "repeated-across-calls"
PENALTY = 1
STANDARD = "efficiency"
SEVERITY = "warning"
NEEDS = "ast"


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    for fn in program_facts(ctx.model).in_file(ctx.path):
        sites = call_sites(fn)  # (cached for the program) the cheap test first
        if len(sites) < 2:
            continue
        values = helper_values(fn)
        if not values or fn.symbol is None:
            continue
        every = [i for i, param in enumerate(fn.symbol.params) if param[2] != "out"]
        for value, indexes in values:
            for caller, calls in _groups(sites, indexes):
                if all(same_arguments(caller, a, b, every) for a, b in zip(calls, calls[1:])):
                    continue  # every argument the same: the calls themselves repeat
                names = [fn.definition.proto.params[i].name or "?" for i in indexes]
                lines = [str(n) for n in sorted({c.loc.line for c in calls})]
                at = f"line {lines[0]}" if len(lines) == 1 else f"lines {_list(lines)}"
                yield Diagnostic(
                    f"'{text(value)}' has the same value in each of the {len(calls)} calls of "
                    f"{fn.definition.proto.name} at {at} (the same {_list(names)}): it is "
                    f"computed {len(calls)} times",
                    value.loc,
                    help="compute it once in the caller and pass it in as a parameter",
                    notes=[Diagnostic("called here", c.loc, severity="note") for c in calls],
                )


def _groups(sites, indexes: list[int]):
    """(caller, calls) of each run of two or more calls in one function that pass the same
    arguments for `indexes` (each the first's, on every path after it)."""
    by_caller: dict[int, tuple] = {}
    for caller, call in sites:
        by_caller.setdefault(id(caller), (caller, []))[1].append(call)
    for caller, calls in by_caller.values():
        calls.sort(key=lambda c: caller.enter[id(c)])
        used: set[int] = set()
        for i, first in enumerate(calls):
            if id(first) in used or caller.is_dead(first):
                continue
            group = [first]
            for then in calls[i + 1 :]:
                if id(then) not in used and same_arguments(caller, group[-1], then, indexes):
                    group.append(then)
            if len(group) >= 2:
                used.update(id(c) for c in group)
                yield caller, group


def _list(names: list[str]) -> str:
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + f" and {names[-1]}"
