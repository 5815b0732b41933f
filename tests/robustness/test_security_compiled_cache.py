"""Security: the compiled engine runs only code it generated, from a cache no other user can write.

Its cache folder holds Python modules it imports and numba's pickled index files. A module
planted under the name a shader's module will have (the name is a hash anyone can compute) must
not run, a module cut short must not break the shader, and a cache folder that other users can
write is not used at all: a private folder serves the run, with a warning that names the folder.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate
from glslcheck.backends.cpu_core import numba_cache
from glslcheck.shadertoy.sources import load_shader

SHADER = (
    "void mainImage(out vec4 fragColor, in vec2 fragCoord) { fragColor = vec4(fragCoord.x / "
    "8.0, 0.25, 0.5, 1.0); }\n"
)


def _render(shader: Path, cache: Path, out: Path) -> subprocess.CompletedProcess:
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache), GLSLCHECK_COMPILED_LANES="0")
    return subprocess.run(
        [
            sys.executable,
            "-m",
            "glslcheck",
            "render",
            str(shader),
            "--backend",
            "compiled",
            "--size",
            "8x4",
            "-o",
            str(out),
        ],
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
    )


def _module_file(shader: Path, cache: Path) -> Path:
    source, path = generate(load_shader(str(shader)))
    return cache / "compiled" / f"m{CompiledProgram(source, path).key}.py"


def _plant(file: Path, marker: Path) -> None:
    file.parent.mkdir(parents=True, exist_ok=True)
    file.write_text(f"open({str(marker)!r}, 'w').close()\nraise SystemExit(0)\n")


@pytest.fixture
def shader(tmp_path: Path) -> Path:
    path = tmp_path / "Image.glsl"
    path.write_text(SHADER)
    return path


def test_a_planted_module_does_not_run(numba, shader, tmp_path):
    cache, marker = tmp_path / "cache", tmp_path / "pwned"
    cache.mkdir(mode=0o700)
    _plant(_module_file(shader, cache), marker)
    done = _render(shader, cache, tmp_path / "out.npy")
    assert done.returncode == 0, done.stderr
    assert not marker.exists(), "the module found in the cache ran"
    image = np.load(tmp_path / "out.npy")
    assert image[0, 0, 1] == np.float32(0.25) and image[0, 3, 0] == np.float32(3.5 / 8.0)


def test_a_module_cut_short_is_written_anew(numba, shader, tmp_path):
    cache = tmp_path / "cache"
    cache.mkdir(mode=0o700)
    assert _render(shader, cache, tmp_path / "first.npy").returncode == 0
    file = _module_file(shader, cache)
    whole = file.read_text()
    file.write_text(whole[: len(whole) // 2])
    done = _render(shader, cache, tmp_path / "second.npy")
    assert done.returncode == 0, done.stderr
    assert file.read_text() == whole
    assert np.array_equal(np.load(tmp_path / "first.npy"), np.load(tmp_path / "second.npy"))


@pytest.mark.skipif(not hasattr(os, "getuid"), reason="file ownership is a POSIX notion")
def test_a_cache_other_users_can_write_is_not_used(numba, shader, tmp_path):
    cache, marker = tmp_path / "shared", tmp_path / "pwned"
    cache.mkdir()
    cache.chmod(0o777)
    file = _module_file(shader, cache)
    _plant(file, marker)
    planted = file.read_text()
    done = _render(shader, cache, tmp_path / "out.npy")
    assert done.returncode == 0, done.stderr
    assert not marker.exists()
    assert f"the numba cache folder {cache} can be written by other users" in done.stderr
    assert file.read_text() == planted and sorted(p.name for p in file.parent.iterdir()) == [
        file.name
    ]


@pytest.mark.skipif(not hasattr(os, "getuid"), reason="file ownership is a POSIX notion")
def test_unsafe_reason(tmp_path):
    own = tmp_path / "own"
    own.mkdir(mode=0o700)
    assert numba_cache.unsafe_reason(str(own)) is None
    own.chmod(0o770)
    assert numba_cache.unsafe_reason(str(own)) == "can be written by other users"
    outer = tmp_path / "outer"
    (outer / "inner").mkdir(parents=True, mode=0o700)
    outer.chmod(0o777)  # anyone could rename inner away and put their own folder there
    assert (
        numba_cache.unsafe_reason(str(outer / "inner"))
        == f"is inside {outer}, which other users can write"
    )
    outer.chmod(0o777 | 0o1000)  # sticky, as /tmp: only the owner renames what is inside
    assert numba_cache.unsafe_reason(str(outer / "inner")) is None
