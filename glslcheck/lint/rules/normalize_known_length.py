"""normalize() of a vector whose length the function already knows.

## What it does
Reports `normalize(v)` when the length of `v` is already known in that function:

* **a sphere normal**: `v` is `p - c` (written there, or a local variable last assigned
  `p - c` on every path to the call) where `p` provably lies on the sphere of center `c`, so
  `|p - c|` is its radius. The rule follows the values, not the names: `p` is the ray point
  `o + t * d` and `t` the result of a user function that intersects a ray with a sphere (it
  computes `oc = origin - center`, `dot(oc, direction)`, `radius * radius` and a `sqrt`),
  called with that same origin `o`, direction `d` and center `c`; or `p` is
  `c + r * normalize(u)`. Values are followed through local variables assigned on every path,
  struct fields (`s.center = ...`, `Sphere(c, r)`) and literal spheres
  (`hit_sphere(vec3(0, 0, -1), 0.5, ...)`). When any link is unsure (a point passed in as a
  parameter, a light's center, the ray origin, another sphere's hit), the rule is silent.
  A hand-written normalize (a function returning `v / length(v)` or
  `v * inversesqrt(dot(v, v))`) counts as normalize here;
* **a length already computed**: `length(v)` (or `distance(a, b)` for `v = a - b`) was
  evaluated earlier on every path to the call with no write to `v`'s variables in between:
  divide by that length;
* **a squared length already computed**: `dot(v, v)` likewise: multiply by its
  `inversesqrt` (the light-vector idiom of Lab 4: one `inversesqrt` gives both the unit vector
  and the distance).

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

from typing import TYPE_CHECKING, Any, Iterator

from ... import ast as A
from ... import types as T
from ...analysis import builtin_call, calls_in, program_facts
from ...check.model import Symbol
from ...diagnostics import Diagnostic
from ._text import text, wrap

if TYPE_CHECKING:
    from ..engine import LintContext

NAME = "normalize-known-length"
PENALTY = 1
SEVERITY = "warning"
NEEDS = "ast"

_MAX_DEPTH = 8  # assignments and fields followed back from one value


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    for fn in program_facts(ctx.model).in_file(ctx.path):
        normalizes = [(n, n.args[0]) for n in fn.nodes if type(n) is A.Call and _is_normalize(fn, n)]
        normalizes += [(n, v) for n in fn.nodes if (v := _written_out(fn, n)) is not None]
        if not normalizes:
            continue
        known = [c for c in calls_in(fn, "length", "distance", "dot") if _measured_key(fn, c) is not None]
        for node, v in sorted(normalizes, key=lambda nv: fn.enter[id(nv[0])]):
            found = None
            if builtin_call(fn.model, node, "normalize"):
                found = _already_measured(fn, node, known)
            found = found or _sphere_normal(fn, node, v)
            if found is not None:
                message, fix = found
                yield Diagnostic(message, node.loc, help=fix)


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
    if len(stmts) != 1 or type(stmts[0]) is not A.Return or stmts[0].value is None or len(d.proto.params) != 1:
        return False
    v, param = stmts[0].value, d.proto.params[0].name

    def is_param(e) -> bool:
        return type(e) is A.Identifier and e.name == param

    def call_of(e, name: str, n: int) -> bool:
        return type(e) is A.Call and e.callee == name and len(e.args) == n and all(is_param(a) for a in e.args)

    if call_of(v, "normalize", 1):
        return True
    if type(v) is A.Binary and v.op == "/" and is_param(v.left):
        return call_of(v.right, "length", 1)
    if type(v) is A.Binary and v.op == "*" and is_param(v.left):
        r = v.right
        return (type(r) is A.Call and r.callee == "inversesqrt" and len(r.args) == 1 and call_of(r.args[0], "dot", 2)) \
            or (type(r) is A.Binary and r.op == "/" and _number(r.left) == 1.0 and call_of(r.right, "length", 1))
    return False


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
        if e.op == "/" and builtin_call(model, m, "length") and fn.key(m.args[0]) == fn.key(v):
            return v
        if e.op == "/" and builtin_call(model, m, "sqrt"):
            m = m.args[0]
        elif not (e.op == "*" and builtin_call(model, m, "inversesqrt")):
            continue
        else:
            m = m.args[0]
        if builtin_call(model, m, "dot") and fn.key(m.args[0]) == fn.key(v) == fn.key(m.args[1]):
            return v
    return None


def _number(e) -> float | None:
    return float(e.value) if type(e) in (A.FloatLiteral, A.IntLiteral) else None


def _measured_key(fn, c: A.Call) -> Any:
    """The key of the vector whose (squared) length the call computes."""
    if c.callee == "length" and len(c.args) == 1:
        return fn.key(c.args[0])
    if c.callee == "distance" and len(c.args) == 2:
        return ("B", "-", fn.key(c.args[0]), fn.key(c.args[1]))
    if c.callee == "dot" and len(c.args) == 2 and fn.key(c.args[0]) == fn.key(c.args[1]):
        return fn.key(c.args[0])
    return None


def _stored_in(fn, e) -> str | None:
    parent = fn.parent.get(id(e))
    if type(parent) is A.Declarator and parent.init is e:
        return parent.name
    return None


def _already_measured(fn, call: A.Call, known: list) -> tuple[str, str] | None:
    v = call.args[0]
    kv = fn.key(v)
    ops = fn.operands(v)
    for c in known:
        if _measured_key(fn, c) != kv or not fn.dominates(c, call) or fn.written_between(c, call, ops):
            continue
        name = _stored_in(fn, c)
        value = name or text(c)
        if c.callee == "dot":
            return (f"normalize() recomputes dot(v, v), already computed at line {c.loc.line}",
                    f"multiply by its reciprocal square root: {wrap(v)} * inversesqrt({value})")
        return (f"normalize() of a vector whose length is already computed at line {c.loc.line}",
                f"divide by that length: {wrap(v)} / {value if name else wrap(c)}")
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


def _sphere_normal(fn, call, v) -> tuple[str, str] | None:
    """`normalize(p - c)` where p provably lies on the sphere of center c: p is a ray's point
    `o + t * d` with t the hit of that ray with that sphere (a user function that intersects a
    sphere, called with the same origin, direction and center), or `c + r * normalize(u)`.
    Values are followed through local assignments and struct fields; anything else is unsure,
    and unsure is silent."""
    diff = _difference(fn, v)
    if diff is None or not getattr(fn.model.type_of(diff), "is_vector", False):
        return None
    center = _vkey(fn, diff.right)
    point = _resolve(fn, _unswizzle(diff.left, fn.model))
    radius, why = _on_sphere(fn, point, center)
    if radius is None:
        return None
    if builtin_call(fn.model, call, "normalize"):
        name = "normalize()"
    elif type(call) is A.Call:
        name = f"{call.callee}() (a normalize)"
    else:
        name = f"'{text(call)}' (a normalize written out)"
    return (f"{name} of {text(diff)}, {why}: its length is the radius, {radius}",
            f"divide by the radius: {wrap(v)} / {radius}")


def _unswizzle(e, model):
    """`p.xyz` -> `p`: a point's first components stand for the point; so does `vec3(p)` of a
    wider vector `p` (a constructor keeps the first components)."""
    while True:
        if type(e) is A.Field and e.name in ("xyz", "rgb", "stp", "xy"):
            e = e.base
        elif type(e) is A.Call and len(e.args) == 1 and e.callee in ("vec2", "vec3") \
                and getattr(model.type_of(e.args[0]), "is_vector", False):
            e = e.args[0]
        else:
            return e


def _resolve(fn, e, depth: int = 0):
    """The expression a local variable (or a local struct's field) holds at `e`, followed back
    through assignments on every path; `e` itself when that is not sure."""
    while depth < _MAX_DEPTH:
        depth += 1
        e = _unswizzle(e, fn.model)
        if type(e) is A.Identifier:
            sym = fn.model.symbol_of(e)
            value = fn.reaching_value(e, sym) if sym is not None and sym.kind == "local" else None
        elif type(e) is A.Field and not fn.model.is_swizzle(e) and type(e.base) is A.Identifier:
            value = _field_value(fn, e.base, e.name, e)
        else:
            value = None
        if value is None:
            return e
        e = value
    return e


def _field_value(fn, base: A.Identifier, name: str, at) -> Any:
    """The value last stored in the field `name` of the local struct `base` before `at`: a
    `base.name = value` or a constructor `S(...)` assigned on every path, no write between."""
    sym = fn.model.symbol_of(base)
    pos = fn.enter.get(id(at))
    if sym is None or sym.kind != "local" or pos is None:
        return None
    for w in reversed([w for w in fn.writes_to(sym) if w.pos < pos]):
        node = w.node
        if w.kind == "part" and type(node) is A.Assignment and type(node.target) is A.Field \
                and type(node.target.base) is A.Identifier:
            if node.target.name != name:
                continue  # another field: this one is unchanged
            return node.value if node.op == "=" and fn.dominates(node, at) else None
        if w.kind in ("=", "init") and type(w.value) is A.Call and fn.dominates(node, at):
            st = fn.model.type_of(w.value)
            if isinstance(st, T.StructType) and w.value.callee == st.name:
                names = [f for f, _ in st.fields]
                if name in names and len(w.value.args) == len(names):
                    return w.value.args[names.index(name)]
        return None
    return None


def _vkey(fn, e, depth: int = 0) -> Any:
    """A key of the value of `e`: variables and fields replaced by what they hold when sure."""
    e = _resolve(fn, e)
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


def _on_sphere(fn, point, center) -> tuple[str | None, str]:
    """(radius text, how we know) when `point` lies on a sphere whose center's value key is
    `center`; (None, "") when that is not sure."""
    if type(point) is not A.Binary or point.op != "+":
        return None, ""
    for o, m in ((point.left, point.right), (point.right, point.left)):
        if type(m) is not A.Binary or m.op != "*":
            continue
        # c + r * normalize(u): a point at distance r from c
        for r, u in ((m.left, m.right), (m.right, m.left)):
            if _vkey(fn, o) == center and type(_resolve(fn, u)) is A.Call and _is_normalize(fn, _resolve(fn, u)):
                return text(r), f"a point at distance {text(r)} from {text(o)}"
        # o + t * d with t = hit(o, d, sphere)
        for t, d in ((m.left, m.right), (m.right, m.left)):
            hit = _resolve(fn, t)
            if type(hit) is not A.Call:
                continue
            roles = _sphere_hit(fn, hit)
            if roles is None:
                continue
            if roles["center"] == center and roles["origin"] == _vkey(fn, o) and roles["direction"] == _vkey(fn, d):
                return roles["radius"], f"the hit point of the ray with the sphere {hit.callee}() intersects"
    return None, ""


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
        if type(e) is A.Identifier and e.name in params and model.symbol_of(e) is not None \
                and model.symbol_of(e).kind == "param":
            return params.index(e.name), field
        return None

    nodes = list(d.body.walk())
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
    radius = next((root(n.left) for n in nodes if type(n) is A.Binary and n.op == "*" and root(n.left)
                   and root(n.left) == root(n.right) and text(n.left) == text(n.right)), None)
    if radius is None:
        return None
    for holder, (origin, center, value) in diffs.items():
        for n in nodes:
            if type(n) is A.Call and n.callee == "dot" and len(n.args) == 2:
                a, b = n.args
                for x, y in ((a, b), (b, a)):
                    is_oc = (type(x) is A.Identifier and x.name == holder) or (holder is None and x is value)
                    if is_oc and root(y) and root(y) not in (origin, center):
                        direction = root(y)
                        roles = {}
                        for role, r in (("origin", origin), ("direction", direction), ("center", center)):
                            roles[role] = _role_key(fn, call, r)
                        roles["radius"] = _role_text(fn, call, radius)
                        if None not in roles.values():
                            return roles
    return None


def _role_arg(fn, call: A.Call, r):
    index, field = r
    if index >= len(call.args):
        return None
    arg = call.args[index]
    if field is None:
        return arg
    base = _resolve(fn, arg)
    if type(base) is A.Identifier:
        value = _field_value(fn, base, field, call)
        if value is not None:
            return value
    if type(base) is A.Call:  # a constructor S(center, radius) passed in place
        st = fn.model.type_of(base)
        if isinstance(st, T.StructType) and base.callee == st.name:
            names = [f for f, _ in st.fields]
            if field in names and len(base.args) == len(names):
                return base.args[names.index(field)]
    return ("field", arg, field)


def _role_key(fn, call: A.Call, r) -> Any:
    e = _role_arg(fn, call, r)
    if e is None:
        return None
    if isinstance(e, tuple):
        _, arg, field = e
        return (".", field, _vkey(fn, arg))
    return _vkey(fn, e)


def _role_text(fn, call: A.Call, r) -> str | None:
    e = _role_arg(fn, call, r)
    if e is None:
        return None
    if isinstance(e, tuple):
        _, arg, field = e
        return f"{text(arg)}.{field}"
    value = _resolve(fn, e)
    return text(value) if type(value) in (A.FloatLiteral, A.IntLiteral) else text(e)
