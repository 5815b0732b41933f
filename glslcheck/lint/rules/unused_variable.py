"""A local or global variable is never read.

## What it does
Reports a variable declared in the file (a local in a function, or a global or `const` at
file scope) that nothing in the program reads. Assigning it (`x = ...`, `x.y = ...`) is not a
read, nor is a local's update of itself with no other effect (`loc *= 4.0;`, `sum += d;`,
`i++` as a statement: the value it updates is still never used); an argument (also `out`: the
call needs a variable to write, even when only another of its outputs is wanted) or any other
use is.
Parameters, uniforms and shader inputs/outputs are not reported. A Common tab is checked
together with the Image tab, so a global of Common that only Image reads is used; when the
shader has other passes too (Buffer A..D), Common's globals are not reported at all.

A local whose value is a computation (`float h = dot(n, normalize(l + v));`: an operation or a
call of a built-in or user function, not a literal or a constructor of constants) is a possible
deduction: the shader does that work for nothing, an "unnecessary practice" of the standards
(possible: the compiler drops the dead code, so the cost is to the reader). The finding lists
every place the value is computed. Any other unused variable is a note, not a deduction.

Likewise a possible deduction: a local's computed value that the next statement of the same
block writing the whole variable replaces (`v = ...;`, or passing `v` to an `out` parameter)
before anything reads it (`dir = target - origin; calcRay(dir, ...);` with
`calcRay(out vec4 dir, ...)`).

## Why is this bad?
An unused variable is dead code: a leftover from an earlier version or a computation whose
result was forgotten (often the bug). The course's coding standards ask to "remove redundant
operations" (Lab 4, part 7) and that every line be explained, which a dead line cannot be.

## Example
```glsl
float attenuation = 1.0 / (1.0 + d / intensity);
vec3 color = kD * albedo * light.color;
```

## Use instead
```glsl
float attenuation = 1.0 / (1.0 + d / intensity);
vec3 color = kD * attenuation * albedo * light.color;
```
"""

from __future__ import annotations

from bisect import bisect_right

from ...base.diagnostics import Diagnostic
from ...frontend import syntax as A
from ...semantics.analysis import param_directions, program_facts, pure_function
from ...semantics.model import Symbol
from ...shadertoy.wrapper import PASS_TABS

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator
    from typing import Any

    from ...semantics.model import Model
    from ..engine import LintContext

NAME = "unused-variable"
PENALTY = 1
STANDARD = "efficiency"
SEVERITY = "warning"
CERTAINTY = "possible"
NEEDS = "ast"
READS = "program"  # a read in code that does not compile may be missing


def common_shared(ctx) -> bool:
    """A Common tab that other passes than the one linted with it may use."""
    if ctx.source.tab != "Common" or ctx.shader is None:
        return False
    return sum(t in ctx.shader.tabs for t in PASS_TABS) > 1


def read_symbols(model: Model) -> set[int]:
    """ids of every Symbol the program reads somewhere (cached on the program facts)."""
    pf = _program_reads.get("model")
    if pf is model:
        return _program_reads["reads"]
    # Every identifier is a read but the variable an `=` writes: the root of its target's
    # fields and indexes (`v`, `v.x`, `a[i].f`; the index `i` is read). An out argument is a
    # read too: the call needs a variable there.
    idents: list[A.Identifier] = []
    written: set[int] = set()  # ids of the identifiers `=` writes, or a local updates itself
    statements: set[int] = set()  # ids of the expressions that are a statement of their own
    for node in model.nodes():
        t = type(node)
        if t is A.Identifier:
            idents.append(node)
        elif t is A.ExpressionStatement and node.expr is not None:
            statements.add(id(node.expr))
        elif t is A.For and node.step is not None:
            statements.add(id(node.step))  # `i++` of a loop header: a statement too
        elif t is A.Assignment and node.op == "=":
            target = node.target
            while type(target) in (A.Field, A.Index):
                target = target.base
            if type(target) is A.Identifier:
                written.add(id(target))
    for node in model.nodes():
        if id(node) in statements and (target := _self_update(model, node)) is not None:
            written.add(id(target))
    symbol_of = model.symbol_of
    reads: set[int] = set()
    for node in idents:
        if id(node) not in written:
            sym = symbol_of(node)
            if sym is not None:
                reads.add(id(sym))
    _program_reads["model"] = model
    _program_reads["reads"] = reads
    return reads


_program_reads: dict[str, Any] = {}


def _self_update(model: Model, node: Any) -> A.Identifier | None:
    """The local a statement only updates from itself (`x *= e;`, `x += e;`, `x++;`), with
    nothing else done (`e` writes nothing and calls only pure functions): that use of `x` only
    feeds `x`, so it is no read."""
    t = type(node)
    if t is A.Assignment and node.op != "=":
        target, value = node.target, node.value
    elif t is A.Postfix or (t is A.Unary and node.op in ("++", "--")):
        target, value = node.operand, None
    else:
        return None
    if type(target) is not A.Identifier:
        return None
    sym = model.symbol_of(target)
    if sym is None or sym.kind != "local":
        return None
    for n in value.walk() if value is not None else ():
        k = type(n)
        if k in (A.Assignment, A.Postfix, A.Sequence) or (k is A.Unary and n.op in ("++", "--")):
            return None
        if k is A.Call:
            callee = model.call_target(n)
            if callee is None or (isinstance(callee, Symbol) and not pure_function(model, callee)):
                return None
            if getattr(callee, "out_params", None):
                return None
    return target


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    model = ctx.model
    if model is None:
        return
    reads = read_symbols(model)
    shared = common_shared(ctx)
    for decl in model.ast.decls:
        if decl.loc.path != ctx.path:
            continue
        if type(decl) is A.VariableDeclaration and not shared:
            storage = decl.qualifiers.storage if decl.qualifiers else None
            if storage not in (None, "const"):
                continue
            for d in decl.declarators:
                yield from _unused(ctx, model, d, reads, "global")
    for fn in program_facts(ctx.model).in_file(ctx.path):
        for n in fn.nodes:
            if type(n) is A.Declarator:
                yield from _unused(ctx, model, n, reads, "local", fn)
        yield from _overwritten(fn, reads)


def _read_positions(fn) -> dict[int, list[int]]:
    """id(symbol) -> the positions where the function reads that variable (not the variable an
    `=` writes whole, nor an `out` argument)."""
    skip: set[int] = set()
    for n in fn.nodes:
        if type(n) is A.Assignment and n.op == "=" and type(n.target) is A.Identifier:
            skip.add(id(n.target))
        elif type(n) is A.Call:
            for arg, d in zip(n.args, param_directions(fn.model.call_target(n))):
                if d == "out" and type(arg) is A.Identifier:
                    skip.add(id(arg))
    out: dict[int, list[int]] = {}
    for n in fn.nodes:
        if type(n) is A.Identifier and id(n) not in skip:
            sym = fn.model.symbol_of(n)
            if sym is not None:
                out.setdefault(id(sym), []).append(fn.enter[id(n)])
    return out


def _out_writes(fn, sym) -> list[int]:
    """Positions of the calls that pass the variable itself to an `out` parameter."""
    found = []
    for w in fn.writes_to(sym):
        if w.kind != "out" or type(w.node) is not A.Call:
            continue
        for arg, d in zip(w.node.args, param_directions(fn.model.call_target(w.node))):
            if d == "out" and type(arg) is A.Identifier and fn.model.symbol_of(arg) is sym:
                found.append(w)
                break
    return found


def _overwritten(fn, reads: set[int]) -> Iterator[Diagnostic]:
    """A local's computed value that the next statement writing the variable replaces, in the
    same block, before anything reads it (`d = a - b; calc(d);` with `calc(out vec4 d)`)."""
    positions = None
    for sym_id, writes in fn.writes.items():
        sym = writes[0].symbol
        if sym.kind != "local" or sym_id not in reads:
            continue  # a variable never read at all is reported as unused
        whole = sorted(
            [w for w in writes if w.kind in ("=", "init")] + _out_writes(fn, sym),
            key=lambda w: w.pos,
        )
        for first, then in zip(whole, whole[1:]):
            if not _computed(fn, first.value) or first.kind not in ("=", "init"):
                continue
            if fn.region[id(first.node)] != fn.region[id(then.node)] or fn.is_dead(then.node):
                continue
            if positions is None:
                positions = _read_positions(fn)
            read_at = positions.get(sym_id, [])  # in execution order: sorted
            i = bisect_right(read_at, first.pos)
            if i < len(read_at) and read_at[i] < then.pos:
                continue
            how = (
                f"{then.node.callee}()'s out parameter"
                if type(then.node) is A.Call
                else "an assignment"
            )
            yield Diagnostic(
                f"the value computed for '{sym.name}' here is never read: {how} at line "
                f"{then.node.loc.line} replaces it first",
                first.value.loc,
                help=f"remove this computation, or use '{sym.name}' before it is replaced",
                notes=[Diagnostic("replaced here", then.node.loc, severity="note")],
            )


def _computed(fn, value) -> bool:
    """`value` is work done at run time: an operation or a call, not constant."""
    return (
        value is not None
        and fn.op_count(value)[0] > 0
        and not fn.model.is_constant(value)
        and not fn.is_dead(value)
    )


def _unused(
    ctx, model, d: A.Declarator, reads: set[int], kind: str, fn: Any = None
) -> Iterator[Diagnostic]:
    sym = model.symbol_of(d)
    if sym is None or id(sym) in reads:
        return
    loc = d.name_loc if d.name_loc.line else d.loc
    what = "constant" if sym.qualifier == "const" else "variable"
    help_ = f"remove '{d.name}', or use it where its value was meant to go"
    work = []  # the writes that compute its value
    if fn is not None:
        for w in fn.writes_to(sym):
            value = w.value if w.kind in ("init", "=") else getattr(w.node, "value", None)
            if value is not None and w.kind in ("init", "=", "part", "op") and _computed(fn, value):
                work.append(value)
    if not work:
        yield Diagnostic(
            f"the {kind} {what} '{d.name}' is never read", loc, help=help_, severity="note"
        )
        return
    lines = sorted({v.loc.line for v in work})
    where = (
        f"line {lines[0]}"
        if len(lines) == 1
        else "lines " + ", ".join(map(str, lines[:-1])) + f" and {lines[-1]}"
    )
    yield Diagnostic(
        f"the {kind} {what} '{d.name}' is never read: its value, computed at {where}, is work "
        "done for nothing",
        loc,
        help=help_,
        notes=[
            Diagnostic("computed here", v.loc, severity="note")
            for v in work
            if v.loc.line != loc.line
        ],
    )
