"""The compiled engine's program: generate the module (codegen.py), load it through numba's
cache, and render frames by rows on threads.

The generated source is written to ``<cache>/compiled/m<hash>.py`` (numba_cache.trusted_dir:
$NUMBA_CACHE_DIR, else $XDG_CACHE_HOME/glslcheck/numba, when no other user can write it), named
by a hash of the source and of glslcheck's, numba's and the scalar runtime's versions; the
source generated in this process is what runs, under that file's name, and every function is
``cache=True``, so a second process loads machine code instead of compiling
(`CompiledProgram.load_seconds`, `cold`).

Frames: the rows are split into bands, each rendered by ``render_rows`` (nogil) on the
engine's worker threads; a band allocates its own copy of the global state. The calling thread
only waits, in short slices, so a frame honours the frame budget (`frame_seconds`) and Ctrl-C
however long the machine code runs; numba's first call (the compile, or the cache load) is
waited on the same way.

The contract when a frame or a compile is abandoned (a GlslError with rule
"compiled-frame-budget", or KeyboardInterrupt): numba's machine code cannot be stopped, so its
threads go on to the end of their band (for ever, for a shader that never ends) as daemon
threads; later frames run on fresh threads. A library user who must have the CPU back ends the
process, and a process that did abandon one should end with os._exit after flushing its
output (as the command line does): the interpreter's own shutdown does not wait for daemon
threads, but it may pull the runtime from under them (LLVM aborts a compile cut off that way).
`workers.abandoned()` says whether that happened.
"""

from __future__ import annotations

import atexit
import hashlib
import math
import os
import subprocess
import sys
import threading
import time
import types
from collections.abc import Callable
from typing import Any

import numpy as np

from ...base import config
from ...base.diagnostics import Diagnostic, GlslError, InputError, Location
from ...base.recursion import enter_deep, leave_deep
from ...shadertoy.frame_inputs import FrameInputs, frame_inputs
from ...shadertoy.wrapper import UNIFORMS_BY_NAME
from ..cpu_core import numba_cache
from ..cpu_core.common import LOOP_CAP
from . import cache_files, numba_linking
from .budget import STARVED, wait_child
from .values import BUDGET_OFF
from .workers import run_bounded

PIP = "pip install 'glslcheck[jit]'"
NO_LIMIT = 2**62  # the loop budget without llvmpipe's limiter: more passes than any frame runs
_LOCK = threading.Lock()
_MODULES: dict[str, Any] = {}  # hash -> loaded module (one per process)
_SOURCES: dict[str, str] = {}  # hash -> the loaded module's source
PARALLEL_PIXELS = 4096  # smaller frames in one band (a hand-off between threads costs more)
# numba's compile (or cache load) has the frame budget, but at least this many seconds: a small
# program takes seconds to compile cold, whatever budget its frames have.
COMPILE_SECONDS = 60.0


# compiles under way in child processes (build_apart), each with the marker a paid-for lockstep
# compile may finish into after this process ends (None: stopped with it)
_CHILDREN: dict[subprocess.Popen, str | None] = {}
_EXITING: list[bool] = []  # the interpreter is exiting: the children were stopped on purpose
FINISHING = "finishing.pid"  # in the modules' folder: the child left to finish, one at a time
LEFT_TO_FINISH = "left to finish after its process, pid"  # a marker's text meanwhile


@atexit.register
def _stop_children() -> None:
    _EXITING.append(True)
    for child, marker in list(_CHILDREN.items()):
        if marker is None or not _leave_to_finish(child, marker):
            child.kill()


def _leave_to_finish(child: subprocess.Popen, marker: str) -> bool:
    """Let a lockstep compile that this process's frames paid for finish after it (build.py), so
    that a later process loads it instead of paying again for a compile its exit would cut off
    again; one such child at a time in a cache. Until the child writes the module's key there,
    the marker says over budget, so no process starts the same compile meanwhile, nor after a
    child its budget (RLIMIT_CPU) or the machine stopped. Whether it was left."""
    if child.poll() is not None:  # (it ended as this process did: nothing to leave)
        return True
    lock = os.path.join(cache_files.folder(), FINISHING)
    other = cache_files.read(lock)
    if other and other.isdigit() and _alive(int(other)):
        return False
    cache_files.write(lock, f"{child.pid}\n")
    cache_files.write(marker, f"{OVER} {LOCKSTEP_BUDGET:g} s: {LEFT_TO_FINISH} {child.pid}\n")
    cache_files.write(marker + ".finish", "")  # the child's leave to go on (build.py)
    return True


def _died(marker: str) -> bool:
    """Whether a marker names a child left to finish that ended without a word: its budget
    writes the marker (build.py), so a child gone otherwise (killed, the machine restarted) says
    nothing of the compile, which a later process may try again."""
    head, _, pid = marker.rpartition(" ")
    return head.endswith(LEFT_TO_FINISH) and pid.isdigit() and not _alive(int(pid))


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:
        return True  # (another user's process)
    return True


def available() -> bool:
    """Whether numba is installed (numba is not imported)."""
    return numba_cache.installed()


def require_numba() -> None:
    """InputError (exit 2) without numba, with the pip line."""
    if not available():
        raise InputError(f"error: --backend compiled needs numba, which is not installed ({PIP})")


def _versions() -> str:
    from importlib.metadata import version

    from ...base.version import __version__

    here = os.path.dirname(__file__)
    math = os.path.join(os.path.dirname(here), "llvmpipe_math")
    h = hashlib.sha256()
    # the runtime numba inlines into a generated module's machine code, which its cache keeps
    for path in (
        os.path.join(here, "scalar.py"),
        os.path.join(here, "lanes_rt.py"),
        os.path.join(here, "lanes_math.py"),
        os.path.join(math, "lane.py"),
        os.path.join(math, "coefficients.py"),
        os.path.join(here, "texture_kernels.py"),
        os.path.join(math, "cube_faces.py"),
    ):
        with open(path, "rb") as f:
            h.update(f.read())
    return f"{__version__} numba {version('numba')} {h.hexdigest()[:16]}"


def lanes_width(lanes: int | None = None) -> int:
    """Pixels per call of a module: `lanes` when given, else $GLSLCHECK_COMPILED_LANES, else 0
    (the per-pixel module, the first tier of TieredProgram: tiered() says when)."""
    if lanes is not None:
        return lanes
    given = config.compiled_lanes()
    return 0 if given is None else given


def tiered() -> bool:
    """Whether programs start per pixel and move to lockstep when that pays (TieredProgram):
    $GLSLCHECK_COMPILED_LANES unset or `auto`; a number fixes the mode."""
    return config.compiled_lanes() is None


def mipmap_channels(shader: Any, tab: str) -> frozenset:
    """The channels of the tab that channels.json (or Shadertoy's export) binds with mipmaps:
    their `texture()` lookups read the quads' implicit LOD (texture_calls.py)."""
    from ...shadertoy.channels import load_bindings

    _, bindings = load_bindings(shader)
    return frozenset(b.channel for b in bindings if b.tab == tab and b.filter == "mipmap")


def generate(
    shader: Any,
    tab: str | None = None,
    lanes: int | None = None,
    budget: bool = False,
    mipmap: frozenset | None = None,
) -> tuple[str, str]:
    """(generated source, path of the GLSL tab) of a shader's tab (default the Image, or the
    plain GLSL one): blocks of `lanes_width(lanes)` pixels in lockstep (lanes.py), or one pixel a
    call when that is 0 or the rewrite does not handle the program (the per-pixel module then
    says why in LANES_FALLBACK); `budget`: with llvmpipe's loop budget
    (CompiledProgram.loop_limit); `mipmap`: the channels bound with mipmaps (default: as the
    shader's bindings say, mipmap_channels)."""
    from ...frontend.parser import parse_shader
    from ...semantics import check
    from ..driver_profile import host_fma, host_model
    from .codegen import Codegen
    from .values import engine_error, not_yet

    if tab is None:
        tab = "Image" if "Image" in shader.tabs else ("GLSL" if "GLSL" in shader.tabs else "Image")
    if mipmap is None:
        mipmap = mipmap_channels(shader, tab) if tab != "GLSL" else frozenset()
    pr = parse_shader(shader, tab)
    model = check(pr)
    src = shader.tabs.get(tab)
    path = src.path if src is not None else shader.root
    enter_deep()
    try:
        cg = Codegen(
            model,
            path,
            host_fma(),
            host_model(),
            budget,
            mipmap,
            keep_alpha=tab.startswith("Buffer"),
            frame_calls=lanes_width(lanes) == 0,
        )
        source = cg.module()
        width = lanes_width(lanes)
        if cg.derivative is not None and cg.switch_local is not None:
            # a neighbour's derivative may read it: llvmpipe computes it in every lane, the NumPy
            # backend writes it under the case's mask (cpu_core/uniformity.py), and this engine
            # gives the bits of one of them only
            raise not_yet(
                "a local declared in a switch, in a program with derivatives", cg.switch_local
            )
        if cg.derivative is not None and not width:
            if lanes is not None or not tiered():
                raise engine_error(
                    f"{cg.derivative.callee}() one pixel a call: the compiled engine computes "
                    "derivatives only with pixels in lockstep (2x2 quads; mipmap LODs too)",
                    cg.derivative,
                    help=f"unset GLSLCHECK_COMPILED_LANES (or set it to {TIER_LANES}), "
                    "or render with --backend numpy or gl",
                )
            width = (
                TIER_LANES  # the default program: lockstep from the first frame (no per-pixel tier)
            )
        if width:
            from .lanes import Unsupported, lanes_module

            try:
                source = lanes_module(source, width)
            except Unsupported as e:
                if cg.derivative is not None:  # no per-pixel module to fall back to
                    raise not_yet(
                        f"{cg.derivative.callee}(): derivatives in this program ({e})",
                        cg.derivative,
                    ) from None
                source += (
                    f"\nLANES_FALLBACK = {str(e)!r}  # why this shader runs one pixel a call\n"
                )
    finally:
        leave_deep()
    return source, path


class CompiledProgram:
    """A shader compiled per pixel; `render` as NumpyProgram.render (float32 only). Each frame,
    has `frame_seconds` (None: GLSLCHECK_FRAME_SECONDS or config.FRAME_SECONDS), and
    numba's compile or cache load as much but at least COMPILE_SECONDS, before it stops with a
    GlslError, rule "compiled-frame-budget" (the module docstring: what runs on after it)."""

    def __init__(
        self, source: str, path: str, threads: int | None = None, remake: Callable | None = None
    ) -> None:
        self.source = source
        self.remake = remake  # () -> the source with llvmpipe's loop budget (generate's budget)
        self.path = path
        self.threads = threads or os.cpu_count() or 1
        self.frame_seconds: float | None = None
        self._loop_limit: int | None = None
        self._limited: set[tuple[str, int]] = set()
        self.mod: Any = None
        self.load_seconds: float | None = None  # wall time of import + numba compile or cache load
        self.cold: bool | None = None  # True when numba compiled (no cache), False when it loaded
        self.cpu_seconds: float | None = None  # this process's CPU time of that compile (cold)
        self.key = hashlib.sha256((_versions() + "\n" + source).encode()).hexdigest()[:24]

    @property
    def loop_limit(self) -> int | None:
        """llvmpipe's loop limiter (scalar.tick): None = loops run until they end (a runaway
        loop is an error after LOOP_CAP passes); 65535 = stop as llvmpipe does (verify sets
        it). A module made without the budget (the faster: it neither counts passes nor passes
        `lc`) is made again with it (`remake`) when a limit is set: set it before the first
        frame, or that module is compiled too."""
        return self._loop_limit

    @loop_limit.setter
    def loop_limit(self, limit: int | None) -> None:
        from .values import BUDGET_OFF

        self._loop_limit = limit
        if limit is not None and BUDGET_OFF in self.source:
            if self.remake is None:
                raise ValueError("this module has no loop budget: generate(..., budget=True)")
            with _LOCK:
                self.source = self.remake()
                self.key = hashlib.sha256((_versions() + "\n" + self.source).encode()).hexdigest()[
                    :24
                ]
                self.mod = None
                self.cold = self.load_seconds = self.cpu_seconds = None

    def load(self, bounded: bool = True) -> Any:
        """The module, compiled or loaded from numba's cache; `bounded`: the compile has the
        frame budget (a compile in the background, which no frame waits for, has none)."""
        require_numba()
        with _LOCK:
            if self.mod is not None:
                return self.mod
            mod = _MODULES.get(self.key)
            if mod is None:
                mod = self._import(bounded)
                _MODULES[self.key] = mod
                _SOURCES[self.key] = self.source
            self.mod = mod
            return mod

    def build_apart(self, seconds: float, finish_into: str | None = None) -> str:
        """Compile the module into numba's cache in a child process (build.py), which holds neither
        this process's GIL nor its frames up, and stop it after `seconds` of its CPU time
        (budget.wait_child; numba's compile cannot be stopped inside a process, a child can). ""
        when the cache holds the machine code (`load` then loads it: tenths of a second), "over
        budget" when stopped there, budget.STARVED when stopped by the machine's load first (a later
        process may try again), EXITING when this process is exiting (the child stopped with it:
        nothing to say), "failed: ..." when the child failed (its last line; `load` in this process
        gives the error itself) or "killed: ..." when it died of a signal. A cache numba cannot
        write leaves `load` to compile here. `finish_into`: the marker file of a compile this
        process may leave to finish after it ends (_leave_to_finish), which the child then writes
        the module's key into."""
        require_numba()
        cache = numba_cache.use_cache_dir()  # (in the environment: the child's numba reads it)
        if self.mod is not None or self.key in _MODULES or cache_files.cached(cache, self.key):
            return ""
        file = os.path.join(cache_files.folder(), f"m{self.key}.py")
        if cache_files.read(file, strip=False) != self.source:
            cache_files.write(file, self.source, quiet=False)
        env = dict(os.environ)
        # the child imports this glslcheck, wherever this process found it
        root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(__file__))))
        env["PYTHONPATH"] = os.pathsep.join(p for p in (root, env.get("PYTHONPATH")) if p)
        child = subprocess.Popen(
            [
                sys.executable,
                *("-m", f"{__package__}.build", file, self.path, str(os.getpid())),
                *(f"{seconds:g}", finish_into or ""),
            ],
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            env=env,
        )
        # no compile outlives the process that wanted it: stopped at its exit (and the child
        # ends by itself when this process is gone without one: build.py)
        _CHILDREN[child] = finish_into
        try:
            err = wait_child(child, seconds)
            if isinstance(err, str):  # OVER or STARVED
                child.kill()
                child.communicate()
                return err
        except BaseException:  # Ctrl-C
            child.kill()
            raise
        finally:
            _CHILDREN.pop(child, None)
        if _EXITING:
            return EXITING
        if child.returncode < 0:
            return f"killed: numba's compile ended by signal {-child.returncode}"
        if child.returncode:
            lines = err.decode("utf-8", "replace").strip().splitlines()
            return f"failed: {lines[-1] if lines else child.returncode}"
        return ""

    def _import(self, bounded: bool) -> Any:
        cache = (
            numba_cache.use_cache_dir()
        )  # before the SLP setting below, which a reload of numba's config would undo
        from numba.core import config

        folder = cache_files.folder()
        name = f"{numba_linking.MODULE_PREFIX}{self.key}"
        file = os.path.join(folder, f"m{self.key}.py")
        # numba's cache needs the module as a file (it keys machine code to its path and stamp);
        # what runs is the source generated here, never what the file holds, and a file that
        # differs from it (cut short, edited) is written anew, which makes numba's entries stale.
        if cache_files.read(file, strip=False) != self.source:
            cache_files.write(file, self.source, quiet=False)
        t0, c0 = time.perf_counter(), time.process_time()
        mod = types.ModuleType(name)
        mod.__file__ = file
        sys.modules[name] = mod
        self.cold = not cache_files.cached(cache, self.key)
        if self.cold:  # numba's SSA passes, the same IR in time linear in the names they fix,
            # its operator typing once per argument types, its liveness on bit sets, a type's
            # size asked of LLVM once, its callees optimized and emitted inside its entries only
            from .numba_patches import install_all

            install_all()
        slp = config.SLP_VECTORIZE
        if "\nLANES = " in self.source:  # LLVM's SLP vectorizer packs the lanes (no reassociation)
            config.SLP_VECTORIZE = 1
        enter_deep()  # numba's SSA pass recurses along long functions
        try:
            # (the module's import compiles its initializer: constant_globals.py)
            exec(compile(self.source, file, "exec"), mod.__dict__)
            self._compile(mod, bounded)
        finally:
            config.SLP_VECTORIZE = slp
            leave_deep()
        self.load_seconds = time.perf_counter() - t0
        if self.cold:  # what compiling it took, for TieredProgram's estimate in later processes
            self.cpu_seconds = time.process_time() - c0
            cache_files.write(
                os.path.join(folder, f"m{self.key}.compile"), f"{self.cpu_seconds:.3f}\n"
            )
        return mod

    def compile_seconds(self) -> float | None:
        """The CPU seconds numba took to compile this module cold, in this process or an earlier
        one (None when not recorded): what a compile beside the frames takes from them, where its
        wall time also counts the waits of a loaded machine."""
        if self.cold:
            return self.cpu_seconds
        text = cache_files.read(os.path.join(cache_files.folder(), f"m{self.key}.compile"))
        try:
            return float(text) if text else None
        except ValueError:
            return None

    def _inputs(
        self, mod: Any, values: dict | None, channels: Any = None
    ) -> tuple[np.ndarray, np.ndarray]:
        uf = np.zeros(max(1, mod.USLOTS["float"]), np.float32)
        ui = np.zeros(getattr(mod, "TM", max(1, mod.USLOTS["int"])), np.int32)
        values = dict(values or {})
        if getattr(mod, "TEXTURES", False):  # the channels after the uniforms (texture_calls.py)
            from ...shadertoy.channels import channel_uniforms
            from .texture_kernels import pack

            chans = list(channels or []) + [None] * 4
            for c, s in enumerate(chans[:4]):
                if s is not None and s.filter == "mipmap" and ({c, -1} & set(mod.LEVEL0)):
                    raise ValueError(
                        f"iChannel{c} has mipmaps, but the program was generated without them "
                        "(generate(..., mipmap=...))"
                    )
            values.update(channel_uniforms(chans[:4]))
            floats, meta = pack(chans[:4], uf.size)
            uf, ui = np.concatenate([uf, floats]), np.concatenate([ui, meta])
        elif channels is not None:
            from ...shadertoy.channels import channel_uniforms

            values.update(channel_uniforms(list(channels)))
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

    def budget(self) -> float:
        return self.frame_seconds if self.frame_seconds is not None else config.frame_seconds()

    def _compile(self, mod: Any, bounded: bool) -> None:
        """numba's compile (or cache load) of the module: a frame of no rows, which runs none of
        the shader's code but its global initializers."""
        seconds = max(self.budget(), COMPILE_SECONDS) if bounded else None
        self._frame(
            mod, 1, 0, np.zeros((1, 2)), *self._inputs(mod, None), seconds=seconds, first=True
        )

    def _frame(
        self,
        mod: Any,
        width: int,
        height: int,
        offs: np.ndarray,
        uf: np.ndarray,
        ui: np.ndarray,
        seconds: float | None = None,
        first: bool = False,
    ) -> np.ndarray:
        """One frame on the worker threads, within `seconds` (None: the frame budget); `first`:
        the call that compiles."""
        slots = mod.SLOTS
        gt = [
            np.zeros(max(1, slots[k]), dt)
            for k, dt in (
                ("float", np.float32),
                ("int", np.int32),
                ("uint", np.uint32),
                ("bool", np.bool_),
            )
        ]
        from .scalar import LoopCapError

        lt = np.zeros(1 + len(mod.LOOPS), np.int64)  # the budget, then a flag per loop id
        lt[0] = NO_LIMIT if self.loop_limit is None else self.loop_limit
        out = np.empty((height, width, 4), np.float32)
        if seconds is None and not first:
            seconds = self.budget()
        try:
            bands = (
                min(self.threads * 4, height)
                if width * height >= PARALLEL_PIXELS and self.threads > 1
                else 1
            )
            edges = [height * k // bands for k in range(bands + 1)]
            if getattr(
                mod, "QUADS", False
            ):  # a block is two rows (a 2x2 quad's): bands start at even rows
                edges = [e - e % 2 for e in edges[:-1]] + [height]
            calls = [
                (mod.render_rows, out, edges[k], edges[k + 1], width, height, offs, uf, ui, *gt, lt)
                for k in range(bands)
                if edges[k] < edges[k + 1] or first
            ]
            deadline = None if seconds is None else time.monotonic() + seconds
            # the globals' initializers run the shader's code too (and numba compiles them first)
            run_bounded(self.threads, [(mod.globals_template, uf, ui, *gt, lt)], deadline)
            run_bounded(self.threads, calls, deadline)
        except TimeoutError:
            assert seconds is not None  # (only a deadline times out)
            raise self._over_budget(mod, seconds, first) from None
        except LoopCapError as e:
            path, line, col = mod.LOOPS.get(int(e.args[0]), (self.path, 0, 0))
            raise GlslError(
                Diagnostic(
                    f"this loop ran more than {LOOP_CAP} times",
                    Location(path, line, col),
                    rule="compiled-engine",
                )
            ) from None
        self._limited |= {tuple(mod.LOOPS[lid][:2]) for lid in np.flatnonzero(lt[1:]) + 1}
        return out

    def limited_loops(self) -> list[tuple[str, int]]:
        """(file, line) of the loops llvmpipe's limiter stopped since the last call."""
        found, self._limited = sorted(self._limited), set()
        return found

    def _over_budget(self, mod: Any, seconds: float, first: bool) -> GlslError:
        path, line, col, name = getattr(mod, "ENTRY", (self.path, 1, 1, "mainImage"))
        how = "--frame-budget SECONDS (or GLSLCHECK_FRAME_SECONDS) sets the budget"
        if first:
            return GlslError(
                Diagnostic(
                    f"numba was still compiling this shader after {seconds:g} s (the frame "
                    "budget, at least "
                    f"{COMPILE_SECONDS:g} s); the compiled engine stopped waiting for it",
                    Location(path, line, col),
                    rule="compiled-frame-budget",
                    help="render with --backend numpy, or make the program shorter (numba's "
                    f"work grows with it); {how}",
                )
            )
        return GlslError(
            Diagnostic(
                f"the frame was still rendering after {seconds:g} s on the CPU, "
                f"in '{name}' or a function it calls; "
                "the compiled engine stopped waiting for it (a GPU would hang or reset)",
                Location(path, line, col),
                rule="compiled-frame-budget",
                help=f"bound the loops' iteration counts (nested loops multiply); {how}",
            )
        )

    @frame_inputs
    def render(
        self, inputs: FrameInputs, precision: str = "float32", stats: bool = False, channels=None
    ) -> np.ndarray:
        """One frame: float32 (height, width, 4), top row first (the NumPy backend's layout);
        `channels`: iChannel0..3's inputs (channels.ChannelInput or None), as NumpyProgram's."""
        if precision != "float32":
            raise ValueError("the compiled engine renders in float32 only")
        if stats:
            raise ValueError("stats=True needs backend='numpy'")
        mod = self.load()
        uf, ui = self._inputs(mod, inputs.uniforms(), channels)
        offs = np.array(inputs.offsets if len(inputs.offsets) > 1 else [(0.0, 0.0)], np.float64)
        return self._frame(mod, inputs.width, inputs.height, offs, uf, ui)


def compiled_folder() -> str:
    """The folder of the compiled modules, beside numba's cache (what other tiers record there
    lives with them)."""
    return cache_files.folder()


def write_cache_file(path: str, text: str) -> None:
    """A small record in the cache folder, written atomically; a read-only cache keeps none."""
    cache_files.write(path, text)


_FINGERPRINT: list[str] = []


def engine_fingerprint() -> str:
    """A hash of this engine's code and of the versions its modules depend on: a record about
    what the engine did with a shader holds for this fingerprint only."""
    if not _FINGERPRINT:
        here = os.path.dirname(__file__)
        h = hashlib.sha256(_versions().encode())
        for name in sorted(os.listdir(here)):
            if name.endswith(".py"):
                with open(os.path.join(here, name), "rb") as f:
                    h.update(f.read())
        _FINGERPRINT.append(h.hexdigest()[:24])
    return _FINGERPRINT[0]


def module_cached(key: str) -> bool:
    """Whether numba's cache holds the machine code of the module of this key."""
    return bool(key) and cache_files.cached(os.path.dirname(cache_files.folder()), key)


TIER_LANES = 8  # the lockstep width TieredProgram moves to (8: AVX2's float32 lanes)
OVER = "over budget"  # a marker's text when the lockstep build was stopped
EXITING = "exiting"  # build_apart's answer when the process exits under it
# Lockstep's cold compile over the per-pixel module's, for TieredProgram's estimate of what
# moving costs: the median over 125 lab and real shaders (quartiles 2.14 and 2.69, 0.96 to 5.7),
# in CPU seconds as compile_seconds records them (benchmarks/bench_lockstep_compile.py --lanes 0
# and --lanes 8; docs/performance.md, "The lockstep estimate measured again").
LOCKSTEP_COMPILE_RATIO = 2.4
# The most CPU time a lockstep compile may take: a module whose estimate (move_cost) is longer is
# not built, and a build still running after it is stopped (build_apart; the program stays per
# pixel, and later processes do not try again). The real corpora's lockstep compiles take a
# median of 3.3 s and at most 26 s CPU cold (h38-2d-sprites), for 2-4x faster frames.
LOCKSTEP_BUDGET = 30.0
# The most CPU time the default CPU program's compile of a per-pixel module may take beside the
# NumPy frames (tiered.py): the real corpora's per-pixel compiles take a median of 1.4 s and at
# most 7.5 s CPU cold (h38-2d-sprites), and they pay back more than lockstep's (NumPy frames are
# 3-10x the compiled engine's on heavy shaders); the budget leaves room for a slower machine.
PIXEL_BUDGET = 60.0
# Seconds of lockstep compile per line of the per-pixel module, the estimate when the per-pixel
# module's compile time is not known (a numba cache filled before compile times were recorded):
# the median of the same run (quartiles 0.0063 and 0.0124; a machine's speed moves it).
LOCKSTEP_SECONDS_PER_LINE = 0.0083
# Lockstep's first frames after a move, timed against the per-pixel frames before it (medians of
# so many): lockstep is slower than per pixel on light shaders whose loops run over constant
# arrays (the per-pixel module folds their globals; benchmarks/bench_compiled.py --lab-only).
LOCKSTEP_TRIAL_FRAMES = 3
# the per-pixel frames whose rates the trial compares with (the latest so many)
PIXEL_RATES_KEPT = 5
SLOWER = "slower"  # a marker's hint: the lockstep module lost its last trial against per pixel


class TieredProgram:
    """The compiled engine's default: per pixel first, lockstep once that pays.

    Lockstep (lanes.py) renders the same bits several times faster on heavy shaders, but numba
    compiles it several times longer than the per-pixel module (seconds to tens of seconds): a
    student's one render of a lab shader would wait for it and gain milliseconds. So frames are
    rendered per pixel until the time they have taken, counting the frame about to be rendered (its
    pixels at the rate measured so far), reaches what compiling lockstep is expected to cost; then
    the lockstep module is made beside the frames, which go on per pixel (numba compiles it in a
    child process, build_apart, and the frames' thread loads it from numba's cache before its next
    frame: no frame waits for the compile), and every frame after it is ready uses it. This is the
    ski-rental rule: whatever the number of frames to come, the total is at most about twice what
    the better of the two modes alone would have cost (moving too late costs at most the compile
    once more, moving never costs nothing when the frames stop first). A process that ends while the
    compile it paid for runs leaves it to finish (engine._leave_to_finish, build.py), for a later
    process to load: otherwise each process shorter than the compile would pay its rent and cut its
    compile off again. The expected cost: the lockstep module's load when numba's cache already
    holds it (an earlier process moved), else LOCKSTEP_COMPILE_RATIO x the per-pixel module's
    compile (CPU time: a compile beside the frames costs them the core it takes, not the waits of a
    loaded machine). The frames are the same either way: lockstep is bit-identical to per pixel
    (tests/compiled/test_lanes.py), so the moment of the move changes no pixel. A lockstep module
    that cannot be made (the rewrite falls back, numba fails) leaves the program per pixel, with a
    warning for a failure, and so does one expected to take more than LOCKSTEP_BUDGET CPU seconds to
    compile, or whose compile (in a child process: CompiledProgram.build_apart) takes more than
    that: the marker beside the per-pixel module then says so, and no later process builds it. A
    lockstep module is not always the faster: its first LOCKSTEP_TRIAL_FRAMES frames are timed
    against the per-pixel frames this process rendered before the move, and a module slower per
    pixel hands the frames back to the per-pixel one for good; the marker keeps the hint, so a later
    process starts per pixel and tries the (cached) lockstep module again once its load is paid (a
    timing depends on the machine's load: it is a hint, not a verdict).
    """

    def __init__(
        self, shader: Any, first: CompiledProgram, threads: int | None = None, tab: str = "Image"
    ) -> None:
        self.shader = shader
        self.tab = tab
        self.first = first
        self.threads = threads
        self.fast: CompiledProgram | None = None  # the lockstep program once moved
        self.stay = False  # the lockstep module cannot be made: per pixel for good
        self.spent = 0.0  # wall seconds of per-pixel frames
        self.paid = 0.0  # seconds of earlier frames towards the move (tiered.py's record)
        self.pixels = 0  # pixels those frames rendered
        self._lock = threading.Lock()
        self._found: list[
            str | None
        ] = []  # _cached_fast's answer, looked up once (it walks the cache)
        self._mover: threading.Thread | None = None  # the lockstep compile, once started
        self._built: CompiledProgram | None = None  # made by the mover, loaded by adopt
        self._over = False  # a lockstep build was stopped at the budget (over_budget)
        self._slower = False  # the marker's hint: lockstep lost its last trial (load_cached)
        # a caller's trial is timing these frames (tiered.py): no move starts meanwhile, which
        # would time a compile beside them or another mode (move_now still starts one)
        self.hold = False
        self.rates: list[float] = []  # seconds per pixel of the latest per-pixel frames
        self.trial: list[float] = []  # and of lockstep's first frames (its trial)

    @property
    def path(self) -> str:
        return self.first.path

    @property
    def source(self) -> str:
        return (self.fast or self.first).source

    @property
    def loop_limit(self) -> int | None:
        """llvmpipe's loop limiter (CompiledProgram.loop_limit), for both tiers."""
        return self.first.loop_limit

    @loop_limit.setter
    def loop_limit(self, limit: int | None) -> None:
        self.first.loop_limit = limit
        if self.fast is not None:
            self.fast.loop_limit = limit

    def limited_loops(self) -> list[tuple[str, int]]:
        found = set(self.first.limited_loops())
        if self.fast is not None:
            found |= set(self.fast.limited_loops())
        return sorted(found)

    @property
    def mode(self) -> str:
        return f"lanes{TIER_LANES}" if self.fast is not None else "pixel"

    def _marker(self) -> str:
        return os.path.join(cache_files.folder(), f"m{self.first.key}.lanes{TIER_LANES}")

    def _cached_fast(self) -> str | None:
        """The lockstep module's source when an earlier process made it and numba cached it
        (looked up on the first call: move_cost runs before every per-pixel frame)."""
        if not self._found:
            self._found.append(self._lookup_fast())
        return self._found[0]

    def over_budget(self) -> bool:
        """Whether a build of the lockstep module was stopped at LOCKSTEP_BUDGET (its marker)."""
        self._cached_fast()
        return self._over

    def _lookup_fast(self) -> str | None:
        marker = cache_files.read(self._marker())
        self._over = marker is not None and marker.startswith(OVER) and not _died(marker)
        key, _, hint = (marker or "").partition(" ")
        self._slower = hint == SLOWER
        if key in _SOURCES:  # loaded in this process already
            return _SOURCES[key]
        if not key or not cache_files.cached(os.path.dirname(cache_files.folder()), key):
            return None
        source = cache_files.read(
            os.path.join(cache_files.folder(), f"m{key}.py"), strip=False
        )  # as written: its hash is its key
        return source if source is not None and CompiledProgram(source, "").key == key else None

    def move_cost(self) -> float:
        """Expected wall seconds of making the lockstep module now (infinite when a build of it
        was stopped at the budget)."""
        if self.over_budget():
            return math.inf
        if self._cached_fast() is not None:
            return self.first.load_seconds or 0.0  # a cache load, as the per-pixel one was
        known = self.first.compile_seconds()
        if known is not None:
            return LOCKSTEP_COMPILE_RATIO * known
        return LOCKSTEP_SECONDS_PER_LINE * self.first.source.count("\n")

    def can_load_cached(self) -> bool:
        """Whether load_cached would load a module (or one is loaded)."""
        source = self._cached_fast()
        if self.fast is not None or source is None or self._slower:
            return self.fast is not None
        # (a module without llvmpipe's loop budget: _move makes the other)
        return self.first.loop_limit is None or BUDGET_OFF not in source

    def load_cached(self) -> bool:
        """Load the lockstep module now when an earlier process made it and numba's cache holds
        it (its marker), so that every frame is lockstep's: no per-pixel frame is left to pay
        for it. Whether it did."""
        source = self._cached_fast()
        if self.fast is not None or source is None or not self.can_load_cached():
            return self.fast is not None
        fast = CompiledProgram(source, self.first.path, self.threads, self._remake_fast)
        fast.frame_seconds = self.first.frame_seconds
        fast.loop_limit = self.first.loop_limit
        fast.load(bounded=False)  # a cache load
        self.fast = fast
        return True

    def _move(self) -> None:
        """Make the lockstep module (in the mover thread); self.fast once it can render."""
        try:
            budget = self.first.loop_limit is not None
            source = self._cached_fast()
            if source is None or (budget and BUDGET_OFF in source):
                source, _ = generate(self.shader, self.tab, lanes=TIER_LANES, budget=budget)
            if "LANES_FALLBACK" in source:
                self.stay = True
                return
            fast = CompiledProgram(source, self.first.path, self.threads, self._remake_fast)
            fast.frame_seconds = self.first.frame_seconds
            fast.loop_limit = self.first.loop_limit
            why = fast.build_apart(LOCKSTEP_BUDGET, finish_into=self._marker())
            if why in (EXITING, STARVED):  # (no verdict: the next process tries again)
                self.stay = True
                return
            if why == "over budget":
                cache_files.write(self._marker(), f"{OVER} {LOCKSTEP_BUDGET:g} s\n")
                self._over, self.stay = True, True
                return
            if why.startswith("killed"):
                raise RuntimeError(why)
            if why:  # a failure: its compile here gives the error
                fast.load(bounded=False)
        except Exception as e:  # noqa: BLE001 - an engine bug: the per-pixel program renders
            self._failed(e)
            return
        self._built = fast

    def adopt(self) -> None:
        """Load the lockstep module the mover made (machine code from numba's cache) in the
        frames' thread: a load beside the frames waits on their GIL, and slows them."""
        fast, self._built = self._built, None
        if fast is None:
            return
        try:
            fast.load(bounded=False)
        except Exception as e:  # noqa: BLE001 - as in _move
            self._failed(e)
            return
        cache_files.write(self._marker(), fast.key + "\n")
        self.fast = fast

    def ready(self) -> bool:
        """Whether the lockstep module is loaded or made."""
        return self.fast is not None or self._built is not None

    def _failed(self, e: Exception) -> None:
        """An engine bug in the lockstep path: per pixel for good, with a warning."""
        import warnings

        warnings.warn(
            f"glslcheck: the lockstep module failed to compile ({type(e).__name__}: {e}); "
            "rendering per pixel",
            RuntimeWarning,
            stacklevel=3,
        )
        self.stay = True

    def move_now(self) -> bool:
        """Start making the lockstep module now (a caller whose own frames paid for it: the
        tiered CPU program's NumPy frames), unless it is started, cannot be made, or is expected
        to take more than LOCKSTEP_BUDGET; whether a move is under way or done."""
        with self._lock:
            if self._mover is None and not self.stay and self.move_cost() <= LOCKSTEP_BUDGET:
                self._mover = threading.Thread(
                    target=self._move, name="glslcheck-lockstep", daemon=True
                )
                self._mover.start()
            return self._mover is not None

    def _remake_fast(self) -> str:
        return generate(self.shader, self.tab, lanes=TIER_LANES, budget=True)[0]

    def settle(self, timeout: float | None = None, adopt: bool = True) -> bool:
        """Wait for a lockstep compile under way (at most timeout seconds), then load it unless
        told not to (the mover of tiered.py, which leaves that to the frames' thread); whether
        none is left."""
        mover = self._mover
        if mover is not None:
            mover.join(timeout)
            if mover.is_alive():
                return False
        if adopt:
            self.adopt()
        return True

    @frame_inputs
    def render(
        self, inputs: FrameInputs, precision: str = "float32", stats: bool = False, channels=None
    ) -> np.ndarray:
        """One frame (CompiledProgram.render), by whichever program is current."""
        kw = dict(inputs.keywords(), precision=precision, stats=stats, channels=channels)
        self.adopt()
        with self._lock:
            if self._mover is None and not self.stay and not self.hold and self.pixels:
                ahead = self.spent / self.pixels * inputs.width * inputs.height
                cost = self.move_cost()  # (over the budget: not built, the frames stay per pixel)
                if cost <= LOCKSTEP_BUDGET and self.paid + self.spent + ahead >= cost:
                    # a daemon: a process that ends first drops the compile (numba writes its
                    # cache files whole, by rename; the marker follows a finished load)
                    self._mover = threading.Thread(
                        target=self._move, name="glslcheck-lockstep", daemon=True
                    )
                    self._mover.start()
        fast = self.fast
        pixels = inputs.width * inputs.height
        if fast is not None:
            if not self.rates or len(self.trial) >= LOCKSTEP_TRIAL_FRAMES:
                return fast.render(**kw)  # (no per-pixel frame to compare with: no trial)
            out, took = self._timed(fast.render, **kw)
            self._judge(took / pixels, fast)
            return out
        self.first.load()  # its compile is not a frame's time
        out, took = self._timed(self.first.render, **kw)
        with self._lock:
            self.spent += took
            self.pixels += pixels
            self.rates = [*self.rates, took / pixels][-PIXEL_RATES_KEPT:]
        return out

    def _timed(self, render: Any, **kw: Any) -> tuple[np.ndarray, float]:
        """One frame of either module's `render` and its wall seconds (the rule's one clock)."""
        t0 = time.perf_counter()
        out = render(**kw)
        return out, time.perf_counter() - t0

    def _judge(self, rate: float, fast: CompiledProgram) -> None:
        """Count one trial frame of the lockstep module (seconds per pixel); after
        LOCKSTEP_TRIAL_FRAMES, hand the frames back to per pixel when its median is not faster
        than the latest per-pixel frames' (the marker keeps the hint for later processes)."""
        self.trial.append(rate)
        if len(self.trial) < LOCKSTEP_TRIAL_FRAMES:
            return
        mine = sorted(self.trial)[len(self.trial) // 2]
        pixel = sorted(self.rates)[len(self.rates) // 2]
        if mine >= pixel:
            self.fast, self.stay = None, True
            cache_files.write(self._marker(), f"{fast.key} {SLOWER}\n")
        elif self._slower:  # won this time: a later process starts on it again
            self._slower = False
            cache_files.write(self._marker(), fast.key + "\n")


def compile_compiled(
    path_or_shader: Any,
    threads: int | None = None,
    budget: bool = False,
    tab: str | None = None,
) -> CompiledProgram | TieredProgram:
    """The compiled engine's program for a shader's tab (default its Image): a TieredProgram
    when the mode is not fixed (tiered()), else a CompiledProgram (`glslcheck.compile(path,
    backend="compiled")` wraps it in a Program). `budget`: made with llvmpipe's loop budget
    from the start, for a caller that sets `loop_limit` (which would otherwise generate the
    module again)."""
    from ...shadertoy.sources import Shader, load_shader

    shader = path_or_shader if isinstance(path_or_shader, Shader) else load_shader(path_or_shader)
    source, path = generate(shader, tab, budget=budget)
    prog = CompiledProgram(source, path, threads, lambda: generate(shader, tab, budget=True)[0])
    if (
        tiered() and "LANES_FALLBACK" not in source and "\nLANES = " not in source
    ):  # lockstep from the start: derivatives
        return TieredProgram(shader, prog, threads, tab or "Image")
    return prog
