"""A local a kept branch leaves in a variable read after it: llvmpipe's register, masked.

Mesa 22.3 flattens a divergent ``if`` into selects (nir_opt_peephole_select, st_nir_opts' limit
8) when its arms cost at most 8 ALU instructions together (a negation, an ``abs``, a vector
constructor free, a derivative counted; loop_unroll.body_cost counts them here); a costlier one
(an ``atan`` costs 29, ``atan(y, x)`` 50) or one with a texture lookup, a loop or a jump stays a
branch. Out of SSA, NIR coalesces a value the branch leaves in a variable read after it (a
phi's source) with the phi's register, and llvmpipe stores registers under the exec mask: in
``float an = atan(r.y, r.x); col = vec3(dFdx(an), dFdy(an), an);`` the local ``an`` lives in
col.z's register, so a derivative of it in the branch reads, in a lane outside the branch, what
that register holds there:

- zero (llvmpipe's registers start at zero) when col's value before the branch is a constant
  (copied in on the else side, which llvmpipe runs after the then side) or undefined, when the
  else arm assigns col (its old value is then no phi's source), or when col is read in the
  branch after ``an`` is computed (the two values interfere: ``an`` takes the register, col's
  old value a copy);
- col's old value otherwise (coalesced into the same register).

In a flattened branch ``an`` is an SSA value computed in every lane, as both engines compute a
local declared in a branch. Measured on llvmpipe: tests/gl/test_llvmpipe_branch_registers.py.

:func:`merged_register` copies the plain case and declines the rest: a scalar local declared
with its value at the top level of an ``if``'s then arm and never written again; a later
statement of that arm, ``X = an`` or ``X = vecN(..., an, ...)``, the arm's only write of ``X``,
a local declared before the ``if`` (or the entry's out parameter) and read after it; an else
arm that leaves ``X`` alone or assigns it whole before reading it; no loop around the ``if``
(here or around a call of its function: NIR's unrolled copies and kept loops carry other
values in the register); a derivative in the arm reading ``an``. The same for ``an = e;`` at
the arm's top level, the branch's only write of a local declared before it that nothing reads
from the branch on but after that write. A texture lookup's implicit LOD is a derivative too
(measured: the lookup keeps even a cheap branch, and its LOD reads the register). Not copied:
a local of the else arm, a merge into another function's out parameter (llvmpipe's register
once NIR inlines the call), a branch in a loop."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ....frontend import syntax as A
from ....semantics.analysis import written_variable
from ....semantics.model import Symbol
from ..common import DERIVATIVES, IMPLICIT_LOD
from .loop_unroll import body_cost
from .queries import current_function

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..fold_protocols import FoldEngine

FLATTEN_LIMIT = 8  # st_nir_opts' nir_opt_peephole_select limit


@dataclass(frozen=True)
class MergedRegister:
    """Where the local's value lives: `branch`'s then arm gives it; a lane outside the arm holds
    component `component` of `target` (the variable it is merged into, read before that
    variable's write in the arm: its value from before the branch), or zero when `target` is
    None."""

    branch: A.If
    target: A.Identifier | None
    component: int


def merged_register(tr: FoldEngine, node: A.Declarator | A.Assignment) -> MergedRegister | None:
    """llvmpipe's register for the value a declarator, or an assignment ``an = e`` to a local
    declared before the branch, gives a local, when that value is coalesced with a phi's
    register of a kept branch (see the module docstring), else None."""
    fn = current_function(tr).sym
    if fn is None or id(fn) not in tr.facts.uses_derivs:
        return None
    facts = _facts(tr, fn)
    if facts is None or id(node) not in facts.enter:
        return None
    if isinstance(node, A.Declarator):
        v = tr.model.symbol_of(node)
        stmt = facts.parent.get(id(facts.parent.get(id(node))))
        ok = node.init is not None and v is not None and len(facts.writes_to(v)) == 1
    else:
        v, whole = written_variable(tr.model, node.target)
        stmt = facts.parent.get(id(node))
        ok = node.op == "=" and whole and isinstance(node.target, A.Identifier)
    if not ok or v is None or v.kind != "local" or not _scalar(v.type):
        return None
    arm = facts.parent.get(id(stmt))
    branch = facts.parent.get(id(arm))
    if not (isinstance(arm, A.Compound) and isinstance(branch, A.If) and branch.then is arm):
        return None
    found = _merge(tr, facts, arm, stmt, v)
    if found is None or facts.enclosing_loops(branch) or not _kept(tr, branch):
        return None
    if isinstance(node, A.Assignment) and not _dead_before_and_after(tr, facts, branch, node, v):
        return None
    if _called_in_a_loop(tr, fn):
        return None
    write, x, k = found
    if any(facts.contains(arm, w.node) and w.node is not write for w in facts.writes_to(x)):
        return None
    overwritten = _else_overwrites(tr, facts, branch, x)
    if overwritten is None:
        return None
    if not _live_after(tr, facts, branch, x, current_function(tr).is_entry):
        return None
    if not any(_derivative_of(tr, n, v) for n in arm.walk()):
        return None
    zero = (
        overwritten
        or _old_is_constant(tr, facts, branch, x, k)
        or _read_between(tr, facts, node, write, x)
    )
    return MergedRegister(branch, None if zero else write.target, k)


def arm_values(arm: A.Compound) -> list[A.Declarator | A.Assignment]:
    """The declarators and plain assignments at the top level of `arm`: what
    :func:`merged_register` is asked about."""
    out: list = []
    for st in arm.stmts:
        if isinstance(st, A.DeclarationStatement) and isinstance(st.decl, A.VariableDeclaration):
            out.extend(st.decl.declarators)
        elif isinstance(st, A.ExpressionStatement) and isinstance(st.expr, A.Assignment):
            out.append(st.expr)
    return out


def _dead_before_and_after(
    tr: FoldEngine, facts: Any, branch: A.If, write: A.Assignment, v: Symbol
) -> bool:
    """The local `v` declared before `branch`, assigned by `write` in it, has no other value
    anyone reads from the branch on: no read of it in the branch but after `write` in the then
    arm, no other write in the branch, no read after it (so its old value can be replaced
    before the branch)."""
    if _inside(facts, branch, v.node):
        return False
    if any(facts.contains(branch, w.node) and w.node is not write for w in facts.writes_to(v)):
        return False
    if branch.else_ is not None and _reads_symbol(tr, branch.else_, v):
        return False
    after = facts.exit[id(write)]
    for n in branch.walk():
        if isinstance(n, A.Identifier) and n is not write.target and tr.model.symbol_of(n) is v:
            if facts.enter[id(n)] < after:
                return False
    return not _live_after(tr, facts, branch, v, False)


def _scalar(t: Any) -> bool:
    return t is not None and t.is_scalar and t.base in ("float", "int", "uint")


def _facts(tr: FoldEngine, sym: Symbol) -> Any:
    from ....semantics.analysis.dataflow import FunctionFacts

    cache = tr.fold_state.fn_facts
    if id(sym) not in cache:
        cache[id(sym)] = FunctionFacts(sym.node, tr.model)
    facts = cache[id(sym)]
    return facts if facts.ok else None


def _merge(tr: FoldEngine, facts: Any, arm: A.Compound, decl: Any, v: Symbol) -> Any:
    """The first statement after `decl` in `arm` that assigns the local `v` whole, or as one
    argument of a vector constructor, to a variable declared before the branch: (the
    assignment, that variable, the component `v` becomes)."""
    start = next(i for i, s in enumerate(arm.stmts) if s is decl)
    for s in arm.stmts[start + 1 :]:
        e = s.expr if isinstance(s, A.ExpressionStatement) else None
        if not (isinstance(e, A.Assignment) and e.op == "=" and isinstance(e.target, A.Identifier)):
            continue
        x = tr.model.symbol_of(e.target)
        if x is None or x.kind not in ("local", "param") or _inside(facts, arm, x.node):
            continue
        k = _component_of(tr, e.value, v)
        if k is not None:
            return e, x, k
    return None


def _inside(facts: Any, outer: Any, node: Any) -> bool:
    """`node` (a declaration: a parameter's is not in the body) is inside `outer`."""
    return id(node) in facts.enter and facts.contains(outer, node)


def _component_of(tr: FoldEngine, value: Any, v: Symbol) -> int | None:
    """The component of `value` that is the local `v` itself: `v`, or one argument of a vector
    constructor of scalars and vectors (no other argument `v` itself)."""
    if isinstance(value, A.Identifier):
        return 0 if tr.model.symbol_of(value) is v else None
    if not (isinstance(value, A.Call) and value.constructor and len(value.args) > 1):
        return None
    t = tr.type_of(value)
    if t is None or not t.is_vector:
        return None
    at, found = 0, None
    for a in value.args:
        ta = tr.type_of(a)
        if ta is None or ta.is_matrix or ta.is_array:
            return None
        if isinstance(a, A.Identifier) and tr.model.symbol_of(a) is v:
            if found is not None:
                return None
            found = at
        at += ta.size
    return found


def _reads_symbol(tr: FoldEngine, node: Any, sym: Symbol) -> bool:
    return any(isinstance(n, A.Identifier) and tr.model.symbol_of(n) is sym for n in node.walk())


def _else_overwrites(tr: FoldEngine, facts: Any, branch: A.If, x: Symbol) -> bool | None:
    """Whether the else arm assigns `x` whole before reading it (then `x`'s old value is no
    phi's source: the register holds zero where the then arm did not write it, the else arm
    running after); False without an else arm or one that leaves `x` alone; None (declined)
    for other uses of `x` there."""
    arm = branch.else_
    if arm is None or not _reads_symbol(tr, arm, x):
        return False
    writes = [w for w in facts.writes_to(x) if facts.contains(arm, w.node)]
    if not writes or writes[0].kind != "=":
        return None
    first = writes[0].node
    if facts.region[id(first)] != facts.region[id(arm)] or _reads_symbol(tr, first.value, x):
        return None
    for n in arm.walk():
        if isinstance(n, A.Identifier) and n is not first.target and tr.model.symbol_of(n) is x:
            if facts.enter[id(n)] < facts.enter[id(first)]:
                return None
    return True


# What keeps a branch a branch in NIR, besides a texture lookup: in its arms, a jump (or a
# discard); in a function the arms call, a loop (or a discard). A call is followed this many
# deep; a longer chain counts as kept.
_IN_ARM = (A.Return, A.Break, A.Continue, A.Discard)
_IN_CALLEE = (A.For, A.While, A.DoWhile, A.Discard)
_CALL_DEPTH = 9


def _kept(tr: FoldEngine, branch: A.If) -> bool:
    """NIR keeps `branch` a branch: a loop, jump or texture lookup in it (here or in a callee),
    or more than FLATTEN_LIMIT instructions in its arms."""
    arms = [branch.then] + ([branch.else_] if branch.else_ is not None else [])
    if any(_holds(tr, arm, _IN_ARM, 0) for arm in arms):
        return True
    return sum(body_cost(tr, arm, None, 0) - _moves(tr, arm) for arm in arms) > FLATTEN_LIMIT


def _moves(tr: FoldEngine, arm: Any) -> int:
    """What body_cost counts for the negations and `abs` of `arm`, which nir_opt_peephole_select
    takes for moves (source modifiers) and does not count."""
    free = 0
    for n in arm.walk():
        negation = isinstance(n, A.Unary) and n.op == "-"
        if (negation or (isinstance(n, A.Call) and n.callee == "abs")) and (
            tr.model.const_value(n) is None
        ):
            t = tr.type_of(n)
            free += t.size if t is not None and t.is_vector else 1
    return free


def _holds(tr: FoldEngine, node: Any, constructs: tuple[type, ...], depth: int) -> bool:
    """`node` (an arm, or a callee's body `depth` calls deep) holds one of `constructs`, a
    texture lookup, or a call of a user function whose body holds a loop, a discard or a lookup."""
    if depth > _CALL_DEPTH:
        return True
    for n in node.walk():
        if isinstance(n, constructs):
            return True
        if isinstance(n, A.Call) and not n.constructor:
            target = tr.model.call_target(n)
            if isinstance(target, Symbol):
                if _holds(tr, target.node.body, _IN_CALLEE, depth + 1):
                    return True
            elif _lookup(n):
                return True
    return False


def _lookup(call: A.Call) -> bool:
    """A texture lookup or fetch: a tex instruction, which nir_opt_peephole_select never moves."""
    return call.callee.startswith(("texture", "texel"))


def _live_after(tr: FoldEngine, facts: Any, branch: A.If, x: Symbol, entry: bool) -> bool:
    """`x` is read after `branch` (an out parameter of the entry is: it is the output)."""
    if x.kind == "param":
        return entry and x.qualifier in ("out", "inout")
    end = facts.exit[id(branch)]
    for n in facts.nodes:
        if facts.enter[id(n)] <= end or not isinstance(n, A.Identifier):
            continue
        if tr.model.symbol_of(n) is not x:
            continue
        parent = facts.parent.get(id(n))
        overwritten = (
            isinstance(parent, A.Assignment)
            and parent.target is n
            and parent.op == "="
            and facts.region[id(parent)] == facts.region[id(branch)]
            and not _reads_symbol(tr, parent.value, x)
        )
        return not overwritten  # (overwritten whole on every path first: the value dies)
    return False


def _derivative_of(tr: FoldEngine, n: Any, v: Symbol) -> bool:
    """`n` is a call taking derivatives of an argument that reads `v`."""
    if not isinstance(n, A.Call) or n.constructor:
        return False
    target = tr.model.call_target(n)
    takes = (
        id(target) in tr.facts.uses_derivs
        if isinstance(target, Symbol)
        else n.callee in DERIVATIVES + IMPLICIT_LOD
    )
    return takes and any(_reads_symbol(tr, a, v) for a in n.args)


def _old_is_constant(tr: FoldEngine, facts: Any, branch: A.If, x: Symbol, k: int) -> bool:
    """Component `k` of `x` before `branch` is a constant NIR knows, or undefined (neither is
    coalesced into the register): the last write before the branch, on every path to it."""
    before = [w for w in facts.writes_to(x) if w.pos < facts.enter[id(branch)]]
    if not before:
        return True  # (undefined: an out parameter, a local declared without a value)
    last = before[-1]
    if last.kind == "decl":
        return True
    if last.kind not in ("=", "init") or not facts.dominates(last.node, branch):
        return False
    if tr.model.const_value(last.value) is not None:
        return True
    value = last.value
    if isinstance(value, A.Call) and value.constructor:
        if len(value.args) == 1:
            return tr.model.const_value(value.args[0]) is not None
        at = 0
        for a in value.args:
            ta = tr.type_of(a)
            if ta is None or ta.is_matrix or ta.is_array:
                return False
            if at <= k < at + ta.size:
                return ta.size == 1 and tr.model.const_value(a) is not None
            at += ta.size
    return False


def _read_between(tr: FoldEngine, facts: Any, node: Any, write: Any, x: Symbol) -> bool:
    """`x` is read after the local's value is computed (`node`) and before (or in) the write
    that merges it: its old value is live where the local's is, so the two take different
    registers."""
    lo, hi = facts.exit[id(node)], facts.enter[id(write.target)]
    for n in facts.nodes:
        pos = facts.enter[id(n)]
        if lo < pos and pos != hi and pos < facts.exit[id(write)]:
            if isinstance(n, A.Identifier) and tr.model.symbol_of(n) is x:
                return True
    return False


def _called_in_a_loop(tr: FoldEngine, fn: Symbol, depth: int = 0) -> bool:
    """A call of `fn`, or of a function calling it, is inside a loop."""
    if depth > 8:
        return True
    for f in tr.facts.functions:
        for n in f.node.body.walk():
            if isinstance(n, A.Call) and tr.model.call_target(n) is fn:
                facts = _facts(tr, f)
                if facts is None or facts.enclosing_loops(n) or _called_in_a_loop(tr, f, depth + 1):
                    return True
    return False
