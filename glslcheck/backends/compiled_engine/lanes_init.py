"""init_globals in the lockstep module: its calls of user functions, as the lockstep variants.

The per-pixel module's init_globals computes, once a frame and once at load, the values that are
the same in every pixel (global initializers, and the calls constant_globals.load_time_parts
moved there). Its code is scalar and stays as it is, but the per-pixel functions it calls are not
in the lockstep module: each call becomes one of the variant whose every parameter is one scalar
for the block (the variant a lockstep call site with those arguments would call), with every
lane live.
"""

from __future__ import annotations

import ast
from typing import Any

from .lanes_render import STATE_LANES


def lockstep_init(lanes: Any) -> tuple[str, tuple[tuple[str, frozenset], ...]] | None:
    """(init_globals' source for the lockstep module `lanes` (lanes.Lanes) makes, the keys of
    the variants its calls need); None when a call cannot be made so."""
    found = [
        f for f in lanes.tree.body if isinstance(f, ast.FunctionDef) and f.name == "init_globals"
    ]
    if not found:
        return "", ()
    node = ast.parse(ast.unparse(found[0]))  # (a copy: the per-pixel tree stays as it was)
    keys: list[tuple[str, frozenset]] = []
    for n in ast.walk(node):
        if not (
            isinstance(n, ast.Call)
            and isinstance(n.func, ast.Name)
            and n.func.id in lanes.functions
        ):
            continue
        callee = lanes.functions[n.func.id]
        params = [a.arg for a in callee.args.args]
        if len(params) != len(n.args) or n.keywords or set(params) & set(STATE_LANES):
            return None
        key = (n.func.id, frozenset(range(len(params))))
        fn = lanes.variant(*key)
        if not all(fn.ret_uniform):
            return None
        keys.append(key)
        n.func = ast.Name(fn.name, ast.Load())
        n.args = [ast.Constant(True) for _ in range(lanes.W)] + n.args
    return ast.unparse(node), tuple(keys)
