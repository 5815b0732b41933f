"""Shared facts about expressions for the AST lint rules (not a rule: no NAME, not in the table).

Owns what several rules ask of one function body, computed once per program and cached:

* `facts(ctx)` -> `ProgramFacts`: the functions defined in the linted file, each as `FnFacts`;
* `FnFacts`: an execution-order walk of one function (a `for` is walked init, cond, body,
  step), with for every node its enter/exit position, its *region* (the chain of branches and
  loops it is evaluated under: if/else arms, `?:` arms, the right side of `&&`/`||`, switch
  cases, loop bodies), every write to a variable (`=`, compound assignment, `++`/`--`, an
  `out`/`inout` argument, a declarator) and every call of a user function;
* pure-expression keys (`key`: structural, identifiers by the symbol they name, locations
  ignored), `operands`, `is_pure`, `op_count`, `is_nontrivial`, `dominates` (A is evaluated
  before B on every path to B) and `written_between` (a write to an operand between A and B);
* a sign analysis, `value_range(expr)`: an interval (lo, hi; None for unbounded) and, when the
  value can be negative, a *witness*: the sub-expression that makes it so (a dot product of two
  different vectors, a difference, a negation, sin/cos, a reflect/refract/cross result, a
  negative constant). Unknown values (a parameter, a user function's result) have no witness:
  rules report "can be negative" only with one. Dot products of different vectors are taken as
  cosines in [-1, 1] (lighting code dots unit vectors), so `1.0 - max(dot(n, v), 0.0)` is known
  to be >= 0. A variable's value is the one assigned by its last write before the use when that
  write is on every path to the use (else unknown).

Everything is keyed by `id(node)`: the model keeps the tree alive for as long as the facts.
"""

from __future__ import annotations

import math
import re
from bisect import bisect_right
from typing import Any, Iterable, Iterator

from ... import ast as A
from ... import builtins as B
from ...check.model import Symbol
from ...diagnostics import Location
from ...printer import to_glsl

COMPARISONS = ("<", "<=", ">", ">=")
FLIPPED = {"<": ">", "<=": ">=", ">": "<", ">=": "<="}  # a op b  <=>  b FLIPPED[op] a
_NONNEG_UNIFORMS = {"iTime", "iTimeDelta", "iFrameRate", "iFrame", "iChannelTime",
                    "iChannelResolution", "iResolution", "iDate", "iSampleRate"}


# ---------------------------------------------------------------------------------------------
# Program and function facts
# ---------------------------------------------------------------------------------------------


class ProgramFacts:
    """The AST facts of one checked program (shared by every AST rule and every file of it)."""

    def __init__(self, model: Any) -> None:
        self.model = model
        self.definitions: list[A.FunctionDefinition] = [
            d for d in model.ast.decls if isinstance(d, A.FunctionDefinition) and d.body is not None
        ]
        self._fns: dict[int, FnFacts] = {}
        errors = [d.loc for d in model.errors if d.loc is not None]
        # functions with a compile error: their types are partly unknown (error recovery)
        self.broken: set[int] = {
            id(d) for d in self.definitions
            if any(e.path == d.loc.path and d.loc.line <= e.line <= (d.loc.end_line or d.loc.line) for e in errors)
        }

    def in_file(self, path: str, *, with_broken: bool = False) -> list["FnFacts"]:
        """Facts of every function defined in the file `path`, in source order; a function with
        a compile error only `with_broken` (for rules that read names and scopes only)."""
        return [
            self.fn(d) for d in self.definitions
            if d.loc.path == path and (with_broken or id(d) not in self.broken)
        ]

    def broken_in_file(self, path: str) -> list[A.FunctionDefinition]:
        """The functions defined in `path` that have a compile error, in source order."""
        return [d for d in self.definitions if d.loc.path == path and id(d) in self.broken]

    def fn(self, definition: A.FunctionDefinition) -> "FnFacts":
        f = self._fns.get(id(definition))
        if f is None:
            f = self._fns[id(definition)] = FnFacts(definition, self.model)
        return f


_CACHE: dict[str, Any] = {"model": None, "facts": None}


def facts(ctx: Any) -> ProgramFacts:
    """The facts of `ctx.model`, built once per program (the engine lints its files in a row).
    Without a semantic model (a tree handed in by a test or a tool), no function has facts."""
    if ctx.model is None:
        return _NO_FACTS
    if _CACHE["model"] is not ctx.model:
        _CACHE["model"] = ctx.model
        _CACHE["facts"] = ProgramFacts(ctx.model)
    return _CACHE["facts"]


class _NoFacts:
    def in_file(self, path: str, *, with_broken: bool = False) -> list:
        return []

    def broken_in_file(self, path: str) -> list:
        return []


_NO_FACTS = _NoFacts()


def _any_between(positions: list[int], lo: int, hi: int) -> bool:
    """Whether the sorted `positions` hold a value strictly between lo and hi."""
    i = bisect_right(positions, lo)
    return i < len(positions) and positions[i] < hi


_JUMPS = (A.Return, A.Break, A.Continue, A.Discard)


_SWIZZLE_SETS = ("xyzw", "rgba", "stpq")


def _is_literal(e: Any) -> bool:
    return type(e) in (A.FloatLiteral, A.IntLiteral)


def _model_cache(model: Any, name: str) -> dict:
    cache = model.__dict__.get(name)
    if cache is None:
        cache = model.__dict__[name] = {}
    return cache


def pure_function(model: Any, sym: Symbol, _seen: frozenset = frozenset()) -> bool:
    """A user function whose result depends only on its arguments: `in` parameters only, no
    write to a global, no read of a global variable that is not const (uniforms are constant in
    a frame), and only pure functions called (`float lenSq(vec2 v) { return dot(v, v); }`)."""
    cache = _model_cache(model, "_lint_pure")
    if id(sym) in cache:
        return cache[id(sym)]
    d = sym.node
    ok = (isinstance(d, A.FunctionDefinition) and d.body is not None and id(sym) not in _seen
          and all(direction == "in" for _, _, direction in sym.params))
    if ok:
        for n in d.body.walk():
            t = type(n)
            if t is A.Identifier:
                s = model.symbol_of(n)
                if s is not None and s.kind == "global" and s.qualifier != "const":
                    ok = False
            elif t is A.Call:
                target = model.call_target(n)
                if target is None or (isinstance(target, B.Overload) and target.out_params) or (
                        isinstance(target, Symbol) and not pure_function(model, target, _seen | {id(sym)})):
                    ok = False
            if not ok:
                break
    if not _seen:
        cache[id(sym)] = ok
    return ok


def function_cost(model: Any, sym: Symbol) -> bool:
    """Whether calling the user function costs more than an add: two operations or a costly
    built-in in its body (a wrapper like `asPoint(v)`, `vec4(v, 1.0)`, does not)."""
    cache = _model_cache(model, "_lint_cost")
    if id(sym) not in cache:
        cache[id(sym)] = False  # a recursive call (an error anyway) costs nothing more
        ops, costly = 0, False
        d = sym.node
        for n in (d.body.walk() if isinstance(d, A.FunctionDefinition) and d.body is not None else ()):
            if type(n) in (A.Binary, A.Ternary) or (type(n) is A.Unary and n.op != "+"):
                ops += 1
            elif type(n) is A.Call:
                target = model.call_target(n)
                if isinstance(target, B.Overload):
                    ops += 1
                    costly = costly or B.COST_ORDER[target.cost] > B.COST_ORDER[B.CHEAP]
                elif isinstance(target, Symbol):
                    costly = costly or function_cost(model, target)
        cache[id(sym)] = costly or ops >= 2
    return cache[id(sym)]


class Write:
    """One write to a variable: `kind` "=" (whole value `value`), "init" (a declarator with an
    initializer `value`), "decl" (a declarator without one), "op" (compound assignment, ++/--),
    "part" (a field, component or element), "out" (an out/inout argument)."""

    __slots__ = ("symbol", "pos", "kind", "value", "node")

    def __init__(self, symbol: Symbol, pos: int, kind: str, value: Any, node: Any) -> None:
        self.symbol, self.pos, self.kind, self.value, self.node = symbol, pos, kind, value, node


class FnFacts:
    """An execution-order walk of one function definition (see the module docstring)."""

    def __init__(self, definition: A.FunctionDefinition, model: Any) -> None:
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

    # -- the walk ------------------------------------------------------------------------------
    def _tick(self) -> int:
        self._clock += 1
        return self._clock

    def _visit(self, node: Any, region: tuple, parent: Any) -> None:
        if node is None:
            return
        i = id(node)
        self.enter[i] = self._tick()
        self.region[i] = region
        self.parent[i] = parent
        self.nodes.append(node)
        t = type(node)
        if t is A.If:
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
        self.exit[i] = self._tick()
        self._record_writes(node)

    def _record_writes(self, node: Any) -> None:
        t = type(node)
        pos = self.exit[id(node)]
        if t is A.Assignment:
            sym, whole = self.target_symbol(node.target)
            if sym is not None:
                kind = ("=" if whole else "part") if node.op == "=" else "op"
                self._add(Write(sym, pos, kind, node.value if kind == "=" else None, node))
        elif t in (A.Unary, A.Postfix) and node.op in ("++", "--"):
            sym, _ = self.target_symbol(node.operand)
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
                dirs = [d for _, _, d in target.params]
            elif isinstance(target, B.Overload):
                dirs = list(target.qualifiers)
            else:
                return
            for arg, d in zip(node.args, dirs):
                if d in ("out", "inout"):
                    sym, _ = self.target_symbol(arg)
                    if sym is not None:
                        self._add(Write(sym, pos, "out", None, node))

    def _add(self, w: Write) -> None:
        self.writes.setdefault(id(w.symbol), []).append(w)

    def target_symbol(self, target: Any) -> tuple[Symbol | None, bool]:
        """The variable an l-value writes and whether it writes all of it."""
        whole = True
        while isinstance(target, (A.Field, A.Index)):
            whole = False
            target = target.base
        if isinstance(target, A.Identifier):
            return self.model.symbol_of(target), whole
        return None, whole

    # -- positions and paths -------------------------------------------------------------------
    def is_dead(self, node: Any) -> bool:
        """`node` is in a statement after a `return` (or break/continue/discard) of its block."""
        pos = self.enter.get(id(node), -1)
        return any(lo <= pos <= hi for lo, hi in self.dead)

    def contains(self, outer: Any, inner: Any) -> bool:
        return self.enter[id(outer)] <= self.enter[id(inner)] and self.exit[id(inner)] <= self.exit[id(outer)]

    def dominates(self, a: Any, b: Any) -> bool:
        """`a` is evaluated, earlier, on every path that evaluates `b` (same or enclosing region)."""
        ra, rb = self.region[id(a)], self.region[id(b)]
        return self.exit[id(a)] < self.enter[id(b)] and rb[: len(ra)] == ra

    def enclosing_loops(self, node: Any) -> list[Any]:
        """Loop statements whose condition, body or step holds `node`, outermost first."""
        return [l for l in self.loops if self.contains(l, node) and l is not node]

    def writes_to(self, sym: Symbol) -> list[Write]:
        return self.writes.get(id(sym), [])

    def written_between(self, a: Any, b: Any, syms: Iterable[Symbol]) -> bool:
        """Whether a variable of `syms` may be written after `a` and before `b` is evaluated:
        a write between them, or anywhere in a loop around `b` that is not around `a`."""
        lo, hi = self.exit[id(a)], self.enter[id(b)]
        spans = [(lo, hi)]
        loops_a = {id(l) for l in self.enclosing_loops(a)}
        for loop in self.enclosing_loops(b):
            if id(loop) not in loops_a:
                spans.append((self.enter[id(loop)], self.exit[id(loop)]))
        globals_read = False
        for s in syms:
            if s.kind == "global" and s.qualifier != "const":
                globals_read = True
            positions = self._positions(id(s), lambda: [w.pos for w in self.writes_to(s)])
            if any(_any_between(positions, l, h) for l, h in spans):
                return True
        if globals_read:
            calls = self._positions("calls", lambda: self.user_calls)
            return any(_any_between(calls, l, h) for l, h in spans)
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
                    products = (("*", tuple(sorted((self._component(e.args[0], i), self._component(e.args[1], i)),
                                                   key=hash))) for i in range(n))
                    return ("+", tuple(sorted(products, key=hash)))
            inlined = self._inline(e, target)
            if inlined is not None:
                return inlined
            return ("C", e.callee, tuple(self.key(a) for a in e.args))
        if t is A.Field:
            if self.model.is_swizzle(e) and len(self.model.swizzle_indices(e)) == 1:
                return self._component(e.base, self.model.swizzle_indices(e)[0])
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
        types = (self.model._types.get(id(e.left)), self.model._types.get(id(e.right)))
        if None in types or any(getattr(t, "is_matrix", False) for t in types):
            return False
        return e.op == "*" or all(getattr(t, "base", None) == "float" for t in types)

    def terms(self, e: Any) -> list[Any] | None:
        """The keys of the operands of a chain of `+`, or of `*` and `/` (a divisor as
        ("inv", its key)), in any grouping: `a / b * a / b` -> a, inv b, a, inv b. None when
        `e` is not such a chain (a matrix product, an integer quotient, another operator)."""
        if type(e) is not A.Binary or e.op not in ("+", "*", "/") or not self._commutes(e):
            return None
        ops = ("+",) if e.op == "+" else ("*", "/")
        out: list[Any] = []

        def walk(x: Any, inverse: bool) -> None:
            if type(x) is A.Binary and x.op in ops and self._commutes(x):
                walk(x.left, inverse)
                walk(x.right, inverse != (x.op == "/"))
            else:
                k = self.key(x)
                out.append(("inv", k) if inverse else k)

        walk(e, False)
        return out

    def written_factors(self, e: Any) -> tuple[list[Any], list[Any]] | None:
        """A `*`/`/` chain as written, left to right: its nodes down the left side (`e`, then
        `e.left`, ...) and the keys of its factors, a divisor as ("inv", key) and a parenthesised
        right operand as one factor (`a / b * a / b` -> a, inv b, a, inv b; `(d * d) / (i * i)`
        -> d, d, inv (i * i)). None when `e` is not a float or integer product chain."""
        if type(e) is not A.Binary or e.op not in ("*", "/") or not self._commutes(e):
            return None
        spine, keys = [], []
        x = e
        while type(x) is A.Binary and x.op in ("*", "/") and self._commutes(x):
            spine.append(x)
            k = self.key(x.right)
            keys.append(("inv", k) if x.op == "/" else k)
            x = x.left
        keys.append(self.key(x))
        return spine, keys[::-1]

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
        if not isinstance(target, Symbol) or not isinstance(d, A.FunctionDefinition) or d.body is None \
                or len(self._subst_stack) >= 4 or not pure_function(self.model, target):
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
            if target is None or (isinstance(target, Symbol) and not pure_function(self.model, target)):
                return False
            if isinstance(target, B.Overload) and target.out_params:
                return False
        return all(self.is_pure(c) for c in e.children())

    def op_count(self, e: Any) -> tuple[int, bool]:
        """(operations, whether a built-in costlier than an add is called) of a pure expression."""
        i = id(e)
        r = self._ops.get(i)
        if r is None:
            n, costly = 0, False
            t = type(e)
            if t in (A.Binary, A.Ternary) or (t is A.Unary and e.op != "+" and not _is_literal(e.operand)):
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
        """Non-trivial, or one float or vector arithmetic operation that is not a sign change
        (`d * invI`, `light.center - position`; not `-1.0 * n`): a value a TA expects to be
        computed once."""
        if type(e) is not A.Binary or e.op not in ("+", "-", "*", "/"):
            return self.is_nontrivial(e)
        n, costly = self.op_count(e)
        if n >= 2 or costly:
            return not self.model.is_constant(e)
        if n != 1 or not is_float_type(self.model.type_of(e)) or self.model.is_constant(e):
            return False
        unit = [x for x in (e.left, e.right) if _numbers(self.model.const_value(x)) in ([1.0], [-1.0])]
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

    def reaching_value(self, ident: A.Identifier, sym: Symbol) -> Any:
        """The expression last assigned to `sym` before `ident` when that assignment is on every
        path to it, no other write can reach it, and it assigns the whole value; else None."""
        pos = self.enter.get(id(ident))
        if pos is None:
            return None
        ws = self.writes_to(sym)
        before = [w for w in ws if w.pos < pos]
        if not before:
            return None
        last = before[-1]
        if last.kind not in ("=", "init") or not self.dominates(last.node, ident):
            return None
        for loop in self.enclosing_loops(ident):  # a later write in the loop reaches it again
            if any(w.pos > pos and self.contains(loop, w.node) for w in ws):
                return None
        return last.value

    # -- sign analysis -------------------------------------------------------------------------
    def value_range(self, e: Any, depth: int = 0) -> tuple:
        """(lo, hi, witness) of an expression; lo/hi None when unbounded; witness is None or
        (reason, node) when the value can be negative for a reason the rules can name."""
        i = id(e)
        r = self._ranges.get(i)
        if r is None:
            r = self._range(e, depth)
            self._ranges[i] = r
        return r

    def _range(self, e: Any, depth: int) -> tuple:
        unknown = (None, None, None)
        if depth > 24:
            return unknown
        value = self.model.const_value(e)
        nums = _numbers(value)
        if nums:
            lo, hi = min(nums), max(nums)
            return (lo, hi, ("a negative constant", e) if lo < 0 else None)
        rec = lambda x: self.value_range(x, depth + 1)  # noqa: E731
        t = type(e)
        if t is A.Identifier:
            sym = self.model.symbol_of(e)
            if sym is None:
                return unknown
            if sym.kind == "uniform":
                return (0.0, None, None) if sym.name in _NONNEG_UNIFORMS else unknown
            if sym.kind == "local":
                v = self.reaching_value(e, sym)
                return rec(v) if v is not None else unknown
            return unknown
        if t is A.Field:
            if self.model.is_swizzle(e):
                return rec(e.base)
            return unknown
        if t is A.Index:
            base_t = self.model.type_of(e.base)
            return rec(e.base) if getattr(base_t, "is_vector", False) or getattr(base_t, "is_matrix", False) else unknown
        if t is A.Unary:
            if e.op == "+":
                return rec(e.operand)
            if e.op == "-":
                lo, hi, why = rec(e.operand)
                nlo = -hi if hi is not None else None
                nhi = -lo if lo is not None else None
                if nlo is not None and nlo >= 0:
                    return (nlo, nhi, None)
                return (nlo, nhi, ("a negation", e))
            return unknown
        if t is A.Binary:
            return self._binary_range(e, rec)
        if t is A.Ternary:
            return _join(rec(e.then), rec(e.else_))
        if t is A.Call:
            return self._call_range(e, rec)
        return unknown

    def _binary_range(self, e: A.Binary, rec) -> tuple:
        op = e.op
        a, b = rec(e.left), rec(e.right)
        (alo, ahi, aw), (blo, bhi, bw) = a, b
        if op == "+":
            lo = _add(alo, blo)
            hi = _add(ahi, bhi)
            return (lo, hi, None if _nonneg(lo) else (aw or bw))
        if op == "-":
            lo = _sub(alo, bhi)
            hi = _sub(ahi, blo)
            if _nonneg(lo):
                return (lo, hi, None)
            return (lo, hi, aw or ("a difference", e))
        if op == "*":
            if self.key(e.left) == self.key(e.right):  # x * x
                return (0.0, None if alo is None or ahi is None else max(alo * alo, ahi * ahi), None)
            if _nonneg(alo) and _nonneg(blo):
                return (alo * blo, _mul(ahi, bhi), None)
            if None not in (alo, ahi, blo, bhi):
                ps = [alo * blo, alo * bhi, ahi * blo, ahi * bhi]
                lo, hi = min(ps), max(ps)
                return (lo, hi, None if lo >= 0 else (aw or bw))
            return (None, None, aw or bw)
        if op == "/":
            if _nonneg(alo) and blo is not None and blo > 0:
                return (0.0, None, None)
            return (None, None, aw or bw)
        return (None, None, None)

    def _call_range(self, e: A.Call, rec) -> tuple:
        target = self.model.call_target(e)
        if isinstance(target, tuple) and target and target[0] == "constructor":
            if not e.args:
                return (None, None, None)
            return _join(*(rec(a) for a in e.args))
        if not isinstance(target, B.Overload):
            return (None, None, None)
        name, args = e.callee, e.args
        if name == "dot":
            if self.key(args[0]) == self.key(args[1]):
                return (0.0, None, None)
            return (-1.0, 1.0, ("a dot product of two different vectors", e))
        if name in ("length", "distance", "sqrt", "inversesqrt", "exp", "exp2", "pow"):
            return (0.0, None, None)
        if name == "abs":
            lo, hi, _ = rec(args[0])
            return (0.0, None if lo is None or hi is None else max(abs(lo), abs(hi)), None)
        if name in ("smoothstep", "step", "fract"):
            return (0.0, 1.0, None)
        if name in ("sin", "cos"):
            return (-1.0, 1.0, (f"{name}() is negative over half its period", e))
        if name in ("tan", "asin", "atan", "sinh", "tanh", "sign", "dFdx", "dFdy"):
            return (None, None, (f"{name}() can be negative", e))
        if name in ("reflect", "refract", "cross", "faceforward", "normalize"):
            return (-1.0 if name == "normalize" else None, 1.0 if name == "normalize" else None,
                    (f"the components of {name}() can be negative", e))
        if name == "max":
            (alo, ahi, aw), (blo, bhi, bw) = rec(args[0]), rec(args[1])
            known = [x for x in (alo, blo) if x is not None]
            lo = max(known) if known else None  # max(a, b) >= a and >= b
            hi = None if ahi is None or bhi is None else max(ahi, bhi)
            if _nonneg(lo):
                return (lo, hi, None)
            # negative only when both are: name a reason only when both sides have one
            return (lo, hi, aw if aw is not None and bw is not None else None)
        if name == "min":
            (alo, ahi, aw), (blo, bhi, bw) = rec(args[0]), rec(args[1])
            lo = None if alo is None or blo is None else min(alo, blo)
            hi = None
            if ahi is not None or bhi is not None:
                hi = min(x for x in (ahi, bhi) if x is not None)
            return (lo, hi, None if _nonneg(lo) else (aw or bw))
        if name == "clamp":
            _, _, xw = rec(args[0])
            llo, _, lw = rec(args[1])
            _, hhi, _ = rec(args[2])
            if _nonneg(llo):
                return (llo, hhi, None)
            return (llo, hhi, lw or xw)
        if name == "mix":
            return _join(rec(args[0]), rec(args[1]))
        if name == "mod":
            lo, hi, _ = rec(args[1])
            return (0.0, hi, None) if lo is not None and lo > 0 else (None, None, None)
        return (None, None, None)

    def negative_witness(self, e: Any) -> tuple[str, Any] | None:
        """(reason, node) when `e` can be negative for a nameable reason, else None."""
        lo, _, why = self.value_range(e)
        if _nonneg(lo):
            return None
        return why


def _numbers(value: Any) -> list[float]:
    if isinstance(value, bool) or value is None:
        return []
    if isinstance(value, (int, float)):
        return [float(value)] if math.isfinite(value) else []
    if isinstance(value, tuple):
        out: list[float] = []
        for v in value:
            sub = _numbers(v)
            if not sub:
                return []
            out += sub
        return out
    return []


def _nonneg(x: float | None) -> bool:
    return x is not None and x >= 0


def _add(a, b):
    return None if a is None or b is None else a + b


def _sub(a, b):
    return None if a is None or b is None else a - b


def _mul(a, b):
    return None if a is None or b is None else a * b


def _join(*ranges: tuple) -> tuple:
    los = [r[0] for r in ranges]
    his = [r[1] for r in ranges]
    lo = None if any(x is None for x in los) else min(los)
    hi = None if any(x is None for x in his) else max(his)
    why = None if _nonneg(lo) else next((r[2] for r in ranges if r[2] is not None), None)
    return (lo, hi, why)


# ---------------------------------------------------------------------------------------------
# Small helpers the rules share
# ---------------------------------------------------------------------------------------------


def text(e: Any) -> str:
    """GLSL text of an expression, shortened for a message."""
    s = to_glsl(e)
    return s if len(s) <= 60 else s[:57] + "..."


def builtin_call(model: Any, e: Any, *names: str) -> bool:
    """`e` is a call of one of the built-in functions `names` (not a user function so named)."""
    return (type(e) is A.Call and e.callee in names
            and isinstance(model.call_target(e), B.Overload))


def is_float_type(t: Any) -> bool:
    return getattr(t, "base", None) == "float" and (t.is_scalar or t.is_vector)


def line_of(node: Any) -> int:
    return node.loc.line


def calls_in(fn: FnFacts, *names: str) -> Iterator[A.Call]:
    """Calls of the built-ins `names` in a function, in execution order."""
    for n in fn.nodes:
        if type(n) is A.Call and n.callee in names and isinstance(fn.model.call_target(n), B.Overload):
            yield n


def looks_like(name: str, pattern: str) -> bool:
    return re.search(pattern, name, re.I) is not None


def loc_of(node: Any) -> Location:
    return node.loc


def is_simple(e: Any) -> bool:
    """A name, a literal, or a field/swizzle/element of one: no parentheses needed around it."""
    while type(e) in (A.Field, A.Index):
        e = e.base
    return type(e) in (A.Identifier, A.FloatLiteral, A.IntLiteral, A.BoolLiteral)


def wrap(e: Any) -> str:
    """GLSL text of `e`, in parentheses unless it is simple."""
    return text(e) if is_simple(e) or type(e) is A.Call else f"({text(e)})"


def squared(model: Any, e: Any) -> str:
    """`r * r` for an expression, or the folded square of a constant bound."""
    nums = _numbers(model.const_value(e))
    if len(nums) == 1:
        v = nums[0] * nums[0]
        s = repr(v) if v != int(v) or abs(v) >= 1e16 else f"{int(v)}.0"
        return s if len(s) < 12 else f"{v:g}"
    w = wrap(e)
    return f"{w} * {w}"
