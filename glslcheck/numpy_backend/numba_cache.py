"""Where numba keeps its compiled machine code for glslcheck, set before anything compiles.

Its own module, imported by numpy_backend/jit.py and jit_kernels.py (and through them by the
compiled engine), so that jit_kernels can set the directory at its import without importing
jit.py, which imports it.
"""

from __future__ import annotations

import os
import sys


def cache_dir() -> str:
    """Where numba keeps the compiled kernels: $NUMBA_CACHE_DIR, else the user's cache."""
    given = os.environ.get("NUMBA_CACHE_DIR")
    if given:
        return given
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "glslcheck", "numba")


def use_cache_dir() -> str:
    """Point numba's cache at :func:`cache_dir` (before any function is compiled) and return it.

    ``$NUMBA_CACHE_DIR`` is set when missing, for numba's import; if numba was imported already,
    its config is reloaded at once, every other setting kept as it is. numba re-reads its whole
    config from the environment at the start of a compile whenever a ``NUMBA_`` variable changed
    since it last looked (CompilerBase calls config.reload_config), which undoes what was
    assigned to numba.core.config meanwhile: the lockstep engine's ``SLP_VECTORIZE = 1`` was
    reset that way for the first module a process compiled (when numba came in before this
    variable was set, as under pytest), and that module was compiled, and cached, without the
    vectoriser (9 packed and 310 scalar float instructions in tests/compiled/test_lanes_math.py's
    shininess loop, 60 and 21 with it)."""
    path = cache_dir()
    changed = os.environ.get("NUMBA_CACHE_DIR") != path
    os.environ["NUMBA_CACHE_DIR"] = path
    if "numba" in sys.modules:
        from numba.core import config

        if changed:
            kept = {k: getattr(config, k) for k in dir(config) if k.isupper() and k != "CACHE_DIR"}
            config.reload_config()  # takes the environment's snapshot now, so no compile reloads it
            for k, v in kept.items():
                setattr(config, k, v)
        config.CACHE_DIR = path
    return path
