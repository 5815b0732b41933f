"""Rule snapshots: each folder under fixtures/ is linted and its findings compared with the
folder's expected.json (`--update-snapshots` rewrites them); the registry's contract."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from glslcheck.lint import lint_paths
from glslcheck.lint.rules import RULE_TABLE, SECTIONS, STANDARDS, _load, all_rules, doc_sections

from .conftest import FIXTURES

FIXTURE_DIRS = sorted(p for p in FIXTURES.iterdir() if (p / "expected.json").is_file())


def _found(folder: Path, select: list[str]) -> list[dict]:
    result = lint_paths([folder], {"select": select})
    return [
        {
            "file": Path(f.path).resolve().relative_to(folder).as_posix(),
            "line": f.loc.line,
            "column": f.loc.column,
            "rule": f.rule,
            "message": f.message,
            "help": f.help,  # the suggested rewrite: what students read
            "certainty": f.certainty,  # certain or possible deduction (None: not a deduction)
        }
        for f in result.findings
    ]


@pytest.mark.parametrize("folder", FIXTURE_DIRS, ids=lambda p: p.name)
def test_rule_fixture_matches_snapshot(update_snapshots, folder: Path):
    expected_file = folder / "expected.json"
    expected = json.loads(expected_file.read_text(encoding="utf-8"))
    found = _found(folder, expected["select"])
    if update_snapshots:
        expected["findings"] = found
        expected_file.write_text(json.dumps(expected, indent=2) + "\n", encoding="utf-8")
    assert found == expected["findings"]


def test_every_rule_has_a_fixture():
    covered = {json.loads((d / "expected.json").read_text())["select"][0] for d in FIXTURE_DIRS}
    covered |= {d.name for d in FIXTURE_DIRS}
    assert {name for name, _ in RULE_TABLE} <= covered


@pytest.mark.parametrize("name", [n for n, _ in RULE_TABLE])
def test_rule_module_contract(name: str):
    rule = all_rules()[name]
    assert rule.name == rule.module.NAME == name
    assert re.fullmatch(r"[a-z]+(-[a-z]+)*", name)
    assert list(doc_sections(rule.doc)) == list(SECTIONS)
    assert all(doc_sections(rule.doc).values())
    assert (rule.severity, rule.penalty > 0) in (
        ("warning", True),
        ("note", False),
        ("error", False),
    )
    assert rule.needs in ("text", "ast", "suppressions")
    assert rule.summary.endswith(".")
    assert (rule.standard in STANDARDS) == (rule.penalty > 0)


def test_a_course_rule_without_its_standard_is_refused(monkeypatch):
    """The registry refuses a course rule that does not say which standard it deducts under:
    the scorer and the docs read it, and nothing else lists the efficiency rules."""
    mod = all_rules()["pow-small-exponent"].module
    monkeypatch.delattr(mod, "STANDARD")
    with pytest.raises(TypeError, match="STANDARD"):
        _load("pow-small-exponent", "pow_small_exponent")
    monkeypatch.setattr(mod, "STANDARD", "style", raising=False)
    with pytest.raises(TypeError, match="STANDARD"):
        _load("pow-small-exponent", "pow_small_exponent")


def test_has_credit_agrees_with_the_case_insensitive_pattern():
    """missing-credit's fast search (ASCII text lowercased, a case-sensitive pattern, faster than
    re.I) gives CREDIT_RE's answer: upper and mixed case, word boundaries, every alternative, and
    non-ASCII text (searched with CREDIT_RE itself: re.I folds the long s and the Kelvin sign)."""
    from glslcheck.lint.rules.missing_credit import _CREDIT, CREDIT_RE, has_credit

    words = [w for w in re.findall(r"[a-z]+", _CREDIT) if len(w) > 2] + [
        "https://x",
        "www.x",
        "Sources :",
    ]
    texts = [
        "",
        "nothing here",
        "STARTER code",
        "Based   On the lab",
        "basedon",
        "restarter",
        "starters",
        "Thanks to Dan",
        "thank  you",
        "Refs: none",
        "cite:",
        "cited :",
        "HTTP://A",
        "xwww.y",
        "WWW.Y",
        "\u017ftarter framework",
        "\u212aelvin",
        "credit\u00e9",
        "caf\u00e9 STARTER",
        "a\tsource:\tb",
        *words,
        *(w.upper() for w in words),
        *(w.title() for w in words),
        *(f"_{w}_" for w in words),
    ]
    assert any(has_credit(t) for t in texts) and not all(has_credit(t) for t in texts)
    for t in texts:
        assert has_credit(t) == bool(CREDIT_RE.search(t)), t
    assert has_credit("\u017ftarter") and not has_credit(
        "\u017ftarter".encode("ascii", "replace").decode()
    )
