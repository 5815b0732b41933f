"""The short CI fuzz run (issue 9): a few thousand inputs from tools/fuzz.py through parse,
check, lint, transpile, render and verify, in-process, each in a worker process with a time
budget. Zero flagged outcomes allowed: no traceback, no escaped exception, no exit code outside
{0, 1, 2}, no hang, no error without file:line:col in the user's file, no modified file, and
every generated (valid) program accepted by parse/check/transpile/render and equal on both
backends when verified.

The run is time-boxed so CI stays under 60 s on a slow runner: two workers take inputs 0..1499
and 1500..2999 of seed 2026 and stop at RUN_SECONDS; a normal machine finishes all 3000. Each
input is a function of (seed, index) alone, so a flagged input is reproduced with
`python tools/fuzz.py --seed 2026 --show INDEX`. The long run is
`python tools/fuzz.py --count 100000` (see tools/fuzz.py).
"""

from __future__ import annotations

import collections
import importlib
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SEED = 2026
PER_WORKER = 1500
RUN_SECONDS = 45  # of the 60 s budget; the rest is start-up and the last input in flight
MIN_INPUTS = 400  # even a very slow runner gets this far, or the harness itself is broken


def _fuzz_module():
    # Imported by name from tools/ (not from a file spec): the harness's workers are spawned
    # processes, which import the module that defines their entry point by its name.
    tools = str(ROOT / "tools")
    if tools not in sys.path:
        sys.path.insert(0, tools)
    return importlib.import_module("fuzz")


def test_short_fuzz_run_has_no_flagged_inputs(tmp_path):
    fuzz = _fuzz_module()
    deadline = time.monotonic() + RUN_SECONDS

    def chunk(k: int):
        # hostile programs take seconds each: test_fuzz_hostile.py runs each shape once
        return fuzz.fuzz_range(SEED, k * PER_WORKER, (k + 1) * PER_WORKER, heavy_rate=0.01,
                               verify_rate=0.02, parse_rate=0.2, out_dir=tmp_path, deadline=deadline,
                               hostile_rate=0.0)

    counts: collections.Counter = collections.Counter()
    flagged: list[dict] = []
    with ThreadPoolExecutor(2) as pool:
        for c, f in pool.map(chunk, range(2)):
            counts.update(c)
            flagged += f
    inputs = sum(n for (k, _), n in counts.items() if k == "input")
    report = "\n".join(f"{f['outcome']} {f['command']} input {f['index']} ({f['kind']}): {f['detail'][-600:]}"
                       for f in flagged[:10])
    assert not flagged, f"{len(flagged)} flagged (reproduce: tools/fuzz.py --seed {SEED} --show INDEX):\n{report}"
    assert inputs >= MIN_INPUTS, f"only {inputs} inputs ran in {RUN_SECONDS} s"
    for command in ("check", "lint", "transpile"):
        assert sum(n for (c, _), n in counts.items() if c == command) > 0, command
    # Kinds and outcomes all occur: the generator reaches clean programs, mutants reach errors.
    assert counts[("check", "ok")] > 0 and counts[("check", "findings")] > 0
