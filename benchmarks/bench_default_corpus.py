"""The default CPU program (`--backend auto`, backends/tiered.py) on the lab and the real
corpora against llvmpipe: what an animation costs from its second frame on, and where the
program settles.

    python benchmarks/bench_default_corpus.py [--groups lab,main,holdout] [--size 400x225]
        [--settle 60] [--length 0] [--frames 3] [--only NAME,...] [--timeout 300]
        [--json out.json]

Each shader runs in a process of its own with the user's numba cache (a first run on a machine
compiles the modules; later runs load them, as a user's later renders do):

1. The default program renders frames at 400x225 (`--size`), a new iTime each (1 + k/60), each
   computed (the NumPy backend's frame cache emptied: a shader that does not animate would cost
   nothing after its first frame), until
   it has settled: it stays on the NumPy backend for good (the tiered program's `stay`: refused,
   differs, slower, over budget), or the compiled engine renders past its trial and its own
   lockstep move is made or ruled out; or `--settle` seconds of frames have passed. With
   `--length` S, frames go on after it settles until S seconds have passed: animations of one
   length, whose "from frame 2" compares between programs that settle at different times (a
   program that settles at once would otherwise be judged on its few first frames alone).
2. Then `--frames` frames of the settled program and as many of llvmpipe (the GL backend, same
   process, same inputs), in turns.

Figures per shader, wall time (the NumPy backend renders on worker processes, whose CPU time its
process does not count): "settled", the settled program's median frame over llvmpipe's; "from
frame 2", the mean of every frame from the second to the last settled one over llvmpipe's median
(an animation of that many frames, the frames before the move included); the engine it settled
on; the frames and seconds it took. Per group: geometric mean and worst of both ratios.
Corpora: tests/real_verify (`python tools/real_verify.py [--set holdout] fetch`); shaders not
fetched are left out.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)
sys.path.insert(0, os.path.join(ROOT, "tools"))

ONE = r"""
import json, statistics, sys, time
import glslcheck
from glslcheck.base.diagnostics import GlslError

path, size, settle, extra = sys.argv[1], sys.argv[2], float(sys.argv[3]), int(sys.argv[4])
length = float(sys.argv[5])
w, h = (int(x) for x in size.split("x"))
prog = glslcheck.compile(path)
impl = prog.impl


def render(side, k):
    # every frame computed: the NumPy backend's frame cache would serve a shader that does not
    # animate for free after its first frame (bench.py's _forget_frames)
    cache = getattr(side.impl, "_cache", None)
    if cache is not None:
        cache.clear()
    t = time.perf_counter()
    side.render(size=(w, h), time=1.0 + k / 60)
    return time.perf_counter() - t


def settled():
    # every pass (a multipass shader's MultipassProgram holds one program a pass); a NumPy
    # program (GLSLCHECK_TIERS=off) has nothing to move
    passes = impl.programs.values() if hasattr(impl, "programs") else [impl]
    return all(getattr(p, "settled", lambda: True)() for p in passes)


times, k, done, took, at = [], 0, False, 0.0, 0
t0 = time.perf_counter()
while True:
    times.append(render(prog, k))
    k += 1
    now = time.perf_counter() - t0
    if not done:
        done, took, at = settled(), now, k
    if (done and now >= length) or now > max(settle, length):
        break
gl = glslcheck.compile(path, backend="gl")
gl.render(size=(w, h), time=1.0)  # warm-up
mine, theirs = [], []
for j in range(extra):
    for side, out in ((prog, mine), (gl, theirs)):
        out.append(render(side, k + j))
times += mine
gl_frame = statistics.median(theirs)
print(json.dumps({
    "engine": prog.engine, "settled": statistics.median(mine) / gl_frame,
    "from2": statistics.mean(times[1:]) / gl_frame, "frames": at, "seconds": took,
    "done": done, "stay": getattr(impl, "stay", None), "gl_ms": gl_frame * 1000,
}))
"""


def shaders(groups: list[str], only: set[str]) -> list[tuple[str, str, str]]:
    """(group, name, path) of each shader, the corpora's fetched texts only."""
    import engines_agree

    out = []
    for g in groups:
        for p in engines_agree.shaders(g):
            if p.exists() and (not only or p.stem in only):
                out.append((g, p.stem, str(p)))
    return out


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--groups", default="lab,main,holdout")
    p.add_argument("--size", default="400x225")
    p.add_argument("--settle", type=float, default=60.0, help="seconds of frames to settle in")
    p.add_argument(
        "--length", type=float, default=0.0, help="seconds of frames at least (after settling)"
    )
    p.add_argument("--frames", type=int, default=3, help="settled frames timed against GL")
    p.add_argument("--only", default="", help="comma-separated shader names")
    p.add_argument("--timeout", type=float, default=300.0)
    p.add_argument("--json", default="", help="write every shader's figures there")
    args = p.parse_args()
    env = dict(os.environ, PYTHONPATH=ROOT)
    rows = []
    only = set(filter(None, args.only.split(",")))
    for group, name, path in shaders(args.groups.split(","), only):
        cmd = [sys.executable, "-c", ONE, path, args.size, str(args.settle), str(args.frames)]
        cmd.append(str(args.length))
        try:
            out = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=args.timeout)
            last = out.stdout.strip().splitlines()[-1:] or [""]
            row = json.loads(last[0]) if out.returncode == 0 else None
            why = "" if row else (out.stderr.strip().splitlines() or ["?"])[-1][:120]
        except subprocess.TimeoutExpired:
            row, why = None, f"timeout after {args.timeout:g} s"
        if row is None:
            print(f"{group:8s} {name:28s} error: {why}", flush=True)
            rows.append({"group": group, "name": name, "error": why})
            continue
        row.update(group=group, name=name)
        rows.append(row)
        stay = f"  ({row['stay']})" if row["stay"] else ""
        print(
            f"{group:8s} {name:28s} settled {row['settled']:6.2f}x  from frame 2 "
            f"{row['from2']:6.2f}x  {row['engine']:16s} {row['frames']:4d} frames "
            f"{row['seconds']:6.1f} s{'' if row['done'] else ' (not settled)'}  gl "
            f"{row['gl_ms']:.1f} ms{stay}",
            flush=True,
        )
    print()
    for group in dict.fromkeys(r["group"] for r in rows):
        ok = [r for r in rows if r["group"] == group and "error" not in r]
        if not ok:
            continue
        parts = []
        for key, label in (("settled", "settled"), ("from2", "from frame 2")):
            geo = math.exp(sum(math.log(r[key]) for r in ok) / len(ok))
            worst = max(ok, key=lambda r: r[key])
            over3 = sum(r[key] > 3 for r in ok)
            parts.append(
                f"{label}: geometric mean {geo:.2f}x, worst {worst[key]:.2f}x ({worst['name']}), "
                f"{over3} over 3x"
            )
        engines: dict[str, int] = {}
        for r in ok:
            engines[r["engine"]] = engines.get(r["engine"], 0) + 1
        errors = sum(1 for r in rows if r["group"] == group and "error" in r)
        print(
            f"{group}: {len(ok)} shaders{f' ({errors} errors)' if errors else ''}; "
            + "; ".join(parts)
            + "; settled on "
            + ", ".join(f"{e} {n}" for e, n in sorted(engines.items()))
        )
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
