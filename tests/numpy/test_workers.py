"""Rendering tiles in worker processes (glslcheck/backends/numpy_engine/workers.py) changes no
pixel, no statistic and no error: every frame here is rendered with processes and with threads and
must be bit-identical. A worker that dies makes the frame fall back to threads.

Worker processes need Linux (memfd_create); elsewhere these tests are skipped and say so (CI
runs on Linux, where a skip would be a bug: the CI check below fails instead).
"""

from __future__ import annotations

import os
import signal

import numpy as np
import pytest
from test_overheads import SHADER as SPARSE_SHADER  # compaction, globals, discard, gl_FragCoord
from test_overheads import knobs  # noqa: F401 - the fixture

from glslcheck.backends.numpy_engine import program as P
from glslcheck.backends.numpy_engine import tiles as F
from glslcheck.backends.numpy_engine import workers
from glslcheck.base.diagnostics import GlslError

DERIVATIVES = """
void mainImage(out vec4 o, in vec2 f) {
    float v = sin(f.x * 0.37) * cos(f.y * 0.21) + (f.x > 20.0 ? 1.0 : 0.0);
    o = vec4(dFdx(v), dFdy(v), fwidth(v * v), 1.0);
}
"""

RUNAWAY = """
void mainImage(out vec4 o, in vec2 f) {
    float acc = 0.0;
    while (f.y > 30.0 && acc >= 0.0) { acc += 1.0; }
    o = vec4(acc);
}
"""


@pytest.fixture(autouse=True)
def fresh_pool():
    if not workers.available():
        if os.environ.get("CI"):
            pytest.fail(
                "worker processes are unavailable on the CI machine (Linux): "
                + str(workers._DISABLED)
            )
        pytest.skip("worker processes need Linux with memfd_create (this machine: threads only)")
    yield
    workers.shutdown()
    workers._DISABLED = None


def _on_processes(make_shader, source: str):
    """A program of `source` that renders on two worker processes."""
    prog = P.compile_numpy(make_shader(source))
    prog.threads, prog.parallel = 2, "processes"
    return prog


def _both(prog, **kw):
    """The same frame rendered by worker processes and by threads."""
    prog.threads = 2
    prog.parallel = "processes"
    prog._cache.clear()
    a = prog.render(**kw)
    assert prog.last_parallel == "processes"
    stats_a = list(prog.last_stats)
    prog.parallel = "threads"
    prog._cache.clear()
    b = prog.render(**kw)
    assert prog.last_parallel == "threads"
    return a, b, stats_a, list(prog.last_stats)


@pytest.mark.parametrize(
    "kw",
    [
        dict(size=(96, 54)),
        dict(size=(96, 54), stats=True),
        dict(size=(60, 40), samples=4),
        dict(size=(61, 37), precision="float16"),
        dict(size=(61, 37), precision="float64", time=1.5),
    ],
)
def test_processes_render_what_threads_render(make_shader, knobs, kw):
    knobs(TILE_LANES=600)  # many tiles, compacted regions in most
    prog = P.compile_numpy(make_shader(SPARSE_SHADER))
    prog.compaction = F.Compaction(min_lanes=16)
    a, b, sa, sb = _both(prog, **kw)
    assert a.shape == b.shape and a.dtype == b.dtype == np.float32
    assert np.array_equal(a, b, equal_nan=True)
    assert sa == sb
    if kw.get("stats"):
        assert any(s.lanes for s in sa)


def test_derivative_quads_stay_whole_in_workers(make_shader, knobs):
    knobs(TILE_LANES=200)
    prog = P.compile_numpy(make_shader(DERIVATIVES))
    a, b, _, _ = _both(prog, size=(64, 30))
    assert np.array_equal(a, b, equal_nan=True) and np.isfinite(a).all()


def test_a_runaway_loop_in_a_worker_is_the_same_located_error(make_shader, knobs):
    knobs(TILE_LANES=400)
    prog = _on_processes(make_shader, RUNAWAY)
    with pytest.raises(GlslError) as e:
        prog.render(size=(40, 40))
    d = e.value.diagnostics[0]
    assert d.loc.line == 4 and "did not end" in d.message
    prog.parallel = "threads"
    with pytest.raises(GlslError) as t:
        prog.render(size=(40, 40))
    assert t.value.diagnostics[0].message == d.message and t.value.diagnostics[0].loc == d.loc
    # the pool is still usable after an error
    ok = _on_processes(make_shader, DERIVATIVES)
    ok.render(size=(32, 32))
    assert ok.last_parallel == "processes"


def test_returned_images_are_the_callers(make_shader, knobs):
    knobs(TILE_LANES=600)
    prog = _on_processes(make_shader, SPARSE_SHADER)
    first = prog.render(size=(48, 32), time=0.0)
    keep = first.copy()
    first[:] = 5.0  # the caller may write to it; the frame cache keeps its own copy
    again = prog.render(size=(48, 32), time=0.0)
    assert np.array_equal(again, keep, equal_nan=True)
    prog._cache.clear()
    third = prog.render(size=(48, 32), time=0.0)  # a new shared file: `again` is untouched
    assert np.array_equal(again, keep, equal_nan=True) and np.array_equal(
        third, keep, equal_nan=True
    )


def test_frame_files_are_reused_only_when_nothing_holds_them(make_shader, knobs):
    """Frames are handed out without a copy (workers._FrameFile): a file takes a new frame only
    when neither the caller's image (nor any view of it) nor the frame cache holds the last."""
    knobs(TILE_LANES=600)
    prog = _on_processes(make_shader, SPARSE_SHADER)
    files = lambda: workers._POOL.files  # noqa: E731

    for t in (0.0, 1.0, 2.0):
        prog._cache.clear()
        prog.render(size=(48, 32), time=t)  # dropped at once: the one file serves every frame
    assert len(files()) == 1
    prog._cache.clear()  # (a cache hit would be a copy, not the file)
    first = prog.render(size=(48, 32), time=3.0)
    rows = first[5:9, ::2]  # a view keeps the file as well as the image does
    keep = rows.copy()
    del first
    prog._cache.clear()
    second = prog.render(size=(48, 32), time=4.0)
    assert len(files()) == 2 and np.array_equal(rows, keep, equal_nan=True)
    rows[:] = -1.0  # a private copy-on-write mapping: the file is untouched
    prog._cache.clear()
    assert np.array_equal(prog.render(size=(48, 32), time=3.0)[5:9, ::2], keep, equal_nan=True)
    del rows, second
    for t in range(6):  # frames of new sizes, nothing held: free files are
        prog._cache.clear()  # closed beyond the spares
        prog.render(size=(48 + 2 * t, 32), time=0.0)
    assert len(files()) == 1 + workers._Pool.SPARE_FILES


def test_frames_held_by_the_caller_hold_no_descriptors_beyond_a_few(
    make_shader, knobs, monkeypatch
):
    knobs(TILE_LANES=600)
    prog = _on_processes(make_shader, SPARSE_SHADER)
    fds = lambda: len(os.listdir("/proc/self/fd"))  # noqa: E731
    prog.render(size=(48, 32), time=0.0)
    before = fds()
    frames = []
    for t in range(40):  # an animation kept in memory (a GIF's frames)
        prog._cache.clear()
        frames.append(prog.render(size=(48, 32), time=float(t)))
    assert len(workers._POOL.files) <= workers._Pool.KEPT_FILES + 1
    # two per file open in the pool (its descriptor and the mapping's duplicate: Python's mmap
    # keeps one) and one per image that is a mapping; past MAX_MAPPINGS images are copies
    held = fds()
    assert held <= before + 2 * (workers._Pool.KEPT_FILES + 1) + len(frames)
    monkeypatch.setattr(workers, "MAX_MAPPINGS", 8)  # 40 are alive: the next ones are copies
    more = [
        prog.render(size=(48, 32), time=float(t))
        for t in range(100, 140)
        if not prog._cache.clear()
    ]
    assert all(img.base is None for img in more) and fds() <= held + 2
    prog._cache.clear()
    for t, img in enumerate(frames):  # every frame is intact, the oldest included
        assert np.array_equal(img, prog.render(size=(48, 32), time=float(t)), equal_nan=True)


def test_workers_report_tile_times_for_the_next_frames_order(make_shader, knobs):
    from test_overheads import UNEVEN  # rows above y = 24 loop 400 times, the others never

    knobs(TILE_LANES=16 * 8, TILE_WIDTH=16)  # 16x32: four tiles of eight rows
    prog = _on_processes(make_shader, UNEVEN)
    first = prog.render(size=(16, 32))
    assert prog.last_parallel == "processes"
    tiles = F.frame_tiles(16, 32)
    assert tiles[prog._tile_order[tuple(tiles)][0]][1] == 24  # the slow tile goes first next time
    prog._cache.clear()
    assert np.array_equal(prog.render(size=(16, 32)), first, equal_nan=True)


def test_another_glslcheck_in_the_working_directory_does_not_shadow_the_workers(
    make_shader, knobs, tmp_path, monkeypatch
):
    # `python -m` puts the working directory first on sys.path: workers start in the package root
    (tmp_path / "glslcheck").mkdir()
    (tmp_path / "glslcheck" / "__init__.py").write_text("raise ImportError('not this glslcheck')\n")
    monkeypatch.chdir(tmp_path)
    workers.shutdown()
    knobs(TILE_LANES=600)
    prog = _on_processes(make_shader, SPARSE_SHADER)
    prog.render(size=(48, 32))
    assert prog.last_parallel == "processes" and workers._DISABLED is None


def test_a_dead_worker_falls_back_to_threads(make_shader, knobs):
    knobs(TILE_LANES=600)
    prog = _on_processes(make_shader, SPARSE_SHADER)
    want = prog.render(size=(48, 32))
    assert prog.last_parallel == "processes"
    os.kill(workers._POOL.workers[0].proc.pid, signal.SIGKILL)
    workers._POOL.workers[0].proc.wait()
    prog._cache.clear()
    got = prog.render(size=(48, 32))
    assert prog.last_parallel == "threads" and np.array_equal(got, want, equal_nan=True)
    assert not workers.available() and "stopped" in workers._DISABLED


def test_auto_starts_processes_only_after_enough_rendering(make_shader, knobs):
    knobs(TILE_LANES=600, PROCESSES_AFTER=3600.0)
    prog = P.compile_numpy(make_shader(SPARSE_SHADER))
    prog.threads, prog.parallel = 2, "auto"
    prog.render(size=(48, 32))
    assert prog.last_parallel == "threads" and not workers.running()
    knobs(PROCESSES_AFTER=0.0)
    prog._cache.clear()
    prog.render(size=(48, 32))
    assert prog.last_parallel == "processes" and workers.running()
    one = P.compile_numpy(make_shader(DERIVATIVES))  # a pool that is up serves every program
    one.threads, one.parallel = 2, "auto"
    knobs(PROCESSES_AFTER=3600.0)
    one.render(size=(48, 32))
    assert one.last_parallel == "processes"


def test_shutdown_ends_the_workers(make_shader, knobs):
    knobs(TILE_LANES=600)
    prog = _on_processes(make_shader, DERIVATIVES)
    prog.render(size=(32, 32))
    procs = [w.proc for w in workers._POOL.workers]
    workers.shutdown()
    assert all(p.poll() is not None for p in procs) and not workers.running()


def test_unknown_parallel_mode_is_refused(make_shader):
    prog = P.compile_numpy(make_shader(DERIVATIVES))
    prog.threads, prog.parallel = 2, "fibres"
    with pytest.raises(ValueError, match="parallel"):
        prog.render(size=(8, 8))


def test_an_interrupted_frame_closes_the_pool(make_shader, knobs, monkeypatch):
    """Ctrl-C while workers render: their answers may still come, so the pool must not serve
    another frame; the next render starts new workers and is right."""
    knobs(TILE_LANES=600)
    prog = _on_processes(make_shader, SPARSE_SHADER)
    want = prog.render(size=(48, 32))
    old = workers._POOL
    procs = [w.proc for w in old.workers]
    real = workers._Pool.render

    def interrupted(self, *a):
        real(self, *a)
        raise KeyboardInterrupt

    monkeypatch.setattr(workers._Pool, "render", interrupted)
    prog._cache.clear()
    with pytest.raises(KeyboardInterrupt):
        prog.render(size=(48, 32))
    assert workers._POOL is None and procs and all(p.poll() is not None for p in procs)
    monkeypatch.setattr(workers._Pool, "render", real)
    prog._cache.clear()
    assert np.array_equal(prog.render(size=(48, 32)), want, equal_nan=True)
    assert prog.last_parallel == "processes" and workers._POOL is not old


def test_workers_that_cannot_start_leave_threads(make_shader, knobs, monkeypatch):
    knobs(TILE_LANES=600)
    prog = _on_processes(make_shader, DERIVATIVES)
    monkeypatch.setattr(workers.sys, "executable", "/nonexistent/python")
    img = prog.render(size=(48, 32))
    assert prog.last_parallel == "threads" and np.isfinite(img).all()
    assert not workers.available() and "cannot start" in workers._DISABLED


def test_cli_parallel_option_and_environment(tmp_path, monkeypatch, capsys):
    from glslcheck.cli.main import main

    shader = tmp_path / "Image.glsl"
    shader.write_text(DERIVATIVES)
    seen = []
    real = P.NumpyProgram.render

    def spy(self, *a, **k):
        seen.append(self.parallel)
        return real(self, *a, **k)

    monkeypatch.setattr(P.NumpyProgram, "render", spy)
    monkeypatch.delenv("GLSLCHECK_PARALLEL", raising=False)
    out = str(tmp_path / "o.npy")
    assert (
        main(["render", str(shader), "--size", "64x40", "-o", out, "--parallel", "processes"]) == 0
    )
    assert seen[-1] == "processes" and "GLSLCHECK_PARALLEL" not in os.environ  # restored
    monkeypatch.setenv("GLSLCHECK_PARALLEL", "threads")
    assert main(["render", str(shader), "--size", "64x40", "-o", out]) == 0
    assert seen[-1] == "threads"
    monkeypatch.setenv("GLSLCHECK_PARALLEL", "fibres")
    assert main(["render", str(shader), "--size", "64x40", "-o", out]) == 2
    assert (
        "GLSLCHECK_PARALLEL must be one of auto, threads, processes, not 'fibres'"
        in capsys.readouterr().err
    )
    assert main(["render", str(shader), "--parallel", "fibres"]) == 2  # argparse: a usage error
