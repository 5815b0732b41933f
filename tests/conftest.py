"""Shared test fixtures.

`gl` and `glslang` give the two external tools the tests compare against: a headless OpenGL
context (Mesa llvmpipe through EGL) and glslangValidator. When one is missing, the tests that
need it are skipped on a developer machine but FAIL on CI (any non-empty `CI` environment
variable), so a CI image without them cannot pass silently.

`make_shader` builds an in-memory Shadertoy shader from tab texts, for tests that need no files.

`--update-snapshots` (the `update_snapshots` fixture) makes every snapshot test rewrite what it
compares against instead of comparing: the transpiler's modules (tests/numpy/snapshots), the lint
rules' expected.json (tests/lint/fixtures) and the golden images (tests/golden). Read the diff
before committing it.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from glslcheck.backends import driver_profile
from glslcheck.base.diagnostics import register_source
from glslcheck.shadertoy.sources import Shader, Source

# numba's kernels (backends/numpy_engine/jit.py) are off unless a test turns them on: in auto mode
# the process would switch to them once the tests before had spent a second in the llvmpipe math,
# so what a test of the NumPy path exercised would depend on the tests run before it. The
# kernels' own tests (tests/numpy/test_jit*.py) set the mode they test.
os.environ.setdefault("GLSLCHECK_JIT", "off")


# What a test needs, as markers (pyproject.toml registers them): from the fixtures it asks for,
# and from the folders whose every test needs the tool (their tests also start it in subprocesses).
FIXTURE_MARKERS = {
    "gl": ("gl",),
    "llvmpipe": ("gl", "mesa"),
    "webgl": ("webgl",),
    "glslang": ("glslang",),
    "numba": ("numba",),
    "jit_kernels": ("numba",),
}
FOLDER_MARKERS = {
    "gl": ("gl",),
    "webgl": ("webgl", "gl"),
    "compiled": ("numba", "slow"),
    "fuzz": ("slow",),
}


def pytest_addoption(parser):
    parser.addoption(
        "--emulated-mesa",
        metavar="VERSION",
        default=None,
        help="declare the NumPy emulation to copy another Mesa release (a test hook: shows what "
        "passes and what skips on a driver that is not the emulated one)",
    )
    parser.addoption(
        "--update-snapshots",
        action="store_true",
        default=False,
        help="rewrite the snapshots and golden images the tests compare against, then compare",
    )


def pytest_configure(config):
    version = config.getoption("--emulated-mesa")
    if version:
        driver_profile.EMULATED_MESA = version


@pytest.fixture(scope="session")
def update_snapshots(request) -> bool:
    """Whether this run rewrites snapshots (--update-snapshots) instead of only comparing."""
    return bool(request.config.getoption("--update-snapshots"))


def pytest_collection_modifyitems(config, items):
    for item in items:
        needs = set(FOLDER_MARKERS.get(Path(str(item.fspath)).parent.name, ()))
        for fixture in getattr(item, "fixturenames", ()):
            needs.update(FIXTURE_MARKERS.get(fixture, ()))
        for marker in sorted(needs):
            item.add_marker(marker)


def _missing(what: str, reason: str) -> None:
    if os.environ.get("CI"):
        pytest.fail(f"{what} is required on CI: {reason}")
    pytest.skip(f"no {what} on this machine (developer machine without it); CI fails instead")


@pytest.fixture(scope="session")
def gl():
    """The process-wide moderngl context (standalone EGL)."""
    from glslcheck.backends.gl import GLUnavailable, get_context

    try:
        return get_context()
    except GLUnavailable as e:
        if os.environ.get("CI"):
            pytest.fail(f"an OpenGL context is required on CI: {e}")
        pytest.skip(
            "no OpenGL context on this machine (developer machine without EGL/Mesa); "
            "CI fails instead"
        )


@pytest.fixture(scope="session")
def jit_kernels():
    """numba's compiled kernels of the llvmpipe math (backends/numpy_engine/jit.py), loaded once.
    numba is the optional `jit` extra: skipped without it on a developer machine, a failure on CI
    (make setup, which .ci/run calls, installs the extra)."""
    from glslcheck.backends.numpy_engine import jit

    if not jit.available():
        _missing("numba", "pip install -e '.[jit]' (make setup does)")
    return jit.load(required=True)


@pytest.fixture(scope="session")
def numba():
    """numba for the compiled engine's tests (tests/compiled): skipped without it on a developer
    machine, a failure on CI, as :func:`jit_kernels`."""
    from glslcheck.backends.compiled_engine.engine import available

    if not available():
        _missing("numba", "pip install -e '.[jit]' (make setup does)")


@pytest.fixture
def llvmpipe(gl):
    """The GL context, for the tests that compare the NumPy backend with the driver bit for bit.

    The NumPy backend's float32 mode copies the algorithms of one driver, llvmpipe of
    `driver_profile.EMULATED_MESA` (gallivm's sin/exp2/log2, nir_opt_algebraic's rewrites,
    nir_lower_flrp's choice); another Mesa may compute other bits, so these tests run only where
    the live driver is that one. Elsewhere they skip with the reason; on CI, whose Mesa is the one
    the project promises to match, another driver is a failure: the emulation must then be
    measured and copied again for it."""
    renderer, mesa = driver_profile.driver_name(gl)
    if not driver_profile.is_emulated(renderer, mesa):
        reason = (
            f"bit-exact emulation of llvmpipe of Mesa {driver_profile.EMULATED_MESA}; "
            f"this GL driver is {renderer}, Mesa {mesa or 'unknown'}"
        )
        if os.environ.get("CI"):
            pytest.fail(f"{reason}: CI must run on the emulated driver")
        pytest.skip(reason)
    return gl


@pytest.fixture(scope="session")
def glslang():
    """The path of glslangValidator."""
    from glslcheck.semantics.glslang import glslang_path

    path = glslang_path()
    if path is None:
        _missing("glslangValidator", "install the Debian package glslang-tools")
    return path


@pytest.fixture
def make_shader():
    """make_shader(image_text, common=None, **other_tabs) -> Shader with files Image.glsl,
    Common.glsl, ...

    The texts are registered as sources so diagnostics can quote their lines.
    """

    def make(image: str | None = None, common: str | None = None, **tabs: str) -> Shader:
        shader = Shader(root="<test>")
        texts = {"Image": image, "Common": common}
        texts.update({name.replace("_", " "): text for name, text in tabs.items()})
        for tab, text in texts.items():
            if text is None:
                continue
            path = f"{tab}.glsl"
            register_source(path, text)
            shader.tabs[tab] = Source(path, text, tab)
        return shader

    return make
