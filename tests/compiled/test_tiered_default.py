"""The default CPU program (backends/tiered.py): NumPy frames first, the compiled engine's once
they pay, and only where the two give the same bits.

The move is forced by an expected compile cost of zero (the rule itself is the compiled
engine's ski rental, tested in test_lanes.py); every frame is compared with the NumPy backend's
own render of the same inputs, bit for bit. The tier records go to a temporary file, so no
verdict of a test reaches another test or the user's cache.
"""

from __future__ import annotations

import json
import threading
from functools import partial

import numpy as np
import pytest
from image_bits import assert_same

import glslcheck
from glslcheck.backends import tiered
from glslcheck.backends.numpy_engine.program import NumpyProgram

SIZE = (40, 24)

ANIMATED = """
float wave(vec2 p) { return 0.5 + 0.5 * sin(p.x * 9.0 + iTime) * cos(p.y * 7.0 - iTime); }
void mainImage(out vec4 c, in vec2 f) {
    vec2 uv = f / iResolution.xy;
    float acc = 0.0;
    for (int i = 0; i < 3; i++) {
        if (uv.x > 0.2 * float(i)) acc += wave(uv + float(i));
    }
    c = vec4(acc, uv, 1.0);
}
"""

# a construct the compiled engine refuses (its error names the line)
REFUSED = """
void mainImage(out vec4 c, in vec2 f) {
    float v = 0.1 * iTime;
    c = vec4(v, float(packHalf2x16(f)) * 1e-9, 0.0, 1.0);
}
"""


@pytest.fixture
def eager(monkeypatch, tmp_path):
    """Move as soon as one frame has rendered, and stay moved (no timing trial); records in a
    temporary file."""
    monkeypatch.setattr(tiered, "COMPILE_GUESS_SECONDS", 0.0)
    monkeypatch.setattr(tiered, "CACHED_LOAD_SECONDS", 0.0)
    monkeypatch.setattr(tiered, "TRIAL_FRAMES", 0)
    monkeypatch.setattr(
        tiered.TieredCpuProgram, "_record_path", lambda self: str(tmp_path / f"{self.tab}.tier")
    )
    monkeypatch.delenv("GLSLCHECK_TIERS", raising=False)


@pytest.fixture
def clock(monkeypatch):
    """Frame timings set by the test, through the program's clock (TieredCpuProgram._timed):
    every frame is rendered, and its seconds are the next of `clock[engine]` ("numpy" or
    "compiled"; the last one repeats)."""
    seconds = {"numpy": [0.1], "compiled": [0.1]}

    def timed(self, render, **kw):
        times = seconds["numpy" if getattr(render, "__self__", None) is self.first else "compiled"]
        return render(**kw), times.pop(0) if len(times) > 1 else times[0]

    monkeypatch.setattr(tiered.TieredCpuProgram, "_timed", timed)
    return seconds


# the default program's frames are the NumPy backend's bits (a NaN any NaN: payloads may differ)
_same_as_numpy = partial(assert_same, names=("auto", "numpy"), mode="bits_any_nan")


def _frames(prog, times):
    return [prog.render(size=SIZE, time=t) for t in times]


def test_the_default_backend_is_the_tiered_program(make_shader, monkeypatch):
    monkeypatch.delenv("GLSLCHECK_TIERS", raising=False)
    prog = glslcheck.compile(make_shader(ANIMATED))
    assert prog.backend.name == "auto" and isinstance(prog.impl, tiered.TieredCpuProgram)
    assert prog.impl.mode == "numpy"
    prog.impl.parallel = "threads"  # the NumPy program's settings are set through it
    assert prog.impl.first.parallel == "threads"
    monkeypatch.setenv("GLSLCHECK_TIERS", "off")
    assert isinstance(glslcheck.compile(make_shader(ANIMATED)).impl, NumpyProgram)


def test_frames_move_to_the_compiled_engine_with_the_same_bits(numba, make_shader, eager):
    shader = make_shader(ANIMATED)
    prog = glslcheck.compile(shader)
    reference = glslcheck.compile(shader, backend="numpy")
    times = [0.5 + 0.1 * k for k in range(6)]
    got = _frames(prog, times[:1])
    assert prog.impl.settle(300)
    assert prog.impl.mode.startswith("compiled"), prog.impl.stay
    assert prog.impl.record()["verdict"] == "same"
    got += _frames(prog, times[1:])
    for t, image, want in zip(times, got, _frames(reference, times)):
        _same_as_numpy(image, want, what=f"iTime {t}")


def test_a_shader_the_compiled_engine_refuses_stays_on_numpy(numba, make_shader, eager):
    shader = make_shader(REFUSED)
    prog = glslcheck.compile(shader)
    _frames(prog, [0.5])
    assert prog.impl.settle(300)
    assert prog.impl.mode == "numpy" and prog.impl.stay.startswith("refused: ")
    assert "packHalf2x16" in prog.impl.stay
    # the verdict is kept: a later program of the shader does not try again
    again = glslcheck.compile(shader)
    _frames(again, [0.5, 0.6])
    assert again.impl.stay == prog.impl.stay and again.impl._mover is None
    want = glslcheck.compile(shader, backend="numpy").render(size=SIZE, time=0.6)
    _same_as_numpy(again.render(size=SIZE, time=0.6), want, what="iTime 0.6")


def test_a_compiled_frame_that_differs_keeps_numpy(numba, make_shader, eager, monkeypatch):
    from glslcheck.backends.compiled_engine import engine

    real = engine.CompiledProgram.render

    def off_by_one_bit(self, **kw):
        image = real(self, **kw)
        image.view(np.uint32)[0, 0, 0] ^= 1
        return image

    monkeypatch.setattr(engine.CompiledProgram, "render", off_by_one_bit)
    monkeypatch.setenv("GLSLCHECK_COMPILED_LANES", "0")  # one program: CompiledProgram.render
    shader = make_shader(ANIMATED)
    prog = glslcheck.compile(shader)
    _frames(prog, [0.5])
    assert prog.impl.settle(300)
    assert prog.impl.mode == "numpy" and prog.impl.stay.startswith("differs: 1 pixels")
    want = glslcheck.compile(shader, backend="numpy").render(size=SIZE, time=0.7)
    _same_as_numpy(prog.render(size=SIZE, time=0.7), want, what="iTime 0.7")


def test_a_slower_compiled_engine_hands_the_frames_back(
    numba, make_shader, eager, clock, monkeypatch
):
    """A compiled program with no lockstep tier to try (a fixed mode) loses for good."""
    monkeypatch.setattr(tiered, "TRIAL_FRAMES", 2)
    monkeypatch.setenv("GLSLCHECK_COMPILED_LANES", "0")
    clock["compiled"] = [1.0]  # (NumPy's frames 0.1 s)
    shader = make_shader(ANIMATED)
    prog = glslcheck.compile(shader)
    _frames(prog, [0.5])
    assert prog.impl.settle(300) and prog.impl.mode.startswith("compiled"), prog.impl.stay
    times = [0.6, 0.7, 0.8]
    got = _frames(prog, times)
    assert prog.impl.mode == "numpy" and prog.impl.stay.startswith("slower: ")
    assert prog.impl.record()["verdict"] == "same"  # a timing is not kept: tried again later
    for t, image, want in zip(
        times, got, _frames(glslcheck.compile(shader, backend="numpy"), times)
    ):
        _same_as_numpy(image, want, what=f"iTime {t}")


@pytest.mark.parametrize("compiled, moves", [(0.2, False), (0.05, True)])
def test_the_trial_times_both_engines_on_its_own_frames(
    numba, make_shader, eager, clock, monkeypatch, compiled, moves
):
    """A process's first NumPy frame is slow (its start-up: worker processes, first calls) and
    the move comes right after it: the compiled program keeps the frames only if it is faster
    than the NumPy backend's renders of its trial frames, not than that first frame."""
    monkeypatch.setattr(tiered, "TRIAL_FRAMES", 3)
    monkeypatch.setenv("GLSLCHECK_COMPILED_LANES", "0")
    clock["numpy"] = [1.0, 0.1]
    clock["compiled"] = [compiled]
    shader = make_shader(ANIMATED)
    prog = glslcheck.compile(shader)
    _frames(prog, [0.5])  # the slow frame; the move starts beside it
    assert prog.impl.settle(300) and prog.impl.mode.startswith("compiled"), prog.impl.stay
    times = [0.6, 0.7, 0.8, 0.9]  # three trial frames, then one on the engine that won
    got = _frames(prog, times)
    if moves:
        assert prog.impl.mode.startswith("compiled") and prog.impl.stay is None
        assert prog.engine.startswith("compiled")
    else:
        assert prog.impl.mode == "numpy" and prog.impl.stay.startswith("slower: ")
        assert prog.engine == "numpy"
    assert prog.impl.numpy_rate == 0.1 / (SIZE[0] * SIZE[1])  # the trial frames', not the first
    want = _frames(glslcheck.compile(shader, backend="numpy"), times)
    for t, image, w in zip(times, got, want):
        _same_as_numpy(image, w, what=f"iTime {t}")


@pytest.mark.parametrize(
    "options", [{"precision": "float64"}, {"precision": "float16"}, {"stats": True}]
)
def test_frames_the_compiled_engine_cannot_render_never_move(make_shader, eager, options):
    prog = glslcheck.compile(make_shader(ANIMATED))
    for k in range(3):
        prog.render(size=SIZE, time=0.5 + k, **options)
    assert prog.impl._mover is None and prog.impl.pixels == 0


# a loop of more passes than the limit the test sets: llvmpipe's limiter stops it
LOOPY = """
void mainImage(out vec4 c, in vec2 f) {
    float acc = 0.0;
    for (int i = 0; i < 1500; i++) { acc += 0.001 * sin(float(i) + iTime); }
    c = vec4(acc, f / iResolution.xy, 1.0);
}
"""


def test_verify_s_loop_limiter_moves_with_the_frames(numba, make_shader, eager):
    """verify stops loops as llvmpipe does (a limit on the NumPy program): the compiled program
    gets the same limit, stops the loop where NumPy does and reports it."""
    shader = make_shader(LOOPY)
    prog = glslcheck.compile(shader)
    prog.impl.loop_limit = 1000  # (llvmpipe's is 65,535: a small one keeps the test quick)
    _frames(prog, [0.5])
    assert prog.impl.settle(300)
    assert prog.impl.mode.startswith("compiled"), prog.impl.stay
    prog.impl.limited_loops()  # (forget the NumPy frame's)
    times = [0.6, 0.7]
    got = _frames(prog, times)
    assert prog.engine.startswith("compiled")
    assert [line for _, line in prog.impl.limited_loops()] == [4]
    reference = glslcheck.compile(shader, backend="numpy")
    reference.impl.loop_limit = 1000
    for t, image, want in zip(times, got, _frames(reference, times)):
        _same_as_numpy(image, want, what=f"iTime {t}")


def test_a_driver_s_float_to_uint_model_stays_on_numpy(make_shader, eager):
    from glslcheck.backends.driver_profile import host_model

    prog = glslcheck.compile(make_shader(ANIMATED))
    prog.impl.emulate_float_to_uint("arm64" if host_model() != "arm64" else "sse")
    _frames(prog, [0.5, 0.6])
    assert prog.impl._mover is None and "float-to-uint" in prog.impl.stay
    assert prog.engine == "numpy"


def test_every_pass_is_a_tiered_program(make_shader, monkeypatch):
    from glslcheck.backends import registry

    monkeypatch.delenv("GLSLCHECK_TIERS", raising=False)
    shader = make_shader(ANIMATED, Buffer_A=ANIMATED)
    for tab in ("Buffer A", "Image"):
        prog = registry.get("auto").compile_pass(shader, tab)
        assert isinstance(prog, tiered.TieredCpuProgram) and prog.tab == tab
    monkeypatch.setenv("GLSLCHECK_TIERS", "off")
    assert isinstance(registry.get("auto").compile_pass(shader, "Buffer A"), NumpyProgram)


# Buffer A reads its own previous frame (feedback) and an image of a size not a power of two;
# the Image reads Buffer A and the image with mipmaps (implicit LODs: lockstep from the start)
FEEDBACK = """void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 uv = fragCoord / iResolution.xy;
    vec4 prev = texture(iChannel0, uv + 0.01 * vec2(sin(uv.y * 12.0 + iTime), cos(uv.x * 9.0)));
    float s = smoothstep(0.2, 0.0, length(uv - 0.5 - 0.2 * vec2(cos(iTime), sin(iTime))));
    fragColor = prev * 0.9 + texture(iChannel1, uv * 2.0) * 0.05 + vec4(s, 0.5 * s, 0.1, 1.0);
}
"""
TEXTURED = """void mainImage(out vec4 c, in vec2 fc) {
    vec2 uv = fc / iResolution.xy;
    vec4 b = texture(iChannel0, uv);
    c = vec4(b.rgb / (1.0 + b.rgb) + texture(iChannel1, uv * (1.0 + 5.0 * uv.x)).rgb * 0.2, 1.0);
}
"""


def _channel_folder(folder, image_filter: str = "mipmap") -> str:
    from PIL import Image

    rng = np.random.default_rng(3)
    Image.fromarray(rng.integers(0, 256, (9, 13, 4), dtype=np.uint8), "RGBA").save(
        folder / "tex.png"
    )
    (folder / "Buffer A.glsl").write_text(FEEDBACK)
    (folder / "Image.glsl").write_text(TEXTURED)
    texture = {"texture": "tex.png", "filter": image_filter, "wrap": "repeat"}
    channels = {
        "Buffer A": {"iChannel0": {"buffer": "Buffer A"}, "iChannel1": texture},
        "Image": {"iChannel0": {"buffer": "Buffer A"}, "iChannel1": texture},
    }
    (folder / "channels.json").write_text(json.dumps(channels))
    return str(folder)


@pytest.mark.parametrize("size", [(40, 24), (41, 23)])
def test_channel_passes_move_with_the_same_bits(numba, tmp_path, eager, size):
    """Each pass of a multipass shader with textures and feedback moves on its own; every frame,
    before and after the move, is the NumPy backend's bit for bit (the buffer carried)."""
    folder = _channel_folder(tmp_path)
    prog = glslcheck.compile(folder)
    reference = glslcheck.compile(folder, backend="numpy")
    passes = prog.impl.programs
    got = [prog.render(size=size, frame=0, time=0.0)]
    for p in passes.values():
        assert p.settle(300)
        assert p.mode.startswith("compiled"), (p.tab, p.stay)
        assert p.record()["verdict"] == "same"
    got += [prog.render(size=size, frame=k, time=k / 60) for k in range(1, 5)]
    assert prog.engine == "compiled lanes8"  # (implicit mipmap LODs: lockstep from the start)
    assert passes["Buffer A"].engine.startswith("compiled")
    for k, image in enumerate(got):
        want = reference.render(size=size, frame=k, time=k / 60)
        _same_as_numpy(image, want, what=f"iFrame {k}")


def test_a_pass_s_verdict_is_kept_per_pass_and_binding(numba, tmp_path):
    """The tier record of a pass is its own, and changes with its channel bindings (they choose
    what the compiled module samples): a verdict is never read for another."""
    a = glslcheck.compile(_channel_folder(_mkdir(tmp_path / "a")))
    b = glslcheck.compile(_channel_folder(_mkdir(tmp_path / "b"), image_filter="linear"))
    # the same two tab texts in both folders: only the tab and the bindings tell them apart
    paths = [p._record_path() for prog in (a, b) for p in prog.impl.programs.values()]
    assert None not in paths and len(set(paths)) == 4


def _mkdir(path):
    path.mkdir()
    return path


def test_a_lockstep_compile_over_the_budget_is_not_built(numba, make_shader, monkeypatch):
    from glslcheck.backends.compiled_engine import engine

    monkeypatch.delenv("GLSLCHECK_COMPILED_LANES", raising=False)
    prog = engine.compile_compiled(make_shader(ANIMATED))
    assert isinstance(prog, engine.TieredProgram)
    monkeypatch.setattr(prog, "move_cost", lambda: engine.LOCKSTEP_BUDGET + 1.0)
    prog.spent = 10 * engine.LOCKSTEP_BUDGET  # frames that would have paid for it many times
    prog.pixels = 1
    prog.render(size=SIZE, time=0.5)
    assert prog._mover is None and prog.mode == "pixel"


def test_a_slower_per_pixel_program_is_tried_again_in_lockstep(
    numba, make_shader, eager, clock, monkeypatch
):
    """Per pixel slower than NumPy: NumPy frames until they pay for lockstep, which is then made
    and tried; faster, it keeps the frames, with NumPy's bits."""
    from glslcheck.backends.compiled_engine import engine

    monkeypatch.setattr(tiered, "TRIAL_FRAMES", 1)
    monkeypatch.delenv("GLSLCHECK_COMPILED_LANES", raising=False)
    # lockstep never pays by itself, and no earlier run left it in numba's cache
    monkeypatch.setattr(engine.TieredProgram, "move_cost", lambda self: 1e9)
    monkeypatch.setattr(engine.TieredProgram, "load_cached", lambda self: False)
    shader = make_shader(ANIMATED)
    prog = glslcheck.compile(shader)
    _frames(prog, [0.5])
    assert prog.impl.settle(300) and prog.impl.mode == "compiled pixel", prog.impl.stay
    clock["compiled"] = [1.0]  # per pixel loses the trial (NumPy's frames 0.1 s)
    _frames(prog, [0.6])
    assert prog.impl.mode == "numpy" and prog.impl.later is not None and prog.impl.stay is None
    monkeypatch.setattr(engine.TieredProgram, "move_cost", lambda self: 0.0)  # lockstep paid
    _frames(prog, [0.7])
    assert prog.impl.later.settle(300) and prog.impl.later.mode == "lanes8"
    clock["compiled"] = [0.01]  # lockstep wins its trial
    times = [0.8, 0.9, 1.0]
    got = _frames(prog, times)
    assert prog.impl.mode == "compiled lanes8" and prog.impl.stay is None
    want = _frames(glslcheck.compile(shader, backend="numpy"), times)
    for t, image, w in zip(times, got, want):
        _same_as_numpy(image, w, what=f"iTime {t}")


def test_no_lockstep_move_starts_during_the_trial(numba, make_shader, eager, clock, monkeypatch):
    """The trial times the per-pixel program alone: its own move to lockstep, paid for already,
    starts only once the trial has kept it."""
    from glslcheck.backends.compiled_engine import engine

    monkeypatch.setattr(tiered, "TRIAL_FRAMES", 2)
    monkeypatch.delenv("GLSLCHECK_COMPILED_LANES", raising=False)
    monkeypatch.setattr(engine.TieredProgram, "move_cost", lambda self: 0.0)  # lockstep paid
    monkeypatch.setattr(engine.TieredProgram, "load_cached", lambda self: False)
    monkeypatch.setattr(tiered.TieredCpuProgram, "record", lambda self: {"pixel": "faster"})
    monkeypatch.setattr(engine, "module_cached", lambda key: True)
    clock["compiled"] = [0.01]  # per pixel wins its trial
    prog = glslcheck.compile(make_shader(ANIMATED))
    _frames(prog, [0.5])
    assert prog.impl.settle(300) and prog.impl.mode == "compiled pixel", prog.impl.stay
    tier = prog.impl.second
    _frames(prog, [0.6, 0.7])  # the trial's frames: nothing starts beside them
    assert tier._mover is None and prog.impl.second is tier and not tier.hold
    _frames(prog, [0.8])  # kept: this frame starts the move
    assert tier._mover is not None and tier.settle(300) and tier.mode == "lanes8"


def test_numpy_frames_pay_for_the_lockstep_move(numba, make_shader, eager, clock, monkeypatch):
    """The NumPy frames rendered before the per-pixel tier count towards lockstep's compile: a
    NumPy frame that cost more than lockstep starts the move right after the trial, where the
    per-pixel frames alone would take long to pay for it."""
    from glslcheck.backends.compiled_engine import engine

    monkeypatch.setattr(tiered, "TRIAL_FRAMES", 1)
    monkeypatch.delenv("GLSLCHECK_COMPILED_LANES", raising=False)
    monkeypatch.setattr(engine.TieredProgram, "move_cost", lambda self: 5.0)  # lockstep: 5 s
    monkeypatch.setattr(engine.TieredProgram, "load_cached", lambda self: False)
    monkeypatch.setattr(tiered.TieredCpuProgram, "record", lambda self: {"pixel": "faster"})
    monkeypatch.setattr(engine, "module_cached", lambda key: True)
    clock["numpy"] = [10.0]  # NumPy's frames: 10 s each, twice lockstep's compile
    clock["compiled"] = [0.001]  # per pixel wins its trial
    prog = glslcheck.compile(make_shader(ANIMATED))
    _frames(prog, [0.5])
    assert prog.impl.settle(300) and prog.impl.mode == "compiled pixel", prog.impl.stay
    tier = prog.impl.second
    _frames(prog, [0.6])  # the trial's frame
    assert tier.paid == pytest.approx(prog.impl.spent) and tier.paid >= 10.0
    _frames(prog, [0.7])  # the trial kept it: paid for, this frame starts the move
    assert tier._mover is not None and tier.settle(300) and tier.mode == "lanes8"


def test_a_lockstep_module_made_earlier_renders_every_compiled_frame(
    numba, make_shader, eager, monkeypatch, tmp_path
):
    """A later program of a shader whose lockstep module an earlier one made starts on it: no
    per-pixel frame pays for it again, and its frames are the NumPy backend's bits."""
    from glslcheck.backends.compiled_engine import engine

    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "numba"))
    monkeypatch.delenv("GLSLCHECK_COMPILED_LANES", raising=False)
    shader = make_shader(ANIMATED)
    earlier = glslcheck.compile(shader)
    _frames(earlier, [0.5])
    assert earlier.impl.settle(300) and earlier.impl.mode == "compiled pixel", earlier.impl.stay
    rule = engine.TieredProgram.move_cost
    monkeypatch.setattr(engine.TieredProgram, "move_cost", lambda self: 0.0)  # lockstep paid
    tier = earlier.impl.second
    assert tier.move_now() and tier.settle(300) and tier.mode == "lanes8"
    monkeypatch.setattr(engine.TieredProgram, "move_cost", rule)

    later = glslcheck.compile(shader)
    _frames(later, [0.5])  # NumPy's frame; the move starts beside it
    assert later.impl.settle(300) and later.impl.mode == "compiled lanes8", later.impl.stay
    times = [0.6, 0.7, 0.8]
    got = _frames(later, times)
    assert later.impl.second.pixels == 0  # no frame rendered per pixel
    want = _frames(glslcheck.compile(shader, backend="numpy"), times)
    for t, image, w in zip(times, got, want):
        _same_as_numpy(image, w, what=f"iTime {t}")


def test_frames_before_lockstep_are_kept_for_later_processes(make_shader, eager, monkeypatch):
    """The seconds of a pass's frames not yet in lockstep go to its record, added to what
    earlier processes kept there."""
    monkeypatch.setattr(tiered, "COMPILE_GUESS_SECONDS", 1e9)  # the frames stay on NumPy
    monkeypatch.setattr(tiered, "REMEMBER_SECONDS", 0.0)
    shader = make_shader(ANIMATED)
    first = glslcheck.compile(shader)
    _frames(first, [0.5, 0.6, 0.7])
    kept = first.impl.record()["spent"]
    assert kept == pytest.approx(first.impl.spent, abs=1e-3) and kept > 0
    later = glslcheck.compile(shader)
    _frames(later, [0.8, 0.9])
    assert later.impl.paid == kept
    assert later.impl.record()["spent"] == pytest.approx(kept + later.impl.spent, abs=1e-3)


def test_compiled_modules_are_loaded_in_the_frames_thread(
    numba, make_shader, eager, monkeypatch, tmp_path
):
    """The movers only compile (in child processes); each module's load from numba's cache is
    made by the thread that renders the frames, where it does not wait on their GIL: the
    per-pixel module at the move, then the lockstep module the per-pixel tier moves to."""
    from glslcheck.backends.compiled_engine import engine

    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "numba"))
    monkeypatch.delenv("GLSLCHECK_COMPILED_LANES", raising=False)
    threads = []
    load = engine.CompiledProgram.load

    def recorded(self, *args, **kw):
        if self.mod is None:
            threads.append(("lanes" if "\nLANES = " in self.source else "pixel", is_main()))
        return load(self, *args, **kw)

    def is_main():
        return threading.current_thread() is threading.main_thread()

    monkeypatch.setattr(engine.CompiledProgram, "load", recorded)
    prog = glslcheck.compile(make_shader(ANIMATED))
    _frames(prog, [0.5])
    assert prog.impl.settle(300) and prog.impl.mode == "compiled pixel", prog.impl.stay
    monkeypatch.setattr(engine.TieredProgram, "move_cost", lambda self: 0.0)  # lockstep paid
    _frames(prog, [0.6])  # starts lockstep's compile beside the per-pixel frame
    tier = prog.impl.second
    assert tier._mover is not None
    tier._mover.join(300)
    assert tier.mode == "pixel"  # made, not loaded yet: the next frame loads it
    _frames(prog, [0.7])
    assert prog.impl.mode == "compiled lanes8"
    assert threads == [("pixel", True), ("lanes", True)]


@pytest.mark.parametrize("paid", [0.0, 1e6])
def test_frames_earlier_processes_rendered_pay_for_lockstep(
    numba, make_shader, eager, monkeypatch, tmp_path, paid
):
    """Frames earlier processes kept in the record that have paid for the lockstep module make
    it at the move, in place of the per-pixel tier; a few quick frames alone do not (this
    process's NumPy frames count towards it too)."""
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "numba"))
    monkeypatch.delenv("GLSLCHECK_COMPILED_LANES", raising=False)
    (tmp_path / "Image.tier").write_text(json.dumps({"spent": paid}))
    shader = make_shader(ANIMATED)
    prog = glslcheck.compile(shader)
    _frames(prog, [0.5])
    assert prog.impl.settle(300), prog.impl.stay
    tier = prog.impl.second
    assert tier.paid == pytest.approx(paid + prog.impl.spent)  # this process's NumPy frame too
    times = [0.6, 0.7]
    got = _frames(prog, times)
    assert prog.impl.settle(300)
    if paid:  # lockstep from the move on: the per-pixel module never loaded
        assert prog.impl.mode == "compiled lanes8" and tier.first.mod is None and not tier.pixels
    else:
        assert prog.impl.mode == "compiled pixel"
    want = _frames(glslcheck.compile(shader, backend="numpy"), times)
    for t, image, w in zip(times, got, want):
        _same_as_numpy(image, w, what=f"iTime {t}")


def test_a_per_pixel_tier_that_won_renders_beside_lockstep_s_compile(
    numba, make_shader, eager, monkeypatch, tmp_path
):
    """Lockstep paid for, and a per-pixel module in the cache that won its last trial: its
    frames go on beside lockstep's compile instead of NumPy's."""
    from glslcheck.backends.compiled_engine import engine

    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "numba"))
    monkeypatch.delenv("GLSLCHECK_COMPILED_LANES", raising=False)
    monkeypatch.setattr(engine, "module_cached", lambda key: True)  # (as a later process finds)
    (tmp_path / "Image.tier").write_text(json.dumps({"spent": 1e6, "pixel": "faster"}))
    prog = glslcheck.compile(make_shader(ANIMATED))
    _frames(prog, [0.5])
    assert prog.impl.settle(300) and prog.impl.mode == "compiled pixel", prog.impl.stay
    _frames(prog, [0.6])  # paid: lockstep's compile starts beside this per-pixel frame
    assert prog.impl.settle(300) and prog.impl.mode == "compiled lanes8"
