"""pow() with a small constant exponent that a multiply or a square root computes faster.

## What it does
Reports `pow(x, e)` where the exponent `e` is a constant (a literal or a folded constant
expression, every component equal) of 2, 3 or 4 (multiply `x` by itself), 0.5 (`sqrt`), -0.5
(`inversesqrt`), 1 (`x` itself) or -1 (`1.0 / x`). The constant may reach the call through
local variables (`float highlight = 4.0; ... pow(specCo, highlight)`) when that value reaches
it on every path, with no other write between (the dataflow's `reaching_value`), and through
scalar arithmetic of such locals (`float eh = 2.0; eh = eh * eh; ... pow(Ks, eh)`: 4).

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
from ._text import is_atom, text, wrap

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

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
    }.get(e)


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    model = ctx.model
    if model is None:  # (no semantic model: no function has facts)
        return
    for fn, node in builtin_calls(model, ctx.path, "pow", arity=2):
        value, through = fn.constant_through_locals(node.args[1])
        values = numbers(value)
        if not values or any(v != values[0] for v in values):
            continue
        fix = _replacement(values[0], node.args[0])
        if fix is None:
            continue
        e = values[0]
        shown = f"{e:g}" if e != int(e) else f"{int(e)}"
        via = f" (through `{through.name}`)" if through is not None else ""
        yield Fixable(
            f"pow() with the constant exponent {shown}{via} costs two transcendentals",
            node.loc,
            help=f"write {fix}",
            fix=_fix(ctx, node, e),
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
