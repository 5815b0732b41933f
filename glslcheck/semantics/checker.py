"""The semantic pass: scopes, symbols and a type for every expression (GLSL ES 3.00 + Shadertoy).

Owns the rules a compiler enforces after parsing (spec chapters 4-6 and 8): declarations and
redefinitions, struct types, function overloads and prototype/definition matching, exact-match
typing of every expression (no implicit conversions), l-values, constant expressions, control
flow placement (`break`, `continue`, `switch`), array sizes and constant indexes, the Shadertoy
entry point and the uniforms each tab sees. The typing rules themselves live in `language/glsl_types.py` and
the built-in table in `language/builtin_functions.py`; this module applies them to the tree and records the
results on a `Model`. Errors are collected, never raised here; `check()` decides. Statements
go to `stmt_<Node>` methods and expressions to `expr_<Node>` ones (`ast.NodeVisitor.dispatch`).

Where GLSL leaves a choice, the behaviour follows glslangValidator on the program Shadertoy
builds (see tests/check/test_glslang_agreement.py for the cases where it deliberately does not).
"""

from __future__ import annotations

from ..frontend import syntax as A
from ..language import builtin_functions as B
from ..language import glsl_types as T
from ..base.diagnostics import Diagnostic, Location
from . import consteval as C
from . import webgl_rules
from ..frontend.preprocess import WRAPPER_COLOR
from .model import ERROR, Constructor, Model, Symbol
from .scopes import Scope, UniqueNames

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up (issue 18)
if TYPE_CHECKING:
    from typing import Any, Iterable

# What the Shadertoy wrapper declares besides the uniforms (shadertoy/wrapper.py's footer and prelude).
WRAPPER_OUTPUT = "shadertoy_out_color"


def _int_hint(node: A.Node) -> str | None:
    """'write 1.0' for an int literal (possibly negated) where a float is needed."""
    if isinstance(node, A.IntLiteral) and not node.unsigned:
        return f"write {node.value}.0"
    if isinstance(node, A.Unary) and node.op == "-" and isinstance(node.operand, A.IntLiteral):
        return f"write -{node.operand.value}.0"
    return None


def _float_hint(node: A.Node) -> str | None:
    if isinstance(node, A.FloatLiteral):
        v = node.value
        if v == int(v):
            return f"write {int(v)}"
    return None


# Uniforms Shadertoy renamed (iGlobalTime became iTime in 2017); old shaders still use them.
_RENAMED_UNIFORMS = {"iGlobalTime": "iTime"}


class _NameAt:
    """Where an error about a declaration or a call points: its name (`name_loc`, a call's
    `callee_loc`), else the whole node. Found only when an error is reported: reading the name's
    location computes it (base/diagnostics.py's pending locations), and most nodes have no error
    (issue 18)."""

    __slots__ = ("node", "field")

    def __init__(self, node: Any, field: str = "name_loc") -> None:
        self.node = node
        self.field = field

    @property
    def loc(self) -> Location:
        name_loc = getattr(self.node, self.field)
        return name_loc if name_loc.line else self.node.loc


class Checker(A.NodeVisitor):
    def __init__(self, parse_result: Any, tab: str, channel_types: dict[str, T.Type] | None = None) -> None:
        self.pr = parse_result
        self.channel_types = channel_types or {}  # iChannelN -> its sampler type (channel_types.py)
        self.ast: A.TranslationUnit = parse_result.ast
        sources = list(getattr(parse_result, "sources", []) or [])
        self.plain = any(getattr(s, "is_plain_glsl", False) for s in sources) or tab == "GLSL"
        self.tab = "GLSL" if self.plain else tab
        self.common_paths = {s.path for s in sources if getattr(s, "tab", None) == "Common"}
        tab_src = [s for s in sources if getattr(s, "tab", None) == self.tab] or sources[-1:]
        self.tab_path = tab_src[0].path if tab_src else (self.ast.loc.path if self.ast.loc else "<string>")
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
        self.default_precision: dict[str, str] = {"int": "mediump", "sampler2D": "lowp", "samplerCube": "lowp"}
        if not self.plain:
            self.default_precision.update({"float": "highp", "int": "highp", "sampler3D": "mediump"})
        self.builtin_scope = Scope(None, "builtin")
        self.scope = Scope(self.builtin_scope, "global")
        self.global_scope = self.scope
        self._declare_predefined()

    def _names_in_program(self) -> set[str]:
        """Every name written in the program (of a node with a `name`)."""
        names = {getattr(n, "name", None) for n in self.model.nodes()}
        return {n for n in names if isinstance(n, str)}

    # -- reporting -----------------------------------------------------------------------------
    def error(self, message: str, node: Any, help: str | None = None, severity: str = "error") -> None:
        loc = node if isinstance(node, Location) else getattr(node, "loc", None)
        self.model.diagnostics.append(Diagnostic(message, loc, severity=severity, rule="type", help=help))

    def warning(self, message: str, node: Any, help: str | None = None) -> None:
        self.error(message, node, help, severity="warning")

    # -- set-up --------------------------------------------------------------------------------
    def _declare_predefined(self) -> None:
        for name, var in B.BUILTIN_VARIABLES.items():
            sym = Symbol(name, "builtin-var", var.type, qualifier=var.storage, unique_name=name,
                         const_value=var.value)
            self.builtin_scope.names[name] = sym
        if self.plain:
            return
        # Shadertoy's uniforms and output are ordinary globals of the compiled program.
        allowed = B.COMMON_TAB_UNIFORMS if self.tab == "Common" else B.SHADERTOY_UNIFORMS.keys()
        for name, u in B.SHADERTOY_UNIFORMS.items():
            if name in allowed:
                self.scope.names[name] = Symbol(name, "uniform", self.channel_types.get(name, u.declared_type),
                                                qualifier="uniform", unique_name=name)
                self.unique.given.add(name)
        if self.tab != "Common":
            self.scope.names[WRAPPER_OUTPUT] = Symbol(WRAPPER_OUTPUT, "global", T.VEC4, qualifier="out",
                                                      unique_name=WRAPPER_OUTPUT)

    # -- the program ---------------------------------------------------------------------------
    def run(self) -> Model:
        for decl in self.ast.decls:
            self.external(decl)
        self._finish()
        return self.model

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
                    self.error(f"'{name}' is not a declared variable", decl,
                               help="a qualifier followed by a name re-qualifies an existing variable; "
                                    "to declare one, give its type")
        elif isinstance(decl, A.QualifierDeclaration):  # `layout(std140) uniform;`
            q = decl.qualifiers
            if q is not None and q.storage not in ("uniform", "in", "out"):
                self.error("a default layout needs 'uniform', 'in' or 'out' after it", decl,
                           help="write e.g. 'layout(std140) uniform;'")

    def block_declaration(self, decl: A.BlockDeclaration) -> None:
        """`uniform Block { members } instance[N];` (spec 4.3.7): a struct-like type whose members
        are globals when there is no instance name."""
        storage = decl.qualifiers.storage if decl.qualifiers is not None else None
        if storage != "uniform":
            self.error(f"a fragment shader's interface block must be 'uniform', not '{storage}'", decl)
        if decl.qualifiers is not None:
            layout_ids = [i.name for l in decl.qualifiers.layouts for i in l.ids]
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
            self.error(f"a default precision can be set only for float, int and sampler types, not '{t}'", decl)
        elif t is not ERROR:
            self.default_precision[str(t)] = decl.precision

    def require_precision(self, t: T.Type, words: Iterable[str], node: Any) -> None:
        """A float or sampler declaration needs a precision: its own or a default (spec 4.5.4)."""
        while t.is_array:
            t = t.element
        if t.base == "float":
            key = "float"
        elif t.is_opaque:
            key = str(t)
        else:
            return
        if key in self.default_precision or any(w in A.PRECISION_QUALIFIERS for w in words):
            return
        self.error(f"no precision is given for '{key}' and this shader sets no default for it", node,
                   help=f"add 'precision highp {key};' after the #version line")

    def qualifier_words(self, words: list[str], node: Any) -> None:
        """At most one storage and one precision qualifier (spec 4.3, 4.5.2)."""
        storage = [w for w in words if w in ("const", "uniform", "in", "out", "inout", "centroid in", "centroid out")]
        precision = [w for w in words if w in A.PRECISION_QUALIFIERS]
        if len(storage) > 1:
            self.error(f"too many storage qualifiers: {' '.join(storage)}", node, help="keep one of them")
        if len(precision) > 1:
            self.error(f"too many precision qualifiers: {' '.join(precision)}", node, help="keep one of them")
        interpolation = [w for w in words if w in ("flat", "smooth")]
        if len(interpolation) > 1:
            self.error(f"too many interpolation qualifiers: {' '.join(interpolation)}", node, help="keep one of them")
        repeated = sorted({w for w in words if words.count(w) > 1 and w != "layout"})
        if repeated and len(storage) <= 1 and len(precision) <= 1 and len(interpolation) <= 1:
            self.error(f"the qualifier '{repeated[0]}' is repeated", node, help="write it once")

    # -- names ---------------------------------------------------------------------------------
    def check_name(self, name: str, node: Any) -> bool:
        if name.startswith("gl_"):
            self.error(f"'{name}': names starting with 'gl_' are reserved for OpenGL", node,
                       help=f"rename it, for example to '{name[3:] or 'value'}'")
            return False
        self.webgl(webgl_rules.name_problem(name), node)
        return True

    def webgl(self, problem: tuple[str, str] | None, node: Any) -> None:
        """A WebGL rule (webgl_rules.py: what Shadertoy's browser rejects): an error in a Shadertoy
        tab, a warning in a plain GLSL ES file, which need not run in WebGL."""
        if problem:
            self.error(problem[0], node, help=problem[1], severity="warning" if self.plain else "error")

    def declare(self, sym: Symbol, node: Any, where: Any) -> None:
        """Add `sym` to the current scope, reporting a redefinition in the same scope."""
        if not self.check_name(sym.name, where):
            pass
        old = self.scope.local(sym.name)
        if old is not None:
            what = {"uniform": "a Shadertoy uniform", "function": "a function", "struct": "a struct",
                    "param": "a parameter"}.get(old.kind, "a variable")
            msg = (f"'{sym.name}' is already declared by Shadertoy as a uniform" if old.kind == "uniform"
                   else f"'{sym.name}' is already declared in this scope (as {what})")
            self.error(msg, where,
                       help="rename one of them" if old.kind != "uniform" else
                       "Shadertoy declares this uniform already; remove your declaration or rename it")
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
                self.error(f"'{spec.name}' is not a type", spec, help=self._did_you_mean(spec.name or "", structs=True))
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
            self.error("arrays of arrays are not available in GLSL ES 3.00", array,
                       help="use a longer one-dimensional array and compute the index")
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
            self.error("an array size must be a constant integer expression", spec.size,
                       help="use an int literal or a 'const int' declared before")
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
                self.error("a struct cannot define another struct inside it (GLSL ES 3.00)", member.type,
                           help=f"declare 'struct {member.type.struct_.name or 'Inner'}' before this struct and use its name")
                ok = False
                continue
            if member.qualifiers is not None and member.qualifiers.storage is not None:
                self.error(f"struct members cannot be '{member.qualifiers.storage}'", member.qualifiers)
            mt = self.resolve_type(member.type)
            if mt is ERROR:
                ok = False
                continue
            self.require_precision(mt, member.qualifiers.words if member.qualifiers else (), member.type)
            for d in member.declarators:
                ft = self.with_array(mt, d.array, d)
                if ft is ERROR:
                    ok = False
                    continue
                if ft.is_void:
                    self.error(f"struct member '{d.name}' cannot be 'void'", d)
                    ok = False
                if ft.is_array and ft.array_size is None:
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

    # -- declarations --------------------------------------------------------------------------
    def variable_declaration(self, decl: A.VariableDeclaration, is_global: bool) -> None:
        storage = decl.qualifiers.storage if decl.qualifiers is not None else None
        if decl.qualifiers is not None:
            self.qualifier_words(decl.qualifiers.words, decl.qualifiers)
            packing = {"std140", "shared", "packed", "row_major", "column_major"}
            if storage != "uniform" and any(i.name in packing for l in decl.qualifiers.layouts for i in l.ids):
                self.error("packing and matrix layout qualifiers apply only to uniforms", decl.qualifiers)
        base = self.resolve_type(decl.type)
        if not decl.declarators:
            return  # `struct S {...};` or `float;`
        if storage in ("uniform", "in", "out", "centroid in", "centroid out") and not is_global:
            self.error(f"a local variable cannot be '{storage}'", decl.qualifiers,
                       help="only global variables take 'uniform', 'in' or 'out'")
        if base is not ERROR:
            self.require_precision(base, decl.qualifiers.words if decl.qualifiers else (), decl.type)
        for d in decl.declarators:
            self.declarator(d, base, storage, is_global, decl)

    def declarator(self, d: A.Declarator, base: T.Type, storage: str | None, is_global: bool,
                   decl: A.VariableDeclaration) -> None:
        t = self.with_array(base, d.array, d)
        if base is not ERROR and base.is_array and d.array is not None:
            t = ERROR
        init_t = self.expr(d.init) if d.init is not None else None
        if t is not ERROR:
            if t.is_void:
                self.error(f"'{d.name}' cannot be declared 'void': void is only a return type", d)
                t = ERROR
            elif t.contains_opaque and storage != "uniform":
                self.error(f"'{d.name}': sampler types can only be uniforms or function parameters", d,
                           help="pass the sampler (iChannel0 ...) to the function as a parameter")
                t = ERROR
        if t is not ERROR and t.is_array and t.array_size is None:
            if init_t is None:
                self.error(f"the array '{d.name}' needs a size or an initializer", d,
                           help=f"write '{d.name}[N]' or initialise it with '{t.element}[](...)'")
                t = ERROR
            elif init_t is not ERROR and init_t.is_array and init_t.element == t.element:
                t = init_t
        sym = Symbol(d.name, "global" if is_global else "local", t, node=d, qualifier=storage)
        if d.init is not None:
            self.initializer(d, t, init_t, storage, is_global)
            if storage == "const" and self.is_const(d.init) and init_t == t:
                sym.const_value = self.model.const_value(d.init)
        elif storage == "const":
            self.error(f"the const '{d.name}' needs an initial value", d,
                       help=f"write 'const {t} {d.name} = ...;'")
        self.declare(sym, d, _NameAt(d))
        if is_global:
            self.model.globals.append(sym)

    def initializer(self, d: Any, t: T.Type, init_t: T.Type | None, storage: str | None, is_global: bool) -> None:
        if storage in ("uniform", "in", "out", "centroid in", "centroid out"):
            self.error(f"a '{storage}' variable cannot have an initializer", d.init,
                       help="uniforms are set by Shadertoy; remove the '= ...'")
            return
        if t is ERROR or init_t is ERROR or init_t is None:
            return
        if init_t != t:
            hint = _int_hint(d.init) if t.base == "float" else None
            msg = f"cannot initialise '{d.name}' of type '{t}' with a value of type '{init_t}'"
            if hint:
                msg += f"; GLSL ES has no implicit conversion: {hint}"
            elif t.is_basic and init_t.is_basic and t.base != init_t.base:
                msg += "; GLSL ES has no implicit conversion"
            self.error(msg, d.init, help=hint or self._conversion_help(t, init_t))
            return
        if storage == "const" and not self.is_const(d.init):
            self.error(f"the initializer of the const '{d.name}' is not a constant expression", d.init,
                       help="use literals, other consts and built-in functions only, or drop 'const'")
        elif is_global and not self.is_const(d.init):
            self.error("a global variable's initializer must be a constant expression in GLSL ES 3.00", d.init,
                       help="declare the global without a value and assign it in mainImage, or pass the value as a parameter")

    def _conversion_help(self, want: T.Type, got: T.Type) -> str | None:
        if want.is_basic and got.is_basic and want.size == got.size:
            return f"convert it: {want}(...)"
        return None

    # -- functions -----------------------------------------------------------------------------
    def function(self, proto: A.FunctionPrototype, definition: A.FunctionDefinition | None) -> None:
        ret = self.resolve_type(proto.return_type)
        if proto.qualifiers is not None:
            self.qualifier_words(proto.qualifiers.words, proto.qualifiers)
        if proto.qualifiers is not None and proto.qualifiers.storage is not None:
            self.error(f"a function's return type cannot be '{proto.qualifiers.storage}'", proto.qualifiers)
        if ret is not ERROR and not ret.is_void:
            self.require_precision(ret, proto.qualifiers.words if proto.qualifiers else (), proto.return_type)
        if ret is not ERROR and ret.contains_opaque:
            self.error("a function cannot return a sampler", proto.return_type)
        if ret is not ERROR and ret.is_array and ret.array_size is None:
            self.error("a function returning an array must give its size", proto.return_type)
        params: list[tuple[str, T.Type, str]] = []
        for p in proto.params:
            if p.type is not None and p.type.struct_ is not None:  # ANGLE and Mesa reject it, glslang does not
                self.error("a parameter's type cannot define a struct", p.type,
                           help=f"declare 'struct {p.type.struct_.name or 'S'} {{ ... }};' before the function "
                                "and use its name as the type")
            pt = self.resolve_type(p.type)
            pt = self.with_array(pt, p.array, p)
            storage = [q for q in p.qualifiers if q in ("const", "in", "out", "inout")]
            precision = [q for q in p.qualifiers if q in A.PRECISION_QUALIFIERS]
            if len(precision) > 1:
                self.error(f"too many precision qualifiers: {' '.join(precision)}", p, help="keep one of them")
            if "const" in storage and any(q in ("out", "inout") for q in storage):
                self.error(f"a parameter cannot be both 'const' and '{p.direction}'", p,
                           help="an 'out' parameter is written by the function; drop 'const'")
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
                self.error("a parameter of a function definition needs a name", p,
                           help="name it, e.g. 'out vec4 fragColor, in vec2 fragCoord' for mainImage")
            if pt is not ERROR and not pt.is_void:
                self.require_precision(pt, p.qualifiers, p.type or p)
            if pt is not ERROR and pt.is_array and pt.array_size is None:
                self.error("an array parameter needs a size", p)
                pt = ERROR
            if pt is not ERROR and pt.contains_opaque and p.direction != "in":
                self.error(f"a sampler parameter cannot be '{p.direction}'", p)
            params.append((p.name or "", pt, p.direction))
        name = proto.name
        where = _NameAt(proto)
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
            self.declare(psym, p, _NameAt(p))
        self.block_statements(definition.body.stmts if definition.body else [])
        if ret is not ERROR and not ret.is_void and self.func_returns == 0:
            self.error(f"the function '{name}' must return a '{ret}' but has no return statement",
                       where, help=f"end it with 'return <{ret} value>;'")
        self.func, self.scope, self.func_returns, self.loop_depth, self.switch_depth = saved

    def _declare_function(self, name: str, ret: T.Type, params: list[tuple[str, T.Type, str]],
                          proto: A.FunctionPrototype, definition: Any, where: Any) -> Symbol | None:
        model = self.model
        if B.is_builtin_function(name):
            self.error(f"'{name}' is a built-in function; GLSL ES does not allow redefining or overloading it",
                       where, help=f"rename your function, for example to 'my{name[:1].upper()}{name[1:]}'")
        elif not self.plain and name == "main":
            self.error("Shadertoy's wrapper defines main(), which calls mainImage(); do not define main",
                       where, help="put the code in 'void mainImage(out vec4 fragColor, in vec2 fragCoord)'")
        self.check_name(name, where)
        existing = self.global_scope.local(name)
        if existing is not None and existing.kind != "function":
            self.error(f"'{name}' is already declared as a {existing.kind if existing.kind != 'uniform' else 'Shadertoy uniform'}"
                       " and cannot also name a function", where, help="rename the function")
        overloads = model.functions.setdefault(name, [])
        key = tuple(t for _, t, _ in params)
        for old in overloads:
            if tuple(t for _, t, _ in old.params) != key:
                continue
            if old.type != ret and ERROR not in (old.type, ret):
                self.error(f"'{name}' is declared again with return type '{ret}' but was declared with '{old.type}'",
                           where, help="overloads must differ in their parameter types, not only the return type")
            for i, ((_, _, d_new), (_, _, d_old)) in enumerate(zip(params, old.params)):
                if d_new != d_old:
                    self.error(f"parameter {i + 1} of '{name}' is '{d_new}' here but '{d_old}' in an earlier declaration",
                               where, help="a prototype and its definition must use the same in/out/inout qualifiers")
                    break
            if definition is not None:
                if old.defined:
                    self.error(f"the function '{old.signature()}' is already defined", where,
                               help="remove one of the two definitions or rename one")
                    return None
                old.defined = True
                old.node = definition
                old.params = params
            self.symbols[id(proto)] = old
            return old
        sym = Symbol(name, "function", ret, node=definition or A.FunctionDeclaration(proto=proto, loc=proto.loc),
                     params=params, defined=definition is not None)
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

    # -- statements ----------------------------------------------------------------------------
    def block_statements(self, stmts: Iterable[A.Node]) -> None:
        for s in stmts:
            self.stmt(s)

    def push(self, kind: str) -> None:
        self.scope = Scope(self.scope, kind)

    def pop(self) -> None:
        assert self.scope.parent is not None
        self.scope = self.scope.parent

    def sub_statement(self, s: A.Node | None, new_scope: bool) -> None:
        """A loop body: a compound body shares the loop's scope (no new scope, spec 6.3)."""
        if s is None:
            return
        if isinstance(s, A.Compound) and not new_scope:
            self.block_statements(s.stmts)
        else:
            self.stmt(s)

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

    def stmt_Compound(self, s: A.Compound) -> None:
        self.push("block")
        self.block_statements(s.stmts)
        self.pop()

    def stmt_DeclarationStatement(self, s: A.DeclarationStatement) -> None:
        decl = s.decl
        if isinstance(decl, A.VariableDeclaration):
            self.variable_declaration(decl, is_global=False)
        elif isinstance(decl, A.FunctionDeclaration):
            self.error("functions cannot be declared inside a function in GLSL ES", decl,
                       help="move the prototype to global scope")
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
                self.error(f"cannot initialise '{cond.name}' of type '{t}' with a value of type '{init_t}'", cond.init)
            storage = cond.qualifiers.storage if cond.qualifiers else None
            sym = Symbol(cond.name, "local", t, node=cond, qualifier=storage)
            self.declare(sym, cond, _NameAt(cond))
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
            self.error(f"a switch needs an int or uint value, not '{t}'", s.expr,
                       help="switch on an int, or use if/else for other types")
            t = ERROR
        self.push("switch")
        self.switch_depth += 1
        seen: dict[Any, A.Node] = {}
        default_seen = False
        body = s.body
        if body and not isinstance(body[0], A.Case):
            self.error("a switch cannot have statements before its first 'case' or 'default' label", body[0],
                       help="move the statement before the switch, or add a 'case' label above it")
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
                    self.error(f"the case label is '{ct}' but the switch value is '{t}'", stmt.expr,
                               help="write the label with the same type (add or remove the 'u' suffix)")
                v = self.model.const_value(stmt.expr)
                if v is not None:
                    if v in seen:
                        self.error(f"'case {v}:' appears twice in this switch", stmt.expr)
                    seen[v] = stmt
            else:
                self.stmt(stmt)
        if body and isinstance(body[-1], A.Case):
            self.error("the last case label of a switch must be followed by a statement", body[-1],
                       help="add 'break;' after it")
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
                self.error(f"this function must return a '{ret}' value", s, help=f"write 'return <{ret} value>;'")
            return
        t = self.expr(s.value)
        if ret is ERROR or t is ERROR:
            return
        if ret.is_void:
            self.error(f"a void function cannot return a value (this returns '{t}')", s.value,
                       help="remove the value, or change the return type")
        elif t != ret:
            hint = _int_hint(s.value) if ret.base == "float" else None
            msg = f"the function returns '{ret}' but this value is '{t}'"
            if hint:
                msg += f": {hint}"
            self.error(msg, s.value, help=hint or self._conversion_help(ret, t))

    # -- expressions ---------------------------------------------------------------------------
    def is_const(self, node: Any) -> bool:
        return id(node) in self.consts

    def expr(self, node: A.Node) -> T.Type:
        t = self.dispatch("expr_", node)
        self.types[id(node)] = t
        return t

    def expr_IntLiteral(self, n: A.IntLiteral) -> T.Type:
        self.consts[id(n)] = n.value
        return T.UINT if n.unsigned else T.INT

    def expr_FloatLiteral(self, n: A.FloatLiteral) -> T.Type:
        self.consts[id(n)] = C.f32(n.value)
        return T.FLOAT

    def expr_BoolLiteral(self, n: A.BoolLiteral) -> T.Type:
        self.consts[id(n)] = n.value
        return T.BOOL

    def expr_Identifier(self, n: A.Identifier) -> T.Type:
        sym = self.scope.lookup(n.name)
        if sym is None:
            self._undeclared(n)
            return ERROR
        if sym.kind == "function":
            self.error(f"'{n.name}' is a function; call it with arguments: {n.name}(...)", n)
            return ERROR
        if sym.kind == "struct":
            self.error(f"'{n.name}' is a struct type, not a value", n,
                       help=f"construct one with {n.name}(...)")
            return ERROR
        self.symbols[id(n)] = sym
        if sym.kind == "uniform":
            if n.loc.path in self.common_paths and n.name not in B.COMMON_TAB_UNIFORMS \
                    and not self._in_macro_entry():
                self._common_uniform_error(n)
            self.model._uniforms_from.setdefault(self.func, set()).add(n.name)
        if sym.qualifier == "const" and sym.kind != "param":
            self.consts[id(n)] = sym.const_value if sym.const_value is not None else C.UNKNOWN
        return sym.type

    def _in_macro_entry(self) -> bool:
        """In the entry function modelled for a `#define mainImage(O, U)` (frontend/preprocess/driver.py): the
        macro expands in the pass's wrapper, where every uniform is declared, even when the
        macro is defined in Common (Common compiled alone never expands it)."""
        f = self.func
        return f is not None and f.name == "mainImage" and bool(f.params) and f.params[0][0] == WRAPPER_COLOR

    def _common_uniform_error(self, n: A.Identifier) -> None:
        self.error(f"'{n.name}' is not available in the Common tab: the Common tab is compiled by Shadertoy "
                   f"without {n.name}; pass it as a parameter from mainImage", n,
                   help=f"add a parameter to this function and pass {n.name} from mainImage")

    def _undeclared(self, n: A.Identifier) -> None:
        if n.name in B.SHADERTOY_UNIFORMS and not self.plain:
            # Only the Common tab compiled alone lacks Shadertoy's uniforms.
            self._common_uniform_error(n)
            return
        if B.is_builtin_function(n.name):
            self.error(f"'{n.name}' is a built-in function; call it with arguments: {n.name}(...)", n)
            return
        if n.name in _RENAMED_UNIFORMS and not self.plain:
            new = _RENAMED_UNIFORMS[n.name]
            self.error(f"'{n.name}' is Shadertoy's old name for '{new}', which Shadertoy no longer "
                       "declares", n, help=f"replace '{n.name}' with '{new}'")
            return
        self.error(f"'{n.name}' is not declared", n, help=self._did_you_mean(n.name))

    def _did_you_mean(self, name: str, functions: bool = False, structs: bool = False) -> str | None:
        if structs:
            known = [s for s in self.scope.visible_names() if (self.scope.lookup(s) or Symbol("", "", T.VOID)).kind == "struct"]
            known += [k for k in T.BY_NAME]
        elif functions:
            known = list(self.model.functions) + list(B.BUILTINS)
        else:
            known = [k for k in self.scope.visible_names() if not k.startswith("gl_Max")]
        import difflib  # only for an error's suggestion: not at every start-up (issue 18)

        match = difflib.get_close_matches(name, known, n=1, cutoff=0.6)
        if match:
            return f"did you mean '{match[0]}'?"
        return None

    def expr_Binary(self, n: A.Binary) -> T.Type:
        lt = self.expr(n.left)
        rt = self.expr(n.right)
        if lt is ERROR or rt is ERROR:
            return ERROR
        res = T.binary_result(n.op, lt, rt)
        if isinstance(res, str):
            hint = self._mix_hint(n.left, lt, n.right, rt)
            if hint and hint.startswith("write"):
                res = res.split(": GLSL ES has no implicit", 1)[0] + f": GLSL ES has no implicit conversion; {hint}"
            self.error(res, n, help=hint)
            return ERROR
        if self.is_const(n.left) and self.is_const(n.right):
            self.consts[id(n)] = C.binary(n.op, lt, rt, res, self.consts[id(n.left)], self.consts[id(n.right)])
        return res

    def _mix_hint(self, left: A.Node, lt: T.Type, right: A.Node, rt: T.Type) -> str | None:
        """'write 2.0' when an int literal meets a float (and the reverse)."""
        if lt.base == "float" and rt.base == "int":
            return _int_hint(right) or "convert the int: float(...)"
        if rt.base == "float" and lt.base == "int":
            return _int_hint(left) or "convert the int: float(...)"
        if lt.base == "int" and rt.base == "uint" or lt.base == "uint" and rt.base == "int":
            return "add a 'u' suffix to the literal, or convert with uint(...) / int(...)"
        return None

    def expr_Unary(self, n: A.Unary) -> T.Type:
        t, res = self._unary(n)
        if res is ERROR:
            return ERROR
        if n.op in ("++", "--"):
            self.require_lvalue(n.operand, f"'{n.op}'")
        elif self.is_const(n.operand):
            self.consts[id(n)] = C.unary(n.op, t, self.consts[id(n.operand)])
        return res

    def expr_Postfix(self, n: A.Postfix) -> T.Type:
        _, res = self._unary(n)
        if res is not ERROR:
            self.require_lvalue(n.operand, f"'{n.op}'")
        return res

    def _unary(self, n: A.Unary | A.Postfix) -> tuple[T.Type, T.Type]:
        """(the operand's type, the result's) of a prefix or postfix operator; the result is
        ERROR after an error (the operator's is reported here)."""
        t = self.expr(n.operand)
        if t is ERROR:
            return t, ERROR
        res = T.unary_result(n.op, t)
        if isinstance(res, str):
            self.error(res, n)
            return t, ERROR
        return t, res

    def expr_Assignment(self, n: A.Assignment) -> T.Type:
        tt = self.expr(n.target)
        vt = self.expr(n.value)
        if tt is ERROR or vt is ERROR:
            if tt is not ERROR:
                self.require_lvalue(n.target, "assignment")
            return ERROR
        res = T.assign_result(n.op, tt, vt)
        if isinstance(res, str):
            hint = None
            if tt.base == "float" and vt.base == "int":
                hint = _int_hint(n.value) or "convert the value: float(...)"
            self.error(res + (f"; {hint}" if hint and hint.startswith("write") else ""), n, help=hint)
            self.require_lvalue(n.target, "assignment")
            return ERROR
        self.require_lvalue(n.target, "assignment")
        return res

    def require_lvalue(self, node: A.Node, what: str) -> bool:
        why = self.lvalue_problem(node)
        if why is None:
            return True
        self.error(f"cannot modify this: {why}", node, help=None)
        return False

    def lvalue_problem(self, node: A.Node) -> str | None:
        if isinstance(node, A.Identifier):
            sym = self.symbols.get(id(node))
            if sym is None:
                return None  # already reported
            if sym.kind == "uniform" or sym.qualifier == "uniform":
                return f"'{node.name}' is a uniform (read-only)"
            if sym.qualifier == "const":
                return f"'{node.name}' is const" + (" (a const parameter)" if sym.kind == "param" else "")
            if sym.kind == "builtin-var" and sym.qualifier != "out":
                return f"'{node.name}' is a read-only built-in variable"
            if sym.kind == "global" and sym.qualifier in ("in", "centroid in"):
                return f"'{node.name}' is a shader input (read-only)"
            return None
        if isinstance(node, A.Field):
            if id(node) in self.model._swizzles:
                idx = self.model._swizzles[id(node)]
                if len(set(idx)) != len(idx):
                    return f"the swizzle '.{node.name}' repeats a component"
            return self.lvalue_problem(node.base)
        if isinstance(node, A.Index):
            return self.lvalue_problem(node.base)
        if isinstance(node, A.Call):
            return "a function call's result is not a variable"
        if isinstance(node, (A.IntLiteral, A.FloatLiteral, A.BoolLiteral)):
            return "a literal is not a variable"
        return "this expression is not a variable"

    def expr_Ternary(self, n: A.Ternary) -> T.Type:
        ct = self.expr(n.cond)
        a = self.expr(n.then)
        b = self.expr(n.else_)
        if ct is not ERROR and ct != T.BOOL:
            self.error(f"the condition of '?:' must be a bool, not '{ct}'", n.cond)
            return ERROR
        if a is ERROR or b is ERROR or ct is ERROR:
            return ERROR
        if a != b:
            hint = None
            if a.base == "float" and b.base == "int":
                hint = _int_hint(n.else_)
            elif b.base == "float" and a.base == "int":
                hint = _int_hint(n.then)
            self.error(f"the two branches of '?:' have different types, '{a}' and '{b}'", n,
                       help=hint or "convert one branch so both have the same type")
            return ERROR
        if a.is_void:
            self.error("the branches of '?:' cannot be void", n)
            return ERROR
        self.webgl(webgl_rules.ternary_problem(a), n)
        if self.is_const(n.cond) and self.is_const(n.then) and self.is_const(n.else_):
            c = self.consts[id(n.cond)]
            self.consts[id(n)] = C.UNKNOWN if c is C.UNKNOWN else self.consts[id(n.then if c else n.else_)]
        return a

    def expr_Sequence(self, n: A.Sequence) -> T.Type:
        t: T.Type = ERROR
        for e in n.exprs:
            t = self.expr(e)
        return t

    def expr_Index(self, n: A.Index) -> T.Type:
        bt = self.expr(n.base)
        it = self.expr(n.index)
        if bt is ERROR or it is ERROR:
            return ERROR
        res = T.index_result(bt)
        if isinstance(res, str):
            self.error(res, n.base)
            return ERROR
        if it not in (T.INT, T.UINT):
            hint = "convert it: int(...)" if it == T.FLOAT else None
            self.error(f"an index must be an int or uint, not '{it}'", n.index, help=hint)
            return ERROR
        if self.is_const(n.index):
            v = self.model.const_value(n.index)
            size = bt.array_size if bt.is_array else (bt.cols if bt.is_matrix else bt.size)
            what = "array" if bt.is_array else ("matrix" if bt.is_matrix else "vector")
            if v is not None and (v < 0 or (size is not None and v >= size)):
                self.error(f"index {v} is out of range for this {what} of {size} "
                           f"{'elements' if bt.is_array else ('columns' if bt.is_matrix else 'components')}"
                           f" (valid: 0 to {size - 1})" if size else f"index {v} is out of range", n.index)
                return ERROR
            if self.is_const(n.base):
                self.consts[id(n)] = C.index(self.consts[id(n.base)], v)
        return res

    def expr_Field(self, n: A.Field) -> T.Type:
        bt = self.expr(n.base)
        if bt is ERROR:
            return ERROR
        if bt.is_struct:
            ft = bt.field_type(n.name)
            if ft is None:
                import difflib

                names = [f for f, _ in bt.fields]
                match = difflib.get_close_matches(n.name, names, n=1)
                self.error(f"the struct '{bt}' has no member '{n.name}'", n.name_loc if n.name_loc.line else n,
                           help=(f"did you mean '{match[0]}'?" if match else f"its members are: {', '.join(names)}"))
                return ERROR
            if self.is_const(n.base):
                i = [f for f, _ in bt.fields].index(n.name)
                v = self.consts[id(n.base)]
                self.consts[id(n)] = C.index(v, i)
            return ft
        res = T.swizzle_result(bt, n.name)
        if isinstance(res, str):
            self.error(res, n.name_loc if n.name_loc.line else n)
            return ERROR
        letters = next(s for s in T.SWIZZLE_SETS if all(c in s for c in n.name))
        idx = tuple(letters.index(c) for c in n.name)
        self.model._swizzles[id(n)] = idx
        if self.is_const(n.base):
            self.consts[id(n)] = C.swizzle(self.consts[id(n.base)], idx)
        return res

    def expr_MethodCall(self, n: A.MethodCall) -> T.Type:
        bt = self.expr(n.base)
        if bt is ERROR:
            return ERROR
        if n.name != "length":
            self.error(f"'.{n.name}()' is not a method: GLSL ES 3.00 has only '.length()' of arrays", n)
            return ERROR
        if not bt.is_array:
            hint = "use length(v) for the Euclidean length of a vector" if bt.is_vector else None
            self.error(f"'.length()' applies to arrays only, not '{bt}'", n, help=hint)
            return ERROR
        if bt.array_size is not None:
            self.consts[id(n)] = bt.array_size
        return T.INT

    # -- calls ---------------------------------------------------------------------------------
    def expr_Call(self, n: A.Call) -> T.Type:
        if n.constructor:
            return self.constructor(n)
        name = n.callee
        sym = self.scope.lookup(name)
        if sym is not None and sym.kind == "struct":
            return self.constructor(n)
        arg_types = [self.expr(a) for a in n.args]
        where = _NameAt(n, "callee_loc")
        if sym is not None and sym.kind != "function":
            self.error(f"'{name}' is a variable, not a function", where,
                       help="a local variable with this name hides the function; rename the variable")
            return ERROR
        if ERROR in arg_types:
            return ERROR
        if sym is None:
            if B.is_builtin_function(name):
                return self.builtin_call(n, name, arg_types)
            self.error(f"'{name}' is not declared", where, help=self._did_you_mean(name, functions=True))
            return ERROR
        overloads = self.model.functions.get(name, [])
        shown = f"{name}({', '.join(map(str, arg_types))})"
        for fn in overloads:
            if [t for _, t, _ in fn.params] == arg_types:
                self.model._calls[id(n)] = fn
                self.model._calls_from.setdefault(self.func, []).append((n, fn))
                for arg, (_, _, direction) in zip(n.args, fn.params):
                    if direction in ("out", "inout"):
                        self._out_argument(arg, direction, name)
                return fn.type
        cands = "; ".join(fn.signature() for fn in overloads)
        hint = None
        if len(overloads) == 1 and len(overloads[0].params) == len(arg_types):
            for i, ((_, want, _), got, arg) in enumerate(zip(overloads[0].params, arg_types, n.args)):
                if want != got:
                    h = _int_hint(arg) if want.base == "float" else None
                    hint = f"argument {i + 1} is '{got}' but the parameter is '{want}'" + (f": {h}" if h else "")
                    break
        self.error(f"no function '{shown}' matches the arguments; candidates: {cands}", where, help=hint)
        return ERROR

    def _out_argument(self, arg: A.Node, direction: str, fname: str) -> None:
        why = self.lvalue_problem(arg)
        if why is not None:
            self.error(f"the argument for an '{direction}' parameter of '{fname}' must be a variable: {why}", arg,
                       help="pass a local variable and copy it afterwards")

    def builtin_call(self, n: A.Call, name: str, arg_types: list[T.Type]) -> T.Type:
        ov = B.resolve(name, arg_types)
        if isinstance(ov, str):
            hint = None
            if any(t.base == "int" for t in arg_types) and any(t.base == "float" for t in arg_types):
                for arg, t in zip(n.args, arg_types):
                    h = _int_hint(arg) if t.base == "int" else None
                    if h:
                        hint = h
                        break
                hint = hint or "GLSL ES has no implicit int-to-float conversion: convert with float(...)"
            self.error(ov, n.callee_loc if n.callee_loc.line else n, help=hint)
            return ERROR
        self.model._calls[id(n)] = ov
        self.model._calls_from.setdefault(self.func, []).append((n, ov))
        for i in ov.out_params:
            self._out_argument(n.args[i], "out", name)
        if name in B.CONSTANT_OFFSET_FUNCTIONS:
            offset = self._offset_index(ov)
            if offset is not None and not self.is_const(n.args[offset]):
                self.error(f"the offset argument of {name}() must be a constant expression", n.args[offset],
                           help="use literals or consts, e.g. ivec2(1, 0)")
        if ov.category != B.TEXTURE and ov.category != B.DERIVATIVE and all(self.is_const(a) for a in n.args):
            self.consts[id(n)] = C.builtin(name, ov.params, ov.returns, [self.consts[id(a)] for a in n.args])
        return ov.returns

    @staticmethod
    def _offset_index(ov: B.Overload) -> int | None:
        idx = [i for i, p in enumerate(ov.params) if p.is_vector and p.base == "int"]
        return idx[-1] if idx else None

    def constructor(self, n: A.Call) -> T.Type:
        arg_types = [self.expr(a) for a in n.args]
        where = _NameAt(n, "callee_loc")
        if n.struct_ is not None:
            target = self.struct(n.struct_)
        elif n.callee in T.BY_NAME:
            target = T.BY_NAME[n.callee]
        else:
            sym = self.scope.lookup(n.callee)
            if sym is None or sym.kind != "struct":
                self.error(f"'{n.callee}' is not a type", where)
                return ERROR
            target = sym.type
        if n.array is not None:
            if target.is_array:
                self.error("arrays of arrays are not available in GLSL ES 3.00", n.array)
                return ERROR
            size = self.array_size(n.array)
            if size is ERROR:
                return ERROR
            target = T.ArrayType(target, size)
        if ERROR in arg_types or target is ERROR:
            return ERROR
        res = T.constructor_result(target, arg_types)
        if isinstance(res, str):
            hint = None
            if target.is_struct or target.is_array:
                elem = target.element if target.is_array else None
                for arg, t, want in zip(n.args, arg_types, [elem] * len(arg_types) if elem else [f for _, f in target.fields]):
                    if want is not None and want.base == "float" and t.base == "int":
                        hint = _int_hint(arg)
                        break
            self.error(res, where, help=hint)
            return ERROR
        self.model._calls[id(n)] = Constructor(res)
        if all(self.is_const(a) for a in n.args):
            self.consts[id(n)] = C.construct(res, arg_types, [self.consts[id(a)] for a in n.args])
        return res

    # -- the whole program ---------------------------------------------------------------------
    def _finish(self) -> None:
        model = self.model
        entry_name = "main" if self.plain else ("mainImage" if self.tab != "Common" else None)
        if entry_name is not None:
            self._find_entry(entry_name)
        # Link-time rules, on what the entry point reaches: every called function has a body,
        # and there is no recursion (GLSL ES 3.00 6.1).
        reach = model.reachable_functions()
        reach_ids = {id(f) for f in reach}
        for fn in reach:
            for call, target in model._calls_from.get(fn, ()):
                if isinstance(target, Symbol) and not target.defined:
                    self.error(f"'{target.signature()}' is declared but has no definition (body)",
                               call.callee_loc if call.callee_loc.line else call,
                               help="write the function's body, or remove the call")
        self._recursion(reach, reach_ids)

    def _find_entry(self, name: str) -> None:
        model = self.model
        overloads = model.functions.get(name, [])
        start = Location(self.tab_path, 1, 1)
        if name == "main":
            for fn in overloads:
                if not fn.params:
                    model.entry = fn
            if model.entry is None:
                self.error("a GLSL fragment shader needs 'void main()'", start)
            return
        want = [T.VEC4, T.VEC2]
        for fn in overloads:
            if [t for _, t, _ in fn.params] == want:
                model.entry = fn
                where = fn.node.proto.name_loc if fn.node is not None and fn.node.proto.name_loc.line else start
                if fn.params[0][2] == "in":
                    self.warning("mainImage's first parameter should be 'out vec4 fragColor': as 'in' the color "
                                 "it computes is thrown away", where,
                                 help="declare it as 'void mainImage(out vec4 fragColor, in vec2 fragCoord)'")
                if fn.params[1][2] != "in":
                    self.warning("mainImage's second parameter should be 'in vec2 fragCoord'", where)
                if not fn.type.is_void and fn.type is not ERROR:
                    self.warning(f"mainImage should return void, not '{fn.type}'", where)
                return
        if not overloads:
            self.error(f"the {self.tab} tab has no 'mainImage' function", start,
                       help="Shadertoy calls 'void mainImage(out vec4 fragColor, in vec2 fragCoord)'; define it")
        else:
            got = "; ".join(fn.signature() for fn in overloads)
            self.error(f"'mainImage' has the wrong parameters ({got}); Shadertoy calls mainImage(vec4, vec2)",
                       start, help="declare it as 'void mainImage(out vec4 fragColor, in vec2 fragCoord)'")

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
                    cycle = path[[id(p) for p in path].index(id(target)):] + [target]
                    self.error("recursion is not allowed in GLSL ES: " + " -> ".join(f.name for f in cycle),
                               call.callee_loc if call.callee_loc.line else call,
                               help="rewrite it as a loop")
                elif s == 0:
                    visit(target, path)
            path.pop()
            state[id(fn)] = 2

        if model.entry is not None:
            visit(model.entry, [])
