"""`glslcheck probe`: one pixel traced statement by statement (with its float64 shadow), and the
origins of NaN/Inf pixels. Each shader here is small enough that the expected steps, lines and
values follow from reading it; nothing is pinned that float rounding on another machine could
change (IEEE float32/float64 arithmetic is the same on every x86-64, and only inequalities are
asserted about bits)."""

from __future__ import annotations

import glob
import json
import os

import numpy as np
import pytest

from glslcheck.cli.main import main
from glslcheck.verification.probe import (
    Inputs,
    Probe,
    bits_kept,
    first_unstable,
    format_nan,
    format_pixel,
)

SMALL = Inputs(size=(8, 8))

# The normalize of line 3 is of a zero vector at fragCoord (4.5, 3.5), i.e. pixel 4,4 from the
# top of an 8x8 image; every other pixel is finite.
NORMALIZE_ZERO = """\
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 p = fragCoord - vec2(4.5, 3.5);
    vec3 d = normalize(vec3(p, 0.0));
    fragColor = vec4(d * 0.5 + 0.5, 1.0);
}
"""


def steps_at(report, line, kind=None):
    return [s for s in report.steps if s.line == line and (kind is None or s.kind == kind)]


# -- NaN origins ------------------------------------------------------------------------------


def test_normalize_of_zero_vector_found_at_its_line_and_operation(make_shader):
    p = Probe(make_shader(NORMALIZE_ZERO))
    report = p.nan_origins(SMALL)
    assert (report.nan_pixels, report.inf_pixels) == (1, 0)
    [o] = report.origins
    assert (o.file, o.line, o.column) == ("Image.glsl", 3, 14)
    assert o.operation == "normalize of a zero vector"
    assert o.code == "normalize(vec3(p, 0.0))"
    assert (o.pixels, o.box) == (1, (4, 4, 4, 4))
    assert "zero vector" in o.help
    text = format_nan(report, "Image.glsl", SMALL)
    assert "Image.glsl:3:14: normalize of a zero vector in `normalize(vec3(p, 0.0))`" in text
    # the same pixel probed: its first NaN, and a finite neighbour has none
    probed = p.pixel(4, 4, SMALL)
    assert probed.first_nan.operation == "normalize of a zero vector" and probed.first_nan.line == 3
    assert np.isnan(probed.color[0])
    assert p.pixel(3, 4, SMALL).first_nan is None
    # with a derivative the lanes run as 2x2 quads: the quad's three finite pixels are not counted
    quads = Probe(
        make_shader(NORMALIZE_ZERO.replace("1.0);\n}", "dFdx(fragCoord.x));\n}"))
    ).nan_origins(SMALL)
    assert [(o.line, o.pixels, o.box) for o in quads.origins] == [(3, 1, (4, 4, 4, 4))]


def test_operations_are_told_apart_and_a_discarded_select_side_is_no_origin(make_shader):
    # column x of an 8x8 image: x = 0 takes log(0) (-inf, line 5); x = 1 divides 0/0 (line 6);
    # x = 2 takes sqrt(-1) (line 7); x = 3 overflows (line 8; not `x * 1e38 * 100.0`, whose
    # constants Mesa multiplies out first, to +Inf, as the NumPy backend now does). Line 4 computes
    # sqrt of a negative for x < 4 on the side the select throws away: not their origin (x >= 4
    # stays finite).
    src = """\
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    float x = floor(fragCoord.x);
    float v = 0.0;
    float s = x >= 4.0 ? sqrt(x - 4.0) : 1.0;
    if (x == 0.0) v = log(x);
    if (x == 1.0) v = (x - 1.0) / (x - 1.0);
    if (x == 2.0) v = sqrt(1.0 - x);
    if (x == 3.0) v = x * 1e38 * x;
    fragColor = vec4(v, x >= 4.0 ? s : 0.0, 0.0, 1.0);
}
"""
    report = Probe(make_shader(src)).nan_origins(SMALL)
    assert (report.nan_pixels, report.inf_pixels) == (16, 16)
    got = {(o.line, o.operation): (o.pixels, o.box) for o in report.origins}
    assert got == {
        (5, "log of zero"): (8, (0, 0, 0, 7)),
        (6, "0/0"): (8, (1, 0, 1, 7)),
        (7, "sqrt of a negative"): (8, (2, 0, 2, 7)),
        (8, "overflow"): (8, (3, 0, 3, 7)),
    }


def test_nan_made_in_an_argument_is_found_in_the_caller(make_shader):
    src = """\
float half_(float v) { return v * 0.5; }
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    float h = half_(inversesqrt(fragCoord.x - 0.5));
    fragColor = vec4(h);
}
"""
    [o] = Probe(make_shader(src)).nan_origins(SMALL).origins
    assert (o.line, o.operation, o.pixels, o.box) == (3, "inversesqrt(0)", 8, (0, 0, 0, 7))


def test_nan_scan_on_many_lanes_with_compaction_and_derivatives(make_shader):
    # 64x64 = 4096 lanes: in shade(), the branch a quarter of them take is compacted (it has a
    # loop, and 1024 lanes is the default Compaction.min_lanes); there they divide 0/0, the others
    # take pow of a negative base. mainImage takes a derivative: the lanes run as 2x2 quads.
    src = """\
float shade(vec2 fc) {
    float v = fc.x - 100.0;
    float w = 0.0;
    if (fc.y < 16.0) {
        for (int i = 0; i < 3; i++) { w += float(i); }
        w = (w - 3.0) / (w - 3.0);
    } else {
        w = pow(v, 1.5);
    }
    return w;
}
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    fragColor = vec4(shade(fragCoord), dFdx(fragCoord.x), 0.0, 1.0);
}
"""
    inputs = Inputs(size=(64, 64))
    p = Probe(make_shader(src))
    assert "X.gather(" in p.source.split("def f_shade")[1].split("def f_mainImage")[0]
    report = p.nan_origins(inputs)
    assert report.nan_pixels == 64 * 64
    got = {(o.line, o.operation): (o.pixels, o.box) for o in report.origins}
    assert got == {
        (6, "0/0"): (64 * 16, (0, 48, 63, 63)),
        (8, "pow of a negative base"): (64 * 48, (0, 0, 63, 47)),
    }


# -- one pixel, step by step --------------------------------------------------------------------

FAR_CAMERA = """\
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec3 eye = vec3(0.0, 0.0, 20000.0);
    vec3 center = vec3(0.0, 0.0, 19990.0);
    vec2 uv = (fragCoord - 0.5 * iResolution.xy) / iResolution.y;
    vec3 dir = normalize(vec3(uv, -1.0));
    vec3 hit = eye + dir * 9.3;
    vec3 local = hit - center;
    fragColor = vec4(local * 0.1 + 0.5, 1.0);
}
"""


def test_cancellation_of_a_far_camera_shows_in_the_bits_column_at_its_line(make_shader):
    p = Probe(make_shader(FAR_CAMERA))
    report = p.pixel(1, 2, SMALL)
    [d] = steps_at(report, 5)
    [hit] = steps_at(report, 6)
    [local] = steps_at(report, 7)
    # float32 spacing at 20000 is 2^-9: |hit - center| ~ 1 keeps at most 24 - 14 + 1 bits, while
    # the direction and the far point itself are good to a few rounding errors.
    assert d.bits >= 22 and hit.bits >= 21
    assert local.bits <= 12
    assert np.max(np.abs(np.array(local.value, np.float64) - local.value64)) > 1e-5
    first = first_unstable(p, 1, 2, SMALL)
    assert (first.file, first.line, first.code) == ("Image.glsl", 7, "vec3 local = hit - center;")
    assert first.bits == local.bits
    text = format_pixel(report, "Image.glsl", SMALL)
    assert "local = " in text and f"{local.bits} bits]" in text


# The float32 run skips the `if` (1 + 1.5e-8 rounds to 1) where the float64 shadow takes it: the
# runs part at line 4 before any value departs (`a` keeps all 24 bits), and the first departure,
# `d` (0 against 0.15 in float64 at x = 1, 0 bits), comes after the parting.
PARTING = """\
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    float a = 1.0 + fragCoord.x * 1e-8;
    float s = 0.0;
    if (a > 1.0) { s = 1.0; }
    float d = fract(a * 1e7);
    fragColor = vec4(d, s, 0.0, 1.0);
}
"""


def test_first_unstable_compares_up_to_the_first_departure_and_realigns_where_the_runs_part(
    make_shader,
):
    p = Probe(make_shader(PARTING))
    report = p.pixel(1, 2, SMALL)
    [d] = steps_at(report, 5)
    assert d.bits == 0 and not steps_at(report, 4, "assign")  # float32 skipped `s = 1.0`
    first = first_unstable(p, 1, 2, SMALL)
    assert (first.line, first.bits) == (5, 0)
    # the first step of the full report below the threshold, for every pixel
    for x in range(8):
        scan = next(s for s in p.pixel(x, 2, SMALL).steps if s.bits is not None and s.bits < 16)
        got = first_unstable(p, x, 2, SMALL, realign=None)
        assert (got.line, got.code, got.bits, got.value, got.value64) == (
            scan.line,
            scan.code,
            scan.bits,
            scan.value,
            scan.value64,
        )
    # with no realignment allowed the pixel gives no answer past the parting
    assert first_unstable(p, 1, 2, SMALL, realign=0) is None
    # the far camera's runs never part: the same answer as the report's first unstable step
    far = Probe(make_shader(FAR_CAMERA))
    assert first_unstable(far, 1, 2, SMALL, realign=0).line == 7


CONTROL = """\
struct Light { vec3 pos; float power; };
float sumTo(int n) {
    float s = 0.0;
    for (int i = 0; i < 100; i++) {
        if (i >= n) break;
        s += float(i);
    }
    return s;
}
void split(in float v, out float whole, out float part) { whole = floor(v); part = v - whole; }
float firstPositive(float a[3]) {
    for (int i = 0; i < 3; i++) { if (a[i] > 0.0) return a[i]; }
    return -1.0;
}
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    if (fragCoord.x < 1.0) discard;
    Light l = Light(vec3(1.0, 2.0, 3.0), 2.5);
    float arr[3] = float[3](-1.0, 0.5, 2.0);
    float w, f;
    split(fragCoord.y * 0.5, w, f);
    float s = sumTo(50);
    float fp = firstPositive(arr);
    fragColor = vec4(l.power * 0.1, fp, f, 1.0);
}
"""


def test_loops_early_return_out_parameters_structs_and_arrays(make_shader):
    report = Probe(make_shader(CONTROL)).pixel(3, 2, SMALL)  # fragCoord (3.5, 5.5)
    js = report.to_json()
    assert js["pixel"] == [3, 2] and js["frag_coord"] == [3.5, 5.5]
    [branch] = steps_at(report, 16)
    assert (branch.kind, branch.name, branch.value) == ("branch", "if", False)
    [light] = [s.to_json() for s in steps_at(report, 17)]
    assert light["value"] == {"pos": [1.0, 2.0, 3.0], "power": 2.5} and light["bits"] == 24
    [arr] = [s.to_json() for s in steps_at(report, 18)]
    assert arr["name"] == "arr" and arr["value"] == [-1.0, 0.5, 2.0]
    # out parameters: the call, the callee's assignments, then w and f written back at the call
    call, w, f = steps_at(report, 20)
    assert (call.kind, call.name) == ("call", "split") and call.to_json()["value"] == {"v": 2.75}
    assert (w.name, w.value, f.name, f.value) == ("w", 2.0, "f", 0.75)
    assert [(s.name, float(s.value)) for s in steps_at(report, 10)] == [
        ("whole", 2.0),
        ("part", 0.75),
    ]
    # the loop of sumTo: 51 iterations (the 51st breaks), s = 0 + 1 + ... + 49
    loop = [s for s in steps_at(report, 4, "loop")]
    assert loop[0].name == "for start" and loop[-1].name == "for end" and loop[-1].value == 51
    assert [s.value for s in loop if s.name == "for iteration"] == list(range(1, 52))
    assert [s.name for s in steps_at(report, 5, "branch")].count("break") == 1
    # i is stepped 50 times: not after the break (the induction variable's step runs unmasked)
    assert [int(s.value) for s in steps_at(report, 4, "assign")] == list(range(0, 51))
    [ret] = steps_at(report, 8)
    assert (ret.kind, ret.name, ret.value) == ("return", "sumTo", 1225.0)
    # early return from inside the loop of firstPositive: line 13 never runs
    assert [(s.kind, float(s.value)) for s in steps_at(report, 12, "return")] == [("return", 0.5)]
    assert steps_at(report, 13) == []
    assert report.color == (0.25, 0.5, 0.75, 1.0)
    text = format_pixel(report, "Image.glsl", SMALL)
    assert "iterations 4 to 49 folded (46 iterations" in text
    assert "loop ends after 51 iterations" in text and "iteration 51" in text
    # a discarded pixel: its discard step, and the GL clear colour
    gone = Probe(make_shader(CONTROL)).pixel(0, 2, SMALL)
    assert [s.kind for s in gone.steps] == ["branch", "discard"]
    assert gone.color == (0.0, 0.0, 0.0, 0.0)


MORE_CONTROL = """\
mat2 rot(float a) { float c = cos(a), s = sin(a); return mat2(c, s, -s, c); }
void bump(inout vec2 v, float k) { v *= k; }
float pick(int i) {
    switch (i) {
        case 0: return 0.25;
        case 1:
        case 2: return 0.5;
        default: break;
    }
    return 1.0;
}
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    int n = int(fragCoord.x);
    float acc = 0.0;
    int k = 0;
    while (k < 10) {
        k++;
        if (k % 2 == 0) continue;
        acc += 1.0;
    }
    do { acc -= 0.5; } while (acc > 4.0);
    vec2 v = rot(0.0) * vec2(1.0, 2.0);
    bump(v, 0.5);
    fragColor = vec4(acc, pick(n), v);
}
"""


def test_switch_while_do_continue_inout_and_matrices(make_shader):
    p = Probe(make_shader(MORE_CONTROL))
    report = p.pixel(1, 0, SMALL)  # n = 1
    loop = steps_at(report, 16, "loop")
    assert [s.name for s in loop][:2] == ["while start", "while iteration"]
    assert (loop[-1].name, loop[-1].value) == ("while end", 10)
    assert [s.name for s in steps_at(report, 18, "branch")].count("continue") == 5
    assert [(s.name, float(s.value)) for s in steps_at(report, 19)] == [
        ("acc", float(a)) for a in range(1, 6)
    ]
    do = steps_at(report, 21, "loop")
    assert (do[0].name, do[-1].name, do[-1].value) == ("do start", "do end", 2)
    [rot] = [s.to_json() for s in steps_at(report, 1, "return")]
    assert rot["value"] == [[1.0, 0.0], [-0.0, 1.0]]  # a mat2 as its columns
    assert [(s.kind, s.name) for s in steps_at(report, 23)] == [("call", "bump"), ("assign", "v")]
    assert steps_at(report, 23)[1].to_json()["value"] == [0.5, 1.0]
    [switch] = steps_at(report, 4)
    assert (switch.kind, switch.name, int(switch.value)) == ("branch", "switch", 1)
    assert [float(s.value) for s in steps_at(report, 7, "return")] == [0.5]
    assert report.color == (4.0, 0.5, 0.5, 1.0)
    other = p.pixel(5, 0, SMALL)  # n = 5: default, break out of the switch, return 1.0
    assert [s.name for s in steps_at(other, 8)] == ["break (switch)"]
    assert [float(s.value) for s in steps_at(other, 10)] == [1.0]


def test_common_tab_and_macros_point_at_the_users_lines(make_shader):
    common = """\
#define SQUARE(x) ((x) * (x))
#define RATIO(a, b) ((a) / (b))
float lum(vec3 c) {
    return dot(c, vec3(0.2126, 0.7152, 0.0722));
}
"""
    image = """\
#define HALF 0.5
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    float k = SQUARE((fragCoord.x - 2.5) * HALF);
    float l = lum(vec3(k, k, k));
    fragColor = vec4(RATIO(l, k));
}
"""
    # (vec3(k, k, k), not vec3(k): a call handing vec3(k) to a dot with a constant is inlined as
    # Mesa inlines it, transpile/inline.py, and shows no call and return steps)
    p = Probe(make_shader(image, common=common))
    report = p.pixel(3, 0, SMALL)  # fragCoord.x 3.5: k = 0.25
    where = [(s.file, s.line, s.kind, s.name) for s in report.steps]
    assert where == [
        ("Image.glsl", 3, "assign", "k"),
        ("Image.glsl", 4, "call", "lum"),
        ("Common.glsl", 4, "return", "lum"),
        ("Image.glsl", 4, "assign", "l"),
        ("Image.glsl", 5, "assign", "fragColor"),
    ]
    assert report.steps[0].code == "float k = SQUARE((fragCoord.x - 2.5) * HALF);"
    assert report.steps[0].value == np.float32(0.25)
    assert report.steps[2].depth == 1 and report.steps[2].code.startswith("return dot(c")
    # x = 2: k = 0, and the 0/0 made inside the Common tab's macro is reported at the line of
    # the user's Image tab that uses the macro
    [o] = p.nan_origins(SMALL).origins
    assert (o.file, o.line, o.operation, o.box) == ("Image.glsl", 5, "0/0", (2, 0, 2, 7))


def test_bits_kept():
    f32 = np.float32
    assert bits_kept(np.array(f32(1 / 3)), np.array(1 / 3)) == 24
    assert bits_kept(np.array(f32(1.0)), np.array(1.0 + 2.0**-10)) == 10
    # a vector is judged as a whole: the small component's own relative error does not count
    assert bits_kept(np.array([f32(1.0), f32(1e-7)]), np.array([1.0, 1.1e-7])) == 24
    assert bits_kept(np.array(f32(1e-7)), np.array(1.1e-7)) == 3
    assert bits_kept(np.array(f32(0.0)), np.array(1e-60)) == 24  # below float32's range
    assert bits_kept(np.array(f32("nan")), np.array(1.0)) == 0
    assert bits_kept(np.array(f32("nan")), np.array(float("nan"))) is None  # no bits to count
    assert bits_kept(np.array([f32("inf"), f32(1.0)]), np.array([float("inf"), 1.0])) is None
    assert bits_kept(np.array(True), np.array(True)) is None
    # several leaves (a call's arguments, a struct): the fewest bits of the leaves with bits
    args = {"a": np.array([f32(1.0), f32(2.0)]), "n": np.array(3), "b": np.array(f32(1.0))}
    shadow = {"a": np.array([1.0, 2.0]), "n": np.array(3), "b": np.array(1.0 + 2.0**-10)}
    assert bits_kept(args, shadow) == 10
    assert (
        bits_kept(
            [np.array(f32("nan")), np.array(f32(1.0))], [np.array(float("nan")), np.array(1.0)]
        )
        == 24
    )
    assert (
        bits_kept([np.zeros(0, f32), np.array(f32("nan"))], [np.zeros(0), np.array(float("nan"))])
        == 24
    )


# -- the command ---------------------------------------------------------------------------------


def write_shader(tmp_path, text, name="Image.glsl"):
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def strict_json(name):
    raise AssertionError(f"{name} is not JSON")


def test_cli_pixel_json_has_exactly_the_issue_fields(tmp_path, capsys):
    path = write_shader(tmp_path, NORMALIZE_ZERO)
    assert main(["probe", path, "--pixel", "4,4", "--size", "8x8", "--format", "json"]) == 0
    out = json.loads(capsys.readouterr().out, parse_constant=strict_json)
    assert list(out) == ["pixel", "frag_coord", "color", "steps", "first_nan"]
    assert out["pixel"] == [4, 4] and out["frag_coord"] == [4.5, 3.5]
    assert out["color"][:3] == ["nan", "nan", "nan"] and out["color"][3] == 1.0
    [d] = [s for s in out["steps"] if s["name"] == "d"]
    assert d["value"] == d["value64"] == ["nan", "nan", "nan"] and d["bits"] is None
    assert all(
        list(s) == ["file", "line", "code", "kind", "name", "value", "value64", "bits"]
        for s in out["steps"]
    )
    assert out["first_nan"] == {
        "file": path,
        "line": 3,
        "column": 14,
        "code": "normalize(vec3(p, 0.0))",
        "operation": "normalize of a zero vector",
    }
    assert (
        main(["probe", path, "--frag-coord", "4.5,3.5", "--size", "8x8", "--format", "json"]) == 0
    )
    assert json.loads(capsys.readouterr().out)["pixel"] == [4, 4]


def test_cli_nan_json_and_exit_codes(tmp_path, capsys):
    path = write_shader(tmp_path, NORMALIZE_ZERO)
    assert main(["probe", path, "--nan", "--size", "8x8", "--format", "json"]) == 1
    out = json.loads(capsys.readouterr().out)
    assert out == {
        "nan_pixels": 1,
        "inf_pixels": 0,
        "origins": [
            {
                "file": path,
                "line": 3,
                "column": 14,
                "code": "normalize(vec3(p, 0.0))",
                "operation": "normalize of a zero vector",
                "pixels": 1,
                "box": [4, 4, 4, 4],
                "undefined_pixels": 0,
            }
        ],
        "undefined_reads": [],
    }
    fixed = write_shader(
        tmp_path, NORMALIZE_ZERO.replace("vec3(p, 0.0)", "vec3(p, 1.0)"), "Fixed.glsl"
    )
    assert main(["probe", fixed, "--nan", "--size", "8x8"]) == 0
    assert "no pixel is NaN or Inf" in capsys.readouterr().out


def test_cli_errors(tmp_path, capsys):
    path = write_shader(tmp_path, NORMALIZE_ZERO)
    assert main(["probe", path, "--pixel", "8,0", "--size", "8x8"]) == 2
    assert "outside the 8x8 image" in capsys.readouterr().err
    assert main(["probe", path, "--pixel", "a,b"]) == 2
    assert main(["probe", path]) == 2  # one of --pixel, --frag-coord, --nan
    bad = write_shader(
        tmp_path, "void mainImage(out vec4 c, in vec2 f) { c = vec4(x); }\n", "Bad.glsl"
    )
    assert main(["probe", bad, "--pixel", "0,0"]) == 1
    assert f"{bad}:1:" in capsys.readouterr().err


def test_render_mentions_probe_nan_when_the_image_has_nan(tmp_path, capsys):
    path = write_shader(tmp_path, NORMALIZE_ZERO)
    assert main(["render", path, "--size", "8x8", "-o", str(tmp_path / "o.png")]) == 0
    assert f"glslcheck probe {path} --nan" in capsys.readouterr().err
    fixed = write_shader(
        tmp_path, NORMALIZE_ZERO.replace("vec3(p, 0.0)", "vec3(p, 1.0)"), "Fixed.glsl"
    )
    assert main(["render", fixed, "--size", "8x8", "-o", str(tmp_path / "o.png")]) == 0
    assert "probe" not in capsys.readouterr().err


def test_the_normal_module_has_no_tracing(make_shader):
    from glslcheck.backends.numpy_engine.transpile import transpile_shader

    source = transpile_shader(make_shader(CONTROL)).source
    assert "T." not in source
    traced = Probe(make_shader(CONTROL)).source
    assert "T.call(" in traced and "T.li(" in traced


ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EVERY_SHADER = sorted(
    glob.glob(os.path.join(ROOT, "tests", "corpus", "*.glsl"))
    + glob.glob(os.path.join(ROOT, "tests", "corpus", "*.frag"))
    + glob.glob(os.path.join(ROOT, "lab_shaders", "*", ""))
)


@pytest.mark.parametrize("shader", EVERY_SHADER, ids=lambda p: os.path.relpath(p, ROOT))
def test_traced_module_computes_what_the_render_computes(shader):
    # the traced module is the normal one plus hooks: the probed pixels' colours are the
    # render's, bit for bit, and --nan counts the render's NaN/Inf pixels
    from glslcheck.backends import registry as api

    inputs = Inputs(size=(32, 18), time=1.5)
    img = api.compile(shader).render(size=inputs.size, time=inputs.time)
    p = Probe(shader)
    for x, y in ((16, 9), (3, 14), (29, 2)):
        got = np.array(p.pixel(x, y, inputs).color, np.float32)
        assert np.array_equal(got, img[y, x], equal_nan=True), (x, y)
    report = p.nan_origins(inputs)
    assert report.nan_pixels == int(np.isnan(img).any(axis=-1).sum())
    assert sum(o.pixels for o in report.origins) == report.nan_pixels + report.inf_pixels


def test_verify_mentions_probe_nan_when_the_numpy_image_has_nan(tmp_path, capsys, gl):
    path = write_shader(tmp_path, NORMALIZE_ZERO)
    main(["verify", path, "--size", "8x8"])
    out = capsys.readouterr().out
    assert f"note: 1 pixel is NaN: `glslcheck probe {path} --nan --size 8x8`" in out
