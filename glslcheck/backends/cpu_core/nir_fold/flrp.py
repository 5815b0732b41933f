"""`mix` as nir_lower_flrp lowers it: the formula chosen from what the compiler knows.

Mesa 22.3 has no FFMA on llvmpipe, so nir_lower_flrp rewrites every ``flrp`` (GLSL's `mix`)
into one of three formulas, ``x + t*(y-x)``, ``x*(1-t) + y*t`` or a form for x = ±1, and the
choice depends on the operands (constants, their magnitudes) and on the other `mix` calls of
the function that share t and x or y (get_similar_flrp_stats). The formulas round
differently, so :func:`mix_hint` passes the choice to ``rt.mix`` from the source, where a
one-pixel probe run picks what the render picks; the rest of the choice is made at run time
(`Runtime._flrp_form`). The compiled engine asks the same question (builtin_calls.mix_call)."""

from __future__ import annotations

from ....frontend import syntax as A
from ....frontend.printer import to_glsl
from .queries import constant_value, current_function, is_builtin

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..fold_protocols import FoldEngine


def mix_hint(tr: FoldEngine, call: A.Call) -> list[str]:
    """The extra argument of ``rt.mix``: the formula nir_lower_flrp (Mesa 22.3, no FFMA on
    llvmpipe) picks for this float-weighted `mix`, in its order: x and y constants whose
    exponents differ by at most 11 -> "fast" ``x + t*(y-x)``; x a constant of all +1 / -1 ->
    "one" / "minus_one"; y a constant of all +1 or -1 -> "strict" ``x*(1-t) + y*t``; another
    mix of the function with the same t and the same x (or y) -> "strict"; a constant t ->
    "strict"; else "fast". "Constant": a constant expression or a never-written local
    initialised by one (NIR propagates it); "the same": the same GLSL text (SSA after CSE).
    Decided here, from the source, so a one-pixel probe run picks what the render picks."""
    if len(call.args) != 3 or tr.fn is None or tr.type_of(call.args[2]).base != "float":
        return []
    x, y, t = call.args
    cx, cy = constant_value(tr, x), constant_value(tr, y)
    if cx is not None and cy is not None and _similar(cx, cy):
        return ["'fast'"]
    for v, form in ((cx, "one"), (cy, "strict")):
        if v is not None and len(set(v)) == 1 and v[0] == 1.0:
            return [f"'{form}'"]
        if v is not None and len(set(v)) == 1 and v[0] == -1.0:
            return [f"'{'minus_one' if form == 'one' else form}'"]
    if id(call) in _shared_mixes(tr) or constant_value(tr, t) is not None:
        return ["'strict'"]
    return ["'fast'"]


def _similar(a: list[float], b: list[float]) -> bool:
    """``sources_are_constants_with_similar_magnitudes``: frexp exponents at most 11 apart."""
    import math

    n = max(len(a), len(b))
    a, b = a * (n // len(a)), b * (n // len(b))
    return all(abs(math.frexp(p)[1] - math.frexp(q)[1]) <= 11 for p, q in zip(a, b))


def _shared_mixes(tr: FoldEngine) -> set[int]:
    """Float-weighted mix calls of the current function that share t and x (or t and y) with
    another one (get_similar_flrp_stats)."""
    cache = tr.fold_state.mix
    key = id(current_function(tr).sym)
    if key not in cache:
        calls = [
            n
            for n in current_function(tr).sym.node.body.walk()
            if isinstance(n, A.Call)
            and n.callee == "mix"
            and len(n.args) == 3
            and is_builtin(tr, n)
            and tr.type_of(n.args[2]).base == "float"
        ]
        texts = [(n, [to_glsl(a) for a in n.args]) for n in calls]
        cache[key] = {
            id(n)
            for n, (x, y, t) in texts
            if any(m is not n and t == t2 and (x == x2 or y == y2) for m, (x2, y2, t2) in texts)
        }
    return cache[key]
