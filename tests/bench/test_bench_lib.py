"""glslcheck.verification.bench as a library, with fake programs and a fake clock: what is rendered
and timed, the reference, the error metrics, the Pareto front and the plot. No real timing is
asserted."""

from __future__ import annotations

import math

import numpy as np
import pytest

from glslcheck.verification.bench import (
    JSON_KEYS,
    Config,
    Row,
    bench_shader,
    configurations,
    format_table,
    mark_pareto,
    measure_error,
    write_plot,
)

W, H = 8, 6


class FakeProgram:
    """Renders a flat colour that depends on precision and samples; records each call."""

    def __init__(self, backend, value):
        self.backend = backend
        self.value = value
        self.calls = []
        self.impl = type("Impl", (), {})()
        self.impl._cache = {"stale": 1}
        self.cache_seen = []

    def render(self, size, time, samples, precision=None):
        self.calls.append((samples, precision))
        self.cache_seen.append(len(self.impl._cache))
        img = np.ones((size[1], size[0], 4), dtype=np.float32)
        img[..., :3] = self.value(samples, precision)
        return img


class FakeClock:
    """A perf_counter stand-in whose renders take longer and longer (medians stay well defined)."""

    def __init__(self):
        self.now = 0.0
        self.ticks = 0

    def __call__(self):
        self.ticks += 1
        if self.ticks % 2 == 0:  # the end of a render
            self.now += 0.001 * self.ticks
        return self.now


def _value(samples, precision):
    # The reference (float64, 16) is 0.5; others are off by an amount that shrinks with samples.
    off = {"float16": 0.1, "float32": 0.01, "float64": 0.0, None: 0.02}[precision]
    return 0.5 + off + (0.0 if samples == 16 else 0.04 / samples)


@pytest.fixture
def rows_and_programs(make_shader):
    shader = make_shader("void mainImage(out vec4 c, in vec2 f) { c = vec4(1.0); }")
    gl, npy = FakeProgram("gl", _value), FakeProgram("numpy", _value)
    steps = []
    rows = bench_shader(
        shader, size=(W, H), runs=3, programs=(gl, npy), step=steps.append, clock=FakeClock()
    )
    return rows, gl, npy, steps


def test_twelve_configurations_gl_first():
    configs = configurations()
    assert len(configs) == 12
    assert [c.label for c in configs[:3]] == ["gl x1", "gl x4", "gl x16"]
    assert {c.precision for c in configs if c.backend == "auto"} == {
        "float16",
        "float32",
        "float64",
    }
    assert [c for c in configs if c.is_reference] == [Config("auto", "float64", 16)]


def test_warm_up_then_round_robin_runs(rows_and_programs):
    rows, gl, npy, steps = rows_and_programs
    assert len(rows) == 12 and len(steps) == 12 * 4
    assert gl.calls == [(1, None), (4, None), (16, None)] * 4  # GL gets no precision
    assert len(npy.calls) == 9 * 4
    assert npy.cache_seen == [0] * len(npy.calls)  # the frame cache is emptied before every render
    assert all(len(r.times_ms) == 3 for r in rows)


def test_reference_row_has_no_error_and_ratio_is_to_gl_at_one_sample(rows_and_programs):
    rows = rows_and_programs[0]
    ref = [r for r in rows if r.config.is_reference]
    assert len(ref) == 1
    assert (
        ref[0].max_abs_error == 0 and ref[0].mean_abs_error == 0 and ref[0].pixels_over_1_255 == 0
    )
    assert math.isinf(ref[0].psnr_db) and ref[0].to_json()["psnr_db"] is None
    gl1 = rows[0]
    assert gl1.config == Config("gl", "float32", 1) and gl1.ratio_to_gl == 1.0
    for r in rows:
        assert r.ratio_to_gl == pytest.approx(r.median_ms / gl1.median_ms)
    f16 = next(r for r in rows if r.config == Config("auto", "float16", 1))
    assert f16.max_abs_error == pytest.approx(0.14, abs=1e-6)
    assert f16.pixels_over_1_255 == W * H


def test_json_keys_exact(rows_and_programs):
    for r in rows_and_programs[0]:
        obj = r.to_json()
        assert tuple(obj) == JSON_KEYS
        assert obj["backend"] in ("gl", "auto")


def test_measure_error_clamps_to_the_display_and_counts_one_step():
    ref = np.zeros((2, 2, 4), dtype=np.float32)
    img = ref.copy()
    img[0, 0, 0] = 3.0  # displayed as 1.0
    img[0, 1, 1] = 1.5 / 255  # over one step
    img[1, 0, 2] = 0.5 / 255  # under one step
    img[1, 1, 3] = 0.9  # alpha: ignored
    max_err, mean_err, psnr, over = measure_error(img, ref)
    assert max_err == 1.0
    assert over == 2
    assert mean_err == pytest.approx((1.0 + 1.5 / 255 + 0.5 / 255) / 12, rel=1e-5)
    assert math.isfinite(psnr)
    assert measure_error(ref, ref)[2] == math.inf


def test_pareto_front_per_shader():
    def row(shader, ms, err):
        return Row(shader, Config("gl", "float32", 1), ms, 1.0, err, err, 30.0, 0)

    a = [row("a", 1, 0.1), row("a", 2, 0.2), row("a", 3, 0.01), row("a", 4, 0.0), row("a", 5, 0.0)]
    b = [row("b", 10, 0.5)]
    front = mark_pareto(a + b)
    assert [r.pareto for r in a] == [True, False, True, True, False]
    assert b[0].pareto and len(front) == 4


def test_table_and_plot(rows_and_programs, tmp_path):
    rows = rows_and_programs[0]
    text = format_table(rows, (W, H), 3, 0.0)
    assert "x GL@1" in text and "median of 3 runs" in text
    assert (
        sum(line.startswith(("  gl x", "  f16", "  f32", "  f64")) for line in text.splitlines())
        == 12
    )
    from PIL import Image

    path = tmp_path / "plot.png"
    write_plot(
        rows
        + [
            Row(
                "other",
                r.config,
                r.median_ms * 2,
                r.ratio_to_gl,
                r.max_abs_error,
                r.mean_abs_error,
                r.psnr_db,
                r.pixels_over_1_255,
                pareto=r.pareto,
            )
            for r in rows
        ],
        path,
    )
    with Image.open(path) as im:
        assert im.format == "PNG" and im.width > im.height > 200


def test_numpy_configurations_share_one_kind_of_worker(make_shader, monkeypatch):
    """ "auto" would move to worker processes part-way through a bench and mix processes and
    threads in one table: the bench pins one (processes where available) unless told."""
    from glslcheck.backends.numpy_engine import workers
    from glslcheck.backends.numpy_engine.program import compile_numpy
    from glslcheck.verification.bench import _pin_parallel

    monkeypatch.delenv("GLSLCHECK_PARALLEL", raising=False)
    prog = compile_numpy(
        make_shader("void mainImage(out vec4 o, in vec2 f) { o = vec4(f, 0.0, 1.0); }")
    )
    assert prog.parallel == "auto"
    _pin_parallel(prog)
    assert prog.parallel == ("processes" if workers.available() else "threads")
    prog.parallel = "threads"  # chosen by the caller (or GLSLCHECK_PARALLEL): kept
    _pin_parallel(prog)
    assert prog.parallel == "threads"
