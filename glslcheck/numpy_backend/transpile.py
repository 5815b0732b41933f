"""The GLSL-to-Python code generator: a checked Shadertoy program becomes a readable NumPy module.

This module owns the translation of the checked AST (types and symbols come from
`glslcheck.check`, never re-derived here) into Python source that calls the runtime
(`glslcheck.numpy_backend.runtime`, lane representation in its docstring). The printer is many
tiny `_print_<Node>` / `_stmt_<Node>` methods; built-ins come from the built-in table; an
unsupported construct (texture lookups, `gl_FragDepth`, ...) is a `GlslError` at its location.

The generated module
====================

* one `def` per GLSL function reachable from `mainImage` (callees first), 4-space indents, a
  `# line N: <GLSL text>` comment before the code of each statement; `shade(S)` is Shadertoy's
  footer (`mainImage(color, fragCoord)`, alpha forced to 1) and `init_globals(S)` runs the
  global initializers once per render;
* every GLSL name is mangled: locals and parameters `v_<name>`, functions `f_<name>`, globals
  `S.g_<name>`, uniforms `S.u_<name>`, struct types `s_<name>`, struct members `m_<name>`
  (the checker's program-wide unique names keep shadowed names apart); generated temporaries
  start with `_`, module constants with `C_`/`Z_`. No GLSL text reaches the code except as
  sanitised comments, so no name can collide with a Python keyword, built-in or the runtime;
* module-level names it uses: `rt` (a `Runtime`), `X` (the lane helpers of `program.py`),
  and its own constants. The host executes it with `__builtins__` empty.

Execution model
===============

All pixels of a tile are lanes. A mask (`_m..`) is `None` ("every lane of the current lane
set") or a bool array; writes under a mask keep the old value elsewhere (`rt.assign`).

* `if`/`?:`/`&&`/`||` with a lane-dependent condition run each side under its mask, and only
  when some lane takes it. A uniform condition (the same in every lane: it depends only on
  constants and uniforms, see `Uniformity`) is a plain Python `if`.
* loops keep `_live` (lanes still looping): the condition, `break` and `return` remove lanes;
  `continue` sets `_cnt` for the rest of the iteration. The Python loop ends when no lane is
  live. A `for` loop's induction variable (declared in the init, changed only by the step) is
  stepped unmasked, so a loop such as `for (int i = 0; i < 64; i++)` stays uniform even when
  lanes `break` at different times. Each loop execution stops after `LOOP_CAP` iterations with
  a GlslError naming the loop's line.
* `switch`: lanes fall through from their matching label (`_fall`) until a `break`.
* `return` inside control flow accumulates the value in `_rv` and the lanes in `_ret`; after a
  statement that can disable lanes the current mask is refreshed and the rest of the block is
  nested under `if X.live(mask):`, so code no lane reaches costs nothing.
* `discard` marks `S.discard` and returns from every function on the call stack; discarded
  pixels keep the framebuffer's clear value (0, 0, 0, 0), as the GL backend does.
* out/inout arguments: arguments are evaluated left to right once (index expressions of an
  l-value included); the callee returns `(value, out1, out2, ...)` and the caller copies the
  outs back under its own mask, left to right. `out` parameters start at zero.
* `pow` with a constant exponent of 1.0, 2.0, 4.0 or +0.0 (per vector component) or a constant
  base of ones is emitted as Mesa compiles it (`rt.pow_const`, `rt.pow_one`): products instead
  of `exp2(y*log2(x))`, so `pow(-0.5, 2.0)` is 0.25 as on llvmpipe, not NaN.
* constant expressions inside functions (`vec3(0.6)`, `-1.0`, constant arrays and structs) are
  module constants `C_x<n>`, computed once when the module is executed; float arithmetic and
  comparisons print as NumPy operators (`(a * b)`: the runtime's ufuncs without a call).
* a function ending in `if (c) return K; return e;` (K constant, no side effects) returns
  `rt.select(c, K, e)` without a return mask: `e` runs on every lane, unless c holds in every
  lane (a tile of pixels that all miss a sphere), which returns K without computing `e`.
* compaction: when fewer than half of the lanes of a varying branch or loop iteration are
  active (and there are enough lanes to matter), the values the region uses are gathered to the
  active lanes (`X.gather` / `X.push`), the region runs on the short arrays with no mask, and the
  values are scattered back afterwards (globals and fragment coordinates are gathered on first
  read). Regions that use derivatives are never compacted.
"""

from __future__ import annotations

import re
import sys
from dataclasses import dataclass, field
from typing import Any

from .. import ast as A
from .. import builtins as B
from .. import types as T
from ..diagnostics import Diagnostic, GlslError, Location
from . import nir_fold

RULE = "numpy-transpile"
LOOP_CAP = 100_000  # iterations per execution of one loop before the render stops with an error
# Python's own limits, which deep GLSL would reach through the generated code (CPython 3.11:
# 100 levels of indentation, 200 nested brackets, 20 nested loops in one function; see "Python's
# limits" below). Normal shaders stay far below these thresholds, so their code is unchanged.
SPILL_HEIGHT = 24  # an expression this many syntax levels high is computed into a temporary
OUTLINE_INDENT = 48  # a statement starting this deep goes to a helper function
OUTLINE_EXPR_INDENT = 64  # an expression (nested `&&`, ternaries with effects) from this deep too
OUTLINE_LOOPS = 16  # and a statement inside this many Python loops of one function
# Per-lane state above which the module's SHADER_META carries "lane_state" (scalars per lane,
# where the largest variable is declared) so the renderer sizes tiles to its memory budget;
# below it the renderer assumes this many (`program.lane_bytes`).
SMALL_STATE = 1024
_IDENT = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
_LOCAL_REF = re.compile(r"(?<![.\w\"'])(v_\w+|_[a-z]+\d*)\b")
_ASSIGNED = re.compile(r"^(?!(?:if|elif|while|return) )([^=]*?)\s*[-+*/]?=(?!=)")  # a stripped statement's targets
_RUNTIME_NAMES = {"min": "min_", "max": "max_", "not": "not_vec"}
_FLOAT_OPERATORS = ("+", "-", "*", "/", "<", "<=", ">", ">=")  # printed as Python operators on floats
_DERIVATIVES = ("dFdx", "dFdy", "fwidth")
# The lookups on a sampler2D that textures.TextureFunctions evaluates.
_TEXTURE_FUNCTIONS = ("texture", "textureLod", "textureGrad", "textureProj", "textureOffset", "texelFetch",
                      "texelFetchOffset", "textureSize", "textureLodOffset", "textureGradOffset",
                      "textureProjOffset", "textureProjLod", "textureProjLodOffset", "textureProjGrad",
                      "textureProjGradOffset")
# Lookups whose mipmap level comes from derivatives (2x2 quads): their regions are never compacted.
_IMPLICIT_LOD = ("texture", "textureProj", "textureOffset", "textureProjOffset")
_BIN_METHODS = {
    "+": "add", "-": "sub", "*": "mul", "/": "div", "<": "lt", "<=": "le", ">": "gt", ">=": "ge",
    "<<": "shl", ">>": "shr", "&": "bit_and", "|": "bit_or", "^": "bit_xor",
    "&&": "and_", "||": "or_", "^^": "xor_",
}


_STRING = re.compile(r'"[^"]*"')
_NAME = re.compile(r"(?<![.\w])([A-Za-z_]\w*)(\s*=(?!=))?")


def _is_constant_text(text: str) -> bool:
    """True when printed code refers to nothing but `rt` and module constants (no lanes, no S)."""
    for name, kwarg in _NAME.findall(_STRING.sub('""', text)):
        if not (kwarg or name == "rt" or name.startswith(("C_", "Z_"))):
            return False
    return True


def _components(v: Any) -> list[Any]:
    """The scalars of a folded constant (a number or nested tuples), in order."""
    if isinstance(v, (tuple, list)):
        return [x for item in v for x in _components(item)]
    return [v]


def _error(message: str, node: Any, help: str | None = None) -> GlslError:
    loc = node if isinstance(node, Location) else getattr(node, "loc", None)
    return GlslError(Diagnostic(message, loc, rule=RULE, help=help))


def _printable(text: str, limit: int = 100) -> str:
    """Text safe inside a Python comment or docstring: printable ASCII, no quotes or backslashes."""
    out = "".join(c if (" " <= c <= "~" and c not in "\"\\") else "?" for c in text.strip())
    return out if len(out) <= limit else out[: limit - 3] + "..."


def _ident(name: str, node: Any) -> str:
    if not _IDENT.match(name or ""):
        raise _error(f"the name {name!r} cannot be transpiled", node)
    return name


# ---------------------------------------------------------------------------------------------
# Model access (the checker's API) -- a small adapter while glslcheck.check settles.
# ---------------------------------------------------------------------------------------------


def check_program(parse_result: Any) -> Any:
    """The semantic model of a parsed program; GlslError when it does not check.

    ADAPTER: uses `glslcheck.check.check` when the package exports it, else runs the checker
    class directly and raises on its errors (the same contract)."""
    try:
        from ..check import check  # type: ignore[attr-defined]
    except ImportError:
        check = None
    if check is not None:
        return check(parse_result)
    from ..check.checker import Checker

    sources = list(getattr(parse_result, "sources", []) or [])
    tab = sources[-1].tab if sources else "Image"
    model = Checker(parse_result, tab).run()
    if model.errors:
        raise GlslError(model.errors)
    return model


def _is_symbol(target: Any) -> bool:
    return hasattr(target, "kind") and getattr(target, "kind", None) == "function"


def _is_constructor(target: Any) -> bool:
    return isinstance(target, tuple) and len(target) == 2 and target[0] == "constructor"


# ---------------------------------------------------------------------------------------------
# Static facts about statements: which "events" (break, continue, return, discard) escape them.
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Events:
    brk: bool = False  # a break of the enclosing loop/switch
    cont: bool = False  # a continue of the enclosing loop
    ret: bool = False  # a return, a discard, or a call that may discard

    def __or__(self, o: "Events") -> "Events":
        return Events(self.brk or o.brk, self.cont or o.cont, self.ret or o.ret)

    @property
    def any(self) -> bool:
        return self.brk or self.cont or self.ret


NO_EVENTS = Events()


class Facts:
    """Program-wide facts the code generator needs: discarding and derivative-using functions,
    written globals, functions whose calls are lane-uniform for uniform arguments."""

    def __init__(self, model: Any, functions: list[Any]) -> None:
        self.model = model
        self.functions = functions  # callees first
        self.may_discard: set[int] = set()
        self.uses_derivs: set[int] = set()
        self.written_globals: set[int] = set()
        self.reads_lane_state: set[int] = set()  # reads gl_FragCoord or a written global
        self._calls_cache: dict[int, list[Any]] = {}
        self.events: dict[int, Events] = {}  # node id -> events_of(node)
        self._discarding: dict[int, bool] = {}  # node id -> a discarding call in its subtree
        self._write_counts: dict[int, int] | None = None
        for fn in functions:
            body = fn.node.body
            for node in body.walk():
                if isinstance(node, A.Discard):
                    self.may_discard.add(id(fn))
                elif isinstance(node, A.Call):
                    tgt = model.call_target(node)
                    if _is_symbol(tgt):
                        if id(tgt) in self.may_discard:
                            self.may_discard.add(id(fn))
                        if id(tgt) in self.uses_derivs:
                            self.uses_derivs.add(id(fn))
                    elif getattr(tgt, "name", None) in _DERIVATIVES + _IMPLICIT_LOD:
                        self.uses_derivs.add(id(fn))
                for target in self._written_targets(node):
                    sym = model.symbol_of(target)
                    if sym is not None and sym.kind == "global":
                        self.written_globals.add(id(sym))
        for fn in functions:
            for node in fn.node.body.walk():
                if isinstance(node, A.Identifier):
                    sym = model.symbol_of(node)
                    if sym is not None and (
                        (sym.kind == "global" and id(sym) in self.written_globals)
                        or (sym.kind == "builtin-var" and sym.name == "gl_FragCoord")
                    ):
                        self.reads_lane_state.add(id(fn))
                elif isinstance(node, A.Call):
                    tgt = model.call_target(node)
                    if _is_symbol(tgt) and id(tgt) in self.reads_lane_state:
                        self.reads_lane_state.add(id(fn))

    def write_counts(self) -> dict[int, int]:
        """Symbol id -> how many places in the program's functions write it (assignments,
        ++/--, out and inout arguments), counted in one walk."""
        if self._write_counts is None:
            counts: dict[int, int] = {}
            for fn in self.functions:
                for node in fn.node.body.walk():
                    for target in self._written_targets(node):
                        sym = self.model.symbol_of(target)
                        if sym is not None:
                            counts[id(sym)] = counts.get(id(sym), 0) + 1
            self._write_counts = counts
        return self._write_counts

    def discarding_call(self, n: Any) -> bool:
        """True when n is a call of a user function that may discard."""
        if not isinstance(n, A.Call):
            return False
        tgt = self.model.call_target(n)
        return _is_symbol(tgt) and id(tgt) in self.may_discard

    def has_discarding_call(self, node: Any) -> bool:
        return _fold(node, self._discarding, lambda n, kids: any(kids) or self.discarding_call(n))

    def _written_targets(self, node: Any) -> list[Any]:
        """The base identifiers a node writes (assignment, ++/--, out arguments)."""
        out: list[Any] = []
        if isinstance(node, A.Assignment):
            out.append(lvalue_base(node.target))
        elif isinstance(node, (A.Unary, A.Postfix)) and node.op in ("++", "--"):
            out.append(lvalue_base(node.operand))
        elif isinstance(node, A.Call):
            tgt = self.model.call_target(node)
            for i, d in enumerate(out_directions(tgt)):
                if d in ("out", "inout") and i < len(node.args):
                    out.append(lvalue_base(node.args[i]))
        return [o for o in out if o is not None]

    def closed(self, fn: Any) -> bool:
        """A call of `fn` with uniform arguments gives a uniform result (no lane state read or
        written, no discard)."""
        return id(fn) not in self.reads_lane_state and id(fn) not in self.may_discard and not self.writes_globals(fn)

    def writes_globals(self, fn: Any) -> bool:
        key = id(fn)
        if key not in self._calls_cache:
            res = False
            for node in fn.node.body.walk():
                for target in self._written_targets(node):
                    sym = self.model.symbol_of(target)
                    if sym is not None and sym.kind == "global":
                        res = True
                if isinstance(node, A.Call):
                    tgt = self.model.call_target(node)
                    if _is_symbol(tgt) and tgt is not fn and self.writes_globals(tgt):
                        res = True
            self._calls_cache[key] = [res]
        return self._calls_cache[key][0]


def lvalue_base(e: Any) -> Any:
    while isinstance(e, (A.Field, A.Index)):
        e = e.base
    return e if isinstance(e, A.Identifier) else None


def out_directions(target: Any) -> list[str]:
    if _is_symbol(target):
        return [d for _, _, d in target.params]
    quals = getattr(target, "qualifiers", None)
    if quals is not None:
        return list(quals)
    return []


def _is_simple(e: Any) -> bool:
    """A value read without computing anything per lane: a literal, a variable, or a field or
    component of one (`!` of one too)."""
    while isinstance(e, (A.Field, A.Unary)) and (not isinstance(e, A.Unary) or e.op == "!"):
        e = e.operand if isinstance(e, A.Unary) else e.base
    return isinstance(e, (A.Identifier, A.IntLiteral, A.FloatLiteral, A.BoolLiteral))


def events_of(stmt: Any, facts: Facts, model: Any, in_loop_or_switch: bool = False) -> Events:
    """Events that escape `stmt` (a break/continue inside a nested loop does not escape it).
    Memoized per node (`facts.events`): asked of every statement at every nesting level."""

    def own(n: Any, kids: list[Events]) -> Events:
        if isinstance(n, A.Break):
            return Events(brk=True)
        if isinstance(n, A.Continue):
            return Events(cont=True)
        ev = Events(ret=True) if isinstance(n, (A.Return, A.Discard)) or facts.discarding_call(n) else NO_EVENTS
        for k in kids:
            ev = ev | k
        if isinstance(n, (A.For, A.While, A.DoWhile)):
            return Events(ret=ev.ret)
        if isinstance(n, A.Switch):
            return Events(cont=ev.cont, ret=ev.ret)
        return ev

    return _fold(stmt, facts.events, own)


# ---------------------------------------------------------------------------------------------
# Uniformity: which values are the same in every lane.
# ---------------------------------------------------------------------------------------------


class Uniformity:
    """A sound, simple uniformity analysis of one function, matching the code generator.

    A value is uniform when it depends only on literals, uniforms, constant or never-written
    globals and uniform variables. A variable is uniform when every write to it stores a uniform
    value under a uniform mask: declarations are unmasked (a lane that is inactive at a
    declaration never reads the variable in its scope; switch bodies excepted), the entry
    function starts with every lane active, other functions start with an unknown mask, and a
    mask stays uniform while every condition and every break/continue/return that shaped it was
    uniform. Parameters (except `out`) are varying. Iterated to a fixed point."""

    def __init__(self, tr: "Transpiler", fn: Any, is_entry: bool) -> None:
        self.tr = tr
        self.model = tr.model
        self.fn = fn
        self.is_entry = is_entry
        self.varying: set[int] = set()
        self.mu = is_entry
        self.switch_depth = 0
        self.loop_flags: list[list[bool]] = []  # per enclosing loop/switch: [varying break]
        self.fn_varying_return = False
        self.cache: dict[int, bool] = {}
        for p in fn.node.proto.params:
            sym = self.model.symbol_of(p)
            if sym is not None and p.direction != "out":
                self.varying.add(id(sym))
        while True:
            before = set(self.varying)
            self.mu = is_entry
            self.fn_varying_return = False
            self.block(fn.node.body.stmts, is_entry)
            if self.varying == before:
                break

    # -- expressions ---------------------------------------------------------------------------
    def is_uniform(self, e: Any) -> bool:
        """The analysis' verdict on an expression node (False for nodes it never saw)."""
        return self.cache.get(id(e), False)

    def uniform(self, e: Any) -> bool:
        if e is None:
            return True
        res = self._uniform(e)
        self.cache[id(e)] = res
        return res

    def _uniform(self, e: Any) -> bool:
        m = self.model
        if isinstance(e, (A.IntLiteral, A.FloatLiteral, A.BoolLiteral)):
            return True
        if isinstance(e, A.Identifier):
            sym = m.symbol_of(e)
            if sym is None:
                return False
            if sym.kind == "uniform":
                return True
            if sym.kind == "builtin-var":
                return sym.name != "gl_FragCoord"
            if sym.kind == "global":
                return id(sym) not in self.tr.facts.written_globals
            return id(sym) not in self.varying
        if isinstance(e, A.Assignment):
            ok = self.uniform(e.value) and (e.op == "=" or self.uniform(e.target))
            self.write(e.target, ok and self.mu and self.index_uniform(e.target))
            return ok and self.mu
        if isinstance(e, (A.Unary, A.Postfix)) and e.op in ("++", "--"):
            ok = self.uniform(e.operand) and self.mu
            self.write(e.operand, ok)
            return ok
        if isinstance(e, A.Call):
            tgt = m.call_target(e)
            args_u = [self.uniform(a) for a in e.args]
            if _is_symbol(tgt):
                res = all(args_u) and self.tr.facts.closed(tgt)
                if id(tgt) in self.tr.facts.may_discard and not self.mu:
                    self.fn_varying_return = True
            else:
                res = all(args_u)
            for i, d in enumerate(out_directions(tgt)):
                if d in ("out", "inout") and i < len(e.args):
                    self.write(e.args[i], res and self.mu)
            return res
        if isinstance(e, A.Ternary):
            c = self.uniform(e.cond)
            saved = self.mu
            self.mu = saved and c
            a, b = self.uniform(e.then), self.uniform(e.else_)
            self.mu = saved
            return c and a and b
        if isinstance(e, A.Binary) and e.op in ("&&", "||"):
            left = self.uniform(e.left)
            saved = self.mu
            self.mu = saved and left
            right = self.uniform(e.right)
            self.mu = saved
            return left and right
        ok = True
        for c in e.children():
            if isinstance(c, A.Expr):
                ok = self.uniform(c) and ok
        return ok

    def index_uniform(self, target: Any) -> bool:
        ok = True
        while isinstance(target, (A.Field, A.Index)):
            if isinstance(target, A.Index):
                ok = self.uniform(target.index) and ok
            target = target.base
        return ok

    def write(self, target: Any, uniform: bool) -> None:
        base = lvalue_base(target)
        if base is None or uniform:
            return
        sym = self.model.symbol_of(base)
        if sym is not None and sym.kind in ("local", "param"):
            self.varying.add(id(sym))

    # -- statements ----------------------------------------------------------------------------
    def block(self, stmts: list[Any], mu: bool) -> bool:
        for s in stmts:
            mu = self.stmt(s, mu)
            if self._discarding_call(s):
                mu = False  # S.discard is lane-dependent in general
        return mu

    def _discarding_call(self, s: Any) -> bool:
        if self.tr.facts.has_discarding_call(s):
            self.fn_varying_return = True
            return True
        return False

    def stmt(self, s: Any, mu: bool) -> bool:
        self.mu = mu
        if s is None:
            return mu
        if isinstance(s, A.Compound):
            return self.block(s.stmts, mu)
        if isinstance(s, A.DeclarationStatement):
            d = s.decl
            if isinstance(d, A.VariableDeclaration):
                for dec in d.declarators:
                    u = self.uniform(dec.init) if dec.init is not None else True
                    if self.switch_depth:
                        u = u and mu
                    sym = self.model.symbol_of(dec)
                    if sym is not None and not u:
                        self.varying.add(id(sym))
            return mu
        if isinstance(s, A.ExpressionStatement):
            self.uniform(s.expr)
            return mu
        if isinstance(s, A.If):
            c = self.uniform(s.cond)
            inner = mu and c
            t = self.stmt(s.then, inner)
            e = self.stmt(s.else_, inner) if s.else_ is not None else inner
            ev_t = events_of(s.then, self.tr.facts, self.model)
            ev_e = events_of(s.else_, self.tr.facts, self.model) if s.else_ is not None else NO_EVENTS
            self.mu = mu
            return mu and (t or not ev_t.any) and (e or not ev_e.any)
        if isinstance(s, (A.For, A.While, A.DoWhile)):
            return self.loop(s, mu)
        if isinstance(s, A.Switch):
            c = self.uniform(s.expr)
            self.loop_flags.append([False])
            self.switch_depth += 1
            inner = mu and c
            cur = inner
            for st in s.body:
                if isinstance(st, A.Case):
                    cur = inner and not self.loop_flags[-1][0]
                    continue
                cur = self.stmt(st, cur)
            self.switch_depth -= 1
            self.loop_flags.pop()
            ev = events_of(s, self.tr.facts, self.model)
            return mu and (not ev.ret or not self.fn_varying_return)
        if isinstance(s, A.Break):
            if not mu and self.loop_flags:
                self.loop_flags[-1][0] = True
            return mu
        if isinstance(s, A.Continue):
            return mu
        if isinstance(s, (A.Return, A.Discard)):
            if isinstance(s, A.Return) and s.value is not None:
                self.uniform(s.value)
            if not mu:
                self.fn_varying_return = True
                for f in self.loop_flags:
                    f[0] = True
            return mu
        return mu

    def loop(self, s: Any, mu: bool) -> bool:
        ind = induction_variable(s, self.model, self.tr.facts)
        if isinstance(s, A.For) and s.init is not None:
            self.stmt(s.init, mu)
        cond = s.cond
        if isinstance(cond, A.ConditionDeclaration):
            u = self.uniform(cond.init)
            sym = self.model.symbol_of(cond)
            if sym is not None and not u:
                self.varying.add(id(sym))
        self.loop_flags.append([False])
        body_mu = mu
        for _ in range(3):
            self.loop_flags[-1][0] = False
            self.mu = body_mu
            c = True
            if cond is not None and not isinstance(s, A.DoWhile):
                c = self.uniform(cond if not isinstance(cond, A.ConditionDeclaration) else cond.init)
            inner = body_mu and c
            self.stmt(s.body, inner)
            if isinstance(s, A.DoWhile):
                self.mu = inner
                c = self.uniform(s.cond)
            if isinstance(s, A.For) and s.step is not None:
                self.mu = True if ind is not None else inner and not self.loop_flags[-1][0]
                self.uniform(s.step)
            new_mu = mu and c and not self.loop_flags[-1][0]
            if new_mu == body_mu:
                break
            body_mu = new_mu
        self.loop_flags.pop()
        ev = events_of(s, self.tr.facts, self.model)
        self.mu = mu
        return mu and (not ev.ret or not self.fn_varying_return)


def induction_variable(s: Any, model: Any, facts: Facts | None = None) -> Any:
    """The Symbol of a for loop's induction variable: declared in the init, written only by the
    step (`i++`, `++i`, `i--`, `i += e`, `i -= e`, `i = i + e`); else None. With `facts`, the
    body is not walked: the variable is scoped to the loop, so it is written nowhere but the
    step when the program writes it once in all (`Facts.write_counts`)."""
    if not isinstance(s, A.For) or not isinstance(s.init, A.DeclarationStatement):
        return None
    decl = s.init.decl
    if not isinstance(decl, A.VariableDeclaration) or len(decl.declarators) != 1:
        return None
    sym = model.symbol_of(decl.declarators[0])
    if sym is None or not (sym.type.is_scalar if hasattr(sym.type, "is_scalar") else False):
        return None
    step = s.step
    if isinstance(step, (A.Unary, A.Postfix)) and step.op in ("++", "--"):
        target = step.operand
    elif isinstance(step, A.Assignment) and step.op in ("=", "+=", "-="):
        target = step.target
    else:
        return None
    if not isinstance(target, A.Identifier) or model.symbol_of(target) is not sym:
        return None
    # the step writes nothing else; the body and the condition never write the variable
    writers = [n for n in step.walk() if isinstance(n, (A.Assignment, A.Unary, A.Postfix, A.Call))]
    for n in writers:
        if n is step:
            continue
        if isinstance(n, A.Assignment) or (isinstance(n, (A.Unary, A.Postfix)) and n.op in ("++", "--")):
            return None
        if isinstance(n, A.Call) and any(d != "in" for d in out_directions(model.call_target(n))):
            return None
    if facts is not None:
        return sym if facts.write_counts().get(id(sym), 0) == 1 else None
    for part in (s.cond, s.body):
        if part is None:
            continue
        for n in part.walk():
            base = None
            if isinstance(n, A.Assignment):
                base = lvalue_base(n.target)
            elif isinstance(n, (A.Unary, A.Postfix)) and n.op in ("++", "--"):
                base = lvalue_base(n.operand)
            elif isinstance(n, A.Call):
                tgt = model.call_target(n)
                for i, d in enumerate(out_directions(tgt)):
                    if d != "in" and i < len(n.args) and (b := lvalue_base(n.args[i])) is not None:
                        if model.symbol_of(b) is sym:
                            return None
            if base is not None and model.symbol_of(base) is sym:
                return None
    return sym


# ---------------------------------------------------------------------------------------------
# Code emission
# ---------------------------------------------------------------------------------------------


# ---------------------------------------------------------------------------------------------
# Python's limits: generated code that CPython can always compile
# ---------------------------------------------------------------------------------------------


def _fold(root: Any, memo: dict[int, Any], own) -> Any:
    """`own(node, [values of its children])` computed bottom-up over root's subtree and memoized
    by node id, so that asking it of every node of a tree stays linear (iterative: expressions
    nest thousands deep)."""
    if id(root) in memo:
        return memo[id(root)]
    stack: list[tuple[Any, bool]] = [(root, False)]
    while stack:
        node, done = stack.pop()
        if id(node) in memo:
            continue
        kids = list(node.children())
        if done:
            memo[id(node)] = own(node, [memo[id(k)] for k in kids])
        else:
            stack.append((node, True))
            stack.extend((k, False) for k in kids if id(k) not in memo)
    return memo[id(root)]


class PythonLimits:
    """What keeps the generated code inside CPython's limits, whatever the GLSL's nesting:

    * an expression node SPILL_HEIGHT syntax levels high (or a multiple of it) is computed into a
      temporary, so no printed expression nests more than about 2 * SPILL_HEIGHT brackets (the
      tokenizer allows 200). Earlier operands of such an expression go to temporaries first
      (`needs_hoist`), so the evaluation order is kept;
    * a statement that would start OUTLINE_INDENT levels deep, or inside OUTLINE_LOOPS Python
      loops of one function (CPython allows 100 levels and 20 loops), is emitted as a
      module-level helper `h_<function>_<n>(S, locals...)` that returns the locals it may
      change; the caller rebinds them. An expression that would start OUTLINE_EXPR_INDENT deep
      (nested `&&`, ternaries with side effects) is outlined the same way, returning its value;
    * the transpiler's own recursion is given room as the checker's is, and the generated module
      is compiled once before it is handed out: whatever still fails (a limit this scheme does
      not foresee) is a located "too complex to render on the CPU" error, not a traceback.

    Mixed into `Transpiler` (it provides `lines`, `indent`, `fn`, `emit`, `tmp`, `fresh`)."""

    def local_names(self, lines: list[str]) -> set[str]:
        """The local names (`v_...`, `_...`) the code of these generated lines mentions. Each
        line is scanned once (`_line_names`): regions nested hundreds deep ask it of the same
        lines again and again."""
        out: set[str] = set()
        cache = self._line_names
        for ln in lines:
            names = cache.get(ln)
            if names is None:
                names = cache[ln] = frozenset(m.group(1) for m in _LOCAL_REF.finditer(ln.split("#", 1)[0]))
            out |= names
        return out

    def _height(self, e: Any) -> int:
        return _fold(e, self._heights, lambda n, kids: 1 + max(kids, default=0))

    def spill(self, e: Any, text: str) -> str:
        """`text` (the printed `e`), or a temporary holding it when e is SPILL_HEIGHT * k high."""
        h = self._height(e)
        if h >= SPILL_HEIGHT and h % SPILL_HEIGHT == 0 and self.fn is not None:
            return self.tmp(text)
        return text

    def too_deep(self, limit: int, loops: bool = True) -> bool:
        fs = self.fn
        return fs is not None and (self.indent >= limit or (loops and fs.blocks >= OUTLINE_LOOPS))

    def outline(self, build, node: Any) -> str | None:
        """Emit what `build()` emits (and its value, if it returns one) in a new module-level
        function of the locals it reads; emit the call here and return the value's name."""
        fs = self.fn
        defined = set(fs.defined)
        saved = self.lines, self.indent, fs.nest, fs.blocks
        self.lines, self.indent, fs.nest, fs.blocks, self.last_line = [], 1, 0, 0, None
        try:
            value = build()
            if value is not None:
                value = self.tmp(value)
            body = self.lines
        finally:
            self.lines, self.indent, fs.nest, fs.blocks = saved
            self.last_line = None
        used = sorted(self.local_names(body) & defined)
        # the locals it may rebind: every name left of an `=` (more than needed is harmless)
        targets = {m.group(1) for ln in body for t in _ASSIGNED.findall(ln.split("#", 1)[0].strip())
                   for m in _LOCAL_REF.finditer(t)}
        out = ([value] if value is not None and value in fs.defined else []) + [u for u in used if u in targets]
        self.n += 1
        sym = fs.sym
        base = self.fn_name(sym)[2:] if getattr(sym, "kind", None) == "function" else "globals"
        name = f"h_{base}_{self.n}"
        loc = getattr(node, "loc", None)
        where = f" line {loc.line}" if loc is not None and loc.line else ""
        self.helpers.append("\n".join(
            [f"def {name}({', '.join(['S'] + used)}):",
             f'    """Part of {_printable(sym.name, 60)}{where}, a function of its own to stay within'
             ' Python\'s nesting limits."""']
            + body + [f"    return ({''.join(o + ', ' for o in out)})", ""]))
        call = f"{name}({', '.join(['S'] + used)})"
        self.emit(f"{''.join(o + ', ' for o in out)}= {call}" if out else call)
        return value


def _scalars(t: Any) -> int:
    """Scalars in one lane's value of type t."""
    if t.is_array:
        return (t.array_size or 0) * _scalars(t.element)
    if t.is_struct:
        return sum(_scalars(ft) for _, ft in t.fields)
    if t.is_matrix:
        return t.cols * t.rows
    return t.size if t.is_vector else 1


def lane_state(model: Any, functions: list[Any]) -> tuple[int, Any]:
    """(an estimate of the scalars one lane holds at once, the declaration of the largest
    variable): every variable of every function (as if all were alive together), two more
    copies of the largest one (a masked write to an array builds the new array beside the old)
    and 256 scalars of temporaries."""
    nodes = [g.node for g in model.globals if g.kind == "global" and not g.type.contains_opaque]
    for fn in functions:
        nodes += fn.node.proto.params
        nodes += [n for n in fn.node.body.walk() if isinstance(n, (A.Declarator, A.ConditionDeclaration))]
    total, largest, at = 0, 0, None
    for n in nodes:
        sym = model.symbol_of(n)
        if sym is None or sym.type.contains_opaque:
            continue
        k = _scalars(sym.type)
        total += k
        if k > largest:
            largest, at = k, n
    return total + 2 * largest + 256, at


def too_complex(message: str, loc: Any) -> GlslError:
    return GlslError(Diagnostic(
        f"this program is too complex to render on the CPU ({message})", loc, rule=RULE,
        help="simplify the nesting here, or render with --backend gl"))


def _glsl_location(source: str, lineno: int, path: str) -> Location:
    """The GLSL line of generated line `lineno`: the nearest `# line N` comment above it."""
    lines = source.splitlines()
    for text in reversed(lines[: max(lineno, 1)]):
        m = re.match(r"\s*# (?:(.*) )?line (\d+): ", text)
        if m and (m.group(1) is None or m.group(1) == _printable(path, 60)):
            return Location(path, int(m.group(2)), 1)
    return Location(path, 1, 1)


def compile_generated(source: str, filename: str, path: str) -> Any:
    """The code object of a generated module; a located GlslError if Python cannot compile it."""
    try:
        return compile(source, filename, "exec")
    except (SyntaxError, RecursionError, MemoryError, ValueError) as e:
        lineno = getattr(e, "lineno", None) or 1
        msg = getattr(e, "msg", None) or str(e) or type(e).__name__
        raise too_complex(f"Python cannot compile the generated code: {msg}",
                          _glsl_location(source, lineno, path)) from None


@dataclass
class LValue:
    """An l-value with its index expressions already evaluated: base name and an access path.
    path items: ("field", "m_name") | ("swz", (i, j, ...)) | ("index", "expr", type_of_base)."""

    base: str
    base_type: Any
    path: list[tuple] = field(default_factory=list)


@dataclass
class LoopCtx:
    kind: str  # "loop" | "switch"
    live: str
    cont: str | None = None


class FnState:
    def __init__(self, sym: Any, uni: Uniformity, is_entry: bool) -> None:
        self.sym = sym
        self.uni = uni
        self.is_entry = is_entry
        self.defined: list[str] = []  # Python locals bound so far, in order
        self.loops: list[LoopCtx] = []
        self.has_ret = False
        self.rv: str | None = None
        self.outs: list[str] = []
        self.switch_depth = 0
        self.no_compact = 0
        self.nest = 0
        self.blocks = 0  # Python loops around the current line, in this Python function
        self.switch_locals: set[str] = set()  # declared in a switch body: bound before the switch


class Transpiler(PythonLimits):
    """`Transpiler(model, tab_path).module()` -> (Python source, meta dict)."""

    COMPACT_MIN_NODES = 24  # syntax nodes: smaller regions without calls or loops run masked

    def __init__(self, model: Any, path: str = "<shader>", source_text: str | None = None,
                 keep_alpha: bool = False) -> None:
        self.keep_alpha = keep_alpha  # a Buffer pass: Shadertoy keeps the alpha mainImage wrote
        self.model = model
        self.path = path
        self.entry = model.entry
        if self.entry is None:
            raise _error("the program has no mainImage (or main) to render", Location(path, 1, 1))
        self.functions = [f for f in model.reachable_functions()]
        self.facts = Facts(model, self.functions)
        self.lines: list[str] = []
        self.consts: dict[str, str] = {}  # name -> defining expression
        self.const_exprs: dict[str, str] = {}  # printed constant expression -> its C_x name
        self.in_const = False
        self.zero_defs: dict[str, str] = {}
        self.fn_names: dict[int, str] = {}
        self.struct_names: dict[int, str] = {}
        self.n = 0
        self.regions: dict[int, tuple[str, str, str, int]] = {}  # id -> (kind, function, path, line)
        self.loops: dict[int, tuple[str, int, int]] = {}
        self.fn: FnState | None = None
        self.indent = 0
        self.last_line: tuple[str, int] | None = None
        self.plain = self.entry.name == "main"
        self.uniforms: set[str] = set()
        self.helpers: list[str] = []  # functions split off the current one (PythonLimits.outline)
        self._heights: dict[int, int] = {}  # node id -> memoized facts about its subtree
        self._effects: dict[int, bool] = {}
        self._hoists: dict[int, bool] = {}
        self._derivs: dict[int, bool] = {}
        self._line_names: dict[str, frozenset] = {}

    # -- small emission helpers ----------------------------------------------------------------
    def emit(self, text: str) -> None:
        self.lines.append("    " * self.indent + text)

    def fresh(self, prefix: str) -> str:
        self.n += 1
        name = f"_{prefix}{self.n}"
        if self.fn is not None:
            self.fn.defined.append(name)
        return name

    def comment_line(self, node: Any) -> None:
        loc = getattr(node, "loc", None)
        if loc is None or not loc.line:
            return
        key = (loc.path, loc.line)
        if key == self.last_line:
            return
        self.last_line = key
        from ..diagnostics import source_line

        text = source_line(loc.path, loc.line) or ""
        where = f"line {loc.line}" if loc.path == self.path else f"{_printable(loc.path, 60)} line {loc.line}"
        self.emit(f"# {where}: {_printable(text)}".rstrip())

    def region(self, kind: str, node: Any) -> int:
        self.n += 1
        loc = getattr(node, "loc", None) or Location(self.path, 0, 0)
        fname = self.fn.sym.name if self.fn else ""
        self.regions[self.n] = (kind, fname, loc.path, loc.line)
        return self.n

    # -- names ---------------------------------------------------------------------------------
    def var_name(self, sym: Any, node: Any) -> str:
        if sym.kind in ("local", "param"):
            return "v_" + _ident(sym.unique_name or sym.name, node)
        if sym.kind == "global" and sym.qualifier == "uniform" and self._fed(sym):
            self.uniforms.add(sym.name)  # a plain file's own `uniform vec3 iResolution;`
            return "S.u_" + sym.name
        if sym.kind == "global":
            if sym.type.contains_opaque:
                raise _error(f"'{sym.name}': textures are not supported by the NumPy backend yet", node,
                             help="render with --backend gl")
            return "S.g_" + _ident(sym.unique_name or sym.name, node)
        if sym.kind == "uniform":
            from ..shadertoy import UNIFORMS_BY_NAME

            u = UNIFORMS_BY_NAME.get(sym.name)
            if u is None:
                raise _error(f"unknown uniform '{sym.name}'", node)
            if u.glsl_type.startswith("sampler") and u.glsl_type != "sampler2D":
                raise _error(f"'{sym.name}': {u.glsl_type} is not supported by the NumPy backend yet", node,
                             help="render with --backend gl")
            self.uniforms.add(sym.name)  # a sampler's value: a channels.ChannelInput (textures.py)
            return "S.u_" + sym.name
        if sym.kind == "builtin-var":
            if sym.name == "gl_FragCoord":
                return "S.frag_coord4"
            if sym.name == "gl_FrontFacing":
                return self.const_bool(True)
            if sym.const_value is not None and isinstance(sym.const_value, int):
                return self.const_int(sym.const_value, False)
            raise _error(f"'{sym.name}' is not supported by the NumPy backend", node)
        raise _error(f"'{sym.name}' ({sym.kind}) cannot be used as a value here", node)

    def fn_name(self, sym: Any) -> str:
        key = id(sym)
        if key not in self.fn_names:
            self.fn_names[key] = "f_" + _ident(sym.unique_name or sym.name, sym.node)
        return self.fn_names[key]

    def struct_name(self, st: Any) -> str:
        key = id(st)
        if key not in self.struct_names:
            name = st.name if _IDENT.match(st.name or "") else f"anon{len(self.struct_names)}"
            names = set(self.struct_names.values())
            base, i = "s_" + name, 1
            cand = base
            while cand in names:
                i += 1
                cand = f"{base}_{i}"
            self.struct_names[key] = cand
        return self.struct_names[key]

    @staticmethod
    def member(name: str, node: Any) -> str:
        return "m_" + _ident(name, node)

    # -- constants and zero values -------------------------------------------------------------
    def const_float(self, v: float) -> str:
        import math

        if math.isnan(v):
            text, lit = "nan", "1e999 - 1e999"  # never produced by a literal; kept for folds
        elif math.isinf(v):
            text, lit = ("inf" if v > 0 else "minf"), ("1e999" if v > 0 else "-1e999")
        else:
            lit = repr(float(v))
            text = lit.replace("-", "m").replace("+", "").replace(".", "p")
        name = "C_f_" + text
        self.consts.setdefault(name, f"rt.const_float({lit})")
        return name

    def const_int(self, v: int, unsigned: bool) -> str:
        v = int(v)
        if unsigned:
            v &= 0xFFFFFFFF
            name = f"C_u_{v}"
            self.consts.setdefault(name, f"rt.const_uint({v})")
        else:
            v = (v + 2**31) % 2**32 - 2**31
            name = f"C_i_{v}".replace("-", "m")
            self.consts.setdefault(name, f"rt.const_int({v})")
        return name

    def const_bool(self, v: bool) -> str:
        name = "C_b_" + ("true" if v else "false")
        self.consts.setdefault(name, f"rt.const_bool({bool(v)})")
        return name

    def shape_of(self, t: Any, node: Any) -> tuple[tuple[int, ...], str]:
        if t.is_array:
            inner, kind = self.shape_of(t.element, node)
            return (t.array_size,) + inner, kind
        if t.is_scalar:
            return (), t.base
        if t.is_vector:
            return (t.size,), t.base
        if t.is_matrix:
            return (t.cols, t.rows), "float"
        raise _error(f"values of type '{t}' are not supported by the NumPy backend", node)

    def zero(self, t: Any, node: Any, lead: tuple[int, ...] = ()) -> str:
        """The name of a module constant holding the zero value of type t (with leading array axes)."""
        if t.is_array and (t.element.is_struct or lead):
            return self.zero(t.element, node, lead + (t.array_size,))
        if t.is_struct:
            sname = self.struct_name(t)
            key = "Z_" + sname + "".join(f"_a{n}" for n in lead)
            if key not in self.zero_defs:
                fields = ", ".join(f"{self.member(fname, node)}={self.zero(ft, node, lead)}" for fname, ft in t.fields)
                self.zero_defs[key] = f'rt.struct("{sname}", {fields})'
            return key
        shape, kind = self.shape_of(t, node)
        shape = lead + shape
        key = f"Z_{kind}" + "".join(f"_{n}" for n in shape)
        self.zero_defs.setdefault(key, f'rt.zeros({shape!r}, "{kind}")')
        return key

    # -- module --------------------------------------------------------------------------------
    def module(self) -> tuple[str, dict]:
        funcs: list[str] = []
        for fn in self.functions:
            self.lines = []
            self.gen_function(fn)
            funcs += self.helpers + ["\n".join(self.lines)]
            self.helpers = []
        self.lines = []
        self.fn = None
        self.gen_globals()
        init = "\n".join(self.helpers + self.lines)
        self.lines = []
        self.gen_shade()
        shade = "\n".join(self.lines)
        meta = {
            "source": self.path,
            "entry": self.fn_name(self.entry),
            "plain": self.plain,
            "uniforms": sorted(self.uniforms),
            "regions": self.regions,
            "loops": self.loops,
            "uses_derivatives": bool(self.facts.uses_derivs),
            "loop_cap": LOOP_CAP,
        }
        scalars, at = lane_state(self.model, self.functions)
        if scalars > SMALL_STATE and at is not None:
            loc = at.loc
            meta["lane_state"] = (scalars, loc.path, loc.line, loc.column)
        out = [self.header(), "", f"SHADER_META = {meta!r}", ""]
        out.append("if __name__ == \"__main__\":  # run on its own: python this_file.py --help")
        out.append("    from glslcheck.numpy_backend.program import standalone_globals")
        out.append("    globals().update(standalone_globals(SHADER_META))")
        out.append("")
        out.append("# Constants in the render precision (rt decides the float dtype).")
        for name, expr in self.consts.items():
            out.append(f"{name} = {expr}")
        for name, expr in self.zero_defs.items():
            out.append(f"{name} = {expr}")
        out.append("")
        for f in funcs:
            out += ["", f, ""]
        out += ["", init, "", "", shade, ""]
        out.append("")
        out.append("if __name__ == \"__main__\":")
        out.append("    from glslcheck.numpy_backend.program import run_standalone")
        out.append("    run_standalone(globals())")
        return "\n".join(out) + "\n", meta

    @staticmethod
    def _fed(sym: Any) -> bool:
        """Whether a declared uniform gets Shadertoy's value (shadertoy.fed_uniform), as on GL."""
        from ..shadertoy import fed_uniform

        u = fed_uniform(sym.name, str(sym.type))
        return u is not None and not u.glsl_type.startswith("sampler")

    def _uniforms_from_model(self) -> set[str]:
        try:
            return set(self.model.uniforms_read())  # samplers included: channels.ChannelInput values
        except Exception:  # pragma: no cover - the model's API is still settling
            return set()

    def header(self) -> str:
        from .. import __version__

        src = _printable(self.path, 200)
        return (
            f'"""Generated by glslcheck {__version__} from {src} (GLSL ES 3.00) -- do not edit.\n\n'
            "Each GLSL function is a Python function over lanes (one lane per pixel); see the\n"
            "docstring of glslcheck/numpy_backend/transpile.py for the execution model and of\n"
            "glslcheck/numpy_backend/runtime.py for the value representation.\n\n"
            "Run it on its own (needs numpy and glslcheck's runtime):\n"
            "    python shader.py -o out.png --size 800x450 --time 0\n"
            "or from Python: glslcheck.numpy_backend.program.load_module('shader.py').render(...)\n"
            '"""'
        )

    def gen_globals(self) -> None:
        self.emit("def init_globals(S):")
        self.indent += 1
        self.emit('"""Global variables at the start of every invocation (their initializers are constant)."""')
        empty = True
        fake = type("G", (), {"name": "<globals>", "node": None})()
        self.fn = FnState(fake, None, True)  # type: ignore[arg-type]
        for sym in self.model.globals:
            if sym.kind != "global" or sym.type.contains_opaque:
                continue  # samplers: an error where they are used
            d = sym.node
            init = d.init if isinstance(d, A.Declarator) else None
            self.comment_line(d)
            value = self.expr(init, None) if init is not None else self.zero(sym.type, d)
            self.emit(f"{self.var_name(sym, d)} = {value}")
            empty = False
        if empty:
            self.emit("pass")
        self.indent -= 1
        self.fn = None

    def gen_shade(self) -> None:
        entry = self.entry
        name = self.fn_name(entry)
        self.emit("def shade(S):")
        self.indent += 1
        if self.plain:
            self.emit('"""main() of a plain GLSL shader: the value of its `out vec4` variable."""')
            outs = [g for g in self.model.globals if g.qualifier == "out" and g.kind == "global"
                    and str(g.type) == "vec4"]
            self.emit(f"{name}(S, None)")
            if not outs:
                raise _error("a plain GLSL shader needs an 'out vec4' variable", entry.node)
            self.emit(f"return {self.var_name(outs[0], entry.node)}")
        else:
            self.emit('"""Shadertoy\'s main(): color = vec4(1e20); mainImage(color, fragCoord); its RGB."""')
            args = []
            init = self.consts.setdefault("C_vec4_1e20", "rt.vec(4, rt.const_float(1e20))") and "C_vec4_1e20"
            (_, _, d0), (_, _, d1) = entry.params
            if d0 != "out":
                args.append(init)
            if d1 != "out":
                args.append("S.frag_coord")
            call = f"{name}(S, None{''.join(', ' + a for a in args)})"
            outs = [d for _, _, d in entry.params if d != "in"]
            if not outs:
                self.emit(call)
                self.emit(f"_color = {init}")
            else:
                self.emit(f"_r = {call}")
                self.emit("_color = _r[1]" if d0 != "in" else f"_color = {init}")
            if self.keep_alpha:
                self.emit("return _color  # a Buffer pass keeps alpha")
            else:
                self.emit('return rt.swizzle(_color, "xyz")  # RGB: the caller sets alpha to 1')
        self.indent -= 1

    # -- functions -----------------------------------------------------------------------------
    def gen_function(self, sym: Any) -> None:
        node = sym.node
        is_entry = sym is self.entry
        uni = Uniformity(self, sym, is_entry)
        self.fn = fs = FnState(sym, uni, is_entry)
        if id(sym) in self.facts.uses_derivs:
            fs.no_compact += 1
        proto = node.proto
        params = []
        prologue = []
        for k, (p, (pname, ptype, direction)) in enumerate(zip(proto.params, sym.params)):
            psym = self.model.symbol_of(p)
            # An unnamed parameter (`void mainImage(out vec4, in vec2 c)`) still takes its
            # argument and, for out/inout, hands a value back: callers count on both.
            pyname = self.var_name(psym, p) if psym is not None else f"_unnamed{k}"
            fs.defined.append(pyname)
            if direction == "out":
                prologue.append(f"{pyname} = {self.zero(ptype, p)}")
            else:
                params.append(pyname)
            if direction != "in":
                fs.outs.append(pyname)
        fs.defined.append("_m")
        self.last_line = None
        sig = ", ".join(["S", "_m"] + params)
        self.emit(f"def {self.fn_name(sym)}({sig}):")
        self.indent += 1
        doc = _printable(sym.signature(), 150) if hasattr(sym, "signature") else sym.name
        loc = getattr(proto, "loc", None)
        self.emit(f'"""{doc} (line {loc.line if loc else "?"})."""')
        rid = self.region("function", proto)
        self.emit(f"X.count(S, {rid}, _m)")
        for line in prologue:
            self.emit(line)
        body = node.body.stmts
        early = self.early_out(body)
        if early is not None:
            body = body[:-2]
        ev = events_of(node.body, self.facts, self.model) if early is None else None
        tail = body[-1] if body and isinstance(body[-1], A.Return) else None
        nontail_ret = early is None and (
            any(isinstance(n, (A.Return, A.Discard)) and n is not tail for n in node.body.walk()) or (
                ev.ret and any(isinstance(n, A.Call) and _is_symbol(self.model.call_target(n))
                               and id(self.model.call_target(n)) in self.facts.may_discard
                               for n in node.body.walk())))
        if nontail_ret:
            fs.has_ret = True
            self.emit("_ret = X.NO")
            fs.defined.append("_ret")
            if not sym.type.is_void:
                fs.rv = "_rv"
                self.emit(f"_rv = {self.zero(sym.type, proto)}")
                fs.defined.append("_rv")
        ended = self.block(body, "_m", top=True)
        if early is not None:
            cond_stmt, ret = early
            self.comment_line(cond_stmt)
            c = self.tmp(self.expr(cond_stmt.cond, "_m"))
            then = cond_stmt.then.stmts[0] if isinstance(cond_stmt.then, A.Compound) else cond_stmt.then
            a = self.expr(then.value, "_m")
            self.emit(f"if X.every({c}):  # no lane goes on: the rest is not computed")
            self.indent += 1
            self.emit(self.final_return(a))
            self.indent -= 1
            self.comment_line(ret)
            b = self.expr(ret.value, "_m")
            self.emit(self.final_return(f"rt.select({c}, {a}, {b})"))
        elif not ended:
            self.emit(self.final_return())
        self.indent -= 1
        self.fn = None

    def early_out(self, body: list[Any]) -> tuple[Any, Any] | None:
        """`if (c) return K; return e;` ending a function, K a constant and c, e without side
        effects: (the If, the last Return). The function then returns `select(c, K, e)`, with no
        return mask: e is computed on every lane either way, and a select is cheaper than
        masked writes of the return value. Any other return or discard in the body keeps the
        general scheme."""
        if len(body) < 2 or not isinstance(body[-1], A.Return) or body[-1].value is None:
            return None
        st = body[-2]
        if not isinstance(st, A.If) or st.else_ is not None:
            return None
        then = st.then
        if isinstance(then, A.Compound):
            if len(then.stmts) != 1:
                return None
            then = then.stmts[0]
        if not isinstance(then, A.Return) or then.value is None:
            return None
        if self.model.const_value(then.value) is None:
            return None
        if self.has_effects(st.cond) or self.has_effects(body[-1].value):
            return None
        for n in body[:-2]:
            for m in n.walk():
                if isinstance(m, (A.Return, A.Discard)):
                    return None
                if isinstance(m, A.Call) and _is_symbol(self.model.call_target(m)) \
                        and id(self.model.call_target(m)) in self.facts.may_discard:
                    return None
        return st, body[-1]

    def final_return(self, value: str | None = None) -> str:
        fs = self.fn
        assert fs is not None
        ret = value if value is not None else (fs.rv or "None")
        if fs.outs:
            return f"return ({ret}, {', '.join(fs.outs)})"
        if value is None and fs.rv is None:
            return "return None"
        return f"return {ret}"

    # -- blocks and masks ----------------------------------------------------------------------
    def block(self, stmts: list[Any], mask: str | None, top: bool = False) -> bool:
        """Emit statements under `mask`; returns True when the Python code ended with `return`
        at this indentation (nothing after it runs)."""
        fs = self.fn
        start_indent = self.indent
        for i, s in enumerate(stmts):
            last = i == len(stmts) - 1
            if top and last and isinstance(s, A.Return):
                # the function's last statement: return directly (when it is nested under the
                # `if X.live(...)` of earlier returns, the final `return _rv` follows that `if`)
                self.comment_line(s)
                val = self.expr(s.value, mask) if s.value is not None else None
                if val is not None and fs.rv is not None and mask not in (None, "_m"):
                    val = f"X.put({fs.rv}, {val}, {mask})"
                self.emit(self.final_return(val) if val is not None or fs.outs else "return None")
                nested = self.indent != start_indent
                fs.nest -= self.indent - start_indent
                self.indent = start_indent
                return not nested
            ev = events_of(s, self.facts, self.model)
            self.stmt(s, mask)
            if ev.any and not last:
                mask = self.refresh(mask, ev)
                if fs.switch_depth == 0 and fs.nest < 40:
                    self.emit(f"if X.live({mask}):")
                    self.indent += 1
                    fs.nest += 1
        fs.nest -= self.indent - start_indent
        self.indent = start_indent
        return False

    def refresh(self, mask: str | None, ev: Events) -> str:
        fs = self.fn
        live = None
        drops = []
        if ev.brk and fs.loops:
            live = fs.loops[-1].live
        if ev.cont:
            loop = next((lp for lp in reversed(fs.loops) if lp.kind == "loop"), None)
            if loop is not None and loop.cont:
                drops.append(loop.cont)
        if ev.ret and fs.has_ret:
            drops.append("_ret")
        new = self.fresh("m")
        self.emit(f"{new} = X.refresh({mask}, {live}{''.join(', ' + d for d in drops)})")
        return new

    def assign_stmt(self, target: str, value: str, mask: str | None) -> None:
        if mask is None:
            self.emit(f"{target} = {value}")
        else:
            self.emit(f"{target} = X.put({target}, {value}, {mask})")

    # -- compaction ------------------------------------------------------------------------------
    def region_body(self, emit_body, mask: str, kind: str, node: Any) -> None:
        """Emit a varying region (already under `if X.live(mask):`) with compaction when sparse."""
        fs = self.fn
        rid = self.region(kind, node)
        if fs.no_compact or self._region_uses_derivs(node) or not self._worth_compacting(node):
            self.emit(f"X.count(S, {rid}, {mask})")
            emit_body(mask)
            return
        snapshot = set(fs.defined)
        start = len(self.lines)
        ix = self.fresh("ix")
        saved = self.fresh("o")
        self.emit(f"X.count(S, {rid}, {mask})")
        emit_body(mask)
        body_lines = self.lines[start:]
        used = sorted((self.local_names(body_lines) & snapshot) - {mask})
        del self.lines[start:]
        tup = "(" + "".join(n + ", " for n in used) + ")"
        self.emit(f"{ix} = X.sparse(S, {mask})")
        self.emit(f"if {ix} is not None:")
        self.emit(f"    S, {saved} = X.gather(S, {ix}, {tup})")
        if used:
            self.emit(f"    {', '.join(used)}, = {saved}.values")
        self.emit(f"    {mask} = None")
        self.lines.extend(body_lines)
        self.emit(f"if {ix} is not None:")
        self.emit(f"    S, {tup if used else '_'} = X.scatter(S, {ix}, {saved}, {tup})")

    def _worth_compacting(self, node: Any) -> bool:
        """Gathering pays off for a region with a loop, a user call or some arithmetic; a
        region of a few assignments (`break;`, `return 0.1;`) is cheaper to run masked."""
        count = 0
        for n in node.walk():
            if isinstance(n, (A.For, A.While, A.DoWhile)):
                return True
            if isinstance(n, A.Call) and (_is_symbol(self.model.call_target(n))
                                          or getattr(self.model.call_target(n), "cost", None) == B.EXPENSIVE):
                return True
            count += 1
            if count >= self.COMPACT_MIN_NODES:
                return True  # (so a region nested hundreds deep is not walked whole)
        return False

    def _region_uses_derivs(self, node: Any) -> bool:
        return _fold(node, self._derivs, self._derivs_here)

    def _derivs_here(self, n: Any, kids: list[bool]) -> bool:
        if any(kids):
            return True
        if isinstance(n, A.Call):
            tgt = self.model.call_target(n)
            if getattr(tgt, "name", None) in _DERIVATIVES + _IMPLICIT_LOD and not _is_symbol(tgt):
                return True
            if _is_symbol(tgt) and id(tgt) in self.facts.uses_derivs:
                return True
        return False

    # -- statements ----------------------------------------------------------------------------
    def stmt(self, s: Any, mask: str | None) -> None:
        method = getattr(self, "_stmt_" + type(s).__name__, None)
        if method is None:
            raise _error(f"{type(s).__name__} statements are not supported by the NumPy backend", s)
        self.where = s
        if self.too_deep(OUTLINE_INDENT):
            self.outline(lambda: method(s, mask), s)
        else:
            method(s, mask)

    def _stmt_Compound(self, s: A.Compound, mask: str | None) -> None:
        if not s.stmts:
            return
        self.block(s.stmts, mask)

    def _stmt_ExpressionStatement(self, s: A.ExpressionStatement, mask: str | None) -> None:
        if s.expr is None:
            return
        self.comment_line(s)
        self.effect(s.expr, mask)

    def effect(self, e: Any, mask: str | None, step_unmasked: bool = False) -> None:
        """An expression evaluated for its side effects only."""
        if isinstance(e, A.Assignment):
            self.assignment(e, mask, want_value=False)
        elif isinstance(e, (A.Unary, A.Postfix)) and e.op in ("++", "--"):
            self.incdec(e, mask, want_value=False)
        elif isinstance(e, A.Sequence):
            for x in e.exprs:
                self.effect(x, mask)
        else:
            value = self.expr(e, mask)
            if isinstance(e, A.Call) and _is_symbol(self.model.call_target(e)):
                self.emit(value)
            elif "(" in value and not value.startswith(("C_", "Z_")):
                self.emit(value)
        self.after_discarding_call(e)

    def after_discarding_call(self, e: Any) -> None:
        fs = self.fn
        if not fs.has_ret:
            return
        for n in e.walk():
            if isinstance(n, A.Call):
                tgt = self.model.call_target(n)
                if _is_symbol(tgt) and id(tgt) in self.facts.may_discard:
                    self.emit("_ret = X.or_(_ret, S.discard)")
                    return

    def _stmt_DeclarationStatement(self, s: A.DeclarationStatement, mask: str | None) -> None:
        d = s.decl
        if isinstance(d, A.PrecisionDeclaration):
            return
        if not isinstance(d, A.VariableDeclaration):
            raise _error("this declaration is not supported inside a function", s)
        for dec in d.declarators:
            self.comment_line(dec)
            sym = self.model.symbol_of(dec)
            if sym is None:
                continue
            name = self.var_name(sym, dec)
            value = self.expr(dec.init, mask) if dec.init is not None else self.zero(sym.type, dec)
            if dec.init is not None:
                self.after_discarding_call(dec.init)
            if name in self.fn.switch_locals:  # (one in a block inside a case is scoped to it)
                self.emit(f"{name} = X.put({name}, {value}, {mask})")
            else:
                self.emit(f"{name} = {value}")
            if name not in self.fn.defined:
                self.fn.defined.append(name)

    def declare_switch_locals(self, s: A.Switch) -> None:
        for st in s.body:
            if isinstance(st, A.DeclarationStatement) and isinstance(st.decl, A.VariableDeclaration):
                for dec in st.decl.declarators:
                    sym = self.model.symbol_of(dec)
                    if sym is not None:
                        name = self.var_name(sym, dec)
                        self.emit(f"{name} = {self.zero(sym.type, dec)}")
                        self.fn.defined.append(name)
                        self.fn.switch_locals.add(name)

    def _stmt_If(self, s: A.If, mask: str | None) -> None:
        self.comment_line(s)
        fs = self.fn
        cond = self.expr(s.cond, mask)
        self.after_discarding_call(s.cond)
        if fs.uni is not None and fs.uni.is_uniform(s.cond):
            # lane-uniform condition: plain Python control flow, same mask inside
            self.emit(f"if X.true({cond}):")
            self.indent += 1
            self.emit(f"X.count(S, {self.region('if', s)}, {mask})")
            self.sub(s.then, mask)
            self.indent -= 1
            if s.else_ is not None:
                self.emit("else:")
                self.indent += 1
                self.emit(f"X.count(S, {self.region('else', s.else_)}, {mask})")
                self.sub(s.else_, mask)
                self.indent -= 1
            return
        c = self.fresh("c")
        self.emit(f"{c} = {cond}")
        mt = self.fresh("m")
        self.emit(f"{mt} = X.and_({mask}, {c})")
        self.emit(f"if X.live({mt}):")
        self.indent += 1
        self.region_body(lambda m: self.sub(s.then, m), mt, "if", s.then)
        self.indent -= 1
        if s.else_ is not None:
            me = self.fresh("m")
            self.emit(f"{me} = X.andnot({mask}, {c})")
            self.emit(f"if X.live({me}):")
            self.indent += 1
            self.region_body(lambda m: self.sub(s.else_, m), me, "else", s.else_)
            self.indent -= 1

    def sub(self, s: Any, mask: str | None) -> None:
        start = len(self.lines)
        if isinstance(s, A.Compound):
            self.block(s.stmts, mask)
        else:
            self.block([s], mask)
        if len(self.lines) == start:
            self.emit("pass")

    def _stmt_Break(self, s: A.Break, mask: str | None) -> None:
        self.comment_line(s)
        lp = self.fn.loops[-1]
        self.emit(f"{lp.live} = X.andnot({lp.live}, {mask})")

    def _stmt_Continue(self, s: A.Continue, mask: str | None) -> None:
        self.comment_line(s)
        lp = next(lp for lp in reversed(self.fn.loops) if lp.kind == "loop")
        self.emit(f"{lp.cont} = X.or_({lp.cont}, {mask})")

    def _stmt_Discard(self, s: A.Discard, mask: str | None) -> None:
        self.comment_line(s)
        self.emit(f"S.discard = X.or_(S.discard, {mask})")
        if self.fn.has_ret:
            self.emit(f"_ret = X.or_(_ret, {mask})")

    def _stmt_Return(self, s: A.Return, mask: str | None) -> None:
        self.comment_line(s)
        fs = self.fn
        if s.value is not None:
            val = self.expr(s.value, mask)
            self.after_discarding_call(s.value)
            if fs.rv is not None:
                self.assign_stmt(fs.rv, val, mask)
        if fs.has_ret:
            self.emit(f"_ret = X.or_(_ret, {mask})")

    def _stmt_Switch(self, s: A.Switch, mask: str | None) -> None:
        self.comment_line(s)
        fs = self.fn
        sel = self.fresh("sv")
        self.emit(f"{sel} = {self.expr(s.expr, mask)}")
        self.declare_switch_locals(s)
        labels = [st for st in s.body if isinstance(st, A.Case)]
        consts = []
        for lab in labels:
            if lab.expr is not None:
                v = self.model.const_value(lab.expr)
                if v is None:
                    raise _error("a case label must be a constant integer", lab)
                consts.append(self.const_int(v, self.model.type_of(lab.expr) == T.UINT))
        dflt = None
        if any(lab.expr is None for lab in labels):
            dflt = self.fresh("d")
            if consts:
                any_case = " | ".join(f"rt.eq({sel}, {c})" for c in consts)
                self.emit(f"{dflt} = rt.not_({any_case})")
            else:
                self.emit(f"{dflt} = {self.const_bool(True)}")
        live = self.fresh("sl")
        fall = self.fresh("fall")
        self.emit(f"{live} = {mask}")
        self.emit(f"{fall} = X.NO")
        fs.loops.append(LoopCtx("switch", live))
        fs.switch_depth += 1
        groups: list[tuple[list[Any], list[Any]]] = []
        for st in s.body:
            if isinstance(st, A.Case):
                if groups and not groups[-1][1]:
                    groups[-1][0].append(st)
                else:
                    groups.append(([st], []))
            else:
                groups[-1][1].append(st)
        ci = 0
        for labs, stmts in groups:
            for lab in labs:
                self.comment_line(lab)
                if lab.expr is None:
                    self.emit(f"{fall} = X.or_({fall}, {dflt})")
                else:
                    self.emit(f"{fall} = X.or_({fall}, rt.eq({sel}, {consts[ci]}))")
                    ci += 1
            cur = self.fresh("m")
            self.emit(f"{cur} = X.and_(X.and_({live}, {fall}), {mask})")
            if fs.has_ret:
                self.emit(f"{cur} = X.andnot({cur}, _ret)")
            self.emit(f"if X.live({cur}):")
            self.indent += 1
            self.emit(f"X.count(S, {self.region('case', labs[0])}, {cur})")
            self.block(stmts, cur)
            self.indent -= 1
        fs.switch_depth -= 1
        fs.loops.pop()

    # loops --------------------------------------------------------------------------------------
    def _stmt_For(self, s: A.For, mask: str | None) -> None:
        self.comment_line(s)
        if s.init is not None:
            self.stmt(s.init, mask)
        self.loop(s, mask, s.cond, s.body, s.step, do_while=False)

    def _stmt_While(self, s: A.While, mask: str | None) -> None:
        self.comment_line(s)
        self.loop(s, mask, s.cond, s.body, None, do_while=False)

    def _stmt_DoWhile(self, s: A.DoWhile, mask: str | None) -> None:
        self.comment_line(s)
        self.loop(s, mask, s.cond, s.body, None, do_while=True)

    def loop(self, s: Any, mask: str | None, cond: Any, body: Any, step: Any, do_while: bool) -> None:
        fs = self.fn
        lid = self.region("loop", s)
        self.loops[lid] = (s.loc.path, s.loc.line, s.loc.column)
        ind = induction_variable(s, self.model, self.facts)
        ev_body = events_of(body, self.facts, self.model)
        if (not do_while and cond is not None and not isinstance(cond, A.ConditionDeclaration)
                and not ev_body.any and fs.uni is not None and fs.uni.is_uniform(cond)):
            self.uniform_loop(lid, mask, cond, body, step, ind)
            return
        live = self.fresh("live")
        count = self.fresh("n")
        self.emit(f"{live} = {mask}")
        self.emit(f"{count} = 0")
        compact = not fs.no_compact and not self._region_uses_derivs(s)
        snapshot = set(fs.defined)
        stack = self.fresh("k") if compact else None
        if stack:
            self.emit(f"{stack} = []")
        start_lines = len(self.lines)
        self.emit("while True:")
        self.indent += 1
        fs.blocks += 1
        self.emit(f"{count} += 1")
        self.emit(f"if {count} > {LOOP_CAP}:")
        self.emit(f"    X.runaway({lid})")
        self.emit(f"if X.tick(S, {lid}, {count}):")  # llvmpipe's loop limiter, if rendering with one
        self.emit("    break")
        if ev_body.ret and fs.has_ret:
            self.emit(f"{live} = X.andnot({live}, _ret)")
        if do_while or cond is None:
            self.emit(f"if not X.live({live}):")
            self.emit("    break")
        else:
            c = self.condition(cond, live)
            self.emit(f"{live} = X.and_({live}, {c})")
            self.emit(f"if not X.live({live}):")
            self.emit("    break")
        compact_at = len(self.lines)
        cont = None
        if ev_body.cont:
            cont = self.fresh("cnt")
            self.emit(f"{cont} = X.NO")
        fs.loops.append(LoopCtx("loop", live, cont))
        self.emit(f"X.count(S, {lid}, {live})")
        bmask = live
        self.sub(body, bmask)
        fs.loops.pop()
        if do_while:
            c = self.condition(cond, live)
            self.emit(f"{live} = X.and_({live}, {c})")
        if step is not None:
            self.comment_line(step)
            if ind is not None:
                self.effect(step, None)
            else:
                smask = live
                if ev_body.ret and fs.has_ret:
                    smask = self.fresh("m")
                    self.emit(f"{smask} = X.andnot({live}, _ret)")
                self.effect(step, smask)
        self.indent -= 1
        fs.blocks -= 1
        if stack:
            loop_lines = self.lines[start_lines:]
            used = sorted((self.local_names(loop_lines) & snapshot) | {live})
            tup = "(" + ", ".join(used) + ",)"
            pad = "    " * (self.indent + 1)
            push = [
                f"{pad}if X.sparse(S, {live}) is not None:",
                f"{pad}    S, ({', '.join(used)},) = X.push({stack}, S, {live}, {tup})",
                f"{pad}    {live} = None",
            ]
            self.lines[compact_at:compact_at] = push
            self.emit(f"if {stack}:")
            self.emit(f"    S, ({', '.join(used)},) = X.unwind({stack}, S, {tup})")

    def uniform_loop(self, lid: int, mask: str | None, cond: Any, body: Any, step: Any, ind: Any) -> None:
        """A loop whose condition is the same in every lane and whose body cannot leave it
        early (no break, continue, return or discard): every iteration runs on the lanes that
        entered, so it is plain Python control flow with no mask of its own."""
        fs = self.fn
        count = self.fresh("n")
        self.emit(f"{count} = 0")
        self.emit("while True:")
        self.indent += 1
        fs.blocks += 1
        self.emit(f"{count} += 1")
        self.emit(f"if {count} > {LOOP_CAP}:")
        self.emit(f"    X.runaway({lid})")
        self.emit(f"if X.tick(S, {lid}, {count}):")  # llvmpipe's loop limiter, if rendering with one
        self.emit("    break")
        c = self.condition(cond, mask)
        self.emit(f"if not X.true({c}):")
        self.emit("    break")
        fs.loops.append(LoopCtx("loop", mask if mask is not None else "None", None))
        self.emit(f"X.count(S, {lid}, {mask})")
        self.sub(body, mask)
        fs.loops.pop()
        if step is not None:
            self.comment_line(step)
            self.effect(step, None if ind is not None else mask)
        self.indent -= 1
        fs.blocks -= 1

    def condition(self, cond: Any, mask: str | None) -> str:
        if isinstance(cond, A.ConditionDeclaration):
            sym = self.model.symbol_of(cond)
            name = self.var_name(sym, cond)
            self.emit(f"{name} = {self.expr(cond.init, mask)}")
            if name not in self.fn.defined:
                self.fn.defined.append(name)
            return name
        return self.expr(cond, mask)

    # -- expressions ---------------------------------------------------------------------------
    def expr(self, e: Any, mask: str | None) -> str:
        method = getattr(self, "_print_" + type(e).__name__, None)
        if method is None:
            raise _error(f"{type(e).__name__} expressions are not supported by the NumPy backend", e)
        if self.too_deep(OUTLINE_EXPR_INDENT, loops=False):
            return self.outline(lambda: self.expr(e, mask), e)
        if self.fn is None or self.in_const or self.model.const_value(e) is None:
            return self.spill(e, method(e, mask))
        # a constant expression inside a function: computed once, as a module constant (the
        # same runtime calls at import time instead of on every call in every tile)
        self.in_const = True
        n_lines = len(self.lines)
        try:
            text = method(e, mask)
        finally:
            self.in_const = False
        if len(self.lines) != n_lines or "(" not in text or not _is_constant_text(text):
            return self.spill(e, text)
        name = self.const_exprs.get(text)
        if name is None:
            name = self.const_exprs[text] = f"C_x{len(self.const_exprs) + 1}"
            self.consts[name] = text
        return name

    def type_of(self, e: Any) -> Any:
        return self.model.type_of(e)

    def needs_hoist(self, e: Any) -> bool:
        """True when evaluating e emits statements (so earlier operands go to temporaries
        first): effects, or a part high enough to be spilled (`PythonLimits.spill`)."""
        return self._height(e) >= SPILL_HEIGHT or _fold(e, self._hoists, self._hoists_here)

    def _hoists_here(self, n: Any, kids: list[bool]) -> bool:
        if any(kids) or isinstance(n, (A.Assignment, A.Sequence)):
            return True
        if isinstance(n, (A.Unary, A.Postfix)) and n.op in ("++", "--"):
            return True
        if isinstance(n, A.Call):
            tgt = self.model.call_target(n)
            if any(d != "in" for d in out_directions(tgt)):
                return True
            if _is_symbol(tgt) and id(tgt) in self.facts.may_discard:
                return True
        if isinstance(n, (A.Ternary, A.Binary)) and (not isinstance(n, A.Binary) or n.op in ("&&", "||")):
            if self.has_effects(n.then if isinstance(n, A.Ternary) else n.right) or (
                    isinstance(n, A.Ternary) and self.has_effects(n.else_)):
                return True
        return False

    def has_effects(self, e: Any) -> bool:
        return _fold(e, self._effects, self._effects_here)

    def _effects_here(self, n: Any, kids: list[bool]) -> bool:
        if any(kids) or isinstance(n, (A.Assignment, A.Sequence)):
            return True
        if isinstance(n, (A.Unary, A.Postfix)) and n.op in ("++", "--"):
            return True
        return isinstance(n, A.Call) and (_is_symbol(self.model.call_target(n))
                                          or any(d != "in" for d in out_directions(self.model.call_target(n))))

    def tmp(self, value: str) -> str:
        if value.startswith(("C_", "Z_")) and value.replace("_", "").isalnum():
            return value
        t = self.fresh("t")
        self.emit(f"{t} = {value}")
        return t

    def exprs(self, items: list[Any], mask: str | None) -> list[str]:
        """Evaluate expressions as Mesa does: a later operand's side effects (calls with out
        arguments, assignments, ++/--) are emitted as statements first and every operand is
        read after them, so `vec4(ip, modf(x, ip), ...)` and `vec2(i, i++)` see the updated
        value in every position (measured on llvmpipe; GLSL IR hoists such calls and reads
        variables lazily). Earlier operands are not copied to temporaries."""
        return [self.expr(e, mask) for e in items]

    def _print_IntLiteral(self, e: A.IntLiteral, mask: str | None) -> str:
        return self.const_int(e.value, e.unsigned or self.type_of(e) == T.UINT)

    def _print_FloatLiteral(self, e: A.FloatLiteral, mask: str | None) -> str:
        return self.const_float(e.value)

    def _print_BoolLiteral(self, e: A.BoolLiteral, mask: str | None) -> str:
        return self.const_bool(e.value)

    def _print_Identifier(self, e: A.Identifier, mask: str | None) -> str:
        sym = self.model.symbol_of(e)
        if sym is None:
            raise _error(f"'{e.name}' has no symbol", e)
        return self.var_name(sym, e)

    def _print_Binary(self, e: A.Binary, mask: str | None) -> str:
        folded = nir_fold.binary(self, e, mask)  # Mesa's reassociations (llvmpipe mode)
        if folded is not None:
            return folded
        op = e.op
        if op in ("&&", "||") and (self.has_effects(e.right) or not _is_simple(e.right)):
            # the right side only where the left does not decide: skipped when no lane needs
            # it (`t > 0.0 && t < best` in a tile where every t is -1)
            return self.short_circuit(e, mask)
        left, right = self.exprs([e.left, e.right], mask)
        lt, rtp = self.type_of(e.left), self.type_of(e.right)
        if op in ("==", "!="):
            if lt.is_scalar and rtp.is_scalar:
                return f"rt.{'eq' if op == '==' else 'ne'}({left}, {right})"
            return f"rt.{'equal_all' if op == '==' else 'nequal_all'}({left}, {right})"
        if op == "%" and self.model.const_value(e.left) is not None and self.model.const_value(e.right) is not None:
            return f"rt.rem_const({left}, {right})"
        if op not in _BIN_METHODS and op != "%":
            raise _error(f"the operator '{op}' is not supported", e)
        return self.binary_values(op, lt, rtp, left, right)

    def short_circuit(self, e: A.Binary, mask: str | None) -> str:
        left = self.tmp(self.expr(e.left, mask))
        res = self.fresh("t")
        self.emit(f"{res} = {self.const_bool(e.op == '||')}")
        m = self.fresh("m")
        self.emit(f"{m} = X.{'and_' if e.op == '&&' else 'andnot'}({mask}, {left})")
        self.emit(f"if X.live({m}):")
        self.indent += 1
        right = self.expr(e.right, m)
        self.emit(f"{res} = {right}")
        self.indent -= 1
        return f"rt.{'and_' if e.op == '&&' else 'or_'}({left}, {res})"

    def _print_Unary(self, e: A.Unary, mask: str | None) -> str:
        if e.op in ("++", "--"):
            return self.incdec(e, mask, want_value=True)
        v = self.expr(e.operand, mask)
        if e.op == "-":
            return f"(-{v})" if self.type_of(e.operand).base == "float" else f"rt.neg({v})"
        if e.op == "+":
            return v
        if e.op == "!":
            return f"rt.not_({v})"
        if e.op == "~":
            return f"rt.bit_not({v})"
        raise _error(f"the operator '{e.op}' is not supported", e)

    def _print_Postfix(self, e: A.Postfix, mask: str | None) -> str:
        return self.incdec(e, mask, want_value=True)

    def incdec(self, e: Any, mask: str | None, want_value: bool) -> str:
        lv = self.lvalue(e.operand, mask)
        old = self.tmp(self.read(lv)) if (want_value and isinstance(e, A.Postfix)) else self.read(lv)
        fn = "inc" if e.op == "++" else "dec"
        new = f"rt.{fn}({old})"
        if want_value and isinstance(e, A.Unary):
            new = self.tmp(new)
        self.write(lv, new, mask)
        return old if isinstance(e, A.Postfix) else new

    def _print_Assignment(self, e: A.Assignment, mask: str | None) -> str:
        return self.assignment(e, mask, want_value=True)

    def assignment(self, e: A.Assignment, mask: str | None, want_value: bool) -> str:
        lv = self.lvalue(e.target, mask)
        value = self.expr(e.value, mask)
        if e.op != "=":
            value = self.binary_values(e.op[:-1], self.type_of(e.target), self.type_of(e.value),
                                       self.read(lv), value)
        if want_value:
            value = self.tmp(value)
        self.write(lv, value, mask)
        return value

    @staticmethod
    def binary_values(op: str, lt: Any, rtp: Any, left: str, right: str) -> str:
        """`left op right` for operand types lt, rtp (matrix products by shape)."""
        if op == "*" and (lt.is_matrix or rtp.is_matrix):
            if lt.is_matrix and rtp.is_matrix:
                return f"rt.mat_mul_mat({left}, {right})"
            if lt.is_matrix and rtp.is_vector:
                return f"rt.mat_mul_vec({left}, {right})"
            if lt.is_vector and rtp.is_matrix:
                return f"rt.vec_mul_mat({left}, {right})"
        if op == "%":
            return f"rt.rem({left}, {right})"
        if op == "*" and lt.base == "float" and rtp.base == "float":
            return f"rt.fmul({left}, {right})"  # NaN times a constant zero is 0 (Runtime.fmul)
        if op in _FLOAT_OPERATORS and lt.base == "float" and rtp.base == "float":
            # float operands are always arrays of the render dtype: NumPy's operator is exactly
            # the runtime's ufunc (rt.add is np.add ...), without a Python call per operation
            return f"({left} {op} {right})"
        return f"rt.{_BIN_METHODS[op]}({left}, {right})"

    def _print_Ternary(self, e: A.Ternary, mask: str | None) -> str:
        fs = self.fn
        effects = self.has_effects(e.then) or self.has_effects(e.else_)
        if not effects:
            if fs is not None and fs.uni is not None and fs.uni.is_uniform(e.cond):
                c = self.expr(e.cond, mask)
                if self.needs_hoist(e.then) or self.needs_hoist(e.else_):
                    c = self.tmp(c)
                a = self.expr(e.then, mask)
                b = self.expr(e.else_, mask)
                return f"({a} if X.true({c}) else {b})"
            c, a, b = self.exprs([e.cond, e.then, e.else_], mask)
            return f"rt.select({c}, {a}, {b})"
        c = self.tmp(self.expr(e.cond, mask))
        t = self.type_of(e)
        res_a, res_b = self.fresh("t"), self.fresh("t")
        for res, branch, how in ((res_a, e.then, "and_"), (res_b, e.else_, "andnot")):
            self.emit(f"{res} = {self.zero(t, e)}")
            m = self.fresh("m")
            self.emit(f"{m} = X.{how}({mask}, {c})")
            self.emit(f"if X.live({m}):")
            self.indent += 1
            self.emit(f"{res} = {self.expr(branch, m)}")
            self.indent -= 1
        return f"rt.select({c}, {res_a}, {res_b})"

    def _print_Sequence(self, e: A.Sequence, mask: str | None) -> str:
        for x in e.exprs[:-1]:
            self.effect(x, mask)
        return self.expr(e.exprs[-1], mask)

    def _print_Index(self, e: A.Index, mask: str | None) -> str:
        base, idx = self.exprs([e.base, e.index], mask)
        cv = self.model.const_value(e.index)
        bt = self.type_of(e.base)
        if isinstance(cv, int) and not isinstance(cv, bool):
            if bt.is_array and bt.element.is_struct:
                return f"rt.index({base}, {cv})"
            return f"{base}[{cv}]"
        return f"rt.index({base}, {idx})"

    def _print_Field(self, e: A.Field, mask: str | None) -> str:
        base = self.expr(e.base, mask)
        bt = self.type_of(e.base)
        if bt.is_struct:
            return f'rt.field({base}, "{self.member(e.name, e)}")'
        idx = self.model.swizzle_indices(e)
        if bt.is_scalar:
            return base if len(idx) == 1 else f'rt.swizzle({base}, "{"x" * len(idx)}")'
        if len(idx) == 1:
            return f"{base}[{idx[0]}]"
        return f'rt.swizzle({base}, "{"".join("xyzw"[i] for i in idx)}")'

    def _print_MethodCall(self, e: A.MethodCall, mask: str | None) -> str:
        bt = self.type_of(e.base)
        if e.name == "length":
            if bt.is_array:
                return self.const_int(bt.array_size, False)
            if bt.is_vector:
                return self.const_int(bt.size, False)
            if bt.is_matrix:
                return self.const_int(bt.cols, False)
        raise _error(f"the method '.{e.name}()' is not supported", e)

    def _print_Call(self, e: A.Call, mask: str | None) -> str:
        tgt = self.model.call_target(e)
        if _is_constructor(tgt):
            return self.constructor(e, tgt[1], mask)
        if _is_symbol(tgt):
            return self.user_call(e, tgt, mask)
        if tgt is None:
            raise _error(f"the call of '{e.callee}' was not resolved by the checker", e)
        return self.builtin_call(e, tgt, mask)

    def constructor(self, e: A.Call, t: Any, mask: str | None) -> str:
        args = self.exprs(e.args, mask)
        if t.is_array:
            return f"rt.array({', '.join(args)})"
        if t.is_struct:
            fields = ", ".join(f"{self.member(fname, e)}={a}" for (fname, _), a in zip(t.fields, args))
            return f'rt.struct("{self.struct_name(t)}", {fields})'
        if t.is_scalar:
            at = self.type_of(e.args[0])
            a = args[0]
            if at.is_matrix:
                a = f"{a}[0][0]"
            elif at.is_vector:
                a = f"{a}[0]"
            if at.base == t.base:
                return a
            return f"rt.to_{t.base}({a})"
        if t.is_vector:
            fn = {"float": "vec", "int": "ivec", "uint": "uvec", "bool": "bvec"}[t.base]
            return f"rt.{fn}({t.size}, {', '.join(args)})"
        if t.is_matrix:
            return f"rt.mat({t.cols}, {t.rows}, {', '.join(args)})"
        raise _error(f"constructing '{t}' is not supported", e)

    def builtin_call(self, e: A.Call, ov: Any, mask: str | None) -> str:
        name = ov.name
        if getattr(ov, "category", None) == B.TEXTURE or name.startswith("texture") or name.startswith("texel"):
            if name not in _TEXTURE_FUNCTIONS or str(self.type_of(e.args[0])) != "sampler2D":
                raise _error(f"{name}(): this texture lookup is not supported by the NumPy backend yet", e,
                             help="render this shader with --backend gl")
            width = ", width=S.width" if name in _IMPLICIT_LOD else ""
            return f"rt.{name}({', '.join(self.exprs(e.args, mask))}{width})"  # textures.py
        quals = list(getattr(ov, "qualifiers", ()) or ())
        if name == "modf":
            x = self.expr(e.args[0], mask)
            lv = self.lvalue(e.args[1], mask)
            r = self.tmp(f"rt.modf({x})")
            self.write(lv, f"{r}[1]", mask)
            return f"{r}[0]"
        if any(q == "out" for q in quals):
            raise _error(f"{name}() with an out parameter is not supported", e)
        args = self.exprs(e.args, mask)
        if name == "mix":
            args += nir_fold.mix_hint(self, e)  # Mesa's flrp lowering: see nir_fold
        if name == "pow":
            rewritten = self.pow_rewrite(e, args)
            if rewritten is not None:
                return rewritten
        method = _RUNTIME_NAMES.get(name, name)
        from .runtime import Runtime

        if not _IDENT.match(method) or not hasattr(Runtime, method):
            raise _error(f"the built-in {name}() is not supported by the NumPy backend", e)
        if name in _DERIVATIVES:
            args.append("S.width")
        return f"rt.{method}({', '.join(args)})"

    def pow_rewrite(self, e: A.Call, args: list[str]) -> str | None:
        """Mesa's compile-time rewrites of `pow` (see `Runtime.pow_const`): a constant exponent
        with a component of 1.0, 2.0, 4.0 or +0.0 becomes products (`rt.pow_const`), a constant
        base of all ones becomes 1 (`rt.pow_one`); None: the run-time `rt.pow`."""
        base = self.model.const_value(e.args[0])
        if base is not None and all(v == 1.0 for v in _components(base)):
            return f"rt.pow_one({args[1]})"
        c = self.model.const_value(e.args[1])
        if c is None:
            return None
        comps = [float(v) for v in _components(c)]
        if not any(v in (1.0, 2.0, 4.0) or (v == 0.0 and str(v) == "0.0") for v in comps):
            return None
        lit = repr(comps[0]) if not isinstance(c, tuple) else "(" + ", ".join(map(repr, comps)) + ")"
        return f"rt.pow_const({args[0]}, {lit})"

    def user_call(self, e: A.Call, fn: Any, mask: str | None) -> str:
        uni = self.fn.uni if self.fn is not None else None
        call_mask = mask
        if uni is not None and self.facts.closed(fn) and all(uni.is_uniform(a) for a in e.args):
            call_mask = None  # same arguments in every lane: compute once, for all lanes
        args: list[str] = []
        outs: list[tuple[int, LValue]] = []
        directions = [d for _, _, d in fn.params]
        for a, d in zip(e.args, directions):  # read after earlier side effects, as exprs()
            if d == "in":
                args.append(self.expr(a, mask))
            else:
                lv = self.lvalue(a, mask)
                outs.append((len(outs) + 1, lv))
                if d == "inout":
                    args.append(self.tmp(self.read(lv)))
        call = self.call_text(e, fn, call_mask, args, mask)
        if not outs:
            return call
        r = self.fresh("t")
        self.emit(f"{r} = {call}")
        for k, lv in outs:
            self.write(lv, f"{r}[{k}]", mask)
        return f"{r}[0]"

    def call_text(self, e: A.Call, fn: Any, call_mask: str | None, args: list[str], mask: str | None) -> str:
        """The Python call of user function `fn` (the tracing transpiler, trace.py, wraps it)."""
        return f"{self.fn_name(fn)}(S, {call_mask}{''.join(', ' + x for x in args)})"

    # -- l-values ------------------------------------------------------------------------------
    def lvalue(self, e: Any, mask: str | None) -> LValue:
        if isinstance(e, A.Identifier):
            sym = self.model.symbol_of(e)
            return LValue(self.var_name(sym, e), sym.type)
        if isinstance(e, A.Field):
            lv = self.lvalue(e.base, mask)
            bt = self.type_of(e.base)
            if bt.is_struct:
                lv.path.append(("field", self.member(e.name, e)))
            else:
                idx = self.model.swizzle_indices(e)
                if bt.is_scalar:
                    return lv
                if lv.path and lv.path[-1][0] == "swz":
                    prev = lv.path.pop()[1]
                    idx = tuple(prev[i] for i in idx)
                lv.path.append(("swz", tuple(idx)))
            return lv
        if isinstance(e, A.Index):
            lv = self.lvalue(e.base, mask)
            cv = self.model.const_value(e.index)
            if isinstance(cv, int) and not isinstance(cv, bool):
                idx = str(cv)
            else:
                idx = self.tmp(self.expr(e.index, mask))
            lv.path.append(("index", idx))
            return lv
        raise _error("this expression cannot be assigned to", e)

    def read(self, lv: LValue, upto: int | None = None) -> str:
        v = lv.base
        for item in lv.path[:upto]:
            kind, arg = item
            if kind == "field":
                v = f'rt.field({v}, "{arg}")'
            elif kind == "swz":
                v = f"{v}[{arg[0]}]" if len(arg) == 1 else f'rt.swizzle({v}, "{"".join("xyzw"[i] for i in arg)}")'
            else:
                v = f"rt.index({v}, {arg})"
        return v

    def write(self, lv: LValue, value: str, mask: str | None) -> None:
        new = value
        m = mask
        for k in range(len(lv.path) - 1, -1, -1):
            parent = self.read(lv, k)
            kind, arg = lv.path[k]
            if kind == "field":
                new = f'rt.assign_field({parent}, "{arg}", {new}, {m})'
            elif kind == "swz":
                new = f'rt.assign_swizzle({parent}, "{"".join("xyzw"[i] for i in arg)}", {new}, {m})'
            else:
                new = f"rt.assign_index({parent}, {arg}, {new}, {m})"
            m = None
        if lv.path:
            self.emit(f"{lv.base} = {new}")
        else:
            self.assign_stmt(lv.base, new, m)


@dataclass
class Transpiled:
    """The generated module: its source, its metadata and the file name it is registered under."""

    source: str
    meta: dict
    filename: str
    code: Any = None  # the compiled module (compiled once, to check it: see `compile_generated`)


def transpile(model: Any, path: str = "<shader>", keep_alpha: bool = False) -> Transpiled:
    """Generate the Python module of a checked program (model from glslcheck.check); a located
    GlslError when it is too complex for Python (see `PythonLimits`)."""
    tr = Transpiler(model, path, keep_alpha=keep_alpha)
    old = sys.getrecursionlimit()
    sys.setrecursionlimit(max(old, 20000))  # expressions nested as deep as the checker allows
    try:
        source, meta = tr.module()
    except RecursionError:
        where = getattr(tr, "where", None)
        raise too_complex("it is nested too deeply", getattr(where, "loc", None) or Location(path, 1, 1)) from None
    finally:
        sys.setrecursionlimit(old)
    filename = f"<glslcheck-numpy {_printable(path, 200)}>"
    return Transpiled(source, meta, filename, compile_generated(source, filename, path))


def transpile_shader(shader: Any, tab: str | None = None) -> Transpiled:
    """Parse, check and transpile a Shadertoy shader (its Image tab, or a plain GLSL file, or the
    Buffer tab `tab`, which keeps its alpha)."""
    from ..parse import parse_shader

    if tab is None:
        tab = "Image" if "Image" in shader.tabs else ("GLSL" if "GLSL" in shader.tabs else "Image")
    pr = parse_shader(shader, tab)
    model = check_program(pr)
    src = shader.tabs.get(tab)
    return transpile(model, src.path if src is not None else shader.root, keep_alpha=tab.startswith("Buffer"))
