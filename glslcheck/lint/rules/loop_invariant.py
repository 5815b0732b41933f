"""An expression in a loop computes the same value on every iteration.

## What it does
Reports an expression worth computing once (at least two operations, a call of a built-in
costlier than an add or of a pure user function, or in the loop body one float or vector
operation such as the ambient term `ambientIntensity * ambientColor`) in the condition, body
or step of a `for`, `while` or `do` loop that depends on nothing the loop changes: it reads no
variable written anywhere in the loop (the loop counter included), no variable declared in the
loop, calls only pure user functions and no built-in with an `out` parameter, and reads no
global variable when the loop calls a user function (which could write it). An argument of a
pure user function for a parameter its result never depends on (a hit record it only fills in
its own copy of) does not count: `hit(ray, rec, spheres[0])` in a loop that writes `rec` still
tests the same sphere every time. One operation in a
loop bound (`i < n - 1`) is idiomatic and not reported; nor is code after a `return` or `break`.
A call of a user function with `out` parameters whose results depend only on its inputs (it
reads and writes no global, nor an `out` parameter before writing it), none of which the loop
changes, is reported too: it computes the same outputs on every iteration (an anti-aliasing
loop that calls `calcRay(dir, origin, viewport)` with a viewport computed before it traces the
same ray every time).
A value a helper function computes from its `in` parameters alone, uniforms aside (one worth
reusing that takes a square root, a transcendental function or a division, on every call of
the helper: a filter's `fragCoord / iResolution.xy` in the sample helper of each tap) is
reported in the helper when a loop calls it with the same arguments for those parameters on
every iteration (the lighting helper called per light computes the view vector from the same
eye and surface point each time), unless every argument is the same (then the call itself is).
So is one a helper computes on every step of a loop that calls it through another function
(a march loop calls `scene(p, time)`, which calls `shape(p, time)`: its `sin(time)` is the same
at every step), when that function passes it arguments the loop does not change.
Only the largest such expression is reported, for the outermost loop it does not depend on:
one finding per run of adjacent statements of the loop holding such work, naming every value
to compute before it and every place it is computed (hoisting them is one fix: `u` and `v` of
an anti-aliasing loop that jitters by a random value of the pixel alone are one finding).

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
from ...semantics.analysis import (
    ignored_parameters,
    param_directions,
    program_facts,
    pure_function,
    unassigned_reads,
)
from ...semantics.model import Symbol
from ..fixes import Fix, Fixable
from ..fixes.build import declare_before, name_hint, node_text, replace_with_name, statement_of
from ._helper_values import call_sites, helper_values, invariant_arguments
from ._text import at_lines, text

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

    from ..engine import LintContext

NAME = "loop-invariant"
PENALTY = 1
STANDARD = "efficiency"
SEVERITY = "warning"
NEEDS = "ast"

_LOOP_WORD: dict[type, str] = {A.For: "for", A.While: "while", A.DoWhile: "do-while"}


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    for fn in program_facts(ctx.model).in_file(ctx.path):
        yield from _check_function(fn, ctx)
        yield from _helper_in_loop(fn)


def _helper_in_loop(fn) -> Iterator[Diagnostic]:
    """A value the helper `fn` computes from `in` parameters alone (_helper_values), where a
    call in a loop passes the same arguments for them on every iteration (and not for all its
    parameters: then the call itself is the same every time, reported where it is)."""
    sites = [(caller, call) for caller, call in call_sites(fn) if caller.enclosing_loops(call)]
    if not sites:
        yield from _helper_through_call(fn)
        return
    values = helper_values(fn)
    every = [i for i, param in enumerate(fn.symbol.params) if param[2] != "out"]
    for value, indexes in values:
        for caller, call in sites:
            if caller.is_dead(call):
                continue
            loop = next(
                (
                    lp
                    for lp in caller.enclosing_loops(call)
                    if caller.contains(lp.body, call)
                    and invariant_arguments(caller, call, lp, indexes)
                ),
                None,
            )
            if loop is None or invariant_arguments(caller, call, loop, every):
                continue
            named = [fn.definition.proto.params[i].name for i in indexes]
            names = ", ".join(named[:-1]) + " and " + named[-1] if len(named) > 1 else named[0]
            yield Diagnostic(
                f"'{text(value)}' in {fn.definition.proto.name} has the same value on every "
                f"iteration of the {_LOOP_WORD[type(loop)]} loop at line {loop.loc.line} that "
                f"calls it (line {call.loc.line}): the loop passes the same {names}",
                value.loc,
                help="compute it once before the loop and pass it in as a parameter",
                notes=[Diagnostic("called here, in the loop", call.loc, severity="note")],
            )


def _helper_through_call(fn) -> Iterator[Diagnostic]:
    """A value of the helper `fn` (_helper_values) whose parameters come, through a function
    `g` that calls `fn` outside any loop, from arguments a loop passes `g` unchanged: a march
    loop calls `scene(p, time)` at every step, and `scene` calls `shape(p, time)`, whose
    `sin(time)` is the same at every step."""
    if not helper_values(fn):
        return
    reported: set[int] = set()
    for g, inner in call_sites(fn):
        if g.enclosing_loops(inner) or g.is_dead(inner) or g.symbol is None:
            continue
        for caller, outer in call_sites(g):
            loop = next(
                (lp for lp in caller.enclosing_loops(outer) if caller.contains(lp.body, outer)),
                None,
            )
            if loop is None or caller.is_dead(outer):
                continue
            fixed = _fixed_through(g, inner, caller, outer, loop)
            if not fixed:
                continue
            for value, indexes in helper_values(fn, frozenset(fixed)):
                if id(value) in reported:
                    continue
                reported.add(id(value))
                named = [fn.definition.proto.params[i].name for i in indexes]
                names = ", ".join(named[:-1]) + " and " + named[-1] if len(named) > 1 else named[0]
                yield Diagnostic(
                    f"'{text(value)}' in {fn.definition.proto.name} has the same value on every "
                    f"iteration of the {_LOOP_WORD[type(loop)]} loop at line {loop.loc.line}, "
                    f"which calls {g.definition.proto.name} (line {outer.loc.line}), which calls "
                    f"{fn.definition.proto.name} (line {inner.loc.line}) with the same {names} "
                    "each time",
                    value.loc,
                    help="compute it once before the loop and pass it in as a parameter",
                    notes=[
                        Diagnostic("called here", inner.loc, severity="note"),
                        Diagnostic("called here, in the loop", outer.loc, severity="note"),
                    ],
                )


def _fixed_through(g, inner: A.Call, caller, outer: A.Call, loop) -> set[int]:
    """The indexes of the parameters of the call `inner` (in `g`) whose arguments are the same
    on every iteration of `loop` that calls `g` (`outer`, in `caller`): pure, reading only
    constants, uniforms and `in` parameters of `g` it never writes whose arguments at `outer`
    the loop does not change."""
    params = [g.model.symbol_of(p) for p in g.definition.proto.params]
    same = {
        id(p)
        for i, p in enumerate(params)
        if p is not None
        and g.symbol.params[i][2] == "in"
        and not g.writes_to(p)
        and invariant_arguments(caller, outer, loop, [i])
    }
    out: set[int] = set()
    for j, arg in enumerate(inner.args):
        if not g.is_pure(arg):
            continue
        if all(
            id(sym) in same
            or sym.kind == "uniform"
            or (sym.kind == "global" and sym.qualifier == "const")
            for sym in g.operands(arg)
        ):
            out.add(j)
    return out


def invariant_places(fn) -> list[tuple[A.Expr, A.Node]]:
    """(expression, loop) for each expression this rule reports in the function `fn` (the
    largest invariant ones, each for the outermost loop it does not depend on), in source
    order; computed once per function (repeated-expression asks too)."""
    cached = fn.__dict__.get("_invariant_places")
    if cached is not None:
        return cached
    found = fn.__dict__["_invariant_places"] = _invariant_places(fn)
    return found


def _invariant_places(fn) -> list[tuple[A.Expr, A.Node]]:
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
            ops = _value_operands(fn, n)
            if any(id(s) in written for s in ops):
                continue
            if calls_user and any(s.kind == "global" and s.qualifier != "const" for s in ops):
                continue
            span = (fn.enter[id(n)], fn.exit[id(n)])
            reported_spans.append(span)
            skip_until = span[1]
            found.append((n, loop))
        for call in fn.calls:  # a call whose outputs are the same on every iteration
            e = enter[id(call)]
            if not lo < e < hi or any(a <= e <= b for a, b in reported_spans):
                continue
            if fn.contains(loop.body, call) and _same_outputs(fn, call, written, calls_user):
                reported_spans.append((e, fn.exit[id(call)]))
                found.append((call, loop))
    found.sort(key=lambda pair: fn.enter[id(pair[0])])
    return found


def _value_operands(fn, e) -> frozenset:
    """The variables `e`'s value depends on: what it reads (`fn.operands`) but the arguments a
    user function it calls never lets reach its result (`ignored_parameters`: the record a
    `bool hit(..., in Hit rec)` only fills in its own copy of)."""
    lo, hi = fn.enter[id(e)], fn.exit[id(e)]
    if not any(lo <= p <= hi for p in fn.user_calls):
        return fn.operands(e)
    if type(e) is A.Call:
        target = fn.model.call_target(e)
        ignored = ignored_parameters(fn.model, target) if isinstance(target, Symbol) else ()
        if ignored:
            args = [a for i, a in enumerate(e.args) if i not in ignored]
            return frozenset().union(*(_value_operands(fn, a) for a in args))
    return frozenset().union(*(_value_operands(fn, c) for c in e.children()))


def _same_outputs(fn, call, written: set[int], calls_user: bool) -> bool:
    """A call of a user function with `out` parameters (`calcRay(dir, origin, viewport)`) whose
    results depend only on its inputs (`pure_function(..., outputs=True)`), none of which the
    loop changes: it computes the same outputs on every iteration."""
    target = fn.model.call_target(call)
    if not isinstance(target, Symbol) or fn.is_dead(call):
        return False
    directions = param_directions(target)
    if "out" not in directions or not pure_function(fn.model, target, outputs=True):
        return False
    if any(u.kind == "out-parameter" for u in unassigned_reads(fn.model, target.node)):
        return False  # it reads an undefined out value: the outputs may differ
    for arg, d in zip(call.args, directions):
        if d == "out":
            continue
        if not fn.is_pure(arg):
            return False
        ops = fn.operands(arg)
        if any(id(s) in written for s in ops):
            return False
        if calls_user and any(s.kind == "global" and s.qualifier != "const" for s in ops):
            return False
    return True


def _statement(fn, n) -> tuple[int, int]:
    """(id of the block, index in it) of the statement holding `n`; (0, -1) outside a block."""
    child, up = n, fn.parent.get(id(n))
    while up is not None and type(up) is not A.Compound:
        child, up = up, fn.parent.get(id(up))
    if up is None:
        return 0, -1
    return id(up), next(i for i, st in enumerate(up.stmts) if st is child)


def _has_outputs(fn, n) -> bool:
    return type(n) is A.Call and "out" in param_directions(fn.model.call_target(n))


def _check_function(fn, ctx: LintContext) -> Iterator[Diagnostic]:
    # one finding per run of adjacent statements of a loop holding invariant work (the `u` and
    # `v` of a sample loop: one block to move before it), every value and place listed
    values: dict = {}  # (loop, key) -> places, in source order
    for n, loop in invariant_places(fn):
        values.setdefault((id(loop), fn.key(n)), (loop, []))[1].append(n)
    runs: list[tuple] = []  # (loop, block, last index, [places of each value])
    for loop, places in sorted(values.values(), key=lambda lp: fn.enter[id(lp[1][0])]):
        block, index = _statement(fn, places[0])
        if runs and runs[-1][0] is loop and runs[-1][1] == block and 0 <= index - runs[-1][2] <= 1:
            last = runs[-1]
            runs[-1] = (loop, block, index, last[3] + [places])
        else:
            runs.append((loop, block, index, [places]))
    for loop, _, _, group in runs:
        first = group[0][0]
        where = f"{_LOOP_WORD[type(loop)]} loop at line {loop.loc.line}"
        places = [p for ps in group for p in ps]
        if len(group) == 1 and _has_outputs(fn, first):
            message = (
                f"'{text(first)}' computes the same outputs on every iteration of the {where}: "
                "none of its inputs changes in the loop"
            )
            help_ = "call it once before the loop"
        elif len(group) == 1:
            ps = group[0]
            times = "" if len(ps) == 1 else f" (computed {len(ps)} times in it, at {at_lines(ps)})"
            message = f"'{text(first)}' has the same value on every iteration of the {where}{times}"
            help_ = "compute it once before the loop, in a local variable, and use that inside"
        else:
            named = [f"'{text(ps[0])}' ({at_lines(ps)})" for ps in group]
            message = (
                f"{len(group)} expressions give the same value on every iteration of the "
                f"{where}: " + ", ".join(named[:-1]) + f" and {named[-1]}"
            )
            help_ = "compute them once before the loop, in local variables, and use those inside"
        # one value computed in the loop: the fix computes it once before the loop
        fix = (
            _fix(ctx, fn, loop, group[0])
            if len(group) == 1 and not _has_outputs(fn, first)
            else None
        )
        yield Fixable(
            message,
            first.loc,
            help=help_,
            fix=fix,
            notes=[
                Diagnostic(
                    "also computed here" if fn.key(p) == fn.key(first) else f"'{text(p)}' here",
                    p.loc,
                    severity="note",
                )
                for p in places[1:]
            ],
        )


def _fix(ctx: LintContext, fn, loop, places: list) -> Fix | None:
    """The value computed once into a local declared before the loop (a statement of a block),
    read at every place the loop computed it."""
    value = node_text(ctx, places[0])
    found = statement_of(fn, loop)
    if value is None or found is None or found[0] is not loop:
        return None
    if any(node_text(ctx, p) is None for p in places):
        return None
    declared = declare_before(
        ctx, fn, loop, fn.model.type_of(places[0]), value, name_hint(places[0]), places
    )
    if declared is None:
        return None
    name, insert = declared
    return Fix(
        f"compute it once before the loop, into '{name}'",
        ctx.path,
        (insert, *(replace_with_name(ctx, p, name) for p in places)),
    )
