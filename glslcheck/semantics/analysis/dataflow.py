"""Dataflow facts of a checked program's functions, computed once per program and cached.

* `program_facts(model)` -> `ProgramFacts`: every function definition, each as `FunctionFacts`
  (those with a compile error apart: `broken`);
* `FunctionFacts`: an execution-order walk of one function (a `for` is walked init, cond, body,
  step), with for every node its enter/exit position, its *region* (the chain of branches and
  loops it is evaluated under: if/else arms, `?:` arms, the right side of `&&`/`||`, switch
  cases, loop bodies), every write to a variable (`=`, compound assignment, `++`/`--`, an
  `out`/`inout` argument, a declarator) and every call of a user function;
* pure-expression keys (`key`: the same key for the same value, identifiers by the symbol they
  name, locations ignored), `operands`, `is_pure`, `op_count`, `is_nontrivial`, `dominates` (A
  is evaluated before B on every path to B), `written_between` (a write to an operand between A
  and B) and `reaching_value` (the value a variable holds at a use);
* the sign analysis of `glslcheck.semantics.analysis.values` (`value_range`, `negative_witness`);
  answers about l-values, calls and functions (`written_variable`, `param_directions`,
  `pure_function`) are purity.py's.

Everything is keyed by `id(node)`: the model keeps the tree alive for as long as the facts.
"""

from __future__ import annotations

from bisect import bisect_right

from ...frontend import syntax as A
from ...language import builtin_functions as B
from ..model import Model, Symbol
from .purity import (
    function_cost,
    param_directions,
    pure_function,
    written_variable,
)
from .values import ValueRanges, numbers

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterable, Iterator
    from typing import Any, overload


def builtin_call(model: Model, e: A.Node, *names: str) -> bool:
    """`e` is a call of one of the built-in functions `names` (not a user function so named)."""
    return type(e) is A.Call and e.callee in names and isinstance(model.call_target(e), B.Overload)


def builtin_calls(
    model: Model, path: str, *names: str, arity: int | None = None
) -> Iterator[tuple[FunctionFacts, A.Call]]:
    """Every call of one of the built-in functions `names` (with `arity` arguments, if given) in
    the functions defined in the file `path` (those with a compile error apart), in source
    order, with the facts of the function it is in."""
    for fn in program_facts(model).in_file(path):
        for node in calls_in(fn, *names):  # the function's calls only, not every node
            if arity is None or len(node.args) == arity:
                yield fn, node


def is_float_type(t: Any) -> bool:
    return getattr(t, "base", None) == "float" and (t.is_scalar or t.is_vector)


class ProgramFacts:
    """The AST facts of one checked program (shared by every AST rule and every file of it)."""

    def __init__(self, model: Model) -> None:
        self.model = model
        self.definitions: list[A.FunctionDefinition] = [
            d for d in model.ast.decls if isinstance(d, A.FunctionDefinition) and d.body is not None
        ]
        self._fns: dict[int, FunctionFacts] = {}
        errors = [d.loc for d in model.errors if d.loc is not None]
        # functions with a compile error: their types are partly unknown (error recovery)
        self.broken: set[int] = {
            id(d)
            for d in self.definitions
            if any(
                e.path == d.loc.path and d.loc.line <= e.line <= (d.loc.end_line or d.loc.line)
                for e in errors
            )
        }

    def in_file(self, path: str, *, with_broken: bool = False) -> list[FunctionFacts]:
        """Facts of every function defined in the file `path`, in source order; a function with
        a compile error only `with_broken` (for rules that read names and scopes only)."""
        return [
            self.fn(d)
            for d in self.definitions
            if d.loc.path == path and (with_broken or id(d) not in self.broken)
        ]

    def broken_in_file(self, path: str) -> list[A.FunctionDefinition]:
        """The functions defined in `path` that have a compile error, in source order."""
        return [d for d in self.definitions if d.loc.path == path and id(d) in self.broken]

    def fn(self, definition: A.FunctionDefinition) -> FunctionFacts:
        f = self._fns.get(id(definition))
        if f is None:
            f = self._fns[id(definition)] = FunctionFacts(definition, self.model)
        return f

    def call_sites(self, function: Symbol) -> list[tuple[FunctionFacts, A.Call]]:
        """Every call of the user function `function` in a function that checks: (the caller's
        facts, the call), in source order."""
        sites: dict[int, list[tuple[FunctionFacts, A.Call]]] | None
        sites = self.__dict__.setdefault("_sites", None)
        if sites is None:
            sites = {}
            self._sites = sites
            for d in self.definitions:
                if id(d) in self.broken:
                    continue
                caller = self.fn(d)
                for n in caller.nodes:
                    if type(n) is A.Call:
                        target = self.model.call_target(n)
                        if isinstance(target, Symbol):
                            sites.setdefault(id(target), []).append((caller, n))
        return sites.get(id(function), [])

    def argument(self, fn: FunctionFacts, param: Symbol) -> tuple[FunctionFacts, A.Expr] | None:
        """The value an `in` parameter of `fn` holds, followed across the call: (the caller's
        facts, the argument) when `fn` has exactly one call site, in another function, and never
        writes the parameter; else None (several callers may pass different values)."""
        if param.kind != "param" or fn.symbol is None or fn.writes_to(param):
            return None
        params = [self.model.symbol_of(p) for p in fn.definition.proto.params]
        if param not in params or fn.symbol.params[params.index(param)][2] != "in":
            return None
        sites = self.call_sites(fn.symbol)
        if len(sites) != 1 or sites[0][0] is fn:
            return None
        caller, call = sites[0]
        i = params.index(param)
        return (caller, call.args[i]) if i < len(call.args) else None


_CACHE: dict[str, Any] = {"model": None, "facts": None}


if TYPE_CHECKING:  # a model's facts are a ProgramFacts; only no model gives none

    @overload
    def program_facts(model: Model) -> ProgramFacts: ...
    @overload
    def program_facts(model: None) -> _NoFacts: ...
    @overload
    def program_facts(model: Model | None) -> ProgramFacts | _NoFacts: ...


def program_facts(model: Model | None) -> ProgramFacts | _NoFacts:
    """The facts of `model`, built once per program (the linter lints its files in a row).
    Without a semantic model (a tree handed in by a test or a tool), no function has facts."""
    if model is None:
        return _NO_FACTS
    if _CACHE["model"] is not model:
        _CACHE["model"] = model
        _CACHE["facts"] = ProgramFacts(model)
    return _CACHE["facts"]


class _NoFacts:
    def in_file(self, path: str, *, with_broken: bool = False) -> list:
        return []

    def argument(self, fn: FunctionFacts, param: Symbol) -> None:
        return None

    def broken_in_file(self, path: str) -> list:
        return []


_NO_FACTS = _NoFacts()


def _written_number(e: Any) -> bool:
    """A number written out: a literal, a negated one, or a constructor of them (`vec3(1.0)`)."""
    while type(e) is A.Unary and e.op in ("-", "+"):
        e = e.operand
    if type(e) in (A.FloatLiteral, A.IntLiteral):
        return True
    return (
        type(e) is A.Call and e.constructor and bool(e.args) and all(map(_written_number, e.args))
    )


def _any_between(positions: list[int], lo: int, hi: int) -> bool:
    """Whether the sorted `positions` hold a value strictly between lo and hi."""
    i = bisect_right(positions, lo)
    return i < len(positions) and positions[i] < hi


def _apart(written: tuple[str, ...] | None, read: list[tuple[str, ...]]) -> bool:
    """A write to the field path `written` leaves every path of `read` unchanged: neither is a
    prefix of the other (`normal` and `point`; not `()`, the whole struct, and `point`)."""
    if written is None:
        return False
    return all(written[: len(r)] != r and r[: len(written)] != written for r in read)


_JUMPS = (A.Return, A.Break, A.Continue, A.Discard)
_WRITERS = frozenset(
    (A.Assignment, A.Unary, A.Postfix, A.Declarator, A.ConditionDeclaration, A.Call)
)  # _record_writes
# the node types `_visit` walks in an order or regions of their own (the others: their children
# in field order); tested first, as one set, instead of each in turn
_ORDERED = frozenset((A.If, A.Ternary, A.Binary, A.For, A.While, A.DoWhile, A.Compound, A.Switch))


_SWIZZLE_SETS = ("xyzw", "rgba", "stpq")


_NO_OPS = (0, False)  # op_count of a leaf


def _is_literal(e: Any) -> bool:
    return type(e) in (A.FloatLiteral, A.IntLiteral)


class Write:
    """One write to a variable: `kind` "=" (whole value `value`), "init" (a declarator with an
    initializer `value`), "decl" (a declarator without one), "op" (compound assignment, ++/--),
    "part" (a field, component or element), "out" (an out/inout argument)."""

    __slots__ = ("symbol", "pos", "kind", "value", "node")

    def __init__(self, symbol: Symbol, pos: int, kind: str, value: Any, node: Any) -> None:
        self.symbol, self.pos, self.kind, self.value, self.node = symbol, pos, kind, value, node


class FunctionFacts(ValueRanges):
    """An execution-order walk of one function definition (see the module docstring)."""

    def __init__(self, definition: A.FunctionDefinition, model: Model) -> None:
        self.definition = definition
        self.model = model
        self.symbol: Symbol | None = model.symbol_of(definition.proto)
        self.enter: dict[int, int] = {}
        self.exit: dict[int, int] = {}
        self.region: dict[int, tuple] = {}
        self.parent: dict[int, Any] = {}
        self.writes: dict[int, list[Write]] = {}  # id(symbol) -> writes in order
        self.user_calls: list[int] = []  # positions of calls to user functions
        self.loops: list[Any] = []  # loop statements, outermost first
        self.nodes: list[Any] = []  # every node in execution order
        self.calls: list[A.Call] = []  # the calls among them, in the same order
        self.dead: list[tuple[int, int]] = []  # (enter, exit) of statements after a return/jump
        self._clock = 0
        self._keys: dict[int, Any] = {}
        self._subst: dict[int, Any] = {}  # parameter symbol -> argument key, while inlining
        self._subst_stack: list[dict[int, Any]] = []
        self._pure: dict[int, bool] = {}
        self._ops: dict[int, tuple[int, bool]] = {}
        self._operands: dict[int, frozenset] = {}
        self._ranges: dict[int, tuple] = {}
        self.ok = True
        try:
            self._visit(definition.body, (), None)
        except RecursionError:  # absurdly deep nesting: no facts, no findings
            self.ok = False
            self.nodes = []
            self.calls = []

    # -- the walk ------------------------------------------------------------------------------
    def _visit(self, node: Any, region: tuple, parent: Any) -> None:
        if node is None:
            return
        i = id(node)
        self._clock += 1
        self.enter[i] = self._clock
        self.region[i] = region
        self.parent[i] = parent
        self.nodes.append(node)
        t = type(node)
        if t is A.Call:
            self.calls.append(node)
        if t not in _ORDERED:  # most nodes: children in field order, or none (one set test each)
            if t not in A.LEAF_CLASSES:
                for child in node.children():
                    self._visit(child, region, node)
        elif t is A.If:
            self._visit(node.cond, region, node)
            self._visit(node.then, region + ((i, 0),), node)
            self._visit(node.else_, region + ((i, 1),), node)
        elif t is A.Ternary:
            self._visit(node.cond, region, node)
            self._visit(node.then, region + ((i, 0),), node)
            self._visit(node.else_, region + ((i, 1),), node)
        elif t is A.Binary and node.op in ("&&", "||"):
            self._visit(node.left, region, node)
            self._visit(node.right, region + ((i, 1),), node)
        elif t is A.For:
            self.loops.append(node)
            self._visit(node.init, region, node)
            inner = region + ((i, "loop"),)
            self._visit(node.cond, inner, node)
            self._visit(node.body, inner, node)
            self._visit(node.step, inner, node)
        elif t in (A.While, A.DoWhile):
            self.loops.append(node)
            inner = region + ((i, "loop"),)
            for child in node.children():
                self._visit(child, inner, node)
        elif t is A.Compound:
            jumped = False
            for child in node.stmts:
                self._visit(child, region, node)
                if jumped:  # after `return`, `break`, `continue` or `discard`: never runs
                    self.dead.append((self.enter[id(child)], self.exit[id(child)]))
                jumped = jumped or type(child) in _JUMPS
        elif t is A.Switch:
            self._visit(node.expr, region, node)
            case = 0
            for s in node.body:
                if isinstance(s, A.Case):
                    case += 1
                self._visit(s, region + ((i, case),), node)
        else:
            for child in node.children():
                self._visit(child, region, node)
        self._clock += 1
        self.exit[i] = self._clock
        if t in _WRITERS:
            self._record_writes(node)

    def _record_writes(self, node: Any) -> None:
        t = type(node)
        pos = self.exit[id(node)]
        if t is A.Assignment:
            sym, whole = written_variable(self.model, node.target)
            if sym is not None:
                kind = ("=" if whole else "part") if node.op == "=" else "op"
                self._add(Write(sym, pos, kind, node.value if kind == "=" else None, node))
        elif t in (A.Unary, A.Postfix) and node.op in ("++", "--"):
            sym, _ = written_variable(self.model, node.operand)
            if sym is not None:
                self._add(Write(sym, pos, "op", None, node))
        elif t is A.Declarator or t is A.ConditionDeclaration:
            sym = self.model.symbol_of(node)
            if sym is not None:
                init = node.init
                self._add(Write(sym, pos, "init" if init is not None else "decl", init, node))
        elif t is A.Call:
            target = self.model.call_target(node)
            if isinstance(target, Symbol):
                self.user_calls.append(pos)
            for arg, d in zip(node.args, param_directions(target)):
                if d in ("out", "inout"):
                    sym, _ = written_variable(self.model, arg)
                    if sym is not None:
                        self._add(Write(sym, pos, "out", None, node))

    def _add(self, w: Write) -> None:
        self.writes.setdefault(id(w.symbol), []).append(w)

    # -- positions and paths -------------------------------------------------------------------
    def is_dead(self, node: Any) -> bool:
        """`node` is in a statement after a `return` (or break/continue/discard) of its block."""
        if not self.dead:
            return False
        pos = self.enter.get(id(node), -1)
        return any(lo <= pos <= hi for lo, hi in self.dead)

    def contains(self, outer: Any, inner: Any) -> bool:
        return (
            self.enter[id(outer)] <= self.enter[id(inner)]
            and self.exit[id(inner)] <= self.exit[id(outer)]
        )

    def dominates(self, a: Any, b: Any) -> bool:
        """`a` is evaluated, earlier, on every path that evaluates `b` (same or enclosing
        region)."""
        ra, rb = self.region[id(a)], self.region[id(b)]
        return self.exit[id(a)] < self.enter[id(b)] and rb[: len(ra)] == ra

    def enclosing_loops(self, node: Any) -> list[Any]:
        """Loop statements whose condition, body or step holds `node`, outermost first."""
        return [lp for lp in self.loops if self.contains(lp, node) and lp is not node]

    def writes_to(self, sym: Symbol) -> list[Write]:
        return self.writes.get(id(sym), [])

    def written_between(self, a: Any, b: Any, syms: Iterable[Symbol], reads: Any = None) -> bool:
        """Whether a variable of `syms` may be written after `a` and before `b` is evaluated:
        a write between them, or anywhere in a loop around `b` that is not around `a`. With
        `reads` (an expression of this function), a write to a struct field the expression
        never reads (`rec.normal = ...` when it reads `rec.point`) does not count."""
        if reads is not None:
            paths = self._field_paths(reads)
            syms = [
                s
                for s in syms
                if not (paths.get(s) and all(paths[s]))  # read whole somewhere: any write
                or self._written_between(a, b, [s], paths[s])
            ]
        return self._written_between(a, b, syms)

    def _field_paths(self, e: Any) -> dict[Symbol, list[tuple[str, ...]]]:
        """For each variable `e` reads, the struct-field paths it reads it by (`rec.point` ->
        ("point",); `rec` whole or through an index -> ()). Cached per expression."""
        cache = self.__dict__.setdefault("_field_path_cache", {})
        if id(e) in cache:
            return cache[id(e)]
        out: dict[Symbol, list[tuple[str, ...]]] = {}
        cache[id(e)] = out
        for n in e.walk():
            if type(n) is not A.Identifier:
                continue
            sym = self.model.symbol_of(n)
            if sym is None:
                continue
            path: list[str] = []
            up = self.parent.get(id(n)) if n is not e else None
            child: A.Expr = n
            while type(up) is A.Field and up.base is child and not self.model.is_swizzle(up):
                path.append(up.name)
                child, up = up, (self.parent.get(id(up)) if up is not e else None)
            out.setdefault(sym, []).append(tuple(path))
        return out

    def _write_path(self, w: Write) -> tuple[str, ...] | None:
        """The struct-field path a "part" assignment writes (`rec.normal = ...` -> ("normal",)),
        None when it is not one of fields only."""
        if w.kind != "part" or type(w.node) is not A.Assignment:
            return None
        path: list[str] = []
        t = w.node.target
        while type(t) is A.Field and not self.model.is_swizzle(t):
            path.append(t.name)
            t = t.base
        if type(t) is not A.Identifier or not path:
            return None  # an element or components: not a field apart
        return tuple(reversed(path))

    def _written_between(
        self, a: Any, b: Any, syms: Iterable[Symbol], read_paths: list | None = None
    ) -> bool:
        lo, hi = self.exit[id(a)], self.enter[id(b)]
        spans = [(lo, hi)]
        loops_a = {id(lp) for lp in self.enclosing_loops(a)}
        for loop in self.enclosing_loops(b):
            if id(loop) not in loops_a:
                spans.append((self.enter[id(loop)], self.exit[id(loop)]))
        globals_read = False
        for s in syms:
            if s.kind == "global" and s.qualifier != "const":
                globals_read = True
            positions = self._positions(id(s), lambda: [w.pos for w in self.writes_to(s)])
            if read_paths is not None:  # a field write elsewhere than every path read: none
                writes = self.writes_to(s)  # in position order, as `positions`
                for lo_, hi_ in spans:
                    i = bisect_right(positions, lo_)
                    while i < len(positions) and positions[i] < hi_:
                        if not _apart(self._write_path(writes[i]), read_paths):
                            return True
                        i += 1
                continue
            if any(_any_between(positions, lo_, hi_) for lo_, hi_ in spans):
                return True
        if globals_read:
            calls = self._positions("calls", lambda: self.user_calls)
            return any(_any_between(calls, lo_, hi_) for lo_, hi_ in spans)
        return False

    def _positions(self, key: Any, make) -> list[int]:
        """Sorted positions, cached: bisected instead of scanned (a 1 MB shader writing one
        variable 27,000 times made repeated-expression cubic)."""
        cache = self.__dict__.setdefault("_position_cache", {})
        if key not in cache:
            cache[key] = sorted(make())
        return cache[key]

    # -- expression properties -----------------------------------------------------------------
    def key(self, e: Any) -> Any:
        """A structural key: equal keys mean the same computation on the same variables.

        The same value written differently gets the same key: `+` and `*` operands in any order
        and grouping (not a matrix product), a component by its index (`v.x`, `v.r`, `v.xy.x`),
        a swizzle that keeps every component in order as the vector itself (`p.xy` of a vec2),
        `dot(a, b)` as the sum of its component products, and a pure user function returning
        one expression as that expression of its arguments: `lenSq(dp.xy)` is
        `dp.x * dp.x + dp.y * dp.y`."""
        if self._subst:  # inside an inlined user function: keys depend on the call
            return self._key(e)
        i = id(e)
        k = self._keys.get(i)
        if k is None:
            k = self._keys[i] = self._key(e)
        return k

    def _key(self, e: Any) -> Any:
        t = type(e)
        if t is A.Identifier:
            sym = self.model.symbol_of(e)
            if sym is not None and id(sym) in self._subst:
                return self._subst[id(sym)]
            return ("I", id(sym) if sym is not None else e.name)
        if t is A.FloatLiteral:
            return ("F", e.value)
        if t is A.IntLiteral:
            return ("N", e.value, e.unsigned)
        if t is A.BoolLiteral:
            return ("Z", e.value)
        if t is A.Binary:
            terms = self.terms(e)
            if terms is not None:
                # operands in a fixed order (by hash: any order works, the same within a run)
                return ("+" if e.op == "+" else "*", tuple(sorted(terms, key=hash)))
            return ("B", e.op, self.key(e.left), self.key(e.right))
        if t is A.Unary and e.op not in ("++", "--"):
            return ("U", e.op, self.key(e.operand))
        if t is A.Call and e.array is None and e.struct_ is None:
            target = self.model.call_target(e)
            if e.callee == "dot" and len(e.args) == 2 and isinstance(target, B.Overload):
                n = getattr(self.model._types.get(id(e.args[0])), "size", None)
                if isinstance(n, int) and n > 1:
                    products = (
                        (
                            "*",
                            tuple(
                                sorted(
                                    (self._component(e.args[0], i), self._component(e.args[1], i)),
                                    key=hash,
                                )
                            ),
                        )
                        for i in range(n)
                    )
                    return ("+", tuple(sorted(products, key=hash)))
            inlined = self._inline(e, target)
            if inlined is not None:
                return inlined
            return ("C", e.callee, tuple(self.key(a) for a in e.args))
        if t is A.Field:
            if self.model.is_swizzle(e):
                picked = self.model.swizzle_indices(e)
                if len(picked) == 1:
                    return self._component(e.base, picked[0])
                size = getattr(self.model.type_of(e.base), "size", None)
                if list(picked) == list(range(size or 0)):
                    return self.key(e.base)  # `v.xy` of a vec2 is `v`
            return (".", e.name, self.key(e.base))
        if t is A.Index:
            return ("[", self.key(e.base), self.key(e.index))
        if t is A.Ternary:
            return ("?", self.key(e.cond), self.key(e.then), self.key(e.else_))
        if t is A.MethodCall:
            return ("M", e.name, self.key(e.base))
        return ("X", id(e))  # assignments, ++/--, sequences: never the same twice

    def _commutes(self, e: Any) -> bool:
        """`+` always; `*` unless a matrix is involved (a matrix product has an order); `/` of
        floats (a float quotient is a product by the inverse: `a / b * c` is `a * c / b`; an
        integer quotient rounds, so it is not)."""
        if e.op == "+":
            return True
        types = self.model._types
        left, right = types.get(id(e.left)), types.get(id(e.right))
        # (`is None`, not `None in (left, right)`: that calls the types' Python __eq__)
        if (
            left is None
            or right is None
            or getattr(left, "is_matrix", False)
            or getattr(right, "is_matrix", False)
        ):
            return False
        return e.op == "*" or (
            getattr(left, "base", None) == "float" and getattr(right, "base", None) == "float"
        )

    def terms(self, e: Any) -> list[Any] | None:
        """The keys of the operands of a chain of `+`, or of `*` and `/` (a divisor as
        ("inv", its key)), in any grouping: `a / b * a / b` -> a, inv b, a, inv b. None when
        `e` is not such a chain (a matrix product, an integer quotient, another operator)."""
        if type(e) is not A.Binary or e.op not in ("+", "*", "/") or not self._commutes(e):
            return None
        ops = ("+",) if e.op == "+" else ("*", "/")
        out: list[Any] = []
        stack: list[tuple[A.Expr, bool]] = [(e, False)]  # depth first, left before right
        while stack:
            x, inverse = stack.pop()
            if type(x) is A.Binary and x.op in ops and self._commutes(x):
                stack.append((x.right, inverse != (x.op == "/")))
                stack.append((x.left, inverse))
            else:
                k = self.key(x)
                out.append(("inv", k) if inverse else k)
        return out

    def written_factors(self, e: Any) -> tuple[list[Any], list[Any]] | None:
        """A `*`/`/` chain as written, left to right: its nodes down the left side (`e`, then
        `e.left`, ...) and the keys of its factors, a divisor as ("inv", key) and a parenthesised
        right operand as one factor (`a / b * a / b` -> a, inv b, a, inv b; `(d * d) / (i * i)`
        -> d, d, inv (i * i)). None when `e` is not a float or integer product chain."""
        if type(e) is not A.Binary or e.op not in ("*", "/") or not self._commutes(e):
            return None
        spine, keys = [], []
        x: A.Expr = e
        while type(x) is A.Binary and x.op in ("*", "/") and self._commutes(x):
            spine.append(x)
            k = self.key(x.right)
            keys.append(("inv", k) if x.op == "/" else k)
            x = x.left
        keys.append(self.key(x))
        return spine, keys[::-1]

    def component_key(self, e: Any, i: int) -> Any:
        """The key of component `i` of the vector `e` (`v.x` for `v`, 0)."""
        return self._component(e, i)

    @staticmethod
    def sum_of_squares_key(keys: list[Any]) -> Any:
        """The key `x * x + y * y + ...` (and `dot(v, v)`, `lenSq(v)`) gets for these
        component keys."""
        squares = (("*", tuple(sorted((k, k), key=hash))) for k in keys)
        return ("+", tuple(sorted(squares, key=hash)))

    def _component(self, e: Any, i: int) -> Any:
        """The key of component `i` of the vector `e` (swizzles composed: `v.zy` 0 is `v.z`)."""
        while type(e) is A.Field and self.model.is_swizzle(e):
            i = self.model.swizzle_indices(e)[i]
            e = e.base
        k = self.key(e)
        while k[0] == "." and isinstance(k[1], str) and i < len(k[1]):  # a swizzle passed in
            sets = [c for c in _SWIZZLE_SETS if k[1][i] in c]
            if not sets or not all(ch in sets[0] for ch in k[1]):
                break
            i, k = sets[0].index(k[1][i]), k[2]
        return ("comp", i, k)

    def _inline(self, call: Any, target: Any) -> Any:
        """The key of a pure user function's single returned expression with its parameters
        replaced by the arguments' keys; None when the function is not that simple."""
        d = getattr(target, "node", None)
        if (
            not isinstance(target, Symbol)
            or not isinstance(d, A.FunctionDefinition)
            or d.body is None
            or len(self._subst_stack) >= 4
            or not pure_function(self.model, target)
        ):
            return None
        stmts = d.body.stmts
        if len(stmts) != 1 or type(stmts[0]) is not A.Return or stmts[0].value is None:
            return None
        params = [self.model.symbol_of(p) for p in d.proto.params]
        if None in params or len(params) != len(call.args):
            return None
        subst = {id(p): self.key(a) for p, a in zip(params, call.args)}
        self._subst_stack.append(self._subst)
        self._subst = {**self._subst, **subst}
        try:
            return self.key(stmts[0].value)
        finally:
            self._subst = self._subst_stack.pop()

    def is_pure(self, e: Any) -> bool:
        """No writes and no calls of user functions or of built-ins with out parameters."""
        i = id(e)
        p = self._pure.get(i)
        if p is None:
            p = self._pure[i] = self._is_pure(e)
        return p

    def _is_pure(self, e: Any) -> bool:
        t = type(e)
        if t in (A.Assignment, A.Postfix, A.Sequence) or (t is A.Unary and e.op in ("++", "--")):
            return False
        if t is A.Call:
            target = self.model.call_target(e)
            if target is None or (
                isinstance(target, Symbol) and not pure_function(self.model, target)
            ):
                return False
            if isinstance(target, B.Overload) and target.out_params:
                return False
        leaves = A.LEAF_CLASSES  # a name or literal is pure: no call to ask
        for c in e.children():
            if type(c) not in leaves and not self.is_pure(c):
                return False
        return True

    def op_count(self, e: Any) -> tuple[int, bool]:
        """(operations, whether a built-in costlier than an add is called) of a pure expression."""
        i = id(e)
        r = self._ops.get(i)
        if r is None:
            t = type(e)
            if t in A.LEAF_CLASSES:  # a name or literal: no operation (not worth a cache entry)
                return _NO_OPS
            n, costly = 0, False
            if (
                t is A.Binary
                or t is A.Ternary
                or (t is A.Unary and e.op != "+" and not _is_literal(e.operand))
            ):
                n = 1  # (a negative literal, `-1.0`, is a constant, not an operation)
            elif t is A.Call:
                target = self.model.call_target(e)
                if isinstance(target, B.Overload):
                    n = 1
                    costly = B.COST_ORDER[target.cost] > B.COST_ORDER[B.CHEAP]
                elif isinstance(target, Symbol):  # a pure user function: what its body costs
                    n, costly = 1, function_cost(self.model, target)
            for c in e.children():
                cn, cc = self.op_count(c)
                n += cn
                costly = costly or cc
            r = self._ops[i] = (n, costly)
        return r

    def is_nontrivial(self, e: Any) -> bool:
        """At least two operations, or a call of a built-in costlier than an add; not constant."""
        if not isinstance(e, A.Expr):
            return False
        n, costly = self.op_count(e)
        return (n >= 2 or costly) and not self.model.is_constant(e)

    def worth_reusing(self, e: Any) -> bool:
        """Non-trivial, a call of a built-in (`step(1.0, uv.x)`), or one float or vector arithmetic
        operation that is not a sign change (`d * invI`, `light.center - position`; not `-1.0 *
        n`): a value a TA expects to be computed once."""
        builtin = type(e) is A.Call and not e.constructor
        if builtin and isinstance(self.model.call_target(e), B.Overload):
            return not self.model.is_constant(e)  # a built-in's call, however cheap: `step(a, x)`
        if type(e) is not A.Binary or e.op not in ("+", "-", "*", "/"):
            return self.is_nontrivial(e)
        n, costly = self.op_count(e)
        if n >= 2 or costly:
            return not self.model.is_constant(e)
        if n != 1 or not is_float_type(self.model.type_of(e)) or self.model.is_constant(e):
            return False
        # a unit written out (`-1.0 * n`: a sign change); a named one (`iTime * FREQ`, FREQ 1.0
        # for now) is a setting, and the product is worth reusing like any other
        unit = [
            x
            for x in (e.left, e.right)
            if _written_number(x) and numbers(self.model.const_value(x)) in ([1.0], [-1.0])
        ]
        return not (unit and e.op in ("*", "/"))

    def operands(self, e: Any) -> frozenset:
        """The variables (Symbols) an expression reads."""
        i = id(e)
        r = self._operands.get(i)
        if r is None:
            if type(e) is A.Identifier:
                sym = self.model.symbol_of(e)
                r = frozenset((sym,)) if sym is not None else frozenset()
            else:
                r = frozenset().union(*(self.operands(c) for c in e.children()))
            self._operands[i] = r
        return r

    def reaching_value(self, ident: A.Identifier, sym: Symbol, as_computed: bool = False) -> Any:
        """The expression last assigned to `sym` before `ident` when that assignment is on every
        path to it, no other write can reach it (for a global, no call between), it assigns the
        whole value and no variable the expression reads is written in between (so it still has
        that value); else None. `as_computed`: the expression as it was computed then, its
        variables written since or not (for what is true of any value it computes: an integer
        from `floor()`)."""
        return self._reaching(ident, sym, None, as_computed)

    def reaching_component(self, read: A.Field, sym: Symbol) -> Any:
        """reaching_value of one component of a vector variable, as computed: the value last
        assigned to the component `read` reads (`v.x = floor(v.x * n);` before `v.x`), past
        writes of its other components (`v.y = ...`)."""
        return self._reaching(read, sym, read, True)

    def _reaching(self, node: Any, sym: Symbol, component: Any, as_computed: bool) -> Any:
        pos = self.enter.get(id(node))
        if pos is None:
            return None
        ws = self.writes_to(sym)
        before = [w for w in ws if w.pos < pos]
        if component is not None:
            mine = set(self.model.swizzle_indices(component))
            while before and not mine & self._components_written(before[-1].node, sym):
                before.pop()
        if not before:
            return None
        last = before[-1]
        if component is None:
            if last.kind not in ("=", "init"):
                return None
        elif last.kind != "part" or self.key(last.node.target) != self.key(component):
            return None
        value = last.node.value if component is not None else last.value
        if not self.dominates(last.node, node):
            return None
        for loop in self.enclosing_loops(node):  # a later write in the loop reaches it again
            if any(w.pos > pos and self.contains(loop, w.node) for w in ws):
                return None
        if sym.kind == "global" and _any_between(
            self._positions("calls", lambda: self.user_calls), last.pos, pos
        ):
            return None  # a call between may write it
        # `l = lengthSq(dp.xy); dp.xy = ...; use(l)`: l no longer equals its expression
        others = self.operands(value) - {sym}
        if others and not as_computed and self.written_between(last.node, node, others):
            return None
        return value

    def _components_written(self, node: Any, sym: Symbol) -> set[int]:
        """The components of `sym` a write writes: a swizzle's (`v.y = ...`), else all (-1)."""
        t = node.target if type(node) is A.Assignment else None
        if type(t) is A.Field and type(t.base) is A.Identifier and self.model.is_swizzle(t):
            return set(self.model.swizzle_indices(t))  # (the write is to sym: t.base is sym)
        return {0, 1, 2, 3, -1}

    def constant_through_locals(self, e: Any) -> tuple[Any, A.Identifier | None]:
        """The constant value of `e` (None: not constant) and the local variable it was reached
        through (None: `e` is a constant expression itself). A local is followed to the value
        reaching it (`float highlight = 4.0; ... pow(s, highlight)`), and on through locals,
        and scalar arithmetic of such values is folded (`float e = 2.0; e = e * e;`: 4)."""
        value = self.model.const_value(e)
        if value is not None:
            return value, None
        through: list[A.Identifier] = []
        value = self._fold_locals(e, through, 0)
        return value, (through[0] if value is not None and through else None)

    def _fold_locals(self, e: Any, through: list[A.Identifier], depth: int) -> Any:
        """constant_through_locals' value: a constant, a local's reaching value, or + - * / and
        negation of scalar ones (folded in double precision: the exponents and factors asked
        about are small integers and halves, exact in float32 too); None otherwise."""
        value = self.model.const_value(e)
        if value is not None or depth >= 8:  # (a chain of locals no longer than 8)
            return value
        if type(e) is A.Identifier:
            sym = self.model.symbol_of(e)
            if sym is None or sym.kind != "local":
                return None
            reaching = self.reaching_value(e, sym)
            if reaching is None:
                return None
            through.append(e)
            return self._fold_locals(reaching, through, depth + 1)
        t = self.model.type_of(e)
        if not (is_float_type(t) and t.is_scalar):
            return None  # (int arithmetic divides otherwise; vectors are not asked about)
        if type(e) is A.Unary and e.op in ("-", "+"):
            x = numbers(self._fold_locals(e.operand, through, depth + 1))
            return (-x[0] if e.op == "-" else x[0]) if len(x) == 1 else None
        if type(e) is A.Binary and e.op in ("+", "-", "*", "/"):
            a = numbers(self._fold_locals(e.left, through, depth + 1))
            b = numbers(self._fold_locals(e.right, through, depth + 1))
            if len(a) != 1 or len(b) != 1 or (e.op == "/" and b[0] == 0.0):
                return None
            u, v = a[0], b[0]
            return {"+": u + v, "-": u - v, "*": u * v, "/": u / v}[e.op]
        return None


def calls_in(fn: FunctionFacts, *names: str) -> Iterator[A.Call]:
    """Calls of the built-ins `names` in a function, in execution order."""
    for n in fn.calls:
        if n.callee in names and isinstance(fn.model.call_target(n), B.Overload):
            yield n
