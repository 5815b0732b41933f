"""The GLSL ES 3.00 type system: type objects and the typing rules of expressions.

This module owns:

* the type objects (spec chapter 4.1): scalars, vectors, matrices, ``void``, samplers,
  arrays and structs. All are immutable and hashable; every built-in type is a single
  interned object reachable through :data:`BY_NAME` (``BY_NAME["mat2"] is BY_NAME["mat2x2"]``);
* the typing of operators (spec 5.8 - 5.10): :func:`binary_result`, :func:`unary_result`,
  :func:`assign_result`, :func:`conditional_result`;
* component selection and indexing (spec 5.5, 5.6, 5.7): :func:`swizzle_result`,
  :func:`swizzle_is_lvalue`, :func:`index_result`;
* the constructor rules (spec 5.4): :func:`constructor_check`.

GLSL ES has no implicit conversions: ``1 + 1.0`` is an error. Every rule here is exact.
Functions that can fail return either a :class:`Type` or an error message in plain words
(a ``str``); the caller turns the message into a diagnostic with a location.
"""

from __future__ import annotations

from ..base.records import field, record

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up

BASES = ("float", "int", "uint", "bool")
_VECTOR_PREFIX = {"float": "vec", "int": "ivec", "uint": "uvec", "bool": "bvec"}


class Type:
    """Base class of every GLSL type. Subclasses override the properties that apply."""

    __slots__ = ()

    # ``base``: "float" | "int" | "uint" | "bool" for scalars, vectors and matrices, else
    # None. Declared by each subclass (a default here would leak into the records).
    if TYPE_CHECKING:
        base: str | None

    @property
    def size(self) -> int:
        """Number of components: 1 for scalars, n for vectors, C*R for matrices, else 0."""
        return 0

    @property
    def cols(self) -> int:
        """Matrix columns; 1 for scalars and vectors (a vector is one column), else 0."""
        return 0

    @property
    def rows(self) -> int:
        """Matrix rows; n for a vector, 1 for a scalar, else 0."""
        return 0

    is_scalar = False
    is_vector = False
    is_matrix = False
    #: A sampler: cannot be constructed, assigned, compared or used in arithmetic.
    is_opaque = False
    is_void = False
    is_array = False
    is_struct = False

    @property
    def is_numeric(self) -> bool:
        """Scalar, vector or matrix of float, int or uint (not bool)."""
        return self.base in ("float", "int", "uint")

    @property
    def is_basic(self) -> bool:
        """Scalar, vector or matrix (of any base, bool included)."""
        return self.is_scalar or self.is_vector or self.is_matrix

    @property
    def component_type(self) -> Type | None:
        """The scalar type of one component (``float`` for ``mat3``), else None."""
        return None

    @property
    def contains_opaque(self) -> bool:
        """True for samplers and for arrays/structs that contain one."""
        return self.is_opaque


@record(frozen=True)
class ScalarType(Type):
    """``float``, ``int``, ``uint`` or ``bool``."""

    base: str

    is_scalar = True

    @property
    def size(self) -> int:
        return 1

    @property
    def cols(self) -> int:
        return 1

    @property
    def rows(self) -> int:
        return 1

    @property
    def component_type(self) -> Type:
        return self

    def __str__(self) -> str:
        return self.base


@record(frozen=True)
class VectorType(Type):
    """``vecN``, ``ivecN``, ``uvecN``, ``bvecN`` with N in 2..4."""

    base: str
    n: int

    is_vector = True

    @property
    def size(self) -> int:
        return self.n

    @property
    def cols(self) -> int:
        return 1

    @property
    def rows(self) -> int:
        return self.n

    @property
    def component_type(self) -> Type:
        return SCALARS[self.base]

    def __str__(self) -> str:
        return f"{_VECTOR_PREFIX[self.base]}{self.n}"


@record(frozen=True)
class MatrixType(Type):
    """``matCxR``: C columns of R rows, always of float (``mat3`` is ``mat3x3``)."""

    ncols: int
    nrows: int

    base = "float"
    is_matrix = True

    @property
    def size(self) -> int:
        return self.ncols * self.nrows

    @property
    def cols(self) -> int:
        return self.ncols

    @property
    def rows(self) -> int:
        return self.nrows

    @property
    def component_type(self) -> Type:
        return FLOAT

    @property
    def column_type(self) -> Type:
        """The type of ``m[i]``: a column, ``vecR``."""
        return vector("float", self.nrows)

    def __str__(self) -> str:
        if self.ncols == self.nrows:
            return f"mat{self.ncols}"
        return f"mat{self.ncols}x{self.nrows}"


@record(frozen=True)
class VoidType(Type):
    """The return type of functions that return nothing."""

    base = None

    is_void = True

    def __str__(self) -> str:
        return "void"


@record(frozen=True)
class SamplerType(Type):
    """An opaque sampler type (spec 4.1.7).

    ``result`` is the base of what a lookup returns ("float", "int" or "uint"), ``dim``
    one of "2D", "3D", "Cube", "2DArray", ``shadow`` marks depth-comparison samplers.
    """

    base = None

    name: str
    result: str
    dim: str
    shadow: bool = False

    is_opaque = True

    @property
    def coord_size(self) -> int:
        """Components of the ``P`` argument of ``texture()`` (the shadow reference included)."""
        return {"2D": 2, "3D": 3, "Cube": 3, "2DArray": 3}[self.dim] + int(self.shadow)

    def __str__(self) -> str:
        return self.name


@record(frozen=True)
class ArrayType(Type):
    """``element[size]``; ``size`` is None for an unsized array (``float[](...)``)."""

    base = None

    element: Type
    array_size: int | None = None

    is_array = True

    @property
    def contains_opaque(self) -> bool:
        return self.element.contains_opaque

    def __str__(self) -> str:
        return f"{self.element}[{'' if self.array_size is None else self.array_size}]"


@record(frozen=True, eq=False)
class StructType(Type):
    """A user struct. Equality is nominal: one declaration, one type (identity)."""

    base = None

    name: str
    fields: tuple[tuple[str, Type], ...] = field(default=())

    is_struct = True

    def field_type(self, name: str) -> Type | None:
        """The type of field ``name``, or None when the struct has no such field."""
        for fname, ftype in self.fields:
            if fname == name:
                return ftype
        return None

    @property
    def contains_opaque(self) -> bool:
        return any(ftype.contains_opaque for _, ftype in self.fields)

    def __str__(self) -> str:
        return self.name


# ---------------------------------------------------------------------------------------
# The built-in types, interned.

SCALARS: dict[str, ScalarType] = {b: ScalarType(b) for b in BASES}
FLOAT, INT, UINT, BOOL = (SCALARS[b] for b in BASES)
VOID = VoidType()

_VECTORS = {(b, n): VectorType(b, n) for b in BASES for n in (2, 3, 4)}
_MATRICES = {(c, r): MatrixType(c, r) for c in (2, 3, 4) for r in (2, 3, 4)}


def vector(base: str, n: int) -> Type:
    """The vector of ``n`` components of ``base``; ``n == 1`` gives the scalar."""
    if n == 1:
        return SCALARS[base]
    return _VECTORS[(base, n)]


def matrix(cols: int, rows: int) -> MatrixType:
    """``matCxR`` (C columns, R rows)."""
    return _MATRICES[(cols, rows)]


def _sampler(name: str) -> SamplerType:
    result = {"i": "int", "u": "uint"}.get(name[0], "float")
    core = name.lstrip("iu")[len("sampler") :]
    shadow = core.endswith("Shadow")
    return SamplerType(name, result, core.removesuffix("Shadow"), shadow)


SAMPLER_NAMES = (
    "sampler2D",
    "sampler3D",
    "samplerCube",
    "sampler2DShadow",
    "samplerCubeShadow",
    "sampler2DArray",
    "sampler2DArrayShadow",
    "isampler2D",
    "isampler3D",
    "isamplerCube",
    "isampler2DArray",
    "usampler2D",
    "usampler3D",
    "usamplerCube",
    "usampler2DArray",
)
SAMPLERS: dict[str, SamplerType] = {n: _sampler(n) for n in SAMPLER_NAMES}

#: Every built-in type keyword (spec 4.1) to its type; ``mat2`` and ``mat2x2`` are one object.
BY_NAME: dict[str, Type] = {"void": VOID, **SCALARS}
BY_NAME.update({str(v): v for v in _VECTORS.values()})
BY_NAME.update({f"mat{c}x{r}": m for (c, r), m in _MATRICES.items()})
BY_NAME.update({f"mat{n}": _MATRICES[(n, n)] for n in (2, 3, 4)})
BY_NAME.update(SAMPLERS)

# Module-level names for the common types, so callers can write ``types.VEC3``.
VEC2, VEC3, VEC4 = (vector("float", n) for n in (2, 3, 4))
IVEC2, IVEC3, IVEC4 = (vector("int", n) for n in (2, 3, 4))
UVEC2, UVEC3, UVEC4 = (vector("uint", n) for n in (2, 3, 4))
BVEC2, BVEC3, BVEC4 = (vector("bool", n) for n in (2, 3, 4))
MAT2, MAT3, MAT4 = (matrix(n, n) for n in (2, 3, 4))


# ---------------------------------------------------------------------------------------
# Operators (spec 5.9).

_VERB = {
    "+": "cannot add '{l}' and '{r}'",
    "-": "cannot subtract '{r}' from '{l}'",
    "*": "cannot multiply '{l}' by '{r}'",
    "/": "cannot divide '{l}' by '{r}'",
}
ARITHMETIC_OPS = frozenset("+-*/")
RELATIONAL_OPS = frozenset({"<", ">", "<=", ">="})
EQUALITY_OPS = frozenset({"==", "!="})
LOGICAL_OPS = frozenset({"&&", "||", "^^"})
BITWISE_OPS = frozenset({"&", "|", "^"})
SHIFT_OPS = frozenset({"<<", ">>"})
BINARY_OPS = (
    ARITHMETIC_OPS | RELATIONAL_OPS | EQUALITY_OPS | LOGICAL_OPS | BITWISE_OPS | SHIFT_OPS | {"%"}
)
ASSIGN_OPS = frozenset({"+=", "-=", "*=", "/=", "%=", "<<=", ">>=", "&=", "|=", "^="})
UNARY_OPS = frozenset({"-", "+", "!", "~", "++", "--"})


def _fail(op: str, left: Type, right: Type, why: str = "") -> str:
    head = _VERB.get(op, "operator '{op}' cannot be applied to '{l}' and '{r}'")
    msg = head.format(op=op, l=left, r=right)
    return f"{msg}: {why}" if why else msg


def _no_conversion(left: Type, right: Type) -> str:
    return (
        f"GLSL ES has no implicit conversion between {left.base} and {right.base}; "
        f"convert one side explicitly, e.g. {right.base}(x) or {left.base}(x)"
    )


def _componentwise(op: str, left: Type, right: Type, bases: tuple[str, ...]) -> Type | str:
    """Scalar/vector operands of one base, with scalar broadcasting (+ - * / % & | ^)."""
    for t in (left, right):
        if not (t.is_scalar or t.is_vector) or t.base not in bases:
            return _fail(op, left, right, f"'{t}' is not {_describe(bases)}")
    if left.base != right.base:
        return _fail(op, left, right, _no_conversion(left, right))
    if left.is_vector and right.is_vector and left.size != right.size:
        return _fail(op, left, right, f"vector sizes differ ({left.size} and {right.size})")
    return left if left.is_vector else right


def _describe(bases: tuple[str, ...]) -> str:
    if bases == ("float", "int", "uint"):
        return "a numeric scalar, vector or matrix"
    if bases == ("int", "uint"):
        return "an int or uint scalar or vector"
    return "a " + " or ".join(bases) + " value"


def _arithmetic(op: str, left: Type, right: Type) -> Type | str:
    for t in (left, right):
        if not t.is_numeric:
            why = "arithmetic needs numeric operands" if t.base == "bool" or t.base is None else ""
            return _fail(op, left, right, f"'{t}' is not numeric; {why}".rstrip("; "))
    if left.base != right.base:
        return _fail(op, left, right, _no_conversion(left, right))
    if not (left.is_matrix or right.is_matrix):
        return _componentwise(op, left, right, ("float", "int", "uint"))
    # At least one matrix; both are float.
    if left.is_scalar:
        return right
    if right.is_scalar:
        return left
    if op != "*":
        if left == right:
            return left
        return _fail(op, left, right, "component-wise matrix operations need the same type")
    # Linear-algebra multiply.
    if left.is_matrix and right.is_vector:  # matCxR * vecC -> vecR
        if left.cols != right.size:
            return _fail(
                op,
                left,
                right,
                f"'{left}' has {left.cols} columns but '{right}' has {right.size} components",
            )
        return vector("float", left.rows)
    if left.is_vector and right.is_matrix:  # vecR * matCxR -> vecC
        if left.size != right.rows:
            return _fail(
                op,
                left,
                right,
                f"'{left}' has {left.size} components but '{right}' has {right.rows} rows",
            )
        return vector("float", right.cols)
    # matCxR * matKxC -> matKxR
    if left.cols != right.rows:
        return _fail(
            op, left, right, f"'{left}' has {left.cols} columns but '{right}' has {right.rows} rows"
        )
    return matrix(right.cols, left.rows)


def _shift(op: str, left: Type, right: Type) -> Type | str:
    for t in (left, right):
        if not (t.is_scalar or t.is_vector) or t.base not in ("int", "uint"):
            return _fail(op, left, right, f"'{t}' is not an int or uint scalar or vector")
    if left.is_scalar and right.is_vector:
        return _fail(op, left, right, "a scalar cannot be shifted by a vector")
    if left.is_vector and right.is_vector and left.size != right.size:
        return _fail(op, left, right, f"vector sizes differ ({left.size} and {right.size})")
    return left


def binary_result(op: str, left: Type, right: Type) -> Type | str:
    """The type of ``left op right``, or an error message (spec 5.9).

    ``op`` is one of ``+ - * / % < > <= >= == != && || ^^ & | ^ << >>``.
    """
    if op in ARITHMETIC_OPS:
        return _arithmetic(op, left, right)
    if op == "%":
        return _componentwise(op, left, right, ("int", "uint"))
    if op in BITWISE_OPS:
        return _componentwise(op, left, right, ("int", "uint"))
    if op in SHIFT_OPS:
        return _shift(op, left, right)
    if op in RELATIONAL_OPS:
        if not (left.is_scalar and right.is_scalar and left.is_numeric and right.is_numeric):
            hint = ""
            if left.is_vector or right.is_vector:
                name = {
                    "<": "lessThan",
                    ">": "greaterThan",
                    "<=": "lessThanEqual",
                    ">=": "greaterThanEqual",
                }[op]
                hint = f"; compare vectors component-wise with {name}()"
            return _fail(op, left, right, "relational operators need numeric scalars" + hint)
        if left.base != right.base:
            return _fail(op, left, right, _no_conversion(left, right))
        return BOOL
    if op in EQUALITY_OPS:
        if left.is_void or right.is_void:
            return _fail(op, left, right, "'void' has no value")
        if left.contains_opaque or right.contains_opaque:
            return _fail(op, left, right, "samplers cannot be compared")
        if left != right:
            if left.is_basic and right.is_basic and left.base != right.base:
                return _fail(op, left, right, _no_conversion(left, right))
            return _fail(op, left, right, "operands must have the same type")
        return BOOL
    if op in LOGICAL_OPS:
        if left != BOOL or right != BOOL:
            return _fail(
                op,
                left,
                right,
                "logical operators need bool scalars; for bvec use any(), all() or not()",
            )
        return BOOL
    raise ValueError(f"unknown binary operator {op!r}")


def assign_result(op: str, target: Type, value: Type) -> Type | str:
    """The type of ``target op value`` for ``=`` and the compound assignments (spec 5.8).

    The result must be the target's own type: ``v3 *= m3`` is fine, ``f += v3`` is not.
    Whether ``target`` is an l-value is the checker's business.
    """
    if op == "=":
        if target.contains_opaque or target.is_void:
            return f"cannot assign to a value of type '{target}'"
        if target != value:
            return f"cannot assign '{value}' to '{target}'"
        return target
    if op not in ASSIGN_OPS:
        raise ValueError(f"unknown assignment operator {op!r}")
    result = binary_result(op[:-1], target, value)
    if isinstance(result, str):
        return result
    if result != target:
        return f"'{target} {op} {value}' would produce '{result}', which does not fit in '{target}'"
    return target


def conditional_result(cond: Type, if_true: Type, if_false: Type) -> Type | str:
    """The type of ``cond ? if_true : if_false`` (spec 5.10)."""
    if cond != BOOL:
        hint = "; for bvec use mix() or any()/all()" if cond.base == "bool" else ""
        return f"the condition of '?:' must be a bool, not '{cond}'{hint}"
    if if_true.is_void or if_true.contains_opaque:
        return f"'?:' cannot choose between values of type '{if_true}'"
    if if_true != if_false:
        why = (
            f": {_no_conversion(if_true, if_false)}"
            if if_true.is_basic and if_false.is_basic and if_true.base != if_false.base
            else ""
        )
        return f"the two branches of '?:' have different types '{if_true}' and '{if_false}'{why}"
    return if_true


def unary_result(op: str, operand: Type) -> Type | str:
    """The type of a prefix/postfix unary operation (spec 5.9): ``- + ! ~ ++ --``."""
    if op in ("-", "+", "++", "--"):
        if not operand.is_numeric:
            return f"operator '{op}' cannot be applied to '{operand}': it needs a numeric value"
        return operand
    if op == "!":
        if operand != BOOL:
            hint = "; for bvec use not()" if operand.is_vector and operand.base == "bool" else ""
            return f"operator '!' cannot be applied to '{operand}': it needs a bool{hint}"
        return BOOL
    if op == "~":
        if not ((operand.is_scalar or operand.is_vector) and operand.base in ("int", "uint")):
            return (
                f"operator '~' cannot be applied to '{operand}': it needs an int or uint "
                f"scalar or vector"
            )
        return operand
    raise ValueError(f"unknown unary operator {op!r}")


# ---------------------------------------------------------------------------------------
# Swizzles and indexing (spec 5.5 - 5.7).

SWIZZLE_SETS = ("xyzw", "rgba", "stpq")


def swizzle_result(t: Type, fields: str) -> Type | str:
    """The type of ``t.fields`` for a vector ``t``, or an error message."""
    if not isinstance(t, VectorType):
        if t.is_scalar:
            return f"cannot select '.{fields}' of scalar '{t}': GLSL ES has no scalar swizzles"
        return f"'{t}' has no components to select with '.{fields}'"
    if len(fields) > 4:
        return f"swizzle '.{fields}' selects more than 4 components"
    for letters in SWIZZLE_SETS:
        if fields and all(c in letters for c in fields):
            for c in fields:
                if letters.index(c) >= t.size:
                    return f"'.{fields}' selects '{c}', beyond the {t.size} components of '{t}'"
            return vector(t.base, len(fields))
    if fields and all(any(c in s for s in SWIZZLE_SETS) for c in fields):
        return f"swizzle '.{fields}' mixes the sets xyzw, rgba and stpq"
    return f"'{t}' has no field '{fields}'"


def swizzle_is_lvalue(fields: str) -> bool:
    """A swizzle can be written to only when no component repeats (``v.xy = ...``, not ``v.xx``)."""
    return len(set(fields)) == len(fields)


def index_result(t: Type) -> Type | str:
    """The type of ``t[i]``: array element, matrix column or vector component."""
    if isinstance(t, ArrayType):
        return t.element
    if isinstance(t, MatrixType):
        return t.column_type
    if isinstance(t, VectorType):
        return t.component_type
    return f"'{t}' cannot be indexed"


# ---------------------------------------------------------------------------------------
# Constructors (spec 5.4).


def _plural(n: int, word: str) -> str:
    return f"{n} {word}" + ("" if n == 1 else "s")


def constructor_check(target: Type, args: list[Type]) -> str | None:
    """Check a constructor call ``target(args...)``; None when valid, else an error message.

    For an unsized array target (``float[](...)``) the size is taken from the arguments; use
    :func:`constructor_result` to get the resulting sized type.
    """
    if target.is_void or target.contains_opaque:
        return f"'{target}' cannot be constructed"
    if not args:
        return f"'{target}' constructor needs arguments"
    for a in args:
        if a.is_void:
            return f"'{target}' constructor got a 'void' argument"
    if isinstance(target, StructType):
        if len(args) != len(target.fields):
            return (
                f"'{target}' constructor takes {_plural(len(target.fields), 'argument')}, "
                f"one per field, but got {len(args)}"
            )
        for (fname, ftype), a in zip(target.fields, args):
            if a != ftype:
                return f"'{target}' field '{fname}' is '{ftype}' but the argument is '{a}'"
        return None
    if isinstance(target, ArrayType):
        if target.array_size is not None and len(args) != target.array_size:
            return (
                f"'{target}' constructor takes {_plural(target.array_size, 'argument')} "
                f"but got {len(args)}"
            )
        for i, a in enumerate(args):
            if a != target.element:
                return f"'{target}' element {i} must be '{target.element}' but is '{a}'"
        return None
    for a in args:
        if not a.is_basic:
            return f"'{target}' cannot be constructed from '{a}'"
    if target.is_scalar:
        if len(args) > 1:
            return f"'{target}' constructor takes one argument: too many arguments"
        return None
    if len(args) == 1:
        a = args[0]
        if a.is_scalar:
            return None  # vector: replicated; matrix: diagonal
        if target.is_matrix and a.is_matrix:
            return None  # any matrix size: copy the overlap, identity elsewhere
        if a.size < target.size:
            return (
                f"'{target}' needs {target.size} components but '{a}' provides only "
                f"{a.size}: not enough data"
            )
        if target.is_matrix and a.size > target.size:
            return (
                f"'{target}' needs {target.size} components but '{a}' provides {a.size}: "
                f"too many arguments"
            )
        return None
    if target.is_matrix:
        for a in args:
            if a.is_matrix:
                return f"a matrix argument to '{target}' must be the only argument"
    total = 0
    for i, a in enumerate(args):
        if total >= target.size:
            return (
                f"'{target}' needs {target.size} components; argument {i + 1} ('{a}') and "
                f"later are unused: too many arguments"
            )
        total += a.size
    if total < target.size:
        return (
            f"'{target}' needs {target.size} components but the arguments provide only "
            f"{total}: not enough data"
        )
    return None


def constructor_result(target: Type, args: list[Type]) -> Type | str:
    """The type a constructor call produces (sizes an unsized array), or an error message."""
    err = constructor_check(target, args)
    if err is not None:
        return err
    if isinstance(target, ArrayType) and target.array_size is None:
        return ArrayType(target.element, len(args))
    return target
