"""Uniformity (divergence) analysis: which values of a function are the same in every lane,
and which writes need no mask.

The transpiler runs every pixel of a tile as a lane of NumPy arrays; a value that is the same
in every lane is kept as an array whose lane axis has size 1 (runtime.py, "Representation"), so
it costs one computation per tile instead of one per pixel. This module tells the code
generator two things about one function, as a GPU compiler's divergence analysis does:

* **uniform values** (`Uniformity.is_uniform`): an expression is uniform when it depends only on
  literals, Shadertoy uniforms, constant or never-written globals, uniform variables and calls
  of functions that read no lane state with uniform arguments. `gl_FragCoord`, the function's
  parameters (their arguments are not known here: `fragCoord` among them), written globals and
  anything computed from them are varying. A condition judged uniform becomes plain Python
  control flow (`if X.true(c):`), a uniform loop a plain Python loop, a call with uniform
  arguments of such a function runs once for all lanes.
* **free writes** (`Uniformity.is_free`): a write `x = e` (also `x[i] = e`, `x.f = e`, `x += e`,
  `x++`, an out argument) to a local variable or an `in` parameter needs no mask when every
  lane the mask leaves out is done with `x`. The mask where `x` is written differs from the one
  where it was declared only by

  - divergent control flow between the two (an `if`, `?:`, `&&`, `||` with a varying
    condition, a `switch`, a loop whose condition, `break` or `continue` varies): the lanes
    left out will read `x` again after the branch, so the write keeps its mask;
  - lanes that left by `return` or `discard` (they never run the function again), or by a
    `break`/`continue` of a loop declared inside which `x` lives (they leave its scope, or
    declare it afresh in the next iteration).

  The analysis counts the divergent constructs around each point (`level`); a write is free
  when it happens at the level of its variable's declaration. A free write of a uniform value
  keeps the variable uniform even inside a varying branch, after an early return, or in a
  function called under a mask: `PointLight L[4]; L[0] = PointLight(...);` stays one value per
  tile, not an array broadcast to every lane and selected per element. Out and inout
  parameters get free writes only in a function no lane leaves early (no `return` but the last
  statement, no `discard`): the caller copies them back in every lane it called with. Return
  values and globals are always written under the mask, and so are variables declared in a
  `switch` body (they are declared before the switch and written under the case's mask). In
  functions that use derivatives (`dFdx`, implicit-LOD texture lookups) a neighbour's
  derivative reads the inactive lanes, so they must hold what llvmpipe's do: its NIR values are
  SSA, computed in every lane of the SIMD vector whatever the exec mask, and only values merged
  across control flow (phis, turned into registers) are stored under the mask. There a write is
  free only at its variable's declaration level and loop depth (an SSA value; a write inside a
  loop the variable is declared outside of is a loop-carried register, a masked store):
  `vec2 p = ...; f += texture(c, p); p = m * p; f += texture(c, p);` in a function called
  under a varying `if` gives the second lookup's quad the neighbours' own `m * p`, as llvmpipe
  (tests/channels test_derivatives_of_values_computed_under_a_branch). A variable declared
  outside a branch and written inside it stays masked (llvmpipe computes the new value in every
  lane until the branch ends: not emulated), except
  - a local whose every use lies inside one arm of a varying `if`, declared at that `if`'s level
    and loop depth (no loop between them: the arm is entered at most once per declaration): no
    lane left out of the arm ever reads it, and the lanes entering it see the declared value, so
    it counts as declared at the arm's start (`PointLight L[4];` before `if (hit) { L[0] = ...;
    ... L[k] ... }` stays one value). Not in functions that use derivatives. Such a local is
    dead when the arm ends (`Uniformity.dead_after`): the NumPy backend does not put it back
    into the lanes of a compacted arm.

A variable is uniform when every write to it stores a uniform value at a uniform index and is
free, or (in `mainImage`, whose lanes start all active) happens under a uniform mask. The
analysis is iterated to a fixed point: a variable found varying makes what reads it varying.
The LlvmpipeMath emulation is untouched by this: a uniform `sin` is the same runtime call on a
one-lane array, rounded as llvmpipe rounds it.
"""

from __future__ import annotations

from typing import Any

from ...frontend import syntax as A
from ...semantics.analysis import param_directions, written_variable
from ...semantics.model import Symbol
from .facts import NO_EVENTS, Facts, events_of, induction_variable

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ...semantics.model import Model


class Uniformity:
    """The analysis of one function `fn` (a function symbol of the checker's model); see the
    module docstring. `facts` are the program-wide facts of `transpile.facts.Facts`."""

    def __init__(
        self,
        model: Model,
        facts: Facts,
        fn: Symbol,
        is_entry: bool,
        uniform_params: frozenset | set = frozenset(),
        out_values: bool = False,
    ) -> None:
        """uniform_params: ids of parameter symbols that start uniform (the compiled engine's
        variants of a function called with values of one lane); a varying write still makes them
        varying. Every other parameter but an `out` one starts varying. out_values: an out or
        inout argument of a call with a varying argument is uniform when the callee's value of
        that parameter is, analysed with the call's uniform arguments (:meth:`uniform_outs`: the
        NumPy backend's arrays of one lane there, which the compiled engine follows); else only
        when every argument is uniform (the transpiler's rule)."""
        self.model = model
        self.facts = facts
        self.fn = fn
        self.out_values = out_values
        self.is_entry = is_entry
        self.allow_free = id(fn) not in facts.uses_derivs
        self.varying: set[int] = set()  # symbol ids
        self.divergent_loops: set[int] = set()  # loop node ids whose live mask may diverge
        self.decl_level: dict[
            int, int | None
        ] = {}  # symbol id -> level of its declaration (None: never free)
        self.decl_loops: dict[int, int] = {}  # symbol id -> loops/switches around its declaration
        self.decl_seq: dict[int, int] = {}  # symbol id -> declarations seen before it in this pass
        self.free: set[int] = set()  # ids of the l-values (whole targets) of free writes
        self.cache: dict[int, bool] = {}
        # for sinking a declaration into the one branch arm that uses it (`sink`): each node's
        # span of preorder numbers (its own, one past its last descendant's), and each local's
        # first and last use in that order
        self.span: dict[int, tuple[int, int]] = {}
        self.uses: dict[int, tuple[int, int]] = {}
        self.sunk: dict[int, frozenset[int]] = {}  # id(arm) -> ids of the locals sunk into it
        stack: list[tuple[Any, bool]] = [(fn.node.body, False)]
        order = 0
        while stack:
            node, done = stack.pop()
            if done:
                self.span[id(node)] = (self.span[id(node)][0], order)
                continue
            self.span[id(node)] = (order, order)
            if isinstance(node, A.Identifier):
                sym = model.symbol_of(node)
                if sym is not None and sym.kind == "local":
                    first, _ = self.uses.get(id(sym), (order, order))
                    self.uses[id(sym)] = (first, order)
            order += 1
            stack.append((node, True))
            stack.extend((c, False) for c in reversed(node.children()))
        # out and inout parameters are copied back to the caller in every lane it called with:
        # free writes only when no lane can leave the function before the end (no return but
        # the last statement, no discard)
        body = fn.node.body.stmts
        tail = body[-1] if body and isinstance(body[-1], A.Return) else None
        leaves_early = any(
            (isinstance(n, (A.Return, A.Discard)) and n is not tail) or facts.discarding_call(n)
            for n in fn.node.body.walk()
        )
        for p in fn.node.proto.params:
            sym = self.model.symbol_of(p)
            if sym is None:
                continue
            if p.direction != "out" and id(sym) not in uniform_params:
                self.varying.add(id(sym))
            self.decl_level[id(sym)] = 0 if p.direction == "in" or not leaves_early else None
            self.decl_seq[id(sym)] = 0
        while True:
            before = (set(self.varying), set(self.divergent_loops))
            # the mask is None or one value for all lanes (mainImage's lanes start all active)
            self.mu = is_entry
            self.level = 0  # divergent constructs around the current point
            self.switch_depth = 0
            self.loop_flags: list[
                list[Any]
            ] = []  # per enclosing loop/switch: [varying exit (mu), body level]
            self.fn_varying_return = False
            self.free = set()
            self.seq = 0
            self.declared: set[int] = set()  # symbol ids declared so far in this pass
            self.compacted_from: int | None = (
                None  # the first declaration inside the outermost masked loop around
            )
            self.block(fn.node.body.stmts, is_entry)
            if (self.varying, self.divergent_loops) == before:
                break

    # -- verdicts --------------------------------------------------------------------------------
    def is_uniform(self, e: Any) -> bool:
        """The analysis' verdict on an expression node (False for nodes it never saw)."""
        return self.cache.get(id(e), False)

    def is_free(self, target: Any) -> bool:
        """True when the write to the l-value `target` (an assignment's target, the operand of
        ++/--, an out argument: the whole l-value, `v.x` not `v`) needs no mask."""
        return id(target) in self.free

    def is_varying(self, sym: Symbol) -> bool:
        """True when the variable (a symbol) may differ between lanes."""
        return id(sym) in self.varying

    def is_own(self, sym: Symbol) -> bool:
        """True for a local or parameter of this function (one the analysis has verdicts on)."""
        return id(sym) in self.decl_level

    def dead_after(self, sym: Symbol, arm: Any) -> bool:
        """True when the local `sym` is declared before the varying `if` whose branch is `arm`
        and used only inside `arm`, with no loop between (`sink`): what `arm` leaves in it is
        never read again, by any lane."""
        return id(sym) in self.sunk.get(id(arm), ())

    # -- expressions ---------------------------------------------------------------------------
    def uniform(self, e: Any) -> bool:
        if e is None:
            return True
        res = self._uniform(e)
        self.cache[id(e)] = res
        return res

    def _uniform(self, e: Any) -> bool:
        m = self.model
        if isinstance(e, (A.IntLiteral, A.FloatLiteral, A.BoolLiteral)):
            return True
        if isinstance(e, A.Identifier):
            sym = m.symbol_of(e)
            if sym is None:
                return False
            if sym.kind == "uniform":
                return True
            if sym.kind == "builtin-var":
                return sym.name != "gl_FragCoord"
            if sym.kind == "global":
                return id(sym) not in self.facts.written_globals
            return id(sym) not in self.varying
        if isinstance(e, A.Assignment):
            ok = self.uniform(e.value) and (e.op == "=" or self.uniform(e.target))
            self.write(e.target, ok and self.index_uniform(e.target))
            return ok and self.mu
        if isinstance(e, (A.Unary, A.Postfix)) and e.op in ("++", "--"):
            ok = self.uniform(e.operand)
            self.write(e.operand, ok)
            return ok and self.mu
        if isinstance(e, A.Call):
            tgt = m.call_target(e)
            dirs = param_directions(tgt)
            args_u = [
                self.uniform(a) or (i < len(dirs) and dirs[i] == "out")
                for i, a in enumerate(e.args)
            ]
            outs: set[int] = set()
            if isinstance(tgt, Symbol):
                res = all(args_u) and self.facts.closed(tgt)
                if id(tgt) in self.facts.may_discard and not self.mu:
                    self.fn_varying_return = True
                if self.out_values and not res:
                    outs = self.uniform_outs(tgt, args_u)
            else:
                res = all(args_u)
            for i, d in enumerate(dirs):
                if d in ("out", "inout") and i < len(e.args):
                    ok = res or i in outs
                    self.write(e.args[i], ok and self.index_uniform(e.args[i]))
            return res
        if isinstance(e, A.Ternary):
            c = self.uniform(e.cond)
            with self.branch(c):
                a, b = self.uniform(e.then), self.uniform(e.else_)
            return c and a and b
        if isinstance(e, A.Binary) and e.op in ("&&", "||"):
            left = self.uniform(e.left)
            with self.branch(left):
                right = self.uniform(e.right)
            return left and right
        ok = True
        for c in e.children():
            if isinstance(c, A.Expr):
                ok = self.uniform(c) and ok
        return ok

    def uniform_outs(self, fn: Symbol, args_u: list[bool]) -> set[int]:
        """Indexes of the out and inout parameters of `fn` whose value at its end is uniform when
        it is called with these arguments (args_u: which are uniform; an out one counts as
        uniform): the callee analysed with those parameters uniform (memo: facts)."""
        params = [self.model.symbol_of(p) for p in fn.node.proto.params]
        dirs = param_directions(fn)
        seed = frozenset(
            id(s) for s, u, d in zip(params, args_u, dirs) if s is not None and u and d != "out"
        )
        memo = self.facts.uniform_outs
        key = (id(fn), seed)
        if key not in memo:
            memo[key] = set()  # (GLSL has no recursion: a placeholder while it is analysed)
            callee = Uniformity(self.model, self.facts, fn, False, seed, out_values=True)
            memo[key] = {
                i
                for i, (s, d) in enumerate(zip(params, dirs))
                if s is not None and d in ("out", "inout") and id(s) not in callee.varying
            }
        return memo[key]

    def index_uniform(self, target: Any) -> bool:
        ok = True
        while isinstance(target, (A.Field, A.Index)):
            if isinstance(target, A.Index):
                ok = self.uniform(target.index) and ok
            target = target.base
        return ok

    def write(self, target: Any, uniform: bool) -> None:
        """A write of a value (uniform or not) to the l-value `target` at the current point."""
        sym = written_variable(self.model, target)[0]
        if sym is None or sym.kind not in ("local", "param"):
            return
        free = self.decl_level.get(id(sym)) == self.level and (
            self.allow_free or self.decl_loops.get(id(sym), 0) == len(self.loop_flags)
        )
        if free:
            self.free.add(id(target))
        if free and not self.mu:
            # a loop that runs with a live mask (any loop but a plain Python one) may be compacted
            # (tiles.LaneHelpers.push): a variable from outside it comes back from the scatter with
            # the lanes of the loop replaced, one value per lane
            uniform = uniform and (
                self.compacted_from is None or self.decl_seq.get(id(sym), -1) >= self.compacted_from
            )
        if not (uniform and (free or self.mu)):
            self.varying.add(id(sym))

    def declare(self, sym: Symbol | None, uniform: bool, level: int | None = None) -> None:
        if sym is None:
            return
        self.seq += 1
        self.decl_seq[id(sym)] = self.seq
        self.declared.add(id(sym))
        self.decl_level[id(sym)] = (
            None
            if self.switch_depth and level is None
            else (self.level if level is None else level)
        )
        self.decl_loops[id(sym)] = len(self.loop_flags)
        if not uniform:
            self.varying.add(id(sym))

    class _Branch:
        """`with self.branch(uniform_condition):` the code of a branch: a varying condition
        makes the mask inside non-uniform and adds a level of divergence."""

        def __init__(self, an: Uniformity, uniform: bool) -> None:
            self.an, self.uniform = an, uniform

        def __enter__(self) -> None:
            an = self.an
            self.saved = an.mu, an.level
            an.mu = an.mu and self.uniform
            an.level += 0 if self.uniform else 1

        def __exit__(self, *exc: Any) -> None:
            self.an.mu, self.an.level = self.saved

    def branch(self, uniform: bool) -> Uniformity._Branch:
        return Uniformity._Branch(self, uniform)

    # -- statements ----------------------------------------------------------------------------
    def block(self, stmts: list[Any], mu: bool) -> bool:
        for s in stmts:
            mu = self.stmt(s, mu)
            if self._discarding_call(s):
                mu = False  # S.discard is lane-dependent in general
        return mu

    def _discarding_call(self, s: Any) -> bool:
        if self.facts.has_discarding_call(s):
            self.fn_varying_return = True
            return True
        return False

    def stmt(self, s: Any, mu: bool) -> bool:
        self.mu = mu
        if s is None:
            return mu
        if isinstance(s, A.Compound):
            return self.block(s.stmts, mu)
        if isinstance(s, A.DeclarationStatement):
            d = s.decl
            if isinstance(d, A.VariableDeclaration):
                for dec in d.declarators:
                    u = self.uniform(dec.init) if dec.init is not None else True
                    if self.switch_depth:
                        u = u and mu
                    self.declare(self.model.symbol_of(dec), u)
            return mu
        if isinstance(s, A.ExpressionStatement):
            self.uniform(s.expr)
            return mu
        if isinstance(s, A.If):
            c = self.uniform(s.cond)
            inner = mu and c
            sunk = [] if c else self.sink(s.then)
            self.level += 0 if c else 1
            t = self.stmt(s.then, inner)
            self.level -= 0 if c else 1
            self.unsink(sunk)
            sunk = [] if c or s.else_ is None else self.sink(s.else_)
            self.level += 0 if c else 1
            e = self.stmt(s.else_, inner) if s.else_ is not None else inner
            self.level -= 0 if c else 1
            self.unsink(sunk)
            ev_t = events_of(s.then, self.facts, self.model)
            ev_e = events_of(s.else_, self.facts, self.model) if s.else_ is not None else NO_EVENTS
            self.mu = mu
            return mu and (t or not ev_t.any) and (e or not ev_e.any)
        if isinstance(s, (A.For, A.While, A.DoWhile)):
            return self.loop(s, mu)
        if isinstance(s, A.Switch):
            c = self.uniform(s.expr)
            self.loop_flags.append([False, None])
            self.switch_depth += 1
            self.level += 1  # a switch's cases always run under masks (case fall-through)
            inner = mu and c
            cur = inner
            for st in s.body:
                if isinstance(st, A.Case):
                    cur = inner and not self.loop_flags[-1][0]
                    continue
                cur = self.stmt(st, cur)
            self.level -= 1
            self.switch_depth -= 1
            self.loop_flags.pop()
            ev = events_of(s, self.facts, self.model)
            return mu and (not ev.ret or not self.fn_varying_return)
        if isinstance(s, (A.Break, A.Continue)):
            if self.loop_flags:
                flags = (
                    self.loop_flags[-1]
                    if isinstance(s, A.Break)
                    else next((f for f in reversed(self.loop_flags) if f[1] is not None), None)
                )
                if flags is not None:
                    if isinstance(s, A.Break) and not mu:
                        flags[0] = True
                    if flags[1] is not None and self.level > flags[1][0]:
                        self.divergent_loops.add(flags[1][1])  # some lanes leave, others go on
            return mu
        if isinstance(s, (A.Return, A.Discard)):
            if isinstance(s, A.Return) and s.value is not None:
                self.uniform(s.value)
            if not mu:
                self.fn_varying_return = True
                for f in self.loop_flags:
                    f[0] = True
            return mu
        return mu

    def sink(self, arm: Any) -> list[int]:
        """Move into `arm` (a branch of a varying `if` about to be analysed at the current level)
        the declarations of the locals declared at this level and loop depth whose every use
        lies inside it (module docstring); returns their ids for `unsink`."""
        if not self.allow_free or self.switch_depth:
            return []
        start, end = self.span[id(arm)]
        moved = [
            sid
            for sid, (first, last) in self.uses.items()
            if start <= first
            and last < end
            and sid in self.declared
            and self.decl_level.get(sid) == self.level
            and self.decl_loops.get(sid) == len(self.loop_flags)
        ]
        for sid in moved:
            self.decl_level[sid] = self.level + 1
        self.sunk[id(arm)] = frozenset(moved)
        return moved

    def unsink(self, moved: list[int]) -> None:
        for sid in moved:
            self.decl_level[sid] = self.level

    def loop(self, s: Any, mu: bool) -> bool:
        ind = induction_variable(s, self.model, self.facts)
        cond = s.cond
        saved_from = self.compacted_from
        plain = (
            not isinstance(s, A.DoWhile)
            and cond is not None
            and not isinstance(cond, A.ConditionDeclaration)
            and not events_of(s.body, self.facts, self.model).any
            and self.uniform(cond)
        )
        if not plain:  # the transpiler's general loop, with a live mask (Statements.loop)
            if self.compacted_from is None:  # (a for's init is inside)
                self.compacted_from = self.seq + 1
        if isinstance(s, A.For) and s.init is not None:
            self.stmt(s.init, mu)
        outer = self.level
        self.level = outer + (1 if id(s) in self.divergent_loops else 0)
        body_level = self.level
        if isinstance(cond, A.ConditionDeclaration):
            self.declare(self.model.symbol_of(cond), self.uniform(cond.init), body_level)
        self.loop_flags.append([False, (body_level, id(s))])
        body_mu = mu
        for _ in range(3):
            self.loop_flags[-1][0] = False
            self.mu = body_mu
            c = True
            if cond is not None and not isinstance(s, A.DoWhile):
                c = self.uniform(
                    cond if not isinstance(cond, A.ConditionDeclaration) else cond.init
                )
            if not c:
                self.divergent_loops.add(id(s))
            inner = body_mu and c
            self.stmt(s.body, inner)
            if isinstance(s, A.DoWhile):
                self.mu = inner
                c = self.uniform(s.cond)
                if not c:
                    self.divergent_loops.add(id(s))
            if isinstance(s, A.For) and s.step is not None:
                self.mu = True if ind is not None else inner and not self.loop_flags[-1][0]
                self.uniform(s.step)
            new_mu = mu and c and not self.loop_flags[-1][0]
            if new_mu == body_mu:
                break
            body_mu = new_mu
        self.loop_flags.pop()
        self.level = outer
        self.compacted_from = saved_from
        ev = events_of(s, self.facts, self.model)
        self.mu = mu
        return mu and (not ev.ret or not self.fn_varying_return)
