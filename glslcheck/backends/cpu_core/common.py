"""What both CPU engines share below their code writers: the groups of built-in names their
analyses decide by (derivatives, texture lookups), `fold_tree`, the memoized bottom-up walk
that asks a question of every node of a tree in linear time, and the few spellings both engines'
generated Python shares: `comment_safe` (GLSL text made safe for a comment or docstring),
`python_ident` (a GLSL name as Python bears it) and `sum_in_order` (a sum in the order
nir_fold decided)."""

from __future__ import annotations

import re
from typing import Any

from ...base.diagnostics import Diagnostic, GlslError, Location

TRANSPILE_RULE = "numpy-transpile"  # the rule of a program the CPU engines cannot write
LOOP_CAP = 100_000  # iterations per execution of one loop before the render stops with an error
IDENT = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")  # a name the generated Python can bear as it is
DERIVATIVES = ("dFdx", "dFdy", "fwidth")
# The lookups on a sampler2D that textures.TextureFunctions evaluates.
TEXTURE_FUNCTIONS = (
    "texture",
    "textureLod",
    "textureGrad",
    "textureProj",
    "textureOffset",
    "texelFetch",
    "texelFetchOffset",
    "textureSize",
    "textureLodOffset",
    "textureGradOffset",
    "textureProjOffset",
    "textureProjLod",
    "textureProjLodOffset",
    "textureProjGrad",
    "textureProjGradOffset",
)
# The lookups on a samplerCube they evaluate (every one ES 3.00 has: no texelFetch, offsets or
# projection on cube maps).
CUBE_FUNCTIONS = ("texture", "textureLod", "textureGrad", "textureSize")
# Lookups whose mipmap level comes from derivatives (2x2 quads): their regions are never compacted.
IMPLICIT_LOD = ("texture", "textureProj", "textureOffset", "textureProjOffset")
# The built-ins whose Runtime method (numpy_engine/runtime.py) bears another name: theirs is a
# Python built-in or keyword. call_fold names a folded call's operation by it.
RUNTIME_NAMES = {"min": "min_", "max": "max_", "not": "not_vec"}


def comment_safe(text: str, limit: int = 100) -> str:
    """Text safe inside a Python comment or docstring: printable ASCII, no quotes or backslashes."""
    out = "".join(c if (" " <= c <= "~" and c not in '"\\') else "?" for c in text.strip())
    return out if len(out) <= limit else out[: limit - 3] + "..."


def sum_in_order(
    order: tuple[int, bool, tuple[tuple[str, int], ...]], terms: list[str], k: str
) -> str:
    """A sum in the order nir_fold decided (returned_sums.SunkOrder: `k` added to one of
    `terms`, negated or not, then the others in turn, left to right), over `terms`, the terms'
    values: Python's operators on float32 values compute the same IEEE operations on the NumPy
    transpiler's arrays and the compiled engine's scalars, so both spell it alike."""
    joined, negated, then = order
    text = f"({'-' if negated else ''}{terms[joined]} + {k})"
    for op, i in then:
        text = f"({text} {op} {terms[i]})"
    return text


def fold_tree(root: Any, memo: dict[int, Any], own) -> Any:
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


def python_ident(name: str, node: Any) -> str:
    """`name`, the GLSL name of a function, variable or field, as the generated Python names it;
    a located error where Python cannot bear it as it is."""
    if not IDENT.match(name or ""):
        loc = node if isinstance(node, Location) else getattr(node, "loc", None)
        raise GlslError(
            Diagnostic(f"the name {name!r} cannot be transpiled", loc, rule=TRANSPILE_RULE)
        )
    return name
