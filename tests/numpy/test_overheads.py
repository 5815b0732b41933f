"""The NumPy backend's overhead cuts change no pixel: lazy gathering of globals and fragment
coordinates in compacted regions (nested too), uniform masks, early-out returns as selects,
constant expressions as module constants, tiles written straight into the image, the frame cache.

Each shader is rendered with compaction on and off (`Compaction(fraction=0,
loop_fraction=0, select_fraction=0)` never compacts), with loops compacted earlier than
branches, and with several tile sizes; the images must be bit-identical.
"""

from __future__ import annotations

import numpy as np
import pytest

from glslcheck.backends.numpy_engine import program as P
from glslcheck.backends.numpy_engine import tiles as F
from glslcheck.backends.numpy_engine.program import compile_numpy
from glslcheck.backends.numpy_engine.tiles import Compaction, LaneHelpers
from glslcheck.backends.numpy_engine.transpile import transpile_shader

# Globals read and written inside sparse (compacted) branches and loops, nested; gl_FragCoord
# read only inside the sparse branch; an early-out function; constant arrays and structs.
SHADER = """
struct Ball { vec3 c; float r; };
float g_acc = 0.0;
vec2 g_seen = vec2(-1.0);
int g_count = 0;

float hit(vec2 p, Ball b) {
    float d = length(p - b.c.xy);
    if (d > b.r) return -1.0;
    return b.r - d;
}

void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 p = fragCoord / iResolution.y;
    Ball balls[3] = Ball[3](Ball(vec3(0.3, 0.3, 0.0), 0.08), Ball(vec3(0.9, 0.5, 0.0), 0.05),
                            Ball(vec3(1.4, 0.7, 0.0), 0.12));
    float best = -1.0;
    int k = -1;
    for (int i = 0; i < 3; i++) {
        float h = hit(p, balls[i]);
        if (h > best) { best = h; k = i; }
    }
    vec3 col = vec3(0.1);
    if (k >= 0) {                           // about 5% of the pixels: compacted
        g_acc += best;
        if (gl_FragCoord.x > 0.5 * iResolution.x) {   // nested sparse branch
            g_seen = gl_FragCoord.xy;
            g_count += 2;
        }
        for (int j = 0; j < 4; j++) {
            if (float(j) * 0.03 > best) break;   // lanes leave at different times
            g_count++;
        }
        col = vec3(best * 10.0, float(g_count) * 0.1, g_seen.x / iResolution.x);
    }
    if (k == 2 && fragCoord.y < 0.7 * iResolution.y) discard;
    fragColor = vec4(col + g_acc, 1.0);
}
"""


def _render(prog, **kw):
    prog._cache.clear()
    return prog.render(size=(96, 54), **kw)


@pytest.fixture
def knobs(monkeypatch):
    """Set module settings for one test: tile sizes (frame.py), frame cache and pool
    (program.py)."""

    def set_(**values):
        for k, v in values.items():
            monkeypatch.setattr(F if hasattr(F, k) else P, k, v)

    return set_


def test_compaction_and_tiles_change_no_pixel(make_shader, knobs):
    prog = compile_numpy(make_shader(SHADER))
    reference = None
    for fraction, loop_fraction in ((0.0, 0.0), (0.5, 0.5), (0.5, 0.9), (0.9, 0.9)):
        for lanes in (64, 600, 10_000):
            prog.compaction = Compaction(
                fraction=fraction,
                min_lanes=16,
                loop_fraction=loop_fraction,
                select_fraction=loop_fraction,
            )
            knobs(TILE_LANES=lanes)
            img = _render(prog)
            if reference is None:
                reference = img
                assert (
                    np.isfinite(img).all() and (img[..., 3] == 0).any() and (img[..., 3] == 1).any()
                )
            else:
                assert np.array_equal(img, reference, equal_nan=True), (
                    fraction,
                    loop_fraction,
                    lanes,
                )


def test_compacted_rendering_matches_gl(gl, make_shader, knobs):
    from glslcheck.backends.gl import compile_gl

    shader = make_shader(SHADER)
    knobs(TILE_LANES=600)
    prog = compile_numpy(shader)
    prog.compaction = Compaction(min_lanes=16)
    ours = _render(prog)
    theirs = compile_gl(shader).render(size=(96, 54))
    assert np.allclose(ours, theirs, rtol=1e-5, atol=1e-5)


def test_frame_cache_is_a_separate_copy(make_shader):
    prog = compile_numpy(make_shader(SHADER))
    a = prog.render(size=(32, 18))
    keep = a.copy()
    a[:] = 7.0  # the caller owns the returned image
    b = prog.render(size=(32, 18))  # a cache hit
    assert np.array_equal(b, keep, equal_nan=True)
    b[:] = 3.0
    assert np.array_equal(prog.render(size=(32, 18)), keep, equal_nan=True)


def test_frame_cache_is_bounded_in_frames_and_bytes(make_shader, knobs):
    prog = compile_numpy(make_shader(SHADER))
    prog.parallel = "threads"
    for w in range(8, 8 + 2 * (P.CACHE_FRAMES + 3), 2):
        prog.render(size=(w, 8))
    assert len(prog._cache) == P.CACHE_FRAMES  # the oldest went first
    knobs(CACHE_BYTES=3 * 40 * 30 * 16)  # room for three 40x30 RGBA float32 frames
    for t in range(5):
        prog.render(size=(40, 30 + t))
    assert len(prog._cache) == 2  # 40x33 and 40x34 fit, a third would not
    prog.render(size=(400, 300))  # larger than the limit alone: still cached
    assert list(prog._cache.values())[0].shape == (300, 400, 4) and len(prog._cache) == 1


EARLY_OUT = """
float rise(float y) {
    float d = y - 4.0;
    if (d < 0.0) return -1.0;   // every lane of the two bottom tiles returns here
    return sqrt(d);
}
void mainImage(out vec4 o, in vec2 f) { o = vec4(rise(f.y), 0.0, 0.0, 1.0); }
"""


def test_early_out_skips_the_rest_where_no_lane_goes_on(make_shader, knobs, monkeypatch):
    prog = compile_numpy(make_shader(EARLY_OUT))
    prog.threads = 1
    knobs(TILE_LANES=32, TILE_WIDTH=16)  # 16x8 image: four tiles of two rows
    rt = prog.module()["rt"]
    sqrt_lanes = []
    real = rt.np_sqrt  # a float sqrt is NumPy's ufunc, called directly (transpile/expressions.py)
    monkeypatch.setattr(rt, "np_sqrt", lambda x: sqrt_lanes.append(np.size(x)) or real(x))
    img = prog.render(size=(16, 8))
    assert sqrt_lanes == [32, 32]  # only the tiles of rows 4-7 compute the rest
    y = np.arange(8, dtype=np.float32)[::-1] + np.float32(0.5)  # top row first
    want = np.where(y < 4.0, np.float32(-1.0), np.sqrt(np.maximum(y - np.float32(4.0), 0)))
    assert np.array_equal(img[..., 0], np.repeat(want[:, None], 16, axis=1))


UNIFORM_LOOPS = """
void mainImage(out vec4 o, in vec2 f) {
    float acc = 0.0;
    for (int i = 0; i < 3; i++) {              // the same trip count in every lane
        if (f.x > float(i) * 4.0) acc += 1.0;  // a varying body
    }
    int j = 0;
    for (int k = 0; k < 5; k++) {              // a uniform condition but a varying break
        if (f.y < float(k) * 2.0) break;
        j++;
    }
    o = vec4(acc, float(j), 0.0, 1.0);
}
"""


def test_uniform_loops_run_as_plain_python_loops(make_shader):
    shader = make_shader(UNIFORM_LOOPS)
    code = transpile_shader(shader).source
    first, second = code.split("# line 8:")[0], code.split("# line 8:")[1]
    assert "if not X.true((v_i < " in first and "_live" not in first  # no mask of its own
    assert "_live" in second and "X.and_(_live" in second  # a lane may leave early
    prog = compile_numpy(shader)
    img = prog.render(size=(12, 10), stats=True)
    x = np.arange(12, dtype=np.float32) + np.float32(0.5)
    y = np.arange(10, dtype=np.float32)[::-1] + np.float32(0.5)  # top row first
    acc = sum((x > np.float32(4 * i)).astype(np.float32) for i in range(3))
    j = np.minimum(np.floor(y / 2) + 1, 5)  # first k with y < 2k
    assert np.array_equal(img[..., 0], np.broadcast_to(acc, (10, 12)))
    assert np.array_equal(img[..., 1], np.broadcast_to(j[:, None], (10, 12)))
    loops = {s.line: s.lanes for s in prog.last_stats if s.kind == "loop"}
    assert loops[4] == 3 * 120  # three iterations of every lane
    assert loops[8] == int(np.where(j < 5, j + 1, 5).sum()) * 12  # up to the one that breaks


UNEVEN = """
void mainImage(out vec4 o, in vec2 f) {
    float acc = 0.0;
    for (int i = 0; i < 400; i++) {     // rows above y = 24 loop 400 times, the others never
        if (f.y < 24.0) break;
        acc = sin(acc + f.x * 0.01);
    }
    o = vec4(acc, f.y, 0.0, 1.0);
}
"""


def test_the_slowest_tiles_of_a_frame_go_first_in_the_next(make_shader, knobs):
    prog = compile_numpy(make_shader(UNEVEN))
    prog.threads = 1
    knobs(TILE_LANES=16 * 8, TILE_WIDTH=16)  # 16x32: four tiles of eight rows
    first = _render_sized(prog, (16, 32))
    tiles = F.frame_tiles(16, 32)
    order = prog._tile_order[tuple(tiles)]
    assert [tiles[i][1] for i in order[:1]] == [24] and tiles[order[-1]][1] < 24
    again = _render_sized(prog, (16, 32))  # rendered in that order: the same image
    assert np.array_equal(first, again, equal_nan=True)


def _render_sized(prog, size):
    prog._cache.clear()
    return prog.render(size=size)


def test_tiles_of_one_colour_are_written_whole(make_shader, knobs, monkeypatch):
    prog = compile_numpy(
        make_shader(
            "void mainImage(out vec4 o, in vec2 f) {\n"
            "    vec4 c = vec4(0.25, 0.5, 0.75, 0.3);\n"
            "    if (f.x < 10.0) c = vec4(f, 0.5, 0.0);   // no lane of the tiles right of x = "
            "16 runs it\n"
            "    o = c;\n"
            "}"
        )
    )
    prog.threads = 1  # in this process (a pool left up by an earlier test would take "auto" frames)
    tiles = []
    real = np.tile  # the one-colour path repeats one pixel
    monkeypatch.setattr(F.np, "tile", lambda a, n: (len(a) == 4 and tiles.append(n)) or real(a, n))
    knobs(TILE_LANES=8 * 6, TILE_WIDTH=8)  # 8x6 tiles, three rows of them
    img = _render_sized(prog, (30, 14))
    assert sorted(tiles) == [6, 6, 6, 8, 8, 8]  # x0 = 16 and 24 (6 wide), in 3 rows of tiles
    assert np.array_equal(
        img[:, 10:], np.broadcast_to(np.float32([0.25, 0.5, 0.75, 1.0]), (14, 20, 4))
    )
    x = np.arange(10, dtype=np.float32) + np.float32(0.5)
    y = np.arange(14, dtype=np.float32)[::-1] + np.float32(0.5)
    assert np.array_equal(img[:, :10, 0], np.broadcast_to(x, (14, 10)))
    assert np.array_equal(img[:, :10, 1], np.broadcast_to(y[:, None], (14, 10)))
    assert np.all(img[:, :10, 2:] == np.float32([0.5, 1.0]))  # alpha is 1, as Shadertoy makes it


SHORT_CIRCUIT = """
void mainImage(out vec4 o, in vec2 f) {
    bool both = f.y > 4.0 && sqrt(f.x) > 2.0;     // the right side where the left holds
    bool either = f.y < 4.0 || sqrt(f.x) > 2.0;   // ... where the left does not
    o = vec4(both ? 1.0 : 0.0, either ? 1.0 : 0.0, 0.0, 1.0);
}
"""


def test_a_pure_right_operand_of_and_or_is_skipped_where_no_lane_needs_it(
    make_shader, knobs, monkeypatch
):
    prog = compile_numpy(make_shader(SHORT_CIRCUIT))
    prog.threads = 1
    knobs(TILE_LANES=32, TILE_WIDTH=16)  # 16x8: four tiles of two rows
    rt = prog.module()["rt"]
    sqrt_lanes = []
    real = rt.np_sqrt  # a float sqrt is NumPy's ufunc, called directly (transpile/expressions.py)
    monkeypatch.setattr(rt, "np_sqrt", lambda x: sqrt_lanes.append(np.size(x)) or real(x))
    img = prog.render(size=(16, 8))
    # rows 0-3 (y < 4): `&&` is decided by its left side there, and `||` above
    assert sqrt_lanes == [32, 32, 32, 32]  # 2 tiles x `||`, 2 tiles x `&&`
    x = np.arange(16, dtype=np.float32) + np.float32(0.5)
    y = np.arange(8, dtype=np.float32)[::-1, None] + np.float32(0.5)
    big = np.sqrt(x) > 2.0
    assert np.array_equal(img[..., 0], ((y > 4.0) & big).astype(np.float32))
    assert np.array_equal(img[..., 1], ((y < 4.0) | big).astype(np.float32))


def test_image_rows_run_top_to_bottom(make_shader, knobs):
    prog = compile_numpy(
        make_shader(
            "void mainImage(out vec4 o, in vec2 f) { o = vec4(f, "
            "gl_FragCoord.x + gl_FragCoord.y, 1.0); }"
        )
    )
    knobs(TILE_LANES=40)
    img = _render(prog)
    h, w = img.shape[:2]
    assert np.array_equal(img[:, 0, 1], np.arange(h, dtype=np.float32)[::-1] + 0.5)
    assert np.array_equal(img[0, :, 0], np.arange(w, dtype=np.float32) + 0.5)
    assert np.array_equal(img[..., 2], img[..., 0] + img[..., 1])  # gl_FragCoord.xy = fragCoord


def test_uniform_masks_combine_without_lane_arrays():
    X = LaneHelpers({})
    T, F = np.ones(1, bool), np.zeros(1, bool)
    m = np.array([True, False, True])
    assert X.and_(T, m) is m and X.and_(m, T) is m and X.and_(F, m) is F and X.and_(m, F) is F
    assert X.or_(F, m) is m and X.or_(m, F) is m and X.or_(T, m) is T
    assert X.andnot(m, T) is X.NO and X.andnot(m, F) is m and X.andnot(None, F) is None
    assert np.array_equal(X.andnot(T, m), ~m) and X.andnot(F, m) is F
    assert np.array_equal(X.and_(m, ~m), np.zeros(3, bool))


def test_generated_code_shapes(make_shader):
    code = transpile_shader(make_shader(SHADER)).source
    # the early-out function returns a select, without return masks
    hit = code[code.index("def f_hit(") : code.index("def f_mainImage(")]
    assert "rt.select(" in hit and "_ret" not in hit and "_rv" not in hit
    assert "if X.every(" in hit  # ... and skips the rest where every lane returns early
    # the constant array of structs is built once, at module level
    assert "v_balls = C_x" in code
    # float arithmetic prints as operators
    assert "(v_fragCoord / " in code
