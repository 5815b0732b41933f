"""Benchmark: the fuzzer's throughput (tools/fuzz.py), with the same inputs' commands run directly
in this process as the reference run in the same process.

1. fuzzer: inputs --start..--start+--count-1 of --seed through tools/fuzz.py's `fuzz_range` on
   one worker process (a pipe per command, the input's files written afresh, CPU-time
   watchdog, 3 GB address-space limit): inputs per second of wall time and per CPU second
   (the worker's CPU time from /proc plus this process's).
2. reference: the same inputs and the same commands through `fuzz_range` with
   `fuzz.InProcess` (each command called in this process, nothing else): CPU seconds.

Printed: both runs' inputs per CPU second, their ratio (the harness's overhead; 1.0 = none),
and what a 100,000-input run costs in CPU hours at the fuzzer's rate. Rates as in the
long run in tools/fuzz.py's docstring (--parse-rate 0.34, --heavy-rate 0.03, --verify-rate 0.03,
--hostile-rate 0.05). Printed, not asserted: timings are facts about a machine (and on a shared
one, CPU seconds mean more than wall seconds: both are shown, with the load average).

    python benchmarks/bench_fuzz.py [--count N] [--seed S] [--hostile-rate R]
"""

from __future__ import annotations

import argparse
import collections
import importlib
import multiprocessing as mp
import os
import platform
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tools"))

fuzz = importlib.import_module("fuzz")  # by name: the spawned workers import it so

RATES = dict(parse_rate=0.34, heavy_rate=0.03, verify_rate=0.03)


def _inputs(counts: collections.Counter) -> int:
    return sum(n for (k, _), n in counts.items() if k == "input")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--count", type=int, default=300, help="inputs per run (default 300)")
    ap.add_argument("--seed", type=int, default=16)
    ap.add_argument("--start", type=int, default=0)
    ap.add_argument("--hostile-rate", type=float, default=fuzz.HOSTILE_RATE)
    args = ap.parse_args()
    span = (args.start, args.start + args.count)
    out = Path(tempfile.mkdtemp(prefix="bench-fuzz-"))
    opts = dict(RATES, hostile_rate=args.hostile_rate, out_dir=out)
    print(
        f"python {platform.python_version()}, {os.cpu_count()} CPUs, load average before: "
        f"{' '.join(f'{x:.1f}' for x in os.getloadavg())}"
    )

    fuzz.seeds_and_pool()  # read once, outside both runs
    worker = fuzz.Worker(mp.get_context("spawn"))
    try:
        worker.run("parse", {"shader.glsl": b"void main(){}"}, 60)  # started and warm
        cpu0, own0, wall0 = worker.cpu_seconds(), time.process_time(), time.perf_counter()
        counts, flagged = fuzz.fuzz_range(args.seed, *span, worker=worker, **opts)
        wall = time.perf_counter() - wall0
        cpu = worker.cpu_seconds() - cpu0 + time.process_time() - own0
    finally:
        worker.close()

    direct = fuzz.InProcess()
    try:
        # warm like the worker: the commands' modules imported before the clock starts
        direct.run(
            "render",
            {"shader.glsl": b"void mainImage(out vec4 c, in vec2 p) { c = vec4(1.0); }"},
            60,
        )
        own0, wall0 = time.process_time(), time.perf_counter()
        ref_counts, _ = fuzz.fuzz_range(args.seed, *span, worker=direct, **opts)
        ref_wall = time.perf_counter() - wall0
        ref_cpu = time.process_time() - own0
    finally:
        direct.close()

    n, ref_n = _inputs(counts), _inputs(ref_counts)
    commands = sum(n for (c, _), n in counts.items() if c not in ("input", "seconds"))
    print(
        f"inputs {span[0]}..{span[1] - 1} of seed {args.seed}, hostile rate {args.hostile_rate:g}; "
        f"{commands} commands; {len(flagged)} flagged"
    )
    print(
        f"fuzzer (worker process): {n} inputs, {cpu:7.1f} CPU s, {wall:7.1f} wall s: "
        f"{n / cpu:6.1f} inputs per CPU s, {n / wall:6.1f} per wall s"
    )
    print(
        f"reference (in process):  {ref_n} inputs, {ref_cpu:7.1f} CPU s, {ref_wall:7.1f} wall s: "
        f"{ref_n / ref_cpu:6.1f} inputs per CPU s"
    )
    print(f"ratio fuzzer/reference CPU per input: {(cpu / n) / (ref_cpu / ref_n):.2f}")
    print(f"100,000 inputs at the fuzzer's rate: {100_000 / (n / cpu) / 3600:.2f} CPU hours")
    print(f"load average after: {' '.join(f'{x:.1f}' for x in os.getloadavg())}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
