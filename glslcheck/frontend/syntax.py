"""The typed GLSL ES 3.00 syntax tree, and a visitor.

Every node class declares its fields once, as annotated class attributes with their defaults
(`LIST` for a fresh empty list); from that one declaration the node gets `__slots__`, an
`__init__` (the fields in order, then the keyword-only `loc`), its `__repr__`, `_fields`, and
`_children`: the fields whose declared type names a node class (a node, a list of nodes, or
None) are its children, in field order; every other field is a plain attribute. This is
pycparser's `_c_ast.cfg` idea without a generated file: the `__init__`s are copies of a few
compiled templates renamed to each class's fields, which costs a small fraction of what
`@dataclass` did at import (start-up time matters for the pre-commit hook).

Every node carries `loc`, the span of its text in the user's own file (after preprocessing
and the Shadertoy wrapper, a location still points into the tab file the user wrote).

`children()`, `walk()`, `NodeVisitor` and `dump()` are derived from `_children`, so a new node
class only has to declare its fields. `dump()` gives a location-free nested tuple: two trees
with equal dumps are the same program (used by the parse -> print -> parse round trip).
`NodeVisitor` dispatches on the node's class by method name (`visit_If`, or any prefix:
the printer's `_stmt_If`), falling back along the class's bases, and returns what the method
returns.
"""

from __future__ import annotations

from types import FunctionType

from ..base.diagnostics import Location
from ..base.records import dataclass_transform, init_code, tuple_getter

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Callable, Iterator
    from dataclasses import KW_ONLY
    from typing import Any, ClassVar

_NOLOC = Location("<builtin>", 0, 0)


class _Factory:
    """A default made fresh for each node (`LIST`: a new empty list)."""

    def __init__(self, make: Callable[[], Any], text: str) -> None:
        self.make = make
        self.text = text

    def __repr__(self) -> str:
        return self.text


# Typed as what it stands for in every field it defaults: a fresh list.
LIST: Any = _Factory(list, "LIST")
# The default of a child the grammar requires (an operator's operands, an `if`'s condition):
# the parser always sets it, so the field is typed as the node; None only in a node built by
# hand without it.
PARSED: Any = None

_NODE_CLASSES: dict[str, _NodeMeta] = {}


@dataclass_transform()
class _NodeMeta(type):
    """Turns a node class's annotated fields into `__slots__` and records their defaults; the
    methods are made for all classes at once by `_make_methods` at the end of the module."""

    # What the metaclass and `_make_methods` set on each node class (see `Node`).
    _fields: tuple[str, ...]
    _defaults: dict[str, Any]
    _children: tuple[str, ...]
    _children_reversed: Callable[[Node], tuple]
    _children_values: Callable[[Node], tuple]
    _shown: tuple[str, ...]

    def __new__(mcls, name, bases, ns):
        own = [f for f in ns.get("__annotations__", {}) if not f.startswith("_")]
        inherited = [f for b in bases for f in getattr(b, "_fields", ())]
        defaults = {f: ns.pop(f) for f in own if f in ns}
        missing = [f for f in own if f not in defaults]
        if missing:
            raise TypeError(f"{name}: fields {missing} need a default")
        ns["__slots__"] = tuple(own)
        cls = super().__new__(mcls, name, bases, ns)
        cls._fields = tuple(inherited + own)
        cls._defaults = {
            **{k: v for b in bases for k, v in getattr(b, "_defaults", {}).items()},
            **defaults,
        }
        _NODE_CLASSES[name] = cls
        return cls


class Node(metaclass=_NodeMeta):
    if TYPE_CHECKING:
        _: KW_ONLY  # `loc` is keyword-only in every node's __init__
    loc: Location = _NOLOC
    _children: ClassVar[tuple[str, ...]] = ()
    _fields: ClassVar[tuple[str, ...]] = ()
    _shown: ClassVar[tuple[str, ...]] = ()  # the fields __repr__ shows: all but locations

    @staticmethod
    def _children_reversed(node: Node) -> tuple:
        """The values of the child fields, last first (each class's own: `_make_methods`)."""
        return ()

    @staticmethod
    def _children_values(node: Node) -> tuple:
        """The values of the child fields, in order (each class's own: `_make_methods`)."""
        return ()

    def __repr__(self) -> str:
        fields = ", ".join(f"{name}={getattr(self, name)!r}" for name in self._shown)
        return f"{type(self).__name__}({fields})"

    def children(self) -> list[Node]:
        """The child nodes, in source order of the fields (a new list: a generator per call was
        most of the cost of the dataflow walk and the rules' recursions)."""
        out: list[Node] = []
        for value in self._children_values(self):
            if value is None:
                continue
            if type(value) is list:
                out.extend([item for item in value if item is not None] if None in value else value)
            else:
                out.append(value)
        return out

    def walk(self) -> Iterator[Node]:
        """This node and all its descendants, depth first, parents before children (iterative)."""
        # `children()` inlined: a generator per node was most of a walk's cost, and the checker,
        # hazards and rules walk whole programs on every `glslcheck lint`. The
        # child fields are read in one call, last first (`_children_reversed`), and pushed so
        # that the first child is popped first.
        stack = [self]
        pop = stack.pop
        push = stack.append
        extend = stack.extend
        while stack:
            node = pop()
            yield node
            for value in node._children_reversed(node):
                if value is None:
                    continue
                if type(value) is list:
                    if None in value:
                        value = [item for item in value if item is not None]
                    extend(reversed(value))
                else:
                    push(value)


# ---------------------------------------------------------------------------------------------
# Types and qualifiers
# ---------------------------------------------------------------------------------------------


class ArraySpec(Node):
    """`[size]` or `[]` (size None)."""

    size: Expr | None = None


class LayoutId(Node):
    name: str = ""
    value: int | None = None


class Layout(Node):
    """`layout(location = 0, std140)`."""

    ids: list[LayoutId] = LIST


PRECISION_QUALIFIERS = ("highp", "mediump", "lowp")  # GLSL ES 3.00 section 4.5.2


class Qualifiers(Node):
    """Storage, precision, interpolation, invariant and layout qualifiers in source order.
    `words` holds the keywords ("const", "uniform", "in", "centroid in", "highp", "flat", ...)."""

    words: list[str] = LIST
    layouts: list[Layout] = LIST

    @property
    def storage(self) -> str | None:
        for w in self.words:
            if w in ("const", "uniform", "in", "out", "inout", "centroid in", "centroid out"):
                return w
        return None

    @property
    def precision(self) -> str | None:
        for w in self.words:
            if w in PRECISION_QUALIFIERS:
                return w
        return None


class StructMember(Node):
    qualifiers: Qualifiers | None = None
    type: TypeSpec = PARSED
    declarators: list[StructDeclarator] = LIST


class StructDeclarator(Node):
    name: str = ""
    array: ArraySpec | None = None


class StructSpec(Node):
    """`struct Name { members }` (name None for an anonymous struct)."""

    name: str | None = None
    members: list[StructMember] = LIST


class TypeSpec(Node):
    """A type as written: a built-in type name, a struct name, or a struct definition;
    optionally with an array size (`float[3]`)."""

    name: str | None = None  # "vec3", "S"; None when `struct_` defines the type here
    struct_: StructSpec | None = None
    array: ArraySpec | None = None
    is_struct_name: bool = False  # `name` refers to a user struct

    @property
    def type_name(self) -> str:
        if self.name is not None:
            return self.name
        return self.struct_.name if self.struct_ and self.struct_.name else "<anonymous struct>"


# ---------------------------------------------------------------------------------------------
# Expressions
# ---------------------------------------------------------------------------------------------


class Expr(Node):
    pass


class Identifier(Expr):
    name: str = ""


class IntLiteral(Expr):
    value: int = 0
    unsigned: bool = False
    text: str = ""


class FloatLiteral(Expr):
    value: float = 0.0
    text: str = ""


class BoolLiteral(Expr):
    value: bool = False


class Binary(Expr):
    """`left op right` for every binary operator but assignment and the comma."""

    op: str = "+"
    left: Expr = PARSED
    right: Expr = PARSED


class Unary(Expr):
    """Prefix `+ - ! ~ ++ --` (op) applied to operand."""

    op: str = "-"
    operand: Expr = PARSED


class Postfix(Expr):
    """Postfix `++` / `--`."""

    op: str = "++"
    operand: Expr = PARSED


class Assignment(Expr):
    """`target op value` with op one of `= += -= *= /= %= <<= >>= &= ^= |=`."""

    op: str = "="
    target: Expr = PARSED
    value: Expr = PARSED


class Ternary(Expr):
    cond: Expr = PARSED
    then: Expr = PARSED
    else_: Expr = PARSED


class Sequence(Expr):
    """The comma operator: `a, b, c` evaluates all, yields the last."""

    exprs: list[Expr] = LIST


class Call(Expr):
    """A function call or a constructor: `f(x)`, `vec3(1.0)`, `S(a, b)`, `float[3](a, b, c)`.
    `callee` is the name as written; `constructor` is True when it names a type (a built-in
    type, a struct, or an array type with `array` set)."""

    callee: str = ""
    struct_: StructSpec | None = None  # `struct {...}[2](...)`, legal but rare
    array: ArraySpec | None = None
    args: list[Expr] = LIST
    constructor: bool = False
    callee_loc: Location = _NOLOC


class Index(Expr):
    base: Expr = PARSED
    index: Expr = PARSED


class Field(Expr):
    """`base.name`: a struct member or a vector swizzle (the checker tells which)."""

    base: Expr = PARSED
    name: str = ""
    name_loc: Location = _NOLOC


class MethodCall(Expr):
    """`base.name()`: GLSL ES 3.00 has one method, `.length()` of arrays."""

    base: Expr = PARSED
    name: str = ""


# ---------------------------------------------------------------------------------------------
# Declarations
# ---------------------------------------------------------------------------------------------


class Declarator(Node):
    """One name of a variable declaration: `name[array] = init`."""

    name: str = ""
    array: ArraySpec | None = None
    init: Expr | None = None
    name_loc: Location = _NOLOC


class VariableDeclaration(Node):
    """`qualifiers type a = 1.0, b[2];` (no declarators: `struct S {...};` or `float;`)."""

    qualifiers: Qualifiers | None = None
    type: TypeSpec = PARSED
    declarators: list[Declarator] = LIST


class Param(Node):
    qualifiers: list[str] = LIST  # "const", "in", "out", "inout", precision
    type: TypeSpec = PARSED
    name: str | None = None
    array: ArraySpec | None = None
    name_loc: Location = _NOLOC

    @property
    def direction(self) -> str:
        for q in self.qualifiers:
            if q in ("out", "inout"):
                return q
        return "in"


class FunctionPrototype(Node):
    qualifiers: Qualifiers | None = None
    return_type: TypeSpec = PARSED
    name: str = ""
    params: list[Param] = LIST
    name_loc: Location = _NOLOC


class FunctionDeclaration(Node):
    """A prototype alone: `float f(float x);`."""

    proto: FunctionPrototype = PARSED


class FunctionDefinition(Node):
    proto: FunctionPrototype = PARSED
    body: Compound = PARSED


class PrecisionDeclaration(Node):
    """`precision highp float;`."""

    precision: str = "highp"
    type: TypeSpec = PARSED


class BlockDeclaration(Node):
    """An interface block: `uniform Block { vec4 a; } name[2];`."""

    qualifiers: Qualifiers | None = None
    block_name: str = ""
    members: list[StructMember] = LIST
    instance: str | None = None
    array: ArraySpec | None = None


class InvariantDeclaration(Node):
    """`invariant a, b;` (redeclaring outputs as invariant)."""

    qualifiers: Qualifiers | None = None
    names: list[str] = LIST


class QualifierDeclaration(Node):
    """A qualifier alone: `layout(std140) uniform;`."""

    qualifiers: Qualifiers | None = None


# ---------------------------------------------------------------------------------------------
# Statements
# ---------------------------------------------------------------------------------------------


class Stmt(Node):
    pass


class Compound(Stmt):
    stmts: list[Node] = LIST


class DeclarationStatement(Stmt):
    decl: Node = PARSED


class ExpressionStatement(Stmt):
    """`expr;` or the empty statement `;` (expr None)."""

    expr: Expr | None = None


class If(Stmt):
    cond: Expr = PARSED
    then: Stmt = PARSED
    else_: Stmt | None = None


class Switch(Stmt):
    expr: Expr = PARSED
    body: list[Stmt] = LIST


class Case(Stmt):
    """`case expr:` (expr None for `default:`)."""

    expr: Expr | None = None


class ConditionDeclaration(Node):
    """The `bool b = f()` of `while (bool b = f())`."""

    qualifiers: Qualifiers | None = None
    type: TypeSpec = PARSED
    name: str = ""
    init: Expr = PARSED
    name_loc: Location = _NOLOC


class While(Stmt):
    cond: Node = PARSED  # Expr or ConditionDeclaration
    body: Stmt = PARSED


class DoWhile(Stmt):
    body: Stmt = PARSED
    cond: Expr = PARSED


class For(Stmt):
    init: Stmt | None = None  # DeclarationStatement or ExpressionStatement
    cond: Node | None = None  # Expr, ConditionDeclaration or None
    step: Expr | None = None
    body: Stmt = PARSED


class Break(Stmt):
    pass


class Continue(Stmt):
    pass


class Return(Stmt):
    value: Expr | None = None


class Discard(Stmt):
    pass


class TranslationUnit(Node):
    """A whole program: the external declarations of every tab, in order (Common first)."""

    decls: list[Node] = LIST


def _is_location(name: str) -> bool:
    return name == "loc" or name.endswith("_loc")


_INIT_TEMPLATES: dict[int, Any] = {}


def _init_template(count: int):
    """The code of an `__init__` with `count` positional parameters (`_f0`, `_f1`, ...; a
    `_Factory` default is replaced by what it makes) and the keyword-only `loc`. Compiled once
    per count; each class gets a copy renamed to its own fields, so importing this module does
    not compile one `__init__` per class (what made `@dataclass` slow to import)."""
    code = _INIT_TEMPLATES.get(count)
    if code is None:
        params = "".join(f"_f{i}, " for i in range(count))
        body = [
            f"    self._f{i} = _f{i}.make() if type(_f{i}) is _Factory else _f{i}"
            for i in range(count)
        ]
        source = "\n".join([f"def __init__(self, {params}*, loc):", *body, "    self.loc = loc"])
        code = _INIT_TEMPLATES[count] = init_code(source)  # a fixed template, no user input
    return code


# The characters of an annotation that are not part of a name (`list["Expr"]`, `Expr | None`):
# splitting on them gives its names without compiling a regular expression at every start.
_NOT_NAME = str.maketrans(dict.fromkeys("[]()|,.'\" ", " "))


def _make_methods() -> None:
    """`_children`, `__init__`, `__match_args__` and the fields `__repr__` shows, of every node
    class, from its declared fields."""
    names = set(_NODE_CLASSES)
    for cls in _NODE_CLASSES.values():
        annotations: dict[str, str] = {}
        for klass in reversed(cls.__mro__):
            annotations.update(getattr(klass, "__annotations__", {}))
        cls._children = tuple(
            f
            for f in cls._fields
            if not names.isdisjoint(annotations[f].translate(_NOT_NAME).split())
        )
        cls._children_reversed = staticmethod(tuple_getter(cls._children[::-1]))
        cls._children_values = staticmethod(tuple_getter(cls._children))
        positional = tuple(f for f in cls._fields if f != "loc")
        defaults = tuple(cls._defaults[f] for f in positional)
        template = _init_template(len(positional))
        rename = {f"_f{i}": f for i, f in enumerate(positional)}
        code = template.replace(
            co_varnames=tuple(rename.get(n, n) for n in template.co_varnames),
            co_names=tuple(rename.get(n, n) for n in template.co_names),
            co_qualname=f"{cls.__name__}.__init__",
        )
        init = FunctionType(code, globals(), "__init__", defaults)
        init.__kwdefaults__ = {"loc": _NOLOC}
        # (set through setattr: mypy refuses assigning either outside a class body)
        setattr(cls, "__init__", init)
        setattr(cls, "__match_args__", positional)
        cls._shown = tuple(f for f in positional if not _is_location(f))


_make_methods()

# The node classes without child fields (names, literals, ...): walks can skip asking for them.
LEAF_CLASSES = frozenset(cls for cls in _NODE_CLASSES.values() if not cls._children)


# ---------------------------------------------------------------------------------------------
# Visiting and comparing
# ---------------------------------------------------------------------------------------------


class NodeVisitor:
    """Dispatch on a node's class by method name, with return values.

    `visit(node, *args)` calls `self.visit_<ClassName>(node, *args)` and returns its value;
    when the class has no such method, the method for its nearest base class that has one
    (`visit_Expr`, `visit_Stmt`, `visit_Node`), else `generic_visit`, which visits the
    children. `dispatch(prefix, node, *args)` does the same for any method prefix, so one
    visitor can have several families (the printer's `_stmt_If` and `_expr_Binary`); a node
    with no method for its prefix goes to `missing(prefix, node)`, which raises TypeError.
    The method found for each (visitor class, prefix, node class) is remembered.
    """

    _methods: dict[tuple[type, str, type], Callable[..., Any] | None] = {}

    def visit(self, node: Node, *args: Any) -> Any:
        method = self._method("visit_", type(node))
        if method is None:
            return self.generic_visit(node, *args)
        return method(self, node, *args)

    def generic_visit(self, node: Node, *args: Any) -> None:
        for child in node.children():
            self.visit(child, *args)

    def dispatch(self, prefix: str, node: Node, *args: Any) -> Any:
        method = self._method(prefix, type(node))
        if method is None:
            return self.missing(prefix, node)
        return method(self, node, *args)

    def missing(self, prefix: str, node: Node) -> Any:
        raise TypeError(f"{type(self).__name__} has no {prefix}{type(node).__name__}")

    def _method(self, prefix: str, node_class: type) -> Callable[..., Any] | None:
        key = (type(self), prefix, node_class)
        try:
            return NodeVisitor._methods[key]
        except KeyError:
            pass
        method = None
        for klass in node_class.__mro__:
            method = getattr(type(self), prefix + klass.__name__, None)
            if method is not None:
                break
        NodeVisitor._methods[key] = method
        return method


def dump(node: Any) -> Any:
    """A location-free nested tuple of the tree: equal dumps mean the same program."""
    if isinstance(node, list):
        return tuple(dump(n) for n in node)
    if not isinstance(node, Node):
        return node
    out: list[Any] = [type(node).__name__]
    for name in node._fields:
        if _is_location(name):
            continue
        out.append((name, dump(getattr(node, name))))
    return tuple(out)


def format_tree(node: Any, indent: int = 0) -> str:
    """A readable indented view of the tree with locations (`glslcheck parse --ast`)."""
    pad = "  " * indent
    if isinstance(node, list):
        return "\n".join(format_tree(n, indent) for n in node)
    attrs = []
    kids = []
    for name in node._fields:
        if _is_location(name):
            continue
        value = getattr(node, name)
        if name in node._children:
            if value is None or value == []:
                continue
            kids.append((name, value))
        elif value not in (None, [], False, ""):
            attrs.append(f"{name}={value!r}")
    loc = node.loc
    where = f"{loc.line}:{loc.column}-{loc.end_line}:{loc.end_column}" if loc.line else ""
    lines = [f"{pad}{type(node).__name__} {' '.join(attrs)} @{where}".rstrip()]
    for name, value in kids:
        if isinstance(value, list):
            lines.append(f"{pad}  .{name}:")
            lines.extend(format_tree(v, indent + 2) for v in value)
        else:
            lines.append(f"{pad}  .{name}:")
            lines.append(format_tree(value, indent + 2))
    return "\n".join(lines)
