"""The budget of a compile in a child process (CompiledProgram.build_apart, build.py): CPU
seconds, what the compile takes from the frames beside it, not the wall time a loaded machine
makes it wait."""

from __future__ import annotations

import os
import subprocess
import time

POLL_SECONDS = 0.25  # how often wait_child reads the child's CPU time
OVER = "over budget"  # wait_child's answer when the child passed its CPU seconds
# its answer when the wall-time limit stopped it first: the machine's load, not the compile
STARVED = "starved"
# a compile's budget is CPU seconds (what it takes from the frames beside it); on a machine so
# loaded that it gets less than a core in WALL_FACTOR, it is stopped at that many times the budget
WALL_FACTOR = 4.0


def cpu_seconds(pid: int) -> float | None:
    """The CPU time (user + system) a running process has used, from /proc; None without it."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as f:
            fields = f.read().rpartition(b")")[2].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
    except (OSError, ValueError, IndexError):
        return None


def wait_child(child: subprocess.Popen, seconds: float) -> bytes | str:
    """The stderr of a build process once it ends; OVER when it is still running after
    `seconds` of CPU time (`seconds` of wall time where its CPU time cannot be read), STARVED
    after WALL_FACTOR x `seconds` of wall time. The caller stops it."""
    start = time.monotonic()
    while True:
        try:
            return child.communicate(timeout=POLL_SECONDS)[1]
        except subprocess.TimeoutExpired:
            pass
        wall = time.monotonic() - start
        cpu = cpu_seconds(child.pid)
        if (cpu if cpu is not None else wall) > seconds:
            return OVER
        if wall > WALL_FACTOR * seconds:
            return STARVED
