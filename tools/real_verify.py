"""Score `glslcheck verify` on real public Shadertoy shaders (tests/real_verify/manifest.json).

The repository keeps only the manifest (repository, path, commit, and a label saying what each
shader is); the texts are third-party code and stay out of it. `fetch` re-reads them into
tests/real_verify/texts/ (git-ignored), `score` verifies each one as `glslcheck verify` does:

    python tools/real_verify.py fetch [--mirror DIR]   # DIR/<owner>+<name>/repo git dirs, else
                                                       # raw.githubusercontent.com over HTTPS
    python tools/real_verify.py score [--size 160x90] [--times 0,1.7,5.3] [--timeout 300]
                                      [--only ID,...] [--json out.json]

Four corpora, one mechanism: `--set main` (the default; manifest.json, texts/) is the corpus the
NumPy backend and the compiled engine were tuned on; `--set holdout` (holdout.json,
holdout_texts/) is a second one chosen after that tuning, to measure how glslcheck does on
shaders it was not tuned on (as a hidden corpus would); `--set fbm` (fbm.json, fbm_texts/) is
the family of iq's sphere-grid fbm SDF, Shadertoy JSON exports; `--set pathtracers`
(pathtracers.json, pathtracers_texts/) is a family of path tracers whose random numbers advance
a seed twice in one constructor's arguments (`vec2(seed+=.1, seed+=.1)`) fed to a sin hash or to
floatBitsToUint and an integer hash. `--set` goes before the command
(`python tools/real_verify.py --set holdout score`); the environment variable REAL_VERIFY_SET
selects the set for every script that reads this module's manifest (benchmarks/bench_real_render.py,
benchmarks/bench_compiled.py).

Each shader runs in its own process (a crash, a hang or a runaway loop costs one shader, not
the run) and gets one verdict:

- match: every frame verifies (the verification/compare.py tolerance model, the same as the CLI);
- mismatch: some frame does not; the reason names the frame, the over-tolerance and NaN/Inf
  pixel counts;
- undefined: the frames that do not verify differ only where the shader reads a value GLSL
  leaves undefined (verify's "undefined" verdict); the reason names the first such read;
- does not compile: the GL driver rejects the shader (a GLSL error on Shadertoy's side too);
- unsupported: the NumPy backend refuses it (texture lookups, a construct it does not
  transpile) or stops it (a loop bound);
- timeout / error: the process took longer than --timeout or failed otherwise.

The summary line is the headline figure: matches among the shaders that compile.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
import urllib.parse
import urllib.request
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SETS = {
    "main": ("manifest.json", "texts"),
    "holdout": ("holdout.json", "holdout_texts"),
    "fbm": ("fbm.json", "fbm_texts"),
    "pathtracers": ("pathtracers.json", "pathtracers_texts"),
}


def select(name: str) -> None:
    """Read the corpus `name` of SETS from now on (this process and, through REAL_VERIFY_SET, its
    children)."""
    global MANIFEST, TEXTS
    if name not in SETS:
        raise SystemExit(
            f"unknown corpus set {name!r} (REAL_VERIFY_SET or --set): one of {', '.join(SETS)}"
        )
    os.environ["REAL_VERIFY_SET"] = name
    MANIFEST, TEXTS = (ROOT / "tests" / "real_verify" / f for f in SETS[name])


select(os.environ.get("REAL_VERIFY_SET") or "main")


def load_manifest() -> list[dict]:
    return json.loads(MANIFEST.read_text())["shaders"]


def text_path(entry: dict, texts: Path | None = None) -> Path:
    """Where the fetched text of `entry` is (in `texts`, by default the selected set's folder):
    a Shadertoy JSON export keeps its suffix, which tells load_shader to read its Image pass."""
    suffix = ".json" if entry["path"].lower().endswith(".json") else ".glsl"
    return (texts or TEXTS) / f"{entry['id']}{suffix}"


def set_paths(name: str) -> list[Path]:
    """The text paths of corpus set `name` of SETS, in manifest order (fetched or not), without
    selecting it."""
    manifest, texts = (ROOT / "tests" / "real_verify" / f for f in SETS[name])
    return [text_path(e, texts) for e in json.loads(manifest.read_text())["shaders"]]


def _from_mirror(mirror: Path, entry: dict) -> bytes | None:
    gitdir = mirror / entry["repo"].replace("/", "+", 1) / "repo"
    if (gitdir / ".git").is_dir():  # a snapshot with a work tree
        gitdir = gitdir / ".git"
    if not gitdir.is_dir():
        return None
    out = subprocess.run(
        ["git", "--git-dir", str(gitdir), "show", f"{entry['commit']}:{entry['path']}"],
        capture_output=True,
    )
    return out.stdout if out.returncode == 0 else None


def _from_github(entry: dict) -> bytes:
    url = (
        f"https://raw.githubusercontent.com/{entry['repo']}/{entry['commit']}/"
        f"{urllib.parse.quote(entry['path'])}"
    )
    with urllib.request.urlopen(url, timeout=30) as response:
        return response.read()


def fetch(mirror: Path | None) -> int:
    TEXTS.mkdir(parents=True, exist_ok=True)
    missing = 0
    for entry in load_manifest():
        target = text_path(entry)
        if target.exists():
            continue
        data = _from_mirror(mirror, entry) if mirror else None
        if data is None:
            try:
                data = _from_github(entry)
            except OSError as e:
                print(
                    f"{entry['id']}: cannot read "
                    f"{entry['repo']}:{entry['path']}@{entry['commit'][:10]} ({e})",
                    file=sys.stderr,
                )
                missing += 1
                continue
        target.write_bytes(data)
    print(f"{len(load_manifest()) - missing} texts in {TEXTS.relative_to(ROOT)}, {missing} missing")
    return 1 if missing else 0


def verify_one(path: str, size: tuple[int, int], times: list[float]) -> dict:
    """The verdict of one shader file (run inside the child process)."""
    from glslcheck.base.diagnostics import GlslError
    from glslcheck.shadertoy.sources import load_shader
    from glslcheck.verification.verify import compile_backend, verify_frames

    shader = load_shader(path)
    try:
        gl = compile_backend(shader, "gl")
    except GlslError as e:
        return {
            "verdict": "does not compile",
            "reason": "; ".join(d.message for d in e.diagnostics)[:200],
        }
    try:
        numpy = compile_backend(shader, "numpy")
    except GlslError as e:
        return {
            "verdict": "unsupported",
            "reason": "; ".join(d.message for d in e.diagnostics)[:200],
        }
    frames = []
    try:
        for r in verify_frames(shader, size=size, times=times, programs=[numpy, gl]):
            frames.append((r.spec.time, r.comparison))
    except GlslError as e:
        return {
            "verdict": "unsupported",
            "reason": "; ".join(d.message for d in e.diagnostics)[:200],
        }
    bad = [(t, c) for t, c in frames if not c.match]
    if not bad:
        return {"verdict": "match", "reason": ""}
    if all(c.verdict == "undefined" for _, c in bad):
        t, c = bad[0]
        u = c.undefined_lines[0] if c.undefined_lines else {}
        return {
            "verdict": "undefined",
            "reason": (
                f"{len(bad)}/{len(frames)} frames; t={t:g}: {c.undefined_pixels} pixels depend on "
                f"{u.get('kind', 'an undefined read')} at line {u.get('line', '?')}"
            ),
        }
    t, c = next((t, c) for t, c in bad if c.verdict == "mismatch")
    j = c.to_json()
    return {
        "verdict": "mismatch",
        "reason": (
            f"{len(bad)}/{len(frames)} frames; t={t:g}: {j['mismatched_pixels']} over tolerance, "
            f"{j['edge_pixels']} edge, NaN/Inf numpy {j['nan_numpy']} gl {j['nan_gl']}, "
            f"max err {j['max_abs_error']:.3g}"
        ),
    }


ORDER = ("match", "mismatch", "undefined", "does not compile", "unsupported", "timeout", "error")


def run_child(cmd: list[str], timeout: float) -> dict:
    """The verdict a `_one` child process prints as its last line (timeout / error otherwise)."""
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, cwd=ROOT)
    except subprocess.TimeoutExpired:
        return {"verdict": "timeout", "reason": f"over {timeout:g} s"}
    lines = proc.stdout.strip().splitlines()
    if proc.returncode == 0 and lines:
        return json.loads(lines[-1])
    tail = (proc.stderr.strip().splitlines() or ["(no output)"])[-1]
    return {"verdict": "error", "reason": tail[:200]}


def score(size: str, times: str, timeout: float, only: set[str] | None, out: Path | None) -> int:
    entries = [e for e in load_manifest() if not only or e["id"] in only]
    absent = [e["id"] for e in entries if not text_path(e).exists()]
    if absent:
        print(
            f"{len(absent)} texts are missing ({', '.join(absent[:5])} ...): "
            "run `python tools/real_verify.py "
            f"--set {os.environ['REAL_VERIFY_SET']} fetch`",
            file=sys.stderr,
        )
        return 2
    results = []
    for entry in entries:
        started = time.perf_counter()
        result = run_child(
            [sys.executable, __file__, "_one", str(text_path(entry)), size, times], timeout
        )
        result.update(
            id=entry["id"], kind=entry["kind"], seconds=round(time.perf_counter() - started, 1)
        )
        results.append(result)
        print(
            f"{entry['id']:<24} {result['verdict']:<17} {result['seconds']:6.1f}s  "
            f"{result['reason']}",
            flush=True,
        )
    counts = {v: sum(r["verdict"] == v for r in results) for v in ORDER}
    compiled = len(results) - counts["does not compile"]
    lab4 = [r for r in results if r["kind"] == "lab4"]
    labs = [r for r in results if r["kind"].startswith("lab")]
    print()
    print("  ".join(f"{v}: {n}" for v, n in counts.items()))
    print(
        f"match among the {compiled} shaders that compile: {counts['match']}/{compiled} = "
        f"{100.0 * counts['match'] / max(compiled, 1):.1f}%; Lab 4 submissions: "
        f"{sum(r['verdict'] == 'match' for r in lab4)}/{len(lab4)} match, "
        f"{sum(r['verdict'] == 'mismatch' for r in lab4)} mismatch; all course labs: "
        f"{sum(r['verdict'] == 'match' for r in labs)}/{len(labs)} match"
    )
    if out:
        out.write_text(json.dumps(results, indent=1))
    return 0


def arguments(
    doc: str, texts: str, size: str, schedule: str, schedule_options: dict, sets: bool = False
) -> argparse.ArgumentParser:
    """The fetch / score command line of this tool and of tools/real_channels.py (`sets`: this
    tool's --set)."""
    p = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    if sets:
        p.add_argument(
            "--set",
            choices=tuple(SETS),
            help="the corpus: main (the default, or REAL_VERIFY_SET), holdout (chosen after "
            "the tuning) or fbm (iq's sphere-grid fbm family)",
        )
    sub = p.add_subparsers(dest="command", required=True)
    f = sub.add_parser("fetch", help=f"re-read the texts into {texts}")
    f.add_argument(
        "--mirror",
        type=Path,
        default=Path(os.environ["REAL_VERIFY_MIRROR"])
        if os.environ.get("REAL_VERIFY_MIRROR")
        else None,
        help="a folder of <owner>+<name>/repo git directories to read before GitHub",
    )
    s = sub.add_parser("score", help="verify every shader and print the counts")
    s.add_argument("--size", default=size)
    s.add_argument(schedule, **schedule_options)
    s.add_argument("--timeout", type=float, default=300.0)
    s.add_argument("--only", default="", help="comma-separated ids")
    s.add_argument("--json", type=Path, help="write the per-shader results here")
    return p


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["_one"]:
        path, size, times = argv[1:4]
        from glslcheck.base.limits import parse_size, parse_times

        print(json.dumps(verify_one(path, parse_size(size), list(parse_times(times)))))
        return 0
    p = arguments(
        __doc__,
        "tests/real_verify/<set's texts>/",
        "160x90",
        "--times",
        {"default": "0,1.7,5.3"},
        sets=True,
    )
    args = p.parse_args(argv)
    if args.set:
        select(args.set)
    if args.command == "fetch":
        return fetch(args.mirror)
    return score(
        args.size,
        args.times,
        args.timeout,
        set(filter(None, args.only.split(","))) or None,
        args.json,
    )


if __name__ == "__main__":
    sys.exit(main())
