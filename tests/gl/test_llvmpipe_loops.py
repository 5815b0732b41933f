"""llvmpipe's loop limiter, emulated when verifying, and Shadertoy's renamed uniform.

llvmpipe stops loops once an invocation has made 65,535 loop passes in all (one budget shared by
every loop, gallivm LP_MAX_TGSI_LOOP_ITERATIONS); `glslcheck verify` makes the NumPy side do the
same and says so. Rendering alone (`NumpyProgram.loop_limit` None) runs loops to their end, as a
GPU does. Pass counts below were measured on llvmpipe (Mesa 22.3.6).
"""

from __future__ import annotations

import numpy as np
import pytest

from glslcheck.base.diagnostics import GlslError
from glslcheck.verification.verify import compile_backend, llvmpipe_loop_limit, verify_frames

SUM_70000 = """
void mainImage(out vec4 c, in vec2 p) {
    float s = 0.0;
    int n = 70000 + int(p.x * 0.0);
    for (int i = 0; i < n; i++) s += 1.0 / 70000.0;
    c = vec4(s, 0.0, 0.0, 1.0);
}"""

# counts per loop, as integers in the colour channels
COUNTS = """
void mainImage(out vec4 c, in vec2 p) {
    int n = 40000 + int(p.x * 0.0);
    int k = 0, m = 0, q = 0, jj = 0;
    for (int i = 0; i < n; i++) k++;
    for (int i = 0; i < n; i++) m++;
    for (int j = 0; j < 100 + int(p.y * 0.0); j++) { jj++; for (int i = 0; i < n / 40; i++) q++; }
    c = vec4(float(k), float(m), float(q), float(jj));
}"""


def test_a_70000_pass_loop_stops_where_llvmpipe_stops_it(llvmpipe, make_shader):
    shader = make_shader(SUM_70000)
    numpy, gl_prog = compile_backend(shader, "numpy"), compile_backend(shader, "gl")
    assert numpy.render(size=(2, 2))[0, 0, 0] == pytest.approx(1.0, abs=1e-3)  # a GPU's answer
    (result,) = verify_frames(shader, size=(4, 2), programs=[numpy, gl_prog], keep_images=True)
    assert result.match
    np.testing.assert_array_equal(result.numpy_image, result.gl_image)  # 0.93665314 on both
    assert result.numpy_image[0, 0, 0] == pytest.approx(65535 / 70000, abs=1e-3)  # float32 sum
    assert (
        len(result.notes) == 1 and "Image.glsl:5" in result.notes[0] and "65,535" in result.notes[0]
    )


def test_the_budget_is_shared_by_sequential_and_nested_loops(llvmpipe, make_shader):
    shader = make_shader(COUNTS)
    numpy, gl_prog = compile_backend(shader, "numpy"), compile_backend(shader, "gl")
    llvmpipe_loop_limit(numpy)
    got_gl = gl_prog.render(size=(2, 2))[0, 0]
    got_np = numpy.render(size=(2, 2))[0, 0]
    # llvmpipe: 40,000 then 25,534 (the first loop's exit pass counts too); the nested loops,
    # entered with no budget left, run one pass each
    np.testing.assert_array_equal(got_gl, [40000, 25534, 1, 1])
    np.testing.assert_array_equal(got_np, got_gl)


def test_iglobaltime_is_an_error_with_the_fix(gl, make_shader):
    shader = make_shader("void mainImage(out vec4 c, in vec2 p) { c = vec4(sin(iGlobalTime)); }")
    with pytest.raises(GlslError) as e:
        list(verify_frames(shader, size=(2, 2)))
    (d,) = e.value.diagnostics
    assert d.loc.line == 1 and d.loc.column == 1 + shader.image.text.index("iGlobalTime")
    assert "old name for 'iTime'" in d.message and d.help == "replace 'iGlobalTime' with 'iTime'"


# How each way of leaving a loop spends the budget: the passes a loop ends by its condition,
# by a break, by a do-while's condition, by a continue, by a return from two loops deep, and
# three nested loops (an outer pass is paid when it ends, after its inner loops ran); the
# counting loop after each shows the budget left, to the pass. Bounds from fragCoord * 0.0 keep
# NIR from unrolling or folding the loops (a few-pass loop around a call that returns from two
# loops deep spends a few passes more or less there: NIR's loop unrolling, not copied).
EXITS = {
    "nested": """
    int a = 0, b = 0, c = 0;
    for (int i = 0; i < Z + 99999; i++) { a++;
        for (int j = 0; j < Z + 99999; j++) { b++;
            for (int k = 0; k < Z + 99999; k++) c++; } }
    fragColor = vec4(float(a), float(b), float(c), 1.0);""",
    "break": """
    int a = 0, m = 0;
    for (int i = 0; i < Z + 99999; i++) { a++; if (i == Z + 30000) break; }
    for (int i = 0; i < Z + 99999; i++) m++;
    fragColor = vec4(float(a), float(m), 0.0, 1.0);""",
    "do_while": """
    int a = 0, m = 0;
    do { a++; } while (a < Z + 30000);
    for (int i = 0; i < Z + 99999; i++) m++;
    fragColor = vec4(float(a), float(m), 0.0, 1.0);""",
    "continue": """
    int a = 0, m = 0;
    for (int i = 0; i < Z + 30000; i++) { if (i % 2 == 0) continue; a++; }
    for (int i = 0; i < Z + 99999; i++) m++;
    fragColor = vec4(float(a), float(m), 0.0, 1.0);""",
    "return": """
    int a = found(Z + 300, Z + 40000);
    int m = 0;
    for (int i = 0; i < Z + 99999; i++) m++;
    fragColor = vec4(float(a), float(m), 0.0, 1.0);""",
}
FOUND = """
int found(int n, int at) {
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            if (i * n + j == at) return i * 1000 + j;
    return -1;
}
"""


@pytest.mark.parametrize("name", sorted(EXITS))
def test_every_way_out_of_a_loop_spends_the_budget_as_llvmpipe(llvmpipe, make_shader, name):
    body = EXITS[name]
    shader = make_shader(
        FOUND + "void mainImage(out vec4 fragColor, in vec2 fragCoord) {\n"
        "    int Z = int(fragCoord.x * 0.0);" + body + "\n}"
    )
    numpy, gl_prog = compile_backend(shader, "numpy"), compile_backend(shader, "gl")
    llvmpipe_loop_limit(numpy)
    got_gl = gl_prog.render(size=(2, 2))
    got_np = numpy.render(size=(2, 2))
    np.testing.assert_array_equal(got_np, got_gl)
    assert got_gl[0, 0, 1] > 1 or name == "nested"  # budget was left to count
