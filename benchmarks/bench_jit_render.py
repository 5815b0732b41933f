"""Whole renders with and without numba's compiled math kernels (backends/numpy_engine/jit.py).

    python benchmarks/bench_jit_render.py [--runs 3] [--modes off,on,auto] [--only NAME,...]

Each shader is rendered by a fresh `glslcheck render ... --jit MODE` process (NumPy backend,
tiles on threads), the modes in turns, `--runs` times each; it prints per mode the best and
median wall time of the whole process (numba's import and the kernels' load from its cache
included: what a user waits) and its CPU time (user + system), the ratios against `off`, and
whether auto loaded the kernels and after how many seconds of small-lane calls. The frames
(.npy, float32) of every mode must be bit-identical: a difference is printed and the exit code
is 1. numba's cache is the user's (see jit.cache_dir); run once beforehand so that `on` reads
it rather than compiling (benchmarks/bench_jit_kernels.py times the compile).

The default shaders are the raymarchers and ray tracers where the emulation's calls on few
lanes dominate, at sizes that take seconds, and the lab's 07_final (whole-tile calls:
auto must not load numba there): the real shaders' texts come from `python tools/real_verify.py
fetch` and `python tools/real_channels.py fetch` (git-ignored folders); missing ones are listed.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

# name: (shader, size, extra render arguments)
SHADERS = {
    "30-raymarch": ("tests/real_verify/texts/30-raymarch.glsl", "100x56", []),
    "36-raymarch": ("tests/real_verify/texts/36-raymarch.glsl", "100x56", []),
    "32-raytrace": ("tests/real_verify/texts/32-raytrace.glsl", "16x9", []),
    "elephant Buffer A": (
        "tests/real_channels/texts/elephant/shader.json",
        "100x56",
        ["--pass", "Buffer A"],
    ),
    "lab 07_final": ("lab_shaders/07_final", "800x450", []),
}

_RUN = """
import json, sys
from glslcheck.cli.main import main
code = main(sys.argv[1:])
from glslcheck.backends.numpy_engine import jit
s = jit._STATE
print(json.dumps({"code": code, "loaded": s.kernels is not None, "load": s.load_seconds, "spent": \
    s.spent,
                  "numba": "numba" in sys.modules}))
"""


def run_once(path: str, size: str, extra: list[str], mode: str, out: str) -> dict:
    args = [
        sys.executable,
        "-c",
        _RUN,
        "render",
        os.path.join(ROOT, path),
        "--size",
        size,
        "--time",
        "1.7",
        "--parallel",
        "threads",
        "--jit",
        mode,
        "--frame-budget",
        "900",
        "-o",
        out,
        *extra,
    ]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    done = subprocess.run(args, capture_output=True, text=True, cwd=ROOT)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        raise SystemExit(f"{path} --jit {mode}: exit {done.returncode}\n{done.stderr}")
    report = json.loads(done.stdout.strip().splitlines()[-1])
    report.update(
        wall=wall, cpu=(after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    )
    return report


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    for flag, kw in (
        ("--runs", dict(type=int, default=3)),
        ("--modes", dict(default="off,on,auto")),
        ("--only", dict(default="", help="comma-separated names of SHADERS")),
    ):
        ap.add_argument(flag, **kw)
    args = ap.parse_args()
    modes = args.modes.split(",")
    names = [n for n in SHADERS if not args.only or n in args.only.split(",")]
    print(
        f"load {' '.join(f'{v:.1f}' for v in os.getloadavg())}; {args.runs} runs per mode, "
        "in turns; wall and CPU seconds of the whole process"
    )
    failed = 0
    with tempfile.TemporaryDirectory() as tmp:
        for name in names:
            path, size, extra = SHADERS[name]
            if not os.path.exists(os.path.join(ROOT, path)):
                print(f"{name}: {path} not fetched, skipped")
                continue
            res: dict[str, list[dict]] = {m: [] for m in modes}
            for _ in range(args.runs):
                for m in modes:
                    res[m].append(run_once(path, size, extra, m, os.path.join(tmp, f"{m}.npy")))
            frames = {m: np.load(os.path.join(tmp, f"{m}.npy")) for m in modes}
            ref = frames[modes[0]]
            differ = {
                m: int((f.view(np.int32) != ref.view(np.int32)).sum()) for m, f in frames.items()
            }
            print(f"{name} ({size}):")
            base = {k: min(r[k] for r in res[modes[0]]) for k in ("wall", "cpu")}
            for m in modes:
                best = {k: min(r[k] for r in res[m]) for k in ("wall", "cpu")}
                med = {k: statistics.median(r[k] for r in res[m]) for k in ("wall", "cpu")}
                last = res[m][-1]
                jit = (
                    f"kernels loaded in {last['load']:.2f} s after {last['spent']:.2f} s of math "
                    "on NumPy"
                    if last["loaded"]
                    else f"no kernels ({last['spent']:.2f} s of math on NumPy counted)"
                )
                print(
                    f"  {m:4s} wall {best['wall']:7.2f} s (median {med['wall']:7.2f}, "
                    f"x{base['wall'] / best['wall']:.2f})"
                    f"  cpu {best['cpu']:7.2f} s (median {med['cpu']:7.2f}, "
                    f"x{base['cpu'] / best['cpu']:.2f})"
                    f"  {jit}; {differ[m]} values differ"
                )
                failed += differ[m] != 0
    print(
        f"load at the end {' '.join(f'{v:.1f}' for v in os.getloadavg())}; (xN: "
        f"{modes[0]}'s best / this mode's best)"
    )
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
