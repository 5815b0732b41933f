"""The semantic pass: scopes, symbols and a type for every expression (GLSL ES 3.00 + Shadertoy).

Owns the rules a compiler enforces after parsing (spec chapters 4-6 and 8): declarations and
redefinitions, struct types, function overloads and prototype/definition matching, exact-match
typing of every expression (no implicit conversions), l-values, constant expressions, control
flow placement (`break`, `continue`, `switch`), array sizes and constant indexes, the Shadertoy
entry point and the uniforms each tab sees. The typing rules themselves live in
`language/glsl_types.py` and the built-in table in `language/builtin_functions.py`; this package
applies them to the tree and records the results on a `Model`. Errors are collected, never raised
here; `semantics.check()` decides.

`Checker` (here) holds the pass's state (the model being filled, the current scope and
function, loop and switch depths) and its reporting; each concern's rules are a part of it:

    declarations.py     global and local declarations, qualifiers, struct and array types
    functions.py        prototypes, definitions, overloads; the whole-program (link) rules
    statements.py       statements and control flow (`stmt_<Node>` methods)
    expressions.py      literals, names, operators, l-values, indexes, fields (`expr_<Node>`)
    calls.py            function calls and constructors
    shadertoy_rules.py  Shadertoy's uniforms and output, the Common tab, mainImage, WebGL rules
    hints.py            the help text of type errors, the location of a declared name

Statements and expressions are dispatched by node class (`syntax.NodeVisitor.dispatch`).
Where GLSL leaves a choice, the behaviour follows glslangValidator on the program Shadertoy
builds (see tests/check/test_glslang_agreement.py for the cases where it deliberately does not).
"""

from __future__ import annotations

from ...base.diagnostics import Diagnostic, Location
from ...frontend import syntax as A
from ...language import glsl_types as T
from ..model import ERROR, Model, Symbol
from ..scopes import Scope, UniqueNames
from .calls import CallChecks
from .declarations import DeclarationChecks
from .expressions import ExpressionChecks
from .functions import FunctionChecks
from .shadertoy_rules import ShadertoyRules
from .statements import StatementChecks

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from typing import Any


class Checker(
    DeclarationChecks,
    FunctionChecks,
    StatementChecks,
    ExpressionChecks,
    CallChecks,
    ShadertoyRules,
    A.NodeVisitor,
):
    """`Checker(parse_result, tab, channel_types).run()`: the `Model` of one program, its
    diagnostics collected on it."""

    def __init__(
        self, parse_result: Any, tab: str, channel_types: dict[str, T.Type] | None = None
    ) -> None:
        self.pr = parse_result
        self.channel_types = channel_types or {}  # iChannelN -> its sampler type (channel_types.py)
        self.ast: A.TranslationUnit = parse_result.ast
        sources = list(getattr(parse_result, "sources", []) or [])
        self.plain = any(getattr(s, "is_plain_glsl", False) for s in sources) or tab == "GLSL"
        self.tab = "GLSL" if self.plain else tab
        self.common_paths = {s.path for s in sources if getattr(s, "tab", None) == "Common"}
        tab_src = [s for s in sources if getattr(s, "tab", None) == self.tab] or sources[-1:]
        self.tab_path = (
            tab_src[0].path if tab_src else (self.ast.loc.path if self.ast.loc else "<string>")
        )
        self.model = Model(self.ast, self.tab)
        m = self.model
        self.types = m._types
        self.symbols = m._symbols
        self.consts = m._consts
        self.func: Symbol | None = None  # the function being checked
        self.func_returns = 0
        self.loop_depth = 0
        self.switch_depth = 0
        self.anon_structs = 0
        self.unique = UniqueNames(self._names_in_program)
        # Default precisions in effect (spec 4.5.4: a fragment shader has none for float and for
        # most samplers); Shadertoy's prelude sets float, int and sampler3D.
        self.default_precision: dict[str, str] = {
            "int": "mediump",
            "sampler2D": "lowp",
            "samplerCube": "lowp",
        }
        if not self.plain:
            self.default_precision.update(
                {"float": "highp", "int": "highp", "sampler3D": "mediump"}
            )
        self.builtin_scope = Scope(None, "builtin")
        self.scope = Scope(self.builtin_scope, "global")
        self.global_scope = self.scope
        self.declare_predefined()

    def _names_in_program(self) -> set[str]:
        """Every name written in the program (of a node with a `name`)."""
        names = {getattr(n, "name", None) for n in self.model.nodes()}
        return {n for n in names if isinstance(n, str)}

    def error(
        self, message: str, node: Any, help: str | None = None, severity: str = "error"
    ) -> None:
        loc = node if isinstance(node, Location) else getattr(node, "loc", None)
        self.model.diagnostics.append(
            Diagnostic(message, loc, severity=severity, rule="type", help=help)
        )

    def warning(self, message: str, node: Any, help: str | None = None) -> None:
        self.error(message, node, help, severity="warning")

    def run(self) -> Model:
        for decl in self.ast.decls:
            self.external(decl)
        self.check_whole_program()
        return self.model

    def push(self, kind: str) -> None:
        self.scope = Scope(self.scope, kind)

    def pop(self) -> None:
        assert self.scope.parent is not None
        self.scope = self.scope.parent

    def stmt(self, s: A.Node) -> None:
        self.dispatch("stmt_", s)

    def missing(self, prefix: str, node: A.Node) -> T.Type | None:
        """A node with no `stmt_` (or `expr_`) method where a statement (or expression) goes:
        an error at it (the expression's type is ERROR, which silences the errors above it)."""
        if prefix == "expr_":
            self.error(f"'{type(node).__name__}' is not an expression", node)
            return ERROR
        self.error(f"unexpected {type(node).__name__} here", node)
        return None

    def is_const(self, node: Any) -> bool:
        return id(node) in self.consts

    def expr(self, node: A.Node) -> T.Type:
        t = self.dispatch("expr_", node)
        self.types[id(node)] = t
        return t
