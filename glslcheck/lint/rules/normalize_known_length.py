"""normalize() of a vector whose length the function already knows.

## What it does
Reports `normalize(v)` when the length of `v` is already known in that function:

* **a sphere normal**: `v` is `p - c` (written there, or a local variable last assigned
  `p - c` on every path to the call) where `p` provably lies on the sphere of center `c`, so
  `|p - c|` is its radius. The rule follows the values, not the names: `p` is the ray point
  `o + t * d` and `t` the result of a user function that intersects a ray with a sphere (it
  computes `oc = origin - center`, `dot(oc, direction)`, `radius * radius` and a `sqrt`),
  called with that same origin `o`, direction `d` and center `c`; or `p` is
  `c + r * normalize(u)`; or `p` is the procedural sphere's point
  `c + vec3(dp.xy, sqrt(r * r - dot(dp.xy, dp.xy)))` (however the squares are written:
  `rSq - lSq`, `dp.z = ...`, `lenSq(dp.xy)`). Values are followed through local variables
  assigned on every path (while what they were computed from is unchanged), vector components
  (`dp.z = ...`), struct fields (`s.center = ...`, `Sphere(c, r)`), literal spheres
  (`hit_sphere(vec3(0, 0, -1), 0.5, ...)`) and across calls: an `in` parameter the function
  never writes, of a function called from one place only, holds that call's argument (for the
  values that make the point and the radius; two parameters are never taken for one value because
  the caller passes the same argument to both). When any
  link is unsure (a function called from several places, a light's center, the ray origin,
  another sphere's hit, a squared length taken before the vector changed), the rule is silent.
  A hand-written normalize counts as normalize here: a function of one vector returning
  `v / length(v)` or `v * inversesqrt(dot(v, v))`, or any straight-line body of arithmetic,
  square roots and helpers of the same kind that computes `v / |v|` (`float s = 1.0 /
  vecLen(v); v.x *= s; v.y *= s; v.z *= s; return v;`, `vec3(v.x / l, v.y / l, v.z / l)`):
  such a body is an algebraic function of `v`, and the rule evaluates it at three generic
  vectors, where a function that is not v / |v| does not agree with it;
* **a length already computed**: `length(v)` (or `distance(a, b)` for `v = a - b` or
  `b - a`, or `sqrt` of v's squared components written out, `sqrt(sq(v.x) + sq(v.y) + ...)`)
  was evaluated earlier on every path to the call with no write to `v`'s variables in between:
  divide by that length;
* **a squared length already computed**: `dot(v, v)` likewise: multiply by its
  `inversesqrt` (the light-vector idiom of Lab 4: one `inversesqrt` gives both the unit vector
  and the distance);
* **a length of 1**: `v` is already of unit length (`_unit_vectors.py`: a normalize, through a
  local too, a helper returning one, `reflect()` of one about another): drop the normalize.

A length computed after the normalize (`L = normalize(light - p); d = distance(light, p);`) is
not known at the normalize: that is `length-computed-twice`.

Vectors are compared by value: a local variable stands for the value assigned to it on every
path (`vec3 d = vec3(p.x - c.x, p.y - c.y, p.z - c.z)` is `p - c`), and `v` and `-v` have the
same length.

## Why is this bad?
The course's coding standards: "Use the most efficient methods (-1 per inefficient/unnecessary
practices)", and the Lab 4 hint for the sphere normal: "What is the most efficient way to
normalize this particular vector? Hint: it's not the 'normalize' function...". `normalize`
computes `v * inversesqrt(dot(v, v))`: a dot product and a reciprocal square root that the
radius, or the value already at hand, makes unnecessary.

## Example
```glsl
vec3 position = ray.origin + t * ray.direction;
vec3 normal = normalize(position - sphere.center);
```

## Use instead
```glsl
vec3 position = ray.origin + t * ray.direction;
vec3 normal = (position - sphere.center) / sphere.radius; // |p - c| is the radius on the surface
```
"""

from __future__ import annotations

import math
import re

from ...base.diagnostics import Diagnostic
from ...frontend import syntax as A
from ...language import glsl_types as T
from ...semantics.analysis import builtin_call, calls_in, program_facts
from ...semantics.model import Constructor, Symbol
from ..fixes import Fix, Fixable
from ..fixes.build import facts_of, fit, node_text, operand_text, replace
from ._text import text, wrap
from ._unit_vectors import normalized_again

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator
    from typing import Any

    from ..engine import LintContext

NAME = "normalize-known-length"
PENALTY = 1
STANDARD = "efficiency"
SEVERITY = "warning"
NEEDS = "ast"

_MAX_DEPTH = 8  # assignments and fields followed back from one value


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    for fn in program_facts(ctx.model).in_file(ctx.path):
        normalizes = [(n, n.args[0]) for n in normalize_calls(fn)]
        normalizes += [(n, v) for n in fn.nodes if (v := _written_out(fn, n)) is not None]
        if not normalizes:
            continue
        known = measured_lengths(fn)
        for node, v in sorted(normalizes, key=lambda nv: fn.enter[id(nv[0])]):
            found = None
            if type(node) is A.Call:  # normalize(), or a user function that is one
                found = measured(fn, node, known, after=False)
            found = found or _sphere_normal(fn, node, v)
            if found is not None:
                message, fix, by = found
                yield Fixable(message, node.loc, help=fix, fix=_fix(ctx, node, v, by))
            elif type(node) is A.Call and (again := normalized_again(fn, node)) is not None:
                yield Diagnostic(again[0], node.loc, help=again[1])


_NAME_OR_NUMBER = r"[A-Za-z_][\w.]*|[0-9][0-9.eE+\-]*"


def _fix(ctx: LintContext, node, v, by: tuple[str, str] | None) -> Fix | None:
    """`v / r` (the radius, or the length already held in a variable) or `v * inversesqrt(s)`
    (the squared length held in a variable) in place of the normalize."""
    import re

    fn = facts_of(ctx, node)
    if by is None or fn is None:
        return None
    how, value = by
    if value.endswith("...") or node_text(ctx, node) is None:
        return None  # a radius too long to name here, or a normalize from a macro
    vt = operand_text(ctx, v, 14)
    if vt is None:
        return None
    if how == "inversesqrt":
        new = f"{vt} * inversesqrt({value})"
    else:
        new = f"{vt} / {value if re.fullmatch(_NAME_OR_NUMBER, value) else f'({value})'}"
    return Fix(
        f"replace the normalize with {new}", ctx.path, (replace(node, fit(fn, node, new, 14)),)
    )


def normalize_calls(fn) -> list[A.Call]:
    """The calls in a function that normalize their one vector: normalize(v), or a user
    function that returns its argument normalized."""
    return [n for n in fn.nodes if type(n) is A.Call and _is_normalize(fn, n)]


def measured_lengths(fn) -> list[tuple[A.Call, tuple[str, Any, frozenset]]]:
    """The calls in a function that measure a vector, each with what it measures
    (_measured_key): length, distance, dot(v, v), sqrt of a squared length written out."""
    return [
        (c, m)
        for c in calls_in(fn, "length", "distance", "dot", "sqrt")
        if (m := _measured_key(fn, c)) is not None
    ]


def _is_normalize(fn, call: A.Call) -> bool:
    """normalize(v), or a user function of one vector that returns its argument normalized
    (`v / length(v)`, `v * inversesqrt(dot(v, v))`, `normalize(v)`)."""
    if len(call.args) != 1:
        return False
    if builtin_call(fn.model, call, "normalize"):
        return True
    target = fn.model.call_target(call)
    d = getattr(target, "node", None)
    if not isinstance(target, Symbol) or not isinstance(d, A.FunctionDefinition) or d.body is None:
        return False
    stmts = [st for st in d.body.stmts]
    if _computes_normalize(fn.model, d):
        return True
    if (
        len(stmts) != 1
        or type(stmts[0]) is not A.Return
        or stmts[0].value is None
        or len(d.proto.params) != 1
    ):
        return False
    v, param = stmts[0].value, d.proto.params[0].name

    def is_param(e) -> bool:
        return type(e) is A.Identifier and e.name == param

    def call_of(e, name: str, n: int) -> bool:
        return (
            type(e) is A.Call
            and e.callee == name
            and len(e.args) == n
            and all(is_param(a) for a in e.args)
        )

    if call_of(v, "normalize", 1):
        return True
    if type(v) is A.Binary and v.op == "/" and is_param(v.left):
        return call_of(v.right, "length", 1)
    if type(v) is A.Binary and v.op == "*" and is_param(v.left):
        r = v.right
        return (
            type(r) is A.Call
            and r.callee == "inversesqrt"
            and len(r.args) == 1
            and call_of(r.args[0], "dot", 2)
        ) or (
            type(r) is A.Binary
            and r.op == "/"
            and _number(r.left) == 1.0
            and call_of(r.right, "length", 1)
        )
    return False


# Three generic vectors a hand-written normalize is evaluated at (see _computes_normalize)
_PROBES = (
    (0.6180339, -1.4142136, 2.7182818, 0.5772157),
    (-2.2360680, 0.3010300, 1.7320508, -0.6931472),
    (1.2020569, 3.1415927, -0.4342945, 1.6487213),
)
# Components of order 1 computed in doubles by a few operations agree with v / |v| to about
# 1e-15 when the function is a normalize; anything else misses by far more than this
_AGREE = 1e-9
_SWIZZLE = {c: i for names in ("xyzw", "rgba", "stpq") for i, c in enumerate(names)}


def _computes_normalize(model, d: A.FunctionDefinition) -> bool:
    """Whether a user function of one `vecN` returns it normalized however it is written
    (`v / sqrt(v.x * v.x + ...)`, `s = 1.0 / len(v); v.x *= s; ...; return v;`, helpers for the
    length). Its body must be straight-line arithmetic, square roots and pure helpers of the
    same kind: such a function is algebraic, and one equal to v / |v| at three generic vectors
    is v / |v| (a different one of this size meets it there with probability zero)."""
    params = d.proto.params
    n = _VEC_SIZE.get(params[0].type.name or "") if len(params) == 1 else None
    if n is None or d.proto.return_type.name != params[0].type.name:
        return False
    for probe in _PROBES:
        v = list(probe[:n])
        got = _run(model, d, [v], 0)
        norm = math.sqrt(sum(x * x for x in v))
        if got is None or len(got) != n or any(abs(g - x / norm) > _AGREE for g, x in zip(got, v)):
            return False
    return True


_VEC_SIZE = {"vec2": 2, "vec3": 3, "vec4": 4}


def _run(model, d: A.FunctionDefinition, args: list, depth: int) -> list[float] | None:
    """The value a straight-line function returns for `args` (lists of floats), or None when
    its body is anything else (a branch, a loop, an out parameter, a call it cannot follow)."""
    if depth > 3 or d.body is None or len(args) != len(d.proto.params):
        return None
    env: dict[str, list[float] | None] = {}
    for p, a in zip(d.proto.params, args):
        if p.name is None or {"out", "inout"} & set(p.qualifiers) or p.array is not None:
            return None
        env[p.name] = a
    for st in d.body.stmts:
        if type(st) is A.Return:
            return _eval(model, st.value, env, depth) if st.value is not None else None
        if type(st) is A.DeclarationStatement and type(st.decl) is A.VariableDeclaration:
            for dc in st.decl.declarators:
                if dc.array is not None:
                    return None
                env[dc.name] = _eval(model, dc.init, env, depth) if dc.init is not None else None
        elif type(st) is A.ExpressionStatement and type(st.expr) is A.Assignment:
            if not _assign(model, st.expr, env, depth):
                return None
        else:
            return None
    return None


def _assign(model, e: A.Assignment, env: dict, depth: int) -> bool:
    """Apply `x = v`, `x op= v` or `x.c op= v` to `env`; False when it cannot."""
    t = e.target
    base = t.base if type(t) is A.Field else t
    if type(base) is not A.Identifier:
        return False
    whole = env.get(base.name)
    if whole is None:  # a variable declared without a value: only `x = v` gives it one
        env[base.name] = _eval(model, e.value, env, depth) if t is base and e.op == "=" else None
        return env[base.name] is not None
    idx = [_SWIZZLE.get(c, 9) for c in t.name] if type(t) is A.Field else list(range(len(whole)))
    if any(i >= len(whole) for i in idx):
        return False
    value = _eval(model, e.value, env, depth)
    if value is None:
        return False
    old = [whole[i] for i in idx]
    new = value if e.op == "=" else _arith(e.op[:-1], old, value)
    if new is None or len(new) not in (1, len(idx)):
        return False
    out = list(whole)
    for k, i in enumerate(idx):
        out[i] = new[k if len(new) > 1 else 0]
    env[base.name] = out
    return True


def _arith(op: str, a: list[float], b: list[float]) -> list[float] | None:
    if len(a) != len(b) and 1 not in (len(a), len(b)):
        return None
    n = max(len(a), len(b))
    a, b = (a * n if len(a) == 1 else a), (b * n if len(b) == 1 else b)
    try:
        if op == "+":
            return [x + y for x, y in zip(a, b)]
        if op == "-":
            return [x - y for x, y in zip(a, b)]
        if op == "*":
            return [x * y for x, y in zip(a, b)]
        if op == "/":
            return [x / y for x, y in zip(a, b)]
    except ZeroDivisionError:
        return None
    return None


def _eval(model, e, env: dict, depth: int) -> list[float] | None:
    """The value of an arithmetic expression over `env` (lists of floats), or None."""
    if type(e) is A.FloatLiteral or type(e) is A.IntLiteral:
        return [float(e.value)]
    if type(e) is A.Identifier:
        return env.get(e.name)
    if type(e) is A.Field:
        v = _eval(model, e.base, env, depth)
        idx = [_SWIZZLE.get(c, 9) for c in e.name]
        return None if v is None or any(i >= len(v) for i in idx) else [v[i] for i in idx]
    if type(e) is A.Unary and e.op in "-+":
        v = _eval(model, e.operand, env, depth)
        return None if v is None else [-x if e.op == "-" else x for x in v]
    if type(e) is A.Binary and e.op in ("+", "-", "*", "/"):
        a, b = _eval(model, e.left, env, depth), _eval(model, e.right, env, depth)
        return None if a is None or b is None else _arith(e.op, a, b)
    if type(e) is not A.Call or e.array is not None:
        return None
    args = [_eval(model, a, env, depth) for a in e.args]
    if any(a is None for a in args):
        return None
    if e.constructor:
        flat = [x for a in args for x in a]  # type: ignore[union-attr]
        n = {"float": 1, **_VEC_SIZE}.get(e.callee)
        if n is None or not flat:
            return None
        return flat * n if len(flat) == 1 else flat[:n] if len(flat) >= n else None
    if builtin_call(model, e, e.callee):
        return _builtin(e.callee, args)  # type: ignore[arg-type]
    target = model.call_target(e)
    body = getattr(target, "node", None)
    if isinstance(target, Symbol) and isinstance(body, A.FunctionDefinition):
        return _run(model, body, args, depth + 1)
    return None


def _builtin(name: str, args: list[list[float]]) -> list[float] | None:
    try:
        if name == "dot" and len(args) == 2 and len(args[0]) == len(args[1]):
            return [sum(x * y for x, y in zip(args[0], args[1]))]
        if len(args) != 1:
            return None
        (a,) = args
        if name == "length":
            return [math.sqrt(sum(x * x for x in a))]
        if name == "sqrt":
            return [math.sqrt(x) for x in a]
        if name == "inversesqrt":
            return [1.0 / math.sqrt(x) for x in a]
        if name == "abs":
            return [abs(x) for x in a]
    except (ValueError, ZeroDivisionError):
        return None
    return None


def _written_out(fn, e) -> Any:
    """`v` when `e` normalizes it by hand: `v / length(v)`, `v / sqrt(dot(v, v))`,
    `v * inversesqrt(dot(v, v))` (either order), with the built-ins; else None."""
    if type(e) is not A.Binary or e.op not in ("/", "*"):
        return None
    pairs = [(e.left, e.right)] if e.op == "/" else [(e.left, e.right), (e.right, e.left)]
    model = fn.model
    for v, m in pairs:
        if not getattr(model.type_of(v), "is_vector", False):
            continue
        if type(m) is not A.Call:  # (builtin_call tells a call of which function)
            continue
        if e.op == "/" and builtin_call(model, m, "length") and fn.key(m.args[0]) == fn.key(v):
            return v
        if e.op == "/" and builtin_call(model, m, "sqrt"):
            m = m.args[0]
        elif not (e.op == "*" and builtin_call(model, m, "inversesqrt")):
            continue
        else:
            m = m.args[0]
        if (
            type(m) is A.Call
            and builtin_call(model, m, "dot")
            and fn.key(m.args[0]) == fn.key(v) == fn.key(m.args[1])
        ):
            return v
    return None


def _number(e) -> float | None:
    return float(e.value) if type(e) in (A.FloatLiteral, A.IntLiteral) else None


def _measured_key(fn, c: A.Call) -> tuple[str, Any, frozenset] | None:
    """("length" | "dot", the length key of the vector, the variables it reads) of a call that
    measures a vector: `length(v)`, `distance(a, b)` (the vector a - b), `dot(v, v)` (its
    squared length) and `sqrt` of a squared length written by hand (`sqrt(x * x + y * y)` of
    v's components, `sqrt(lenSq(v))`); None for any other call."""
    reads: set = set()
    kind, k = "length", None
    if c.callee == "length" and len(c.args) == 1:
        k = _length_key(fn, c.args[0], reads)
    elif c.callee == "distance" and len(c.args) == 2:
        k = _difference_key(fn, c.args[0], c.args[1], reads)
    elif c.callee == "dot" and len(c.args) == 2 and fn.key(c.args[0]) == fn.key(c.args[1]):
        kind, k = "dot", _length_key(fn, c.args[0], reads)
    elif c.callee == "sqrt" and len(c.args) == 1 and not builtin_call(fn.model, c.args[0], "dot"):
        v = _squared_vector(fn, c.args[0])  # (sqrt(dot(v, v)): the dot is taken as the measure)
        k = None if v is None else _length_key(fn, v, reads)
    return None if k is None else (kind, k, frozenset(reads))


def _squared_vector(fn, squared) -> Any:
    """The vector v when `squared` computes the sum of the squares of all of v's components
    (`v.x * v.x + v.y * v.y + v.z * v.z`, `sq(v.x) + ...`, `lenSq(v)`), else None."""
    key = fn.key(squared)
    if key[0] != "+":
        return None
    for n in squared.walk():
        size = getattr(fn.model.type_of(n), "size", None)
        if (
            type(n) in (A.Identifier, A.Field)
            and getattr(fn.model.type_of(n), "is_vector", False)
            and isinstance(size, int)
            and fn.sum_of_squares_key([fn.component_key(n, i) for i in range(size)]) == key
        ):
            return n
    return None


def _components(fn, v, reads: set, depth: int = 0) -> tuple | None:
    """The keys of the components of the vector `v`: a local variable followed to the value
    reaching it, a constructor of scalars to its arguments, a difference or sum of two vectors
    component by component (`vec3(p.x - c.x, ...)` and `p - c` are the same); None when `v` is
    not a vector of known size. The variables the components read are added to `reads`."""
    t = fn.model.type_of(v)
    size = getattr(t, "size", None)
    if not getattr(t, "is_vector", False) or not isinstance(size, int) or depth > _MAX_DEPTH:
        return None
    if type(v) is A.Identifier:
        sym = fn.model.symbol_of(v)
        value = fn.reaching_value(v, sym) if sym is not None and sym.kind == "local" else None
        if value is not None:
            found = _components(fn, value, reads, depth + 1)
            if found is not None:
                return found
    if type(v) is A.Binary and v.op in ("-", "+"):
        left = _components(fn, v.left, reads, depth + 1)
        right = _components(fn, v.right, reads, depth + 1)
        if left is not None and right is not None and len(left) == len(right) == size:
            return tuple(("B", v.op, a, b) for a, b in zip(left, right))
    reads.update(fn.operands(v))
    if (
        type(v) is A.Call
        and len(v.args) == size
        and isinstance(fn.model.call_target(v), Constructor)
        and all(getattr(fn.model.type_of(a), "is_scalar", False) for a in v.args)
    ):
        return tuple(_scalar_key(fn, a) for a in v.args)
    return tuple(fn.component_key(v, i) for i in range(size))


def _scalar_key(fn, e) -> Any:
    """The key of a scalar, a difference of two components compared as the vectors' ones."""
    if type(e) is A.Binary and e.op in ("-", "+"):
        return ("B", e.op, fn.key(e.left), fn.key(e.right))
    return fn.key(e)


def _negated(k) -> Any:
    return ("B", "-", k[3], k[2]) if k[0] == "B" and k[1] == "-" else ("U", "-", k)


def _length_key(fn, v, reads: set) -> Any:
    """A key of |v|: the same for vectors of the same components, and for v and -v (`a - b` and
    `b - a`); None when `v` is not a vector. The variables it reads are added to `reads`."""
    comps = _components(fn, v, reads)
    if comps is None:
        return None
    return frozenset((comps, tuple(_negated(k) for k in comps)))


def _difference_key(fn, a, b, reads: set) -> Any:
    ca, cb = _components(fn, a, reads), _components(fn, b, reads)
    if ca is None or cb is None or len(ca) != len(cb):
        return None
    comps = tuple(("B", "-", x, y) for x, y in zip(ca, cb))
    return frozenset((comps, tuple(_negated(k) for k in comps)))


def _stored_in(fn, e) -> str | None:
    """The local variable `e` is stored in (`float d = e;`, `d = e;`), if any."""
    parent = fn.parent.get(id(e))
    if type(parent) is A.Declarator and parent.init is e:
        return parent.name
    if (
        type(parent) is A.Assignment
        and parent.op == "="
        and parent.value is e
        and type(parent.target) is A.Identifier
    ):
        return parent.target.name
    return None


def measured(fn, call: A.Call, known: list, after: bool) -> tuple[str, str, Any] | None:
    """A length (or squared length) of the vector `call` normalizes computed in the same
    function on the same path: before the normalize (reuse it), or with `after` one computed
    after it with nothing it reads written in between (the length is computed twice: compute it
    once, first, and divide by it). With the message and help, what a fix may write (None: no
    fix). `known` is measured_lengths(fn)."""
    v = call.args[0]
    reads: set = set()
    kv = _length_key(fn, v, reads)
    if kv is None:
        return None
    for c, (kind, k, measured_reads) in known:
        if k != kv or fn.contains(call, c) or fn.contains(c, call):
            continue
        both = reads | measured_reads
        before = fn.dominates(c, call) and not fn.written_between(c, call, both)
        later = not before and fn.dominates(call, c) and not fn.written_between(call, c, both)
        if not (later if after else before):
            continue
        root = fn.parent.get(id(c))
        if kind == "dot" and builtin_call(fn.model, root, "sqrt") and root.args[0] is c:
            c, kind = root, "length"  # sqrt(dot(v, v)): the length, written by hand
        name = _stored_in(fn, c)
        what = "normalize()" if builtin_call(fn.model, call, "normalize") else f"{call.callee}()"
        if after:
            squared = kind == "dot"
            use = f"{wrap(v)} * inversesqrt({name})" if squared else f"{wrap(v)} / {name}"
            return (
                f"{what} computes the length of {text(v)}, and "
                f"{'its square' if squared else 'that length'} is computed again at line "
                f"{c.loc.line}",
                f"compute {name} first and write {use}"
                if name
                else f"compute {text(c)} once, into a local variable before the {what}, and "
                f"{'multiply by its inversesqrt' if squared else 'divide by it'}",
                None,  # the length comes after: no rewrite in place
            )
        value = name or text(c)
        # a fix reads the variable holding the length, when nothing writes it before the call
        held = name is not None and not fn.written_between(
            fn.parent[id(c)], call, [fn.model.symbol_of(fn.parent[id(c)])]
        )
        if kind == "dot":
            return (
                f"{what} recomputes dot(v, v), already computed at line {c.loc.line}",
                f"multiply by its reciprocal square root: {wrap(v)} * inversesqrt({value})",
                ("inversesqrt", name) if held else None,
            )
        return (
            f"{what} of a vector whose length is already computed at line {c.loc.line}",
            f"divide by that length: {wrap(v)} / {value if name else wrap(c)}",
            ("divide", name) if held else None,
        )
    return None


def _difference(fn, v) -> A.Binary | None:
    if type(v) is A.Binary and v.op == "-":
        return v
    if type(v) is A.Identifier:
        sym = fn.model.symbol_of(v)
        if sym is not None and sym.kind == "local":
            value = fn.reaching_value(v, sym)
            if type(value) is A.Binary and value.op == "-":
                return value
    return None


def _sphere_normal(fn, call, v) -> tuple[str, str, Any] | None:
    """`normalize(p - c)` where p provably lies on the sphere of center c: p is a ray's point
    `o + t * d` with t the hit of that ray with that sphere (a user function that intersects a
    sphere, called with the same origin, direction and center), or `c + r * normalize(u)`.
    Values are followed through local assignments and struct fields; anything else is unsure,
    and unsure is silent."""
    diff = _difference(fn, v)
    if diff is None or not getattr(fn.model.type_of(diff), "is_vector", False):
        return None
    center = _vkey(fn, diff.right)
    radius, why = _on_sphere(*_resolve(fn, _unswizzle(diff.left, fn.model)), center, fn)
    if radius is None:
        return None
    if builtin_call(fn.model, call, "normalize"):
        name = "normalize()"
    elif type(call) is A.Call:
        name = f"{call.callee}() (a normalize)"
    else:
        name = f"'{text(call)}' (a normalize written out)"
    return (
        f"{name} of {text(diff)}, {why}: its length is the radius, {radius}",
        f"divide by the radius: {wrap(v)} / {radius}",
        ("divide", radius),
    )


def _unswizzle(e, model):
    """`p.xyz` -> `p`: a point's first components stand for the point; so does `vec3(p)` of a
    wider vector `p` (a constructor keeps the first components)."""
    while True:
        if type(e) is A.Field and e.name in ("xyz", "rgb", "stp", "xy"):
            e = e.base
        elif (
            type(e) is A.Call
            and len(e.args) == 1
            and e.callee in ("vec2", "vec3")
            and getattr(model.type_of(e.args[0]), "is_vector", False)
        ):
            e = e.args[0]
        else:
            return e


def _resolve(
    fn, e, depth: int = 0, params_only: bool = False, across_calls: bool = True
) -> tuple[Any, Any]:
    """(facts, expression): what a local variable, a local struct's field or an `in` parameter
    holds at `e`, followed back through assignments on every path and, for a parameter of a
    function called from one place only, to the argument of that call (in the caller's facts);
    `(fn, e)` itself when that is not sure. With `params_only`, parameters only (a variable of
    the caller then stands for itself, as in the keys of what was resolved fully)."""
    while depth < _MAX_DEPTH:
        depth += 1
        e = _unswizzle(e, fn.model)
        value, where = None, fn
        if type(e) is A.Identifier:
            sym = fn.model.symbol_of(e)
            if sym is not None and sym.kind == "local" and not params_only:
                value = fn.reaching_value(e, sym)
            elif sym is not None and sym.kind == "param" and across_calls:
                where, value = _argument(fn, sym)
        elif params_only:
            pass
        elif type(e) is A.Field and type(e.base) is A.Identifier and fn.model.is_swizzle(e):
            if len(e.name) == 1:  # one component of a local vector: `dp.z = ...`
                value = _field_value(fn, e.base, e.name, e)
        elif type(e) is A.Field and type(e.base) is A.Identifier:
            base = fn.model.symbol_of(e.base)
            if (
                base is not None and base.kind == "param" and across_calls
            ):  # a field of a struct passed in
                arg_fn, arg = _argument(fn, base)
                if arg is not None:
                    arg_fn, arg = _resolve(arg_fn, arg, depth)
                    value, where = _field_in(arg_fn, arg, e.name), arg_fn
            elif base is not None and base.kind != "param":
                value = _field_value(fn, e.base, e.name, e)
        if value is None:
            return fn, e
        fn, e = where, value
    return fn, e


def _argument(fn, sym) -> tuple[Any, Any]:
    """(caller's facts, argument) of an `in` parameter when its function has one call site."""
    found = program_facts(fn.model).argument(fn, sym)
    return found if found is not None else (fn, None)


def _field_in(fn, e, name: str) -> Any:
    """The field `name` of the struct value `e` (a local struct or a constructor), else None."""
    if type(e) is A.Identifier:
        return _field_value(fn, e, name, e)
    if type(e) is A.Call:
        st = fn.model.type_of(e)
        if isinstance(st, T.StructType) and e.callee == st.name:
            names = [f for f, _ in st.fields]
            if name in names and len(e.args) == len(names):
                return e.args[names.index(name)]
    return None


def _field_value(fn, base: A.Identifier, name: str, at) -> Any:
    """The value last stored in the field `name` of the local struct `base` before `at`: a
    `base.name = value` or a constructor `S(...)` assigned on every path, no write between."""
    sym = fn.model.symbol_of(base)
    pos = fn.enter.get(id(at))
    if sym is None or sym.kind != "local" or pos is None:
        return None
    for w in reversed([w for w in fn.writes_to(sym) if w.pos < pos]):
        node = w.node
        if (
            w.kind == "part"
            and type(node) is A.Assignment
            and type(node.target) is A.Field
            and type(node.target.base) is A.Identifier
        ):
            if node.target.name != name:
                if _disjoint(fn, node.target, at):
                    continue  # another field or other components: this one is unchanged
                return None
            if (
                node.op != "="
                or not fn.dominates(node, at)
                or fn.written_between(node, at, fn.operands(node.value) - {sym})
            ):
                return None
            return node.value
        if w.kind in ("=", "init") and type(w.value) is A.Call and fn.dominates(node, at):
            return _field_in(fn, w.value, name)
        return None
    return None


def _disjoint(fn, target: A.Field, at) -> bool:
    """The write `target` leaves the field or components `at` reads alone: another struct field,
    or a swizzle with no component in common (`dp.z = ...` and `dp.xy`)."""
    model = fn.model
    if model.is_swizzle(target) != (type(at) is A.Field and model.is_swizzle(at)):
        return False
    if not model.is_swizzle(target):
        return True
    return not set(model.swizzle_indices(target)) & set(model.swizzle_indices(at))


def _vkey(fn, e, depth: int = 0) -> Any:
    """A key of the value of `e`: variables and fields replaced by what they hold when sure."""
    # within the function only: two parameters stay two values even when the one caller passes
    # the same argument to both (`unsure(s, s)`: the function is written for two spheres)
    fn, e = _resolve(fn, e, across_calls=False)
    if depth > _MAX_DEPTH:
        return fn.key(e)
    t = type(e)
    if t is A.Binary:
        return ("B", e.op, _vkey(fn, e.left, depth + 1), _vkey(fn, e.right, depth + 1))
    if t is A.Call and e.array is None and e.struct_ is None:
        return ("C", e.callee, tuple(_vkey(fn, a, depth + 1) for a in e.args))
    if t is A.Unary:
        return ("U", e.op, _vkey(fn, e.operand, depth + 1))
    return fn.key(e)


def _on_sphere(fn, point, center, home) -> tuple[str | None, str]:
    """(radius text, how we know) when `point` (in the facts `fn`) lies on a sphere whose
    center's value key is `center`; (None, "") when that is not sure. `home` is the function of
    the normalize: the radius is named as it can write it."""
    if type(point) is not A.Binary or point.op != "+":
        return None, ""
    for o, m in ((point.left, point.right), (point.right, point.left)):
        # c + vec3(dp.xy, sqrt(r * r - dot(dp.xy, dp.xy))): the procedural sphere's point
        radius = _procedural_offset(fn, m, home) if _vkey(fn, o) == center else None
        if radius is not None:
            return radius, "a point built on the sphere (center + (dp.xy, sqrt(r^2 - |dp.xy|^2)))"
        # c + r * normalize(u): a point at distance r from c
        for r, u in (
            ((m.left, m.right), (m.right, m.left)) if type(m) is A.Binary and m.op == "*" else ()
        ):
            unit_fn, unit = _resolve(fn, u)
            if _vkey(fn, o) == center and type(unit) is A.Call and _is_normalize(unit_fn, unit):
                return text(r), f"a point at distance {text(r)} from {text(o)}"
        # o + t * d with t = hit(o, d, sphere)
        for t, d in (
            ((m.left, m.right), (m.right, m.left)) if type(m) is A.Binary and m.op == "*" else ()
        ):
            hit_fn, hit = _resolve(fn, t)
            if type(hit) is not A.Call:
                continue
            roles = _sphere_hit(hit_fn, hit)
            if roles is None:
                continue
            if (
                roles["center"] == center
                and roles["origin"] == _vkey(fn, o)
                and roles["direction"] == _vkey(fn, d)
            ):
                return roles[
                    "radius"
                ], f"the hit point of the ray with the sphere {hit.callee}() intersects"
    return None, ""


def _procedural_offset(fn, m, home) -> str | None:
    """The radius (as text) when `m` is `vec3(x, y, sqrt(z))` (or `vec3(v.xy, sqrt(z))`) with z
    the value r * r - (x * x + y * y) (written as `rSq - lSq`, `dp.z = ...`, lenSq(dp.xy), ...):
    an offset of length r. Values are followed as by `_resolve` (across a call too); the squared
    length and x, y must end in the same function's values (else unsure: None)."""
    m_fn, m = _resolve(fn, m)
    if (
        type(m) is not A.Call
        or m.callee != "vec3"
        or not isinstance(m_fn.model.call_target(m), Constructor)
    ):
        return None
    args = m.args
    if len(args) == 3:
        (x_fn, x), (part_fn, y) = (
            _resolve(m_fn, args[0], params_only=True),
            _resolve(m_fn, args[1], params_only=True),
        )
        if x_fn is not part_fn:
            return None
        parts = [part_fn.key(x), part_fn.key(y)]
    elif len(args) == 2 and getattr(m_fn.model.type_of(args[0]), "size", None) == 2:
        part_fn, v = _resolve(m_fn, args[0], params_only=True)
        parts = [part_fn.component_key(v, 0), part_fn.component_key(v, 1)]
    else:
        return None
    root_fn, root = _resolve(m_fn, args[-1])
    if not builtin_call(root_fn.model, root, "sqrt"):
        return None
    z_fn, z = _resolve(root_fn, root.args[0])
    if type(z) is not A.Binary or z.op != "-":
        return None
    sq_fn, sq = _resolve(z_fn, z.right)
    r_fn, r2 = _resolve(z_fn, z.left)
    if sq_fn is not part_fn or sq_fn.key(sq) != part_fn.sum_of_squares_key(parts):
        return None
    if type(r2) is not A.Binary or r2.op != "*" or r_fn.key(r2.left) != r_fn.key(r2.right):
        return None
    # the radius as the normalize's function can write it: its own variable, or a literal
    r = _resolve(r_fn, r2.left, across_calls=r_fn is not home)[1]
    if type(r) in (A.FloatLiteral, A.IntLiteral):
        return text(r)
    return text(r2.left) if r_fn is home else f"sqrt({text(z.left)})"


def _sphere_hit(fn, call: A.Call) -> dict | None:
    """For a call of a user function that intersects a ray with a sphere, the value keys of the
    ray origin, direction and sphere center it was called with, and the radius as text.

    The function is recognised by its data flow: `oc = origin - center` (or the difference
    written in place), `dot(oc, direction)`, `radius * radius` (or `pow(radius, 2.0)`) and a
    `sqrt`, every one of origin, direction, center and radius a parameter or a parameter's
    field."""
    target = fn.model.call_target(call)
    d = getattr(target, "node", None)
    if not isinstance(target, Symbol) or not isinstance(d, A.FunctionDefinition) or d.body is None:
        return None
    params = [p.name for p in d.proto.params]
    model = fn.model

    def root(e):
        """(parameter index, field name or None) of a parameter or a parameter's field."""
        e = _unswizzle(e, model)
        field = None
        if type(e) is A.Field and not model.is_swizzle(e):
            e, field = _unswizzle(e.base, model), e.name
        if (
            type(e) is A.Identifier
            and e.name in params
            and model.symbol_of(e) is not None
            and model.symbol_of(e).kind == "param"
        ):
            return params.index(e.name), field
        return None

    nodes = model.body_nodes(d)
    diffs = {}  # the name holding origin - center (or None for the expression itself)
    for n in nodes:
        value, holder = None, None
        if type(n) is A.Declarator and n.init is not None:
            value, holder = n.init, n.name
        elif type(n) is A.Binary and n.op == "-":
            value = n
        if type(value) is A.Binary and value.op == "-" and root(value.left) and root(value.right):
            diffs[holder] = (root(value.left), root(value.right), value)
    if not diffs or not any(type(n) is A.Call and n.callee == "sqrt" for n in nodes):
        return None
    radius = next(
        (
            root(n.left) or _local_radius(model, d, n.left)
            for n in nodes
            if type(n) is A.Binary
            and n.op == "*"
            and (root(n.left) or _local_radius(model, d, n.left))
            and root(n.left) == root(n.right)
            and text(n.left) == text(n.right)
        ),
        None,
    )
    if radius is None:
        return None
    for holder, (origin, center, value) in diffs.items():
        for n in nodes:
            if type(n) is A.Call and n.callee == "dot" and len(n.args) == 2:
                a, b = n.args
                for x, y in ((a, b), (b, a)):
                    is_oc = (type(x) is A.Identifier and x.name == holder) or (
                        holder is None and x is value
                    )
                    if is_oc and root(y) and root(y) not in (origin, center):
                        direction = root(y)
                        roles = {}
                        for role, r in (
                            ("origin", origin),
                            ("direction", direction),
                            ("center", center),
                        ):
                            roles[role] = _role_key(fn, call, r)
                        roles["radius"] = (
                            _expression_text(call, params, radius)
                            if isinstance(radius, A.Node)
                            else _role_text(fn, call, radius)
                        )
                        if None not in roles.values():
                            return roles
    return None


def _local_radius(model, d: A.FunctionDefinition, e) -> A.Expr | None:
    """The value of a local of the hit function `d` computed from its parameters only, with
    built-ins (`float r = 0.5 + 0.25 * sin(time);`): the radius the caller's arguments make."""
    if type(e) is not A.Identifier:
        return None
    sym = model.symbol_of(e)
    if sym is None or sym.kind != "local":
        return None
    value = program_facts(model).fn(d).reaching_value(e, sym)
    if value is None:
        return None
    todo, names = [value], 0
    while todo:
        n = todo.pop()
        if type(n) is A.Identifier:
            ref = model.symbol_of(n)
            if ref is None or ref.kind != "param":
                return None
            names += 1
        elif type(n) is A.Call and not (
            builtin_call(model, n, n.callee) or isinstance(model.call_target(n), Constructor)
        ):
            return None  # a user function: not followed
        todo.extend(n.children())
    return value if names else None


def _expression_text(call: A.Call, params: list[str | None], value: A.Node) -> str | None:
    """`value` (an expression of the callee's parameters) as the caller writes it: each
    parameter replaced by the argument the call passes."""
    out = text(value)
    for name, arg in zip(params, call.args):
        if name is None:
            continue  # an unnamed parameter: the expression cannot name it
        argument = wrap(arg)  # returned by a function, so that re.sub reads no escapes in it
        out = re.sub(rf"(?<![.\w]){re.escape(name)}\b", lambda _m: argument, out)
    return out if type(value) in (A.Identifier, A.Call, A.Field) else f"({out})"


def _role_arg(fn, call: A.Call, r):
    """(facts, expression) of what the call passes for the role `r` (a parameter, or a field of
    one); (fn, ("field", argument, field)) when the field's value is not known; None."""
    index, field = r
    if index >= len(call.args):
        return None
    arg = call.args[index]
    if field is None:
        return fn, arg
    base_fn, base = _resolve(fn, arg, across_calls=False)  # compared by key: see _vkey
    value = (
        _field_value(fn, base, field, call)
        if base_fn is fn and type(base) is A.Identifier
        else _field_in(base_fn, base, field)
    )
    if value is not None:
        return base_fn, value
    return fn, ("field", arg, field)


def _role_key(fn, call: A.Call, r) -> Any:
    found = _role_arg(fn, call, r)
    if found is None:
        return None
    fn, e = found
    if isinstance(e, tuple):
        _, arg, field = e
        return (".", field, _vkey(fn, arg))
    return _vkey(fn, e)


def _role_text(fn, call: A.Call, r) -> str | None:
    found = _role_arg(fn, call, r)
    if found is None:
        return None
    value_fn, e = found
    index, field = r
    if isinstance(e, tuple) or value_fn is not fn:  # unknown, or known only from the caller:
        arg = call.args[index]  # name it as this function can
        return f"{text(arg)}.{field}" if field else text(arg)
    value = _resolve(fn, e, across_calls=False)[1]
    return text(value) if type(value) in (A.FloatLiteral, A.IntLiteral) else text(e)
