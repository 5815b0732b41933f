"""The semantic model of a checked program: symbols and what the checker learned about each node.

This module owns `Symbol` (one declared name: variable, parameter, function, struct, built-in
variable or Shadertoy uniform) and `Model`, the read-only result of `check()` that every later
stage consumes: the linter asks it for types and symbols, the NumPy transpiler for unique names,
call targets, swizzle indices and folded constants. AST nodes are slotted, so everything is kept
in dictionaries keyed by `id(node)`; the model holds the AST so those ids stay valid.
"""

from __future__ import annotations

from ..base.diagnostics import Diagnostic, GlslError
from ..base.records import field, record
from ..frontend import syntax as A
from ..language import glsl_types as T
from ..language.builtin_functions import Overload
from .consteval import UNKNOWN  # the checker imports it anyway; a call-time import cost every call

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from typing import Any


class ErrorType(T.Type):
    """The type of an expression that failed to check; it silences follow-up errors."""

    __slots__ = ()
    base = None

    def __str__(self) -> str:
        return "<error>"

    def __repr__(self) -> str:
        return "ERROR"


ERROR = ErrorType()


@record(frozen=True)
class Constructor:
    """The target of a constructor call (`vec3(...)`, `float[2](...)`, a struct's name): the type
    it builds. Tell it from a Symbol or an Overload with `isinstance(target, Constructor)`."""

    type: T.Type


class CheckError(GlslError):
    """Raised by `check()` when the program has errors (carries every diagnostic)."""


@record(eq=False, slots=False)
class Symbol:
    """A declared name. Symbols compare by identity: two `x` in different scopes differ.

    kind: "global", "local", "param", "function", "builtin-var", "uniform" (a Shadertoy uniform)
    or "struct". For a function `type` is the return type and `params` lists
    (name, Type, direction); `defined` says whether a body was seen. `unique_name` is unique in
    the program (`x`, `x_1` for a shadowing `x`, `f_1` for a second overload of `f`).
    """

    name: str
    kind: str
    type: T.Type
    node: Any = None
    qualifier: str | None = None
    function: Symbol | None = None
    unique_name: str = ""
    const_value: Any = None
    params: list[tuple[str, T.Type, str]] = field(default_factory=list)
    defined: bool = False

    def __repr__(self) -> str:
        return f"Symbol({self.kind} {self.type} {self.unique_name or self.name})"

    def signature(self) -> str:
        """`float f(in vec2, out float)` for functions, `vec3 x` for variables."""
        if self.kind != "function":
            return f"{self.type} {self.name}"
        ps = ", ".join(("" if d == "in" else d + " ") + str(t) for _, t, d in self.params)
        return f"{self.type} {self.name}({ps})"


class Model:
    """What `check()` learned about a program. See the package docstring for the API."""

    def __init__(self, ast: Any, tab: str) -> None:
        self.ast = ast
        self.tab = tab
        self.functions: dict[str, list[Symbol]] = {}
        self.structs: dict[str, T.StructType] = {}
        self.globals: list[Symbol] = []
        self.entry: Symbol | None = None
        self.diagnostics: list[Diagnostic] = []
        self._types: dict[int, T.Type] = {}
        self._symbols: dict[int, Symbol] = {}
        self._calls: dict[int, Any] = {}
        self._swizzles: dict[int, tuple[int, ...]] = {}
        self._consts: dict[int, Any] = {}
        self._calls_from: dict[Symbol | None, list[tuple[Any, Any]]] = {}
        self._uniforms_from: dict[Symbol | None, set[str]] = {}
        # memo tables the analyses keep per program (semantics/analysis/dataflow.py), by name
        self.analysis_caches: dict[str, dict] = {}

    # -- per-node facts ------------------------------------------------------------------------
    def type_of(self, node: Any) -> T.Type:
        """The type of an expression node (ERROR where the expression did not check)."""
        try:
            return self._types[id(node)]
        except KeyError:
            raise KeyError(f"no type recorded for {type(node).__name__} at {node.loc}") from None

    def symbol_of(self, node: Any) -> Symbol | None:
        """The symbol an Identifier refers to, or the symbol a declaring node declares."""
        return self._symbols.get(id(node))

    def call_target(self, call: Any) -> CallTarget | None:
        """What a call calls: a user function's Symbol, a built-in's Overload, or a Constructor
        (None for a call that did not check). Tell them apart with isinstance."""
        return self._calls.get(id(call))

    def is_swizzle(self, node: Any) -> bool:
        return id(node) in self._swizzles

    def swizzle_indices(self, node: Any) -> tuple[int, ...]:
        return self._swizzles[id(node)]

    def const_value(self, node: Any) -> Any:
        """The folded value of a constant expression (int/float/bool, tuples for vectors,
        tuples of columns for matrices, tuples for arrays and structs), else None."""
        v = self._consts.get(id(node))
        return None if v is UNKNOWN else v

    def is_constant(self, node: Any) -> bool:
        """True when the node is a constant expression (even if its value was not folded)."""
        return id(node) in self._consts

    # -- the tree's nodes, listed once ---------------------------------------------------------
    def nodes(self) -> list[Any]:
        """Every node of the program in `walk()` order (the unit first), listed at the first
        call. The checker, its hazard warnings and the lint rules each read the whole program or
        its function bodies, and a walk costs several times what reading a list does. The tree
        is not changed once parsed: callers must not change the list."""
        nodes = self.__dict__.get("_nodes")
        if nodes is None:
            nodes = self._nodes = list(self.ast.walk())
        return nodes

    def body_nodes(self, definition: Any) -> list[Any]:
        """`definition.body` (a function definition's) and every node in it, in `walk()` order:
        the slice of `nodes()` it spans (a list of its own for a definition not in the program's
        top level). Callers must not change the list."""
        bodies = self.__dict__.get("_bodies")
        if bodies is None:
            bodies = self._bodies = self._body_spans()
        got = bodies.get(id(definition))
        if got is None:
            return list(definition.body.walk())
        if type(got) is tuple:  # sliced when first asked for
            got = bodies[id(definition)] = self.nodes()[got[0] : got[1]]
        return got

    def _body_spans(self) -> dict[int, Any]:
        """id(top-level function definition with a body) -> (start, end) of its body in `nodes()`:
        in walk order a declaration is its own node and its subtree, up to the next declaration;
        a definition's body follows its prototype's subtree."""
        nodes = self.nodes()
        tops: list[tuple[int, Any]] = []
        at = 0
        for d in self.ast.decls:
            if d is not None:
                at = nodes.index(d, at)  # (identity: nodes have no __eq__)
                tops.append((at, d))
                at += 1
        spans: dict[int, Any] = {}
        for k, (start, d) in enumerate(tops):
            body = d.body if isinstance(d, A.FunctionDefinition) else None
            if body is not None:
                end = tops[k + 1][0] if k + 1 < len(tops) else len(nodes)
                spans[id(d)] = (nodes.index(body, start, end), end)
        return spans

    # -- whole-program facts -------------------------------------------------------------------
    def calls_from(self, func: Symbol | None) -> list[tuple[Any, Any]]:
        """(Call node, target) of every call in `func`'s body (None: global initializers)."""
        return list(self._calls_from.get(func, ()))

    def reachable_functions(self) -> list[Symbol]:
        """User functions reachable from the entry point, callees before callers."""
        if self.entry is None:
            return []
        order: list[Symbol] = []
        seen: set[int] = set()
        stack: list[tuple[Symbol, int]] = [(self.entry, 0)]
        seen.add(id(self.entry))
        while stack:
            fn, i = stack.pop()
            callees = [t for _, t in self._calls_from.get(fn, ()) if isinstance(t, Symbol)]
            if i < len(callees):
                stack.append((fn, i + 1))
                nxt = callees[i]
                if id(nxt) not in seen:
                    seen.add(id(nxt))
                    stack.append((nxt, 0))
            else:
                order.append(fn)
        return order

    def uniforms_read(self) -> set[str]:
        """Shadertoy uniforms referenced by reachable functions and global initializers."""
        out = set(self._uniforms_from.get(None, ()))
        for fn in self.reachable_functions():
            out |= self._uniforms_from.get(fn, set())
        return out

    @property
    def errors(self) -> list[Diagnostic]:
        return [d for d in self.diagnostics if d.severity == "error"]


#: What `Model.call_target` returns for a call that checked.
CallTarget = Symbol | Overload | Constructor
