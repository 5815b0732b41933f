"""The compiled engine against the NumPy backend on the real textured and multipass shaders of
tests/real_channels (fetched by `python tools/real_channels.py fetch`): bit for bit, over
consecutive frames, the buffers carried by the one multipass driver.

    python tools/compiled_channels.py [--size 48x27] [--frames 2] [--timeout 300] [--only ID,...]
                                      [--default]

Verdicts, one per shader, each in its own process (numba's compile is seconds to minutes):

- same bits: every frame of the Image pass equal, bit for bit (a NaN for a NaN);
- differs: the most pixels that differ in a frame;
- compiled refuses: the compiled engine's located error (what it does not run yet);
- numpy refuses: the NumPy backend (or glslcheck) refuses the shader (a cube map, ...);
- timeout / error.

`--default` runs the default CPU program (`--backend auto`, backends/tiered.py) instead of
`--backend compiled`, made to move each pass at once and without a timing trial (its check
frame still compares the engines): frame 0 on NumPy, the moves made (one compile at a time),
then every later frame by whichever engine each pass settled on, against the NumPy backend's.
Each line adds the passes' engines and, for a pass kept on NumPy, why. Its tier records go to a
temporary folder (none reaches the user's cache).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from real_channels import load_manifest, shader_path  # noqa: E402
from real_verify import run_child  # noqa: E402


def _one(path: str, size: tuple[int, int], frames: int) -> dict:
    import numpy as np

    import glslcheck
    from glslcheck.base.diagnostics import GlslError, InputError

    try:
        numpy_prog = glslcheck.compile(path, backend="numpy")
    except (GlslError, InputError) as e:
        return {"verdict": "numpy refuses", "reason": str(e).splitlines()[0][:200]}
    try:
        compiled = glslcheck.compile(path, backend="compiled")
    except GlslError as e:
        return {"verdict": "compiled refuses", "reason": str(e).splitlines()[0][:200]}
    worst, seconds = 0, {"numpy": 0.0, "compiled": 0.0}
    for f in range(frames):
        kw = dict(size=size, time=f / 60, frame=f)
        t0 = time.perf_counter()
        try:
            want = numpy_prog.render(**kw)
        except GlslError as e:
            return {"verdict": "numpy refuses", "reason": str(e).splitlines()[0][:200]}
        seconds["numpy"] += time.perf_counter() - t0
        t0 = time.perf_counter()
        try:
            got = compiled.render(**kw)
        except GlslError as e:
            return {"verdict": "compiled refuses", "reason": str(e).splitlines()[0][:200]}
        seconds["compiled"] += time.perf_counter() - t0
        same = (got.view(np.uint32) == want.view(np.uint32)) | (np.isnan(got) & np.isnan(want))
        worst = max(worst, int((~same.all(axis=-1)).sum()))
    return {
        "verdict": "same bits" if worst == 0 else "differs",
        "pixels": worst,
        "seconds": {k: round(v, 1) for k, v in seconds.items()},  # the compile included
    }


def _one_default(path: str, size: tuple[int, int], frames: int) -> dict:
    import tempfile

    import numpy as np

    import glslcheck
    from glslcheck.backends import tiered
    from glslcheck.base.diagnostics import GlslError, InputError

    records = tempfile.mkdtemp()
    # move at once, no timing trial: the check frame alone decides
    tiered.COMPILE_GUESS_SECONDS = tiered.CACHED_LOAD_SECONDS = 0.0
    tiered.TRIAL_FRAMES = 0
    tiered.TieredCpuProgram._record_path = lambda self: f"{records}/{self.tab}.tier"
    try:
        numpy_prog = glslcheck.compile(path, backend="numpy")
        prog = glslcheck.compile(path)
        passes = getattr(prog.impl, "programs", {"Image": prog.impl})
        worst, engines = 0, {}
        for f in range(frames):
            kw = dict(size=size, time=f / 60, frame=f)
            want, got = numpy_prog.render(**kw), prog.render(**kw)
            same = (got.view(np.uint32) == want.view(np.uint32)) | (np.isnan(got) & np.isnan(want))
            worst = max(worst, int((~same.all(axis=-1)).sum()))
            if f == 0:
                for p in passes.values():
                    p.settle()
            engines = {t: p.engine + (f" ({p.stay})" if p.stay else "") for t, p in passes.items()}
    except (GlslError, InputError) as e:
        return {"verdict": "numpy refuses", "reason": str(e).splitlines()[0][:200]}
    return {"verdict": "same bits" if worst == 0 else "differs", "pixels": worst, **engines}


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--size", default="48x27")
    p.add_argument("--frames", type=int, default=2)
    p.add_argument("--timeout", type=float, default=300.0)
    p.add_argument("--only", default="", help="comma-separated shader ids")
    p.add_argument("--default", action="store_true", help="the default CPU program, moved at once")
    p.add_argument("--child", default=None, help=argparse.SUPPRESS)
    args = p.parse_args()
    w, h = (int(v) for v in args.size.lower().split("x"))
    if args.child:
        one = _one_default if args.default else _one
        print(json.dumps(one(args.child, (w, h), args.frames)))
        return 0
    only = set(filter(None, args.only.split(",")))
    counts: dict[str, int] = {}
    for entry in load_manifest()["shaders"]:
        if only and entry["id"] not in only:
            continue
        path = shader_path(entry)
        if not path.exists():
            print(f"{entry['id']}: not fetched (python tools/real_channels.py fetch)")
            continue
        cmd = [sys.executable, __file__, "--child", str(path), "--size", args.size]
        cmd += ["--frames", str(args.frames)] + (["--default"] if args.default else [])
        result = run_child(cmd, args.timeout)
        counts[result["verdict"]] = counts.get(result["verdict"], 0) + 1
        print(f"{entry['id']:<34} {json.dumps(result)}", flush=True)
    print(", ".join(f"{v}: {n}" for v, n in sorted(counts.items())))
    return 0


if __name__ == "__main__":
    sys.exit(main())
