"""Functions: prototypes and definitions, overloads, and the rules checked on the whole program.

Owns a function's return and parameter types and qualifiers, overload and redefinition rules
(a prototype and its definition must agree), the body's scope (parameters share it with the
body's top-level declarations, ES 3.00 6.1), and the link-time rules on what the entry point
reaches: every called function has a body, and there is no recursion.
"""

from __future__ import annotations

from ...frontend import syntax as A
from ...language import builtin_functions as B
from ...language import glsl_types as T
from ..model import ERROR, Symbol
from ..scopes import Scope
from .hints import NameAt
from .state import CheckerState

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from typing import Any


class FunctionChecks(CheckerState):
    """Function declarations and definitions, and the whole-program rules, for `Checker`."""

    # -- functions -----------------------------------------------------------------------------
    def function(self, proto: A.FunctionPrototype, definition: A.FunctionDefinition | None) -> None:
        ret = self.resolve_type(proto.return_type)
        if proto.qualifiers is not None:
            self.qualifier_words(proto.qualifiers.words, proto.qualifiers)
        if proto.qualifiers is not None and proto.qualifiers.storage is not None:
            self.error(
                f"a function's return type cannot be '{proto.qualifiers.storage}'", proto.qualifiers
            )
        if ret is not ERROR and not ret.is_void:
            self.require_precision(
                ret, proto.qualifiers.words if proto.qualifiers else (), proto.return_type
            )
        if ret is not ERROR and ret.contains_opaque:
            self.error("a function cannot return a sampler", proto.return_type)
        if ret is not ERROR and isinstance(ret, T.ArrayType) and ret.array_size is None:
            self.error("a function returning an array must give its size", proto.return_type)
        params: list[tuple[str, T.Type, str]] = []
        for p in proto.params:
            if (
                p.type is not None and p.type.struct_ is not None
            ):  # ANGLE and Mesa reject it, glslang does not
                self.error(
                    "a parameter's type cannot define a struct",
                    p.type,
                    help=f"declare 'struct {p.type.struct_.name or 'S'} {{ ... "
                    "};' before the function "
                    "and use its name as the type",
                )
            pt = self.resolve_type(p.type)
            pt = self.with_array(pt, p.array, p)
            storage = [q for q in p.qualifiers if q in ("const", "in", "out", "inout")]
            precision = [q for q in p.qualifiers if q in A.PRECISION_QUALIFIERS]
            if len(precision) > 1:
                self.error(
                    f"too many precision qualifiers: {' '.join(precision)}",
                    p,
                    help="keep one of them",
                )
            if "const" in storage and any(q in ("out", "inout") for q in storage):
                self.error(
                    f"a parameter cannot be both 'const' and '{p.direction}'",
                    p,
                    help="an 'out' parameter is written by the function; drop 'const'",
                )
            if len([q for q in storage if q in ("in", "out", "inout")]) > 1:
                self.error("a parameter takes one of 'in', 'out', 'inout'", p)
            if pt is not ERROR and pt.is_void:
                if len(proto.params) == 1 and p.name is None and p.array is None:
                    continue  # f(void)
                self.error("a parameter cannot be 'void'", p)
                pt = ERROR
            if definition is not None and p.name is None and pt is not ERROR and not pt.is_void:
                # The spec lets a prototype omit names; Mesa also rejects a nameless parameter of
                # a definition ("formal parameter lacks a name"), so check does as the driver.
                self.error(
                    "a parameter of a function definition needs a name",
                    p,
                    help="name it, e.g. 'out vec4 fragColor, in vec2 fragCoord' for mainImage",
                )
            if pt is not ERROR and not pt.is_void:
                self.require_precision(pt, p.qualifiers, p.type or p)
            if pt is not ERROR and isinstance(pt, T.ArrayType) and pt.array_size is None:
                self.error("an array parameter needs a size", p)
                pt = ERROR
            if pt is not ERROR and pt.contains_opaque and p.direction != "in":
                self.error(f"a sampler parameter cannot be '{p.direction}'", p)
            params.append((p.name or "", pt, p.direction))
        name = proto.name
        where = NameAt(proto)
        sym = self._declare_function(name, ret, params, proto, definition, where)
        if definition is None or sym is None:
            return
        # The body: parameters and the body's top-level declarations share one scope (ES 3.00 6.1).
        saved = (self.func, self.scope, self.func_returns, self.loop_depth, self.switch_depth)
        self.func = sym
        self.func_returns = 0
        self.loop_depth = self.switch_depth = 0
        self.model._calls_from.setdefault(sym, [])
        self.scope = Scope(self.global_scope, "function")
        for p, (pname, pt, direction) in zip(proto.params, params):
            if p.name is None:
                continue
            qual = "const" if "const" in p.qualifiers else direction
            psym = Symbol(p.name, "param", pt, node=p, qualifier=qual)
            self.declare(psym, p, NameAt(p))
        self.block_statements(definition.body.stmts if definition.body else [])
        if ret is not ERROR and not ret.is_void and self.func_returns == 0:
            self.error(
                f"the function '{name}' must return a '{ret}' but has no return statement",
                where,
                help=f"end it with 'return <{ret} value>;'",
            )
        self.func, self.scope, self.func_returns, self.loop_depth, self.switch_depth = saved

    def _declare_function(
        self,
        name: str,
        ret: T.Type,
        params: list[tuple[str, T.Type, str]],
        proto: A.FunctionPrototype,
        definition: Any,
        where: Any,
    ) -> Symbol | None:
        model = self.model
        if B.is_builtin_function(name):
            self.error(
                f"'{name}' is a built-in function; GLSL ES does not allow redefining or "
                "overloading it",
                where,
                help=f"rename your function, for example to 'my{name[:1].upper()}{name[1:]}'",
            )
        elif not self.plain and name == "main":
            self.error(
                "Shadertoy's wrapper defines main(), which calls mainImage(); do not define main",
                where,
                help="put the code in 'void mainImage(out vec4 fragColor, in vec2 fragCoord)'",
            )
        self.check_name(name, where)
        existing = self.global_scope.local(name)
        if existing is not None and existing.kind != "function":
            self.error(
                f"'{name}' is already declared as a "
                f"{existing.kind if existing.kind != 'uniform' else 'Shadertoy uniform'}"
                " and cannot also name a function",
                where,
                help="rename the function",
            )
        overloads = model.functions.setdefault(name, [])
        key = tuple(t for _, t, _ in params)
        for old in overloads:
            if tuple(t for _, t, _ in old.params) != key:
                continue
            if old.type != ret and ERROR not in (old.type, ret):
                self.error(
                    f"'{name}' is declared again with return type '{ret}' but was declared with "
                    f"'{old.type}'",
                    where,
                    help="overloads must differ in their parameter types, not only the return type",
                )
            for i, ((_, _, d_new), (_, _, d_old)) in enumerate(zip(params, old.params)):
                if d_new != d_old:
                    self.error(
                        f"parameter {i + 1} of '{name}' is '{d_new}' here but '{d_old}' in an "
                        "earlier declaration",
                        where,
                        help="a prototype and its definition must use the same in/out/inout "
                        "qualifiers",
                    )
                    break
            if definition is not None:
                if old.defined:
                    self.error(
                        f"the function '{old.signature()}' is already defined",
                        where,
                        help="remove one of the two definitions or rename one",
                    )
                    return None
                old.defined = True
                old.node = definition
                old.params = params
            self.symbols[id(proto)] = old
            return old
        sym = Symbol(
            name,
            "function",
            ret,
            node=definition or A.FunctionDeclaration(proto=proto, loc=proto.loc),
            params=params,
            defined=definition is not None,
        )
        if definition is None:
            sym.node = self._decl_node(proto)
        sym.unique_name = self.unique.make(name)
        overloads.append(sym)
        if existing is None:
            self.global_scope.names[name] = sym
        self.symbols[id(proto)] = sym
        return sym

    def _decl_node(self, proto: A.FunctionPrototype) -> Any:
        for decl in self.ast.decls:
            if isinstance(decl, A.FunctionDeclaration) and decl.proto is proto:
                return decl
        return A.FunctionDeclaration(proto=proto, loc=proto.loc)

    # -- the whole program ---------------------------------------------------------------------
    def check_whole_program(self) -> None:
        model = self.model
        entry_name = "main" if self.plain else ("mainImage" if self.tab != "Common" else None)
        if entry_name is not None:
            self.find_entry(entry_name)
        # Link-time rules, on what the entry point reaches: every called function has a body,
        # and there is no recursion (GLSL ES 3.00 6.1).
        reach = model.reachable_functions()
        reach_ids = {id(f) for f in reach}
        for fn in reach:
            for call, target in model._calls_from.get(fn, ()):
                if isinstance(target, Symbol) and not target.defined:
                    self.error(
                        f"'{target.signature()}' is declared but has no definition (body)",
                        call.callee_loc if call.callee_loc.line else call,
                        help="write the function's body, or remove the call",
                    )
        self._recursion(reach, reach_ids)

    def _recursion(self, reach: list[Symbol], reach_ids: set[int]) -> None:
        model = self.model
        state: dict[int, int] = {}
        reported: set[int] = set()

        def visit(fn: Symbol, path: list[Symbol]) -> None:
            state[id(fn)] = 1
            path.append(fn)
            for call, target in model._calls_from.get(fn, ()):
                if not isinstance(target, Symbol):
                    continue
                s = state.get(id(target), 0)
                if s == 1 and id(call) not in reported:
                    reported.add(id(call))
                    cycle = path[[id(p) for p in path].index(id(target)) :] + [target]
                    self.error(
                        "recursion is not allowed in GLSL ES: "
                        + " -> ".join(f.name for f in cycle),
                        call.callee_loc if call.callee_loc.line else call,
                        help="rewrite it as a loop",
                    )
                elif s == 0:
                    visit(target, path)
            path.pop()
            state[id(fn)] = 2

        if model.entry is not None:
            visit(model.entry, [])
