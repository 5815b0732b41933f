"""Rendering a frame's tiles in worker processes.

Why processes: NumPy releases the GIL inside each operation, but a shader runs hundreds of short
operations per tile, and two threads then hand the GIL back and forth at every one of them. On
the benchmark machine two threads render the sparse four-sphere scene no faster than one
(benchmarks/bench_render.py prints both); two processes render it 1.5x faster.

Design:
- A process-wide pool of workers, each a fresh interpreter (`python -m
  glslcheck.backends.numpy_engine.workers FD`) that imports only NumPy and this package; nothing of
  the caller is inherited (no GL context, threads or locks), and the caller's `__main__` is never
  imported. Parent and worker talk over a socket pair with `multiprocessing.connection`.
- A worker compiles a program's module the first time it sees the program's key and keeps the
  last few.
- The image is written into an anonymous shared-memory file (memfd) whose descriptor the
  workers receive over their socket. Workers take tiles from a counter at the start of that
  file (under a POSIX lock) until none is left and write their rows straight into the shared
  image, in the order the caller gives (the slowest tiles of its last frame first, so the
  workers finish together). The finished frame is not copied: the caller gets a copy-on-write
  mapping of the file and the frame cache a read-only view of it; the file takes another frame
  once both are gone (`_FrameFile`). A caller that keeps many frames gets copies past
  MAX_MAPPINGS of them, and the pool lets go of held files past KEPT_FILES, so descriptors
  stay bounded.
- A worker dies with its parent, at once, even mid-tile (killed, SIGTERM, a crash): it watches
  the read end of a pipe only the parent holds open (`_watch_parent`). The frame's deadline
  (`frame.Budget`) travels with each frame; Ctrl-C in the caller kills the workers.
- A GlslError raised in a worker (a runaway loop, with its GLSL line) is raised in the caller.
  If a worker dies or cannot start, the pool closes, `Unavailable` is raised and the caller
  renders the frame with threads.

Linux only (memfd_create and descriptor passing over the socket); elsewhere `available()` is
False and renders use threads.
"""

from __future__ import annotations

import atexit
import fcntl
import hashlib
import mmap
import os
import socket
import subprocess
import sys
import threading
import time
import weakref
from collections import OrderedDict
from collections.abc import Sequence
from multiprocessing import reduction
from multiprocessing.connection import Connection
from typing import Any

import numpy as np

from . import jit
from .tiles import execute_module, render_tile

WORKER_MODULES = 8  # compiled programs a worker keeps
# A fresh process's malloc maps every block above 128 kB anew and returns it on free, so each
# tile temporary (a few hundred kB) page-faults on first write: the same tiles took 1.7x longer
# in a new worker than in a process that had already grown its heap. The worker keeps up to
# 128 MB of freed memory instead (glibc; other allocators ignore these variables).
MMAP_THRESHOLD, TRIM_THRESHOLD = 32 * 2**20, 128 * 2**20
MALLOC_ENV = {
    "MALLOC_MMAP_THRESHOLD_": str(MMAP_THRESHOLD),
    "MALLOC_TRIM_THRESHOLD_": str(TRIM_THRESHOLD),
}
M_TRIM_THRESHOLD, M_MMAP_THRESHOLD = -1, -3  # mallopt parameters (malloc.h)


def tune_malloc() -> bool:
    """The same malloc settings for this process (the CLI's render, verify and bench commands
    call it; a library user's process is left alone). True when applied."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        import ctypes

        libc = ctypes.CDLL("libc.so.6")
        return bool(libc.mallopt(M_MMAP_THRESHOLD, MMAP_THRESHOLD)) and bool(
            libc.mallopt(M_TRIM_THRESHOLD, TRIM_THRESHOLD)
        )
    except (OSError, AttributeError):  # not glibc
        return False


HEADER = 64  # bytes before the image in a frame's shared file: the next-tile counter
MAX_MAPPINGS = 64  # frames handed out as mappings and still alive; later ones are copies


class Unavailable(Exception):
    """The process pool cannot render this frame (not supported here, or a worker died)."""


def available() -> bool:
    return sys.platform.startswith("linux") and hasattr(os, "memfd_create") and _DISABLED is None


_DISABLED: str | None = None  # why the pool was given up for this process, if it was
_POOL: _Pool | None = None
_POOL_LOCK = threading.Lock()


def program_key(source: str, meta: dict, precision: str) -> str:
    return hashlib.sha1(f"{precision}\0{meta!r}\0{source}".encode()).hexdigest()


def render(
    key: str,
    source: str,
    filename: str,
    meta: dict,
    precision: str,
    spec: Any,
    tiles: Sequence[tuple[int, int, int, int]],
    workers: int,
    budget: Any = None,
) -> tuple[np.ndarray, np.ndarray, list[dict], dict]:
    """Render `tiles` of the frame `spec` with `workers` processes, in that order: (the caller's
    image, a read-only view of the same pixels for the frame cache (see `_FrameFile`), per-tile
    stats, {tile: seconds it took}). `budget`: the frame's `frame.Budget` (its deadline)."""
    global _POOL
    with _POOL_LOCK:  # one frame at a time through the pool
        if not available():
            raise Unavailable(_DISABLED or "worker processes need Linux")
        try:
            if _POOL is None or _POOL.size != workers:
                if _POOL is not None:
                    _POOL.close()
                    _POOL = None
                _POOL = _Pool(workers)
            image, shared, stats, seconds, errors = _POOL.render(
                key, source, filename, meta, precision, spec, tiles, budget
            )
        except Unavailable as e:
            _give_up(str(e))
            raise
        except BaseException:  # interrupted mid-frame (Ctrl-C, ...): replies may still be on
            if _POOL is not None:  # the way, so these workers cannot serve another frame
                _POOL.close(now=True)
                _POOL = None
            raise
    if errors:  # raised in a worker, every worker has answered: the pool stays usable
        raise errors[0]
    return image, shared, stats, seconds


def running() -> bool:
    """True when a pool is up (starting one costs a few tenths of a second)."""
    return _POOL is not None


def shutdown() -> None:
    global _POOL
    with _POOL_LOCK:
        if _POOL is not None:
            _POOL.close()
            _POOL = None


def _give_up(reason: str) -> None:
    global _POOL, _DISABLED
    if _POOL is not None:
        _POOL.close(now=True)  # the frame is abandoned: a live worker may still be in it
        _POOL = None
    _DISABLED = reason


atexit.register(shutdown)


class _Worker:
    def __init__(self) -> None:
        ours, theirs = socket.socketpair()
        # the worker's lifeline: it reads the other end of this pipe, which nobody writes, and
        # exits when the read returns end-of-file, that is when this process is gone (killed,
        # SIGTERM, a crash: no atexit needed). PR_SET_PDEATHSIG would fire when the *thread* that
        # started the worker ends, and a pool made in a short-lived thread must outlive it.
        lifeline, self.lifeline = os.pipe()  # neither end is inherited by other children
        env = dict(os.environ)
        # the worker imports the same glslcheck as this process (a source tree, a worktree, ...)
        root = os.path.dirname(
            os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
        )
        env["PYTHONPATH"] = root + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
        env.update(MALLOC_ENV)
        try:
            self.proc = subprocess.Popen(
                [
                    sys.executable,
                    "-m",
                    "glslcheck.backends.numpy_engine.workers",
                    str(theirs.fileno()),
                    str(lifeline),
                ],
                pass_fds=(theirs.fileno(), lifeline),
                env=env,
                stdin=subprocess.DEVNULL,
                close_fds=True,
                # `-m` puts the working directory first on sys.path: another checkout there would
                # win
                cwd=root,
                # a worker that fails is reported as Unavailable, no traceback
                stderr=subprocess.DEVNULL,
                start_new_session=True,
            )  # Ctrl-C reaches the caller, which ends the workers
        except BaseException:
            os.close(self.lifeline)
            raise
        finally:
            theirs.close()
            os.close(lifeline)
        self.conn = Connection(ours.detach())
        self.files: set[int] = set()  # the numbers of the frame files this worker has mapped

    def close(self, now: bool = False) -> None:
        """Ask the worker to end (at once with `now`: it may be in the middle of a frame)."""
        if now:
            self.proc.kill()
        else:
            try:
                self.conn.send(None)
            except OSError:
                pass
        self.conn.close()
        try:
            self.proc.wait(timeout=2)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        finally:
            os.close(self.lifeline)


class _FrameFile:
    """A shared file the workers write frames into: a next-tile counter, then one image.

    A finished frame is handed out without copying it: the caller gets a private copy-on-write
    mapping of the file (a page is copied only if the caller writes to it, so the caller may
    write freely) and the frame cache a read-only view of the shared mapping. The file takes a
    new frame only when neither is alive any more (weak references to both), so frames that
    are kept are never overwritten; the pool makes a new file when no free one has the size.
    Reusing a file matters: a new one page-faults on every first write (3.8 ms for an 800x450
    image; copying the image out of a mapped one took 0.4 ms, and twice that with the cache's
    copy, all of it in the caller while the workers wait)."""

    def __init__(self, shape: tuple[int, int, int], number: int) -> None:
        self.shape = shape
        self.number = number
        self.size = HEADER + shape[0] * shape[1] * shape[2] * 4
        self.fd = os.memfd_create("glslcheck-frame", os.MFD_CLOEXEC)
        os.ftruncate(self.fd, self.size)
        self.mm = mmap.mmap(self.fd, self.size)
        self.counter = np.frombuffer(self.mm, dtype=np.int64, count=1)
        self.holders: tuple = ()  # weak references to the arrays handed out for the last frame

    def free(self) -> bool:
        return all(ref() is None for ref in self.holders)

    def hand_out(self, mappings: list) -> tuple[np.ndarray, np.ndarray]:
        """(the caller's copy-on-write image, a read-only shared view for the frame cache).

        Each mapping holds a file descriptor (Python's mmap keeps a duplicate), so past
        MAX_MAPPINGS images still alive (`mappings`: weak references to them) the caller gets
        a plain copy instead, as it does if the mapping cannot be made."""
        count = self.shape[0] * self.shape[1] * self.shape[2]
        shared = np.frombuffer(self.mm, dtype=np.float32, offset=HEADER, count=count)
        shared.flags.writeable = False
        mappings[:] = [ref for ref in mappings if ref() is not None]
        mine = None
        if len(mappings) < MAX_MAPPINGS:
            try:
                private = mmap.mmap(self.fd, self.size, flags=mmap.MAP_PRIVATE)
                mine = np.frombuffer(private, dtype=np.float32, offset=HEADER, count=count)
                mappings.append(weakref.ref(mine))
            except OSError:  # out of descriptors or address space: copy
                mine = None
        if mine is None:
            self.holders = (weakref.ref(shared),)
            return shared.reshape(self.shape).copy(), shared.reshape(self.shape)
        # every view of these arrays keeps them alive (NumPy points a view's base at them)
        self.holders = (weakref.ref(mine), weakref.ref(shared))
        return mine.reshape(self.shape), shared.reshape(self.shape)

    def close(self) -> None:
        """Close the file; mappings still in use stay valid (the kernel keeps the memory)."""
        del self.counter
        try:
            self.mm.close()
        except BufferError:  # a view is alive somewhere: the mapping goes when it does
            pass
        os.close(self.fd)


class _Pool:
    SPARE_FILES = 2  # free frame files kept for the next frames (the others are closed)
    # files still held (by the caller or the frame cache) that the pool keeps open to reuse
    # once they are free; older ones are let go (closed here and in the workers: their memory
    # lives on in the caller's arrays), so holding many frames does not hold as many descriptors
    KEPT_FILES = 12

    def __init__(self, size: int) -> None:
        self.size = size
        self.workers: list[_Worker] = []
        self.files: list[_FrameFile] = []
        self.numbers = 0  # frame files made so far (a file's number names it to the workers)
        self.retired: list[int] = []  # closed files the workers still have mapped
        self.mappings: list = []  # weak references to the images handed out as mappings
        try:
            for _ in range(size):
                self.workers.append(_Worker())
        except OSError as e:
            self.close()
            raise Unavailable(f"cannot start a render worker: {e}") from None

    def close(self, now: bool = False) -> None:
        for w in self.workers:
            w.close(now)
        self.workers = []
        for f in self.files:
            f.close()
        self.files = []

    def _file(self, shape: tuple[int, int, int]) -> _FrameFile:
        """A free file of this shape (a new one if none is), closing free files beyond the
        spares."""
        free = [f for f in self.files if f.free()]
        file = next((f for f in free if f.shape == shape), None)
        if file is None:
            self.numbers += 1
            try:
                file = _FrameFile(shape, self.numbers)
            except OSError as e:  # out of memory or descriptors
                raise Unavailable(f"cannot make a shared frame file: {e}") from None
            self.files.append(file)
        else:
            free.remove(file)
        held = [f for f in self.files if f not in free and f is not file]
        for f in free[self.SPARE_FILES :] + held[: -self.KEPT_FILES]:  # oldest first
            f.close()
            self.files.remove(f)
            self.retired.append(f.number)
        return file

    def render(self, key, source, filename, meta, precision, spec, tiles, budget=None):
        file = self._file((spec.height, spec.width, 4))
        file.counter[0] = 0
        retired, self.retired = self.retired, []
        try:
            for w in self.workers:  # the source too (tens of kB): a worker may have dropped it
                new_file = file.number not in w.files
                w.conn.send(
                    (
                        key,
                        source,
                        filename,
                        meta,
                        precision,
                        spec,
                        tiles,
                        file.shape,
                        file.number,
                        new_file,
                        retired,
                        budget,
                        jit.decided(),
                    )
                )
                w.files.difference_update(retired)
                if new_file:
                    reduction.send_handle(w.conn, file.fd, w.proc.pid)
                    w.files.add(file.number)
        except OSError as e:
            raise Unavailable(f"a render worker stopped: {e}") from None
        stats: list[dict] = []
        seconds: dict = {}
        errors: list[BaseException] = []
        try:
            counted = 0.0
            for w in self.workers:
                tile_stats, tile_seconds, error, math_seconds = w.conn.recv()
                counted += math_seconds
                stats.extend(tile_stats)
                seconds.update(tile_seconds)
                if error is not None:
                    errors.append(error)
        except (EOFError, OSError) as e:
            raise Unavailable(f"a render worker stopped: {e or type(e).__name__}") from None
        jit.add_counted(counted, len(self.workers))  # the compiled math kernels' rule (jit.py)
        if errors:
            return None, None, stats, seconds, errors
        image, shared = file.hand_out(self.mappings)
        return image, shared, stats, seconds, errors


# ---------------------------------------------------------------------------------------------
# The worker process
# ---------------------------------------------------------------------------------------------


def _picklable(e: BaseException) -> BaseException:
    import pickle

    try:
        pickle.loads(pickle.dumps(e))
        return e
    except Exception:  # noqa: BLE001 - any exception must reach the caller as something
        return RuntimeError(f"{type(e).__name__}: {e}")


def _serve(conn: Connection) -> None:
    modules: OrderedDict[str, dict] = OrderedDict()
    files: dict[int, tuple[int, mmap.mmap]] = {}  # frame file number -> (descriptor, mapping)
    while True:
        try:
            msg = conn.recv()
        except EOFError:
            return
        if msg is None:
            return
        (
            key,
            source,
            filename,
            meta,
            precision,
            spec,
            tiles,
            shape,
            number,
            new_file,
            retired,
            budget,
            kernels,
        ) = msg
        if kernels and jit.mode() != "off":  # the parent's rule chose the compiled math kernels
            jit.load()
        for n in retired:  # files the caller has closed
            fd, mm = files.pop(n, (-1, None))
            if mm is not None:
                mm.close()
                os.close(fd)
        if new_file:
            fd = reduction.recv_handle(conn)
            files[number] = (fd, mmap.mmap(fd, HEADER + shape[0] * shape[1] * shape[2] * 4))
        fd, mm = files[number]
        stats: list[dict] = []
        # tile -> seconds it took here (the caller orders the next frame's tiles)
        seconds: dict = {}
        try:
            _render_frame(
                fd,
                mm,
                modules,
                key,
                source,
                filename,
                meta,
                precision,
                spec,
                tiles,
                shape,
                stats,
                seconds,
                budget,
            )
            error = None
        except BaseException as e:  # noqa: BLE001 - reported to the caller, which raises it
            _take_tile(fd, mm, stop=len(tiles))  # the other workers stop too
            e.__traceback__ = e.__context__ = e.__cause__ = None  # frames hold views of the file
            error = _picklable(e)
        conn.send((stats, seconds, error, jit.counted()))


def _take_tile(fd: int, mm: mmap.mmap, stop: int | None = None) -> int:
    """The next tile index from the frame's shared counter (a POSIX lock around it)."""
    fcntl.lockf(fd, fcntl.LOCK_EX, HEADER, 0)
    try:
        counter = np.frombuffer(mm, dtype=np.int64, count=1)
        i = int(counter[0])
        counter[0] = stop if stop is not None else i + 1
        del counter
        return i
    finally:
        fcntl.lockf(fd, fcntl.LOCK_UN, HEADER, 0)


def _render_frame(
    fd,
    mm,
    modules,
    key,
    source,
    filename,
    meta,
    precision,
    spec,
    tiles,
    shape,
    stats,
    seconds,
    budget=None,
):
    ns = modules.get(key)
    if ns is None:
        ns = modules[key] = execute_module(source, filename, meta, precision)
        while len(modules) > WORKER_MODULES:
            modules.popitem(last=False)
    modules.move_to_end(key)
    image = np.frombuffer(mm, dtype=np.float32, offset=HEADER).reshape(shape)
    if budget is not None:
        budget.start()  # the frame's deadline, on this machine's one monotonic clock
    try:
        while True:
            i = _take_tile(fd, mm)
            if i >= len(tiles):
                return
            t0 = time.perf_counter()
            st = render_tile(ns, spec, tiles[i], image, budget=budget)
            seconds[tiles[i]] = time.perf_counter() - t0
            if st is not None:
                stats.append(st)
    finally:
        if budget is not None:
            budget.finish()


def _watch_parent(lifeline: int) -> None:
    """End this worker at once when the parent is gone (its end of the lifeline pipe closed),
    even in the middle of a tile: an orphan would go on at 100% CPU."""

    def watch() -> None:
        try:
            while os.read(lifeline, 1):
                pass
        except OSError:
            pass
        os._exit(0)

    threading.Thread(target=watch, name="glslcheck-lifeline", daemon=True).start()


def main(argv: list[str]) -> int:
    if len(argv) > 1:
        _watch_parent(int(argv[1]))
    conn = Connection(int(argv[0]))
    try:
        _serve(conn)
    except (EOFError, OSError, KeyboardInterrupt):
        pass
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
