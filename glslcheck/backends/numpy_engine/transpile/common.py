"""What every pass of the transpiler shares: its limits and names, located errors, the
checker adapter and `_fold`, the memoized bottom-up walk the passes use to ask a question of
every node of a tree in linear time."""

from __future__ import annotations

import re
from typing import Any

from ....base.diagnostics import Diagnostic, GlslError, Location

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
# Model access (the checker's API) -- a small adapter while glslcheck.semantics settles.
# ---------------------------------------------------------------------------------------------


def check_program(parse_result: Any) -> Any:
    """The semantic model of a parsed program; GlslError when it does not check.

    ADAPTER: uses `glslcheck.semantics.check` when the package exports it, else runs the checker
    class directly and raises on its errors (the same contract)."""
    try:
        from ....semantics import check  # type: ignore[attr-defined]
    except ImportError:
        check = None
    if check is not None:
        return check(parse_result)
    from ....semantics.checker import Checker

    sources = list(getattr(parse_result, "sources", []) or [])
    tab = sources[-1].tab if sources else "Image"
    model = Checker(parse_result, tab).run()
    if model.errors:
        raise GlslError(model.errors)
    return model


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
