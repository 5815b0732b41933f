"""`switch` and `discard` in the compiled engine, against the NumPy backend bit for bit (per
pixel: test_compiled_render's `_compare`) and the per-pixel module against lockstep
(test_lanes' `_same_bits`). The shaders take every path: fall-through, `default` first, in the
middle and absent, `break` in a nested `if`, `continue` and `return` inside a case, a switch in
a loop and a loop in a switch, varying and uniform selectors, int and uint; `discard` in
mainImage and in a called function, under varying and uniform conditions, in loops.
"""

from __future__ import annotations

import pytest
from test_compiled_render import _compare
from test_lanes import _same_bits

SWITCHES = {
    "fall-through and default in the middle": """
void mainImage(out vec4 c, in vec2 f) {
    float v = 0.0;
    switch (int(f.x) % 6) {
        case 0: v += 0.1;
        case 1: v += 0.2; break;
        default: v += 0.05;
        case 3: v += 0.3;
        case 4: { if (f.y > 10.0) break; v += 0.4; }
    }
    c = vec4(v, 0.0, 0.0, 1.0);
}
""",
    "in a loop, with continue and return": """
float pick(int k, float y) {
    switch (k) {
        case 0: return y * 0.01;
        case 2: if (y > 12.0) return 0.5;
        default: break;
    }
    return 0.25;
}
void mainImage(out vec4 c, in vec2 f) {
    float acc = 0.0;
    for (int i = 0; i < 5; i++) {
        switch ((int(f.x) + i) % 4) {
            case 1: acc += 0.125; continue;
            case 2:
                for (int j = 0; j < 3; j++) { if (j == i) break; acc += 0.01; }
                break;
            case 3: acc -= 0.05;
        }
        acc += pick(i % 3, f.y);
    }
    c = vec4(acc, 0.0, 0.0, 1.0);
}
""",
    "uniform and uint selectors, no default": """
void mainImage(out vec4 c, in vec2 f) {
    vec3 col = vec3(0.1);
    switch (int(iTime) % 3) {
        case 0: col.r = 0.9; break;
        case 1: col.g = sin(iTime);
        case 2: col.b = 0.7;
    }
    switch (uint(f.y) % 3u) {
        case 1u: col *= 0.5; break;
        case 2u: col += 0.25; break;
    }
    c = vec4(col, 1.0);
}
""",
}

DISCARDS = {
    "in mainImage": """
void mainImage(out vec4 c, in vec2 f) {
    c = vec4(f / iResolution.xy, 0.5, 1.0);
    if (length(f - 0.5 * iResolution.xy) < 7.0) discard;
    c.b = 0.75;
}
""",
    "in a called function and a loop": """
float shade(vec2 p) {
    float s = 0.0;
    for (int i = 0; i < 4; i++) {
        s += 0.2;
        if (p.x + float(i) > 30.0) discard;
    }
    return s;
}
void mainImage(out vec4 c, in vec2 f) {
    float v = 0.1;
    if (f.y > 6.0) v = shade(f);
    c = vec4(v, f.y * 0.01, 0.0, 1.0);
}
""",
    "under a uniform condition": """
void mainImage(out vec4 c, in vec2 f) {
    if (iTime > 1.0) discard;
    c = vec4(0.3, 0.2, 0.1, 1.0);
}
""",
}


@pytest.mark.parametrize("name", sorted(SWITCHES))
def test_switch_bit_for_bit(numba, make_shader, name):
    shader = make_shader(SWITCHES[name])
    _compare(shader)
    _compare(shader, time=2.5)
    _same_bits(shader, 8)


@pytest.mark.parametrize("name", sorted(DISCARDS))
def test_discard_bit_for_bit(numba, make_shader, name):
    shader = make_shader(DISCARDS[name])
    _compare(shader)
    _compare(shader, time=0.5)
    _same_bits(shader, 8)


def test_discarded_samples_average_as_the_numpy_backends(numba, make_shader):
    """With several samples a pixel, a discarded sample counts as the clear colour."""

    import glslcheck
    from glslcheck.backends.compiled_engine.engine import compile_compiled

    shader = make_shader(DISCARDS["in mainImage"])
    got = compile_compiled(shader).render(size=(40, 24), samples=4)
    want = glslcheck.compile(shader, backend="numpy").render(size=(40, 24), samples=4)
    assert got.tobytes() == want.tobytes()
    assert ((want[..., 3] > 0.0) & (want[..., 3] < 1.0)).any()  # partly discarded pixels
