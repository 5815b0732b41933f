"""Do the two CPU engines give one answer? Render each shader with the NumPy backend and the
compiled engine (per pixel, and 8 pixels in lockstep) and compare the bits.

    python tools/engines_agree.py [--groups lab,main,holdout,scenes] [--size 64x36]
                                  [--times 0,1.3] [--frame 60] [--mouse 40,20,40,20]
                                  [--lanes 0,8] [--only NAME,...] [--timeout 600] [--json out.json]

The shaders: lab_shaders/* (`lab`), the real corpora of tools/real_verify.py (`main`: texts/,
`holdout`: holdout_texts/, fetched by `python tools/real_verify.py [--set holdout] fetch`) and
the render benchmark's scenes (`scenes`: benchmarks/scenes/*). Both engines render as `verify`
runs the CPU side: loops stop as llvmpipe's do (verify.llvmpipe_loop_limit); where GLSL leaves
a value to the CPU (uint() of a negative float) both take this machine's predicted model
(driver_profile.host_model), which verify replaces by the live driver's when it differs.

Each shader runs in its own process (a compile that crashes or a frame that never ends costs
that shader only) and gets one line per lockstep width:

- identical: every frame the same bits (a NaN equals any NaN: GLSL does not define payloads);
- differs: the pixels that differ in the first frame that does, the largest difference, and the
  first differing pixel (x, y from the top left) with both engines' values;
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
GROUPS = ("lab", "main", "holdout", "scenes")
VERDICTS = ("identical", "differs", "refused", "per pixel", "timeout", "error")


def shaders(group: str) -> list[Path]:
    """The shader paths of one group, in a stable order (the corpora: only the fetched texts)."""
    if group == "lab":
        return sorted(p for p in (ROOT / "lab_shaders").iterdir() if p.is_dir())
    if group == "scenes":
        return sorted(p for p in (ROOT / "benchmarks" / "scenes").iterdir() if p.is_dir())
    if group in ("main", "holdout"):
        manifest, texts = {
            "main": ("manifest.json", "texts"),
            "holdout": ("holdout.json", "holdout_texts"),
        }[group]
        folder = ROOT / "tests" / "real_verify"
        entries = json.loads((folder / manifest).read_text())["shaders"]
        return [folder / texts / f"{e['id']}.glsl" for e in entries]
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
    frame: int = 60,
    mouse: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0),
    lanes: tuple[int, ...] = (0, 8),
) -> list[dict]:
    """One result per lockstep width: {"lanes", "verdict", "reason", and for "differs" "diff"}."""
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
    kw = dict(size=size, frame=frame, mouse=mouse)
    try:
        numpy = NUMPY.compile_pass(shader, "Image")
        llvmpipe_loop_limit(numpy)
        reference = [numpy.render(time=t, **kw) for t in times]
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
            images = [prog.render(time=t, **kw) for t in times]
        except GlslError as e:
            out.append({"lanes": width, "verdict": "refused", "reason": "compiled: " + _refusal(e)})
            continue
        result = {"lanes": width, "verdict": "identical", "reason": ""}
        for t, a, b in zip(times, reference, images, strict=True):
            d = compare(a, b)
            if d is not None:
                result.update(
                    verdict="differs",
                    diff=dict(d, time=t),
                    reason=(
                        f"t={t:g}: {d['pixels']} px, max {d['max_abs']:.3g}, first "
                        f"{d['first'][0]},{d['first'][1]}: numpy {_rgba(d['numpy'])} "
                        f"compiled {_rgba(d['compiled'])}"
                    ),
                )
                break
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
    p.add_argument("--size", default="64x36")
    p.add_argument("--times", default="0,1.3")
    p.add_argument("--frame", type=int, default=60)
    p.add_argument("--mouse", default="40,20,40,20", help="iMouse x,y,z,w (z>0: button down)")
    p.add_argument("--lanes", default="0,8", help="the compiled engine's widths (0: per pixel)")
    p.add_argument("--only", default="", help="comma-separated shader names (file or folder stem)")
    p.add_argument("--timeout", type=float, default=600.0)
    p.add_argument("--json", type=Path, help="write the per-shader results here")
    a = p.parse_args(argv)
    from glslcheck.base.limits import parse_size, parse_times

    size = parse_size(a.size)
    times = list(parse_times(a.times))
    lanes = tuple(int(w) for w in a.lanes.split(","))
    mouse = tuple(float(v) for v in a.mouse.split(","))
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
                path=str(path), size=size, times=times, frame=a.frame, mouse=mouse, lanes=lanes
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
