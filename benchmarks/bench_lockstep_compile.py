"""What the lockstep modules of the real corpora cost to compile cold (the goal: a median of
<= 5 s and at most 30 s).

    python benchmarks/bench_lockstep_compile.py [--groups main,holdout] [--lanes 8]
        [--only NAME,...] [--timeout 300] [--passes 3] [--against CHECKOUT] [--json out.json]

Each shader runs in a child process of its own, one after the other (numba compiles on one
core; a compile that never ends costs that shader only, stopped at --timeout), which generates
the shader's module with --lanes pixels in lockstep (engine.generate) and loads it
(CompiledProgram.load: numba compiles every function the module's render loop reaches). All
children share one numba cache, empty at the start and first filled by a warm-up child (the
first lab shader, not counted): the runtime's functions it calls are then loaded from it, as on
a user's machine, and every module is compiled cold (its key is new to the cache). A runtime
function is compiled once a cache for each argument types, by the first shader that calls it
so (sin and cos, pow...): the "runtime" seconds of that shader, which the shaders after it in
the same run do not pay (the order of the shaders moves them).

Per shader: the seconds of generating the module ("gen") and of compiling it ("compile", numba's
wall time, the figure the goal is about; "cpu", the CPU time of it, which a loaded machine moves
less; "runtime", the part of it that compiled runtime functions the cache lacked, see above),
the module's lines, its largest function's statements, and numba's slowest passes over all its
functions (--passes of them). A shader the rewrite does not handle is compiled per pixel and
says so ("per pixel"). Then the median and the maximum of the compile times and the slowest
shaders, with the load average at the start and the end (the machine is shared: a loaded machine
moves every figure).

--against CHECKOUT: before and after a change. The shaders are compiled by that checkout's
glslcheck and by this one in turns (each with its own cache, warmed alike), so both see the same
load; per shader the ratios this / against of wall and CPU seconds, and their geometric means.
Make the checkout with `git worktree add /tmp/before COMMIT` (the shaders are read from this
checkout's folders).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)
sys.path.insert(0, os.path.join(ROOT, "tools"))

CHILD = r"""
import ast, json, sys, time
from collections import defaultdict

from numba.core import event

from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate
from glslcheck.backends.compiled_engine.numba_linking import MODULE_PREFIX
from glslcheck.shadertoy.sources import load_shader


# CPU seconds numba spends compiling functions that are not the module's (the runtime's, for
# argument types the cache lacks: numba signals compiles, not cache loads), counted from the
# outermost such compile (one thread compiles at a time: numba's compiler lock)
class Runtime(event.Listener):
    def __init__(self):
        self.depth, self.start, self.seconds = 0, 0.0, 0.0

    def on_start(self, ev):
        if not ev.data["dispatcher"].py_func.__module__.startswith(MODULE_PREFIX):
            if self.depth == 0:
                self.start = time.process_time()
            self.depth += 1

    def on_end(self, ev):
        if not ev.data["dispatcher"].py_func.__module__.startswith(MODULE_PREFIX):
            self.depth -= 1
            if self.depth == 0:
                self.seconds += time.process_time() - self.start


path, lanes = sys.argv[1], int(sys.argv[2])
t0 = time.perf_counter()
source, tab = generate(load_shader(path), lanes=lanes)
gen = time.perf_counter() - t0
prog = CompiledProgram(source, tab)
runtime = Runtime()
event.register("numba:compile", runtime)
c0 = time.process_time()
mod = prog.load(bounded=False)
cpu = time.process_time() - c0
# numba's passes over every function it compiled; type inference compiles the callees, so
# their whole time is taken off it (what is left: the typing of the functions themselves)
passes = defaultdict(float)
for key, obj in vars(mod).items():
    for cres in getattr(obj, "overloads", {}).values():
        whole = 0.0
        for timings in ((cres.metadata or {}).get("pipeline_times") or {}).values():
            for name, t in timings.items():
                passes[name.split("_", 1)[-1]] += t.init + t.run + t.finalize
                whole += t.init + t.run + t.finalize
        if key not in ("render_rows", "globals_template"):
            passes["nopython_type_inference"] -= whole
tree = ast.parse(source)
largest = max(
    (sum(1 for n in ast.walk(f) if isinstance(n, ast.stmt)), f.name)
    for f in tree.body
    if isinstance(f, ast.FunctionDef)
)
print(json.dumps(dict(
    gen=gen,
    compile=prog.load_seconds,
    cpu=cpu,
    runtime=runtime.seconds,
    cold=prog.cold,
    lockstep="LANES_FALLBACK" not in source and lanes > 0,
    lines=source.count("\n"),
    largest=largest,
    passes=sorted(passes.items(), key=lambda kv: -kv[1]),
)))
"""


def _load() -> str:
    return " ".join(f"{x:.1f}" for x in os.getloadavg())


def run_one(path: str, lanes: int, cache: str, timeout: float, root: str = ROOT) -> dict:
    """One shader's figures from a child process running the glslcheck of the checkout `root`
    (`error`/`timeout` when it gave none)."""
    env = dict(os.environ, NUMBA_CACHE_DIR=cache)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (root, env.get("PYTHONPATH")) if p)
    t0 = time.perf_counter()
    try:
        done = subprocess.run(
            [sys.executable, "-c", CHILD, path, str(lanes)],
            capture_output=True,
            text=True,
            timeout=timeout,
            env=env,
            cwd=root,
        )
    except subprocess.TimeoutExpired:
        return {"timeout": timeout, "wall": time.perf_counter() - t0}
    if done.returncode:
        lines = done.stderr.strip().splitlines()
        return {"error": lines[-1] if lines else f"exit {done.returncode}"}
    out = json.loads(done.stdout.strip().splitlines()[-1])
    out["wall"] = time.perf_counter() - t0
    return out


def _line(r: dict, passes: int, label: str) -> str:
    if "compile" not in r:
        what = f"timeout {r['timeout']:g} s" if "timeout" in r else f"error {r['error']}"
        return f"  {r['shader']:28s}{label} {what}"
    top = ", ".join(f"{n} {t:.1f}" for n, t in r["passes"][:passes])
    mode = "lockstep" if r["lockstep"] else "per pixel"
    return (
        f"  {r['shader']:28s}{label} compile {r['compile']:7.2f} s (cpu {r['cpu']:6.2f}, "
        f"runtime {r.get('runtime', 0.0):5.2f})"
        f"  gen {r['gen']:5.2f} s  {mode:9s} {r['lines']:6d} lines, largest "
        f"{r['largest'][1]} {r['largest'][0]} stmts  ({top})"
    )


def _seconds(r: dict, key: str) -> float | None:
    """A shader's compile seconds (`compile` or `cpu`); a compile stopped at the timeout took
    at least that long and counts as the timeout."""
    return r.get(key, r.get("timeout"))


def summary(rows: list, label: str) -> None:
    seconds = [s for r in rows if (s := _seconds(r, "compile")) is not None]
    if not seconds:
        return
    cpu = [s for r in rows if (s := _seconds(r, "cpu")) is not None]
    lock = [r["compile"] for r in rows if r.get("lockstep")]
    print(
        f"\n{label}{len(seconds)} shaders ({len(lock)} lockstep, "
        f"{sum('timeout' in r for r in rows)} timed out, "
        f"{sum('error' in r for r in rows)} failed): compile median "
        f"{statistics.median(seconds):.2f} s, max {max(seconds):.2f} s (cpu: median "
        f"{statistics.median(cpu):.2f} s, max {max(cpu):.2f} s)"
    )
    slow = sorted((r for r in rows if "error" not in r), key=lambda r: -_seconds(r, "compile"))
    print(
        "  slowest: " + ", ".join(f"{r['shader']} {_seconds(r, 'compile'):.1f} s" for r in slow[:5])
    )


def main() -> int:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--groups", default="main,holdout")
    ap.add_argument("--lanes", type=int, default=8)
    ap.add_argument("--only", default="")
    ap.add_argument("--timeout", type=float, default=300.0)
    ap.add_argument("--passes", type=int, default=3)
    ap.add_argument(
        "--against",
        default=None,
        help="another checkout (an older commit's `git worktree`): each shader compiled by it "
        "and by this one in turns, with the ratios",
    )
    ap.add_argument("--json", default=None)
    args = ap.parse_args()
    import engines_agree

    only = set(args.only.split(",")) if args.only else None
    paths = [
        p
        for g in args.groups.split(",")
        for p in engines_agree.shaders(g)
        if p.exists() and (only is None or p.stem in only or p.name in only)
    ]
    roots = ([("against", os.path.abspath(args.against))] if args.against else []) + [
        ("this", ROOT)
    ]
    print(f"load average at start: {_load()}; {len(paths)} shaders, lanes {args.lanes}", flush=True)
    rows: dict[str, list] = {name: [] for name, _ in roots}
    with tempfile.TemporaryDirectory(prefix="glslcheck-ctime-") as folder:
        caches = {}
        warm = sorted(p for p in (engines_agree.ROOT / "lab_shaders").iterdir() if p.is_dir())[0]
        for name, root in roots:
            caches[name] = os.path.join(folder, name)
            # the runtime's functions, cached
            run_one(str(warm), args.lanes, caches[name], args.timeout, root)
        for p in paths:
            for name, root in roots:
                r = run_one(str(p), args.lanes, caches[name], args.timeout, root)
                r["shader"] = p.stem if p.suffix else p.name
                rows[name].append(r)
                label = f" {name:7s}" if args.against else ""
                print(_line(r, args.passes, label), flush=True)
            if args.against:
                a, b = rows["against"][-1], rows["this"][-1]
                if "cpu" in a and "cpu" in b:
                    print(
                        f"  {'':28s} this / against: wall {b['compile'] / a['compile']:.2f}, "
                        f"cpu {b['cpu'] / a['cpu']:.2f}",
                        flush=True,
                    )
    for name, _ in roots:
        summary(rows[name], f"{name}: " if args.against else "")
    if args.against:
        pairs = [
            (a, b)
            for a, b in zip(rows["against"], rows["this"])
            if _seconds(a, "cpu") is not None and _seconds(b, "cpu") is not None
        ]
        if pairs:
            for key in ("compile", "cpu"):
                g = statistics.geometric_mean(_seconds(b, key) / _seconds(a, key) for a, b in pairs)
                print(f"  this / against, {key}: geometric mean {g:.2f} over {len(pairs)} shaders")
    print(f"load average at end: {_load()}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows if args.against else rows["this"], f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
