"""Score `glslcheck lint` on real student code: a labelled corpus of public GPR-200 repositories.

The corpus is tests/real_lint/manifest.json (repository, commit, path of each file) and
tests/real_lint/labels.json (the deductions a TA would make, labelled by reading the Lab 4
rubric before the linter ran on the file). The students' texts carry no licence, so they are
never committed: they live in tests/real_lint/texts/<id>/<file name> (git-ignored).

    python tools/real_lint.py populate --mirrors DIR   copy the texts out of git mirrors
    python tools/real_lint.py populate --clone         ... or clone the repositories (network)
    python tools/real_lint.py score [--verbose]        recall and precision per rule and overall
    python tools/real_lint.py score --only f27-f37     ... of some files only
    python tools/real_lint.py score --labels L.json --manifest M.json --texts DIR
                                                       ... of another labelled set, no code edit
    python tools/real_lint.py merge-labels L.json --rules R,... --source TEXT
                                                       take another labeller's labels of some
                                                       rules into labels.json

`populate --mirrors DIR` reads each file with `git --git-dir=<mirror> show <commit>:<path>`,
where <mirror> is DIR/<owner>+<name>/repo (or .../repo/.git): the layout the agents' `fetch`
tool leaves in /work/.mirror. Without mirrors, `--clone` runs `git clone --bare` of
https://github.com/<owner>/<name> into a temporary folder (the commits are pinned, so the texts
are the labelled ones). `score` reads only the local folder and names every missing file.

Labels: labels.json's form ({"rules": [...], "files": {id: [label, ...]}, "corrections": [...]})
or the blind labellers' form (/work/labels/RULES.md: {id: [label, ...]}); a label is {"rule",
"lines", "why", "certainty"}. The scored rules are the rules the labels cover (labels.json's
"rules"; for the labellers' form every rule id of RULES.md, or `--rules`): a file with no label
for a scored rule is labelled clean for it, so every finding there counts against precision.
Findings of other rules and notes (penalty 0) are not scored, except that where the labels
cover "other-inefficiency" (the guide's id for an inefficiency none of its ids fits), a deduction
of an efficiency rule the guide has no id for (unused-variable, no-op-arithmetic) is scored as
one: it is that kind of deduction, and counts against precision where no label meets it.

Matching: a finding matches a label of the same rule when they share a line: the finding's own
line (a missing-comment finding: every line of its run, first to last; repeated-expression and
loop-invariant: every place the message lists) and the label's lines (a missing-comment label
is a run [first, last]: any line in it). Labels and findings are matched one to one (a maximum
matching): recall and precision count the points a student loses, so a labeller's one run
over four blocks against four findings is one hit and three extras. Beside them, at line level
and not one to one: "held", the share of labels sharing a line with some finding, and
"inside", the share of findings sharing a line with some label (where the linter and the
labeller disagree only on how to cut the same uncommented code into runs, these stay high).
Certainty is reported apart: the recall of the certain and of the possible labels (a label
without one is certain), the precision of the certain and of the possible findings.

`--second L2.json` (a second blind reading of the same files) adds the figures with the readers'
own disagreement taken out: recall on the labels both readings give (paired as
tools/label_agreement.py pairs them), and precision against either reading (a finding counts
when it matches a label of the first reading or an unpaired label of the second). The
headline stays the first reading's figures.
"""

from __future__ import annotations

import argparse
import glob
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
sys.path.insert(0, str(ROOT))

from glslcheck.lint.rules import all_rules  # noqa: E402
from glslcheck.shadertoy.sources import common_sibling  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from label_agreement import pairs as label_pairs  # noqa: E402

# Every rule id of the labelling guide (/work/labels/RULES.md): what a blind labeller labels.
GUIDE_RULES = [
    "compile-error",
    "missing-header",
    "incomplete-header",
    "missing-comment",
    "uniform-outside-mainimage",
    "length-comparison",
    "sqrt-comparison",
    "pow-small-exponent",
    "pow-negative-base",
    "repeated-expression",
    "loop-invariant",
    "branch-replaceable",
    "normalize-known-length",
    "out-parameter-read",
    "other-inefficiency",
]
# The rules of the efficiency standard: a finding of one of them on the lines of an
# "other-inefficiency" label (the guide's id for an inefficiency no specific id fits) is the
# same deduction under a more specific name; `score` counts those pairs apart. The registry
# of this checkout names them (a rule's STANDARD), also when scoring an older linter.
EFFICIENCY_RULES = tuple(r.name for r in all_rules().values() if r.standard == "efficiency")
OTHER = "other-inefficiency"
RUN_RULES = ("missing-comment",)  # labelled and reported as runs of lines [first, last]


def load_labels(
    path: Path | None = None, corrected: bool = True, rules: list[str] | None = None
) -> dict:
    """Labels in labels.json's form ({"rules", "files", "corrections"}); a labellers' file
    ({id: [label, ...]}) is read into it, covering `rules` (default: every guide rule). With
    `corrected`, the documented corrections are applied."""
    doc = json.loads((path or CORPUS / "labels.json").read_text())
    if "files" not in doc:
        doc = {"rules": list(GUIDE_RULES), "files": doc, "corrections": []}
    if rules is not None:
        doc["rules"] = list(rules)
    if corrected:
        for c in doc.get("corrections", []):
            files = doc["files"].setdefault(c["file"], [])
            if c["action"] == "add":
                files.append(c["label"])
            else:
                gone = next(
                    lab
                    for lab in files
                    if lab["rule"] == c["label"]["rule"] and lab["lines"] == c["label"]["lines"]
                )
                files.remove(gone)
    return doc


def load(corrected: bool = True) -> tuple[list[dict], dict]:
    """The manifest and the labels; with `corrected`, the labels' documented corrections applied."""
    return json.loads((CORPUS / "manifest.json").read_text()), load_labels(None, corrected)


def text_path(entry: dict, texts: Path = TEXTS) -> Path:
    """Where `populate` writes a manifest entry's text: <texts>/<id>/<file name>, a JSON export's
    tab as <file stem>.txt."""
    path = texts / entry["id"] / Path(entry["path"]).name
    return path.with_suffix(".txt") if "tab" in entry else path


def local_path(entry: dict, texts: Path = TEXTS) -> Path:
    """Where a manifest entry's text is: `text_path`, else the one file in <texts>/<id>/, else
    a flat folder's <texts>/<id>.<ext> or <texts>/<file name>."""
    path = text_path(entry, texts)
    if path.exists():
        return path
    if (texts / entry["id"]).is_dir():
        inside = [p for p in (texts / entry["id"]).iterdir() if p.is_file()]
        if len(inside) == 1:
            return inside[0]
    flat = sorted(texts.glob(f"{glob.escape(entry['id'])}.*")) if texts.is_dir() else []
    if len(flat) == 1:
        return flat[0]
    if (texts / Path(entry["path"]).name).is_file():
        return texts / Path(entry["path"]).name
    return path


def _git_dir(mirrors: Path, repo: str) -> Path | None:
    base = mirrors / repo.replace("/", "+") / "repo"
    for cand in (base / ".git", base):
        if (cand / "objects").is_dir():
            return cand
    return None


def populate(
    mirrors: Path | None, clone: bool, manifest_path: Path | None = None, texts: Path = TEXTS
) -> int:
    """Write each manifest entry's text to `texts`/<id>/<file name>, from a git mirror or a
    clone, at its pinned commit."""
    manifest = json.loads((manifest_path or CORPUS / "manifest.json").read_text())
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
            out = text_path(e, texts)  # where score looks first
            data, common = shown.stdout, None
            if "tab" in e:  # a Shadertoy JSON export: the tab as the student's editor had it
                passes = _export_passes(data)
                code = _tab_code(passes, e["tab"])
                if code is None:
                    print(f"missing: {e['id']} has no {e['tab']} pass")
                    missing += 1
                    continue
                data = code.encode()
                common = _tab_code(passes, "Common") if e["tab"] != "Common" else None
            out.parent.mkdir(parents=True, exist_ok=True)
            out.write_bytes(data)
            # the Common tab beside it, which glslcheck reads with it
            if "tab" not in e:
                _copy_common(git_dir, e, out.parent)
            elif common is not None:
                (out.parent / "Common.txt").write_text(common)
    print(f"{len(manifest) - missing} of {len(manifest)} files in {texts}")
    return 1 if missing else 0


def _copy_common(git_dir: Path, e: dict, folder: Path) -> None:
    """Write the Common tab file beside the entry's file in its repository (as glslcheck finds
    it: `common_sibling`) into `folder`, as a student's checkout has it."""
    parent = str(Path(e["path"]).parent)
    listed = subprocess.run(
        ["git", f"--git-dir={git_dir}", "ls-tree", "--name-only", e["commit"], f"{parent}/"],
        capture_output=True,
        text=True,
    ).stdout.split("\n")
    common = common_sibling(e["path"], [n for n in listed if n])
    if common is not None:
        shown = subprocess.run(
            ["git", f"--git-dir={git_dir}", "show", f"{e['commit']}:{common}"], capture_output=True
        )
        if not shown.returncode:
            (folder / Path(common).name).write_bytes(shown.stdout)


def _export_passes(export: bytes) -> list[dict]:
    """The render passes of a Shadertoy JSON export: one shader (`{"info", "renderpass"}`) or an
    account's export (`{"shaders": [...]}`, its first)."""
    shader = json.loads(export)
    if "renderpass" not in shader:
        shader = shader["shaders"][0]
    return shader["renderpass"]


def _tab_code(passes: list[dict], tab: str) -> str | None:
    """The code of pass `tab` ("Image", "Common", "Buffer A", ...) among an export's passes;
    None when it has no such pass."""
    for rp in passes:
        if rp.get("name") == tab or (tab == "Image" and rp.get("type") == "image"):
            return rp["code"]
    return None


_RUN = re.compile(r"\(lines? (\d+)(?:-(\d+))?\)")
_PLACES = re.compile(r"\blines? ((?:\d+(?:, | and )?)+)")


def finding_lines(f: dict) -> set[int]:
    """The lines a finding points at: its own (a run's every line), and the places its message or
    JSON lists."""
    lines = {f["line"]}
    if f["rule"] in RUN_RULES:  # the run: its span, or the `(lines 12-15)` its message names
        run = _RUN.search(f["message"])
        last = int(run.group(2) or run.group(1)) if run else f.get("end_line", f["line"])
        lines.update(range(f["line"], max(last, f.get("end_line", f["line"])) + 1))
    lines.update(n["line"] for n in f.get("notes", ()))
    if f["rule"] in ("repeated-expression", "loop-invariant"):
        for m in _PLACES.finditer(f["message"]):
            lines.update(int(n) for n in re.findall(r"\d+", m.group(1)))
    return lines


def label_lines(lab: dict) -> set[int]:
    """The lines a label is about: a run label's every line from its first to its last."""
    if lab["rule"] in RUN_RULES:
        return set(range(lab["lines"][0], lab["lines"][-1] + 1))
    return set(lab["lines"])


def shares_line(lab: dict, f: dict, any_rule: bool = False) -> bool:
    """Whether a finding and a label can match: the same rule (or the guide id the finding is
    "also"; any rule with `any_rule`) and a line in common."""
    same = any_rule or lab["rule"] in (f["rule"], f.get("also"))
    return same and bool(finding_lines(f) & label_lines(lab))


def line_level(labels: list[dict], findings: list[dict]) -> tuple[Counter, Counter]:
    """Per rule, the labels holding some finding and the findings inside some label (sharing a
    line, as `match` pairs them, but not one to one)."""
    held = Counter(lab["rule"] for lab in labels if any(shares_line(lab, f) for f in findings))
    inside = Counter(f["rule"] for f in findings if any(shares_line(lab, f) for lab in labels))
    return held, inside


def match(labels: list[dict], findings: list[dict], any_rule: bool = False) -> dict[int, int]:
    """A maximum matching of labels to findings (label index -> finding index): same rule (any
    rule with `any_rule`) and a shared line; augmenting paths, so the order of labels and
    findings does not matter."""
    can = [[i for i, f in enumerate(findings) if shares_line(lab, f, any_rule)] for lab in labels]
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


# A rule the guide has no id for whose deduction is also the one a guide id names: a value a
# helper computes again in each call (repeated-across-calls) is "the same pure computation done
# again with the same operand values", which readers label repeated-expression as often as
# other-inefficiency (both readings of set 5 on m06's seven calls, set 2's on the view vector).
ALSO = {"repeated-across-calls": "repeated-expression"}


def scored_as(f: dict, rules: list[str]) -> dict:
    """The finding as scored: a deduction of an efficiency rule the guide has no id for
    (unused-variable, no-op-arithmetic) is what the guide's other-inefficiency labels (an
    inefficiency none of its ids fits), so where the labels cover that id it is scored as one,
    its own rule kept in "as"; where ALSO names a guide id the labels cover too, it may match
    a label of either ("also")."""
    if (
        OTHER in rules
        and f["rule"] in EFFICIENCY_RULES
        and f["rule"] not in GUIDE_RULES
        and f["penalty"]
    ):
        also = ALSO.get(f["rule"])
        extra = {"also": also} if also in rules else {}
        return {**f, "rule": OTHER, "as": f["rule"], **extra}
    return f


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
    """`f27-f37,m40` -> {"f27", ..., "f37", "m40"} (each set's own letter); None for every
    file."""
    if not spec:
        return None
    out: set[str] = set()
    for part in spec.split(","):
        lo, _, hi = part.strip().partition("-")
        hi = hi or lo
        letter, width = lo[0], len(lo) - 1
        out.update(f"{letter}{i:0{width}d}" for i in range(int(lo[1:]), int(hi[1:]) + 1))
    return out


def _rate(hit: int, total: int) -> str:
    return f"{hit / total:.2f}" if total else "-"


def score(
    verbose: bool,
    corrected: bool = True,
    root: Path = ROOT,
    only: str | None = None,
    labels_path: Path | None = None,
    manifest_path: Path | None = None,
    texts: Path = TEXTS,
    rules: list[str] | None = None,
    second_path: Path | None = None,
) -> int:
    manifest = json.loads((manifest_path or CORPUS / "manifest.json").read_text())
    labels = load_labels(labels_path, corrected, rules)
    rules = labels["rules"]
    second = load_labels(second_path, corrected, rules)["files"] if second_path else None
    both = Counter()  # against both readings: agreed labels (found), findings (either matched)
    ids = _ids(only)
    if ids is not None:
        manifest = [e for e in manifest if e["id"] in ids]
        labels = {**labels, "files": {k: v for k, v in labels["files"].items() if k in ids}}
    present = [e for e in manifest if local_path(e, texts).exists()]
    for e in manifest:
        if e not in present:
            print(f"missing text: {e['id']} {e.get('repo', '')}:{e['path']} (run `populate`)")
    if not present:
        print("no file of the manifest to score" + (f" among {only}" if only else ""))
        return 2
    tp, fp, fn = Counter(), Counter(), Counter()
    # line level, not one to one: findings inside some label, labels holding some finding
    inside, held = Counter(), Counter()
    # certainty: labels found / labels, findings matched / findings, per certainty
    by_label, by_finding = Counter(), Counter()
    not_full = []
    crossed: list[str] = []  # an extra efficiency finding on a missed other-inefficiency label
    for e in present:
        findings, stderr, rc = lint_json([local_path(e, texts).resolve()], root)
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
        got = [
            scored_as(f, rules)
            for f in findings
            if scored_as(f, rules)["rule"] in rules and f["severity"] != "note"
        ]
        pairs = match(want, got)
        used = set(pairs.values())
        file_held, file_inside = line_level(want, got)
        held.update(file_held)
        inside.update(file_inside)
        for j, lab in enumerate(want):
            sure = lab.get("certainty") or "certain"
            by_label[sure, "all"] += 1
            if j in pairs:
                tp[lab["rule"]] += 1
                by_label[sure, "hit"] += 1
                said = got[pairs[j]].get("certainty") or "certain"
                by_label["pairs", "agree" if said == sure else "differ"] += 1
            else:
                fn[lab["rule"]] += 1
                if verbose:
                    print(f"  missed  {e['id']}:{lab['lines'][0]} {lab['rule']}: {lab['why']}")
        for i, f in enumerate(got):
            sure = f.get("certainty") or "certain"  # compile errors: none, as the labels
            by_finding[sure, "all"] += 1
            if i in used:
                by_finding[sure, "hit"] += 1
            else:
                fp[f["rule"]] += 1
                if verbose:
                    print(f"  extra   {e['id']}:{f['line']} {f['rule']}: {f['message']}")
        if second is not None:
            other = [lab for lab in second.get(e["id"], []) if lab["rule"] in rules]
            agreed = label_pairs(want, other)
            paired_other = {i for _, i in agreed}
            both["agreed"] += len(agreed)
            both["agreed found"] += sum(j in pairs for j, _ in agreed)
            either = want + [lab for i, lab in enumerate(other) if i not in paired_other]
            both["findings"] += len(got)
            both["either matched"] += len(match(either, got))
        missed_other = [
            lab for j, lab in enumerate(want) if j not in pairs and lab["rule"] == OTHER
        ]
        extra_efficiency = [
            f for i, f in enumerate(got) if i not in used and f["rule"] in EFFICIENCY_RULES
        ] + [  # deductions of efficiency rules the labels have no id for, when not scored
            f
            for f in findings
            if f["rule"] in EFFICIENCY_RULES
            and scored_as(f, rules)["rule"] not in rules
            and f["penalty"]
        ]
        for j, i in match(missed_other, extra_efficiency, any_rule=True).items():
            f = extra_efficiency[i]
            crossed.append(f"{e['id']}:{missed_other[j]['lines'][0]} {f['rule']}")
    which = (
        "with the documented corrections"
        if corrected and labels.get("corrections")
        else "as first labelled, before any linter run"
    )
    count = sum(len([lab for lab in v if lab["rule"] in rules]) for v in labels["files"].values())
    print(f"{len(present)} of {len(manifest)} files, {count} labels ({which})")
    print(
        f"{'rule':28} {'labels':>6} {'found':>6} {'tp':>4} {'recall':>7} {'precision':>9}"
        f"   {'held':>5} {'inside':>6}"
    )
    for rule in [*rules, "overall"]:
        if rule == "overall":
            t, p, n = sum(tp.values()), sum(fp.values()), sum(fn.values())
            h, i = sum(held.values()), sum(inside.values())
        else:
            t, p, n = tp[rule], fp[rule], fn[rule]
            h, i = held[rule], inside[rule]
        print(
            f"{rule:28} {t + n:6d} {t + p:6d} {t:4d} {_rate(t, t + n):>7} {_rate(t, t + p):>9}"
            f"   {_rate(h, t + n):>5} {_rate(i, t + p):>6}"
        )
    print(
        "  held: share of labels sharing a line with some finding; inside: share of findings "
        "sharing a line with some label (line level, not one to one)"
    )
    if crossed:
        print(
            f"{OTHER} labels met by an extra finding of an efficiency rule on their lines (the "
            f"same deduction, a specific id; counted above as a miss, and a scored rule's "
            f"finding as an extra): "
            f"{len(crossed)}: {', '.join(crossed)}"
        )
    if second is not None:
        a, af = both["agreed"], both["agreed found"]
        n, nm = both["findings"], both["either matched"]
        print(
            f"against both readings: recall on the labels both give {_rate(af, a)} ({af}/{a}), "
            f"precision against either reading {_rate(nm, n)} ({nm}/{n})"
        )
    print("by certainty (labels: the labeller's; findings: the linter's)")
    for sure in ("certain", "possible"):
        lab_hit, lab_all = by_label[sure, "hit"], by_label[sure, "all"]
        f_hit, f_all = by_finding[sure, "hit"], by_finding[sure, "all"]
        print(
            f"  {sure:9} labels {lab_all:4d}, found {lab_hit:4d}: "
            f"recall {_rate(lab_hit, lab_all):>4}"
            f"   findings {f_all:4d}, matched {f_hit:4d}: precision {_rate(f_hit, f_all):>4}"
        )
    agree, differ = by_label["pairs", "agree"], by_label["pairs", "differ"]
    print(f"  matched pairs whose certainty agrees: {agree} of {agree + differ}")
    print(
        "files that did not lint fully (as the linter reports it):"
        if not_full
        else "every file linted fully"
    )
    for line in not_full:
        print("  " + line)
    return 0


def labels_text(doc: dict) -> str:
    """labels.json as it is kept: its notes and rules first, then one label or correction a line
    (a diff then shows each label changed)."""

    def one(x: object) -> str:
        return json.dumps(x, ensure_ascii=False)

    out = ["{"]
    for key, value in doc.items():
        if key == "files":
            out.append(' "files": {')
            for n, (fid, labs) in enumerate(value.items()):
                body = ",\n".join(f"   {one(lab)}" for lab in labs)
                out.append(f"  {one(fid)}: [\n{body}\n  ]" if labs else f"  {one(fid)}: []")
                out[-1] += "," if n < len(value) - 1 else ""
            out.append(" }")
        elif key == "corrections":
            body = ",\n".join(f"  {one(c)}" for c in value)
            out.append(f' "corrections": [\n{body}\n ]' if value else ' "corrections": []')
        else:
            out.append(f" {one(key)}: {one(value)}")
        out[-1] += ","
    out[-1] = out[-1].rstrip(",")
    return "\n".join(out) + "\n}\n"


def merge_labels(source: Path, rules: list[str], provenance: str) -> int:
    """Take `source`'s labels (the labellers' form) of `rules` into labels.json: for each file it
    labels, its labels of those rules replace the ones there, as first labels (corrections of
    those rules on those files are dropped: they corrected the replaced labels). `provenance`
    is recorded in "about"."""
    path = CORPUS / "labels.json"
    doc = json.loads(path.read_text())
    new = json.loads(source.read_text())
    wanted = set(rules)
    for fid, labs in sorted(new.items()):
        kept = [lab for lab in doc["files"].get(fid, []) if lab["rule"] not in wanted]
        doc["files"][fid] = kept + [lab for lab in labs if lab["rule"] in wanted]
    doc["corrections"] = [
        c for c in doc["corrections"] if not (c["file"] in new and c["label"]["rule"] in wanted)
    ]
    doc["rules"] = [r for r in GUIDE_RULES if r in set(doc["rules"]) | wanted]
    files = f"{min(new)}-{max(new)}" if new else "no files"
    note = f" Labels of {', '.join(rules)} for {files}: {provenance}"
    if note not in doc["about"]:
        doc["about"] += note
    doc["files"] = dict(sorted(doc["files"].items()))
    path.write_text(labels_text(doc))
    print(f"merged {sum(len(v) for v in new.values())} labels of {len(new)} files into {path}")
    return 0


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    p = sub.add_parser("populate", help="copy the texts into tests/real_lint/texts")
    p.add_argument("--mirrors", type=Path, help="folder of git mirrors <owner>+<name>/repo")
    p.add_argument("--clone", action="store_true", help="clone repositories without a mirror")
    p.add_argument(
        "--manifest", type=Path, metavar="FILE", help="another manifest (manifest.json's form)"
    )
    p.add_argument(
        "--texts", type=Path, default=TEXTS, metavar="DIR", help="where to write: DIR/<id>/<name>"
    )
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
    s.add_argument(
        "--labels",
        type=Path,
        metavar="FILE",
        help="labels to score against (labels.json's form, or the labellers' {id: [label]})",
    )
    s.add_argument(
        "--manifest", type=Path, metavar="FILE", help="the files' manifest (manifest.json's form)"
    )
    s.add_argument(
        "--texts", type=Path, default=TEXTS, metavar="DIR", help="the texts: DIR/<id>/<file name>"
    )
    s.add_argument(
        "--rules",
        metavar="R,...",
        help="the rules the labels cover (default: labels.json's, or every rule of the guide)",
    )
    s.add_argument(
        "--second",
        type=Path,
        metavar="FILE",
        help="a second blind reading: also score on the labels both give, and against either",
    )
    m = sub.add_parser("merge-labels", help="take another labeller's labels into labels.json")
    m.add_argument("source", type=Path, help="a labellers' file {id: [label, ...]}")
    m.add_argument("--rules", required=True, metavar="R,...", help="the rules to take")
    m.add_argument("--source", dest="provenance", required=True, help="who labelled, and how")
    args = ap.parse_args()
    if args.cmd == "populate":
        return populate(args.mirrors, args.clone, args.manifest, args.texts)
    if args.cmd == "merge-labels":
        return merge_labels(args.source, args.rules.split(","), args.provenance)
    return score(
        args.verbose,
        not args.as_labelled,
        args.glslcheck_root.resolve(),
        args.only,
        args.labels,
        args.manifest,
        args.texts,
        args.rules.split(",") if args.rules else None,
        args.second,
    )


if __name__ == "__main__":
    sys.exit(main())
