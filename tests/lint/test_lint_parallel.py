"""Linting on two cores (lint/parallel.py): the same findings and report, byte for byte, as one
process; a failing child costs time, never a finding."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from glslcheck.lint import parallel
from glslcheck.lint.report import render

from .conftest import FIXTURES, REPO_ROOT

LAB = REPO_ROOT / "lab_shaders"


def _cli(*args: str, jobs: str) -> subprocess.CompletedProcess:
    env = {**os.environ, "GLSLCHECK_JOBS": jobs}
    return subprocess.run(
        [sys.executable, "-m", "glslcheck", *args],
        capture_output=True,
        text=True,
        env=env,
        cwd=REPO_ROOT,
    )


@pytest.mark.parametrize("fmt", ["text", "json"])
@pytest.mark.parametrize("folder", [LAB, FIXTURES])
def test_two_processes_print_what_one_prints(folder, fmt):
    one = _cli("lint", "--format", fmt, str(folder), jobs="1")
    two = _cli("lint", "--format", fmt, str(folder), jobs="2")
    assert one.stdout and one.returncode in (0, 1)
    assert (two.returncode, two.stdout, two.stderr) == (one.returncode, one.stdout, one.stderr)


@pytest.fixture
def no_other_threads(monkeypatch):
    """Earlier tests of the suite leave the NumPy backend's tile threads (program._POOLS, kept
    for the next render) alive in this process, and `jobs` rightly refuses to fork beside them:
    the tests that exercise the fork say the process runs no other thread.
    test_no_fork_beside_other_threads checks that rule itself, in a fresh interpreter."""
    monkeypatch.setattr(parallel, "_threads", lambda: False)


def test_the_child_lints_the_second_half(monkeypatch, no_other_threads):
    monkeypatch.setenv("GLSLCHECK_JOBS", "2")
    parent = os.getpid()
    registry: dict = {}

    def lint(items):
        for i in items:
            registry[f"file{i}"] = [f"line of {i}"]
        return [(i, os.getpid() == parent) for i in items]

    out = parallel.run_split(list(range(6)), [5000] * 6, lint, lambda: None, registry)
    assert [i for i, _ in out] == list(range(6))
    assert [here for _, here in out] == [True] * 3 + [
        False
    ] * 3  # the second half came from the child
    assert registry == {
        f"file{i}": [f"line of {i}"] for i in range(6)
    }  # the child's texts came back


def test_a_failing_child_is_redone_here(monkeypatch, no_other_threads):
    monkeypatch.setenv("GLSLCHECK_JOBS", "2")
    parent = os.getpid()

    def lint(items):
        if os.getpid() != parent:
            raise RuntimeError("the child fails")
        return list(items)

    assert parallel.run_split(list(range(4)), [5000] * 4, lint, lambda: None, {}) == [0, 1, 2, 3]


def test_an_error_in_the_first_half_is_raised_and_the_child_reaped(monkeypatch, no_other_threads):
    monkeypatch.setenv("GLSLCHECK_JOBS", "2")
    forked = []
    fork = os.fork

    def recording_fork():
        pid = fork()
        if pid:
            forked.append(pid)
        return pid

    monkeypatch.setattr(parallel.os, "fork", recording_fork)

    def lint(items):
        if 0 in items:
            raise ValueError("first half")
        return list(items)

    with pytest.raises(ValueError, match="first half"):
        parallel.run_split(list(range(4)), [5000] * 4, lint, lambda: None, {})
    assert len(forked) == 1
    with pytest.raises(ChildProcessError):
        os.waitpid(forked[0], os.WNOHANG)  # the child was reaped: not left behind


def test_small_runs_and_one_job_stay_in_this_process(monkeypatch):
    parent = os.getpid()

    def lint(items):
        assert os.getpid() == parent
        return list(items)

    monkeypatch.setenv("GLSLCHECK_JOBS", "2")
    assert parallel.run_split([1, 2], [100, 100], lint, lambda: None, {}) == [
        1,
        2,
    ]  # too little text
    monkeypatch.setenv("GLSLCHECK_JOBS", "1")
    assert parallel.run_split(list(range(4)), [5000] * 4, lint, lambda: None, {}) == [0, 1, 2, 3]


def test_jobs(monkeypatch, no_other_threads):
    monkeypatch.setattr(parallel.os, "sched_getaffinity", lambda pid: {0, 1}, raising=False)
    monkeypatch.delenv("GLSLCHECK_JOBS", raising=False)
    monkeypatch.setattr(parallel.os, "getloadavg", lambda: (0.3, 0.5, 0.5))
    assert parallel.jobs() == 2  # a quiet two-core machine
    monkeypatch.setattr(parallel.os, "getloadavg", lambda: (3.9, 3.0, 2.0))
    assert parallel.jobs() == 1  # both cores busy: a second process would only take turns
    monkeypatch.setenv("GLSLCHECK_JOBS", "2")
    assert parallel.jobs() == 2  # asked for
    monkeypatch.setenv("GLSLCHECK_JOBS", "1")
    monkeypatch.setattr(parallel.os, "getloadavg", lambda: (0.0, 0.0, 0.0))
    assert parallel.jobs() == 1
    monkeypatch.delenv("GLSLCHECK_JOBS")
    monkeypatch.setattr(parallel.os, "sched_getaffinity", lambda pid: {0}, raising=False)
    assert parallel.jobs() == 1  # one usable core


def test_no_fork_beside_other_threads():
    # a fresh interpreter: this test process may already run other tests' threads
    code = """if True:
        import threading
        from glslcheck.lint import parallel
        assert parallel.jobs() == 2, "no other thread yet"
        stop = threading.Event()
        thread = threading.Thread(target=stop.wait)
        thread.start()
        try:
            assert parallel.jobs() == 1, "a child would hold only this thread, and its locks"
        finally:
            stop.set()
            thread.join()
        assert parallel.jobs() == 2, "the thread has ended"
    """
    env = {**os.environ, "GLSLCHECK_JOBS": "2"}
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, cwd=REPO_ROOT
    )
    assert done.returncode == 0, done.stderr


def test_split_point_halves_the_text():
    assert parallel.split_point([1, 1]) == 1
    assert parallel.split_point([10, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1]) == 1
    assert parallel.split_point([1, 1, 1, 1, 10]) == 4
    assert parallel.split_point([3, 3, 3, 3]) == 2


def test_lint_paths_in_process_matches(monkeypatch, no_other_threads):
    from glslcheck.lint import lint_paths

    monkeypatch.setenv("GLSLCHECK_JOBS", "1")
    one = lint_paths([str(FIXTURES)])
    monkeypatch.setenv("GLSLCHECK_JOBS", "2")
    two = lint_paths([str(FIXTURES)])
    assert two.findings == one.findings and two.paths == one.paths
    assert render(two, "json") == render(one, "json")
