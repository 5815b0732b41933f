"""Values a select throws away are computed only on the lanes that keep them
(transpile/dead_lanes.py), with the same pixels as the program that computes them everywhere.

Each shader is rendered as generated and with the analysis turned off (the unmoved program);
the images must be bit-identical. Where statements move, the lane statistics show the moved
function running on exactly the lanes whose weight reads it, counted from a render of the
weight itself; where they must not move, the generated module is the unmoved one.
"""

from __future__ import annotations

import numpy as np
import pytest

from glslcheck.backends.numpy_engine.program import compile_numpy
from glslcheck.backends.numpy_engine.runtime import Runtime
from glslcheck.backends.numpy_engine.tiles import Compaction
from glslcheck.backends.numpy_engine.transpile import dead_lanes, transpile_shader

SIZE = (96, 54)  # 5,184 lanes: enough for a sparse region to be compacted

# A disc lit by a loop of lights over a gradient: `hit` is exactly 0 or 1, the background a
# mix of the two; WEIGHT and COLOR are replaced per case.
SCENE = """
float gCount;
vec3 shade(vec3 p, vec3 n) {
    vec3 c = vec3(0.0);
    for (int i = 0; i < 4; ++i) {
        vec3 l = normalize(vec3(float(i) - 1.5, 1.0, 0.5) - p);
        c += pow(max(dot(n, l), 0.0), 16.0) * vec3(0.3, 0.25, 0.2);
    }
    return c;
}
vec3 shadeCounting(vec3 n) { gCount = n.x; return n * 2.0; }
vec3 shadeOut(vec3 n, out float k) { k = n.x; return n * 0.5; }
void mainImage(out vec4 o, in vec2 f) {
    vec2 uv = (f + f - iResolution.xy) / iResolution.y;
    float d = 1.0 - dot(uv, uv) * 4.0;
    float hit = WEIGHT;
    vec3 n = vec3(uv, sqrt(max(d, 0.0)));
    vec3 bg = vec3(0.1, 0.2, 0.3) * (uv.y + 1.0);
    vec3 view = -normalize(vec3(uv, -2.0));
    BODY
}
"""
MOVED_BODY = """vec3 color = shade(n, view) + view * 0.1 COLOR;
    o = vec4(mix(bg, color, hit), 1.0);"""


def _shader(make_shader, weight="step(0.0, d)", color="", body=MOVED_BODY):
    return make_shader(
        SCENE.replace("BODY", body).replace("WEIGHT", weight).replace("COLOR", color)
    )


def _render(shader, precision="float32", compaction=None):
    prog = compile_numpy(shader)
    prog.threads = 1
    if compaction is not None:
        prog.compaction = compaction
    img = prog.render(size=SIZE, time=0.0, precision=precision, stats=True)
    lanes = {(s.kind, s.function): s.lanes for s in prog.last_stats}
    return img, lanes


def _unmoved(monkeypatch):
    monkeypatch.setattr(dead_lanes, "plan", lambda tr, stmts: dead_lanes.NO_PLAN)


def _same(a, b):
    return np.array_equal(np.asarray(a).view(np.uint32), np.asarray(b).view(np.uint32))


def _weight_lanes(make_shader, weight):
    """How many pixels have a weight other than 0 (those that read the lit colour), from a
    render of the weight itself."""
    body = "o = vec4(hit, 0.0, 0.0, 1.0);"
    img, _ = _render(_shader(make_shader, weight=weight, body=body))
    return int(np.count_nonzero(img[..., 0] != 0))


@pytest.mark.parametrize(
    ("weight", "color"),
    [
        ("step(0.0, d)", ""),  # 0 or 1: a select in every lane
        ("step(0.0, d)", "+ vec3(sqrt(d))"),  # NaN where the select throws it away
        ("step(0.0, d) * float(d < 0.5)", "+ vec3(sqrt(d))"),  # a product of b2f: a select
        ("max(step(0.0, d), float(d < -12.0))", ""),  # the corners too
    ],
)
def test_a_value_only_a_select_reads_runs_on_its_lanes_with_the_same_pixels(
    make_shader, monkeypatch, weight, color
):
    shader = _shader(make_shader, weight=weight, color=color)
    assert "rt.mix_reads(" in transpile_shader(shader).source
    img, lanes = _render(shader)
    masked, _ = _render(shader, compaction=Compaction(select_fraction=0.0))  # (never gathered)
    _unmoved(monkeypatch)
    before, lanes_before = _render(_shader(make_shader, weight=weight, color=color))
    assert _same(img, before) and _same(masked, before)
    assert lanes_before[("function", "shade")] == SIZE[0] * SIZE[1]
    assert lanes[("function", "shade")] == _weight_lanes(make_shader, weight)
    assert lanes[("function", "shade")] < SIZE[0] * SIZE[1] // 4  # (the disc: a sparse region)


@pytest.mark.parametrize("weight", ["clamp(d * 8.0, 0.0, 1.0)", "1.0 - step(d, 0.0)"])
def test_an_interpolating_weight_moves_nothing(make_shader, weight):
    """A weight NIR does not see as a bool converted to float interpolates in every lane, 0 and
    1 included (nir_fold.mix_form): both sides are read everywhere, nothing moves."""
    assert "rt.mix_reads(" not in transpile_shader(_shader(make_shader, weight=weight)).source


def test_a_value_only_a_conditional_reads_runs_on_its_lanes(make_shader, monkeypatch):
    """`c ? a : b` without side effects is a select in every lane (Mesa's bcsel, np.where): the
    value of its then side is computed where c holds."""
    body = "bool lit = hit > 0.5;\n" + MOVED_BODY.replace("mix(bg, color, hit)", "lit ? color : bg")
    shader = _shader(make_shader, color="+ vec3(sqrt(d))", body=body)
    assert "rt.mix_reads(" in transpile_shader(shader).source
    img, lanes = _render(shader)
    _unmoved(monkeypatch)
    before, _ = _render(_shader(make_shader, color="+ vec3(sqrt(d))", body=body))
    assert _same(img, before)
    assert lanes[("function", "shade")] == _weight_lanes(make_shader, "step(0.0, d)")


LOOP_BODY = """if (uv.y > 0.8) { o = vec4(1.0); return; }
    vec3 acc = vec3(0.0);
    for (int k = 0; k < 3; ++k) {
        if (k == 2 && uv.x > 0.5) break;
        float w = step(0.0, d - 0.1 * float(k));
        vec3 c = shade(n, view) * float(k + 1);
        acc += mix(bg, c, w);
    }
    o = vec4(acc, 1.0);"""


def test_a_select_in_a_loop_after_an_early_return(make_shader, monkeypatch):
    """The region sits in the loop's body, under the mask the return and the break leave."""
    shader = _shader(make_shader, body=LOOP_BODY)
    assert "rt.mix_reads(" in transpile_shader(shader).source
    img, lanes = _render(shader)
    _unmoved(monkeypatch)
    before, lanes_before = _render(_shader(make_shader, body=LOOP_BODY))
    assert _same(img, before)
    assert lanes[("function", "shade")] < lanes_before[("function", "shade")] // 4


def test_a_bool_select_in_float32_and_float64(make_shader, monkeypatch):
    """A bool weight selects in every precision: the x side runs where it is false."""
    body = "bvec3 miss = bvec3(hit < 0.5);\n" + MOVED_BODY.replace(
        "mix(bg, color, hit)", "mix(color, bg, miss)"
    )
    shader = _shader(make_shader, body=body)
    assert "rt.mix_reads(" in transpile_shader(shader).source
    img, lanes = _render(shader)
    img64, lanes64 = _render(shader, "float64")
    _unmoved(monkeypatch)
    assert _same(img, _render(_shader(make_shader, body=body))[0])
    assert _same(img64, _render(_shader(make_shader, body=body), "float64")[0])
    hits = _weight_lanes(make_shader, "step(0.0, d)")
    assert lanes[("function", "shade")] == lanes64[("function", "shade")] == hits


def test_float64_renders_interpolate_and_run_the_region_on_every_lane(make_shader, monkeypatch):
    """The float64 reference computes mix as written (0 * NaN is NaN there): nothing is left
    out, and the pixels stay the same."""
    shader = _shader(make_shader, color="+ vec3(sqrt(d))")
    img, lanes = _render(shader, "float64")
    _unmoved(monkeypatch)
    assert _same(img, _render(_shader(make_shader, color="+ vec3(sqrt(d))"), "float64")[0])
    assert np.isnan(img[..., :3]).any()  # (the background's NaN is kept, as before)
    assert lanes[("function", "shade")] == SIZE[0] * SIZE[1]


@pytest.mark.parametrize(
    "body",
    [
        # the value is read elsewhere too
        "vec3 color = shade(n, view);\n o = vec4(mix(bg, color, hit), color.x);",
        # its function writes a global
        "vec3 color = shadeCounting(n) + shade(n, view);\n o = vec4(mix(bg, color, hit), 1.0);",
        # it writes an out argument
        "float k;\n vec3 color = shadeOut(n, k) + shade(n, view);\n"
        " o = vec4(mix(bg, color, hit), k);",
        # moving it would cross a write of what it reads
        "vec3 color = shade(n, view) + n;\n n = vec3(0.0);\n o = vec4(mix(bg, color, hit), n.x);",
        # the select's own statement writes the weight
        "vec3 color = shade(n, view);\n o = vec4(mix(bg, color, hit), hit = 0.5);",
        # a constant weight: Mesa's strict formula, no select
        "vec3 color = shade(n, view);\n o = vec4(mix(bg, color, 0.5), 1.0);",
        # a few operations, no loop: cheaper on every lane than behind a region
        "vec3 color = normalize(view + n) * 0.5;\n o = vec4(mix(bg, color, hit), 1.0);",
        # a program that takes derivatives: lanes outside the mask are read
        "vec3 color = shade(n, view);\n o = vec4(mix(bg, color, hit), dFdx(hit));",
    ],
)
def test_what_must_not_move_stays_as_it_was(make_shader, monkeypatch, body):
    shader = _shader(make_shader, body=body)
    moved = transpile_shader(shader).source
    img, _ = _render(shader)
    _unmoved(monkeypatch)
    shader = _shader(make_shader, body=body)
    assert transpile_shader(shader).source == moved
    assert _same(img, _render(shader)[0])


def test_statements_that_only_feed_the_value_move_with_it(make_shader):
    """`n` and `view` feed only `color`: they move too; `uv` feeds the background and the
    weight as well, and stays."""
    source = transpile_shader(_shader(make_shader)).source
    region = source[source.index("rt.mix_reads(") :]
    assert all(f": vec3 {v} = " in region for v in ("n", "view", "color"))
    assert ": vec2 uv = " not in region and ": vec3 bg = " not in region


@pytest.mark.parametrize("side", [0, 1])
def test_mix_reads_names_every_lane_whose_result_depends_on_that_side(side):
    """Against the runtime's mix itself: replacing the side by NaN changes no lane that
    `mix_reads` leaves out, and changes every interpolating lane it keeps."""
    rt = Runtime("float32")
    rng = np.random.default_rng(7)
    n = 4096
    a = rng.choice(np.array([0.0, 1.0], np.float32), size=n)  # (a b2f weight: 0 or 1)
    x, y = (rng.standard_normal((3, n)).astype(np.float32) for _ in range(2))
    reads = rt.mix_reads(a, side, "select")
    assert reads is not None and reads.shape == (n,)
    nan = np.full_like(x, np.nan)
    base = rt.mix(x, y, a, "select")
    other = rt.mix(nan, y, a, "select") if side == 0 else rt.mix(x, nan, a, "select")
    assert _same(base[:, ~reads], other[:, ~reads])
    assert np.isnan(other[:, reads]).all()
    assert rt.mix_reads(a, side, "strict") is None
    assert rt.mix_reads(a, side, "fast") is None  # (interpolates: x + a*(y - x) everywhere)
    assert np.isnan(rt.mix(nan, y, a, "fast")).all()
    assert Runtime("float64").mix_reads(a.astype(np.float64), side, "select") is None
