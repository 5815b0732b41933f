"""The compiled engine's vocabulary, shared by the code generator and the built-in calls: how a
GLSL value is held in generated code (`Val` of scalar leaves, `Arr` array leaves, `Dyn` run-time
indexed components, `leaves` of a type), the scalar kinds' tables, which generated expressions are
pure (`pure_expr`, also read by lanes.py), and the located errors the engine raises."""

from __future__ import annotations

import ast as pyast
import re
from dataclasses import dataclass
from typing import Any

from ...base.diagnostics import Diagnostic, GlslError, Location

RULE = "compiled-engine"
NOT_YET = "not supported by the compiled engine yet"
# Ternaries computed on both sides (Codegen._speculable): a side of more than SPECULATE_LINES
# pure temporaries (pure_expr) keeps its branch (its work would be paid where it is not taken).
PURE_LINE = re.compile(r"^( *)_t[0-9]+ = (.*)$")
SPECULATE_LINES = 4
PURE_NODES = (
    pyast.Name,
    pyast.Constant,
    pyast.BinOp,
    pyast.UnaryOp,
    pyast.Compare,
    pyast.IfExp,
    pyast.BoolOp,
    pyast.Load,
    pyast.Add,
    pyast.Sub,
    pyast.Mult,
    pyast.Div,
    pyast.USub,
    pyast.UAdd,
    pyast.Not,
    pyast.And,
    pyast.Or,
    pyast.Eq,
    pyast.NotEq,
    pyast.Lt,
    pyast.LtE,
    pyast.Gt,
    pyast.GtE,
)


def pure_expr(e: Any) -> bool:
    """A generated expression (its text or its Python ast) that reads names and constants with
    float arithmetic, compares, `and`/`or`/`not`, lsel and daz only: it has no effect and cannot
    fail (error_model="numpy"; this generator wraps int arithmetic in casts, which are calls), so
    computing it where its value is not used changes nothing (codegen's ternaries, lanes.py's
    conditional expressions)."""
    if isinstance(e, str):
        try:
            e = pyast.parse(e, mode="eval").body
        except SyntaxError:
            return False
    for n in pyast.walk(e):
        if isinstance(n, pyast.Call):
            if not (isinstance(n.func, pyast.Name) and n.func.id in PURE_CALLS and not n.keywords):
                return False
        elif not isinstance(n, PURE_NODES):
            return False
    return True


# calls of the runtime a pure expression may make: a select, and a subnormal flushed to zero
PURE_CALLS = ("lsel", "daz")


ATOM = re.compile(r"^(?:[A-Za-z_][A-Za-z0-9_]*(?:\[[A-Za-z0-9_ +]+\])?|True|False)$")
_FIXED = re.compile(r"[FIU]_\w+|True|False|_t\d+")  # constants, bools, temporaries


def may_change(part: Any) -> bool:
    """A value part whose text may read something a later write changes (a variable's name, an
    expression): anything but a module constant, a bool literal or a temporary `fresh` made."""
    return isinstance(part, str) and _FIXED.fullmatch(part) is None


KIND_ARRAY = {"float": "gf", "int": "gi", "uint": "gu", "bool": "gb"}
DTYPE = {"float": "np.float32", "int": "np.int32", "uint": "np.uint32", "bool": "np.bool_"}
CAST = {"float": "F32", "int": "I32", "uint": "U32", "bool": "bool"}
SWIZZLE_LETTERS = "xyzw"
# the per-pixel state arrays (codegen's docstring); `lc`: llvmpipe's loop pass budget (scalar.tick)
STATE = ("gf", "gi", "gu", "gb", "uf", "ui", "lc")
STATE_NAME = re.compile(r"(?<![\w.])(gf|gi|gu|gb|uf|ui|lc)(?!\w)")
BUDGET_OFF, BUDGET_ON = "BUDGET = False", "BUDGET = True"  # the generated module's line
SMALL_ARRAY = 64  # arrays of up to this many scalars are scalars too (no allocation per pixel)


def engine_error(message: str, node: Any, help: str | None = None) -> GlslError:
    """A GlslError of the compiled engine at node (a syntax node or a Location)."""
    loc = node if isinstance(node, Location) else getattr(node, "loc", None)
    return GlslError(Diagnostic(message, loc, rule=RULE, help=help))


def not_yet(what: str, node: Any) -> GlslError:
    """The error for a construct the compiled engine does not handle yet."""
    return engine_error(f"{what}: {NOT_YET}", node, help="render with --backend numpy or gl")


@dataclass
class Arr:
    """An array leaf: elements off .. off+size-1 of the numba array `name`."""

    name: str
    off: int
    size: int
    base: str

    def at(self, idx: str) -> str:
        return f"{self.name}[{idx}]" if not self.off else f"{self.name}[{self.off} + {idx}]"

    def whole(self) -> str:
        """The array as a value: a local array itself, else a copy of its slots."""
        if self.name.startswith(("a_", "_")):
            return self.name
        return f"aslice({self.name}, {self.off}, {self.size})"


@dataclass
class Dyn:
    """A vector component (or matrix column entry) chosen by a run-time index: parts[idx]."""

    idx: str
    parts: list


@dataclass
class Val:
    """A GLSL value in generated code: its type, its leaves, and its compile-time constant
    leaves (None when it is not a constant)."""

    t: Any
    parts: list
    const: list | None = None
    uni: bool = False  # one value for a whole tile in the NumPy backend, taken there for a constant
    one: bool = False  # one lane there, a uniform input too (fold_values.py: its rules read it)

    @property
    def constlike(self) -> bool:
        return self.const is not None or self.uni


def leaves(t: Any, node: Any) -> list[tuple[str, int | None]]:
    """The scalar leaves of type t: (base type, array size or None)."""
    if t.is_scalar:
        return [(t.base, None)]
    if t.is_vector:
        return [(t.base, None)] * t.size
    if t.is_matrix:
        return [("float", None)] * (t.cols * t.rows)
    if t.is_struct:
        return [leaf for _, ft in t.fields for leaf in leaves(ft, node)]
    if t.is_array:
        inner = leaves(t.element, node)
        if any(n is not None for _, n in inner):
            raise not_yet("an array of structs that hold arrays", node)
        if t.array_size is None:
            raise not_yet("an unsized array", node)
        if t.array_size * len(inner) <= SMALL_ARRAY:  # scalars, leaf by leaf (see the docstring)
            return [(b, None) for b, _ in inner for _ in range(t.array_size)]
        return [(b, t.array_size) for b, _ in inner]
    if str(t) in ("sampler2D", "samplerCube"):  # its channel number (texture_calls.py)
        return [("int", None)]
    if t.contains_opaque:
        raise not_yet(f"'{t}' values", node)
    raise not_yet(f"values of type '{t}'", node)


def flatten(v: Any) -> list:
    """A nested tuple/list of constant values as a flat list."""
    if isinstance(v, (tuple, list)):
        return [x for item in v for x in flatten(item)]
    return [v]


def broadcast_const(const: list | None, n: int) -> list | None:
    """Constant leaves for n components: a scalar constant repeated, None kept."""
    if const is None:
        return None
    return const * n if len(const) == 1 and n > 1 else const
