"""Uniformity (divergence) analysis: which values of a function are the same in every lane."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from .. import ast as A
from .transpile.common import _is_symbol
from .transpile.facts import NO_EVENTS, events_of, induction_variable, lvalue_base, out_directions

if TYPE_CHECKING:
    from .transpile import Transpiler

class Uniformity:
    """A sound, simple uniformity analysis of one function, matching the code generator.

    A value is uniform when it depends only on literals, uniforms, constant or never-written
    globals and uniform variables. A variable is uniform when every write to it stores a uniform
    value under a uniform mask: declarations are unmasked (a lane that is inactive at a
    declaration never reads the variable in its scope; switch bodies excepted), the entry
    function starts with every lane active, other functions start with an unknown mask, and a
    mask stays uniform while every condition and every break/continue/return that shaped it was
    uniform. Parameters (except `out`) are varying. Iterated to a fixed point."""

    def __init__(self, tr: "Transpiler", fn: Any, is_entry: bool) -> None:
        self.tr = tr
        self.model = tr.model
        self.fn = fn
        self.is_entry = is_entry
        self.varying: set[int] = set()
        self.mu = is_entry
        self.switch_depth = 0
        self.loop_flags: list[list[bool]] = []  # per enclosing loop/switch: [varying break]
        self.fn_varying_return = False
        self.cache: dict[int, bool] = {}
        for p in fn.node.proto.params:
            sym = self.model.symbol_of(p)
            if sym is not None and p.direction != "out":
                self.varying.add(id(sym))
        while True:
            before = set(self.varying)
            self.mu = is_entry
            self.fn_varying_return = False
            self.block(fn.node.body.stmts, is_entry)
            if self.varying == before:
                break

    # -- expressions ---------------------------------------------------------------------------
    def is_uniform(self, e: Any) -> bool:
        """The analysis' verdict on an expression node (False for nodes it never saw)."""
        return self.cache.get(id(e), False)

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
                return id(sym) not in self.tr.facts.written_globals
            return id(sym) not in self.varying
        if isinstance(e, A.Assignment):
            ok = self.uniform(e.value) and (e.op == "=" or self.uniform(e.target))
            self.write(e.target, ok and self.mu and self.index_uniform(e.target))
            return ok and self.mu
        if isinstance(e, (A.Unary, A.Postfix)) and e.op in ("++", "--"):
            ok = self.uniform(e.operand) and self.mu
            self.write(e.operand, ok)
            return ok
        if isinstance(e, A.Call):
            tgt = m.call_target(e)
            args_u = [self.uniform(a) for a in e.args]
            if _is_symbol(tgt):
                res = all(args_u) and self.tr.facts.closed(tgt)
                if id(tgt) in self.tr.facts.may_discard and not self.mu:
                    self.fn_varying_return = True
            else:
                res = all(args_u)
            for i, d in enumerate(out_directions(tgt)):
                if d in ("out", "inout") and i < len(e.args):
                    self.write(e.args[i], res and self.mu)
            return res
        if isinstance(e, A.Ternary):
            c = self.uniform(e.cond)
            saved = self.mu
            self.mu = saved and c
            a, b = self.uniform(e.then), self.uniform(e.else_)
            self.mu = saved
            return c and a and b
        if isinstance(e, A.Binary) and e.op in ("&&", "||"):
            left = self.uniform(e.left)
            saved = self.mu
            self.mu = saved and left
            right = self.uniform(e.right)
            self.mu = saved
            return left and right
        ok = True
        for c in e.children():
            if isinstance(c, A.Expr):
                ok = self.uniform(c) and ok
        return ok

    def index_uniform(self, target: Any) -> bool:
        ok = True
        while isinstance(target, (A.Field, A.Index)):
            if isinstance(target, A.Index):
                ok = self.uniform(target.index) and ok
            target = target.base
        return ok

    def write(self, target: Any, uniform: bool) -> None:
        base = lvalue_base(target)
        if base is None or uniform:
            return
        sym = self.model.symbol_of(base)
        if sym is not None and sym.kind in ("local", "param"):
            self.varying.add(id(sym))

    # -- statements ----------------------------------------------------------------------------
    def block(self, stmts: list[Any], mu: bool) -> bool:
        for s in stmts:
            mu = self.stmt(s, mu)
            if self._discarding_call(s):
                mu = False  # S.discard is lane-dependent in general
        return mu

    def _discarding_call(self, s: Any) -> bool:
        if self.tr.facts.has_discarding_call(s):
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
                    sym = self.model.symbol_of(dec)
                    if sym is not None and not u:
                        self.varying.add(id(sym))
            return mu
        if isinstance(s, A.ExpressionStatement):
            self.uniform(s.expr)
            return mu
        if isinstance(s, A.If):
            c = self.uniform(s.cond)
            inner = mu and c
            t = self.stmt(s.then, inner)
            e = self.stmt(s.else_, inner) if s.else_ is not None else inner
            ev_t = events_of(s.then, self.tr.facts, self.model)
            ev_e = events_of(s.else_, self.tr.facts, self.model) if s.else_ is not None else NO_EVENTS
            self.mu = mu
            return mu and (t or not ev_t.any) and (e or not ev_e.any)
        if isinstance(s, (A.For, A.While, A.DoWhile)):
            return self.loop(s, mu)
        if isinstance(s, A.Switch):
            c = self.uniform(s.expr)
            self.loop_flags.append([False])
            self.switch_depth += 1
            inner = mu and c
            cur = inner
            for st in s.body:
                if isinstance(st, A.Case):
                    cur = inner and not self.loop_flags[-1][0]
                    continue
                cur = self.stmt(st, cur)
            self.switch_depth -= 1
            self.loop_flags.pop()
            ev = events_of(s, self.tr.facts, self.model)
            return mu and (not ev.ret or not self.fn_varying_return)
        if isinstance(s, A.Break):
            if not mu and self.loop_flags:
                self.loop_flags[-1][0] = True
            return mu
        if isinstance(s, A.Continue):
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

    def loop(self, s: Any, mu: bool) -> bool:
        ind = induction_variable(s, self.model, self.tr.facts)
        if isinstance(s, A.For) and s.init is not None:
            self.stmt(s.init, mu)
        cond = s.cond
        if isinstance(cond, A.ConditionDeclaration):
            u = self.uniform(cond.init)
            sym = self.model.symbol_of(cond)
            if sym is not None and not u:
                self.varying.add(id(sym))
        self.loop_flags.append([False])
        body_mu = mu
        for _ in range(3):
            self.loop_flags[-1][0] = False
            self.mu = body_mu
            c = True
            if cond is not None and not isinstance(s, A.DoWhile):
                c = self.uniform(cond if not isinstance(cond, A.ConditionDeclaration) else cond.init)
            inner = body_mu and c
            self.stmt(s.body, inner)
            if isinstance(s, A.DoWhile):
                self.mu = inner
                c = self.uniform(s.cond)
            if isinstance(s, A.For) and s.step is not None:
                self.mu = True if ind is not None else inner and not self.loop_flags[-1][0]
                self.uniform(s.step)
            new_mu = mu and c and not self.loop_flags[-1][0]
            if new_mu == body_mu:
                break
            body_mu = new_mu
        self.loop_flags.pop()
        ev = events_of(s, self.tr.facts, self.model)
        self.mu = mu
        return mu and (not ev.ret or not self.fn_varying_return)
