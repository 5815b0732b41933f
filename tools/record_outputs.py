"""Record a fingerprint of every glslcheck output, to show that a restructure changes none of them.

    python tools/record_outputs.py [--out outputs.json] [--only SECTION,...] [--jobs N]
                                   [--lockstep] [--root DIR] [--python EXE] ...
    python tools/record_outputs.py compare A.json B.json

The script drives glslcheck only through its command line (`python -m glslcheck ...` in
subprocesses, with the checkout under test first on PYTHONPATH and as the working directory)
and uses only the standard library, so it runs unchanged however the package's modules move.
It writes one JSON object: one key per output (sorted), each a sha256, and `_meta` (what was
run, what is missing, what was left out and why; `compare` does not compare it).

Sections, cheapest first (`--only` takes a comma-separated list of them):

  lint        `lint --format json` of each lab shader, each lint fixture folder (all rules, and
              the rules its expected.json selects), each real-lint text, and of each folder whole
  check       `check` of each lab shader, tests/corpus file, real-verify text (both sets), and
              of each folder whole
  transpile   `transpile` (the NumPy module on stdout) of each lab and real-verify shader
  verify      `verify --format json` of each lab shader (and of all of them in one call)
  render      `render --backend numpy -o x.npy` of each lab and real-verify shader
  compiled    `render --backend compiled -o x.npy` per pixel (GLSLCHECK_COMPILED_LANES=0): the
              frame, and the generated numba module the engine left in $NUMBA_CACHE_DIR/compiled/
              (a fresh cache folder for every shader)
  lockstep    the same with GLSLCHECK_COMPILED_LANES=8 (pixels in lockstep); numba compiles each
              for up to a minute, so only with --lockstep (or --only lockstep)

Values: `out rc=N <sha256>` hashes the exit code, stdout and stderr of a command (check prints
its diagnostics on stderr); `npy <sha256>` and `source <sha256>` hash a written file's bytes;
`fail rc=N <sha256>` is a render that wrote no file (its exit code, stdout and stderr);
`none` is a compiled render that left no generated module. In every text the absolute path of
the checkout and of the run's temporary folder are replaced by <ROOT> and <TMP> (two checkouts
live in different folders); files are hashed as written.

Reproducibility: every subprocess gets the same environment (GLSLCHECK_JOBS=1, GLSLCHECK_JIT=off,
GLSLCHECK_PARALLEL=threads, GLSLCHECK_COMPILED_LANES per section, PYTHONHASHSEED=0, a fresh
NUMBA_CACHE_DIR and XDG_CACHE_HOME under the run's temporary folder, CI, GITHUB_ACTIONS and
every other GLSLCHECK_*, NUMBA_* and REAL_VERIFY_* variable removed). After a section,
`--samples` of its cases (first, middle, last) run a second time in another temporary folder;
a key whose two values differ is left out and named in `_meta.excluded` with the reason, as is
a command that timed out or that stopped on the NumPy frame budget (a wall-clock limit).

Texts that are not in the repository (tests/real_lint/texts, tests/real_verify/texts and
holdout_texts: third-party code) are read where tools/real_lint.py and tools/real_verify.py
put them; the missing ones are listed in `_meta.missing` (get them with
`python tools/real_verify.py [--set holdout] fetch [--mirror DIR]` and
`python tools/real_lint.py populate --mirrors DIR`).
"""

from __future__ import annotations

import argparse
import concurrent.futures
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

SECTIONS = ("lint", "check", "transpile", "verify", "render", "compiled", "lockstep")
DEFAULT_SECTIONS = SECTIONS[:-1]
CORPORA = ("lab", "corpus", "fixtures", "real_lint", "real_verify", "holdout")
# JSON fields of `verify --format json` that would hold wall-clock figures; removed before
# hashing if present (verify's documented fields hold none: see the _meta record)
TIMING_FIELDS = re.compile(
    r"(^|_)(seconds|secs|elapsed|duration|timing|timings|wall|ms|time_s)($|_)"
)
FRAME_BUDGET = "numpy-frame-budget"  # the rule of a NumPy frame stopped by its wall-clock budget
FRAME_BUDGET_TEXT = "the frame was still rendering after"


@dataclass
class Case:
    key: str  # the output's key (several outputs, e.g. frame and source: key prefix, see `keys`)
    section: str
    argv: list[str]  # after `python -m glslcheck`
    kind: str = "out"  # out: stdout+stderr+rc; npy: the file written; compiled: npy + module source
    lanes: str | None = None  # GLSLCHECK_COMPILED_LANES
    strip_timing: bool = False  # parse stdout as JSON and drop timing fields
    keys: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if not self.keys:
            self.keys = (
                (f"{self.key}/frame", f"{self.key}/source")
                if self.kind == "compiled"
                else (self.key,)
            )


@dataclass
class Result:
    values: dict[str, str]
    seconds: float
    excluded: dict[str, str] = field(default_factory=dict)  # key -> reason
    notes: list[str] = field(default_factory=list)


def sha(*parts: bytes) -> str:
    h = hashlib.sha256()
    for p in parts:
        h.update(p)
    return h.hexdigest()


def out_hash(rc: int, stdout: bytes, stderr: bytes) -> str:
    return sha(
        b"rc=%d\n" % rc, b"stdout %d\n" % len(stdout), stdout, b"stderr %d\n" % len(stderr), stderr
    )


def safe_name(key: str) -> str:
    return re.sub(r"[^A-Za-z0-9._-]+", "_", key)


class Runner:
    def __init__(self, args: argparse.Namespace, root: Path) -> None:
        self.args = args
        self.root = root
        self.python = args.python
        self.timing_removed: set[str] = set()
        self.substituted: set[str] = set()  # keys whose texts held <ROOT> or <TMP>
        self._lock = threading.Lock()

    def env(self, tmp: Path, case_dir: Path, lanes: str | None) -> dict[str, str]:
        env = {
            k: v
            for k, v in os.environ.items()
            if not k.startswith(("GLSLCHECK_", "NUMBA_", "REAL_VERIFY_", "PYTHON"))
            and k not in ("CI", "GITHUB_ACTIONS", "XDG_CACHE_HOME", "MESA_SHADER_CACHE_DIR")
        }
        env.update(
            {
                "PYTHONPATH": str(self.root),
                "PYTHONHASHSEED": "0",
                "PYTHONDONTWRITEBYTECODE": "1",
                "PYTHONUNBUFFERED": "1",
                "PYTHONIOENCODING": "utf-8",
                "LANG": "C.UTF-8",
                "LC_ALL": "C.UTF-8",
                "GLSLCHECK_JOBS": "1",
                "GLSLCHECK_JIT": "off",
                "GLSLCHECK_PARALLEL": "threads",
                "GLSLCHECK_FRAME_SECONDS": str(self.args.frame_budget),
                "NUMBA_CACHE_DIR": str(case_dir / "numba"),
                "XDG_CACHE_HOME": str(tmp / "xdg"),
                "TMPDIR": str(case_dir / "tmp"),
            }
        )
        if lanes is not None:
            env["GLSLCHECK_COMPILED_LANES"] = lanes
        return env

    def normalize(self, data: bytes, tmp: Path, key: str) -> bytes:
        out = data
        for path, name in ((str(tmp), b"<TMP>"), (str(self.root), b"<ROOT>")):
            for form in {path, os.path.realpath(path)}:
                b = form.encode()
                if b in out:
                    out = out.replace(b, name)
        if out != data:
            with self._lock:
                self.substituted.add(key)
        return out

    def run(self, case: Case, tmp: Path) -> Result:
        case_dir = tmp / "cases" / safe_name(case.key)
        if case_dir.exists():
            shutil.rmtree(case_dir)
        (case_dir / "tmp").mkdir(parents=True)
        argv = list(case.argv)
        target = case_dir / "out.npy"
        if case.kind in ("npy", "compiled"):
            argv += ["-o", str(target)]
        cmd = [self.python, "-m", "glslcheck", *argv]
        t0 = time.perf_counter()
        try:
            proc = subprocess.run(
                cmd,
                cwd=self.root,
                env=self.env(tmp, case_dir, case.lanes),
                stdin=subprocess.DEVNULL,
                capture_output=True,
                timeout=self.args.timeout,
            )
        except subprocess.TimeoutExpired:
            secs = time.perf_counter() - t0
            return Result(
                {}, secs, {k: f"timed out after {self.args.timeout:g} s" for k in case.keys}
            )
        secs = time.perf_counter() - t0
        stdout = self.normalize(proc.stdout, tmp, case.key)
        stderr = self.normalize(proc.stderr, tmp, case.key)
        if FRAME_BUDGET.encode() in stderr or FRAME_BUDGET_TEXT.encode() in stderr:
            return Result(
                {},
                secs,
                {k: "stopped by the NumPy frame budget (a wall-clock limit)" for k in case.keys},
            )
        rc = proc.returncode
        if case.kind == "out":
            if case.strip_timing:
                stdout = self.strip_timing(stdout)
            return Result({case.key: f"out rc={rc} {out_hash(rc, stdout, stderr)}"}, secs)
        values: dict[str, str] = {}
        notes: list[str] = []
        frame_key = case.keys[0]
        if rc == 0 and target.is_file():
            data = target.read_bytes()
            values[frame_key] = f"npy {sha(data)}"
            bad = self.check_npy(target)
            if bad:
                notes.append(f"{frame_key}: {bad}")
        else:
            values[frame_key] = f"fail rc={rc} {out_hash(rc, stdout, stderr)}"
        if case.kind == "compiled":
            folder = case_dir / "numba" / "compiled"
            modules = sorted(folder.glob("m*.py")) if folder.is_dir() else []
            if not modules:
                values[case.keys[1]] = "none"
            else:
                texts = sorted(self.normalize(m.read_bytes(), tmp, case.key) for m in modules)
                if len(texts) > 1:
                    notes.append(f"{case.keys[1]}: {len(texts)} generated modules, hashed together")
                if len(texts) == 1:
                    values[case.keys[1]] = f"source {sha(texts[0])}"
                else:
                    joined = sha(*(b"%d\n" % len(t) + t for t in texts))
                    values[case.keys[1]] = f"source*{len(texts)} {joined}"
        shutil.rmtree(case_dir / "numba", ignore_errors=True)
        return Result(values, secs, notes=notes)

    def strip_timing(self, stdout: bytes) -> bytes:
        try:
            data = json.loads(stdout)
        except ValueError:
            return stdout
        removed: set[str] = set()

        def walk(v):
            if isinstance(v, dict):
                out = {}
                for k, x in v.items():
                    if TIMING_FIELDS.search(k):
                        removed.add(k)
                    else:
                        out[k] = walk(x)
                return out
            if isinstance(v, list):
                return [walk(x) for x in v]
            return v

        cleaned = walk(data)
        if not removed:
            return stdout  # hashed as printed
        with self._lock:
            self.timing_removed |= removed
        return json.dumps(cleaned, sort_keys=False).encode()

    @staticmethod
    def check_npy(path: Path) -> str | None:
        try:
            import numpy as np
        except ImportError:
            return None
        a = np.load(path)
        return None if a.dtype == np.float32 else f"dtype {a.dtype}, not float32"


# ---------------------------------------------------------------------------------------------
# the cases


def lab_shaders(root: Path) -> list[Path]:
    return sorted(p for p in (root / "lab_shaders").iterdir() if p.is_dir())


def real_verify(root: Path, name: str, missing: dict[str, list[str]]) -> list[tuple[str, Path]]:
    manifest, folder = {
        "real_verify": ("manifest.json", "texts"),
        "holdout": ("holdout.json", "holdout_texts"),
    }[name]
    base = root / "tests" / "real_verify"
    entries = json.loads((base / manifest).read_text())["shaders"]
    out = []
    for e in entries:
        p = base / folder / f"{e['id']}.glsl"
        if p.is_file():
            out.append((e["id"], p))
        else:
            missing.setdefault(name, []).append(e["id"])
    return out


def real_lint(root: Path, missing: dict[str, list[str]]) -> list[tuple[str, Path]]:
    base = root / "tests" / "real_lint"
    out = []
    for e in json.loads((base / "manifest.json").read_text()):
        p = base / "texts" / e["id"] / Path(e["path"]).name
        if p.is_file():
            out.append((e["id"], p.parent))
        else:
            missing.setdefault("real_lint", []).append(e["id"])
    return out


def lint_fixtures(root: Path) -> Path:
    """The lint fixtures: tests/lint/fixtures (every folder with an expected.json)."""
    return root / "tests" / "lint" / "fixtures"


def build_cases(
    root: Path, args: argparse.Namespace, missing: dict[str, list[str]]
) -> dict[str, list[Case]]:
    # paths relative to the checkout: the same in every checkout
    rel = lambda p: str(Path(p).relative_to(root))  # noqa: E731
    want = set(args.corpora)
    size, t = args.size, args.time
    lab = [(p.name, p) for p in lab_shaders(root)] if "lab" in want else []
    rv = real_verify(root, "real_verify", missing) if "real_verify" in want else []
    ho = real_verify(root, "holdout", missing) if "holdout" in want else []
    shaders = (
        [("lab", n, p) for n, p in lab]
        + [("real_verify", n, p) for n, p in rv]
        + [("holdout", n, p) for n, p in ho]
    )
    cases: dict[str, list[Case]] = {s: [] for s in SECTIONS}

    # lint
    L = cases["lint"]
    lint = ["lint", "--format", "json"]
    if lab:
        L += [Case(f"lint/lab/{n}", "lint", lint + [rel(p)]) for n, p in lab]
        L.append(Case("lint/lab/_all", "lint", lint + ["lab_shaders"]))
    if "fixtures" in want:
        fx = lint_fixtures(root)
        for d in sorted(p for p in fx.iterdir() if p.is_dir()):
            L.append(Case(f"lint/fixtures/{d.name}", "lint", lint + [rel(d)]))
            exp = d / "expected.json"
            if exp.is_file():
                sel = json.loads(exp.read_text()).get("select")
                if sel:
                    L.append(
                        Case(
                            f"lint/fixtures/{d.name}/select",
                            "lint",
                            lint + ["--select", ",".join(sel), rel(d)],
                        )
                    )
        L.append(Case("lint/fixtures/_all", "lint", lint + [rel(fx)]))
    if "real_lint" in want:
        rl = real_lint(root, missing)
        L += [Case(f"lint/real_lint/{n}", "lint", lint + [rel(p)]) for n, p in rl]
        if rl:
            L.append(Case("lint/real_lint/_all", "lint", lint + [rel(p) for _, p in rl]))

    # check
    C = cases["check"]
    if lab:
        C += [Case(f"check/lab/{n}", "check", ["check", rel(p)]) for n, p in lab]
        C.append(Case("check/lab/_all", "check", ["check", "lab_shaders"]))
    if "corpus" in want:
        files = sorted(p for p in (root / "tests" / "corpus").iterdir() if p.is_file())
        C += [Case(f"check/corpus/{p.name}", "check", ["check", rel(p)]) for p in files]
        C.append(Case("check/corpus/_all", "check", ["check", "tests/corpus"]))
    for name, items in (("real_verify", rv), ("holdout", ho)):
        C += [Case(f"check/{name}/{n}", "check", ["check", rel(p)]) for n, p in items]
        if items:
            C.append(Case(f"check/{name}/_all", "check", ["check", *(rel(p) for _, p in items)]))

    # transpile, render, compiled, lockstep
    frame = ["--size", size, "--time", t]
    for corpus, n, p in shaders:
        cases["transpile"].append(
            Case(f"transpile/{corpus}/{n}", "transpile", ["transpile", rel(p)])
        )
        cases["render"].append(
            Case(
                f"render/{corpus}/{n}",
                "render",
                ["render", "--backend", "numpy", *frame, rel(p)],
                kind="npy",
            )
        )
        cases["compiled"].append(
            Case(
                f"compiled/{corpus}/{n}",
                "compiled",
                ["render", "--backend", "compiled", *frame, rel(p)],
                kind="compiled",
                lanes="0",
            )
        )
        cases["lockstep"].append(
            Case(
                f"lockstep/{corpus}/{n}",
                "lockstep",
                ["render", "--backend", "compiled", *frame, rel(p)],
                kind="compiled",
                lanes="8",
            )
        )

    # verify (lab shaders)
    V = cases["verify"]
    verify = ["verify", "--format", "json", "--size", args.verify_size, "--time", t]
    V += [Case(f"verify/lab/{n}", "verify", verify + [rel(p)], strip_timing=True) for n, p in lab]
    if lab:
        V.append(
            Case("verify/lab/_all", "verify", verify + [rel(p) for _, p in lab], strip_timing=True)
        )
    return cases


def samples(items: list[Case], k: int) -> list[Case]:
    if k <= 0 or not items:
        return []
    idx = sorted({round(i * (len(items) - 1) / max(k - 1, 1)) for i in range(k)}) if k > 1 else [0]
    return [items[i] for i in idx]


# ---------------------------------------------------------------------------------------------


def record(args: argparse.Namespace) -> int:
    started = time.perf_counter()
    root = Path(args.root).resolve()
    sections = (
        [s for s in SECTIONS if s in args.only]
        if args.only
        else list(DEFAULT_SECTIONS) + (["lockstep"] if args.lockstep else [])
    )
    runner = Runner(args, root)
    tmp = Path(tempfile.mkdtemp(prefix="record-outputs-"))
    try:
        # the glslcheck the subprocesses import must be this checkout's
        (tmp / "probe" / "tmp").mkdir(parents=True)
        probe = subprocess.run(
            [args.python, "-c", "import glslcheck, sys; print(glslcheck.__file__)"],
            cwd=root,
            env=runner.env(tmp, tmp / "probe", None),
            capture_output=True,
            text=True,
        )
        where = Path(probe.stdout.strip() or "?").resolve()
        if probe.returncode or root not in where.parents:
            print(
                f"error: `python -m glslcheck` in {root} imports {where}, "
                "not this checkout's package "
                f"({probe.stderr.strip()[-300:]})",
                file=sys.stderr,
            )
            return 2
        version = subprocess.run(
            [args.python, "-m", "glslcheck", "--version"],
            cwd=root,
            env=runner.env(tmp, tmp / "probe", None),
            capture_output=True,
            text=True,
        )
        head = subprocess.run(
            ["git", "-C", str(root), "rev-parse", "HEAD"], capture_output=True, text=True
        )
        print(
            f"glslcheck: {where} ({version.stdout.strip()}), {root} at "
            f"{head.stdout.strip()[:12] or '?'}"
        )
        print(
            f"sections: {', '.join(sections)}; jobs {args.jobs}; temporary folder {tmp}", flush=True
        )

        missing: dict[str, list[str]] = {}
        cases = build_cases(root, args, missing)
        for name, ids in missing.items():
            print(f"missing {len(ids)} texts of {name}: {', '.join(ids)}", file=sys.stderr)
        values: dict[str, str] = {}
        excluded: dict[str, str] = {}
        notes: list[str] = []
        per_section: dict[str, dict] = {}
        pool = concurrent.futures.ThreadPoolExecutor(max(1, args.jobs))
        for section in sections:
            todo = cases[section]
            t0 = time.perf_counter()
            print(f"[{section}] {len(todo)} commands ...", flush=True)
            results: dict[str, Result] = {}
            done = 0
            futures = {pool.submit(runner.run, c, tmp): c for c in todo}
            for fut in concurrent.futures.as_completed(futures):
                c = futures[fut]
                r = results[c.key] = fut.result()
                done += 1
                if args.verbose or r.excluded or (done % 25 == 0):
                    state = (
                        "; ".join(f"{k}: {v}" for k, v in r.excluded.items())
                        or ", ".join(r.values.values())[:60]
                    )
                    print(
                        f"  [{section} {done}/{len(todo)}] {c.key} {r.seconds:.1f}s {state}",
                        flush=True,
                    )
            # determinism: the samples once more, in another temporary folder
            again = samples(todo, args.samples)
            tmp2 = Path(tempfile.mkdtemp(prefix="record-outputs-again-"))
            checked = 0
            for c in again:
                r1 = results[c.key]
                r2 = runner.run(c, tmp2)
                checked += 1
                for k in c.keys:
                    v1, v2 = r1.values.get(k), r2.values.get(k)
                    if k in r1.excluded or k in r2.excluded:
                        r1.excluded.setdefault(k, r2.excluded.get(k, "excluded in the second run"))
                        r1.values.pop(k, None)
                    elif v1 != v2:
                        r1.excluded[k] = f"not deterministic: two runs gave {v1} and {v2}"
                        r1.values.pop(k, None)
                        print(
                            f"  [{section}] {k}: NOT DETERMINISTIC ({v1} / {v2}): left out",
                            flush=True,
                        )
            shutil.rmtree(tmp2, ignore_errors=True)
            n_keys = 0
            for c in todo:
                r = results[c.key]
                values.update(r.values)
                n_keys += len(r.values)
                excluded.update(r.excluded)
                notes += r.notes
            secs = time.perf_counter() - t0
            n_excl = sum(len(results[c.key].excluded) for c in todo)
            per_section[section] = {
                "commands": len(todo),
                "keys": n_keys,
                "excluded": n_excl,
                "corpora": list(args.corpora),
                "determinism_checked": [c.key for c in again],
                "seconds": round(secs, 1),
            }
            print(
                f"[{section}] {n_keys} keys, {n_excl} excluded, {checked} commands run twice: "
                f"same; {secs:.0f} s",
                flush=True,
            )
        pool.shutdown()
        for k, why in sorted(excluded.items()):
            print(f"excluded {k}: {why}")
        for n in notes:
            print(f"note: {n}")
        total = time.perf_counter() - started
        meta = {
            "root": str(root),
            "glslcheck": str(where),
            "version": version.stdout.strip(),
            "commit": head.stdout.strip(),
            "python": args.python,
            "sections": per_section,
            "size": args.size,
            "time": args.time,
            "verify_size": args.verify_size,
            "corpora": list(args.corpora),
            "missing": missing,
            "excluded": excluded,
            "notes": notes,
            "timing_fields_removed": sorted(runner.timing_removed),
            "keys_with_paths_replaced": sorted(runner.substituted),
            "seconds": round(total, 1),
        }
        out = Path(args.out)
        if args.merge and out.exists():  # keep the sections not run this time, and their _meta
            old = json.loads(out.read_text())
            om = old.pop("_meta", {})
            ours = lambda k: k.split("/", 1)[0] in sections  # noqa: E731
            values = {**{k: v for k, v in old.items() if not ours(k)}, **values}
            meta["sections"] = {
                **{k: v for k, v in om.get("sections", {}).items() if k not in sections},
                **per_section,
            }
            meta["excluded"] = {
                **{k: v for k, v in om.get("excluded", {}).items() if not ours(k)},
                **excluded,
            }
            meta["notes"] = [n for n in om.get("notes", []) if not ours(n)] + notes
            meta["keys_with_paths_replaced"] = sorted(
                {k for k in om.get("keys_with_paths_replaced", []) if not ours(k)}
                | runner.substituted
            )
            meta["timing_fields_removed"] = sorted(
                set(om.get("timing_fields_removed", [])) | runner.timing_removed
            )
            meta["corpora"] = sorted(
                set(om.get("corpora", [])) | set(args.corpora), key=CORPORA.index
            )
            meta["seconds_before_merge"] = om.get("seconds_before_merge", []) + [om.get("seconds")]
        doc = {"_meta": meta, **values}
        tmp_out = out.with_name(out.name + ".tmp")
        tmp_out.write_text(json.dumps(doc, indent=1, sort_keys=True) + "\n")
        tmp_out.replace(out)
        print(
            f"wrote {len(values)} keys to {out} in {total:.0f} s"
            + (
                f"; timing fields removed: {', '.join(sorted(runner.timing_removed))}"
                if runner.timing_removed
                else ""
            )
        )
        return 0
    finally:
        if args.keep_tmp:
            print(f"kept {tmp}")
        else:
            shutil.rmtree(tmp, ignore_errors=True)


def compare(a_path: str, b_path: str) -> int:
    a, b = (json.loads(Path(p).read_text()) for p in (a_path, b_path))
    ma, mb = a.pop("_meta", {}), b.pop("_meta", {})
    ex = set(ma.get("excluded", {})) | set(mb.get("excluded", {}))
    # a section that only one of the two records ran (--only) is not compared
    sa, sb = set(ma.get("sections", {})), set(mb.get("sections", {}))
    if sa and sb and sa != sb:
        for name, m, keys in ((a_path, sa - sb, a), (b_path, sb - sa, b)):
            if m:
                print(f"not compared: sections {', '.join(sorted(m))} (only {name} ran them)")
        for d in (a, b):
            for k in [k for k in d if k.split("/", 1)[0] not in sa & sb]:
                del d[k]
    differ = sorted(k for k in a.keys() & b.keys() if a[k] != b[k])
    only_a = sorted(k for k in a.keys() - b.keys() if k not in ex)
    only_b = sorted(k for k in b.keys() - a.keys() if k not in ex)
    skipped = sorted(k for k in (a.keys() ^ b.keys()) if k in ex)
    for k in differ:
        print(f"differs: {k}\n  {a_path}: {a[k]}\n  {b_path}: {b[k]}")
    for k in only_a:
        print(f"missing in {b_path}: {k}")
    for k in only_b:
        print(f"missing in {a_path}: {k}")
    for k in skipped:
        print(f"excluded in one of them (not compared): {k}")
    same = len(a.keys() & b.keys()) - len(differ)
    print(
        f"{same} keys identical, {len(differ)} differ, {len(only_a)} only in {a_path}, "
        f"{len(only_b)} only in {b_path}"
    )
    return 1 if differ or only_a or only_b else 0


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["compare"]:
        p = argparse.ArgumentParser(
            prog="record_outputs.py compare",
            description="print the keys that differ or are missing between two records",
        )
        p.add_argument("a")
        p.add_argument("b")
        a = p.parse_args(argv[1:])
        return compare(a.a, a.b)
    p = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0],
        epilog="compare mode: record_outputs.py compare A.json B.json",
    )
    p.add_argument(
        "--out", default="outputs.json", help="the JSON file to write (default outputs.json)"
    )
    p.add_argument("--only", default="", help=f"comma-separated sections: {','.join(SECTIONS)}")
    p.add_argument("--jobs", type=int, default=2, help="commands at once (default 2)")
    p.add_argument(
        "--lockstep", action="store_true", help="also the lockstep compiled renders (slow)"
    )
    p.add_argument(
        "--corpora", default=",".join(CORPORA), help=f"comma-separated: {','.join(CORPORA)}"
    )
    p.add_argument(
        "--root", default=".", help="the checkout under test (default: the working directory)"
    )
    p.add_argument(
        "--python",
        default=sys.executable,
        help="the Python that runs `-m glslcheck` (default: this one)",
    )
    p.add_argument("--size", default="64x36", help="render size (default 64x36)")
    p.add_argument("--verify-size", default="64x36", help="verify size (default 64x36)")
    p.add_argument("--time", default="1.3", help="iTime of renders and verify (default 1.3)")
    p.add_argument(
        "--samples", type=int, default=3, help="commands of each section run twice (default 3)"
    )
    p.add_argument("--timeout", type=float, default=900.0, help="seconds per command (default 900)")
    p.add_argument(
        "--frame-budget", type=float, default=300.0, help="GLSLCHECK_FRAME_SECONDS (default 300)"
    )
    p.add_argument(
        "--merge", action="store_true", help="keep the other sections' keys of an existing --out"
    )
    p.add_argument("--keep-tmp", action="store_true", help="keep the temporary folder")
    p.add_argument("-v", "--verbose", action="store_true")
    args = p.parse_args(argv)
    args.only = [s.strip() for s in args.only.split(",") if s.strip()]
    bad = [s for s in args.only if s not in SECTIONS]
    args.corpora = [c.strip() for c in args.corpora.split(",") if c.strip()]
    bad += [c for c in args.corpora if c not in CORPORA]
    if bad:
        p.error(f"unknown section or corpus: {', '.join(bad)}")
    return record(args)


if __name__ == "__main__":
    sys.exit(main())
