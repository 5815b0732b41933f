"""llvmpipe's loop limiter in the compiled engine, against the NumPy backend, bit for bit.

llvmpipe stops every loop of an invocation once it has made 65,535 passes in all (one budget
shared by all loops; verify makes both CPU engines stop as it does: `loop_limit`). The NumPy
backend's count (LaneHelpers.tick) is the one measured against the driver; the compiled engine
must spend the budget pass for pass as it does: the pass that ends a loop on its condition, a
`break`, a do-while's false condition and a return from inside loops each cost what they cost
there. A small budget makes it run out at many different places of the same program, so a pass
counted once too often or too rarely shows as different pixels. The loops' pass counts are the
same in every pixel (the NumPy backend counts a tile's passes, llvmpipe an 8-lane group's,
the compiled engine a pixel's or a block's: for loops that diverge they may stop at another
pass), their values differ by pixel.
"""

from __future__ import annotations

import time

import pytest
from image_bits import assert_same, frame_text
from test_compiled_render import SIZE

import glslcheck
from glslcheck.verification.verify import LLVMPIPE_LOOP_LIMIT

EVERY_EXIT = """
float partial(vec2 p, int stop) {
    float s = 0.0;
    for (int i = 0; i < 30; i++) {
        s += sin(p.x * float(i + 1));
        for (int j = 0; j < 4; j++) {
            if (i * 4 + j == stop) return s;  // leaves two loops
            s += p.y * 0.001;
        }
    }
    return s;
}

void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 p = fragCoord / iResolution.xy;
    float a = 0.0;
    for (int k = 0; k < 12; k++) {
        a += partial(p + float(k), 37 + k);
        int j = 0;
        do { a += p.y * 0.01; j++; } while (j < 7);
        for (int m = 0; m < 50; m++) {
            if (m == 13) break;
            if (m % 3 == 0) continue;
            a -= p.x * 0.001;
        }
        while (a > 1e6) { a -= 1.0; }  // no pass: its condition still costs one
        int n = 0;
        do { n++; if (n == 3) continue; a += 0.5 * p.x; } while (n < 5);
    }
    fragColor = vec4(a, p, 1.0);
}
"""

# budgets that run out in the first loop, inside the function's nested loops, in a do-while,
# at a break, and never (65,535: llvmpipe's own)
BUDGETS = (1, 2, 37, 50, 141, 400, 777, 1100, LLVMPIPE_LOOP_LIMIT)


@pytest.fixture(scope="module")
def programs(numba):
    from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate
    from glslcheck.base.diagnostics import register_source
    from glslcheck.shadertoy.sources import Shader, Source

    register_source("Image.glsl", EVERY_EXIT)
    shader = Shader(root="<test>")
    shader.tabs["Image"] = Source("Image.glsl", EVERY_EXIT, "Image")
    numpy = glslcheck.compile(shader, backend="numpy").impl
    compiled = {}
    for lanes in (0, 8):
        source, path = generate(shader, lanes=lanes, budget=True)
        if lanes:
            assert "LANES_FALLBACK" not in source
        compiled[lanes] = CompiledProgram(source, path)
    return _Memo(numpy), compiled, shader


class _Memo:
    """The NumPy program's render and loops per budget, rendered once (its frame cache would
    return the image of a second render without the loops)."""

    def __init__(self, prog) -> None:
        self.prog = prog
        self.seen: dict = {}

    @property
    def loop_limit(self):
        return self.prog.loop_limit

    @loop_limit.setter
    def loop_limit(self, limit) -> None:
        self.prog.loop_limit = limit

    def render(self, **kw):
        key = (self.prog.loop_limit, tuple(sorted(kw.items())))
        if key not in self.seen:
            self.seen[key] = (self.prog.render(**kw), self.prog.limited_loops())
        self.last = self.seen[key][1]
        return self.seen[key][0]

    def limited_loops(self):
        return self.last


def _frame(limit) -> str:
    return f"{frame_text(SIZE, time=0.5)}, loop limit {limit}"


def _render(prog, limit):
    prog.loop_limit = limit
    image = prog.render(size=SIZE, time=0.5)
    return image, prog.limited_loops()


@pytest.mark.parametrize("lanes", [0, 8])
@pytest.mark.parametrize("budget", BUDGETS)
def test_budget_spent_as_the_numpy_backend_spends_it(programs, budget, lanes):
    numpy, compiled, _ = programs
    want, want_loops = _render(numpy, budget)
    got, got_loops = _render(compiled[lanes], budget)
    assert_same(got, want, what=_frame(budget), names=(f"lanes {lanes}", "numpy"))
    assert got_loops == want_loops
    if budget == LLVMPIPE_LOOP_LIMIT:
        assert got_loops == []  # the program's 2,000-odd passes never reach llvmpipe's limit
    else:
        assert got_loops  # the budget stopped some loop


def test_no_limit_renders_every_pass(programs):
    """Without the limiter (render, not verify) no loop stops early: the same image as a budget
    the program never reaches, and as a module made without the budget (the one `render`
    compiles: it neither counts passes nor passes `lc`)."""
    from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate

    numpy, compiled, shader = programs
    want, _ = _render(numpy, None)
    for lanes, prog in compiled.items():
        got, loops = _render(prog, None)
        assert_same(got, want, what=_frame(None), names=(f"lanes {lanes}", "numpy"))
        assert loops == []
        limited, _ = _render(prog, LLVMPIPE_LOOP_LIMIT)
        limit = _frame(LLVMPIPE_LOOP_LIMIT)
        assert_same(got, limited, what=limit, names=("no limit", "llvmpipe's limit"))
        source, path = generate(shader, lanes=lanes)
        assert "tick(" not in source and "BUDGET = False" in source
        image = CompiledProgram(source, path).render(size=SIZE, time=0.5)
        assert_same(image, want, what=_frame(None), names=("the module without a budget", "numpy"))


NESTED = """void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    float s = 0.0;
    for (int i = 0; i < 99999; i++) {
        for (int j = 0; j < 99999; j++) {
            for (int k = 0; k < 99999; k++) {
                s += sin(float(i + j + k) + fragCoord.x);
            }
        }
    }
    fragColor = vec4(s, 0.0, 0.0, 1.0);
}
"""


@pytest.mark.parametrize("lanes", [0, 8])
def test_three_nested_runaway_loops_stop_as_llvmpipe_does(numba, make_shader, lanes):
    """10**15 passes without the limiter; llvmpipe's 65,535 per pixel with it, which verify sets
    on both engines: the frame ends (a frame budget turns a regression into an error, not a
    hang), the same pixels as the NumPy backend's, and all three loops are reported."""
    from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate

    shader = make_shader(NESTED)
    numpy = glslcheck.compile(shader, backend="numpy").impl
    source, path = generate(shader, lanes=lanes, budget=True)
    compiled = CompiledProgram(source, path)
    compiled.loop_limit = LLVMPIPE_LOOP_LIMIT  # (the module with the budget)
    compiled.load()  # numba's compile is not the frame's time
    compiled.frame_seconds = numpy.frame_seconds = 120.0
    want, want_loops = _render(numpy, LLVMPIPE_LOOP_LIMIT)
    t0 = time.perf_counter()
    got, got_loops = _render(compiled, LLVMPIPE_LOOP_LIMIT)
    seconds = time.perf_counter() - t0
    what = f"NESTED at {frame_text(SIZE, time=0.5)}, loop limit {LLVMPIPE_LOOP_LIMIT}"
    assert_same(got, want, what=what, names=(f"lanes {lanes}", "numpy"))
    assert [line for _, line in got_loops] == [4, 5, 6] == [line for _, line in want_loops]
    assert seconds < 120.0
