"""Nested loops test every cell of a grid for each pixel.

## What it does
Reports a loop nested in another (a row loop and a column loop) whose body compares the
pixel's 2D position with a position made from the loop counters: `uv.x > leftBound` with
`leftBound = float(i) / float(rows)`, `distance(center, uv)` with `center = vec2(X * float(j),
Y * float(i))`, `step(rad, distance(vec2(50.0 * i + 25.0, ...), fragCoord))`, or a helper
called with both (`square(uv, vec2(size * float(j), ...))` whose body compares them). Every
pixel then runs rows x columns iterations to find or draw the cell it lies in, which
`floor(uv * vec2(columns, rows))` gives at once (its parity, `fract` of it, the distance to
its centre: each computed once).

The pixel's position is a `vec2` (or a component of one) the loops never write, read on one
side; the cell's is computed from the counters alone with + - * / and constructors (through
locals the loops write so), read on the other: a lattice, not particles at hashed or orbiting
positions, which a loop has to visit one by one. Loops that only offset the pixel (an
anti-aliasing grid, a filter kernel: `uv + vec2(i, j) / n`) compare nothing and are not
reported, nor are loops over 3D positions (a ray tracer's grid of spheres, which a ray has to
test one by one).

## Why is this bad?
The course's coding standards: "Use the most efficient methods (-1 per inefficient/unnecessary
practices) ... figure out if there are more efficient ways to do it." A 10 x 10 board is a
hundred iterations, each with its tests, for every pixel, where one `floor()` finds the cell.

## Example
```glsl
for (int i = 0; i < 8; i++)
    for (int j = 0; j < 8; j++)
        if (uv.x >= float(i) / 8.0 && uv.x < float(i + 1) / 8.0
            && uv.y >= float(j) / 8.0 && uv.y < float(j + 1) / 8.0)
            col = mod(float(i + j), 2.0) == 0.0 ? black : white;
```

## Use instead
```glsl
vec2 cell = floor(uv * 8.0); // the pixel's cell
col = mix(black, white, mod(cell.x + cell.y, 2.0));
```
"""

from __future__ import annotations

from ...base.diagnostics import Diagnostic
from ...frontend import syntax as A
from ...semantics.analysis import builtin_call, program_facts
from ...semantics.model import Symbol

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator
    from typing import Any

    from ..engine import LintContext

NAME = "cell-search-loop"
PENALTY = 1
STANDARD = "efficiency"
SEVERITY = "warning"
NEEDS = "ast"

_COMPARE = ("<", "<=", ">", ">=")
_TESTS = ("step", "smoothstep", "distance")  # built-ins that compare two positions


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    for fn in program_facts(ctx.model).in_file(ctx.path):
        reported: set[int] = set()
        for outer in fn.loops:
            if id(outer) in reported or fn.is_dead(outer):
                continue
            inner = next(
                (lp for lp in fn.loops if lp is not outer and fn.contains(outer, lp)), None
            )
            if inner is None:
                continue
            site = _cell_test(fn, outer, inner)
            if site is None:
                continue
            reported.update(id(lp) for lp in fn.loops if fn.contains(outer, lp))
            yield Diagnostic(
                f"the loops at lines {outer.loc.line} and {inner.loc.line} test every cell of a "
                f"grid for each pixel (line {site.loc.line} compares the pixel's position with "
                "each cell's): floor() of the position finds its cell without a loop",
                outer.loc,
                help="find the pixel's cell once, e.g. `vec2 cell = floor(uv * vec2(columns, "
                "rows));`, and compute what the loop body computes for that cell alone",
                notes=[Diagnostic("compared here", site.loc, severity="note")],
            )


def _counters(fn, loop) -> set[int]:
    """The symbols a `for` loop declares in its init (its counters)."""
    init = loop.init if type(loop) is A.For else None
    if type(init) is not A.DeclarationStatement:
        return set()
    return {id(s) for n in init.walk() if (s := fn.model.symbol_of(n)) is not None}


def _cell_test(fn, outer, inner) -> Any:
    """The first node of the inner loop's body comparing the pixel's 2D position with a
    position computed from both loops' counters (the module docstring), else None."""
    counters = _counters(fn, outer) | _counters(fn, inner)
    if len(counters) < 2:
        return None
    lo, hi = fn.enter[id(outer)], fn.exit[id(outer)]
    # what the counters reach: locals written in the loops from them, to a fixpoint
    cell = set(counters)
    writes = [w for ws in fn.writes.values() for w in ws if lo < w.pos < hi]
    grew = True
    while grew:
        grew = False
        for w in writes:
            value = w.value if w.value is not None else getattr(w.node, "value", None)
            if id(w.symbol) in cell or value is None:
                continue
            if any(id(s) in cell for s in fn.operands(value)) and _affine(fn, value):
                cell.add(id(w.symbol))
                grew = True
    written = {id(w.symbol) for w in writes}
    for n in inner.body.walk():
        sides = _sides(fn, n)
        if sides is None:
            continue
        kinds = {_side(fn, s, cell, written) for s in sides if _affine(fn, s)}
        if {"cell", "pixel"} <= kinds:
            return n
    return None


def _affine(fn, e) -> bool:
    """Whether `e` is made with + - * /, conversions and constructors only: a lattice of cells
    when it reads the counters (not a particle's hashed or orbiting position)."""
    for n in e.walk():
        t = type(n)
        if t is A.Call and not n.constructor or t is A.Index or t is A.Assignment:
            return False
        if t is A.Binary and n.op not in ("+", "-", "*", "/"):
            return False
    return True


def _sides(fn, n) -> list[Any] | None:
    """The two operands a node compares: a comparison's, a step's or smoothstep's edge(s) and
    value, a distance's (or length's of a difference), or the arguments of a call of a helper
    that compares two of its parameters."""
    t = type(n)
    if t is A.Binary and n.op in _COMPARE:
        return [n.left, n.right]
    if t is not A.Call:
        return None
    if builtin_call(fn.model, n, *_TESTS):
        return list(n.args)
    if builtin_call(fn.model, n, "length") and len(n.args) == 1:
        d = n.args[0]
        return [d.left, d.right] if type(d) is A.Binary and d.op == "-" else None
    target = fn.model.call_target(n)
    if isinstance(target, Symbol) and getattr(target, "node", None) is not None:
        return list(n.args) if _compares_parameters(fn.model, target.node) else None
    return None


def _compares_parameters(model, definition) -> bool:
    """Whether a helper compares (step, smoothstep, distance, <, ...) one `vec2` parameter with
    another: a cell test its callers give the pixel and a cell."""
    facts = program_facts(model).fn(definition)
    params = {
        id(s)
        for p in definition.proto.params
        if (s := model.symbol_of(p)) is not None and _is_vec2(s.type)
    }
    for n in definition.body.walk():
        sides = _sides_builtin(facts, n)
        if sides is None:
            continue
        read = [{id(s) for s in facts.operands(side)} & params for side in sides]
        if len({i for r in read for i in r}) >= 2 and sum(bool(r) for r in read) >= 2:
            return True
    return False


def _sides_builtin(fn, n) -> list[Any] | None:
    if type(n) is A.Binary and n.op in _COMPARE:
        return [n.left, n.right]
    if type(n) is A.Call and builtin_call(fn.model, n, *_TESTS):
        return list(n.args)
    return None


def _is_vec2(kind) -> bool:
    return getattr(kind, "is_vector", False) and kind.size == 2 and kind.base == "float"


def _side(fn, e, cell: set[int], written: set[int]) -> str:
    """ "cell" when `e` reads what the counters reach and no pixel position, "pixel" when it
    reads a `vec2` the loops never write (or a component of one) and nothing the counters
    reach, else "other"."""
    ops = fn.operands(e)
    from_cell = any(id(s) in cell for s in ops)
    pixel = any(
        id(s) not in written and _is_vec2(s.type) and s.kind in ("local", "param", "global")
        for s in ops
    )
    if from_cell and not pixel:
        return "cell"
    if pixel and not from_cell:
        return "pixel"
    return "other"
