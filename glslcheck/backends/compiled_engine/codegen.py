"""The GLSL-to-numba code generator: a checked Shadertoy program becomes a Python module of
scalar functions, one call per pixel.

Where backends/numpy_engine/transpile runs every pixel of a tile as lanes of NumPy arrays, this
generator writes the program for ONE pixel, and numba compiles it (nopython, no fast-math,
error_model="numpy": x / 0 is IEEE). Types and symbols come from glslcheck.semantics, as in the
NumPy transpiler; every operation computes what glslcheck/backends/numpy_engine/runtime.py computes
for one lane (the scalar functions are backends/compiled_engine/scalar.py).

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
no global gets none); the globals are reset to their initial values before each pixel. Globals
no function writes are read from module constants instead (constant_globals.py: numba freezes
them into the machine code, LLVM folds them), and a state array no function writes is not reset.

Control flow is Python's own: `if`, `while` loops for GLSL's three loops (a `continue` in a
`for` runs the step first; in a `do`-`while` it tests the condition), `return` anywhere,
`&&`/`||`/`?:` evaluate only the side they need; a `switch` is a loop of one pass over its
sections from the one its selector enters at (fall-through; `break` leaves it, a `continue` of
the loop around leaves it by a flag); `discard` sets a per-pixel flag and returns, every call
of a function that may discard returns after it when the flag is set, and `shade` gives the
clear colour (0, 0, 0, 0). Each loop counts its passes and stops after
transpile.LOOP_CAP by raising LoopCapError(its id) (the engine raises the located error), and
spends llvmpipe's pass budget as the NumPy backend does (`lc`, scalar.tick; `loop`). A user
function returns a tuple: its value's leaves, then the leaves of its out/inout parameters,
which the caller writes back left to right.

Texture lookups on a sampler2D or samplerCube: texture_calls.py (a sampler is its channel
number; texels and channel descriptions follow the uniforms in `uf`/`ui`).

Not supported yet (a GlslError at the construct, "not supported by the compiled engine yet"):
cube maps and other sampler types, arrays of structs holding arrays, inverse() of 3x3 and 4x4
matrices, and the packing built-ins; derivatives and implicit mipmap LODs only in lockstep
(lanes.py).

Mesa's reassociations (backends/cpu_core/nir_fold/, call_fold.py, inline.py) are
decided there for both engines and computed here with this engine's values (fold_values.py;
docs/compiled-engine.md lists what is asked and the few rules not yet). A value the NumPy
backend holds as one lane for a tile counts there as a constant (Runtime.fmul/fadd/pow);
`Val.uni` marks the same values here (Uniformity with out_values), with a run-time test where
the value is not known when generating.
"""

from __future__ import annotations

import ast
import math
from typing import Any

from ...base.diagnostics import Location
from ...frontend import syntax as A
from ...semantics.model import Constructor, Symbol
from ..cpu_core import nir_fold
from ..cpu_core.common import LOOP_CAP, comment_safe, python_ident
from ..cpu_core.facts import Facts
from ..cpu_core.uniformity import Uniformity
from .constant_globals import (
    emit_load_time_calls,
    frozen_globals,
    frozen_parts,
    reset_kinds,
    written_state,
)
from .expressions import ExpressionEmitter, FnState, nir_chain_params
from .module_text import FREEZE, HEADER, RENDER
from .ray_dots import ray_param_names
from .values import (
    ATOM,
    BUDGET_OFF,
    BUDGET_ON,
    DTYPE,
    KIND_ARRAY,
    STATE,
    STATE_NAME,
    Arr,
    Val,
    engine_error,
    flatten,
    leaves,
    not_yet,
)

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ...semantics.model import Model
    from .fold_values import FoldValues


class Codegen(ExpressionEmitter):
    """`Codegen(model, path).module()` -> the generated Python source."""

    def __init__(
        self,
        model: Model,
        path: str,
        fma: bool,
        float_to_uint: str,
        budget: bool = False,
        mipmap: frozenset = frozenset(),
        keep_alpha: bool = False,
        frame_calls: bool = True,
    ) -> None:
        self.model = model
        # calls the same in every pixel of a frame computed once a frame (load_time_parts): a
        # per-pixel module's gain; lockstep computes them once a block already, and reading
        # them from the state costs its functions an array each
        self.frame_calls = frame_calls
        self.keep_alpha = keep_alpha  # a Buffer pass: Shadertoy keeps the alpha mainImage wrote
        # texture lookups (texture_calls.py): the channels bound with mipmaps, whether the
        # module samples, and the float16 trees being written in their float32 form
        self.mipmap = frozenset(mipmap)
        self.textures = False
        # the channels (-1: a sampler parameter) of implicit-LOD lookups written without a LOD
        self.level0_lookups: set[int] = set()
        self.sampler_flow: dict | None = None  # texture_calls.sampler_flow, made on first use
        self.lowp_written: set[int] = set()
        self.budget = budget  # llvmpipe's loop budget in the code (`loop`), else none of it
        self.path = path
        self.fma = fma
        self.float_to_uint = float_to_uint
        self.entry = model.entry
        if self.entry is None:
            raise engine_error(
                "the program has no mainImage (or main) to render", Location(path, 1, 1)
            )
        self.functions = list(model.reachable_functions())
        self.samples = any(  # texture lookups anywhere (texture_calls.lowp_tree asked)
            isinstance(n, A.Call) and str(n.callee).startswith(("texture", "texel"))
            for fn in self.functions
            for n in fn.node.body.walk()
        )
        self.facts = Facts(model, self.functions)  # (nir_fold.mix_form reads it: fold_context)
        # globals the functions read from module constants (constant_globals.py)
        self.frozen = frozen_globals(model, self.facts)
        # calls computed once, at load or once a frame (constant_globals.load_time_parts):
        # key -> (call, function, variant seed, state slots)
        self.load_calls: dict[tuple, tuple[A.Call, Symbol, frozenset, list[str]]] = {}
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
        self.discarded: str | None = None  # the discard flag's slot (discard_flag)
        self.last_line: tuple[str, int] | None = None
        self.needs: dict[str, list[str]] = {}  # function -> the state arrays it takes
        self.variants: set[tuple[int, frozenset]] = (
            set()
        )  # (function, uniform parameters) made or asked
        self.pending: list[tuple[Any, frozenset]] = []
        # the first dFdx/dFdy/fwidth call: its leaves are written `dfdx(v)` / `dfdy(v)`, which
        # only the lockstep rewrite computes (lanes.py: a block's lanes hold whole 2x2 quads)
        self.derivative: Any = None
        # the first local declared inside a switch: engine.generate refuses it with derivatives
        self.switch_local: Any = None
        self._fold_context: FoldValues | None = None  # fold_context(): made on first use
        self.registers: dict[int, list[str]] = {}  # a call -> its result's slots (kept_register)
        self.numpy_uniformity: dict[int, Uniformity] = {}  # a function -> the NumPy backend's

    def fold_context(self) -> FoldValues:
        """The NumPy backend's Mesa rewrites' context at the current function: the decisions this
        engine shares with it (nir_fold.mix_form: nir_lower_flrp's formula for a `mix`;
        nir_fold.zero_add: an added constant zero) and the rewrites it computes with this
        engine's values (fold_values.py)."""
        from .fold_values import FoldValues

        if self._fold_context is None:
            self._fold_context = FoldValues(self)
        assert self.fn is not None  # asked while a function is generated
        return self._fold_context.at(self.fn.sym, self.fn.sym is self.entry)

    # -- emission ------------------------------------------------------------------------------
    def emit(self, text: str) -> None:
        self.lines.append("    " * self.indent + text)

    def fresh(self, prefix: str = "t") -> str:
        self.n += 1
        return f"_{prefix}{self.n}"

    def tmp(self, value: str) -> str:
        if ATOM.match(value) and not value.startswith(("gf[", "gi[", "gu[", "gb[")):
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

        if (loc.path, loc.line) == self.last_line:
            return
        self.last_line = (loc.path, loc.line)
        text = source_line(loc.path, loc.line) or ""
        self.emit(f"# line {loc.line}: {comment_safe(text)}".rstrip())

    # -- constants -----------------------------------------------------------------------------
    def cf(self, v: float) -> str:
        if math.isnan(v):
            name, lit = "F_nan", "np.float32(np.nan)"
        elif math.isinf(v):
            name, lit = (
                ("F_inf", "np.float32(np.inf)") if v > 0 else ("F_minf", "np.float32(-np.inf)")
            )
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
                self.emit(f"{a} = np.zeros({n}, {DTYPE[base]})")
                out.append(Arr(a, 0, n, base))
        return out

    # -- variables -----------------------------------------------------------------------------
    def declare_local(self, sym: Symbol, node: Any) -> list:
        name = python_ident(sym.unique_name or sym.name, node)
        parts: list = []
        for k, (base, n) in enumerate(leaves(sym.type, node)):
            if n is None:
                parts.append(f"v_{name}_{k}")
            else:
                parts.append(Arr(f"a_{name}_{k}", 0, n, base))
        self.vars[id(sym)] = parts
        return parts

    def global_parts(self, sym: Symbol, node: Any) -> list:
        parts = self.vars.get(id(sym))
        if parts is None:
            parts = []
            for base, n in leaves(sym.type, node):
                off = self.slots[base]
                self.slots[base] += n or 1
                arr = KIND_ARRAY[base]
                parts.append(f"{arr}[{off}]" if n is None else Arr(arr, off, n, base))
            self.vars[id(sym)] = parts
        return parts

    def uniform_parts(self, name: str, node: Any) -> list:
        from ...shadertoy.wrapper import UNIFORMS_BY_NAME

        u = UNIFORMS_BY_NAME.get(name)
        if u is None:
            raise engine_error(f"unknown uniform '{name}'", node)
        if u.glsl_type.startswith("sampler"):  # its channel number (texture_calls.py)
            return [self.ci(int(name[len("iChannel") :]))]
        comps = 1 if u.glsl_type in ("float", "int") else int(u.glsl_type[-1])
        kind = "int" if u.glsl_type == "int" else "float"
        arr = "ui" if kind == "int" else "uf"
        if name not in self.uniforms:
            self.uniforms[name] = (kind, self.uslots[kind], u)
            self.uslots[kind] += comps * (u.array_size or 1)
        _, off, _ = self.uniforms[name]
        if u.array_size:  # component c of element k at off + c*n + k: the small arrays' layout
            return [
                f"{arr}[{off + c * u.array_size + k}]"
                for c in range(comps)
                for k in range(u.array_size)
            ]
        return [f"{arr}[{off + c}]" for c in range(comps)]

    def literal_global(self, sym: Symbol) -> list | None:
        """A `const` global of literals (`const float EPS = 0.001;`, `const vec3 K = vec3(1, 0,
        -2);`) as module constants: the value init_globals would store (a literal, its negation
        and a constructor of them are exact), read without a state array, folded by LLVM."""
        d = sym.node
        if sym.qualifier != "const" or not isinstance(d, A.Declarator) or d.init is None:
            return None
        t = sym.type
        base = t.base
        if not (t.is_scalar or t.is_vector) or base is None:  # (a scalar or vector has a base)
            return None
        if not _literal_tree(self.model, d.init, base):
            return None
        cv = self.model.const_value(d.init)
        if cv is None:
            return None
        values = flatten(cv)
        values = values * t.size if t.is_vector and len(values) == 1 else values
        return [self.const_part(base, v) for v in values]

    def var_parts(self, sym: Symbol, node: Any) -> list:
        if sym.kind in ("local", "param"):
            parts = self.vars.get(id(sym))
            if parts is None:
                raise engine_error(f"'{sym.name}' is used before its declaration", node)
            return parts
        if sym.kind == "global" and sym.qualifier == "uniform":
            from ...shadertoy.wrapper import fed_uniform

            if str(sym.type) in ("sampler2D", "samplerCube") and sym.name in _CHANNELS:
                return [self.ci(_CHANNELS.index(sym.name))]

            if fed_uniform(sym.name, str(sym.type)) is not None:
                return self.uniform_parts(sym.name, node)
            raise not_yet(f"the uniform '{sym.name}'", node)
        if sym.kind == "global":
            if sym.type.contains_opaque:
                raise not_yet(f"'{sym.name}': textures and channels", node)
            literal = self.literal_global(sym)
            if literal is not None:
                return literal
            parts = self.global_parts(sym, node)
            if id(sym) in self.frozen and self.fn is not None and self.fn.sym is not None:
                return frozen_parts(parts)  # (init_globals computes them in the state arrays)
            return parts
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
        if self.textures:
            from .texture_calls import IMPORT

            out += [IMPORT, ""]
            out.append("TEXTURES = True  # iChannel lookups: their words in ui from TM")
            out.append(f"TM = {max(1, self.uslots['int'])}")
            level0 = tuple(sorted(self.level0_lookups))
            out.append(f"LEVEL0 = {level0!r}  # channels whose texture() reads level 0 (-1: any)")
        out.append(f"FMA = {self.fma!r}  # llvm.fmuladd is fused on this CPU (runtime.HOST_FMA)")
        out.append(f"SLOTS = {dict(self.slots)!r}  # global state per scalar type")
        out.append(f"USLOTS = {dict(self.uslots)!r}")
        layout = {k: (v[0], v[1]) for k, v in self.uniforms.items()}
        out.append(f"UNIFORMS = {layout!r}  # uniform -> (kind, offset in uf/ui)")
        out.append(f"LOOPS = {self.loop_lines!r}  # loop id -> (file, line, column)")
        out.append(f"{BUDGET_ON if self.budget else BUDGET_OFF}  # llvmpipe's loop budget (`lc`)")
        loc = getattr(self.entry.node, "loc", None) or Location(self.path, 1, 1)
        entry = (loc.path, loc.line, loc.column, self.entry.name)
        out.append(
            f"ENTRY = {entry!r}  # mainImage (file, line, column, name): "
            "where a frame over budget stops"
        )
        if self.derivative is not None:
            out.append("QUADS = True  # dFdx/dFdy: lockstep blocks of 2x2 quads only (lanes.py)")
        out.append("")
        for name, lit in self.consts.items():
            out.append(f"{name} = {lit}")
        out.append("")
        for f in funcs + [init]:
            out += ["", "@jit", *f.split("\n"), ""]
        out += ["", "@jit_loop", *shade.split("\n"), ""]  # (the pixel loop's: module_text)
        render = RENDER if self.budget else RENDER.replace("uf, ui, lc,", "uf, ui,")
        resets = reset_kinds(written_state(ast.parse("\n".join(funcs + [shade])).body))
        for kind in sorted(set(KIND_ARRAY.values()) - resets):  # (its template all frame)
            render = render.replace(f"                aset({kind}, 0, gt{kind[1]})\n", "")
        out.append(render)
        if self.frozen or self.load_calls:
            out.append(FREEZE)
        return "\n".join(out) + "\n"

    def gen_globals(self) -> None:
        self.emit(f"def init_globals({', '.join(self.state())}):")
        self.indent += 1
        self.emit('"""Global variables at the start of every invocation."""')
        self.fn = FnState(None)
        for sym in self.model.globals:
            if (
                sym.kind != "global"
                or sym.type.contains_opaque
                or sym.qualifier in ("uniform", "in", "out")
            ):
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
        emit_load_time_calls(self)
        self.emit("return 0")
        self.indent -= 1
        self.fn = None

    def gen_shade(self) -> None:
        entry = self.entry
        name = self.fn_name(entry)
        self.emit(f"def shade({', '.join(self.state())}, fx, fy, px, py):")
        self.indent += 1
        self.emit('"""One pixel: fragCoord (fx, fy), pixel centre (px, py) -> RGBA."""')
        if self.frag4 is not None:
            for part, v in zip(self.frag4, ("px", "py", "F32(0.5)", "F32(1.0)")):
                self.emit(f"{part} = {v}")
        if entry.name == "main":
            outs = [
                g
                for g in self.model.globals
                if g.qualifier == "out" and g.kind == "global" and str(g.type) == "vec4"
            ]
            if not outs:
                raise engine_error("a plain GLSL shader needs an 'out vec4' variable", entry.node)
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
            if id(entry) in self.facts.may_discard:
                self.emit(f"if {self.discard_flag()}:  # a discarded pixel keeps the clear colour")
                self.emit("    return F32(0.0), F32(0.0), F32(0.0), F32(0.0)")
            if self.keep_alpha:
                self.emit(f"return {color[0]}, {color[1]}, {color[2]}, {color[3]}  # a Buffer")
            else:
                self.emit(f"return {color[0]}, {color[1]}, {color[2]}, F32(1.0)  # RGB: alpha 1")
        self.indent -= 1

    # -- functions -----------------------------------------------------------------------------
    def state(self) -> list[str]:
        """The state arrays shade and init_globals take (`lc` only with the loop budget)."""
        return [a for a in STATE if a != "lc" or self.budget]

    def fn_name(self, sym: Symbol) -> str:
        return "f_" + python_ident(sym.unique_name or sym.name, sym.node)

    def variant_name(self, sym: Symbol, seed: frozenset) -> str:
        """A function's name, with the indices of its lane-uniform parameters when it has any
        (`f_map__u0_2`): the NumPy backend passes a value of one lane to the parameter there,
        which its constant folding reads as a constant (see `lane_uniform`)."""
        base = self.fn_name(sym)
        return base if not seed else base + "__u" + "_".join(str(i) for i in sorted(seed))

    def gen_function(self, sym: Symbol, seed: frozenset = frozenset()) -> None:
        node = sym.node
        self.variants.add((id(sym), seed))
        params_u = {
            id(self.model.symbol_of(p)) for i, p in enumerate(node.proto.params) if i in seed
        }
        # out arguments by the callee's values (out_values): what the NumPy backend's arrays hold
        uni = Uniformity(self.model, self.facts, sym, sym is self.entry, params_u, out_values=True)
        self.fn = fs = FnState(sym, uni)
        proto = node.proto
        params: list[str] = []
        prologue: list[tuple[list, Any, str]] = []
        for k, (p, (pname, ptype, direction)) in enumerate(zip(proto.params, sym.params)):
            psym = self.model.symbol_of(p)
            if (
                psym is None
            ):  # an unnamed parameter still takes its argument and returns its out value
                psym = Symbol(f"_unnamed{k}", "param", ptype, node=p, unique_name=f"_unnamed{k}")
            parts = self.declare_local(psym, p)
            if direction == "out":
                prologue.append((parts, ptype, p))
            else:
                for part in parts:
                    params.append(part.name if isinstance(part, Arr) else part)
            if direction != "in":
                fs.outs += parts
        for i, program in sorted(nir_chain_params(self, sym).items()):  # a caller's chain
            params += [f"_c{i}f", f"_c{i}b"] + [f"_c{i}k{m}" for m in range(program.slots())]
        params += ray_param_names(self, sym)  # a caller's ray (nir_fold.ray_dots)
        if self.sunk_chain(sym) is not None:  # a caller's constant sunk into the returned sum
            params += ["_kf"] + [f"_k{j}" for j in range(len(leaves(sym.type, node)))]
        def_at = len(self.lines)
        self.emit("")  # the def line, once the state arrays the body uses are known
        self.indent += 1
        self.emit(
            f'"""{comment_safe(sym.signature(), 150)} (line '
            f'{proto.loc.line if proto.loc else "?"})."""'
        )
        for part in [p for p in self.vars_of_params(sym) if isinstance(p, Arr)]:
            self.emit(f"{part.name} = acopy({part.name})  # arrays are passed by value")
        for parts, ptype, p in prologue:
            self.write(parts, self.zero_parts(ptype, p), fresh_arrays=True)
        ended = self.block(node.body.stmts)
        if not ended:  # the end of the body (also after an if/else that returned in both branches)
            self.emit(
                self.return_text(None if sym.type.is_void else self.zero_parts(sym.type, node))
            )
        self.indent -= 1
        used = set(STATE_NAME.findall("\n".join(self.lines[def_at + 1 :])))
        name = self.fn_name(sym)
        if not seed:
            self.needs[name] = [a for a in STATE if a in used]
        self.lines[def_at] = (
            f"def {self.variant_name(sym, seed)}({', '.join(self.needs[name] + params)}):"
        )
        self.fn = None

    def vars_of_params(self, sym: Symbol) -> list:
        out = []
        for p, (_, _, d) in zip(sym.node.proto.params, sym.params):
            psym = self.model.symbol_of(p)
            if psym is not None and d != "out":
                out += self.vars[id(psym)]
        return out

    def return_text(self, value: list | None) -> str:
        fs = self.fn
        assert fs is not None  # generating a function's body
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
        if isinstance(d, A.PrecisionDeclaration) or (
            isinstance(d, A.VariableDeclaration) and not d.declarators
        ):
            return
        if not isinstance(d, A.VariableDeclaration):
            raise not_yet("this declaration inside a function", s)
        for dec in d.declarators:
            sym = self.model.symbol_of(dec)
            if sym is None:
                continue
            self.comment(dec)
            fs = self.fn
            if self.switch_local is None and fs and any(k == "switch" for k, _ in fs.loops):
                self.switch_local = dec
            value: list | None = None
            if dec.init is not None:
                merged = self.component_write(dec)  # (NIR's SSA per component: nir_fold)
                init = merged if merged is not None else self.expr(dec.init)
                value = self.keep_term(dec, init).parts
            parts = self.declare_local(sym, dec)
            if value is None:
                value = self.zero_parts(sym.type, dec)
            self.write(parts, value, fresh_arrays=True)

    def _stmt_If(self, s: A.If) -> None:
        self.comment(s)
        self.merged_registers(s)
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

    def merged_registers(self, s: A.If) -> None:
        """Before a divergent kept branch, the value a lane outside it holds for each local of
        its then arm that llvmpipe keeps in a register (nir_fold.merged_register): zero, or the
        component of the variable it is merged into. The local is written here, so the lockstep
        rewrite writes its value in the arm under the arm's mask over that one, as the NumPy
        backend's `X.put` (per pixel the arm's write replaces it)."""
        fs = self.fn
        if fs is None or fs.sym is None or not isinstance(s.then, A.Compound):
            return

        for node in nir_fold.arm_values(s.then):
            found = nir_fold.merged_register(self.fold_context(), node)
            if found is None or self.uniformity().is_uniform(s.cond):
                continue
            sym = self.model.symbol_of(node if isinstance(node, A.Declarator) else node.target)
            assert sym is not None  # (a local the checker declared)
            if isinstance(node, A.Declarator):
                parts = self.declare_local(sym, node)
            else:
                parts = self.vars[id(sym)]
            if found.target is None:
                fill = self.zero_parts(sym.type, node)
            else:
                fill = [self.expr(found.target).parts[found.component]]
            self.comment(node)
            self.write(parts, fill, fresh_arrays=True)

    def uniformity(self) -> Uniformity:
        """The NumPy backend's analysis of the current function (which branches diverge)."""
        fs = self.fn
        assert fs is not None and fs.sym is not None
        uni = self.numpy_uniformity.get(id(fs.sym))
        if uni is None:
            uni = Uniformity(self.model, self.facts, fs.sym, fs.sym is self.entry)
            self.numpy_uniformity[id(fs.sym)] = uni
        return uni

    def _stmt_Return(self, s: A.Return) -> bool:
        self.comment(s)
        value = self.expr(s.value).parts if s.value is not None else None
        if value is not None:
            value = [self.atom(p) if not isinstance(p, Arr) else p for p in value]
            value = self.sunk_return(value)
        assert self.fn is not None  # generating a function's body
        for kind, _ in self.fn.loops if self.budget else ():
            if kind == "loop":  # each loop it leaves (not a switch): its pass costs 1
                self.emit("tick_end(lc)")
        self.emit(self.return_text(value))
        return True

    def _stmt_Break(self, s: A.Break) -> bool:
        self.emit("break")
        return True

    def _stmt_Continue(self, s: A.Continue | None) -> bool:
        assert self.fn is not None  # generating a function's body
        kind, cont = self.fn.loops[-1]
        if kind == "switch":  # leave the switch's one-pass loop, then continue the loop around
            if cont[0] is None:
                cont[0] = self.fresh("sc")
            self.emit(f"{cont[0]} = True")
            self.emit("break")
            return True
        if cont is not None:
            cont()
        self.emit("continue")
        return True

    def kept_register(self, e: A.Call, fn: Symbol, value: list) -> list:
        """The parts of the result of the call `e` of `fn`, where llvmpipe keeps that result in a
        register (nir_fold.register_call: returns merged from inside a branch, in a function that
        takes derivatives, in a loop NIR keeps): the value goes through per-pixel slots of this
        call, which the lockstep rewrite writes under the mask, so a lane the mask leaves out
        reads what the call gave it the last time it ran for it (zero before), as the NumPy
        backend's tiles.LaneHelpers.reg. Not where the NumPy backend computes the call for every
        lane (all arguments uniform by its own analysis, a function that reads no varying
        global): there it has no mask."""
        fs = self.fn
        if fs is None or fs.sym is None or not value:
            return value

        if not nir_fold.register_call(self.fold_context(), e, fn):
            return value
        uni = self.uniformity()
        if self.facts.closed(fn) and all(
            uni.is_uniform(a) or d == "out" for a, (_, _, d) in zip(e.args, fn.params)
        ):
            return value
        if any(isinstance(p, Arr) for p in value):
            raise not_yet("a call's array result kept in llvmpipe's register (derivatives)", e)
        slots = self.registers.get(id(e))
        if slots is None:  # one register a call in the GLSL text, for every variant of its function
            slots = []
            for base, _ in leaves(fn.type, e):
                slots.append(f"{KIND_ARRAY[base]}[{self.slots[base]}]")
                self.slots[base] += 1
            self.registers[id(e)] = slots
        out = []
        for slot, part in zip(slots, value, strict=True):
            self.emit(f"{slot} = {part}")
            out.append(self.tmp_fresh(slot))
        return out

    def discard_flag(self) -> str:
        """The per-pixel bool slot that says the pixel was discarded (one for the program; the
        state is reset for every pixel, so it starts False)."""
        if self.discarded is None:
            off = self.slots["bool"]
            self.slots["bool"] += 1
            self.discarded = f"gb[{off}]"
        return self.discarded

    def leave_discarded(self, node: Any) -> None:
        """Return from the current function (any value: the pixel's output is dropped) once the
        pixel is discarded; the callers do the same after each call that may discard."""
        fs = self.fn
        if fs is None or fs.sym is None:
            raise not_yet("discard in a global initializer", node)
        rtype = fs.sym.type
        self.emit(self.return_text(None if rtype.is_void else self.zero_parts(rtype, node)))

    def _stmt_Discard(self, s: A.Discard) -> bool:
        self.comment(s)
        self.emit(f"{self.discard_flag()} = True")
        self.leave_discarded(s)
        return True

    def _stmt_Switch(self, s: A.Switch) -> None:
        """A switch as a loop of one pass: the index of the section the selector enters at (its
        case's, else default's, else past the end), then each section when that index is at or
        before it (fall-through), `break` leaving the loop; a `continue` sets a flag, leaves,
        and continues the enclosing loop after it."""
        self.comment(s)
        sel = self.atom(self.expr(s.expr).parts[0])
        sections: list[tuple[list, list]] = []  # (case labels, None for default; statements)
        for st in s.body:
            if isinstance(st, A.Case):
                if not sections or sections[-1][1]:
                    sections.append(([], []))
                sections[-1][0].append(st.expr)
            elif sections:  # (a statement before the first label is never run)
                sections[-1][1].append(st)
        entry = self.fresh("sw")
        default = next((k for k, (labels, _) in enumerate(sections) if None in labels), None)
        self.emit(f"{entry} = {len(sections) if default is None else default}")
        for k, (labels, _) in enumerate(sections):
            for label in labels:
                if label is not None:
                    self.emit(f"if {sel} == {self.expr(label).parts[0]}:")
                    self.emit(f"    {entry} = {k}")
        flag: list[str | None] = [None]
        at = len(self.lines)
        self.emit("")  # the continue flag's initialisation, once it is known to be needed
        self.emit("while True:")
        self.indent += 1
        assert self.fn is not None  # generating a function's body
        self.fn.loops.append(("switch", flag))
        for k, (_, stmts) in enumerate(sections):
            if not stmts:
                continue
            self.emit(f"if {entry} <= {k}:")
            self.indent += 1
            n = len(self.lines)
            if not self.block(stmts) and len(self.lines) == n:
                self.emit("pass")
            self.indent -= 1
        self.emit("break")
        self.fn.loops.pop()
        self.indent -= 1
        if flag[0] is not None:
            self.lines[at] = "    " * self.indent + f"{flag[0]} = False"
            self.emit(f"if {flag[0]}:")
            self.indent += 1
            self._stmt_Continue(None)
            self.indent -= 1

    def condition(self, cond: Any) -> str:
        if isinstance(cond, A.ConditionDeclaration):
            sym = self.model.symbol_of(cond)
            assert sym is not None  # every declaration of a checked program has its symbol
            value = self.expr(cond.init).parts
            parts = self.declare_local(sym, cond)
            self.write(parts, value)
            return parts[0]
        return self.expr(cond).parts[0]

    def _stmt_For(self, s: A.For) -> None:
        self.comment(s)
        if s.init is not None:
            self.stmt(s.init)
        self.enter_unrolled(s)
        step = (lambda: self.expr(s.step)) if s.step is not None else None
        self.loop(s, s.cond, s.body, step, do_while=False)

    def _stmt_While(self, s: A.While) -> None:
        self.comment(s)
        self.loop(s, s.cond, s.body, None, do_while=False)

    def enter_unrolled(self, loop: A.For) -> None:
        """Before a loop NIR unrolls (as the NumPy backend's transpile/sum_chains.enter_unrolled):
        the value before a chain that starts there, kept, the temporaries a later copy's merge
        reads (nir_fold.later_values), and a count of its passes where its steps' constants (or
        a merge) differ from copy to copy."""

        fs = self.fn
        assert fs is not None  # generating a function's body
        ctx = self.fold_context()
        entry = nir_fold.sum_entry(ctx, loop)
        if entry is not None and entry.root:
            self.chain_base(entry, [self.read(p) for p in self.var_parts(entry.sym, loop)])
        for value, sym in nir_fold.later_values(ctx, loop):  # (a later copy's merge reads it)
            parts = [self.tmp_fresh(self.read(p)) for p in self.var_parts(sym, loop)]
            ctx.fold_state.kept_slots[id(value)] = (Val(self.type_of(value), parts), fs)
        if nir_fold.indexed_loop(ctx, loop):
            name = self.fresh("ix")
            self.emit(f"{name} = 0")
            fs.sum_index[id(loop)] = name

    def end_of_unrolled_body(self, loop: A.For) -> None:
        """The loop's pass count advanced (:meth:`enter_unrolled`)."""
        fs = self.fn
        assert fs is not None  # generating a function's body
        name = fs.sum_index.get(id(loop))
        if name is not None:
            self.emit(f"{name} = {name} + 1")

    def _stmt_DoWhile(self, s: A.DoWhile) -> None:
        self.comment(s)
        self.loop(s, s.cond, s.body, None, do_while=True)

    def loop(self, s: Any, cond: Any, body: Any, step: Any, do_while: bool) -> None:
        """GLSL's loops as the NumPy backend's (transpile/statements.py loop_top): the top of
        every pass counts it (a runaway loop past LOOP_CAP is an error at its line) and pays
        the pass before it from llvmpipe's budget (scalar.tick), which stops the loop when none
        is left; the pass a loop leaves by its condition or a `break` pays after the loop, one
        a loop (`stopped`: not when the budget stopped it), and a return pays one per loop it
        leaves (`tick_end`): every pass costs 1 when it ends, as in llvmpipe. Only in a module
        made with the budget (`budget`; engine.CompiledProgram.loop_limit makes it): the others
        neither count it nor pass `lc`."""
        lid = len(self.loop_lines) + 1
        loc = s.loc
        self.loop_lines[lid] = (loc.path, loc.line, loc.column)
        count = self.fresh("n")
        stopped = self.fresh("s")
        self.emit(f"{count} = 0")
        if self.budget:
            self.emit(f"{stopped} = False")
        self.emit("while True:")
        self.indent += 1
        self.emit(f"{count} += 1")
        self.emit(f"if {count} > {LOOP_CAP}:  # a runaway loop: the engine reports its line")
        self.emit(f"    raise LoopCapError({lid})")
        if self.budget:
            self.emit(f"if tick(lc, {count}):")  # uniform: one call a block in lockstep
            self.emit(f"    limited(lc, {lid})")
            self.emit(f"    {stopped} = True")
            self.emit("    break")

        def test() -> None:
            if cond is not None:
                c = self.condition(cond)
                self.emit(f"if not {c}:")
                self.emit("    break")

        if not do_while:
            test()
        cont = step if not do_while else test
        assert self.fn is not None  # generating a function's body
        self.fn.loops.append(("loop", cont))
        ended = self.stmt(body)
        if isinstance(s, A.For) and not ended:
            self.end_of_unrolled_body(s)
        self.fn.loops.pop()
        if not ended:
            if do_while:
                test()
            elif step is not None:
                step()
        self.indent -= 1
        if self.budget:
            self.emit(f"if not {stopped}:  # the pass that left the loop")
            self.emit("    tick_end(lc)")


def _literal_tree(model: Model, e: Any, base: str) -> bool:
    """Literals of type `base`, their negations and vector constructors of them only."""
    if isinstance(e, (A.FloatLiteral, A.IntLiteral, A.BoolLiteral)):
        return model.type_of(e).base == base
    if isinstance(e, A.Unary) and e.op == "-":
        return _literal_tree(model, e.operand, base)
    if isinstance(e, A.Call) and isinstance(model.call_target(e), Constructor):
        t = model.type_of(e)
        return (
            (t.is_scalar or t.is_vector)
            and t.base == base
            and all(_literal_tree(model, a, base) for a in e.args)
        )
    return False


_CHANNELS = ("iChannel0", "iChannel1", "iChannel2", "iChannel3")


def _safe(text: str) -> str:
    return comment_safe(text, 200)
