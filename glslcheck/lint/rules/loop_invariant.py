"""An expression in a loop computes the same value on every iteration.

## What it does
Reports an expression worth computing once (at least two operations, a call of a built-in
costlier than an add or of a pure user function, or in the loop body one float or vector
operation such as the ambient term `ambientIntensity * ambientColor`) in the condition, body
or step of a `for`, `while` or `do` loop that depends on nothing the loop changes: it reads no
variable written anywhere in the loop (the loop counter included), no variable declared in the
loop, calls only pure user functions and no built-in with an `out` parameter, and reads no
global variable when the loop calls a user function (which could write it). One operation in a
loop bound (`i < n - 1`) is idiomatic and not reported; nor is code after a `return` or `break`.
Only the largest such expression is reported, for the outermost loop it does not depend on:
one finding per loop, naming every value to compute before it and every place it is computed
(hoisting them is one fix: `u` and `v` of an anti-aliasing loop that jitters by a random value
of the pixel alone are one finding).

## Why is this bad?
The course's coding standards: "Use the most efficient methods (-1 per inefficient/unnecessary
practices)"; Lab 4 part 6 sums over lights, and part 7 asks to "remove redundant operations".
Work that does not depend on the light is done once per light instead of once per pixel.

## Example
```glsl
for (int i = 0; i < kLightCount; ++i)
{
    vec3 viewDir = normalize(eye - position);
    color += shade(lights[i], position, normal, viewDir);
}
```

## Use instead
```glsl
vec3 viewDir = normalize(eye - position); // the same for every light
for (int i = 0; i < kLightCount; ++i)
{
    color += shade(lights[i], position, normal, viewDir);
}
```
"""

from __future__ import annotations

from ...base.diagnostics import Diagnostic
from ...frontend import syntax as A
from ...semantics.analysis import program_facts
from ._text import text

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

    from ..engine import LintContext

NAME = "loop-invariant"
PENALTY = 1
SEVERITY = "warning"
NEEDS = "ast"

_LOOP_WORD = {A.For: "for", A.While: "while", A.DoWhile: "do-while"}


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    for fn in program_facts(ctx.model).in_file(ctx.path):
        yield from _check_function(fn)


def invariant_places(fn) -> list[tuple[A.Expr, A.Node]]:
    """(expression, loop) for each expression this rule reports in the function `fn` (the
    largest invariant ones, each for the outermost loop it does not depend on), in source
    order."""
    reported_spans: list[tuple[int, int]] = []
    targets = {id(n.target) for n in fn.nodes if type(n) is A.Assignment}
    found = []
    nodes = fn.nodes  # in execution order: a loop's nodes follow it
    index = {id(n): i for i, n in enumerate(nodes)} if fn.loops else {}
    enter, leaves = fn.enter, A.LEAF_CLASSES
    for loop in fn.loops:
        lo, hi = fn.enter[id(loop)], fn.exit[id(loop)]
        written = {id(w.symbol) for ws in fn.writes.values() for w in ws if lo < w.pos < hi}
        calls_user = any(lo < p < hi for p in fn.user_calls)
        parts = [p for p in (loop.cond, loop.body, getattr(loop, "step", None)) if p is not None]
        spans = [(fn.enter[id(p)], fn.exit[id(p)]) for p in parts]
        skip_until = 0
        first = index.get(id(loop))  # None when the walk gave up (absurd nesting: no nodes)
        for i in range(len(nodes) if first is None else first + 1, len(nodes)):
            n = nodes[i]
            e = enter[id(n)]
            if e >= hi:
                break  # past the loop
            # the cheap tests first (a name or literal is never worth hoisting)
            if e < skip_until or type(n) in leaves or not isinstance(n, A.Expr) or id(n) in targets:
                continue
            x = fn.exit[id(n)]
            if not any(a <= e and x <= b for a, b in spans):
                continue  # the for-init runs once
            if any(a <= e <= b for a, b in reported_spans):
                continue
            if not (fn.worth_reusing(n) and fn.is_pure(n)) or fn.is_dead(n):
                continue
            if not fn.is_nontrivial(n) and not fn.contains(loop.body, n):
                continue  # a bound like `i < n - 1`: one operation, idiomatic, hoisted by compilers
            ops = fn.operands(n)
            if any(id(s) in written for s in ops):
                continue
            if calls_user and any(s.kind == "global" and s.qualifier != "const" for s in ops):
                continue
            span = (fn.enter[id(n)], fn.exit[id(n)])
            reported_spans.append(span)
            skip_until = span[1]
            found.append((n, loop))
    found.sort(key=lambda pair: fn.enter[id(pair[0])])
    return found


def _lines(places) -> str:
    lines = sorted({p.loc.line for p in places})
    if len(lines) == 1:
        return f"line {lines[0]}"
    return "lines " + ", ".join(map(str, lines[:-1])) + f" and {lines[-1]}"


def _check_function(fn) -> Iterator[Diagnostic]:
    loops: dict = {}  # one finding per loop: every invariant value in it, all its places listed
    for n, loop in invariant_places(fn):
        loops.setdefault(id(loop), (loop, {}))[1].setdefault(fn.key(n), []).append(n)
    for loop, values in loops.values():
        places = [n for ns in values.values() for n in ns]
        first = places[0]
        where = f"{_LOOP_WORD[type(loop)]} loop at line {loop.loc.line}"
        if len(values) == 1:
            times = (
                ""
                if len(places) == 1
                else f" (computed {len(places)} times in it, at {_lines(places)})"
            )
            message = f"'{text(first)}' has the same value on every iteration of the {where}{times}"
            help_ = "compute it once before the loop, in a local variable, and use that inside"
        else:
            named = [f"'{text(ns[0])}' ({_lines(ns)})" for ns in values.values()]
            message = (
                f"{len(values)} expressions give the same value on every iteration of the "
                f"{where}: " + ", ".join(named[:-1]) + f" and {named[-1]}"
            )
            help_ = "compute them once before the loop, in local variables, and use those inside"
        yield Diagnostic(
            message,
            first.loc,
            help=help_,
            notes=[
                Diagnostic(
                    "also computed here" if fn.key(p) == fn.key(first) else f"'{text(p)}' here",
                    p.loc,
                    severity="note",
                )
                for p in places[1:]
            ],
        )
