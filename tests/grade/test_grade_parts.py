"""The pieces of grade on their own: choosing the shader of a submission, certain and possible
points, the outputs' shapes, the progress bar."""

from __future__ import annotations

import csv
import io
import json
import shutil

import pytest
from lab_class import FINAL

from glslcheck.verification.grade import (
    CSV_COLUMNS,
    Deduction,
    Grade,
    GradeProgress,
    Options,
    Submission,
    SubmissionError,
    from_paths,
    grade_class,
    submission_shader,
    table,
    to_csv,
    to_json,
)


def _two_shaders(tmp_path):
    for name in ("lab3", "lab4"):
        shutil.copytree(FINAL, tmp_path / "repo" / name)
    return tmp_path / "repo"


def test_several_shaders_need_a_path_and_the_path_chooses(tmp_path):
    repo = _two_shaders(tmp_path)
    with pytest.raises(
        SubmissionError, match=r"2 shaders in the submission .*roster's path column"
    ):
        submission_shader(str(repo))
    assert submission_shader(str(repo), "lab4").root.endswith("lab4")
    with pytest.raises(SubmissionError, match="lab5: no such file or folder in the submission"):
        submission_shader(str(repo), "lab5")


def test_a_text_file_without_main_image_is_not_the_shader(tmp_path):
    repo = tmp_path / "repo"
    shutil.copytree(FINAL, repo / "lab4")
    (repo / "notes.txt").write_text("Remember: comment every line.\n")
    assert submission_shader(str(repo)).root.endswith("lab4")


def _deduction(rule: str, certainty: str) -> Deduction:
    return Deduction(rule, "m", "Image.txt", 3, 1, 1, certainty, "code")


def test_certain_and_possible_points_are_apart_everywhere():
    sure = Grade("sure", "s", deductions=[_deduction("missing-comment", "certain")] * 2)
    maybe = Grade(
        "maybe",
        "m",
        deductions=[_deduction("missing-comment", "certain"), _deduction("branch", "possible")],
    )
    assert (maybe.certain_points, maybe.possible_points, maybe.points) == (1, 1, 2)
    # fewer certain points rank first, whatever the possible ones
    assert [g.team for g in sorted([sure, maybe], key=Grade.rank_key)] == ["maybe", "sure"]
    rows = {r["team"]: r for r in csv.DictReader(io.StringIO(to_csv([sure, maybe])))}
    assert list(rows["maybe"]) == list(CSV_COLUMNS)
    assert (rows["maybe"]["points_certain"], rows["maybe"]["points_possible"]) == ("-1", "-1")
    assert rows["maybe"]["deductions"] == "missing-comment -1; branch -1"
    doc = json.loads(to_json([sure, maybe], Options(), None))
    assert doc["teams"][0]["points"] == {"certain": -1, "possible": -1, "total": -2}
    text = table([sure, maybe], None)
    assert "-2 (1 possible)" in text and "Image.txt:3:1: -1 [branch] (possible) m" in text


def test_the_progress_bar_counts_the_submissions(tmp_path):
    stream = io.StringIO()
    bar = GradeProgress(2, stream=stream)
    paths = [str(FINAL), str(tmp_path / "missing")]
    grade_class(from_paths(paths), Options(size=(32, 18), times=(0.0,)), jobs=1, progress=bar)
    bar.finish()
    text = stream.getvalue()
    assert "grade [" in text and "2/2 missing" in text and text.endswith("\n")


def test_a_findings_certainty_is_read_from_its_fields():
    from types import SimpleNamespace

    from glslcheck.verification.grade.grading import certainty

    assert certainty(SimpleNamespace(rule="x")) == "certain"
    assert certainty(SimpleNamespace(certainty="possible")) == "possible"
    assert certainty(SimpleNamespace(certainty="certain")) == "certain"
    assert certainty(SimpleNamespace(certain=False)) == "possible"


def test_images_writes_every_render_and_diff_and_the_json_names_them(tmp_path, capsys):
    from glslcheck.cli.main import main

    out = tmp_path / "images"
    js = tmp_path / "g.json"
    paths = [str(FINAL), str(FINAL.parent / "06_multiple_lights")]
    args = ["grade", *paths, "--reference", str(FINAL), "--size", "48x27", "--times", "0,1"]
    assert main([*args, "--images", str(out), "--json", str(js), "--jobs", "1"]) == 0
    names = sorted(p.name for p in out.iterdir())
    assert names == sorted(
        [f"reference-t{i}.png" for i in (0, 1)]
        + [
            f"{team}-t{i}{kind}.png"
            for team in ("07_final", "06_multiple_lights")
            for i in (0, 1)
            for kind in ("", "-diff")
        ]
    )
    teams = json.loads(js.read_text())["teams"]
    assert all(set(t["images"]) == {"0:render", "0:diff", "1:render", "1:diff"} for t in teams)
    from glslcheck.base.images import load_image

    assert load_image(out / "07_final-t1.png").shape == (27, 48, 4)


def test_nan_pixels_and_a_flat_picture_are_render_problems(tmp_path):
    nan = tmp_path / "nan"
    nan.mkdir()
    (nan / "Image.glsl").write_text(
        "void mainImage(out vec4 fragColor, in vec2 fragCoord)\n{\n"
        "    vec2 uv = fragCoord / iResolution.xy;\n"
        "    fragColor = vec4(sqrt(uv.x - 0.5), uv.y, 0.25, 1.0);\n}\n"
    )
    flat = tmp_path / "flat"
    flat.mkdir()
    (flat / "Image.glsl").write_text(
        "void mainImage(out vec4 fragColor, in vec2 fragCoord)\n{\n"
        "    fragColor = vec4(0.2, 0.3, 0.4, 1.0);\n}\n"
    )
    animated = FINAL.parent / "bonus_animated_lights"
    options = Options(size=(64, 36), times=(0.0, 1.7))
    grades = grade_class(from_paths([str(nan), str(flat)]), options, animated, jobs=1)
    by = {g.team: g for g in grades}
    # left half NaN (x < 32 of 64, every row), counted from the renders themselves
    assert by["nan"].problems[0].startswith("NaN/Inf pixels: 1152 at iTime 0, 1152 at iTime 1.7")
    assert by["nan"].verdict == "different"
    assert by["flat"].problems == [
        "the image is one flat colour at every time rendered",
        "it does not animate (the reference does)",
    ]


class Crasher(Submission):
    """A submission whose grading kills the worker process (as a crash in a library would);
    in this process it is an ordinary submission."""

    @property
    def path(self):
        import multiprocessing
        import os

        if multiprocessing.parent_process() is not None:
            os._exit(3)
        return None

    @path.setter
    def path(self, value):
        pass


def test_a_worker_that_dies_costs_only_its_submission():
    subs = [
        Submission("before", str(FINAL)),
        Crasher("crasher", str(FINAL)),
        Submission("after", str(FINAL)),
    ]
    grades = grade_class(subs, Options(size=(32, 18), times=(0.0,)), jobs=2)
    assert [g.team for g in grades] == ["before", "crasher", "after"]
    assert [g.status for g in grades] == ["graded", "failed", "graded"]
    assert grades[1].reason.startswith("the process grading it died")
