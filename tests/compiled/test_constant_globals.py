"""Globals no function writes, read from module constants (constant_globals.py): which globals
are frozen, the per-pixel reset left where nothing writes the state, and the frames bit for bit
against the NumPy backend (test_compiled_render's `_compare`) and per pixel against lockstep
(test_lanes' `_same_bits`); a module loaded from numba's cache in a new process gives the bits
of the process that compiled it."""

from __future__ import annotations

import hashlib
import os
import subprocess
import sys

import pytest
from test_compiled_render import _compare
from test_lanes import _same_bits

SHADERS = {
    # a const array of vec3, a plain global nothing writes, const ints, a global initialized
    # from others, and one global mainImage writes
    "written and never written": """
const vec3 kCenters[4] = vec3[4](vec3(-1.5, 0.2, 4.0), vec3(0.5, -0.3, 5.0),
                                 vec3(1.7, 0.6, 6.5), vec3(-0.2, 1.1, 3.3));
float gScale = 0.37;
const int kCount = 4;
int gStride = kCount * 3 - 1;
uint gMask = 0xF0u;
bool gFlip = true;
vec3 gDerived = normalize(kCenters[1] * 1.3 + vec3(0.37));
float gHits = 0.0;
void mainImage(out vec4 c, in vec2 f) {
    vec2 uv = (f - 0.5 * iResolution.xy) / iResolution.y;
    vec3 rd = normalize(vec3(uv, 1.0));
    float best = 1e9;
    for (int i = 0; i < kCount; i++) {
        vec3 oc = -kCenters[i];
        float b = dot(oc, rd);
        float h = b * b - dot(oc, oc) + gScale * gScale;
        if (h > 0.0) { best = min(best, -b - sqrt(h)); gHits += 1.0; }
    }
    int cell = (int(f.x) * gStride) & int(gMask);
    vec3 col = best < 1e8 ? gDerived * 0.5 + 0.5 : vec3(float(cell) / 255.0);
    if (gFlip) col = col.bgr;
    c = vec4(col * (0.5 + 0.25 * gHits), 1.0);
}
""",
    "written only in a function never called": """
float gGain = 0.8;
vec2 gShift = vec2(0.25, -0.5);
void neverCalled() { gGain = 2.0; gShift.x += 1.0; }
void mainImage(out vec4 c, in vec2 f) {
    vec2 uv = f / iResolution.xy + gShift;
    c = vec4(fract(uv * 3.0) * gGain, gGain * 0.5, 1.0);
}
""",
    "arrays of structs": """
struct Light { vec3 pos; vec3 color; float power; };
const Light kLights[3] = Light[3](
    Light(vec3(2.0, 3.0, -1.0), vec3(1.0, 0.8, 0.6), 7.5),
    Light(vec3(-3.0, 1.0, 0.5), vec3(0.3, 0.5, 1.0), 4.25),
    Light(vec3(0.0, -2.0, 2.0), vec3(0.9, 0.2, 0.3), 2.0));
Light gKey = Light(vec3(0.5, 4.0, 1.0), vec3(1.0), 3.0);
void mainImage(out vec4 c, in vec2 f) {
    vec2 uv = (f - 0.5 * iResolution.xy) / iResolution.y;
    vec3 p = vec3(uv, 0.0), n = normalize(vec3(uv, 1.0));
    vec3 col = vec3(0.02);
    for (int i = 0; i < 3; i++) {
        vec3 l = kLights[i].pos - p;
        float d = length(l);
        col += kLights[i].color * kLights[i].power * max(dot(n, l / d), 0.0) / (d * d);
    }
    gKey.power *= 0.5;  // a global that is written: state, reset for every pixel
    col += gKey.color * gKey.power * max(dot(n, normalize(gKey.pos - p)), 0.0) * 0.1;
    c = vec4(col, 1.0);
}
""",
    # more than 64 scalars: a state array read at a run-time index (values.SMALL_ARRAY)
    "a large table at a run-time index": """
const float kTable[72] = float[72]("""
    + ", ".join(f"{(k * 37 % 101) / 101.0:.6f}" for k in range(72))
    + """);
float gOffset = kTable[5] * 2.0;
void mainImage(out vec4 c, in vec2 f) {
    int i = int(f.x + f.y * 3.0) % 72;
    c = vec4(kTable[i], kTable[(i + 7) % 72] + gOffset, 0.25, 1.0);
}
""",
    # built-in calls of constants in initializers (computed by the runtime's sin, pow, sqrt
    # when the module loads), a matrix, and a global initialized from them
    "computed by built-in calls": """
const float kAngle = 0.6;
const mat2 kRot = mat2(cos(kAngle), sin(kAngle), -sin(kAngle), cos(kAngle));
const vec3 kTint = pow(vec3(0.3, 0.55, 0.8), vec3(2.2)) * sqrt(2.0);
vec3 gGlow = normalize(kTint) * exp2(-1.5) + kRot[1].xyx;
void mainImage(out vec4 c, in vec2 f) {
    vec2 uv = kRot * (f / iResolution.xy - 0.5);
    c = vec4(gGlow * (0.5 + 0.5 * sin(uv.x * 9.0 + kTint.y)) + kTint * uv.y, 1.0);
}
""",
}

# the globals each shader reads from module constants (the others are per-pixel state)
FROZEN = {
    "written and never written": {"kCenters", "gScale", "gStride", "gMask", "gFlip", "gDerived"},
    "written only in a function never called": {"gGain", "gShift"},
    "arrays of structs": {"kLights"},
    "a large table at a run-time index": {"kTable", "gOffset"},
    "computed by built-in calls": {"kRot", "kTint", "gGlow"},
}


def _frozen_names(shader) -> set[str]:
    from glslcheck.backends.compiled_engine.constant_globals import frozen_globals
    from glslcheck.backends.cpu_core.facts import Facts
    from glslcheck.frontend.parser import parse_shader
    from glslcheck.semantics import check

    model = check(parse_shader(shader, "Image"))
    frozen = frozen_globals(model, Facts(model, list(model.reachable_functions())))
    return {s.name for s in model.globals if id(s) in frozen}


@pytest.mark.parametrize("name", sorted(SHADERS))
def test_frozen_globals(make_shader, name):
    """(`const` scalars of literals are module constants already, literal_global: frozen too,
    since nothing writes them, and not counted here.)"""
    got = _frozen_names(make_shader(SHADERS[name]))
    assert got - {"kCount", "kAngle"} == FROZEN[name]


@pytest.mark.parametrize("name", sorted(SHADERS))
def test_bit_for_bit(numba, make_shader, name):
    shader = make_shader(SHADERS[name])
    _compare(shader)
    _compare(shader, time=2.75)
    _same_bits(shader, 8)


def test_the_module_reads_constants_and_resets_only_written_state(numba, make_shader):
    from glslcheck.backends.compiled_engine.engine import generate

    read_only, _ = generate(
        make_shader(SHADERS["written only in a function never called"]), lanes=0
    )
    written, _ = generate(make_shader(SHADERS["arrays of structs"]), lanes=0)
    assert "GCF[" in read_only and "GCF[" in written
    assert "aset(gf, 0, gtf)" not in read_only  # no function writes the state: no reset
    assert "aset(gf, 0, gtf)" in written  # gKey.power is written in every pixel
    lanes, _ = generate(make_shader(SHADERS["written only in a function never called"]), lanes=8)
    assert "LANES = 8" in lanes and "aset(gf__0, 0, gtf)" not in lanes


CACHED = """
import hashlib, sys
from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate
from glslcheck.shadertoy.sources import load_shader
source, where = generate(load_shader(sys.argv[1]), lanes=int(sys.argv[2]))
program = CompiledProgram(source, where)
frame = program.render(size=(64, 36), time=1.3)
print(program.cold, hashlib.sha256(frame.tobytes()).hexdigest())
"""


@pytest.mark.parametrize("lanes", [0, 8])
def test_a_module_from_numbas_cache_gives_the_same_bits(numba, tmp_path, lanes):
    """numba keeps a global array's values in the machine code it caches, and does not look at
    them when it loads it: the frozen arrays are the module's own initializer's values, which
    the module's text (its cache key) decides. A second process loads the machine code (not
    cold) and renders the first one's bits, which are this process's."""
    import glslcheck
    from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate
    from glslcheck.shadertoy.sources import load_shader

    lab = os.path.join(os.path.dirname(__file__), "..", "..", "lab_shaders", "06_multiple_lights")
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path), XDG_CACHE_HOME=str(tmp_path))
    root = os.path.dirname(os.path.dirname(glslcheck.__file__))  # this checkout's glslcheck
    env["PYTHONPATH"] = os.pathsep.join(p for p in (root, env.get("PYTHONPATH")) if p)
    runs = [
        subprocess.run(
            [sys.executable, "-c", CACHED, lab, str(lanes)],
            env=env,
            capture_output=True,
            text=True,
            check=True,
        ).stdout.split()
        for _ in range(2)
    ]
    assert [r[0] for r in runs] == ["True", "False"]  # compiled, then loaded from the cache
    source, where = generate(load_shader(lab), lanes=lanes)
    here = CompiledProgram(source, where).render(size=(64, 36), time=1.3)
    assert runs[0][1] == runs[1][1] == hashlib.sha256(here.tobytes()).hexdigest()


# calls the same in every pixel (constant_globals.load_time_call): computed when the module
# loads, by init_globals; and calls that are not
LOAD_TIME = """
const float kTilt = 0.35;
mat2 rot(float a) { return mat2(cos(a), sin(a), -sin(a), cos(a)); }
vec2 offset(float a, vec2 b) { return b * exp2(a) + vec2(sin(a)); }
float wobble(float a) { return sin(a + iTime); }
float summed(float a) { float s = 0.0; for (int i = 0; i < 3; i++) s += a * float(i); return s; }
float scene(vec3 p) {
    p.xz = rot(0.7) * p.xz;                   // frozen
    p.yz = rot(-kTilt) * p.yz;                // frozen: a const global argument
    p.xy += offset(-1.25, vec2(0.5, -0.25));  // frozen: two arguments
    p.x += wobble(0.3);                       // once a frame: it reads iTime
    p.x += wobble(p.y);                       // not: an argument per pixel
    p.y += summed(0.2);                       // not: it runs a loop
    p.z *= rot(p.x)[0].x;                     // not: an argument per pixel
    p.y *= rot(iTime * 0.5)[1].y;             // once a frame: an argument of iTime
    return length(p) - 1.0;
}
void mainImage(out vec4 c, in vec2 f) {
    vec2 uv = (f - 0.5 * iResolution.xy) / iResolution.y;
    vec3 ro = vec3(0.0, 0.0, -3.0), rd = normalize(vec3(uv, 1.0));
    float t = 0.0;
    for (int i = 0; i < 40; i++) { float d = scene(ro + rd * t); if (d < 1e-3) break; t += d; }
    c = vec4(vec3(exp(-0.3 * t)) * (rot(0.7) * vec2(1.0, 0.5)).xyx, 1.0);
}
"""


def test_constant_calls_are_computed_at_load(numba, make_shader):
    """rot(0.7) twice (one value), rot(-kTilt) and offset(-1.25, ...) run in init_globals and
    are read from the module's constants; wobble(0.3) and rot(iTime * 0.5), which read iTime,
    run there too and are read from the frame's state; the calls that run a loop or take a
    per-pixel argument stay where they are. Lockstep moves the load's only. The frames are the
    bits of the NumPy backend and of lockstep."""
    from glslcheck.backends.compiled_engine.engine import generate

    shader = make_shader(LOAD_TIME)
    source, _ = generate(shader, lanes=0)
    init = source[source.index("def init_globals") : source.index("def shade")]
    scene = source[source.index("def f_scene") : source.index("def f_mainImage")]
    assert init.count("= f_rot") == 3 and init.count("= f_offset") == 1
    assert init.count("= f_wobble") == 1 and "uf[" in init
    assert "f_rot" not in scene.replace("f_rot(", "") and scene.count("f_rot(") == 1
    assert scene.count("f_wobble(") == 1 and "f_summed" in scene and "f_offset" not in scene
    assert "GCF[" in scene and "gf[" in scene  # the load's values, and the frame's
    _compare(shader)
    _compare(shader, time=2.75)
    _same_bits(shader, 8)
    lanes, _ = generate(shader, lanes=8)
    assert "LANES = 8" in lanes
    init8 = lanes[lanes.index("def init_globals") :]
    init8 = init8[: init8.index("\n@")]
    # lockstep computes a value of the frame once a block already: only the load's are moved
    assert init8.count("= f_rot") == 2 and init8.count("(True, True") == 3
    assert "f_wobble" not in init8
