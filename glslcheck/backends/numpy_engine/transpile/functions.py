"""Functions and calls: a GLSL function becomes a Python `def` over lanes (parameters, out
parameters, return masks, the early-out select), and a call of a user function becomes a Python
call that copies out-arguments back under the caller's mask. Mixed into `Transpiler`."""

from __future__ import annotations

from typing import Any

from ....frontend import syntax as A
from ....semantics.model import Symbol
from ...cpu_core import nir_fold
from ...cpu_core.common import comment_safe
from ...cpu_core.facts import events_of
from ...cpu_core.inline import inline_call, worth_inlining
from ...cpu_core.uniformity import Uniformity
from .call_fold import folded_call
from .ray_dots import ray_call_args, ray_param_names
from .returned_sums import return_constant_args
from .state import FnState, LValue, TranspilerState
from .sum_chains import chain_call_args, chain_param_names


class Functions(TranspilerState):
    """The function and call pass of `Transpiler`."""

    # -- functions -----------------------------------------------------------------------------
    def gen_function(self, sym: Symbol) -> None:
        node = sym.node
        is_entry = sym is self.entry
        uni = Uniformity(self.model, self.facts, sym, is_entry)
        self.fn = fs = FnState(sym, uni, is_entry)
        if id(sym) in self.facts.uses_derivs:
            fs.no_compact += 1
        proto = node.proto
        params = []
        prologue = []
        for k, (p, (pname, ptype, direction)) in enumerate(zip(proto.params, sym.params)):
            psym = self.model.symbol_of(p)
            # An unnamed parameter (`void mainImage(out vec4, in vec2 c)`) still takes its
            # argument and, for out/inout, hands a value back: callers count on both.
            pyname = self.var_name(psym, p) if psym is not None else f"_unnamed{k}"
            fs.defined.append(pyname)
            if direction == "out":
                prologue.append(f"{pyname} = {self.initial(ptype, p, '_m')}")
            else:
                params.append(pyname)
            if direction != "in":
                fs.outs.append(pyname)
        fs.defined.append("_m")
        if is_entry:
            prologue += self.entry_prologue()
        if nir_fold.sunk_return(self, sym) is not None:
            params.append("_k")  # a constant the caller adds to the result (nir_fold.sunk_return)
        chains = chain_param_names(self, sym)  # the caller's `+= #c` chains
        params += chains
        fs.defined += chains[::2]  # (a base has lanes: a compacted region gathers it)
        rays = ray_param_names(self, sym)  # a caller's ray (nir_fold.ray_dots)
        params += rays
        fs.defined += rays[:1]  # (its rsq has lanes)
        self.last_line = None
        sig = ", ".join(["S", "_m"] + params)
        self.emit(f"def {self.fn_name(sym)}({sig}):")
        self.indent += 1
        doc = comment_safe(sym.signature(), 150) if hasattr(sym, "signature") else sym.name
        loc = getattr(proto, "loc", None)
        self.emit(f'"""{doc} (line {loc.line if loc else "?"})."""')
        rid = self.region("function", proto)
        self.emit(f"X.count(S, {rid}, _m)")
        for line in prologue:
            self.emit(line)
        body = node.body.stmts
        early = self.early_out(body)
        if early is not None:
            body = body[:-2]
        ev = events_of(node.body, self.facts, self.model) if early is None else None
        tail = body[-1] if body and isinstance(body[-1], A.Return) else None
        nontail_ret = early is None and (
            any(isinstance(n, (A.Return, A.Discard)) and n is not tail for n in node.body.walk())
            or (
                ev is not None  # (computed when there is no early out)
                and ev.ret
                and any(
                    isinstance(n, A.Call)
                    and isinstance(self.model.call_target(n), Symbol)
                    and id(self.model.call_target(n)) in self.facts.may_discard
                    for n in node.body.walk()
                )
            )
        )
        if nontail_ret:
            fs.has_ret = True
            self.emit("_ret = X.NO")
            fs.defined.append("_ret")
            if not sym.type.is_void:
                fs.rv = "_rv"
                self.emit(f"_rv = {self.zero(sym.type, proto)}")
                fs.defined.append("_rv")
        ended = self.block(body, "_m", top=True)
        if early is not None:
            cond_stmt, ret = early
            self.comment_line(cond_stmt)
            c = self.tmp(self.expr(cond_stmt.cond, "_m"))
            then = (
                cond_stmt.then.stmts[0]
                if isinstance(cond_stmt.then, A.Compound)
                else cond_stmt.then
            )
            assert isinstance(then, A.Return)  # (early_out)
            a = self.expr(then.value, "_m")
            self.emit(f"if X.every({c}):  # no lane goes on: the rest is not computed")
            self.indent += 1
            self.emit(self.final_return(a))
            self.indent -= 1
            self.comment_line(ret)
            b = self.expr(ret.value, "_m")
            self.emit(self.final_return(f"rt.select({c}, {a}, {b})"))
        elif not ended:
            self.emit(self.final_return())
        self.indent -= 1
        self.fn = None

    def entry_prologue(self) -> list[str]:
        """Statements run first in the entry point (the tracing transpiler's: where the globals
        that enter it undefined are reported)."""
        return []

    def early_out(self, body: list[Any]) -> tuple[Any, Any] | None:
        """`if (c) return K; return e;` ending a function, K a constant and c, e without side
        effects: (the If, the last Return). The function then returns `select(c, K, e)`, with no
        return mask: e is computed on every lane either way, and a select is cheaper than
        masked writes of the return value. Any other return or discard in the body keeps the
        general scheme."""
        if len(body) < 2 or not isinstance(body[-1], A.Return) or body[-1].value is None:
            return None
        st = body[-2]
        if not isinstance(st, A.If) or st.else_ is not None:
            return None
        then: A.Node = st.then
        if isinstance(then, A.Compound):
            if len(then.stmts) != 1:
                return None
            then = then.stmts[0]
        if not isinstance(then, A.Return) or then.value is None:
            return None
        if self.model.const_value(then.value) is None:
            return None
        if self.has_effects(st.cond) or self.has_effects(body[-1].value):
            return None
        for n in body[:-2]:
            for m in n.walk():
                if isinstance(m, (A.Return, A.Discard)):
                    return None
                if (
                    isinstance(m, A.Call)
                    and isinstance(self.model.call_target(m), Symbol)
                    and id(self.model.call_target(m)) in self.facts.may_discard
                ):
                    return None
        return st, body[-1]

    def final_return(self, value: str | None = None) -> str:
        fs = self.fn
        assert fs is not None
        ret = value if value is not None else (fs.rv or "None")
        if fs.outs:
            return f"return ({ret}, {', '.join(fs.outs)})"
        if value is None and fs.rv is None:
            return "return None"
        return f"return {ret}"

    def user_call(self, e: A.Call, fn: Symbol, mask: str | None) -> str:
        if worth_inlining(self, e, fn, nir_fold.dot_operand):
            return inline_call(
                self, e, fn, mask
            )  # Mesa's rewrites reach into an argument: inline.py
        folded = folded_call(self, e, fn, mask)  # constants propagated into the call: call_fold.py
        if folded is not None:
            return folded
        uni = self.fn.uni if self.fn is not None else None
        call_mask = mask
        if (
            uni is not None
            and self.facts.closed(fn)
            and all(uni.is_uniform(a) or d == "out" for a, (_, _, d) in zip(e.args, fn.params))
        ):
            call_mask = None  # same arguments in every lane: compute once, for all lanes
        args: list[str] = []
        outs: list[tuple[int, LValue]] = []
        inouts: dict[int, str] = {}
        directions = [d for _, _, d in fn.params]
        order = self.facts.order
        for i, (a, d) in enumerate(zip(e.args, directions)):  # (after earlier side effects)
            if d == "in":
                args.append(self.expr(a, mask))
            else:
                lv = self.lvalue(a, mask)
                outs.append((len(outs) + 1, lv))
                if d == "inout":
                    # read at the call, as Mesa copies it in: after the later arguments' effects
                    later = order.reads(a) & order.written_after(e, i)
                    args.append(self.read(lv) if later else self.tmp(self.read(lv)))
                    inouts[i] = args[-1]
        args += return_constant_args(self, e, fn)
        for key, g in nir_fold.chain_globals(self, fn):  # (a global's chain runs through too)
            inouts[key] = self.tmp(self.var_name(g, e))
        args += chain_call_args(self, e, fn, inouts)
        args += ray_call_args(self, e, fn)
        call = self.call_text(e, fn, call_mask, args, mask)
        if call_mask is not None and nir_fold.register_call(self, e, fn):
            self.n += 1  # (a name no GLSL global has: `__` is reserved)
            call = f'X.reg(S, "g___r{self.n}", {call}, {call_mask})'  # (tiles.LaneHelpers.reg)
        if not outs:
            # a call that writes a global an earlier part of the statement reads runs where it
            # stands (Mesa emits every call as it meets it and evaluates that read later)
            return self.tmp(call) if self.facts.order.runs_first(e) else call
        r = self.fresh("t")
        self.emit(f"{r} = {call}")
        for k, lv in outs:
            self.write(lv, f"{r}[{k}]", mask)
        return f"{r}[0]"

    def call_text(
        self, e: A.Call, fn: Symbol, call_mask: str | None, args: list[str], mask: str | None
    ) -> str:
        """The Python call of user function `fn` (the tracing transpiler, tracing.py, wraps it)."""
        return f"{self.fn_name(fn)}(S, {call_mask}{''.join(', ' + x for x in args)})"
