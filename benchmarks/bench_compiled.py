"""The compiled engine (glslcheck/compiled_backend) against llvmpipe and the NumPy backend.

    python benchmarks/bench_compiled.py [--size 128x72,400x225] [--repeat 3] [--only ID,...]
                                        [--lab-only | --real-only] [--numpy-size 128x72]
                                        [--fresh-cache] [--json out.json] [--lanes 0,8] [--scenes]

For every lab shader and every real public shader of tests/real_verify (texts fetched by
tools/real_verify.py fetch), and with --scenes the render benchmark's scenes (bench_render.py's
800x450 scenes: `--scenes --lab-only --only scene-four_spheres,... --size 800x450`), in this one
process:

- compile: the wall time of generating the module and of loading it (numba compiling it, or
  loading its machine code from numba's cache: `cold` says which; --fresh-cache points numba at
  an empty temporary cache, so every figure is cold, the scalar runtime's own compile included
  in the first shader's);
- frame: best of --repeat frames, wall and CPU time (time.process_time: this process's, so
  llvmpipe's threads and the engine's row threads are both counted), compiled vs GL (moderngl,
  llvmpipe) in turns, each frame at a new iTime; the NumPy backend's frame once at
  --numpy-size only (it takes minutes on the slowest shaders at larger sizes);
- modes (--lanes, default 0,8: the two tiers of the engine's default program, TieredProgram,
  which renders per pixel first and moves to 8 lanes once the frames have cost what compiling
  them is expected to cost, so a shader rendered many times runs in lockstep): 0 is the
  per-pixel module (one pixel a call), W > 0 pixels in lockstep blocks of W
  (backends/compiled_engine/lanes.py; a shader the rewrite does not handle falls back to per pixel,
  `fallback` says why); each mode is timed against the same GL frames, and a lockstep frame is
  compared bit for bit with the per-pixel one when 0 is listed;
- agreement: the compiled frame against the NumPy frame of the same inputs (pixels differing,
  max abs difference), and against GL by glslcheck's verify rule (compare.compare: `match`),
  beside the NumPy frame's own verdict.

Prints one line per shader and size, worst CPU ratio first, then per size the geometric mean of
the CPU and wall ratios and the shaders over 6x (the goals: <= 3x a scene, mean <= 1.5x, none
over 6x), and the load average at the start and end (a shared machine moves both sides of a
ratio; CPU time least).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)
sys.path.insert(0, os.path.join(ROOT, "tools"))


def _load() -> str:
    return " ".join(f"{x:.1f}" for x in os.getloadavg())


def _size(text: str) -> tuple[int, int]:
    w, h = text.lower().split("x")
    return int(w), int(h)


_T = [0]


def _time() -> float:
    _T[0] += 1
    return 1.0 + _T[0] * 0.01


# the render benchmark's scenes without channels (bench_render.SCENES: the four-sphere scene, its
# lights built element by element in mainImage, a Lab 4 submission's shape), with --scenes
SCENE_DIRS = ("four_spheres", "lights_array", "lab4_submission")


def shaders(
    lab: bool, real: bool, only: set[str] | None, scenes: bool = False
) -> list[tuple[str, str]]:
    out = []
    if scenes:
        out += [(f"scene-{d}", os.path.join(HERE, "scenes", d)) for d in SCENE_DIRS]
    if lab:
        root = os.path.join(ROOT, "lab_shaders")
        out += [
            (d, os.path.join(root, d))
            for d in sorted(os.listdir(root))
            if os.path.isdir(os.path.join(root, d))
        ]
    if real:
        import real_verify

        for e in real_verify.load_manifest():
            p = str(real_verify.text_path(e))
            if os.path.exists(p):
                out.append((e["id"], p))
    return [(i, p) for i, p in out if not only or i in only]


def measure(name: str, path: str, sizes: list, repeat: int, numpy_size, modes: list) -> list[dict]:
    import numpy as np

    import glslcheck
    from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate, lanes_width
    from glslcheck.backends.gl import compile_gl
    from glslcheck.base.diagnostics import GlslError
    from glslcheck.shadertoy.sources import load_shader
    from glslcheck.verification.compare import compare

    shader = load_shader(path)
    progs = {}
    for mode in modes:
        t0 = time.perf_counter()
        try:
            source, tab = generate(shader, lanes=mode)
        except GlslError as e:
            # derivatives: no per-pixel module (lockstep only); the other modes are measured
            if mode or len(modes) == 1 or "only with pixels in lockstep" not in str(e):
                raise
            print(f"  {name}: mode 0 left out: {e.diagnostics[0].message}", flush=True)
            continue
        gen = time.perf_counter() - t0
        prog = CompiledProgram(source, tab)
        prog.load()
        width = lanes_width(mode)
        label = "pixel" if not width or "LANES_FALLBACK" in source else f"lanes{width}"
        fallback = (
            source.rsplit("LANES_FALLBACK = ", 1)[1].split("  #")[0]
            if "LANES_FALLBACK" in source
            else ""
        )
        progs[mode] = (prog, gen, label, fallback)
    gl = compile_gl(shader)
    rows = []
    for size in sizes:
        t = {k: math.inf for m in progs for k in (f"c{m}", f"c{m} cpu")}
        t.update({"gl": math.inf, "gl cpu": math.inf})
        for prog, *_ in progs.values():
            prog.render(size=size, time=_time())  # warm-up (threads, GL buffers)
        gl.render(size=size, time=_time())
        for _ in range(repeat):
            for key, fn in [(f"c{m}", p[0].render) for m, p in progs.items()] + [("gl", gl.render)]:
                tm = _time()
                c0, w0 = time.process_time(), time.perf_counter()
                fn(size=size, time=tm)
                t[key] = min(t[key], time.perf_counter() - w0)
                t[key + " cpu"] = min(t[key + " cpu"], time.process_time() - c0)
        tm = _time()
        gimg = gl.render(size=size, time=tm)
        imgs = {m: p[0].render(size=size, time=tm) for m, p in progs.items()}
        nimg = None
        for m, (prog, gen, label, fallback) in progs.items():
            img = imgs[m]
            row = dict(
                shader=name,
                size=f"{size[0]}x{size[1]}",
                mode=m,
                label=label,
                fallback=fallback,
                gen=gen,
                load=prog.load_seconds,
                cold=prog.cold,
                compiled=t[f"c{m}"],
                gl=t["gl"],
                **{"compiled cpu": t[f"c{m} cpu"], "gl cpu": t["gl cpu"]},
                ratio=t[f"c{m}"] / t["gl"],
                cpu_ratio=t[f"c{m} cpu"] / t["gl cpu"],
                gl_match=compare(img, gimg).match,
            )
            if 0 in imgs and m != 0:
                row["pixel_differ"] = int(
                    (img.view(np.uint32) != imgs[0].view(np.uint32)).any(axis=2).sum()
                )
            if size == numpy_size:
                if nimg is None:
                    nprog = glslcheck.compile(shader, backend="numpy")
                    c0, w0 = time.process_time(), time.perf_counter()
                    nimg = nprog.render(size=size, time=tm)
                    ncost = time.perf_counter() - w0, time.process_time() - c0
                row["numpy"], row["numpy cpu"] = ncost
                same = (img == nimg) | (np.isnan(img) & np.isnan(nimg))
                diff = ~same.all(axis=2)
                fin = np.isfinite(img) & np.isfinite(nimg)
                row["numpy_differ"] = int(diff.sum())
                row["numpy_max_abs"] = float(np.abs(img - nimg)[fin].max(initial=0.0))
                row["numpy_nan_differ"] = int((np.isnan(img) != np.isnan(nimg)).any(axis=2).sum())
                row["numpy_gl_match"] = compare(nimg, gimg).match
            rows.append(row)
    return rows


def summary(rows: list, label: str, mode) -> None:
    """Per size and mode: the worst CPU ratios, geometric means, over-6x, agreement."""
    sel = sorted(
        (r for r in rows if r["size"] == label and r["mode"] == mode), key=lambda r: -r["cpu_ratio"]
    )
    if not sel:
        return
    lanes = sum(r["label"] != "pixel" for r in sel)
    print(
        f"\n{label}, mode {mode if mode is not None else 'auto'} ({lanes} of {len(sel)} in "
        f"lockstep): {len(sel)} shaders, worst CPU ratios first"
    )
    for r in sel[:12]:
        print(
            f"  {r['shader']:24s} {r['label']:>7s} cpu {r['cpu_ratio']:6.2f}x  wall "
            f"{r['ratio']:6.2f}x"
        )
    for key, what in (("cpu_ratio", "CPU"), ("ratio", "wall")):
        g = math.exp(sum(math.log(r[key]) for r in sel) / len(sel))
        over = [r["shader"] for r in sel if r[key] > 6.0]
        print(
            f"  geometric mean ({what}) {g:.2f}x llvmpipe; over 6x: {len(over)} {', '.join(over)}"
        )
    match = sum(r["gl_match"] for r in sel)
    print(f"  verify against GL: {match} of {len(sel)} match")
    withp = [r for r in sel if "pixel_differ" in r and r["label"] != "pixel"]
    if withp:
        print(
            "  lockstep bit-identical to the per-pixel engine: "
            f"{sum(r['pixel_differ'] == 0 for r in withp)} "
            f"of {len(withp)}"
        )
    withn = [r for r in sel if "numpy_differ" in r]
    if withn:
        same = sum(r["numpy_differ"] == 0 for r in withn)
        print(
            f"  bit-identical to the NumPy render: {same} of {len(withn)}; "
            f"numpy's own verify: {sum(r['numpy_gl_match'] for r in withn)} match"
        )
        g = math.exp(sum(math.log(r["numpy cpu"] / r["compiled cpu"]) for r in withn) / len(withn))
        print(f"  NumPy CPU / compiled CPU, geometric mean: {g:.1f}x")


def main() -> int:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--size", default="128x72,400x225")
    ap.add_argument("--numpy-size", default="128x72")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--only", default="")
    ap.add_argument("--lab-only", action="store_true")
    ap.add_argument("--real-only", action="store_true")
    ap.add_argument("--fresh-cache", action="store_true")
    ap.add_argument(
        "--scenes",
        action="store_true",
        help="also the render benchmark's scenes (benchmarks/scenes: four_spheres, lights_array, "
        "lab4_submission)",
    )
    ap.add_argument("--json", default=None)
    ap.add_argument(
        "--lanes",
        default="0,8",
        help="modes: pixels a call, 0 = per pixel (default 0,8: both tiers)",
    )
    args = ap.parse_args()
    modes = [int(x) for x in args.lanes.split(",")]
    if args.fresh_cache:
        os.environ["NUMBA_CACHE_DIR"] = tempfile.mkdtemp(prefix="glslcheck-bench-numba-")
    os.environ.setdefault("GLSLCHECK_JIT", "off")  # the NumPy side: its default NumPy math
    sizes = [_size(s) for s in args.size.split(",")]
    numpy_size = _size(args.numpy_size) if args.numpy_size else None
    only = set(args.only.split(",")) if args.only else None
    from glslcheck.base.diagnostics import GlslError

    print(f"load average at start: {_load()}", flush=True)
    rows, skipped = [], []
    for name, path in shaders(not args.real_only, not args.lab_only, only, args.scenes):
        try:
            got = measure(name, path, sizes, args.repeat, numpy_size, modes)
        except GlslError as e:
            skipped.append((name, str(e).split(";")[0][:110]))
            print(f"  {name}: skipped: {skipped[-1][1]}", flush=True)
            continue
        except Exception as e:  # an engine bug: reported with the others, the run goes on
            skipped.append((name, f"FAILED {type(e).__name__}: {str(e).splitlines()[0][:100]}"))
            print(f"  {name}: {skipped[-1][1]}", flush=True)
            continue
        for r in got:
            extra = ""
            if "numpy" in r:
                extra = (
                    f"  numpy {r['numpy cpu'] / r['gl cpu']:6.2f}x cpu, "
                    f"differ {r['numpy_differ']:5d} px "
                    f"(max {r['numpy_max_abs']:.2g}, nan {r['numpy_nan_differ']}), "
                    f"verify {'match' if r['gl_match'] else 'MISMATCH'} (numpy "
                    f"{'match' if r['numpy_gl_match'] else 'MISMATCH'})"
                )
            else:
                extra = f"  verify {'match' if r['gl_match'] else 'MISMATCH'}"
            if "pixel_differ" in r:
                extra += f"  vs per pixel: {r['pixel_differ']} px differ"
            if r["fallback"]:
                extra += f"  (fallback: {r['fallback']})"
            print(
                f"  {name:24s} {r['size']:>8s} {r['label']:>7s} load "
                f"{r['load']:6.2f}s{' cold' if r['cold'] else ' warm'}  "
                f"compiled {r['compiled cpu'] * 1000:8.1f} ms cpu {r['compiled'] * 1000:8.1f} ms "
                f"wall  gl {r['gl cpu'] * 1000:7.1f} / {r['gl'] * 1000:7.1f} ms  cpu "
                f"{r['cpu_ratio']:6.2f}x  "
                f"wall {r['ratio']:6.2f}x{extra}",
                flush=True,
            )
        rows += got
    for size in sizes:
        for mode in modes:
            summary(rows, f"{size[0]}x{size[1]}", mode)
    first = f"{sizes[0][0]}x{sizes[0][1]}"
    for mode in modes:  # one load per shader and mode
        loaded = [r for r in rows if r["size"] == first and r["mode"] == mode]
        for what, xs in (
            ("cold", [r["load"] for r in loaded if r["cold"]]),
            ("warm", [r["load"] for r in loaded if not r["cold"]]),
        ):
            if xs:
                print(
                    f"mode {mode if mode is not None else 'auto'}: load ({what}, wall): median "
                    f"{sorted(xs)[len(xs) // 2]:.2f} s, max {max(xs):.2f} s over {len(xs)}"
                )
    for name, why in skipped:
        print(f"skipped {name}: {why}")
    print(f"load average at end: {_load()}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"rows": rows, "skipped": skipped}, f, indent=1, default=str)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
