"""numba_linking: a generated module's callees are linked into its entries, not optimized nor
compiled to machine code of their own, and the module renders the bits numba's own finalize
gives; numba's cache holds the entries, which a new process loads without compiling anything.

Each test has a numba cache of its own (a temporary $NUMBA_CACHE_DIR): every module is compiled
cold here, and none reaches another test or the user's cache.
"""

from __future__ import annotations

import hashlib
import json
import os
import subprocess
import sys

import numpy as np
import pytest

from glslcheck.backends.compiled_engine import engine, numba_linking, numba_patches

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SIZE = (24, 16)
TIMES = (0.0, 0.37, 1.9, 7.3, 31.4, 123.25)  # spread iTime values: other branches, other rings

# a chain of calls below mainImage (ring -> band -> mainImage), a global initialized by a call
# (globals_template's callee), a loop and a branch
SHADER = """
float k = 0.5 + 0.25 * cos(1.5);
float band(float d, float w) { return smoothstep(w, w - 0.02, abs(d)); }
float ring(vec2 p, float r) {
    float s = 0.0;
    for (int i = 0; i < 3; i++) { s += band(length(p) - r * float(i + 1) / 3.0, 0.05); }
    return s;
}
void mainImage(out vec4 c, in vec2 f) {
    vec2 p = (f - 0.5 * iResolution.xy) / iResolution.y;
    float v = ring(p, k + 0.1 * sin(iTime));
    if (p.x > 0.0) { v = 1.0 - v; }
    c = vec4(v, fract(iTime * p.y), p.x * k, %s);
}
"""

CHILD = r"""
import hashlib, json, sys
from glslcheck.backends.compiled_engine import engine
from glslcheck.backends.compiled_engine.numba_linking import MODULE_PREFIX

source = open(sys.argv[1], encoding="utf-8").read()
prog = engine.CompiledProgram(source, "Image.glsl")
mod = prog.load(bounded=False)
size, times = tuple(json.loads(sys.argv[2])), json.loads(sys.argv[3])
frames = [prog.render(size=size, time=t, frame=k) for k, t in enumerate(times)]
jitted = [v for v in vars(mod).values() if hasattr(v, "overloads")]
mine = [f for f in jitted if f.__module__.startswith(MODULE_PREFIX)]
print(json.dumps(dict(
    cold=prog.cold,
    misses=sorted(f.__name__ for f in mine if f.stats.cache_misses),
    hits=sorted(f.__name__ for f in mine if f.stats.cache_hits),
    compiled=sorted(f.__name__ for f in mine if f.overloads),
    frames=hashlib.sha256(b"".join(f.tobytes() for f in frames)).hexdigest(),
)))
"""


@pytest.fixture
def own_cache(monkeypatch, tmp_path):
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "numba"))
    return tmp_path


def _functions(mod) -> dict:
    """The module's jitted functions by name -> their compiled libraries."""
    return {
        name: [cres.library for cres in obj.overloads.values()]
        for name, obj in vars(mod).items()
        if hasattr(obj, "overloads") and obj.__module__ == mod.__name__
    }


def _frames(prog) -> list[np.ndarray]:
    return [prog.render(size=SIZE, time=t, frame=k) for k, t in enumerate(TIMES)]


@pytest.mark.parametrize("lanes", [0, 8])
def test_callees_are_linked_only_and_the_frames_are_numbas_own(
    numba, make_shader, own_cache, lanes
):
    source, _ = engine.generate(make_shader(SHADER % f"{lanes}.0"), lanes=lanes)
    linked = engine.CompiledProgram(source, "Image.glsl")
    linked.load(bounded=False)
    assert linked.cold
    if not numba_patches.install(numba_linking):
        pytest.skip("numba_linking is not checked against this numba (numba's own runs)")
    # the same program compiled by numba's own finalize: the reference (another module, by a
    # comment: a module is loaded once per process)
    own = engine.CompiledProgram(source + "\n# numba's own finalize\n", "Image.glsl")
    with numba_linking.numba_own():
        own.load(bounded=False)
    assert own.cold

    entries = {"render_rows", "globals_template"}
    compiled = {name: libs for name, libs in _functions(linked.mod).items() if libs}
    assert entries < set(compiled)  # and callees, which the entries' calls compiled
    for name, libraries in compiled.items():
        assert all(numba_linking.linked_only(lib) != (name in entries) for lib in libraries), name
    for name, libraries in _functions(own.mod).items():
        assert not any(numba_linking.linked_only(lib) for lib in libraries), name

    for k, (got, want) in enumerate(zip(_frames(linked), _frames(own))):
        assert got.tobytes() == want.tobytes(), f"iTime {TIMES[k]}: the frames differ"


def test_a_cached_module_loads_in_a_new_process_without_compiling(numba, make_shader, own_cache):
    source, _ = engine.generate(make_shader(SHADER % "0.75"), lanes=8)
    prog = engine.CompiledProgram(source, "Image.glsl")
    prog.load(bounded=False)
    assert prog.cold
    want = hashlib.sha256(b"".join(f.tobytes() for f in _frames(prog))).hexdigest()
    file = own_cache / "module.py"
    file.write_text(source, encoding="utf-8")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([ROOT, os.environ.get("PYTHONPATH", "")]))
    out = subprocess.run(
        [sys.executable, "-c", CHILD, str(file), json.dumps(SIZE), json.dumps(TIMES)],
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
        check=True,
    )
    got = json.loads(out.stdout.strip().splitlines()[-1])
    assert got["cold"] is False
    assert got["misses"] == []  # (the scalar runtime's functions are its own modules')
    assert got["hits"] == ["globals_template", "render_rows"]  # loaded from the cache
    assert got["compiled"] == ["globals_template", "render_rows"]  # no callee compiled
    assert got["frames"] == want


def _entry_increfs(source: str) -> int:
    """NRT_incref calls in render_rows' own code (callees inlined into it, not the functions it
    links in), compiled here: numba inspects no code loaded from its cache."""
    prog = engine.CompiledProgram(source, "Image.glsl")
    prog.load(bounded=False)
    assert prog.cold
    (ir,) = prog.mod.render_rows.inspect_llvm().values()
    count, inside = 0, False
    for line in ir.splitlines():
        if line.startswith("define "):
            inside = "render_rows" in line and "linkonce" not in line and "cpython" not in line
            inside = inside and not line.split("@", 1)[1].startswith("cfunc")
        elif inside and "call void @NRT_incref(" in line:
            count += 1
    return count


def test_the_pixel_loop_counts_no_references(numba, own_cache):
    # numba counts each array passed to a call (an atomic add and subtract): a block of 8 lanes
    # passes shade 32 state arrays where a pixel passes 4, and render_rows' code counts as many
    # references for one as for the other (its copies of the state, made once a band)
    from glslcheck.shadertoy.sources import load_shader

    shader = load_shader(os.path.join(ROOT, "lab_shaders", "05_blinn_phong"))
    counts = [_entry_increfs(engine.generate(shader, lanes=w)[0]) for w in (0, 8)]
    assert counts[0] == counts[1]
