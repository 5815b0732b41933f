"""A local or global variable is never read.

## What it does
Reports a variable declared in the file (a local in a function, or a global or `const` at
file scope) that nothing in the program reads. Assigning it (`x = ...`, `x.y = ...`) is not a
read, nor is a local's update of itself with no other effect (`loc *= 4.0;`, `sum += d;`,
`i++` as a statement: the value it updates is still never used); an argument (also `out`: the
call needs a variable to write, even when only another of its outputs is wanted) or any other
use is, but for an argument of a call, as a statement, of a user function that takes `in`
parameters only and writes no global (`add(world, s);` with `void add(in List l, in Sphere s)`):
such a call changes nothing the caller sees, so passing the variable to it reads nothing.
Parameters, uniforms and shader inputs/outputs are not reported. A Common tab is checked
together with the Image tab, so a global of Common that only Image reads is used; when the
shader has other passes too (Buffer A..D), Common's globals are not reported at all.

A local whose value is a computation (`float h = dot(n, normalize(l + v));`: an operation or a
call of a built-in or user function, not a literal or a constructor of constants) is a possible
deduction: the shader does that work for nothing, an "unnecessary practice" of the standards
(possible: the compiler drops the dead code, so the cost is to the reader). The finding lists
every place the value is computed. A global, a `const` local (a named constant, as the starter's
`warm` and `cool`), a local declared with no value or copied from another variable is a note,
not a deduction.

Unused computed locals declared in statements one right after the other in a block (`vec4
chan2 = chan2(uv); vec4 chan3 = chan3(uv);`, or effects tried one after another and none kept)
are one finding, at the first: a group of values left unused together is one leftover, which
readers deduct once.

Unused locals (not `const`) whose every value is typed in (`float waveFrequency = 7.5;`,
`vec3 bgColor = vec3(0, 1, 0);`: literals and constructors of them) are one possible deduction
a function, a setting left behind when its use was removed or commented out: readers deduct
such leftovers once for the function, joined to its unused computed local where it has one.

Likewise a possible deduction: a local's computed value that the next statement of the same
block writing the whole variable replaces (`v = ...;`, or passing `v` to an `out` parameter)
before anything reads it (`dir = target - origin; calcRay(dir, ...);` with
`calcRay(out vec4 dir, ...)`). A parameter's value written over so is one too, whatever it is
but a constant (a default): `fragColor = vec4(d, d, d, 1.0);` left above the final
`fragColor = ...;`, the shader's output computed twice.
So is a value, not a constant, that the statements after it in its block replace on every
path before anything reads it: an `if` whose arms both assign the whole variable (`vec3 col =
randColOne; if (c) { col = randColTwo; } else { col = randColOne; }`), or a copy the next
assignment replaces. A loop or a jump after it ends the search (no finding).

Likewise a possible deduction: a value assigned to a local (or to an `in` parameter, the
function's own copy) that nothing after it reads, a compound update (`uv *= 0.25;`) included,
outside any loop (`px = uv * res;` as the last use of `px`, with the return reading neither):
one finding at that assignment, naming the
earlier statements and declarations whose values only it reads (in turn). Writing the fields
of an `in` parameter as the function's last work (`hit.normal = ...;` in a `void` function)
is the same: the caller never sees it, and the fix says `inout` may have been meant.

Likewise a possible deduction: a call, as a statement, of a user function whose results are
its `out` arguments (it writes no global) when each of them is replaced before anything reads
it, on every path from the call: by the next write of the whole variable in the same block, or
in a counting loop there that runs at least once, with no jump between (`calcViewport(vp, ...);
calcRay(dir, vp);` before a sampling loop that calls both again first thing), or is never read
at all. A read by another such call is no read, and calls that follow each other are one
finding. A function that reads an `out` parameter before writing it meant `inout`: its calls
are left to `out-parameter-read`.

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
from ...semantics.analysis import (
    param_directions,
    program_facts,
    pure_function,
    unassigned_reads,
)
from ...semantics.hazards import loop_ranges
from ...semantics.model import Symbol
from ...shadertoy.wrapper import PASS_TABS
from ._text import at_lines

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
        elif id(node) in statements and no_effect_call(model, node):
            written.update(id(n) for a in node.args for n in a.walk() if type(n) is A.Identifier)
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


def no_effect_call(model: Model, node: Any) -> bool:
    """A call, as a statement, of a user function that takes `in` parameters only and writes no
    global (`add(list, s);` with `void add(in List l, in Sphere s)` writing only its copies): it
    does nothing the caller sees, so what its arguments read is no read."""
    if type(node) is not A.Call:
        return False
    target = model.call_target(node)
    return (
        isinstance(target, Symbol)
        and pure_function(model, target)
        and all(_pure_value(model, a) for a in node.args)
    )


def _pure_value(model: Model, e: Any) -> bool:
    """`e` writes nothing and calls only pure functions."""
    for n in e.walk():
        k = type(n)
        if k in (A.Assignment, A.Postfix, A.Sequence) or (k is A.Unary and n.op in ("++", "--")):
            return False
        if k is A.Call:
            callee = model.call_target(n)
            if callee is None or (isinstance(callee, Symbol) and not pure_function(model, callee)):
                return False
            if getattr(callee, "out_params", None):
                return False
    return True


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
    if value is not None and not _pure_value(model, value):
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
        found: list[tuple[A.Declarator, Diagnostic]] = []
        typed: list[A.Declarator] = []  # unused locals set only to values typed in
        for n in fn.nodes:
            if type(n) is A.Declarator:
                if _typed_in_only(fn, n, reads):
                    typed.append(n)
                else:
                    found.extend((n, f) for f in _unused(ctx, model, n, reads, "local", fn))
        yield from _with_typed_in(_adjacent_joined(fn, found), typed)
        reported: set[int] = set()
        yield from _overwritten(fn, reads, reported)
        yield from _replaced_on_every_path(fn, reads, reported)
        yield from _dead_stores(fn, reads)
        yield from _dead_calls(fn)


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


def _overwritten(fn, reads: set[int], reported: set[int]) -> Iterator[Diagnostic]:
    """A local's computed value (a parameter's value not constant) that the next statement
    writing the variable replaces, in the same block, before anything reads it (`d = a - b;
    calc(d);` with `calc(out vec4 d)`; `fragColor = a; fragColor = b;`)."""
    positions = None
    for sym_id, writes in fn.writes.items():
        sym = writes[0].symbol
        # a local never read at all is reported as unused; a parameter's last value is the
        # result its caller sees, read or not
        if sym.kind != "param" and (sym.kind != "local" or sym_id not in reads):
            continue
        whole = sorted(
            [w for w in writes if w.kind in ("=", "init")] + _out_writes(fn, sym),
            key=lambda w: w.pos,
        )
        for first, then in zip(whole, whole[1:]):
            # (a parameter's first output written over: any value not constant, `fragColor =
            # vec4(d, d, d, 1.0);` left above the final one; a constant is a default)
            shown = sym.kind == "param" and first.value is not None
            shown = shown and not fn.model.is_constant(first.value)
            if not (_computed(fn, first.value) or shown) or first.kind not in ("=", "init"):
                continue
            if fn.region[id(first.node)] != fn.region[id(then.node)] or fn.is_dead(then.node):
                continue
            if positions is None:
                positions = _read_positions(fn)
            read_at = positions.get(sym_id, [])  # in execution order: sorted
            i = bisect_right(read_at, first.pos)
            if i < len(read_at) and read_at[i] < then.pos:
                continue
            reported.add(id(first.node))
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


def _replaced_on_every_path(fn, reads: set[int], reported: set[int]) -> Iterator[Diagnostic]:
    """A variable's value, not a constant, that the statements after it in its block replace
    whole on every path before anything reads it: an `if` whose arms both assign it (`col =
    a; if (c) col = b; else col = a;`), or a copy of another variable the next assignment
    replaces (`vec3 col = base; col = shade(p);`)."""
    for writes in fn.writes.values():
        sym = writes[0].symbol
        if sym.kind not in ("local", "param") or (sym.kind == "local" and id(sym) not in reads):
            continue
        for w in writes:
            if w.kind not in ("=", "init") or w.value is None or id(w.node) in reported:
                continue
            if fn.model.is_constant(w.value) or fn.is_dead(w.node) or _in_loop(fn, w.node):
                continue
            if not fn.is_pure(w.value):
                continue  # (a call writing something else is wanted for that)
            stmt = fn.parent.get(id(w.node))
            if type(stmt) is A.VariableDeclaration:
                stmt = fn.parent.get(id(stmt))
            block = fn.parent.get(id(stmt))
            if type(block) is not A.Compound:
                continue
            at = next(i for i, x in enumerate(block.stmts) if x is stmt)
            fate, by = _fate(fn, block.stmts[at + 1 :], sym)
            if fate != "replaced" or not by:
                continue
            arms = " on every path" if len(by) > 1 else ""
            yield Diagnostic(
                f"the value given to '{sym.name}' here is never read: {at_lines(by)} "
                f"replace{'' if len(by) > 1 else 's'} it first{arms}",
                w.value.loc,
                help=f"remove this assignment, or use '{sym.name}' before it is replaced",
                notes=[Diagnostic("replaced here", b.loc, severity="note") for b in by],
            )


def _fate(fn, stmts: list, sym) -> tuple[str, list]:
    """What the statements `stmts`, run in order, do first with the variable `sym`: ("read",
    []) when a path may read it (or anything the reading cannot follow: a loop, a jump that
    mentions it or leaves), ("replaced", the assignments) when every path assigns it whole
    first, ("none", the assignments of the paths that do) when some path does neither."""
    by: list = []
    for st in stmts:
        if type(st) is A.Compound:
            fate, found = _fate(fn, st.stmts, sym)
        elif type(st) is A.If:
            if _mentions(fn, st.cond, sym):
                return "read", []
            fate, found = _fate(fn, _body(st.then), sym)
            if fate != "read":
                other, more = _fate(fn, _body(st.else_), sym)
                found = found + more
                fate = "read" if other == "read" else fate if fate == other else "none"
        elif type(st) is A.ExpressionStatement:
            e = st.expr
            if (
                type(e) is A.Assignment
                and e.op == "="
                and type(e.target) is A.Identifier
                and fn.model.symbol_of(e.target) is sym
            ):
                fate, found = ("read", []) if _mentions(fn, e.value, sym) else ("replaced", [e])
            else:
                fate, found = (
                    ("read", []) if e is not None and _mentions(fn, e, sym) else ("none", [])
                )
        elif type(st) is A.DeclarationStatement:
            fate, found = ("read", []) if _mentions(fn, st, sym) else ("none", [])
        else:  # a loop, a switch, a jump: not followed
            return "read", []
        if fate == "read":
            return "read", []
        by += found
        if fate == "replaced":
            return "replaced", by
    return "none", by


def _body(st) -> list:
    return [] if st is None else st.stmts if type(st) is A.Compound else [st]


def _mentions(fn, node, sym) -> bool:
    return any(type(n) is A.Identifier and fn.model.symbol_of(n) is sym for n in node.walk())


def _dead_stores(fn, reads: set[int]) -> Iterator[Diagnostic]:
    """A value assigned to a local (or an `in` parameter, the function's own copy) that nothing
    after it reads: the statement is the variable's last write on its path, outside any loop
    (the next iteration could read it), and computes something. The writes whose values only
    such a statement reads (in turn) are work done for nothing too: one finding, at the value
    never read, naming them."""
    own = _own_variables(fn)
    writes = []  # (write, the assignment or declaration it is): pure statements, not in a loop
    for sym_id, ws in fn.writes.items():
        if sym_id not in own or sym_id not in reads:
            continue  # a variable never read at all is reported as unused
        for w in ws:
            node = w.node
            if w.kind in ("=", "op", "part") and type(node) is A.Assignment:
                if type(fn.parent.get(id(node))) is not A.ExpressionStatement:
                    continue
                value = node.value
            elif w.kind == "init":
                value = w.value
            else:
                continue
            if _in_loop(fn, node) or fn.is_dead(node) or not fn.is_pure(value):
                continue
            writes.append((w, value))
    if not writes:
        return
    positions = _read_positions(fn)  # in execution order: sorted
    everywhere = sorted(p for read_at in positions.values() for p in read_at)
    # Last first: a statement's reads come before its own position, so the statements that only
    # a later one of the chain reads are met after it, in one pass.
    writes.sort(key=lambda wv: -wv[0].pos)

    def read_after(w, ignored: set[int]) -> bool:
        read_at = positions.get(id(w.symbol), [])
        return any(p not in ignored for p in read_at[bisect_right(read_at, w.pos) :])

    for root, value in writes:
        # (`uv *= 0.25;` computes: the update is an operation whatever its operand)
        work = _computed(fn, value) or root.kind == "op"
        if root.kind == "init" or not work or read_after(root, set()):
            continue
        chain = [root]
        ignored: set[int] = set()  # the read positions inside the chain's statements: no reads
        for w, _ in writes:
            if w is not root and w.pos < root.pos and not read_after(w, ignored):
                chain.append(w)
            if w is root or w is chain[-1]:
                lo, hi = fn.enter[id(w.node)], fn.exit[id(w.node)]
                ignored.update(
                    everywhere[bisect_right(everywhere, lo) : bisect_right(everywhere, hi)]
                )
        feeding = sorted(
            (w for w in chain[1:] if w.kind != "init" or w.value is not None), key=lambda w: w.pos
        )
        name = root.symbol.name
        param = root.symbol.kind == "param"
        yield Diagnostic(
            f"the value assigned to '{name}' here is never read: nothing after it reads "
            f"'{name}'"
            + (f"; {_where(feeding)} only what it reads" if feeding else "")
            + (
                f" ('{name}' is an in parameter: the caller never sees what is written to it)"
                if param
                else ""
            ),
            root.node.loc,
            help=(
                f"declare '{name}' inout (or out) if the caller is meant to get it; else remove "
                "the assignment"
                if param
                else "remove the assignment and the work only it uses, or use the value"
            ),
            notes=[
                Diagnostic("computed only for it", w.node.loc, severity="note")
                for w in feeding[:_LISTED]
            ],
        )


_LISTED = 8  # places a message lists one by one; more are given as a span


def _where(writes: list) -> str:
    """`line 4 computes`, `lines 4, 6 and 9 compute`, or `20 lines from 4 to 31 compute`."""
    lines = sorted({w.node.loc.line for w in writes})
    if len(lines) == 1:
        return f"line {lines[0]} computes"
    if len(lines) <= _LISTED:
        return f"{at_lines([w.node for w in writes])} compute"
    return f"{len(lines)} lines from {lines[0]} to {lines[-1]} compute"


def _own_variables(fn) -> set[int]:
    """ids of the function's locals and `in` parameters: values no caller sees."""
    own = {sym_id for sym_id, ws in fn.writes.items() if ws[0].symbol.kind == "local"}
    if fn.symbol is not None:
        for p, (_, _, direction) in zip(fn.definition.proto.params, fn.symbol.params):
            sym = fn.model.symbol_of(p)
            if sym is not None and direction == "in":
                own.add(id(sym))
    return own


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
    callees = sorted({c.callee for c in _passed_to_no_effect_calls(fn, sym)} if fn else ())
    only = (
        f" (only passed to {', '.join(c + '()' for c in callees)}, which "
        + (
            "takes in parameters only and changes"
            if len(callees) == 1
            else "take in parameters only and change"
        )
        + " nothing the caller sees)"
        if callees
        else ""
    )
    if not work:
        yield Diagnostic(
            f"the {kind} {what} '{d.name}' is never read{only}", loc, help=help_, severity="note"
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
        f"done for nothing{only}",
        loc,
        help=help_,
        notes=[
            Diagnostic("computed here", v.loc, severity="note")
            for v in work
            if v.loc.line != loc.line
        ],
    )


def _typed_in(model, value) -> bool:
    """`value` is typed in: literals, their negations and constructors of them (`7.5`,
    `vec3(0, 1, 0)`), no operation and no other variable."""
    for n in value.walk():
        k = type(n)
        if k is A.Call and n.constructor:
            continue
        if k is A.Unary and n.op in ("-", "+"):
            continue
        if k not in (A.IntLiteral, A.FloatLiteral, A.BoolLiteral):
            return False
    return True


def _typed_in_only(fn, d: A.Declarator, reads: set[int]) -> bool:
    """A local, not `const`, never read, whose every value is typed in (a setting declared and
    left unused: `float waveFrequency = 7.5;` whose one use was commented out)."""
    model = fn.model
    sym = model.symbol_of(d)
    if sym is None or id(sym) in reads or sym.qualifier == "const" or d.init is None:
        return False
    if _passed_to_no_effect_calls(fn, sym):
        return False
    for w in fn.writes_to(sym):
        value = w.value if w.kind in ("init", "=") else None
        if value is None or not _typed_in(model, value):
            return False
    return True


def _adjacent_joined(fn, found: list[tuple[A.Declarator, Diagnostic]]) -> list[Diagnostic]:
    """The unused computed locals' findings, those declared in statements one right after the
    other in a block joined into the first's: a group of values left unused together (`vec4
    chan2 = chan2(uv); vec4 chan3 = chan3(uv);`) is one leftover, deducted once."""
    out: list[Diagnostic] = []
    groups: list[tuple[Diagnostic, list[str]]] = []  # each group's finding, and the others
    last: tuple[Any, int] | None = None  # the block and index of the last deduction's statement
    for d, f in found:
        at = _statement_at(fn, d)
        if f.severity == "note" or at is None:
            out.append(f)
            continue
        if groups and last is not None and at[0] is last[0] and at[1] - last[1] <= 1:
            loc = d.name_loc if d.name_loc.line else d.loc
            groups[-1][1].append(f"'{d.name}' (line {loc.line})")
            groups[-1][0].notes.append(
                Diagnostic("also computed and never read", loc, severity="note")
            )
            groups[-1][0].notes.extend(f.notes)
        else:
            out.append(f)
            groups.append((f, []))
        last = at
    for f, others in groups:
        if others:
            f.message += (
                f"; nor {'is' if len(others) == 1 else 'are'} {', '.join(others)}, declared in "
                f"the statement{'s' if len(others) > 1 else ''} right after it"
            )
    return out


def _statement_at(fn, d: A.Declarator) -> tuple[Any, int] | None:
    """(the block, the index in it) of the statement declaring `d`."""
    node: Any = d
    while True:
        parent = fn.parent.get(id(node))
        if parent is None:
            return None
        if type(parent) is A.Compound:
            index = next((i for i, s in enumerate(parent.stmts) if s is node), None)
            return None if index is None else (parent, index)
        node = parent


def _with_typed_in(found: list[Diagnostic], typed: list[A.Declarator]) -> Iterator[Diagnostic]:
    """The function's unused-variable findings, with its unused locals set to values typed in
    as one more deduction: readers deduct such leftover settings once a function (or with the
    function's unused computed local, where it has one), not once a variable."""
    if not typed:
        yield from found
        return
    locs = [d.name_loc if d.name_loc.line else d.loc for d in typed]
    names = ", ".join(f"'{d.name}'" for d in typed)
    notes = [Diagnostic("also set and never read", loc, severity="note") for loc in locs]
    deduction = next((f for f in found if f.severity != "note"), None)
    if deduction is not None:
        deduction.message += (
            f"; {names}, set to {'values' if len(typed) > 1 else 'a value'} typed in, "
            f"{'are' if len(typed) > 1 else 'is'} never read either"
        )
        deduction.notes.extend(notes)
        yield from found
        return
    yield from found
    many = len(typed) > 1
    yield Diagnostic(
        f"the local variable{'s' if many else ''} {names} {'are' if many else 'is'} set to "
        f"{'values' if many else 'a value'} typed in and never read: "
        f"{'declarations' if many else 'a declaration'} left for nothing",
        locs[0],
        help=f"remove {names}, or use {'them' if many else 'it'} where meant",
        notes=notes[1:],
    )


def _passed_to_no_effect_calls(fn, sym) -> list[A.Call]:
    """The call statements with no effect (`no_effect_call`) whose arguments name `sym`."""
    return [
        c
        for c in fn.calls
        if type(fn.parent.get(id(c))) is A.ExpressionStatement
        and no_effect_call(fn.model, c)
        and any(
            type(n) is A.Identifier and fn.model.symbol_of(n) is sym
            for a in c.args
            for n in a.walk()
        )
    ]


_JUMPS = (A.Break, A.Continue, A.Return, A.Discard)


def _dead_calls(fn) -> Iterator[Diagnostic]:
    """Calls whose every output is replaced before anything reads it (see the module's doc),
    consecutive ones in a block as one finding."""
    model = fn.model
    calls = []
    for c in fn.calls:
        target = model.call_target(c)
        if (
            type(fn.parent.get(id(c))) is not A.ExpressionStatement
            or not isinstance(target, Symbol)
            or fn.is_dead(c)
            or not pure_function(model, target, outputs=True)
            or any(u.kind == "out-parameter" for u in unassigned_reads(model, target.node))
        ):
            continue  # one that reads an out parameter first meant `inout`: out-parameter-read
        outs = [a for a, d in zip(c.args, param_directions(target)) if d in ("out", "inout")]
        syms = [model.symbol_of(a) if type(a) is A.Identifier else None for a in outs]
        if syms and all(s is not None and s.kind == "local" for s in syms):
            calls.append((c, syms))
    if not calls:
        return
    positions = _read_positions(fn)
    ranges = loop_ranges(model, [lp for lp in fn.loops if type(lp) is A.For])
    dead: dict[int, tuple[A.Call, list]] = {}
    changed = True
    while changed:  # a read by a dead call is no read: its outputs may be dead in turn
        changed = False
        ignored = [(fn.enter[id(c)], fn.exit[id(c)]) for c, _ in dead.values()]
        for c, syms in calls:
            if id(c) in dead:
                continue
            replaced = [_replaced_at(fn, c, s, positions, ignored, ranges) for s in syms]
            if all(r is not None for r in replaced) and any(r for r in replaced):
                dead[id(c)] = (c, [w for r in replaced if r for w in r])
                changed = True
    group: list[tuple[A.Call, list]] = []
    for c, _ in calls:
        if id(c) not in dead:
            continue
        if group and not _next_statement(fn, group[-1][0], c):
            yield _dead_finding(group)
            group = []
        group.append(dead[id(c)])
    if group:
        yield _dead_finding(group)


def _replaced_at(fn, call: A.Call, sym, positions: dict, ignored: list, ranges: dict):
    """The write that replaces the value `call` writes to `sym` before anything reads it: the
    next whole write, on every path from the call (in its block, or in a counting loop there
    that runs at least once, with no jump between); [] when nothing ever reads `sym`; None
    when the value may be read."""
    read_at = [p for p in positions.get(id(sym), []) if not any(a <= p <= b for a, b in ignored)]
    start = fn.exit[id(call)]
    later = sorted(
        (
            w
            for w in [w for w in fn.writes_to(sym) if w.kind == "="] + _out_writes(fn, sym)
            if w.pos > start
        ),
        key=lambda w: w.pos,
    )
    if not later:
        return None if any(p > start for p in read_at) or _in_loop(fn, call) else []
    then = later[0]
    home, there = fn.region[id(call)], fn.region[id(then.node)]
    if there[: len(home)] != home or fn.is_dead(then.node):
        return None
    for loop_id, kind in there[len(home) :]:
        loop = next((lp for lp in fn.loops if id(lp) == loop_id), None)
        if kind != "loop" or type(loop) is not A.For or not _runs(fn.model, loop, ranges):
            return None
    if any(start < p < then.pos for p in read_at):
        return None
    end = fn.enter[id(then.node)]
    if any(type(n) in _JUMPS and start < fn.enter[id(n)] < end for n in fn.nodes):
        return None
    return [then]


def _in_loop(fn, node) -> bool:
    return any(kind == "loop" for _, kind in fn.region[id(node)])


def _runs(model, loop: A.For, ranges: dict) -> bool:
    """Whether a counting for loop runs its body at least once (a constant, non-empty range)."""
    init = loop.init
    if type(init) is not A.DeclarationStatement or type(init.decl) is not A.VariableDeclaration:
        return False
    sym = model.symbol_of(init.decl.declarators[0]) if init.decl.declarators else None
    return sym is not None and id(sym) in ranges


def _next_statement(fn, a: A.Call, b: A.Call) -> bool:
    """Whether call statement `b` follows call statement `a` right away in the same block."""
    sa, sb = fn.parent.get(id(a)), fn.parent.get(id(b))
    block = fn.parent.get(id(sa))
    if type(block) is not A.Compound or fn.parent.get(id(sb)) is not block:
        return False
    stmts = block.stmts
    return any(x is sa and y is sb for x, y in zip(stmts, stmts[1:]))


def _dead_finding(group: list[tuple[A.Call, list]]) -> Diagnostic:
    first = group[0][0]
    names = " and ".join(f"{c.callee}()" for c, _ in group)
    replaced = sorted({w.node.loc.line for _, ws in group for w in ws})
    where = (
        f"line {replaced[0]}"
        if len(replaced) == 1
        else ("lines " + ", ".join(map(str, replaced[:-1])) + f" and {replaced[-1]}")
    )
    return Diagnostic(
        f"what {names} compute{'s' if len(group) == 1 else ''} here is work done for nothing: "
        f"each output is replaced (at {where}) before anything reads it, or never read",
        first.loc,
        help="remove the calls, or use what they compute"
        if len(group) > 1
        else "remove the call, or use what it computes",
        notes=[Diagnostic("also never read", c.loc, severity="note") for c, _ in group[1:]],
    )
