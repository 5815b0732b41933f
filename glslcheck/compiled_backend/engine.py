"""The compiled engine's program: generate the module (codegen.py), load it through numba's
cache, and render frames by rows on threads.

The generated source is written to ``<cache>/compiled/m<hash>.py`` (the cache directory of
numpy_backend/jit.py: $NUMBA_CACHE_DIR, else $XDG_CACHE_HOME/glslcheck/numba), named by a hash
of the source and of glslcheck's, numba's and the scalar runtime's versions, and imported from
there; every function is ``cache=True``, so a second process loads machine code instead of
compiling (`CompiledProgram.load_seconds`, `cold`).

Frames: the rows are split into bands, each rendered by ``render_rows`` (nogil) on its own
thread; a band allocates its own copy of the global state.
"""

from __future__ import annotations

import hashlib
import importlib.util
import os
import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from typing import Any

import numpy as np

from ..diagnostics import Diagnostic, GlslError, InputError, Location
from ..shadertoy import UNIFORMS_BY_NAME, FrameInputs, frame_inputs

PIP = "pip install 'glslcheck[jit]'"
_LOCK = threading.Lock()
_MODULES: dict[str, Any] = {}  # hash -> loaded module (one per process)
PARALLEL_PIXELS = 4096  # smaller frames on the calling thread (a thread hand-off costs more)
_POOLS: dict[int, ThreadPoolExecutor] = {}


def _pool(threads: int) -> ThreadPoolExecutor:
    """The process's row-band threads (made once: starting threads costs a frame of a small shader)."""
    with _LOCK:
        pool = _POOLS.get(threads)
        if pool is None:
            pool = _POOLS[threads] = ThreadPoolExecutor(threads, thread_name_prefix="glslcheck-compiled")
        return pool


def available() -> bool:
    """Whether numba is installed: numpy_backend/jit.py's answer (numba is not imported)."""
    from ..numpy_backend import jit

    return jit.available()


def require_numba() -> None:
    """InputError (exit 2) without numba, with the pip line."""
    if not available():
        raise InputError(f"error: --backend compiled needs numba, which is not installed ({PIP})")


def _versions() -> str:
    from importlib.metadata import version

    from .. import __version__

    here = os.path.dirname(__file__)
    nb = os.path.join(os.path.dirname(here), "numpy_backend")
    h = hashlib.sha256()
    for path in (os.path.join(here, "scalar.py"), os.path.join(here, "lanes_rt.py"), os.path.join(nb, "jit_kernels.py"),
                 os.path.join(nb, "llvmpipe_fast.py")):
        with open(path, "rb") as f:
            h.update(f.read())
    return f"{__version__} numba {version('numba')} {h.hexdigest()[:16]}"


def lanes_width(lanes: int | None = None) -> int:
    """Pixels per call: `lanes` when given, else $GLSLCHECK_COMPILED_LANES, else 0 (the
    per-pixel module). Lockstep (8 or 16 pixels, with the branch-free math of lanes_math.py) renders
    every shader measured faster, bit for bit, but numba takes several times longer and much
    more memory to compile it: 10-lab4 of the real corpus, cold, 341 s and 9.2 GB peak against
    17 s and 0.4 GB per pixel (docs/performance.md, "Pixels in lockstep"). So it is a choice
    (GLSLCHECK_COMPILED_LANES=8 or 16) for a shader rendered many times, not the default."""
    if lanes is not None:
        return lanes
    text = os.environ.get("GLSLCHECK_COMPILED_LANES", "").strip()
    if not text:
        return 0
    try:
        return max(0, int(text))
    except ValueError:
        raise InputError(f"error: GLSLCHECK_COMPILED_LANES must be a number of pixels (0: one at a time), not {text!r}") from None


def generate(shader: Any, tab: str | None = None, lanes: int | None = None) -> tuple[str, str]:
    """(generated source, path of the GLSL tab) of a shader's Image (or plain GLSL) tab: blocks
    of `lanes_width(lanes)` pixels in lockstep (lanes.py), or one pixel a call when that is 0 or
    the rewrite does not handle the program (the per-pixel module then says why in
    LANES_FALLBACK)."""
    from ..channels import needs_passes
    from ..driver_profile import host_model
    from ..numpy_backend.runtime import HOST_FMA
    from ..numpy_backend.transpile.common import check_program
    from ..parse import parse_shader
    from .codegen import Codegen

    if needs_passes(shader):
        loc = Location(shader.root, 1, 1)
        raise GlslError(Diagnostic("Buffer tabs and iChannel inputs: not supported by the compiled engine yet",
                                   loc, rule="compiled-engine", help="render with --backend numpy or gl"))
    if tab is None:
        tab = "Image" if "Image" in shader.tabs else ("GLSL" if "GLSL" in shader.tabs else "Image")
    pr = parse_shader(shader, tab)
    model = check_program(pr)
    src = shader.tabs.get(tab)
    path = src.path if src is not None else shader.root
    old = sys.getrecursionlimit()
    sys.setrecursionlimit(max(old, 20000))
    try:
        source = Codegen(model, path, HOST_FMA, host_model()).module()
        width = lanes_width(lanes)
        if width:
            from .lanes import Unsupported, lanes_module

            try:
                source = lanes_module(source, width)
            except Unsupported as e:
                source += f"\nLANES_FALLBACK = {str(e)!r}  # why this shader runs one pixel a call\n"
    finally:
        sys.setrecursionlimit(old)
    return source, path


class CompiledProgram:
    """A shader compiled per pixel; `render` as NumpyProgram.render (float32 only)."""

    def __init__(self, source: str, path: str, threads: int | None = None) -> None:
        self.source = source
        self.path = path
        self.threads = threads or os.cpu_count() or 1
        self.mod: Any = None
        self.load_seconds: float | None = None  # wall time of import + numba compile or cache load
        self.cold: bool | None = None  # True when numba compiled (no cache), False when it loaded
        self.key = hashlib.sha256((_versions() + "\n" + source).encode()).hexdigest()[:24]

    def load(self) -> Any:
        require_numba()
        with _LOCK:
            if self.mod is not None:
                return self.mod
            mod = _MODULES.get(self.key)
            if mod is None:
                mod = self._import()
                _MODULES[self.key] = mod
            self.mod = mod
            return mod

    def _import(self) -> Any:
        from ..numpy_backend import jit

        cache = jit.cache_dir()
        os.environ.setdefault("NUMBA_CACHE_DIR", cache)
        from numba.core import config

        config.CACHE_DIR = cache
        folder = os.path.join(cache, "compiled")
        os.makedirs(folder, exist_ok=True)
        name = f"glslcheck_compiled_m{self.key}"
        file = os.path.join(folder, f"m{self.key}.py")
        if not os.path.exists(file):
            tmp = f"{file}.{os.getpid()}"
            with open(tmp, "w") as f:
                f.write(self.source)
            os.replace(tmp, file)
        t0 = time.perf_counter()
        spec = importlib.util.spec_from_file_location(name, file)
        mod = importlib.util.module_from_spec(spec)
        sys.modules[name] = mod
        spec.loader.exec_module(mod)
        self.cold = not _cached(cache, self.key)
        slp, limit = config.SLP_VECTORIZE, sys.getrecursionlimit()
        if getattr(mod, "LANES", 0):  # LLVM's SLP vectorizer packs the lanes (no reassociation: same bits)
            config.SLP_VECTORIZE = 1
            sys.setrecursionlimit(max(limit, 20000))  # numba's SSA pass recurses along long functions
        try:
            self._frame(mod, 1, 1, np.zeros((1, 2)), *self._inputs(mod, None))  # compiles, or loads the cache
        finally:
            config.SLP_VECTORIZE = slp
            sys.setrecursionlimit(limit)
        self.load_seconds = time.perf_counter() - t0
        return mod

    def _inputs(self, mod: Any, values: dict | None) -> tuple[np.ndarray, np.ndarray]:
        uf = np.zeros(max(1, mod.USLOTS["float"]), np.float32)
        ui = np.zeros(max(1, mod.USLOTS["int"]), np.int32)
        values = values or {}
        for name, (kind, off) in mod.UNIFORMS.items():
            u = UNIFORMS_BY_NAME[name]
            v = values.get(name, u.default)
            if u.array_size:  # one array per component: component c of element k at off + c*n + k
                comps = [list(x) if isinstance(x, (tuple, list)) else [x] for x in v]
                for k, elem in enumerate(comps):
                    for c, x in enumerate(elem):
                        uf[off + c * u.array_size + k] = np.float32(float(x))
                continue
            flat = list(v) if isinstance(v, (tuple, list)) else [v]
            for c, x in enumerate(flat):
                if kind == "int":
                    ui[off + c] = np.int32(int(x))
                else:
                    uf[off + c] = np.float32(float(x))
        return uf, ui

    def _frame(self, mod: Any, width: int, height: int, offs: np.ndarray, uf: np.ndarray,
               ui: np.ndarray) -> np.ndarray:
        slots = mod.SLOTS
        gt = [np.zeros(max(1, slots[k]), dt) for k, dt in
              (("float", np.float32), ("int", np.int32), ("uint", np.uint32), ("bool", np.bool_))]
        from .scalar import LoopCapError

        out = np.empty((height, width, 4), np.float32)
        try:
            mod.globals_template(uf, ui, *gt)
            bands = min(self.threads * 4, height) if width * height >= PARALLEL_PIXELS else 1
            edges = [height * k // bands for k in range(bands + 1)]
            if bands <= 1 or self.threads <= 1:
                mod.render_rows(out, 0, height, width, height, offs, uf, ui, *gt)
            else:
                futures = [_pool(self.threads).submit(mod.render_rows, out, edges[k], edges[k + 1], width, height,
                                                      offs, uf, ui, *gt)
                           for k in range(bands) if edges[k] < edges[k + 1]]
                for f in futures:
                    f.result()
        except LoopCapError as e:
            from ..numpy_backend.transpile.common import LOOP_CAP

            path, line, col = mod.LOOPS.get(int(e.args[0]), (self.path, 0, 0))
            raise GlslError(Diagnostic(f"this loop ran more than {LOOP_CAP} times", Location(path, line, col),
                                       rule="compiled-engine")) from None
        return out

    @frame_inputs
    def render(self, inputs: FrameInputs, precision: str = "float32", stats: bool = False) -> np.ndarray:
        """One frame: float32 (height, width, 4), top row first (the NumPy backend's layout)."""
        if precision != "float32":
            raise ValueError("the compiled engine renders in float32 only")
        if stats:
            raise ValueError("stats=True needs backend='numpy'")
        mod = self.load()
        uf, ui = self._inputs(mod, inputs.uniforms())
        offs = np.array(inputs.offsets if len(inputs.offsets) > 1 else [(0.0, 0.0)], np.float64)
        return self._frame(mod, inputs.width, inputs.height, offs, uf, ui)


def _cached(folder: str, key: str) -> bool:
    """Whether numba had machine code for the module before this load (its index files)."""
    return any(n.startswith(f"m{key}.") and n.endswith(".nbi") for n in _listdir(folder))


def _listdir(folder: str) -> list[str]:
    out = []
    for root, _, files in os.walk(folder):
        out += files
    return out


def compile_compiled(path_or_shader: Any, threads: int | None = None) -> Any:
    """`glslcheck.compile(path, backend="compiled")`: an api.Program over a CompiledProgram."""
    from ..api import Program
    from ..sources import Shader, load_shader

    shader = path_or_shader if isinstance(path_or_shader, Shader) else load_shader(path_or_shader)
    source, path = generate(shader)
    return Program(shader, "compiled", CompiledProgram(source, path, threads))
