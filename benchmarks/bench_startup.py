"""Benchmark: `glslcheck lint` and `check` as whole processes (what a pre-commit hook pays on
every commit), against glslangValidator on the same programs, timed alternately in the same run.

Like hyperfine: one warm-up of each command, then `--runs` rounds that run each command once,
in turn; the median wall time of each is printed with the ratio to glslangValidator's, and
beside it the median CPU time (user + system) of the process, which waiting for a busy
machine's cores does not inflate. The interpreter's own start-up (`python -c pass` in the same
environment) is printed as the floor no Python tool can go under.

Targets: `glslcheck lint FILE` on one 200-line file <= 150 ms; `glslcheck lint
lab_shaders` <= 0.5 s. Printed, not asserted: timings are facts about a machine.

Two set-ups are measured: (1) the dev venv's `glslcheck` (`make setup`: an editable install,
whose import hook costs every start tens of milliseconds in `site`), and (2) the wheel
installed as pip installs it into a hook's environment (unpacked into a fresh venv, .pyc
compiled). Both with the package's .pyc files in place (pip writes them at install
time; the warm-up writes them here even when PYTHONDONTWRITEBYTECODE is set in this
environment). `--no-pyc` measures the other case: every module compiled from source at each
start (an empty PYTHONPYCACHEPREFIX and PYTHONDONTWRITEBYTECODE=1).

`lint lab_shaders` runs its programs on two cores when it may (glslcheck/lint/parallel.py: not
when the 1-minute load average says both cores are busy); the row `GLSLCHECK_JOBS=1` is the same
command in one process. Its CPU time counts both processes.
`--outside` copies the lab into a temporary folder and runs every command from there, as in a
student's repository: here this repository's own pyproject.toml is read for a [tool.glslcheck]
table at every start (tomllib, with `typing`: about 40 M instructions a run).

    python benchmarks/bench_startup.py [--runs N] [--no-pyc] [--only venv|installed] [--outside]
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
import zipfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

LAB = ROOT / "lab_shaders"
# One ~200-line lab file: the longest tab of the lab (its Common tab, checked alone as
# Shadertoy compiles it for the Common pass).
FILE = LAB / "bonus_animated_lights" / "Common.glsl"


def paired(
    commands: dict[str, list[str]],
    runs: int,
    env: dict[str, str],
    extra: dict[str, dict[str, str]] | None = None,
    cwd: Path | None = None,
) -> dict[str, tuple[float, float]]:
    """Median (wall, CPU) seconds of each command: one warm-up each, then `runs` rounds running
    each once. CPU is the child's user + system time (and its own children's): on a machine
    shared with other jobs the wall time also counts waiting for a core, the CPU time does not
    (on an idle machine the two agree for one-process commands). `extra`: environment variables
    of some commands."""

    def once(name: str, cmd: list[str]) -> tuple[float, float]:
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t = time.perf_counter()
        done = subprocess.run(
            cmd,
            env={**env, **(extra or {}).get(name, {})},
            cwd=cwd,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
        )
        elapsed = time.perf_counter() - t
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        if (
            done.returncode not in (0, 1) or b"Traceback" in done.stderr
        ):  # 1: findings, a normal outcome
            raise SystemExit(
                f"{' '.join(cmd)} failed ({done.returncode}):\n{done.stderr.decode()[-2000:]}"
            )
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        return elapsed, cpu

    for k, cmd in commands.items():
        once(k, cmd)
    times: dict[str, list[tuple[float, float]]] = {k: [] for k in commands}
    for _ in range(runs):
        for k, cmd in commands.items():
            times[k].append(once(k, cmd))
    return {
        k: (statistics.median(w for w, _ in v), statistics.median(c for _, c in v))
        for k, v in times.items()
    }


def _programs(paths: list[Path], tmp: Path) -> list[str]:
    """Each Shadertoy program of the shaders under `paths`, wrapped as Shadertoy compiles it
    (Common alone, then Common + each other tab), written as .frag files for glslangValidator."""
    from glslcheck.shadertoy.sources import find_shaders
    from glslcheck.shadertoy.wrapper import build_program

    files = []
    for shader in find_shaders([str(p) for p in paths]):
        tabs = (["Common"] if shader.common is not None else []) + [
            t for t in shader.tabs if t != "Common"
        ]
        for tab in tabs:
            f = tmp / f"{len(files):02d}_{Path(shader.root).name}_{tab.replace(' ', '_')}.frag"
            f.write_text(build_program(shader, tab).text)
            files.append(str(f))
    return files


def _ms(wall: float, cpu: float) -> str:
    return f"{wall * 1000:7.1f} ms ({cpu * 1000:5.1f})"


def _load() -> str:
    try:
        return " ".join(f"{v:.1f}" for v in os.getloadavg())
    except OSError:
        return "unknown"


def _installed(tmp: Path) -> tuple[list[str], dict[str, str]]:
    """glslcheck as a pre-commit hook's environment has it: a fresh venv with the wheel
    unpacked into its site-packages and compiled to .pyc (as pip installs it), so without the
    dev venv's editable-install import hook (tens of milliseconds of `site` at every start).
    Lint and check need none of the dependencies (test_import_hygiene.py), so none is installed."""
    wheels = tmp / "wheel"
    subprocess.run(
        [
            sys.executable,
            "-m",
            "pip",
            "wheel",
            "--no-deps",
            "--no-build-isolation",
            "-q",
            "-w",
            str(wheels),
            str(ROOT),
        ],
        check=True,
        capture_output=True,
    )
    (wheel,) = wheels.glob("glslcheck-*.whl")
    venv = tmp / "hook-venv"
    base = getattr(sys, "_base_executable", sys.executable)
    subprocess.run([base, "-m", "venv", "--without-pip", str(venv)], check=True)
    python = venv / "bin" / "python"
    site = subprocess.run(
        [str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
        check=True,
        capture_output=True,
        text=True,
    ).stdout.strip()
    with zipfile.ZipFile(wheel) as z:
        z.extractall(site)
    subprocess.run([str(python), "-m", "compileall", "-q", site], check=True)
    env = dict(os.environ)
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    # -P: not the current folder first on sys.path (it would be this checkout's glslcheck/).
    return [
        str(python),
        "-P",
        "-c",
        "import sys; from glslcheck.cli.main import main; sys.exit(main())",
    ], env


def _section(
    title: str,
    exe: list[str],
    python: list[str],
    env: dict[str, str],
    glslang: str,
    one: list[str],
    lab: list[str],
    runs: int,
    where: Path = ROOT,
) -> None:
    file, folder = where / FILE.relative_to(ROOT), where / LAB.relative_to(ROOT)
    lines = file.read_text().count("\n")
    rows = [
        (f"lint FILE ({lines} lines)", [*exe, "lint", str(file)], [glslang, *one], 0.150, {}),
        (f"check FILE ({lines} lines)", [*exe, "check", str(file)], [glslang, *one], None, {}),
        (
            f"lint lab_shaders ({len(lab)} programs)",
            [*exe, "lint", str(folder)],
            [glslang, *lab],
            0.5,
            {},
        ),
        (
            "  ... GLSLCHECK_JOBS=1 (one process)",
            [*exe, "lint", str(folder)],
            [glslang, *lab],
            0.5,
            {"ours": {"GLSLCHECK_JOBS": "1"}},
        ),
        (
            f"check lab_shaders ({len(lab)} programs)",
            [*exe, "check", str(folder)],
            [glslang, *lab],
            None,
            {},
        ),
    ]
    print(f"{title} (load {_load()})")
    print(
        f"   {'whole process: wall time (CPU time)':40s} {'glslcheck':>19s} {'glslang':>19s}   "
        "ratio (CPU)   target"
    )
    for label, ours, theirs, target, extra in rows:
        t = paired({"ours": ours, "glslang": theirs}, runs, env, extra, cwd=where)
        (wall, cpu), (ref_wall, ref_cpu) = t["ours"], t["glslang"]
        verdict = (
            ""
            if target is None
            else f"{target * 1000:4.0f} ms {'met' if wall <= target else 'missed'}"
        )
        print(
            f"   {label:40s} {_ms(wall, cpu)} {_ms(ref_wall, ref_cpu)}  {wall / ref_wall:5.2f}x "
            f"({cpu / ref_cpu:5.2f}x)   {verdict}"
        )
    floor = paired({"python -c pass": [*python, "-c", "pass"]}, runs, env, cwd=where)
    for label, (wall, cpu) in floor.items():
        print(f"   {label:40s} {_ms(wall, cpu)}   (the interpreter alone)")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--runs", type=int, default=21)
    ap.add_argument(
        "--no-pyc", action="store_true", help="compile every module from source at each start"
    )
    ap.add_argument("--only", choices=("venv", "installed"), help="measure one of the two set-ups")
    ap.add_argument(
        "--outside",
        action="store_true",
        help="copy the lab into a temporary folder and run there (no pyproject.toml above it)",
    )
    args = ap.parse_args()
    glslang = shutil.which("glslangValidator")
    if not glslang:
        print("glslangValidator not installed: nothing to compare against", file=sys.stderr)
        return 2
    exe = shutil.which("glslcheck") or str(Path(sys.executable).with_name("glslcheck"))
    python = str(Path(exe).with_name("python"))
    print(
        f"glslcheck start-up (benchmarks/bench_startup.py, median of {args.runs} runs, "
        f"{'no .pyc: compiled from source' if args.no_pyc else 'with .pyc'}; "
        f"{os.cpu_count()} cores; "
        f"load = 1/5/15-minute load average)"
    )
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        one = _programs([FILE], tmp)
        lab = _programs([LAB], tmp)
        env = dict(os.environ)
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        env.pop("GLSLCHECK_JOBS", None)
        where = ROOT
        if args.outside:
            where = tmp / "student-repo"
            shutil.copytree(LAB, where / LAB.relative_to(ROOT))
            print(
                f"shaders copied to {where} (no pyproject.toml above it), commands run from there"
            )
        if args.no_pyc:
            env.update(PYTHONDONTWRITEBYTECODE="1", PYTHONPYCACHEPREFIX=str(tmp / "no-pyc"))
        if args.only in (None, "venv"):
            _section(
                "1. the dev venv's `glslcheck` (editable install: `make setup`)",
                [exe],
                [python],
                env,
                glslang,
                one,
                lab,
                args.runs,
                where,
            )
        if args.only in (None, "installed"):
            command, installed_env = _installed(tmp)
            if args.no_pyc:
                installed_env.update(
                    PYTHONDONTWRITEBYTECODE="1", PYTHONPYCACHEPREFIX=str(tmp / "no-pyc")
                )
            installed_env.pop("GLSLCHECK_JOBS", None)
            _section(
                "2. installed from the wheel (what a pre-commit hook's environment runs)",
                command,
                command[:2],
                installed_env,
                glslang,
                one,
                lab,
                args.runs,
                where,
            )
    print(f"load at the end {_load()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
