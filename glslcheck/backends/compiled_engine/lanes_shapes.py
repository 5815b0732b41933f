"""What the lockstep rewrite (lanes.py) asks of a generated statement or expression: a loop
counter, an array made, the exits of a block, an array index's test, a pure value, and an arm
of a divergent `if` run in every lane under its mask."""

from __future__ import annotations

import ast
from typing import Any

from .values import PURE_CALLS, PURE_NODES, pure_expr


def is_counter(name: str) -> bool:
    return name.startswith("_n") and name[2:].isdigit()


ARRAY_CALLS = {"acopy", "aslice", "np.zeros", "np.empty"}


def call_name(node: Any) -> str | None:
    if isinstance(node, ast.Call):
        return ast.unparse(node.func)
    return None


def makes_array(value: Any) -> bool:
    return any(call_name(n) in ARRAY_CALLS for n in ast.walk(value))


def count_free(texts: dict[str, str], calls: dict[str, set[str]]) -> set[str]:
    """The functions (name -> text, name -> the names it calls) that may run without numba's
    reference counts (module_text's jit_loop): neither they nor a function they call makes an
    array (a GLSL array, or one returned: `acopy`), so each array they see is one render_rows
    holds, and no count is owed on any."""
    bad: dict[str, bool] = {}

    def makes(name: str) -> bool:
        if name not in bad:
            bad[name] = True  # (GLSL has no recursion: a cycle keeps its counts)
            text = texts[name]
            bad[name] = any(f"{c}(" in text for c in ARRAY_CALLS) or any(
                makes(c) for c in calls[name]
            )
        return bad[name]

    return {name for name in texts if not makes(name)}


def exits_of(stmts: list) -> set[str]:
    """The exits in stmts: 'return' anywhere, 'break'/'continue' of the enclosing loop."""
    out: set[str] = set()
    for s in stmts:
        if isinstance(s, ast.Return):
            out.add("return")
        elif isinstance(s, ast.Break):
            out.add("break")
        elif isinstance(s, ast.Continue):
            out.add("continue")
        elif isinstance(s, ast.If):
            out |= exits_of(s.body) | exits_of(s.orelse)
        elif isinstance(s, ast.While):
            out |= exits_of(s.body) & {"return"}
    return out


def index_test(node: Any) -> bool:
    """`i == 2` of a name and an int constant: the test of codegen's selects over an array's
    elements at a run-time index (one per component read: `lsel(i == 0, a0, lsel(i == 1, ...))`)."""
    return (
        isinstance(node, ast.Compare)
        and isinstance(node.left, ast.Name)
        and len(node.ops) == 1
        and isinstance(node.ops[0], ast.Eq)
        and isinstance(node.comparators[0], ast.Constant)
        and type(node.comparators[0].value) is int
    )


def pure_value(e: Any) -> bool:
    """values.pure_expr of a renamed expression, whose pure `and`/`or` may already be `&`/`|`
    of bools (_Rename.visit_BoolOp: no effect, no failure either)."""
    for n in ast.walk(e):
        if isinstance(n, ast.Call):
            if not (isinstance(n.func, ast.Name) and n.func.id in PURE_CALLS and not n.keywords):
                return False
        elif not isinstance(n, (*PURE_NODES, ast.BitAnd, ast.BitOr)):
            return False
    return True


STRAIGHT_ARM = 8  # the most statements of a divergent arm computed in every lane (straight_arm)


def straight_arm(stmts: list) -> bool:
    """An arm of a divergent `if` run in every lane, its writes under the arm's mask, with no
    `if` of the mask around it: a few writes of pure values to names (no effect, no failure:
    lanes the mask leaves out keep their values, and what the arm computes there is dropped).
    The `if` and its test of the lanes were two blocks more for numba and split the run the
    SLP vectorizer packs; the && chains of codegen's short circuits are such arms."""
    return 0 < len(stmts) <= STRAIGHT_ARM and all(
        isinstance(s, ast.Assign)
        and len(s.targets) == 1
        and isinstance(s.targets[0], ast.Name)
        and not is_counter(s.targets[0].id)
        and pure_expr(s.value)
        for s in stmts
    )
