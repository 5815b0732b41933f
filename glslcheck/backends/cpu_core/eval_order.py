"""Which values of an expression must be computed before a later part of it writes what they read.

Mesa's GLSL front end (ast_to_hir) turns an expression into instructions left to right, but
only some of its nodes become instructions where they are met; the others stay a tree of
reads that the instruction consuming them evaluates later:

* a call (user or built-in: Mesa inlines built-ins at once), a vector, matrix, struct or array
  constructor, a `?:`, an assignment and `++`/`--` are instructions: their operands are read
  where they stand, before any later part of the expression runs;
* a variable, a field, a swizzle, an index, an operator and a scalar constructor are read only
  by the instruction that consumes them, after every earlier-emitted instruction, including a
  later operand's call that writes the variable.

Measured on llvmpipe: in `vec4(f(seed), bump(seed), seed, 1.0)` with `bump(inout float s)`,
f sees the old seed and the plain `seed` the new one; `seed + bump(seed)` adds the new seed;
`id(seed) + bump(seed)` the old. A call's inout argument is read at the call, after its
later arguments' effects.

Both engines print an expression as one lazy text, emitting only side-effecting calls and
assignments as statements where they are met, so a lazy text is read later than Mesa reads
it. `EvalOrder.needs_temp(e)` names the nodes Mesa computes before a later part of the same
statement writes something they read: the engines put those in a temporary where they are
printed; `runs_first(call)` the calls that write a global an earlier part of their statement
reads, which the NumPy backend runs where they stand rather than inside the statement's text.
Everything else keeps the printed order (no code changes where no effect follows)."""

from __future__ import annotations

from typing import Any

from ...frontend import syntax as A
from ...semantics.model import Constructor, Symbol

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ...semantics.model import Model

EMPTY: frozenset[int] = frozenset()


class EvalOrder:
    """Per program: the variables each expression node reads and writes (a user call: its
    callee's globals too, Facts.global_effects), and the nodes that need a temporary."""

    def __init__(self, model: Model, facts: Any) -> None:  # (facts.Facts, which builds it)
        self.model = model
        self.facts = facts
        self._reads: dict[int, frozenset[int]] = {}
        self._writes: dict[int, frozenset[int]] = {}
        self._temps: set[int] | None = None
        self._first: set[int] = set()
        self._after: dict[tuple[int, int], frozenset[int]] = {}

    # -- what a node reads and writes ------------------------------------------------------
    def reads(self, e: Any) -> frozenset[int]:
        """Ids of the variables evaluating `e` reads."""
        return self._fold(e, self._reads, self._reads_here)

    def writes(self, e: Any) -> frozenset[int]:
        """Ids of the variables evaluating `e` writes (an out argument's copy back included)."""
        return self._fold(e, self._writes, self._writes_here)

    def _reads_here(self, n: Any) -> frozenset[int]:
        if isinstance(n, A.Identifier):
            sym = self.model.symbol_of(n)
            return frozenset((id(sym),)) if sym is not None else EMPTY
        if isinstance(n, A.Call):
            tgt = self.model.call_target(n)
            if isinstance(tgt, Symbol):
                return self.facts.global_effects(tgt)[0]
        return EMPTY

    def _writes_here(self, n: Any) -> frozenset[int]:
        own = frozenset(id(sym) for sym in self.facts.written_variables(n))
        if isinstance(n, A.Call):
            tgt = self.model.call_target(n)
            if isinstance(tgt, Symbol):
                own |= self.facts.global_effects(tgt)[1]
        return own

    @staticmethod
    def _fold(e: Any, memo: dict[int, frozenset[int]], here) -> frozenset[int]:
        known = memo.get(id(e))
        if known is not None:
            return known
        stack: list[tuple[Any, bool]] = [(e, False)]
        while stack:
            node, done = stack.pop()
            if id(node) in memo:
                continue
            kids = node.children()
            if done:
                acc = here(node)
                for k in kids:
                    acc = acc | memo[id(k)]
                memo[id(node)] = acc
            else:
                stack.append((node, True))
                stack.extend((k, False) for k in kids if id(k) not in memo)
        return memo[id(e)]

    # -- which nodes Mesa computes where they stand -----------------------------------------
    def instruction(self, e: Any) -> bool:
        """Mesa's front end makes `e` an instruction where it is met (the module docstring):
        a call, a constructor of more than a scalar, `?:`, an assignment, `++`/`--`."""
        if isinstance(e, A.Call):
            tgt = self.model.call_target(e)
            if isinstance(tgt, Constructor):
                return not tgt.type.is_scalar
            return tgt is not None
        if isinstance(e, (A.Ternary, A.Assignment)):
            return True
        return isinstance(e, (A.Unary, A.Postfix)) and e.op in ("++", "--")

    def needs_temp(self, e: Any) -> bool:
        """`e` is an instruction to Mesa that reads a variable a later part of its statement
        writes before the engines' lazy text of it would be read: compute it where it stands."""
        if self._temps is None:
            self._temps = set()
            for fn in self.facts.functions:
                self._mark(fn.node.body)
        return id(e) in self._temps

    def written_after(self, call: A.Call, i: int) -> frozenset[int]:
        """The variables the arguments after argument i of `call` write."""
        key = (id(call), i)
        known = self._after.get(key)
        if known is None:
            known = EMPTY
            for a in call.args[i + 1 :]:
                known = known | self.writes(a)
            self._after[key] = known
        return known

    def runs_first(self, call: Any) -> bool:
        """`call` writes a global that an earlier part of its statement reads: the engines must
        run it where it stands, not when the statement's text is evaluated (Mesa emits it
        there, and reads that global later, after it)."""
        self.needs_temp(call)  # (marks the program once)
        return id(call) in self._first

    def _mark(self, body: Any) -> None:
        """Walk a function body: a statement's expressions start with nothing written after
        and nothing read before them; inside an expression, a child is followed by its later
        siblings' writes and whatever follows its parent, and preceded by its earlier
        siblings' reads and whatever precedes its parent."""
        temps, first = self._temps, self._first
        assert temps is not None
        stack: list[tuple[Any, frozenset[int] | None, frozenset[int]]] = [(body, None, EMPTY)]
        while stack:
            node, after, before = stack.pop()
            if after and self.instruction(node) and self.reads(node) & after:
                temps.add(id(node))
            if before and isinstance(node, A.Call):
                tgt = self.model.call_target(node)
                if isinstance(tgt, Symbol) and self.facts.global_effects(tgt)[1] & before:
                    first.add(id(node))
            kids = node.children()
            if not isinstance(node, A.Expr):
                stack.extend((k, EMPTY if isinstance(k, A.Expr) else None, EMPTY) for k in kids)
                continue
            later = after if after is not None else EMPTY
            afters = []
            for k in reversed(kids):  # the last child is followed only by what follows node
                afters.append(later)
                later = later | self.writes(k)
            afters.reverse()
            earlier = before
            for k, k_after in zip(kids, afters):
                stack.append((k, k_after, earlier))
                earlier = earlier | self.reads(k)
