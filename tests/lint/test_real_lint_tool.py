"""tools/real_lint.py, the scorer of the real-code corpus: its matching of run labels, its
reading of a blind labeller's file, and `score` on a labelled set of its own (our texts)."""

from __future__ import annotations

import json
import subprocess
import sys

from .conftest import REPO_ROOT

sys.path.insert(0, str(REPO_ROOT / "tools"))
import real_lint  # noqa: E402


def _comment_finding(first: int, last: int) -> dict:
    return {
        "rule": "missing-comment",
        "line": first,
        "end_line": last,
        "message": f"{last - first + 1} lines of code without a comment (lines {first}-{last})",
    }


def test_a_finding_anywhere_in_a_labelled_run_matches_it_once():
    labels = [
        {"rule": "missing-comment", "lines": [10, 14]},
        {"rule": "missing-comment", "lines": [20, 20]},
    ]
    # 12-16 overlaps the first run only; 13 is inside it too, but a label matches one finding
    findings = [_comment_finding(12, 16), _comment_finding(13, 13), _comment_finding(17, 19)]
    assert real_lint.match(labels, findings) == {0: 0}
    assert real_lint.match(labels, [_comment_finding(19, 21)]) == {1: 0}


def test_line_level_counts_a_run_split_in_four_as_held_and_inside():
    # one labelled run 10-30 and four findings cutting it in four, one finding outside: one to
    # one that is one hit and four extras; at line level the label holds a finding and four of
    # the five findings lie inside a label
    labels = [{"rule": "missing-comment", "lines": [10, 30]}]
    cuts = [(10, 12), (15, 17), (20, 22), (25, 30), (40, 41)]
    findings = [_comment_finding(a, b) for a, b in cuts]
    assert len(real_lint.match(labels, findings)) == 1
    held, inside = real_lint.line_level(labels, findings)
    assert held == {"missing-comment": 1} and inside == {"missing-comment": 4}
    assert real_lint.line_level(labels, []) == ({}, {})


def test_an_other_inefficiency_label_meets_a_specific_finding_only_across_rules():
    labels = [{"rule": "other-inefficiency", "lines": [123, 124]}]
    findings = [{"rule": "normalize-known-length", "line": 123, "message": "normalize() ..."}]
    assert real_lint.match(labels, findings) == {}
    assert real_lint.match(labels, findings, any_rule=True) == {0: 0}
    assert "normalize-known-length" in real_lint.EFFICIENCY_RULES


def test_a_deduction_the_guide_has_no_id_for_is_scored_as_other_inefficiency():
    unused = {"rule": "unused-variable", "line": 130, "message": "never read", "penalty": 1}
    note = {**unused, "penalty": 0}
    specific = {"rule": "normalize-known-length", "line": 123, "message": "...", "penalty": 1}
    guide = real_lint.GUIDE_RULES
    assert real_lint.scored_as(unused, guide)["rule"] == "other-inefficiency"
    assert real_lint.scored_as(unused, guide)["as"] == "unused-variable"
    # a note costs nothing; a guide id keeps its own; labels without the id leave it alone
    assert real_lint.scored_as(note, guide) is note
    assert real_lint.scored_as(specific, guide) is specific
    assert real_lint.scored_as(unused, ["missing-comment"]) is unused
    labels = [{"rule": "other-inefficiency", "lines": [130]}]
    assert real_lint.match(labels, [real_lint.scored_as(unused, guide)]) == {0: 0}


def test_a_value_repeated_across_calls_matches_either_guide_id_once():
    across = {
        "rule": "repeated-across-calls",
        "line": 77,
        "message": "'length(dist)' has the same value in each of the 2 calls of f at lines 87 "
        "and 88",
        "notes": [{"line": 87}, {"line": 88}],
        "penalty": 1,
    }
    scored = real_lint.scored_as(across, real_lint.GUIDE_RULES)
    assert scored["rule"] == "other-inefficiency" and scored["also"] == "repeated-expression"
    repeated = {"rule": "repeated-expression", "lines": [87, 88]}
    other = {"rule": "other-inefficiency", "lines": [87]}
    assert real_lint.match([repeated], [scored]) == {0: 0}
    assert real_lint.match([other], [scored]) == {0: 0}
    # one finding, one deduction: of two labels on its lines it matches one
    assert len(real_lint.match([repeated, other], [scored])) == 1
    # another guide id, or labels that do not cover repeated-expression, do not take it
    assert real_lint.match([{"rule": "loop-invariant", "lines": [87]}], [scored]) == {}
    assert "also" not in real_lint.scored_as(across, ["other-inefficiency"])


def test_a_labellers_file_covers_every_rule_of_the_guide(tmp_path):
    path = tmp_path / "labels.json"
    path.write_text(json.dumps({"f01": [{"rule": "missing-header", "lines": [1]}], "f02": []}))
    doc = real_lint.load_labels(path)
    assert doc["rules"] == real_lint.GUIDE_RULES and set(doc["files"]) == {"f01", "f02"}
    assert real_lint.load_labels(path, rules=["missing-header"])["rules"] == ["missing-header"]


def test_labels_json_is_kept_one_label_a_line():
    path = REPO_ROOT / "tests" / "real_lint" / "labels.json"
    assert real_lint.labels_text(json.loads(path.read_text())) == path.read_text()


def _one_file_set(tmp_path) -> None:
    """A set of one file of ours, t01 (an uncommented mainImage with no header): its text and
    manifest under tmp_path, as `populate` leaves a set."""
    text = (
        "void mainImage(out vec4 fragColor, in vec2 fragCoord)\n{\n    fragColor = vec4(1.0);\n}\n"
    )
    (tmp_path / "texts" / "t01").mkdir(parents=True)
    (tmp_path / "texts" / "t01" / "Lab 4.txt").write_text(text)
    manifest = [{"id": "t01", "repo": "ours/lab", "commit": "0" * 40, "path": "Lab 4.txt"}]
    (tmp_path / "manifest.json").write_text(json.dumps(manifest))


def test_score_a_set_given_on_the_command_line(tmp_path):
    _one_file_set(tmp_path)
    labels = {
        "t01": [
            {"rule": "missing-header", "lines": [1], "why": "no author", "certainty": "certain"},
            {
                "rule": "missing-comment",
                "lines": [1, 3],
                "why": "no comment",
                "certainty": "certain",
            },
        ]
    }
    (tmp_path / "labels.json").write_text(json.dumps(labels))
    proc = subprocess.run(
        [
            sys.executable,
            str(REPO_ROOT / "tools" / "real_lint.py"),
            "score",
            "--labels",
            str(tmp_path / "labels.json"),
            "--manifest",
            str(tmp_path / "manifest.json"),
            "--texts",
            str(tmp_path / "texts"),
            "--rules",
            "missing-header,missing-comment,incomplete-header",
        ],
        capture_output=True,
        text=True,
        cwd=tmp_path,
    )
    assert proc.returncode == 0, proc.stderr
    rows = {line.split()[0]: line.split()[1:] for line in proc.stdout.splitlines() if line}
    assert rows["missing-header"] == ["1", "1", "1", "1.00", "1.00", "1.00", "1.00"]
    assert rows["missing-comment"] == ["1", "1", "1", "1.00", "1.00", "1.00", "1.00"]
    assert rows["incomplete-header"] == ["0", "0", "0", "-", "-", "-", "-"]
    assert "certain   labels    2, found    2: recall 1.00" in proc.stdout


def test_texts_in_a_flat_folder_are_found(tmp_path):
    (tmp_path / "t07.txt").write_text("x")
    (tmp_path / "Lab04.txt").write_text("y")
    assert real_lint.local_path({"id": "t07", "path": "a/b/c.txt"}, tmp_path).name == "t07.txt"
    assert real_lint.local_path({"id": "t08", "path": "x/Lab04.txt"}, tmp_path).name == "Lab04.txt"


def test_only_reads_each_sets_own_letter():
    """`--only` names files by their set's letter (f, g, k, m, ...), ranges and lists alike."""
    assert real_lint._ids("m01-m03,k10") == {"m01", "m02", "m03", "k10"}
    assert real_lint._ids("f27-f28") == {"f27", "f28"}
    assert real_lint._ids(None) is None


def test_a_second_reading_takes_the_readers_disagreement_out(tmp_path):
    """The first reading misses the header the linter reports; the second labels it and a run of
    its own cut: on the label both give the linter is found, and against either reading each of
    its two findings matches."""
    _one_file_set(tmp_path)
    run = {"rule": "missing-comment", "why": "no comment", "certainty": "certain"}
    header = {"rule": "missing-header", "lines": [1], "why": "no author", "certainty": "certain"}
    first = {"t01": [{**run, "lines": [1, 3]}]}
    second = {"t01": [{**run, "lines": [2, 3]}, header]}
    for name, labels in (("first.json", first), ("second.json", second)):
        (tmp_path / name).write_text(json.dumps(labels))
    cmd = [sys.executable, str(REPO_ROOT / "tools" / "real_lint.py"), "score"]
    cmd += ["--labels", str(tmp_path / "first.json"), "--second", str(tmp_path / "second.json")]
    cmd += ["--manifest", str(tmp_path / "manifest.json"), "--texts", str(tmp_path / "texts")]
    cmd += ["--rules", "missing-header,missing-comment"]
    proc = subprocess.run(cmd, capture_output=True, text=True, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    rows = {line.split()[0]: line.split()[1:] for line in proc.stdout.splitlines() if line}
    assert rows["overall"][:5] == ["1", "2", "1", "1.00", "0.50"]
    assert (
        "against both readings: recall on the labels both give 1.00 (1/1), "
        "precision against either reading 1.00 (2/2)" in proc.stdout
    )


def test_populate_takes_a_json_export_s_image_tab(tmp_path):
    """A manifest entry with `"tab"` names a Shadertoy JSON export: populate writes that pass's
    code (one shader's export, or an account's, whose first shader it takes) as a .txt file."""
    image = "void mainImage(out vec4 c, in vec2 f) { c = vec4(1.0); }\n"
    one = {
        "info": {},
        "renderpass": [
            {"type": "buffer", "name": "Buffer A", "code": "x"},
            {"type": "image", "name": "Image", "code": image},
        ],
    }
    account = {"userName": "s", "shaders": [one]}
    repo = tmp_path / "mirrors" / "a+b" / "repo"
    subprocess.run(["git", "init", "-q", str(repo)], check=True)
    for name, data in (("one.json", one), ("all shaders.json", account)):
        (repo / name).write_text(json.dumps(data))
    subprocess.run(["git", "-C", str(repo), "add", "."], check=True)
    subprocess.run(
        ["git", "-C", str(repo), "-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qm", "t"],
        check=True,
    )
    commit = subprocess.run(
        ["git", "-C", str(repo), "rev-parse", "HEAD"], capture_output=True, text=True, check=True
    ).stdout.strip()
    entries = [
        {"id": "n1", "repo": "a/b", "commit": commit, "path": "one.json", "tab": "Image"},
        {"id": "n2", "repo": "a/b", "commit": commit, "path": "all shaders.json", "tab": "Image"},
        {"id": "n3", "repo": "a/b", "commit": commit, "path": "one.json", "tab": "Buffer A"},
    ]
    manifest = tmp_path / "m.json"
    manifest.write_text(json.dumps(entries))
    texts = tmp_path / "texts"
    assert real_lint.populate(tmp_path / "mirrors", False, manifest, texts) == 0
    assert (texts / "n1" / "one.txt").read_text() == image
    assert (texts / "n2" / "all shaders.txt").read_text() == image
    assert (texts / "n3" / "one.txt").read_text() == "x"
