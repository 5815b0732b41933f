"""`glslcheck grade` over the small class of tests/grade/conftest.py, as a TA would read it:
the correct solutions first, the one with a deduction after them, the lighting bug "different",
the ones that cannot be graded last with the reason; every expected deduction is the linter's
own finding on the same files, not a number typed here."""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path

import pytest
from lab_class import BRANCH, FINAL

from glslcheck.cli.main import main
from glslcheck.lint import lint_paths
from glslcheck.verification.grade import (
    CLOSE,
    DIFFERENT,
    SAME,
    Options,
    grade_class,
    read_roster,
)
from glslcheck.verification.grade.submissions import Checkout

# Small frames keep the class quick; the lighting bug's PSNR (19 dB at 320x180) and the
# correct parts' match do not depend on the size.
SIZE = (96, 54)
TIMES = (0.0, 1.7)


@pytest.fixture(scope="module")
def graded(lab_class):
    submissions = read_roster(lab_class["roster"])
    grades = grade_class(submissions, Options(size=SIZE, times=TIMES), reference=FINAL, jobs=2)
    return {g.team: g for g in grades}, submissions


def _penalty_findings(files: list[str]) -> list[tuple[str, int, str]]:
    """What the linter itself deducts on those files: (file name, line, rule)."""
    return sorted(
        (Path(f.loc.path).name, f.loc.line, f.rule)
        for f in lint_paths(files).findings
        if f.penalty > 0
    )


def test_correct_solutions_are_the_same_picture_with_no_deduction(graded):
    grades, _ = graded
    for team in ("correct-a", "correct-b"):
        g = grades[team]
        assert g.status == "graded" and g.compiles, g.reason
        assert g.verdict == SAME and [f.verdict for f in g.frames] == [SAME, SAME]
        assert g.deductions == [] and g.problems == []
    assert grades["correct-a"].tabs == ["Common.txt", "Image.txt"]
    # the README.txt beside lab4/ is no shader: the folder with the tabs is chosen
    assert grades["correct-b"].tabs == ["lab4/Common.txt", "lab4/Image.txt"]


def test_the_lighting_bug_is_a_different_picture(graded):
    g = graded[0]["lighting-bug"]
    assert g.status == "graded" and g.verdict == DIFFERENT
    assert all(f.psnr_db < 30 for f in g.frames)  # closeness.CLOSE_PSNR_DB
    assert g.deductions == []  # the code is as clean as the reference's: only the picture tells


def test_uniform_read_in_a_helper_is_deducted_where_it_is(graded, lab_class):
    g = graded[0]["uniforms-in-helper"]
    assert g.status == "graded" and g.verdict in (SAME, CLOSE)
    with Checkout(read_roster(lab_class["roster"])[3]) as checkout:
        root = Path(checkout.root)
        expected = _penalty_findings([str(root / "Image.txt"), str(root / "Common.txt")])
        image = (root / "Image.txt").read_text().split("\n")
    assert sorted((d.file, d.line, d.rule) for d in g.deductions) == expected
    uniform = [d for d in g.deductions if d.rule == "uniform-outside-mainimage"]
    assert len(uniform) == 1 and "iResolution" in image[uniform[0].line - 1]
    assert uniform[0].code == image[uniform[0].line - 1] and uniform[0].penalty == 1
    assert g.points == len(g.deductions)


def test_a_shader_that_does_not_compile_gets_its_error_and_its_deductions(graded, lab_class):
    g = graded[0]["no-compile"]
    assert g.status == "failed" and g.compiles is False and g.frames == []
    (error,) = g.errors
    with Checkout(read_roster(lab_class["roster"])[4]) as checkout:
        lines = (Path(checkout.root) / "Image.txt").read_text().split("\n")
    assert error.file == "Image.txt" and "calcRay(viewport)" in "\n".join(
        lines[error.line - 2 : error.line]
    )
    assert g.reason.startswith(f"does not compile: Image.txt:{error.line}:{error.column}: ")


def test_a_missing_branch_is_named_with_the_branches_there_are(graded):
    g = graded[0]["missing-branch"]
    assert g.status == "failed" and g.tabs == [] and g.frames == []
    # named as the roster names it, not as the clone's path
    assert g.reason == f"repos/missing-branch: no branch '{BRANCH}' (branches: main)"


def test_the_class_is_ranked_as_a_ta_would(graded):
    grades, submissions = graded
    order = [g.team for g in sorted(grades.values(), key=lambda g: g.rank_key())]
    assert set(order[:2]) == {"correct-a", "correct-b"}
    assert order[2:4] == ["uniforms-in-helper", "lighting-bug"]
    assert set(order[4:]) == {"no-compile", "missing-branch"}
    assert [s.contributors for s in submissions][0] == ["Ada correct-a", "Bo correct-a"]


def test_the_command_writes_table_csv_json_and_page(lab_class, tmp_path, capsys):
    out = {k: tmp_path / f"grades.{k}" for k in ("csv", "json", "html")}
    out["html"].write_text("the old page\n")
    code = main(
        [
            "grade",
            "--roster",
            str(lab_class["roster"]),
            "--reference",
            str(FINAL),
            "--size",
            "96x54",
            "--times",
            "0,1.7",
            "--csv",
            str(out["csv"]),
            "--json",
            str(out["json"]),
            "-o",
            str(out["html"]),
        ]
    )
    assert code == 1  # two submissions could not be graded
    captured = capsys.readouterr()
    assert "grade [" not in captured.err  # no progress bar when stderr is not a terminal
    table = captured.out.split("\n\n")[0].split("\n")
    assert table[0].split()[:4] == ["#", "team", "status", "verdict"]
    assert {line.split()[1] for line in table[1:3]} == {"correct-a", "correct-b"}
    assert [line.split()[1] for line in table[3:5]] == ["uniforms-in-helper", "lighting-bug"]
    rows = list(csv.DictReader(io.StringIO(out["csv"].read_text())))
    by_team = {r["team"]: r for r in rows}
    assert [r["rank"] for r in rows] == [str(i) for i in range(1, 7)]
    assert by_team["lighting-bug"]["verdict"] == DIFFERENT
    assert by_team["missing-branch"]["status"] == "failed" and by_team["missing-branch"]["reason"]
    doc = json.loads(out["json"].read_text())
    assert doc["schema"] == 1 and doc["times"] == [0.0, 1.7] and len(doc["teams"]) == 6
    helper = next(t for t in doc["teams"] if t["team"] == "uniforms-in-helper")
    assert helper["points"]["total"] == -len(helper["deductions"]) < 0
    assert {"file", "line", "column", "rule", "penalty", "certainty", "code"} <= set(
        helper["deductions"][0]
    )
    # the default CPU program, whose first frame is always the NumPy backend's
    assert doc["backend"] == "auto" and helper["frames"][0]["engine"] == "numpy"
    assert {f["engine"] for f in helper["frames"]} <= {"numpy", "compiled pixel", "compiled lanes8"}
    page = out["html"].read_text()
    assert page.startswith("<!DOCTYPE html>") and page.count('<tr id="team-') == 6


def test_a_reference_that_does_not_render_leaves_the_old_outputs(tmp_path, capsys):
    broken = tmp_path / "ref"
    broken.mkdir()
    (broken / "Image.glsl").write_text("void mainImage(out vec4 c, in vec2 p) { c = vec4(p) }\n")
    page = tmp_path / "grades.html"
    page.write_text("the old page\n")
    code = main(["grade", str(FINAL), "--reference", str(broken), "-o", str(page)])
    assert code == 2 and page.read_text() == "the old page\n"
    assert "the reference does not render" in capsys.readouterr().err


def test_folders_files_and_bad_submissions_each_get_a_row(tmp_path):
    from glslcheck.verification.grade import from_paths

    binary = tmp_path / "binary"
    binary.mkdir()
    (binary / "Image.txt").write_bytes(b"\x89PNG\r\n\x1a\n\x00\xff")
    no_image = tmp_path / "no-image"
    no_image.mkdir()
    (no_image / "Common.txt").write_text((FINAL / "Common.glsl").read_text())
    empty = tmp_path / "empty"
    empty.mkdir()
    paths = [
        str(FINAL / "Image.glsl"),
        str(binary),
        str(no_image),
        str(empty),
        str(tmp_path / "gone"),
    ]
    grades = grade_class(from_paths(paths), Options(size=SIZE, times=(0.0,)), jobs=1)
    by = {g.team: g for g in grades}
    assert by["Image.glsl"].status == "graded" and by["Image.glsl"].verdict is None
    assert [len(f.thumbnail) > 0 for f in by["Image.glsl"].frames] == [True]
    assert by["binary"].status == "failed" and "not UTF-8 text" in by["binary"].reason
    assert by["no-image"].status == "failed" and by["no-image"].reason.startswith("no Image tab")
    assert by["empty"].status == "failed" and "empty" in by["empty"].reason
    assert by["gone"].status == "failed" and "no such file" in by["gone"].reason


def test_a_render_over_the_frame_budget_is_a_row_with_the_loop(tmp_path, capsys):
    slow = tmp_path / "slow"
    slow.mkdir()
    # 90,000 passes per pixel: seconds on any CPU, far over a 0.05 s budget
    (slow / "Image.glsl").write_text(
        "void mainImage(out vec4 fragColor, in vec2 fragCoord)\n{\n    float x = fragCoord.x;\n"
        "    for (int i = 0; i < 90000; i++) { x = fract(x * 1.0001 + 0.1); }\n"
        "    fragColor = vec4(x);\n}\n"
    )
    code = main(
        [
            "grade",
            str(slow),
            str(FINAL),
            "--size",
            "96x54",
            "--times",
            "0",
            "--frame-budget",
            "0.05",
        ]
    )
    out = capsys.readouterr().out
    assert code == 1
    row = next(line for line in out.split("\n") if " slow " in line)
    assert "failed" in row and "render at iTime 0 failed: " in row
    assert f"{slow}/Image.glsl:4:" in row and "still rendering after 0.05 s" in row
    assert next(line for line in out.split("\n") if " 07_final " in line).split()[2] == "graded"


def test_a_bad_roster_is_named_at_its_line_and_column(tmp_path, capsys):
    roster = tmp_path / "roster.csv"
    roster.write_text("team,repo,branch\na,repos/a,lab4-main\nb,,lab4-main\n")
    assert main(["grade", "--roster", str(roster)]) == 2
    assert f"{roster}:3:2: error: the repo cell is empty" in capsys.readouterr().err
    roster.write_text("team,contributors,repository\n")
    assert main(["grade", "--roster", str(roster)]) == 2
    assert "the roster's header has no repo, branch column" in capsys.readouterr().err
    roster.write_text("team,repo,branch\na,x,b\na,y,b\n")
    assert main(["grade", "--roster", str(roster)]) == 2
    assert f"{roster}:3:1: error: team 'a' is on line 2 too" in capsys.readouterr().err
