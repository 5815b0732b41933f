"""`glslcheck probe` against its targets, each side measured in the same run:

1. `glslcheck probe lab_shaders/07_final --pixel 400,225`, the whole process (target: <= 1 s),
   against `glslcheck check lab_shaders/07_final`, the floor of any glslcheck process (start,
   parse, check), measured alternately; wall and CPU (user + sys) seconds of the child.
2. `probe --nan` on an 800x450 frame against one render of the same frame (target: <= 3x), in
   process, the frame cache emptied before each, tiles on threads for both (the render inside
   --nan is the same NumpyProgram render): lab 07_final (no NaN pixel: the scan is the render
   plus the NaN test), and the same scene with NaN in the left half of the picture (its Image
   tab ends with `fragColor.rgb *= sqrt(viewport.x + 0.0)`: every pixel there is traced).
3. The normal generated module is unchanged by the tracing mode: the module text of every lab
   shader against the module of the transpiler at BASE (the commit before probe existed, read
   with `git show`), and the 07_final render time with each (same run, alternately).

Timings are medians of --runs measurements after a warm-up. Printed, not asserted.

    python benchmarks/bench_probe.py [--runs N]
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(HERE))

from run_all import ms, paired  # noqa: E402

from glslcheck.backends.numpy_engine.program import NumpyProgram  # noqa: E402
from glslcheck.backends.numpy_engine.transpile import check_program, transpile  # noqa: E402
from glslcheck.frontend.parser import parse_shader  # noqa: E402
from glslcheck.shadertoy.sources import find_shaders, load_shader  # noqa: E402
from glslcheck.verification.probe import Inputs, Probe  # noqa: E402

BASE = "6671b61"  # main before glslcheck probe
FINAL = ROOT / "lab_shaders" / "07_final"
GLSLCHECK = [sys.executable, "-m", "glslcheck"]


def child(args: list[str]) -> tuple[float, float]:
    """(wall, CPU) seconds of one glslcheck process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    subprocess.run(
        GLSLCHECK + args, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, cwd=ROOT
    )
    wall = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def processes(runs: int) -> None:
    cmds = {
        "probe --pixel": ["probe", "lab_shaders/07_final", "--pixel", "400,225"],
        "check": ["check", "lab_shaders/07_final"],
    }
    cpu: dict[str, list[float]] = {k: [] for k in cmds}

    def one(key):
        def run():
            cpu[key].append(child(cmds[key])[1])

        return run

    wall = paired({k: one(k) for k in cmds}, runs)
    cpu_med = {k: sorted(v)[len(v) // 2] for k, v in cpu.items()}
    print("1. whole process, lab_shaders/07_final (target: probe --pixel <= 1 s)")
    for k in cmds:
        print(f"   glslcheck {k:<14} wall {ms(wall[k])}   CPU {ms(cpu_med[k])}")
    print(
        f"   probe --pixel / check: wall {wall['probe --pixel'] / wall['check']:.2f}x, "
        f"CPU {cpu_med['probe --pixel'] / cpu_med['check']:.2f}x"
    )


def nan_scene(folder: Path) -> Path:
    """lab 07_final with NaN in the left half: its Image tab with one line added at the end."""
    (folder / "Common.glsl").write_text((FINAL / "Common.glsl").read_text())
    image = (FINAL / "Image.glsl").read_text().rstrip()
    assert image.endswith("}")
    (folder / "Image.glsl").write_text(
        image[:-1] + "    fragColor.rgb *= sqrt(viewport.x + 0.0);\n}\n"
    )
    return folder


def nan_scan(runs: int, folder: Path) -> None:
    inputs = Inputs(size=(800, 450))
    print(
        "2. probe --nan against one render, 800x450, in process, tiles on threads (target: <= 3x)"
    )
    for name, path in (("07_final", FINAL), ("07_final + NaN left half", nan_scene(folder))):
        probe = Probe(str(path))
        ref = probe.program()
        ref_prog = NumpyProgram(ref.source, ref.meta, ref.filename)
        ref.parallel = ref_prog.parallel = "threads"
        result = []

        def scan():
            ref._cache.clear()
            result.append(probe.nan_origins(inputs))

        def render():
            ref_prog._cache.clear()
            ref_prog.render(size=inputs.size)

        t = paired({"scan": scan, "render": render}, runs)
        r = result[-1]
        print(
            f"   {name:<26} --nan {ms(t['scan'])}  render {ms(t['render'])}  ratio "
            f"{t['scan'] / t['render']:.2f}x"
            f"   ({r.nan_pixels} NaN pixels, {len(r.origins)} origin(s))"
        )


def base_transpiler():
    """transpile.py as it was at BASE, loaded as a module of the package (relative imports work)."""
    text = subprocess.run(
        ["git", "show", f"{BASE}:glslcheck/backends/numpy_engine/transpile.py"],
        cwd=ROOT,
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    fd, name = tempfile.mkstemp(suffix=".py")
    with os.fdopen(fd, "w") as f:
        f.write(text)
    spec = importlib.util.spec_from_file_location(
        "glslcheck.backends.numpy_engine._base_transpile", name
    )
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod
    spec.loader.exec_module(mod)
    os.unlink(name)
    return mod


def unchanged(runs: int) -> None:
    base = base_transpiler()
    shaders = find_shaders([str(ROOT / "lab_shaders")])
    same = 0
    for sh in shaders:
        model = check_program(parse_shader(sh, "Image"))
        path = sh.tabs["Image"].path
        same += transpile(model, path).source == base.transpile(model, path).source
    print(
        f"3. normal generated module: identical to the transpiler at {BASE} for {same} of "
        f"{len(shaders)} lab shaders"
    )
    sh = load_shader(FINAL)
    model = check_program(parse_shader(sh, "Image"))
    progs = {}
    for key, mod in (
        ("now", sys.modules["glslcheck.backends.numpy_engine.transpile"]),
        (BASE, base),
    ):
        t = mod.transpile(model, sh.tabs["Image"].path)
        progs[key] = NumpyProgram(t.source, t.meta, t.filename, parallel="threads")

    def render(key):
        def run():
            progs[key]._cache.clear()
            progs[key].render(size=(800, 450))

        return run

    t = paired({k: render(k) for k in progs}, runs)
    print(
        f"   07_final 800x450 render: now {ms(t['now'])}, {BASE} {ms(t[BASE])}, "
        f"ratio {t['now'] / t[BASE]:.3f}"
    )


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--runs", type=int, default=5)
    args = ap.parse_args()
    print(
        f"python {sys.version.split()[0]}, {os.cpu_count()} CPUs, load average "
        f"{', '.join(f'{x:.2f}' for x in os.getloadavg())}"
    )
    processes(args.runs)
    with tempfile.TemporaryDirectory() as tmp:
        nan_scan(args.runs, Path(tmp))
    unchanged(args.runs)
    return 0


if __name__ == "__main__":
    sys.exit(main())
