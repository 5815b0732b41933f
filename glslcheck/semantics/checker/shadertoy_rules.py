"""What Shadertoy adds to GLSL ES: its uniforms and output, the Common tab's limits, `mainImage`,
WebGL.

Owns the names the Shadertoy wrapper declares (shadertoy/wrapper.py's prelude and footer: the
uniforms a tab sees, the Common tab compiled alone with only iDate and iSampleRate, the output
variable), the uniforms Shadertoy renamed, the entry point (`mainImage(out vec4, in vec2)` in a
tab, `main()` in a plain GLSL file) and how a WebGL rule is reported (webgl_rules.py).
"""

from __future__ import annotations

from ...base.diagnostics import Location
from ...frontend import syntax as A
from ...frontend.preprocess import WRAPPER_COLOR
from ...language import builtin_functions as B
from ...language import glsl_types as T
from ..model import ERROR, Symbol
from .state import CheckerState

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from typing import Any

# What the Shadertoy wrapper declares besides the uniforms (shadertoy/wrapper.py's footer and
# prelude).
WRAPPER_OUTPUT = "shadertoy_out_color"

# Uniforms Shadertoy renamed (iGlobalTime became iTime in 2017); old shaders still use them.
RENAMED_UNIFORMS = {"iGlobalTime": "iTime"}


class ShadertoyRules(CheckerState):
    """Shadertoy's declarations, entry point and WebGL reporting, for `Checker`."""

    # -- what Shadertoy declares ---------------------------------------------------------------
    def declare_predefined(self) -> None:
        for name, var in B.BUILTIN_VARIABLES.items():
            sym = Symbol(
                name,
                "builtin-var",
                var.type,
                qualifier=var.storage,
                unique_name=name,
                const_value=var.value,
            )
            self.builtin_scope.names[name] = sym
        if self.plain:
            return
        # Shadertoy's uniforms and output are ordinary globals of the compiled program.
        allowed = B.COMMON_TAB_UNIFORMS if self.tab == "Common" else B.SHADERTOY_UNIFORMS.keys()
        for name, u in B.SHADERTOY_UNIFORMS.items():
            if name in allowed:
                self.scope.names[name] = Symbol(
                    name,
                    "uniform",
                    self.channel_types.get(name, u.declared_type),
                    qualifier="uniform",
                    unique_name=name,
                )
                self.unique.given.add(name)
        if self.tab != "Common":
            self.scope.names[WRAPPER_OUTPUT] = Symbol(
                WRAPPER_OUTPUT, "global", T.VEC4, qualifier="out", unique_name=WRAPPER_OUTPUT
            )

    def in_macro_entry(self) -> bool:
        """In the entry function modelled for a `#define mainImage(O, U)`
        (frontend/preprocess/driver.py): the macro expands in the pass's wrapper, where every
        uniform is declared, even when the macro is defined in Common (Common compiled alone never
        expands it)."""
        f = self.func
        return (
            f is not None
            and f.name == "mainImage"
            and bool(f.params)
            and f.params[0][0] == WRAPPER_COLOR
        )

    def common_uniform_error(self, n: A.Identifier) -> None:
        self.error(
            f"'{n.name}' is not available in the Common tab: the Common tab is compiled by "
            f"Shadertoy without {n.name}; pass it as a parameter from mainImage",
            n,
            help=f"add a parameter to this function and pass {n.name} from mainImage",
        )

    # -- WebGL ---------------------------------------------------------------------------------
    def webgl(self, problem: tuple[str, str] | None, node: Any) -> None:
        """A WebGL rule (webgl_rules.py: what Shadertoy's browser rejects): an error in a Shadertoy
        tab, a warning in a plain GLSL ES file, which need not run in WebGL."""
        if problem:
            self.error(
                problem[0], node, help=problem[1], severity="warning" if self.plain else "error"
            )

    # -- the entry point -----------------------------------------------------------------------
    def find_entry(self, name: str) -> None:
        model = self.model
        overloads = model.functions.get(name, [])
        start = Location(self.tab_path, 1, 1)
        if name == "main":
            for fn in overloads:
                if not fn.params:
                    model.entry = fn
            if model.entry is None:
                self.error("a GLSL fragment shader needs 'void main()'", start)
            return
        want = [T.VEC4, T.VEC2]
        for fn in overloads:
            if [t for _, t, _ in fn.params] == want:
                model.entry = fn
                where = (
                    fn.node.proto.name_loc
                    if fn.node is not None and fn.node.proto.name_loc.line
                    else start
                )
                if fn.params[0][2] == "in":
                    self.warning(
                        "mainImage's first parameter should be 'out vec4 fragColor': "
                        "as 'in' the color "
                        "it computes is thrown away",
                        where,
                        help="declare it as 'void mainImage(out vec4 fragColor, "
                        "in vec2 fragCoord)'",
                    )
                if fn.params[1][2] != "in":
                    self.warning(
                        "mainImage's second parameter should be 'in vec2 fragCoord'", where
                    )
                if not fn.type.is_void and fn.type is not ERROR:
                    self.warning(f"mainImage should return void, not '{fn.type}'", where)
                return
        if not overloads:
            self.error(
                f"the {self.tab} tab has no 'mainImage' function",
                start,
                help="Shadertoy calls 'void mainImage(out vec4 fragColor, in vec2 fragCoord)'; "
                "define it",
            )
        else:
            got = "; ".join(fn.signature() for fn in overloads)
            self.error(
                f"'mainImage' has the wrong parameters ({got}); Shadertoy calls mainImage(vec4, "
                "vec2)",
                start,
                help="declare it as 'void mainImage(out vec4 fragColor, in vec2 fragCoord)'",
            )
