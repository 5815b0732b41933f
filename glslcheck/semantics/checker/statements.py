"""Statements and control flow: scopes of blocks and loops, conditions, `switch`, `break`, `return`.

Owns the scope each statement opens (a loop's compound body shares the loop's scope, spec 6.3),
bool conditions, the placement of `break`, `continue` and `case` labels, the rules of a
`switch` (int selector, constant distinct labels, no statement before the first label) and the
type of a returned value. Statements go to `stmt_<Node>` methods (`syntax.NodeVisitor.dispatch`).
"""

from __future__ import annotations

from ...frontend import syntax as A
from ...language import glsl_types as T
from ..model import ERROR, Symbol
from .hints import NameAt, conversion_help, int_literal_hint
from .state import CheckerState

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterable
    from typing import Any


class StatementChecks(CheckerState):
    """Statements and control flow, for `Checker`."""

    # -- statements ----------------------------------------------------------------------------
    def block_statements(self, stmts: Iterable[A.Node]) -> None:
        for s in stmts:
            self.stmt(s)

    def sub_statement(self, s: A.Node | None, new_scope: bool) -> None:
        """A loop body: a compound body shares the loop's scope (no new scope, spec 6.3)."""
        if s is None:
            return
        if isinstance(s, A.Compound) and not new_scope:
            self.block_statements(s.stmts)
        else:
            self.stmt(s)

    def stmt_Compound(self, s: A.Compound) -> None:
        self.push("block")
        self.block_statements(s.stmts)
        self.pop()

    def stmt_DeclarationStatement(self, s: A.DeclarationStatement) -> None:
        decl = s.decl
        if isinstance(decl, A.VariableDeclaration):
            self.variable_declaration(decl, is_global=False)
        elif isinstance(decl, A.FunctionDeclaration):
            self.error(
                "functions cannot be declared inside a function in GLSL ES",
                decl,
                help="move the prototype to global scope",
            )
        elif isinstance(decl, A.PrecisionDeclaration):
            self.precision_declaration(decl)
        else:
            self.error("this declaration is only allowed at global scope", decl)

    def stmt_ExpressionStatement(self, s: A.ExpressionStatement) -> None:
        if s.expr is not None:
            self.expr(s.expr)

    def condition(self, cond: A.Node | None, what: str) -> None:
        if cond is None:
            return
        if isinstance(cond, A.ConditionDeclaration):
            t = self.resolve_type(cond.type)
            init_t = self.expr(cond.init) if cond.init is not None else ERROR
            if t is not ERROR and t != T.BOOL:
                self.error(f"the condition of {what} must be a bool, not '{t}'", cond)
            elif t is not ERROR and init_t is not ERROR and init_t != t:
                self.error(
                    f"cannot initialise '{cond.name}' of type '{t}' with a value of type "
                    f"'{init_t}'",
                    cond.init,
                )
            storage = cond.qualifiers.storage if cond.qualifiers else None
            sym = Symbol(cond.name, "local", t, node=cond, qualifier=storage)
            self.declare(sym, cond, NameAt(cond))
            return
        t = self.expr(cond)
        if t is not ERROR and t != T.BOOL:
            hint = None
            if t.is_vector and t.base == "bool":
                hint = "use any(...) or all(...) to turn a bvec into a bool"
            elif t.is_numeric and t.is_scalar:
                hint = f"compare it: ({'x != 0' if t.base != 'float' else 'x != 0.0'})"
            self.error(f"the condition of {what} must be a bool, not '{t}'", cond, help=hint)

    def stmt_If(self, s: A.If) -> None:
        self.condition(s.cond, "an if")
        self.sub(s.then)
        if s.else_ is not None:
            self.sub(s.else_)

    def sub(self, s: A.Node) -> None:
        """A nested statement that is not a compound opens its own scope too."""
        if isinstance(s, A.Compound):
            self.stmt(s)
        else:
            self.push("block")
            self.stmt(s)
            self.pop()

    def stmt_While(self, s: A.While) -> None:
        self.push("while")
        self.condition(s.cond, "a while loop")
        self.loop_depth += 1
        self.sub_statement(s.body, new_scope=False)
        self.loop_depth -= 1
        self.pop()

    def stmt_DoWhile(self, s: A.DoWhile) -> None:
        self.loop_depth += 1
        self.sub(s.body)
        self.loop_depth -= 1
        self.condition(s.cond, "a do-while loop")

    def stmt_For(self, s: A.For) -> None:
        self.push("for")
        if s.init is not None:
            self.stmt(s.init)
        self.condition(s.cond, "a for loop")
        if s.step is not None:
            self.expr(s.step)
        self.loop_depth += 1
        self.sub_statement(s.body, new_scope=False)
        self.loop_depth -= 1
        self.pop()

    def stmt_Switch(self, s: A.Switch) -> None:
        t = self.expr(s.expr) if s.expr is not None else ERROR
        if t is not ERROR and t not in (T.INT, T.UINT):
            self.error(
                f"a switch needs an int or uint value, not '{t}'",
                s.expr,
                help="switch on an int, or use if/else for other types",
            )
            t = ERROR
        self.push("switch")
        self.switch_depth += 1
        seen: dict[Any, A.Node] = {}
        default_seen = False
        body = s.body
        if body and not isinstance(body[0], A.Case):
            self.error(
                "a switch cannot have statements before its first 'case' or 'default' label",
                body[0],
                help="move the statement before the switch, or add a 'case' label above it",
            )
        for stmt in body:
            if isinstance(stmt, A.Case):
                if stmt.expr is None:
                    if default_seen:
                        self.error("this switch already has a 'default' label", stmt)
                    default_seen = True
                    continue
                ct = self.expr(stmt.expr)
                if ct is ERROR:
                    continue
                if ct not in (T.INT, T.UINT) or not self.is_const(stmt.expr):
                    self.error("a case label must be a constant integer expression", stmt.expr)
                    continue
                if t is not ERROR and ct != t:
                    self.error(
                        f"the case label is '{ct}' but the switch value is '{t}'",
                        stmt.expr,
                        help="write the label with the same type (add or remove the 'u' suffix)",
                    )
                v = self.model.const_value(stmt.expr)
                if v is not None:
                    if v in seen:
                        self.error(f"'case {v}:' appears twice in this switch", stmt.expr)
                    seen[v] = stmt
            else:
                self.stmt(stmt)
        if body and isinstance(body[-1], A.Case):
            self.error(
                "the last case label of a switch must be followed by a statement",
                body[-1],
                help="add 'break;' after it",
            )
        self.switch_depth -= 1
        self.pop()

    def stmt_Case(self, s: A.Case) -> None:
        self.error("'case' and 'default' labels belong inside a switch", s)

    def stmt_Break(self, s: A.Break) -> None:
        if self.loop_depth == 0 and self.switch_depth == 0:
            self.error("'break' is only allowed inside a loop or a switch", s)

    def stmt_Continue(self, s: A.Continue) -> None:
        if self.loop_depth == 0:
            self.error("'continue' is only allowed inside a loop", s)

    def stmt_Discard(self, s: A.Discard) -> None:
        pass

    def stmt_Return(self, s: A.Return) -> None:
        self.func_returns += 1
        ret = self.func.type if self.func is not None else T.VOID
        if s.value is None:
            if ret is not ERROR and not ret.is_void:
                self.error(
                    f"this function must return a '{ret}' value",
                    s,
                    help=f"write 'return <{ret} value>;'",
                )
            return
        t = self.expr(s.value)
        if ret is ERROR or t is ERROR:
            return
        if ret.is_void:
            self.error(
                f"a void function cannot return a value (this returns '{t}')",
                s.value,
                help="remove the value, or change the return type",
            )
        elif t != ret:
            hint = int_literal_hint(s.value) if ret.base == "float" else None
            msg = f"the function returns '{ret}' but this value is '{t}'"
            if hint:
                msg += f": {hint}"
            self.error(msg, s.value, help=hint or conversion_help(ret, t))
