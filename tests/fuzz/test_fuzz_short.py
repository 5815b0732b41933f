"""The short CI fuzz run (bad input never breaks glslcheck): a fixed set of inputs from
tools/fuzz.py -- inputs 0..399 of seed 2026 -- through parse, check, lint, transpile, render,
verify and the compiled engine, in-process, each in a worker process with a time budget. Zero
flagged outcomes allowed: no traceback, no escaped exception, no exit code outside {0, 1, 2}, no
hang, no error without file:line:col in the user's file, no modified file, and every generated
(valid) program accepted by parse/check/transpile/ render and equal on both backends when
verified.

A count, not a time box: every run checks the same 400 inputs, however busy the machine (a run
that stopped at a deadline checked fewer inputs on a slow machine and failed under load). The
fuzzer's speed is benchmarks/bench_fuzz.py's business. Each input is a function of (seed,
index) alone, so a flagged input is reproduced with `python tools/fuzz.py --seed 2026 --show
INDEX`. The long run is `python tools/fuzz.py --count 100000` (see tools/fuzz.py); the hostile
shapes at their largest are test_fuzz_hostile.py's.
"""

from __future__ import annotations

import collections
import importlib
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SEED = 2026
PER_WORKER = 200
WORKERS = 2


def _fuzz_module():
    # Imported by name from tools/ (not from a file spec): the harness's workers are spawned
    # processes, which import the module that defines their entry point by its name.
    tools = str(ROOT / "tools")
    if tools not in sys.path:
        sys.path.insert(0, tools)
    return importlib.import_module("fuzz")


def test_short_fuzz_run_has_no_flagged_inputs(gl, tmp_path):
    fuzz = _fuzz_module()

    def chunk(k: int):
        # hostile programs take seconds each: test_fuzz_hostile.py runs each shape once
        return fuzz.fuzz_range(
            SEED,
            k * PER_WORKER,
            (k + 1) * PER_WORKER,
            heavy_rate=0.01,
            verify_rate=0.02,
            parse_rate=0.2,
            out_dir=tmp_path,
            hostile_rate=0.0,
            compiled_rate=0.02,
        )

    counts: collections.Counter = collections.Counter()
    flagged: list[dict] = []
    with ThreadPoolExecutor(WORKERS) as pool:
        for c, f in pool.map(chunk, range(WORKERS)):
            counts.update(c)
            flagged += f
    report = "\n".join(
        f"{f['outcome']} {f['command']} input {f['index']} ({f['kind']}): {f['detail'][-600:]}"
        for f in flagged[:10]
    )
    assert not flagged, (
        f"{len(flagged)} flagged (reproduce: tools/fuzz.py --seed {SEED} --show INDEX):\n{report}"
    )
    kinds = {k: n for (c, k), n in counts.items() if c == "input"}
    assert sum(kinds.values()) == WORKERS * PER_WORKER, kinds
    assert {"mutate", "generate", "soup", "bytes", "channels", "channels-bad"} <= set(kinds), kinds
    for command in ("parse", "check", "lint", "transpile", "render", "verify", "compiled"):
        assert sum(n for (c, _), n in counts.items() if c == command) > 0, command
    # The generator reaches clean programs and the mutants reach errors.
    assert counts[("check", "ok")] > 0 and counts[("check", "findings")] > 0
