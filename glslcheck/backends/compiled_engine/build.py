"""`python -m glslcheck.backends.compiled_engine.build MODULE.py PATH PARENT`: compile one generated
module into numba's cache, in a process of its own (CompiledProgram.build_apart, which stops it when
it runs past its budget: budget.wait_child). PATH is the shader file the module's errors name;
PARENT the process id of the process that asked: when that process is gone (it ended, however), so
is this one, since nobody waits for the compile. Exit 0 once the machine code is in the cache; a
failure's message goes to stderr, exit 1."""

from __future__ import annotations

import os
import sys
import threading
import time

WATCH_SECONDS = 0.5  # how often the parent is looked for


def _watch(parent: int) -> None:
    while os.getppid() == parent:
        time.sleep(WATCH_SECONDS)
    os._exit(1)  # (numba writes its cache files whole, by rename: nothing is left half written)


def main(argv: list[str]) -> int:
    file, path, parent = argv
    threading.Thread(target=_watch, args=(int(parent),), daemon=True).start()
    from .engine import CompiledProgram

    with open(file, encoding="utf-8") as f:
        source = f.read()
    try:
        CompiledProgram(source, path).load(bounded=False)
    except Exception as e:  # noqa: BLE001 - reported to the parent, which decides
        print(f"{type(e).__name__}: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
