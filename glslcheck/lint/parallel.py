"""Linting the programs of one run on two cores: the same findings, in the same order, as one
process gives.

`glslcheck lint FOLDER` parses, checks and lints each program (a shader's Common and pass tab)
on its own, so the programs are independent work. When the run has at least two programs and
the process may use two or more cores, `run_split` forks one child after the imports, the
parser tables and the rules are loaded (the child inherits them, so it pays none of the
start-up), lets it lint the second half of the programs (by text size) while this process lints
the first, and joins the child's findings after its own. Nothing is written anywhere: the child
sends its findings back through a pipe (pickled), with the source texts it registered for the
report to quote.

The result does not depend on the split: each program is linted by the same code with the same
configuration, and the findings are concatenated in the order of the programs. If the child
fails in any way (it crashed, was killed, raised: a bug or an unreadable file), this process
lints the child's half itself, so an error is reported exactly as one process reports it.

`GLSLCHECK_JOBS=1` (or no `os.fork`, one usable core, or a machine whose cores are all busy, by
the load average) lints in this process only; `GLSLCHECK_JOBS=2` splits whatever the load. Start-up
is what a pre-commit hook pays (docs/performance.md): a fork costs about a
millisecond, so one small program is not worth it and runs here.
"""

from __future__ import annotations

import os

from ..base import config

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import TypeVar

    Work = TypeVar("Work")
    Result = TypeVar("Result")

# Below this much source text in all (about two 200-line programs) the fork and the pickled
# findings cost more than the second core saves.
MIN_TEXT = 8000


def jobs() -> int:
    """How many processes may lint: 1 or 2. `GLSLCHECK_JOBS` when set; else 2 when this process
    may use two or more cores and the machine has one to spare: a 1-minute load average of at
    least the cores less a half means the other cores are busy, and a second process would only
    take turns with the first (the same wall time, the fork's CPU time more)."""
    if not hasattr(os, "fork") or _threads():
        return 1
    given = config.jobs()
    if given is not None:
        return given
    try:
        cores = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        cores = os.cpu_count() or 1
    try:
        busy = os.getloadavg()[0] >= cores - 0.5
    except (AttributeError, OSError):
        busy = False
    return 2 if cores >= 2 and not busy else 1


def _threads() -> bool:
    """Whether this process runs other threads (a program calling lint_paths may): a forked
    child gets only the forking thread, and a lock another thread held stays held there."""
    import sys

    threading = sys.modules.get("threading")  # not imported: no thread was started through it
    return threading is not None and threading.active_count() > 1


def split_point(sizes: list[int]) -> int:
    """Where to cut the programs (sizes in characters) into two halves of about equal text."""
    total = sum(sizes)
    best, best_gap, acc = 1, total, 0
    for i, n in enumerate(sizes[:-1], start=1):
        acc += n
        gap = abs(total - 2 * acc)
        if gap < best_gap:
            best, best_gap = i, gap
    return best


def run_split(
    items: list,
    sizes: list[int],
    lint: Callable[[list], list],
    prepare: Callable[[], None],
    registry: dict,
) -> list:
    """`lint(items)`, computed as `lint(items[:k]) + lint(items[k:])` with the second half in a
    forked child when that pays (see the module docstring). `prepare()` loads what the child
    should inherit; `registry` is the report's table of source texts (path -> lines), whose
    entries the child adds are copied back."""
    if len(items) < 2 or sum(sizes) < MIN_TEXT or jobs() < 2:
        return lint(items)
    prepare()
    k = split_point(sizes)
    first, second = items[:k], items[k:]
    read_end, write_end = os.pipe()
    try:
        pid = os.fork()
    except OSError:  # no process left to fork: lint everything here
        os.close(read_end)
        os.close(write_end)
        return lint(items)
    if pid == 0:  # the child: lint the second half, send it back, exit without cleanup
        status = 1
        try:
            os.close(read_end)
            import pickle

            before = dict(registry)
            found = lint(second)
            added = {p: lines for p, lines in registry.items() if before.get(p) is not lines}
            data = pickle.dumps((found, added), protocol=pickle.HIGHEST_PROTOCOL)
            with os.fdopen(write_end, "wb") as out:
                out.write(data)
            status = 0
        except BaseException:  # noqa: BLE001 - the parent lints this half itself
            pass
        finally:
            os._exit(status)
    os.close(write_end)
    try:
        found = lint(first)
    except BaseException:
        os.close(read_end)
        _reap(pid, kill=True)
        raise
    with os.fdopen(read_end, "rb") as inp:
        data = inp.read()
    if _reap(pid) == 0 and data:
        import pickle

        try:
            theirs, added = pickle.loads(data)
        except Exception:  # noqa: BLE001 - a cut-off message: lint this half here
            theirs = None
        if theirs is not None:
            registry.update(added)
            return found + theirs
    return found + lint(second)


def _reap(pid: int, kill: bool = False) -> int:
    """Wait for the child (after ending it, with `kill`); its exit status, or -1."""
    if kill:
        import signal

        try:
            os.kill(pid, signal.SIGKILL)
        except OSError:
            pass
    try:
        _, status = os.waitpid(pid, 0)
    except ChildProcessError:
        return -1
    return os.waitstatus_to_exitcode(status)
