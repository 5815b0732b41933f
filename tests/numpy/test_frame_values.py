"""Values the same in every tile, computed once a frame (transpile/frame_values.py).

Each shader is rendered in several tiles with frame values on and with them off (the code that
computes everything in every tile); the images must be bit-identical. The generated code shows
which statements became frame values, and a counted user function shows how often they ran.
"""

from __future__ import annotations

import os
import pickle

import numpy as np
import pytest

from glslcheck.backends.numpy_engine import tiles
from glslcheck.backends.numpy_engine.program import compile_numpy
from glslcheck.backends.numpy_engine.transpile.statements import Statements

SIZE = (48, 40)  # cut in several tiles by TILE_LANES below
TILE_LANES = 256

# Lights filled by calls at the top of a function that only the hit pixels run, and again
# inside the branch the hit pixels take; the sphere array built before the nearest-hit loop.
LIGHTS = """
struct Light { vec3 pos; vec3 color; float power; };
void initLight(out Light l, in vec3 pos, in vec3 color, in float power) {
    l.pos = pos; l.color = color; l.power = power;
}
vec3 shade(in vec3 p, in vec3 n) {
    Light lights[2];
    initLight(lights[0], vec3(2.0 * cos(iTime), 2.0, 1.0), vec3(1.0, 0.8, 0.6), 3.0);
    initLight(lights[1], vec3(-2.0, 1.0, 2.0 * sin(iTime)), vec3(0.3, 0.5, 1.0), 2.0);
    vec3 c = vec3(0.0);
    for (int i = 0; i < 2; ++i) {
        vec3 l = normalize(lights[i].pos - p);
        c += max(dot(n, l), 0.0) * lights[i].color * lights[i].power;
    }
    return c;
}
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 uv = (2.0 * fragCoord - iResolution.xy) / iResolution.y;
    vec3 rd = normalize(vec3(uv, -1.5));
    vec3 ro = vec3(0.0, 0.0, 3.0);
    float b = dot(ro, rd);
    float h = b * b - dot(ro, ro) + 1.0;
    vec3 col = vec3(0.1);
    if (h > 0.0) {
        Light extra[1];
        initLight(extra[0], vec3(0.0, 3.0, 0.0), vec3(0.2), pow(1.5, iTime));
        vec3 p = ro + rd * (-b - sqrt(h));
        col = shade(p, normalize(p)) + extra[0].color * extra[0].power;
    }
    fragColor = vec4(col, 1.0);
}
"""


def _program(make_shader, monkeypatch, text: str, frame_values: bool):
    monkeypatch.setattr(Statements, "FRAME_VALUES", frame_values)
    prog = compile_numpy(make_shader(text))
    prog.threads = 1
    return prog


def _frame_blocks(source: str) -> list[str]:
    """The lines computed once a frame: those between `if _fvN is None:` and its `else:`."""
    lines = source.splitlines()
    found = []
    for i, line in enumerate(lines):
        if "= X.frame(S, " in line:
            indent = len(line) - len(line.lstrip())
            j = i + 2
            while not (lines[j].startswith(" " * indent + "else:")):
                found.append(lines[j].strip())
                j += 1
    return found


def _both(make_shader, monkeypatch, text: str, **render):
    """(image with frame values, image without, the first program) over several tiles."""
    monkeypatch.setattr(tiles, "TILE_LANES", TILE_LANES)
    assert len(tiles.frame_tiles(*SIZE)) > 2
    on = _program(make_shader, monkeypatch, text, True)
    off = _program(make_shader, monkeypatch, text, False)
    assert "X.frame(" not in off.source
    images = []
    for prog in (on, off):
        images.append(np.stack([prog.render(size=SIZE, time=t, **render) for t in (0.0, 1.3, 2.9)]))
    return images[0], images[1], on


def test_lights_built_by_calls_are_frame_values_with_the_same_pixels(make_shader, monkeypatch):
    img, reference, prog = _both(make_shader, monkeypatch, LIGHTS)
    assert np.array_equal(img, reference) and np.isfinite(img).all()
    assert len(np.unique(img.reshape(-1, 4), axis=0)) > 10  # a lit sphere, not a flat frame
    hoisted = _frame_blocks(prog.source)
    # both light arrays (in `shade`, and in the divergent branch of mainImage)
    assert sum("f_initLight(S, None" in line for line in hoisted) == 3


def test_frame_values_run_once_a_frame_not_once_a_tile(make_shader, monkeypatch):
    monkeypatch.setattr(tiles, "TILE_LANES", TILE_LANES)
    calls: dict[bool, int] = {}
    for on in (True, False):
        prog = _program(make_shader, monkeypatch, LIGHTS, on)
        ns = prog.module()
        real = ns["f_initLight"]

        def counted(*args, _real=real, _on=on):
            calls[_on] = calls.get(_on, 0) + 1
            return _real(*args)

        ns["f_initLight"] = counted
        prog.render(size=SIZE, time=0.7)
    # without: three lights in every tile that has a hit pixel; with: three for the frame
    assert calls[False] % 3 == 0 and calls[False] // 3 > 2
    assert calls[True] == 3


@pytest.mark.parametrize(
    "text",
    [
        pytest.param(
            """
            struct L { vec3 pos; float power; };
            void initL(out L l, in vec3 pos, in float power) { l.pos = pos; l.power = power; }
            void mainImage(out vec4 o, in vec2 f) {
                L lights[2];
                initL(lights[0], vec3(f.x * 0.01, 1.0, 2.0), 2.0);
                initL(lights[1], vec3(1.0, f.y * 0.02, 2.0), iTime);
                o = vec4(lights[0].pos + lights[1].pos * lights[1].power, 1.0);
            }
            """,
            id="values-read-fragCoord",
        ),
        pytest.param(
            """
            vec3 at(in float k) { return vec3(gl_FragCoord.xy * 0.01, k); }
            void mainImage(out vec4 o, in vec2 f) {
                vec3 a[2];
                a[0] = at(1.0);
                a[1] = at(iTime);
                o = vec4(a[0] + a[1], 1.0);
            }
            """,
            id="a-call-reading-gl_FragCoord",
        ),
        pytest.param(
            """
            struct L { vec3 pos; float power; };
            void initL(out L l, in vec3 pos, in float power) { l.pos = pos; l.power = power; }
            void mainImage(out vec4 o, in vec2 f) {
                vec3 c = vec3(0.0);
                int n = int(f.x) % 5;
                for (int i = 0; i < n; ++i) {
                    L lights[1];
                    initL(lights[0], vec3(float(i), 1.0, cos(iTime)), 2.0);
                    c += lights[0].pos * lights[0].power;
                }
                o = vec4(c * 0.1, 1.0);
            }
            """,
            id="in-a-loop-whose-count-varies-by-lane",
        ),
        pytest.param(
            """
            float total = 0.0;
            float bump(in float k) { total += k; return k * 2.0; }
            void mainImage(out vec4 o, in vec2 f) {
                float a[2];
                a[0] = bump(1.0);
                a[1] = bump(iTime);
                o = vec4(a[0] + a[1], total, f.x * 0.01, 1.0);
            }
            """,
            id="a-call-writing-a-global",
        ),
        pytest.param(
            """
            float a[2];
            void mainImage(out vec4 o, in vec2 f) {
                vec3 c = vec3(0.1);
                if (f.x > 20.0) {
                    c.x = 0.5;
                    a[0] = cos(iTime);
                }
                o = vec4(c + a[0], 1.0);
            }
            """,
            id="a-global-written-in-a-branch",
        ),
        pytest.param(
            """
            void mainImage(out vec4 o, in vec2 f) {
                vec3 c[2];
                c[0] = vec3(0.2);
                if (f.x > 20.0) {
                    c[0] = vec3(cos(iTime));
                }
                c[1] = c[0] * 2.0;
                o = vec4(c[1], 1.0);
            }
            """,
            id="a-local-written-behind-a-divergent-branch",
        ),
    ],
)
def test_what_varies_or_has_effects_stays_in_every_tile(make_shader, monkeypatch, text):
    img, reference, prog = _both(make_shader, monkeypatch, text)
    assert np.array_equal(img, reference) and np.isfinite(img).all()
    assert "X.frame(" not in prog.source
    assert len(np.unique(img.reshape(-1, 4), axis=0)) > 1  # it does vary across the frame


def test_statistics_and_the_loop_limiter_see_every_tile_run_them(make_shader, monkeypatch):
    monkeypatch.setattr(tiles, "TILE_LANES", TILE_LANES)
    on = _program(make_shader, monkeypatch, LIGHTS, True)
    off = _program(make_shader, monkeypatch, LIGHTS, False)
    stats = []
    for prog in (on, off):
        prog.render(size=SIZE, time=0.4, stats=True)
        stats.append([(r.kind, r.function, r.line, r.lanes) for r in prog.last_stats])
    assert stats[0] == stats[1]
    assert any(kind == "function" and fn == "initLight" and n for kind, fn, _, n in stats[0])
    images = []
    for prog in (on, off):
        prog.loop_limit = 65535
        images.append(prog.render(size=SIZE, time=0.4))
    assert np.array_equal(images[0], images[1])


def test_a_worker_process_computes_its_own(make_shader, monkeypatch):
    from glslcheck.backends.numpy_engine import workers

    if not workers.available():
        if os.environ.get("CI"):
            pytest.fail("worker processes are unavailable on the CI machine (Linux)")
        pytest.skip("worker processes need Linux with memfd_create (this machine: threads only)")
    img, reference, prog = _both(make_shader, monkeypatch, LIGHTS)
    prog.threads = 2
    prog.parallel = "processes"
    prog._cache.clear()
    try:
        got = prog.render(size=SIZE, time=1.3)
    finally:
        workers.shutdown()  # (the next tests start their own, with their settings)
    assert prog.last_parallel == "processes"
    assert np.array_equal(got, reference[1])
    spec = next(iter(prog._specs.values()))
    assert spec.values  # this process's threads filled it (the earlier frames)
    assert pickle.loads(pickle.dumps(spec)).values == {}  # a worker starts afresh
