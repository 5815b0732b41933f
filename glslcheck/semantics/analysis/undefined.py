"""Where a checked program reads a value GLSL ES 3.00 leaves undefined: the one home of that answer.

    from glslcheck.semantics.analysis import undefined_reads, unassigned_reads
    for u in undefined_reads(model):       # UndefinedRead, every reachable function, source order
        u.kind, u.loc, u.message, u.help, u.origin
    unassigned_reads(model, definition)      # the variable reads of one function (lint's rules)

Kinds (`UndefinedRead.kind`):

* "out-parameter": an `out` parameter read before it is written. Its value on entry is
  undefined (spec 6.1.1: out parameters are copied out, not in); WebGL passes zero, a desktop
  driver whatever its register held. `origin` is the parameter's declaration.
* "out-parameter-unwritten": an `out` parameter some path returns without writing; the caller's
  variable then receives an undefined value. `loc` is that return (or the body's end). Not one
  of `undefined_reads` (a `bool hit(..., out float t)` writing `t` only when it returns true is
  correct), only of `origins`: verify varies it, and a pixel whose colour changes used it.
* "uninitialized-local": a local variable declared without an initializer and read before it
  is assigned (spec 4.3: undefined; WebGL zero-initialises it, desktop GL does not). `origin` is
  the declarator.
* "uninitialized-global": a global variable declared without an initializer (and without
  `const`, `uniform`, `in` or `out`) read before every path from the entry point assigns it
  (spec 4.3: such globals "enter main() with undefined values"; WebGL zero-initialises them,
  desktop GL does not). The read may be in a callee: the analysis follows the calls (a function
  that assigns the global on every path to its return counts as assigning it). `origin` is the
  global's declarator: a backend gives it its value at the entry point's start.
* "division-by-zero": an integer `/` or `%` (or `/=`, `%=`) by a constant zero (spec 5.9), or a
  float value that is not a constant divided by a constant zero (see `_float_division`).
* "shift-out-of-range": `<<` or `>>` by a constant below 0 or of 32 or more (spec 5.9).
* "conversion-out-of-range": `int(x)`/`uint(x)` of a constant float outside the type's range,
  or a negative float to `uint` (spec 5.4.1).
* "domain": `pow`, `log`, `log2`, `sqrt` or `inversesqrt` of constant arguments outside the
  domain where the built-in is defined (spec 8.2).

The variable kinds are found by definite assignment, path by path: a state is the set of tracked
variables assigned on every path so far; an `if` without `else` (or with one arm only
assigning), a loop body (which may run zero times), a `?:` or `&&`/`||` arm and a `switch` case
are the paths. An assignment to a part (`v.x = ..`, `a[i] = ..`) counts as an assignment, and
so does passing the variable as an `out` argument; an `inout` argument is a read. The first
unassigned read of each variable is reported. Globals are followed across calls: each
function's summary (computed callees first: GLSL has no recursion) is the first read of each
global that some path from its entry reaches unassigned, and the globals it assigns on every
path to a return; at a call the caller's state decides which of the callee's reads are
undefined, and the callee's assigned globals join the state. For the other kinds `origin` is
the operation itself: its value is the undefined one.

A backend that renders a program decides what these values are (the NumPy backend: zero, as
WebGL); `verify` and `probe` use these sites to tell the shader's undefined behaviour from a
renderer's fault.
"""

from __future__ import annotations

import math

from ...base.diagnostics import Diagnostic, Location
from ...base.records import record
from ...frontend import syntax as A
from ..model import Model, Symbol
from .dataflow import builtin_call
from .purity import param_directions, written_variable

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import Any

KINDS = (
    "out-parameter",
    "out-parameter-unwritten",
    "uninitialized-local",
    "uninitialized-global",
    "division-by-zero",
    "shift-out-of-range",
    "conversion-out-of-range",
    "domain",
)
# The kinds whose undefined value is a variable's initial value (the others: an operation's).
VARIABLE_KINDS = (
    "out-parameter",
    "out-parameter-unwritten",
    "uninitialized-local",
    "uninitialized-global",
)


@record(frozen=True)
class UndefinedRead:
    """One place a program reads an undefined value: `loc` the read (or the operation),
    `origin` the node whose value is undefined (a parameter or declarator, or the operation),
    `symbol` the variable (None for an operation), `via` the calls from the entry point that
    reach a global's read in a callee, outermost first."""

    kind: str
    loc: Location
    message: str
    help: str
    origin: Any
    node: Any
    symbol: Symbol | None = None
    via: tuple = ()


def undefined_reads(model: Model) -> list[UndefinedRead]:
    """Every undefined read in the functions reachable from the entry point, in source order
    (cached on the model)."""
    cache = model.analysis_caches.setdefault("undefined_reads", {})
    got = cache.get("all")
    if got is None:
        got = list(global_reads(model))
        for fn in model.reachable_functions():
            definition = fn.node
            if isinstance(definition, A.FunctionDefinition) and definition.body is not None:
                got += unassigned_reads(model, definition)
                got += undefined_operations(model, definition)
        got.sort(key=lambda u: (u.loc.path, u.loc.line, u.loc.column))
        cache["all"] = got
    return got


def origins(model: Model) -> dict[int, UndefinedRead]:
    """id(origin node) -> the first undefined read of it (what a backend makes undefined): the
    reads `check` warns at, then the out parameters left unwritten (`unwritten_outs`)."""
    out: dict[int, UndefinedRead] = {}
    for u in undefined_reads(model):
        out.setdefault(id(u.origin), u)
    for fn in model.reachable_functions():
        definition = fn.node
        if isinstance(definition, A.FunctionDefinition) and definition.body is not None:
            for u in unwritten_outs(model, definition):
                out.setdefault(id(u.origin), u)
    return out


def stop_notes(reads: list[UndefinedRead], rule: str, limit: int = 4) -> list[Diagnostic]:
    """Notes for an error that stopped a render (a loop that never ended, a frame over its
    budget) in a program with undefined reads: where the loop ends may depend on them (a
    `while (true)` waiting for a random point whose seed is an out parameter ends on a driver
    that leaves the seed's garbage in, never with WebGL's zeros)."""
    return [
        Diagnostic(
            f"the program reads a value GLSL leaves undefined here ({u.kind}); this render gives "
            "it WebGL's value, and where the loop ends may depend on it",
            u.loc,
            severity="note",
            rule=rule,
        )
        for u in reads[:limit]
    ]


# Rules of the errors that stop a render early (the NumPy renderer's), which stop_notes explains
STOPS = ("numpy-runaway-loop", "numpy-frame-budget")


# ---------------------------------------------------------------------------------------------
# Variables read before they are assigned


def unassigned_reads(model: Model, definition: A.FunctionDefinition) -> list[UndefinedRead]:
    """The first read of each `out` parameter and each local declared without an initializer
    that some path reaches before an assignment (cached per function)."""
    return _assignment(model, definition)[0]


def unwritten_outs(model: Model, definition: A.FunctionDefinition) -> list[UndefinedRead]:
    """Each `out` parameter that some path to a `return` (or the end) leaves unwritten, kind
    "out-parameter-unwritten", at the first such return: the caller's variable then receives
    an undefined value. Not a warning of `check` (a `bool hit(..., out float t)` that writes `t`
    only when it returns true is the usual, correct pattern), but where verify varies the value
    (a pixel whose colour then changes did use it)."""
    return _assignment(model, definition)[1]


def _assignment(model: Model, definition: A.FunctionDefinition) -> tuple[list, list]:
    cache = model.analysis_caches.setdefault("unassigned_reads", {})
    got = cache.get(id(definition))
    if got is not None:
        return got
    tracked: dict[int, tuple[str, Any]] = {}
    for p in definition.proto.params:
        sym = model.symbol_of(p)
        if sym is not None and "out" in p.qualifiers and p.name is not None:
            tracked[id(sym)] = ("out-parameter", p)
    for n in model.body_nodes(definition):
        if type(n) is A.Declarator and n.init is None:
            sym = model.symbol_of(n)
            if sym is not None and sym.kind == "local":
                tracked[id(sym)] = ("uninitialized-local", n)
    reads: list = []
    unwritten: list = []
    if tracked:
        flow = _Flow(model, tracked)
        try:
            end = flow.stmt(definition.body, set())
        except RecursionError:
            flow.found, flow.returns, end = [], [], None
        reads = [_variable_read(model, ident, *tracked[i]) for i, ident, _ in flow.found]
        exits = flow.returns + ([(None, end)] if end is not None else [])
        for p in definition.proto.params:
            sym = model.symbol_of(p)
            if sym is None or tracked.get(id(sym), ("", None))[0] != "out-parameter":
                continue
            unwritten_at = [r for r, st in exits if id(sym) not in st]
            if unwritten_at:
                where = unwritten_at[0]  # a return statement, or None: the body's end
                loc = where.loc if where is not None else _end(definition)
                unwritten.append(
                    UndefinedRead(
                        "out-parameter-unwritten",
                        loc,
                        f"the out parameter '{sym.name}' is not written on this path: the "
                        "caller's variable receives an undefined value (GLSL ES 3.00 6.1.1)",
                        f"write '{sym.name}' on every path, "
                        "or leave the caller's variable unread there",
                        p,
                        where if where is not None else definition,
                        sym,
                    )
                )
    got = cache[id(definition)] = (reads, unwritten)
    return got


def _end(definition: A.FunctionDefinition) -> Location:
    """Where a function's body ends (its closing brace), else its start."""
    loc = definition.body.loc or definition.loc
    if loc.end_line:
        return Location(loc.path, loc.end_line, max(1, (loc.end_column or 2) - 1))
    return loc


def _variable_read(model: Model, ident: A.Identifier, kind: str, origin: Any) -> UndefinedRead:
    name = ident.name
    sym = model.symbol_of(ident)
    if kind == "out-parameter":
        message = (
            f"'{name}' is an out parameter read before it is written: its value on entry is "
            "undefined (GLSL ES 3.00 6.1.1: an out parameter is not copied in; WebGL passes 0, "
            "other drivers whatever they hold)"
        )
        help = (
            f"declare '{name}' inout if the caller's value is meant to come in, "
            "or write it before reading it"
        )
    else:
        message = (
            f"'{name}' may be read before it is assigned a value (declared at line "
            f"{origin.loc.line} without an initializer): WebGL zero-initialises it, desktop GL "
            "leaves it undefined (GLSL ES 3.00 4.3)"
        )
        help = (
            f"initialise '{name}' where it is declared, or assign it on every path before this read"
        )
    return UndefinedRead(kind, ident.loc, message, help, origin, ident, sym)


# ---------------------------------------------------------------------------------------------
# Globals read before they are assigned, across the calls from the entry point


def global_reads(model: Model) -> list[UndefinedRead]:
    """The first read of each global declared without an initializer that some path from the
    entry point reaches before an assignment (kind "uninitialized-global"), in the entry point
    or in a function it calls (cached on the model)."""
    cache = model.analysis_caches.setdefault("undefined_reads", {})
    got = cache.get("globals")
    if got is not None:
        return got
    got = []
    tracked = _uninitialized_globals(model)
    entry = model.entry
    if tracked and entry is not None:
        summaries: dict[int, tuple[list, set | None]] = {}
        for fn in model.reachable_functions():  # callees before callers
            definition = fn.node
            if isinstance(definition, A.FunctionDefinition) and definition.body is not None:
                summaries[id(fn)] = _summary(model, definition, tracked, summaries)
        found = summaries.get(id(entry), ([], None))[0]
        got = [_global_read(model, entry, ident, tracked[i][1], via) for i, ident, via in found]
    cache["globals"] = got
    return got


def _uninitialized_globals(model: Model) -> dict[int, tuple[str, Any]]:
    """id(symbol) -> ("uninitialized-global", declarator) of each global variable without an
    initializer and without a storage qualifier (a const has an initializer; a uniform or an
    `in` is the application's value; an `out` is the shader's result)."""
    out: dict[int, tuple[str, Any]] = {}
    for sym in model.globals:
        d = sym.node
        if sym.kind == "global" and sym.qualifier is None and type(d) is A.Declarator:
            if d.init is None:
                out[id(sym)] = ("uninitialized-global", d)
    return out


def _summary(
    model: Model, definition: A.FunctionDefinition, tracked: dict, summaries: dict
) -> tuple[list, set | None]:
    """A function's effect on the tracked globals: (id(symbol), first read some path from its
    entry reaches unassigned, the calls it is reached through) of each, and the globals assigned
    on every path to a return (None: no path returns, every one discards)."""
    flow = _Flow(model, tracked, summaries)
    try:
        end = flow.stmt(definition.body, set())
    except RecursionError:
        return [], set(tracked)  # too deep to follow: nothing found in it, nor after it
    exits = [st for _, st in flow.returns] + ([end] if end is not None else [])
    return flow.found, _meet_all(exits)


def _global_read(
    model: Model, entry: Symbol, ident: A.Identifier, origin: Any, via: tuple
) -> UndefinedRead:
    name = ident.name
    message = (
        f"the global '{name}' may be read before it is assigned a value (declared at line "
        f"{origin.loc.line} without an initializer{reached_through(entry, via)}): WebGL "
        "zero-initialises it, desktop GL leaves it undefined (GLSL ES 3.00 4.3: globals without "
        "one enter main() undefined)"
    )
    help = (
        f"initialise '{name}' where it is declared, or assign it at the start of {entry.name} "
        "(before the calls that read it)"
    )
    sym = model.symbol_of(ident)
    return UndefinedRead(
        "uninitialized-global", ident.loc, message, help, origin, ident, sym, tuple(via)
    )


def reached_through(entry: Symbol | None, via: tuple) -> str:
    """ "; reached from mainImage through march (line 40) -> step (line 12)" for a read in a
    callee (`UndefinedRead.via`), "" for a read in the entry point."""
    if not via or entry is None:
        return ""
    calls = " -> ".join(f"{c.callee} (line {c.loc.line})" for c in via)
    return f"; reached from {entry.name} through {calls}"


class _Flow:
    """Definite assignment: a state is the set of tracked variables assigned on every path
    (None: unreachable, after return/break/continue/discard). `found`: (id(symbol), the first
    unassigned read, the calls it is reached through) in the order they are met. With
    `summaries` (id(function symbol) -> `_summary`) a call applies its callee's: the globals
    it reads unassigned, then the ones it assigns."""

    def __init__(self, model: Model, tracked: dict, summaries: dict | None = None) -> None:
        self.model = model
        self.tracked = tracked
        self.summaries = summaries
        self.reported: set[int] = set()
        self.found: list = []
        # (states at each break, states at each continue) of the loops and switches being
        # walked, innermost last (a switch has no continues: None)
        self.frames: list[tuple[list, list | None]] = []
        self.returns: list[tuple[Any, set]] = []  # (return statement, its state), in order

    # -- statements ----------------------------------------------------------------------------
    def stmt(self, s: Any, st: set | None) -> set | None:
        if s is None or st is None:
            return st
        t = type(s)
        if t is A.Compound:
            for x in s.stmts:
                st = self.stmt(x, st)
            return st
        if t is A.DeclarationStatement:
            d = s.decl
            if type(d) is A.VariableDeclaration:
                for dec in d.declarators:
                    if dec.array is not None and dec.array.size is not None:
                        self.expr(dec.array.size, st)
                    sym = self.model.symbol_of(dec)
                    if dec.init is not None:
                        st = self.expr(dec.init, st)
                        if sym is not None:
                            st = st | {id(sym)}
                    elif sym is not None:
                        st = st - {id(sym)}  # a declaration in a loop starts undefined again
            return st
        if t is A.ExpressionStatement:
            return self.expr(s.expr, st) if s.expr is not None else st
        if t is A.If:
            st = self.expr(s.cond, st)
            return _meet(self.stmt(s.then, set(st)), self.stmt(s.else_, set(st)) if s.else_ else st)
        if t in (A.For, A.While):
            st = self.stmt(s.init, st) if t is A.For else st
            # a for's init is a declaration or an expression statement: it never ends the path
            assert st is not None
            forever = s.cond is None or self.model.const_value(s.cond) is True
            once = t is A.For and _runs_once(self.model, s)
            st = self.cond(s.cond, st)
            breaks: list = []
            continues: list = []
            self.frames.append((breaks, continues))
            body = self.stmt(s.body, set(st))
            self.frames.pop()
            step_st = _meet(body, _meet_all(continues))
            if step_st is not None and t is A.For and s.step is not None:
                self.expr(s.step, step_st)
            # the body may run zero times, unless the condition is always true (the loop is
            # left only by a break) or holds for the first value of a counting loop (the loop
            # is left after a pass of the body, or by a break)
            if forever:
                return _meet_all(breaks)
            return _meet(step_st, _meet_all(breaks)) if once else st
        if t is A.DoWhile:
            breaks, continues = [], []
            self.frames.append((breaks, continues))
            body = self.stmt(s.body, st)
            self.frames.pop()
            at_cond = _meet(body, _meet_all(continues))
            after = self.expr(s.cond, at_cond) if at_cond is not None else None
            if after is not None and self.model.const_value(s.cond) is True:
                after = None  # `do { } while (true)`: left only by a break
            return _meet(after, _meet_all(breaks))
        if t is A.Switch:
            st = self.expr(s.expr, st)
            breaks = []
            self.frames.append((breaks, None))
            cur: set | None = None
            has_default = False
            for x in s.body:
                if type(x) is A.Case:
                    has_default = has_default or x.expr is None
                    cur = set(st) if cur is None else _meet(cur, set(st))
                    continue
                cur = self.stmt(x, cur) if cur is not None else None
            self.frames.pop()
            out = _meet(_meet_all(breaks), cur)
            if not has_default:
                out = _meet(out, st)
            return out if out is not None else st
        if t is A.Return:
            if s.value is not None:
                st = self.expr(s.value, st)
            self.returns.append((s, st))
            return None
        if t is A.Break:
            if self.frames:
                self.frames[-1][0].append(st)
            return None
        if t is A.Continue:
            loops = [cs for _, cs in self.frames if cs is not None]
            if loops:
                loops[-1].append(st)
            return None
        if t is A.Discard:
            return None
        return st

    def cond(self, c: Any, st: set) -> set:
        if c is None:
            return st
        if type(c) is A.ConditionDeclaration:
            st = self.expr(c.init, st) if c.init is not None else st
            sym = self.model.symbol_of(c)
            return st | {id(sym)} if sym is not None else st
        return self.expr(c, st)

    # -- expressions ---------------------------------------------------------------------------
    def read(self, ident: A.Identifier, st: set, via: tuple = ()) -> None:
        sym = self.model.symbol_of(ident)
        if sym is None:
            return
        i = id(sym)
        if i in self.tracked and i not in st and i not in self.reported:
            self.reported.add(i)
            self.found.append((i, ident, via))

    def target(self, e: Any, st: set, reads: bool, assigns: bool = True) -> set:
        """Evaluate an l-value: index expressions are read; the variable is read when `reads`,
        and assigned when `assigns` (an out argument is assigned after the call)."""
        root = e
        while type(root) in (A.Field, A.Index):
            if type(root) is A.Index:
                st = self.expr(root.index, st)
            root = root.base
        if type(root) is A.Identifier:
            if reads:
                self.read(root, st)
            return (st | self._root(root)) if assigns else st
        return self.expr(root, st)

    def call(self, e: A.Call, callee: Symbol, st: set) -> set:
        """The callee's effect at a call, after its arguments are evaluated."""
        summary = self.summaries.get(id(callee)) if self.summaries is not None else None
        if summary is None:
            return st  # not a user function with a body (or recursion, which the checker rejects)
        reads, assigned = summary
        for i, ident, via in reads:
            if i not in st:
                self.read(ident, st, (e,) + via)
        return st | (assigned if assigned is not None else set(self.tracked))

    def expr(self, e: Any, st: set) -> set:
        if e is None:
            return st
        t = type(e)
        if t is A.Identifier:
            self.read(e, st)
            return st
        if t is A.MethodCall:  # `a.length()` is the array's size, not a read of its elements
            return st if type(e.base) is A.Identifier else self.expr(e.base, st)
        if t is A.Assignment:
            if e.op != "=":
                st = self.expr(e.target, st)
            st = self.expr(e.value, st)
            return self.target(e.target, st, reads=False)
        if t in (A.Unary, A.Postfix) and e.op in ("++", "--"):
            st = self.expr(e.operand, st)
            return self.target(e.operand, st, reads=False)
        if t is A.Ternary:
            st = self.expr(e.cond, st)
            return self.expr(e.then, set(st)) & self.expr(e.else_, set(st))  # both paths
        if t is A.Binary and e.op in ("&&", "||"):
            st = self.expr(e.left, st)
            self.expr(e.right, set(st))
            return st
        if t is A.Call:
            callee = self.model.call_target(e)
            dirs = param_directions(callee)
            outs = []
            for i, arg in enumerate(e.args):
                d = dirs[i] if i < len(dirs) else "in"
                if d == "out":
                    outs.append(arg)
                    st = self.target(arg, st, reads=False, assigns=False)  # assigned below
                elif d == "inout":
                    outs.append(arg)
                    st = self.expr(arg, st)
                else:
                    st = self.expr(arg, st)
            if isinstance(callee, Symbol):
                st = self.call(e, callee, st)
            for arg in outs:  # copied out when the call returns
                st = st | self._root(arg)
            return st
        for child in e.children():
            st = self.expr(child, st)
        return st

    def _root(self, e: Any) -> set:
        sym, _ = written_variable(self.model, e)
        return {id(sym)} if sym is not None else set()


_COMPARE = {
    "<": lambda a, b: a < b,
    "<=": lambda a, b: a <= b,
    ">": lambda a, b: a > b,
    ">=": lambda a, b: a >= b,
    "!=": lambda a, b: a != b,
}


def _runs_once(model: Model, loop: A.For) -> bool:
    """A counting loop whose condition holds for its variable's first value
    (`for (int i = 0; i < 8; i++)`): its body runs at least once."""
    init, cond = loop.init, loop.cond
    if type(init) is not A.DeclarationStatement or type(init.decl) is not A.VariableDeclaration:
        return False
    decs = init.decl.declarators
    if len(decs) != 1 or decs[0].init is None or type(cond) is not A.Binary:
        return False
    compare = _COMPARE.get(cond.op)
    start = model.const_value(decs[0].init)
    sym = model.symbol_of(decs[0])
    if compare is None or not isinstance(start, (int, float)) or sym is None:
        return False
    if type(cond.left) is A.Identifier and model.symbol_of(cond.left) is sym:
        bound = model.const_value(cond.right)
        return isinstance(bound, (int, float)) and compare(start, bound)
    if type(cond.right) is A.Identifier and model.symbol_of(cond.right) is sym:
        bound = model.const_value(cond.left)
        return isinstance(bound, (int, float)) and compare(bound, start)
    return False


def _meet_all(states: list) -> set | None:
    out: set | None = None
    for x in states:
        out = _meet(out, x)
    return out


def _meet(a: set | None, b: set | None) -> set | None:
    if a is None:
        return b
    if b is None:
        return a
    return a & b


# ---------------------------------------------------------------------------------------------
# Operations on constants outside their defined range

INT_RANGE = (-(2**31), 2**31)  # [lo, hi) of a 32-bit int, the range int(x) is defined on
UINT_RANGE = (0, 2**32)
SHIFT_BITS = 32  # int and uint are 32-bit (highp; Shadertoy's prelude sets highp int)
# built-in -> (the test of its constant arguments that makes it undefined, why), spec 8.2
_DOMAINS: dict[str, tuple[int, Callable[..., bool], str]] = {
    "pow": (
        2,
        lambda x, y: x < 0 or (x == 0 and y <= 0),
        "pow(x, y) is undefined for x < 0, and for x == 0 with y <= 0",
    ),
    "log": (1, lambda x: x <= 0, "log(x) is undefined for x <= 0"),
    "log2": (1, lambda x: x <= 0, "log2(x) is undefined for x <= 0"),
    "sqrt": (1, lambda x: x < 0, "sqrt(x) is undefined for x < 0"),
    "inversesqrt": (1, lambda x: x <= 0, "inversesqrt(x) is undefined for x <= 0"),
}
_INT_CONSTRUCTORS = ("int", "uint", "ivec2", "ivec3", "ivec4", "uvec2", "uvec3", "uvec4")
_CHECKED_CALLS = frozenset(_INT_CONSTRUCTORS) | frozenset(_DOMAINS)


def undefined_operations(model: Model, definition: A.FunctionDefinition) -> list[UndefinedRead]:
    """Integer division by zero, out-of-range shifts and conversions, and built-ins outside
    their domain, where the operands that decide it are constants."""
    out = []
    binary, call, assignment = A.Binary, A.Call, A.Assignment  # (locals: every node is tested)
    int_ops, int_assignments, checked_calls = _INT_OPS, _INT_ASSIGNMENTS, _CHECKED_CALLS
    for n in model.body_nodes(definition):
        t = type(n)
        if t is binary:
            if n.op in int_ops:
                out.append(_binary(model, n, n.op, n.right))
        elif t is call:
            if n.callee in checked_calls:
                out.append(_call(model, n))
        elif t is assignment and n.op in int_assignments:
            out.append(_binary(model, n, n.op[:-1], n.value))
    return [u for u in out if u is not None]


_INT_OPS = frozenset(("/", "%", "<<", ">>"))
_INT_ASSIGNMENTS = frozenset(op + "=" for op in _INT_OPS)


def _components(v: Any) -> list:
    """The scalars of a folded constant (a vector is a tuple)."""
    if isinstance(v, tuple):
        return [x for c in v for x in _components(c)]
    return [v]


def _binary(model: Model, n: Any, op: str, right: Any) -> UndefinedRead | None:
    if op not in ("/", "%", "<<", ">>"):
        return None
    value = model.const_value(right)
    if value is None:
        return None
    if op == "/" and model.type_of(n).base == "float":
        return _float_division(model, n, value)
    scalars = [x for x in _components(value) if isinstance(x, int) and not isinstance(x, bool)]
    if op in ("/", "%"):
        if model.type_of(n).base not in ("int", "uint") or 0 not in scalars:
            return None
        return UndefinedRead(
            "division-by-zero",
            right.loc,
            f"integer {'division' if op == '/' else 'remainder'} by zero: the result is "
            "undefined (GLSL ES 3.00 5.9); drivers differ",
            "test the divisor before dividing, or divide by a value that cannot be zero",
            n,
            n,
        )
    bad = [x for x in scalars if not 0 <= x < SHIFT_BITS]
    if not bad:
        return None
    return UndefinedRead(
        "shift-out-of-range",
        right.loc,
        f"a shift by {bad[0]}: undefined for a count below 0 or of {SHIFT_BITS} or more "
        "(GLSL ES 3.00 5.9); drivers differ (most take the count modulo 32)",
        f"shift by a count in 0..{SHIFT_BITS - 1}",
        n,
        n,
    )


def _float_division(model: Model, n: Any, divisor: Any) -> UndefinedRead | None:
    """A float value that is not a constant divided by a constant with a zero component. GLSL
    ES 3.00 does not require infinities (4.5.1), and Mesa folds the constant's reciprocal at
    compile time: llvmpipe then gives arbitrary bits (measured: 0, 1.0, NaN or a subnormal,
    changing with the rest of the shader), where a zero known only at run time gives IEEE's
    +-Inf. Two constants divide at compile time (``1.0 / 0.0`` is Inf): not reported."""
    numerator = n.target if isinstance(n, A.Assignment) else n.left
    if model.const_value(numerator) is not None:
        return None
    if not any(isinstance(x, float) and x == 0.0 for x in _components(divisor)):
        return None
    return UndefinedRead(
        "division-by-zero",
        (n.value if isinstance(n, A.Assignment) else n.right).loc,
        "float division by a constant zero: GLSL ES 3.00 does not require infinities (4.5.1) "
        "and drivers differ (llvmpipe folds the division at compile time into arbitrary "
        "values, not +-Inf)",
        "divide by a value that cannot be zero, or write the infinity you want (1e30)",
        n,
        n,
    )


def _call(model: Model, n: A.Call) -> UndefinedRead | None:
    if not n.args:
        return None
    values = [model.const_value(a) for a in n.args]
    if any(v is None for v in values):
        return None
    name = n.callee
    if n.constructor and len(n.args) == 1 and name in _INT_CONSTRUCTORS:
        if model.type_of(n.args[0]).base != "float":
            return None
        lo, hi = UINT_RANGE if name.startswith("u") else INT_RANGE
        for x in _components(values[0]):
            if not isinstance(x, float):
                continue
            if not math.isfinite(x) or not lo <= math.trunc(x) < hi or (lo == 0 and x < 0):
                what = (
                    "a negative float to uint"
                    if lo == 0 and math.isfinite(x) and x < 0
                    else f"{x:g} to {'uint' if lo == 0 else 'int'}, outside its range"
                )
                return UndefinedRead(
                    "conversion-out-of-range",
                    n.loc,
                    f"converting {what} is undefined (GLSL ES 3.00 5.4.1); drivers differ",
                    "clamp the value into the integer type's range before converting",
                    n,
                    n,
                )
        return None
    domain = _DOMAINS.get(name)
    if domain is None or len(values) != domain[0] or not builtin_call(model, n, name):
        return None
    _, test, why = domain
    columns = [_components(v) for v in values]
    width = max(len(c) for c in columns)
    for i in range(width):
        args = [c[i] if len(c) > 1 else c[0] for c in columns]
        if all(isinstance(a, (int, float)) for a in args) and test(*args):
            return UndefinedRead(
                "domain",
                n.loc,
                f"{why} (GLSL ES 3.00 8.2): these constant arguments give a value drivers may "
                "choose (most give NaN)",
                "keep the argument inside the function's domain (e.g. max(x, 0.0) or abs(x))",
                n,
                n,
            )
    return None
