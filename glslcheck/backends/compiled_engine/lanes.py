"""Pixels in lockstep: the per-pixel module of codegen.py rewritten so that one call computes a
block of W pixels of a row (`render --backend compiled` moves to it once it pays,
engine.TieredProgram; GLSLCHECK_COMPILED_LANES=8 or 16 starts with it).

Why: the per-pixel functions run one pixel's chain of dependent float operations at a time,
while llvmpipe runs 8 pixels an AVX2 instruction. Here every per-pixel scalar becomes W locals
(`x` -> `x__0 .. x__{W-1}`), each statement is written once per lane, one after the other, so
the W independent chains overlap in the CPU's pipelines and LLVM's SLP vectorizer (switched on
for these modules, engine.py) can pack them into vector instructions.

How: this is a rewrite of the generated Python (its `ast`), not a second code generator: the
per-pixel module is the reference, and every lane of a statement is that statement with its
names renamed, so each lane computes exactly the per-pixel engine's operations (the bits).

The rewrite in detail (uniform names, uniform arguments and results across calls, control
flow under masks, free writes, branch-free math): docs/compiled-engine.md, "Lockstep lanes".

What is not rewritten (`Unsupported`: the engine falls back to the per-pixel module for that
shader, the result unchanged): statements the per-pixel generator does not write today (an
augmented assignment other than a loop counter, a `for` statement, ...).

Derivatives. codegen writes a dFdx/dFdy leaf as `dfdx(v)` (QUADS = True in the module), which
one pixel a call cannot compute; here a block is then W/2 pixels of two rows, 2x2 quads from an
even x and y (fragCoord.y per lane, no ROW_UNIFORM), and lane k's `dfdx(v)` is the difference
of two lanes of its quad (quad_lanes: llvmpipe's fine derivatives, as the NumPy backend's).
Every lane computes each statement its block runs, also the lanes a divergent branch leaves
out (a masked name keeps their last value), so a derivative taken under a branch reads what its
neighbours computed: bit for bit with the NumPy backend in tests/compiled/test_derivatives.py,
branches, loops and early returns included. At an odd right or top edge the quad's other pixels are
helper pixels past the image (render_source). Such a shader has no per-pixel module to fall
back to: what this rewrite refuses there is an error at the derivative's line (engine.generate).
"""

from __future__ import annotations

import ast
import copy
import gc
from typing import Any

from .constant_globals import reset_kinds, written_state
from .lanes_init import lockstep_init
from .lanes_render import (
    ROW_UNIFORM,
    STATE_LANES,
    math_imports,
    quad_lanes,
    render_source,
    rt_hash,
)
from .lanes_shapes import (
    call_name,
    count_free,
    exits_of,
    index_test,
    is_counter,
    makes_array,
    pure_value,
    straight_arm,
)
from .lanes_slim import hoistable_globals, names_in, slim_function, walk_nodes
from .select_chains import SelectChains, is_temp_write

UNIFORM_STATE = ("uf", "ui", "lc")  # lc: llvmpipe's loop budget, one per block as there
BLOCK_CALLS = ("limited", "tick_end")  # the loop budget's statements (scalar.tick)


class Unsupported(Exception):
    """A construct of the per-pixel module this rewrite does not handle (the engine renders the
    shader per pixel)."""


_QUAD_CALLS = ("dfdx", "dfdy", "qdx", "qdy")  # a difference of two lanes of a quad
_LANE_MARK = "\x00"  # a lane number to come (lanes_of)


class _Rename(ast.NodeTransformer):
    def __init__(self, varying: set[str], k: int | str, quads: int = 0) -> None:
        self.varying = varying
        self.k = k
        self.quads = quads  # W when the block is 2x2 quads (derivatives), else 0

    def visit_IfExp(self, node: ast.IfExp) -> Any:
        """`a if c else b` of pure sides (codegen's `0 if x == 0 else y * x` for a value the NumPy
        backend takes for a constant) as lsel: two basic blocks per lane stop the SLP
        vectorizer from packing the lanes; both sides computed, the same value picked."""
        self.generic_visit(node)  # (in place: it returns `node`)
        if pure_value(node):
            return ast.copy_location(
                ast.Call(ast.Name("lsel", ast.Load()), [node.test, node.body, node.orelse], []),
                node,
            )
        return node

    def visit_BoolOp(self, node: ast.BoolOp) -> Any:
        """`a and b` of pure sides (GLSL's `&&`, `||`, any, all: bools) as `a & b`: Python's
        short circuit is a branch and a block per lane in numba's IR (h38-2d-sprites' DrawGame:
        1,210 blocks, 240 without), which numba's passes walk and which split the lanes' runs
        for the SLP vectorizer; the right side computed also where the left decides (no effect,
        no failure), the same bool."""
        self.generic_visit(node)
        if not pure_value(node):
            return node
        op: ast.operator = ast.BitAnd() if isinstance(node.op, ast.And) else ast.BitOr()
        out = node.values[0]
        for v in node.values[1:]:
            out = ast.BinOp(out, op, v)
        return ast.copy_location(out, node)

    def visit_Call(self, node: ast.Call) -> Any:
        f = node.func
        if (
            self.quads
            and isinstance(f, ast.Name)
            and f.id in _QUAD_CALLS
            and len(node.args) == 1
            and isinstance(node.args[0], ast.Name)
            and node.args[0].id in self.varying
        ):
            # a difference of two lanes of the quad; of a uniform value, lanes_rt.dfdx (0)
            v = node.args[0].id
            assert isinstance(self.k, int)  # (with quads, lanes_of renames lane by lane)
            a, b = quad_lanes(f.id, self.k, self.quads)
            return ast.copy_location(
                ast.BinOp(
                    ast.Name(f"{v}__{a}", ast.Load()), ast.Sub(), ast.Name(f"{v}__{b}", ast.Load())
                ),
                node,
            )
        return self.generic_visit(node)

    def visit_Name(self, node: ast.Name) -> Any:
        if node.id in self.varying:
            return ast.copy_location(ast.Name(f"{node.id}__{self.k}", node.ctx), node)
        return node


class _SharedReads(ast.NodeTransformer):
    """Reads of global state no function writes (a `const` array of structs, a global written
    only by its initializer) read lane 0's copy, `gf__0[k]`: every lane's copy holds the same
    template values, and the read is uniform (one scalar for the block, not W loads). Written:
    the constant slots stored to outside init_globals; a write at a run-time index or by aset
    makes the whole state array written."""

    def __init__(self, functions: Any) -> None:
        self.written = written_state(functions)

    def visit_Subscript(self, node: ast.Subscript) -> Any:
        self.generic_visit(node)
        base = node.value
        if not (
            isinstance(node.ctx, ast.Load) and isinstance(base, ast.Name) and base.id in STATE_LANES
        ):
            return node
        written = self.written[base.id]
        if written is None:
            return node
        index = node.slice
        if isinstance(index, ast.Constant) and isinstance(index.value, int):
            if index.value in written:
                return node
        elif written:
            return node
        return ast.copy_location(
            ast.Subscript(ast.Name(f"{base.id}__0", ast.Load()), index, node.ctx), node
        )


class _Fn(SelectChains):
    """One function's rewrite (see the module docstring)."""

    def __init__(self, lanes: Lanes, fn: ast.FunctionDef, uniform: frozenset = frozenset()) -> None:
        self.L = lanes
        self.fn = fn
        self.W = lanes.W
        self.params = [a.arg for a in fn.args.args]
        self.uniform = uniform  # the indices of the parameters the callers pass as one scalar
        self.name = variant_name(fn.name, uniform)
        self.scalar_params = {
            p for i, p in enumerate(self.params) if p in UNIFORM_STATE or i in uniform
        }
        self.varying: set[str] = {p for p in self.params if p not in self.scalar_params}
        self.counts: dict[str, int] = {p: 1 for p in self.params}
        for n in walk_nodes(fn):
            if isinstance(n, ast.Assign):
                for t in n.targets:
                    for x in [t] if not isinstance(t, ast.Tuple) else t.elts:
                        if isinstance(x, ast.Name):
                            self.counts[x.id] = self.counts.get(x.id, 0) + 1
            elif isinstance(n, ast.AugAssign) and isinstance(n.target, ast.Name):
                self.counts[n.target.id] = self.counts.get(n.target.id, 0) + 2
        self.reads: dict[str, int] = {}
        for n in walk_nodes(fn):
            if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load):
                self.reads[n.id] = self.reads.get(n.id, 0) + 1
        self.nret = 0
        for n in ast.walk(fn):
            if isinstance(n, ast.Return) and isinstance(n.value, ast.Tuple):
                self.nret = len(n.value.elts)
        # which result slots are one scalar for the block: every return is in uniform control
        # with a value free of lanes there (optimistic at first, settled by the fixpoint)
        self.ret_uniform = [True] * self.nret
        self.calls: set[tuple[str, frozenset]] = set()  # the callee variants of the last walk

    # -- lanes of expressions ----------------------------------------------------------------
    def is_varying(self, e: Any) -> bool:
        return bool(names_in(e) & self.varying)

    def lanes_of(self, e: Any) -> list[str]:
        """e's text in each lane. A lane differs from lane 0 only in its names' suffixes, so e
        is renamed and unparsed once, with a lane mark no text can hold (a NUL in a name) that
        each lane replaces; a derivative's lanes differ in more (the quad's neighbours) and are
        written one by one."""
        if not self.is_varying(e):
            text = ast.unparse(e)
            return [text] * self.W
        if self.L.quads and any(
            isinstance(n, ast.Call) and isinstance(n.func, ast.Name) and n.func.id in _QUAD_CALLS
            for n in ast.walk(e)
        ):
            return [
                ast.unparse(_Rename(self.varying, k, self.W).visit(copy.deepcopy(e)))
                for k in range(self.W)
            ]
        text = ast.unparse(_Rename(self.varying, _LANE_MARK).visit(copy.deepcopy(e)))
        return [text.replace(_LANE_MARK, str(k)) for k in range(self.W)]

    def lanenames_in(self, name: str) -> list[str]:
        return [f"{name}__{k}" for k in range(self.W)]

    # -- emission ----------------------------------------------------------------------------
    def emit(self, text: str) -> None:
        self.lines.append("    " * self.indent + text)

    def fresh(self, prefix: str) -> str:
        self.n += 1
        return f"_{prefix}{self.n}L"

    def atom(self, text: str) -> str:
        """text as a name or constant (a long call's arguments may not hold control flow:
        Python passes them as one list, which numba reads only without branches)."""
        if text.isidentifier() or text in ("True", "False"):
            return text
        name = self.fresh("a")
        self.emit(f"{name} = {text}")
        return name

    def any_of(self, mask: str) -> str:
        return "(" + " | ".join(self.lanenames_in(mask)) + ")"

    def new_mask(self, prefix: str, texts: list[str]) -> str:
        name = self.fresh(prefix)
        for k, t in enumerate(texts):
            self.emit(f"{name}__{k} = {t}")
        return name

    def mark(self, name: str) -> None:
        if not is_counter(name) and name not in self.varying:
            self.varying.add(name)
            self.changed = True

    # -- the walk ----------------------------------------------------------------------------
    def run(self) -> list[str]:
        """Fixpoint of the varying names, then the rewritten function's lines."""
        for _ in range(100):
            self.changed = False
            self.ret_seen = list(self.ret_uniform)
            self.walk_function()
            if self.ret_seen != self.ret_uniform:
                self.ret_uniform = self.ret_seen
                self.changed = True
            if not self.changed:
                return self.lines
        raise Unsupported("the uniformity fixpoint did not settle")

    def walk_function(self) -> None:
        self.lines: list[str] = []
        self.indent = 1
        self.n = 0
        self.div = False  # divergent control: writes by select under self.mask
        # locals too: False while the only lanes left out are lanes that have returned (they
        # never read this call's locals again), True in a divergent branch or loop
        self.ldiv = False
        self.mask = "m"  # the current region's mask (the function's in uniform control)
        self.loops: list[tuple[str, str, str] | None] = []  # None: a loop of Python's own
        self.guarded: set[int] = set()  # return slots written under a flag (guarded_write)
        self.live = False  # a divergent return happened: `live__k` lanes are still running
        self.defined = set(self.params)  # names written so far in the text
        # with derivatives: each local's (mask, loop depth) at its declaration, its first write
        self.declared: dict[str, tuple[str, int]] = {}
        self.calls = set()
        self.tests: dict[tuple[str, int], str] = {}  # hoisted index tests (hoist_tests)
        self.block(self.fn.body, top=True)

    def block(self, stmts: list, top: bool = False) -> None:
        n0 = len(self.lines)
        i = 0
        while i < len(stmts):
            # a chain starts where a statement follows one that is not a temporary's
            chain = None if i and is_temp_write(stmts[i - 1]) else self.select_chain(stmts, i)
            if chain is None:
                s, i = self.result_copies(stmts, i)
                self.stmt(s, top)
            else:
                i = self.fuse_chain(chain, top)
        if len(self.lines) == n0:
            self.emit("pass")

    def result_copies(self, stmts: list, i: int) -> tuple[Any, int]:
        """stmts[i], and the index of the statement after it. A call's results into temporaries
        (`_t1, _t2 = f(...)`) that the statements right after copy into names (`a = _t1`, each
        temporary read there alone) is the call with those names as its targets, `a, _t2 = f(...)`:
        the same values written to the same names (the arguments are read before either write),
        without W copies a result in the lockstep text."""
        s = stmts[i]
        if not (
            isinstance(s, ast.Assign)
            and len(s.targets) == 1
            and isinstance(s.targets[0], ast.Tuple)
            and call_name(s.value) in self.L.functions
            and all(isinstance(x, ast.Name) for x in s.targets[0].elts)
        ):
            return s, i + 1
        targets = [x.id for x in s.targets[0].elts if isinstance(x, ast.Name)]  # (all are)
        j = i + 1
        while j < len(stmts):
            c = stmts[j]
            if not (
                isinstance(c, ast.Assign)
                and len(c.targets) == 1
                and isinstance(c.targets[0], ast.Name)
                and isinstance(c.value, ast.Name)
                and c.value.id in targets
                and self.reads.get(c.value.id) == 1
                and self.counts.get(c.value.id) == 1
                and c.targets[0].id not in targets
                and not is_counter(c.targets[0].id)
            ):
                break
            targets[targets.index(c.value.id)] = c.targets[0].id
            j += 1
        if j == i + 1:
            return s, j
        folded = ast.Assign(
            [ast.Tuple([ast.Name(x, ast.Store()) for x in targets], ast.Store())], s.value
        )
        return ast.copy_location(folded, s), j

    def refresh(self) -> None:
        """After a statement with exits, the current region loses the lanes that left."""
        loop = (
            next((x for x in reversed(self.loops) if x is not None), None) if self.loops else None
        )
        if not self.div:
            if not self.live:
                return
            self.div = True
            # a returned lane never reads this call's locals again: plain writes, as the NumPy
            # backend's free writes (cpu_core/uniformity.py), whose values a neighbour's
            # derivative reads as llvmpipe computes them in every lane; with derivatives, in a
            # loop masked (a variable declared outside it is a loop-carried register there)
            self.ldiv = self.L.quads and bool(self.loops)
            # a block whose every lane has returned stops here (the rest, loops included,
            # would run for nothing: the sky of a raymarcher after `if (miss) return`)
            self.emit(f"if not {self.any_of('live')}:")
            self.indent += 1
            self.emit_slots_return(self.nret > 0)
            self.indent -= 1
            self.mask = self.new_mask("mr", [f"(m__{k} & live__{k})" for k in range(self.W)])
            return
        terms = []
        if loop is not None:
            act, cont, _ = loop
            terms.append(f"{act}__{{k}}")
            if cont:
                terms.append(f"(not {cont}__{{k}})")  # `not`: no branch (`and`/`or` are two blocks)
        if self.live:
            terms.append("live__{k}")
        if not terms:
            return
        for k in range(self.W):
            self.emit(
                f"{self.mask}__{k} = {self.mask}__{k} & " + " & ".join(t.format(k=k) for t in terms)
            )

    def stmt(self, s: Any, top: bool) -> None:
        method = getattr(self, "_" + type(s).__name__, None)
        if method is None:
            raise Unsupported(f"the statement {type(s).__name__}")
        if isinstance(s, (ast.If, ast.While)):
            self.tests = {}  # a hoisted test is defined in the straight-line run that made it
            method(s, top)
            self.tests = {}
            return
        s = self.hoist_tests(s)
        method(s, top)
        written = {
            n.id for n in walk_nodes(s) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)
        }
        self.tests = {k: v for k, v in self.tests.items() if k[0] not in written}

    def hoist_tests(self, s: Any) -> Any:
        """s with the index tests of its selects (`index_test`) read from names computed once
        before it and kept until the name tested is written or control flow starts or ends: the
        component reads of one element at a run-time index test the same `i == k` W times each
        (the same compare, computed earlier: the same bits; a compare of a name has no effect)."""

        def hoistable(n: Any) -> bool:
            if isinstance(n, ast.IfExp):
                return index_test(n.test)
            return (
                isinstance(n, ast.Call)
                and isinstance(n.func, ast.Name)
                and n.func.id == "lsel"
                and bool(n.args)
                and index_test(n.args[0])
            )

        if not any(hoistable(n) for n in walk_nodes(s)):
            return s
        s = copy.deepcopy(s)
        for n in ast.walk(s):
            if hoistable(n):
                if isinstance(n, ast.IfExp):
                    n.test = ast.Name(self.hoisted(n.test), ast.Load())
                elif isinstance(n, ast.Call):  # lsel(test, ...)
                    n.args[0] = ast.Name(self.hoisted(n.args[0]), ast.Load())
        return s

    def hoisted(self, test: Any) -> str:
        key = (test.left.id, test.comparators[0].value)
        name = self.tests.get(key)
        if name is None:
            name = self.fresh("q")
            if self.is_varying(test):
                self.varying.add(name)  # (a name of this walk's text: not a fixpoint change)
                for k, text in enumerate(self.lanes_of(test)):
                    self.emit(f"{name}__{k} = {text}")
            else:
                self.varying.discard(name)
                self.emit(f"{name} = {ast.unparse(test)}")
            self.tests[key] = name
        return name

    def _Pass(self, s: Any, top: bool) -> None:
        self.emit("pass")

    def _Raise(self, s: Any, top: bool) -> None:
        if self.is_varying(s):
            raise Unsupported("a raise of lane values")
        self.emit(ast.unparse(s))

    def _Expr(self, s: ast.Expr, top: bool) -> None:
        v = s.value
        if isinstance(v, ast.Constant):
            self.emit(ast.unparse(s))
            return
        name = call_name(v)
        if name in self.L.functions and isinstance(v, ast.Call):  # (a name: a call)
            self.user_call(v, [])
            return
        if name in BLOCK_CALLS:  # once for the block, when one of its lanes does it
            self.emit((f"if {self.any_of(self.mask)}: " if self.div else "") + ast.unparse(s))
            return
        if name == "aset" and isinstance(v, ast.Call):
            dst = v.args[0]
            if not isinstance(dst, ast.Name):
                raise Unsupported("aset of an expression")
            self.mark(dst.id)  # arrays are per lane
            self.masked_store(dst.id, v)
            return
        raise Unsupported(f"the call statement {name}")

    def masked_store(self, base: str, stmt_or_expr: Any) -> None:
        """A write into an array (aset, a subscript): under the mask unless it is a local in
        uniform control."""
        node = stmt_or_expr if isinstance(stmt_or_expr, ast.stmt) else ast.Expr(stmt_or_expr)
        texts = self.lanes_of(node)
        guard = self.ldiv or base in STATE_LANES
        for k, t in enumerate(texts):
            self.emit(f"if {self.mask}__{k}: {t}" if guard else t)

    def _Assign(self, s: ast.Assign, top: bool) -> None:
        if len(s.targets) != 1:
            raise Unsupported("chained assignments")
        t = s.targets[0]
        v = s.value
        if isinstance(t, ast.Tuple) or (call_name(v) in self.L.functions):
            targets = t.elts if isinstance(t, ast.Tuple) else [t]
            if call_name(v) not in self.L.functions or not all(
                isinstance(x, ast.Name) for x in targets
            ):
                raise Unsupported("a tuple assignment")
            assert isinstance(v, ast.Call)  # (what has a call's name)
            self.user_call(v, [x.id for x in targets if isinstance(x, ast.Name)])  # (all are)
            return
        if isinstance(t, ast.Subscript):
            if not isinstance(t.value, ast.Name):
                raise Unsupported("a nested subscript")
            self.mark(t.value.id)  # arrays are per lane
            self.masked_store(t.value.id, s)
            return
        if not isinstance(t, ast.Name):
            raise Unsupported("an assignment target")
        name = t.id
        if is_counter(name):
            self.emit(ast.unparse(s))
            return
        if self.masked(name) or self.is_varying(v) or makes_array(v):
            self.mark(name)
        self.write(name, self.lanes_of(v) if name in self.varying else [ast.unparse(v)])

    def write(self, name: str, texts: list[str]) -> None:
        if name not in self.varying:
            self.emit(f"{name} = {texts[0]}")
            return
        # plain: in uniform control, a name written once, or its first write in the text (a
        # declaration, a ternary's first side: the lanes it does not concern read it nowhere);
        # with derivatives also a write in the region and loop its declaration is in: llvmpipe's
        # SSA value, computed in every lane, which a neighbour's derivative reads (`q.x -= k;`
        # after `vec3 q = ...;` in a branch), as the NumPy backend's free writes
        # (cpu_core/uniformity.py); a write in a branch or loop nested inside stays masked
        plain = self.plain_write(name)
        for k, text in enumerate(texts):
            if plain:
                self.emit(f"{name}__{k} = {text}")
            else:
                self.emit(f"{name}__{k} = lsel({self.mask}__{k}, {text}, {name}__{k})")

    def masked(self, name: str) -> bool:
        """Whether a write of `name` here may keep other lanes' values (then it has lanes). A
        name written once is written in every lane (plain: `write`), so a value free of lanes
        keeps it one scalar also in a divergent region; with derivatives it has lanes there
        (a neighbour's difference of it is computed, as the NumPy backend's)."""
        return self.ldiv and (self.counts.get(name, 0) > 1 or bool(self.L.quads))

    def plain_write(self, name: str) -> bool:
        """Whether this write of the varying `name` is plain (`write`), recorded as written."""
        where = (self.mask, len(self.loops))
        if name not in self.defined:
            self.declared[name] = where
        plain = (
            not self.ldiv
            or self.counts.get(name, 0) <= 1
            or name not in self.defined
            or (bool(self.L.quads) and self.declared.get(name) == where)
        )
        self.defined.add(name)
        return plain

    def _AugAssign(self, s: ast.AugAssign, top: bool) -> None:
        if not (isinstance(s.target, ast.Name) and is_counter(s.target.id)):
            raise Unsupported("an augmented assignment")
        self.emit(ast.unparse(s))

    def user_call(self, call: ast.Call, targets: list[str]) -> None:
        name = ast.unparse(call.func)  # (call_name of a call)
        callee = self.L.functions[name]
        params = [a.arg for a in callee.args.args]
        if len(params) != len(call.args) or call.keywords:
            raise Unsupported("a call's arguments")
        mask = self.mask if self.div else "m"
        # arguments free of lanes go as one scalar: the callee's variant for them
        uniform = frozenset(
            i
            for i, (p, a) in enumerate(zip(params, call.args))
            if p not in UNIFORM_STATE and not self.is_varying(a)
        )
        fn = self.L.variant(name, uniform)
        self.calls.add((name, uniform))
        args = self.lanenames_in(mask)
        for p, a in zip(params, call.args):
            if p in fn.scalar_params:
                args.append(self.atom(ast.unparse(a)))
            else:
                args += [self.atom(t) for t in self.lanes_of(a)]
        text = f"{fn.name}({', '.join(args)})"
        if not targets:
            self.emit(text)
            return
        if len(targets) != fn.nret:
            raise Unsupported("a call's results")
        res = [self.fresh("c") for _ in targets]
        for x, uni in zip(targets, fn.ret_uniform):
            if self.masked(x) or not uni:
                self.mark(x)  # a result per lane (or written under a mask)
        # a result whose write would be a plain copy (one scalar into a name free of lanes, a
        # lane into its lane) is the call's own target: W copies fewer for numba
        flat: list[str] = []
        after = []
        for x, r, uni in zip(targets, res, fn.ret_uniform):
            if x not in self.varying:
                flat.append(x)
            elif not uni and self.plain_write(x):
                flat += self.lanenames_in(x)
            else:
                flat += [r] if uni else self.lanenames_in(r)
                after.append((x, r, uni))
        self.emit(f"{', '.join(flat)}, = {text}")
        for x, r, uni in after:
            self.write(x, [r] * self.W if uni else self.lanenames_in(r))

    def _If(self, s: ast.If, top: bool) -> None:
        exits = exits_of([s])
        if not self.is_varying(s.test):
            self.emit(f"if {ast.unparse(s.test)}:")
            self.nested(s.body, self.div, self.mask, self.ldiv)
            if s.orelse:
                self.emit("else:")
                self.nested(s.orelse, self.div, self.mask, self.ldiv)
        else:
            base = self.mask if self.div else "m"
            tests = self.lanes_of(s.test)
            # the masks are made before either arm writes the test's names: a name tested, or a
            # test the `then` mask alone reads, is read as it is; a test of both masks computed once
            if all(t.isidentifier() for t in tests):
                conds = tests
            elif s.orelse:
                conds = self.lanenames_in(self.new_mask("c", tests))
            else:
                conds = [f"({t})" for t in tests]
            then = self.new_mask("mt", [f"({base}__{k} & {c})" for k, c in enumerate(conds)])
            other = None
            if s.orelse:
                other = self.new_mask(
                    "me", [f"({base}__{k} & (not {c}))" for k, c in enumerate(conds)]
                )
            for arm, mask in ((s.body, then), (s.orelse, other)):
                if mask is None:
                    continue
                if straight_arm(arm):  # computed in every lane, written under the mask
                    self.nested(arm, True, mask, True, flat=True)
                else:
                    self.emit(f"if {self.any_of(mask)}:")
                    self.nested(arm, True, mask, True)
        if exits:
            self.refresh()

    def nested(self, stmts: list, div: bool, mask: str, ldiv: bool, flat: bool = False) -> None:
        """An arm's statements under `mask`, in an `if` of it (indented) or, `flat`, in the
        straight-line run around it."""
        saved = (self.div, self.mask, self.ldiv)
        self.div, self.mask, self.ldiv = div, mask, ldiv
        if not flat:
            self.indent += 1
        self.tests = {}  # (a test hoisted in one arm is not defined in the other)
        n0 = len(self.lines)
        self.block(stmts)
        if flat and len(self.lines) == n0 + 1 and self.lines[-1].strip() == "pass":
            self.lines.pop()
        self.tests = {}
        if not flat:
            self.indent -= 1
        self.div, self.mask, self.ldiv = saved

    def loop_divergent(self, body: list) -> bool:
        """Whether a loop in uniform control has an exit under a divergent condition."""

        def scan(stmts: list, inner: bool) -> bool:
            for s in stmts:
                if isinstance(s, ast.If):
                    ex = exits_of(s.body) | exits_of(s.orelse)
                    if inner:
                        ex &= {"return"}
                    if self.is_varying(s.test) and ex:
                        return True
                    if scan(s.body, inner) or scan(s.orelse, inner):
                        return True
                elif isinstance(s, ast.While):
                    if "return" in exits_of(s.body) and self.loop_divergent(s.body):
                        return True
                    if scan(s.body, True):
                        return True
            return False

        return scan(body, False)

    def _While(self, s: ast.While, top: bool) -> None:
        if not (isinstance(s.test, ast.Constant) and s.test.value is True) or s.orelse:
            raise Unsupported("a while loop with a condition")
        exits = exits_of(s.body)
        # a plain loop also after returns (the returned lanes run it for nothing), unless it can
        # return: under a mask a return does not leave the Python loop
        if (
            not self.ldiv
            and not self.loop_divergent(s.body)
            and not (self.div and "return" in exits)
        ):
            self.emit("while True:")
            self.loops.append(None)
            self.indent += 1
            self.block(s.body)
            self.indent -= 1
            self.loops.pop()
            if "return" in exits:
                self.refresh()
            return
        saved = (self.div, self.mask, self.ldiv)
        base = self.mask if self.div else "m"
        act = self.new_mask("act", [f"{base}__{k}" for k in range(self.W)])
        cont = self.fresh("cont") if "continue" in exits else ""
        self.emit("while True:")
        self.indent += 1
        if cont:
            for k in range(self.W):
                self.emit(f"{cont}__{k} = False")
        body = self.new_mask("mb", [f"{act}__{k}" for k in range(self.W)])
        self.loops.append((act, cont, body))
        self.div, self.mask, self.ldiv = True, body, True
        for st in s.body:
            self.stmt(st, False)
            ex = exits_of([st])
            if ex:
                self.refresh()
                self.emit(f"if not {self.any_of(act)}:")
                self.emit("    break")
                if "continue" in ex:
                    self.emit(f"if not {self.any_of(self.mask)}:")
                    self.emit("    continue")
        self.loops.pop()
        self.indent -= 1
        self.div, self.mask, self.ldiv = saved
        if "return" in exits:
            self.refresh()

    def _Break(self, s: Any, top: bool) -> None:
        loop = self.loops[-1] if self.loops else None
        if loop is None:
            self.emit("break")
            return
        act = loop[0]
        for k in range(self.W):
            self.emit(f"{act}__{k} = {act}__{k} & (not {self.mask}__{k})")

    def _Continue(self, s: Any, top: bool) -> None:
        loop = self.loops[-1] if self.loops else None
        if loop is None:
            self.emit("continue")
            return
        cont = loop[1]
        for k in range(self.W):
            self.emit(f"{cont}__{k} = {cont}__{k} | {self.mask}__{k}")

    def _Return(self, s: ast.Return, top: bool) -> None:
        v = s.value
        elts = v.elts if isinstance(v, ast.Tuple) else None
        if elts is None and not (isinstance(v, ast.Constant) and v.value == 0):
            raise Unsupported("a return value")
        if not self.div and not self.live:
            if elts is None:
                self.emit("return 0")
            else:
                flat = []
                for i, e in enumerate(elts):
                    if self.is_varying(e):
                        self.ret_seen[i] = False
                    flat += (
                        [self.atom(ast.unparse(e))]
                        if self.ret_uniform[i]
                        else [self.atom(t) for t in self.lanes_of(e)]
                    )
                self.emit(f"return ({', '.join(flat)},)")
            return
        if elts is not None:
            self.ret_seen[:] = [False] * len(self.ret_seen)  # the return slots are per lane
            for i, e in enumerate(elts):  # the first slot write in the text is plain (see write)
                first = f"_r{i}" not in self.defined
                self.defined.add(f"_r{i}")
                texts = self.lanes_of(e)
                if i in self.guarded or (first and self.loops):
                    self.guarded_write(i, texts)
                    continue
                for k, text in enumerate(texts):
                    self.emit(
                        f"_r{i}__{k} = {self.first_slot_value(k, text)}"
                        if first
                        else f"_r{i}__{k} = lsel({self.mask}__{k}, {text}, _r{i}__{k})"
                    )
        if top and not self.loops:
            self.emit_slots_return(elts is not None)
            return
        self.live = True  # from here on, `live__k`: the lanes that have not returned
        for k in range(self.W):
            self.emit(f"live__{k} = live__{k} & (not {self.mask}__{k})")
        for loop in self.loops:
            if loop is not None:
                for k in range(self.W):
                    self.emit(f"{loop[0]}__{k} = {loop[0]}__{k} & (not {self.mask}__{k})")

    def guarded_write(self, i: int, texts: list[str]) -> None:
        """A slot whose first write in the text is inside a loop: the write that runs first (on
        whichever pass, from whichever return) is plain, every later one keeps the lanes that
        returned before. A flag set at the function's top tells them apart (the slot's type is
        not known here to start it with a value of its own)."""
        flag = f"_rs{i}"
        if i not in self.guarded:
            self.guarded.add(i)
            self.lines.insert(0, "    " + f"{flag} = False")
        self.emit(f"if not {flag}:")  # (numba reads the plain write first: it defines the slot)
        for k, text in enumerate(texts):
            self.emit(f"    _r{i}__{k} = {self.first_slot_value(k, text)}")
        self.emit("else:")
        for k, text in enumerate(texts):
            self.emit(f"    _r{i}__{k} = lsel({self.mask}__{k}, {text}, _r{i}__{k})")
        self.emit(f"{flag} = True")

    def first_slot_value(self, k: int, text: str) -> str:
        """Lane k's first write of a return slot. With derivatives, a neighbour reads a call's
        result in the lanes its mask leaves out (a plain write of it after a divergent return):
        there the slot holds zero until a return writes it, as the NumPy backend's `_rv` and
        llvmpipe's value (tests/gl: a loop NIR unrolls); else no lane reads it, and it is plain."""
        if not self.L.quads:
            return text
        return f"lsel({self.mask}__{k}, {text}, lzero({text}))"

    def emit_slots_return(self, value: bool) -> None:
        if not value:
            self.emit("return 0")
            return
        flat = [f"_r{i}__{k}" for i in range(self.nret) for k in range(self.W)]
        self.emit(f"return ({', '.join(flat)},)")

    # -- the function ------------------------------------------------------------------------
    def source(self) -> str:
        lines = self.lines
        params = self.lanenames_in("m")
        for p in self.params:
            params += [p] if p in self.scalar_params else self.lanenames_in(p)
        head = [f"def {self.name}({', '.join(params)}):"]
        for p in self.params:  # a parameter passed as one scalar and written with lane values
            if (
                p in self.scalar_params and p in self.varying
            ):  # (`ro += rd * t`): its lanes start from it
                head += [f"    {p}__{k} = {p}" for k in range(self.W)]
        if any("live__0" in line for line in lines):
            head += [f"    live__{k} = True" for k in range(self.W)]
        return "\n".join(head + lines)


def variant_name(name: str, uniform: frozenset) -> str:
    """A function's name in the lockstep module, with the indices of the parameters passed as
    one scalar for the block (`f_rad__u0__s0`)."""
    return name if not uniform else name + "__s" + "_".join(str(i) for i in sorted(uniform))


class Lanes:
    """`Lanes(source, W).module()`: the per-pixel module's source rewritten for blocks of W."""

    def __init__(self, source: str, width: int) -> None:
        self.tree = ast.parse(source)
        self.W = width
        # derivatives (codegen writes dFdx as `dfdx(v)`, QUADS = True): a block is 2x2 quads,
        # W/2 pixels of two rows, and fragCoord.y is per lane
        self.quads = any(
            isinstance(n, ast.Assign)
            and isinstance(n.targets[0], ast.Name)
            and n.targets[0].id == "QUADS"
            for n in self.tree.body
        )
        if self.quads and width % 4:
            raise Unsupported(
                f"derivatives in blocks of {width} lanes (2x2 quads need a multiple of 4)"
            )
        self.functions = {
            f.name: f
            for f in self.tree.body
            if isinstance(f, ast.FunctionDef)
            and f.name not in ("init_globals", "render_rows", "rows_loop", "globals_template")
        }
        shared = _SharedReads(self.functions.values())
        for f in self.functions.values():
            shared.visit(f)
        self.resets = reset_kinds(shared.written)  # the state reset before each block
        self.variants: dict[tuple[str, frozenset], _Fn] = {}
        self.pending: set[tuple[str, frozenset]] = set()

    def variant(self, name: str, uniform: frozenset) -> _Fn:
        """The rewrite of function `name` with the parameters at `uniform` one scalar for the
        block (made once; GLSL has no recursion, so a callee settles before its caller)."""
        key = (name, uniform)
        fn = self.variants.get(key)
        if fn is None:
            if key in self.pending:
                raise Unsupported("a recursive call")
            self.pending.add(key)
            fn = _Fn(self, self.functions[name], uniform)
            fn.run()
            self.pending.discard(key)
            self.variants[key] = fn
        return fn

    def entry(self) -> tuple[str, frozenset]:
        """shade, with the parameters that are the same for every pixel of a block (a block is
        W pixels of one row: fragCoord's and the pixel centre's y) passed as one scalar."""
        if "shade" not in self.functions:
            raise Unsupported("a module without shade")
        params = [a.arg for a in self.functions["shade"].args.args]
        if self.quads:  # two rows a block
            return "shade", frozenset()
        return "shade", frozenset(i for i, p in enumerate(params) if p in ROW_UNIFORM)

    def reachable(self, more: tuple = ()) -> list[_Fn]:
        """The variants the entry's final code calls (and the keys `more`), callees first."""
        order: list[_Fn] = []
        seen: set = set()

        def visit(key: tuple[str, frozenset]) -> None:
            if key in seen:
                return
            seen.add(key)
            fn = self.variant(*key)
            for callee in sorted(fn.calls, key=lambda c: (c[0], sorted(c[1]))):
                visit(callee)
            order.append(fn)

        for key in [self.entry(), *more]:
            visit(key)
        return order

    def module(self) -> str:
        out: list[str] = []
        made = lockstep_init(self)
        if made is None:
            raise Unsupported("a call of a global initializer's")
        init, keys = made
        variants = self.reachable(keys)
        constants, own = hoistable_globals(self.tree)
        own |= {fn.name for fn in variants}  # (called as numba's dispatchers: not hoisted)
        texts = {fn.name: fn.source() for fn in variants}
        free = count_free(
            texts, {fn.name: {self.variants[c].name for c in fn.calls} for fn in variants}
        )
        free.add(self.variant(*self.entry()).name)  # shade: makes no array, returns none
        functions = [
            ("@jit_loop\n" if fn.name in free else "@jit\n")
            + slim_function(texts[fn.name], constants, own)
            for fn in variants
        ]
        for node in self.tree.body:
            if isinstance(node, ast.FunctionDef):
                if node.name == "shade":
                    out += functions
                elif node.name == "init_globals":
                    out.append(init)
                elif node.name == "globals_template":
                    out.append(ast.unparse(node))
                continue
            if (
                isinstance(node, ast.ImportFrom)
                and node.module == "glslcheck.backends.compiled_engine.scalar"
            ):
                out += math_imports()
                names = "lsel, lzero, dfdx, dfdy, qdx, qdy" if self.quads else "lsel"
                out.append(
                    f"from glslcheck.backends.compiled_engine.lanes_rt import {names}  # "
                    f"{rt_hash()}"
                )
                continue
            if (
                isinstance(node, ast.ImportFrom)
                and node.module == "glslcheck.backends.compiled_engine.lanes_rt"
            ):
                continue  # the per-pixel module's lsel import: the line above, with the hash
            out.append(ast.unparse(node))
        out.append(f"LANES = {self.W}  # pixels per call of shade")
        shade = self.variants[self.entry()]
        render = render_source(
            self.W, self.resets, shade.name, shade.scalar_params, shade.ret_uniform, self.quads
        )
        out.append(render if "lc" in shade.params else render.replace("uf, ui, lc,", "uf, ui,"))
        return "\n\n".join(out) + "\n"


def lanes_module(source: str, width: int = 8) -> str:
    """The per-pixel module `source` (codegen.Codegen.module) for blocks of `width` pixels;
    Unsupported when it has a construct this rewrite does not handle."""
    # the rewrite makes and drops some hundred thousand syntax nodes, none in a cycle: Python's
    # cycle collector, run every 700 allocations, would walk them for nothing (an eighth of the
    # largest module's rewrite); paused here, then back as it was (freed by their counts)
    collecting = gc.isenabled()
    gc.disable()
    try:
        return Lanes(source, width).module()
    except RecursionError:
        raise Unsupported("an expression nested too deep") from None
    finally:
        if collecting:
            gc.enable()
