"""Benchmark: wall time of linting every file of lab_shaders/ (all rules) in one process.

    python tools/bench_lint.py [PATH ...] [--repeat N]

Prints the import time, the first lint run (it also loads the cached LALR parser) and the
median of N further runs, each from scratch (the engine's per-program tree cache and the AST
rules' fact cache are cleared, so every program is parsed, checked and analysed again).
The budget is 0.5 s for the first run; exit 1 when it is exceeded. The process CPU time is
printed too: on a machine busy with other work the wall time says more about the machine.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

BUDGET = 0.5


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("paths", nargs="*", default=[str(ROOT / "lab_shaders")])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args(argv)

    t0 = time.perf_counter()
    from glslcheck.lint import engine, lint_paths
    from glslcheck.lint.rules import all_rules
    from glslcheck.semantics.analysis import dataflow

    all_rules()
    t_import = time.perf_counter() - t0

    cpu: list[float] = []

    def run() -> tuple[float, int, int]:
        engine._TREES.clear()
        dataflow._CACHE.update(model=None, facts=None)
        start, start_cpu = time.perf_counter(), time.process_time()
        result = lint_paths(args.paths)
        cpu.append(time.process_time() - start_cpu)
        return time.perf_counter() - start, result.files, len(result.findings)

    first, files, findings = run()
    rest = [run()[0] for _ in range(args.repeat)]
    print(f"import + rule loading: {t_import:.3f} s")
    print(
        f"lint {files} files, {findings} findings: first run {first:.3f} s wall"
        + (f", median of {len(rest)} more {statistics.median(rest):.3f} s" if rest else "")
    )
    print(
        f"cpu time (less sensitive to a busy machine): first {cpu[0]:.3f} s, median "
        f"{statistics.median(cpu[1:] or cpu):.3f} s"
    )
    ok = first <= BUDGET
    print(f"budget {BUDGET:.1f} s: {'ok' if ok else 'EXCEEDED'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
