"""The semantic model: scopes, symbols and types of a parsed GLSL ES 3.00 / Shadertoy program.

    from glslcheck.semantics import check, Model, Symbol, CheckError
    model = check(parse_result, tab="Image")   # raises CheckError (a GlslError) on errors
    model = check(parse_result, collect=True)  # never raises; see model.diagnostics

`Model` answers: type_of(expr), symbol_of(identifier or declaring node), call_target(call),
is_swizzle / swizzle_indices(field), const_value(expr), functions, structs, globals, entry,
reachable_functions(), calls_from(function), uniforms_read(), diagnostics.

`tab` is the Shadertoy pass ("Image", "Buffer A".."Buffer D", or "Common" for the Common tab
compiled alone with only iDate and iSampleRate); a plain GLSL file (own #version and main) is
recognised from its source and checked as such. An iChannel the program samples only as a cube
map is declared samplerCube, as Shadertoy's wrapper does for a bound cube map (channel_types.py).
"""

from __future__ import annotations

from ..base.diagnostics import Diagnostic, Location
from ..base.recursion import enter_deep, leave_deep
from .channel_types import SAMPLER_CUBE, cube_channels
from .checker import Checker
from .model import ERROR, CallTarget, CheckError, Constructor, ErrorType, Model, Symbol

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from typing import Any

__all__ = [
    "check",
    "Model",
    "Symbol",
    "Constructor",
    "CallTarget",
    "CheckError",
    "ERROR",
    "ErrorType",
]


def check(parse_result: Any, tab: str = "Image", *, collect: bool = False) -> Model:
    """Check a ParseResult (from parse_shader / parse_units) as the pass `tab`."""
    # Blocks and expressions nested hundreds deep recurse in the checker (as in frontend/parser.py's
    # builder): allow it; deeper than even this becomes an error at the file's start.
    enter_deep()
    try:
        model = Checker(parse_result, tab).run()
        cube = cube_channels(model) if model.errors else frozenset()
        if cube:  # channels sampled only as cube maps: Shadertoy declares them samplerCube
            model = Checker(parse_result, tab, {c: SAMPLER_CUBE for c in cube}).run()
        if not model.errors:  # undefined behaviour the backends may not agree on (hazards.py)
            from .hazards import hazard_warnings

            model.diagnostics.extend(hazard_warnings(model))
    except RecursionError:
        sources = getattr(parse_result, "sources", None) or []
        loc = Location(sources[-1].path, 1, 1) if sources else None
        raise CheckError([Diagnostic("the program is nested too deeply to analyse", loc)]) from None
    finally:
        leave_deep()
    order = {s.path: i for i, s in enumerate(getattr(parse_result, "sources", []) or [])}
    model.diagnostics.sort(
        key=lambda d: (
            (order.get(d.loc.path, len(order)), d.loc.line, d.loc.column) if d.loc else (-1, 0, 0)
        )
    )
    if not collect and model.errors:
        raise CheckError(model.errors)
    return model
