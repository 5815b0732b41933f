"""The typed GLSL ES 3.00 syntax tree, and a visitor.

Every node is a slotted dataclass. Its class attribute `_children` names the fields that hold
child nodes (a node, a list of nodes, or None); every other field is a plain attribute. Every
node carries `loc`, the span of its text in the user's own file (after preprocessing and the
Shadertoy wrapper, a location still points into the tab file the user wrote).

`children()`, `walk()`, `NodeVisitor` and `dump()` are derived from `_children`, so a new node
class only has to declare its fields. `dump()` gives a location-free nested tuple: two trees
with equal dumps are the same program (used by the parse -> print -> parse round trip).
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from typing import Any, Iterator, Optional

from .diagnostics import Location

_NOLOC = Location("<builtin>", 0, 0)


@dataclass(slots=True, eq=False)
class Node:
    loc: Location = field(default=_NOLOC, kw_only=True, repr=False)
    _children = ()

    def children(self) -> Iterator["Node"]:
        """The child nodes, in source order of the fields."""
        for name in self._children:
            value = getattr(self, name)
            if value is None:
                continue
            if isinstance(value, list):
                for item in value:
                    if item is not None:
                        yield item
            else:
                yield value

    def walk(self) -> Iterator["Node"]:
        """This node and all its descendants, depth first, parents before children (iterative)."""
        stack = [self]
        while stack:
            node = stack.pop()
            yield node
            kids = list(node.children())
            kids.reverse()
            stack.extend(kids)


# ---------------------------------------------------------------------------------------------
# Types and qualifiers
# ---------------------------------------------------------------------------------------------


@dataclass(slots=True, eq=False)
class ArraySpec(Node):
    """`[size]` or `[]` (size None)."""

    size: Optional["Expr"] = None
    _children = ("size",)


@dataclass(slots=True, eq=False)
class LayoutId(Node):
    name: str = ""
    value: int | None = None


@dataclass(slots=True, eq=False)
class Layout(Node):
    """`layout(location = 0, std140)`."""

    ids: list[LayoutId] = field(default_factory=list)
    _children = ("ids",)


@dataclass(slots=True, eq=False)
class Qualifiers(Node):
    """Storage, precision, interpolation, invariant and layout qualifiers in source order.
    `words` holds the keywords ("const", "uniform", "in", "centroid in", "highp", "flat", ...)."""

    words: list[str] = field(default_factory=list)
    layouts: list[Layout] = field(default_factory=list)
    _children = ("layouts",)

    @property
    def storage(self) -> str | None:
        for w in self.words:
            if w in ("const", "uniform", "in", "out", "inout", "centroid in", "centroid out"):
                return w
        return None

    @property
    def precision(self) -> str | None:
        for w in self.words:
            if w in ("highp", "mediump", "lowp"):
                return w
        return None


@dataclass(slots=True, eq=False)
class StructMember(Node):
    qualifiers: Optional[Qualifiers] = None
    type: Optional["TypeSpec"] = None
    declarators: list["StructDeclarator"] = field(default_factory=list)
    _children = ("qualifiers", "type", "declarators")


@dataclass(slots=True, eq=False)
class StructDeclarator(Node):
    name: str = ""
    array: Optional[ArraySpec] = None
    _children = ("array",)


@dataclass(slots=True, eq=False)
class StructSpec(Node):
    """`struct Name { members }` (name None for an anonymous struct)."""

    name: str | None = None
    members: list[StructMember] = field(default_factory=list)
    _children = ("members",)


@dataclass(slots=True, eq=False)
class TypeSpec(Node):
    """A type as written: a built-in type name, a struct name, or a struct definition;
    optionally with an array size (`float[3]`)."""

    name: str | None = None  # "vec3", "S"; None when `struct_` defines the type here
    struct_: Optional[StructSpec] = None
    array: Optional[ArraySpec] = None
    is_struct_name: bool = False  # `name` refers to a user struct
    _children = ("struct_", "array")

    @property
    def type_name(self) -> str:
        if self.name is not None:
            return self.name
        return self.struct_.name if self.struct_ and self.struct_.name else "<anonymous struct>"


# ---------------------------------------------------------------------------------------------
# Expressions
# ---------------------------------------------------------------------------------------------


@dataclass(slots=True, eq=False)
class Expr(Node):
    pass


@dataclass(slots=True, eq=False)
class Identifier(Expr):
    name: str = ""


@dataclass(slots=True, eq=False)
class IntLiteral(Expr):
    value: int = 0
    unsigned: bool = False
    text: str = ""


@dataclass(slots=True, eq=False)
class FloatLiteral(Expr):
    value: float = 0.0
    text: str = ""


@dataclass(slots=True, eq=False)
class BoolLiteral(Expr):
    value: bool = False


@dataclass(slots=True, eq=False)
class Binary(Expr):
    """`left op right` for every binary operator but assignment and the comma."""

    op: str = "+"
    left: Optional[Expr] = None
    right: Optional[Expr] = None
    _children = ("left", "right")


@dataclass(slots=True, eq=False)
class Unary(Expr):
    """Prefix `+ - ! ~ ++ --` (op) applied to operand."""

    op: str = "-"
    operand: Optional[Expr] = None
    _children = ("operand",)


@dataclass(slots=True, eq=False)
class Postfix(Expr):
    """Postfix `++` / `--`."""

    op: str = "++"
    operand: Optional[Expr] = None
    _children = ("operand",)


@dataclass(slots=True, eq=False)
class Assignment(Expr):
    """`target op value` with op one of `= += -= *= /= %= <<= >>= &= ^= |=`."""

    op: str = "="
    target: Optional[Expr] = None
    value: Optional[Expr] = None
    _children = ("target", "value")


@dataclass(slots=True, eq=False)
class Ternary(Expr):
    cond: Optional[Expr] = None
    then: Optional[Expr] = None
    else_: Optional[Expr] = None
    _children = ("cond", "then", "else_")


@dataclass(slots=True, eq=False)
class Sequence(Expr):
    """The comma operator: `a, b, c` evaluates all, yields the last."""

    exprs: list[Expr] = field(default_factory=list)
    _children = ("exprs",)


@dataclass(slots=True, eq=False)
class Call(Expr):
    """A function call or a constructor: `f(x)`, `vec3(1.0)`, `S(a, b)`, `float[3](a, b, c)`.
    `callee` is the name as written; `constructor` is True when it names a type (a built-in
    type, a struct, or an array type with `array` set)."""

    callee: str = ""
    args: list[Expr] = field(default_factory=list)
    constructor: bool = False
    array: Optional[ArraySpec] = None
    struct_: Optional[StructSpec] = None  # `struct {...}[2](...)`, legal but rare
    callee_loc: Location = field(default=_NOLOC, repr=False)
    _children = ("struct_", "array", "args")


@dataclass(slots=True, eq=False)
class Index(Expr):
    base: Optional[Expr] = None
    index: Optional[Expr] = None
    _children = ("base", "index")


@dataclass(slots=True, eq=False)
class Field(Expr):
    """`base.name`: a struct member or a vector swizzle (the checker tells which)."""

    base: Optional[Expr] = None
    name: str = ""
    name_loc: Location = field(default=_NOLOC, repr=False)
    _children = ("base",)


@dataclass(slots=True, eq=False)
class MethodCall(Expr):
    """`base.name()`: GLSL ES 3.00 has one method, `.length()` of arrays."""

    base: Optional[Expr] = None
    name: str = ""
    _children = ("base",)


# ---------------------------------------------------------------------------------------------
# Declarations
# ---------------------------------------------------------------------------------------------


@dataclass(slots=True, eq=False)
class Declarator(Node):
    """One name of a variable declaration: `name[array] = init`."""

    name: str = ""
    array: Optional[ArraySpec] = None
    init: Optional[Expr] = None
    name_loc: Location = field(default=_NOLOC, repr=False)
    _children = ("array", "init")


@dataclass(slots=True, eq=False)
class VariableDeclaration(Node):
    """`qualifiers type a = 1.0, b[2];` (no declarators: `struct S {...};` or `float;`)."""

    qualifiers: Optional[Qualifiers] = None
    type: Optional[TypeSpec] = None
    declarators: list[Declarator] = field(default_factory=list)
    _children = ("qualifiers", "type", "declarators")


@dataclass(slots=True, eq=False)
class Param(Node):
    qualifiers: list[str] = field(default_factory=list)  # "const", "in", "out", "inout", precision
    type: Optional[TypeSpec] = None
    name: str | None = None
    array: Optional[ArraySpec] = None
    name_loc: Location = field(default=_NOLOC, repr=False)
    _children = ("type", "array")

    @property
    def direction(self) -> str:
        for q in self.qualifiers:
            if q in ("out", "inout"):
                return q
        return "in"


@dataclass(slots=True, eq=False)
class FunctionPrototype(Node):
    qualifiers: Optional[Qualifiers] = None
    return_type: Optional[TypeSpec] = None
    name: str = ""
    params: list[Param] = field(default_factory=list)
    name_loc: Location = field(default=_NOLOC, repr=False)
    _children = ("qualifiers", "return_type", "params")


@dataclass(slots=True, eq=False)
class FunctionDeclaration(Node):
    """A prototype alone: `float f(float x);`."""

    proto: Optional[FunctionPrototype] = None
    _children = ("proto",)


@dataclass(slots=True, eq=False)
class FunctionDefinition(Node):
    proto: Optional[FunctionPrototype] = None
    body: Optional["Compound"] = None
    _children = ("proto", "body")


@dataclass(slots=True, eq=False)
class PrecisionDeclaration(Node):
    """`precision highp float;`."""

    precision: str = "highp"
    type: Optional[TypeSpec] = None
    _children = ("type",)


@dataclass(slots=True, eq=False)
class BlockDeclaration(Node):
    """An interface block: `uniform Block { vec4 a; } name[2];`."""

    qualifiers: Optional[Qualifiers] = None
    block_name: str = ""
    members: list[StructMember] = field(default_factory=list)
    instance: str | None = None
    array: Optional[ArraySpec] = None
    _children = ("qualifiers", "members", "array")


@dataclass(slots=True, eq=False)
class InvariantDeclaration(Node):
    """`invariant a, b;` (redeclaring outputs as invariant)."""

    qualifiers: Optional[Qualifiers] = None
    names: list[str] = field(default_factory=list)
    _children = ("qualifiers",)


@dataclass(slots=True, eq=False)
class QualifierDeclaration(Node):
    """A qualifier alone: `layout(std140) uniform;`."""

    qualifiers: Optional[Qualifiers] = None
    _children = ("qualifiers",)


# ---------------------------------------------------------------------------------------------
# Statements
# ---------------------------------------------------------------------------------------------


@dataclass(slots=True, eq=False)
class Stmt(Node):
    pass


@dataclass(slots=True, eq=False)
class Compound(Stmt):
    stmts: list[Node] = field(default_factory=list)
    _children = ("stmts",)


@dataclass(slots=True, eq=False)
class DeclarationStatement(Stmt):
    decl: Optional[Node] = None
    _children = ("decl",)


@dataclass(slots=True, eq=False)
class ExpressionStatement(Stmt):
    """`expr;` or the empty statement `;` (expr None)."""

    expr: Optional[Expr] = None
    _children = ("expr",)


@dataclass(slots=True, eq=False)
class If(Stmt):
    cond: Optional[Expr] = None
    then: Optional[Stmt] = None
    else_: Optional[Stmt] = None
    _children = ("cond", "then", "else_")


@dataclass(slots=True, eq=False)
class Switch(Stmt):
    expr: Optional[Expr] = None
    body: list[Stmt] = field(default_factory=list)
    _children = ("expr", "body")


@dataclass(slots=True, eq=False)
class Case(Stmt):
    """`case expr:` (expr None for `default:`)."""

    expr: Optional[Expr] = None
    _children = ("expr",)


@dataclass(slots=True, eq=False)
class ConditionDeclaration(Node):
    """The `bool b = f()` of `while (bool b = f())`."""

    qualifiers: Optional[Qualifiers] = None
    type: Optional[TypeSpec] = None
    name: str = ""
    init: Optional[Expr] = None
    name_loc: Location = field(default=_NOLOC, repr=False)
    _children = ("qualifiers", "type", "init")


@dataclass(slots=True, eq=False)
class While(Stmt):
    cond: Optional[Node] = None  # Expr or ConditionDeclaration
    body: Optional[Stmt] = None
    _children = ("cond", "body")


@dataclass(slots=True, eq=False)
class DoWhile(Stmt):
    body: Optional[Stmt] = None
    cond: Optional[Expr] = None
    _children = ("body", "cond")


@dataclass(slots=True, eq=False)
class For(Stmt):
    init: Optional[Stmt] = None  # DeclarationStatement or ExpressionStatement
    cond: Optional[Node] = None  # Expr, ConditionDeclaration or None
    step: Optional[Expr] = None
    body: Optional[Stmt] = None
    _children = ("init", "cond", "step", "body")


@dataclass(slots=True, eq=False)
class Break(Stmt):
    pass


@dataclass(slots=True, eq=False)
class Continue(Stmt):
    pass


@dataclass(slots=True, eq=False)
class Return(Stmt):
    value: Optional[Expr] = None
    _children = ("value",)


@dataclass(slots=True, eq=False)
class Discard(Stmt):
    pass


@dataclass(slots=True, eq=False)
class TranslationUnit(Node):
    """A whole program: the external declarations of every tab, in order (Common first)."""

    decls: list[Node] = field(default_factory=list)
    _children = ("decls",)


# ---------------------------------------------------------------------------------------------
# Visiting and comparing
# ---------------------------------------------------------------------------------------------


class NodeVisitor:
    """`visit(node)` calls `visit_<ClassName>(node)` when defined, else `generic_visit`, which
    visits the children."""

    def visit(self, node: Node) -> Any:
        method = getattr(self, "visit_" + type(node).__name__, None)
        if method is None:
            return self.generic_visit(node)
        return method(node)

    def generic_visit(self, node: Node) -> None:
        for child in node.children():
            self.visit(child)


def dump(node: Any) -> Any:
    """A location-free nested tuple of the tree: equal dumps mean the same program."""
    if isinstance(node, list):
        return tuple(dump(n) for n in node)
    if not isinstance(node, Node):
        return node
    out: list[Any] = [type(node).__name__]
    for f in fields(node):
        if f.name == "loc" or f.name.endswith("_loc"):
            continue
        out.append((f.name, dump(getattr(node, f.name))))
    return tuple(out)


def format_tree(node: Any, indent: int = 0) -> str:
    """A readable indented view of the tree with locations (`glslcheck parse --ast`)."""
    pad = "  " * indent
    if isinstance(node, list):
        return "\n".join(format_tree(n, indent) for n in node)
    attrs = []
    kids = []
    for f in fields(node):
        if f.name == "loc" or f.name.endswith("_loc"):
            continue
        value = getattr(node, f.name)
        if f.name in node._children:
            if value is None or value == []:
                continue
            kids.append((f.name, value))
        elif value not in (None, [], False, ""):
            attrs.append(f"{f.name}={value!r}")
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
