"""Grading a class: every submission, in parallel across the cores, with a progress bar.

    grades = grade_class(submissions, Options(times=(0.0, 1.7)), reference="lab_shaders/07_final")

The reference is rendered once, here, before any worker starts (a reference that fails is the
TA's error and raises). Each submission is graded in a worker process, `jobs` at a time. The
workers are started fresh (spawned), not forked: this process has rendered the reference, so
it may hold the NumPy renderer's tile threads (a forked copy of their pool has no threads and
waits for ever) or a GL context; each worker gets the reference's renders once, when it
starts, and pays the imports (about a second) once. A worker that dies (a crash
in a library, the memory killer) costs only the submission it was grading: the ones still
waiting are graded again one at a time in fresh workers, and the one that kills its worker
again gets a row saying so. The grades come back in the order of `submissions`.

Inside the workers the NumPy renderer keeps its tiles on threads (unless --parallel says
otherwise) and the linter in the one process: the cores are already shared by submissions.
"""

from __future__ import annotations

import multiprocessing
import os
from collections.abc import Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from concurrent.futures.process import BrokenProcessPool

from ...base import config
from ..verify import Progress
from .grading import Options, Reference, grade_submission, render_reference
from .records import FAILED, Grade
from .submissions import Submission


class GradeProgress(Progress):
    NAME = "grade"


_REFERENCE: Reference | None = None  # each worker's copy, set when it starts


def _worker_setup(reference: Reference | None) -> None:
    global _REFERENCE
    _REFERENCE = reference
    if config.parallel() == "auto":  # the cores are taken by the other workers already
        os.environ.update(GLSLCHECK_PARALLEL="threads")
    os.environ.update(GLSLCHECK_JOBS="1")


def _grade_in_worker(submission: Submission, options: Options) -> Grade:
    return grade_submission(submission, options, _REFERENCE)


def default_jobs(count: int) -> int:
    """Worker processes for `count` submissions: one per core this process may use."""
    try:
        cores = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        cores = os.cpu_count() or 1
    return max(1, min(cores, count))


def grade_class(
    submissions: Sequence[Submission],
    options: Options = Options(),
    reference=None,
    *,
    jobs: int | None = None,
    progress: Progress | None = None,
) -> list[Grade]:
    """A Grade per submission, in their order (see the module docstring). `reference` is a
    path or an already rendered `Reference`."""
    if reference is not None and not isinstance(reference, Reference):
        reference = render_reference(reference, options)
    jobs = default_jobs(len(submissions)) if jobs is None else max(1, int(jobs))
    if jobs == 1 or len(submissions) < 2:
        out = []
        for s in submissions:
            out.append(grade_submission(s, options, reference))
            if progress is not None:
                progress.step(s.team)
        return out
    return _in_pool(list(submissions), options, reference, jobs, progress)


def _in_pool(submissions: list[Submission], options: Options, reference, jobs, progress):
    results: dict[int, Grade] = {}
    left = _run_pool(
        submissions, range(len(submissions)), options, reference, jobs, results, progress
    )
    for i in left:  # the pool broke: one at a time, so a second death names its submission
        if _run_pool(submissions, [i], options, reference, 1, results, progress):
            results[i] = Grade(
                team=submissions[i].team,
                source=submissions[i].source,
                branch=submissions[i].branch,
                contributors=list(submissions[i].contributors),
                status=FAILED,
                reason="the process grading it died (a crash or out of memory); grade it alone "
                "to see more",
            )
            if progress is not None:
                progress.step(submissions[i].team)
    return [results[i] for i in range(len(submissions))]


def _run_pool(submissions, indices, options, reference, jobs, results, progress) -> list[int]:
    """Grade `indices` in a pool of `jobs` workers into `results`; the indices left ungraded
    when a worker died."""
    context = multiprocessing.get_context("spawn")
    with ProcessPoolExecutor(
        jobs, mp_context=context, initializer=_worker_setup, initargs=(reference,)
    ) as pool:
        futures = {pool.submit(_grade_in_worker, submissions[i], options): i for i in indices}
        try:
            for future in as_completed(futures):
                i = futures[future]
                try:
                    results[i] = future.result()
                except BrokenProcessPool:
                    continue
                if progress is not None:
                    progress.step(submissions[i].team)
        except KeyboardInterrupt:
            for future in futures:
                future.cancel()
            raise
    return [i for i in indices if i not in results]
