"""The one home of glslcheck's environment variables: every `GLSLCHECK_*` setting is listed in
VARIABLES (name, what it sets, allowed values, default, who reads it) and read by one function
here, with its default and its validation. The table in docs/configuration.md is
`table()`'s output; tests/test_config.py holds the two to each other and to the source.

Each function reads os.environ when called, never at import: the CLI sets some variables from
its options for the duration of a command (--frame-budget, --parallel, --jit) and tests set them
per test. A value outside what a variable allows raises InputError naming the variable (exit 2).

Variables of other programs that glslcheck reads (FOREIGN) are theirs: they are read where they
are used and listed here only so that the table names everything the environment can change.
Imported on the start-up path of `lint`: nothing heavier than base.diagnostics.
"""

from __future__ import annotations

import math
import os

from .diagnostics import InputError

# Defaults and allowed values that the readers below and their callers share.
FRAME_SECONDS = (
    300.0  # the NumPy and compiled engines' frame budget (base/limits.py holds its range)
)
JIT_MODES = ("auto", "on", "off")  # backends/numpy_engine/jit.py
TIER_MODES = ("auto", "off")  # backends/tiered.py
PARALLEL_MODES = ("auto", "threads", "processes")  # NumpyProgram.parallel
# The compiled engine's widths: one pixel a call, or AVX2's and AVX-512's float32 lanes (wider
# blocks only grow the compile, and a width of 1,000,000 took minutes and 5 GB).
LANE_WIDTHS = ("0", "8", "16")
WEBGL_TIMEOUT = 60.0  # seconds one compile or render may take in the browser
MAX_WEBGL_TIMEOUT = (
    86400.0  # a day, as --frame-budget: longer is a hang (and inf overflows the browser's timer)
)

# (name, what it sets, allowed values, default, who reads it)
VARIABLES = (
    (
        "GLSLCHECK_FRAME_SECONDS",
        "seconds a NumPy or compiled frame may render before it stops with an error "
        "(set by `--frame-budget`)",
        "0.01 to 86400",
        "300",
        "backends/numpy_engine/program.py, compiled_engine",
    ),
    (
        "GLSLCHECK_MEMORY_MB",
        "megabytes the NumPy engine's tiles rendering at once may hold",
        "a positive number",
        "half the memory (or of `ulimit -v`)",
        "backends/numpy_engine/program.py",
    ),
    (
        "GLSLCHECK_PARALLEL",
        "how the NumPy engine spreads a frame's tiles (set by `--parallel`)",
        "auto, threads, processes",
        "auto",
        "backends/numpy_engine/program.py, cli/main.py",
    ),
    (
        "GLSLCHECK_JIT",
        "whether the NumPy engine's llvmpipe math runs in numba kernels (set by `--jit`)",
        "auto, on, off",
        "auto",
        "backends/numpy_engine/jit.py, cli/main.py",
    ),
    (
        "GLSLCHECK_COMPILED_LANES",
        "pixels per call of the compiled engine; a number fixes the mode",
        "auto, 0, 8, 16",
        "auto (per pixel, then lockstep when it pays)",
        "backends/compiled_engine/engine.py",
    ),
    (
        "GLSLCHECK_TIERS",
        "whether the default CPU program (`--backend auto`) may move its frames from the NumPy "
        "engine to the compiled engine once that pays",
        "auto, off",
        "auto",
        "backends/tiered.py",
    ),
    (
        "GLSLCHECK_WEBGL_TIMEOUT",
        "seconds one compile or render may take in the browser",
        "more than 0, at most 86400",
        "60",
        "backends/webgl/browser.py",
    ),
    (
        "GLSLCHECK_CHROMIUM",
        "the Chromium executable of the WebGL backend",
        "an executable file",
        "`chromium` or `chromium-browser` on PATH",
        "backends/webgl/browser.py",
    ),
    (
        "GLSLCHECK_JOBS",
        "processes `lint` may use",
        "auto, or a whole number from 1 (2 and more: 2)",
        "auto (2 when a core is idle)",
        "lint/parallel.py",
    ),
)

# Read, not owned: (name, whose it is, who reads it)
FOREIGN = (
    (
        "NUMBA_CACHE_DIR",
        "numba's cache folder (glslcheck then sets it to the folder it trusts)",
        "backends/cpu_core/numba_cache.py",
    ),
    ("XDG_CACHE_HOME", "the user's cache folder", "backends/cpu_core/numba_cache.py"),
    ("COLUMNS", "the terminal's width, for `--help`", "cli/main.py"),
    (
        "glsl_zero_init",
        "Mesa's zero-initialisation of GLSL variables (set when unset)",
        "backends/gl/context.py",
    ),
    (
        "CI",
        "a CI run: tests that need an optional tool fail instead of skipping",
        "tests/conftest.py",
    ),
)


def _text(name: str) -> str:
    return os.environ.get(name, "").strip()


def frame_seconds(default: float = FRAME_SECONDS) -> float:
    """GLSLCHECK_FRAME_SECONDS, else `default` (FRAME_SECONDS; `glslcheck grade` has its own):
    the range --frame-budget takes."""
    from .limits import MAX_FRAME_SECONDS, MIN_FRAME_SECONDS

    text = _text("GLSLCHECK_FRAME_SECONDS")
    try:
        value = float(text) if text else default
    except ValueError:
        value = math.nan
    if not MIN_FRAME_SECONDS <= value <= MAX_FRAME_SECONDS:
        raise InputError(
            "error: GLSLCHECK_FRAME_SECONDS must be a number of seconds from "
            f"{MIN_FRAME_SECONDS:g} "
            f"to {MAX_FRAME_SECONDS:g} (like --frame-budget), not {text!r}"
        )
    return value


def memory_mb() -> float | None:
    """GLSLCHECK_MEMORY_MB in megabytes; None when unset (the caller sizes to the machine)."""
    text = _text("GLSLCHECK_MEMORY_MB")
    if not text:
        return None
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not 0 < value < math.inf:
        raise InputError(
            f"error: GLSLCHECK_MEMORY_MB must be a positive number of megabytes, not {text!r}"
        )
    return value


def _mode(name: str, modes: tuple[str, ...]) -> str:
    value = _text(name) or "auto"
    if value not in modes:
        raise InputError(f"error: {name} must be one of {', '.join(modes)}, not {value!r}")
    return value


def parallel() -> str:
    """GLSLCHECK_PARALLEL: one of PARALLEL_MODES, "auto" when unset."""
    return _mode("GLSLCHECK_PARALLEL", PARALLEL_MODES)


def jit() -> str:
    """GLSLCHECK_JIT: one of JIT_MODES, "auto" when unset."""
    return _mode("GLSLCHECK_JIT", JIT_MODES)


def tiers() -> bool:
    """GLSLCHECK_TIERS: False for `off` (every frame of `--backend auto` on the NumPy engine)."""
    return _mode("GLSLCHECK_TIERS", TIER_MODES) != "off"


def compiled_lanes() -> int | None:
    """GLSLCHECK_COMPILED_LANES as a width of LANE_WIDTHS; None when unset or `auto` (tiered)."""
    text = _text("GLSLCHECK_COMPILED_LANES")
    if not text or text == "auto":
        return None
    if text not in LANE_WIDTHS:
        raise InputError(
            f"error: GLSLCHECK_COMPILED_LANES must be auto, 0 (one pixel a call) or "
            f"{' or '.join(LANE_WIDTHS[1:])} (pixels in lockstep), not {text!r}"
        )
    return int(text)


def webgl_timeout() -> float:
    """GLSLCHECK_WEBGL_TIMEOUT in seconds, else WEBGL_TIMEOUT; set but empty is an error."""
    name = "GLSLCHECK_WEBGL_TIMEOUT"
    text = os.environ.get(name)
    try:
        value = WEBGL_TIMEOUT if text is None else float(text)
    except ValueError:
        raise InputError(f"error: ${name} must be a number of seconds, not {text!r}") from None
    if not 0 < value <= MAX_WEBGL_TIMEOUT:
        raise InputError(
            f"error: ${name} must be a number of seconds from 0 to {MAX_WEBGL_TIMEOUT:g}, "
            f"not {text!r}"
        )
    return value


def chromium() -> str | None:
    """GLSLCHECK_CHROMIUM, an executable file; None when unset or empty (the caller searches
    PATH)."""
    given = os.environ.get("GLSLCHECK_CHROMIUM")
    if not given:
        return None
    if not os.access(given, os.X_OK) or os.path.isdir(given):
        raise InputError(f"error: GLSLCHECK_CHROMIUM must be an executable file, not {given!r}")
    return given


def jobs() -> int | None:
    """GLSLCHECK_JOBS: 1 or 2 processes (more counts as 2); None when unset or `auto`."""
    text = _text("GLSLCHECK_JOBS")
    if not text or text == "auto":
        return None
    if not (text.isdigit() and int(text) >= 1):
        raise InputError(
            "error: GLSLCHECK_JOBS must be auto or a whole number of processes from 1, "
            f"not {text!r}"
        )
    return min(int(text), 2)


def table() -> str:
    """VARIABLES and FOREIGN as the Markdown tables of docs/configuration.md."""
    rows = ["| Variable | Sets | Allowed | Default | Read by |", "|---|---|---|---|---|"]
    rows += [
        f"| `{name}` | {sets} | {allowed} | {default} | {readers} |"
        for name, sets, allowed, default, readers in VARIABLES
    ]
    rows += [
        "",
        "Read, not owned (other programs' variables):",
        "",
        "| Variable | What it is | Read by |",
        "|---|---|---|",
    ]
    rows += [f"| `{name}` | {what} | {readers} |" for name, what, readers in FOREIGN]
    return "\n".join(rows) + "\n"
