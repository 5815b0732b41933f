"""The base of every part of the checker: what the parts share, declared for type checkers.

`Checker` (checker/__init__.py) is made of one class per concern (declarations, functions,
statements, expressions, calls, Shadertoy's rules); each part reads the state `Checker.__init__`
sets up and calls methods another part defines. `CheckerState` declares both, so each part is
checked on its own against them (and mypy checks each definition against its declaration). At
run time it is an empty class.
"""

from __future__ import annotations

from ...frontend import syntax as A

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterable
    from typing import Any

    from ...language import glsl_types as T
    from ..model import Model, Symbol
    from ..scopes import Scope, UniqueNames


class CheckerState(A.NodeVisitor):
    if TYPE_CHECKING:
        # Set up by Checker.__init__ (see there).
        pr: Any
        channel_types: dict[str, T.Type]
        ast: A.TranslationUnit
        plain: bool
        tab: str
        common_paths: set[str]
        tab_path: str
        model: Model
        types: dict[int, T.Type]
        symbols: dict[int, Symbol]
        consts: dict[int, Any]
        func: Symbol | None
        func_returns: int
        loop_depth: int
        switch_depth: int
        anon_structs: int
        unique: UniqueNames
        default_precision: dict[str, str]
        builtin_scope: Scope
        scope: Scope
        global_scope: Scope

        # Checker (checker/__init__.py)
        def error(
            self, message: str, node: Any, help: str | None = None, severity: str = "error"
        ) -> None: ...
        def warning(self, message: str, node: Any, help: str | None = None) -> None: ...
        def push(self, kind: str) -> None: ...
        def pop(self) -> None: ...
        def stmt(self, s: A.Node) -> None: ...
        def expr(self, node: A.Node) -> T.Type: ...
        def is_const(self, node: Any) -> bool: ...

        # DeclarationChecks (declarations.py)
        def precision_declaration(self, decl: A.PrecisionDeclaration) -> None: ...
        def require_precision(self, t: T.Type, words: Iterable[str], node: Any) -> None: ...
        def qualifier_words(self, words: list[str], node: Any) -> None: ...
        def check_name(self, name: str, node: Any) -> bool: ...
        def declare(self, sym: Symbol, node: Any, where: Any) -> None: ...
        def resolve_type(self, spec: A.TypeSpec | None, allow_array: bool = True) -> T.Type: ...
        def with_array(self, t: T.Type, array: A.ArraySpec | None, where: Any) -> T.Type: ...
        def array_size(self, spec: A.ArraySpec) -> Any: ...
        def struct(self, spec: A.StructSpec) -> T.Type: ...
        def variable_declaration(self, decl: A.VariableDeclaration, is_global: bool) -> None: ...

        # FunctionChecks (functions.py)
        def function(
            self, proto: A.FunctionPrototype, definition: A.FunctionDefinition | None
        ) -> None: ...

        # StatementChecks (statements.py)
        def block_statements(self, stmts: Iterable[A.Node]) -> None: ...

        # ExpressionChecks (expressions.py)
        def did_you_mean(
            self, name: str, functions: bool = False, structs: bool = False
        ) -> str | None: ...
        def lvalue_problem(self, node: A.Node) -> str | None: ...

        # ShadertoyRules (shadertoy_rules.py)
        def in_macro_entry(self) -> bool: ...
        def common_uniform_error(self, n: A.Identifier) -> None: ...
        def webgl(self, problem: tuple[str, str] | None, node: Any) -> None: ...
        def find_entry(self, name: str) -> None: ...
