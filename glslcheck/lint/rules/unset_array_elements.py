"""A loop reads elements of a local array that are never set.

## What it does
Reports a counting `for` loop (`for (int i = 0; i < N; i++)`, or counting down from `N - 1`)
that reads `a[i]` of a local array declared without an initializer, when some of the indices the
loop visits are never set anywhere in the function: every write to the array sets one element at
a constant index (`a[1] = ...`, `a[0].center = ...`, `a[2]` passed as an `out` argument), and
the loop goes past them (`Sphere objects[5]` with `objects[0]` and `objects[1]` set, looped over
all five). The array may reach the loop as an `in` parameter of a function called from one place
only (`hitWorld(spheres, ray)` looping over the `spheres` mainImage set). A write at an index
that is not a constant, to the whole array, or an initializer, makes the elements unknown and
the rule silent, as does a loop left by a `break`, `continue` or `return` that tests the loop's
variable (it may stop before the unset elements).

## Why is this bad?
The course's coding standards: "Use the most efficient methods (-1 per inefficient/unnecessary
practices)". Each iteration over an element never set is work done for nothing (a ray tested
against spheres that were never placed, a light that was never lit), and its value is undefined
(GLSL ES 3.00, section 4.3: a local variable without an initializer has an undefined value):
what those iterations add depends on the driver.

## Example
```glsl
const int MAX_LIGHTS = 4;
PointLight lights[MAX_LIGHTS];
initLight(lights[0], vec3(2.0, 2.0, 0.0), 10.0);
initLight(lights[1], vec3(-2.0, 1.0, 0.0), 5.0);
for (int i = 0; i < MAX_LIGHTS; i++)
{
    color += shade(lights[i], position, normal);
}
```

## Use instead
```glsl
const int LIGHTS = 2; // the lights the scene sets
PointLight lights[LIGHTS];
initLight(lights[0], vec3(2.0, 2.0, 0.0), 10.0);
initLight(lights[1], vec3(-2.0, 1.0, 0.0), 5.0);
for (int i = 0; i < LIGHTS; i++)
{
    color += shade(lights[i], position, normal);
}
```
"""

from __future__ import annotations

from ...base.diagnostics import Diagnostic
from ...frontend import syntax as A
from ...language import glsl_types as T
from ...semantics.analysis import param_directions, program_facts, written_variable
from ...semantics.hazards import loop_ranges

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator
    from typing import Any

    from ..engine import LintContext

NAME = "unset-array-elements"
PENALTY = 1
STANDARD = "efficiency"
SEVERITY = "warning"
NEEDS = "ast"

_EXITS = (A.Break, A.Continue, A.Return)


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    model = ctx.model
    if model is None:
        return
    facts = program_facts(model)
    for fn in facts.in_file(ctx.path):
        fors = [lp for lp in fn.loops if type(lp) is A.For and not fn.is_dead(lp)]
        ranges = loop_ranges(model, fors)
        for loop in fors:
            index = _loop_variable(model, loop)
            if index is None or id(index) not in ranges:
                continue
            lo, hi = ranges[id(index)]
            if _exits_on(model, loop.body, index):
                continue
            reported: set[int] = set()
            for read in _element_reads(model, loop.body, index):
                array = model.symbol_of(read.base)
                if array is None or id(array) in reported:
                    continue
                home, local = _local_array(facts, fn, array)
                size = _local_array_size(local, home) if local is not None else 0
                set_ = _set_indices(home, local) if size else None
                if set_ is None:
                    continue
                unset = [k for k in range(int(lo), int(hi) + 1) if 0 <= k < size and k not in set_]
                if not unset:
                    continue
                reported.add(id(array))
                passed = (
                    f" (in {home.definition.proto.name}, which passes it as '{array.name}')"
                    if local is not array
                    else ""
                )
                yield Diagnostic(
                    f"the loop reads '{array.name}[{index.name}]' for {index.name} = "
                    f"{int(lo)}..{int(hi)}, but {_which(local.name, sorted(set_))}{passed}: "
                    f"the iterations over {_span(local.name, unset)} work on undefined values, "
                    "for nothing",
                    loop.loc,
                    help=f"loop over the {len(set_)} element{'s' * (len(set_) != 1)} "
                    f"{home.definition.proto.name} sets, or set the others",
                    notes=[Diagnostic("read here", read.loc, severity="note")],
                )


def _loop_variable(model, loop: A.For) -> Any:
    """The symbol a `for` loop declares and counts with, else None."""
    init = loop.init
    if type(init) is not A.DeclarationStatement or type(init.decl) is not A.VariableDeclaration:
        return None
    declarators = init.decl.declarators
    return model.symbol_of(declarators[0]) if len(declarators) == 1 else None


def _tests(model, e: Any, index) -> bool:
    """Whether `e` uses the loop's variable as a value (`i >= n`), not only to pick an element
    (`hit(spheres[i])`)."""
    picks = {id(n.index) for n in e.walk() if type(n) is A.Index}
    return any(
        type(n) is A.Identifier and id(n) not in picks and model.symbol_of(n) is index
        for n in e.walk()
    )


def _exits_on(model, body: Any, index) -> bool:
    """Whether the body leaves the loop (or skips an iteration) under a test of its variable:
    it may stop before the elements it would read."""
    return any(
        type(node) is A.If
        and _tests(model, node.cond, index)
        and any(type(n) in _EXITS for n in node.walk())
        for node in body.walk()
    )


def _element_reads(model, body: Any, index) -> Iterator[A.Index]:
    """`a[i]` in the body, `i` the loop's variable, that read the element (not an l-value)."""
    written = set()
    for node in body.walk():
        if type(node) is A.Assignment:
            target = node.target
            while isinstance(target, (A.Field, A.Index)):
                written.add(id(target))
                target = target.base
    for node in body.walk():
        if (
            type(node) is A.Index
            and id(node) not in written
            and type(node.base) is A.Identifier
            and type(node.index) is A.Identifier
            and model.symbol_of(node.index) is index
        ):
            yield node


def _local_array(facts, fn, array, depth: int = 0) -> tuple[Any, Any]:
    """(the facts of the function that declares it, the local array) that `array` is: itself,
    or the array an `in` parameter holds, passed from the one place the function is called
    (`hitWorld(spheres, ...)` of a `Sphere spheres[4]` declared in mainImage); (fn, None)
    when it is neither."""
    while array.kind == "param" and depth < 8:
        passed = facts.argument(fn, array)
        if passed is None or type(passed[1]) is not A.Identifier:
            return fn, None
        fn, array = passed[0], fn.model.symbol_of(passed[1])
        if array is None:
            return fn, None
        depth += 1
    return (fn, array) if array.kind == "local" else (fn, None)


def _local_array_size(array, fn) -> int:
    """The constant size of a local array declared in the function without an initializer,
    else 0."""
    t = array.type
    if array.kind != "local" or not isinstance(t, T.ArrayType) or not t.array_size:
        return 0
    writes = fn.writes_to(array)
    if any(w.kind == "init" for w in writes) or not any(w.kind == "decl" for w in writes):
        return 0  # initialized, or declared elsewhere
    return int(t.array_size)


def _set_indices(fn, array) -> set[int] | None:
    """The constant indices at which the function writes the array's elements; None when a
    write may set others (an index that is not a constant, the whole array)."""
    model = fn.model
    found: set[int] = set()
    for w in fn.writes_to(array):
        if w.kind == "decl":
            continue
        if w.kind == "out":
            targets = [
                a
                for a, d in zip(w.node.args, param_directions(model.call_target(w.node)))
                if d in ("out", "inout") and written_variable(model, a)[0] is array
            ]
        elif type(w.node) is A.Assignment:
            targets = [w.node.target]
        else:  # ++ / --
            targets = [w.node.operand]
        for target in targets:
            k = _element_index(model, target, array)
            if k is None:
                return None
            found.add(k)
    return found


def _element_index(model, target: Any, array) -> int | None:
    """The constant index of the element of `array` an l-value writes, else None."""
    while isinstance(target, (A.Field, A.Index)):
        if (
            type(target) is A.Index
            and type(target.base) is A.Identifier
            and model.symbol_of(target.base) is array
        ):
            k = model.const_value(target.index)
            return k if isinstance(k, int) and not isinstance(k, bool) else None
        target = target.base
    return None


def _which(name: str, indices: list[int]) -> str:
    if not indices:
        return f"no element of '{name}' is set"
    listed = " and ".join(f"'{name}[{k}]'" for k in indices) if len(indices) == 2 else None
    return f"only {listed or _span(name, indices)} {'is' if len(indices) == 1 else 'are'} set"


def _span(name: str, indices: list[int]) -> str:
    """`a[2]`, `a[2..4]` (consecutive), or `a[2], a[4]`."""
    if len(indices) == 1:
        return f"'{name}[{indices[0]}]'"
    if indices == list(range(indices[0], indices[-1] + 1)):
        return f"'{name}[{indices[0]}..{indices[-1]}]'"
    return ", ".join(f"'{name}[{k}]'" for k in indices)
