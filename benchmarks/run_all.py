"""The project's benchmark suite in one run, every result a ratio against a reference measured
in the same run (so a busy machine shifts both sides alike):

1. parse + check against glslangValidator on the same programs (the lab's 17 shaders, each
   compiled as Shadertoy does: Common alone and Common + Image, 34 programs; and one ~300-line
   synthetic shader from bench_parse.py): whole processes (`glslcheck check` against one
   `glslangValidator` call on the same programs), and glslcheck warm in-process (parse + check
   of the already loaded sources) against the glslangValidator process (it has no warm mode).
2. NumPy render time against GL on Mesa llvmpipe at 800x450: bench_render.py's four-sphere,
   four-point-light Blinn-Phong scene and lab 07_final (float32, 1 sample; the NumPy frame
   cache is emptied before every render), NumPy on worker processes and on threads.
3. Coverage scaling: the sphere scene with spheres covering ~10% and nearly 100% of the pixels.
4. Peak memory of a 3840x2160 NumPy render, in a fresh subprocess (ru_maxrss; a 8x8 render in
   another fresh subprocess is the baseline: interpreter, NumPy, the compiled shader), on
   threads and on worker processes (the caller and its largest worker times their number).

Timings are medians of --runs measurements after a warm-up; the two sides of each ratio are
measured alternately. Printed, not asserted: timings are facts about a machine.

    python benchmarks/run_all.py [--runs N] [--skip-memory]
"""

from __future__ import annotations

import argparse
import os
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(HERE))

import bench_parse  # noqa: E402
import bench_render  # noqa: E402
import numpy as np  # noqa: E402

from glslcheck.shadertoy.sources import find_shaders, load_shader  # noqa: E402

LAB = ROOT / "lab_shaders"
SIZE = bench_render.SIZE  # 800x450
UHD = (3840, 2160)


# ---------------------------------------------------------------------------------------------
# Measuring.


def paired(fns: dict, runs: int) -> dict:
    """Median seconds of each function: one warm-up each, then `runs` rounds calling each once."""
    for fn in fns.values():
        fn()
    times = {k: [] for k in fns}
    for _ in range(runs):
        for k, fn in fns.items():
            t = time.perf_counter()
            fn()
            times[k].append(time.perf_counter() - t)
    return {k: statistics.median(v) for k, v in times.items()}


def ms(seconds: float) -> str:
    return f"{seconds * 1000:8.1f} ms"


def machine() -> list[str]:
    cpu = "unknown CPU"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    usable = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    try:
        from glslcheck.backends.gl import renderer_name

        gl = renderer_name()
    except Exception as e:  # noqa: BLE001 - reported, not fatal
        gl = f"none ({e})"
    glslang = shutil.which("glslangValidator")
    version = "not installed"
    if glslang:
        out = subprocess.run(
            [glslang, "--version"], capture_output=True, text=True
        ).stdout.splitlines()
        version = out[0].split(":", 1)[-1].strip() if out else "unknown"
    import moderngl

    return [
        f"CPU        {cpu}, {os.cpu_count()} cores ({usable} usable), {platform.machine()}",
        f"Python     {platform.python_version()} ({platform.python_implementation()}), "
        f"NumPy {np.__version__}, "
        f"moderngl {moderngl.__version__}",
        f"GL         {gl}",
        f"glslang    glslangValidator {version}",
        f"load       {_load()} (1/5/15-minute load average at the start; "
        f"above {os.cpu_count()} other jobs compete)",
    ]


def _load() -> str:
    try:
        return " ".join(f"{v:.1f}" for v in os.getloadavg())
    except OSError:
        return "unknown"


# ---------------------------------------------------------------------------------------------
# 1. parse + check against glslangValidator.


def lab_programs():
    """(shader, tab, Program) for every lab shader: Common alone, then Common + Image."""
    from glslcheck.shadertoy.wrapper import build_program

    out = []
    for shader in find_shaders([str(LAB)]):
        tabs = (["Common"] if shader.common is not None else []) + ["Image"]
        out += [(shader, tab, build_program(shader, tab)) for tab in tabs]
    return out


def parse_and_check(shader, tab):
    from glslcheck.frontend.parser import parse_shader
    from glslcheck.semantics import check

    return check(parse_shader(shader, tab), tab, collect=True)


def section_parse(runs: int) -> list[str]:
    glslang = shutil.which("glslangValidator")
    exe = shutil.which("glslcheck") or str(Path(sys.executable).with_name("glslcheck"))
    lines = [
        "1. parse + check against glslangValidator (same programs; ratio = glslcheck / glslang)"
    ]
    if not glslang:
        return lines + ["   glslangValidator not installed: skipped"]
    programs = lab_programs()
    final = [p for p in programs if p[0].root.rstrip("/").endswith("07_final")]
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        files = []
        for i, (shader, tab, program) in enumerate(programs):
            f = tmp / f"{i:02d}_{Path(shader.root).name}_{tab}.frag"
            f.write_text(program.text)
            files.append(str(f))
        final_files = [files[programs.index(p)] for p in final]
        synthetic = tmp / "synthetic" / "Image.glsl"
        synthetic.parent.mkdir()
        synthetic.write_text(bench_parse.make_shader())
        syn_shader = load_shader(synthetic)
        from glslcheck.shadertoy.wrapper import build_program

        syn_frag = tmp / "synthetic.frag"
        syn_frag.write_text(build_program(syn_shader, "Image").text)
        syn_lines = synthetic.read_text().count("\n") + 1

        def run(cmd):
            return lambda: subprocess.run(cmd, check=True, capture_output=True)

        rows = [
            (
                f"whole process, lab ({len(programs)} programs)",
                run([exe, "check", "-q", str(LAB)]),
                run([glslang, *files]),
            ),
            (
                f"whole process, 07_final ({len(final)} programs)",
                run([exe, "check", "-q", str(LAB / "07_final")]),
                run([glslang, *final_files]),
            ),
            (
                f"whole process, synthetic {syn_lines} lines",
                run([exe, "check", "-q", str(synthetic)]),
                run([glslang, str(syn_frag)]),
            ),
            (
                f"warm in-process, lab ({len(programs)} programs)",
                lambda: [parse_and_check(s, t) for s, t, _ in programs],
                run([glslang, *files]),
            ),
            (
                f"warm in-process, synthetic {syn_lines} lines",
                lambda: parse_and_check(syn_shader, "Image"),
                run([glslang, str(syn_frag)]),
            ),
        ]
        lines.append(f"   {'':44s} {'glslcheck':>11s} {'glslang':>11s}   ratio")
        for label, ours, theirs in rows:
            t = paired({"ours": ours, "glslang": theirs}, runs)
            lines.append(
                f"   {label:44s} {ms(t['ours'])} {ms(t['glslang'])}   "
                f"{t['ours'] / t['glslang']:5.2f}x"
            )
    return lines


# ---------------------------------------------------------------------------------------------
# 2 and 3. NumPy against GL.


def _pair(shader):
    import glslcheck

    return glslcheck.compile(shader, backend="numpy"), glslcheck.compile(shader, backend="gl")


def _render_fns(shader, size=SIZE) -> dict:
    """NumPy on worker processes, NumPy on threads of this process, GL: one function each."""
    numpy_prog, gl_prog = _pair(shader)

    def numpy_render(mode):
        def render():
            numpy_prog.impl.parallel = mode
            numpy_prog.impl._cache.clear()  # the frame cache would answer a still shader at once
            numpy_prog.render(size=size)
            assert numpy_prog.impl.last_parallel == mode

        return render

    return {
        "processes": numpy_render("processes"),
        "threads": numpy_render("threads"),
        "gl": lambda: gl_prog.render(size=size),
    }


def section_render(runs: int) -> list[str]:
    lines = [
        f"2. NumPy (float32, 1 sample) against GL on llvmpipe at {SIZE[0]}x{SIZE[1]} (ratio = "
        "numpy / gl;",
        f"   NumPy on {os.cpu_count()} worker processes and on {os.cpu_count()} threads)",
    ]
    lines.append(f"   {'':40s} {'processes':>11s} {'threads':>11s} {'gl':>11s}   ratios")
    for label, folder in bench_render.SCENES:
        t = paired(_render_fns(load_shader(folder)), runs)
        lines.append(
            f"   {label:40s} {ms(t['processes'])} {ms(t['threads'])} {ms(t['gl'])}   "
            f"{t['processes'] / t['gl']:5.2f}x {t['threads'] / t['gl']:5.2f}x"
        )
    return lines


def section_coverage(runs: int) -> list[str]:
    import glslcheck

    lines = ["3. coverage scaling: the sphere scene, small against large spheres (same run)"]
    results = {}
    lines.append(f"   {'':40s} {'processes':>11s} {'threads':>11s} {'gl':>11s}")
    for label, radius in (
        ("small", bench_render.SMALL_RADIUS),
        ("large", bench_render.LARGE_RADIUS),
    ):
        shader = bench_render._scene(radius)
        coverage = bench_render.sphere_coverage(glslcheck.compile(shader, backend="numpy"))
        t = paired(_render_fns(shader), runs)
        results[label] = t
        lines.append(
            f"   {label + f' spheres, {coverage:.0%} of the pixels':40s} {ms(t['processes'])} "
            f"{ms(t['threads'])} {ms(t['gl'])}"
        )
    for side in ("processes", "threads", "gl"):
        lines.append(
            f"   {side}: time(small) / time(large) = "
            f"{results['small'][side] / results['large'][side]:.0%}"
        )
    return lines


# ---------------------------------------------------------------------------------------------
# 4. Memory.


def _child(size, mode: str = "threads") -> tuple[float, int, int, int]:
    """(render seconds, tracemalloc peak, ru_maxrss bytes, largest worker's ru_maxrss) of
    bench_render's child at `size`."""
    code = bench_render._MEMORY_CHILD.format(root=str(ROOT), scene=bench_render.FINAL, mode=mode)
    code = code.replace("(3840, 2160)", repr(tuple(size)))
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    ).stdout.split()
    return float(out[-4]), int(out[-3]), int(out[-2]), int(out[-1])


def section_memory() -> list[str]:
    seconds, traced, rss, _ = _child(UHD)
    _, _, base, _ = _child((8, 8))
    p_seconds, _, p_rss, worker = _child(UHD, "processes")
    workers = os.cpu_count() or 1
    image = UHD[0] * UHD[1] * 4 * 4
    mib = 2**20
    return [
        f"4. memory of a {UHD[0]}x{UHD[1]} NumPy render of lab 07_final (fresh subprocess each)",
        f"   threads: peak resident {rss / mib:.0f} MiB; baseline (8x8 render) {base / mib:.0f} "
        f"MiB; render adds {(rss - base) / mib:.0f} MiB = {(rss - base) / image:.1f} x the float32 "
        f"RGBA image ({image / mib:.0f} MiB)",
        f"   tracemalloc peak {traced / mib:.0f} MiB; render {seconds:.2f} s",
        f"   worker processes: caller {p_rss / mib:.0f} MiB + {workers} workers of at most "
        f"{worker / mib:.0f} MiB "
        f"= {(p_rss + workers * worker) / mib:.0f} MiB at most; "
        f"render {p_seconds:.2f} s (workers started first)",
    ]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument(
        "--runs", type=int, default=5, help="measurements per timing after a warm-up (default 5)"
    )
    ap.add_argument("--skip-memory", action="store_true", help="skip the 4K memory measurement")
    args = ap.parse_args()
    started = time.perf_counter()
    out = [
        f"glslcheck benchmarks (benchmarks/run_all.py, median of {args.runs} runs)",
        *machine(),
        "",
    ]
    print("\n".join(out), flush=True)
    sections = [section_parse, section_render, section_coverage]
    for section in sections:
        print("\n".join(section(args.runs)) + "\n", flush=True)
    if not args.skip_memory:
        print("\n".join(section_memory()) + "\n", flush=True)
    print(f"total {time.perf_counter() - started:.0f} s; load at the end {_load()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
