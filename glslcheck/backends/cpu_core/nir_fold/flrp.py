"""`mix` as nir_lower_flrp lowers it: the formula chosen from what the compiler knows, or a
select where the weight is a bool converted to float.

Mesa 22.3 has no FFMA on llvmpipe, so nir_lower_flrp rewrites every ``flrp`` (GLSL's `mix`)
into one of three formulas, ``x + t*(y-x)``, ``x*(1-t) + y*t`` or a form for x = ±1, and the
choice depends on the operands (constants, their magnitudes) and on the other `mix` calls of
the function that share t and x or y (get_similar_flrp_stats). The formulas round
differently, so :func:`mix_form` decides from the source, where a one-pixel probe run picks
what the render picks: the NumPy transpiler passes the form to ``rt.mix`` (the rest of the
choice is made at run time, `Runtime._flrp_form`), the compiled engine writes its formula
(builtin_calls.mix_call).

Before the lowering, nir_opt_algebraic's ``('~flrp', a, b, ('b2f', 'c@1')) -> ('bcsel', c, b,
a)`` makes a `mix` whose weight NIR sees as a bool converted to float a select, the other side
ignored (NaN included). :func:`b2f_weight` tells that form from the source; measured on
llvmpipe (Mesa 22.3, docs/llvmpipe.md "mix weights that select"): ``step()``, ``float(bool)``,
``c ? 1.0 : 0.0`` and ``c ? 0.0 : 1.0``, their products, min, max, abs, clamp to [0, 1] and
``* 1.0``, through locals, calls and parameters select; ``1.0 - step()``, ``step() +
step()``, a saturated ``clamp()``, ``floor``, ``sign`` and ``smoothstep`` interpolate even
where the weight is exactly 0 or 1."""

from __future__ import annotations

import numpy as np

from ....frontend import syntax as A
from ....frontend.printer import to_glsl
from ..inline import bound_argument
from .inlined_results import called_function, only_return
from .queries import (
    asked_in,
    constant_value,
    current_function,
    is_builtin,
    reaching_value,
    written_symbols,
)

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..fold_protocols import FoldEngine


def mix_form(tr: FoldEngine, call: A.Call) -> str | tuple[str, ...] | None:
    """The formula nir_lower_flrp (Mesa 22.3, no FFMA on llvmpipe) picks for each component of this
    float-weighted `mix` (llvmpipe lowers it to scalars first), in its order: x and y constants
    whose exponents differ by at most 11 -> "fast" ``x + t*(y-x)``; x a constant +1 / -1 -> "one" /
    "minus_one"; y a constant +1 or -1 -> "strict" ``x*(1-t) + y*t``; another scalar flrp of the
    function (another component included) with the same t and the same x (or y) -> "strict"; a
    constant t -> "strict"; else "fast". "Constant": a constant expression or a never-written local
    initialised by one (NIR propagates it); "the same": the same value or GLSL text (SSA after CSE).
    One form, or a tuple of one per component where they differ; None for a `mix` with a bool weight
    or outside a function. Decided here, from the source, so a one-pixel probe run picks what the
    render picks. Before all these: a weight NIR sees as a bool converted to float -> "select"
    (:func:`b2f_weight`)."""
    if len(call.args) != 3 or tr.fn is None or tr.type_of(call.args[2]).base != "float":
        return None
    x, y, t = call.args
    if b2f_weight(tr, t):
        return "select"
    size = tr.type_of(call).size if tr.type_of(call).is_vector else 1
    forms = [_component_form(tr, call, c) for c in range(size)]
    return forms[0] if len(set(forms)) == 1 else tuple(forms)


def _component_form(tr: FoldEngine, call: A.Call, c: int) -> str:
    """The form of component `c` of a `mix`: llvmpipe lowers it to scalars before
    nir_lower_flrp, so each component has its operands and its similar flrps."""
    kx, ky, kt = (_scalar(tr, a, c) for a in call.args)
    if kx[0] == "k" and ky[0] == "k" and _similar([kx[1]], [ky[1]]):
        return "fast"
    if kx in (("k", 1.0), ("k", -1.0)):
        return "one" if kx[1] == 1.0 else "minus_one"
    if ky in (("k", 1.0), ("k", -1.0)):
        return "strict"
    if (id(call), c) in _shared_mixes(tr) or kt[0] == "k":
        return "strict"
    return "fast"


def _scalar(tr: FoldEngine, e: A.Node, c: int) -> tuple:
    """What NIR sees as component `c` of operand `e`, as a key: ("k", value) for a constant,
    the GLSL text of a scalar (a float, or the one argument of a ``vec3(s)``: every component
    the same value after CSE), else the text and the component."""
    v = constant_value(tr, e)
    if v is not None:
        return ("k", v[c] if len(v) > 1 else v[0])
    if tr.type_of(e).is_scalar:
        return ("e", to_glsl(e))
    if isinstance(e, A.Call) and e.constructor and len(e.args) == 1:
        if tr.type_of(e.args[0]).is_scalar:
            return ("e", to_glsl(e.args[0]))
    return ("e", to_glsl(e), c)


def _similar(a: list[float], b: list[float]) -> bool:
    """``sources_are_constants_with_similar_magnitudes``: frexp exponents at most 11 apart."""
    import math

    n = max(len(a), len(b))
    a, b = a * (n // len(a)), b * (n // len(b))
    return all(abs(math.frexp(p)[1] - math.frexp(q)[1]) <= 11 for p, q in zip(a, b))


def _shared_mixes(tr: FoldEngine) -> set[tuple[int, int]]:
    """(id(call), component) of the scalar flrps of the current function's float-weighted mix
    calls that share t and x (or t and y) with another scalar flrp (get_similar_flrp_stats,
    after the lowering to scalars)."""
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
        flrps = []
        for n in calls:
            size = tr.type_of(n).size if tr.type_of(n).is_vector else 1
            flrps += [((id(n), c), [_scalar(tr, a, c) for a in n.args]) for c in range(size)]
        cache[key] = {
            k
            for k, (x, y, t) in flrps
            if any(m != k and t == t2 and (x == x2 or y == y2) for m, (x2, y2, t2) in flrps)
        }
    return cache[key]


_BOOL_FLOAT = ("min", "max", "abs")  # of b2f values: a b2f value again (nir_opt_algebraic)


def b2f_weight(tr: FoldEngine, e: A.Node, depth: int = 0) -> bool:
    """NIR sees `e`, a float expression of the function being emitted, as ``b2f`` of a bool
    after inlining and nir_opt_algebraic: ``step()``, ``float(bool)``, ``c ? 1.0 : 0.0`` (or
    ``0.0 : 1.0``), a component of one, their products, min, max, abs, clamp to [0, 1],
    ``* 1.0``, a local whose reaching value is one, a parameter every call passes one to, a
    call of a user function that returns one. Anything else (``1.0 - step()``: measured) is
    arithmetic to NIR."""
    if depth > 8:
        return False
    d = depth + 1
    if isinstance(e, A.Call) and e.constructor:  # float(bool), vec3(b2f, ...): components
        return all(tr.type_of(a).base == "bool" or b2f_weight(tr, a, d) for a in e.args)
    if isinstance(e, A.Call) and is_builtin(tr, e):
        if e.callee == "step":
            return True
        if e.callee in _BOOL_FLOAT:
            return all(b2f_weight(tr, a, d) for a in e.args)
        if e.callee == "clamp" and len(e.args) == 3:
            bounds = [constant_value(tr, b) for b in e.args[1:]]
            return bounds == [[0.0], [1.0]] and b2f_weight(tr, e.args[0], d)
        return False
    if isinstance(e, A.Call):
        fn = called_function(tr, e)
        value = None if fn is None else only_return(tr, fn)
        if fn is None or value is None:
            return False
        with asked_in(tr, fn):
            return b2f_weight(tr, value, d)
    if isinstance(e, A.Ternary):
        arms = [constant_value(tr, e.then), constant_value(tr, e.else_)]
        return arms in ([[1.0], [0.0]], [[0.0], [1.0]])
    if isinstance(e, A.Field):
        return b2f_weight(tr, e.base, d)
    if isinstance(e, A.Binary) and e.op == "*":  # b2f factors, constants of product 1
        factors = _factors(e)
        ks = [constant_value(tr, f) for f in factors]
        product = np.float32(1.0)
        for k in ks:
            product = product * np.float32(k[0]) if k is not None and len(k) == 1 else product
        others = [f for f, k in zip(factors, ks) if k is None]
        return product == 1.0 and bool(others) and all(b2f_weight(tr, f, d) for f in others)
    if isinstance(e, A.Binary) and e.op == "-" and constant_value(tr, e.left) == [1.0]:
        inner = e.right  # 1.0 - (1.0 - b): b
        return (
            isinstance(inner, A.Binary)
            and inner.op == "-"
            and constant_value(tr, inner.left) == [1.0]
            and b2f_weight(tr, inner.right, d)
        )
    if isinstance(e, A.Identifier):
        return _b2f_variable(tr, e, d)
    return False


def _factors(e: A.Node) -> list:
    if isinstance(e, A.Binary) and e.op == "*":
        return _factors(e.left) + _factors(e.right)
    return [e]


def _b2f_variable(tr: FoldEngine, e: A.Identifier, depth: int) -> bool:
    """A local whose value here is a b2f one, or a parameter (of an inlined call: its argument;
    of the function being emitted: every call's argument, NIR inlines each)."""
    sym = tr.model.symbol_of(e)
    if sym is None:
        return False
    bound = bound_argument(tr, sym)
    if bound is not None:
        return b2f_weight(tr, bound, depth)
    value = reaching_value(tr, e)
    if value is not None:
        return b2f_weight(tr, value, depth)
    if sym.kind != "param" or id(sym) in written_symbols(tr):
        return False
    fn = current_function(tr).sym
    index = [i for i, p in enumerate(fn.node.proto.params) if tr.model.symbol_of(p) is sym]
    calls = [
        (caller, c)
        for caller in tr.model.reachable_functions()
        for c in caller.node.body.walk()
        if isinstance(c, A.Call) and tr.model.call_target(c) is fn
    ]
    if not index or not calls:
        return False
    for caller, c in calls:
        with asked_in(tr, caller):
            if not b2f_weight(tr, c.args[index[0]], depth):
                return False
    return True
