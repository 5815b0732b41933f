"""`python -m glslcheck.backends.compiled_engine.build MODULE.py PATH PARENT [SECONDS [MARKER]]`:
compile one generated module into numba's cache, in a process of its own (CompiledProgram.
build_apart, which stops it when it runs past its budget: budget.wait_child). PATH is the shader
file the module's errors name; PARENT the process id of the process that asked: when that process
is gone (it ended, however), so is this one, since nobody waits for the compile; unless the parent
left it to finish (engine._leave_to_finish: the file MARKER.finish), and then it goes on, niced,
and writes the module's key into MARKER once the machine code is in the cache, for a later process
to load. SECONDS, the budget of its CPU time, is also the kernel's limit on it (RLIMIT_CPU, a
little past it: the parent stops it first while it waits), the one that holds once it is alone.
Exit 0 once the machine code is in the cache; a failure's message goes to stderr, exit 1."""

from __future__ import annotations

import math
import os
import signal
import sys
import threading
import time

WATCH_SECONDS = 0.5  # how often the parent is looked for
LIMIT_MARGIN = 2.0  # CPU seconds past the budget that the kernel's limit allows
KILL_AFTER = 10  # and past that, for SIGXCPU's handler to run (Python runs it between bytecodes)


def _watch(parent: int, marker: str, seconds: float) -> None:
    while os.getppid() == parent:
        time.sleep(WATCH_SECONDS)
    leave = marker + ".finish"
    if not marker or not os.path.exists(leave):
        os._exit(1)  # (numba writes its cache files whole, by rename: nothing is left half written)
    os.remove(leave)
    _LEFT.append(True)
    null = os.open(os.devnull, os.O_WRONLY)
    os.dup2(null, 2)  # (the parent's end of the stderr pipe is gone)
    os.nice(10)
    from .budget import WALL_FACTOR

    time.sleep(WALL_FACTOR * seconds)  # a machine too loaded to let it finish: stopped
    os._exit(1)


def _over(marker: str, seconds: float) -> None:
    """SIGXCPU: the budget is spent. Left to finish, the marker says so for good; else the
    parent, which waits for it, keeps the verdict."""
    if _LEFT:
        from . import cache_files
        from .engine import OVER

        cache_files.write(marker, f"{OVER} {seconds:g} s\n")
    os._exit(1)


_LEFT: list[bool] = []  # left to finish by its parent (_watch)


def main(argv: list[str]) -> int:
    file, path, parent, *rest = argv
    seconds = float(rest[0]) if rest else 0.0
    marker = rest[1] if len(rest) > 1 else ""
    if seconds > 0:
        import resource

        limit = math.ceil(seconds + LIMIT_MARGIN)
        # (at the soft limit SIGXCPU, below; at the hard one, SIGKILL)
        resource.setrlimit(resource.RLIMIT_CPU, (limit, limit + KILL_AFTER))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))  # (SIGXCPU's default dumps a core)
        if marker:  # stopped by it while left to finish: the marker says so, for good
            signal.signal(signal.SIGXCPU, lambda *_: _over(marker, seconds))
    threading.Thread(target=_watch, args=(int(parent), marker, seconds), daemon=True).start()
    from . import cache_files
    from .engine import FINISHING, CompiledProgram

    with open(file, encoding="utf-8") as f:
        source = f.read()
    try:
        prog = CompiledProgram(source, path)
        prog.load(bounded=False)
    except Exception as e:  # noqa: BLE001 - reported to the parent, which decides
        print(f"{type(e).__name__}: {e}", file=sys.stderr)
        return 1
    if _LEFT:  # left to finish: the parent is not there to mark it done
        cache_files.write(marker, prog.key + "\n")
        lock = os.path.join(cache_files.folder(), FINISHING)
        if cache_files.read(lock) == str(os.getpid()):
            os.remove(lock)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
