"""The same pure expression is computed again in a function, with the same operand values.

## What it does
Reports a pure expression worth reusing (at least two operations, like the ray position
`ro + t * rd`; a call of a built-in, like `dot`, `normalize`, `length`, `mix`, or a cheap
one like `step` or `floor`, or of a pure user function that costs more than an add; or one
float or vector operation on
variables, like `d * invIntensity` or `light.center - position`, but not a sign change like
`-1.0 * n`) that a function evaluates again after an identical evaluation, when

* the first evaluation happens on every path to the second one (the same straight-line code,
  or an enclosing block: two occurrences in the two arms of an `if`/`else` or `?:` are not
  repeated), or both are parts of one test joined by `&&` and `||` (`mod(y, 2.0) == 0.0` and
  `mod(y, 2.0) == 1.0` on either side of an `||`: written twice in one condition),
* no variable it reads is written in between (an assignment, `++`/`--`, an `out` or `inout`
  argument, or any write in a loop around the second one but not the first; a global it reads
  is taken as written by any user function called in between; an assignment to a field of a
  struct it reads, `rec.normal = ...`, counts only when it reads that field or the whole
  struct), and
* it calls no built-in with an `out` parameter and only pure user functions (`in` parameters
  only, no global variable read or written, only pure functions called: `lenSq(v)`).

Expressions are compared by value, variables by the declaration they name: operands of `+` and
`*` in any order and grouping (not a matrix product), a float quotient as a product by the
inverse (`a / b * c` is `a * c / b`; integer division rounds, so not there), a component by its \
index (`v.x`, `v.r`),
`dot(a, b)` as its sum of products and a pure one-line user function by what it returns, so
`lenSq(dp.xy)` and `dp.x * dp.x + dp.y * dp.y` are the same value, and so are the two
`length(v)` in `length(v) * length(v)`. A one-operation value written again inside a longer
product chain counts there too: `a / b * a / b` is `((a / b) * a) / b` and computes `a / b`
twice (where its two factors stand side by side as written: `(d * d) / (k * k)` does not write
`d / k`). Code after a
`return` (or `break`, `continue`, `discard`) never runs and is not counted. One finding per
repeated value, at its second evaluation, listing every place it is computed (in the message,
and as notes: the JSON `notes`): the deduction counts one inefficient practice once. A repeated
value's repeated parts are not reported again; a part that is also repeated elsewhere at most
once (`sin(t)` at line 5 and inside `sin(t) * k` twice at line 6) joins the larger value's
finding. A value computed only inside expressions that loop-invariant reports, or once before
the loop and then only inside them, is left to that rule: hoisted out of the loop, it is
computed once (and reused).

## Why is this bad?
The course's coding standards: "Use the most efficient methods (-1 per inefficient/unnecessary
practices)", and the Lab 4 hint on the ray position: "How can we optimize this for repeated
use? Hint: don't reimplement the formula every time you want to use it...". Part 7 asks to
"remove redundant operations". Compilers often, but not always, merge repeated code; a local
variable also names the value, which is the comment the standards ask for.

## Example
```glsl
vec3 normal = normalize(ro + t * rd - center);
vec3 toLight = light.center - (ro + t * rd);
```

## Use instead
```glsl
vec3 position = ro + t * rd; // the surface point, computed once
vec3 normal = (position - center) / radius;
vec3 toLight = light.center - position;
```
"""

from __future__ import annotations

from ...base.diagnostics import Diagnostic
from ...frontend import syntax as A
from ...semantics.analysis import program_facts, written_variable
from ..fixes import Fix, Fixable
from ..fixes.build import local_for, node_text, replace_with_name
from . import loop_invariant
from ._text import at_lines, text

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

    from ..engine import LintContext

NAME = "repeated-expression"
PENALTY = 1
STANDARD = "efficiency"
SEVERITY = "warning"
NEEDS = "ast"


def _holder(fn, first) -> str | None:
    """The local variable `first` was stored in (`float d = first;` / `d = first;`), if any."""
    parent = fn.parent.get(id(first))
    if type(parent) is A.Declarator and parent.init is first:
        return parent.name
    if (
        type(parent) is A.Assignment
        and parent.op == "="
        and parent.value is first
        and type(parent.target) is A.Identifier
    ):
        return parent.target.name
    return None


def _holder_symbol(fn, first):
    parent = fn.parent.get(id(first))
    if type(parent) is A.Declarator:
        return fn.model.symbol_of(parent)
    if type(parent) is A.Assignment:
        return written_variable(fn.model, parent.target)[0]
    return None


_CANDIDATES = 64  # earlier occurrences tried as the one to reuse
_LEAVES = (A.Identifier, A.FloatLiteral, A.IntLiteral, A.BoolLiteral)


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    hoisted = ctx.config.enabled(loop_invariant.NAME)
    for fn in program_facts(ctx.model).in_file(ctx.path):
        inside = [n for n, _ in loop_invariant.invariant_places(fn)] if hoisted else []
        yield from _check_function(fn, ctx, inside)


def _within_chains(fn, groups: dict) -> dict[int, object]:
    """Values written again inside a `*`/`/` chain without being a part of its tree:
    `a / b * a / b` is `((a / b) * a) / b`, computing `a / b` twice, and `c * a / b` computes
    `a / b` once. A value of one operation counts where its two factors stand next to each other
    as written
    (`(d * d) / (i * i)` does not write `d / i`). For each such chain (innermost first; a chain
    holding one already counted does not count it again), the key of the value (one met
    elsewhere as a part of its own, `a / b`) gets the chain as one more place in its group;
    returns id(chain) -> that key."""
    found: dict[int, object] = {}
    wanted = [k for k in groups if k[0] == "*" and len(k[1]) == 2]  # one operation: two factors
    if not wanted:
        return found
    binaries = [m for m in fn.nodes if type(m) is A.Binary]
    for n in sorted(binaries, key=lambda m: fn.exit[id(m)]):
        written = fn.written_factors(n)
        if written is None or not fn.is_pure(n) or fn.is_dead(n):
            continue
        spine, keys = written
        for k in wanted:
            x, y = k[1]
            times, i = 0, 0
            while i + 2 <= len(
                keys
            ):  # non-overlapping pairs of the value's two factors, either order
                a, b = keys[i], keys[i + 1]
                if (a == x and b == y) or (a == y and b == x):
                    times, i = times + 1, i + 2
                else:
                    i += 1
            if not times:
                continue
            counted = sum(fn.key(m) == k or found.get(id(m)) == k for m in spine[1:])
            if times > counted + (fn.key(n) == k):
                found[id(n)] = k
                groups[k].append(n)
                groups[k].sort(key=lambda m: fn.exit[id(m)])
                break
    return found


def _check_function(fn, ctx: LintContext, hoisted: list) -> Iterator[Diagnostic]:
    """The findings of one function; a value computed only inside the expressions of `hoisted`
    (what loop-invariant reports: computed once before the loop, it is computed once), or first
    elsewhere and then only inside them (hoisted, it is that value, reused), is not."""
    groups: dict = {}
    targets = {id(n.target) for n in fn.nodes if type(n) is A.Assignment}
    for n in fn.nodes:
        if (
            type(n) in _LEAVES
        ):  # no operation: never worth reusing (half the nodes, skipped cheaply)
            continue
        if (
            isinstance(n, A.Expr)
            and id(n) not in targets
            and fn.worth_reusing(n)
            and fn.is_pure(n)
            and not fn.is_dead(n)
        ):
            groups.setdefault(fn.key(n), []).append(n)
    within = _within_chains(fn, groups)
    groups = {k: v for k, v in groups.items() if len(v) > 1}
    if not groups:
        return
    # a value's text: one place that computes it as a tree of its own (not inside a chain)
    sample = {k: next(n for n in occ if within.get(id(n)) != k) for k, occ in groups.items()}
    # Largest expressions first, so a repeated expression hides its repeated parts.
    order = sorted(groups.items(), key=lambda kv: -(fn.exit[id(kv[1][0])] - fn.enter[id(kv[1][0])]))
    covered: set[int] = set()
    values: list[
        list
    ] = []  # per repeated value: (place, key) of first, repeats..., parts merged in
    owner: dict[int, list] = {}  # id of a node inside a reported occurrence -> its value
    for k, occ in order:
        chains: dict[int, list] = {}  # id(first occurrence) -> the occurrences of that value
        for j, b in enumerate(occ):
            if id(b) in covered:
                continue
            operands = fn.operands(b)
            # The first _CANDIDATES occurrences only: the same for any real shader, linear (not
            # quadratic) for a generated file repeating one expression thousands of times.
            first = next(
                (
                    a
                    for a in occ[: min(j, _CANDIDATES)]
                    if (
                        fn.dominates(a, b)
                        or (id(b) in within and fn.contains(b, a))
                        or _one_test(fn, a, b)
                    )
                    and not fn.written_between(a, b, operands, reads=b)
                ),
                None,
            )
            if first is None:
                continue
            root = next((r for r, chain in chains.items() if first in chain), None)
            chain = chains.setdefault(
                root if root is not None else id(first), [first] if root is None else []
            )
            chain.append(b)
            covered.update(id(n) for n in b.walk())
        for chain in chains.values():
            # a repeated part of a value already reported (sin(t) in `sin(t) * k`, both
            # repeated) is the same inefficiency when at most one of its places is outside
            # that value: its places join that value's finding
            places = [(n, k) for n in chain]
            outside = [n for n in chain if id(n) not in owner]
            host = next((owner[id(n)] for n in chain if id(n) in owner), None)
            if host is not None and len(outside) <= 1:
                host.extend(p for p in places if p not in host)
                continue
            values.append(places)
            for n in chain:
                for m in n.walk():
                    owner.setdefault(id(m), places)
    values.sort(key=lambda places: fn.enter[id(places[1][0])])
    for places in values:
        (first, key), (b, _) = places[0], places[1]
        again = [n for n, _ in places if not fn.contains(first, n)]  # not the first or its parts
        if hoisted and again and all(any(fn.contains(h, n) for h in hoisted) for n in again):
            continue
        same = [n for n, k in places if k == key]
        parts: dict = {}  # repeated parts merged into this value: key -> their places
        for n, k in places:
            if k != key:
                parts.setdefault(k, []).append(n)
        holder = _holder(fn, first) if within.get(id(first)) != key else None
        sym = _holder_symbol(fn, first) if holder else None
        reuse = (
            holder and sym is not None and not fn.written_between(fn.parent[id(first)], b, [sym])
        )
        if reuse:
            fix = f"reuse '{holder}', which holds this value since line {first.loc.line}"
        else:
            fix = "compute it once into a local variable (named for what it is) and reuse that"
        edit = None
        if len(parts) == 0 and all(within.get(id(n)) != key for n in same):
            edit = _fix(ctx, fn, same, holder if reuse else None, sym)
        times = "twice" if len(same) == 2 else f"{len(same)} times"
        message = (
            f"'{text(sample[key])}' is computed {times}, with the same value, at {at_lines(same)}"
        )
        for k, where in parts.items():
            message += f"; its part '{text(sample[k])}' also at {at_lines(where)}"
        notes, seen = [], {(b.loc.line, b.loc.column)}
        for n, k in places:
            where = (n.loc.line, n.loc.column)
            if where not in seen:
                seen.add(where)
                what = (
                    "also computed here" if k == key else f"'{text(sample[k])}' also computed here"
                )
                notes.append(Diagnostic(what, n.loc, severity="note"))
        yield Fixable(message, b.loc, help=fix, notes=notes, fix=edit)


def _fix(ctx: LintContext, fn, same: list, holder: str | None, sym) -> Fix | None:
    """Every later computation of the value replaced by the variable that holds it: `holder`
    (still holding it at each of them), else a new local declared before the first's statement
    (`build.local_for`, named after what the expression reads)."""
    first, repeats = same[0], same[1:]
    if holder is not None:
        decl = fn.parent[id(first)]
        if any(fn.written_between(decl, b, [sym]) for b in repeats) or any(
            node_text(ctx, b) is None for b in repeats
        ):
            return None
        return Fix(
            f"reuse '{holder}'", ctx.path, tuple(replace_with_name(ctx, b, holder) for b in repeats)
        )
    found = local_for(ctx, fn, first, repeats)
    if found is None:
        return None
    name, edits = found
    return Fix(f"compute it once into '{name}'", ctx.path, tuple(edits))


def _one_test(fn, a, b) -> bool:
    """Whether `a` and then `b` are parts of one condition joined by `&&` and `||` (`x == 0.0 &&
    mod(y, 2.0) == 0.0 || x == 1.0 && mod(y, 2.0) == 1.0`): written twice in one test, which
    a TA reads as computed twice, though `||` may skip one of them."""
    if fn.exit[id(a)] >= fn.enter[id(b)]:
        return False
    up: dict[int, object] = {}
    n = fn.parent.get(id(a))
    while n is not None and isinstance(n, A.Expr):
        up[id(n)] = n
        n = fn.parent.get(id(n))
    n = fn.parent.get(id(b))
    while n is not None and id(n) not in up:
        if not isinstance(n, A.Expr) or type(n) is A.Ternary:
            return False
        n = fn.parent.get(id(n))
    if n is None or type(n) is not A.Binary or n.op not in ("&&", "||"):
        return False
    m = fn.parent.get(id(a))
    while m is not n:  # (no `?:` arm between the test and `a` either)
        if type(m) is A.Ternary:
            return False
        m = fn.parent.get(id(m))
    return True
