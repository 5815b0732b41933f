"""Which user functions compute their results from their arguments alone, and what they cost:
answers about functions and calls the dataflow facts (dataflow.py) and the rules share.

* `written_variable`: the variable an l-value writes, and whether all of it;
* `param_directions`: in/out/inout of each argument of a call;
* `pure_function`: a user function whose results depend only on its arguments;
* `ignored_parameters`: the parameters of a pure function that never reach its result;
* `function_cost`: whether calling a user function costs more than an add.
"""

from __future__ import annotations

from ...frontend import syntax as A
from ...language import builtin_functions as B
from ..model import CallTarget, Model, Symbol

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from typing import Any


def written_variable(model: Model, target: A.Expr) -> tuple[Symbol | None, bool]:
    """The variable an l-value writes (`v`, `v.x`, `a[i].f` all write `v`/`a`) and whether it
    writes all of it; (None, ...) when the l-value is not rooted in a variable."""
    whole = True
    while isinstance(target, (A.Field, A.Index)):
        whole = False
        target = target.base
    if isinstance(target, A.Identifier):
        return model.symbol_of(target), whole
    return None, whole


def param_directions(target: CallTarget | None) -> list[str]:
    """ "in", "out" or "inout" for each parameter of a call's target (a constructor: none)."""
    if isinstance(target, Symbol):
        return [d for _, _, d in target.params]
    if isinstance(target, B.Overload):
        return list(target.qualifiers)
    return []


def _model_cache(model: Model, name: str) -> dict:
    return model.analysis_caches.setdefault(name, {})


def pure_function(
    model: Model, sym: Symbol, _seen: frozenset = frozenset(), outputs: bool = False
) -> bool:
    """A user function whose result depends only on its arguments: `in` parameters only, no
    write to a global, no read of a global variable that is not const (uniforms are constant in
    a frame), and only pure functions called (`float lenSq(vec2 v) { return dot(v, v); }`), or
    ones whose `out` arguments are its own locals.
    With `outputs`, `out` and `inout` parameters are allowed too: its results (returned and
    written out) depend only on its arguments' values."""
    cache = _model_cache(model, "pure_outputs" if outputs else "pure_function")
    if id(sym) in cache:
        return cache[id(sym)]
    d = sym.node
    allowed = ("in", "out", "inout") if outputs else ("in",)
    ok = (
        isinstance(d, A.FunctionDefinition)
        and d.body is not None
        and id(sym) not in _seen
        and all(direction in allowed for _, _, direction in sym.params)
    )
    if ok:
        for n in model.body_nodes(d):
            t = type(n)
            if t is A.Identifier:
                s = model.symbol_of(n)
                if s is not None and s.kind == "global" and s.qualifier != "const":
                    ok = False
            elif t is A.Call:
                target = model.call_target(n)
                seen = _seen | {id(sym)}
                if target is None:
                    ok = False
                elif isinstance(target, B.Overload) and target.out_params:
                    ok = _local_outputs(model, n)
                elif isinstance(target, Symbol) and not pure_function(model, target, seen, outputs):
                    # a call whose outputs are this function's own locals writes nothing else
                    # (`float sdf(vec3 p) { int id; return sdf(p, id); }`)
                    ok = _local_outputs(model, n) and pure_function(model, target, seen, True)
            if not ok:
                break
    if not _seen:
        cache[id(sym)] = ok
    return ok


def _local_outputs(model: Model, call: A.Call) -> bool:
    """Whether every `out` or `inout` argument of a call is a local variable (or a part of one)
    of the function making it."""
    for arg, direction in zip(call.args, param_directions(model.call_target(call))):
        if direction in ("out", "inout"):
            written, _ = written_variable(model, arg)
            if written is None or written.kind != "local":
                return False
    return True


def ignored_parameters(model: Model, sym: Symbol) -> frozenset[int]:
    """Indexes of the parameters of a pure function (`pure_function`) whose value never reaches
    its result: no returned value and no condition (of a branch, a loop, a `?:` or a switch)
    reads it, directly or through the variables assigned from it (`rec` of `bool hit(in Ray r,
    in Hit rec)` that only fills in the fields of its own copy). Flow-insensitive: a variable
    any of whose values reads a parameter depends on it everywhere, so it errs toward
    dependence."""
    cache = _model_cache(model, "ignored_parameters")
    found = cache.get(id(sym))
    if found is not None:
        return found
    found = cache[id(sym)] = frozenset()
    if not pure_function(model, sym):
        return found
    symbol_of = model.symbol_of

    def reads(e: Any) -> set[int]:
        return {
            id(v) for n in e.walk() if type(n) is A.Identifier and (v := symbol_of(n)) is not None
        }

    flows: dict[int, set[int]] = {}  # id(variable) -> ids of the variables its values read
    reached: set[int] = set()  # the variables a returned value or a condition reads
    for n in model.body_nodes(sym.node):
        t = type(n)
        if t is A.Assignment:
            target, _ = written_variable(model, n.target)
            if target is not None:
                flows.setdefault(id(target), set()).update(reads(n.value), reads(n.target))
        elif t is A.Declarator and n.init is not None and (v := symbol_of(n)) is not None:
            flows.setdefault(id(v), set()).update(reads(n.init))
        elif t is A.Return and n.value is not None:
            reached |= reads(n.value)
        elif t in (A.If, A.While, A.DoWhile, A.Ternary, A.For) and n.cond is not None:
            reached |= reads(n.cond)
        elif t is A.Switch:
            reached |= reads(n.expr)
    todo = list(reached)
    while todo:
        for other in flows.get(todo.pop(), ()):
            if other not in reached:
                reached.add(other)
                todo.append(other)
    params = [symbol_of(p) for p in sym.node.proto.params]
    found = cache[id(sym)] = frozenset(
        i for i, p in enumerate(params) if p is not None and id(p) not in reached
    )
    return found


def function_cost(model: Model, sym: Symbol) -> bool:
    """Whether calling the user function costs more than an add: two operations or a costly
    built-in in its body (a wrapper like `asPoint(v)`, `vec4(v, 1.0)`, does not)."""
    cache = _model_cache(model, "op_cost")
    if id(sym) not in cache:
        cache[id(sym)] = False  # a recursive call (an error anyway) costs nothing more
        ops, costly = 0, False
        d = sym.node
        for n in (
            model.body_nodes(d)
            if isinstance(d, A.FunctionDefinition) and d.body is not None
            else ()
        ):
            if type(n) in (A.Binary, A.Ternary) or (type(n) is A.Unary and n.op != "+"):
                ops += 1
            elif type(n) is A.Call:
                target = model.call_target(n)
                if isinstance(target, B.Overload):
                    ops += 1
                    costly = costly or B.COST_ORDER[target.cost] > B.COST_ORDER[B.CHEAP]
                elif isinstance(target, Symbol):
                    costly = costly or function_cost(model, target)
        cache[id(sym)] = costly or ops >= 2
    return cache[id(sym)]
