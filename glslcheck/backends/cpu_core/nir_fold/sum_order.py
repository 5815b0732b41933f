"""The float32 constant of each value of a chain of additions of constants, in Mesa's order.

A chain is a value advanced by constants again and again (``seed += 0.1``; repeated_sums.py
finds them, through inlined calls and unrolled loops). nir_opt_algebraic's ``#a + (b + #c) ->
(a + c) + b`` merges the constants into one, but in an order the source does not show, so it
is simulated here on a small copy of what NIR holds (Mesa 22.3, src/compiler/nir/nir_search.c
nir_algebraic_impl, and the optimisation loop that runs it):

- one pass visits the additions last first (its worklist pops the last instruction first); a
  rewrite builds ``(a + c) + b`` whose inner sum of two constants is no constant to the rules
  until the constant-folding pass after it, and a rewritten value's users are visited again
  at the end of the pass;
- ``x - #c`` is ``x + fneg(#c)``, and the negation is a constant only after that folding;
- passes repeat until nothing changes, and a loop of a constant count is unrolled after the
  first one: its body merged once relative to the loop's phi, then the copies chained.

The result is ``base + K`` for every value (the rule leaves no constant inside); K is read from
the simulation. Measured on llvmpipe: tests/gl/test_llvmpipe_repeated_sums.py (straight lines
of additions and subtractions, through calls, loops with constants before, inside and after
them, each bit for bit on 14,400 values, where left-to-right or right-to-left folding alone
differ)."""

from __future__ import annotations

from typing import Any

import numpy as np

_F = np.float32


class Step:
    """One addition: the value of op `prev` (-1: the chain's base; in a loop body, -1 is the
    value at the top of the iteration) plus the constant `k`, written as a subtraction when
    `neg` (k is then already negated)."""

    __slots__ = ("prev", "k", "neg")

    def __init__(self, prev: int, k: Any, neg: bool = False) -> None:  # k: one, or a vector's
        self.prev, self.k, self.neg = prev, _F(k), neg


class Loop:
    """A loop NIR unrolls, `count` copies of `body` (Steps and Loops indexed within the body),
    entered with the value of op `prev`; the value after the loop is its last op's, or, when
    the loop can be left early (`breaks`), a phi (a later op that reads it starts afresh)."""

    __slots__ = ("prev", "count", "body", "breaks")

    def __init__(self, prev: int, count: int, body: list, breaks: bool = False) -> None:
        self.prev, self.count, self.body, self.breaks = prev, count, body, breaks


class _Const:
    __slots__ = ("v",)

    def __init__(self, v: np.float32) -> None:
        self.v = v


class _Neg:  # fneg of a constant: an instruction until constant folding
    __slots__ = ("v",)

    def __init__(self, v: np.float32) -> None:
        self.v = v


class _Add:
    __slots__ = ("a", "b", "region")

    def __init__(self, a: object, b: object, region: object) -> None:
        self.a, self.b, self.region = a, b, region


class _Opaque:  # the base, a loop's phi or its exit value
    __slots__ = ()


class _Program:
    def __init__(self) -> None:
        self.instrs: list[_Add] = []
        self.outs: list[object] = []

    def users(self, v: object) -> list[_Add]:
        return [i for i in self.instrs if i.a is v or i.b is v]

    def replace(self, old: object, new: object) -> None:
        for i in self.instrs:
            if i.a is old:
                i.a = new
            if i.b is old:
                i.b = new
        self.outs = [new if o is old else o for o in self.outs]

    def live(self) -> set[int]:
        out = {id(o) for o in self.outs}
        for i in self.instrs:
            out.add(id(i.a))
            out.add(id(i.b))
        return out


def _match(p: _Program, x: _Add, present: set[int]) -> tuple[object, object, object] | None:
    """``#a + (b + #c)`` with b no constant, either operand order at both levels."""
    for a, y in ((x.a, x.b), (x.b, x.a)):
        if isinstance(a, _Const) and isinstance(y, _Add) and id(y) in present:
            for b, c in ((y.a, y.b), (y.b, y.a)):
                if isinstance(c, _Const) and not isinstance(b, (_Const, _Neg)):
                    return a, b, c
    return None


def _algebraic(p: _Program) -> bool:
    work = list(reversed(p.instrs))  # (popped last instruction first)
    done: set[int] = set()
    progress = False
    while work:
        x = work.pop(0)
        present = {id(i) for i in p.instrs}
        if id(x) not in present or id(x) in done:
            continue
        m = _match(p, x, present)
        if m is None:
            continue
        a, b, c = m
        k = p.instrs.index(x)
        inner = _Add(a, c, x.region)
        outer = _Add(inner, b, x.region)
        p.instrs[k:k] = [inner, outer]
        p.replace(x, outer)
        p.instrs.remove(x)
        done.add(id(x))
        work += p.users(outer)
        progress = True
    return progress


def _fold(p: _Program) -> bool:
    progress = False
    for x in list(p.instrs):
        for side in ("a", "b"):
            v = getattr(x, side)
            if isinstance(v, _Neg):
                setattr(x, side, _Const(v.v))
                progress = True
        if isinstance(x.a, _Const) and isinstance(x.b, _Const):
            p.replace(x, _Const(_F(x.a.v + x.b.v)))
            p.instrs.remove(x)
            progress = True
    return progress


def _dce(p: _Program) -> bool:
    progress = False
    while True:
        live = p.live()
        dead = [x for x in p.instrs if id(x) not in live]
        if not dead:
            return progress
        for x in dead:
            p.instrs.remove(x)
        progress = True


def _one_pass(p: _Program) -> bool:
    progress = _algebraic(p)
    progress |= _fold(p)
    return _dce(p) or progress


def chain_constants(ops: list) -> list | None:
    """K for each op of the chain (`ops`: Steps and Loops in program order), a float32 such
    that the op's value is ``base + K``; a Loop's entry is the list of its copies' entries,
    each a list for its body's ops. None when some value is not of that form (a constant
    base, or a loop's exit phi read later: the caller keeps the written order then)."""
    p = _Program()
    base = _Opaque()
    outs: list = []
    loops: list = []

    def build(items: list, start: object, region: object) -> list:
        vals: list = []
        for op in items:
            src = start if op.prev < 0 else vals[op.prev]
            if isinstance(op, Step):
                k = _Neg(op.k) if op.neg else _Const(op.k)
                x = _Add(src, k, region)
                p.instrs.append(x)
                p.outs.append(x)
                vals.append(x)
            else:
                phi, exit_ = _Opaque(), _Opaque()
                body = build(op.body, phi, op)
                loops.append((op, src, phi, exit_, body))
                vals.append(exit_)
        return vals

    outs = build(ops, base, None)
    positions = {id(o): i for i, o in enumerate(p.outs)}
    _one_pass(p)

    resolved: dict[int, object] = {}  # a loop's exit value -> its last copy's

    def current(v: object) -> object:
        v = resolved.get(id(v), v)
        return p.outs[positions[id(v)]] if id(v) in positions else v

    copies_of: dict[int, list] = {}
    for op, src, phi, exit_, body in loops:
        template = [x for x in p.instrs if x.region is op]
        at = p.instrs.index(template[0]) if template else len(p.instrs)
        for x in template:
            p.instrs.remove(x)
        carried, copies, new = current(src), [], []
        for _ in range(op.count):
            mapping: dict[int, object] = {id(phi): carried}
            for x in template:
                y = _Add(mapping.get(id(x.a), x.a), mapping.get(id(x.b), x.b), None)
                mapping[id(x)] = y
                new.append(y)
            copy = [mapping.get(id(current(v)), current(v)) for v in body]
            copies.append(copy)
            if copy:
                carried = copy[-1]
        p.instrs[at:at] = new
        for c in copies:
            for v in c:
                positions.setdefault(id(v), len(p.outs))
                p.outs.append(v)
        copies_of[id(op)] = copies
        if not op.breaks:
            p.replace(exit_, carried)
            resolved[id(exit_)] = carried
    while _one_pass(p):
        pass

    def constant(v: object) -> np.float32 | None:
        if v is base:
            return _F(0.0)
        if isinstance(v, _Add):
            for k, b in ((v.a, v.b), (v.b, v.a)):
                if isinstance(k, _Const) and b is base:
                    return k.v
        return None

    def read(items: list, vals: list) -> list | None:
        out: list = []
        for op, v in zip(items, vals):
            if isinstance(op, Step):
                k = constant(current(v))
                if k is None:
                    return None
                out.append(k)
            else:
                copies = []
                for c in copies_of[id(op)]:
                    got = read(op.body, c)
                    if got is None:
                        return None
                    copies.append(got)
                out.append(copies)
        return out

    return read(ops, outs)
