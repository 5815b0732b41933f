"""A local variable may be read before it is assigned a value.

## What it does
Follows each function's statements in order and reports the first read of a local variable
declared without an initializer when some path reaches the read without an assignment: an
`if` without `else` (or with one arm only assigning), a loop body (which may run zero times), a
`?:` or `&&`/`||` arm, a `switch` case. An assignment to a part (`v.x = ..`, `a[i] = ..`)
counts as an assignment, and so does passing the variable as an `out` argument
(`traceScene(ray, position, normal)`); an `inout` argument is a read. One finding per variable.

This is a note, not a deduction: WebGL implementations zero-initialise variables, so the
shader may look right; GLSL ES 3.00 itself leaves the value undefined.

## Why is this bad?
GLSL ES 3.00 (section 4.3): a local variable without an initializer has an undefined value.
What it reads depends on the driver: the shader may work in one browser and show garbage in
another. It is also usually a logic error (a branch that forgot to set the value).

## Example
```glsl
float kS;
if (kD > 0.0) kS = pow(max(dot(viewDir, reflected), 0.0), alpha);
color += kS * specularColor;
```

## Use instead
```glsl
float kS = 0.0; // no highlight where the light does not reach
if (kD > 0.0) kS = pow(max(dot(viewDir, reflected), 0.0), alpha);
color += kS * specularColor;
```
"""

from __future__ import annotations

from ...base.diagnostics import Diagnostic
from ...frontend import syntax as A
from ...semantics.analysis import param_directions, program_facts, written_variable

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator
    from typing import Any

    from ...semantics.model import Model
    from ..engine import LintContext

NAME = "uninitialized-read"
PENALTY = 0
SEVERITY = "note"
NEEDS = "ast"


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    for fn in program_facts(ctx.model).in_file(ctx.path):
        tracked = {id(w.symbol): w for ws in fn.writes.values() for w in ws if w.kind == "decl"}
        if not tracked:
            continue
        flow = _Flow(fn.model, tracked)
        try:
            flow.stmt(fn.definition.body, set())
        except RecursionError:
            continue
        for ident, decl in flow.found:
            yield Diagnostic(
                f"'{ident.name}' may be read before it is assigned a value "
                f"(declared at line {decl.node.loc.line} without an initializer)",
                ident.loc,
                help=f"initialise '{ident.name}' where it is declared, or assign it on every path before this read",
            )


class _Flow:
    """Definite assignment: a state is the set of tracked variables assigned on every path
    (None: unreachable, after return/break/continue/discard)."""

    def __init__(self, model: Model, tracked: dict) -> None:
        self.model = model
        self.tracked = tracked
        self.reported: set[int] = set()
        self.found: list = []

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
        if t is A.For:
            st = self.stmt(s.init, st)
            assert st is not None  # an init (a declaration or an expression) always completes
            st = self.cond(s.cond, st)
            body = self.stmt(s.body, set(st))
            if body is not None and s.step is not None:
                self.expr(s.step, body)
            return st
        if t is A.While:
            st = self.cond(s.cond, st)
            self.stmt(s.body, set(st))
            return st
        if t is A.DoWhile:
            body = self.stmt(s.body, st)
            return self.expr(s.cond, body) if body is not None else st
        if t is A.Switch:
            st = self.expr(s.expr, st)
            ends: list = []
            cur: set | None = None
            has_default = False
            for x in s.body:
                if type(x) is A.Case:
                    has_default = has_default or x.expr is None
                    cur = set(st) if cur is None else _meet(cur, set(st))
                    continue
                if type(x) is A.Break:
                    ends.append(cur)
                    cur = None
                    continue
                cur = self.stmt(x, cur) if cur is not None else None
            ends.append(cur)
            if not has_default:
                ends.append(st)
            out: set | None = None
            for e in ends:
                out = _meet(out, e)
            return out if out is not None else st
        if t is A.Return:
            if s.value is not None:
                self.expr(s.value, st)
            return None
        if t in (A.Break, A.Continue, A.Discard):
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
    def read(self, ident: A.Identifier, st: set) -> None:
        sym = self.model.symbol_of(ident)
        if sym is None:
            return
        i = id(sym)
        if i in self.tracked and i not in st and i not in self.reported:
            self.reported.add(i)
            self.found.append((ident, self.tracked[i]))

    def target(self, e: Any, st: set, reads: bool) -> set:
        """Evaluate an l-value: index expressions are read; the variable is read when `reads`."""
        root = e
        while type(root) in (A.Field, A.Index):
            if type(root) is A.Index:
                st = self.expr(root.index, st)
            root = root.base
        if type(root) is A.Identifier:
            if reads:
                self.read(root, st)
            return st | self._root(root)
        return self.expr(root, st)

    def expr(self, e: Any, st: set) -> set:
        if e is None:
            return st
        t = type(e)
        if t is A.Identifier:
            self.read(e, st)
            return st
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
            return self.expr(e.then, set(st)) & self.expr(e.else_, set(st))  # both complete
        if t is A.Binary and e.op in ("&&", "||"):
            st = self.expr(e.left, st)
            self.expr(e.right, set(st))
            return st
        if t is A.Call:
            dirs = param_directions(self.model.call_target(e))
            outs = []
            for i, arg in enumerate(e.args):
                d = dirs[i] if i < len(dirs) else "in"
                if d == "out":
                    outs.append(arg)
                    st = self.target(arg, st, reads=False)  # assigned by the call
                elif d == "inout":
                    outs.append(arg)
                    st = self.expr(arg, st)
                else:
                    st = self.expr(arg, st)
            for arg in outs:
                st = st | self._root(arg)
            return st
        for child in e.children():
            st = self.expr(child, st)
        return st

    def _root(self, e: Any) -> set:
        sym, _ = written_variable(self.model, e)
        return {id(sym)} if sym is not None else set()


def _meet(a: set | None, b: set | None) -> set | None:
    if a is None:
        return b
    if b is None:
        return a
    return a & b
