"""Values a helper function computes from its `in` parameters alone, and the calls that pass it
the same arguments (shared by repeated-across-calls and loop-invariant).

A value of a helper `H` is an expression worth reusing (as repeated-expression means it) that
takes a square root, a transcendental function or a division (`normalize`, `length`, `sqrt`,
`pow`, `sin`, ..., `(p - c) / r`, or a user function that does), pure, that reads `in`
parameters `H` never writes and nothing else but constants and uniforms, that `H` computes on
every call (not inside a branch or a loop of `H`, nor after its `return`), and that is not part
of a returned value computed from those parameters alone (then the calls themselves are the
repeated value, the caller's to reuse). Two calls of `H` with the same arguments for those
parameters compute it twice with the same value; a call in a loop whose arguments for them the
loop does not change computes it on every iteration with the same value."""

from __future__ import annotations

from ...frontend import syntax as A
from ...semantics.analysis import param_directions, program_facts
from ...semantics.model import Symbol

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from typing import Any

# what makes a part of a function run on some calls only
_CONDITIONAL = (A.If, A.For, A.While, A.DoWhile, A.Switch, A.Ternary)


def helper_values(fn, only: frozenset[int] | None = None) -> list[tuple[A.Expr, list[int]]]:
    """The values of the helper `fn` (see the module's doc), the largest ones only, each with
    the indexes of the parameters it reads; `only`: of those parameters alone (the others are
    read as variables of the call). Cached on the facts."""
    key = "_helper_values" if only is None else f"_helper_values{sorted(only)}"
    cached = fn.__dict__.get(key)
    if cached is not None:
        return cached
    found: list[tuple[A.Expr, list[int]]] = []
    fn.__dict__[key] = found
    if fn.symbol is None:
        return found
    model = fn.model
    params = [model.symbol_of(p) for p in fn.definition.proto.params]
    usable = {
        id(p): i
        for i, p in enumerate(params)
        if p is not None
        and fn.symbol.params[i][2] == "in"
        and not fn.writes_to(p)
        and (only is None or i in only)
    }
    if not usable:
        return found
    skip_until = -1  # the exit of the last value chosen: its parts are not values of their own
    for n in fn.nodes:  # in execution order: a value's parts follow it
        if type(n) in A.LEAF_CLASSES or not isinstance(n, A.Expr):
            continue
        if fn.enter[id(n)] <= skip_until:
            continue
        ops = fn.operands(n)  # (cached) the cheap test first: parameters (and frame inputs)
        if not any(id(s) in usable for s in ops) or not all(_fixed(s, usable) for s in ops):
            continue
        if fn.is_dead(n) or model.is_constant(n) or not (fn.worth_reusing(n) and fn.is_pure(n)):
            continue
        ups = _ancestors(fn, n)
        if any(type(a) in _CONDITIONAL or _short_circuit(a) for a in ups):
            continue
        ret = next((a for a in ups if type(a) is A.Return), None)
        if ret is not None and all(_fixed(s, usable) for s in fn.operands(ret.value)):
            continue  # what the helper returns comes from those parameters alone
        if not _costly(model, n, 0):
            continue
        skip_until = fn.exit[id(n)]
        found.append((n, sorted({usable[id(s)] for s in ops if id(s) in usable})))
    return found


# built-ins that take a square root or a transcendental function
_COSTLY = frozenset(
    "normalize length distance sqrt inversesqrt pow exp exp2 log log2 sin cos tan asin acos atan"
    " sinh cosh tanh asinh acosh atanh refract".split()
)


def _costly(model, e, depth: int) -> bool:
    """Whether `e` divides, calls a built-in of _COSTLY, or a user function whose body does."""
    for n in e.walk():
        if type(n) is A.Binary and n.op == "/":
            return True  # a reciprocal: dearer than adds and multiplies
        if type(n) is not A.Call:
            continue
        target = model.call_target(n)
        if not isinstance(target, Symbol):
            if n.callee in _COSTLY:
                return True
            continue
        body = getattr(getattr(target, "node", None), "body", None)
        if body is not None and depth < 4 and _costly(model, body, depth + 1):
            return True
    return False


def _fixed(s: Symbol, usable: dict[int, int]) -> bool:
    """A variable a value may read: a usable parameter, a constant, or a uniform (the same for
    every call in a frame: `fragCoord / iResolution.xy` is a value of `fragCoord` alone)."""
    return id(s) in usable or s.kind == "uniform" or (s.kind == "global" and s.qualifier == "const")


def _ancestors(fn, n) -> list[Any]:
    out, up = [], fn.parent.get(id(n))
    while up is not None:
        out.append(up)
        up = fn.parent.get(id(up))
    return out


def _short_circuit(a) -> bool:
    return type(a) is A.Binary and a.op in ("&&", "||")


def same_arguments(caller, first: A.Call, then: A.Call, indexes: list[int]) -> bool:
    """Whether two calls in `caller`, `first` on every path to `then`, pass the same values for
    the parameters `indexes`: the same pure expressions, no variable they read written in
    between (nor by the first call's `out` arguments)."""
    if not caller.dominates(first, then):
        return False
    outs = _out_symbols(caller, first)
    for i in indexes:
        if i >= len(first.args) or i >= len(then.args):
            return False
        a, b = first.args[i], then.args[i]
        if not (caller.is_pure(a) and caller.is_pure(b)) or caller.key(a) != caller.key(b):
            return False
        ops = caller.operands(a)
        if ops & outs or caller.written_between(first, then, ops, reads=a):
            return False
    return True


def invariant_arguments(caller, call: A.Call, loop, indexes: list[int]) -> bool:
    """Whether the arguments of `call` for the parameters `indexes` are the same on every
    iteration of `loop`: pure, and reading no variable the loop writes."""
    lo, hi = caller.enter[id(loop)], caller.exit[id(loop)]
    written = {id(w.symbol) for ws in caller.writes.values() for w in ws if lo < w.pos < hi}
    calls_user = any(lo < p < hi for p in caller.user_calls)
    for i in indexes:
        if i >= len(call.args) or not caller.is_pure(call.args[i]):
            return False
        for s in caller.operands(call.args[i]):
            if id(s) in written:
                return False
            if calls_user and s.kind == "global" and s.qualifier != "const":
                return False
    return True


def _out_symbols(caller, call: A.Call) -> frozenset:
    target = caller.model.call_target(call)
    syms: set = set()
    for arg, d in zip(call.args, param_directions(target)):
        if d in ("out", "inout"):
            syms |= caller.operands(arg)
    return frozenset(syms)


def call_sites(fn) -> list[tuple[Any, A.Call]]:
    """(caller's facts, call) of every call of the helper `fn`, in source order."""
    if not isinstance(fn.symbol, Symbol):
        return []
    return program_facts(fn.model).call_sites(fn.symbol)
