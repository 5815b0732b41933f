"""A/B of the lockstep engine's branch-free math: backends/compiled_engine/lanes_math.py as it was
at a git revision against the working tree's, on the same lockstep modules, in one process.

    python benchmarks/ab_lanes_math.py --rev 287eb58 [--size 400x225] [--repeat 7] SHADER ...

(--rev may also be the path of a lanes_math.py file.)

SHADER: a shader folder (lab_shaders/07_final) or a one-file shader (a real corpus text,
tests/real_verify/texts/57-2d.glsl). For each, the lockstep module (8 lanes) is generated once
and compiled twice, without numba's cache: importing the revision's lanes_math (loaded from
`git show`, as the module ``glslcheck.backends.compiled_engine.lanes_math_ab``) and the working
tree's. Both render the same frames in turns (each at a new iTime); printed: whether the two images
have the same bits, and the best CPU time (time.process_time) of --repeat frames of each, with their
ratio. One process, so the machine's load moves both sides alike: the way a change to lanes_math.py
is judged (docs/performance.md), a full bench_compiled.py run moving per-shader ratios by 0.5-3.4x
between runs.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time
import types

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)

IMPORT = "from glslcheck.backends.compiled_engine.lanes_math import *"
AB_NAME = "glslcheck.backends.compiled_engine.lanes_math_ab"


def load_revision(rev: str) -> None:
    """lanes_math.py of ``rev`` (a git revision, or the path of a file) as the module AB_NAME
    (its relative imports resolve in the package)."""
    if os.path.isfile(rev):
        with open(rev) as f:
            text = f.read()
    else:
        text = None
        # the file's home, then where it lived before the package was laid out by stage
        for path in (
            "glslcheck/backends/compiled_engine/lanes_math.py",
            "glslcheck/compiled_backend/lanes_math.py",
        ):
            done = subprocess.run(
                ["git", "show", f"{rev}:{path}"], cwd=ROOT, capture_output=True, text=True
            )
            if done.returncode == 0:
                text = done.stdout.replace("from ..numpy_backend", "from ..numpy_engine")
                break
        if text is None:
            raise SystemExit(f"{rev}: no lanes_math.py at that revision")
    assert "cache=True" in text, "lanes_math.py's numba options changed: update this script"
    mod = types.ModuleType(AB_NAME)
    mod.__package__ = "glslcheck.backends.compiled_engine"
    mod.__file__ = os.path.join(
        ROOT, "glslcheck", "backends", "compiled_engine", "lanes_math_ab.py"
    )  # not written
    sys.modules[AB_NAME] = mod
    exec(
        compile(text.replace("cache=True", "cache=False"), f"lanes_math.py@{rev}", "exec"),
        mod.__dict__,
    )


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument(
        "--rev",
        required=True,
        help="the git revision whose lanes_math.py is 'before' (or a file's path)",
    )
    ap.add_argument("--size", default="400x225")
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("shaders", nargs="+")
    args = ap.parse_args()
    import numpy as np

    from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate
    from glslcheck.backends.numpy_engine import jit
    from glslcheck.shadertoy.sources import load_shader

    jit.use_cache_dir()
    load_revision(args.rev)
    size = tuple(int(v) for v in args.size.split("x"))
    print(
        f"lanes_math.py at {args.rev} (before) against the working tree (after), lockstep 8, "
        f"{args.size}, best of {args.repeat} frames, CPU"
    )
    for path in args.shaders:
        source, tab = generate(load_shader(path), lanes=8)
        if IMPORT not in source:
            print(f"{path}: no lanes_math import in its module (per-pixel fallback?)")
            continue
        # both compiled now: numba's cache keys a module by its text and the working tree's
        # runtime, so a cached 'before' could hold another revision's inlined math
        source = source.replace("cache=True", "cache=False")
        progs = {
            "before": CompiledProgram(
                source.replace(IMPORT, IMPORT.replace("lanes_math", "lanes_math_ab")), tab
            ),
            "after": CompiledProgram(source, tab),
        }
        for p in progs.values():
            p.load()
        images = {k: p.render(size=size, time=1.3) for k, p in progs.items()}
        same = bool((images["before"].view(np.uint32) == images["after"].view(np.uint32)).all())
        best = dict.fromkeys(progs, float("inf"))
        for r in range(args.repeat):
            for k, p in progs.items():
                c0 = time.process_time()
                p.render(size=size, time=1.0 + r * 0.01)
                best[k] = min(best[k], time.process_time() - c0)
        name = os.path.basename(path.rstrip("/"))
        print(
            f"  {name:32s} same bits {str(same):5s}  before {best['before'] * 1e3:8.1f} ms  "
            f"after {best['after'] * 1e3:8.1f} ms  after/before "
            f"{best['after'] / best['before']:.3f}",
            flush=True,
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
