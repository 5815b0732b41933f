"""Static facts about the program the code generator needs before it emits anything: which
functions may discard or use derivatives, which globals are written, which "events" (break,
continue, return, discard) escape a statement, and a for loop's induction variable."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ...frontend import syntax as A
from ...semantics.analysis import param_directions, written_variable
from ...semantics.model import Symbol
from .common import DERIVATIVES, IMPLICIT_LOD, fold_tree

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ...semantics.model import Model


@dataclass(frozen=True)
class Events:
    brk: bool = False  # a break of the enclosing loop/switch
    cont: bool = False  # a continue of the enclosing loop
    ret: bool = False  # a return, a discard, or a call that may discard

    def __or__(self, o: Events) -> Events:
        return Events(self.brk or o.brk, self.cont or o.cont, self.ret or o.ret)

    @property
    def any(self) -> bool:
        return self.brk or self.cont or self.ret


NO_EVENTS = Events()


class Facts:
    """Program-wide facts the code generator needs: discarding and derivative-using functions,
    written globals, functions whose calls are lane-uniform for uniform arguments."""

    def __init__(self, model: Model, functions: list[Any]) -> None:
        self.model = model
        self.functions = functions  # callees first
        self.may_discard: set[int] = set()
        self.uses_derivs: set[int] = set()
        self.written_globals: set[int] = set()
        self.reads_lane_state: set[int] = set()  # reads gl_FragCoord or a written global
        # function id -> (globals it reads, globals it writes), through its calls
        self._global_effects: dict[int, tuple[frozenset[int], frozenset[int]]] = {}
        self.events: dict[int, Events] = {}  # node id -> events_of(node)
        self._discarding: dict[int, bool] = {}  # node id -> a discarding call in its subtree
        self._write_counts: dict[int, int] | None = None
        self._order: Any = None
        # (function id, ids of its uniform parameters) -> its out parameters left uniform
        # (Uniformity.uniform_outs)
        self.uniform_outs: dict[tuple[int, frozenset], set[int]] = {}
        for fn in functions:
            body = fn.node.body
            for node in body.walk():
                if isinstance(node, A.Discard):
                    self.may_discard.add(id(fn))
                elif isinstance(node, A.Call):
                    tgt = model.call_target(node)
                    if isinstance(tgt, Symbol):
                        if id(tgt) in self.may_discard:
                            self.may_discard.add(id(fn))
                        if id(tgt) in self.uses_derivs:
                            self.uses_derivs.add(id(fn))
                    elif getattr(tgt, "name", None) in DERIVATIVES + IMPLICIT_LOD:
                        self.uses_derivs.add(id(fn))
                for sym in self.written_variables(node):
                    if sym.kind == "global":
                        self.written_globals.add(id(sym))
        for fn in functions:
            for node in fn.node.body.walk():
                if isinstance(node, A.Identifier):
                    read = model.symbol_of(node)
                    if read is not None and (
                        (read.kind == "global" and id(read) in self.written_globals)
                        or (read.kind == "builtin-var" and read.name == "gl_FragCoord")
                    ):
                        self.reads_lane_state.add(id(fn))
                elif isinstance(node, A.Call):
                    tgt = model.call_target(node)
                    if isinstance(tgt, Symbol) and id(tgt) in self.reads_lane_state:
                        self.reads_lane_state.add(id(fn))

    @property
    def order(self) -> Any:
        """The program's EvalOrder (eval_order.py): which values Mesa computes before a later
        part of their statement writes what they read."""
        if self._order is None:
            from .eval_order import EvalOrder

            self._order = EvalOrder(self.model, self)
        return self._order

    def write_counts(self) -> dict[int, int]:
        """Symbol id -> how many places in the program's functions write it (assignments,
        ++/--, out and inout arguments), counted in one walk."""
        if self._write_counts is None:
            counts: dict[int, int] = {}
            for fn in self.functions:
                for node in fn.node.body.walk():
                    for sym in self.written_variables(node):
                        counts[id(sym)] = counts.get(id(sym), 0) + 1
            self._write_counts = counts
        return self._write_counts

    def discarding_call(self, n: Any) -> bool:
        """True when n is a call of a user function that may discard."""
        if not isinstance(n, A.Call):
            return False
        tgt = self.model.call_target(n)
        return isinstance(tgt, Symbol) and id(tgt) in self.may_discard

    def has_discarding_call(self, node: Any) -> bool:
        return fold_tree(
            node, self._discarding, lambda n, kids: any(kids) or self.discarding_call(n)
        )

    def written_variables(self, node: Any) -> list[Symbol]:
        """The variables a node itself writes (assignment, ++/--, out and inout arguments)."""
        return written_variables(self.model, node)

    def closed(self, fn: Symbol) -> bool:
        """A call of `fn` with uniform arguments gives a uniform result (no lane state read or
        written, no discard)."""
        return (
            id(fn) not in self.reads_lane_state
            and id(fn) not in self.may_discard
            and not self.writes_globals(fn)
        )

    def writes_globals(self, fn: Symbol) -> bool:
        """A call of `fn` writes a global, through the functions it calls."""
        return bool(self.global_effects(fn)[1])

    def global_effects(self, fn: Symbol) -> tuple[frozenset[int], frozenset[int]]:
        """(ids of the globals read, ids of the globals written) by a call of `fn`, through
        the functions it calls."""
        key = id(fn)
        known = self._global_effects.get(key)
        if known is not None:
            return known
        self._global_effects[key] = (frozenset(), frozenset())  # (no recursion in GLSL: a guard)
        reads: set[int] = set()
        writes: set[int] = set()
        for node in fn.node.body.walk():
            if isinstance(node, A.Identifier):
                sym = self.model.symbol_of(node)
                if sym is not None and sym.kind == "global":
                    reads.add(id(sym))
            elif isinstance(node, A.Call):
                tgt = self.model.call_target(node)
                if isinstance(tgt, Symbol) and tgt is not fn:
                    r, w = self.global_effects(tgt)
                    reads |= r
                    writes |= w
            writes.update(id(sym) for sym in self.written_variables(node) if sym.kind == "global")
        self._global_effects[key] = (frozenset(reads), frozenset(writes))
        return self._global_effects[key]


def written_lvalues(model: Model, node: Any) -> list[Any]:
    """The l-values a node itself writes: an assignment's target, the operand of ++/--, the
    out and inout arguments of a call."""
    if isinstance(node, A.Assignment):
        return [node.target]
    if isinstance(node, (A.Unary, A.Postfix)) and node.op in ("++", "--"):
        return [node.operand]
    if isinstance(node, A.Call):
        dirs = param_directions(model.call_target(node))
        return [a for a, d in zip(node.args, dirs) if d != "in"]
    return []


def written_variables(model: Model, node: Any) -> list[Symbol]:
    """The variables a node itself writes (`written_variable` of each of its `written_lvalues`)."""
    return [
        sym
        for t in written_lvalues(model, node)
        if (sym := written_variable(model, t)[0]) is not None
    ]


class SideEffects:
    """``effects(e)``: whether evaluating e writes a variable (an assignment, ++/--, an out or
    inout argument) or calls a user function, asked of many nodes of one program (memoized per
    node: linear over a tree)."""

    def __init__(self, model: Model) -> None:
        self.model = model
        self.memo: dict[int, bool] = {}

    def __call__(self, e: Any) -> bool:
        return fold_tree(e, self.memo, self._here)

    def _here(self, n: Any, kids: list[bool]) -> bool:
        if any(kids) or isinstance(n, (A.Assignment, A.Sequence)):
            return True
        if isinstance(n, (A.Unary, A.Postfix)) and n.op in ("++", "--"):
            return True
        return isinstance(n, A.Call) and (
            isinstance(self.model.call_target(n), Symbol)
            or any(d != "in" for d in param_directions(self.model.call_target(n)))
        )


def is_plain_read(e: Any) -> bool:
    """A value read without computing anything per lane: a literal, a variable, or a field or
    component of one (`!` of one too)."""
    while isinstance(e, (A.Field, A.Unary)) and (not isinstance(e, A.Unary) or e.op == "!"):
        e = e.operand if isinstance(e, A.Unary) else e.base
    return isinstance(e, (A.Identifier, A.IntLiteral, A.FloatLiteral, A.BoolLiteral))


def events_of(stmt: Any, facts: Facts, model: Model, in_loop_or_switch: bool = False) -> Events:
    """Events that escape `stmt` (a break/continue inside a nested loop does not escape it).
    Memoized per node (`facts.events`): asked of every statement at every nesting level."""

    def own(n: Any, kids: list[Events]) -> Events:
        if isinstance(n, A.Break):
            return Events(brk=True)
        if isinstance(n, A.Continue):
            return Events(cont=True)
        ev = (
            Events(ret=True)
            if isinstance(n, (A.Return, A.Discard)) or facts.discarding_call(n)
            else NO_EVENTS
        )
        for k in kids:
            ev = ev | k
        if isinstance(n, (A.For, A.While, A.DoWhile)):
            return Events(ret=ev.ret)
        if isinstance(n, A.Switch):
            return Events(cont=ev.cont, ret=ev.ret)
        return ev

    return fold_tree(stmt, facts.events, own)


def induction_variable(s: Any, model: Model, facts: Facts | None = None) -> Any:
    """The Symbol of a for loop's induction variable: declared in the init, written only by the
    step (`i++`, `++i`, `i--`, `i += e`, `i -= e`, `i = i + e`); else None. With `facts`, the
    body is not walked: the variable is scoped to the loop, so it is written nowhere but the
    step when the program writes it once in all (`Facts.write_counts`)."""
    if not isinstance(s, A.For) or not isinstance(s.init, A.DeclarationStatement):
        return None
    decl = s.init.decl
    if not isinstance(decl, A.VariableDeclaration) or len(decl.declarators) != 1:
        return None
    sym = model.symbol_of(decl.declarators[0])
    if sym is None or not (sym.type.is_scalar if hasattr(sym.type, "is_scalar") else False):
        return None
    step = s.step
    if isinstance(step, (A.Unary, A.Postfix)) and step.op in ("++", "--"):
        target = step.operand
    elif isinstance(step, A.Assignment) and step.op in ("=", "+=", "-="):
        target = step.target
    else:
        return None
    if not isinstance(target, A.Identifier) or model.symbol_of(target) is not sym:
        return None
    # the step writes nothing else; the body and the condition never write the variable
    writers = [n for n in step.walk() if isinstance(n, (A.Assignment, A.Unary, A.Postfix, A.Call))]
    for n in writers:
        if n is step:
            continue
        if isinstance(n, A.Assignment) or (
            isinstance(n, (A.Unary, A.Postfix)) and n.op in ("++", "--")
        ):
            return None
        if isinstance(n, A.Call) and written_lvalues(model, n):
            return None
    if facts is not None:
        return sym if facts.write_counts().get(id(sym), 0) == 1 else None
    for part in (s.cond, s.body):
        if part is None:
            continue
        for node in part.walk():
            if any(w is sym for w in written_variables(model, node)):
                return None
    return sym
