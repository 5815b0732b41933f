"""Mesa's NIR rewrites that change float32 bits, emitted by the transpiler for llvmpipe mode.

Mesa 22.3's compiler reassociates float arithmetic that GLSL ES 3.00 leaves unordered (no
`precise`): nir_opt_algebraic's inexact (`~`) rules rewrite the written expression, so llvmpipe
computes other float32 roundings than the source spells. A hash (`fract(x * 43758.5453)`)
amplifies the last bit, so verify mismatches unless the NumPy backend rewrites the same way.
The rules copied here, each measured bit for bit against llvmpipe on 50,000 random operands
(tests/gl/test_llvmpipe_lowering.py):

- factoring (``('~fadd', ('fmul', a, b), ('fmul', a, c)) -> a * (b + c)``): ``a*b + c*a``
  is ``a * (b + c)``; NIR sees through SSA values, so a product stored in a local that is
  never written again counts too (``vec2 uv = 50.0 * f; ... uv.x + uv.y`` is
  ``50.0 * (f.x + f.y)``);
- constants sunk into a sum (``(a + b) + #c -> (a + #c) + b``, both sums used once, a and b
  not constant; the variant that keeps a product ``b`` whole is tried first, so
  ``(a*b + c) + K`` is ``(c + K) + a*b``); subtraction is addition of the negation; the new
  sum is matched again, so the constant sinks down a chain of sums used once, also through
  a local read once (:func:`_sink_sum`: iq's noise);
- the same for products (``(a * b) * #c -> (a * #c) * b``, also ``#c * (a * b)``), also past a
  broadcast operand (a vector times a scalar), where a factor is a variable a folded call
  wrote as a sum (:func:`_settled`), a never-written product by a constant or ``1.0 / y``
  (:func:`_scaled`), the constant possibly a never-written local (:func:`_local_constant`):
  gargantua's ``eyevec * dither * far`` is ``(eyevec * far) * dither``; a factor
  ``normalize(x)`` read once takes the constant on into x, ``((x * #c) *
  inversesqrt(dot(x, x))) * b`` (:func:`_normalized_once`);
- constants merged (``#a * (b * #c) -> (a*c) * b``, ``#a + (b + #c) -> (a + c) + b``, with
  no "used once" condition, so also through a never-written local: ``uv = q * 1.2`` then
  ``uv * 0.2`` is ``q * 0.24``, the constant folded in float32);
- ``dot(u, v) + #c``: the constant lands in the innermost addition of the dot product, which
  llvmpipe sums right to left: ``u.x*v.x + (u.y*v.y + (u.z*v.z + #c))``; a squared length
  ``pow(length(x), 2.0)`` or ``pow(distance(x, #0), 2.0)`` is that dot product
  (``sqrt(a)*sqrt(a) -> a``), with the constant inside unless another length, normalize or dot
  of x shares it (:func:`_squared_length`, :func:`_shared_dot`);
- a sum of two products returned through a folded call (transpile/call_fold.py) and read once,
  ``(p1 + p2) + e``, is ``(p1 + e) + p2``: llvmpipe fuses ``p1 + p2`` into an ffma, moves e
  into its addend and splits it again (fuse_ffma32 with lower_ffma32: :func:`_fused_after_call`,
  measured; inside one written expression, ``(a*b + c*d) + e``, measured the same but not
  copied);
- constants merged into a dot product, ``dot(x * #c, #K)`` is ``dot(x, K * c)``, tree by tree
  (:func:`merged_dot`), also through the parameter of a call inlined for it
  (transpile/inline.py: Mesa inlines every function before these passes);
- a constant added to a call's result sinks into the ``+=`` chain the function returns
  (:func:`sunk_return`: ``displacement(x) - 0.4`` of iq's terrain);
- NIR sees SSA values: a variable assigned again still stands for its value, so ``p = m*p*2.02;
  p = m*p*2.03`` is ``(m*2.02) * (m*p)`` for a constant matrix m, and ``(y * #c) * #k`` is
  ``y * (c*k)`` through such a variable too (:func:`_keep_factor`, :func:`_merge_into_matrix`);
- NIR splits vectors into components (SSA per component): a component written as ``y * #c``
  (or a whole local so written) merges with a later ``*=`` or ``*`` by a constant, also through
  a copy ``q = r + 0.0``, the constants folded right to left (nir_opt_algebraic visits the last
  instruction first): gargantua's ``radialCoords.z = distFromDisc * 1.5; radialCoords *= 0.95;``
  is ``distFromDisc * (1.5*0.95)`` (:func:`component_write`, :func:`_merge_components`); a
  component's ``+= e`` undone by a later ``-= e`` is its value before (``('~fadd', ('fneg',
  a), ('fadd', a, b)) -> b``, :func:`_cancelled_sum`); ``x *= b; ... x * #c`` with the new x
  read once is ``(a * #c) * b``, one level deep (:func:`_sunk_through_compound`);
- a call's result returned from inside a branch, made under a mask in a function that takes
  derivatives, keeps in the lanes the mask leaves out the value of the last time it ran for
  them, in a loop NIR does not unroll: llvmpipe's register for the merged returns, read by a
  neighbour's derivative (:func:`register_call`, frame.Lanes.reg);
- constants are what Mesa knows as constants: also a global variable initialised by a
  constant expression and never written (:func:`_constant_global`: GLSL IR propagates it);
- an added constant zero dropped, ``fadd(a, 0.0) -> a`` (:func:`zero_add`, ``Runtime.fadd``),
  also where the zero comes through a function argument or an out parameter
  (transpile/constant_flow.py): it keeps the sign of a -0.0.

Not a rewrite of the order but of the type: arithmetic on lowp lookups (Shadertoy's iChannels
are lowp) is float16 on llvmpipe (Mesa's lower_precision.cpp), copied for trees of ``+ - * /``
over lookups and constants, ``pow(x, 2.0)`` among them as ``x * x`` with a constant factor sunk
into it, ``(x * #k) * x`` (:func:`lowp_tree`, :func:`_square`).

Each rewrite is emitted as ``(<rewritten> if rt.lp else <written>)``: float32 renders take
Mesa's order, float64 (the accuracy reference) and float16 keep the written one. Not copied
(measured, left as written): chains GLSL IR rebalances before NIR sees them, such as
``(a + b + c) + K`` of variables (llvmpipe gives ``(a + b) + (c + K)``: do_rebalance_tree),
other rewrites that reach across a call (NIR inlines every function: followed are a constant
added to a returned ``+=`` chain, :func:`sunk_return`, products by constants merged into a
``dot`` through an argument, transpile/inline.py, and constants a call site passes in, folded
and merged through the callee's arithmetic, matrix products included, for straight-line
callees: transpile/call_fold.py, gargantua's camera rotation ``(cos(-0.45)*10) * sin(x)``),
and a squared length that is not followed by a constant sum (``sqrt(a)*sqrt(a)`` stays).

`mix` is lowered by nir_lower_flrp, whose choice depends on the other `mix` calls of the
shader (:func:`mix_hint`); the rest of that choice is made at run time (`Runtime._flrp_form`).
"""

from __future__ import annotations

from typing import Any

from ...frontend import syntax as A
from ...language import builtin_functions as B
from ...semantics.analysis import param_directions
from ...semantics.model import Symbol
from ...base.diagnostics import Location
from ...frontend.printer import to_glsl
from ...language.glsl_types import FLOAT
from ..cpu_core.common import TEXTURE_FUNCTIONS
from ..cpu_core.facts import induction_variable
from .transpile.call_fold import out_roots, product_sums
from .transpile.constant_flow import constant_flow
from .transpile.inline import bound_argument, inline_owner

_SUMS = ("+", "-")


# -- mix: nir_lower_flrp's choice, decided from what the compiler knows -------------------------
def mix_hint(tr: Any, call: A.Call) -> list[str]:
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
    cx, cy = _constant_value(tr, x), _constant_value(tr, y)
    if cx is not None and cy is not None and _similar(cx, cy):
        return ["'fast'"]
    for v, form in ((cx, "one"), (cy, "strict")):
        if v is not None and len(set(v)) == 1 and v[0] == 1.0:
            return [f"'{form}'"]
        if v is not None and len(set(v)) == 1 and v[0] == -1.0:
            return [f"'{'minus_one' if form == 'one' else form}'"]
    if id(call) in _shared_mixes(tr) or _constant_value(tr, t) is not None:
        return ["'strict'"]
    return ["'fast'"]


def _constant_value(tr: Any, node: Any) -> list[float] | None:
    """The scalars of a constant operand (see :func:`mix_hint`), else None."""
    v = tr.model.const_value(node)
    if v is None and isinstance(node, A.Identifier) and _constant_global(tr, tr.model.symbol_of(node)):
        v = tr.model.const_value(tr.model.symbol_of(node).node.init)
    if v is None and isinstance(node, A.Identifier):
        init = _stable_init(tr, node)
        v = tr.model.const_value(init) if init is not None else None
    if v is None:
        return None
    flat: list[float] = []
    stack = [v]
    while stack:
        item = stack.pop(0)
        if isinstance(item, (tuple, list)):
            stack[:0] = list(item)
        else:
            flat.append(float(item))
    return flat


def _similar(a: list[float], b: list[float]) -> bool:
    """``sources_are_constants_with_similar_magnitudes``: frexp exponents at most 11 apart."""
    import math

    n = max(len(a), len(b))
    a, b = a * (n // len(a)), b * (n // len(b))
    return all(abs(math.frexp(p)[1] - math.frexp(q)[1]) <= 11 for p, q in zip(a, b))


def _shared_mixes(tr: Any) -> set[int]:
    """Float-weighted mix calls of the current function that share t and x (or t and y) with
    another one (get_similar_flrp_stats)."""
    cache = tr.fold_state.mix
    key = id(tr.fn.sym)
    if key not in cache:
        calls = [n for n in tr.fn.sym.node.body.walk() if isinstance(n, A.Call) and n.callee == "mix"
                 and len(n.args) == 3 and _builtin(tr, n) and tr.type_of(n.args[2]).base == "float"]
        texts = [(n, [to_glsl(a) for a in n.args]) for n in calls]
        cache[key] = {id(n) for n, (x, y, t) in texts
                      if any(m is not n and t == t2 and (x == x2 or y == y2) for m, (x2, y2, t2) in texts)}
    return cache[key]


# -- an added constant zero ---------------------------------------------------------------------
def zero_add(tr: Any, e: A.Binary, left: str, right: str) -> str | None:
    """``rt.fadd(l, r)`` / ``rt.fsub(l, r)`` for a float ``+`` / ``-`` whose operand may be a
    constant zero once Mesa has inlined the function, else None (the plain operator).

    Mesa 22.3's nir_opt_algebraic drops ``fadd(a, 0.0)`` (``('fadd(is_only_used_as_float)',
    'a@32', 0.0) -> a``; llvmpipe lowers ``a - b`` to ``fadd(a, fneg(b))``), which keeps the
    sign of a -0.0 that IEEE addition would make +0.0. NIR applies it after inlining every
    function, so the zero may come through an argument or an out parameter, not only a
    literal: `transpile.constant_flow` finds the operands that may be one, and the runtime
    (`Runtime.fadd`) checks the value they hold. Elsewhere, the common case, the operator
    stays a NumPy operator without a Python call."""
    if e.op not in _SUMS or tr.fn is None:
        return None
    if any(tr.type_of(x).base != "float" for x in (e, e.left, e.right)):
        return None
    flow = constant_flow(tr)
    if not (flow.may_be_zero_constant(e.left) or flow.may_be_zero_constant(e.right)):
        return None
    return f"rt.{'fadd' if e.op == '+' else 'fsub'}({left}, {right})"


# -- arithmetic on lowp lookups: float16 -------------------------------------------------------
_LOWP_OPS = ("+", "-", "*", "/")


def lowp_tree(tr: Any, e: A.Binary, mask: str | None) -> str | None:
    """``e`` computed in float16 where llvmpipe does, else None.

    Mesa's GLSL compiler lowers GLSL ES precision to float16 (glsl/lower_precision.cpp, on
    for llvmpipe): an operation whose operands are all lowp or mediump runs in float16, a
    constant taking its partner's precision (rounded to float16 to nearest), and the result
    is converted to float32 where a highp operand or variable takes it. Shadertoy's iChannels
    are lowp sampler2D (backends/numpy_engine/textures.py), so ``2.1 + 0.1*textureLod(iChannel2, uv,
    0.0).x`` (elephant's terrain height) is two float16 operations on llvmpipe: 2.130859375
    where float32 gives 2.1319335. Copied for trees of ``+ - * /`` and negation whose leaves
    are literal constants (a `const` variable or a never-written global is a highp variable
    here, measured) and lookups on an iChannel (swizzled or not), at least one lookup; measured
    bit for bit (tests/gl/test_llvmpipe_lowering.py). Emitted as ``(rt.lowp_full(<float16
    tree>) if rt.lowp_arith(<samplers>) else <written>)``: float64 and float16 renders, and
    samplers that are not lowp (the WebGL comparison's), keep float32. ``pow(x, 2.0)`` is
    ``x * x`` there (:func:`_square`, measured). Not copied: other built-in calls on such
    values (``smoothstep(0.3, 0.4, texture(..).x)`` is float16 on llvmpipe too,
    not measured), lookups through a sampler parameter, mediump/lowp variables (see
    glslcheck/semantics/mediump.py), and NIR's reassociations inside the float16 tree."""
    if tr.fn is None or getattr(tr, "lowp_written", None) is not None and id(e) in tr.lowp_written:
        return None
    memo = tr.fold_state.lowp  # id(node) -> kind: linear in a chain
    if _lowp_kind(tr, e, memo) != "low" or tr.has_effects(e):
        return None
    nodes: list[Any] = []
    samplers: list[Any] = []
    _lowp_parts(e, memo, nodes, samplers)
    low = _lowp_code(tr, e, mask, {id(n) for n in nodes})
    tr.lowp_written = {id(n) for n in nodes}  # the written form: this tree without the rule
    try:
        written = tr.expr(e, mask)
    finally:
        tr.lowp_written = None
    used = ", ".join(dict.fromkeys(tr.expr(s, mask) for s in samplers))
    return f"(rt.lowp_full({low}) if rt.lowp_arith({used}) else {written})"


def _lowp_kind(tr: Any, node: Any, memo: dict[int, Any]) -> str | None:
    """"const" (a literal constant), "lookup" (an iChannel lookup, swizzled or not), "low" (an
    operation float16 on llvmpipe) or None (float32) for a node of such a tree (memoised)."""
    key = id(node)
    if key not in memo:
        memo[key] = _lowp_kind_of(tr, node, memo)
    return memo[key]


def _lowp_kind_of(tr: Any, node: Any, memo: dict[int, Any]) -> str | None:
    if isinstance(node, (A.FloatLiteral, A.IntLiteral)):
        return "const"
    if isinstance(node, A.Identifier):
        return None  # (a `const` variable or a never-written global is highp: measured,
        # `const float K = 0.1; K * texture(..).x` is float32 on llvmpipe)
    kids = list(node.children())
    if tr.model.const_value(node) is not None:
        # literals only; a zero is left to the float32 forms (Mesa drops `x + 0.0` and
        # `x * 0.0`, a NaN operand too)
        if not all(_lowp_kind(tr, k, memo) == "const" for k in kids) or not all(_constant_value(tr, node) or [0.0]):
            return None
        return "const"
    t = tr.type_of(node)
    if t.base != "float" or t.is_matrix or t.is_array:
        return None
    if isinstance(node, A.Field):
        return "lookup" if _lowp_kind(tr, node.base, memo) == "lookup" else None
    if isinstance(node, A.Call) and _square(tr, node):
        return "low" if _lowp_kind(tr, node.args[0], memo) in ("low", "lookup") else None
    if isinstance(node, A.Call):
        sampler = node.args[0] if node.args else None
        sym = tr.model.symbol_of(sampler) if isinstance(sampler, A.Identifier) else None
        if (getattr(tr.model.call_target(node), "name", None) not in TEXTURE_FUNCTIONS or sym is None
                or sym.kind != "uniform" or str(tr.type_of(sampler)) != "sampler2D"):
            return None
        return "lookup"
    if isinstance(node, A.Unary) and node.op == "-":
        return "low" if _lowp_kind(tr, node.operand, memo) in ("low", "lookup") else None
    if isinstance(node, A.Binary) and node.op in _LOWP_OPS:
        kinds = {_lowp_kind(tr, node.left, memo), _lowp_kind(tr, node.right, memo)}
        return None if None in kinds or kinds == {"const"} else "low"
    return None


def _square(tr: Any, node: A.Call) -> bool:
    """``pow(x, 2.0)`` (a vector of 2.0 too) of the built-in: x * x to NIR (``fpow(a, 2.0) ->
    a * a``), in float16 for a float16 x (gargantua's ``pow(texture(..).rgb, vec3(2.0)) * 4.0``)."""
    return (node.callee == "pow" and len(node.args) == 2 and _builtin(tr, node)
            and set(_constant_value(tr, node.args[1]) or [0.0]) == {2.0})


def _lowp_parts(node: Any, memo: dict[int, Any], nodes: list[Any], samplers: list[Any]) -> None:
    """The operation nodes of a float16 tree and the samplers its lookups read."""
    kind = memo.get(id(node))
    if kind == "low":
        nodes.append(node)
        for k in (node.operand,) if isinstance(node, A.Unary) else node.args[:1] if isinstance(node, A.Call) else (node.left, node.right):
            _lowp_parts(k, memo, nodes, samplers)
    elif kind == "lookup":
        while isinstance(node, A.Field):
            node = node.base
        samplers.append(node.args[0])


def _lowp_code(tr: Any, node: Any, mask: str | None, ops: set[int]) -> str:
    """The float16 code of a tree found by :func:`_lowp_kind`: leaves rounded to float16
    (``rt.half``), each operation a NumPy float16 operation (one rounding each)."""
    if id(node) not in ops:
        return f"rt.half({tr.expr(node, mask)})"
    if isinstance(node, A.Unary):
        return f"(-{_lowp_code(tr, node.operand, mask, ops)})"
    if isinstance(node, A.Call):  # pow(x, 2.0): x * x, x computed once
        x = tr.fresh("h")
        return f"(({x} := {_lowp_code(tr, node.args[0], mask, ops)}) * {x})"
    square, k = (node.left, node.right) if isinstance(node.left, A.Call) else (node.right, node.left)
    if node.op == "*" and isinstance(square, A.Call) and id(square) in ops and tr.model.const_value(k) is not None:
        # (x*x) * #k, the square used once: (x * #k) * x (``(a*b)*#c -> (a*#c)*b``)
        x = tr.fresh("h")
        xk = f"(({x} := {_lowp_code(tr, square.args[0], mask, ops)}) * {_lowp_code(tr, k, mask, ops)})"
        return f"({xk} * {x})"
    return f"({_lowp_code(tr, node.left, mask, ops)} {node.op} {_lowp_code(tr, node.right, mask, ops)})"


# -- binary expressions -----------------------------------------------------------------------
def binary(tr: Any, e: A.Binary, mask: str | None) -> str | None:
    """The generated code of ``e`` when a rule above rewrites it, else None."""
    low = lowp_tree(tr, e, mask) if e.op in _LOWP_OPS else None
    if low is not None:
        return low
    if e.op not in ("+", "-", "*") or tr.fn is None:
        return None
    if tr.type_of(e).base != "float":
        return None
    if tr.has_effects(e):
        return _sink_into_call(tr, e, mask)
    if tr.type_of(e.left).is_matrix or tr.type_of(e.right).is_matrix:
        return _merge_into_matrix(tr, e, mask)
    if e.op == "+":
        folded = _factor(tr, e, mask)
        if folded is None:
            folded = _fused_after_call(tr, e, mask)
        if folded is not None:
            return folded
    folded = _merge_constants(tr, e, mask)
    if folded is not None:
        return folded
    folded = _merge_components(tr, e, mask)
    if folded is None:
        folded = _sunk_through_compound(tr, e, mask)
    if folded is not None:
        return folded
    folded = _sink(tr, e, mask)
    return folded if folded is not None else _keep_factor(tr, e, mask)


# -- a product by a constant, seen through a variable assigned again ----------------------------
def _keep_factor(tr: Any, e: A.Binary, mask: str | None) -> str | None:
    """``x = y * #c`` where x is read later in a product by a constant: the code of the
    product, y's value kept in a temporary for that read (:func:`_product_parts`). NIR sees
    through x to y however often x is assigned (``p = m*p*2.02; p = m*p*2.03;`` in an fbm:
    the second is ``(m*2.02) * (m*p)``, SSA); the generated code has one variable per GLSL
    one, so the value y had is kept here, in float32 and float64 mode alike (the same
    values: only llvmpipe mode reads the temporary)."""
    if e.op != "*" or tr.type_of(e.left) != tr.type_of(e.right) and not (
            tr.type_of(e.left).is_scalar or tr.type_of(e.right).is_scalar):
        return None
    k_left = _const(tr, e.left)
    y, k = (e.right, e.left) if k_left else (e.left, e.right)
    if not _const(tr, k) or _const(tr, y) or tr.type_of(y) != tr.type_of(e):
        return None
    if not isinstance(y, (A.Binary, A.Call)) or _fmul(tr, y) and _product_parts(tr, y):
        return None  # (a plain read is no new value to keep; a longer chain: not copied)
    w = _write_of(tr, e)
    if w is None or id(w.symbol) not in _written(tr):
        return None  # (a variable written once: its initializer is read again instead)
    if not any(_reaching_value(tr, r) is e for r in _merge_reads(tr).get(id(w.symbol), ())):
        return None  # (no product by a constant reads this value)
    ty = tr.tmp(tr.expr(y, mask))
    tk = tr.expr(k, mask)
    tr.fold_state.kept[id(e)] = (ty, tr.lines)
    t = tr.type_of(e)
    return tr.binary_values("*", t, t, tk, ty) if k_left else tr.binary_values("*", t, t, ty, tk)


def _write_of(tr: Any, value: Any) -> Any:
    """The write (analysis.dataflow.Write) of a local whose whole new value is ``value``."""
    facts = _facts(tr)
    if not facts.ok:
        return None
    index = tr.fold_state.writes
    key = id(tr.fn.sym)
    if key not in index:
        index[key] = {id(w.value): w for ws in facts.writes.values() for w in ws
                      if w.kind in ("=", "init") and w.value is not None and w.symbol.kind in ("local", "param")}
    return index[key].get(id(value))


def _merge_reads(tr: Any) -> dict[int, list[A.Identifier]]:
    """id(symbol) -> the reads of it as a factor of a product by a constant, in the current
    function."""
    cache = tr.fold_state.merge_reads
    key = id(tr.fn.sym)
    if key not in cache:
        out: dict[int, list[A.Identifier]] = {}
        for n in tr.fn.sym.node.body.walk():
            if isinstance(n, A.Binary) and n.op == "*":
                for a, b in ((n.left, n.right), (n.right, n.left)):
                    if isinstance(b, A.Identifier) and _const(tr, a) and tr.model.symbol_of(b) is not None:
                        out.setdefault(id(tr.model.symbol_of(b)), []).append(b)
        cache[key] = out
    return cache[key]


def _product_parts(tr: Any, node: Any) -> tuple[Any, Any, str | None] | None:
    """(y, #c, code) when the value of the variable ``node`` is ``y * #c`` to NIR: a
    never-written local's initializer (code None: y is computed again here), or the
    assignment reaching this read when :func:`_keep_factor` kept y (code: its temporary)."""
    if not isinstance(node, A.Identifier):
        return None
    init, code = _stable_init(tr, node), None
    if init is None:
        init = _reaching_value(tr, node)
        kept = tr.fold_state.kept.get(id(init))
        if kept is None or kept[1] is not tr.lines:
            return None  # (not kept, or kept in another Python function: an outlined part)
        code = kept[0]
    if not (isinstance(init, A.Binary) and init.op == "*") or _has_matrix(tr, init.left, init.right):
        return None
    if _const(tr, init.right) and not _const(tr, init.left):
        return init.left, init.right, code
    if _const(tr, init.left) and not _const(tr, init.right):
        return init.right, init.left, code
    return None


def _merge_into_matrix(tr: Any, e: A.Binary, mask: str | None) -> str | None:
    """``#M * v`` with v a vector whose value is ``y * #c`` (c a scalar): NIR lowers the
    product to columns, ``M[j][i] * (y[j] * c)``, and merges each constant, ``(M[j][i]*c) *
    y[j]`` (``('~fmul', '#a', ('fmul', 'b(is_not_const)', '#c'))``): ``(M * c) * y``, M * c
    folded in float32 (measured: ``p = m*p*2.02; p = m*p*2.03`` of iq's fbm)."""
    if e.op != "*" or not (tr.type_of(e.left).is_matrix and tr.type_of(e.right).is_vector):
        return None
    if tr.model.const_value(e.left) is None and not _const(tr, e.left):
        return None
    parts = _product_parts(tr, e.right)
    if parts is None or not tr.type_of(parts[1]).is_scalar or tr.type_of(parts[0]) != tr.type_of(e.right):
        return None
    y, c, code = parts
    if code is None and (not _varying(tr, y) or tr.has_effects(y)):
        return None
    tm, tc, tv = tr.exprs([e.left, c, e.right], mask)
    ty = code if code is not None else tr.expr(y, mask)
    mt, vt = tr.type_of(e.left), tr.type_of(e.right)
    merged = tr.binary_values("*", mt, tr.type_of(c), tm, tc)
    rewritten = tr.binary_values("*", mt, vt, merged, ty)
    return f"({rewritten} if rt.lp else {tr.binary_values('*', mt, vt, tm, tv)})"


def _merge_constants(tr: Any, e: A.Binary, mask: str | None) -> str | None:
    """``#a * (b * #c) -> (a*c) * b`` and ``#a + (b + #c) -> (a + c) + b`` (no "used once"
    condition: they reach through any SSA value, here a never-written local such as
    ``vec2 uv = q * 1.2; ... uv * 0.2``, which is ``q * 0.24`` on llvmpipe: 1.2*0.2 is folded
    in float32). Subtraction is addition of the negation."""
    if e.op == "-" and not _const(tr, e.right):
        return None
    k_node, x_node = (e.right, e.left) if _const(tr, e.right) else (e.left, e.right)
    if not _const(tr, k_node) or _const(tr, x_node):
        return None
    inner, kept = x_node, None
    if isinstance(inner, A.Identifier):
        parts = _product_parts(tr, inner) if e.op == "*" else None
        kept = parts[2] if parts is not None else None  # (y's value kept: :func:`_keep_factor`)
        inner = _reaching_value(tr, inner) if kept is not None else _stable_init(tr, inner)
    ops = ("*",) if e.op == "*" else _SUMS
    factored = _broadcast_dot(tr, inner) if e.op == "*" and kept is None else None
    if factored is not None and tr.type_of(k_node).is_scalar:  # s * sum(K) by broadcast_dot, then merged
        tk, tx = tr.exprs([k_node, x_node], mask)
        written = tr.binary_values("*", FLOAT, FLOAT, tx, tk) if x_node is e.left else tr.binary_values(
            "*", FLOAT, FLOAT, tk, tx)
        rewritten = tr.binary_values("*", FLOAT, FLOAT, tr.expr(factored[0], mask),
                                     f"({tk} * {tr.const_float(factored[1])})")
        return f"({rewritten} if rt.lp else {written})"
    parts = _scalar_dot(tr, inner) if e.op == "*" else None
    if parts is None:
        if not isinstance(inner, A.Binary):
            return None
        parts = (inner.op, inner.left, inner.right)
    op, left, right = parts
    if op not in ops or tr.has_effects(inner):
        return None
    if _const(tr, right) and not _const(tr, left):
        b_node, c_node, c_sign, b_sign = left, right, op, "+"
    elif _const(tr, left) and not _const(tr, right):
        b_node, c_node, c_sign, b_sign = right, left, "+", op
    else:
        return None
    if tr.type_of(inner) != tr.type_of(x_node) or not _varying(tr, b_node):
        return None  # (all constant after propagation: NIR folds it left to right)
    if _has_matrix(tr, b_node, c_node):
        return None  # m * v is no elementwise product: NIR lowers it to columns first
    b_inner = _stable_init(tr, b_node) if isinstance(b_node, A.Identifier) else b_node
    if (isinstance(b_inner, A.Binary) and b_inner.op in ops and (_const(tr, b_inner.left) or _const(tr, b_inner.right))
            and not _has_matrix(tr, b_inner.left, b_inner.right)):
        return None  # NIR would merge further into b: not copied (m * v is a sum of columns)
    if kept is not None:
        tk, tc, tx = tr.exprs([k_node, c_node, x_node], mask)
        tb = kept
    else:
        tk, tc, tb, tx = tr.exprs([k_node, c_node, b_node, x_node], mask)
    t = tr.type_of(e)
    if e.op == "*":
        rewritten = tr.binary_values("*", t, t, tb, f"({tk} * {tc})")
        written = tr.binary_values("*", t, t, tx, tk) if x_node is e.left else tr.binary_values("*", t, t, tk, tx)
    else:
        k = f"(-{tk})" if e.op == "-" else tk
        c = f"(-{tc})" if c_sign == "-" else tc
        rewritten = f"(({k} + {c}) {b_sign} {tb})"
        written = f"({tx} {e.op} {tk})" if x_node is e.left else f"({tk} {e.op} {tx})"
    return f"({rewritten} if rt.lp else {written})"


def _scalar_dot(tr: Any, node: Any) -> tuple[str, Any, Any] | None:
    """``("*", a, b)`` for ``dot(a, b)`` of two floats: Mesa's built-in is a multiply there
    (builtin_functions.cpp ``_dot``: ``ir_binop_mul`` for one component), so NIR merges a
    constant into it as into ``a * b`` (a hash's ``dot(n, 123.456) * 789.123`` is ``n *
    (123.456*789.123)``, measured); None for anything else."""
    if not (isinstance(node, A.Call) and node.callee == "dot" and len(node.args) == 2 and _builtin(tr, node)):
        return None
    if not all(tr.type_of(a).is_scalar and tr.type_of(a).base == "float" for a in node.args):
        return None
    return "*", node.args[0], node.args[1]


def merged_dot(tr: Any, call: A.Call, args: list[str], mask: str | None) -> str | None:
    """``dot(v, #K)`` where v is a chain of products by constants, ``(x * #c1) * #c2``, also
    through never-written locals and inlined parameters (:func:`_stable_init`).

    Two compilers merge the constants, in this order (measured bit for bit, Mesa 22.3):
    GLSL IR first folds the constants of one expression tree (``r * 2.1 * 0.7`` is
    ``r * (2.1*0.7)``; its tree grafting puts a variable written once and read once, such as an
    inlined argument, into the tree that reads it); then NIR lowers the dot product to
    component products and its reassociation ``('~fmul', '#a', ('fmul', 'b(is_not_const)',
    '#c')) -> ('fmul', ('fmul', a, c), b)`` (nir_opt_algebraic.py) merges K with each tree's
    constant, the outer tree first. So ``vec2 uv = q * 1.2`` read twice and ``dot(uv * 0.2, K)``
    is ``dot(q, (K * 0.2) * 1.2)`` (``K * (0.2 * 1.2)`` differs in 70% of the pixels), and
    ``dot(r * 2.1 * 0.7, K)`` is ``dot(r, K * (2.1 * 0.7))``. Float32 only, like every rule."""
    if len(call.args) != 2 or tr.fn is None or tr.type_of(call).base != "float":
        return None
    u, w = call.args
    if _const(tr, w) and not _const(tr, u):
        v, k, v_first = u, w, True
    elif _const(tr, u) and not _const(tr, w):
        v, k, v_first = w, u, False
    else:
        return None
    x, trees = _product_chain(tr, v)
    if not trees or not _varying(tr, x) or tr.type_of(x) != tr.type_of(v) or tr.has_effects(x):
        return None
    built = _stable_init(tr, x) if isinstance(x, A.Identifier) else x
    if isinstance(built, A.Call) and built.constructor:
        return None  # NIR merges further into each component (vec3(p * 0.37, ...)): not copied
    t = tr.type_of(v)
    tx, tk = tr.exprs([x, k], mask)
    merged = tk
    for tree in trees:
        codes = tr.exprs(tree[::-1], mask)  # GLSL IR folds the tree's constants inner first
        folded = codes[0]
        for c in codes[1:]:
            folded = tr.binary_values("*", t, t, folded, c)
        merged = tr.binary_values("*", t, t, merged, folded)
    rewritten = f"rt.dot({tx}, {merged})" if v_first else f"rt.dot({merged}, {tx})"
    return f"({rewritten} if rt.lp else rt.dot({args[0]}, {args[1]}))"


def broadcast_dot(tr: Any, call: A.Call, args: list[str], mask: str | None) -> str | None:
    """``dot(vecN(s), #K)`` (s a float, also through a never-written local or an inlined
    parameter, :func:`_stable_init`) is ``s * (K[0] + (K[1] + ...))`` on llvmpipe: the dot
    product lowered to ``s*K[0] + (s*K[1] + ...)`` (summed right to left), NIR's factoring
    ``('~fadd', ('fmul', a, b), ('fmul', a, c)) -> a * (b + c)`` leaves one product by the
    constants' float32 sum (measured bit for bit for vec2, vec3, vec4: a hash's
    ``dot(vec2(index), vec2(12.9898, 78.233))``; the sum left to right differs for vec4)."""
    parts = _broadcast_dot(tr, call)
    if parts is None:
        return None
    x, total = parts
    rewritten = tr.binary_values("*", FLOAT, FLOAT, tr.expr(x, mask), tr.const_float(total))
    return f"({rewritten} if rt.lp else rt.dot({args[0]}, {args[1]}))"


def _broadcast_dot(tr: Any, call: Any) -> tuple[Any, float] | None:
    """(s, the float32 sum of K right to left) for a call ``dot(vecN(s), #K)``, else None."""
    if not (isinstance(call, A.Call) and call.callee == "dot" and len(call.args) == 2 and _builtin(tr, call)):
        return None
    if tr.fn is None or tr.type_of(call).base != "float" or tr.has_effects(call):
        return None
    for v, k in ((call.args[0], call.args[1]), (call.args[1], call.args[0])):
        x = _broadcast(tr, v)
        ks = _constant_value(tr, k) if x is not None else None
        if ks is None or len(ks) != tr.type_of(v).size or not _varying(tr, x):
            continue
        import numpy as np

        total = np.float32(ks[-1])
        for c in reversed(ks[:-1]):
            total = np.float32(np.float32(c) + total)
        return (x, float(total)) if np.isfinite(total) else None
    return None


def dot_operand(tr: Any, node: Any) -> bool:
    """``node`` is an operand the rules of a ``dot`` with a constant rewrite: a product by a
    constant (:func:`constant_product`, for :func:`merged_dot`) or ``vecN(s)`` (for
    :func:`broadcast_dot`); transpile/inline.py inlines a call that passes one to such a dot."""
    return constant_product(tr, node) or tr.fn is not None and _broadcast(tr, node) is not None


def _broadcast(tr: Any, v: Any) -> Any:
    """The float s of a vector ``vecN(s)`` (also a never-written local or inlined parameter
    so built, or a swizzle of one), else None."""
    if isinstance(v, A.Field) and tr.model.is_swizzle(v):
        v = v.base
    built = _stable_init(tr, v) if isinstance(v, A.Identifier) else v
    if not (isinstance(built, A.Call) and built.constructor and len(built.args) == 1):
        return None
    s = built.args[0]
    t = tr.type_of(built)
    if not (t.is_vector and t.base == "float" and tr.type_of(s).is_scalar and tr.type_of(s).base == "float"):
        return None
    return None if tr.has_effects(s) else s


def _product_chain(tr: Any, v: Any) -> tuple[Any, list[list[Any]]]:
    """(x, trees) for ``v = (x * #c2) * #c1``: the constant factors grouped by the GLSL IR
    expression tree they sit in, outer tree and outer factor first. A never-written local read
    once (or an inlined parameter, read once in its function) is grafted into the tree that
    reads it; another one starts a new tree. ([] when v is no such product.)"""
    trees: list[list[Any]] = [[]]
    node = v
    for _ in range(16):
        inner = node
        while isinstance(inner, A.Identifier):
            init = _stable_init(tr, inner)
            if init is None:
                break
            if not _read_once(tr, inner) and trees[-1]:
                trees.append([])
            inner = init
        if not (isinstance(inner, A.Binary) and inner.op == "*") or _has_matrix(tr, inner.left, inner.right):
            break
        if tr.type_of(inner) != tr.type_of(v) or tr.has_effects(inner):
            break
        if _const(tr, inner.right) and not _const(tr, inner.left):
            trees[-1].append(inner.right)
            node = inner.left
        elif _const(tr, inner.left) and not _const(tr, inner.right):
            trees[-1].append(inner.left)
            node = inner.right
        else:
            break
    return node, [tree for tree in trees if tree]


def constant_product(tr: Any, node: Any) -> bool:
    """``node`` is, or is a never-written local initialised by, a product of a constant and a
    value that is not constant (the start of :func:`_product_chain`)."""
    if tr.fn is None or tr.has_effects(node):
        return False
    _, trees = _product_chain(tr, node)
    return bool(trees)


def _read_once(tr: Any, ident: A.Identifier) -> bool:
    """The variable is read at one place of its function (GLSL IR grafts its value there)."""
    sym = tr.model.symbol_of(ident)
    owner = inline_owner(tr, sym)
    body = owner.node.body if owner is not None else tr.fn.sym.node.body
    reads = tr.fold_state.reads
    if id(body) not in reads:
        counts: dict[int, int] = {}
        for n in body.walk():
            if isinstance(n, A.Identifier):
                s = tr.model.symbol_of(n)
                if s is not None:
                    counts[id(s)] = counts.get(id(s), 0) + 1
        reads[id(body)] = counts
    return reads[id(body)].get(id(sym), 0) == 1


def _const(tr: Any, node: Any) -> bool:
    if tr.model.const_value(node) is not None:
        return True
    return isinstance(node, A.Identifier) and _constant_global(tr, tr.model.symbol_of(node))


def _constant_global(tr: Any, sym: Any) -> bool:
    """A global variable (not `const`) initialised by a constant expression and never written:
    a constant to Mesa (GLSL IR propagates it, opt_constant_variable), so to every rule here
    (``float PI = 3.14159265;`` then ``fract(p / PI)``: measured, the rules apply as for a
    `const`)."""
    if sym is None or sym.kind != "global" or sym.const_value is not None:
        return False
    init = sym.node.init if isinstance(sym.node, A.Declarator) else None
    return (init is not None and tr.model.const_value(init) is not None
            and id(sym) not in tr.facts.written_globals)


def _is_product(tr: Any, node: Any) -> bool:
    """A product of numbers or vectors (a matrix product is no elementwise product)."""
    return (isinstance(node, A.Binary) and node.op == "*" and not _const(tr, node)
            and not _has_matrix(tr, node.left, node.right))


def _has_matrix(tr: Any, *nodes: Any) -> bool:
    return any(tr.type_of(n).is_matrix for n in nodes)


# built-ins whose NIR result is an fadd or fmul (lowered to arithmetic): their values are not
# opaque to nir_opt_algebraic
_ARITHMETIC_BUILTINS = {"dot", "mix", "smoothstep", "normalize", "cross", "reflect", "refract",
                        "faceforward", "radians", "degrees", "mod", "step", "atan", "asin", "acos",
                        "tan", "sinh", "cosh", "tanh", "asinh", "acosh", "atanh", "exp", "log", "pow"}


def _opaque(tr: Any, node: Any, depth: int = 0) -> bool:
    """The value reaches NIR as something no algebraic rule looks into: a uniform, a
    never-written parameter of mainImage, a built-in computed by its own instruction (sin,
    fract, floor, sqrt, ...), a swizzle of one, or a never-written local initialised so."""
    if depth > 8:
        return False
    if isinstance(node, A.Field):
        return _opaque(tr, node.base, depth + 1)
    if isinstance(node, A.Call):
        if node.constructor:
            return False
        return (_builtin(tr, node) and node.callee not in _ARITHMETIC_BUILTINS
                and not _const(tr, node))
    if isinstance(node, A.Identifier):
        sym = tr.model.symbol_of(node)
        if sym is None or _const(tr, node):
            return False
        if sym.kind in ("uniform", "builtin-var"):
            return True
        if sym.kind == "param":
            return tr.fn.is_entry and id(sym) not in _written(tr)
        init = _stable_init(tr, node)
        return init is not None and _opaque(tr, init, depth + 1)
    return False


def _used_once(tr: Any, e: Any) -> bool:
    """``e`` feeds one instruction: its GLSL text appears once in the function (NIR's CSE
    would merge a copy) and it is an operand of a larger expression (a value stored in a
    variable feeds every use of the variable)."""
    return id(e) in _uses(tr)[2] and _one_copy(tr, e)


def _one_copy(tr: Any, e: Any) -> bool:
    """The GLSL text of ``e`` appears once in the function (NIR's CSE would merge a copy)."""
    shapes, counts, _ = _uses(tr)
    return counts.get(shapes.get(id(e), -1), 0) <= 1


def _uses(tr: Any) -> tuple[dict[int, int], dict[int, int], set[int]]:
    """(shape of each node, copies of each shape among the binary expressions, ids of the
    operands of binary expressions and built-in calls) of the current function."""
    parents = tr.fold_state.parents
    key = id(tr.fn.sym)
    if key not in parents:
        shapes = _shapes(tr.fn.sym.node.body)
        counts: dict[int, int] = {}
        operands: set[int] = set()
        for n in tr.fn.sym.node.body.walk():
            if isinstance(n, A.Binary):
                operands.update((id(n.left), id(n.right)))
                counts[shapes[id(n)]] = counts.get(shapes[id(n)], 0) + 1
            elif isinstance(n, A.Call) and (n.constructor or _builtin(tr, n)):
                operands.update(id(a) for a in n.args)  # (a user function may read it twice)
        parents[key] = (shapes, counts, operands)
    return parents[key]


def _shapes(root: Any) -> dict[int, int]:
    """id(node) -> a number shared by exactly the nodes of the same shape (same class, same
    fields, same shapes of children; locations left out): what equal GLSL text means, found in
    one pass (hash-consing) instead of printing every subtree, which is quadratic in a chain
    `a + b + c + ...` of thousands of terms (issue 16's hostile sums)."""
    ids: dict[int, int] = {}
    table: dict[tuple, int] = {}
    stack: list[tuple[Any, bool]] = [(root, False)]
    while stack:
        node, ready = stack.pop()
        if not ready:
            stack.append((node, True))
            stack.extend((c, False) for c in node.children())
            continue
        parts: list[Any] = [type(node)]
        for name in node._fields:
            value = getattr(node, name)
            if name in node._children:
                if isinstance(value, list):
                    value = tuple(ids[id(v)] for v in value)
                elif value is not None:
                    value = ids[id(value)]
            elif isinstance(value, Location):
                continue
            elif isinstance(value, list):
                value = tuple(value)
            parts.append(value)
        ids[id(node)] = table.setdefault(tuple(parts), len(table))
    return ids


def _sink(tr: Any, e: A.Binary, mask: str | None) -> str | None:
    """Constants sunk into a sum (:func:`_sink_sum`), a two-term product, or a dot product."""
    inner, k, k_left = e.left, e.right, False
    if _const(tr, inner) and not _const(tr, k) or e.op == "*" and _local_constant(tr, inner):
        inner, k, k_left = e.right, e.left, True
    if not (_const(tr, k) or e.op == "*" and _local_constant(tr, k)) or _const(tr, inner):
        return None
    if tr.type_of(k) != tr.type_of(e) and not tr.type_of(k).is_scalar:
        return None  # (a scalar constant added to or multiplying a vector: each component)
    if not _used_once(tr, e):
        return None
    if k_left and e.op == "-":
        return None  # #c - (a + b): the negation sits between the two sums
    if e.op in _SUMS:
        return _sink_sum(tr, e, inner, k, mask)
    if not (_used_once(tr, inner) and isinstance(inner, A.Binary) and inner.op == "*"):
        return None
    a, b = inner.left, inner.right
    if _has_matrix(tr, a, b):
        return None  # a matrix product is not reassociated as numbers are
    if not ((_opaque(tr, a) or _settled(tr, a) or _normalized_once(tr, a) is not None)
            and (_opaque(tr, b) or _settled(tr, b) or _scaled(tr, b))):
        return None  # an operand NIR would look into further: not copied
    t, ty = tr.type_of(e), [tr.type_of(x) for x in (a, b, k)]
    if any(x != t and not x.is_scalar for x in ty):
        return None
    ta, tb, tk = tr.exprs([a, b, k], mask)
    prod = lambda x, y, tx, ty: tr.binary_values("*", tx, ty, x, y)  # noqa: E731
    ab, ak = tr.type_of(inner), (ty[0] if ty[0] == t else ty[2])  # (types of a*b, a*#c)
    written = prod(prod(ta, tb, ty[0], ty[1]), tk, ab, ty[2]) if not k_left else prod(
        tk, prod(ta, tb, ty[0], ty[1]), ty[2], ab)
    x = _normalized_once(tr, a)
    if x is not None:  # a = x * inversesqrt(dot(x, x)) to NIR, used once: the constant sinks into it
        tx = tr.tmp(tr.expr(x, mask))
        scaled = prod(tx, tk, ty[0], ty[2])
        ta_k = prod(scaled, f"rt.inversesqrt(rt.dot({tx}, {tx}))", ty[0], tr.type_of(k))
        return f"({prod(ta_k, tb, ak, ty[1])} if rt.lp else {written})"
    return f"({prod(prod(ta, tk, ty[0], ty[2]), tb, ak, ty[1])} if rt.lp else {written})"


def _local_constant(tr: Any, node: Any) -> bool:
    """A never-written local initialised by a constant expression (``float warpAmount = 5.0;``):
    a constant to NIR (GLSL IR's constant propagation), counted as one by the product sink."""
    sym = tr.model.symbol_of(node) if isinstance(node, A.Identifier) else None
    if sym is None or sym.kind != "local" or not isinstance(sym.node, A.Declarator) or sym.node.init is None:
        return False
    return tr.model.const_value(sym.node.init) is not None and id(sym) not in _written(tr)


def _normalized_once(tr: Any, node: Any) -> Any:
    """x when ``node`` reads a never-written local initialised as ``normalize(x)`` (x a vector)
    and read only here: NIR sees ``x * frsq(dot(x, x))`` used once, and a constant multiplying
    it sinks on to x: ``(normalize(x) * b) * #c`` is ``((x * #c) * inversesqrt(dot(x, x))) * b``
    (measured: gargantua's WarpSpace, ``singularityVector * warpFactor * warpAmount``, 1 of
    43,200 values off on a copy of the function, 8 with the constant beside normalize's
    result); else None."""
    sym = tr.model.symbol_of(node) if isinstance(node, A.Identifier) else None
    if sym is None or sym.kind != "local" or not isinstance(sym.node, A.Declarator) or id(sym) in _written(tr):
        return None
    init = sym.node.init
    if not (isinstance(init, A.Call) and init.callee == "normalize" and _builtin(tr, init)
            and tr.type_of(init.args[0]).is_vector and not tr.has_effects(init)):
        return None
    reads = [n for n in tr.fn.sym.node.body.walk() if isinstance(n, A.Identifier) and tr.model.symbol_of(n) is sym]
    return init.args[0] if reads == [node] else None


def _fused_after_call(tr: Any, e: A.Binary, mask: str | None) -> str | None:
    """``x + e`` where x's value, written by a call folded per call site
    (transpile/call_fold.py), is ``p1 + p2`` in a component, two products, and this is x's
    only read: ``(p1 + e) + p2`` there. llvmpipe fuses ``p1 + p2`` into ``ffma(p2's factors,
    p1)`` (nir_opt_algebraic_late, fuse_ffma32), ``ffma(a, b, fmul(c, d)) + e`` becomes
    ``ffma(a, b, ffma(c, d, e))``, and lower_ffma32 splits each ffma into a product and a sum
    (measured: gargantua's ``raypos = eyepos + eyevec*dither*far/200`` after RotateCamera,
    576 of 576 pixels; ``(a*e + b*h) + d`` is ``(a*e + d) + b*h`` in every pixel, while
    ``(a*e + b) + d`` keeps its order). In the written code, inside one expression, not
    copied here."""
    for x, other in ((e.left, e.right), (e.right, e.left)):
        w = _call_write(tr, x)
        if w is None:
            continue
        sums = product_sums(tr, w.node, tr.model.symbol_of(x))
        tx, to = tr.type_of(x), tr.type_of(other)
        if (sums is None or not any(sums) or to.base != "float" or to.is_matrix or tx.is_matrix
                or to != tx and not to.is_scalar or tr.has_effects(other)):
            continue
        reads = [n for n in tr.fn.sym.node.body.walk() if isinstance(n, A.Identifier)
                 and tr.model.symbol_of(n) is tr.model.symbol_of(x) and _facts(tr).enter.get(id(n), -1) > _facts(tr).exit[id(w.node)]]
        if reads != [x]:
            return None  # (x read again: the sum is used twice)
        tl, trr = tr.exprs([e.left, e.right], mask)
        if other is e.right:
            trr = to_code = tr.tmp(trr)
        else:
            tl = to_code = tr.tmp(tl)
        tx_code = tl if x is e.left else trr
        parts = []
        for i, s in enumerate(sums):
            oi = f"{to_code}[{i}]" if to.is_vector else to_code
            xi = f"{tx_code}[{i}]" if tx.is_vector else tx_code
            parts.append(f"(({s[0]} + {oi}) + {s[1]})" if s is not None else f"({xi} + {oi})")
        rewritten = parts[0] if tx.is_scalar else f"rt.vec({tx.size}, {', '.join(parts)})"
        return f"({rewritten} if rt.lp else {tr.binary_values('+', tr.type_of(e.left), tr.type_of(e.right), tl, trr)})"
    return None


def _call_write(tr: Any, node: Any) -> Any:
    """The write (analysis.dataflow.Write) of a call of a user function that gave the variable
    ``node`` its value here (an out or inout argument, nothing written since), else None."""
    sym = tr.model.symbol_of(node) if isinstance(node, A.Identifier) else None
    if sym is None or sym.kind not in ("local", "param"):
        return None
    facts = _facts(tr)
    if not facts.ok or id(node) not in facts.enter:
        return None
    before = [w for w in facts.writes_to(sym) if w.pos < facts.enter[id(node)]]
    if not before or before[-1].kind != "out" or not isinstance(before[-1].node, A.Call):
        return None
    w = before[-1]
    if not facts.dominates(w.node, node) or facts.written_between(w.node, node, [sym]):
        return None
    return w


def _settled(tr: Any, node: Any) -> bool:
    """A variable whose value here is what a call of a user function wrote into it (an out or
    inout argument, nothing written since), where that value is, to NIR after inlining, a sum
    or a built-in's result in every component (transpile/call_fold.out_roots: gargantua's
    eyevec after RotateCamera): no algebraic rule looks into it as a factor."""
    w = _call_write(tr, node)
    if w is None:
        return False
    roots = out_roots(tr, w.node, tr.model.symbol_of(node))
    return roots is not None and roots <= {"+", "call"}


def _scaled(tr: Any, node: Any) -> bool:
    """A never-written local initialised as a product by a constant (``float dither = rand(uv)
    * 2.0``) or a constant divided by a value (``1.0 / (...)``): beside ``(a * dither) * #c``
    NIR leaves it whole, measured (gargantua: ``((eyevec * dither) * 15.0) / 200.0`` is
    ``((eyevec * 15.0) * dither) / 200.0``; WarpSpace's warpFactor likewise)."""
    sym = tr.model.symbol_of(node) if isinstance(node, A.Identifier) else None
    if sym is None or sym.kind != "local" or not isinstance(sym.node, A.Declarator) or id(sym) in _written(tr):
        return False
    init = sym.node.init  # (its value, whatever calls compute it: a user function's result too)
    if isinstance(init, A.Binary) and init.op == "/" and _const(tr, init.left) and not _const(tr, init.right):
        return tr.type_of(init).is_scalar  # (1.0 / y, gargantua's warpFactor: measured the same)
    return (isinstance(init, A.Binary) and init.op == "*" and not _has_matrix(tr, init.left, init.right)
            and _const(tr, init.left) != _const(tr, init.right))


def _sink_sum(tr: Any, e: A.Binary, inner: Any, k: Any, mask: str | None) -> str | None:
    """``(a + b) + #c -> (a + #c) + b`` as nir_opt_algebraic applies it: first the variant that
    keeps a product ``b`` whole (``is_fmul``, so the constant joins the other term), else the
    constant joins ``a``; the new sum ``a + #c`` is matched again, so the constant sinks down
    a chain of sums each used once: ``uv = (p.xy + K*p.z) + f.xy; uv + 0.5`` is
    ``((p.xy + 0.5) + K*p.z) + f.xy`` (iq's noise). A sum may be the initializer of a
    never-written local read once (to NIR the same SSA value, used once). Not copied (None):
    a chain GLSL IR rebalances first (:func:`_rebalanced`), a ``dot`` other than
    ``dot(oc, oc)`` (:func:`_stable_vector`), a term that is none of opaque, product, sum."""
    if (isinstance(inner, A.Call) and inner.callee == "dot" and _builtin(tr, inner)
            and all(_stable_vector(tr, x) for x in inner.args)):
        u, v, kk = tr.exprs([*inner.args, k], mask)
        signed = f"(-{kk})" if e.op == "-" else kk
        return f"(rt.dot_add({u}, {v}, {signed}) if rt.lp else (rt.dot({u}, {v}) {e.op} {kk}))"
    squared = _squared_length(tr, inner)
    if squared is not None:
        u, kk, written = tr.exprs([squared, k, inner], mask)
        signed = f"(-{kk})" if e.op == "-" else kk
        if _shared_dot(tr, squared, inner) and not _merged_argument(tr, squared):
            # (dot(x, x) used twice after CSE: the constant stays outside)
            return f"((rt.dot({u}, {u}) {e.op} {kk}) if rt.lp else ({written} {e.op} {kk}))"
        return f"(rt.dot_add({u}, {u}, {signed}) if rt.lp else ({written} {e.op} {kk}))"
    plan = _sum_plan(tr, inner, tr.type_of(e), 0)
    if plan is None or plan[0] != "sum" or _rebalanced(tr, e):
        return None
    leaves: list[Any] = []
    _plan_leaves(plan, leaves)
    codes = tr.exprs([*leaves, e.left, e.right, k], mask)
    tk = f"(-{codes[-1]})" if e.op == "-" else codes[-1]
    rewritten = _plan_code(plan, iter(codes), tk)
    return f"({rewritten} if rt.lp else ({codes[-3]} {e.op} {codes[-2]}))"


def _squared_length(tr: Any, node: Any) -> Any:
    """x when ``node`` is ``pow(L, 2.0)`` and L is ``length(x)`` or ``distance(x, #0)`` (or a
    never-written local initialised so), x a parameter the function never writes: to NIR
    ``fsqrt(dot(x, x))`` squared is the dot product itself (fpow(a, 2.0) -> a*a, then
    sqrt(a)*sqrt(a) -> a), so ``pow(L, 2.0) + #c`` is ``dot(x, x) + #c`` with the constant in
    its innermost addition (measured: gargantua's ``1.0 / (pow(distance(raypos, origin),
    2.0) + 0.000001)``, 14,400 of 14,400 pixels; the written ``sqrt(d)*sqrt(d) + c`` differs
    in 6,014); else None."""
    if not (isinstance(node, A.Call) and node.callee == "pow" and _builtin(tr, node) and len(node.args) == 2
            and _constant_value(tr, node.args[1]) == [2.0] and tr.type_of(node).is_scalar):
        return None
    length = node.args[0]
    if isinstance(length, A.Identifier):
        length = _stable_init(tr, length)
    if not (isinstance(length, A.Call) and _builtin(tr, length) and length.callee in ("length", "distance")):
        return None
    args = list(length.args)
    if length.callee == "distance":
        zero = [a for a in args if (_constant_value(tr, a) or [1.0]) and not any(_constant_value(tr, a) or [1.0])]
        if len(zero) != 1:
            return None
        args.remove(zero[0])
    x = args[0]
    sym = tr.model.symbol_of(x) if isinstance(x, A.Identifier) else None
    if sym is None or sym.kind != "param" or id(sym) in _written(tr) or not tr.type_of(x).is_vector:
        return None
    return x


def _shared_dot(tr: Any, x: Any, pow_call: Any) -> bool:
    """Another ``length``, ``distance``, ``normalize`` or ``dot`` of the current function reads
    the parameter x (alone, negated or subtracted from a constant): after inlining and CSE its
    ``dot(x, x)`` is the squared length's too, used twice, and a constant added to one of them
    stays outside (measured: ``glow(r) = pow(length(r), 2.0) - 0.37`` beside ``warp(r)``)."""
    sym = tr.model.symbol_of(x)
    own = set()
    for n in pow_call.walk():
        own.add(id(n))
    init = _stable_init(tr, pow_call.args[0]) if isinstance(pow_call.args[0], A.Identifier) else None
    for n in (init.walk() if init is not None else ()):
        own.add(id(n))
    for n in tr.fn.sym.node.body.walk():
        if (id(n) in own or not isinstance(n, A.Call) or n.callee not in ("length", "distance", "normalize", "dot")
                or not _builtin(tr, n)):
            continue
        for a in n.args:
            while isinstance(a, A.Unary) and a.op == "-" or isinstance(a, A.Binary) and a.op == "-" and (
                    _constant_value(tr, a.left) is not None):
                a = a.operand if isinstance(a, A.Unary) else a.right
            if isinstance(a, A.Identifier) and tr.model.symbol_of(a) is sym:
                return True
    return False


def _merged_argument(tr: Any, x: Any) -> bool:
    """Every call of the current function passes for the parameter x a variable whose value
    there merges several writes (to NIR a phi: written in a loop around the call, or last
    written in a branch before it). Then the constant joins the shared dot product's innermost
    addition after all: nir_opt_algebraic's ``(a + b) + #c`` sink (``fadd(is_used_once)``)
    runs before CSE has merged the two dot products when x is a phi, after it when x is an
    ALU value (measured on a copy of gargantua's WarpSpace, 14,400 pixels each: called in a
    loop that writes x, 0 pixels off sunk and 1-3 outside; after an ``if`` that writes x, 0
    and 1; in a loop that does not write x, or after straight-line writes, 1 sunk and 0
    outside). Which pass ordering makes a phi differ was not traced in Mesa's source."""
    fn = tr.fn.sym
    names = [name for name, _, _ in fn.params]
    if x.name not in names:
        return False
    index = names.index(x.name)
    found = False
    for caller in tr.model.reachable_functions():
        for call in caller.node.body.walk():
            if not (isinstance(call, A.Call) and tr.model.call_target(call) is fn):
                continue
            arg = call.args[index] if index < len(call.args) else None
            sym = tr.model.symbol_of(arg) if isinstance(arg, A.Identifier) else None
            if sym is None or sym.kind not in ("local", "param"):
                return False
            saved = tr.fn
            tr.fn = _Standin(caller)
            try:
                facts = _facts(tr)
            finally:
                tr.fn = saved
            if not facts.ok or id(arg) not in facts.enter:
                return False
            # (the out write of a call of this function, which never writes x, changes nothing)
            writes = [w for w in facts.writes_to(sym)
                      if not (w.kind == "out" and isinstance(w.node, A.Call) and tr.model.call_target(w.node) is fn)]
            at = facts.enter[id(arg)]
            before = [w for w in writes if w.pos < at]
            if not before:
                return False
            last = before[-1]
            merged = not facts.dominates(last.node, arg)
            if not merged:
                outer = {id(loop) for loop in facts.enclosing_loops(last.node)}
                merged = any(facts.enter[id(loop)] <= w.pos <= facts.exit[id(loop)]
                             for loop in facts.enclosing_loops(arg) if id(loop) not in outer for w in writes)
            if not merged:
                return False
            found = True
    return found


def _sum_plan(tr: Any, x: Any, t: Any, depth: int) -> tuple | None:
    """Where a constant added to ``x`` goes: ("leaf", x) when x is a term it stays beside,
    ("sum", receiver plan, other term, operator, receiver on the left) when x is a sum used
    once, None where the rewrite is not copied."""
    if tr.type_of(x) != t or tr.has_effects(x):
        return None  # (a broadcast operand: keep it simple)
    inner = x
    if isinstance(x, A.Identifier) and _read_once(tr, x):
        init = _stable_init(tr, x) or _reaching_value(tr, x, unchanged=True)
        inner = init if init is not None and _one_copy(tr, init) else x
    elif not _used_once(tr, x):
        inner = None
    if not (isinstance(inner, A.Binary) and inner.op in _SUMS) or depth > 16:
        return ("leaf", x) if _known_term(tr, x) else None
    a, b = inner.left, inner.right
    if any(_const(tr, y) or _has_matrix(tr, y) or tr.type_of(y) != t for y in (a, b)):
        return None
    if not all(_known_term(tr, y) for y in (a, b)):
        return None  # a term NIR looks into (a call inlined, a mix, ...): not copied
    if _factor_parts(tr, inner) is not None:
        return ("leaf", x)  # factored first (a*b + a*c -> a*(b + c)): a product, no sum
    if _fmul(tr, b) or not _fmul(tr, a):
        recv = _sum_plan(tr, a, t, depth + 1)
        return None if recv is None else ("sum", recv, b, inner.op, True)
    if inner.op == "-":
        return ("sum", ("neg", b), a, "+", False)  # fneg(b) + #c: no sum to sink into
    recv = _sum_plan(tr, b, t, depth + 1)
    return None if recv is None else ("sum", recv, a, "+", False)


def _plan_leaves(plan: tuple, out: list[Any]) -> None:
    """The nodes of a :func:`_sum_plan` in the order :func:`_plan_code` reads their codes."""
    if plan[0] == "sum":
        _plan_leaves(plan[1], out)
        out.append(plan[2])
    else:
        out.append(plan[1])


def _plan_code(plan: tuple, codes: Any, k: str) -> str:
    if plan[0] == "leaf":
        return f"({next(codes)} + {k})"
    if plan[0] == "neg":
        return f"((-{next(codes)}) + {k})"
    recv = _plan_code(plan[1], codes, k)
    other = next(codes)
    return f"({recv} {plan[3]} {other})" if plan[4] else f"({recv} + {other})"


def _known_term(tr: Any, node: Any) -> bool:
    """A term whose kind to NIR is known: opaque, a product (:func:`_fmul`), a sum, or a
    selection (``c ? x : y``, a bcsel: no product), written or the value of a local here."""
    if _opaque(tr, node) or _fmul(tr, node) or _sum(tr, node):
        return True
    if isinstance(node, A.Identifier):
        node = _stable_init(tr, node) or _reaching_value(tr, node)
    if not isinstance(node, A.Ternary):
        return False
    x, y = node.then, node.else_  # (c ? a*b : a*d is a * (c ? b : d) to NIR: not copied)
    return not (isinstance(x, A.Binary) and isinstance(y, A.Binary) and x.op == y.op)


def _sum(tr: Any, node: Any) -> bool:
    """A sum or difference (no product: :func:`_fmul` tells which term keeps the constant)."""
    return isinstance(node, A.Binary) and node.op in _SUMS


def _rebalanced(tr: Any, e: A.Binary) -> bool:
    """GLSL IR's do_rebalance_tree balances an expression tree of three or more additions of
    the same type whose leaves are variables (at most one constant) before NIR sees it:
    ``(a + b + c) + K`` reaches NIR as ``(a + b) + (c + K)`` (measured)."""
    stack, ops, constants = [e], 0, 0
    while stack:
        n = stack.pop()
        if isinstance(n, A.Binary):
            if n.op != "+" or tr.type_of(n) != tr.type_of(e):
                return False
            ops += 1
            stack += [n.left, n.right]
        elif _const(tr, n):
            constants += 1
        elif not (isinstance(n, A.Identifier) or (isinstance(n, A.Field) and tr.model.is_swizzle(n))):
            return False
    return ops >= 3 and constants <= 1


def _fmul(tr: Any, node: Any) -> bool:
    """The value is a product in NIR (nir_search's ``is_fmul``): a product of numbers or
    vectors, a local whose value here is one (its initializer, or the assignment that reaches
    this read: ``f = f*f*(3.0 - 2.0*f); ... f.xy``), or a component of either."""
    while isinstance(node, A.Field) and tr.model.is_swizzle(node):
        node = node.base
    if isinstance(node, A.Identifier):
        node = _stable_init(tr, node) or _reaching_value(tr, node)
    return node is not None and _is_product(tr, node)


def _facts(tr: Any) -> Any:
    """analysis.dataflow's execution-order facts of the current function, made once."""
    from ...semantics.analysis.dataflow import FunctionFacts

    cache = tr.fold_state.facts
    key = id(tr.fn.sym)
    if key not in cache:
        cache[key] = FunctionFacts(tr.fn.sym.node, tr.model)
    return cache[key]


def _reaching_value(tr: Any, ident: A.Identifier, unchanged: bool = False) -> Any:
    """The value the last whole assignment (or initializer) of a local gave it, when that write
    runs before this read on every path and nothing writes the variable in between (in
    program order, loops included: analysis.dataflow); else None. Its operands may have
    changed since (``f = f*f*...`` reads the old f): with `unchanged`, only a value whose
    variables nothing writes in between either, so its expression computes it again here."""
    sym = tr.model.symbol_of(ident)
    if sym is None or sym.kind not in ("local", "param") or tr.fn is None:
        return None
    facts = _facts(tr)
    if not facts.ok or id(ident) not in facts.enter:
        return None  # (a node of an inlined body: another function's)
    before = [w for w in facts.writes_to(sym) if w.pos < facts.enter[id(ident)]]
    if not before or before[-1].kind not in ("=", "init") or before[-1].value is None:
        return None
    w = before[-1]
    if not facts.dominates(w.node, ident) or facts.written_between(w.node, ident, [sym]):
        return None
    if unchanged:
        if tr.has_effects(w.value):
            return None
        read = [tr.model.symbol_of(n) for n in w.value.walk() if isinstance(n, A.Identifier)]
        if sym in read or facts.written_between(w.node, ident, [r for r in read if r is not None]):
            return None
    return w.value


def _factor(tr: Any, e: A.Binary, mask: str | None) -> str | None:
    """``a*b + a*c`` (either operand order, products possibly stored in never-written locals)
    as ``a * (b + c)``."""
    parts = _factor_parts(tr, e)
    if parts is None:
        return None
    shared, b, c = parts
    t = tr.type_of(e)
    ts, tb, tc = (_code(tr, x, mask) for x in (shared, b, c))
    tl, trr = tr.exprs([e.left, e.right], mask)
    rewritten = tr.binary_values("*", t, t, ts, f"({tb} + {tc})")  # float, no matrix: rt.fmul
    return f"({rewritten} if rt.lp else ({tl} + {trr}))"


def _factor_parts(tr: Any, e: Any) -> tuple[Any, Any, Any] | None:
    """(a, b, c) when the sum ``e`` is ``a*b + a*c`` as :func:`_factor` rewrites it, else None."""
    if not (isinstance(e, A.Binary) and e.op == "+"):
        return None
    left, right = _factors(tr, e.left), _factors(tr, e.right)
    if left is None or right is None or sorted(left[0]) == sorted(right[0]):
        return None  # (x*y + x*y is CSE'd to p + p first)
    for i in (0, 1):
        for j in (0, 1):
            if left[0][i] == right[0][j]:
                shared, b, c = left[1][i], left[1][1 - i], right[1][1 - j]
                break
        else:
            continue
        break
    else:
        return None
    rest = [x[0] if isinstance(x, tuple) else x for x in (b, c)]
    if not all(_opaque(tr, x) or _const(tr, x) for x in rest) or all(_const(tr, x) for x in rest):
        return None  # b + c would be rewritten further (or folded): not copied
    return shared, b, c


def _stable_vector(tr: Any, node: Any) -> bool:
    """A never-written vector local initialised as the difference of two opaque vectors
    (``vec3 oc = ro - center``: measured). A vector built from scalars is left out: there
    llvmpipe's bits follow neither order (other rules, such as ``sqrt(x) * sqrt(x) -> x``,
    reach into the components)."""
    init = _stable_init(tr, node) if isinstance(node, A.Identifier) else None
    if not (isinstance(init, A.Binary) and init.op == "-"):
        return False
    return all(_opaque(tr, x) or (isinstance(x, A.Call) and x.constructor and len(x.args) > 1
                                  and all(_opaque(tr, a) for a in x.args)) for x in (init.left, init.right))


def _varying(tr: Any, node: Any, depth: int = 0) -> bool:
    """The value depends on an input (a uniform, fragCoord, a parameter, a written variable):
    it is not a constant after NIR's constant propagation."""
    if depth > 8:
        return True
    for n in node.walk():
        if isinstance(n, A.Identifier):
            s = tr.model.symbol_of(n)
            if s is None or s.const_value is not None or _constant_global(tr, s):
                continue
            if s.kind != "local":
                return True
            init = _stable_init(tr, n)
            if init is None or _varying(tr, init, depth + 1):
                return True
    return False


def _builtin(tr: Any, call: A.Call) -> bool:
    """The call names a built-in function (not a user function, not a constructor)."""
    tgt = tr.model.call_target(call)
    return isinstance(tgt, B.Overload)


def _factors(tr: Any, node: Any) -> tuple[tuple[str, str], tuple[Any, Any]] | None:
    """The two factors of a product ``node`` (their GLSL texts, and nodes or (node, component)
    pairs), looking through a never-written local defined as a product; None otherwise."""
    if _is_product(tr, node):
        if tr.type_of(node.left) != tr.type_of(node.right) and not (
                tr.type_of(node.left).is_scalar or tr.type_of(node.right).is_scalar):
            return None
        return (to_glsl(node.left), to_glsl(node.right)), (node.left, node.right)
    comp = None
    if isinstance(node, A.Field) and isinstance(node.base, A.Identifier) and len(node.name) == 1:
        comp = "xyzwrgbastpq".index(node.name) % 4 if node.name in "xyzwrgbastpq" else None
        if comp is None:
            return None
        node = node.base
    if not isinstance(node, A.Identifier):
        return None
    init = _stable_init(tr, node)
    if init is None or not _is_product(tr, init):
        return None
    parts = []
    for f in (init.left, init.right):
        ft = tr.type_of(f)
        if comp is not None and not ft.is_scalar:
            parts.append(((f, comp), f"({to_glsl(f)})[{comp}]"))
        elif comp is None and not ft == tr.type_of(init) and not ft.is_scalar:
            return None
        else:
            parts.append((f, to_glsl(f)))
    return (parts[0][1], parts[1][1]), (parts[0][0], parts[1][0])


def _code(tr: Any, x: Any, mask: str | None) -> str | None:
    if isinstance(x, tuple):
        node, comp = x
        return f"{tr.expr(node, mask)}[{comp}]"
    return tr.expr(x, mask)


def _stable_init(tr: Any, ident: A.Identifier) -> Any:
    """The initializer of a local that is written only by its declaration, whose identifiers
    are all such locals, never-written parameters, uniforms or constants; else None."""
    sym = tr.model.symbol_of(ident)
    bound = bound_argument(tr, sym)  # a parameter of an inlined call (transpile/inline.py)
    if bound is not None:
        return None if tr.has_effects(bound) else bound
    if sym is None or sym.kind != "local" or not isinstance(sym.node, A.Declarator) or sym.node.init is None:
        return None
    init = sym.node.init
    if tr.has_effects(init):
        return None
    written = _written(tr)
    if id(sym) in written:
        return None
    for n in init.walk():
        if isinstance(n, A.Identifier):
            s = tr.model.symbol_of(n)
            if s is None:
                continue
            if s.kind in ("local", "param") and id(s) in written:
                return None
            if s.kind == "global" and s.const_value is None and not _constant_global(tr, s):
                return None
    return init


def _written(tr: Any) -> set[int]:
    """Symbols of the current function that are assigned, incremented or passed to an out or
    inout parameter of a user function."""
    cache = tr.fold_state.written
    key = id(tr.fn.sym)
    if key not in cache:
        out: set[int] = set()

        def roots(x: Any) -> None:
            while isinstance(x, (A.Field, A.Index)):
                x = x.base
            if isinstance(x, A.Identifier):
                s = tr.model.symbol_of(x)
                if s is not None:
                    out.add(id(s))

        for n in tr.fn.sym.node.walk():
            if isinstance(n, A.Assignment):
                roots(n.target)
            elif isinstance(n, (A.Unary, A.Postfix)) and n.op in ("++", "--"):
                roots(n.operand)
            elif isinstance(n, A.Call) and isinstance(tr.model.call_target(n), Symbol):
                for a, d in zip(n.args, param_directions(tr.model.call_target(n))):
                    if d != "in":
                        roots(a)
        cache[key] = out
    return cache[key]


# -- products by constants merged per component, through component writes ---------------------
def component_write(tr: Any, node: Any, mask: str | None, old: str | None = None) -> str | None:
    """The code of the value a write gives a local, component by component as NIR sees it,
    or None (the write as usual). ``node``: a declarator with an initializer, or an assignment
    ``=`` / ``*=`` (``old``: the code of the target's value before a ``*=``).

    NIR splits a vector into its components (SSA per component), so a component's last write
    is what a later product by a constant reads, and ``#a * (b * #c) -> (a*c) * b`` merges the
    two constants: gargantua's ``radialCoords.z = distFromDisc * 1.5; radialCoords *= 0.95;``
    is ``distFromDisc * (1.5*0.95)`` on llvmpipe, and ``rc = radialCoords + 0.0; ... rc * 3.0``
    (``x + 0.0`` is x) merges a third constant. For a local that is written in part (a
    component, or a compound assignment) and read in such a product, directly or through a
    copy, each write keeps, per component, the factor y and the constants c1, c2, ... of its
    value ``y * c1 * c2 ...`` (y in a temporary: :func:`_chain`), and a later ``*`` by a
    constant (:func:`_merge_components`) or ``*=`` reads them through the write that last gave
    that component its value (:func:`_component_record`). The constants are folded in float32
    left to right, as NIR merges the inner product first."""
    if tr.fn is None or isinstance(tr.fn, _Standin):
        return None
    if isinstance(node, A.Assignment) and node.op in ("+=", "-="):
        return _cancelled_sum(tr, node, mask, old)
    if isinstance(node, A.Declarator):
        sym, comps, value = tr.model.symbol_of(node), None, node.init
    elif node.op in ("=", "*="):
        sym, comps = _target_components(tr, node.target)
        value = node.value
    else:
        return None
    if sym is None or id(sym) not in _component_locals(tr) or value is None or _writes_locals(tr, value):
        return None
    facts = _facts(tr)
    if id(node) not in facts.enter:
        return None  # (a node of an inlined body)
    compound = isinstance(node, A.Assignment) and node.op == "*="
    if compound and not _const(tr, value):
        return _kept_product(tr, node, mask, old)
    if compound and _has_matrix(tr, value):
        return None
    kept = compound and any(cs for _, cs in _chain(tr, node.target, mask, keep=False)[0])
    if not kept and not _read_later(tr, facts, sym, node):
        return None  # (no product by a constant reads what this write would keep)
    if compound:
        t = tr.type_of(node.target)
        entries, old = _times(tr, _chain(tr, node.target, mask, keep=True)[0], old, value, _size(t), mask, True)
        written = tr.binary_values("*", t, tr.type_of(value), old, tr.expr(value, mask))
    else:
        entries, written = _chain(tr, value, mask, keep=True)
    n = len(entries)
    comps = comps if comps is not None else tuple(range(n))
    if len(comps) != n:
        return None
    records = tr.fold_state.components
    records[id(node)] = (tr.lines, {c: (y, cs) for c, (y, cs) in zip(comps, entries) if cs})
    return _merged_code(tr, entries, written)


def _merge_components(tr: Any, e: A.Binary, mask: str | None) -> str | None:
    """``x * #k`` with x (or a swizzle of it) a local whose components :func:`component_write`
    kept, when a component's constants merge: each component ``y * (c*...*k)`` (llvmpipe
    mode), else as written."""
    if e.op != "*" or _has_matrix(tr, e.left, e.right):
        return None
    k, x = (e.left, e.right) if _const(tr, e.left) else (e.right, e.left)
    if not _const(tr, k) or _const(tr, x) or _local_root(tr, x) is None:
        return None
    if isinstance(tr.fn, _Standin) or id(_local_root(tr, x)) not in _component_locals(tr):
        return None
    entries, written = _chain(tr, e, mask, keep=False)
    if not any(len(cs) > 1 for _, cs in entries):
        return None
    return _merged_code(tr, entries, written)


def _merged_code(tr: Any, entries: list[tuple[str, list[Any]]], written: str) -> str:
    if not any(len(cs) > 1 for _, cs in entries):
        return written
    parts = []
    for y, cs in entries:
        cs = [c if isinstance(c, str) else tr.const_float(c) for c in cs]
        c = cs[-1] if cs else None
        for inner in reversed(cs[:-1]):
            c = f"({inner} * {c})"  # (nir_opt_algebraic visits the last instruction first)
        parts.append(y if c is None else tr.binary_values("*", FLOAT, FLOAT, y, c))
    merged = parts[0] if len(parts) == 1 else f"rt.vec({len(parts)}, {', '.join(parts)})"
    return f"({merged} if rt.lp else {written})"


def _chain(tr: Any, node: Any, mask: str | None, keep: bool) -> tuple[list[tuple[str, list[Any]]], str]:
    """([(y, [c1, c2, ...]) per component], the code of the value as written): the value of
    each component is ``y * c1 * c2 ...`` to NIR, y's code and the constants' codes.
    Followed: products by constants, swizzles, ``x + 0.0`` (x to NIR) and reads of a local
    (the components its reaching writes kept); anything else is y itself, no constant. With
    `keep`, a y that has constants is a temporary (it must outlive later writes)."""
    n = _size(tr.type_of(node))
    if isinstance(node, A.Binary) and node.op == "*" and not _has_matrix(tr, node.left, node.right):
        k_left = _const(tr, node.left)
        k, x = (node.left, node.right) if k_left else (node.right, node.left)
        if _const(tr, k) and not _const(tr, x):
            inner, wx = _chain(tr, x, mask, keep)
            entries, wx = _times(tr, inner, wx, k, n, mask, keep)
            tk = tr.expr(k, mask)
            lt, rt_ = tr.type_of(node.left), tr.type_of(node.right)
            written = tr.binary_values("*", lt, rt_, tk, wx) if k_left else tr.binary_values("*", lt, rt_, wx, tk)
            return entries, written
    if isinstance(node, A.Binary) and node.op == "+" and _zero(tr, node.right) and tr.type_of(node.left) == tr.type_of(node):
        inner, wx = _chain(tr, node.left, mask, keep)
        return inner, f"rt.fadd({wx}, {tr.expr(node.right, mask)})"
    if isinstance(node, A.Field) and tr.model.is_swizzle(node) and not tr.type_of(node.base).is_scalar:
        inner, wb = _chain(tr, node.base, mask, keep)
        idx = tr.model.swizzle_indices(node)
        sw = "".join("xyzw"[i] for i in idx)
        return [inner[i] for i in idx], (f"{wb}[{idx[0]}]" if len(idx) == 1 else f'rt.swizzle({wb}, "{sw}")')
    code = tr.expr(node, mask)
    found = [None] * n
    if isinstance(node, A.Identifier) and tr.type_of(node).base == "float":
        found = [_component_record(tr, node, i) for i in range(n)]
    return [f if f else (_component(code, i, n), []) for i, f in enumerate(found)], code


def _times(tr: Any, entries: list[tuple[str, list[Any]]], code: str, k: Any, n: int, mask: str | None,
           keep: bool) -> tuple[list[tuple[str, list[Any]]], str]:
    """Each component's entry times the constant k (a scalar, or a vector: its component), and
    the code of the factor (a temporary with `keep` when a component is the factor itself)."""
    if keep and any(not cs for _, cs in entries):
        code = tr.tmp(code)
        entries = [(y, cs) if cs else (_component(code, i, len(entries)), []) for i, (y, cs) in enumerate(entries)]
    if len(entries) == 1 and n > 1:
        entries = entries * n  # (a scalar times a vector constant)
    if tr.type_of(k).is_scalar:
        ks: list[Any] = [tr.expr(k, mask)] * n
    else:
        ks = list(_constant_value(tr, k))  # (values: named by _merged_code only if it uses them)
    return [(y, cs + [kc]) for (y, cs), kc in zip(entries, ks)], code


def _component(code: str, i: int, n: int) -> str:
    return code if n == 1 else f"{code}[{i}]"


def _size(t: Any) -> int:
    return t.size if t.is_vector else 1


def _zero(tr: Any, node: Any) -> bool:
    """A float constant +0.0 (``fadd(a, 0.0) -> a``)."""
    import math

    v = tr.model.const_value(node)
    return isinstance(v, float) and v == 0.0 and math.copysign(1.0, v) > 0


def _local_root(tr: Any, node: Any) -> Any:
    """The local or parameter a read names, through swizzles and ``+ 0.0``; else None."""
    while True:
        if isinstance(node, A.Field) and tr.model.is_swizzle(node):
            node = node.base
        elif isinstance(node, A.Binary) and node.op == "+" and _zero(tr, node.right):
            node = node.left
        else:
            break
    if isinstance(node, A.Identifier):
        s = tr.model.symbol_of(node)
        if s is not None and s.kind in ("local", "param") and tr.type_of(node).base == "float":
            return s
    return None


def _target_components(tr: Any, target: Any) -> tuple[Any, tuple[int, ...] | None]:
    """(the local an assignment writes, the components it writes: None for all) for a target
    that is a local or one swizzle of it; else (None, None)."""
    if isinstance(target, A.Identifier):
        return tr.model.symbol_of(target), None
    if (isinstance(target, A.Field) and isinstance(target.base, A.Identifier) and tr.model.is_swizzle(target)
            and not tr.type_of(target.base).is_scalar):
        return tr.model.symbol_of(target.base), tuple(tr.model.swizzle_indices(target))
    return None, None


def _component_locals(tr: Any) -> set[int]:
    """ids of the float locals of the current function :func:`component_write` follows: written
    in part (a component, a compound assignment) and read in a product by a constant (or by
    ``*=`` one), directly or through a copy into such a local."""
    cache = tr.fold_state.component_locals
    key = id(tr.fn.sym)
    if key in cache:
        return cache[key]
    facts = _facts(tr)
    if not facts.ok:
        cache[key] = set()
        return cache[key]
    partly = {key_ for key_, ws in facts.writes.items() if any(w.kind in ("part", "op") for w in ws)}
    reads: dict[int, list[Any]] = {}  # id(symbol) -> the nodes that read it so
    copies: list[tuple[Any, Any, Any]] = []
    for n in tr.fn.sym.node.body.walk():
        if isinstance(n, A.Binary) and n.op == "*":
            for a, b in ((n.left, n.right), (n.right, n.left)):
                s = _local_root(tr, b) if _const(tr, a) and not _const(tr, b) else None
                if s is not None:
                    reads.setdefault(id(s), []).append(n)
        elif isinstance(n, A.Assignment) and n.op == "*=" and _const(tr, n.value):
            s = _target_components(tr, n.target)[0]
            if s is not None:
                reads.setdefault(id(s), []).append(n)
        elif isinstance(n, A.Assignment) and n.op == "=" and isinstance(n.target, A.Identifier):
            copies.append((tr.model.symbol_of(n.target), _local_root(tr, n.value), n))
        elif isinstance(n, A.Declarator) and n.init is not None:
            copies.append((tr.model.symbol_of(n), _local_root(tr, n.init), n))
    grew = True
    while grew:
        grew = False
        for t, s, n in copies:
            if t is not None and s is not None and id(t) in reads and n not in reads.get(id(s), ()):
                reads.setdefault(id(s), []).append(n)
                grew = True
    tr.fold_state.component_reads[key] = reads
    cache[key] = set(reads) & partly
    return cache[key]


def _cancelled_sum(tr: Any, node: A.Assignment, mask: str | None, old: str) -> str | None:
    """``x.y += e; ... x.y -= e`` (either order, e the same text, its variables not written in
    between): x.y is its value before the ``+=`` to NIR (``('~fadd', ('fneg', a), ('fadd', a,
    b)) -> b``), with the constants :func:`component_write` kept for it (gargantua's ``rc.y +=
    iTime * speed; ... rc.y -= iTime * speed; ... rc * 6.0``). Each such write keeps the
    component's value before it (a temporary) for a later write that cancels it."""
    if tr.fn is None or isinstance(tr.fn, _Standin):
        return None
    sym, comps = _target_components(tr, node.target)
    value = node.value
    if sym is None or id(sym) not in _component_locals(tr) or _writes_locals(tr, value) or _has_matrix(tr, value):
        return None
    facts = _facts(tr)
    if id(node) not in facts.enter or tr.type_of(node.target).base != "float":
        return None
    ident = node.target if isinstance(node.target, A.Identifier) else node.target.base
    comps = comps if comps is not None else tuple(range(_size(tr.type_of(node.target))))
    undo = tr.fold_state.undo
    records = tr.fold_state.components
    before = []  # per component: (code, record) of its value before the write this one cancels
    for c in comps:
        w = _component_source(tr, ident, c)
        kept = undo.get(id(w.node)) if w is not None else None
        if (kept is None or kept[0] is not tr.lines or c not in kept[1] or w.node.op == node.op
                or to_glsl(w.node.value) != to_glsl(value) or tr.type_of(w.node.value) != tr.type_of(value)):
            before = None
            break
        read = [tr.model.symbol_of(n) for n in value.walk() if isinstance(n, A.Identifier)]
        if facts.written_between(w.node, node, [r for r in read if r is not None]):
            before = None
            break
        before.append(kept[1][c])
    if before is None and not _cancelled_later(tr, facts, sym, node):
        return None
    n = len(comps)
    t_old = tr.tmp(old)
    undo[id(node)] = (tr.lines, {c: (_component(t_old, j, n), _component_record(tr, ident, c))
                                 for j, c in enumerate(comps)})
    written = tr.binary_values(node.op[0], tr.type_of(node.target), tr.type_of(value), t_old, tr.expr(value, mask))
    if before is None:
        return written
    records[id(node)] = (tr.lines, {c: rec for c, (_, rec) in zip(comps, before) if rec})
    lp = before[0][0] if n == 1 else f"rt.vec({n}, {', '.join(code for code, _ in before)})"
    return f"({lp} if rt.lp else {written})"


def _kept_product(tr: Any, node: A.Assignment, mask: str | None, old: str) -> str | None:
    """``x *= b`` read once, by a product by a constant: its factors kept for
    :func:`_sunk_through_compound` (None: the write as usual)."""
    if not isinstance(node.target, A.Identifier) or id(node) not in _sink_reads(tr).values():
        return None
    t = tr.type_of(node.target)
    ta, tb = tr.tmp(old), tr.tmp(tr.expr(node.value, mask))
    tr.fold_state.kept_products[id(node)] = (tr.lines, ta, tb)
    return tr.binary_values("*", t, tr.type_of(node.value), ta, tb)


def _sunk_through_compound(tr: Any, e: A.Binary, mask: str | None) -> str | None:
    """``x * #c`` where x's value is ``a * b`` from ``x *= b``, read only here: ``(a * #c) * b``
    (``('~fmul', ('fmul(is_used_once)', a, b), '#c') -> (a * #c) * b``, the product used once
    in SSA): gargantua's ``coverage *= saturate(..); coverage = saturate(coverage * 0.7)``.
    Copied one level deep only: where a is itself a product NIR sees as used once the constant
    sinks on (not copied, left as written), so a must not be one (a sum, a built-in, or a
    call of a user function repeated with the same arguments in the function: CSE shares
    its value, as gargantua's second ``pcurve(radialGradient, 4.0, 0.9)``)."""
    if isinstance(tr.fn, _Standin) or getattr(tr.fn.sym, "node", None) is None:
        return None  # (a global's initializer)
    w_id = _sink_reads(tr).get(id(e))
    kept = tr.fold_state.kept_products.get(w_id) if w_id is not None else None
    if kept is None or kept[0] is not tr.lines:
        return None
    k = e.right if _const(tr, e.right) else e.left
    tk = tr.expr(k, mask)
    written = tr.binary_values("*", tr.type_of(e.left), tr.type_of(e.right), *tr.exprs([e.left, e.right], mask))
    t = tr.type_of(e)
    sunk = tr.binary_values("*", t, t, tr.binary_values("*", t, tr.type_of(k), kept[1], tk), kept[2])
    return f"({sunk} if rt.lp else {written})"


def _returns_product(tr: Any, call: A.Call) -> bool:
    """The user function called returns a product (its last statement ``return a * b``), or
    its result is not known here."""
    stmts = tr.model.call_target(call).node.body.stmts
    last = stmts[-1] if stmts else None
    return not isinstance(last, A.Return) or last.value is None or _is_product(tr, last.value) or any(
        isinstance(n, A.Return) for st in stmts[:-1] for n in st.walk())


def _sink_reads(tr: Any) -> dict[int, int]:
    """id(``x * #c``) -> id(``x *= b``) for the products :func:`_sunk_through_compound`
    rewrites: b not constant, x's value read only by that product, the value x had before
    the ``*=`` not a product NIR would sink into (see there)."""
    cache = tr.fold_state.sink_reads
    key = id(tr.fn.sym)
    if key in cache:
        return cache[key]
    out: dict[int, int] = {}
    facts = _facts(tr)
    calls: dict[str, int] = {}
    for n in tr.fn.sym.node.body.walk():
        if isinstance(n, A.Call) and isinstance(tr.model.call_target(n), Symbol):
            calls[to_glsl(n)] = calls.get(to_glsl(n), 0) + 1
    reads: dict[int, list[Any]] = {}
    targets = {id(n.target) for n in tr.fn.sym.node.body.walk() if isinstance(n, A.Assignment) and n.op == "="}
    for n in tr.fn.sym.node.body.walk():
        if isinstance(n, A.Identifier) and tr.model.symbol_of(n) is not None and id(n) not in targets:
            reads.setdefault(id(tr.model.symbol_of(n)), []).append(n)
    for n in tr.fn.sym.node.body.walk() if facts.ok else ():
        if not (isinstance(n, A.Binary) and n.op == "*" and tr.type_of(n).base == "float"
                and not _has_matrix(tr, n.left, n.right)):
            continue
        x = n.left if _const(tr, n.right) else n.right if _const(tr, n.left) else None
        if not isinstance(x, A.Identifier) or _const(tr, x) or id(x) not in facts.enter:
            continue
        sym = tr.model.symbol_of(x)
        before = [w for w in facts.writes_to(sym) if w.pos < facts.enter[id(x)]]
        w = before[-1] if before else None
        if (w is None or not isinstance(w.node, A.Assignment) or w.node.op != "*=" or _const(tr, w.node.value)
                or not isinstance(w.node.target, A.Identifier) or tr.type_of(w.node.target) != tr.type_of(x)
                or not facts.dominates(w.node, x) or facts.written_between(w.node, x, [sym])):
            continue
        later = [w2.pos for w2 in facts.writes_to(sym) if w2.pos > w.pos]
        end = min(later) if later else None
        users = [r for r in reads.get(id(sym), ()) if id(r) in facts.enter and facts.enter[id(r)] > w.pos
                 and (end is None or facts.enter[id(r)] < end) and r is not w.node.target]
        if users != [x] or facts.enclosing_loops(x) != facts.enclosing_loops(w.node):
            continue
        prev = [v for v in facts.writes_to(sym) if v.pos < facts.enter[id(w.node.target)]]
        a = prev[-1].value if prev and prev[-1].kind in ("=", "init") else None
        if a is None or _is_product(tr, a) or (isinstance(a, A.Call) and isinstance(tr.model.call_target(a), Symbol)
                                               and calls.get(to_glsl(a), 0) < 2 and _returns_product(tr, a)):
            continue
        out[id(n)] = id(w.node)
    cache[key] = out
    return out


def _cancelled_later(tr: Any, facts: Any, sym: Any, node: A.Assignment) -> bool:
    """A later compound assignment of ``sym`` subtracts what ``node`` adds (or adds what it
    subtracts), the same text: :func:`_cancelled_sum` may need the value before ``node``."""
    text, end = to_glsl(node.value), facts.exit[id(node)]
    return any(isinstance(w.node, A.Assignment) and w.node.op in ("+=", "-=") and w.node.op != node.op
               and w.pos > end and to_glsl(w.node.value) == text for w in facts.writes_to(sym))


def _component_record(tr: Any, ident: A.Identifier, i: int) -> tuple[str, list[str]] | None:
    """(y, constants) :func:`component_write` kept for component i of the local read here (from
    :func:`_component_source`'s write)."""
    last = _component_source(tr, ident, i)
    kept = tr.fold_state.components.get(id(last.node)) if last is not None else None
    if kept is None or kept[0] is not tr.lines:
        return None  # (not kept, or kept in another Python function: an outlined part)
    return kept[1].get(i)


def _component_source(tr: Any, ident: A.Identifier, i: int) -> Any:
    """The write (analysis.dataflow.Write) that last gave component i of the local read here its
    value: it runs before this read on every path, and nothing writes the component in between
    (loops around the read included); else None."""
    sym = tr.model.symbol_of(ident)
    if sym is None or sym.kind not in ("local", "param"):
        return None
    facts = _facts(tr)
    if not facts.ok or id(ident) not in facts.enter:
        return None
    at = facts.enter[id(ident)]
    writes = facts.writes_to(sym)
    last = None
    for w in writes:
        if w.pos < at and _writes_component(tr, w, i):
            last = w
    if last is None or not facts.dominates(last.node, ident):
        return None
    loops_w = {id(l) for l in facts.enclosing_loops(last.node)}
    for loop in facts.enclosing_loops(ident):
        if id(loop) not in loops_w:
            lo, hi = facts.enter[id(loop)], facts.exit[id(loop)]
            if any(lo <= w.pos <= hi and _writes_component(tr, w, i) for w in writes):
                return None
    return last


def _writes_locals(tr: Any, value: Any) -> bool:
    """The expression writes a variable (an assignment, ++/--, an out argument): a user call
    that only reads its arguments is computed once, as written, so it may stay."""
    for n in value.walk():
        if isinstance(n, (A.Assignment, A.Sequence)) or isinstance(n, (A.Unary, A.Postfix)) and n.op in ("++", "--"):
            return True
        if isinstance(n, A.Call) and any(d != "in" for d in param_directions(tr.model.call_target(n))):
            return True
    return False


def _read_later(tr: Any, facts: Any, sym: Any, node: Any) -> bool:
    """A product by a constant (or a copy into a local read so) reads ``sym`` after ``node``
    (one before it, in a loop, is not reached by this write: :func:`_component_record`)."""
    end = facts.exit[id(node)]
    return any(facts.enter.get(id(r), -1) > end for r in _component_reads(tr).get(id(sym), ()))


def _component_reads(tr: Any) -> dict[int, list[Any]]:
    _component_locals(tr)
    return tr.fold_state.component_reads[id(tr.fn.sym)]


def _writes_component(tr: Any, w: Any, i: int) -> bool:
    if isinstance(w.node, A.Assignment):
        comps = _target_components(tr, w.node.target)[1]
        if comps is not None:
            return i in comps
    return True


# -- a call's result in the lanes a mask leaves out: llvmpipe's register ------------------------
def register_call(tr: Any, call: A.Call, fn: Any) -> bool:
    """The result of this call of ``fn``, made under a mask in a function that takes
    derivatives, is llvmpipe's register in the lanes the mask leaves out: they keep the value
    they had the last time this call ran for them (frame.Lanes.reg).

    After inlining, NIR merges returns from inside a branch into one value (a phi); a branch
    computed by a built-in call (atan, pow, ...) is too costly to flatten into selects, so the
    phi becomes a register, stored under the exec mask, and a neighbour's derivative reads the
    old value in a lane that left (gargantua's GasDisc: ``atan2`` called after
    ``if (coverage < 0.01) return;`` in its 200-step loop, measured: the lane's value of the
    iteration before). Only in a loop NIR keeps: a loop of at most 32 iterations
    (max_unroll_iterations) is unrolled, each copy its own register, zero in such a lane
    (measured on a 4-step loop: the register kept across iterations put 917 of 14,400 pixels
    off, zero none)."""
    if tr.fn is None or id(tr.fn.sym) not in tr.facts.uses_derivs or not _returns_in_branch(tr, fn):
        return False
    return _in_kept_loop(tr, tr.fn.sym, call, 0)


def _returns_in_branch(tr: Any, fn: Any) -> bool:
    """``fn`` returns a value from inside an ``if`` or a loop, computed there by a call."""
    if fn.type is None or str(fn.type) == "void":
        return False
    for n in fn.node.body.walk():
        if isinstance(n, (A.If, A.For, A.While, A.DoWhile)) and any(
                isinstance(r, A.Return) and r.value is not None
                and any(isinstance(c, A.Call) and not c.constructor for c in r.value.walk()) for r in n.walk()):
            return True
    return False


def _in_kept_loop(tr: Any, sym: Any, node: Any, depth: int) -> bool:
    """``node`` (in function ``sym``) runs again and again in one invocation: its innermost
    loop, here or around every call of the function, is one NIR does not unroll."""
    from ...semantics.analysis.dataflow import FunctionFacts

    if depth > 8:
        return False
    cache = tr.fold_state.fn_facts
    if id(sym) not in cache:
        cache[id(sym)] = FunctionFacts(sym.node, tr.model)
    facts = cache[id(sym)]
    if not facts.ok or id(node) not in facts.enter:
        return False
    loops = facts.enclosing_loops(node)
    if loops:
        return not _unrolled(tr, loops[-1])
    sites = [(f, n) for f in tr.facts.functions for n in f.node.body.walk()
             if isinstance(n, A.Call) and tr.model.call_target(n) is sym]
    return bool(sites) and all(_in_kept_loop(tr, f, n, depth + 1) for f, n in sites)


def _unrolled(tr: Any, loop: Any) -> bool:
    """A ``for`` loop of a constant count of at most 32 iterations (NIR unrolls it)."""
    if not isinstance(loop, A.For) or induction_variable(loop, tr.model) is None:
        return False
    decl = loop.init.decl.declarators[0]
    start, cond, step = tr.model.const_value(decl.init), loop.cond, loop.step
    if not (isinstance(start, int) and isinstance(cond, A.Binary) and cond.op in ("<", "<=")
            and isinstance(cond.left, A.Identifier) and tr.model.symbol_of(cond.left) is tr.model.symbol_of(decl)):
        return False
    end = tr.model.const_value(cond.right)
    inc = 1 if isinstance(step, (A.Unary, A.Postfix)) and step.op == "++" else (
        tr.model.const_value(step.value) if isinstance(step, A.Assignment) and step.op == "+=" else None)
    if not isinstance(end, int) or not isinstance(inc, int) or inc <= 0:
        return False
    return (end - start + (cond.op == "<=") + inc - 1) // inc <= 32


# -- a constant added to a function's result, sunk into the sum it returns ----------------------
def sunk_return(tr: Any, fn: Any) -> list[tuple[Any, Any, str]] | None:
    """The sum a user function returns when a caller adds a constant to its result and NIR,
    which inlines every function, would sink that constant into it (:func:`_sink_sum`):
    ``float f; f = 0.5*noise(p); f += 0.25*noise(q); ... return f;`` called as
    ``displacement(x) - 0.4`` (iq's terrain) is ``((0.5*noise(p) - 0.4) + 0.25*noise(q)) + ...``
    on llvmpipe. Only the plain shape: the function's last statement returns a float local
    that nothing else reads, written by statements of the function's body (no branch, no loop)
    as ``f = a`` (or an initializer) then ``f += t`` / ``f -= t``; no out parameter, no other
    return. The terms [(write, value, operator)], else None. Such a function takes one more
    argument, the constant (None: add nothing; :func:`return_constant_args`), its terms are
    kept in temporaries (:func:`keep_term`) and its return reads them (:func:`sunk_return_value`)."""
    cache = tr.fold_state.sunk_returns
    if id(fn) not in cache:
        cache[id(fn)] = None
        if id(fn) in _sink_calls(tr) and all(d == "in" for _, _, d in fn.params):
            saved = tr.fn
            tr.fn = _Standin(fn)
            try:
                cache[id(fn)] = _return_chain(tr, fn)
            finally:
                tr.fn = saved
    return cache[id(fn)]


class _Standin:
    """What the rules read of the transpiler's current function (`tr.fn`), for another one."""

    def __init__(self, sym: Any) -> None:
        self.sym, self.is_entry = sym, False


def _sink_calls(tr: Any) -> set[int]:
    """ids of the user functions some call of which has a constant added to its result."""
    found = tr.fold_state.sink_calls
    if found is None:
        found = tr.fold_state.sink_calls = set()
        for sym in tr.model.reachable_functions():
            for n in sym.node.body.walk():
                if isinstance(n, A.Binary) and n.op in _SUMS:
                    for call, k in ((n.left, n.right), (n.right, n.left)):
                        target = tr.model.call_target(call) if isinstance(call, A.Call) else None
                        if isinstance(target, Symbol) and tr.model.const_value(k) is not None:
                            found.add(id(target))
    return found


def _return_chain(tr: Any, fn: Any) -> list[tuple[Any, Any, str]] | None:
    body = fn.node.body.stmts
    if not body or not isinstance(body[-1], A.Return) or not isinstance(body[-1].value, A.Identifier):
        return None
    ret = body[-1].value
    sym = tr.model.symbol_of(ret)
    if sym is None or sym.kind != "local" or tr.type_of(ret).base != "float" or tr.type_of(ret).is_matrix:
        return None
    for n in fn.node.body.walk():
        if isinstance(n, (A.Return, A.Discard)) and n is not body[-1] or isinstance(n, A.Call) and id(
                tr.model.call_target(n)) in tr.facts.may_discard:
            return None  # (an early exit: the return would not be the function's last statement)
    top = {id(st.expr) for st in body if isinstance(st, A.ExpressionStatement)}
    top |= {id(d) for st in body if isinstance(st, A.DeclarationStatement)
            and isinstance(st.decl, A.VariableDeclaration) for d in st.decl.declarators}
    writes = [w for w in _facts(tr).writes_to(sym) if w.kind != "decl"]
    if len(writes) < 2 or writes[0].kind not in ("=", "init") or writes[0].value is None:
        return None
    chain = [(writes[0].node, writes[0].value, "+")]
    for w in writes[1:]:
        if not (isinstance(w.node, A.Assignment) and w.node.op in ("+=", "-=")):
            return None
        chain.append((w.node, w.node.value, w.node.op[0]))
    targets = {id(w.node.target) for w in writes if isinstance(w.node, A.Assignment)}
    for n in fn.node.body.walk():
        if isinstance(n, A.Identifier) and tr.model.symbol_of(n) is sym and n is not ret and id(n) not in targets:
            return None  # (f read elsewhere: an intermediate sum used twice)
    if any(id(w) not in top or tr.type_of(v) != tr.type_of(ret) for w, v, _ in chain):
        return None
    first = chain[0][1]
    if not (_opaque(tr, first) or _fmul(tr, first)):
        return None  # a sum would take the constant further
    if not all(_known_term(tr, v) for _, v, _ in chain[1:]):
        return None
    if isinstance(first, A.Call) and isinstance(tr.model.call_target(first), Symbol):
        return None  # (a user function's result: what NIR sees in it is not followed)
    return chain


def _sink_into_call(tr: Any, e: A.Binary, mask: str | None) -> str | None:
    """``f(...) +- #c`` where f has a :func:`sunk_return`: the call, passed the constant in
    llvmpipe mode (the callee adds it where NIR sinks it), else None. Not where the function
    computes the same sum for another call of this function (same arguments, or any other call
    of a vector function: NIR scalarises, then CSE merges equal components): that sum is used
    twice there, and the constant stays outside (measured). Calls in other functions are not
    compared: a copy CSE merges across functions is not detected."""
    if e.op not in _SUMS:
        return None
    call, k = (e.left, e.right) if isinstance(e.left, A.Call) else (e.right, e.left)
    target = tr.model.call_target(call) if isinstance(call, A.Call) else None
    if (not isinstance(target, Symbol) or tr.model.const_value(k) is None or tr.type_of(k) != tr.type_of(e)
            or call is e.right and e.op == "-" or sunk_return(tr, target) is None):
        return None
    if not (_used_once(tr, e) and _used_once(tr, call)):
        return None
    shapes = _uses(tr)[0]
    others = [n for n in tr.fn.sym.node.body.walk()
              if isinstance(n, A.Call) and n is not call and tr.model.call_target(n) is target]
    if any(shapes.get(id(n)) == shapes.get(id(call)) for n in others) or others and tr.type_of(call).is_vector:
        return None  # NIR's CSE merges the inlined copies (per component for a vector): used twice
    tk = tr.expr(k, mask)
    signed = f"(-{tk})" if e.op == "-" else tk
    tr.fold_state.call_k[id(call)] = f"({signed} if rt.lp else None)"
    result = tr.tmp(tr.expr(call, mask))
    return f"({result} if rt.lp else ({result} {e.op} {tk}))"


def return_constant_args(tr: Any, call: A.Call, fn: Any) -> list[str]:
    """The extra argument of a call of a function with a :func:`sunk_return`: the constant the
    caller adds (:func:`_sink_sum`, llvmpipe mode) or None; [] for other functions."""
    if sunk_return(tr, fn) is None:
        return []
    return [tr.fold_state.call_k.get(id(call), "None")]


def keep_term(tr: Any, node: Any, code: str) -> str:
    """The code of a term of a :func:`sunk_return` sum, kept in a temporary; other values as
    they are. ``node``: the assignment or declarator that writes it."""
    if tr.fn is None or isinstance(tr.fn, _Standin):
        return code
    chain = sunk_return(tr, tr.fn.sym)
    if chain is None or not any(w is node for w, _, _ in chain):
        return code
    t = tr.tmp(code)
    tr.fold_state.terms[id(node)] = t
    return t


def sunk_return_value(tr: Any, ret: A.Return, code: str) -> str:
    """The returned value of a function with a :func:`sunk_return`: ``code`` when the caller
    adds nothing (``_k`` None), else the sum with the constant sunk as NIR sinks it."""
    chain = sunk_return(tr, tr.fn.sym) if tr.fn is not None else None
    terms = tr.fold_state.terms
    if chain is None or ret.value is None or not all(id(w) in terms for w, _, _ in chain):
        return code
    codes = [terms[id(w)] for w, _, _ in chain]
    (_, a, _), (_, t1, op1) = chain[0], chain[1]
    if _fmul(tr, t1) or not _fmul(tr, a):
        sunk = f"(({codes[0]} + _k) {op1} {codes[1]})"
    else:  # only a is a product: the constant joins the other term (its negation for -=)
        sunk = f"(({'-' if op1 == '-' else ''}{codes[1]} + _k) + {codes[0]})"
    for (_, _, op), c in zip(chain[2:], codes[2:]):
        sunk = f"({sunk} {op} {c})"
    return f"({code} if _k is None else {sunk})"
