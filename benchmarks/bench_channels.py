"""Benchmark of textured and multipass shaders: the NumPy backend against the GL driver.

    python benchmarks/bench_channels.py [--frames N] [--repeat R] [--size WxH] [--webgl]
                                        [--compiled] [--default] [--settle S]

Scenes (benchmarks/scenes): `textured` (one pass sampling an image with mipmap and linear
filtering; its tex.png, 256x256 noise, is written into a temporary copy of the folder) and
`feedback` (Buffer A reads its own previous frame, Image reads Buffer A). Each backend renders
N consecutive frames (buffers carried, see glslcheck/shadertoy/channels.py), the two backends in
turns, R rounds; reported: the best time per frame of each and the ratio numpy / gl. NumPy runs on
worker processes and on threads of this process (NumpyProgram.parallel). --webgl adds the WebGL
backend (headless Chromium, SwiftShader; the channels go to the page each pass) and its ratio
webgl / gl. --compiled adds the compiled engine (numba; its compile is done before the timing,
by a frame at 8x8) and its ratio compiled / gl. --default adds the default CPU program
(`--backend auto`, backends/tiered.py) and its ratio default / gl: before the timing it renders
frames at the benchmark's size until every pass has settled (stays on NumPy for good, or the
compiled engine renders past its trial; at most --settle seconds), and the line after the scene
says on which engine each pass settled and what settling took (frames, seconds).
"""

from __future__ import annotations

import argparse
import os
import shutil
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

from glslcheck.backends import registry as api  # noqa: E402

SCENES = ("textured", "feedback")


def copy_scene(name: str, into: str) -> str:
    dst = os.path.join(into, name)
    shutil.copytree(os.path.join(HERE, "scenes", name), dst)
    if name == "textured":
        from PIL import Image

        rng = np.random.default_rng(7)
        Image.fromarray(rng.integers(0, 256, (256, 256, 4), dtype=np.uint8), "RGBA").save(
            os.path.join(dst, "tex.png")
        )
    return dst


def _per_frame(prog, frames: int, size, start: int) -> float:
    t0 = time.perf_counter()
    for i in range(start, start + frames):
        prog.render(size=size, frame=i, time=i / 60.0)
    return (time.perf_counter() - t0) / frames


def _settle(prog, size, seconds: float) -> tuple[int, float]:
    """Frames of the default program from frame 0 until every pass has settled (at most
    `seconds`): (frames rendered, seconds taken)."""
    passes = list(prog.impl.programs.values())
    t0, k = time.perf_counter(), 0
    while time.perf_counter() - t0 < seconds:
        prog.render(size=size, frame=k, time=k / 60.0)
        k += 1
        if all(getattr(p, "settled", lambda: True)() for p in passes):
            break
    return k, time.perf_counter() - t0


def _engines(prog) -> str:
    """Each pass's engine and, for one kept on NumPy for good, why."""
    out = []
    for tab, p in prog.impl.programs.items():
        stay = getattr(p, "stay", None)
        out.append(f"{tab}: {getattr(p, 'mode', 'numpy')}" + (f" ({stay})" if stay else ""))
    return "; ".join(out)


def _set_mode(prog, mode: str) -> None:
    """NumpyProgram.parallel of every pass (Program -> MultipassProgram -> one per tab)."""
    for p in prog.impl.programs.values():
        p.parallel = mode


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--frames", type=int, default=10)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--size", default="800x450")
    ap.add_argument("--webgl", action="store_true", help="also time the WebGL backend")
    ap.add_argument("--compiled", action="store_true", help="also time the compiled engine")
    ap.add_argument("--default", action="store_true", help="also time the default CPU program")
    ap.add_argument("--settle", type=float, default=300.0, help="seconds the default may settle")
    args = ap.parse_args()
    size = tuple(int(v) for v in args.size.lower().split("x"))
    started = time.perf_counter()
    print(
        f"textured and multipass shaders, {size[0]}x{size[1]}, {args.frames} consecutive frames, "
        f"best of {args.repeat} rounds (ms per frame; ratio = numpy / gl)"
    )
    print(
        f"{'':<38}{'processes':>10}{'threads':>10}{'gl':>10}   ratios"
        + ("   webgl     ratio" if args.webgl else "")
        + ("   compiled  ratio" if args.compiled else "")
        + ("   default   ratio" if args.default else "")
    )
    with tempfile.TemporaryDirectory() as tmp:
        for name in SCENES:
            folder = copy_scene(name, tmp)
            progs = {"gl": api.compile(folder, backend="gl")}
            if args.webgl:
                progs["webgl"] = api.compile(folder, backend="webgl")
            if args.compiled:
                progs["compiled"] = api.compile(folder, backend="compiled")
                progs["compiled"].render(size=(8, 8))  # numba's compile (or cache load)
            # the frame each program continues from: consecutive frames carry the buffers (a
            # frame out of order would replay them from frame 0)
            first = {}
            settled = ""
            if args.default:
                progs["default"] = api.compile(folder)
                k, took = _settle(progs["default"], size, args.settle)
                first["default"] = k
                settled = f"      default settled after {k} frames, {took:.1f} s: "
                settled += _engines(progs["default"])
            for mode in ("processes", "threads"):  # one program each: each carries its own buffers
                progs[mode] = api.compile(folder, backend="numpy")
                _set_mode(progs[mode], mode)
            best = {k: float("inf") for k in progs}
            for r in range(args.repeat):
                for k, prog in progs.items():
                    start = first.get(k, 0) + r * args.frames
                    best[k] = min(best[k], _per_frame(prog, args.frames, size, start))
            p, t, g = (best[k] * 1000 for k in ("processes", "threads", "gl"))
            line = f"   {name:<35}{p:>8.1f} ms{t:>7.1f} ms{g:>7.1f} ms   {p / g:.2f}x  {t / g:.2f}x"
            if args.webgl:
                w = best["webgl"] * 1000
                line += f"  {w:>7.1f} ms  {w / g:.2f}x"
            if args.compiled:
                c = best["compiled"] * 1000
                line += f"  {c:>7.1f} ms  {c / g:.2f}x"
            if args.default:
                d = best["default"] * 1000
                line += f"  {d:>7.1f} ms  {d / g:.2f}x"
            print(line + ("\n" + settled if settled else ""), flush=True)
    print(
        f"total {time.perf_counter() - started:.0f} s; load at the end "
        f"{' '.join(f'{v:.1f}' for v in os.getloadavg())}"
    )


if __name__ == "__main__":
    main()
