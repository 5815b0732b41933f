"""The Transpiler, made of its passes, and the module it writes: constants, one `def` per
function, `init_globals` and Shadertoy's `shade`; `transpile` and `transpile_shader`, the entry
points."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ....base.diagnostics import Location
from ....base.recursion import enter_deep, leave_deep
from ....frontend import syntax as A
from ....semantics.analysis import origins
from ...cpu_core.common import LOOP_CAP, comment_safe
from ...cpu_core.facts import Facts, SideEffects
from ...cpu_core.fold_state import FoldState
from .common import SMALL_STATE, UNDEFINED_MODES, _error, check_program
from .expressions import Expressions
from .functions import Functions
from .limits import PythonLimits, compile_generated, lane_state, too_complex
from .names import Names
from .state import FnState
from .statements import Statements

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ....semantics.model import Model, Symbol


class Transpiler(Names, Functions, Statements, Expressions, PythonLimits):
    """`Transpiler(model, tab_path).module()` -> (Python source, meta dict)."""

    COMPACT_MIN_NODES = 24  # syntax nodes: smaller regions without calls or loops run masked
    # The tracing transpiler's expressions to report, id(expr) -> (hook, statement, name)
    # (tracing.py); None when not tracing.
    watched: dict[int, tuple[str, Any, str]] | None = None

    def __init__(
        self,
        model: Model,
        path: str = "<shader>",
        source_text: str | None = None,
        keep_alpha: bool = False,
        undefined: str = "zero",
        undefined_sites: tuple[int, ...] | None = None,
    ) -> None:
        self.keep_alpha = keep_alpha  # a Buffer pass: Shadertoy keeps the alpha mainImage wrote
        # What the program's undefined reads (semantics.analysis.undefined) see: "zero", WebGL's
        # values, or "vary": a value drawn anew at each (X.undefined), so that pixels whose colour
        # depends on one differ between the two modules (verify's taint of undefined values);
        # `undefined_sites` limits "vary" to those origins (indexes into `origins(model)`).
        if undefined not in UNDEFINED_MODES:
            raise ValueError(f"undefined must be one of {', '.join(UNDEFINED_MODES)}")
        self.undefined = undefined
        varied = origins(model) if undefined == "vary" else {}
        if undefined_sites is not None:
            keep = {k for i, k in enumerate(varied) if i in undefined_sites}
            varied = {k: v for k, v in varied.items() if k in keep}
        self.undefined_origins = varied
        self.model = model
        self.path = path
        self.entry = model.entry
        if self.entry is None:
            raise _error("the program has no mainImage (or main) to render", Location(path, 1, 1))
        self.functions = [f for f in model.reachable_functions()]
        self.facts = Facts(model, self.functions)
        self.fold_state = FoldState()  # the Mesa rewrites' memo of this program (fold_state.py)
        self.lines: list[str] = []
        self.consts: dict[str, str] = {}  # name -> defining expression
        self.float_consts: dict[
            str, float
        ] = {}  # a float literal's name -> its value (const_float)
        self.const_exprs: dict[str, str] = {}  # printed constant expression -> its C_x name
        self.in_const = False
        self.zero_defs: dict[str, str] = {}
        self.fn_names: dict[int, str] = {}
        self.struct_names: dict[int, str] = {}
        self.n = 0
        self.regions: dict[
            int, tuple[str, str, str, int]
        ] = {}  # id -> (kind, function, path, line)
        self.loops: dict[int, tuple[str, int, int]] = {}
        self.fn: FnState | None = None
        self.indent = 0
        self.last_line: tuple[str, int] | None = None
        self.plain = self.entry.name == "main"
        self.uniforms: set[str] = set()
        self.helpers: list[str] = []  # functions split off the current one (PythonLimits.outline)
        self._heights: dict[int, int] = {}  # node id -> memoized facts about its subtree
        self.side_effects = SideEffects(model)  # has_effects, memoized per node
        self._hoists: dict[int, bool] = {}
        self._derivs: dict[int, bool] = {}
        self._line_names: dict[str, frozenset] = {}
        self.dead_lane_reads: dict[int, dict[int, int]] = {}  # dead_lanes.read_counts' memo

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
        if self.undefined != "zero":  # (the normal module is the same text as without the option)
            meta["undefined"] = self.undefined
        scalars, at = lane_state(self.model, self.functions)
        if scalars > SMALL_STATE and at is not None:
            loc = at.loc
            meta["lane_state"] = (scalars, loc.path, loc.line, loc.column)
        out = [self.header(), "", f"SHADER_META = {meta!r}", ""]
        out.append('if __name__ == "__main__":  # run on its own: python this_file.py --help')
        out.append("    from glslcheck.backends.numpy_engine.program import standalone_globals")
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
        out.append('if __name__ == "__main__":')
        out.append("    from glslcheck.backends.numpy_engine.program import run_standalone")
        out.append("    run_standalone(globals())")
        return "\n".join(out) + "\n", meta

    @staticmethod
    def _fed(sym: Symbol) -> bool:
        """Whether a declared uniform gets Shadertoy's value (shadertoy.fed_uniform), as on GL."""
        from ....shadertoy.wrapper import fed_uniform

        u = fed_uniform(sym.name, str(sym.type))
        return u is not None and not u.glsl_type.startswith("sampler")

    def _uniforms_from_model(self) -> set[str]:
        try:
            return set(
                self.model.uniforms_read()
            )  # samplers included: channels.ChannelInput values
        except Exception:  # pragma: no cover - the model's API is still settling
            return set()

    def header(self) -> str:
        from ....base.version import __version__

        src = comment_safe(self.path, 200)
        return (
            f'"""Generated by glslcheck {__version__} from {src} (GLSL ES 3.00) -- do not edit.\n\n'
            "Each GLSL function is a Python function over lanes (one lane per pixel); see the\n"
            "docstring of glslcheck/backends/numpy_engine/transpile/__init__.py for the "
            "execution model and of\n"
            "glslcheck/backends/numpy_engine/runtime.py for the value representation.\n\n"
            "Run it on its own (needs numpy and glslcheck's runtime):\n"
            "    python shader.py -o out.png --size 800x450 --time 0\n"
            "or from Python: "
            "glslcheck.backends.numpy_engine.program.load_module('shader.py').render(...)\n"
            '"""'
        )

    def gen_globals(self) -> None:
        self.emit("def init_globals(S):")
        self.indent += 1
        self.emit(
            '"""Global variables at the start of every invocation (their initializers are '
            'constant)."""'
        )
        empty = True
        fake = type("G", (), {"name": "<globals>", "node": None})()
        self.fn = FnState(fake, None, True)
        for sym in self.model.globals:
            if sym.kind != "global" or sym.type.contains_opaque:
                continue  # samplers: an error where they are used
            d = sym.node
            init = d.init if isinstance(d, A.Declarator) else None
            self.comment_line(d)
            # (without an initializer: zero, WebGL's value, or in the "vary" mode a value drawn
            # for a global the checker finds read before it is assigned)
            value = self.expr(init, None) if init is not None else self.initial(sym.type, d)
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
            outs = [
                g
                for g in self.model.globals
                if g.qualifier == "out" and g.kind == "global" and str(g.type) == "vec4"
            ]
            self.emit(f"{name}(S, None)")
            if not outs:
                raise _error("a plain GLSL shader needs an 'out vec4' variable", entry.node)
            self.emit(f"return {self.var_name(outs[0], entry.node)}")
        else:
            self.emit(
                '"""Shadertoy\'s main(): color = vec4(1e20); mainImage(color, fragCoord); '
                'its RGB."""'
            )
            args = []
            init = (
                self.consts.setdefault("C_vec4_1e20", "rt.vec(4, rt.const_float(1e20))")
                and "C_vec4_1e20"
            )
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


@dataclass
class Transpiled:
    """The generated module: its source, its metadata and the file name it is registered under."""

    source: str
    meta: dict
    filename: str
    code: Any = None  # the compiled module (compiled once, to check it: see `compile_generated`)


def transpile(
    model: Model,
    path: str = "<shader>",
    keep_alpha: bool = False,
    undefined: str = "zero",
    undefined_sites: tuple[int, ...] | None = None,
) -> Transpiled:
    """Generate the Python module of a checked program (model from glslcheck.semantics); a located
    GlslError when it is too complex for Python (see `PythonLimits`). `undefined`: see
    `Transpiler`."""
    tr = Transpiler(
        model, path, keep_alpha=keep_alpha, undefined=undefined, undefined_sites=undefined_sites
    )
    enter_deep()  # expressions nested as deep as the checker allows
    try:
        source, meta = tr.module()
    except RecursionError:
        where = getattr(tr, "where", None)
        raise too_complex(
            "it is nested too deeply", getattr(where, "loc", None) or Location(path, 1, 1)
        ) from None
    finally:
        leave_deep()
    filename = f"<glslcheck-numpy {comment_safe(path, 200)}>"
    return Transpiled(source, meta, filename, compile_generated(source, filename, path))


def transpile_shader(
    shader: Any,
    tab: str | None = None,
    undefined: str = "zero",
    undefined_sites: tuple[int, ...] | None = None,
) -> Transpiled:
    """Parse, check and transpile a Shadertoy shader (its Image tab, or a plain GLSL file, or the
    Buffer tab `tab`, which keeps its alpha); `undefined`: see `Transpiler`."""
    from ....frontend.parser import parse_shader

    if tab is None:
        tab = "Image" if "Image" in shader.tabs else ("GLSL" if "GLSL" in shader.tabs else "Image")
    pr = parse_shader(shader, tab)
    model = check_program(pr)
    src = shader.tabs.get(tab)
    return transpile(
        model,
        src.path if src is not None else shader.root,
        keep_alpha=tab.startswith("Buffer"),
        undefined=undefined,
        undefined_sites=undefined_sites,
    )
