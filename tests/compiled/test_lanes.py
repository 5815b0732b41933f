"""Pixels in lockstep (backends/compiled_engine/lanes.py) against the per-pixel compiled engine, bit
for bit.

The per-pixel module is the reference: every lane of the lockstep module must compute exactly
its operations, so the two images are compared bit for bit (a NaN must be the same NaN: both
engines run the same operations on it). The construct shaders of test_compiled_render.py
(divergent loops with break/continue/return, `&&`/`||` with side effects on globals, ternaries,
out/inout parameters, arrays, run-time indices, int/uint, hard math inputs) and a lab sample,
at 40x24: 40 pixels a row is not a multiple of 16, so the last block of a row is partial.
Each program must be a lockstep module (no fallback), else the test would compare the
per-pixel engine with itself.
"""

from __future__ import annotations

import os
import re

import numpy as np
import pytest
from image_bits import assert_same, frame_text
from test_compiled_render import CONSTRUCTS, LAB, SIZE

MOUSE = (10.0, 7.0, 3.0, -2.0)


def _render(shader, lanes: int, time: float = 1.3) -> np.ndarray:
    from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate

    source, path = generate(shader, lanes=lanes)
    if lanes:
        assert f"LANES = {lanes}" in source and "LANES_FALLBACK" not in source, source[-300:]
    return CompiledProgram(source, path).render(size=SIZE, time=time, mouse=MOUSE)


def _same_bits(shader, lanes: int) -> None:
    """`lanes` pixels in lockstep render `shader` (iTime 1.3) to the per-pixel module's bits."""
    what = f"{getattr(shader, 'root', shader)} at {frame_text(SIZE, time=1.3, mouse=MOUSE)}"
    assert_same(
        _render(shader, lanes), _render(shader, 0), what=what, names=(f"lanes {lanes}", "per pixel")
    )


@pytest.mark.parametrize("lanes", [8, 16])
@pytest.mark.parametrize("name", sorted(CONSTRUCTS))
def test_construct_lanes_bit_for_bit(numba, make_shader, name, lanes):
    _same_bits(make_shader(CONSTRUCTS[name]), lanes)


@pytest.mark.parametrize("name", ["01_spheres_procedural", "05_blinn_phong", "bonus_spot_lights"])
def test_lab_lanes_bit_for_bit(numba, name):
    from glslcheck.shadertoy.sources import load_shader

    _same_bits(load_shader(os.path.join(LAB, name)), 8)


UNIFORM_CALLS = """
float wave(float t) { return sin(t * 1.7) * 0.5 + 0.5; }
float early(float t) { if (t > 1.0) return cos(t); return t * t; }
float diverge(float t, float x) { if (x > t) return x - t; return t; }
void split(float t, out float a, out float b) { a = fract(t); b = t - a; }
float row(float y) { if (y > 11.5) return 0.25; return 0.75; }
// ro one scalar (iTime's), then written with lane values: its lanes start from the scalar
float walk(vec3 ro, vec3 rd) { ro = ro + rd * 2.0; if (rd.x > 0.4) ro.y += 1.0; return ro.x + \
    ro.y; }
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 uv = fragCoord / iResolution.xy;
    float a, b;
    split(iTime * 3.1, a, b);
    float w = wave(iTime) + wave(uv.x) + early(iTime) + early(uv.x * 2.0);
    float d = diverge(iTime * 0.1, uv.x) + row(fragCoord.y) + row(fragCoord.x * 0.5)
              + walk(vec3(iTime), vec3(uv, 1.0)) * 0.1;
    fragColor = vec4(w * 0.25, d * 0.5 + a, b * 0.01, 1.0);
}
"""


def test_uniform_arguments_stay_scalars(numba, make_shader):
    """A call whose arguments are free of lanes (iTime, a row's fragCoord.y) runs the callee's
    variant that takes them as one scalar for the block (`f_wave__s0`), and a result that is the
    same for every lane (a return in uniform control of such a value) comes back as one scalar:
    sin(iTime * 1.7) once a block. The same function called with a per-pixel value keeps its
    per-lane variant; a return under a divergent condition (`diverge`) stays per lane. The bits
    are the per-pixel engine's."""
    from glslcheck.backends.compiled_engine.engine import generate

    shader = make_shader(UNIFORM_CALLS)
    source, _ = generate(shader, lanes=8)
    # per-pixel names may carry codegen's own suffix (`f_diverge__u0`), the lockstep ones `__s<i>`
    defs = {
        line[4:].split("(")[0]: line for line in source.splitlines() if line.startswith("def f_")
    }

    def body(fn: str, scalar: bool) -> str:
        names = [d for d in defs if d.split("__")[0] == fn and d.endswith("__s0") == scalar]
        assert len(names) == 1, (fn, scalar, sorted(defs))
        text = source[source.index(f"def {names[0]}(") :]
        return text[: text.index("\n\n")]

    for fn in ("f_wave", "f_early", "f_row"):
        body(fn, False)  # the per-lane variant, for the per-pixel argument
    wave = body("f_wave", True)
    assert "m__7, v_t_0)" in wave  # t: one scalar
    assert "sin(" in wave and "__1" not in wave.split("\n", 1)[1]  # one sin, no lane copies
    assert wave.rstrip().endswith(",)") and "__" not in wave.splitlines()[-1]  # one result
    assert "_r0__7" in body("f_diverge", True)  # a return under a divergent condition: per lane
    _same_bits(shader, 8)


def test_unhandled_statement_is_unsupported():
    """A statement the rewrite does not know (the per-pixel generator writes no `for`) is
    Unsupported, not rewritten wrongly."""
    from glslcheck.backends.compiled_engine.lanes import Unsupported, lanes_module

    source = (
        "@jit\ndef f_g(v_x_0):\n    for i in range(3):\n        pass\n    return (v_x_0,)\n\n"
        "@jit\ndef shade(fx, fy, px, py):\n    _t1, = f_g(fx)\n    return (_t1, _t1, _t1, "
        "F32(1.0))\n"
    )
    with pytest.raises(Unsupported, match="For"):
        lanes_module(source, 8)


def test_fallback_and_mode_switch(make_shader, monkeypatch):
    """GLSLCHECK_COMPILED_LANES=0 gives the per-pixel module, a width the lockstep one, nothing
    the engine's choice; a shader the rewrite refuses falls back to the per-pixel module, which says
    why; a bad value is an input error (exit 2)."""
    from glslcheck.backends.compiled_engine import lanes
    from glslcheck.backends.compiled_engine.engine import generate
    from glslcheck.base.diagnostics import InputError

    shader = make_shader(CONSTRUCTS["control_flow"])
    monkeypatch.setenv("GLSLCHECK_COMPILED_LANES", "0")
    pixel, _ = generate(shader)
    assert "LANES =" not in pixel and "LANES_FALLBACK" not in pixel
    monkeypatch.setenv("GLSLCHECK_COMPILED_LANES", "16")
    assert "LANES = 16" in generate(shader)[0]
    monkeypatch.delenv("GLSLCHECK_COMPILED_LANES")
    # unset, a module is per pixel: TieredProgram's first tier (test_tiered_program_moves)
    assert generate(shader)[0] == pixel
    monkeypatch.setenv("GLSLCHECK_COMPILED_LANES", "auto")
    assert generate(shader)[0] == pixel

    def refuse(self):
        raise lanes.Unsupported("a construct")

    monkeypatch.setattr(lanes.Lanes, "module", refuse)
    source, _ = generate(shader, lanes=8)
    assert source.startswith(pixel) and "LANES_FALLBACK = 'a construct'" in source
    monkeypatch.setenv("GLSLCHECK_COMPILED_LANES", "eight")
    with pytest.raises(InputError, match="GLSLCHECK_COMPILED_LANES"):
        generate(shader)


def test_tiered_program_moves(numba, make_shader, monkeypatch, tmp_path):
    """The default program (GLSLCHECK_COMPILED_LANES unset): per pixel while the frames have cost
    less than lockstep's expected compile, lockstep from the frame that reaches it, the same bits
    throughout; a later program of the same shader finds the lockstep module in numba's cache
    (the marker) and expects only its load."""
    from glslcheck.backends.compiled_engine import engine

    monkeypatch.delenv("GLSLCHECK_COMPILED_LANES", raising=False)
    monkeypatch.setenv(
        "NUMBA_CACHE_DIR", str(tmp_path)
    )  # no lockstep module cached by an earlier run
    shader = make_shader(CONSTRUCTS["control_flow"])
    want = _render(shader, 0, time=2.0)
    frame = f"control_flow at {frame_text(SIZE, time=2.0, mouse=MOUSE)}"
    prog = engine.compile_compiled(shader)
    assert isinstance(prog, engine.TieredProgram) and prog.mode == "pixel"
    monkeypatch.setattr(engine, "LOCKSTEP_COMPILE_RATIO", 1e9)  # never pays: stays per pixel
    monkeypatch.setattr(engine, "LOCKSTEP_SECONDS_PER_LINE", 1e9)
    for _ in range(3):
        got = prog.render(size=SIZE, time=2.0, mouse=MOUSE)
        assert_same(got, want, what=frame, names=(prog.mode, "per pixel"))
    assert prog.mode == "pixel" and prog.pixels == 3 * SIZE[0] * SIZE[1]
    monkeypatch.setattr(
        engine, "LOCKSTEP_COMPILE_RATIO", 0.0
    )  # pays at once: the next frame starts the move
    monkeypatch.setattr(engine, "LOCKSTEP_SECONDS_PER_LINE", 0.0)
    # the lockstep compile runs in its own thread; frames meanwhile are per pixel, the same bits
    got = prog.render(size=SIZE, time=2.0, mouse=MOUSE)
    assert_same(got, want, what=frame, names=(prog.mode, "per pixel"))
    assert (
        prog._mover is not None
        and prog.settle(600)
        and prog.mode == "lanes8"
        and "LANES = 8" in prog.source
    )
    got = prog.render(size=SIZE, time=2.0, mouse=MOUSE)
    assert_same(got, want, what=frame, names=(prog.mode, "per pixel"))
    again = engine.compile_compiled(shader)
    again.first.load()
    assert again._cached_fast() == prog.fast.source
    assert again.move_cost() == (
        again.first.load_seconds or 0.0
    )  # None: loaded already in this process


@pytest.mark.parametrize("lockstep", [0.5, 2.0])
def test_a_lockstep_module_is_tried_against_per_pixel(
    numba, make_shader, monkeypatch, tmp_path, lockstep
):
    """Lockstep's first frames are timed against the per-pixel frames before the move: slower,
    it hands the frames back to per pixel for good, and a later program starts per pixel (the
    marker's hint); faster, it keeps them. The bits are per pixel's either way."""
    from glslcheck.backends.compiled_engine import engine

    monkeypatch.delenv("GLSLCHECK_COMPILED_LANES", raising=False)
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(engine, "LOCKSTEP_TRIAL_FRAMES", 2)
    seconds = {"pixel": 1.0, "lanes8": lockstep}  # a frame's seconds, by the module's mode

    def timed(self, render, **kw):
        mode = "pixel" if getattr(render, "__self__", None) is self.first else "lanes8"
        return render(**kw), seconds[mode]

    monkeypatch.setattr(engine.TieredProgram, "_timed", timed)
    shader = make_shader(CONSTRUCTS["control_flow"])
    want = _render(shader, 0, time=2.0)
    prog = engine.compile_compiled(shader)
    prog.render(size=SIZE, time=2.0, mouse=MOUSE)
    assert prog.move_now() and prog.settle(600) and prog.mode == "lanes8"
    modes = []
    for _ in range(4):
        got = prog.render(size=SIZE, time=2.0, mouse=MOUSE)
        assert_same(got, want, what="control_flow", names=(prog.mode, "per pixel"))
        modes.append(prog.mode)
    slower = lockstep >= 1.0
    assert modes == (["lanes8", "pixel", "pixel", "pixel"] if slower else ["lanes8"] * 4)
    assert prog.stay == slower and prog.trial == [lockstep / (SIZE[0] * SIZE[1])] * 2
    again = engine.compile_compiled(shader)
    assert again.load_cached() != slower  # slower: per pixel first, lockstep tried again later
    assert again._cached_fast() is not None


def test_fixed_mode_is_not_tiered(numba, make_shader, monkeypatch):
    """GLSLCHECK_COMPILED_LANES=0 or a width: that module only, no tiers."""
    from glslcheck.backends.compiled_engine import engine

    shader = make_shader(CONSTRUCTS["control_flow"])
    for value in ("0", "8"):
        monkeypatch.setenv("GLSLCHECK_COMPILED_LANES", value)
        assert isinstance(engine.compile_compiled(shader), engine.CompiledProgram)


def test_pure_conditional_expressions_are_selects():
    """codegen's `0 if x == 0 else y * x` (x a value the NumPy backend takes for a constant: a
    light's colour in 07_final's light loop) is a select in each lane, not two basic blocks (they
    stop the SLP vectorizer); a uniform one stays one conditional for the block. (The bits:
    test_lab_lanes_bit_for_bit.)"""
    import re

    from glslcheck.backends.compiled_engine.engine import generate
    from glslcheck.shadertoy.sources import load_shader

    source, _ = generate(load_shader(os.path.join(LAB, "07_final")), lanes=8)
    source = re.sub(r"\b_g_", "", source)  # (globals read from locals: lanes_slim)
    lane_ifexp = [
        line
        for line in source.splitlines()
        if re.search(r"__\d+ = .* if .* else ", line) and not line.lstrip().startswith("#")
    ]
    assert not lane_ifexp, lane_ifexp[:3]
    assert re.search(r"lsel\(v_light_\d+ == F_0p0, F_0p0, ", source)


AFTER_RETURN = """
struct Light { vec3 pos; float power; };
float shadeIt(vec2 uv) {
    if (uv.x < 0.3) return 0.1;               // a divergent early return
    Light L[2];                               // built after it: the returned lanes never read it
    L[0] = Light(vec3(1.0, 2.0, 3.0), 0.5);
    L[1] = Light(vec3(cos(iTime), 0.0, 1.0), 0.25);
    float acc = 0.0;
    for (int k = 0; k < 2; k++) acc += L[k].power * dot(L[k].pos, vec3(uv, 1.0));
    float w = 0.0;
    if (uv.x > 0.6) { w = 1.0; }              // a divergent branch: w's write stays masked
    int n = 0;
    for (;;) { n++; if (n > 3) return acc + w + float(n); }   // a loop that returns, after returns
}
void mainImage(out vec4 c, in vec2 f) {
    vec2 uv = f / iResolution.xy;
    c = vec4(shadeIt(uv), uv, 1.0);
}
"""


def test_locals_after_a_return_stay_uniform(numba, make_shader):
    """After a divergent return the lanes left out have returned and never read the call's
    locals again: writes to locals need no mask there, and a local array of uniform values
    built element by element (the lights array of benchmarks/scenes/lights_array, the common
    Lab 4 pattern) stays one scalar per element for the block; a branch's write keeps its
    mask, and a loop that can return stays a masked loop; a block whose every lane has returned
    stops at the return. The bits are the per-pixel engine's."""
    from glslcheck.backends.compiled_engine.engine import generate

    shader = make_shader(AFTER_RETURN)
    source, _ = generate(shader, lanes=8)
    fn = source[source.index("def f_shadeIt") :]
    fn = re.sub(r"\b_g_", "", fn[: fn.index("\n\n")])  # (globals read from locals: lanes_slim)
    assert re.search(r"\bv_L_\d+ = ", fn) and not re.search(r"\bv_L_\d+__\d", fn), "L per lane"
    assert re.search(r"v_w_\d+__0 = lsel\(", fn), "w's write in the branch unmasked"
    # a block whose lanes have all returned stops there (the loops after it would run for nothing)
    # (`not a | b` is `not (a | b)`: ast.unparse drops the parentheses)
    assert re.search(r"if not \(?live__0 \| live__1 .*:\n +return \(_r0__0, ", fn), "no early exit"
    _same_bits(shader, 8)
    _same_bits(shader, 16)


FILLED_IN_A_BRANCH = """
struct Light { vec3 pos; float power; };
float shadeIt(vec2 uv) {
    Light L[2];                               // used only inside the branch below
    float acc = 0.1;
    if (uv.x > 0.3) {                         // a divergent branch
        L[0] = Light(vec3(1.0, 2.0, 3.0), 0.5);
        L[1] = Light(vec3(cos(iTime), 0.0, 1.0), 0.25);
        for (int k = 0; k < 2; k++) acc += L[k].power * dot(L[k].pos, vec3(uv, 1.0));
    }
    return acc;
}
void mainImage(out vec4 c, in vec2 f) {
    vec2 uv = f / iResolution.xy;
    c = vec4(shadeIt(uv), uv, 1.0);
}
"""


def test_a_local_used_only_inside_a_branch_has_the_numpy_backends_bits(numba, make_shader):
    """A local declared before a divergent branch and used only inside it is one value per tile
    in the NumPy backend (cpu_core/uniformity.py), which the compiled engine's constant-like
    values follow: per pixel and in lockstep, the NumPy backend's bits."""
    from test_compiled_render import _compare

    shader = make_shader(FILLED_IN_A_BRANCH)
    _compare(shader)
    _same_bits(shader, 8)


SELECT_CHAINS = """
float table(float x, float y, float frame) {
    float idx = 0.0;
    if (frame == 0.0) {
        idx = y == 3.0 ? (x <= 7.0 ? 1.0 : 2.0) : idx;
        idx = y == 2.0 ? (x <= 7.0 ? 3.0 : 4.0) : idx;
        idx = y == 1.0 ? 5.0 : idx;
        idx = y == 3.0 ? (x <= 7.0 ? 6.0 : 7.0) : idx;  // the last that holds wins
        idx = y == 0.0 ? (x <= 7.0 ? 8.0 : (x <= 11.0 ? 9.0 : 10.0)) : idx;  // another tree
        idx = y == 8.0 ? (x <= 7.0 ? 11.0 : (x <= 11.0 ? 12.0 : 13.0)) : idx;
    } else {
        idx = y == 4.0 ? (x <= 5.0 ? 0.0 : (x <= 11.0 ? 9.0 : 10.0)) : idx;
        idx = y == 5.0 ? (x <= 5.0 ? 11.0 : (x <= 11.0 ? 12.0 : 13.0)) : idx;
        float k = idx;  // a read between two chains
        idx = y == 6.0 ? 14.0 : idx;
        idx = y == 7.0 ? (frame > 1.5 ? 15.0 : 16.0) : idx;
        idx = y == 6.0 ? idx + 1.0 : idx;  // reads idx: not a table's step
        idx += k;
    }
    return idx;
}
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    float y = mod(floor(fragCoord.y), 9.0);  // one value a row
    float x = mod(floor(fragCoord.x), 16.0);
    float a = table(x, y, floor(mod(iTime, 3.0)));  // frame one value a block
    float b = table(x, y, step(8.0, x) * 2.0);  // frame per lane: the arms under masks
    float c = table(x, mod(floor(fragCoord.x + fragCoord.y), 9.0), 0.0);  // y per lane
    fragColor = vec4(a / 16.0, b / 16.0, c / 16.0, 1.0);
}
"""


def test_select_chains_over_uniform_conditions(numba, make_shader):
    """A sprite's table, `idx = y == 3.0 ? (x <= 7.0 ? 1.0 : 2.0) : idx;` a row, with y one
    value for the block: the run's constants are chosen once for the block (scalars `_u..L`)
    and idx written once per lane, in uniform control and under a mask; where y has lanes
    every row is written per lane. The bits are the per-pixel engine's, at times that take each
    arm."""
    from glslcheck.backends.compiled_engine.engine import generate

    shader = make_shader(SELECT_CHAINS)
    source, _ = generate(shader, lanes=8)
    assert re.search(r"= (_g_)?lsel\(_u\d+L, (_g_)?F_\d+p0, _u\d+L\)", source), source
    for time in (0.4, 1.3, 2.5):
        what = f"select chains at {frame_text(SIZE, time=time, mouse=MOUSE)}"
        assert_same(
            _render(shader, 8, time),
            _render(shader, 0, time),
            what=what,
            names=("lanes 8", "per pixel"),
        )


SHORT_CIRCUITS = """
void paint(inout vec3 c, float x, float y) {
    c = vec3(fract(x * 0.37), fract(y * 0.11), c.b);
}
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    float x = floor(fragCoord.x), y = floor(fragCoord.y);
    float t = floor(mod(iTime * 3.0, 5.0));
    vec3 col = vec3(0.1, 0.2, 0.3);
    paint(col, y, x);                                      // in uniform control
    bool band = x > 4.0 && x < 20.0 || y == t;             // pure sides
    // codegen's short circuit with a statement first: `if` arms that write pure values
    if (y <= 12.0 && !(x >= 7.0 && x < 9.0) && !(x >= 13.0 + t && x < 15.0)) {
        paint(col, x, y);                                  // under a mask
    }
    float k = 0.0;
    if (band) { k = x * 0.5; } else { k = y * 0.25; }
    fragColor = vec4(col, k / 16.0);
}
"""


def test_short_circuits_and_straight_arms_branch_once_a_block(numba, make_shader):
    """A pure `&&`/`||` with lanes is `&`/`|` of each lane's bools (a short circuit is a branch
    per lane); an arm of a divergent `if` that writes a few pure values runs in every lane under
    its mask, with no `if` of its lanes (codegen's `&&` chains, `band`'s two arms); a call's
    results are written into the names they go to, not copied there. The bits are the
    per-pixel engine's, at times that move the chains' bounds."""
    from glslcheck.backends.compiled_engine.engine import generate

    shader = make_shader(SHORT_CIRCUITS)
    source, _ = generate(shader, lanes=8)
    fn = source[source.index("def f_mainImage") :]
    fn = re.sub(r"\b_g_", "", fn[: fn.index("\n\n")])  # (globals read from locals: lanes_slim)
    lane_lines = [line for line in fn.splitlines() if re.match(r"\s+\w+__\d+ = ", line)]
    assert not [line for line in lane_lines if re.search(r"\b(and|or)\b", line)], lane_lines
    assert re.search(r"\bv_band_\d+__0 = \w+ \| \(", fn), fn
    # one `if` of a mask's lanes: the arm that calls paint
    assert len(re.findall(r"^\s+if \w+__0 \| ", fn, re.M)) == 1, fn
    assert re.search(r"^    v_col_\d+__0, v_col_\d+__1, .* = f_paint", fn, re.M), fn
    for lanes in (8, 16):
        for time in (0.4, 1.3, 2.5):
            what = f"short circuits at {frame_text(SIZE, time=time, mouse=MOUSE)}"
            assert_same(
                _render(shader, lanes, time),
                _render(shader, 0, time),
                what=what,
                names=(f"lanes {lanes}", "per pixel"),
            )


ARRAY_CALLS_SHADER = """
const int kCount = 50;
float spread(float x) {
    vec2 pts[kCount];
    for (int i = 0; i < kCount; i++) { pts[i] = vec2(x + float(i) * 0.01, x); }
    return pts[int(x * 7.0) % kCount].x;  // an index with lanes
}
float blur(float x) { return 0.5 * sin(spread(x)); }
float shape(vec2 p) { return length(p) - 0.3 * sin(iTime); }
float march(vec2 p) {
    float d = 0.0;
    for (int i = 0; i < 8; i++) { d += shape(p + float(i) * 0.01); }
    return d;
}
void mainImage(out vec4 c, in vec2 f) {
    vec2 p = f / iResolution.xy;
    c = vec4(blur(p.x), march(p), p.y, 1.0);
}
"""


def test_functions_that_make_no_array_count_no_references(numba, make_shader):
    """A lockstep function runs without numba's reference counts (module_text's jit_loop) when
    neither it nor a function it calls makes an array: `shape` and `march` (and shade); `spread`
    makes one (an array indexed with lanes), and `blur`, which calls it, and mainImage, which
    calls blur, keep them. The bits are the per-pixel engine's."""
    from glslcheck.backends.compiled_engine.engine import generate

    shader = make_shader(ARRAY_CALLS_SHADER)
    source, _ = generate(shader, lanes=8)
    found = re.findall(r"^@(\w+)\ndef (f_[a-zA-Z]+|shade)", source, re.M)
    decorated = {name: deco for deco, name in found}
    assert decorated["f_shape"] == decorated["f_march"] == decorated["shade"] == "jit_loop"
    assert decorated["f_spread"] == decorated["f_blur"] == decorated["f_mainImage"] == "jit"
    _same_bits(shader, 8)
