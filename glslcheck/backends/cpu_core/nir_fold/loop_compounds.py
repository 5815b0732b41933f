"""A compound ``x *= #k`` (``+=``, ``-=``) merged into the value x holds in each copy of a loop NIR
unrolls, as loop_copies.py merges ``x * #k``: to NIR it is ``x = x * #k``
(``float a = p.y * 0.013; for (...) { a *= 1.01; a = sin(a); }`` is ``sin(p.y * (0.013*1.01))``
in the first copy; measured: tests/gl/test_llvmpipe_loop_copies.py). A ``+=`` that is a step of
a longer chain of constant sums is repeated_sums.py's (its order: sum_order.py) and left to it."""

from __future__ import annotations

from typing import Any

from ....frontend import syntax as A
from .loop_copies import merged_copies
from .queries import FunctionStandin
from .repeated_sums import chain_plan, param_step, sum_entry

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..fold_protocols import FoldEmitter, FoldEngine


def compound_copies(tr: FoldEmitter, e: A.Assignment, mask: str | None, old: Any) -> Any:
    """The code of the new value of ``x op= #k`` with the constant merged (`old`: x's code), or
    None: the write as usual."""
    if e.op not in ("*=", "+=", "-=") or tr.fn is None or isinstance(tr.fn, FunctionStandin):
        return None
    if e.op != "*=" and _chained(tr, e):
        return None
    return merged_copies(tr, e, mask, old)


def _chained(tr: FoldEngine, e: A.Assignment) -> bool:
    """The step continues or starts a chain of more than one constant sum (or a caller's)."""
    if param_step(tr, e) is not None:
        return True
    entry = sum_entry(tr, e)
    if entry is None:
        return False
    return len(entry.ks) > 1 or any(
        o is not entry and o.chain == entry.chain for o in chain_plan(tr).values()
    )
