"""The compiled engine's two tiers (engine.TieredProgram) against each mode alone, as a user meets
them.

    python benchmarks/bench_tiers.py [--size 400x225] [--frames 1,30] [--only ID,...]

For each shader (default: a cheap lab shader and two of the real corpus's slowest; real ids
need `tools/real_verify.py fetch`) and each frame count, three runs, each a process of its own
with numba's cache as a first run of that shader finds it (the scalar runtime compiled, no
module of this shader): per pixel only (GLSLCHECK_COMPILED_LANES=0), lockstep only (=8) and
the default (tiers). Each run compiles the program and renders the frames (a new iTime each)
through glslcheck's API; the figure is that run's wall time, compile included, as a `render
--frames N` waits for it. Prints the three totals, the mode the default ended in, and the
default's total over the better mode alone's (the ski-rental rule's promise: at most about 2).
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)
sys.path.insert(0, os.path.join(ROOT, "tools"))

DEFAULT = "05_blinn_phong,29-raymarch,30-raymarch"

RUN = r"""
import json, sys, time
t0 = time.perf_counter()
from glslcheck.backends.compiled_engine.engine import compile_compiled
prog = compile_compiled(sys.argv[1])
w, h = (int(x) for x in sys.argv[2].split("x"))
for k in range(int(sys.argv[3])):
    prog.impl.render(size=(w, h), time=1.0 + k / 60)
print(json.dumps({"seconds": time.perf_counter() - t0,
                  "mode": getattr(prog.impl, "mode", "fixed")}))
"""


def _path(name: str) -> str:
    lab = os.path.join(ROOT, "lab_shaders", name)
    if os.path.isdir(lab):
        return lab
    import real_verify

    for e in real_verify.load_manifest():
        if e["id"] == name:
            return str(real_verify.text_path(e))
    raise SystemExit(f"bench_tiers: no shader {name!r}")


def _run(path: str, size: str, frames: int, lanes: str | None, cache: str) -> dict:
    env = dict(os.environ, NUMBA_CACHE_DIR=cache, GLSLCHECK_JIT="off")
    env.pop("GLSLCHECK_COMPILED_LANES", None)
    if lanes is not None:
        env["GLSLCHECK_COMPILED_LANES"] = lanes
    out = subprocess.run(
        [sys.executable, "-c", RUN, path, size, str(frames)],
        env=env,
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
    )
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> int:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--size", default="400x225")
    ap.add_argument("--frames", default="1,30")
    ap.add_argument("--only", default=DEFAULT)
    args = ap.parse_args()
    base = tempfile.mkdtemp(prefix="glslcheck-tiers-")
    warm = os.path.join(base, "runtime")
    # the scalar runtime's own cache: a first run of any shader compiles it once
    _run(os.path.join(ROOT, "lab_shaders", "01_spheres_raytraced"), "8x8", 1, "0", warm)
    shutil.rmtree(os.path.join(warm, "compiled"), ignore_errors=True)
    print(f"load average at start: {' '.join(f'{x:.1f}' for x in os.getloadavg())}", flush=True)
    worst = 0.0
    for name in args.only.split(","):
        path = _path(name)
        for frames in (int(x) for x in args.frames.split(",")):
            got = {}
            for label, lanes in (("pixel", "0"), ("lanes8", "8"), ("tiers", None)):
                cache = os.path.join(base, f"{name}-{frames}-{label}")
                shutil.copytree(warm, cache)
                got[label] = _run(path, args.size, frames, lanes, cache)
                shutil.rmtree(cache, ignore_errors=True)
            best = min(got["pixel"]["seconds"], got["lanes8"]["seconds"])
            over = got["tiers"]["seconds"] / best
            worst = max(worst, over)
            print(
                f"  {name:24s} {frames:4d} frames  per pixel {got['pixel']['seconds']:7.1f} s  "
                f"lockstep {got['lanes8']['seconds']:7.1f} s  tiers "
                f"{got['tiers']['seconds']:7.1f} s "
                f"(ended {got['tiers']['mode']})  tiers / better {over:.2f}",
                flush=True,
            )
    print(f"worst tiers / better mode alone: {worst:.2f}")
    print(f"load average at end: {' '.join(f'{x:.1f}' for x in os.getloadavg())}")
    shutil.rmtree(base, ignore_errors=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
