"""The uniformity (divergence) analysis, glslcheck/backends/cpu_core/uniformity.py: its verdicts on
small functions, and what it changes in the rendered frames (nothing) and in the lane shapes of
the values (uniform ones stay one value per tile).

Three layers: the analysis' verdicts read from `Uniformity` directly (which variables are
varying, which writes are free); the same programs rendered with free writes turned off, which
must give bit-identical frames (a free write only skips the mask where no lane left out reads
the value again); and renders against llvmpipe.
"""

from __future__ import annotations

import numpy as np
import pytest

from glslcheck.backends.cpu_core.facts import Facts, written_lvalues
from glslcheck.backends.cpu_core.uniformity import Uniformity
from glslcheck.backends.numpy_engine import program as P
from glslcheck.backends.numpy_engine.transpile import check_program
from glslcheck.frontend import syntax as A
from glslcheck.frontend.parser import parse_shader
from glslcheck.semantics.analysis import written_variable


def _image(body: str, helpers: str = "") -> str:
    return helpers + "\nvoid mainImage(out vec4 fragColor, in vec2 fragCoord) {\n" + body + "\n}\n"


def analyse(make_shader, text: str, fn_name: str = "mainImage"):
    """(the analysis of function `fn_name`, the model, {variable name: [its free-write
    verdicts]})."""
    model = check_program(parse_shader(make_shader(text), "Image"))
    functions = list(model.reachable_functions())
    facts = Facts(model, functions)
    fn = next(f for f in functions if f.name == fn_name)
    uni = Uniformity(model, facts, fn, fn is model.entry)
    writes: dict[str, list[bool]] = {}
    for node in fn.node.body.walk():
        for t in written_lvalues(model, node):
            writes.setdefault(written_variable(model, t)[0].name, []).append(uni.is_free(t))
    return uni, model, writes


def varying(uni, model, name: str) -> bool:
    fn = uni.fn
    for node in list(fn.node.body.walk()) + list(fn.node.proto.params):
        if isinstance(node, (A.Declarator, A.Param)) and getattr(node, "name", None) == name:
            return uni.is_varying(model.symbol_of(node))
    raise KeyError(name)


LIGHTS_AFTER_RETURN = _image(
    """
    if (fragCoord.x < 8.0) { fragColor = vec4(0.0); return; }
    Light L[2];
    L[0] = Light(vec3(1.0, 2.0, 3.0), 0.5 + 0.5 * sin(iTime));
    L[1] = Light(vec3(-1.0, 2.0, 3.0), 1.0);
    vec3 c = vec3(0.0);
    for (int k = 0; k < 2; k++) {
        c += L[k].color * L[k].pos * fragCoord.y;
    }
    fragColor = vec4(c, 1.0);""",
    "struct Light { vec3 pos; float color; };\n",
)


def test_a_lights_array_built_after_an_early_return_stays_uniform(make_shader):
    uni, model, writes = analyse(make_shader, LIGHTS_AFTER_RETURN)
    assert writes["L"] == [True, True]  # no mask: the lanes that returned never read L
    assert not varying(uni, model, "L")
    assert varying(uni, model, "c")  # it reads fragCoord
    assert writes["c"] == [True]  # the loop's lanes are the declaration's: no mask either
    assert writes["fragColor"] == [False, False]  # an out parameter of a function left early


def test_writes_under_a_varying_condition_keep_their_mask(make_shader):
    uni, model, writes = analyse(
        make_shader,
        _image("""
    float a = 1.0;
    float b = 2.0;
    if (fragCoord.x > 4.0) {
        a = 3.0;
        float inner = 0.0;
        inner = 5.0;
        b = inner;
    }
    if (iTime > 1.0) { b = 7.0; }
    fragColor = vec4(a, b, 0.0, 1.0);"""),
    )
    assert writes["a"] == [False] and varying(uni, model, "a")  # other lanes read a after the if
    assert writes["inner"] == [True] and not varying(uni, model, "inner")  # declared in the branch
    assert writes["b"] == [False, True]  # under fragCoord: masked; under iTime: a uniform branch


LIGHTS_FILLED_IN_A_BRANCH = _image(
    """
    Light L[2];
    float depth = fragCoord.x - 6.0;
    vec3 c = vec3(0.1);
    if (depth > 0.0) {
        L[0] = Light(vec3(1.0, 2.0, 3.0), 0.5 + 0.5 * sin(iTime));
        L[1] = Light(vec3(-1.0, 2.0, 3.0), 1.0);
        for (int k = 0; k < 2; k++) {
            c += L[k].color * L[k].pos * depth;
        }
    }
    fragColor = vec4(c, 1.0);""",
    "struct Light { vec3 pos; float color; };\n",
)


def test_a_local_used_only_inside_one_branch_is_declared_there(make_shader):
    uni, model, writes = analyse(make_shader, LIGHTS_FILLED_IN_A_BRANCH)
    assert writes["L"] == [True, True]  # no lane left out of the branch ever reads L
    assert not varying(uni, model, "L")
    assert writes["c"] == [False] and varying(uni, model, "c")  # read after the branch


@pytest.mark.parametrize(
    "body",
    [
        # read after the branch: the lanes left out see the declared value
        "float a; if (fragCoord.x > 4.0) { a = 2.0; fragColor = vec4(a); } fragColor.y = a;",
        # a loop between the declaration and the branch: a later pass reads the earlier value
        "float a = 0.0; for (int i = 0; i < 3; i++) {"
        " if (fragCoord.x > float(i)) { fragColor.x += a; a = 2.0; } }",
        # used in both arms: the else arm runs after the then arm has written every lane
        "float a = 1.0; if (fragCoord.x > 4.0) { a = 2.0; fragColor = vec4(a); }"
        " else { fragColor = vec4(a); }",
    ],
)
def test_a_local_used_outside_the_branch_keeps_its_mask(make_shader, body):
    uni, model, writes = analyse(make_shader, _image(body))
    assert False in writes["a"] and varying(uni, model, "a")


def test_a_local_of_a_function_with_derivatives_keeps_its_mask(make_shader):
    """llvmpipe computes the inactive lanes of a branch with the register's old value, and a
    neighbour's derivative reads them: no sinking where derivatives are taken."""
    uni, model, writes = analyse(
        make_shader,
        _image("float a; if (fragCoord.x > 4.0) { a = 2.0 * iTime; fragColor = vec4(dFdx(a)); }"),
    )
    assert writes["a"] == [False] and varying(uni, model, "a")


def test_loops_whose_lanes_diverge(make_shader):
    uni, model, writes = analyse(
        make_shader,
        _image("""
    float outer = 0.0;
    float total = 0.0;
    for (int i = 0; i < 8; i++) {
        float step = 1.0;
        if (fragCoord.x < float(i)) continue;
        step = 2.0;
        outer = step;
    }
    for (int j = 0; j < 8; j++) {
        total += 1.0;
    }
    fragColor = vec4(outer, total, 0.0, 1.0);"""),
    )
    # the lanes that continue come back: outer, from before the loop, is written under the mask;
    # step is declared afresh in every iteration
    assert writes["outer"] == [False] and varying(uni, model, "outer")
    assert writes["step"] == [True] and not varying(uni, model, "step")
    assert writes["total"] == [True] and not varying(uni, model, "total")
    assert writes["i"] == [False]  # (the induction variable: stepped unmasked by the loop itself)


def test_a_varying_break_makes_the_loop_divergent(make_shader):
    uni, model, writes = analyse(
        make_shader,
        _image("""
    float t = 0.0;
    for (int i = 0; i < 8; i++) {
        if (t > fragCoord.x) break;
        t += 1.0;
    }
    fragColor = vec4(t);"""),
    )
    assert writes["t"] == [False] and varying(uni, model, "t")


def test_out_parameters(make_shader):
    helpers = """
void init(out vec3 v, float k) { v = vec3(k); v.y = 2.0; }
float early(out float o, float x) { o = 1.0; if (x > 0.5) return 0.0; o = 2.0; return 1.0; }
"""
    body = (
        "vec3 a; init(a, 1.0); float o; float r = early(o, fragCoord.x); fragColor = vec4(a, "
        "o + r);"
    )
    _, _, writes = analyse(make_shader, _image(body, helpers), "init")
    assert writes["v"] == [True, True]  # nothing leaves init early: the caller's lanes are init's
    _, _, writes = analyse(make_shader, _image(body, helpers), "early")
    assert writes["o"] == [False, False]  # lanes that returned must keep o = 1.0
    uni, model, writes = analyse(make_shader, _image(body, helpers))
    assert not varying(uni, model, "a")  # a call of a closed function with uniform arguments
    assert varying(uni, model, "o")


def test_where_derivatives_read_neighbours_only_ssa_values_are_free(make_shader):
    # llvmpipe computes SSA values in every lane (a neighbour's dFdx reads them) and stores only
    # values merged across control flow under the mask: a write at the declaration's level and
    # loop depth is free (w, fragColor), one inside a branch or loop around it keeps its mask (v,
    # u); tests/channels test_derivatives_of_values_computed_under_a_branch against the driver
    uni, _, writes = analyse(
        make_shader,
        _image("""
    float v = fragCoord.x;
    float u = 0.0;
    if (fragCoord.y > 2.0) { float w = 0.0; w = v * v; v = dFdx(w); }
    for (int i = 0; i < 2; i++) u = u + dFdy(v);
    fragColor = vec4(v + u);"""),
    )
    assert writes == {"w": [True], "v": [False], "u": [False], "i": [False], "fragColor": [True]}


def test_switch_bodies_keep_their_masks(make_shader):
    uni, model, writes = analyse(
        make_shader,
        _image("""
    float c = 0.0;
    switch (int(iTime)) {
        case 0: float d = 1.0; d = 2.0; c = d; break;
        default: c = 3.0;
    }
    fragColor = vec4(c);"""),
    )
    assert writes["d"] == [False] and writes["c"] == [False, False]


def test_fragment_coordinates_are_varying(make_shader):
    uni, model, _ = analyse(
        make_shader,
        _image("""
    float a = gl_FragCoord.x;
    float b = iResolution.x * 2.0;
    float c = fragCoord.y;
    fragColor = vec4(a, b, c, 1.0);"""),
    )
    assert varying(uni, model, "a") and varying(uni, model, "c")
    assert not varying(uni, model, "b")


def test_a_free_write_in_a_masked_loop_of_a_function_is_varying(make_shader):
    """A loop run with a live mask may be compacted (LaneHelpers.push): variables from outside it
    come back from the scatter one value per lane, so they cannot be judged uniform."""
    helpers = """
float f(float x) {
    float acc = 0.0;
    for (int i = 0; i < 4; i++) {
        if (iTime > 100.0) break;
        acc += 1.0;
    }
    return acc * x;
}
"""
    uni, model, writes = analyse(
        make_shader, _image("fragColor = vec4(f(fragCoord.x));", helpers), "f"
    )
    assert writes["acc"] == [True] and varying(uni, model, "acc")


class _ShapeSpy:
    """Wraps a Runtime: records the lane count of what the named functions return."""

    def __init__(self, rt, names):
        self._rt, self.names, self.shapes = rt, names, {}

    def __getattr__(self, name):
        f = getattr(self._rt, name)
        if name not in self.names:
            return f

        def spy(*args, **kwargs):
            out = f(*args, **kwargs)
            leaves = list(out._fields.values()) if hasattr(out, "_fields") else [out]
            for leaf in leaves:
                self.shapes.setdefault(name, set()).add(leaf.shape[-1])
            return out

        return spy


def test_uniform_arrays_are_not_broadcast_to_the_lanes(make_shader):
    prog = P.compile_numpy(make_shader(LIGHTS_AFTER_RETURN))
    ns = prog.module()
    spy = _ShapeSpy(ns["rt"], ("assign_index", "index", "sin"))
    ns["rt"] = spy
    img = prog.render(size=(16, 8), time=0.7)
    assert spy.shapes == {"assign_index": {1}, "index": {1}, "sin": {1}}
    assert np.all(img[:, :8, :3] == 0.0) and np.all(img[1:, 8:, 1] > 0.0)


def test_an_array_filled_inside_a_branch_is_not_broadcast_to_the_lanes(make_shader):
    prog = P.compile_numpy(make_shader(LIGHTS_FILLED_IN_A_BRANCH))
    ns = prog.module()
    spy = _ShapeSpy(ns["rt"], ("assign_index", "index"))
    ns["rt"] = spy
    prog.render(size=(16, 8), time=0.7)
    assert spy.shapes == {"assign_index": {1}, "index": {1}}


# Programs whose frames must not change when free writes are turned off: each exercises one way
# lanes leave the mask (returns, breaks, continues, out parameters, switch, nested functions).
SAME_WITH_MASKS = {
    "lights after return": LIGHTS_AFTER_RETURN,
    "loops": _image("""
    float acc = 0.0;
    for (int i = 0; i < 6; i++) {
        float w = float(i) * 0.1;
        if (fragCoord.x < float(i) * 2.0) continue;
        if (fragCoord.y > 6.0 && i > 3) break;
        w += 0.05;
        acc += w;
    }
    float t = 0.0;
    int n = 0;
    while (t < fragCoord.x) { t += 1.5; n++; }
    fragColor = vec4(acc, t * 0.05, float(n) * 0.1, 1.0);"""),
    "functions": _image(
        """
    vec3 a; fill(a, fragCoord.x * 0.1);
    float o = 0.0;
    float r = pick(o, fragCoord.y);
    vec3 s = shade(vec3(fragCoord, 1.0));
    fragColor = vec4(a.x * 0.1 + s.x, o + r, s.z + a.y * 0.1, 1.0);  // (alpha is not kept)""",
        """
void fill(out vec3 v, float k) { v = vec3(k); v.y = 2.0; }
float pick(inout float o, float x) { o = 0.5; if (x > 4.0) return 0.25; o = 0.75; return 1.0; }
struct L { vec3 p; float i; };
vec3 shade(vec3 p) {
    if (p.x < 3.0) return vec3(0.0);
    L ls[2];
    ls[0] = L(vec3(1.0, 2.0, 3.0), 0.5);
    ls[1].p = vec3(4.0, 5.0, 6.0);
    ls[1].i = 0.25 + 0.1 * cos(iTime);
    vec3 c = vec3(0.0);
    for (int k = 0; k < 2; k++) { c += ls[k].i * normalize(ls[k].p - p); }
    return c;
}""",
    ),
    "lights filled in a branch": LIGHTS_FILLED_IN_A_BRANCH,
    "locals used in one arm": _image("""
    float a;
    vec2 b = vec2(0.5);
    float c = 0.0;
    if (fragCoord.x > 7.0) {
        a = 0.25;
        b.y = 0.75;
        if (fragCoord.y > 3.0) { float d; d = a + b.y; c = d; }
    } else {
        float e = 0.5;
        c = e * 0.5;
    }
    float f = 0.0;
    for (int i = 0; i < 4; i++) {
        if (fragCoord.x > float(i) * 4.0) { c += f; f = 0.125; }
    }
    fragColor = vec4(a * 0.0 + c, 0.0, 0.0, 1.0);"""),
    "switch": _image("""
    float c = 0.1;
    switch (int(fragCoord.x) % 3) {
        case 0: float d = 0.2; d += 0.1; c = d; break;
        case 1: c = 0.6;
        default: c += 0.2;
    }
    fragColor = vec4(c, 0.0, 0.0, 1.0);"""),
}


@pytest.mark.parametrize("name", sorted(SAME_WITH_MASKS))
def test_free_writes_change_no_pixel(make_shader, monkeypatch, name):
    shader = make_shader(SAME_WITH_MASKS[name])
    fast = P.compile_numpy(shader).render(size=(24, 12), time=1.3)
    monkeypatch.setattr(Uniformity, "is_free", lambda self, target: False)
    masked = P.compile_numpy(shader).render(size=(24, 12), time=1.3)
    np.testing.assert_array_equal(fast, masked)


def test_lab_shaders_render_the_same_without_free_writes(monkeypatch):
    """Every lab shader, bit for bit, at a size where compaction runs (COMPACT_MIN_LANES)."""
    import glob
    import os

    from glslcheck.shadertoy.sources import load_shader

    root = os.path.join(os.path.dirname(__file__), "..", "..", "lab_shaders")
    shaders = {p: load_shader(p) for p in sorted(glob.glob(os.path.join(root, "*", "")))}
    fast = {p: P.compile_numpy(s).render(size=(96, 54), time=2.0) for p, s in shaders.items()}
    monkeypatch.setattr(Uniformity, "is_free", lambda self, target: False)
    for p, s in shaders.items():
        np.testing.assert_array_equal(
            fast[p], P.compile_numpy(s).render(size=(96, 54), time=2.0), err_msg=p
        )


def test_uniform_transcendentals_round_as_llvmpipe(gl, make_shader):
    """A uniform sin/exp2/pow is the runtime's call on a one-lane array: the LlvmpipeMath
    emulation applies to it as to a per-lane one, so a frame of them after an early return (the
    values computed once, under no mask) equals llvmpipe's bit for bit."""
    from glslcheck.backends.gl import compile_gl

    shader = make_shader(
        _image("""
    if (fragCoord.x < 4.0) { fragColor = vec4(0.25); return; }
    float s = sin(iTime * 3.7);
    float e = exp2(iTime * 0.37);
    float p = pow(iTime + 0.5, 1.7);
    fragColor = vec4(s, e * 0.1, p * 0.1, 1.0);""")
    )
    for t in (0.3, 1.7, 12.9):
        a = P.compile_numpy(shader).render(size=(8, 2), time=t)
        b = compile_gl(shader, gl).render(size=(8, 2), time=t)
        np.testing.assert_array_equal(a, b)


def test_memo_math_gives_the_emulations_bits_and_computes_each_input_once():
    """lane_memo.MemoMath in front of LlvmpipeMath: one-lane inputs (uniform values) answered
    from the table are the emulation's own results bit for bit (-0.0, NaN and inf included);
    lane arrays go straight through."""
    from glslcheck.backends.numpy_engine.lane_memo import MemoMath
    from glslcheck.backends.numpy_engine.llvmpipe_reference import LlvmpipeMath

    lp = LlvmpipeMath()
    memo = MemoMath(lp)
    values = np.array([0.0, -0.0, 1.7, -3.0e5, 1e-40, np.nan, np.inf, 12345.678], dtype=np.float32)
    y = np.full(1, 1.3, dtype=np.float32)
    with np.errstate(all="ignore"):  # (NaN and inf inputs, as a render runs them)
        for v in values:
            x = np.array([v], dtype=np.float32)
            for _ in range(2):  # the second time from the table
                for got, want in (
                    (memo.sin_or_cos(x, cos=False), lp.sin_or_cos(x, cos=False)),
                    (memo.sin_or_cos(x, cos=True), lp.sin_or_cos(x, cos=True)),
                    (memo.exp2(x), lp.exp2(x)),
                    (memo.log2(x), lp.log2(x)),
                    (memo.pow(x, y), lp.pow(x, y)),
                ):
                    assert got.tobytes() == want.tobytes()
    assert memo.misses == 5 * len(values) and memo.hits == 5 * len(values)
    lanes = np.linspace(-10, 10, 1000, dtype=np.float32)
    assert memo.sin_or_cos(lanes, cos=False).tobytes() == lp.sin_or_cos(lanes, cos=False).tobytes()
    assert memo.misses == 5 * len(values)  # (not through the table)
    out = memo.exp2(np.array([2.0], dtype=np.float32))
    out[0] = 99.0  # the caller owns what it gets: the table keeps its own copy
    assert memo.exp2(np.array([2.0], dtype=np.float32))[0] == 4.0


def test_frames_are_the_same_with_and_without_the_memo(make_shader, monkeypatch):
    shader = make_shader(
        _image("""
    float acc = 0.0;
    for (int i = 0; i < 5; i++) {
        float a = sin(float(i) * 0.7 + iTime);
        acc += a * cos(fragCoord.x * 0.3 + float(i));
    }
    fragColor = vec4(acc, pow(abs(sin(iTime)), 2.5), exp2(-fragCoord.y * 0.1), 1.0);""")
    )
    frames = [P.compile_numpy(shader).render(size=(24, 12), time=t) for t in (0.5, 0.5, 1.25)]
    from glslcheck.backends.numpy_engine import tiles as frame

    monkeypatch.setattr(frame, "MemoMath", lambda lp: lp)
    plain = [P.compile_numpy(shader).render(size=(24, 12), time=t) for t in (0.5, 0.5, 1.25)]
    for a, b in zip(frames, plain):
        np.testing.assert_array_equal(a, b)


# Code after early exits is compacted (Statements.rest_compacted): most lanes leave mainImage
# (x < 80 of 128), the rest runs on the gathered lanes (3072 of a 128x64 tile), where most
# leave shade() and split() early again (y < 40 of 64): their rest is gathered once more.
AFTER_EARLY_EXITS = _image(
    """
    vec3 base = vec3(0.1);
    if (fragCoord.x < 80.0) { fragColor = vec4(base, 1.0); return; }
    float acc = shade(fragCoord);
    vec2 p = fragCoord * 0.05;
    for (int i = 0; i < 6; i++) {
        if (p.y > 1.2 && i > 2) continue;
        p = p * 1.1 + vec2(0.1 * sin(float(i) + iTime), 0.2);
        if (length(p) > 3.0) break;
        acc += 0.05 * length(p);
    }
    vec3 o; float k = split(fragCoord.y, o);
    fragColor = vec4(acc, k * 0.1, o.z * 0.01 + base.x, 1.0);""",
    """
float shade(vec2 f) {
    if (f.y < 40.0) return 0.5;
    float s = 0.0;
    for (int i = 0; i < 4; i++) { s += sin(f.x * 0.1 + float(i)) * 0.1; }
    vec3 n = normalize(vec3(f, 3.0));
    return s + n.x * n.y;
}
float split(float y, out vec3 o) {
    o = vec3(1.0, 2.0, 3.0);
    if (y < 40.0) return 1.0;
    o = vec3(y, y * 2.0, y * 3.0);
    float t = y * 0.5 + sqrt(y) * 0.25 + exp2(-y * 0.1);
    return t * t;
}""",
)


def test_code_after_early_exits_is_compacted_and_changes_no_pixel(gl, make_shader, monkeypatch):
    from glslcheck.backends.gl import compile_gl
    from glslcheck.backends.numpy_engine.transpile import Transpiler
    from glslcheck.verification.compare import compare

    shader = make_shader(AFTER_EARLY_EXITS)
    assert "rest" in {k for k, *_ in P.compile_numpy(shader).meta["regions"].values()}
    prog = P.compile_numpy(shader)
    prog.parallel, prog.threads = "threads", 1
    seen = []
    real = P.LaneHelpers.gather
    monkeypatch.setattr(
        P.LaneHelpers,
        "gather",
        lambda self, S, idx, values: seen.append(len(idx)) or real(self, S, idx, values),
    )
    fast = prog.render(size=(128, 64), time=0.8)
    assert (
        sorted(seen)[-1] == 48 * 64 and len(seen) >= 3
    )  # mainImage's rest, then shade's and split's
    monkeypatch.setattr(P.LaneHelpers, "gather", real)
    monkeypatch.setattr(Transpiler, "rest_compacted", lambda self, rest, mask: False)
    masked = P.compile_numpy(shader).render(size=(128, 64), time=0.8)
    np.testing.assert_array_equal(fast, masked)
    c = compare(fast, compile_gl(shader, gl).render(size=(128, 64), time=0.8))
    assert c.match, (c.max_abs_error, c.mismatched_pixels)


# Values a compacted region leaves behind (Statements._region_names): in a 128x64 tile the
# branch and the code after the early return run on the 40 of 128 columns gathered. `L` is
# declared before them and written there with uniform values only: used in one arm of the `if`
# (dead after it), or after a return, also read after the region (its writes are free, the
# lanes that returned never read it: one value for the lanes left).
LIGHTS_LEFT_BEHIND = {
    "declared before a branch": _image(
        """
    Light L[2];
    float depth = 40.0 - fragCoord.x;
    vec3 c = vec3(0.1);
    if (depth > 0.0) {
        L[0] = Light(vec3(1.0, 2.0, 3.0), 0.5 + 0.5 * sin(iTime));
        L[1] = Light(vec3(-1.0, 2.0, 3.0), 1.0);
        for (int k = 0; k < 2; k++) {
            c += L[k].color * normalize(L[k].pos - vec3(fragCoord * 0.01, depth));
        }
    }
    fragColor = vec4(c, 1.0);""",
        "struct Light { vec3 pos; float color; };\n",
    ),
    "declared before a return": _image(
        """
    Light L[2];
    vec3 c = vec3(0.1);
    if (fragCoord.x >= 40.0) { fragColor = vec4(c, 1.0); return; }
    L[0] = Light(vec3(1.0, 2.0, 3.0), 0.5 + 0.5 * sin(iTime));
    L[1] = Light(vec3(-1.0, 2.0, 3.0), 1.0);
    for (int k = 0; k < 2; k++) {
        c += L[k].color * normalize(L[k].pos - vec3(fragCoord * 0.01, 1.0));
    }
    fragColor = vec4(c, 1.0);""",
        "struct Light { vec3 pos; float color; };\n",
    ),
    "read after the region": _image(
        """
    Light L[2];
    vec3 c = vec3(0.1);
    if (iTime >= 0.0) {
        if (fragCoord.x >= 40.0) { fragColor = vec4(c, 1.0); return; }
        L[0] = Light(vec3(1.0, 2.0, 3.0), 0.5 + 0.5 * sin(iTime));
        L[1] = Light(vec3(-1.0, 2.0, 3.0), 1.0);
        for (int k = 0; k < 2; k++) {
            c += 0.1 * float(k) * normalize(vec3(fragCoord * 0.01, 1.0));
        }
    }
    for (int k = 0; k < 2; k++) {
        c += L[k].color * normalize(L[k].pos - vec3(fragCoord * 0.01, 1.0));
    }
    fragColor = vec4(c, 1.0);""",
        "struct Light { vec3 pos; float color; };\n",
    ),
}


@pytest.mark.parametrize("name", sorted(LIGHTS_LEFT_BEHIND))
def test_a_compacted_region_leaves_uniform_values_one_value(make_shader, monkeypatch, name):
    from glslcheck.backends.numpy_engine.runtime_values import Struct, lanes_of

    prog = P.compile_numpy(make_shader(LIGHTS_LEFT_BEHIND[name]))
    prog.parallel, prog.threads = "threads", 1
    real = P.LaneHelpers.scatter
    back: list = []  # per compacted region: the structs it put back

    def scatter(self, S, idx, rec, values, *rest):
        parent, out = real(self, S, idx, rec, values, *rest)
        back.append([v for v in out if isinstance(v, Struct)])
        return parent, out

    monkeypatch.setattr(P.LaneHelpers, "scatter", scatter)
    prog.render(size=(128, 64), time=0.7)
    if name == "declared before a branch":
        assert back == [[]]  # the one region, compacted; L is dead after it: left as it is
    else:
        # the code after the return (in the uniform `if`'s arm, then after the `if`): L is put
        # back as one value for all lanes
        assert len(back) == (2 if name == "read after the region" else 1)
        assert all(len(b) == 1 and lanes_of(b[0]) == 1 for b in back)


@pytest.mark.parametrize("name", sorted(LIGHTS_LEFT_BEHIND) + sorted(SAME_WITH_MASKS))
def test_values_left_in_place_change_no_pixel(gl, make_shader, monkeypatch, name):
    """Against the same module with every value put back into the lanes, at a size where the
    regions are compacted, and against llvmpipe."""
    from glslcheck.backends.gl import compile_gl
    from glslcheck.backends.numpy_engine.transpile import Transpiler
    from glslcheck.verification.compare import compare

    shader = make_shader({**LIGHTS_LEFT_BEHIND, **SAME_WITH_MASKS}[name])
    fast = P.compile_numpy(shader).render(size=(128, 64), time=0.8)
    monkeypatch.setattr(Transpiler, "_region_names", lambda self, used, node: (used, [], []))
    slow = P.compile_numpy(shader).render(size=(128, 64), time=0.8)
    np.testing.assert_array_equal(fast, slow)
    if name in LIGHTS_LEFT_BEHIND:
        c = compare(fast, compile_gl(shader, gl).render(size=(128, 64), time=0.8))
        assert c.match, (c.max_abs_error, c.mismatched_pixels)
