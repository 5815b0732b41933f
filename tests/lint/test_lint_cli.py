"""`glslcheck lint` and `glslcheck rule` from the command line: exit codes, config discovery,
overrides, errors without tracebacks, files never modified, docs/rules.md up to date."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from glslcheck.cli.main import main
from glslcheck.lint import lint_paths
from glslcheck.lint.rules import RULE_TABLE

from .conftest import BAD_SHADER, CLEAN_SHADER, FIXTURES, REPO_ROOT, snapshot


def glslcheck(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "glslcheck", *args], cwd=cwd, capture_output=True, text=True
    )


@pytest.fixture
def workdir(tmp_path, monkeypatch) -> Path:
    monkeypatch.chdir(tmp_path)
    return tmp_path


# --- exit codes ---------------------------------------------------------------------------


def test_exit_0_without_findings(workdir, capsys):
    (workdir / "Image.glsl").write_text(CLEAN_SHADER)
    assert main(["lint", "Image.glsl"]) == 0
    assert capsys.readouterr().out == "no findings in 1 file\n"


def test_exit_1_with_findings(workdir, capsys):
    (workdir / "Image.glsl").write_text(BAD_SHADER)
    assert main(["lint", "Image.glsl"]) == 1
    assert "estimated deduction: -2 points" in capsys.readouterr().out


def test_missing_file_exit_2_without_traceback(workdir):
    proc = glslcheck("lint", "nope.glsl", cwd=workdir)
    assert proc.returncode == 2
    assert "nope.glsl" in proc.stderr and "Traceback" not in proc.stderr
    assert proc.stdout == ""


def test_unknown_rule_in_select_exit_2(workdir):
    (workdir / "Image.glsl").write_text(CLEAN_SHADER)
    proc = glslcheck(
        "lint", "Image.glsl", "--select", "missing-comment,length-comparisn", cwd=workdir
    )
    assert proc.returncode == 2
    assert "--select names unknown rule(s) length-comparisn" in proc.stderr
    assert "Traceback" not in proc.stderr


def test_bad_format_is_usage_error(workdir):
    (workdir / "Image.glsl").write_text(CLEAN_SHADER)
    proc = glslcheck("lint", "Image.glsl", "--format", "xml", cwd=workdir)
    assert proc.returncode == 2 and "Traceback" not in proc.stderr


def test_not_utf8_exit_2(workdir):
    (workdir / "Image.glsl").write_bytes(b"// caf\xe9\n")
    assert glslcheck("lint", "Image.glsl", cwd=workdir).returncode == 2


def test_output_file(workdir, capsys):
    (workdir / "Image.glsl").write_text(BAD_SHADER)
    assert main(["lint", "Image.glsl", "--format", "json", "--output", "report.json"]) == 1
    assert capsys.readouterr().out == ""
    assert json.loads((workdir / "report.json").read_text())["summary"]["findings"] == 3


def test_output_never_overwrites_a_linted_file(workdir):
    (workdir / "Image.glsl").write_text(BAD_SHADER)
    proc = glslcheck("lint", "Image.glsl", "--output", "Image.glsl", cwd=workdir)
    assert proc.returncode == 2
    assert (workdir / "Image.glsl").read_text() == BAD_SHADER


def test_folder_and_duplicate_paths(workdir):
    lab = workdir / "lab4"
    lab.mkdir()
    (lab / "Image.glsl").write_text(CLEAN_SHADER)
    (lab / "Common.glsl").write_text(BAD_SHADER)
    result = lint_paths([lab, lab / "Image.glsl"])
    assert result.files == 2
    # Common's mainImage comes first in the Image pass: Image's own is a redefinition, which
    # Shadertoy rejects too; that compile error is Image's only finding
    assert {Path(f.path).name for f in result.findings if f.rule != "compile-error"} == {
        "Common.glsl"
    }
    assert [(Path(f.path).name, f.severity) for f in result.findings if f.rule == "compile-error"][
        :1
    ] == [("Image.glsl", "error")]


def test_named_image_file_lints_only_that_file(workdir):
    (workdir / "Image.glsl").write_text(CLEAN_SHADER)
    (workdir / "Common.glsl").write_text(BAD_SHADER)  # loaded as context, not linted
    assert lint_paths(["Image.glsl"]).files == 1


def test_skip_non_shaders(workdir, capsys):
    (workdir / "README.md").write_text("# notes\n")
    (workdir / "notes.txt").write_text("plain notes\n")
    (workdir / "Image.txt").write_text(CLEAN_SHADER)
    assert main(["lint", "--skip-non-shaders", "README.md", "notes.txt", "Image.txt"]) == 0
    assert capsys.readouterr().out == "no findings in 1 file\n"


def test_lint_folder_takes_txt_tab_files_by_their_text(workdir, capsys):
    (workdir / "Lab4").mkdir()
    (workdir / "Lab4" / "Lab4.txt").write_text(BAD_SHADER)
    (workdir / "notes.txt").write_text("We split the work: Ana the spheres, Ben the lights.\n")
    assert main(["lint", "."]) == 1
    out = capsys.readouterr().out
    assert "Lab4/Lab4.txt:1:1: missing-header" in out and "notes.txt" not in out


def test_lint_of_no_shader_file_is_no_clean_bill(workdir, capsys):
    (workdir / "notes.txt").write_text("plain notes\n")
    assert main(["lint", "--skip-non-shaders", "notes.txt"]) == 0
    captured = capsys.readouterr()
    assert captured.out == "no shader files linted (0 files): nothing was checked\n"
    assert "1 file given left out as not shader files: notes.txt" in captured.err


# --- lint never modifies files -----------------------------------------------------------


def test_lint_modifies_no_file(workdir):
    shaders = sorted(p for p in FIXTURES.rglob("*") if p.is_file())
    before = snapshot(shaders)
    for fmt in ("text", "json", "sarif", "github"):
        proc = glslcheck("lint", str(FIXTURES), "--format", fmt, cwd=workdir)
        assert proc.returncode == 1, proc.stderr
    assert snapshot(shaders) == before


# --- configuration ------------------------------------------------------------------------


def _rules_found(path: str | Path, **overrides) -> set[str]:
    return {f.rule for f in lint_paths([path], overrides).findings}


def test_pyproject_in_parent_folder(workdir):
    (workdir / "pyproject.toml").write_text('[tool.glslcheck]\nignore = ["missing-comment"]\n')
    (workdir / "lab" / "part1").mkdir(parents=True)
    shader = workdir / "lab" / "part1" / "Image.glsl"
    shader.write_text(BAD_SHADER)
    assert _rules_found(shader) == {"missing-header", "missing-credit"}


def test_pyproject_without_table_is_skipped(workdir):
    (workdir / "pyproject.toml").write_text('[tool.glslcheck]\nselect = ["missing-header"]\n')
    (workdir / "lab").mkdir()
    (workdir / "lab" / "pyproject.toml").write_text('[project]\nname = "x"\n')
    (workdir / "lab" / "Image.glsl").write_text(BAD_SHADER)
    assert _rules_found(workdir / "lab" / "Image.glsl") == {"missing-header"}


def test_glslcheck_toml(workdir):
    (workdir / "glslcheck.toml").write_text('select = ["missing-comment"]\ncomment-span = 1\n')
    (workdir / "Image.glsl").write_text(
        "// two lines, one covered\nfloat a = 1.0;\nfloat b = 2.0;\n"
    )
    findings = lint_paths(["Image.glsl"]).findings
    assert [(f.rule, f.loc.line) for f in findings] == [("missing-comment", 3)]


def test_glslcheck_toml_wins_over_pyproject_in_same_folder(workdir):
    (workdir / "glslcheck.toml").write_text('select = ["missing-credit"]\n')
    (workdir / "pyproject.toml").write_text('[tool.glslcheck]\nselect = ["missing-header"]\n')
    (workdir / "Image.glsl").write_text(BAD_SHADER)
    assert _rules_found("Image.glsl") == {"missing-credit"}


def test_config_from_cwd_when_none_above_the_file(tmp_path, monkeypatch):
    cwd, elsewhere = tmp_path / "cwd", tmp_path / "elsewhere"
    cwd.mkdir()
    elsewhere.mkdir()
    (cwd / "glslcheck.toml").write_text('select = ["missing-credit"]\n')
    (elsewhere / "Image.glsl").write_text(BAD_SHADER)
    monkeypatch.chdir(cwd)
    assert _rules_found(elsewhere / "Image.glsl") == {"missing-credit"}


def test_folders_without_configuration_are_read_once(tmp_path, monkeypatch):
    """The files of a folder with no configuration above it do not each read every parent's
    pyproject.toml again (a lab of 34 files read this repository's 34 times)."""
    from glslcheck.lint import config

    lab = tmp_path / "lab"
    for name in ("a", "b"):
        (lab / name).mkdir(parents=True)
    (tmp_path / "pyproject.toml").write_text('[project]\nname = "not-glslcheck-settings"\n')
    reads = []
    monkeypatch.setattr(
        config, "_read_toml", lambda path, read=config._read_toml: reads.append(path) or read(path)
    )
    monkeypatch.chdir(tmp_path)
    finder = config.ConfigFinder({}, frozenset())
    found = [
        finder.for_file(lab / name / tab)
        for name in ("a", "b")
        for tab in ("Image.glsl", "Common.glsl")
    ]
    assert found == [config.LintConfig()] * 4
    assert reads == [
        str(tmp_path / "pyproject.toml")
    ]  # the folders are strings: no pathlib (start-up time)


def test_cli_overrides_config(workdir, capsys):
    (workdir / "glslcheck.toml").write_text(
        'select = ["missing-credit"]\nignore = ["missing-header"]\n'
    )
    (workdir / "Image.glsl").write_text(BAD_SHADER)
    assert (
        main(
            ["lint", "Image.glsl", "--select", "missing-header,missing-comment", "--format", "json"]
        )
        == 1
    )
    found = {f["rule"] for f in json.loads(capsys.readouterr().out)["findings"]}
    assert found == {"missing-comment"}  # --select replaced select; the file's ignore still holds
    assert (
        main(
            ["lint", "Image.glsl", "--select", "missing-header", "--ignore", "", "--format", "json"]
        )
        == 1
    )
    found = {f["rule"] for f in json.loads(capsys.readouterr().out)["findings"]}
    assert found == {"missing-header"}


@pytest.mark.parametrize(
    "config, message",
    [
        ('select = "missing-comment"\n', "`select` must be a list of rule names"),
        ('ignore = ["no-such-rule"]\n', "`ignore` names unknown rule(s) no-such-rule"),
        ("comment-span = 0\n", "`comment-span` must be a positive integer"),
        ('colour = "red"\n', "unknown setting `colour`"),
        ("select = [\n", "not valid TOML"),
    ],
)
def test_bad_config_exit_2_names_the_file(workdir, config, message):
    (workdir / "glslcheck.toml").write_text(config)
    (workdir / "Image.glsl").write_text(CLEAN_SHADER)
    proc = glslcheck("lint", "Image.glsl", cwd=workdir)
    assert proc.returncode == 2
    assert str(workdir / "glslcheck.toml") in proc.stderr
    assert message in proc.stderr and "Traceback" not in proc.stderr


def test_bad_pyproject_table_names_the_table(workdir):
    (workdir / "pyproject.toml").write_text("[tool.glslcheck]\ncomment-span = true\n")
    (workdir / "Image.glsl").write_text(CLEAN_SHADER)
    proc = glslcheck("lint", "Image.glsl", cwd=workdir)
    assert proc.returncode == 2
    assert f"{workdir / 'pyproject.toml'} [tool.glslcheck]: error: `comment-span`" in proc.stderr


# --- glslcheck rule and the generated docs ------------------------------------------------


def test_rule_prints_docs(capsys):
    assert main(["rule", "missing-comment"]) == 0
    out = capsys.readouterr().out
    assert out.startswith(
        "missing-comment: Code that no comment explains, as a TA reads the comments.\n"
    )
    for section in ("## What it does", "## Why is this bad?", "## Example", "## Use instead"):
        assert section in out


def test_rule_all_lists_every_rule(capsys):
    assert main(["rule", "--all"]) == 0
    out = capsys.readouterr().out
    for name, _ in RULE_TABLE:
        assert name in out


def test_rule_unknown_exit_2():
    proc = glslcheck("rule", "missing-coment")
    assert proc.returncode == 2 and "did you mean `missing-comment`" in proc.stderr


def test_rules_doc_is_up_to_date():
    proc = subprocess.run(
        [sys.executable, str(REPO_ROOT / "tools" / "gen_rules_doc.py"), "--check"],
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 0, proc.stderr


def test_tab_patterns_make_more_files_shaders(workdir, capsys):
    (workdir / "glslcheck.toml").write_text('tab-patterns = ["lab4/*.txt"]\n')
    (workdir / "lab4").mkdir()
    (workdir / "lab4" / "part1.txt").write_text(BAD_SHADER)
    (workdir / "notes.txt").write_text("plain notes\n")
    assert (
        main(["lint", "--skip-non-shaders", "--format", "json", "lab4/part1.txt", "notes.txt"]) == 1
    )
    report = json.loads(capsys.readouterr().out)
    assert report["summary"]["files"] == 1
    assert {f["path"] for f in report["findings"]} == {"lab4/part1.txt"}
