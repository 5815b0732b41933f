"""A generated module's text is the same in every process: numba's cache and the tier record
are keyed by a hash of it, so a text that followed Python's string hashing (a set's order)
would miss the cache in a later process and compile again."""

from __future__ import annotations

import os
import subprocess
import sys

# `mix` calls whose components take different flrp formulas (nir_fold.mix_form: x a constant 1
# -> "one", y a constant -1 -> "strict", else "fast"), each formula written once: the order
# they are written in must not follow the hash seed
SHADER = """
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 p = fragCoord / iResolution.xy;
    vec3 q = vec3(p, p.x * p.y);
    vec3 a = mix(vec3(1.0, 5.0, 7.0), q, p.x * 0.5);
    vec3 b = mix(q.zyx, vec3(-1.0, 2.0, 3.0), p.y);
    fragColor = vec4(a + b, 1.0);
}
"""

# the compiled engine's modules (per pixel, lockstep of 8) and the NumPy backend's
GENERATE = """
import hashlib, sys
from glslcheck.shadertoy.sources import load_shader
from glslcheck.backends.compiled_engine.engine import generate
from glslcheck.backends.numpy_engine.transpile.module import transpile_shader
for path in sys.argv[1:]:
    shader = load_shader(path)
    texts = [generate(shader, lanes=lanes)[0] for lanes in (0, 8)]
    texts.append(transpile_shader(shader).source)
    print(path, [hashlib.sha256(t.encode()).hexdigest() for t in texts])
"""
LAB = os.path.join(os.path.dirname(__file__), "..", "..", "lab_shaders", "07_final")


def _texts(paths: list[str], seed: int) -> str:
    env = {**os.environ, "PYTHONHASHSEED": str(seed)}
    done = subprocess.run(
        [sys.executable, "-c", GENERATE, *paths],
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_the_module_text_does_not_follow_the_hash_seed(numba, tmp_path):
    path = tmp_path / "mixed_forms.glsl"
    path.write_text(SHADER)
    # eight seeds: two formulas of a set come out in either order about half the time each
    seen = {_texts([str(path), LAB], seed) for seed in range(8)}
    assert len(seen) == 1, f"{len(seen)} different module texts over 8 hash seeds"
