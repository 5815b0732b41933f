"""An operation that gives back its other operand unchanged.

## What it does
Reports a multiply or divide by one (`x * 1.0`, `c * vec4(1.0, 1.0, 1.0, 1.0)`, `x / 1.0`)
and an add or subtract of zero (`v + vec3(0.0)`, `x - 0.0`) whose result is the other operand
itself: the constant, written out as a literal or a constructor of literals, has every
component exactly 1 (or 0), and the other operand already has the result's type. The compound
assignments are the same operations (`uv /= 1.0;`, `p.xy -= vec2(0.0);`): the statement
changes nothing. A named constant (`x * kGain`) is a setting and is not reported.

Likewise `abs`, `max`, `min`, `clamp`, `fract` and `mod` of a value already in their range, as
far as the value analysis knows it (`abs(t)` of `t = fract(...)`, `max(d, 0.0)` of `d =
clamp(x, 0.2, 1.0)`, `fract(uv)` of `uv = fragCoord / iResolution.xy`, in [0, 1)): the call
gives its argument back.

Likewise a mod inside a mod by the same constant (`mod(p.x + mod(p.y, 2.0), 2.0)`, an int's
`(x + y % 2) % 2`, or a local holding `x + y % 2` that is only ever taken `% 2`): the outer mod
gives the same remainder without the inner one. And a float product that multiplies and
divides by the same value (`columns / rows * rows`, `height * width / height`, or through a
local holding a quotient: `ratio * height` with `ratio = width / height`): the two cancel (a
quotient that cancels inside a local's own value is reported where the local is set).

Likewise `mix(a, b, 1.0)` (which is `b`) and `mix(a, b, 0.0)` (`a`), the weight written out,
and a float product by a factor that is zero in every component, written out or a local
holding zero (`vec3 black = vec3(0.0); ... black * mask`): the product is zero whatever the rest
(the same zero factor in a function is one finding naming every place).

The same no-op written again in a function (`time * 1.0` in each of its returns) is one
finding naming every place: one unnecessary practice.

A possible deduction: a literal left at its neutral value may stand for a setting too (a speed
of `1.0`, a white light color), and the compiler folds the operation away. A constant that
widens a scalar to a vector (`t * vec3(1.0)`, the starter's white in `(1.0 - t) * vec3(1.0) + t
* blue`) does something and is not reported; nor is a constant expression (`2.0 * 0.5`).

## Why is this bad?
The course's coding standards: "Use the most efficient methods (-1 per inefficient/unnecessary
practices)". An operation that changes nothing is unnecessary: it is read, and maybe computed,
for nothing.

## Example
```glsl
uv /= 1.0; // zoom
return texture(iChannel0, uv) * vec4(1.0, 1.0, 1.0, 1.0) * diffuse;
```

## Use instead
```glsl
return texture(iChannel0, uv) * diffuse;
```
"""

from __future__ import annotations

from ...base.diagnostics import Diagnostic
from ...frontend import syntax as A
from ...semantics.analysis import numbers, program_facts
from ._text import at_lines, text

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator
    from typing import Any

    from ..engine import LintContext

NAME = "no-op-arithmetic"
PENALTY = 1
STANDARD = "efficiency"
SEVERITY = "warning"
CERTAINTY = "possible"
NEEDS = "ast"

# operator -> (the constant that changes nothing, whether it may stand on the left too)
_IDENTITY = {"*": (1.0, True), "/": (1.0, False), "+": (0.0, True), "-": (0.0, False)}
_VERB = {"*": "multiplying by", "/": "dividing by", "+": "adding", "-": "subtracting"}


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    for fn in program_facts(ctx.model).in_file(ctx.path):
        # the same no-op written again in a function (`time * 1.0` in each of its returns) is one
        # unnecessary practice, as the rubric deducts it: one finding naming every place
        same: dict[tuple, list[tuple]] = {}  # (operator, the constant's values) -> places
        reported: set[int] = set()  # inner mods found (a local's, through each of its reads)
        zeros: dict[str, list[tuple]] = {}  # products by the same zero: one practice
        for n in fn.nodes:
            if fn.is_dead(n):
                continue
            inner = _inner_mod(fn, n)
            if inner is not None and id(inner[0]) not in reported:
                reported.add(id(inner[0]))
                yield _inner_mod_finding(*inner)
                continue
            if type(n) is A.Call and n.callee == "mix" and len(n.args) == 3:
                picked = _mix_end(fn, n)
                if picked is not None:
                    yield Diagnostic(
                        f"'{text(n)}' is {text(picked)}: a mix() by {text(n.args[2])} gives "
                        "that end whole",
                        n.loc,
                        help=f"write {text(picked)}",
                    )
                    continue
            split = _split(fn, n) if _product_top(fn, n) else None
            if split is not None and n.op == "*":
                zero = _zero_factor(fn, split[0])
                if zero is not None:
                    zeros.setdefault(text(zero), []).append((n, zero))
                    continue
            if type(n) is A.Call and n.callee in _RANGED and len(n.args) == _RANGED[n.callee]:
                why = _in_range(fn, n)
                if why is not None:
                    x = n.args[0]
                    yield Diagnostic(
                        f"'{text(n)}' is {text(x)}: {text(x)} is {why} here, so "
                        f"{n.callee}() changes nothing",
                        n.loc,
                        help=f"write {text(x)}",
                    )
                continue
            if split is not None:
                cancelled = _cancelled(fn, n, *split)
                if cancelled is not None:
                    yield cancelled
            if type(n) is A.Binary and n.op in _IDENTITY:
                found = _no_op(fn, n)
            elif type(n) is A.Assignment and n.op[:-1] in _IDENTITY:
                found = _no_op_update(fn, n)
            else:
                continue
            if found is not None:
                constant, other = found
                op = n.op[0]
                key = (op, tuple(numbers(fn.model.const_value(constant))))
                same.setdefault(key, []).append((n, constant, other))
        for places in zeros.values():
            n, zero = places[0]
            again = (
                ""
                if len(places) == 1
                else f", and {len(places) - 1} more at {at_lines([p[0] for p in places[1:]])}"
            )
            yield Diagnostic(
                f"'{text(n)}' is always zero: it multiplies by {text(zero)}, which is zero "
                f"here{again}",
                n.loc,
                help="write the zero value, or remove the term",
            )
        for places in same.values():
            n, constant, other = places[0]
            again = (
                ""
                if len(places) == 1
                else f", and {len(places) - 1} more at {at_lines([p[0] for p in places[1:]])}"
            )
            likewise = " (and likewise at each place)" if again else ""
            if type(n) is A.Assignment:
                yield Diagnostic(
                    f"'{text(n)}' leaves {text(other)} as it is: {_VERB[n.op[0]]} "
                    f"{text(constant)} changes nothing{again}",
                    n.loc,
                    help="remove the statement" + likewise,
                )
                continue
            yield Diagnostic(
                f"'{text(n)}' is {text(other)}: {_VERB[n.op]} {text(constant)} changes "
                f"nothing{again}",
                n.loc,
                help=f"write {text(other)}" + likewise,
            )


# built-ins that give back their first argument on the range their other arguments set
_RANGED = {"abs": 1, "max": 2, "min": 2, "clamp": 3, "fract": 1, "mod": 2}


def _in_range(fn, n: A.Call) -> str | None:
    """Why `n` (abs, max, min or clamp of a float value with constant bounds) gives back its
    first argument: the range the value analysis knows it in, else None."""
    model = fn.model
    x = n.args[0]
    if model.is_constant(n) or getattr(model.type_of(x), "base", None) != "float":
        return None
    if model.type_of(n) != model.type_of(x):
        return None
    lo, hi, _ = fn.value_range(x)
    bounds = [numbers(model.const_value(a)) for a in n.args[1:]]
    if any(len(b) != 1 for b in bounds):
        return None
    b = [v[0] for v in bounds]
    shown = f"in [{_num(lo)}, {_num(hi)}]" if lo is not None and hi is not None else None
    if n.callee == "abs" and lo is not None and lo >= 0:
        return shown or "never negative"
    if n.callee == "max" and lo is not None and lo >= b[0]:
        return shown or f"never below {_num(b[0])}"
    if n.callee == "min" and hi is not None and hi <= b[0]:
        return shown or f"never above {_num(b[0])}"
    if n.callee == "clamp" and lo is not None and hi is not None and b[0] <= lo and hi <= b[1]:
        return shown
    if n.callee == "fract" and lo is not None and lo >= 0 and hi is not None and hi < 1:
        return f"in [{_num(lo)}, 1)"
    if n.callee == "mod" and lo is not None and lo >= 0 and hi is not None and hi < b[0]:
        return f"in [{_num(lo)}, {_num(b[0])})"
    return None


def _num(v: float | None) -> str:
    return "?" if v is None else f"{v:g}"


def _inner_mod(fn, n) -> tuple[Any, Any, Any] | None:
    """(the inner mod, the outer, the local followed or None) when `n` is `mod(a + mod(b, m),
    m)`, `(a + b % m) % m` or the same with `-`, the two `m` the same constant, directly or
    through a local that holds `a + mod(b, m)` and is read only by such mods: the outer mod
    gives the same parity (the same remainder) without the inner one."""
    modulus = _modulus(fn, n)
    if modulus is None:
        return None
    x, m = modulus
    via = None
    if type(x) is A.Identifier:
        sym = fn.model.symbol_of(x)
        if sym is None or sym.kind != "local":
            return None
        value = fn.reaching_value(x, sym)
        reads = [r for r in fn.nodes if type(r) is A.Identifier and fn.model.symbol_of(r) is sym]
        if value is None or any(_read_modulus(fn, r) != m for r in reads):
            return None
        x, via = value, x
    if type(x) is not A.Binary or x.op not in ("+", "-"):
        return None
    for side in (x.left, x.right):
        inner = _modulus(fn, side)
        if inner is not None and inner[1] == m and fn.is_pure(side):
            return side, n, via
    return None


def _modulus(fn, e) -> tuple[Any, list] | None:
    """(the dividend, the constant modulus's values) of `mod(x, m)` or of an int `x % m`."""
    model = fn.model
    if type(e) is A.Call and e.callee == "mod" and len(e.args) == 2 and not e.constructor:
        m = numbers(model.const_value(e.args[1]))
        return (e.args[0], m) if m and getattr(model.type_of(e), "is_scalar", False) else None
    if type(e) is A.Binary and e.op == "%":
        m = numbers(model.const_value(e.right))
        return (e.left, m) if m and getattr(model.type_of(e), "is_scalar", False) else None
    return None


def _read_modulus(fn, r) -> list | None:
    """The modulus of the mod whose dividend is the read `r`, else None."""
    up = fn.parent.get(id(r))
    found = _modulus(fn, up) if up is not None else None
    return found[1] if found is not None and found[0] is r else None


def _inner_mod_finding(inner, outer, via) -> Diagnostic:
    held = "" if via is None else f" (through '{text(via)}', only ever taken mod it)"
    return Diagnostic(
        f"'{text(inner)}' is needless: the outer '{text(outer)}'{held} gives the same "
        "remainder without it",
        inner.loc,
        help=f"write {text(_modulus_dividend(inner))} in its place",
    )


def _modulus_dividend(e):
    return e.args[0] if type(e) is A.Call else e.left


def _mix_end(fn, n: A.Call):
    """The end `mix(a, b, t)` gives back when `t` is a written 0.0 (a) or 1.0 (b), every
    component; None otherwise (a named weight is a setting)."""
    t = n.args[2]
    if not _written_out(t) or fn.model.is_constant(n.args[0]) and fn.model.is_constant(n.args[1]):
        return None
    values = numbers(fn.model.const_value(t))
    kind = fn.model.type_of(n)
    if not values or getattr(kind, "base", None) != "float":
        return None
    end = n.args[0] if all(v == 0.0 for v in values) else None
    end = n.args[1] if all(v == 1.0 for v in values) else end
    if end is None or fn.model.type_of(end) != kind or not fn.is_pure(n):
        return None
    return end


def _split(fn, n: A.Binary) -> tuple[list, list, list] | None:
    """The factors the top float product `n` multiplies and divides by, and the locals followed
    (`_factors`); None for a constant or impure product."""
    if fn.model.is_constant(n) or not fn.is_pure(n):
        return None
    num: list = []
    den: list = []
    via: list = []
    _factors(fn, n, num, den, via, 0, None)
    return num, den, via


def _zero_factor(fn, num: list):
    """A factor written in the product (`num`: `_factors`'s, not one inside a local's value,
    reported where that local is set) that is zero in every component: written out, or a local
    whose value reaching here is (`vec3 black = vec3(0.0); ... black * mask`); None otherwise.
    The product is zero whatever the rest (but for infinities and NaN)."""
    for f, held in num:
        if held is not None:
            continue
        value = fn.model.const_value(f)
        if value is None and type(f) is A.Identifier:
            sym = fn.model.symbol_of(f)
            reaching = (
                fn.reaching_value(f, sym) if sym is not None and sym.kind == "local" else None
            )
            value = None if reaching is None else fn.model.const_value(reaching)
        values = numbers(value)
        if values and all(v == 0.0 for v in values):
            return f
    return None


def _product_top(fn, n) -> bool:
    """Whether `n` is a float `*` or `/` that no other such operation contains."""
    if type(n) is not A.Binary or n.op not in ("*", "/") or not _float_factor(fn, n):
        return False
    up = fn.parent.get(id(n))
    return not (type(up) is A.Binary and up.op in ("*", "/") and _float_factor(fn, up))


def _float_factor(fn, e) -> bool:
    t = fn.model.type_of(e)
    return getattr(t, "base", None) == "float" and (t.is_scalar or t.is_vector)


def _cancelled(fn, n: A.Binary, num: list, den: list, via: list) -> Diagnostic | None:
    """A float product (its factors `num` / `den`, the locals followed `via`: `_split`) that
    multiplies and divides by the same value (`columns / rows * rows`, `height * width /
    height`, or through a local holding a quotient: `numHeight * ratio` with `ratio = numWide /
    numHeight`): the two cancel."""
    for d, d_from in den:
        k = fn.key(d)
        # (a pair both inside one local's value is that local's own finding, where it is set)
        if any(fn.key(m) == k and (m_from is None or m_from is not d_from) for m, m_from in num):
            held = "".join(f"; {text(v)} is {text(value)}" for v, value in via)
            return Diagnostic(
                f"'{text(n)}' multiplies and divides by {text(d)}{held}: the two cancel",
                n.loc,
                help=f"leave out both the factor {text(d)} and the division by it",
            )
    return None


def _factors(fn, e, num: list, den: list, via: list, depth: int, held) -> None:
    """Split the float product `e` into the factors it multiplies by (`num`) and divides by
    (`den`), each with the local's value it was reached through (`held`, None: written in
    `e`), through locals holding a product or a quotient (each added to `via`)."""
    if depth < 8 and type(e) is A.Binary and e.op in ("*", "/") and _float_factor(fn, e):
        if all(_float_factor(fn, x) for x in (e.left, e.right)):
            _factors(fn, e.left, num, den, via, depth + 1, held)
            if e.op == "*":
                _factors(fn, e.right, num, den, via, depth + 1, held)
            else:
                _factors(fn, e.right, den, num, via, depth + 1, held)
            return
    if depth < 8 and type(e) is A.Identifier:
        sym = fn.model.symbol_of(e)
        value = fn.reaching_value(e, sym) if sym is not None and sym.kind == "local" else None
        if type(value) is A.Binary and value.op in ("*", "/") and _float_factor(fn, value):
            via.append((e, value))
            _factors(fn, value, num, den, via, depth + 1, value)
            return
    num.append((e, held))


def _no_op(fn, n: A.Binary):
    """(the constant, the other operand) when `n` gives back its other operand unchanged."""
    model = fn.model
    if model.is_constant(n):
        return None  # folded by the compiler, and often a named constant's meaning
    identity, either_side = _IDENTITY[n.op]
    sides = [(n.right, n.left)] + ([(n.left, n.right)] if either_side else [])
    result = model.type_of(n)
    for constant, other in sides:
        if not _written_out(constant):
            continue  # a named constant (`x * kGain`) is a setting, 1.0 for now
        values = numbers(model.const_value(constant))
        if not values or any(v != identity for v in values):
            continue
        if getattr(model.type_of(constant), "base", None) != "float":
            continue  # an int product may be a conversion's spelling; floats only
        if model.type_of(other) == result:
            return constant, other
    return None


def _no_op_update(fn, n: A.Assignment):
    """(the constant, the target) when the compound assignment `n` (`x /= 1.0`) leaves its
    target as it was: the operation `target op value` would give back the target."""
    model = fn.model
    identity, _ = _IDENTITY[n.op[0]]
    if not _written_out(n.value) or not fn.is_pure(n.target):
        return None
    values = numbers(model.const_value(n.value))
    if not values or any(v != identity for v in values):
        return None
    if getattr(model.type_of(n.value), "base", None) != "float":
        return None
    kind, target = model.type_of(n.value), model.type_of(n.target)
    if kind != target and not getattr(kind, "is_scalar", False):
        return None  # a constant of another shape: a conversion or an error, not a no-op
    return n.value, n.target


def _written_out(e) -> bool:
    """A literal, or a constructor of literals (`vec4(1.0, 1.0, 1.0, 1.0)`)."""
    if type(e) in (A.FloatLiteral, A.IntLiteral):
        return True
    return type(e) is A.Call and bool(e.args) and all(_written_out(a) for a in e.args)
