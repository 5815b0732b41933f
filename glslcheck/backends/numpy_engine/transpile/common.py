"""What every pass of the transpiler shares: its limits and names, located errors, the
checker adapter and `fold_tree`, the memoized bottom-up walk the passes use to ask a question of
every node of a tree in linear time."""

from __future__ import annotations

import re
from typing import Any

from ....base.diagnostics import Diagnostic, GlslError, Location
from ...cpu_core.common import TRANSPILE_RULE

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
_LOCAL_REF = re.compile(r"(?<![.\w\"'])(v_\w+|_[a-z]+\d*)\b")
_ASSIGNED = re.compile(
    r"^(?!(?:if|elif|while|return) )([^=]*?)\s*[-+*/]?=(?!=)"
)  # a stripped statement's targets
_FLOAT_OPERATORS = (
    "+",
    "-",
    "*",
    "/",
    "<",
    "<=",
    ">",
    ">=",
)  # printed as Python operators on floats
_BIN_METHODS = {
    "+": "add",
    "-": "sub",
    "*": "mul",
    "/": "div",
    "<": "lt",
    "<=": "le",
    ">": "gt",
    ">=": "ge",
    "<<": "shl",
    ">>": "shr",
    "&": "bit_and",
    "|": "bit_or",
    "^": "bit_xor",
    "&&": "and_",
    "||": "or_",
    "^^": "xor_",
}


_STRING = re.compile(r'"[^"]*"')
_NAME = re.compile(r"(?<![.\w])([A-Za-z_]\w*)(\s*=(?!=))?")


UNDEFINED_MODES = ("zero", "vary")  # what undefined reads see (Transpiler's `undefined`)


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
    return GlslError(Diagnostic(message, loc, rule=TRANSPILE_RULE, help=help))


# ---------------------------------------------------------------------------------------------
# Model access (the checker's API) -- a small adapter while glslcheck.semantics settles.
# ---------------------------------------------------------------------------------------------


def check_program(parse_result: Any) -> Any:
    """The semantic model of a parsed program (`glslcheck.semantics.check`); GlslError when it
    does not check."""
    from ....semantics import check

    return check(parse_result)
