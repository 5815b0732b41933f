"""The questions several of nir_fold's rule families ask about a value, as Mesa sees it.

What NIR knows that the written GLSL does not show: a constant is also a global or local
initialised by a constant expression and never written (GLSL IR's constant propagation); a
local written only by its declaration stands for its initializer, and an inlined parameter for
its argument (SSA values: :func:`stable_init`, :func:`reaching_value`); a value is "used once"
when its GLSL text appears once in the function (NIR's CSE would merge a copy: hash-consed by
:func:`node_shapes`); a value is opaque when no algebraic rule looks into it (a uniform, a
built-in computed by its own instruction: :func:`is_opaque`), a product in NIR's sense
(nir_search's ``is_fmul``: :func:`is_fmul`). The answers are memoised per function in the
transpiler's `fold_state`."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from ....base.diagnostics import Location
from ....frontend import syntax as A
from ....language import builtin_functions as B
from ....semantics.analysis import param_directions
from ....semantics.model import Symbol
from ..call_sites import local_initializer
from ..common import TEXTURE_FUNCTIONS, fold_tree
from ..fold_protocols import FoldedFunction, FoldEngine
from ..inline import bound_argument, inline_owner
from .inlined_results import returned_value

SUMS = ("+", "-")


def constant_value(tr: FoldEngine, node: Any) -> list[float] | None:
    """The scalars of a constant operand (see :func:`flrp.mix_form`), else None."""
    v = tr.model.const_value(node)
    if (
        v is None
        and isinstance(node, A.Identifier)
        and constant_global(tr, tr.model.symbol_of(node))
    ):
        v = tr.model.const_value(tr.model.symbol_of(node).node.init)
    if v is None and isinstance(node, A.Identifier):
        init = stable_init(tr, node)
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


def read_once(tr: FoldEngine, ident: A.Identifier) -> bool:
    """The variable is read at one place of its function (GLSL IR grafts its value there)."""
    sym = tr.model.symbol_of(ident)
    owner = inline_owner(tr, sym)
    body = owner.node.body if owner is not None else current_function(tr).sym.node.body
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


def is_constant(tr: FoldEngine, node: Any) -> bool:
    if tr.model.const_value(node) is not None:
        return True
    return isinstance(node, A.Identifier) and constant_global(tr, tr.model.symbol_of(node))


def constant_global(tr: FoldEngine, sym: Symbol | None) -> bool:
    """A global variable (not `const`) initialised by a constant expression and never written:
    a constant to Mesa (GLSL IR propagates it, opt_constant_variable), so to every rule here
    (``float PI = 3.14159265;`` then ``fract(p / PI)``: measured, the rules apply as for a
    `const`)."""
    if sym is None or sym.kind != "global" or sym.const_value is not None:
        return False
    init = sym.node.init if isinstance(sym.node, A.Declarator) else None
    return (
        init is not None
        and tr.model.const_value(init) is not None
        and id(sym) not in tr.facts.written_globals
    )


def is_product(tr: FoldEngine, node: Any) -> bool:
    """A product of numbers or vectors (a matrix product is no elementwise product)."""
    return (
        isinstance(node, A.Binary)
        and node.op == "*"
        and not is_constant(tr, node)
        and not has_matrix(tr, node.left, node.right)
    )


def has_matrix(tr: FoldEngine, *nodes: Any) -> bool:
    return any(tr.type_of(n).is_matrix for n in nodes)


# built-ins whose NIR result is an fadd or fmul (lowered to arithmetic): their values are not
# opaque to nir_opt_algebraic
_ARITHMETIC_BUILTINS = {
    "dot",
    "mix",
    "smoothstep",
    "normalize",
    "cross",
    "reflect",
    "refract",
    "faceforward",
    "radians",
    "degrees",
    "mod",
    "step",
    "atan",
    "asin",
    "acos",
    "tan",
    "sinh",
    "cosh",
    "tanh",
    "asinh",
    "acosh",
    "atanh",
    "exp",
    "log",
    "pow",
}


def is_opaque(tr: FoldEngine, node: Any, depth: int = 0) -> bool:
    """The value reaches NIR as something no algebraic rule looks into: a uniform, a
    never-written parameter of mainImage, a built-in computed by its own instruction (sin,
    fract, floor, sqrt, ...), a swizzle of one, or a never-written local initialised so."""
    if depth > 8:
        return False
    if isinstance(node, A.Field):
        return is_opaque(tr, node.base, depth + 1)
    if isinstance(node, A.Call):
        if node.constructor:
            return False
        if not is_builtin(tr, node):
            return opaque_call(tr, node, depth)
        return node.callee not in _ARITHMETIC_BUILTINS and not is_constant(tr, node)
    if isinstance(node, A.Identifier):
        sym = tr.model.symbol_of(node)
        if sym is None or is_constant(tr, node):
            return False
        if sym.kind in ("uniform", "builtin-var"):
            return True
        if sym.kind == "param":
            return current_function(tr).is_entry and id(sym) not in written_symbols(tr)
        init = stable_init(tr, node)
        return init is not None and is_opaque(tr, init, depth + 1)
    return False


def opaque_call(tr: FoldEngine, call: A.Call, depth: int = 0) -> bool:
    """A call of a user function that, inlined, is an opaque value (inlined_results.py: a
    ``fract`` the function returns) with an argument that varies (constant arguments: NIR
    folds the whole call to a constant)."""
    memo = tr.fold_state.opaque_call
    if id(call) not in memo:
        value = returned_value(tr, call)
        memo[id(call)] = (
            isinstance(value, A.Call)
            and is_builtin(tr, value)
            and value.callee not in TEXTURE_FUNCTIONS  # (a lookup's precision: lower_precision)
            and is_opaque(tr, value, depth + 1)
            and any(is_varying(tr, a) for a in call.args)
        )
    return memo[id(call)]


def inlined_calls_only(tr: FoldEngine, e: Any) -> bool:
    """``e``'s only side effects are calls :func:`opaque_call` counts as values (their
    arguments too): the rules may treat ``e`` as having none (dispatch.py)."""
    return bool(fold_tree(e, tr.fold_state.opaque_calls, lambda n, kids: _inlined(tr, n, kids)))


def _inlined(tr: FoldEngine, n: Any, kids: list[bool]) -> bool:
    if not all(kids) or isinstance(n, (A.Assignment, A.Sequence)):
        return False
    if isinstance(n, (A.Unary, A.Postfix)) and n.op in ("++", "--"):
        return False
    if not isinstance(n, A.Call) or n.constructor:
        return True
    if is_builtin(tr, n):
        return all(d == "in" for d in param_directions(tr.model.call_target(n)))
    return opaque_call(tr, n)


def used_once(tr: FoldEngine, e: Any) -> bool:
    """``e`` feeds one instruction: its GLSL text appears once in the function (NIR's CSE
    would merge a copy) and it is an operand of a larger expression (a value stored in a
    variable feeds every use of the variable)."""
    return id(e) in use_counts(tr)[2] and one_copy(tr, e)


def one_copy(tr: FoldEngine, e: Any) -> bool:
    """The GLSL text of ``e`` appears once in the function (NIR's CSE would merge a copy)."""
    shapes, counts, _ = use_counts(tr)
    return counts.get(shapes.get(id(e), -1), 0) <= 1


def use_counts(tr: FoldEngine) -> tuple[dict[int, int], dict[int, int], set[int]]:
    """(shape of each node, copies of each shape among the binary expressions, ids of the
    operands of binary expressions and built-in calls) of the current function."""
    parents = tr.fold_state.parents
    key = id(current_function(tr).sym)
    if key not in parents:
        shapes = node_shapes(
            current_function(tr).sym.node.body, lambda n: not has_matrix(tr, n.left, n.right)
        )
        counts: dict[int, int] = {}
        operands: set[int] = set()
        for n in current_function(tr).sym.node.body.walk():
            if isinstance(n, A.Binary):
                operands.update((id(n.left), id(n.right)))
                counts[shapes[id(n)]] = counts.get(shapes[id(n)], 0) + 1
            elif isinstance(n, A.Call) and (n.constructor or is_builtin(tr, n)):
                operands.update(id(a) for a in n.args)  # (a user function may read it twice)
        parents[key] = (shapes, counts, operands)
    return parents[key]


def node_shapes(root: Any, commutes: Any = None) -> dict[int, int]:
    """id(node) -> a number shared by exactly the nodes of the same shape (same class, same
    fields, same shapes of children; locations left out): what equal GLSL text means, found in
    one pass (hash-consing) instead of printing every subtree, which is quadratic in a chain
    `a + b + c + ...` of thousands of terms (as a hostile input may hold). With `commutes` (a
    test of a ``+`` or ``*``: no matrix operand), ``a * b`` and ``b * a`` are one shape, as
    NIR's CSE compares a commutative operation's operands in either order
    (nir_instrs_equal)."""
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
        if commutes is not None and isinstance(node, A.Binary) and node.op in ("+", "*"):
            if parts[2] > parts[3] and commutes(node):  # ([Binary, op, left, right])
                parts[2], parts[3] = parts[3], parts[2]
        ids[id(node)] = table.setdefault(tuple(parts), len(table))
    return ids


def call_write(tr: FoldEngine, node: Any) -> Any:
    """The write (analysis.dataflow.Write) of a call of a user function that gave the variable
    ``node`` its value here (an out or inout argument, nothing written since), else None."""
    sym = tr.model.symbol_of(node) if isinstance(node, A.Identifier) else None
    if sym is None or sym.kind not in ("local", "param"):
        return None
    facts = function_facts(tr)
    if not facts.ok or id(node) not in facts.enter:
        return None
    before = [w for w in facts.writes_to(sym) if w.pos < facts.enter[id(node)]]
    if not before or before[-1].kind != "out" or not isinstance(before[-1].node, A.Call):
        return None
    w = before[-1]
    if not facts.dominates(w.node, node) or facts.written_between(w.node, node, [sym]):
        return None
    return w


def is_fmul(tr: FoldEngine, node: Any) -> bool:
    """The value is a product in NIR (nir_search's ``is_fmul``): a product of numbers or
    vectors, a local whose value here is one (its initializer, or the assignment that reaches
    this read: ``f = f*f*(3.0 - 2.0*f); ... f.xy``), or a component of either."""
    while isinstance(node, A.Field) and tr.model.is_swizzle(node):
        node = node.base
    if isinstance(node, A.Identifier):
        node = stable_init(tr, node) or reaching_value(tr, node)
    return node is not None and is_product(tr, node)


def function_facts(tr: FoldEngine) -> Any:
    """analysis.dataflow's execution-order facts of the current function, made once."""
    from ....semantics.analysis.dataflow import FunctionFacts

    cache = tr.fold_state.facts
    key = id(current_function(tr).sym)
    if key not in cache:
        cache[key] = FunctionFacts(current_function(tr).sym.node, tr.model)
    return cache[key]


def reaching_value(tr: FoldEngine, ident: A.Identifier, unchanged: bool = False) -> Any:
    """The value the last whole assignment (or initializer) of a local gave it, when that write
    runs before this read on every path and nothing writes the variable in between (in
    program order, loops included: analysis.dataflow); else None. Its operands may have
    changed since (``f = f*f*...`` reads the old f): with `unchanged`, only a value whose
    variables nothing writes in between either, so its expression computes it again here."""
    sym = tr.model.symbol_of(ident)
    if sym is None or sym.kind not in ("local", "param") or tr.fn is None:
        return None
    facts = function_facts(tr)
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


def is_varying(tr: FoldEngine, node: Any, depth: int = 0) -> bool:
    """The value depends on an input (a uniform, fragCoord, a parameter, a written variable):
    it is not a constant after NIR's constant propagation."""
    if depth > 8:
        return True
    for n in node.walk():
        if isinstance(n, A.Identifier):
            s = tr.model.symbol_of(n)
            if s is None or s.const_value is not None or constant_global(tr, s):
                continue
            if s.kind != "local":
                return True
            init = stable_init(tr, n)
            if init is None or is_varying(tr, init, depth + 1):
                return True
    return False


def is_builtin(tr: FoldEngine, call: A.Call) -> bool:
    """The call names a built-in function (not a user function, not a constructor)."""
    tgt = tr.model.call_target(call)
    return isinstance(tgt, B.Overload)


def stable_init(tr: FoldEngine, ident: A.Identifier) -> Any:
    """The initializer of a local that is written only by its declaration, whose identifiers
    are all such locals, never-written parameters, uniforms or constants, with no side effect
    but calls :func:`inlined_calls_only` counts as values; else None."""
    sym = tr.model.symbol_of(ident)
    bound = bound_argument(tr, sym)  # a parameter of an inlined call (cpu_core/inline.py)
    if bound is not None:
        return None if tr.has_effects(bound) else bound
    init = local_initializer(sym)
    if init is None:
        return None
    assert sym is not None  # (a local's initializer)
    if tr.has_effects(init) and not inlined_calls_only(tr, init):
        return None  # (a call that is its returned value once inlined is no effect)
    written = written_symbols(tr)
    if id(sym) in written:
        return None
    for n in init.walk():
        if isinstance(n, A.Identifier):
            s = tr.model.symbol_of(n)
            if s is None:
                continue
            if s.kind in ("local", "param") and id(s) in written:
                return None
            if s.kind == "global" and s.const_value is None and not constant_global(tr, s):
                return None
    return init


def written_symbols(tr: FoldEngine) -> set[int]:
    """Symbols of the current function that are assigned, incremented or passed to an out or
    inout parameter of a user function."""
    cache = tr.fold_state.written
    key = id(current_function(tr).sym)
    if key not in cache:
        out: set[int] = set()

        def roots(x: Any) -> None:
            while isinstance(x, (A.Field, A.Index)):
                x = x.base
            if isinstance(x, A.Identifier):
                s = tr.model.symbol_of(x)
                if s is not None:
                    out.add(id(s))

        for n in current_function(tr).sym.node.walk():
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


class FunctionStandin:
    """The engine's current function (`tr.fn`) as the rules read it, for another one."""

    def __init__(self, sym: Symbol) -> None:
        self.sym = sym
        self.is_entry = False


@contextmanager
def asked_in(tr: FoldEngine, fn: Symbol) -> Iterator[None]:
    """The rules asked about user function `fn` for a while (its facts, its chains), the
    engine's current function put back after. The one place that moves `tr.fn`, which the
    rules otherwise only read."""
    engine: Any = tr  # FoldEngine's fn is read-only to the rules
    saved = engine.fn
    engine.fn = FunctionStandin(fn)
    try:
        yield
    finally:
        engine.fn = saved


def current_function(tr: FoldEngine) -> FoldedFunction:
    """The function the rules are asked about (they run inside one: `tr.fn` is set)."""
    fn = tr.fn
    assert fn is not None
    return fn
