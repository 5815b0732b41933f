"""The preprocessor's driver: each unit read line by line (directive lines to the directives, runs
of active text to macro expansion, inactive lines blanked), units in order as one program, and
Shadertoy's call of a user's `mainImage` macro modelled after the last unit.
"""

from __future__ import annotations

from ...base.diagnostics import Diagnostic, GlslError
from ...base.regexes import compiled
from ...shadertoy.sources import Source
from .context import PreprocessorState
from .directives import handle_directive
from .expansion import expand_text_run
from .result import PPResult
from .tokens import WS
from .units import RULE, Unit

# The first parameter of the entry function modelled for a `mainImage` macro (see _wrapper_call):
# the checker knows that function's body by it (it is compiled in the pass, never in Common alone).
WRAPPER_COLOR = "glslcheck_color"
_LEAD_WS_RE = compiled(rf"[{WS}]*")


def preprocess(
    units: list[Source], predefined: dict[str, str] | None = None, *, shadertoy: bool = True
) -> PPResult:
    """Preprocess `units` in order (Shadertoy: Common, then the pass's tab) as one program.

    Raises GlslError at the first error, located in the user's file."""
    pp = PreprocessorState(predefined, shadertoy)
    for index, src in enumerate(units):
        run_unit(pp, Unit(src, index))
    if shadertoy and units and units[-1].tab != "Common":
        _wrapper_call(pp, len(units))
    return pp.result()


def _wrapper_call(pp: PreprocessorState, index: int) -> None:
    """Shadertoy compiles its wrapper after the user's code, so a user macro `mainImage(O, U)`
    (code golf: `#define mainImage(O, U) O = ...`) expands inside the wrapper's call
    `mainImage(color, gl_FragCoord.xy);`. Model that call as the entry function: its header
    is written as it is, its body is the call expanded by the user's macro (placed on the
    macro's line, so messages point at it)."""
    macro = pp.macros.get("mainImage")
    if macro is None or macro.params is None or len(macro.params) != 2 or macro.loc is None:
        return
    pad = "\n" * (macro.loc.line - 1)
    header = Source(
        macro.loc.path,
        pad + f"void mainImage(out vec4 {WRAPPER_COLOR}, in vec2 glslcheck_coord) {{\n",
    )
    body = Source(
        macro.loc.path,
        pad + f"{WRAPPER_COLOR} = vec4(1e20); mainImage({WRAPPER_COLOR}, glslcheck_coord); }}\n",
    )
    del pp.macros["mainImage"]  # the header names the function; only the call expands
    run_unit(pp, Unit(header, index))
    pp.macros["mainImage"] = macro
    run_unit(pp, Unit(body, index + 1))


def run_unit(pp: PreprocessorState, u: Unit) -> None:
    """Read one unit line by line; GlslError for an #if it leaves open."""
    pp.start_unit(u)
    text = u.stripped
    nls = u.newlines()
    soft = u.soft_newlines
    run_start = None  # start of the pending run of active text lines
    run_end = 0
    start = 0
    for i, nl in enumerate(nls):
        if nl in soft:
            continue
        lead = _LEAD_WS_RE.match(text, start, nl)
        assert lead is not None  # a run of white space, maybe empty: it matches everywhere
        f = lead.end()
        active = pp.cond_active
        if f < nl and text[f] == "#":
            if run_start is not None:
                expand_text_run(pp, u, run_start, run_end)
                run_start = None
            handle_directive(pp, u, start, f, nl, active)
            pp.emit_blank(u, i)
        elif active:
            if run_start is None:
                run_start = start
            run_end = nl + 1
            if f < nl and not pp.seen_code:
                pp.seen_code = True
            if f < nl:
                pp.seen_tokens = True
        else:
            pp.mark_inactive(u, start, nl)
            pp.emit_blank(u, i)
        start = nl + 1
    if run_start is not None:
        expand_text_run(pp, u, run_start, run_end)
    if pp.conds:
        c = pp.conds[-1]
        raise GlslError(Diagnostic("this #if is never closed: add #endif", c.loc, rule=RULE))
