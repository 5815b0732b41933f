"""The default CPU program (`--backend auto`): the NumPy backend's frames first, the compiled
engine's once they pay, the same bits.

The NumPy backend's first frame is the cheapest there is (a transpile and a module import: tenths of
a second), while the compiled engine renders each frame several times faster but must first be
compiled by numba (seconds; a cache load in a later process). So frames are rendered by the NumPy
backend until the time they have taken, counting the frame about to be rendered (its pixels at the
rate measured so far), reaches what making the compiled program is expected to cost
(`TieredCpuProgram.move_cost`); then the compiled program is made beside the frames, which go on in
NumPy (no frame waits for numba): numba compiles it in a child process
(CompiledProgram.build_apart), stopped after engine.PIXEL_BUDGET seconds of its CPU time (the shader
then stays on NumPy, and the record keeps it there), and the frames' own thread loads the machine
code from numba's cache before its next frame (tenths of a second; in another thread the load waits
on the frames' interpreter lock and slows them); every frame after it is ready and checked uses it.
This is the compiled engine's ski-rental rule (compiled_engine/engine.py, TieredProgram) with the
NumPy backend as the first tier: whatever the number of frames, the total is at most about twice
what the better engine alone would have cost. The compiled program is itself tiered (per pixel, then
lockstep within engine.LOCKSTEP_BUDGET).

The move happens only where the two engines are known to give the same bits:

* frames the compiled engine renders at all: float32, no lane statistics, numba installed; any
  pass (Image or Buffer A-D, each pass of a multipass shader a program of its own, moving on its
  own frames) with the channel inputs channels.json binds: the check and trial frames below
  sample the same `ChannelInput`s on both engines (buffers carried from frame to frame by
  backends/multipass.py, feedback included). llvmpipe's loop limiter (verify's) is passed on to
  the compiled program, which emulates it alike, while a driver's float-to-uint model other than
  this machine's keeps the frames on NumPy;
* a shader the compiled engine compiles (one with a construct it refuses stays on NumPy);
* and agrees on: the compiled program's first frame renders the inputs of the last NumPy frame
  before the move, and each of its trial frames (below) is rendered by both engines; any pixel
  of a different bit pattern (NaN for NaN excepted) in any of them keeps the program on NumPy
  for good. Bits that differ only at inputs no checked frame had (the engines' known
  differences are listed in tests/compiled/test_engines_agree.py) are not caught: these checks
  are evidence on the frames this shader renders, the agreement tests are the proof;
* and is faster on: the compiled program's first TRIAL_FRAMES frames, per pixel, against the
  NumPy backend's renders of the same frames (the check renders them, and timing them there
  compares the engines at one load, past the NumPy backend's start-up: a process's first NumPy
  frames start worker processes and load kernels, and a move that comes early would otherwise
  be judged against them). A light shader's NumPy frames, whose uniform values are computed
  once a tile, can beat the compiled engine's per-pixel ones. A
  per-pixel program's own move to lockstep waits for the trial's end (a compile beside the
  trial frames, or a mode changed among them, would be what the trial times), and counts the
  NumPy frames before it as paid towards lockstep's compile (the rent of the ski rental is
  every frame rendered on a slower engine: lockstep comes about as soon as they paid for it). A
  per-pixel program found slower hands the frames back to NumPy until they have paid for its
  lockstep module too (engine.TieredProgram.move_cost, within engine.LOCKSTEP_BUDGET), which is
  then made beside them, checked on one frame against NumPy's and tried the same way; slower
  again (or no lockstep module, or a differing frame), NumPy keeps the frames for good.

The verdict, the compiled module's key, what compiling it took (CPU seconds) and the seconds of
frames rendered before lockstep in every process so far are kept beside numba's cache
(`<cache>/compiled/t<hash>.tier`, keyed by the NumPy module, the loop limiter, the compiled
engine's code and the pass's channel bindings): a later process moves as soon as the cache load
pays, counts the earlier processes' frames as paid towards its lockstep module (the ski rental
over all the frames a user renders of a shader, not each process's alone), starts on that
module when an earlier process made it (TieredProgram.load_cached) or makes it first when it
is paid for (unless the per-pixel module is cached and won its last trial: the record's
"pixel" hint), and never retries a shader refused or found to differ (a timing trial lost is
not kept as a verdict: it depends on the machine's load).
`GLSLCHECK_TIERS=off` (config.tiers) keeps every frame on NumPy. One compile runs at a time in
a process (`_COMPILING`): the passes of a multipass shader that pay at the same frame compile one
after another instead of taking every core from the frames.
"""

from __future__ import annotations

import hashlib
import json
import os
import threading
import time
import warnings
from typing import Any

import numpy as np

from ..base import config
from ..shadertoy.frame_inputs import FrameInputs, frame_inputs
from .interface import Backend

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from .compiled_engine.engine import CompiledProgram, TieredProgram
    from .numpy_engine.program import NumpyProgram

# Expected wall seconds of numba's first compile of a shader's per-pixel module when nothing is
# known about it yet: the hidden real set's median was 2.0 s (max 16 s), the lab shaders 4-7 s
# on a loaded 2-core machine (benchmarks/bench_default.py prints both).
COMPILE_GUESS_SECONDS = 3.0
# The compiled program's first frames, each timed against the NumPy backend's render of it (the
# medians of so many, per pixel): a compiled engine slower on this shader (the NumPy backend
# computes uniform values once a tile, the compiled one per pixel) hands the frames back.
TRIAL_FRAMES = 3
# How often (seconds of frames before lockstep) the record keeps them for later processes
REMEMBER_SECONDS = 2.0
# Expected seconds of loading the compiled module from numba's cache (import of numba included:
# 0.45 s measured on a lab shader, 0.04 s once numba is loaded).
CACHED_LOAD_SECONDS = 0.5
# held by a move while numba compiles its module (one compile at a time in a process)
_COMPILING = threading.Lock()
_KEEPING = threading.Lock()  # held while a record is updated and written


class TieredCpuProgram:
    """A NumPy program (`first`) that moves its frames to the compiled engine once that pays
    (module docstring). Every attribute it does not define is the NumPy program's (`parallel`,
    `threads`, `loop_limit`, `format_stats`, ...), read and set there."""

    # its own attributes (the names annotated here), set in __init__ through __dict__
    shader: Any
    tab: str
    first: NumpyProgram
    second: CompiledProgram | TieredProgram | None
    stay: str | None
    spent: float
    pixels: int
    _lock: threading.Lock
    _mover: threading.Thread | None
    _ready: tuple | None
    _record: dict | None
    numpy_rate: float
    trial: list[float]
    numpy_trial: list[float]
    later: TieredProgram | None
    engine: str
    paid: float
    _kept: float

    def __init__(self, shader: Any, first: NumpyProgram, tab: str = "Image") -> None:
        d = self.__dict__
        d["shader"] = shader
        d["tab"] = tab  # the pass it renders
        d["first"] = first
        d["second"] = None  # the compiled program, once made and checked
        d["stay"] = None  # why the frames stay on NumPy for good (None: they may move)
        d["spent"] = 0.0  # wall seconds of NumPy frames that could have moved
        d["pixels"] = 0  # their pixels
        d["_lock"] = threading.Lock()
        d["_mover"] = None  # the thread that makes the compiled program, once started
        d["_ready"] = None  # (program, check frame's inputs, its NumPy pixels) to load: _finish
        d["_record"] = None  # the tier record read from the cache folder ({} when none)
        d["trial"] = []  # seconds per pixel of the compiled program's first frames
        d["numpy_trial"] = []  # and of the NumPy backend's renders of the same frames
        d["numpy_rate"] = 0.0  # the median of those, once the trial is over
        # a compiled program slower per pixel that may still move to lockstep (engine's
        # TieredProgram): tried again once its lockstep module is ready
        d["later"] = None
        d["engine"] = "numpy"  # the engine that rendered the last frame (`mode` at that time)
        # seconds of frames earlier processes rendered before lockstep (the record's "spent"),
        # and this process's as last written there (_remember)
        d["paid"] = 0.0
        d["_kept"] = 0.0

    def __getattr__(self, name: str) -> Any:
        return getattr(self.__dict__["first"], name)

    def __setattr__(self, name: str, value: Any) -> None:
        if name in TieredCpuProgram.__annotations__:
            self.__dict__[name] = value
            return
        setattr(self.first, name, value)
        if name == "loop_limit":  # both engines stop loops alike
            for other in (self.second, self.later):
                if other is not None:
                    other.loop_limit = value

    def limited_loops(self) -> list[tuple[str, int]]:
        """(file, line) of the loops llvmpipe's limiter stopped, in the frames of either engine
        since the last call (NumpyProgram.limited_loops)."""
        found = set(self.first.limited_loops())
        for other in (self.second, self.later):
            if other is not None:
                found |= set(other.limited_loops())
        return sorted(found)

    @property
    def source(self) -> str:
        return self.first.source

    @property
    def mode(self) -> str:
        """Which engine renders the next frame: "numpy", or the compiled program's mode
        ("compiled pixel", "compiled lanes8")."""
        second = self.second
        if second is None:
            return "numpy"
        mode = getattr(second, "mode", None)
        if mode is None:  # a program of one mode (lockstep from the start: derivatives)
            width = second.source.partition("\nLANES = ")[2].split(" ", 1)[0]
            mode = f"lanes{width}" if width else "pixel"
        return f"compiled {mode}"

    # -- the record kept beside numba's cache ----------------------------------------------------
    def _record_path(self) -> str | None:
        from ..shadertoy.channels import load_bindings
        from .compiled_engine.engine import compiled_folder, engine_fingerprint

        try:
            folder = compiled_folder()
            # (llvmpipe's loop limiter makes another compiled module, with a verdict of its own)
            limit = self.first.loop_limit
            # (the bindings choose the compiled module's mipmap lookups and the texels sampled)
            bound = sorted(repr(b) for b in load_bindings(self.shader)[1] if b.tab == self.tab)
            h = hashlib.sha256(
                f"{engine_fingerprint()} {limit} {self.tab} {bound}\n{self.first.source}".encode()
            )
        except OSError:
            return None
        return os.path.join(folder, f"t{h.hexdigest()[:24]}.tier")

    def record(self) -> dict:
        """The tier record of this shader from an earlier run ({} when none)."""
        if self._record is None:
            found: dict = {}
            path = self._record_path()
            if path is not None:
                try:
                    with open(path, encoding="utf-8") as f:
                        found = json.load(f)
                except (OSError, ValueError):
                    found = {}
            self._record = found if isinstance(found, dict) else {}
            spent = self._record.get("spent")
            self.paid = float(spent) if isinstance(spent, (int, float)) and spent > 0 else 0.0
        return self._record

    def _remember(self) -> None:
        """Keep in the record the seconds of this pass's frames rendered before lockstep, in
        every process so far, every REMEMBER_SECONDS of them: a later process counts them as
        paid towards its moves (the ski rental over all the frames a user renders of it)."""
        tier = self.second or self.later
        rent = self.spent + getattr(tier, "spent", 0.0)
        if self.stay is not None or getattr(tier, "fast", None) is not None:
            return
        if rent - self._kept >= REMEMBER_SECONDS:
            self.record()  # (read first: it sets `paid`)
            self._kept = rent
            self._keep(spent=round(self.paid + rent, 3))

    def _keep(self, **fields: Any) -> None:
        from .compiled_engine.engine import write_cache_file

        path = self._record_path()
        with _KEEPING:  # (the mover's verdict and the frames' seconds, from two threads)
            self._record = {**self.record(), **fields}
            if path is not None:
                write_cache_file(path, json.dumps(self._record) + "\n")

    # -- the rule --------------------------------------------------------------------------------
    def move_cost(self) -> float:
        """Expected wall seconds of making the compiled program now."""
        rec = self.record()
        if rec.get("verdict") == "same":
            from .compiled_engine.engine import module_cached

            if module_cached(str(rec.get("key", ""))):
                return CACHED_LOAD_SECONDS
            if isinstance(rec.get("seconds"), (int, float)):
                return float(rec["seconds"])
        return COMPILE_GUESS_SECONDS

    def _refusal(self, precision: str, stats: bool) -> str:
        """Why this frame cannot move ("" when it can)."""
        if precision != "float32":
            return "precision"
        if stats:
            return "stats"
        return ""

    def _eligible(self) -> str:
        """Why no frame of this program can move ("" when they can)."""
        from .compiled_engine.engine import available
        from .driver_profile import host_model

        if not config.tiers():
            return "GLSLCHECK_TIERS=off"
        if not available():
            return "numba is not installed"
        if self.first.meta.get("float_to_uint", host_model()) != host_model():
            return "a driver's float-to-uint model"
        verdict = self.record().get("verdict")
        if verdict not in (None, "same"):
            return verdict
        return ""

    @frame_inputs
    def render(
        self, inputs: FrameInputs, precision: str = "float32", stats: bool = False, channels=None
    ) -> np.ndarray:
        """One frame (NumpyProgram.render), by whichever engine is current."""
        kw = inputs.keywords()
        why = self._refusal(precision, stats)
        # a compiled frame: the same inputs, channels included
        ckw = {**kw, "channels": channels} if channels is not None else kw
        pixels = inputs.width * inputs.height
        if self._ready is not None:
            self._finish()
        second = self.second
        if second is not None and not why:
            if len(self.trial) >= TRIAL_FRAMES:
                self.engine = self.mode
                out = second.render(**ckw)
                self._remember()
                return out
            # a trial frame: checked against the NumPy backend's render of it, both timed
            got, took = self._timed(second.render, **ckw)
            out, numpy_took = self._timed(
                self.first.render, **kw, precision=precision, stats=stats, channels=channels
            )
            self.engine = "numpy"
            differ = _differing(got, out)
            if differ:
                self.second, self.later = None, None
                self.stay = f"differs: {differ} pixels of a trial frame"
                self._keep(verdict=self.stay)
            else:
                self._judge(took / pixels, numpy_took / pixels)
            return out
        later = self.later
        self.engine = "numpy"
        if later is not None and not why and getattr(later, "fast", None) is not None:
            # lockstep is ready: this frame on both engines (the check), then a new trial
            out = self.first.render(**kw, precision=precision, stats=stats, channels=channels)
            self.later, self.trial, self.numpy_trial = None, [], []
            differ = _differing(later.render(**ckw), out)
            if differ:
                self.stay = f"differs: {differ} pixels of the lockstep check frame"
                self._keep(verdict=self.stay)
            else:
                self.second = later
            return out
        out, took = self._timed(
            self.first.render, **kw, precision=precision, stats=stats, channels=channels
        )
        if why:
            return out
        with self._lock:
            self.spent += took
            self.pixels += pixels
            if later is not None and (
                later.stay
                or later.over_budget()
                or (self.paid + self.spent >= later.move_cost() and not later.move_now())
            ):
                self._give_up(later)
            if self._mover is not None or self.stay is not None:
                self._remember()
                return out
            # the next frame of this size, at the rate measured so far
            ahead = self.spent / self.pixels * pixels
            # (no move costs less than a cache load: a quick frame reads no record; the cost
            # reads it, and with it what earlier processes paid)
            if self.spent + ahead < CACHED_LOAD_SECONDS:
                return out
            if self.spent + ahead < self.move_cost() - self.paid:
                self._remember()
                return out
            why = self._eligible()
            if why:
                self.stay = why
                return out
            # a daemon: a process that ends first drops the move (and stops the compile's child
            # process: engine.build_apart); the check frame is this one
            self._mover = threading.Thread(
                target=self._move, args=(ckw, out.copy()), name="glslcheck-tier", daemon=True
            )
            self._mover.start()
        return out

    def _timed(self, render: Any, **kw: Any) -> tuple[np.ndarray, float]:
        """One frame of either engine's `render` and its wall seconds (the rule's one clock)."""
        t0 = time.perf_counter()
        out = render(**kw)
        return out, time.perf_counter() - t0

    def _judge(self, rate: float, numpy_rate: float) -> None:
        """Count one trial frame (seconds per pixel of the compiled program's render and of the
        NumPy backend's); after TRIAL_FRAMES, keep the compiled program only when its median is
        faster than the NumPy backend's."""
        from .compiled_engine.engine import TieredProgram

        self.trial.append(rate)
        self.numpy_trial.append(numpy_rate)
        if len(self.trial) < TRIAL_FRAMES:
            return
        mine = sorted(self.trial)[len(self.trial) // 2]
        self.numpy_rate = sorted(self.numpy_trial)[len(self.numpy_trial) // 2]
        if isinstance(self.second, TieredProgram):
            self.second.hold = False  # the trial is over: its own move is its rule's again
            self.second.paid = self.paid + self.spent  # (the NumPy frames during the compile)
        pixel = isinstance(self.second, TieredProgram) and self.second.mode == "pixel"
        if pixel:  # (a hint for a later process's order of tiers, not a verdict: _move)
            self._keep(pixel="slower" if mine >= self.numpy_rate else "faster")
        if mine < self.numpy_rate:
            return
        second, self.second = self.second, None
        # (a per-pixel TieredProgram whose lockstep module may still be made)
        if isinstance(second, TieredProgram) and second.mode == "pixel" and not second.stay:
            self.later = second  # NumPy frames until lockstep pays and is made, then a trial
            return
        # (not recorded: a timing on a loaded machine; a later process tries again)
        self.stay = (
            f"slower: the compiled engine {mine * 1e9:.0f} ns a pixel, "
            f"the NumPy backend {self.numpy_rate * 1e9:.0f}"
        )

    def _give_up(self, later: Any) -> None:
        """The lockstep module of a slower per-pixel program cannot be made: NumPy for good."""
        self.later = None
        self.stay = "slower: the compiled engine per pixel, and no lockstep module"

    def _move(self, kw: dict, want: np.ndarray) -> None:
        """Make the compiled program (in the mover thread): generate it and have numba compile
        it into its cache; `_finish`, in the frames' thread, loads and checks it."""
        from .compiled_engine.budget import STARVED
        from .compiled_engine.engine import (
            EXITING,
            PIXEL_BUDGET,
            CompiledProgram,
            compile_compiled,
            module_cached,
        )

        try:
            limit = self.first.loop_limit  # (verify's: the module counts loop passes)
            # (the Image: the compiled engine picks the Image or a plain GLSL file's one tab)
            tab = None if self.tab == "Image" else self.tab
            prog = compile_compiled(self.shader, budget=limit is not None, tab=tab)
            if limit is not None:
                prog.loop_limit = limit
            base = prog if isinstance(prog, CompiledProgram) else prog.first
            base.frame_seconds = self.first.frame_seconds
            if not isinstance(prog, CompiledProgram):
                # lockstep's rent: the frames before it, earlier processes' and this one's NumPy
                # frames alike (the rule's rent is every frame on a slower engine)
                prog.paid = self.paid + self.spent
            # a lockstep module an earlier process made: its frames from the first (checked and
            # tried like any), with nothing to compile; or one that earlier processes' frames
            # have paid for, made now in place of the per-pixel tier when that would be
            # compiled too, or lost its last trial (its trial frames cost both engines' frames
            # again); a per-pixel module that won renders beside lockstep's compile instead
            if not isinstance(prog, CompiledProgram) and not prog.can_load_cached():
                skip = self.record().get("pixel") == "slower" or not module_cached(base.key)
                if skip and prog.paid >= prog.move_cost() and prog.move_now():
                    with _COMPILING:
                        prog.settle(None, adopt=False)
            if isinstance(prog, CompiledProgram) or not prog.ready():
                # numba's compile in a child process, stopped at the budget: the NumPy frames
                # keep this process's GIL and cores (but the one it takes)
                with _COMPILING:
                    why = base.build_apart(PIXEL_BUDGET)
                if why == EXITING:  # (the process ends: no verdict)
                    return
                if why == STARVED:  # (the machine's load: not kept, a later process tries)
                    self.stay = f"{why}: numba's compile got too little of a loaded machine"
                    return
                if why == "over budget":
                    self.stay = f"over budget: numba's compile passed {PIXEL_BUDGET:g} s of CPU"
                    self._keep(verdict=self.stay)
                    return
                if why.startswith("killed"):
                    raise RuntimeError(why)
                if why:  # a failure: its compile here gives the error
                    base.load(bounded=False)
        except Exception as e:  # noqa: BLE001 - refused, or an engine bug: NumPy renders on
            self._failed(e)
            return
        self._ready = (prog, kw, want)

    def _finish(self) -> None:
        """Load the compiled program the mover made (machine code from numba's cache) and check
        it on the NumPy frame the move started on, in the frames' thread: a load beside NumPy
        frames waits on their GIL, and slows them."""
        from .compiled_engine.engine import CompiledProgram

        ready, self._ready = self._ready, None
        if ready is None:
            return
        prog, kw, want = ready
        try:
            if not isinstance(prog, CompiledProgram) and not prog.load_cached():
                prog.adopt()  # a lockstep module made in place of the per-pixel tier
            got = prog.render(**kw)
        except Exception as e:  # noqa: BLE001 - as in _move
            self._failed(e)
            return
        differ = _differing(got, want)
        if differ:
            self.stay = f"differs: {differ} pixels of the check frame"
            self._keep(verdict=self.stay)
            return
        base = prog if isinstance(prog, CompiledProgram) else prog.first
        fields: dict[str, Any] = {"verdict": "same", "key": base.key}
        seconds = base.compile_seconds()  # (the child's compile, recorded beside the module)
        if seconds is not None:
            fields["seconds"] = round(seconds, 3)
        self._keep(**fields)
        if not isinstance(prog, CompiledProgram):
            prog.hold = TRIAL_FRAMES > 0  # its own move waits for the trial (_judge)
        self.second = prog

    def _failed(self, e: Exception) -> None:
        """The frames stay on NumPy: a construct the compiled engine refuses (a loop cap, a
        budget: kept as the verdict), or an engine bug (a warning; tried again later)."""
        from ..base.diagnostics import GlslError

        if isinstance(e, GlslError):
            first = e.diagnostics[0] if getattr(e, "diagnostics", None) else None
            self.stay = f"refused: {first.message if first is not None else e}"
            self._keep(verdict=self.stay)
            return
        warnings.warn(
            f"glslcheck: the compiled engine failed on this shader ({type(e).__name__}: {e}); "
            "rendering with the NumPy backend",
            RuntimeWarning,
            stacklevel=3,
        )
        self.stay = f"failed: {type(e).__name__}"

    def settled(self) -> bool:
        """Whether the engine of this program's frames is decided: NumPy for good (`stay`), or
        the compiled program past its trial with its own move to lockstep made or ruled out."""
        if self.stay is not None:
            return True
        from .compiled_engine.engine import TieredProgram

        second = self.second
        if second is None or len(self.trial) < TRIAL_FRAMES:
            return False
        if not isinstance(second, TieredProgram):  # a program of one fixed mode
            return True
        return bool(second.fast is not None or second.stay or second.over_budget())

    def settle(self, timeout: float | None = None) -> bool:
        """Wait for a move under way (at most `timeout` seconds); whether none is left."""
        mover = self._mover
        if mover is not None:
            mover.join(timeout)
            if mover.is_alive():
                return False
        self._finish()
        second = self.second
        return second is None or getattr(second, "settle", lambda t: True)(timeout)


def _differing(got: np.ndarray, want: np.ndarray) -> int:
    """Pixels of different bit patterns (a NaN for a NaN is the same)."""
    same = (got.view(np.uint32) == want.view(np.uint32)) | (np.isnan(got) & np.isnan(want))
    return int((~same.all(axis=-1)).sum())


def compile_tiered(shader: Any, tab: str = "Image") -> Any:
    """The default CPU program of one pass (the Image or a Buffer): a TieredCpuProgram, or the
    NumPy backend's program when GLSLCHECK_TIERS=off."""
    from .numpy_engine.program import compile_numpy

    first = compile_numpy(shader, tab if tab != "Image" else None)
    if not config.tiers():
        return first
    return TieredCpuProgram(shader, first, tab)


def _compile_pass(shader: Any, tab: str) -> Any:
    return compile_tiered(shader, tab)


BACKEND = Backend(
    name="auto",
    title="CPU (NumPy, then compiled)",
    called="the default CPU program",
    precisions=("float16", "float32", "float64"),
    multipass=True,
    lane_stats=True,
    driver=False,
    needs="",
    compile_pass=_compile_pass,
    program_text=lambda program: program.source,
)
