"""normalize() of a vector whose length the function already knows.

## What it does
Reports `normalize(v)` when the length of `v` is already known in that function:

* **a sphere normal**: `v` is `p - c` (written there, or a local variable last assigned
  `p - c` on every path to the call) where `c` is a sphere's center: the `center`/`centre`
  field of a struct that also has a `radius` field (`normalize(p - sphere.center)`), or a
  variable named like `*center*`/`*centre*` in a function that also reads a `*radius*`
  variable. For a point `p` on the sphere, `|p - c|` is the radius: divide by it. The center
  must be the subtracted side (`p - c`): a light vector `normalize(light.center - p)` is not a
  sphere normal, and centers of lights or lamps are never taken for spheres;
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

import re
from typing import Any, Iterator

from ... import ast as A
from ... import types as T
from ...diagnostics import Diagnostic
from ._exprs import builtin_call, calls_in, facts, text, wrap

NAME = "normalize-known-length"
PENALTY = 1
SEVERITY = "warning"
NEEDS = "ast"

_CENTER = re.compile(r"cent(er|re)", re.I)
_RADIUS = re.compile(r"radius|^rad$|^r$", re.I)  # a struct field
_RADIUS_NAME = re.compile(r"radius|^rad$", re.I)  # a variable
_LIGHT = re.compile(r"light|lamp", re.I)


def check(ctx) -> Iterator[Diagnostic]:
    for fn in facts(ctx).in_file(ctx.path):
        normalizes = list(calls_in(fn, "normalize"))
        if not normalizes:
            continue
        known = [c for c in calls_in(fn, "length", "distance", "dot") if _measured_key(fn, c) is not None]
        for call in normalizes:
            if len(call.args) != 1:
                continue
            found = _already_measured(fn, call, known) or _sphere_normal(fn, call)
            if found is not None:
                message, fix = found
                yield Diagnostic(message, call.loc, rule=NAME, severity=SEVERITY, help=fix)


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


def _sphere_normal(fn, call: A.Call) -> tuple[str, str] | None:
    v = call.args[0]
    diff = _difference(fn, v)
    if diff is None or not getattr(fn.model.type_of(diff), "is_vector", False):
        return None
    radius = _sphere_radius(fn, diff.right)
    if radius is None:
        return None
    return (f"normalize() of {text(diff)}, a point on a sphere minus its center: its length is the "
            f"radius",
            f"divide by the radius: {wrap(v)} / {radius}")


def _sphere_radius(fn, c) -> str | None:
    """The radius that goes with the center `c`, as GLSL text, when `c` is a sphere's center."""
    if type(c) is A.Field and _CENTER.search(c.name) and not fn.model.is_swizzle(c):
        st = fn.model.type_of(c.base)
        if not isinstance(st, T.StructType) or _LIGHT.search(st.name) or _LIGHT.search(text(c.base)):
            return None
        field = next((f for f, ft in st.fields if _RADIUS.search(f) and ft == T.FLOAT), None)
        return f"{text(c.base)}.{field}" if field else None
    if type(c) is A.Identifier and _CENTER.search(c.name) and not _LIGHT.search(c.name):
        names = {n.name for n in fn.nodes if type(n) is A.Identifier}
        names |= {p.name for p in fn.definition.proto.params if p.name}
        radii = sorted(n for n in names if _RADIUS_NAME.search(n) and not _LIGHT.search(n))
        if not radii:
            return None
        stem = _CENTER.split(c.name)[0].lower()
        return max(radii, key=lambda r: (r.lower().startswith(stem) and bool(stem), -len(r)))
    return None
