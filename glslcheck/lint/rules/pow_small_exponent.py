"""pow() with a small constant exponent that a multiply or a square root computes faster.

## What it does
Reports `pow(x, e)` where the exponent `e` is a constant (a literal or a folded constant
expression, every component equal) of 2, 3 or 4 (multiply `x` by itself), 0.5 (`sqrt`), -0.5
(`inversesqrt`), 1 (`x` itself) or -1 (`1.0 / x`); and, as a possible deduction (whether they
count as small is a reading), 8 and 16, three and four squarings (a Blinn-Phong exponent). The
constant may reach the call through local variables (`float highlight = 4.0; ... pow(specCo,
highlight)`) when that value reaches it on every path, with no other write between (the
dataflow's `reaching_value`), and through scalar arithmetic of such locals (`float eh = 2.0; eh
= eh * eh; ... pow(Ks, eh)`: 4).

The rubric deducts "per inefficient practice": the calls of one line (`pow(dx, 2.0) +
pow(dy, 2.0)`) are one finding that names each call, and so are the same calls written again on
other lines of the function (`pow(1.618, -1.)` on three lines); the fix rewrites every call.

## Why is this bad?
The course's coding standards: "Use the most efficient methods (-1 per inefficient/unnecessary
practices)". `pow` is evaluated as `exp2(e * log2(x))`: two transcendental functions where a
multiply or one square root does. It is also undefined for `x < 0`, where `x * x` is not.

## Example
```glsl
float attenuation = 1.0 / (1.0 + d / I + pow(d / I, 2.0));
float fresnel = pow(k, 4.0);
```

## Use instead
```glsl
float dI = d / I;
float attenuation = 1.0 / (1.0 + dI + dI * dI);
float k2 = k * k;
float fresnel = k2 * k2;
```
"""

from __future__ import annotations

from ...semantics.analysis import builtin_calls, numbers
from ..fixes import Fix, Fixable
from ..fixes.build import (
    declare_before,
    facts_of,
    fit,
    name_hint,
    node_text,
    operand_text,
    precedence,
    replace,
)
from ._text import at_lines, is_atom, text, wrap

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator
    from typing import Any

    from ...base.diagnostics import Diagnostic
    from ..engine import LintContext

NAME = "pow-small-exponent"
PENALTY = 1
STANDARD = "efficiency"
SEVERITY = "warning"
NEEDS = "ast"


def _replacement(e: float, base) -> str | None:
    x = text(base)
    if is_atom(base):
        v, pre = x, ""
    else:
        v, pre = "v", f"float v = {x}; then "
    return {
        2.0: f"{pre}{v} * {v}",
        3.0: f"{pre}{v} * {v} * {v}",
        4.0: f"{pre}float v2 = {v} * {v}; then v2 * v2",
        0.5: f"sqrt({x})",
        -0.5: f"inversesqrt({x})",
        1.0: f"{x}",
        -1.0: f"1.0 / {wrap(base)}",
        8.0: f"{pre}float v2 = {v} * {v}; float v4 = v2 * v2; then v4 * v4",
        16.0: f"{pre}float v2 = {v} * {v}; float v4 = v2 * v2; float v8 = v4 * v4; then v8 * v8",
    }.get(e)


# exponents reached by squaring three or four times: whether they count as small is a reading
SQUARINGS = {8.0: 3, 16.0: 4}


def small_exponent(fn, node) -> tuple[float, Any] | None:
    """(the exponent, the local it came through or None) when this rule reports the pow() call
    `node` of the function `fn`, else None."""
    value, through = fn.constant_through_locals(node.args[1])
    values = numbers(value)
    if not values or any(v != values[0] for v in values):
        return None
    if _replacement(values[0], node.args[0]) is None:
        return None
    return values[0], through


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    model = ctx.model
    if model is None:  # (no semantic model: no function has facts)
        return
    # The rubric deducts "per inefficient practice": the calls of one line are one practice, and
    # a line of the same calls written again in the function (`pow(g, -1.)` on three lines) is
    # that practice again, not a new one. One finding for each, naming every call.
    groups: dict[tuple, list[tuple]] = {}  # (function, line) -> [(call, exponent, local)]
    for fn, node in builtin_calls(model, ctx.path, "pow", arity=2):
        small = small_exponent(fn, node)
        if small is not None:
            groups.setdefault((id(fn), node.loc.line), []).append((node, *small))
    merged: dict[tuple, list[tuple]] = {}  # (function, the line's calls as text) -> calls
    for (fn_id, _), calls in groups.items():
        merged.setdefault((fn_id, tuple(text(c[0]) for c in calls)), []).extend(calls)
    for calls in merged.values():
        yield _finding(ctx, calls)


def _shown(e: float) -> str:
    return f"{e:g}" if e != int(e) else f"{int(e)}"


def _finding(ctx: LintContext, calls: list[tuple]) -> Fixable:
    node, e, through = calls[0]
    if len(calls) == 1:
        via = f" (through `{through.name}`)" if through is not None else ""
        if e in SQUARINGS:
            return Fixable(
                f"pow() with the constant exponent {_shown(e)}{via} costs two transcendentals "
                f"where {SQUARINGS[e]} squarings do (a possible deduction: whether "
                f"{_shown(e)} counts as a small exponent)",
                node.loc,
                help=f"write {_replacement(e, node.args[0])}",
                certainty="possible",
            )
        return Fixable(
            f"pow() with the constant exponent {_shown(e)}{via} costs two transcendentals",
            node.loc,
            help=f"write {_replacement(e, node.args[0])}",
            fix=_fix(ctx, node, e),
        )
    named = []
    for n, ne, nthrough in calls:
        via = f" through `{nthrough.name}`" if nthrough is not None else ""
        named.append(f"`{text(n)}` (exponent {_shown(ne)}{via})")
    distinct = list(dict.fromkeys(named))
    where = at_lines([c[0] for c in calls])
    listed = ", ".join(distinct[:-1]) + f" and {distinct[-1]}" if len(distinct) > 1 else named[0]
    helps = list(
        dict.fromkeys(f"{_replacement(ne, n.args[0])} for `{text(n)}`" for n, ne, _ in calls)
    )
    return Fixable(
        f"{len(calls)} pow() calls with small constant exponents at {where}, {listed}, cost two "
        "transcendentals each",
        node.loc,
        help="write " + "; ".join(helps),
        fix=_joined(ctx, [_fix(ctx, n, ne) for n, ne, _ in calls]),
        certainty="possible" if all(ne in SQUARINGS for _, ne, _ in calls) else None,
    )


def _joined(ctx: LintContext, fixes: list[Fix | None]) -> Fix | None:
    """The fixes of several calls as one: None when one has none, two touch the same text or
    two declare the same name (each was made as if it were alone)."""
    if any(f is None for f in fixes):
        return None
    real = [f for f in fixes if f is not None]
    declared = [e.text.split("=")[0].split()[-1] for f in real for e in f.edits if "=" in e.text]
    if len(set(declared)) < len(declared):
        return None
    if any(a.overlaps(b) for i, a in enumerate(real) for b in real[i + 1 :]):
        return None
    unsafe = [f for f in real if f.applicability != "safe"]
    return Fix(
        f"replace the {len(real)} pow() calls",
        ctx.path,
        tuple(e for f in real for e in f.edits),
        "unsafe" if unsafe else "safe",
        unsafe[0].why if unsafe else "",
    )


_MUL = 14  # the printer's precedence of `*` and `/`


def _fix(ctx: LintContext, node, e: float) -> Fix | None:
    """`x * x` for pow(x, 2.0) (a local first when x is not a name), `sqrt(x)` for 0.5, ...:
    the same value where pow is defined (x >= 0); where x may be negative pow is undefined and
    the rewrite is not, so the fix is unsafe there."""
    fn = facts_of(ctx, node)
    base = node.args[0]
    x = node_text(ctx, base)
    operand = operand_text(ctx, base, _MUL + 1)  # x as a factor: parenthesised when it must be
    if fn is None or x is None or operand is None:
        return None
    edits = []
    if e in SQUARINGS:
        return None  # (a reading, not a sure deduction: no fix offered)
    if e in (0.5, -0.5):
        new, binds = f"{'sqrt' if e > 0 else 'inversesqrt'}({x})", 16
    elif e == 1.0:
        new, binds = x, precedence(base)
    elif e == -1.0:
        new, binds = f"1.0 / {operand}", _MUL
    else:
        v = operand
        kind = fn.model.type_of(base)
        if not is_atom(base):
            found = declare_before(ctx, fn, node, kind, x, name_hint(base))
            if found is None:
                return None
            v, insert = found
            edits.append(insert)
        if e == 4.0:
            hint = (name_hint(base) if is_atom(base) else v) + "Sq"
            found = declare_before(ctx, fn, node, kind, f"{v} * {v}", hint)
            if found is None:
                return None
            v2, insert = found
            edits.append(insert)
            new = f"{v2} * {v2}"
        else:
            new = " * ".join([v] * int(e))
        binds = _MUL
    edits.append(replace(node, fit(fn, node, new, binds)))
    nonneg = e in (0.5, -0.5) or _nonnegative(fn, base)
    return Fix(
        f"replace the pow() call with {new}",
        ctx.path,
        tuple(edits),
        "safe" if nonneg else "unsafe",
        ""
        if nonneg
        else "pow() is undefined for a negative base and the rewrite is not: the "
        "picture changes wherever the base is negative",
    )


def _nonnegative(fn, e) -> bool:
    lo = fn.value_range(e)[0]
    return lo is not None and lo >= 0
