"""Statements and control flow over lanes: blocks and masks, compaction of sparse regions,
declarations, `if`, `switch`, loops (uniform loops as plain Python loops), break, continue,
return and discard. Mixed into `Transpiler`."""

from __future__ import annotations

from typing import Any

from ....base.diagnostics import Location
from ....frontend import syntax as A
from ....language import builtin_functions as B
from ....language import glsl_types as T
from ....semantics.model import Symbol
from ...cpu_core import nir_fold
from ...cpu_core.common import DERIVATIVES, IMPLICIT_LOD, LOOP_CAP, fold_tree
from ...cpu_core.facts import Events, events_of, induction_variable
from . import dead_lanes, frame_values
from .common import OUTLINE_INDENT, _error
from .returned_sums import keep_term, sunk_return_value
from .state import LoopCtx, TranspilerState
from .sum_chains import end_of_unrolled_body, enter_unrolled


class Statements(TranspilerState):
    """The statement pass of `Transpiler`."""

    FRAME_VALUES = True  # values the same in every tile computed once a frame (frame_values.py)

    # -- blocks and masks ----------------------------------------------------------------------
    def block(self, stmts: list[Any], mask: str | None, top: bool = False) -> bool:
        """Emit statements under `mask`; returns True when the Python code ended with `return`
        at this indentation (nothing after it runs)."""
        fs = self.fn
        assert fs is not None  # generating a function's body
        start_indent = self.indent
        moves = dead_lanes.plan(self, stmts)
        run: list[Any] = []  # statements computing frame values (frame_values.py), and where
        run_start = 0
        for i, s in enumerate(stmts):
            last = i == len(stmts) - 1
            hoist = (
                self.FRAME_VALUES
                and id(s) not in moves.moved
                and not moves.at.get(id(s))
                and frame_values.qualifies(self, s)
            )
            if run and not hoist:
                self.frame_run(run, run_start)
                run = []
            if hoist and not run:
                run_start = len(self.lines)
            if hoist:
                run.append(s)
            if id(s) in moves.moved:
                continue  # (emitted before the select that reads it: dead_lane_region)
            for move in moves.at.get(id(s), ()):
                self.dead_lane_region(move, mask)
            if top and last and isinstance(s, A.Return):
                # the function's last statement: return directly (when it is nested under the
                # `if X.live(...)` of earlier returns, the final `return _rv` follows that `if`)
                self.comment_line(s)
                val = self.expr(s.value, mask) if s.value is not None else None
                val = sunk_return_value(self, s, val)  # (a constant the caller adds)
                if val is not None and fs.rv is not None and mask not in (None, "_m"):
                    val = f"X.put({fs.rv}, {val}, {mask})"
                self.emit(self.final_return(val) if val is not None or fs.outs else "return None")
                nested = self.indent != start_indent
                fs.nest -= self.indent - start_indent
                self.indent = start_indent
                return not nested
            ev = events_of(s, self.facts, self.model)
            self.stmt(s, mask)
            if ev.any and not last:
                mask = self.refresh(mask, ev)
                if fs.switch_depth == 0 and fs.nest < 40:
                    self.emit(f"if X.live({mask}):")
                    self.indent += 1
                    fs.nest += 1
                    if self.rest_compacted(stmts[i + 1 :], mask):
                        break
        if run:
            self.frame_run(run, run_start)
        fs.nest -= self.indent - start_indent
        self.indent = start_indent
        return False

    def frame_run(self, run: list[Any], start: int) -> None:
        """The lines of `run` since `start` computed once a frame when that pays off."""
        if frame_values.worth_it(run):
            frame_values.wrap(self, start, self.indent)

    def rest_compacted(self, rest: list[Any], mask: str) -> bool:
        """The statements after an early exit (`if (miss) { ...; return; }`, a `break` or
        `continue`) run on the lanes still going, often few of them: emit them as a compacted
        region (`region_body`) when that pays off, and return True; else emit nothing and return
        False (they follow under the `if X.live(...)` inline). A `return` among them assigns the
        return value under the mask (no Python `return` inside the gathered region: the
        scatter must run); the function's `return _rv` follows the block."""
        fs = self.fn
        assert fs is not None  # generating a function's body
        if fs.no_compact or not rest:
            return False
        node = A.Compound(
            stmts=rest, loc=getattr(rest[0], "loc", None) or Location(self.path, 0, 0)
        )
        if self._region_uses_derivs(node) or not self._worth_compacting(node):
            return False
        self.region_body(lambda m: self.block(rest, m), mask, "rest", node)
        return True

    def dead_lane_region(self, move: dead_lanes.Move, mask: str | None) -> None:
        """The statements of `move` on the lanes whose select reads what they compute (the
        others select the other side whatever these hold: dead_lanes.py), as a region that is
        compacted when few lanes are in it and skipped when none is. Their locals start at
        zero before it, so the select reads a full-lane value."""
        fs = self.fn
        assert fs is not None  # generating a function's body
        for sym, dec in move.declared:
            name = self.var_name(sym, dec)
            self.emit(f"{name} = {self.zero(sym.type, dec)}")
            if name not in fs.defined:
                fs.defined.append(name)
        weight = self.expr(move.weight, mask)
        m = self.fresh("m")
        lanes = f"rt.mix_reads({weight}, {move.side}, {move.form!r})"
        self.emit(f"{m} = X.reads(S, {mask}, {lanes})  # the lanes the select keeps them in")
        self.emit(f"if X.live({m}):")
        self.indent += 1
        node = A.Compound(stmts=list(move.stmts), loc=move.stmts[0].loc)
        self.region_body(lambda mb: self.block(list(move.stmts), mb), m, "select", node)
        self.indent -= 1

    def refresh(self, mask: str | None, ev: Events) -> str:
        fs = self.fn
        assert fs is not None  # generating a function's body
        live = None
        drops = []
        if ev.brk and fs.loops:
            live = fs.loops[-1].live
        if ev.cont:
            loop = next((lp for lp in reversed(fs.loops) if lp.kind == "loop"), None)
            if loop is not None and loop.cont:
                drops.append(loop.cont)
        if ev.ret and fs.has_ret:
            drops.append("_ret")
        new = self.fresh("m")
        self.emit(f"{new} = X.refresh({mask}, {live}{''.join(', ' + d for d in drops)})")
        return new

    def assign_stmt(self, target: str, value: str, mask: str | None) -> None:
        if mask is None:
            self.emit(f"{target} = {value}")
        else:
            self.emit(f"{target} = X.put({target}, {value}, {mask})")

    # -- compaction ------------------------------------------------------------------------------
    def region_body(self, emit_body, mask: str, kind: str, node: Any) -> None:
        """Emit a varying region (already under `if X.live(mask):`) with compaction when sparse."""
        fs = self.fn
        assert fs is not None  # generating a function's body
        rid = self.region(kind, node)
        if fs.no_compact or self._region_uses_derivs(node) or not self._worth_compacting(node):
            self.emit(f"X.count(S, {rid}, {mask})")
            emit_body(mask)
            return
        snapshot = set(fs.defined)
        start = len(self.lines)
        ix = self.fresh("ix")
        saved = self.fresh("o")
        self.emit(f"X.count(S, {rid}, {mask})")
        emit_body(mask)
        body_lines = self.lines[start:]
        lanes, uniform, dead = self._region_names(
            sorted((self.local_names(body_lines) & snapshot) - {mask}), node
        )
        used = lanes + uniform + dead
        del self.lines[start:]
        tup = "(" + "".join(n + ", " for n in used) + ")"
        sparse = "X.select_sparse" if kind == "select" else "X.sparse"
        self.emit(f"{ix} = {sparse}(S, {mask})")
        self.emit(f"if {ix} is not None:")
        self.emit(f"    S, {saved} = X.gather(S, {ix}, {tup})")
        if used:
            self.emit(f"    {', '.join(used)}, = {saved}.values")
        self.emit(f"    {mask} = None")
        self.lines.extend(body_lines)
        self.emit(f"if {ix} is not None:")
        back = lanes + uniform
        out = "(" + "".join(n + ", " for n in back) + ")"
        extra = f", {len(uniform)}" if uniform else ""
        self.emit(f"    S, {out if back else '_'} = X.scatter(S, {ix}, {saved}, {out}{extra})")

    def _region_names(self, used: list[str], node: Any) -> tuple[list[str], list[str], list[str]]:
        """The variables a compacted region reads or writes, in three groups: those put back
        into the region's lanes at its end; uniform locals (every write of them in the region is
        free: `X.scatter` keeps one value for all lanes as that); and locals used only in this
        branch of a varying `if` (`Uniformity.dead_after`), gathered but never put back."""
        fs = self.fn
        assert fs is not None  # generating a function's body
        lanes: list[str] = []
        uniform: list[str] = []
        dead: list[str] = []
        for name in used:
            sym = fs.local_syms.get(name)
            if sym is None or fs.uni is None or not fs.uni.is_own(sym):
                lanes.append(name)
            elif fs.uni.dead_after(sym, node):
                dead.append(name)
            elif not fs.uni.is_varying(sym):
                uniform.append(name)
            else:
                lanes.append(name)
        return lanes, uniform, dead

    def _worth_compacting(self, node: Any) -> bool:
        """Gathering pays off for a region with a loop, a user call or some arithmetic; a
        region of a few assignments (`break;`, `return 0.1;`) is cheaper to run masked."""
        count = 0
        for n in node.walk():
            if isinstance(n, (A.For, A.While, A.DoWhile)):
                return True
            if isinstance(n, A.Call) and (
                isinstance(self.model.call_target(n), Symbol)
                or getattr(self.model.call_target(n), "cost", None) == B.EXPENSIVE
            ):
                return True
            count += 1
            if count >= self.COMPACT_MIN_NODES:
                return True  # (so a region nested hundreds deep is not walked whole)
        return False

    def _region_uses_derivs(self, node: Any) -> bool:
        return fold_tree(node, self._derivs, self._derivs_here)

    def _derivs_here(self, n: Any, kids: list[bool]) -> bool:
        if any(kids):
            return True
        if isinstance(n, A.Call):
            tgt = self.model.call_target(n)
            if getattr(tgt, "name", None) in DERIVATIVES + IMPLICIT_LOD and not isinstance(
                tgt, Symbol
            ):
                return True
            if isinstance(tgt, Symbol) and id(tgt) in self.facts.uses_derivs:
                return True
        return False

    # -- statements ----------------------------------------------------------------------------
    def stmt(self, s: Any, mask: str | None) -> None:
        method = getattr(self, "_stmt_" + type(s).__name__, None)
        if method is None:
            raise _error(f"{type(s).__name__} statements are not supported by the NumPy backend", s)
        self.where = s
        if self.too_deep(OUTLINE_INDENT):
            self.outline(lambda: method(s, mask), s)
        else:
            method(s, mask)

    def _stmt_Compound(self, s: A.Compound, mask: str | None) -> None:
        if not s.stmts:
            return
        self.block(s.stmts, mask)

    def _stmt_ExpressionStatement(self, s: A.ExpressionStatement, mask: str | None) -> None:
        if s.expr is None:
            return
        self.comment_line(s)
        self.effect(s.expr, mask)

    def effect(self, e: Any, mask: str | None, step_unmasked: bool = False) -> None:
        """An expression evaluated for its side effects only."""
        if isinstance(e, A.Assignment):
            self.assignment(e, mask, want_value=False)
        elif isinstance(e, (A.Unary, A.Postfix)) and e.op in ("++", "--"):
            self.incdec(e, mask, want_value=False)
        elif isinstance(e, A.Sequence):
            for x in e.exprs:
                self.effect(x, mask)
        else:
            value = self.expr(e, mask)
            if isinstance(e, A.Call) and isinstance(self.model.call_target(e), Symbol):
                self.emit(value)
            elif "(" in value and not value.startswith(("C_", "Z_")):
                self.emit(value)
        self.after_discarding_call(e)

    def after_discarding_call(self, e: Any) -> None:
        fs = self.fn
        assert fs is not None  # generating a function's body
        if not fs.has_ret:
            return
        for n in e.walk():
            if isinstance(n, A.Call):
                tgt = self.model.call_target(n)
                if isinstance(tgt, Symbol) and id(tgt) in self.facts.may_discard:
                    self.emit("_ret = X.or_(_ret, S.discard)")
                    return

    def _stmt_DeclarationStatement(self, s: A.DeclarationStatement, mask: str | None) -> None:
        fs = self.fn
        assert fs is not None  # generating a function's body
        d = s.decl
        if isinstance(d, A.PrecisionDeclaration):
            return
        if not isinstance(d, A.VariableDeclaration):
            raise _error("this declaration is not supported inside a function", s)
        for dec in d.declarators:
            self.comment_line(dec)
            sym = self.model.symbol_of(dec)
            if sym is None:
                continue
            name = self.var_name(sym, dec)
            value = nir_fold.component_write(self, dec, mask) if dec.init is not None else None
            if value is None:
                value = (
                    self.expr(dec.init, mask)
                    if dec.init is not None
                    else self.initial(sym.type, dec, mask)
                )
            if dec.init is not None:
                value = keep_term(self, dec, value)
                self.after_discarding_call(dec.init)
            register = self.merged_register(dec, mask)
            if name in fs.switch_locals:  # (one in a block inside a case is scoped to it)
                self.emit(f"{name} = X.put({name}, {value}, {mask})")
            elif register is not None:  # (llvmpipe's register of a kept branch: nir_fold)
                self.emit(f"{name} = X.put({register}, {value}, {mask})")
            else:
                self.emit(f"{name} = {value}")
            if name not in fs.defined:
                fs.defined.append(name)

    def merged_register(self, node: Any, mask: str | None) -> str | None:
        """What the lanes outside a divergent kept branch hold for the value the declarator or
        assignment `node` gives a local, where llvmpipe keeps it in a register
        (nir_fold.merged_register): zero, or a component of the variable it is merged into,
        read here; None where it is an SSA value."""
        fs = self.fn
        assert fs is not None  # generating a function's body
        found = nir_fold.merged_register(self, node)
        if found is None or (fs.uni is not None and fs.uni.is_uniform(found.branch.cond)):
            return None
        target = node if isinstance(node, A.Declarator) else node.target
        if found.target is None:
            sym = self.model.symbol_of(target)
            assert sym is not None  # (a local the checker declared)
            return self.zero(sym.type, node)
        old = self.expr(found.target, mask)
        t = self.type_of(found.target)
        return self.component(old, found.component) if t is not None and t.is_vector else old

    def merged_registers(self, s: A.If, mask: str | None) -> None:
        """Before a divergent kept branch, a local declared before it that the branch assigns
        and merges into a variable (nir_fold.merged_register) takes what the lanes outside the
        branch hold, so the arm's masked write of it leaves that there (its old value is dead:
        the rule asks that). A local declared in the arm takes it at its declaration."""
        if not isinstance(s.then, A.Compound):
            return
        for node in nir_fold.arm_values(s.then):
            if isinstance(node, A.Assignment):
                fill = self.merged_register(node, mask)
                if fill is not None:
                    self.comment_line(node)
                    self.write(self.lvalue(node.target, mask), fill, None)

    def declare_switch_locals(self, s: A.Switch) -> None:
        fs = self.fn
        assert fs is not None  # generating a function's body
        for st in s.body:
            if isinstance(st, A.DeclarationStatement) and isinstance(
                st.decl, A.VariableDeclaration
            ):
                for dec in st.decl.declarators:
                    sym = self.model.symbol_of(dec)
                    if sym is not None:
                        name = self.var_name(sym, dec)
                        self.emit(f"{name} = {self.zero(sym.type, dec)}")
                        fs.defined.append(name)
                        fs.switch_locals.add(name)

    def _stmt_If(self, s: A.If, mask: str | None) -> None:
        self.comment_line(s)
        fs = self.fn
        assert fs is not None  # generating a function's body
        self.merged_registers(s, mask)
        cond = self.expr(s.cond, mask)
        self.after_discarding_call(s.cond)
        if fs.uni is not None and fs.uni.is_uniform(s.cond):
            # lane-uniform condition: plain Python control flow, same mask inside
            self.emit(f"if X.true({cond}):")
            self.indent += 1
            self.emit(f"X.count(S, {self.region('if', s)}, {mask})")
            self.sub(s.then, mask)
            self.indent -= 1
            if s.else_ is not None:
                self.emit("else:")
                self.indent += 1
                self.emit(f"X.count(S, {self.region('else', s.else_)}, {mask})")
                self.sub(s.else_, mask)
                self.indent -= 1
            return
        c = self.fresh("c")
        self.emit(f"{c} = {cond}")
        for branch, how, kind in ((s.then, "and_", "if"), (s.else_, "andnot", "else")):
            if branch is None:
                continue
            mb = self.fresh("m")
            self.emit(f"{mb} = X.{how}({mask}, {c})")
            self.emit(f"if X.live({mb}):")
            self.indent += 1
            self.region_body(lambda m, branch=branch: self.sub(branch, m), mb, kind, branch)
            self.indent -= 1

    def sub(self, s: Any, mask: str | None) -> None:
        start = len(self.lines)
        if isinstance(s, A.Compound):
            self.block(s.stmts, mask)
        else:
            self.block([s], mask)
        if len(self.lines) == start:
            self.emit("pass")

    def _stmt_Break(self, s: A.Break, mask: str | None) -> None:
        fs = self.fn
        assert fs is not None  # generating a function's body
        self.comment_line(s)
        lp = fs.loops[-1]
        self.emit(f"{lp.live} = X.andnot({lp.live}, {mask})")

    def _stmt_Continue(self, s: A.Continue, mask: str | None) -> None:
        fs = self.fn
        assert fs is not None  # generating a function's body
        self.comment_line(s)
        lp = next(lp for lp in reversed(fs.loops) if lp.kind == "loop")
        self.emit(f"{lp.cont} = X.or_({lp.cont}, {mask})")

    def _stmt_Discard(self, s: A.Discard, mask: str | None) -> None:
        fs = self.fn
        assert fs is not None  # generating a function's body
        self.comment_line(s)
        self.emit(f"S.discard = X.or_(S.discard, {mask})")
        if fs.has_ret:
            self.emit(f"_ret = X.or_(_ret, {mask})")

    def _stmt_Return(self, s: A.Return, mask: str | None) -> None:
        self.comment_line(s)
        fs = self.fn
        assert fs is not None  # generating a function's body
        if s.value is not None:
            val = self.expr(s.value, mask)
            self.after_discarding_call(s.value)
            if fs.rv is not None:
                self.assign_stmt(fs.rv, val, mask)
        if fs.has_ret:
            self.emit(f"_ret = X.or_(_ret, {mask})")

    def _stmt_Switch(self, s: A.Switch, mask: str | None) -> None:
        self.comment_line(s)
        fs = self.fn
        assert fs is not None  # generating a function's body
        sel = self.fresh("sv")
        self.emit(f"{sel} = {self.expr(s.expr, mask)}")
        self.declare_switch_locals(s)
        labels = [st for st in s.body if isinstance(st, A.Case)]
        consts = []
        for lab in labels:
            if lab.expr is not None:
                v = self.model.const_value(lab.expr)
                if v is None:
                    raise _error("a case label must be a constant integer", lab)
                consts.append(self.const_int(v, self.model.type_of(lab.expr) == T.UINT))
        dflt = None
        if any(lab.expr is None for lab in labels):
            dflt = self.fresh("d")
            if consts:
                any_case = " | ".join(f"rt.eq({sel}, {c})" for c in consts)
                self.emit(f"{dflt} = rt.not_({any_case})")
            else:
                self.emit(f"{dflt} = {self.const_bool(True)}")
        live = self.fresh("sl")
        fall = self.fresh("fall")
        # lanes that `continue` the loop around in one case run no later case
        around = next((lp for lp in reversed(fs.loops) if lp.kind == "loop"), None)
        cont = around.cont if around is not None else None
        self.emit(f"{live} = {mask}")
        self.emit(f"{fall} = X.NO")
        fs.loops.append(LoopCtx("switch", live))
        fs.switch_depth += 1
        groups: list[tuple[list[Any], list[Any]]] = []
        for st in s.body:
            if isinstance(st, A.Case):
                if groups and not groups[-1][1]:
                    groups[-1][0].append(st)
                else:
                    groups.append(([st], []))
            else:
                groups[-1][1].append(st)
        ci = 0
        for labs, stmts in groups:
            for lab in labs:
                self.comment_line(lab)
                if lab.expr is None:
                    self.emit(f"{fall} = X.or_({fall}, {dflt})")
                else:
                    self.emit(f"{fall} = X.or_({fall}, rt.eq({sel}, {consts[ci]}))")
                    ci += 1
            cur = self.fresh("m")
            self.emit(f"{cur} = X.and_(X.and_({live}, {fall}), {mask})")
            if fs.has_ret:
                self.emit(f"{cur} = X.andnot({cur}, _ret)")
            if cont is not None:
                self.emit(f"{cur} = X.andnot({cur}, {cont})")
            self.emit(f"if X.live({cur}):")
            self.indent += 1
            self.emit(f"X.count(S, {self.region('case', labs[0])}, {cur})")
            self.block(stmts, cur)
            self.indent -= 1
        fs.switch_depth -= 1
        fs.loops.pop()

    # loops --------------------------------------------------------------------------------------
    def _stmt_For(self, s: A.For, mask: str | None) -> None:
        self.comment_line(s)
        if s.init is not None:
            self.stmt(s.init, mask)
        enter_unrolled(self, s)  # a `+= #c` chain the unrolled copies continue
        self.loop(s, mask, s.cond, s.body, s.step, do_while=False)

    def _stmt_While(self, s: A.While, mask: str | None) -> None:
        self.comment_line(s)
        self.loop(s, mask, s.cond, s.body, None, do_while=False)

    def _stmt_DoWhile(self, s: A.DoWhile, mask: str | None) -> None:
        self.comment_line(s)
        self.loop(s, mask, s.cond, s.body, None, do_while=True)

    def loop(
        self, s: Any, mask: str | None, cond: Any, body: Any, step: Any, do_while: bool
    ) -> None:
        fs = self.fn
        assert fs is not None  # generating a function's body
        lid = self.region("loop", s)
        self.loops[lid] = (s.loc.path, s.loc.line, s.loc.column)
        ind = induction_variable(s, self.model, self.facts)
        ev_body = events_of(body, self.facts, self.model)
        if (
            not do_while
            and cond is not None
            and not isinstance(cond, A.ConditionDeclaration)
            and not ev_body.any
            and fs.uni is not None
            and fs.uni.is_uniform(cond)
        ):
            self.uniform_loop(s, lid, mask, cond, body, step, ind)
            return
        live = self.fresh("live")
        count = self.fresh("n")
        self.emit(f"{live} = {mask}")
        self.emit(f"{count} = 0")
        compact = not fs.no_compact and not self._region_uses_derivs(s)
        snapshot = set(fs.defined)
        stack = self.fresh("k") if compact else None
        if stack:
            self.emit(f"{stack} = []")
        start_lines = len(self.lines)
        self.loop_top(
            lid, count, live, f"X.andnot({live}, _ret)" if ev_body.ret and fs.has_ret else None
        )
        self.emit(f"if not X.live({live}):")
        self.emit("    break")
        if not (do_while or cond is None):
            c = self.condition(cond, live)
            self.emit(f"{live} = X.and_({live}, {c})")
            self.emit(f"if not X.live({live}):")
            self.emit("    X.spend(S)")
            self.emit("    break")
        compact_at = len(self.lines)
        cont = None
        if ev_body.cont:
            cont = self.fresh("cnt")
            self.emit(f"{cont} = X.NO")
        fs.loops.append(LoopCtx("loop", live, cont))
        self.emit(f"X.count(S, {lid}, {live})")
        bmask = live
        self.sub(body, bmask)
        if isinstance(s, A.For):
            end_of_unrolled_body(self, s)
        fs.loops.pop()
        if do_while:
            c = self.condition(cond, live)
            self.emit(f"{live} = X.and_({live}, {c})")
        if step is not None:
            self.comment_line(step)
            if ind is not None:
                self.effect(step, None)
            else:
                smask = live
                if ev_body.ret and fs.has_ret:
                    smask = self.fresh("m")
                    self.emit(f"{smask} = X.andnot({live}, _ret)")
                self.effect(step, smask)
        self.indent -= 1
        fs.blocks -= 1
        if stack:
            loop_lines = self.lines[start_lines:]
            used = sorted((self.local_names(loop_lines) & snapshot) | {live})
            tup = "(" + ", ".join(used) + ",)"
            pad = "    " * (self.indent + 1)
            push = [
                f"{pad}if X.loop_sparse(S, {live}) is not None:",
                f"{pad}    S, ({', '.join(used)},) = X.push({stack}, S, {live}, {tup})",
                f"{pad}    {live} = None",
            ]
            self.lines[compact_at:compact_at] = push
            self.emit(f"if {stack}:")
            self.emit(f"    S, ({', '.join(used)},) = X.unwind({stack}, S, {tup})")

    def loop_top(
        self, lid: int, count: str, live: str | None = None, returned: str | None = None
    ) -> None:
        """Open a loop's `while True:` with its guards: the iteration count (`LOOP_CAP`, a located
        error past it) and llvmpipe's loop limiter, if rendering with one (`X.tick`; it stops
        the loop's `live` lanes, after the lanes that returned, `returned`, left them)."""
        fs = self.fn
        assert fs is not None  # generating a function's body
        self.emit("while True:")
        self.indent += 1
        fs.blocks += 1
        self.emit(f"{count} += 1")
        self.emit(f"if {count} > {LOOP_CAP}:")
        self.emit(f"    X.runaway({lid})")
        if returned is not None:
            self.emit(f"{live} = {returned}")
        self.emit(f"if X.tick(S, {count}):")
        self.emit(f"    X.stop({lid}, {live or 'None'})")
        self.emit("    break")

    def uniform_loop(
        self, s: Any, lid: int, mask: str | None, cond: Any, body: Any, step: Any, ind: Any
    ) -> None:
        """A loop whose condition is the same in every lane and whose body cannot leave it
        early (no break, continue, return or discard): every iteration runs on the lanes that
        entered, so it is plain Python control flow with no mask of its own."""
        fs = self.fn
        assert fs is not None  # generating a function's body
        count = self.fresh("n")
        self.emit(f"{count} = 0")
        self.loop_top(lid, count, mask)
        c = self.condition(cond, mask)
        self.emit(f"if not X.true({c}):")
        self.emit("    X.spend(S)")
        self.emit("    break")
        fs.loops.append(LoopCtx("loop", mask if mask is not None else "None", None))
        self.emit(f"X.count(S, {lid}, {mask})")
        self.sub(body, mask)
        if isinstance(s, A.For):
            end_of_unrolled_body(self, s)
        fs.loops.pop()
        if step is not None:
            self.comment_line(step)
            self.effect(step, None if ind is not None else mask)
        self.indent -= 1
        fs.blocks -= 1

    def condition(self, cond: Any, mask: str | None) -> str:
        fs = self.fn
        assert fs is not None  # generating a function's body
        if isinstance(cond, A.ConditionDeclaration):
            sym = self.model.symbol_of(cond)
            assert sym is not None  # every declaration of a checked program has its symbol
            name = self.var_name(sym, cond)
            self.emit(f"{name} = {self.expr(cond.init, mask)}")
            if name not in fs.defined:
                fs.defined.append(name)
            return name
        return self.expr(cond, mask)
