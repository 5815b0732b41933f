"""Output formats: text, JSON (exact shape), SARIF 2.1.0 (structure GitHub code scanning needs,
checked by hand: the official schema is not available offline here), GitHub annotations."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from glslcheck.lint import lint_paths
from glslcheck.lint.engine import LintResult
from glslcheck.lint.report import artifact_uri, render, summary_line

from .conftest import BAD_SHADER, CLEAN_SHADER


@pytest.fixture
def linted(tmp_path, monkeypatch) -> LintResult:
    monkeypatch.chdir(tmp_path)
    Path("Buffer A.glsl").write_text(BAD_SHADER)
    Path("Image.glsl").write_text(CLEAN_SHADER)
    return lint_paths(["Buffer A.glsl", "Image.glsl"])


def test_text_format(linted):
    text = render(linted, "text")
    assert text.split("\n\n")[1].splitlines()[0] == (
        "Buffer A.glsl:1:1: missing-header the file opens with no header comment: no student is "
        "named at its top"
    )
    block = text.split("\n\n")[0].splitlines()
    assert block == [
        "Buffer A.glsl:1:1: missing-comment 2 lines of code without a comment that explains them "
        "(lines 1-3)",
        "    void mainImage(out vec4 fragColor, in vec2 fragCoord)",
        "    ^" + "~" * 52,
        "  help: add a comment above saying why these lines are there",
    ]
    assert text.endswith("\n3 findings in 2 files, estimated deduction: -2 points\n")


def test_text_summary_without_findings():
    assert summary_line(LintResult([], 2)) == "no findings in 2 files"
    assert summary_line(LintResult([], 1)) == "no findings in 1 file"


def test_json_format_exact_shape(linted):
    doc = json.loads(render(linted, "json"))
    assert set(doc) == {"findings", "summary"}
    assert doc["summary"] == {
        "files": 2,
        "findings": 3,
        "penalty": 2,
        "possible_findings": 0,
        "possible_penalty": 0,
    }
    keys = [
        "path",
        "line",
        "column",
        "end_line",
        "end_column",
        "rule",
        "severity",
        "penalty",
        "certainty",
        "message",
        "help",
        "notes",
        "fix",
    ]
    for f in doc["findings"]:
        assert list(f) == keys
    comment = next(f for f in doc["findings"] if f["rule"] == "missing-comment")
    assert comment == {
        "path": "Buffer A.glsl",
        "line": 1,
        "column": 1,
        "end_line": 1,
        "end_column": 54,
        "rule": "missing-comment",
        "severity": "warning",
        "penalty": 1,
        "certainty": "certain",
        "message": "2 lines of code without a comment that explains them (lines 1-3)",
        "help": "add a comment above saying why these lines are there",
        "notes": [],
        "fix": None,  # comments are never written for the student
    }
    credit = next(f for f in doc["findings"] if f["rule"] == "missing-credit")
    assert (credit["severity"], credit["penalty"], credit["certainty"]) == ("note", 0, None)


def _check_sarif(doc: dict) -> None:
    """The SARIF 2.1.0 structure: required properties and types per the OASIS standard's schema
    (sarifLog, run, tool/toolComponent, reportingDescriptor, result, location, region), plus
    what GitHub code scanning reads (driver.name, rules' ids, ruleId, message.text, a physical
    location with a relative uri and a startLine)."""
    assert doc["version"] == "2.1.0"
    assert isinstance(doc.get("$schema", ""), str)
    assert isinstance(doc["runs"], list) and doc["runs"]
    for run in doc["runs"]:
        driver = run["tool"]["driver"]
        assert isinstance(driver["name"], str) and driver["name"]
        ids = []
        for rule in driver.get("rules", []):
            assert isinstance(rule["id"], str) and rule["id"]
            ids.append(rule["id"])
            for key in ("shortDescription", "fullDescription", "help"):
                if key in rule:
                    assert isinstance(rule[key]["text"], str) and rule[key]["text"]
            level = rule.get("defaultConfiguration", {}).get("level", "warning")
            assert level in ("none", "note", "warning", "error")
        assert len(ids) == len(set(ids))
        assert run.get("columnKind", "unicodeCodePoints") in ("utf16CodeUnits", "unicodeCodePoints")
        for result in run["results"]:
            assert isinstance(result["message"]["text"], str) and result["message"]["text"]
            assert result["ruleId"] in ids
            if "ruleIndex" in result:
                assert driver["rules"][result["ruleIndex"]]["id"] == result["ruleId"]
            assert result["level"] in ("none", "note", "warning", "error")
            assert result["locations"]
            for loc in result["locations"]:
                phys = loc["physicalLocation"]
                uri = phys["artifactLocation"]["uri"]
                assert isinstance(uri, str) and not uri.startswith("/") and " " not in uri
                region = phys["region"]
                for key in ("startLine", "startColumn", "endLine", "endColumn"):
                    assert isinstance(region[key], int) and region[key] >= 1
                assert (region["endLine"], region["endColumn"]) >= (
                    region["startLine"],
                    region["startColumn"],
                )


def test_sarif_format(linted):
    doc = json.loads(render(linted, "sarif"))
    _check_sarif(doc)
    run = doc["runs"][0]
    assert run["tool"]["driver"]["name"] == "glslcheck"
    assert {r["ruleId"] for r in run["results"]} == {
        "missing-header",
        "missing-comment",
        "missing-credit",
    }
    uris = {
        r["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] for r in run["results"]
    }
    assert uris == {"Buffer%20A.glsl"}
    levels = {r["ruleId"]: r["level"] for r in run["results"]}
    assert levels["missing-comment"] == "warning" and levels["missing-credit"] == "note"


def test_sarif_without_findings(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    Path("Image.glsl").write_text(CLEAN_SHADER)
    doc = json.loads(render(lint_paths(["Image.glsl"]), "sarif"))
    _check_sarif(doc)
    assert doc["runs"][0]["results"] == []


def test_artifact_uri(tmp_path):
    (tmp_path / "lab 4").mkdir()
    assert (
        artifact_uri(str(tmp_path / "lab 4" / "Image.glsl"), str(tmp_path)) == "lab%204/Image.glsl"
    )
    assert artifact_uri("/elsewhere/x.glsl", str(tmp_path)) == "file:///elsewhere/x.glsl"


def test_github_format(linted):
    lines = render(linted, "github").splitlines()
    assert len(lines) == 3
    assert lines[0] == (
        "::warning file=Buffer A.glsl,line=1,col=1,endLine=1,endColumn=54,title=missing-comment::"
        "2 lines of code without a comment that explains them (lines 1-3)%0Ahelp: "
        "add a comment above saying why these lines are there"
    )
    assert lines[2].startswith("::notice file=Buffer A.glsl,line=1,col=1,")
    for line in lines:
        assert re.fullmatch(r"::(warning|notice) [^:]*::[^\n]*", line)


def test_github_escapes_properties(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    Path("a,b:c.glsl").write_text(BAD_SHADER)
    out = render(lint_paths(["a,b:c.glsl"]), "github")
    assert "file=a%2Cb%3Ac.glsl," in out


# A student named (a certain deduction avoided) but no file name, purpose or roles: a possible
# deduction (incomplete-header), beside a certain one (missing-comment on the uncommented body).
POSSIBLE_SHADER = """\
// Modified by Ana Ruiz

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(1.0);
}
"""


@pytest.fixture
def possible(tmp_path, monkeypatch) -> LintResult:
    monkeypatch.chdir(tmp_path)
    Path("Image.glsl").write_text(POSSIBLE_SHADER)
    return lint_paths(["Image.glsl"], {"select": ["incomplete-header", "missing-comment"]})


def test_certain_and_possible_apart_in_text(possible):
    text = render(possible, "text")
    assert "Image.glsl:1:1: incomplete-header [possible] the header names its author" in text
    assert "missing-comment [possible]" not in text
    assert text.endswith(
        "\n2 findings in 1 file, estimated deduction: -1 point, and -1 point more possible "
        "(1 possible deduction: a reading of an ambiguous rubric sentence, marked [possible])\n"
    )


def test_certain_and_possible_apart_in_json_sarif_and_github(possible):
    doc = json.loads(render(possible, "json"))
    assert {f["rule"]: f["certainty"] for f in doc["findings"]} == {
        "incomplete-header": "possible",
        "missing-comment": "certain",
    }
    assert doc["summary"] == {
        "files": 1,
        "findings": 2,
        "penalty": 1,
        "possible_findings": 1,
        "possible_penalty": 1,
    }
    sarif = json.loads(render(possible, "sarif"))
    _check_sarif(sarif)
    results = {r["ruleId"]: r for r in sarif["runs"][0]["results"]}
    assert results["incomplete-header"]["level"] == "note"
    assert results["incomplete-header"]["properties"] == {"penalty": 1, "certainty": "possible"}
    assert results["missing-comment"]["level"] == "warning"
    rules = {r["id"]: r for r in sarif["runs"][0]["tool"]["driver"]["rules"]}
    assert rules["incomplete-header"]["defaultConfiguration"]["level"] == "note"
    github = render(possible, "github").splitlines()
    assert [line.split(" ", 1)[0] for line in github] == ["::notice", "::warning"]
