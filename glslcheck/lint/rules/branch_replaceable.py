"""A branch selects what max, min, clamp, step or mix computes without one.

## What it does
Reports an `if`/`else` or a `?:` whose only job is a selection a built-in makes branch-free,
and shows the replacement:

* `a > b ? a : b` -> `max(a, b)`, `a < b ? a : b` -> `min(a, b)` (any of `< <= > >=`, either
  order), and the statement forms `if (x < 0.0) x = 0.0;` -> `x = max(x, 0.0);`,
  `if (a > b) m = a; else m = b;` -> `m = max(a, b);`;
* a max of a min with constant bounds (`x < lo ? lo : (x > hi ? hi : x)`) -> `clamp(x, lo, hi)`;
* `x >= e ? 1.0 : 0.0` -> `step(e, x)` (and the other comparisons, exactly:
  `x > e ? 1.0 : 0.0` is `1.0 - step(x, e)`);
* `x < e ? a : b` with `a` and `b` float values mix() may compute both of (names, literals,
  fields, swizzles, constants, and constructors, negations, sums, differences and products of
  those, or one divided by a value that cannot be zero; no call) -> `mix(a, b, step(e, x))`,
  also as `if (..) v = a; else v = b;`, as `if (..) v = a;` (`v = mix(v, a, ...)`), as
  `if (..) return a; else return b;` and as `if (..) return a; return b;` (the return right
  after the if runs exactly when the condition is false);
* nested if/else statements whose arms each give one variable (or the result) such a value
  (`if (..) { if (..) c = red; else c = blue; } else ...`, an `else if` chain of returns ending
  in an `else`, or of assignments with no last `else`, which keeps the variable's value): one
  finding at the outer if, with the mix of mixes;
* arms that compute the same thing but for such values (`cos(8.0 * time + vec3(0, 2, 4))` or
  `cos(8.0 * time - vec3(4, 2, 0))`, `mix(a, b, x)` or `mix(a, b, 1.0 - x)`): the values are
  mixed and the rest, calls included, computed once (`cos(mix(..., ..., s))`), which the
  branch computes once too;
* conditions beyond one comparison: `&&`, `||` and `!` of float comparisons (a product, a max
  and `1.0 -` of their steps), an equality of floats (`fragCoord.y == 50.5`: `step(y, 50.5) *
  step(50.5, y)`, 1.0 exactly where they are equal), a step() result compared with 0.0 or 1.0
  (the branch on a step value, which is the selector itself), `^^` of such (`abs(a - b)`), two
  parities compared with each other (`mod(x, 2.0) == mod(y, 2.0)`: `1.0 - abs(px - py)`), and a
  parity compared with 0 or 1: `mod(n, 2.0)` of a whole number (floor(), float() of an int,
  their sums and products, a local holding one, its operands written since or not: a
  checkerboard's `mod(floor(p.x) + floor(p.y), 2.0)`) is exactly 0.0 or 1.0 and is the selector,
  and an int's `n % 2` is `float(n & 1)`;
* `dot(d, n) < 0.0 ? n : -n` (the front-face normal of a ray tracer) -> `faceforward(n, d, n)`,
  which is `n` exactly when `dot(n, d) < 0.0`, else `-n`; also when the comparison is kept in
  a bool variable or field first (`rec.frontFace = dot(d, n) < 0.0;
  rec.normal = rec.frontFace ? n : -n;`, with no write between to what it reads), and as
  `if (..) v = n; else v = -n;`. A comparison that differs from faceforward's where the dot
  product is 0 (`<= 0.0`) is not reported.

Arms that sample a texture (`if (uv.x <= split) col = texture(iChannel0, uv); else col =
texture(iChannel1, uv);`, lookups of a named sampler at cheap coordinates) are a possible
deduction: mix() of both lookups gives the same colour without a branch, but samples each
texture where the branch samples one; readers of the rubric part on whether that is the more
efficient method.

Except for faceforward, the condition must be made of comparisons of two float (or, for one
min/max, int) scalars; the statement forms must be a single assignment to the same variable (or
a return) in each arm. Ifs in a row that each select a part of one variable (`if (..) col.x =
1.0;`, then `col.y`, `col.z`) are one finding, and so are selects on the same condition written
again in a function (a checkerboard's `if (parity == 0.0)` in two arms): the rubric deducts
"per inefficient practice". Ifs in a row setting different variables (three layers' alphas),
or one variable whole (one of two images chosen, then black past the last tile), are a finding
each, and the same words on a variable written between (`center` moved for the
next circle) are another condition. The replacement gives
the same value on every path: conditions and arms are free of side effects, and step() is
exactly 0.0 or 1.0, so the mix picks an arm (an arm the branch skipped may not divide by zero).

## Why is this bad?
The course's coding standards: "Use inefficient functions and methods sparingly and out of
necessity (including but not limited to conditionals, square roots, etc.)" (-1 per instance).
On a GPU the pixels of a group run in lockstep: a data-dependent branch makes the group run both
arms; `max`, `min`, `clamp`, `step` and `mix` are single instructions.

## Example
```glsl
float kD = dot(normal, lightDir);
if (kD < 0.0) kD = 0.0;
vec3 color = t > 0.0 ? surface : background;
```

## Use instead
```glsl
float kD = max(dot(normal, lightDir), 0.0);
vec3 color = mix(background, surface, step(0.0, t)); // t == 0.0 counts as a hit here
```
"""

from __future__ import annotations

from ...base.diagnostics import Diagnostic
from ...frontend import syntax as A
from ...frontend.printer import to_glsl
from ...semantics.analysis import builtin_call, numbers, program_facts
from ._text import at_lines, is_atom, text

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Callable, Iterator
    from typing import Any

    from ..engine import LintContext

NAME = "branch-replaceable"
PENALTY = 1
STANDARD = "efficiency"
SEVERITY = "warning"
NEEDS = "ast"

_OPS = ("<", "<=", ">", ">=")


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    for fn in program_facts(ctx.model).in_file(ctx.path):
        inner: set[int] = set()  # ternaries already explained as part of a clamp
        covered: set[int] = set()  # ifs already explained as part of an outer one's select
        run: list[tuple[Any, str, tuple[str, str]]] = []  # selecting ifs in a row, one finding
        runs: list[list[tuple[Any, str, tuple[str, str]]]] = []
        for node in fn.nodes:
            if type(node) is A.Ternary and id(node) not in inner:
                fix = _select(fn, node.cond, node.then, node.else_, inner)
                if fix is not None:
                    runs.append([(node, "?:", fix)])
            elif type(node) is A.If and id(node) not in covered:
                nest: list[Any] = []
                fallthrough = _return_after(fn, node)
                fix = (
                    _nested(fn, fallthrough, nest)
                    if fallthrough is not None
                    else _nested(fn, node, nest) or _if_statement(fn, node)
                )
                if fix is None:
                    continue
                covered.update(id(n) for n in nest)
                what = (
                    "nest"
                    if len(nest) > 1
                    else "if return"
                    if fallthrough is not None
                    else "if"
                    if node.else_ is not None
                    else "lone if"
                )
                if run and _follows(fn, run[-1][0], node) and _same_target(fn, run[-1][0], node):
                    run.append((node, what, fix))
                    continue
                if run:
                    runs.append(run)
                run = [(node, what, fix)]
        if run:
            runs.append(run)
            run = []
        yield from _merged(fn, runs)


def _return_after(fn, node: A.If) -> A.If | None:
    """`if (c) return a; return b;` read as `if (c) return a; else return b;` (the same
    selection: the return after the if runs exactly when the condition is false), or None."""
    if node.else_ is None and _returned(node.then) is not None:
        block = fn.parent.get(id(node))
        if type(block) is A.Compound:
            stmts = block.stmts
            i = next((k for k, st in enumerate(stmts) if st is node), len(stmts))
            after: Any = stmts[i + 1] if i + 1 < len(stmts) else None
            if type(after) is A.Return and after.value is not None:
                return A.If(cond=node.cond, then=node.then, else_=after, loc=node.loc)
    return None


def _part(stmt: Any) -> tuple[str, str] | None:
    """(the variable, the part of it) a selecting if assigns (`col`, `col.x` of `col.x =
    1.0;`), or None; the part of a whole variable is its name."""
    assign = _single_assignment(stmt.then)
    target: Any = assign.target if assign is not None else None
    part = to_glsl(target) if target is not None else ""
    while type(target) in (A.Field, A.Index):
        target = target.base
    return (target.name, part) if type(target) is A.Identifier else None


def _same_target(fn, before: A.If, node: A.If) -> bool:
    """Ifs in a row are one selection when they set parts of the same variable (`col.x`,
    `col.y`, `col.z`: one colour chosen); ifs setting different variables (three layers'
    alphas), or the same one whole (a pair of images chosen, then black past the last tile),
    are as many selections."""
    first, then = _part(before), _part(node)
    return (
        first is not None
        and then is not None
        and first[0] == then[0]
        and first[1] != first[0]
        and then[1] != then[0]
    )


def _merged(fn, runs: list[list[tuple[Any, str, tuple[str, str]]]]) -> Iterator[Diagnostic]:
    """The findings of a function's selects: a select written again on the same condition
    (`if (modulus == 0.0)` in two arms, each choosing its own pair of colors) is one finding
    naming every place, the rubric's one inefficient practice; the same words on values
    written between (`center` moved for the next circle) are another condition."""
    groups: dict[str, list] = {}
    for run in runs:
        node = run[0][0]
        key = to_glsl(node.cond) if len(run) == 1 else f"#{id(node)}"
        same = groups.get(key)
        if same is not None and _rewritten(fn, same[0][0][0], node):
            key = f"#{id(node)}"
        groups.setdefault(key, []).append(run)
    for same in groups.values():
        first = _finding(same[0])
        if len(same) == 1:
            yield first
            continue
        again = [r[0][0] for r in same[1:]]
        yield Diagnostic(
            f"{first.message}, and the same selection again at {at_lines(again)}",
            first.loc,
            help=f"{first.help} (and likewise at {at_lines(again)})",
            certainty=first.certainty,
        )


def _rewritten(fn, first: Any, node: Any) -> bool:
    """Whether a variable both conditions read may be written after `first`'s and before
    `node`'s (the same words, another value). Locals of their own in each arm, computed the
    same way (a checker's `modulus` declared again in the next arm), are the same condition."""

    def read(cond: Any) -> set:
        return {
            sym
            for n in cond.walk()
            if type(n) is A.Identifier and (sym := fn.model.symbol_of(n)) is not None
        }

    return fn.written_between(first.cond, node.cond, read(first.cond) & read(node.cond))


def _follows(fn, before: Any, node: Any) -> bool:
    """Whether the statement `node` comes right after `before` in the same block."""
    block = fn.parent.get(id(node))
    if type(block) is not A.Compound or fn.parent.get(id(before)) is not block:
        return False
    i = next((k for k, st in enumerate(block.stmts) if st is node), 0)
    return i > 0 and block.stmts[i - 1] is before


def _finding(run: list[tuple[Any, str, tuple[str, str]]]) -> Diagnostic:
    """One finding for a select, or for a run of if statements in a row that each select (three
    ifs setting `col.x`, `col.y`, `col.z`): the rubric's one inefficient practice."""
    node, what, (fn_name, replacement) = run[0]
    # a reading: the branch samples one texture where the mix samples each (possible)
    sampled = any(_picks_lookup(n) for n, _, _ in run)
    certainty = "possible" if sampled else None
    also = ", sampling each texture where the branch samples one" if sampled else ""
    kinds = {
        "if": "an if/else",
        "lone if": "an if",
        "if return": "an if and the return after it",
        "nest": "nested if/else statements",
    }
    if len(run) == 1:
        verb = "compute" if what in ("nest", "if return") else "computes"
        return Diagnostic(
            f"{kinds.get(what, 'a ?: selection')} {verb} what {fn_name}() computes without a "
            f"branch{also}",
            node.loc,
            help=f"write {replacement}",
            certainty=certainty,
        )
    names = list(dict.fromkeys(f"{f[0]}()" for _, _, f in run))
    return Diagnostic(
        f"{len(run)} if statements in a row (lines {node.loc.line}-{run[-1][0].loc.line}) compute "
        f"what {' and '.join(names)} {'computes' if len(names) == 1 else 'compute'} without a "
        f"branch{also}",
        node.loc,
        help="write " + " ".join(f[1] for _, _, f in run),
        certainty=certainty,
    )


def _single_assignment(stmt: Any) -> A.Assignment | None:
    while type(stmt) is A.Compound and len(stmt.stmts) == 1:
        stmt = stmt.stmts[0]
    if (
        type(stmt) is A.ExpressionStatement
        and type(stmt.expr) is A.Assignment
        and stmt.expr.op == "="
    ):
        return stmt.expr
    return None


def _if_statement(fn, node: A.If) -> tuple[str, str] | None:
    then = _single_assignment(node.then)
    if then is None or not fn.is_pure(then.target):
        return None
    if node.else_ is None:
        other = then.target  # if (c) x = a;  is  x = c ? a : x;
    else:
        other_assign = _single_assignment(node.else_)
        if other_assign is None or fn.key(other_assign.target) != fn.key(then.target):
            return None
        other = other_assign.value
    found = _select(fn, node.cond, then.value, other, set())
    if found is None:
        return None
    name, expr = found
    return name, f"{text(then.target)} = {expr.removeprefix('`').removesuffix('`')};"


def _comparison(fn, cond: Any, *bases: str) -> tuple[Any, str, Any] | None:
    if type(cond) is not A.Binary or cond.op not in _OPS:
        return None
    if not _scalars(fn, cond.left, cond.right, bases):
        return None
    return cond.left, cond.op, cond.right


def _scalars(fn, a, b, bases: tuple[str, ...]) -> bool:
    """Whether `a` and `b` are pure scalars of one type whose base is one of `bases`."""
    t = fn.model.type_of(a)
    if not (getattr(t, "is_scalar", False) and t.base in bases) or fn.model.type_of(b) != t:
        return False
    return fn.is_pure(a) and fn.is_pure(b)


def _minmax(fn, cond, a, b) -> tuple[str, Any, Any] | None:
    """('max' | 'min', x, y) when `cond ? a : b` is max(x, y) or min(x, y)."""
    cmp = _comparison(fn, cond, "float", "int", "uint")
    if cmp is None:
        return None
    left, op, right = cmp
    kl, kr, ka, kb = fn.key(left), fn.key(right), fn.key(a), fn.key(b)
    if (ka, kb) == (kl, kr):
        return ("max" if op in (">", ">=") else "min"), left, right
    if (ka, kb) == (kr, kl):
        return ("min" if op in (">", ">=") else "max"), left, right
    return None


def _as_minmax(fn, e) -> tuple[str, Any, Any] | None:
    if type(e) is A.Ternary:
        return _minmax(fn, e.cond, e.then, e.else_)
    if type(e) is A.Call and e.callee in ("min", "max") and len(e.args) == 2:
        return e.callee, e.args[0], e.args[1]
    return None


def _clamp(fn, cond, a, b, inner: set[int]) -> tuple[str, str] | None:
    """`x < lo ? lo : min(x, hi)` and its mirror images: clamp(x, lo, hi)."""
    cmp = _comparison(fn, cond, "float", "int", "uint")
    if cmp is None:
        return None
    left, op, right = cmp
    if _is_const(fn, right) and not _is_const(fn, left):
        x, bound = left, right
    elif _is_const(fn, left) and not _is_const(fn, right):
        x, bound, op = right, left, {"<": ">", "<=": ">=", ">": "<", ">=": "<="}[op]
    else:
        return None
    kb = fn.key(bound)
    if fn.key(a) == kb:
        nested, bound_when_below = b, op in ("<", "<=")  # x < c ? c : N
    elif fn.key(b) == kb:
        nested, bound_when_below = a, op in (">", ">=")  # x > c ? N : c
    else:
        return None
    sub = _as_minmax(fn, nested)
    if sub is None or sub[0] != ("min" if bound_when_below else "max"):
        return None
    _, p, q = sub
    kx = fn.key(x)
    other = q if fn.key(p) == kx else p if fn.key(q) == kx else None
    if other is None or not _is_const(fn, other):
        return None
    if type(nested) is A.Ternary:
        inner.add(id(nested))
    lo, hi = (bound, other) if bound_when_below else (other, bound)
    return "clamp", f"clamp({text(x)}, {text(lo)}, {text(hi)})"


def _is_const(fn, e) -> bool:
    return len(numbers(fn.model.const_value(e))) == 1


def _select(fn, cond, a, b, inner: set[int]) -> tuple[str, str] | None:
    """(built-in, replacement text) for `cond ? a : b`, or None."""
    facing = _face_forward(fn, cond, a, b)
    if facing is not None:
        return facing
    clamp = _clamp(fn, cond, a, b, inner)
    if clamp is not None:
        return clamp
    mm = _minmax(fn, cond, a, b)
    if mm is not None:
        name, x, y = mm
        # max(lo, min(x, hi)) / min(hi, max(x, lo)) with constant bounds: clamp
        for bound, nested in ((x, y), (y, x)):
            sub = _as_minmax(fn, nested)
            if sub is None or sub[0] == name or not _is_const(fn, bound):
                continue
            _, p, q = sub
            value, other = (p, q) if _is_const(fn, q) else (q, p)
            if not _is_const(fn, other):
                continue
            lo, hi = (bound, other) if name == "max" else (other, bound)
            if type(nested) is A.Ternary:
                inner.add(id(nested))
            return "clamp", f"clamp({text(value)}, {text(lo)}, {text(hi)})"
        return name, f"{name}({text(x)}, {text(y)})"
    ta = fn.model.type_of(a)
    va, vb = numbers(fn.model.const_value(a)), numbers(fn.model.const_value(b))
    ones = len(va) == 1 and len(vb) == 1 and getattr(ta, "is_scalar", False) and ta.base == "float"
    cmp = _comparison(fn, cond, "float")
    if cmp is not None:
        left, op, right = cmp
        t, sense = _step(left, op, right)
        if ones and (va[0], vb[0]) == (1.0, 0.0):
            return "step", t if sense else f"1.0 - {t}{_near(left, op, right)}"
        if ones and (va[0], vb[0]) == (0.0, 1.0):
            return "step", f"1.0 - {t}{_near(left, op, right)}" if sense else t
    else:
        indicator = _indicator(fn, cond)
        if indicator is None:
            return None
        t, sense = indicator, True
        if ones and (va[0], vb[0]) == (1.0, 0.0):
            return "step", t
        if ones and (va[0], vb[0]) == (0.0, 1.0):
            return "step", f"1.0 - {_factor(t)}"
    first, second = (b, a) if sense else (a, b)
    if not (_value(fn, a) and _value(fn, b)):
        return _shared(fn, first, second, t)
    if not _float_valued(fn, a) or fn.model.type_of(b) != ta:
        return None
    return "mix", f"mix({text(first)}, {text(second)}, {t})"


def _shared(fn, first, second, t: str) -> tuple[str, str] | None:
    """`mix` for arms that compute the same thing but for some values mix() may compute both
    of (`cos(8.0 * time + vec3(0, 2, 4))` or `cos(8.0 * time - vec3(4, 2, 0))`): the rest,
    calls included, is computed once on the selected values. `first` is the value at t == 0.0;
    the text is `first` with each differing value replaced by its mix."""
    if not (fn.is_pure(first) and fn.is_pure(second)):
        return None
    pairs: list[tuple[Any, Any]] = []
    if not _differing(fn, first, second, pairs) or not pairs:
        return None
    mixed = {id(x): f"mix({text(x)}, {text(y)}, {t})" for x, y in pairs}
    return "mix", to_glsl(_rebuilt(first, mixed))


def _differing(fn, a, b, pairs: list) -> bool:
    """Whether `a` and `b` are the same expression but for values mix() may compute both of,
    of one float type (added to `pairs`, the largest ones)."""
    if fn.key(a) == fn.key(b):
        return True
    kind = fn.model.type_of(a)
    if _value(fn, a) and _value(fn, b) and _float_valued(fn, a) and fn.model.type_of(b) == kind:
        pairs.append((a, b))
        return True
    t = type(a)
    if t is not type(b) or t not in _SAME_HEAD or not _SAME_HEAD[t](fn, a, b):
        return False
    ca, cb = a.children(), b.children()
    return len(ca) == len(cb) and all(_differing(fn, x, y, pairs) for x, y in zip(ca, cb))


_SAME_HEAD: dict[type, Callable[[Any, Any, Any], bool]] = {
    A.Binary: lambda fn, a, b: a.op == b.op,
    A.Unary: lambda fn, a, b: a.op == b.op,
    A.Field: lambda fn, a, b: a.name == b.name,
    A.Index: lambda fn, a, b: True,
    A.Call: lambda fn, a, b: (
        a.callee == b.callee
        and a.array is None
        and b.array is None
        and fn.model.call_target(a) is fn.model.call_target(b)
    ),
}


def _rebuilt(e, mixed: dict[int, str]):
    """A copy of `e` with the nodes `mixed` names replaced by their text (for printing)."""
    if id(e) in mixed:
        return A.Identifier(name=mixed[id(e)], loc=e.loc)
    if not isinstance(e, A.Node):
        return e
    fields = {}
    for f in type(e)._fields:
        v = getattr(e, f)
        if f in type(e)._children:
            v = [_rebuilt(x, mixed) for x in v] if type(v) is list else _rebuilt(v, mixed)
        fields[f] = v
    return type(e)(**fields)


def _step(left, op, right) -> tuple[str, bool]:
    """(a step() call, sense): the call is 1.0 exactly when `left op right` holds (sense True)
    or exactly when it fails (sense False); step(e, x) is 1.0 exactly when x >= e."""
    if op == ">=":
        return f"step({text(right)}, {text(left)})", True
    if op == "<":
        return f"step({text(right)}, {text(left)})", False
    if op == "<=":
        return f"step({text(left)}, {text(right)})", True
    return f"step({text(left)}, {text(right)})", False  # >


def _factor(t: str) -> str:
    """`t` as an operand of `*` or `-`: parenthesised when it is a difference or a product."""
    return f"({t})" if " - " in t or " * " in t else t


def _indicator(fn, cond) -> str | None:
    """A float that is exactly 1.0 when `cond` holds and 0.0 when it does not, made without a
    branch: a step() of a comparison of float scalars, the product (`&&`), max (`||`) and
    `1.0 -` (`!`) of such, or a step() result compared with 0.0 or 1.0 (a branch on the step
    value, which is the selector itself). None for any other condition."""
    t = type(cond)
    if t is A.Binary and cond.op in ("&&", "||"):
        a, b = _indicator(fn, cond.left), _indicator(fn, cond.right)
        if a is None or b is None:
            return None
        return f"{_factor(a)} * {_factor(b)}" if cond.op == "&&" else f"max({a}, {b})"
    if t is A.Unary and cond.op == "!":
        a = _indicator(fn, cond.operand)
        return None if a is None else f"1.0 - {_factor(a)}"
    if t is A.Binary and cond.op == "^^":
        a, b = _indicator(fn, cond.left), _indicator(fn, cond.right)
        return None if a is None or b is None else f"abs({a} - {_factor(b)})"
    if t is A.Binary and cond.op in ("==", "!=") and not fn.model.is_constant(cond.right):
        # two parities compared (`mod(x, 2.0) == mod(y, 2.0)`, a checkerboard's test): each is
        # exactly 0.0 or 1.0, so they are equal where their difference is 0
        pa, pb = _parity(fn, cond.left, 0), _parity(fn, cond.right, 0)
        if pa is not None and pb is not None and not fn.model.is_constant(cond.left):
            differ = f"abs({pa} - {_factor(pb)})"
            return differ if cond.op == "!=" else f"1.0 - {differ}"
    if t is A.Binary and cond.op in ("==", "!="):
        for side, other in ((cond.left, cond.right), (cond.right, cond.left)):
            bound = numbers(fn.model.const_value(other))
            kind = fn.model.type_of(side)
            if (
                builtin_call(fn.model, side, "step")
                and getattr(kind, "is_scalar", False)
                and fn.is_pure(side)
                and bound in ([0.0], [1.0])
            ):
                one = (bound == [1.0]) == (cond.op == "==")  # the condition holds at 1.0
                return text(side) if one else f"1.0 - {text(side)}"
            parity = _parity(fn, side, 0) if bound in ([0.0], [1.0]) else None
            if parity is not None:
                one = (bound == [1.0]) == (cond.op == "==")
                return parity if one else f"1.0 - {_factor(parity)}"
        # float scalars equal (`fragCoord.y == 50.5`): both steps 1.0 exactly there
        if _scalars(fn, cond.left, cond.right, ("float",)):
            a, b = text(cond.left), text(cond.right)
            equal = f"step({a}, {b}) * step({b}, {a})"
            return equal if cond.op == "==" else f"1.0 - {equal}"
        return None
    cmp = _comparison(fn, cond, "float")
    if cmp is None:
        return None
    step, sense = _step(*cmp)
    return step if sense else f"1.0 - {step}"


def _parity(fn, e, depth: int) -> str | None:
    """A float that is exactly 0.0 or 1.0, as `e` is (`mod(floor(x) + floor(y), 2.0)`, an int
    `n % 2` as `float(n & 1)`, or a local holding one); None for any other value."""
    if depth > 8 or not fn.is_pure(e):
        return None
    model = fn.model
    if type(e) is A.Identifier:
        sym = model.symbol_of(e)
        variable = sym is not None and sym.kind in _VARIABLES
        reaching = fn.reaching_value(e, sym, as_computed=True) if variable else None
        if reaching is None or _parity(fn, reaching, depth + 1) is None:
            return None
        kind = model.type_of(e)
        return text(e) if getattr(kind, "base", None) == "float" else f"float({text(e)} & 1)"
    if builtin_call(model, e, "mod") and len(e.args) == 2:
        t = model.type_of(e)
        if (
            getattr(t, "is_scalar", False)
            and numbers(model.const_value(e.args[1])) == [2.0]
            and _integral(fn, e.args[0], 0)
        ):
            return text(e)
    if type(e) is A.Binary and e.op == "%" and model.const_value(e.right) == 2:
        kind = model.type_of(e)
        if getattr(kind, "base", None) in ("int", "uint") and getattr(kind, "is_scalar", False):
            left = (
                text(e.left) if is_atom(e.left) or type(e.left) is A.Call else f"({text(e.left)})"
            )
            one = "1u" if kind.base == "uint" else "1"
            return f"float({left} & {one})"  # n % 2 where n >= 0 (undefined below)
    return None


_ROUNDING = ("floor", "ceil", "round", "roundEven", "trunc")
# built-ins whose value is a whole number when their arguments are (mod(n, 2.0) of a floor)
_WHOLE_OF_WHOLE = ("mod", "abs", "min", "max")
# variables whose last write a read is followed to (a global: written in this function)
_VARIABLES = ("local", "param", "global")


def _integral(fn, e, depth: int) -> bool:
    """Whether the float `e` always holds integers (a floor(), a float() of an int, a vector
    made of such, sums, products and mods of such, a component of such a vector, a local
    holding one, a parameter or global written over with one: `uv = floor(uv);`, and a
    component written with one: `uv.x = floor(uv.x * 8.0);`)."""
    if depth > 8:
        return False
    model = fn.model
    values = numbers(model.const_value(e))
    if values:
        return all(float(v).is_integer() for v in values)
    t = type(e)
    if t is A.Call:
        if builtin_call(model, e, *_ROUNDING):
            return True
        made = e.constructor and e.array is None and _float_valued(fn, e)  # (not a struct)
        if made or builtin_call(model, e, *_WHOLE_OF_WHOLE):
            return bool(e.args) and all(
                getattr(model.type_of(a), "base", None) in ("int", "uint")
                or _integral(fn, a, depth + 1)
                for a in e.args
            )
        return False
    if t is A.Binary and e.op in ("+", "-", "*"):
        return _integral(fn, e.left, depth + 1) and _integral(fn, e.right, depth + 1)
    if t is A.Unary and e.op in ("-", "+"):
        return _integral(fn, e.operand, depth + 1)
    if t is A.Field and model.is_swizzle(e):
        sym = model.symbol_of(e.base) if type(e.base) is A.Identifier else None
        if sym is not None and sym.kind in _VARIABLES and len(model.swizzle_indices(e)) == 1:
            written = fn.reaching_component(e, sym)
            if written is not None:
                return _integral(fn, written, depth + 1)
        return _integral(fn, e.base, depth + 1)
    if t is A.Identifier:
        sym = model.symbol_of(e)
        if sym is None or sym.kind not in _VARIABLES:
            return False
        reaching = fn.reaching_value(e, sym, as_computed=True)
        return reaching is not None and _integral(fn, reaching, depth + 1)
    return False


def _nested(fn, node: A.If, nest: list) -> tuple[str, str] | None:
    """`mix` for an if/else whose arms give one variable (or the function's result) a value
    each, through nested if/else statements too (`if (a) { if (b) c = x; else c = y; } else
    ...`, `if (a) return x; else if (b) return x; else return y;`): one finding for the whole
    nest, whose ifs go to `nest`. None for a single if/else assigning (`_if_statement`'s)."""
    if node.else_ is None:
        return None
    returned = _returned(node.then), _returned(node.else_)
    both = returned[0] is not None and returned[1] is not None
    if both and not (_value(fn, returned[0]) and _value(fn, returned[1])):
        cmp = _comparison(fn, node.cond, "float")
        indicator, sense = _step(*cmp) if cmp is not None else (_indicator(fn, node.cond), True)
        if indicator is None or not _float_valued(fn, returned[0]):
            return None
        first, second = returned[::-1] if sense else returned
        found = _shared(fn, first, second, indicator)
        return None if found is None else (found[0], f"return {found[1]};")
    leaf: Any = node.then
    while True:
        while type(leaf) is A.Compound and len(leaf.stmts) == 1:
            leaf = leaf.stmts[0]
        if type(leaf) is not A.If:
            break
        leaf = leaf.then
    assign = _single_assignment(leaf)
    if type(leaf) is A.Return:
        target = None
    elif assign is not None and fn.is_pure(assign.target):
        target = assign.target
    else:
        return None
    kinds: list[Any] = []
    value = _arm(fn, node, target, nest, kinds)
    if value is None or any(k != kinds[0] for k in kinds) or (target is not None and len(nest) < 2):
        return None
    if target is None:
        return "mix", f"return {value};"
    return "mix", f"{text(target)} = {value};"


def _arm(fn, stmt, target, nest: list, kinds: list) -> str | None:
    """The value an arm gives `target` (None: returns) as text: a single `target = v;` (or
    `return v;`) of a branch-free float value (`_value`), or an if/else of such arms on a
    condition `_indicator` makes a selector of (added to `nest`). None otherwise."""
    while type(stmt) is A.Compound and len(stmt.stmts) == 1:
        stmt = stmt.stmts[0]
    if type(stmt) is A.If:
        if stmt.else_ is None and target is None:
            return None
        cmp = _comparison(fn, stmt.cond, "float")
        indicator, sense = _step(*cmp) if cmp is not None else (_indicator(fn, stmt.cond), True)
        if indicator is None:
            return None
        a = _arm(fn, stmt.then, target, nest, kinds)
        # an inner if with no else keeps the variable's value (`else if (b) c = x;`)
        b = text(target) if stmt.else_ is None else _arm(fn, stmt.else_, target, nest, kinds)
        if a is None or b is None:
            return None
        nest.append(stmt)
        return f"mix({b}, {a}, {indicator})" if sense else f"mix({a}, {b}, {indicator})"
    value = None
    if target is None:
        value = stmt.value if type(stmt) is A.Return else None
    else:
        assign = _single_assignment(stmt)
        if assign is not None and fn.key(assign.target) == fn.key(target):
            value = assign.value
    if value is None or not _value(fn, value) or not _float_valued(fn, value):
        return None
    kinds.append(fn.model.type_of(value))
    return text(value)


def _returned(stmt) -> Any:
    """The value of an arm that is a single `return v;`, else None."""
    while type(stmt) is A.Compound and len(stmt.stmts) == 1:
        stmt = stmt.stmts[0]
    return stmt.value if type(stmt) is A.Return else None


def _float_valued(fn, e) -> bool:
    kind = fn.model.type_of(e)
    return getattr(kind, "base", None) == "float" and (kind.is_scalar or kind.is_vector)


def _negation_of(fn, e, v) -> bool:
    """`e` is `-v` (or `v * -1.0`, `-1.0 * v`)."""
    if type(e) is A.Unary and e.op == "-":
        return fn.key(e.operand) == fn.key(v)
    if type(e) is A.Binary and e.op == "*":
        for x, y in ((e.left, e.right), (e.right, e.left)):
            if numbers(fn.model.const_value(x)) == [-1.0] and fn.key(y) == fn.key(v):
                return True
    return False


def _stored_condition(fn, cond) -> Any:
    """The comparison a bool variable or field holds where it is read: the value last assigned
    to it (`frontFace = dot(d, n) < 0.0;`, `rec.frontFace = ...`) when that assignment is on
    every path to the read, nothing else writes the variable in between and nothing the value
    reads is written in between; else `cond` itself."""
    if type(cond) not in (A.Identifier, A.Field):
        return cond
    root = cond
    while type(root) is A.Field:
        root = root.base
    sym = fn.model.symbol_of(root) if type(root) is A.Identifier else None
    pos = fn.enter.get(id(cond))
    if sym is None or pos is None:
        return cond
    before = [w for w in fn.writes_to(sym) if w.pos < pos]
    if not before:
        return cond
    node = before[-1].node
    value = None
    if type(node) is A.Declarator and type(cond) is A.Identifier:
        value = node.init
    elif type(node) is A.Assignment and node.op == "=" and fn.key(node.target) == fn.key(cond):
        value = node.value
    if (
        value is None
        or not fn.dominates(node, cond)
        or fn.enclosing_loops(cond) != fn.enclosing_loops(node)
        or fn.written_between(node, cond, fn.operands(value))
    ):
        return cond
    return value


def _face_forward(fn, cond, a, b) -> tuple[str, str] | None:
    """`dot(i, n) < 0.0 ? n : -n` (the condition also through a bool variable or field that
    holds it, and its mirror images): what faceforward(n, i, n) computes, exactly."""
    if _negation_of(fn, b, a):
        n, sense = a, True  # n when the condition holds
    elif _negation_of(fn, a, b):
        n, sense = b, False
    else:
        return None
    value = _stored_condition(fn, cond)
    if type(value) is not A.Binary or value.op not in _OPS:
        return None
    left, op, right = value.left, value.op, value.right
    if numbers(fn.model.const_value(left)) == [0.0]:
        left, right, op = right, left, {"<": ">", "<=": ">=", ">": "<", ">=": "<="}[op]
    if numbers(fn.model.const_value(right)) != [0.0] or not builtin_call(fn.model, left, "dot"):
        return None
    # faceforward(n, i, n) is n exactly when dot(n, i) < 0.0
    if (op, sense) not in (("<", True), (">=", False)):
        return None
    assert isinstance(left, A.Call)  # builtin_call said so
    x, y = left.args
    i = y if fn.key(x) == fn.key(n) else x if fn.key(y) == fn.key(n) else None
    if i is None:
        return None
    return "faceforward", f"faceforward({text(n)}, {text(i)}, {text(n)})"


def _near(left, op, right) -> str:
    """The simpler step() that differs only where the two sides are equal."""
    edge, x = (right, left) if op in (">", ">=") else (left, right)
    return f" (or step({text(edge)}, {text(x)}) if equality may count)"


def _cheap(fn, e) -> bool:
    """A value, not a computation: a name, literal, field, swizzle, constant or constructor of
    those."""
    if fn.model.is_constant(e):
        return True
    t = type(e)
    if t in (A.Identifier, A.FloatLiteral, A.IntLiteral):
        return True
    if t is A.Field:
        return _cheap(fn, e.base)
    if t is A.Unary and e.op == "-":
        return _cheap(fn, e.operand)
    return False


# the texture lookups a mix() may take both of (a reading: the branch samples one of them)
_LOOKUPS = ("texture", "textureLod", "textureOffset", "textureProj", "texelFetch")


def _lookup(fn, e) -> bool:
    """A texture lookup of a named sampler whose other arguments are cheap values."""
    return (
        type(e) is A.Call
        and builtin_call(fn.model, e, *_LOOKUPS)
        and bool(e.args)
        and type(e.args[0]) is A.Identifier
        and all(_value(fn, a) for a in e.args[1:])
    )


def _picks_lookup(node) -> bool:
    """Whether a select's arms give a texture lookup (`if (c) col = texture(iChannel0, uv);`):
    the branch-free form samples every arm's texture, the branch one."""
    arms = [node.then, node.else_]
    return any(
        type(n) is A.Call and n.callee in _LOOKUPS
        for arm in arms
        if arm is not None
        for n in arm.walk()
    )


def _value(fn, e) -> bool:
    """A value mix() may compute on both sides: a cheap value (`_cheap`), or a constructor, a
    negation, a sum, difference or product of such, or one divided by a value that cannot be
    zero. No call: each side costs a few arithmetic operations; no division by what may be
    zero: the side the branch skipped would make an infinity that mix() turns into NaN."""
    if _cheap(fn, e):
        return True
    t = type(e)
    if t is A.Unary and e.op == "-":
        return _value(fn, e.operand)
    if t is A.Call:
        if _lookup(fn, e):
            return True
        return e.constructor and e.array is None and all(_value(fn, a) for a in e.args)
    if t is A.Binary and e.op in ("+", "-", "*"):
        return _value(fn, e.left) and _value(fn, e.right)
    if t is A.Binary and e.op == "/":
        lo, hi, _ = fn.value_range(e.right)
        nonzero = (lo is not None and lo > 0) or (hi is not None and hi < 0)
        return nonzero and _value(fn, e.left) and _value(fn, e.right)
    return False
