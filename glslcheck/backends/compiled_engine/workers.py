"""The compiled engine's worker threads: daemons that run the bands of a frame, and the wait
on them that a budget or Ctrl-C can end (engine.py's contract for an abandoned frame)."""

from __future__ import annotations

import queue
import threading
import time
from collections.abc import Callable
from concurrent.futures import FIRST_EXCEPTION, Future, wait
from typing import Any

WAIT_SLICE = (
    0.1  # seconds the calling thread waits at a time: how soon Ctrl-C and the budget are seen
)


class Workers:
    """Daemon threads that run the bands of frames (made once per thread count: starting
    threads costs a frame of a small shader). A daemon, unlike ThreadPoolExecutor's threads, is
    not joined at the interpreter's exit: a band that never ends cannot hold the process."""

    def __init__(self, threads: int) -> None:
        self.jobs: queue.SimpleQueue = queue.SimpleQueue()
        for k in range(threads):
            threading.Thread(
                target=self._serve, name=f"glslcheck-compiled-{k}", daemon=True
            ).start()
        self.threads = threads

    def _serve(self) -> None:
        while True:
            job = self.jobs.get()
            if job is None:  # retired
                return
            fn, args, future = job
            if not future.set_running_or_notify_cancel():
                continue
            try:
                future.set_result(fn(*args))
            except BaseException as e:  # noqa: BLE001 - handed to the waiting thread
                future.set_exception(e)

    def submit(self, fn: Callable, *args: Any) -> Future:
        future: Future = Future()
        self.jobs.put((fn, args, future))
        return future

    def retire(self) -> None:
        """No more jobs: each thread ends once its current band does."""
        for _ in range(self.threads):
            self.jobs.put(None)


_WORKERS: dict[int, Workers] = {}
_WORKERS_LOCK = (
    threading.Lock()
)  # apart from _LOCK, which a compile holds while it waits for its thread
_ABANDONED: list[float] = []  # when frames or compiles were left running (abandoned())


def _workers(threads: int) -> Workers:
    with _WORKERS_LOCK:
        workers = _WORKERS.get(threads)
        if workers is None:
            workers = _WORKERS[threads] = Workers(threads)
        return workers


def abandoned() -> bool:
    """Whether this process left a frame or a compile running (over budget or interrupted):
    its threads go on until the process ends (the module docstring)."""
    return bool(_ABANDONED)


def run_bounded(threads: int, calls: list[tuple], deadline: float | None) -> None:
    """Run `calls` ((function, *args) each) on the worker threads; the calling thread waits in
    slices of WAIT_SLICE, so Ctrl-C (KeyboardInterrupt) reaches it. Raises TimeoutError when
    they have not all returned by `deadline` (time.monotonic(); None: none), KeyboardInterrupt as it
    came, or the first call's exception; on a timeout or an interrupt the calls not yet started are
    dropped and the threads of the others are retired (`abandoned()`)."""
    workers = _workers(threads)
    futures = [workers.submit(*c) for c in calls]
    try:
        while True:
            left = None if deadline is None else deadline - time.monotonic()
            if left is not None and left <= 0:
                raise TimeoutError
            done, pending = wait(
                futures, WAIT_SLICE if left is None else min(WAIT_SLICE, left), FIRST_EXCEPTION
            )
            for f in done:
                error = f.exception()
                if error is not None:
                    _drop(workers, futures)
                    raise error
            if not pending:
                return
    except (TimeoutError, KeyboardInterrupt):
        _drop(workers, futures)
        raise


def _drop(workers: Workers, futures: list[Future]) -> None:
    """Cancel the calls not started; retire the threads when some are still running."""
    for f in futures:
        f.cancel()
    if any(not f.done() for f in futures):
        with _WORKERS_LOCK:
            if _WORKERS.get(workers.threads) is workers:
                del _WORKERS[workers.threads]
        workers.retire()
        _ABANDONED.append(time.monotonic())
