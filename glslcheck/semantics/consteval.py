"""Constant folding for GLSL ES 3.00 constant expressions (spec 4.3.3).

Owns the value representation and the arithmetic on it: a scalar is a Python int / float /
bool, a vector a tuple of scalars, a matrix a tuple of column tuples, an array or a struct a
tuple of its elements. Floats are rounded to IEEE float32 after every operation and ints wrap
to 32 bits, as on a GPU. The checker decides *whether* an expression is constant; this module
only computes values. Anything it cannot compute (division by zero, a built-in it does not
fold) gives `UNKNOWN`: still a constant expression, value not known.
"""

from __future__ import annotations

import math
import struct

from ..language import glsl_types as T

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import Any


class _Unknown:
    __slots__ = ()

    def __repr__(self) -> str:
        return "UNKNOWN"


UNKNOWN = _Unknown()


def f32(x: float) -> float:
    """Round a Python float to the nearest float32 (overflow gives +-inf)."""
    try:
        return struct.unpack("f", struct.pack("f", x))[0]
    except OverflowError:
        return math.inf if x > 0 else -math.inf


def wrap(base: str, v: Any) -> Any:
    """Coerce a Python scalar to the representation of `base`."""
    if base == "float":
        return f32(float(v))
    if base == "bool":
        return bool(v)
    if isinstance(v, float):
        if math.isnan(v) or math.isinf(v):
            return 0
        v = int(v)  # truncation toward zero
    v = int(v) & 0xFFFFFFFF
    if base == "int" and v >= 0x80000000:
        v -= 1 << 32
    return v


def flatten(t: T.Type, v: Any) -> list[Any]:
    """The components of a scalar/vector/matrix value, column-major."""
    if t.is_scalar:
        return [v]
    if t.is_vector:
        return list(v)
    return [c for col in v for c in col]


def build(t: T.Type, comps: list[Any]) -> Any:
    """A value of scalar/vector/matrix type `t` from its components (column-major)."""
    base = t.base
    assert base is not None  # a scalar, vector or matrix type has a base
    comps = [wrap(base, c) for c in comps]
    if t.is_scalar:
        return comps[0]
    if t.is_vector:
        return tuple(comps)
    r = t.rows
    return tuple(tuple(comps[c * r : (c + 1) * r]) for c in range(t.cols))


def known(*values: Any) -> bool:
    return all(_known(v) for v in values)


def _known(v: Any) -> bool:
    if v is UNKNOWN or v is None:
        return False
    if isinstance(v, tuple):
        return all(_known(x) for x in v)
    return True


# ---------------------------------------------------------------------------------------------
# Operators


def _idiv(a: int, b: int) -> int:
    q = abs(a) // abs(b)
    return q if (a >= 0) == (b >= 0) else -q


def _scalar_op(op: str, base: str, a: Any, b: Any) -> Any:
    if op == "+":
        return a + b
    if op == "-":
        return a - b
    if op == "*":
        return a * b
    if op == "/":
        if base == "float":
            if b == 0:
                if a == 0 or math.isnan(a):
                    return math.nan
                return math.copysign(math.inf, a) * math.copysign(1.0, b)
            return a / b
        if b == 0:
            raise ZeroDivisionError
        return _idiv(a, b)
    if op == "%":
        if b == 0:
            raise ZeroDivisionError
        return a - b * _idiv(a, b)
    if op == "&":
        return a & b
    if op == "|":
        return a | b
    if op == "^":
        return a ^ b
    if op == "<<":
        return a << (b & 31)
    if op == ">>":
        return a >> (b & 31)
    raise ValueError(op)


def _guarded(fn: Callable[..., Any]) -> Callable[..., Any]:
    """A folding function gives UNKNOWN instead of failing on a value it did not expect."""

    def wrapped(*args: Any) -> Any:
        try:
            return fn(*args)
        except (TypeError, IndexError, ValueError, ZeroDivisionError, OverflowError):
            return UNKNOWN

    wrapped.__name__ = fn.__name__
    wrapped.__doc__ = fn.__doc__
    return wrapped


@_guarded
def binary(op: str, lt: T.Type, rt: T.Type, result: T.Type, a: Any, b: Any) -> Any:
    if not known(a, b):
        return UNKNOWN
    try:
        if op in ("<", ">", "<=", ">="):
            return {"<": a < b, ">": a > b, "<=": a <= b, ">=": a >= b}[op]
        if op == "==":
            return a == b
        if op == "!=":
            return a != b
        if op == "&&":
            return a and b
        if op == "||":
            return a or b
        if op == "^^":
            return a != b
        if op == "*" and (lt.is_matrix or rt.is_matrix) and not (lt.is_scalar or rt.is_scalar):
            return _linear_multiply(lt, rt, result, a, b)
        la, lb = flatten(lt, a), flatten(rt, b)
        n = max(len(la), len(lb))
        if len(la) == 1:
            la = la * n
        if len(lb) == 1:
            lb = lb * n
        base = result.base
        assert base is not None  # the result of arithmetic is a scalar, vector or matrix
        return build(result, [_scalar_op(op, base, x, y) for x, y in zip(la, lb)])
    except (ZeroDivisionError, OverflowError, ValueError):
        return UNKNOWN


def _linear_multiply(lt: T.Type, rt: T.Type, result: T.Type, a: Any, b: Any) -> Any:
    if lt.is_vector:  # v * M: result[c] = dot(v, M[c])
        return build(result, [sum(x * y for x, y in zip(a, col)) for col in b])
    if rt.is_vector:  # M * v: result[r] = sum_c M[c][r] * v[c]
        return build(result, [sum(a[c][r] * b[c] for c in range(lt.cols)) for r in range(lt.rows)])
    out = []
    for k in range(rt.cols):
        for r in range(lt.rows):
            out.append(sum(a[c][r] * b[k][c] for c in range(lt.cols)))
    return build(result, out)


@_guarded
def unary(op: str, t: T.Type, v: Any) -> Any:
    if not known(v):
        return UNKNOWN
    if op == "+":
        return v
    if op == "!":
        return not v
    comps = flatten(t, v)
    if op == "-":
        return build(t, [-c for c in comps])
    if op == "~":
        return build(t, [~c for c in comps])
    return UNKNOWN


# ---------------------------------------------------------------------------------------------
# Constructors, selection


@_guarded
def construct(target: T.Type, arg_types: list[T.Type], values: list[Any]) -> Any:
    if not known(*values):
        return UNKNOWN
    if target.is_struct or target.is_array:
        return tuple(values)
    if target.is_matrix and len(values) == 1 and (arg_types[0].is_scalar or arg_types[0].is_matrix):
        src_t, src = arg_types[0], values[0]
        out = []
        for c in range(target.cols):
            for r in range(target.rows):
                if src_t.is_scalar:
                    out.append(float(src) if c == r else 0.0)
                elif c < src_t.cols and r < src_t.rows:
                    out.append(src[c][r])
                else:
                    out.append(1.0 if c == r else 0.0)
        return build(target, out)
    comps: list[Any] = []
    for t, v in zip(arg_types, values):
        comps.extend(flatten(t, v))
    if len(comps) == 1 and not target.is_scalar:
        comps = comps * target.size
    base = target.base
    assert base is not None  # constructed from components: a scalar, vector or matrix
    comps = [_convert(c, base) for c in comps[: target.size]]
    return build(target, comps)


def _convert(c: Any, base: str) -> Any:
    if base == "bool":
        return c != 0
    if base == "float":
        return float(c)
    if isinstance(c, bool):
        return int(c)
    if isinstance(c, float):
        if base == "uint" and c < 0:
            return wrap("uint", int(c))
        return int(c)
    return c


@_guarded
def swizzle(v: Any, indices: tuple[int, ...]) -> Any:
    if not known(v):
        return UNKNOWN
    if len(indices) == 1:
        return v[indices[0]]
    return tuple(v[i] for i in indices)


@_guarded
def index(v: Any, i: Any) -> Any:
    if not known(v, i):
        return UNKNOWN
    try:
        return v[i]
    except (IndexError, TypeError):
        return UNKNOWN


# ---------------------------------------------------------------------------------------------
# Built-in functions with constant arguments (ES 3.00: constant expressions). Component-wise
# functions fold through a scalar function; the others are listed one by one.


def _safe(fn: Callable[..., float]) -> Callable[..., float]:
    def wrapped(*args: float) -> float:
        try:
            return fn(*args)
        except (ValueError, ZeroDivisionError):
            return math.nan
        except OverflowError:
            return math.inf

    return wrapped


def _sign(x: Any) -> Any:
    return (x > 0) - (x < 0) if isinstance(x, int) else float((x > 0) - (x < 0))


def _fract(x: float) -> float:
    return x - math.floor(x)


def _smoothstep(e0: float, e1: float, x: float) -> float:
    t = min(max((x - e0) / (e1 - e0), 0.0), 1.0)
    return t * t * (3.0 - 2.0 * t)


_COMPONENTWISE: dict[str, Callable[..., Any]] = {
    "radians": lambda x: x * math.pi / 180.0,
    "degrees": lambda x: x * 180.0 / math.pi,
    "sin": math.sin,
    "cos": math.cos,
    "tan": math.tan,
    "asin": math.asin,
    "acos": math.acos,
    "sinh": math.sinh,
    "cosh": math.cosh,
    "tanh": math.tanh,
    "asinh": math.asinh,
    "acosh": math.acosh,
    "atanh": math.atanh,
    "pow": math.pow,
    "exp": math.exp,
    "log": math.log,
    "exp2": lambda x: 2.0**x,
    "log2": math.log2,
    "sqrt": math.sqrt,
    "inversesqrt": lambda x: 1.0 / math.sqrt(x),
    "abs": abs,
    "sign": _sign,
    "floor": math.floor,
    "ceil": math.ceil,
    "trunc": math.trunc,
    "fract": _fract,
    "round": lambda x: math.floor(x + 0.5),
    "roundEven": round,
    "mod": lambda x, y: x - y * math.floor(x / y),
    "min": min,
    "max": max,
    "clamp": lambda x, lo, hi: min(max(x, lo), hi),
    "mix": lambda x, y, a: x * (1.0 - a) + y * a if not isinstance(a, bool) else (y if a else x),
    "step": lambda e, x: 0.0 if x < e else 1.0,
    "smoothstep": _smoothstep,
}


@_guarded
def builtin(name: str, param_types: tuple[T.Type, ...], result: T.Type, values: list[Any]) -> Any:
    """The value of built-in `name` on constant arguments, or UNKNOWN."""
    if not known(*values):
        return UNKNOWN
    try:
        fn = _COMPONENTWISE.get(name)
        if name == "atan":
            fn = math.atan2 if len(values) == 2 else math.atan
        if fn is not None and (result.is_scalar or result.is_vector):
            lists = [flatten(t, v) for t, v in zip(param_types, values)]
            n = result.size
            lists = [x * n if len(x) == 1 else x for x in lists]
            return build(result, [_safe(fn)(*args) for args in zip(*lists)])
        fl = [flatten(t, v) for t, v in zip(param_types, values)]
        if name == "dot":
            return build(result, [sum(x * y for x, y in zip(fl[0], fl[1]))])
        if name == "length":
            return build(result, [math.sqrt(sum(x * x for x in fl[0]))])
        if name == "distance":
            return build(result, [math.sqrt(sum((x - y) ** 2 for x, y in zip(fl[0], fl[1])))])
        if name == "normalize":
            norm = math.sqrt(sum(x * x for x in fl[0]))
            return build(result, [x / norm if norm else math.nan for x in fl[0]])
        if name == "cross":
            (a0, a1, a2), (b0, b1, b2) = fl
            return build(result, [a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0])
        if name in ("any", "all"):
            return (any if name == "any" else all)(fl[0])
        if name == "not":
            return build(result, [not x for x in fl[0]])
    except (ValueError, ZeroDivisionError, OverflowError, TypeError):
        return UNKNOWN
    return UNKNOWN
