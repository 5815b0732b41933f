"""Deep recursion for the stages that walk nested programs, one limit across threads.

Python's recursion limit is one value for the whole process. The parser, the checker and both
code generators raise it while they walk a program nested hundreds deep. Each saving the value
and restoring it after, two threads interleave (the default program generates a faster module in
a thread beside the frames): one saves the other's raised value, restores it last, and the
process keeps the raised limit for good, so a render that should stop at the normal limit (a
call chain too deep, an error at its function) recurses on. Here the first entry raises the
limit and the last exit restores the value from before the first.
"""

from __future__ import annotations

import sys
import threading
from collections.abc import Iterator
from contextlib import contextmanager

DEEP = 20000  # frames: expressions and blocks nested as deep as the checker allows
_LOCK = threading.Lock()
_STATE = {"inside": 0, "saved": 0}


def enter_deep() -> None:
    """Raise the recursion limit to at least DEEP (until the matching :func:`leave_deep`)."""
    with _LOCK:
        if _STATE["inside"] == 0:
            _STATE["saved"] = sys.getrecursionlimit()
            sys.setrecursionlimit(max(_STATE["saved"], DEEP))
        _STATE["inside"] += 1


def leave_deep() -> None:
    """The last thread out puts back the limit from before the first came in."""
    with _LOCK:
        _STATE["inside"] -= 1
        if _STATE["inside"] == 0:
            sys.setrecursionlimit(_STATE["saved"])


@contextmanager
def deep_recursion() -> Iterator[None]:
    """The recursion limit at least DEEP while any thread is inside."""
    enter_deep()
    try:
        yield
    finally:
        leave_deep()
