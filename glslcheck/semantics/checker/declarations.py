"""Declarations and types: the part of the semantic pass that declares names and resolves types.

Owns global declarations (variables, interface blocks, default precisions, `invariant` and
default layouts), qualifier rules (at most one storage and one precision qualifier, a precision
for every float and sampler), struct types, array sizes (constant, positive, one dimension),
initializers (exact types, constant where the spec requires) and the redefinition rule of
`declare` (one name per scope, `gl_` reserved, WebGL's name limits).
"""

from __future__ import annotations

from ...frontend import syntax as A
from ...language import glsl_types as T
from .. import webgl_rules
from ..model import ERROR, Symbol
from .hints import NameAt, conversion_help, int_literal_hint
from .state import CheckerState

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterable
    from typing import Any


class DeclarationChecks(CheckerState):
    """Declarations of a program and of its functions' bodies, for `Checker`."""

    # -- the program's declarations ------------------------------------------------------------
    def external(self, decl: A.Node) -> None:
        if isinstance(decl, A.FunctionDefinition):
            self.function(decl.proto, decl)
        elif isinstance(decl, A.FunctionDeclaration):
            self.function(decl.proto, None)
        elif isinstance(decl, A.VariableDeclaration):
            self.variable_declaration(decl, is_global=True)
        elif isinstance(decl, A.PrecisionDeclaration):
            self.precision_declaration(decl)
        elif isinstance(decl, A.BlockDeclaration):
            self.block_declaration(decl)
        elif isinstance(decl, A.InvariantDeclaration):
            # `invariant name;` / `qualifier name;` re-qualifies variables declared before.
            for name in decl.names:
                sym = self.scope.lookup(name)
                if sym is None or sym.kind in ("function", "struct"):
                    self.error(
                        f"'{name}' is not a declared variable",
                        decl,
                        help="a qualifier followed by a name re-qualifies an existing variable; "
                        "to declare one, give its type",
                    )
        elif isinstance(decl, A.QualifierDeclaration):  # `layout(std140) uniform;`
            q = decl.qualifiers
            if q is not None and q.storage not in ("uniform", "in", "out"):
                self.error(
                    "a default layout needs 'uniform', 'in' or 'out' after it",
                    decl,
                    help="write e.g. 'layout(std140) uniform;'",
                )

    def block_declaration(self, decl: A.BlockDeclaration) -> None:
        """`uniform Block { members } instance[N];` (spec 4.3.7): a struct-like type whose members
        are globals when there is no instance name."""
        storage = decl.qualifiers.storage if decl.qualifiers is not None else None
        if storage != "uniform":
            self.error(
                f"a fragment shader's interface block must be 'uniform', not '{storage}'", decl
            )
        if decl.qualifiers is not None:
            layout_ids = [i.name for lay in decl.qualifiers.layouts for i in lay.ids]
            self.webgl(webgl_rules.block_layout_problem(layout_ids), decl.qualifiers)
        fields: list[tuple[str, T.Type]] = []
        for member in decl.members:
            if member.type is not None and member.type.struct_ is not None:
                self.error("a block cannot define a struct inside it", member.type)
                continue
            mt = self.resolve_type(member.type)
            for d in member.declarators:
                ft = self.with_array(mt, d.array, d)
                fields.append((d.name, ft))
        block_t = T.StructType(decl.block_name, tuple(fields))
        self.model.structs[self.unique.make(decl.block_name)] = block_t
        if decl.instance is None:
            for name, ft in fields:
                sym = Symbol(name, "global", ft, node=decl, qualifier="uniform")
                self.declare(sym, decl, decl)
                self.model.globals.append(sym)
            return
        t: T.Type = block_t
        if decl.array is not None:
            t = self.with_array(block_t, decl.array, decl)
        sym = Symbol(decl.instance, "global", t, node=decl, qualifier="uniform")
        self.declare(sym, decl, decl)
        self.model.globals.append(sym)

    def precision_declaration(self, decl: A.PrecisionDeclaration) -> None:
        t = self.resolve_type(decl.type)
        if t is not ERROR and not (t in (T.FLOAT, T.INT) or t.is_opaque):
            self.error(
                f"a default precision can be set only for float, int and sampler types, not '{t}'",
                decl,
            )
        elif t is not ERROR:
            self.default_precision[str(t)] = decl.precision

    def require_precision(self, t: T.Type, words: Iterable[str], node: Any) -> None:
        """A float or sampler declaration needs a precision: its own or a default (spec 4.5.4)."""
        while isinstance(t, T.ArrayType):
            t = t.element
        if t.base == "float":
            key = "float"
        elif t.is_opaque:
            key = str(t)
        else:
            return
        if key in self.default_precision or any(w in A.PRECISION_QUALIFIERS for w in words):
            return
        self.error(
            f"no precision is given for '{key}' and this shader sets no default for it",
            node,
            help=f"add 'precision highp {key};' after the #version line",
        )

    def qualifier_words(self, words: list[str], node: Any) -> None:
        """At most one storage and one precision qualifier (spec 4.3, 4.5.2)."""
        storage = [
            w
            for w in words
            if w in ("const", "uniform", "in", "out", "inout", "centroid in", "centroid out")
        ]
        precision = [w for w in words if w in A.PRECISION_QUALIFIERS]
        if len(storage) > 1:
            self.error(
                f"too many storage qualifiers: {' '.join(storage)}", node, help="keep one of them"
            )
        if len(precision) > 1:
            self.error(
                f"too many precision qualifiers: {' '.join(precision)}",
                node,
                help="keep one of them",
            )
        interpolation = [w for w in words if w in ("flat", "smooth")]
        if len(interpolation) > 1:
            self.error(
                f"too many interpolation qualifiers: {' '.join(interpolation)}",
                node,
                help="keep one of them",
            )
        repeated = sorted({w for w in words if words.count(w) > 1 and w != "layout"})
        if repeated and len(storage) <= 1 and len(precision) <= 1 and len(interpolation) <= 1:
            self.error(f"the qualifier '{repeated[0]}' is repeated", node, help="write it once")

    # -- names ---------------------------------------------------------------------------------
    def check_name(self, name: str, node: Any) -> bool:
        if name.startswith("gl_"):
            self.error(
                f"'{name}': names starting with 'gl_' are reserved for OpenGL",
                node,
                help=f"rename it, for example to '{name[3:] or 'value'}'",
            )
            return False
        self.webgl(webgl_rules.name_problem(name), node)
        return True

    def declare(self, sym: Symbol, node: Any, where: Any) -> None:
        """Add `sym` to the current scope, reporting a redefinition in the same scope."""
        if not self.check_name(sym.name, where):
            pass
        old = self.scope.local(sym.name)
        if old is not None:
            what = {
                "uniform": "a Shadertoy uniform",
                "function": "a function",
                "struct": "a struct",
                "param": "a parameter",
            }.get(old.kind, "a variable")
            msg = (
                f"'{sym.name}' is already declared by Shadertoy as a uniform"
                if old.kind == "uniform"
                else f"'{sym.name}' is already declared in this scope (as {what})"
            )
            self.error(
                msg,
                where,
                help="rename one of them"
                if old.kind != "uniform"
                else "Shadertoy declares this uniform already; remove your declaration or rename "
                "it",
            )
        else:
            self.scope.names[sym.name] = sym
        sym.unique_name = self.unique.make(sym.name)
        sym.function = self.func
        self.symbols[id(node)] = sym

    # -- types ---------------------------------------------------------------------------------
    def resolve_type(self, spec: A.TypeSpec | None, allow_array: bool = True) -> T.Type:
        if spec is None:
            return ERROR
        if spec.struct_ is not None:
            t: T.Type = self.struct(spec.struct_)
        elif spec.name in T.BY_NAME:
            t = T.BY_NAME[spec.name]
        else:
            sym = self.scope.lookup(spec.name or "")
            if sym is None or sym.kind != "struct":
                self.error(
                    f"'{spec.name}' is not a type",
                    spec,
                    help=self.did_you_mean(spec.name or "", structs=True),
                )
                return ERROR
            t = sym.type
            self.symbols[id(spec)] = sym
        if spec.array is not None:
            size = self.array_size(spec.array)
            if t is ERROR or size is ERROR:
                return ERROR
            return T.ArrayType(t, size)
        return t

    def with_array(self, t: T.Type, array: A.ArraySpec | None, where: Any) -> T.Type:
        if array is None or t is ERROR:
            return t
        if t.is_array:
            self.error(
                "arrays of arrays are not available in GLSL ES 3.00",
                array,
                help="use a longer one-dimensional array and compute the index",
            )
            return ERROR
        size = self.array_size(array)
        if size is ERROR:
            return ERROR
        return T.ArrayType(t, size)

    def array_size(self, spec: A.ArraySpec) -> Any:
        """The constant size of `[size]` (None for `[]`), or ERROR after reporting."""
        if spec.size is None:
            return None
        t = self.expr(spec.size)
        if t is ERROR:
            return ERROR
        if t not in (T.INT, T.UINT) or not self.is_const(spec.size):
            self.error(
                "an array size must be a constant integer expression",
                spec.size,
                help="use an int literal or a 'const int' declared before",
            )
            return ERROR
        v = self.model.const_value(spec.size)
        if v is None:
            return ERROR
        if v <= 0:
            self.error(f"an array size must be greater than zero, not {v}", spec.size)
            return ERROR
        return v

    def struct(self, spec: A.StructSpec) -> T.Type:
        fields: list[tuple[str, T.Type]] = []
        seen: set[str] = set()
        ok = True
        for member in spec.members:
            if member.type is not None and member.type.struct_ is not None:
                self.error(
                    "a struct cannot define another struct inside it (GLSL ES 3.00)",
                    member.type,
                    help=f"declare 'struct {member.type.struct_.name or 'Inner'}' before this "
                    "struct and use its name",
                )
                ok = False
                continue
            if member.qualifiers is not None and member.qualifiers.storage is not None:
                self.error(
                    f"struct members cannot be '{member.qualifiers.storage}'", member.qualifiers
                )
            mt = self.resolve_type(member.type)
            if mt is ERROR:
                ok = False
                continue
            self.require_precision(
                mt, member.qualifiers.words if member.qualifiers else (), member.type
            )
            for d in member.declarators:
                ft = self.with_array(mt, d.array, d)
                if ft is ERROR:
                    ok = False
                    continue
                if ft.is_void:
                    self.error(f"struct member '{d.name}' cannot be 'void'", d)
                    ok = False
                if isinstance(ft, T.ArrayType) and ft.array_size is None:
                    self.error(f"struct member '{d.name}' needs an array size", d)
                    ok = False
                if d.name in seen:
                    self.error(f"struct member '{d.name}' is declared twice", d)
                    ok = False
                self.check_name(d.name, d)
                seen.add(d.name)
                fields.append((d.name, ft))
        if not fields and ok:
            self.error("a struct needs at least one member", spec)
        name = spec.name
        if name is None:
            self.anon_structs += 1
            name = f"anonymous_struct_{self.anon_structs}"
        st = T.StructType(name, tuple(fields))
        if spec.name is not None:
            sym = Symbol(spec.name, "struct", st, node=spec)
            self.declare(sym, spec, spec)
            self.model.structs[sym.unique_name] = st
        else:
            self.model.structs[self.unique.make(name)] = st
        return st

    # -- variables -----------------------------------------------------------------------------
    def variable_declaration(self, decl: A.VariableDeclaration, is_global: bool) -> None:
        storage = decl.qualifiers.storage if decl.qualifiers is not None else None
        if decl.qualifiers is not None:
            self.qualifier_words(decl.qualifiers.words, decl.qualifiers)
            packing = {"std140", "shared", "packed", "row_major", "column_major"}
            if storage != "uniform" and any(
                i.name in packing for lay in decl.qualifiers.layouts for i in lay.ids
            ):
                self.error(
                    "packing and matrix layout qualifiers apply only to uniforms", decl.qualifiers
                )
        base = self.resolve_type(decl.type)
        if not decl.declarators:
            return  # `struct S {...};` or `float;`
        if storage in ("uniform", "in", "out", "centroid in", "centroid out") and not is_global:
            self.error(
                f"a local variable cannot be '{storage}'",
                decl.qualifiers,
                help="only global variables take 'uniform', 'in' or 'out'",
            )
        if base is not ERROR:
            self.require_precision(
                base, decl.qualifiers.words if decl.qualifiers else (), decl.type
            )
        for d in decl.declarators:
            self.declarator(d, base, storage, is_global, decl)

    def declarator(
        self,
        d: A.Declarator,
        base: T.Type,
        storage: str | None,
        is_global: bool,
        decl: A.VariableDeclaration,
    ) -> None:
        t = self.with_array(base, d.array, d)
        if base is not ERROR and base.is_array and d.array is not None:
            t = ERROR
        init_t = self.expr(d.init) if d.init is not None else None
        if t is not ERROR:
            if t.is_void:
                self.error(f"'{d.name}' cannot be declared 'void': void is only a return type", d)
                t = ERROR
            elif t.contains_opaque and storage != "uniform":
                self.error(
                    f"'{d.name}': sampler types can only be uniforms or function parameters",
                    d,
                    help="pass the sampler (iChannel0 ...) to the function as a parameter",
                )
                t = ERROR
        if t is not ERROR and isinstance(t, T.ArrayType) and t.array_size is None:
            if init_t is None:
                self.error(
                    f"the array '{d.name}' needs a size or an initializer",
                    d,
                    help=f"write '{d.name}[N]' or initialise it with '{t.element}[](...)'",
                )
                t = ERROR
            elif (
                init_t is not ERROR
                and isinstance(init_t, T.ArrayType)
                and init_t.element == t.element
            ):
                t = init_t
        sym = Symbol(d.name, "global" if is_global else "local", t, node=d, qualifier=storage)
        if d.init is not None:
            self.initializer(d, t, init_t, storage, is_global)
            if storage == "const" and self.is_const(d.init) and init_t == t:
                sym.const_value = self.model.const_value(d.init)
        elif storage == "const":
            self.error(
                f"the const '{d.name}' needs an initial value",
                d,
                help=f"write 'const {t} {d.name} = ...;'",
            )
        self.declare(sym, d, NameAt(d))
        if is_global:
            self.model.globals.append(sym)

    def initializer(
        self, d: Any, t: T.Type, init_t: T.Type | None, storage: str | None, is_global: bool
    ) -> None:
        if storage in ("uniform", "in", "out", "centroid in", "centroid out"):
            self.error(
                f"a '{storage}' variable cannot have an initializer",
                d.init,
                help="uniforms are set by Shadertoy; remove the '= ...'",
            )
            return
        if t is ERROR or init_t is ERROR or init_t is None:
            return
        if init_t != t:
            hint = int_literal_hint(d.init) if t.base == "float" else None
            msg = f"cannot initialise '{d.name}' of type '{t}' with a value of type '{init_t}'"
            if hint:
                msg += f"; GLSL ES has no implicit conversion: {hint}"
            elif t.is_basic and init_t.is_basic and t.base != init_t.base:
                msg += "; GLSL ES has no implicit conversion"
            self.error(msg, d.init, help=hint or conversion_help(t, init_t))
            return
        if storage == "const" and not self.is_const(d.init):
            self.error(
                f"the initializer of the const '{d.name}' is not a constant expression",
                d.init,
                help="use literals, other consts and built-in functions only, or drop 'const'",
            )
        elif is_global and not self.is_const(d.init):
            self.error(
                "a global variable's initializer must be a constant expression in GLSL ES 3.00",
                d.init,
                help="declare the global without a value and assign it in mainImage, "
                "or pass the value as a parameter",
            )
