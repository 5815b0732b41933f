"""Score `glslcheck lint` on real student code: a labelled corpus of public GPR-200 repositories.

The corpus is tests/real_lint/manifest.json (repository, commit, path of each file) and
tests/real_lint/labels.json (the deductions a TA would make, labelled by reading the Lab 4
rubric before the linter ran on the file). The students' texts carry no licence, so they are
never committed: they live in tests/real_lint/texts/<id>/<file name> (git-ignored).

    python tools/real_lint.py populate --mirrors DIR   copy the texts out of git mirrors
    python tools/real_lint.py populate --clone         ... or clone the repositories (network)
    python tools/real_lint.py score [--verbose]        recall and precision per rule and overall
    python tools/real_lint.py score --only f27-f37     ... of some files only

`populate --mirrors DIR` reads each file with `git --git-dir=<mirror> show <commit>:<path>`,
where <mirror> is DIR/<owner>+<name>/repo (or .../repo/.git): the layout the agents' `fetch`
tool leaves in /work/.mirror. Without mirrors, `--clone` runs `git clone --bare` of
https://github.com/<owner>/<name> into a temporary folder (the commits are pinned, so the texts
are the labelled ones). `score` reads only the local folder and names every missing file.

Matching: a finding matches a label of the same rule when one of the finding's lines (its own
line, or for repeated-expression and loop-invariant every place its message lists) is one of
the label's lines. Each label and each finding counts once. The scored rules are the course
deductions of labels.json's "rules"; findings of other rules (notes) are not scored.
"""

from __future__ import annotations

import argparse
import json
import re
import subprocess
import sys
import tempfile
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CORPUS = ROOT / "tests" / "real_lint"
TEXTS = CORPUS / "texts"


def load(corrected: bool = True) -> tuple[list[dict], dict]:
    """The manifest and the labels; with `corrected`, the labels' documented corrections applied."""
    manifest = json.loads((CORPUS / "manifest.json").read_text())
    labels = json.loads((CORPUS / "labels.json").read_text())
    if corrected:
        for c in labels.get("corrections", []):
            files = labels["files"].setdefault(c["file"], [])
            if c["action"] == "add":
                files.append(c["label"])
            else:
                gone = next(
                    lab
                    for lab in files
                    if lab["rule"] == c["label"]["rule"] and lab["lines"] == c["label"]["lines"]
                )
                files.remove(gone)
    return manifest, labels


def local_path(entry: dict) -> Path:
    return TEXTS / entry["id"] / Path(entry["path"]).name


def _git_dir(mirrors: Path, repo: str) -> Path | None:
    base = mirrors / repo.replace("/", "+") / "repo"
    for cand in (base / ".git", base):
        if (cand / "objects").is_dir():
            return cand
    return None


def populate(mirrors: Path | None, clone: bool) -> int:
    manifest, _ = load()
    missing = 0
    with tempfile.TemporaryDirectory() as tmp:
        for e in manifest:
            git_dir = _git_dir(mirrors, e["repo"]) if mirrors else None
            if git_dir is None and clone:
                git_dir = Path(tmp) / e["repo"].replace("/", "+")
                if not git_dir.exists():
                    url = f"https://github.com/{e['repo']}"
                    subprocess.run(["git", "clone", "-q", "--bare", url, str(git_dir)], check=False)
            if git_dir is None or not git_dir.exists():
                print(f"missing: {e['id']} {e['repo']} (no mirror)")
                missing += 1
                continue
            shown = subprocess.run(
                ["git", f"--git-dir={git_dir}", "show", f"{e['commit']}:{e['path']}"],
                capture_output=True,
            )
            if shown.returncode:
                print(f"missing: {e['id']} {e['repo']}@{e['commit'][:8]}:{e['path']}")
                missing += 1
                continue
            out = local_path(e)
            out.parent.mkdir(parents=True, exist_ok=True)
            out.write_bytes(shown.stdout)
    print(f"{len(manifest) - missing} of {len(manifest)} files in {TEXTS.relative_to(ROOT)}")
    return 1 if missing else 0


_PLACES = re.compile(r"\blines? ((?:\d+(?:, | and )?)+)")


def finding_lines(f: dict) -> set[int]:
    """The lines a finding points at: its own, and the places its message or JSON lists."""
    lines = {f["line"]}
    lines.update(n["line"] for n in f.get("notes", ()))
    if f["rule"] in ("repeated-expression", "loop-invariant"):
        for m in _PLACES.finditer(f["message"]):
            lines.update(int(n) for n in re.findall(r"\d+", m.group(1)))
    return lines


def match(labels: list[dict], findings: list[dict]) -> dict[int, int]:
    """A maximum matching of labels to findings (label index -> finding index): same rule and a
    shared line; augmenting paths, so the order of labels and findings does not matter."""
    can = [
        [
            i
            for i, f in enumerate(findings)
            if f["rule"] == lab["rule"] and finding_lines(f) & set(lab["lines"])
        ]
        for lab in labels
    ]
    owner: dict[int, int] = {}  # finding -> label

    def augment(j: int, seen: set[int]) -> bool:
        for i in can[j]:
            if i not in seen:
                seen.add(i)
                if i not in owner or augment(owner[i], seen):
                    owner[i] = j
                    return True
        return False

    for j in range(len(labels)):
        augment(j, set())
    return {j: i for i, j in owner.items()}


def lint_json(paths: list[Path], root: Path = ROOT) -> tuple[list[dict], str, int]:
    """`glslcheck lint --format json` of the glslcheck in `root` (its folder comes first on the
    path of `python -m`): another checkout scores an older linter on the same labels."""
    cmd = [sys.executable, "-m", "glslcheck", "lint", "--format", "json", *map(str, paths)]
    run = subprocess.run(cmd, capture_output=True, text=True, cwd=root)
    try:
        findings = json.loads(run.stdout)["findings"]
    except (ValueError, KeyError):
        findings = []
    return findings, run.stderr, run.returncode


def _ids(spec: str | None) -> set[str] | None:
    """`f27-f37,f40` -> {"f27", ..., "f37", "f40"}; None for every file."""
    if not spec:
        return None
    out: set[str] = set()
    for part in spec.split(","):
        lo, _, hi = part.strip().partition("-")
        hi = hi or lo
        width = len(lo) - 1
        out.update(f"f{i:0{width}d}" for i in range(int(lo[1:]), int(hi[1:]) + 1))
    return out


def score(verbose: bool, corrected: bool = True, root: Path = ROOT, only: str | None = None) -> int:
    manifest, labels = load(corrected)
    rules = labels["rules"]
    ids = _ids(only)
    if ids is not None:
        manifest = [e for e in manifest if e["id"] in ids]
        labels = {**labels, "files": {k: v for k, v in labels["files"].items() if k in ids}}
    present = [e for e in manifest if local_path(e).exists()]
    for e in manifest:
        if e not in present:
            print(f"missing text: {e['id']} {e['repo']}:{e['path']} (run `populate`)")
    if not present:
        return 2
    tp, fp, fn = Counter(), Counter(), Counter()
    not_full = []
    for e in present:
        findings, stderr, rc = lint_json([local_path(e).resolve()], root)
        if "Traceback" in stderr or rc not in (0, 1):
            not_full.append(f"{e['id']}: exit {rc}: {stderr.strip().splitlines()[-1:]}")
        errors = [
            f"line {f['line']}"
            for f in findings
            if f["rule"] == "compile-error" and f["severity"] == "error"
        ]
        not_run = [
            f["message"].split(" could not run")[0]
            for f in findings
            if " could not run " in f["message"]
        ]
        if errors or not_run:
            not_full.append(
                f"{e['id']}: compile errors at {', '.join(errors) or '-'}; "
                "rules that could not run "
                f"everywhere: {', '.join(not_run) or 'none'}"
            )
        want = [lab for lab in labels["files"].get(e["id"], []) if lab["rule"] in rules]
        # a "could not run" note (compile-error, severity note) is not a finding to score
        got = [f for f in findings if f["rule"] in rules and f["severity"] != "note"]
        pairs = match(want, got)
        used = set(pairs.values())
        for j, lab in enumerate(want):
            if j in pairs:
                tp[lab["rule"]] += 1
            else:
                fn[lab["rule"]] += 1
                if verbose:
                    print(f"  missed  {e['id']}:{lab['lines'][0]} {lab['rule']}: {lab['why']}")
        for i, f in enumerate(got):
            if i not in used:
                fp[f["rule"]] += 1
                if verbose:
                    print(f"  extra   {e['id']}:{f['line']} {f['rule']}: {f['message']}")
    which = (
        "with the documented corrections"
        if corrected
        else "as first labelled, before any linter run"
    )
    print(
        f"{len(present)} of {len(manifest)} files, "
        f"{sum(len(v) for v in labels['files'].values())} labels ({which})"
    )
    print(f"{'rule':28} {'labels':>6} {'found':>6} {'tp':>4} {'recall':>7} {'precision':>9}")
    for rule in [*rules, "overall"]:
        if rule == "overall":
            t, p, n = sum(tp.values()), sum(fp.values()), sum(fn.values())
        else:
            t, p, n = tp[rule], fp[rule], fn[rule]
        rec = f"{t / (t + n):.2f}" if t + n else "-"
        pre = f"{t / (t + p):.2f}" if t + p else "-"
        print(f"{rule:28} {t + n:6d} {t + p:6d} {t:4d} {rec:>7} {pre:>9}")
    print(
        "files that did not lint fully (as the linter reports it):"
        if not_full
        else "every file linted fully"
    )
    for line in not_full:
        print("  " + line)
    return 0


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    p = sub.add_parser("populate", help="copy the texts into tests/real_lint/texts")
    p.add_argument("--mirrors", type=Path, help="folder of git mirrors <owner>+<name>/repo")
    p.add_argument("--clone", action="store_true", help="clone repositories without a mirror")
    s = sub.add_parser("score", help="lint the local texts and score against the labels")
    s.add_argument("--verbose", "-v", action="store_true", help="list every miss and extra finding")
    s.add_argument(
        "--as-labelled",
        action="store_true",
        help="the labels as first made, without the corrections",
    )
    s.add_argument(
        "--glslcheck-root",
        type=Path,
        default=ROOT,
        help="score the glslcheck of another checkout (e.g. `git archive <commit>` unpacked)",
    )
    s.add_argument("--only", metavar="IDS", help="score these files only, e.g. f27-f37 or f01,f04")
    args = ap.parse_args()
    if args.cmd == "populate":
        return populate(args.mirrors, args.clone)
    return score(args.verbose, not args.as_labelled, args.glslcheck_root.resolve(), args.only)


if __name__ == "__main__":
    sys.exit(main())
