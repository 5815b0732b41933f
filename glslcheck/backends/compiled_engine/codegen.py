"""The GLSL-to-numba code generator: a checked Shadertoy program becomes a Python module of
scalar functions, one call per pixel.

Where backends/numpy_engine/transpile runs every pixel of a tile as lanes of NumPy arrays, this
generator writes the program for ONE pixel, and numba compiles it (nopython, no fast-math,
error_model="numpy": x / 0 is IEEE). Types and symbols come from glslcheck.semantics, as in the
NumPy transpiler; every operation computes what glslcheck/backends/numpy_engine/runtime.py computes for
one lane (the scalar functions are backends/compiled_engine/scalar.py).

Values
======

Every GLSL value is flattened to its scalar leaves: a float is one float32 Python value, a vec3
three, a mat3 nine (column-major), a struct the leaves of its fields in order. An array is one
numba array per leaf of its element type (`vec3 a[4]` is three float32 arrays of 4). A value in
the generator (`Val`) is its type and its parts: Python expressions for scalar leaves, `Arr` for
array leaves. Generated names: locals `v_<name>_<k>` (leaf k), arrays `a_<name>_<k>`,
temporaries `_t<n>`, module constants `F_`/`I_`/`U_`. Literals are float32/int32/uint32
module constants (a Python float in numba is float64 and would promote), and every int32 or
uint32 operation is cast back to its type (numba widens int32 arithmetic to int64): GLSL's
wrap-around.

Global variables and Shadertoy's uniforms live in per-pixel state arrays, one per scalar type
(`gf` float32, `gi` int32, `gu` uint32, `gb` bool; uniforms `uf`, `ui`); a function receives
those it reads or writes, itself or through its callees, as its first parameters (passing an
array costs numba two atomic reference-count updates a call, so a distance function that reads
no global gets none); the globals are reset to their initial values before each pixel.

Control flow is Python's own: `if`, `while` loops for GLSL's three loops (a `continue` in a
`for` runs the step first; in a `do`-`while` it tests the condition), `return` anywhere,
`&&`/`||`/`?:` evaluate only the side they need. Each loop counts its passes and stops after
transpile.LOOP_CAP by raising LoopCapError(its id) (the engine raises the located error). A user
function returns a tuple: its value's leaves, then the leaves of its out/inout parameters,
which the caller writes back left to right.

Not supported yet (a GlslError at the construct, "not supported by the compiled engine yet"):
textures and channels, derivatives, discard, switch, arrays of structs holding arrays,
inverse() of 3x3 and 4x4 matrices, and the packing built-ins.

What the NumPy backend does that this generator does not copy: Mesa's reassociations
(backends/numpy_engine/nir_fold.py, transpile/call_fold.py, inline.py) and its run-time test of
"a value the same in every lane counts as a constant" (Runtime.fmul/fadd/pow on values of one
lane): here only compile-time constants (`model.const_value`) fold, so `x * 0.0` is 0 for a
NaN x, as there, but `float k = 0.0; x * k` multiplies. docs/performance.md measures what that
changes.
"""

from __future__ import annotations

import ast as pyast
import math
import re
from dataclasses import dataclass
from typing import Any

from ...frontend import syntax as A
from ...language import glsl_types as T
from ...semantics.model import Constructor, Symbol
from ...base.diagnostics import Diagnostic, GlslError, Location

RULE = "compiled-engine"
NOT_YET = "not supported by the compiled engine yet"
# Ternaries computed on both sides (Codegen._speculable): a side of more than _SPECULATE_LINES
# pure temporaries (pure_expr) keeps its branch (its work would be paid where it is not taken).
_PURE_LINE = re.compile(r"^( *)_t[0-9]+ = (.*)$")
_SPECULATE_LINES = 4
_PURE_NODES = (pyast.Name, pyast.Constant, pyast.BinOp, pyast.UnaryOp, pyast.Compare, pyast.IfExp, pyast.BoolOp,
               pyast.Load, pyast.Add, pyast.Sub, pyast.Mult, pyast.Div, pyast.USub, pyast.UAdd, pyast.Not,
               pyast.And, pyast.Or, pyast.Eq, pyast.NotEq, pyast.Lt, pyast.LtE, pyast.Gt, pyast.GtE)


def pure_expr(e: Any) -> bool:
    """A generated expression (its text or its Python ast) that reads names and constants with
    float arithmetic, compares, `and`/`or`/`not` and lsel only: it has no effect and cannot fail
    (error_model="numpy"; this generator wraps int arithmetic in casts, which are calls), so
    computing it where its value is not used changes nothing (codegen's ternaries, lanes.py's
    conditional expressions)."""
    if isinstance(e, str):
        try:
            e = pyast.parse(e, mode="eval").body
        except SyntaxError:
            return False
    for n in pyast.walk(e):
        if isinstance(n, pyast.Call):
            if not (isinstance(n.func, pyast.Name) and n.func.id == "lsel" and not n.keywords):
                return False
        elif not isinstance(n, _PURE_NODES):
            return False
    return True


_ATOM = re.compile(r"^(?:[A-Za-z_][A-Za-z0-9_]*(?:\[[A-Za-z0-9_ +]+\])?|True|False)$")
_KIND_ARRAY = {"float": "gf", "int": "gi", "uint": "gu", "bool": "gb"}
_DTYPE = {"float": "np.float32", "int": "np.int32", "uint": "np.uint32", "bool": "np.bool_"}
_CAST = {"float": "F32", "int": "I32", "uint": "U32", "bool": "bool"}
_SWZ = "xyzw"
STATE = ("gf", "gi", "gu", "gb", "uf", "ui")  # the per-pixel state arrays (see the docstring)
_STATE_NAME = re.compile(r"(?<![\w.])(gf|gi|gu|gb|uf|ui)(?!\w)")
SMALL_ARRAY = 64  # arrays of up to this many scalars are scalars too (no allocation per pixel)


def _error(message: str, node: Any, help: str | None = None) -> GlslError:
    loc = node if isinstance(node, Location) else getattr(node, "loc", None)
    return GlslError(Diagnostic(message, loc, rule=RULE, help=help))


def not_yet(what: str, node: Any) -> GlslError:
    return _error(f"{what}: {NOT_YET}", node, help="render with --backend numpy or gl")


@dataclass
class Arr:
    """An array leaf: elements off .. off+size-1 of the numba array `name`."""

    name: str
    off: int
    size: int
    base: str

    def at(self, idx: str) -> str:
        return f"{self.name}[{idx}]" if not self.off else f"{self.name}[{self.off} + {idx}]"

    def whole(self) -> str:
        """The array as a value: a local array itself, else a copy of its slots."""
        if self.name.startswith(("a_", "_")):
            return self.name
        return f"aslice({self.name}, {self.off}, {self.size})"


@dataclass
class Dyn:
    """A vector component (or matrix column entry) chosen by a run-time index: parts[idx]."""

    idx: str
    parts: list


@dataclass
class Val:
    """A GLSL value in generated code: its type, its leaves, and its compile-time constant
    leaves (None when it is not a constant)."""

    t: Any
    parts: list
    const: list | None = None
    uni: bool = False  # one value for a whole tile in the NumPy backend, taken there for a constant

    @property
    def constlike(self) -> bool:
        return self.const is not None or self.uni


def leaves(t: Any, node: Any) -> list[tuple[str, int | None]]:
    """The scalar leaves of type t: (base type, array size or None)."""
    if t.is_scalar:
        return [(t.base, None)]
    if t.is_vector:
        return [(t.base, None)] * t.size
    if t.is_matrix:
        return [("float", None)] * (t.cols * t.rows)
    if t.is_struct:
        return [leaf for _, ft in t.fields for leaf in leaves(ft, node)]
    if t.is_array:
        inner = leaves(t.element, node)
        if any(n is not None for _, n in inner):
            raise not_yet("an array of structs that hold arrays", node)
        if t.array_size is None:
            raise not_yet("an unsized array", node)
        if t.array_size * len(inner) <= SMALL_ARRAY:  # scalars, leaf by leaf (see the docstring)
            return [(b, None) for b, _ in inner for _ in range(t.array_size)]
        return [(b, t.array_size) for b, _ in inner]
    if t.contains_opaque:
        raise not_yet("textures and channels", node)
    raise not_yet(f"values of type '{t}'", node)


def _flat(v: Any) -> list:
    if isinstance(v, (tuple, list)):
        return [x for item in v for x in _flat(item)]
    return [v]


class FnState:
    def __init__(self, sym: Any, uni: Any = None) -> None:
        self.sym = sym
        self.uni = uni  # numpy_backend's Uniformity of the function (None: global initializers)
        self.outs: list = []  # the parts of out/inout parameters, returned after the value
        self.loops: list[tuple[str, Any]] = []  # (kind, continue emitter)


class Codegen:
    """`Codegen(model, path).module()` -> the generated Python source."""

    def __init__(self, model: Any, path: str, fma: bool, float_to_uint: str) -> None:
        from ..numpy_engine.transpile.facts import Facts

        self.model = model
        self.path = path
        self.fma = fma
        self.float_to_uint = float_to_uint
        self.entry = model.entry
        if self.entry is None:
            raise _error("the program has no mainImage (or main) to render", Location(path, 1, 1))
        self.functions = list(model.reachable_functions())
        self.facts = Facts(model, self.functions)  # (nir_fold.mix_hint reads it)
        self.lines: list[str] = []
        self.indent = 0
        self.n = 0
        self.consts: dict[str, str] = {}
        self.vars: dict[int, list] = {}
        self.slots = {"float": 0, "int": 0, "uint": 0, "bool": 0}
        self.uslots = {"float": 0, "int": 0}
        self.uniforms: dict[str, tuple[str, int, Any]] = {}  # name -> (kind, offset, type)
        self.loop_lines: dict[int, tuple[str, int, int]] = {}
        self.fn: FnState | None = None
        self.frag4: list[str] | None = None
        self.last_line: tuple[str, int] | None = None
        self.needs: dict[str, list[str]] = {}  # function -> the state arrays it takes
        self.variants: set[tuple[int, frozenset]] = set()  # (function, uniform parameters) made or asked
        self.pending: list[tuple[Any, frozenset]] = []
        # the first dFdx/dFdy/fwidth call: its leaves are written `dfdx(v)` / `dfdy(v)`, which
        # only the lockstep rewrite computes (lanes.py: a block's lanes hold whole 2x2 quads)
        self.derivative: Any = None

    def numpy_transpiler(self) -> Any:
        """The NumPy backend's Transpiler at the current function, for the decisions this engine
        shares with it (nir_fold.mix_hint: nir_lower_flrp's formula for a `mix`)."""
        from ..numpy_engine.transpile import FnState as NumpyFnState, Transpiler

        if getattr(self, "_tr", None) is None:
            self._tr = Transpiler(self.model, self.path)
        sym = self.fn.sym
        if self._tr.fn is None or self._tr.fn.sym is not sym:
            self._tr.fn = NumpyFnState(sym, None, sym is self.entry)
        return self._tr

    # -- emission ------------------------------------------------------------------------------
    def emit(self, text: str) -> None:
        self.lines.append("    " * self.indent + text)

    def fresh(self, prefix: str = "t") -> str:
        self.n += 1
        return f"_{prefix}{self.n}"

    def tmp(self, value: str) -> str:
        if _ATOM.match(value) and not value.startswith(("gf[", "gi[", "gu[", "gb[")):
            return value
        return self.tmp_fresh(value)

    def tmp_fresh(self, value: str) -> str:
        """value into a new temporary, whatever it is."""
        t = self.fresh()
        self.emit(f"{t} = {value}")
        return t

    def atom(self, value: Any) -> Any:
        return self.tmp(value) if isinstance(value, str) else value

    def comment(self, node: Any) -> None:
        loc = getattr(node, "loc", None)
        if loc is None or not loc.line:
            return
        from ...base.diagnostics import source_line
        from ..numpy_engine.transpile.common import _printable

        if (loc.path, loc.line) == self.last_line:
            return
        self.last_line = (loc.path, loc.line)
        text = source_line(loc.path, loc.line) or ""
        self.emit(f"# line {loc.line}: {_printable(text)}".rstrip())

    # -- constants -----------------------------------------------------------------------------
    def cf(self, v: float) -> str:
        if math.isnan(v):
            name, lit = "F_nan", "np.float32(np.nan)"
        elif math.isinf(v):
            name, lit = ("F_inf", "np.float32(np.inf)") if v > 0 else ("F_minf", "np.float32(-np.inf)")
        else:
            text = repr(float(v))
            name = "F_" + text.replace("-", "m").replace("+", "").replace(".", "p")
            lit = f"np.float32({text})"
        self.consts.setdefault(name, lit)
        return name

    def ci(self, v: int, unsigned: bool = False) -> str:
        v = int(v)
        if unsigned:
            v &= 0xFFFFFFFF
            name = f"U_{v}"
            self.consts.setdefault(name, f"np.uint32({v})")
        else:
            v = (v + 2**31) % 2**32 - 2**31
            name = f"I_{v}".replace("-", "m")
            self.consts.setdefault(name, f"np.int32({v})")
        return name

    def const_part(self, base: str, v: Any) -> str:
        if base == "float":
            return self.cf(float(v))
        if base == "bool":
            return "True" if v else "False"
        return self.ci(int(v), base == "uint")

    def zero_parts(self, t: Any, node: Any) -> list:
        out: list = []
        for base, n in leaves(t, node):
            if n is None:
                out.append(self.const_part(base, 0))
            else:
                a = self.fresh("z")
                self.emit(f"{a} = np.zeros({n}, {_DTYPE[base]})")
                out.append(Arr(a, 0, n, base))
        return out

    # -- variables -----------------------------------------------------------------------------
    def declare_local(self, sym: Any, node: Any) -> list:
        from ..numpy_engine.transpile.common import _ident

        name = _ident(sym.unique_name or sym.name, node)
        parts: list = []
        for k, (base, n) in enumerate(leaves(sym.type, node)):
            if n is None:
                parts.append(f"v_{name}_{k}")
            else:
                parts.append(Arr(f"a_{name}_{k}", 0, n, base))
        self.vars[id(sym)] = parts
        return parts

    def global_parts(self, sym: Any, node: Any) -> list:
        parts = self.vars.get(id(sym))
        if parts is None:
            parts = []
            for base, n in leaves(sym.type, node):
                off = self.slots[base]
                self.slots[base] += n or 1
                arr = _KIND_ARRAY[base]
                parts.append(f"{arr}[{off}]" if n is None else Arr(arr, off, n, base))
            self.vars[id(sym)] = parts
        return parts

    def uniform_parts(self, name: str, node: Any) -> list:
        from ...shadertoy.wrapper import UNIFORMS_BY_NAME

        u = UNIFORMS_BY_NAME.get(name)
        if u is None:
            raise _error(f"unknown uniform '{name}'", node)
        if u.glsl_type.startswith("sampler"):
            raise not_yet(f"'{name}': textures and channels", node)
        comps = 1 if u.glsl_type in ("float", "int") else int(u.glsl_type[-1])
        kind = "int" if u.glsl_type == "int" else "float"
        arr = "ui" if kind == "int" else "uf"
        if name not in self.uniforms:
            self.uniforms[name] = (kind, self.uslots[kind], u)
            self.uslots[kind] += comps * (u.array_size or 1)
        _, off, _ = self.uniforms[name]
        if u.array_size:  # component c of element k at off + c*n + k: the small arrays' layout
            return [f"{arr}[{off + c * u.array_size + k}]" for c in range(comps) for k in range(u.array_size)]
        return [f"{arr}[{off + c}]" for c in range(comps)]

    def literal_global(self, sym: Any) -> list | None:
        """A `const` global of literals (`const float EPS = 0.001;`, `const vec3 K = vec3(1, 0,
        -2);`) as module constants: the value init_globals would store (a literal, its negation
        and a constructor of them are exact), read without a state array, folded by LLVM."""
        d = sym.node
        if sym.qualifier != "const" or not isinstance(d, A.Declarator) or d.init is None:
            return None
        t = sym.type
        if not (t.is_scalar or t.is_vector) or not _literal_tree(self.model, d.init, t.base):
            return None
        cv = self.model.const_value(d.init)
        if cv is None:
            return None
        values = _flat(cv)
        values = values * t.size if t.is_vector and len(values) == 1 else values
        return [self.const_part(t.base, v) for v in values]

    def var_parts(self, sym: Any, node: Any) -> list:
        if sym.kind in ("local", "param"):
            parts = self.vars.get(id(sym))
            if parts is None:
                raise _error(f"'{sym.name}' is used before its declaration", node)
            return parts
        if sym.kind == "global" and sym.qualifier == "uniform":
            from ...shadertoy.wrapper import fed_uniform

            if fed_uniform(sym.name, str(sym.type)) is not None:
                return self.uniform_parts(sym.name, node)
            raise not_yet(f"the uniform '{sym.name}'", node)
        if sym.kind == "global":
            if sym.type.contains_opaque:
                raise not_yet(f"'{sym.name}': textures and channels", node)
            literal = self.literal_global(sym)
            if literal is not None:
                return literal
            return self.global_parts(sym, node)
        if sym.kind == "uniform":
            return self.uniform_parts(sym.name, node)
        if sym.kind == "builtin-var":
            if sym.name == "gl_FragCoord":
                if self.frag4 is None:
                    off = self.slots["float"]
                    self.slots["float"] += 4
                    self.frag4 = [f"gf[{off + c}]" for c in range(4)]
                return self.frag4
            if sym.name == "gl_FrontFacing":
                return ["True"]
            if sym.const_value is not None and isinstance(sym.const_value, int):
                return [self.ci(sym.const_value)]
        raise not_yet(f"'{sym.name}'", node)

    # -- module --------------------------------------------------------------------------------
    def module(self) -> str:
        funcs = []
        for fn in self.functions:
            self.lines = []
            self.gen_function(fn, frozenset())
            funcs.append("\n".join(self.lines))
        while self.pending:  # variants with lane-uniform parameters, as the calls asked for them
            fn, seed = self.pending.pop(0)
            self.lines = []
            self.gen_function(fn, seed)
            funcs.append("\n".join(self.lines))
        self.lines = []
        self.gen_globals()
        init = "\n".join(self.lines)
        self.lines = []
        self.gen_shade()
        shade = "\n".join(self.lines)
        out = [HEADER.format(path=_safe(self.path)), ""]
        out.append(f"FMA = {self.fma!r}  # llvm.fmuladd is fused on this CPU (runtime.HOST_FMA)")
        out.append(f"SLOTS = {dict(self.slots)!r}  # global state per scalar type")
        out.append(f"USLOTS = {dict(self.uslots)!r}")
        layout = {k: (v[0], v[1]) for k, v in self.uniforms.items()}
        out.append(f"UNIFORMS = {layout!r}  # uniform -> (kind, offset in uf/ui)")
        out.append(f"LOOPS = {self.loop_lines!r}  # loop id -> (file, line, column)")
        if self.derivative is not None:
            out.append("QUADS = True  # dFdx/dFdy: lockstep blocks of 2x2 quads only (lanes.py)")
        out.append("")
        for name, lit in self.consts.items():
            out.append(f"{name} = {lit}")
        out.append("")
        for f in funcs + [init, shade]:
            out += ["", "@jit", *f.split("\n"), ""]
        out.append(RENDER)
        return "\n".join(out) + "\n"

    def gen_globals(self) -> None:
        self.emit(f"def init_globals({', '.join(STATE)}):")
        self.indent += 1
        self.emit('"""Global variables at the start of every invocation."""')
        self.fn = FnState(None)
        for sym in self.model.globals:
            if sym.kind != "global" or sym.type.contains_opaque or sym.qualifier in ("uniform", "in", "out"):
                if sym.kind == "global" and sym.qualifier == "out":
                    self.global_parts(sym, sym.node)
                continue
            d = sym.node
            init = d.init if isinstance(d, A.Declarator) else None
            parts = self.global_parts(sym, d)
            if init is not None:
                self.comment(d)
                self.write(parts, self.expr(init).parts)
            else:
                self.write(parts, self.zero_parts(sym.type, d))
        self.emit("return 0")
        self.indent -= 1
        self.fn = None

    def gen_shade(self) -> None:
        entry = self.entry
        name = self.fn_name(entry)
        self.emit(f"def shade({', '.join(STATE)}, fx, fy, px, py):")
        self.indent += 1
        self.emit('"""One pixel: fragCoord (fx, fy), pixel centre (px, py) -> RGBA."""')
        if self.frag4 is not None:
            for part, v in zip(self.frag4, ("px", "py", "F32(0.5)", "F32(1.0)")):
                self.emit(f"{part} = {v}")
        if entry.name == "main":
            outs = [g for g in self.model.globals if g.qualifier == "out" and g.kind == "global"
                    and str(g.type) == "vec4"]
            if not outs:
                raise _error("a plain GLSL shader needs an 'out vec4' variable", entry.node)
            self.emit(f"{name}({', '.join(self.needs[name])})")
            parts = self.global_parts(outs[0], outs[0].node)
            self.emit(f"return {parts[0]}, {parts[1]}, {parts[2]}, {parts[3]}")
        else:
            (_, _, d0), (_, _, d1) = entry.params
            big = self.cf(1e20)
            args = []
            if d0 != "out":
                args += [big] * 4
            if d1 != "out":
                args += ["fx", "fy"]
            res = [self.fresh() for _ in range(4 * (d0 != "in") + 2 * (d1 != "in"))]
            call = f"{name}({', '.join(self.needs[name] + args)})"
            if res:
                self.emit(f"{', '.join(res)}, = {call}")
            else:
                self.emit(call)
            color = res[:4] if d0 != "in" else [big] * 4
            self.emit(f"return {color[0]}, {color[1]}, {color[2]}, F32(1.0)  # RGB: alpha is 1")
        self.indent -= 1

    # -- functions -----------------------------------------------------------------------------
    def fn_name(self, sym: Any) -> str:
        from ..numpy_engine.transpile.common import _ident

        return "f_" + _ident(sym.unique_name or sym.name, sym.node)

    def variant_name(self, sym: Any, seed: frozenset) -> str:
        """A function's name, with the indices of its lane-uniform parameters when it has any
        (`f_map__u0_2`): the NumPy backend passes a value of one lane to the parameter there,
        which its constant folding reads as a constant (see `lane_uniform`)."""
        base = self.fn_name(sym)
        return base if not seed else base + "__u" + "_".join(str(i) for i in sorted(seed))

    def gen_function(self, sym: Any, seed: frozenset = frozenset()) -> None:
        node = sym.node
        self.variants.add((id(sym), seed))
        params_u = {id(self.model.symbol_of(p)) for i, p in enumerate(node.proto.params) if i in seed}
        self.fn = fs = FnState(sym, SeededUniformity(self.model, self.facts, sym, sym is self.entry, params_u))
        proto = node.proto
        params: list[str] = []
        prologue: list[tuple[list, Any, str]] = []
        for k, (p, (pname, ptype, direction)) in enumerate(zip(proto.params, sym.params)):
            psym = self.model.symbol_of(p)
            if psym is None:  # an unnamed parameter still takes its argument and returns its out value
                psym = Symbol(f"_unnamed{k}", "param", ptype, node=p, unique_name=f"_unnamed{k}")
            parts = self.declare_local(psym, p)
            if direction == "out":
                prologue.append((parts, ptype, p))
            else:
                for part in parts:
                    params.append(part.name if isinstance(part, Arr) else part)
            if direction != "in":
                fs.outs += parts
        def_at = len(self.lines)
        self.emit("")  # the def line, once the state arrays the body uses are known
        self.indent += 1
        from ..numpy_engine.transpile.common import _printable

        self.emit(f'"""{_printable(sym.signature(), 150)} (line {proto.loc.line if proto.loc else "?"})."""')
        for part in [p for p in self.vars_of_params(sym) if isinstance(p, Arr)]:
            self.emit(f"{part.name} = acopy({part.name})  # arrays are passed by value")
        for parts, ptype, p in prologue:
            self.write(parts, self.zero_parts(ptype, p), fresh_arrays=True)
        ended = self.block(node.body.stmts)
        if not ended:  # the end of the body (also after an if/else that returned in both branches)
            self.emit(self.return_text(None if sym.type.is_void else self.zero_parts(sym.type, node)))
        self.indent -= 1
        used = set(_STATE_NAME.findall("\n".join(self.lines[def_at + 1:])))
        name = self.fn_name(sym)
        if not seed:
            self.needs[name] = [a for a in STATE if a in used]
        self.lines[def_at] = f"def {self.variant_name(sym, seed)}({', '.join(self.needs[name] + params)}):"
        self.fn = None

    def vars_of_params(self, sym: Any) -> list:
        out = []
        for p, (_, _, d) in zip(sym.node.proto.params, sym.params):
            psym = self.model.symbol_of(p)
            if psym is not None and d != "out":
                out += self.vars[id(psym)]
        return out

    def return_text(self, value: list | None) -> str:
        fs = self.fn
        parts = list(value or []) + list(fs.outs)
        if not parts:
            return "return 0"
        texts = [(f"acopy({p.whole()})" if isinstance(p, Arr) else p) for p in parts]
        return f"return ({', '.join(texts)},)"

    # -- statements ----------------------------------------------------------------------------
    def block(self, stmts: list[Any]) -> bool:
        """Emit statements; True when the last one left the block (return, break, continue)."""
        for s in stmts:
            if self.stmt(s):
                return True
        return False

    def stmt(self, s: Any) -> bool:
        method = getattr(self, "_stmt_" + type(s).__name__, None)
        if method is None:
            raise not_yet(f"the statement {type(s).__name__}", s)
        return bool(method(s))

    def sub(self, s: Any) -> None:
        """A statement in a nested Python block (which must not be empty)."""
        n = len(self.lines)
        ended = self.stmt(s)
        if len(self.lines) == n and not ended:
            self.emit("pass")

    def _stmt_Compound(self, s: A.Compound) -> bool:
        return self.block(s.stmts)

    def _stmt_ExpressionStatement(self, s: A.ExpressionStatement) -> None:
        if s.expr is None:
            return
        self.comment(s)
        self.expr(s.expr)  # a value nobody reads: only its statements (calls, writes) are emitted

    def _stmt_DeclarationStatement(self, s: A.DeclarationStatement) -> None:
        d = s.decl
        if isinstance(d, A.PrecisionDeclaration) or (isinstance(d, A.VariableDeclaration) and not d.declarators):
            return
        if not isinstance(d, A.VariableDeclaration):
            raise not_yet("this declaration inside a function", s)
        for dec in d.declarators:
            sym = self.model.symbol_of(dec)
            if sym is None:
                continue
            self.comment(dec)
            value = self.expr(dec.init).parts if dec.init is not None else None
            parts = self.declare_local(sym, dec)
            if value is None:
                value = self.zero_parts(sym.type, dec)
            self.write(parts, value, fresh_arrays=True)

    def _stmt_If(self, s: A.If) -> None:
        self.comment(s)
        c = self.expr(s.cond).parts[0]
        self.emit(f"if {c}:")
        self.indent += 1
        self.sub(s.then)
        self.indent -= 1
        if s.else_ is not None:
            self.emit("else:")
            self.indent += 1
            self.sub(s.else_)
            self.indent -= 1

    def _stmt_Return(self, s: A.Return) -> bool:
        self.comment(s)
        value = self.expr(s.value).parts if s.value is not None else None
        if value is not None:
            value = [self.atom(p) if not isinstance(p, Arr) else p for p in value]
        self.emit(self.return_text(value))
        return True

    def _stmt_Break(self, s: A.Break) -> bool:
        self.emit("break")
        return True

    def _stmt_Continue(self, s: A.Continue) -> bool:
        kind, cont = self.fn.loops[-1]
        if cont is not None:
            cont()
        self.emit("continue")
        return True

    def _stmt_Discard(self, s: A.Discard) -> None:
        raise not_yet("discard", s)

    def _stmt_Switch(self, s: A.Switch) -> None:
        raise not_yet("switch", s)

    def condition(self, cond: Any) -> str:
        if isinstance(cond, A.ConditionDeclaration):
            sym = self.model.symbol_of(cond)
            value = self.expr(cond.init).parts
            parts = self.declare_local(sym, cond)
            self.write(parts, value)
            return parts[0]
        return self.expr(cond).parts[0]

    def _stmt_For(self, s: A.For) -> None:
        self.comment(s)
        if s.init is not None:
            self.stmt(s.init)
        step = (lambda: self.expr(s.step)) if s.step is not None else None
        self.loop(s, s.cond, s.body, step, do_while=False)

    def _stmt_While(self, s: A.While) -> None:
        self.comment(s)
        self.loop(s, s.cond, s.body, None, do_while=False)

    def _stmt_DoWhile(self, s: A.DoWhile) -> None:
        self.comment(s)
        self.loop(s, s.cond, s.body, None, do_while=True)

    def loop(self, s: Any, cond: Any, body: Any, step: Any, do_while: bool) -> None:
        from ..numpy_engine.transpile.common import LOOP_CAP

        lid = len(self.loop_lines) + 1
        loc = s.loc
        self.loop_lines[lid] = (loc.path, loc.line, loc.column)
        count = self.fresh("n")
        self.emit(f"{count} = 0")
        self.emit("while True:")
        self.indent += 1

        def test() -> None:
            if cond is not None:
                c = self.condition(cond)
                self.emit(f"if not {c}:")
                self.emit("    break")

        if not do_while:
            test()
        self.emit(f"{count} += 1")
        self.emit(f"if {count} > {LOOP_CAP}:  # a runaway loop: the engine reports its line")
        self.emit(f"    raise LoopCapError({lid})")
        cont = step if not do_while else test
        self.fn.loops.append(("loop", cont))
        ended = self.stmt(body)
        self.fn.loops.pop()
        if not ended:
            if do_while:
                test()
            elif step is not None:
                step()
        self.indent -= 1

    # -- writes --------------------------------------------------------------------------------
    def write(self, targets: list, values: list, fresh_arrays: bool = False) -> None:
        """Assign value parts to target parts, in order. Values that read a target are copied
        first when several parts are written (`v.xy = v.yx`)."""
        if len(targets) > 1:
            values = [self.tmp_copy(v) if isinstance(v, str) and not v.startswith(("F_", "I_", "U_", "_t"))
                      and v not in ("True", "False") else v for v in values]
        for t, v in zip(targets, values):
            if isinstance(t, Arr):
                src = v.whole() if isinstance(v, Arr) else v
                if fresh_arrays and t.name.startswith("a_"):
                    self.emit(f"{t.name} = acopy({src})")
                else:
                    self.emit(f"aset({t.name}, {t.off}, {src})")
            elif isinstance(t, Dyn):
                # Every element takes the value where the index is its own, itself elsewhere:
                # one select each (lanes_rt.lsel), no branch (see read()).
                v = self.tmp(v)
                for k, p in enumerate(t.parts):
                    self.write([p], [f"lsel({t.idx} == {k}, {v}, {self.read(p)})"])
            else:
                self.emit(f"{t} = {v}")

    def read(self, p: Any) -> Any:
        """A target part as a value part (a run-time index becomes a chain of selects).

        lanes_rt.lsel, not Python's `a if c else b`: the parts are names and constants, so
        computing all of them costs nothing, and a conditional expression is two basic blocks
        in numba's IR. `lights[i].pos` in a lights loop read 4 x 3 leaves that way, 600 of
        the 711 blocks of a Lab 4 submission's shading function (10-lab4 of the real corpus);
        numba's liveness and SSA passes grow with blocks x variables, and its lockstep module
        (8 lanes, 5,627 blocks) took 341 s and 9.2 GB to compile."""
        if isinstance(p, Dyn):
            parts = [self.read(q) for q in p.parts]
            text = parts[-1]
            for k in range(len(parts) - 2, -1, -1):
                text = f"lsel({p.idx} == {k}, {parts[k]}, {text})"
            return self.tmp(text)
        return p

    def lvalue(self, e: Any) -> list:
        """The target parts of an l-value, its index expressions evaluated (once, in order)."""
        if isinstance(e, A.Identifier):
            sym = self.model.symbol_of(e)
            return list(self.var_parts(sym, e))
        if isinstance(e, A.Field):
            base = self.lvalue(e.base)
            return self.select_field(self.type_of(e.base), base, e)
        if isinstance(e, A.Index):
            base = self.lvalue(e.base)
            return self.select_index(self.type_of(e.base), base, e)
        raise _error("this expression cannot be assigned to", e)

    def select_field(self, bt: Any, parts: list, e: A.Field) -> list:
        if bt.is_struct:
            k = 0
            for fname, ft in bt.fields:
                n = len(leaves(ft, e))
                if fname == e.name:
                    return parts[k:k + n]
                k += n
            raise _error(f"no field '{e.name}'", e)
        idx = self.model.swizzle_indices(e)
        if bt.is_scalar:
            return [parts[0]] * len(idx)
        return [parts[i] for i in idx]

    def select_index(self, bt: Any, parts: list, e: A.Index) -> list:
        cv = self.model.const_value(e.index)
        const = isinstance(cv, int) and not isinstance(cv, bool)
        if bt.is_array:
            n = bt.array_size
            if const:
                i = str(min(max(cv, 0), n - 1))
            else:
                i = self.tmp(f"index({self.expr(e.index).parts[0]}, {n})")
            if any(isinstance(p, Arr) for p in parts):
                return [p.at(i) if isinstance(p, Arr) else self.bad_array(e) for p in parts]
            m = len(parts) // n  # scalars, leaf by leaf: leaf j of element k is parts[j * n + k]
            if const:
                return [parts[j * n + int(i)] for j in range(m)]
            return [Dyn(i, parts[j * n:(j + 1) * n]) for j in range(m)]
        if bt.is_vector:
            if const:
                return [parts[min(max(cv, 0), bt.size - 1)]]
            i = self.tmp(f"index({self.expr(e.index).parts[0]}, {bt.size})")
            return [Dyn(i, list(parts))]
        if bt.is_matrix:
            r = bt.rows
            if const:
                c = min(max(cv, 0), bt.cols - 1)
                return parts[c * r:(c + 1) * r]
            i = self.tmp(f"index({self.expr(e.index).parts[0]}, {bt.cols})")
            return [Dyn(i, [parts[c * r + row] for c in range(bt.cols)]) for row in range(r)]
        raise _error("this value cannot be indexed", e)

    def bad_array(self, e: Any) -> str:
        raise not_yet("this array access", e)

    # -- expressions ---------------------------------------------------------------------------
    def type_of(self, e: Any) -> Any:
        return self.model.type_of(e)

    def expr(self, e: Any) -> Val:
        method = getattr(self, "_expr_" + type(e).__name__, None)
        if method is None:
            raise not_yet(f"{type(e).__name__} expressions", e)
        v = method(e)
        cv = self.model.const_value(e)
        if cv is not None and v.const is None and not self.type_of(e).is_array and not self.type_of(e).is_struct:
            v.const = _flat(cv)
        v.uni = self.lane_uniform(e)
        # long expressions go to temporaries (Python's parser nests 200 brackets at most)
        v.parts = [self.tmp(p) if isinstance(p, str) and len(p) > 300 else p for p in v.parts]
        return v

    def lane_uniform(self, e: Any) -> bool:
        """Whether the NumPy backend holds e's value as one lane for the whole tile and takes it
        for a compile-time constant (Runtime._const: a lane-uniform value that is not a uniform
        input): Mesa's constant folding, approximated there (Runtime.fmul). By numpy_backend's
        own analysis (Uniformity); global initializers run on one lane there."""
        node = e
        while isinstance(node, (A.Field, A.Index)) and not (isinstance(node, A.Field) and self.model.is_swizzle(node)
                                                            and len(self.model.swizzle_indices(node)) > 1):
            node = node.base
        if isinstance(node, A.Field) and self.model.is_swizzle(node):
            idx = tuple(self.model.swizzle_indices(node))
            inner = node.base
            if isinstance(inner, A.Identifier) and self._is_input(inner) and (
                    idx == tuple(range(len(idx))) or (len(idx) > 1 and idx[1] - idx[0] > 0 and all(
                        b - a == idx[1] - idx[0] for a, b in zip(idx, idx[1:])))):
                return False  # a view of a read-only uniform (Runtime.swizzle)
        elif isinstance(node, A.Identifier) and self._is_input(node):
            return False
        if self.fn is None or self.fn.uni is None:
            return True
        return self.fn.uni.is_uniform(e)

    def _is_input(self, ident: Any) -> bool:
        sym = self.model.symbol_of(ident)
        return sym is not None and (sym.kind == "uniform" or (sym.kind == "global" and sym.qualifier == "uniform")
                                    or (sym.kind == "builtin-var" and sym.name == "gl_FragCoord"))

    def _expr_IntLiteral(self, e: A.IntLiteral) -> Val:
        t = self.type_of(e)
        return Val(t, [self.ci(e.value, e.unsigned or t == T.UINT)], [e.value])

    def _expr_FloatLiteral(self, e: A.FloatLiteral) -> Val:
        return Val(T.FLOAT, [self.cf(e.value)], [e.value])

    def _expr_BoolLiteral(self, e: A.BoolLiteral) -> Val:
        return Val(T.BOOL, ["True" if e.value else "False"], [e.value])

    def _expr_Identifier(self, e: A.Identifier) -> Val:
        sym = self.model.symbol_of(e)
        if sym is None:
            raise _error(f"'{e.name}' has no symbol", e)
        return Val(sym.type, [self.read(p) for p in self.var_parts(sym, e)])

    def _expr_Field(self, e: A.Field) -> Val:
        base = self.expr(e.base)
        return Val(self.type_of(e), self.select_field(base.t, base.parts, e))

    def _expr_Index(self, e: A.Index) -> Val:
        bt = self.type_of(e.base)
        base = self.expr(e.base)
        parts = self.select_index(bt, [p if isinstance(p, Arr) else self.atom(p) for p in base.parts], e)
        return Val(self.type_of(e), [self.read(p) for p in parts])

    def _expr_MethodCall(self, e: A.MethodCall) -> Val:
        bt = self.type_of(e.base)
        if e.name == "length":
            n = bt.array_size if bt.is_array else bt.size if bt.is_vector else bt.cols if bt.is_matrix else None
            if n is not None:
                return Val(T.INT, [self.ci(n)], [n])
        raise not_yet(f"the method '.{e.name}()'", e)

    def _expr_Sequence(self, e: A.Sequence) -> Val:
        for x in e.exprs[:-1]:
            self.expr(x)
        return self.expr(e.exprs[-1])

    def _expr_Assignment(self, e: A.Assignment) -> Val:
        targets = self.lvalue(e.target)
        value = self.expr(e.value)
        tt = self.type_of(e.target)
        if e.op != "=":
            old = Val(tt, [self.read(p) for p in targets])
            value = self.binary_values(e.op[:-1], old, value, e)
        parts = [self.tmp(p) if isinstance(p, str) else p for p in value.parts]
        self.write(targets, parts)
        return Val(tt, parts)

    def _expr_Unary(self, e: A.Unary) -> Val:
        if e.op in ("++", "--"):
            return self.incdec(e, post=False)
        v = self.expr(e.operand)
        t = v.t
        if e.op == "+":
            return v
        if e.op == "-":
            if t.base == "float":
                return Val(t, [f"(-{p})" for p in v.parts])
            return Val(t, [f"{_CAST[t.base]}(-np.int64({p}))" for p in v.parts])
        if e.op == "!":
            return Val(t, [f"(not {v.parts[0]})"])
        if e.op == "~":
            return Val(t, [f"{_CAST[t.base]}(~{p})" for p in v.parts])
        raise not_yet(f"the operator '{e.op}'", e)

    def _expr_Postfix(self, e: A.Postfix) -> Val:
        return self.incdec(e, post=True)

    def incdec(self, e: Any, post: bool) -> Val:
        targets = self.lvalue(e.operand)
        t = self.type_of(e.operand)
        old = [self.tmp(self.read(p)) if post else self.read(p) for p in targets]
        if post:
            old = [self.tmp_copy(p) for p in old]
        one = self.cf(1.0) if t.base == "float" else self.ci(1, t.base == "uint")
        op = "+" if e.op == "++" else "-"
        if t.base == "float":
            new = [self.tmp(f"({p} {op} {one})") for p in old]
        else:
            new = [self.tmp(f"{_CAST[t.base]}({p} {op} {one})") for p in old]
        self.write(targets, new)
        return Val(t, old if post else new)

    def tmp_copy(self, p: str) -> str:
        t = self.fresh()
        self.emit(f"{t} = {p}")
        return t

    def _expr_Ternary(self, e: A.Ternary) -> Val:
        t = self.type_of(e)
        c = self.tmp(self.expr(e.cond).parts[0])
        n = len(leaves(t, e))
        mark = len(self.lines)
        a = self.expr(e.then).parts
        if self._speculable(mark, a):
            then_end = len(self.lines)
            b = self.expr(e.else_).parts
            if self._speculable(then_end, b):
                # Both sides are a few selects, compares and arithmetic of names and
                # constants: computed both, one select each (lanes_rt.lsel), no branch.
                # Computing the side not taken does nothing and cannot fail (IEEE float
                # math, error_model="numpy"); as if/else each leaf would be two basic blocks
                # per pixel and a masked write per lane in lockstep (h38-2d-sprites: 524
                # ternaries, `idx = y == 14.0 ? (x <= 7.0 ? 40960.0 : 42.0) : idx`).
                return Val(t, [self.tmp(f"lsel({c}, {x}, {y})") for x, y in zip(a, b)])
            del self.lines[then_end:]  # the else side's statements: written again in its branch
        res = [self.fresh() for _ in range(n)]
        # the then side's statements (if any) run only where c holds
        body = self.lines[mark:]
        del self.lines[mark:]
        self.emit(f"if {c}:")
        self.indent += 1
        self.lines += ["    " + line for line in body]
        self.assign_fresh(res, a)
        self.indent -= 1
        self.emit("else:")
        self.indent += 1
        b = self.expr(e.else_).parts
        self.assign_fresh(res, b)
        self.indent -= 1
        out = [Arr(r, 0, p.size, p.base) if isinstance(p, Arr) else r for r, p in zip(res, a)]
        return Val(t, out)

    def _speculable(self, mark: int, parts: list) -> bool:
        """The lines written since mark and the value parts are pure and cheap: at most a few
        assignments of temporaries, each of names, literals, operators and lsel."""
        if any(not isinstance(p, str) or not pure_expr(p) for p in parts):
            return False
        body = self.lines[mark:]
        if len(body) > _SPECULATE_LINES:
            return False
        pad = "    " * self.indent
        for line in body:
            m = _PURE_LINE.match(line)
            if m is None or m.group(1) != pad or not pure_expr(m.group(2)):
                return False
        return True

    def assign_fresh(self, names: list[str], parts: list) -> None:
        for r, p in zip(names, parts):
            self.emit(f"{r} = acopy({p.whole()})" if isinstance(p, Arr) else f"{r} = {p}")

    def _expr_Binary(self, e: A.Binary) -> Val:
        op = e.op
        if op in ("&&", "||"):
            left = self.tmp(self.expr(e.left).parts[0])
            mark = len(self.lines)
            self.indent += 1
            right = self.expr(e.right).parts[0]
            self.indent -= 1
            if len(self.lines) == mark:  # nothing to run first: Python's own short circuit
                return Val(T.BOOL, [f"({left} {'and' if op == '&&' else 'or'} {right})"])
            res = self.fresh()
            body = self.lines[mark:]
            del self.lines[mark:]
            self.emit(f"{res} = {left}")
            self.emit(f"if {'' if op == '&&' else 'not '}{res}:")
            self.lines += body
            self.emit(f"    {res} = {right}")
            return Val(T.BOOL, [res])
        left = self.expr(e.left)
        right = self.expr(e.right)
        if op == "%" and left.const is not None and right.const is not None and left.t.base == "int":
            return self.componentwise(left, right, self.type_of(e), lambda a, b, i: f"irem_const({a}, {b})")
        return self.binary_values(op, left, right, e)

    def binary_values(self, op: str, left: Val, right: Val, e: Any) -> Val:
        lt, rt_ = left.t, right.t
        rtype = self.type_of(e) if not isinstance(e, A.Assignment) else lt
        if op == "*" and (lt.is_matrix or rt_.is_matrix) and not (lt.is_scalar or rt_.is_scalar):
            return self.linear_product(left, right, rtype)
        if op in ("==", "!="):
            pairs = []
            for a, b, base in zip(left.parts, right.parts, [x for x, _ in leaves(lt, e)]):
                if isinstance(a, Arr):
                    pairs.append(f"np.array_equal({a.whole()}, {b.whole()})")
                else:
                    pairs.append(f"({a} == {b})")
            text = " and ".join(pairs) if len(pairs) > 1 else pairs[0]
            text = f"({text})"
            return Val(T.BOOL, [text if op == "==" else f"(not {text})"])
        if op == "^^":
            return Val(T.BOOL, [f"({left.parts[0]} != {right.parts[0]})"])
        base = lt.base
        if base == "float":
            if op == "*":
                return self.fmul(left, right, rtype)
            if op in ("+", "-"):
                return self.fadd(op, left, right, rtype, e)
            if op in ("/", "<", "<=", ">", ">="):
                return self.componentwise(left, right, rtype, lambda a, b, i: f"({a} {op} {b})")
        elif base in ("int", "uint"):
            cast = _CAST[base]
            u = base == "uint"
            if op in ("+", "-", "*"):
                return self.componentwise(left, right, rtype, lambda a, b, i: f"{cast}({a} {op} {b})")
            if op in ("<", "<=", ">", ">="):
                return self.componentwise(left, right, rtype, lambda a, b, i: f"({a} {op} {b})")
            if op in ("&", "|", "^"):
                return self.componentwise(left, right, rtype, lambda a, b, i: f"{cast}({a} {op} {b})")
            fn = {"/": "udiv" if u else "idiv", "%": "urem" if u else "irem",
                  "<<": "ushl" if u else "ishl", ">>": "ushr" if u else "ishr"}.get(op)
            if fn is not None:
                return self.componentwise(left, right, rtype, lambda a, b, i: f"{fn}({a}, {b})")
        raise not_yet(f"the operator '{op}' on '{lt}'", e)

    def componentwise(self, left: Val, right: Val, rtype: Any, fn) -> Val:
        n = max(len(left.parts), len(right.parts))
        a = left.parts if len(left.parts) == n else [self.atom(left.parts[0])] * n
        b = right.parts if len(right.parts) == n else [self.atom(right.parts[0])] * n
        return Val(rtype, [fn(x, y, i) for i, (x, y) in enumerate(zip(a, b))])

    def fmul(self, left: Val, right: Val, rtype: Any) -> Val:
        """Float `*` as Runtime.fmul: a compile-time constant zero component times a value that
        is not a constant is 0 (NIR folds x * 0.0), also for NaN and Inf."""
        n = max(len(left.parts), len(right.parts))
        if left.constlike == right.constlike:
            return self.componentwise(left, right, rtype, lambda a, b, i: f"({a} * {b})")
        zv = left if left.constlike else right
        zc = _bcast(zv.const, n)
        zero = self.cf(0.0)
        zparts = zv.parts if len(zv.parts) == n else [self.atom(zv.parts[0])] * n
        if zc is None:
            zparts = [self.atom(p) for p in zparts]
            if zv is left:
                left = Val(left.t, zparts)
            else:
                right = Val(right.t, zparts)

        def one(a: str, b: str, i: int) -> str:
            if zc is not None:
                return zero if zc[i] == 0 else f"({a} * {b})"
            return f"({zero} if {zparts[i]} == {zero} else ({a} * {b}))"
        return self.componentwise(left, right, rtype, one)

    def fadd(self, op: str, left: Val, right: Val, rtype: Any, e: Any = None) -> Val:
        """Float `+`/`-` as Runtime.fadd/fsub: a compile-time constant zero added to (or
        subtracted from) a value that is not a constant leaves that value, its sign kept."""
        n = max(len(left.parts), len(right.parts))
        if left.constlike == right.constlike or not self.zero_add(e):
            return self.componentwise(left, right, rtype, lambda a, b, i: f"({a} {op} {b})")
        zleft = left.constlike  # the operand that may be a constant zero: the left one?
        zc = _bcast((left if zleft else right).const, n)
        zero = self.cf(0.0)
        left = Val(left.t, [self.atom(p) for p in left.parts], left.const, left.uni)
        right = Val(right.t, [self.atom(p) for p in right.parts], right.const, right.uni)

        def one(a: str, b: str, i: int) -> str:
            z = a if zleft else b
            kept = (b if op == "+" else f"(-{b})") if zleft else a
            if zc is not None:
                return kept if zc[i] == 0 else f"({a} {op} {b})"
            return f"({kept} if {z} == {zero} else ({a} {op} {b}))"
        return self.componentwise(left, right, rtype, one)

    def zero_add(self, e: Any) -> bool:
        """Whether the NumPy backend tests this `+`/`-` for a constant zero operand (nir_fold.
        zero_add: Mesa drops an added constant zero, keeping the sign of a -0.0)."""
        if e is None:
            return True
        if self.fn is None or self.fn.sym is None or not isinstance(e, A.Binary):
            return self.fn is None or self.fn.sym is None
        from ..numpy_engine import nir_fold

        return nir_fold.zero_add(self.numpy_transpiler(), e, "l", "r") is not None

    def linear_product(self, left: Val, right: Val, rtype: Any) -> Val:
        lt, rt_ = left.t, right.t
        a = [self.atom(p) for p in left.parts]
        b = [self.atom(p) for p in right.parts]
        if lt.is_matrix and rt_.is_vector:  # sum of m[c] * v[c] in c order
            return Val(rtype, self.mat_vec(a, lt.cols, lt.rows, b))
        if lt.is_vector and rt_.is_matrix:  # component c: dot(v, m[c])
            r = rt_.rows
            return Val(rtype, [self.dot_text(a, b[c * r:(c + 1) * r]) for c in range(rt_.cols)])
        out = []
        k = lt.cols
        for c in range(rt_.cols):
            out += [self.atom(p) for p in self.mat_vec(a, k, lt.rows, b[c * k:(c + 1) * k])]
        return Val(rtype, out)

    def mat_vec(self, m: list, cols: int, rows: int, v: list) -> list:
        out = []
        for r in range(rows):
            s = f"({m[r]} * {v[0]})"
            for c in range(1, cols):
                s = f"({s} + ({m[c * rows + r]} * {v[c]}))"
            out.append(s)
        return out

    def dot_text(self, a: list, b: list, ca: list | None = None, cb: list | None = None) -> str:
        """Sum of products right to left (Runtime.dot); with exactly one constant operand, a
        product with a constant zero is 0."""
        n = len(a)
        fold = (ca is None) != (cb is None)
        prods = []
        for i in range(n):
            if fold and ((ca is not None and ca[i] == 0) or (cb is not None and cb[i] == 0)):
                prods.append(self.cf(0.0))
            else:
                prods.append(f"({a[i]} * {b[i]})")
        s = prods[-1]
        for i in range(n - 2, -1, -1):
            s = f"({prods[i]} + {s})"
        return s

    # -- calls ---------------------------------------------------------------------------------
    def _expr_Call(self, e: A.Call) -> Val:
        tgt = self.model.call_target(e)
        if isinstance(tgt, Constructor):
            return self.constructor(e, tgt.type)
        if isinstance(tgt, Symbol):
            return self.user_call(e, tgt)
        if tgt is None:
            raise _error(f"the call of '{e.callee}' was not resolved by the checker", e)
        from .builtin_calls import builtin_call

        return builtin_call(self, e, tgt)

    def user_call(self, e: A.Call, fn: Any) -> Val:
        args: list[str] = []
        outs: list[list] = []
        for a, (_, ptype, d) in zip(e.args, fn.params):
            if d == "in":
                parts = self.expr(a).parts
            else:
                targets = self.lvalue(a)
                outs.append(targets)
                parts = [self.read(p) for p in targets] if d == "inout" else []
            for p in parts:
                args.append(p.whole() if isinstance(p, Arr) else p)
        rtype = fn.type
        n_val = 0 if rtype.is_void else len(leaves(rtype, e))
        ret_leaves = [] if rtype.is_void else leaves(rtype, e)
        out_leaves = [leaf for (_, pt, d) in fn.params if d != "in" for leaf in leaves(pt, e)]
        res = [self.fresh() for _ in range(n_val + len(out_leaves))]
        seed = frozenset(i for i, (a, (_, _, d)) in enumerate(zip(e.args, fn.params))
                         if d != "out" and self.lane_uniform(a))
        if seed and (id(fn), seed) not in self.variants:
            self.variants.add((id(fn), seed))
            self.pending.append((fn, seed))
        call = f"{self.variant_name(fn, seed)}({', '.join(self.needs[self.fn_name(fn)] + args)})"
        if res:
            self.emit(f"{', '.join(res)}, = {call}")
        else:
            self.emit(call)
        k = n_val
        for targets in outs:
            vals = []
            for _ in targets:
                base, size = out_leaves[k - n_val]
                vals.append(Arr(res[k], 0, size, base) if size is not None else res[k])
                k += 1
            self.write(targets, vals)
        value = [Arr(r, 0, n, b) if n is not None else r for r, (b, n) in zip(res[:n_val], ret_leaves)]
        return Val(rtype, value)

    def constructor(self, e: A.Call, t: Any) -> Val:
        args = [self.expr(a) for a in e.args]
        if t.is_array and all(size is None for _, size in leaves(t, e)):
            m = len(leaves(t.element, e))
            return Val(t, [self.atom(v.parts[j]) for j in range(m) for v in args])
        if t.is_array:
            n = len(args)
            out = []
            for k, (base, _) in enumerate(leaves(t.element, e)):
                a = self.fresh("a")
                self.emit(f"{a} = np.empty({n}, {_DTYPE[base]})")
                for i, v in enumerate(args):
                    self.emit(f"{a}[{i}] = {v.parts[k]}")
                out.append(Arr(a, 0, n, base))
            return Val(t, out)
        if t.is_struct:
            return Val(t, [p for v in args for p in v.parts])
        comps: list[str] = []
        for v in args:
            comps += [self.convert(p, v.t.base if not v.t.is_matrix else "float", t.base or "float")
                      for p in v.parts]
        const = None
        if all(v.const is not None for v in args):
            const = [c for v in args for c in v.const]
        if t.is_scalar:
            return Val(t, comps[:1], const[:1] if const else None)
        if t.is_vector:
            if len(comps) == 1:
                c = self.atom(comps[0])
                return Val(t, [c] * t.size, const * t.size if const else None)
            return Val(t, comps[:t.size], const[:t.size] if const else None)
        if t.is_matrix:
            c, r = t.cols, t.rows
            if len(args) == 1 and args[0].t.is_scalar:
                s = self.atom(comps[0])
                zero = self.cf(0.0)
                return Val(t, [s if i == j else zero for i in range(c) for j in range(r)])
            if len(args) == 1 and args[0].t.is_matrix:
                m = args[0]
                mc, mr = m.t.cols, m.t.rows
                one, zero = self.cf(1.0), self.cf(0.0)
                out = []
                for i in range(c):
                    for j in range(r):
                        if i < mc and j < mr:
                            out.append(m.parts[i * mr + j])
                        else:
                            out.append(one if i == j else zero)
                return Val(t, out)
            return Val(t, comps[:c * r])
        raise not_yet(f"constructing '{t}'", e)

    def convert(self, p: str, src: str, dst: str) -> str:
        """A scalar converted as runtime.Runtime.to_<dst>: bool to 0/1, float to int through
        cvttps2dq (to_int), float to uint by this CPU's model (driver_profile), the rest by
        their bits or value (numba's casts)."""
        if src == dst:
            return p
        if dst == "bool":
            return f"({p} != 0)"
        if src == "bool":
            one, zero = (self.cf(1.0), self.cf(0.0)) if dst == "float" else (f"{_CAST[dst]}(1)", f"{_CAST[dst]}(0)")
            return f"({one} if {p} else {zero})"
        if src == "float":
            return f"to_int({p})" if dst == "int" else f"to_uint_{self.float_to_uint}({p})"
        return f"{_CAST[dst]}({p})"


def _seeded_uniformity():
    from ..numpy_engine.uniformity import Uniformity

    class _SkipFirst(set):
        """The analysis' varying symbols, but the first `add` of each seeded parameter (the
        analysis starts by marking every parameter varying) is ignored."""

        def __init__(self, skip: set) -> None:
            super().__init__()
            self.skip = set(skip)

        def add(self, x: Any) -> None:
            if x in self.skip:
                self.skip.discard(x)
                return
            super().add(x)

    class Seeded(Uniformity):
        """numpy_backend's Uniformity of a function whose parameters `uniform_params` (symbol
        ids) get a value of one lane from the call (NumPy evaluates a call with the arguments'
        own lane counts): they start uniform; a varying write still makes them varying."""

        def __init__(self, model: Any, facts: Any, fn: Any, is_entry: bool, uniform_params: set) -> None:
            self.__dict__["_seed"] = set(uniform_params)
            super().__init__(model, facts, fn, is_entry)

        def __setattr__(self, name: str, value: Any) -> None:
            if name == "varying" and "varying" not in self.__dict__:
                value = _SkipFirst(self.__dict__["_seed"])
            object.__setattr__(self, name, value)

    return Seeded


def SeededUniformity(model: Any, facts: Any, fn: Any, is_entry: bool, uniform_params: set) -> Any:
    global _SEEDED
    if _SEEDED is None:
        _SEEDED = _seeded_uniformity()
    return _SEEDED(model, facts, fn, is_entry, uniform_params)


_SEEDED = None


def _literal_tree(model: Any, e: Any, base: str) -> bool:
    """Literals of type `base`, their negations and vector constructors of them only."""
    if isinstance(e, (A.FloatLiteral, A.IntLiteral, A.BoolLiteral)):
        return model.type_of(e).base == base
    if isinstance(e, A.Unary) and e.op == "-":
        return _literal_tree(model, e.operand, base)
    if isinstance(e, A.Call) and isinstance(model.call_target(e), Constructor):
        t = model.type_of(e)
        return (t.is_scalar or t.is_vector) and t.base == base and all(_literal_tree(model, a, base) for a in e.args)
    return False


def _bcast(const: list | None, n: int) -> list | None:
    if const is None:
        return None
    return const * n if len(const) == 1 and n > 1 else const


def _safe(text: str) -> str:
    from ..numpy_engine.transpile.common import _printable

    return _printable(text, 200)


HEADER = '''"""Generated by glslcheck's compiled engine from {path} (GLSL ES 3.00) -- do not edit.

One call of `shade` computes one pixel; numba compiles every function (see the docstring of
glslcheck/backends/compiled_engine/codegen.py for the value representation).
"""

import numba
import numpy as np

from glslcheck.backends.compiled_engine.scalar import *  # noqa: F401,F403 (the scalar runtime)
from glslcheck.backends.compiled_engine.lanes_rt import lsel  # a branch-free select

F32 = np.float32
I32 = np.int32
U32 = np.uint32
jit = numba.njit(cache=True, nogil=True, error_model="numpy")'''

RENDER = '''
@numba.njit(cache=True, nogil=True, error_model="numpy")
def render_rows(out, y0, y1, width, height, offs, uf, ui, gtf, gti, gtu, gtb):
    """Rows y0..y1-1 (counted from the bottom) into out (height, width, 4), top row first;
    offs: the (dx, dy) sample offsets (one row of zeros for one sample)."""
    gf = acopy(gtf)
    gi = acopy(gti)
    gu = acopy(gtu)
    gb = acopy(gtb)
    samples = offs.shape[0]
    for y in range(y0, y1):
        row = height - 1 - y
        py = F32(y + 0.5)
        for x in range(width):
            px = F32(x + 0.5)
            ar = ag = ab = aa = 0.0
            for s in range(samples):  # one sample: offset 0, the sum its value (a -0.0 kept)
                aset(gf, 0, gtf)
                aset(gi, 0, gti)
                aset(gu, 0, gtu)
                aset(gb, 0, gtb)
                r, g, b, a = shade(gf, gi, gu, gb, uf, ui, F32(px + F32(offs[s, 0])), F32(py + F32(offs[s, 1])),
                                   px, py)
                if s == 0:
                    ar, ag, ab, aa = np.float64(r), np.float64(g), np.float64(b), np.float64(a)
                else:
                    ar, ag, ab, aa = ar + r, ag + g, ab + b, aa + a
            out[row, x, 0] = ar / samples
            out[row, x, 1] = ag / samples
            out[row, x, 2] = ab / samples
            out[row, x, 3] = aa / samples


@numba.njit(cache=True, nogil=True, error_model="numpy")
def globals_template(uf, ui, gtf, gti, gtu, gtb):
    """The globals' initial values, written into the template arrays (once per frame)."""
    init_globals(gtf, gti, gtu, gtb, uf, ui)
'''
