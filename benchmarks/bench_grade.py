"""`glslcheck grade` on a class of 17: every part of lab_shaders/ as a submission, graded against
lab_shaders/07_final at the command's defaults (320x180, iTime 0, 1.7, 5.3), each side measured
in the same run:

1. The whole command as a TA runs it (`glslcheck grade lab_shaders/* --reference
   lab_shaders/07_final --csv ... -o ...`, one process, a worker per core): wall and CPU
   seconds, and wall seconds per submission.
2. In process, one submission at a time (jobs=1), against the floor of what grading does: for
   each part, lint its files, compile it and render it at the three times, then compare each
   frame with the reference's (`lint_paths`, `compile`, `render`, `compare`, nothing else):
   the time grade adds around that work (thumbnails, diff images, the checkout, the records).
3. In process, the class on a worker per core (jobs=N) against jobs=1: what the cores buy.

Timings are medians of --runs measurements after a warm-up; the sides of each ratio are measured
alternately. Printed, not asserted.

    python benchmarks/bench_grade.py [--runs N]
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(HERE))

from run_all import machine, ms, paired  # noqa: E402

import glslcheck  # noqa: E402
from glslcheck.lint import lint_paths  # noqa: E402
from glslcheck.shadertoy.sources import load_shader  # noqa: E402
from glslcheck.verification.compare import compare  # noqa: E402
from glslcheck.verification.grade import (  # noqa: E402
    DEFAULT_SIZE,
    DEFAULT_TIMES,
    Options,
    from_paths,
    grade_class,
    render_reference,
)
from glslcheck.verification.grade.run import default_jobs  # noqa: E402

FINAL = ROOT / "lab_shaders" / "07_final"
PARTS = sorted(str(p) for p in (ROOT / "lab_shaders").iterdir() if p.is_dir())


def command() -> tuple[float, float]:
    """(wall, CPU of the process and its workers) seconds of one `glslcheck grade` run."""
    with tempfile.TemporaryDirectory() as out:
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t = time.perf_counter()
        subprocess.run(
            [sys.executable, "-m", "glslcheck", "grade", *PARTS, "--reference", str(FINAL)]
            + ["--csv", f"{out}/g.csv", "-o", f"{out}/g.html"],
            check=False,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            cwd=ROOT,
            env=dict(os.environ, PYTHONPATH=str(ROOT)),
        )
        wall = time.perf_counter() - t
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def floor(reference) -> None:
    """What grading a part cannot do without: lint, compile, render, compare."""
    for part in PARTS:
        shader = load_shader(part)
        lint_paths([s.path for s in shader.sources()])
        program = glslcheck.compile(shader, backend="numpy")
        for t, ref in zip(DEFAULT_TIMES, reference.images):
            compare(program.render(size=DEFAULT_SIZE, time=t), ref)


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--runs", type=int, default=3)
    args = p.parse_args()
    options = Options()
    reference = render_reference(FINAL, options)
    submissions = from_paths(PARTS)
    jobs = default_jobs(len(submissions))
    n = len(submissions)
    print("\n".join(machine()))
    print(
        f"class: {n} submissions (lab_shaders/*) against lab_shaders/07_final, {DEFAULT_SIZE[0]}x"
        f"{DEFAULT_SIZE[1]}, iTime {', '.join(f'{t:g}' for t in DEFAULT_TIMES)}; "
        f"median of {args.runs}"
    )

    walls, cpus = [], []
    command()  # warm-up: the file cache, numba's and the parser's caches
    for _ in range(args.runs):
        wall, cpu = command()
        walls.append(wall)
        cpus.append(cpu)
    walls.sort()
    cpus.sort()
    wall, cpu = walls[len(walls) // 2], cpus[len(cpus) // 2]
    print(
        f"1. glslcheck grade (whole process, {jobs} workers): {wall:.2f} s wall, {cpu:.2f} s CPU; "
        f"{ms(wall / n)} wall, {ms(cpu / n)} CPU per submission"
    )

    times = paired(
        {
            "grade, jobs=1": lambda: grade_class(submissions, options, reference, jobs=1),
            "floor (lint, compile, render, compare)": lambda: floor(reference),
            f"grade, jobs={jobs}": lambda: grade_class(submissions, options, reference, jobs=jobs),
        },
        args.runs,
    )
    one, base, many = (
        times["grade, jobs=1"],
        times["floor (lint, compile, render, compare)"],
        times[f"grade, jobs={jobs}"],
    )
    print(
        f"2. in process, jobs=1: {ms(one / n)} per submission; the floor {ms(base / n)}: "
        f"grade takes {one / base:.2f}x the floor"
    )
    print(
        f"3. in process, jobs={jobs}: {ms(many / n)} per submission, "
        f"{one / many:.2f}x faster than jobs=1"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
