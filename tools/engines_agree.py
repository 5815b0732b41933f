"""Do the two CPU engines give one answer? Render each shader with the NumPy backend and the
compiled engine (per pixel, and 8 pixels in lockstep) and compare the bits.

    python tools/engines_agree.py [--groups lab,main,holdout,fbm,pathtracers,scenes]
                                  [--size 64x36] [--times 0,1.3,2.67,...] [--frame N]
                                  [--mouse 40,20,40,20] [--lanes 0,8]
                                  [--only NAME,...] [--timeout 600] [--json out.json]

The shaders: lab_shaders/* (`lab`), the real corpora of tools/real_verify.py (`main`: texts/,
`holdout`: holdout_texts/, `fbm`: fbm_texts/, `pathtracers`: pathtracers_texts/, fetched by
`python tools/real_verify.py [--set NAME] fetch`) and the render benchmark's scenes (`scenes`:
benchmarks/scenes/*). Both engines render as `verify` runs the CPU side: loops stop as
llvmpipe's do (verify.llvmpipe_loop_limit); where GLSL leaves a value to the CPU (uint() of a
negative float) both take this machine's predicted model (driver_profile.host_model), which
verify replaces by the live driver's when it differs.

The frames: one a time, as an animation at 60 fps has them (iFrame = round(60 * iTime), or
--frame N for all), the mouse button down (--mouse) in the first, third, ... frame and released
in the others (Shadertoy's iMouse after a click: z and w negative). An engine can differ at
some inputs only (a value computed from iTime rounds to the other side at some times), so the
default times are many and not round, at a small size that keeps the renders cheap.

Each shader runs in its own process (a compile that crashes or a frame that never ends costs
that shader only) and gets one line per lockstep width:

- identical: every frame the same bits (a NaN equals any NaN: GLSL does not define payloads);
- differs: the frames that differ, and in the first of them (its iTime, iFrame and iMouse) the
  differing pixels, the largest difference, and the first differing pixel (x, y from the top
  left) with both engines' values;
- refused: an engine (or both) stops with an error, named with its message;
- per pixel: the lockstep rewrite does not handle the program (the engine renders it one pixel
  a call, what the per-pixel line measures), and why;
- timeout / error: the process did not answer in --timeout, or failed otherwise.

Exit status 0 when no shader differs or errs, 1 otherwise.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
GROUPS = ("lab", "main", "holdout", "fbm", "pathtracers", "scenes")
VERDICTS = ("identical", "differs", "refused", "per pixel", "timeout", "error")
# iTime of the frames compared: 0 and times spread up to minutes, none a round number (a value
# computed from iTime may round otherwise in one engine at some times only)
TIMES = (0.0, 1.3, 2.67, 6.1, 9.83, 37.7, 123.4)
SIZE = (64, 36)
MOUSE = (40.0, 20.0, 40.0, 20.0)


def frames(
    times: list[float], frame: int | None = None, mouse: tuple[float, ...] = MOUSE
) -> list[dict]:
    """The render inputs of the frames compared: one a time, iFrame as an animation at 60 fps
    has it (or `frame` for all), the mouse button down in every other frame and released (z and
    w negative, as on Shadertoy) in the others."""
    x, y, z, w = mouse
    released = (x, y, -abs(z), -abs(w))
    return [
        dict(
            time=t,
            frame=round(60 * t) if frame is None else frame,
            mouse=tuple(mouse) if i % 2 == 0 else released,
        )
        for i, t in enumerate(times)
    ]


def shaders(group: str) -> list[Path]:
    """The shader paths of one group, in a stable order (the corpora: only the fetched texts)."""
    if group == "lab":
        return sorted(p for p in (ROOT / "lab_shaders").iterdir() if p.is_dir())
    if group == "scenes":
        return sorted(p for p in (ROOT / "benchmarks" / "scenes").iterdir() if p.is_dir())
    if group in ("main", "holdout", "fbm", "pathtracers"):
        from real_verify import set_paths  # this folder: the corpora's one home

        return set_paths(group)
    raise SystemExit(f"unknown group {group!r}: one of {', '.join(GROUPS)}")


def _refusal(e: BaseException) -> str:
    from glslcheck.base.diagnostics import GlslError

    if isinstance(e, GlslError):
        d = e.diagnostics[0]
        if d.loc is None:
            return d.message[:300]
        path = str(d.loc.path)
        where = os.path.relpath(path, ROOT) if os.path.isabs(path) else path
        return f"{where}:{d.loc.line}:{d.loc.column}: {d.message}"[:300]
    return f"{type(e).__name__}: {e}"[:300]


def compare(a, b) -> dict | None:
    """None when two float32 images hold the same bits (NaN = NaN), else what differs."""
    import numpy as np

    same = (a.view(np.uint32) == b.view(np.uint32)) | (np.isnan(a) & np.isnan(b))
    bad = ~same.all(axis=-1)
    if not bad.any():
        return None
    with np.errstate(invalid="ignore", over="ignore"):
        diff = np.abs(a.astype(np.float64) - b.astype(np.float64))
    diff = np.where(np.isnan(diff), np.inf, diff)  # a NaN on one side only
    y, x = (int(v) for v in np.argwhere(bad)[0])
    return {
        "pixels": int(bad.sum()),
        "max_abs": float(diff[bad].max()),
        "first": [x, y],
        "numpy": [float(v) for v in a[y, x]],
        "compiled": [float(v) for v in b[y, x]],
    }


def agree_one(
    path: str,
    size: tuple[int, int],
    times: list[float],
    frame: int | None = None,
    mouse: tuple[float, float, float, float] = MOUSE,
    lanes: tuple[int, ...] = (0, 8),
) -> list[dict]:
    """One result per lockstep width: {"lanes", "verdict", "reason", and for "differs" "diff"
    (the first differing frame's) and "frames" (how many of them differ)}; the frames: frames()."""
    from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate
    from glslcheck.backends.numpy_engine.backend import BACKEND as NUMPY
    from glslcheck.base.diagnostics import GlslError
    from glslcheck.shadertoy.sources import load_shader
    from glslcheck.verification.verify import llvmpipe_loop_limit

    scene = Path(path)
    if scene.parent == ROOT / "benchmarks" / "scenes" and scene.name == "textured":
        # its texture is made by the channel benchmark, into a copy of the folder
        sys.path.insert(0, str(ROOT / "benchmarks"))
        from bench_channels import copy_scene

        folder = tempfile.TemporaryDirectory(prefix="engines-agree-")  # gone with the call
        path = copy_scene(scene.name, folder.name)
    shader = load_shader(path)
    inputs = frames(times, frame, mouse)
    try:
        numpy = NUMPY.compile_pass(shader, "Image")
        llvmpipe_loop_limit(numpy)
        reference = [numpy.render(size=size, **kw) for kw in inputs]
    except GlslError as e:
        return [
            {"lanes": w, "verdict": "refused", "reason": "numpy: " + _refusal(e)} for w in lanes
        ]
    out = []
    for width in lanes:
        try:
            source, where = generate(shader, lanes=width, budget=True)
            if width and "LANES_FALLBACK" in source:
                why = source.rsplit("LANES_FALLBACK = ", 1)[1].split("  #")[0]
                out.append({"lanes": width, "verdict": "per pixel", "reason": why})
                continue
            prog = CompiledProgram(source, where)
            llvmpipe_loop_limit(prog)
            images = [prog.render(size=size, **kw) for kw in inputs]
        except GlslError as e:
            out.append({"lanes": width, "verdict": "refused", "reason": "compiled: " + _refusal(e)})
            continue
        result = {"lanes": width, "verdict": "identical", "reason": ""}
        diffs = [
            dict(d, **kw)
            for kw, a, b in zip(inputs, reference, images, strict=True)
            if (d := compare(a, b)) is not None
        ]
        if diffs:
            d = diffs[0]
            mouse_text = ",".join(f"{v:g}" for v in d["mouse"])
            result.update(
                verdict="differs",
                diff=d,
                frames=len(diffs),
                reason=(
                    f"{len(diffs)} of {len(inputs)} frames; t={d['time']:g} "
                    f"iFrame {d['frame']} iMouse {mouse_text}: {d['pixels']} px, "
                    f"max {d['max_abs']:.3g}, first {d['first'][0]},{d['first'][1]}: "
                    f"numpy {_rgba(d['numpy'])} compiled {_rgba(d['compiled'])}"
                ),
            )
        out.append(result)
    return out


def _rgba(v: list[float]) -> str:
    return "(" + ", ".join(f"{x:.9g}" for x in v) + ")"


def run_child(cmd: list[str], timeout: float, lanes: tuple[int, ...]) -> list[dict]:
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, cwd=ROOT)
    except subprocess.TimeoutExpired:
        return [{"lanes": w, "verdict": "timeout", "reason": f"over {timeout:g} s"} for w in lanes]
    lines = proc.stdout.strip().splitlines()
    if proc.returncode == 0 and lines:
        return json.loads(lines[-1])
    tail = (proc.stderr.strip().splitlines() or ["(no output)"])[-1]
    return [{"lanes": w, "verdict": "error", "reason": tail[:300]} for w in lanes]


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["_one"]:
        args = json.loads(argv[1])
        print(json.dumps(agree_one(**args)))
        return 0
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--groups", default=",".join(GROUPS))
    p.add_argument("--size", default="x".join(map(str, SIZE)))
    p.add_argument("--times", default=",".join(f"{t:g}" for t in TIMES), help="iTime of each frame")
    p.add_argument("--frame", help="iFrame of every frame (default: round(60 * iTime) each)")
    p.add_argument(
        "--mouse",
        default=",".join(f"{v:g}" for v in MOUSE),
        help="iMouse x,y,z,w of every other frame (z>0: button down; released in the others)",
    )
    p.add_argument("--lanes", default="0,8", help="the compiled engine's widths (0: per pixel)")
    p.add_argument("--only", default="", help="comma-separated shader names (file or folder stem)")
    p.add_argument("--timeout", type=float, default=600.0)
    p.add_argument("--json", type=Path, help="write the per-shader results here")
    a = p.parse_args(argv)
    from glslcheck.base.limits import parse_frame, parse_mouse, parse_size, parse_times

    size = parse_size(a.size)
    times = list(parse_times(a.times))
    frame = None if a.frame is None else parse_frame(a.frame)
    lanes = tuple(int(w) for w in a.lanes.split(","))
    mouse = parse_mouse(a.mouse)
    only = {s for s in a.only.split(",") if s}
    results = []
    for group in a.groups.split(","):
        paths = [s for s in shaders(group) if not only or s.stem in only]
        absent = [s for s in paths if not s.exists()]
        if absent:
            print(
                f"{group}: {len(absent)} texts not fetched (python tools/real_verify.py fetch)",
                file=sys.stderr,
            )
        for path in (s for s in paths if s.exists()):
            started = time.perf_counter()
            job = dict(
                path=str(path), size=size, times=times, frame=frame, mouse=mouse, lanes=lanes
            )
            rows = run_child([sys.executable, __file__, "_one", json.dumps(job)], a.timeout, lanes)
            seconds = round(time.perf_counter() - started, 1)
            for r in rows:
                r.update(group=group, shader=path.stem, seconds=seconds)
                results.append(r)
                print(
                    f"{group:<8} {path.stem:<26} L{r['lanes']:<2} {r['verdict']:<10} "
                    f"{seconds:6.1f}s  {r['reason']}",
                    flush=True,
                )
    print()
    for w in lanes:
        mine = [r for r in results if r["lanes"] == w]
        counts = "  ".join(f"{v}: {sum(r['verdict'] == v for r in mine)}" for v in VERDICTS)
        print(f"lanes {w}: {counts}")
    if a.json:
        a.json.write_text(json.dumps(results, indent=1))
    return 1 if any(r["verdict"] in ("differs", "timeout", "error") for r in results) else 0


if __name__ == "__main__":
    sys.path.insert(0, str(ROOT))
    raise SystemExit(main())
