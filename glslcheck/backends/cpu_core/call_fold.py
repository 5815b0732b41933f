"""Constants propagated into a call, per call site and per component, as NIR does after inlining.

Mesa inlines every function before its optimisations run (nir_inline_functions), scalarises
vectors and matrices (nir_lower_alu_to_scalar), then nir_opt_constant_folding and
nir_opt_algebraic work on each component's SSA value. So a vector argument whose components
are partly compile-time constants at one call site carries those constants into the callee's
arithmetic, and Mesa's constant-merging rules then reach across the call. The real shader
that shows it (gargantua, lstSRS, Buffer A):

    vec3 rotate(vec3 p, float x, float y, float z) { mat3 matx = mat3(1.0, 0.0, 0.0, 0.0,
        cos(x), sin(x), 0.0, -sin(x), cos(x)); ...  p = matx * p; p = matz * p; p = maty * p; }
    void RotateCamera(inout vec3 eyevec, inout vec3 eyepos) { ... vec3 angle = vec3(..., -0.45);
        eyepos = rotate(eyepos, angle.x, angle.y, angle.z); }
    ... vec3 eyepos = vec3(0.0, -0.0, -10.0); eyepos.x += ...; RotateCamera(eyevec, eyepos);

eyepos's y and z are -0.0 and -10.0 at the call, so the products by matx's zeros fold away
and ``matz * p`` multiplies the constant ``cos(-0.45)`` by ``-sin(ax) * -10.0``: NIR's
``#a * (b * #c) -> (a*c) * b`` gives ``(cos(-0.45) * 10) * sin(ax)`` (measured: llvmpipe's
eyepos.y is ``sin(-0.45)*x + (cos(-0.45)*10)*sin(ax)`` bit for bit). The NumPy backend writes a
function once for every call, so its code cannot see the constants of one call site.

Here a call of a straight-line function (declarations, assignments and a final return; nested
calls of such functions) is evaluated at the call site as NIR sees it: one scalar term per
component, the arguments' compile-time constant components (literals, a vector constructor's
constant arguments, and a local's components that are constant where the call reads them:
`_constant_components`) as constants, an argument
``y * #c`` as that product in each component (`_scaled_argument`), then

- constants folded in float32 (``+ - * /``, negation; a built-in of constants is a constant
  computed by the runtime's own function, as the written code computes it, but ``radians``
  and ``tan``, folded at compile time as Mesa does: :meth:`Evaluator.angle`);
- ``a * 1.0 -> a``, ``a * -1.0 -> -a``, ``a * 0.0 -> 0.0`` (inexact, a not constant),
  ``a + 0.0 -> a``;
- constants merged: ``#a * (b * #c) -> (a*c) * b`` and ``#a + (b + #c) -> (a+c) + b``;
- matrix products in GLSL IR's order (``m * v`` is ``(m[0]*v.x + m[1]*v.y) + m[2]*v.z`` per
  row), component-wise built-ins (sin, cos, ...) per component;
- ``dot`` summed right to left as Runtime.dot, two products that share a value factored,
  ``a*b + a*c -> a * (b + c)`` (`Evaluator.factored_add`: a hash's ``vec3(p)`` has three equal
  components).

Only where a merge happens (the other folds give the written bits, up to a -0.0, a NaN or an
infinity times a constant zero, which `Runtime.fmul`/`fadd` already fold at run time) is the
call replaced, in llvmpipe mode only: ``if rt.lp:`` the folded components, ``else:`` the call
as written, so the float64 reference and float16 keep the written order.

Structs of float members are values of their members' components one after the other (a
member read or written is a slice; ``S r;`` declares it unknown until written), ``normalize``
is ``x * inversesqrt(dot(x, x))`` and ``cross`` is Runtime.cross, per component. A struct
argument is followed where it is a local initialised by a call of such a function
(``cam k = make(vec3(off, -6.0), 7.0); ... ray(k, s, t)``): that call is evaluated again at
the call, its arguments read there (:func:`.call_sites.struct_source` checks that nothing
they read is written in between), so the constant -6.0 reaches ``ray``'s arithmetic as it
does after NIR inlines both. An argument's constant is also sunk down sums each used once,
``(a + b) + #c -> (a + #c) + b`` (:meth:`Evaluator.sunk`), where it cancels a constant of the same
component (the camera ray's ``ll + s*h + t*v - orig``, measured:
tests/gl/test_llvmpipe_constant_components.py). A call returning a struct of float members
is folded where an argument carries a constant (``ray get_ray(camera k, float s, float t)``:
the engines build the struct from its members' terms); a call writing a struct through an
out argument is left as written.

A call without arguments inside the callee that is not followed (a loop, a global written:
p05-3lccz8's ``cam.lens_radius * random_in_unit_disk()``, whose loop advances the global seed)
is an unknown value to NIR's rules after inlining, as a loop's result is: it is a run-time
value of the terms, the call made once by the engines among the values read at run time
(after the folded call's arguments, in the order of the callee's statements:
:meth:`Evaluator.opaque_call`).

Not copied: calls under a loop or a branch of the caller whose constants come from there (a
local counts as constant only where its writes are top-level statements before the call),
callees with branches, loops, arrays or non-float arithmetic, ``vec * mat``, and the other
rewrites that need "used once" (nir_fold's sink and sunk_return stay the rules within a
function).

What it tells nir_fold about a folded call's results: :func:`out_roots` (the operation at the
root of each component, so ``(eyevec * dither) * far`` may move its constant: eyevec is a
sum to NIR) and :func:`product_sums` (the two products of a component ``p1 + p2``, for
``(p1 + e) + p2``).

It does not replace the two older rules that reach across a call. inline.py's inlining for
``merged_dot`` needs the caller's never-written local seen through (``uv = q * 1.2`` passed as
``uv * 0.2``) and a ``dot`` with a constant merged, neither evaluated here (an argument that
is not a constant component is a run-time value); nir_fold.sunk_return sinks a constant into
a ``+=`` chain, a rewrite that needs "used once", not copied here. Both stay as they are, and
their generated code is unchanged.
"""

from __future__ import annotations

from typing import Any

from ...frontend import syntax as A
from ...language import builtin_functions as B
from ...semantics.model import Symbol
from .call_sites import struct_source, top_level_places, unchanged_init, written_components
from .fold_eval import (
    UNKNOWN,
    Evaluator,
    Refuse,
    Term,
    const_term,
    flat_terms,
    float_global,
    leaves_of,
    size_of,
    width_of,
)

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from .fold_protocols import FoldEmitter, FoldEngine


def _constant_components(tr: FoldEmitter, arg: Any, call: A.Call) -> list[Term | None] | None:
    """Per component of an argument `arg` of `call`, a vector constructor or a local: a
    constant term where its value is a compile-time constant there, else None; None when `arg`
    is neither. A constructor's constant arguments are its constant components
    (``f(vec2(x, 1.5))``: NIR's inlined ``p.y`` is 1.5). A local's are known only for a local
    declared, then written, by top-level statements of the current function before the one
    that holds `call` (writes of single components keep the others)."""
    if isinstance(arg, A.Call):
        t = tr.type_of(arg)
        if not (arg.constructor and t.is_vector and t.base == "float" and len(arg.args) > 1):
            return None
        return _constructed_components(tr, arg, t)
    sym = tr.model.symbol_of(arg) if isinstance(arg, A.Identifier) else None
    places = top_level_places(tr, sym, call)
    if places is None:
        return None
    stmts, decl, at = places
    assert sym is not None and isinstance(sym.node, A.Declarator) and sym.node.init is not None
    init, t = sym.node.init, tr.type_of(arg)
    if t.is_array or t.is_struct or t.base != "float":
        return None
    cv = tr.model.const_value(init)
    if cv is not None:
        comps: list[Term | None] = [const_term(v, True) for v in flat_terms(cv)]
    elif isinstance(init, A.Call) and init.constructor and t.is_vector and len(init.args) > 1:
        comps = _constructed_components(tr, init, t)
    else:
        return None
    for st in stmts[decl + 1 : at + 1]:
        for n in st.walk():
            hit = written_components(tr, n, sym, call)
            if hit == "all":
                comps = [None] * len(comps)
            elif hit:
                for i in hit:
                    comps[i] = None
    return comps


def _constructed_components(tr: FoldEmitter, ctor: A.Call, t: Any) -> list[Term | None]:
    """Per component of the vector constructor `ctor` (of type `t`): its constant term, or None
    where an argument is not a compile-time constant."""
    comps: list[Term | None] = []
    for a in ctor.args:
        v = tr.model.const_value(a)
        comps += (
            [const_term(x, True) for x in flat_terms(v)]
            if v is not None
            else [None] * width_of(tr.type_of(a))
        )
    return comps[: t.size]


def fold_plan(
    tr: FoldEmitter, call: A.Call, fn: Symbol, mask: str | None, chained: Any = None
) -> tuple | None:
    """(the parameters' final terms by symbol id, the parameter symbols, the result's terms,
    the arguments read at run time as (index, node)) of the call `call` of user function `fn`
    evaluated with constants propagated as NIR does (module doc: each engine emits the terms);
    None where this call is left as written (the common case): no argument has a constant
    component, or the constants merge no more than they do with every argument a run-time value
    (merges inside the callee alone are nir_fold's, in the function's own code), and no dot
    product of the callee factors (``vec3(p.xyx)`` of Dave Hoskins' hash12: two products share
    p.x). `chained(fn)`: whether a seed chain runs through user function fn (the engines
    pass nir_fold.repeated_sums.chain_params, which imports this module: Evaluator.opaque_call)."""
    if (
        tr.fn is None
        or tr.fold_state.call_fold_off
        or tr.fold_state.inline_frames
        or any(tr.has_effects(a) for a in call.args)
        or any(d != "in" and tr.type_of(a).is_struct for a, (_, _, d) in zip(call.args, fn.params))
    ):
        return None
    try:
        constant = _has_constant_argument(tr, call, fn)
        if not constant and (tr.type_of(call).is_struct or not _calls_dot(tr, fn)):
            return None  # (a struct result: only where an argument carries a constant)
        ev, env, params, result, holders = _evaluate(tr, call, fn, mask, True, chained)
        if (
            ev.factored == 0
        ):  # (a factored dot product is folded here only: Runtime.dot keeps the products)
            if not constant or ev.merges == 0:
                return None
            if _evaluate(tr, call, fn, mask, False, chained)[0].merges >= ev.merges:
                return None
    except Refuse:
        return None
    if ev.wrote_global and opaque_calls(call, holders):
        return None  # (the call as written makes the global writes, the opaque call its own)
    return env, params, result, holders


def opaque_calls(call: A.Call, holders: list[tuple[int, Any]]) -> bool:
    """Whether a folded call's run-time values include calls the callee makes
    (:meth:`Evaluator.opaque_call`): their side effects (a global seed advanced) happen in the
    folded code, so the call is not run as written too."""
    return any(i >= len(call.args) for i, _ in holders)


def _calls_dot(tr: FoldEngine, fn: Symbol) -> bool:
    """`fn`'s body calls the built-in dot (where :meth:`Evaluator.factored_add` may apply)."""
    memo = tr.fold_state.call_fold_dots
    if id(fn) not in memo:
        memo[id(fn)] = any(
            isinstance(n, A.Call)
            and n.callee == "dot"
            and isinstance(tr.model.call_target(n), B.Overload)
            for n in fn.node.body.walk()
        )
    return memo[id(fn)]


def _has_constant_argument(tr: FoldEmitter, call: A.Call, fn: Symbol) -> bool:
    for a, (_, _, dr) in zip(call.args, fn.params):
        if dr == "in" and tr.type_of(a).is_struct:
            source = struct_source(tr, a, call)
            inner = tr.model.call_target(source) if source is not None else None
            if (
                source is not None
                and isinstance(inner, Symbol)
                and _has_constant_argument(tr, source, inner)
            ):
                return True
        elif dr != "out" and (
            tr.model.const_value(a) is not None
            or _scaled_argument(tr, a, call) is not None
            or any(k is not None for k in _constant_components(tr, a, call) or ())
        ):
            return True
    return False


def _scaled_argument(tr: FoldEmitter, a: Any, call: A.Call) -> tuple[Any, Any] | None:
    """(y, #c) for an argument written ``y * #c`` or ``#c * y`` (c a compile-time constant of
    y's type or a scalar, y not constant, no matrix): after inlining each component of the
    parameter is that product, into which NIR merges the callee's constants (NebulaSmoke's
    ``hash11(fi * 0.017)`` with ``fract(vec3(p) * 443.8975)``: ``fi * (0.017*443.8975)``), also
    through a local so initialised that nothing writes before `call` (NIR's SSA value)."""
    if isinstance(a, A.Identifier):
        a = unchanged_init(tr, a, call)
    if not (isinstance(a, A.Binary) and a.op == "*") or tr.has_effects(a):
        return None
    for y, c in ((a.left, a.right), (a.right, a.left)):
        ty, tc = tr.type_of(y), tr.type_of(c)
        if (
            tr.model.const_value(c) is not None
            and tr.model.const_value(y) is None
            and ty == tr.type_of(a)
            and not ty.is_matrix
            and not tc.is_matrix
            and (tc.is_scalar or tc == ty)
        ):
            return y, c
    return None


def _evaluate(
    tr: FoldEmitter,
    call: A.Call,
    fn: Symbol,
    mask: str | None,
    constants: bool,
    chained: Any = None,
) -> tuple:
    """The call evaluated with its arguments bound to stand-in parameters: (the evaluation,
    the parameters' final terms by symbol id, the parameter symbols, the result's terms, the
    arguments read at run time as (index, node)); `constants`: the arguments' constant
    components as constants, else every argument a run-time value. Raises Refuse."""
    ev = Evaluator(tr, mask)
    ev.slots, ev.chained = len(call.args), chained
    known = known_globals(tr, call)
    ev.globals = {k: [const_term(v) for v in vs] for k, vs in (known or {}).items()}
    ev.unknown = known is not None
    env: dict[int, list] = {}
    holders = ev.holders
    args = _argument_terms(tr, ev, call, fn, constants, holders, list(range(len(call.args))))
    params = [tr.model.symbol_of(p) for p in fn.node.proto.params]
    if any(p is None for p in params):
        raise Refuse
    for p, v in zip(params, args):
        env[id(p)] = v
    result = ev.body(fn, env)
    if ev.unknown and _reads_unknown(
        [result] + [env[id(p)] for p, (_, _, d) in zip(params, fn.params) if d != "in"]
    ):
        raise Refuse
    if constants:
        outs = [id(p) for p, (_, _, dr) in zip(params, fn.params) if dr != "in"]
        result, *written = ev.sunk([result] + [env[k] for k in outs])
        env.update(zip(outs, written))
    return ev, env, params, result, holders


def _argument_terms(
    tr: FoldEmitter,
    ev: Evaluator,
    call: A.Call,
    fn: Symbol,
    constants: bool,
    holders: list[tuple[int, Any]],
    slots: list[int],
    source_of: A.Call | None = None,
) -> list[list[Any]]:
    """Per argument of `call` (of `fn`), its components' terms (None: an out parameter's,
    unknown); an argument read at run time is added to `holders` as (its slot, the node). A
    struct argument is a local the value of a call of a user function initialises
    (:func:`.call_sites.struct_source`): that call is evaluated here, its own arguments in new slots
    (`source_of`: the call they are then read at)."""
    args: list[list[Any]] = []
    for a, (_, _, dr), i in zip(call.args, fn.params, slots):
        t = tr.type_of(a)
        if t.is_struct and dr == "in":
            source = struct_source(tr, a, call)
            inner = tr.model.call_target(source) if source is not None else None
            if (
                source is None
                or not isinstance(inner, Symbol)
                or any(d != "in" for _, _, d in inner.params)
            ):
                raise Refuse
            more = list(range(ev.slots, ev.slots + len(source.args)))
            ev.slots += len(source.args)
            values = _argument_terms(tr, ev, source, inner, constants, holders, more, call)
            args.append(ev.bound_call(inner, values))
            continue
        if t.is_array or t.is_struct or t.base != "float":
            raise Refuse
        if dr == "out":
            args.append([None] * width_of(t))
            continue
        cv = tr.model.const_value(a) if constants else None
        if cv is not None:
            args.append([const_term(v, True) for v in flat_terms(cv)])
            continue
        scaled = (
            _scaled_argument(tr, a, call)
            if constants and (source_of is None or not isinstance(a, A.Identifier))
            else None
        )  # (a local's initializer read at another call than its own: not followed)
        if (
            scaled is not None
        ):  # y * #c: each component a product by the constant (NIR merges into it)
            y, c = scaled
            holders.append((i, y))
            cs = [const_term(v, True) for v in flat_terms(tr.model.const_value(c))]
            args.append(
                [
                    Term("*", (x, cs[0] if len(cs) == 1 else cs[j]))
                    for j, x in enumerate(leaves_of(f"@{i}@", t))
                ]
            )
            continue
        known = _constant_components(tr, a, call) if constants else None
        leaves = leaves_of(f"@{i}@", t)
        holders.append((i, a))
        args.append(
            [k if k is not None else x for k, x in zip(known or [None] * len(leaves), leaves)]
        )
    return args


def out_roots(tr: FoldEmitter, call: A.Call, sym: Symbol | None) -> set[str] | None:
    """The operations at the root of each component of the value `call` (a call of a user
    function in the current function) writes into the variable `sym` passed whole as an out
    or inout argument, as NIR sees them after inlining: "+" (a sum), "*", "/", "neg", "call"
    (a built-in), "x" (an argument read as it is), "k" (a constant); None when the callee is
    not of the shape evaluated here (for nir_fold, which asks what a rule would look into)."""
    fn = tr.model.call_target(call)
    if not isinstance(fn, Symbol):
        return None
    memo = tr.fold_state.call_fold_roots
    key = (id(call), id(sym))
    if key not in memo:
        memo[key] = None
        try:
            _, env, params, _, _ = _evaluate(tr, call, fn, None, True)
        except Refuse:
            return None
        for a, p, (_, _, dr) in zip(call.args, params, fn.params):
            if dr != "in" and isinstance(a, A.Identifier) and tr.model.symbol_of(a) is sym:
                memo[key] = {"k" if t.const else t.op for t in env[id(p)]}
    return memo[key]


def _product_sum(t: Term) -> bool:
    """The term is ``p1 + p2`` of two run-time products (or negated products: fneg(fmul) is
    fused as fmul of a negated factor)."""
    return t.op == "+" and all(
        (x.args[0] if x.op == "neg" else x).op == "*" and not x.const for x in t.args
    )


def record_sums(tr: FoldEngine, call: A.Call, arg: Any, terms: list, memo: dict) -> None:
    """Where the folded call `call` writes the variable `arg` (an out argument), the code of
    the two products each of its components sums (`memo`: a term's id -> its code), for
    :func:`product_sums`; read where the call was emitted (`tr.lines`)."""
    if isinstance(arg, A.Identifier):
        tr.fold_state.call_fold_sums[(id(call), id(tr.model.symbol_of(arg)))] = (
            [tuple(memo[id(x)] for x in t.args) if _product_sum(t) else None for t in terms],
            tr.lines,
        )


def product_sums(
    tr: FoldEngine, call: A.Call, sym: Symbol | None
) -> list[tuple[str, str] | None] | None:
    """Per component of the value the folded call `call` (written by an engine in the current
    Python function: :func:`record_sums`) wrote into the variable `sym`: the code of its two
    products when it is ``p1 + p2`` to NIR, else None; None when the call was not folded here.
    For nir_fold's ``(p1 + p2) + e -> (p1 + e) + p2``, read in llvmpipe mode only: the codes
    are temporaries of the ``if rt.lp:`` branch."""
    found = tr.fold_state.call_fold_sums.get((id(call), id(sym)))
    if found is None or found[1] is not tr.lines:
        return None  # (not folded, or folded in another Python function: an outlined part)
    return found[0]


def _reads_unknown(outs: list[list]) -> bool:
    """Some term of `outs` reads a global's unknown value."""
    seen: set[int] = set()
    todo = [t for terms in outs for t in terms if t is not None]
    while todo:
        t = todo.pop()
        if t is UNKNOWN:
            return True
        if id(t) not in seen:
            seen.add(id(t))
            todo.extend(t.args)
    return False


def known_globals(tr: FoldEmitter, call: A.Call) -> dict[int, list[float]] | None:
    """The float globals whose values are compile-time constants where the entry point makes
    `call` (by symbol id, their components), as Mesa knows them after inlining every call: the
    entry has no caller, so its globals start at their constant initializers (zero without
    one), and a top-level statement before `call` that only calls straight-line functions
    (:meth:`Evaluator.body`) leaves each global it writes at the constant those functions compute
    (``bump(); bump();`` with ``gCount += 1.0``). A global written under a branch or a loop, by
    a function this evaluation refuses, or from a run-time value is unknown from there on. Empty
    for a call in any other function, or under a branch or a loop of the entry: None."""
    f = tr.fn
    if f is None or not f.is_entry or f.sym is None:
        return None
    memo = tr.fold_state.call_fold_globals
    if memo is None:
        memo = tr.fold_state.call_fold_globals = _entry_globals(tr, f.sym)
    return memo.get(id(call))


def _entry_globals(tr: FoldEmitter, entry: Symbol) -> dict[int, dict[int, list[float]]]:
    """:func:`known_globals` for each call of a user function at the entry's top level."""
    state: dict[int, list[float]] = {}
    for sym in _globals(tr):
        t = sym.type
        init = sym.node.init if isinstance(sym.node, A.Declarator) else None
        if not float_global(sym):
            continue
        cv = tr.model.const_value(init) if init is not None else None
        if init is None:
            state[id(sym)] = [0.0] * size_of(t)
        elif cv is not None:
            state[id(sym)] = flat_terms(cv)
    found: dict[int, dict[int, list[float]]] = {}
    for st in entry.node.body.stmts:
        calls = _straight_calls(tr, st)
        if calls is None:
            _forget(tr, st, state)
            continue
        for c in calls:
            found[id(c)] = dict(state)
            _call_effect(tr, c, state)
        if isinstance(st, A.ExpressionStatement) and isinstance(st.expr, A.Assignment):
            a = st.expr
            g = tr.model.symbol_of(a.target) if isinstance(a.target, A.Identifier) else None
            if g is not None and id(g) in state:
                cv = tr.model.const_value(a.value) if a.op == "=" else None
                if cv is not None and len(flat_terms(cv)) == len(state[id(g)]):
                    state[id(g)] = flat_terms(cv)
                else:
                    del state[id(g)]
    return found


def _globals(tr: FoldEmitter) -> list[Symbol]:
    """The global variables the entry's calls may read or write."""
    seen: dict[int, Symbol] = {}
    for root in _reached(tr):
        for n in root.node.body.walk():
            if isinstance(n, A.Identifier):
                sym = tr.model.symbol_of(n)
                if sym is not None and sym.kind == "global" and sym.const_value is None:
                    seen[id(sym)] = sym
    return list(seen.values())


def _reached(tr: FoldEmitter) -> list[Symbol]:
    """The entry and the user functions it calls, through the functions they call."""
    assert tr.fn is not None and tr.fn.sym is not None
    out: dict[int, Symbol] = {}
    todo = [tr.fn.sym]
    while todo:
        fn = todo.pop()
        if id(fn) in out:
            continue
        out[id(fn)] = fn
        for n in fn.node.body.walk():
            if isinstance(n, A.Call) and isinstance(t := tr.model.call_target(n), Symbol):
                todo.append(t)
    return list(out.values())


def _straight_calls(tr: FoldEmitter, st: Any) -> list[A.Call] | None:
    """The calls of user functions of a declaration or expression statement of the entry, in the
    order they run (arguments first); None for any other statement, or one that writes a
    global other than as ``g = value;`` or chooses what runs (``?:``, ``&&``, ``||``)."""
    if isinstance(st, A.ExpressionStatement):
        root: Any = st.expr
    elif isinstance(st, A.DeclarationStatement) and isinstance(st.decl, A.VariableDeclaration):
        root = st.decl
    else:
        return None
    top = root.target if isinstance(root, A.Assignment) else None
    calls: list[A.Call] = []

    def visit(n: Any) -> bool:
        if isinstance(n, A.Ternary) or isinstance(n, A.Binary) and n.op in ("&&", "||"):
            return False
        for c in n.children():
            if not visit(c):
                return False
        for sym in tr.facts.written_variables(n):
            if sym.kind == "global" and not (n is root and top is not None):
                return False
        if isinstance(n, A.Call) and isinstance(tr.model.call_target(n), Symbol):
            calls.append(n)
        return True

    return calls if visit(root) else None


def _call_effect(tr: FoldEmitter, call: A.Call, state: dict[int, list[float]]) -> None:
    """`state` after `call`: the globals the callee writes at the constants it computes from
    `state`, or unknown."""
    fn = tr.model.call_target(call)
    written = tr.facts.global_effects(fn)[1]
    if not written:
        return
    try:
        ev = _evaluated(tr, call, {k: [const_term(v) for v in vs] for k, vs in state.items()})
    except Refuse:
        for k in written:
            state.pop(k, None)
        return
    for k in written:
        terms = ev.globals.get(k)
        if terms is not None and all(t.op == "k" and t.value is not None for t in terms):
            state[k] = [float(t.value) for t in terms]
        else:
            state.pop(k, None)


def writes_constants(tr: FoldEmitter, call: A.Call, key: int) -> bool:
    """The straight-line function `call` calls leaves global `key` at constants (call_fold's
    evaluation: its arguments' constants, built-ins of constants, computed at run time or not),
    whatever it was before: a compile-time constant to Mesa there (nir_fold/ray_dots.py)."""
    try:
        ev = _evaluated(tr, call, {})
    except Refuse:
        return False
    terms = ev.globals.get(key)
    return terms is not None and all(t.const for t in terms)


def _evaluated(tr: FoldEmitter, call: A.Call, known: dict[int, list[Any]]) -> Evaluator:
    """An evaluation of the body of the straight-line function `call` calls, on its arguments'
    terms and the globals `known` (their terms by key); Refuse when it cannot be made."""
    fn = tr.model.call_target(call)
    ev = Evaluator(tr, None)
    ev.slots = len(call.args)
    ev.globals = known
    ev.unknown = True
    args = _argument_terms(tr, ev, call, fn, False, [], list(range(len(call.args))))
    params = [tr.model.symbol_of(p) for p in fn.node.proto.params]
    if any(p is None for p in params):
        raise Refuse
    ev.body(fn, {id(p): v for p, v in zip(params, args)})
    return ev


def _forget(tr: FoldEmitter, st: Any, state: dict[int, list[float]]) -> None:
    """Every global statement `st` may write (itself or through the functions it calls) is
    unknown from there on."""
    for n in st.walk():
        for sym in tr.facts.written_variables(n):
            state.pop(id(sym), None)
        if isinstance(n, A.Call) and isinstance(t := tr.model.call_target(n), Symbol):
            for k in tr.facts.global_effects(t)[1]:
                state.pop(k, None)
