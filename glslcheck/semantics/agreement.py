"""Accept/reject of a whole Shadertoy shader by glslcheck and by glslangValidator.

Owns the one definition both the agreement tests and tools/mutation_agreement.py use: a shader
is accepted when every program Shadertoy compiles from it is accepted - the Common tab alone
(only iDate and iSampleRate declared), then Common + each pass tab (Image, Buffer A..D), or a
plain GLSL file as it is. For glslcheck that means: it preprocesses, parses and checks without
an error; for glslangValidator: every wrapped program (glslcheck.shadertoy.wrapper) compiles.
"""

from __future__ import annotations

from ..base.diagnostics import Diagnostic, GlslError
from ..shadertoy.sources import Shader
from ..shadertoy.wrapper import PASS_TABS, build_common_only, build_program

_TABS = (*PASS_TABS, "GLSL")


def passes(shader: Shader) -> list[str]:
    """Common alone first (when present), then every pass tab present."""
    out = ["Common"] if "Common" in shader.tabs else []
    return out + [t for t in _TABS if t in shader.tabs]


def our_errors(shader: Shader) -> list[Diagnostic]:
    """glslcheck's errors over every pass of `shader` (parse + check)."""
    from ..frontend.parser import parse_shader
    from . import check

    errors: list[Diagnostic] = []
    for tab in passes(shader):
        try:
            model = check(parse_shader(shader, tab), tab, collect=True)
        except GlslError as e:
            errors.extend(e.diagnostics)
            continue
        errors.extend(model.errors)
    return errors


def glslang_errors(shader: Shader) -> list[str]:
    """glslangValidator's error messages over every program Shadertoy compiles from `shader`."""
    from .glslang import validate

    out: list[str] = []
    for tab in passes(shader):
        program = build_common_only(shader) if tab == "Common" else build_program(shader, tab)
        result = validate(program.text)
        if not result.ok:
            out.extend(f"[{tab}] {m}" for _, m in result.messages)
    return out
