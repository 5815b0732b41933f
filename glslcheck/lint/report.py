"""Reporting lint findings: a `LintResult` in, text for a person or a tool out.

Detection is the engine's job; this module only formats. Formats (`FORMATS`):

    text    `path:line:col: rule-name message` (`rule-name [possible]` for a possible
            deduction), the source line with `^~~~` under the span, a `help:` line, a
            `fix (safe|unsafe): ...` line when the rule offers a fix, how many findings have a
            fix and the command that applies them, and a closing summary with the estimated
            deduction, the certain and the possible apart
    json    {"findings": [{path, line, column, end_line, end_column, rule, severity, penalty,
            certainty, message, help, notes: [{line, column, message}], fix: null or {title,
            applicability, why, edits: [{line, column, end_line, end_column, text, item}]}}],
            "summary": {files, findings, penalty, possible_findings, possible_penalty}}
    sarif   SARIF 2.1.0 for GitHub code scanning (one run; every rule in tool.driver.rules); a
            certain deduction is level "warning", a possible one "note", and each result's
            properties hold its penalty and certainty; a finding's fix is the result's `fixes`
    github  GitHub Actions workflow commands (`::warning file=...::message`; `::notice` for a
            possible deduction)

Certainty: a deduction (penalty > 0) is "certain" when the rubric's text makes it one, and
"possible" when it rests on a reading of an ambiguous rubric sentence (a TA may deduct it or
not); other findings (compile errors, notes) have none (JSON null). `penalty` counts the
certain deductions' points, `possible_penalty` those a TA may add.

Lines and columns are 1-based and point into the user's file; an end column is the column just
past the span's last character. A file name's bytes that are not UTF-8 (kept by Python as lone
surrogates) are written as `\\udcXX` text in every format, as the text format shows them, and as
percent-escapes of the original bytes in a SARIF URI: every report is valid UTF-8.
"""

from __future__ import annotations

import os

from ..base.diagnostics import format_text, printable
from ..shadertoy.sources import posix_path
from .engine import NOT_RUN_HELP, Finding, LintResult
from .rules import all_rules

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import Any

    from .fixes import Fix

SARIF_SCHEMA = "https://json.schemastore.org/sarif-2.1.0.json"
SARIF_VERSION = "2.1.0"


def _no_surrogates(text: str, backslash: str = "\\") -> str:
    """`text` with each lone surrogate (an undecodable byte of a file name) written as `\\udcXX`,
    its backslash spelt `backslash` (two of them inside a JSON string)."""
    try:
        text.encode("utf-8")  # lone surrogates are all UTF-8 cannot encode
        return text
    except UnicodeEncodeError:
        pass
    return "".join(
        f"{backslash}u{ord(ch):04x}" if "\ud800" <= ch <= "\udfff" else ch for ch in text
    )


def _json_text(doc) -> str:
    """`doc` as indented JSON that is valid UTF-8: a lone surrogate can only sit inside a JSON
    string, where `\\\\udcXX` reads back as the text `\\udcXX`."""
    import json  # only for --format json and sarif: a text lint need not pay for importing it

    return _no_surrogates(json.dumps(doc, indent=2, ensure_ascii=False), "\\\\") + "\n"


def _plural(n: int, word: str) -> str:
    return f"{n} {word}{'' if n == 1 else 's'}"


def summary_line(result: LintResult) -> str:
    files = _plural(result.files, "file")
    if not result.files:  # never a clean bill: nothing was read
        return "no shader files linted (0 files): nothing was checked"
    if not result.findings:
        return f"no findings in {files}"
    points = result.penalty
    deduction = f"-{_plural(points, 'point')}" if points else "0 points"
    line = (
        f"{_plural(len(result.findings), 'finding')} in {files}, estimated deduction: {deduction}"
    )
    possible = sum(1 for f in result.findings if f.certainty == "possible")
    if possible:
        line += (
            f", and -{_plural(result.possible_penalty, 'point')} more possible "
            f"({_plural(possible, 'possible deduction')}: a reading of an ambiguous rubric "
            "sentence, marked [possible])"
        )
    errors = sum(1 for f in result.findings if f.severity == "error")
    if errors:
        # (a reserved word used as a name is an error that leaves every rule running)
        partial = any(f.help == NOT_RUN_HELP for f in result.findings)
        line += (
            f" ({_plural(errors, 'compile error')}, not counted: they are not coding-standard "
            "deductions" + (", and the code they are in was not fully linted)" if partial else ")")
        )
    return line


def format_finding(f: Finding) -> str:
    """One finding as text: the compiler-style block of `diagnostics.format_text`, with the rule
    name in place of the severity and no colon after it."""
    block = format_text(f, show_rule=True)
    head = f"{printable(str(f.loc))}: {f.rule}: " if f.loc else f"{f.rule}: "
    mark = " [possible]" if f.certainty == "possible" else ""
    if block.startswith(head):
        block = head[:-2] + mark + " " + block[len(head) :]
    return block


def text_report(result: LintResult, fix_command: str = "glslcheck lint --fix") -> str:
    blocks: list[str] = []
    not_run: list[Finding] = []  # a run of "rule could not run" notes: one block, folded

    def flush() -> None:
        if not_run:
            blocks.append(_not_run_block(not_run))
            not_run.clear()

    for f in result.findings:
        if f.rule == "compile-error" and f.severity == "note":
            not_run.append(f)
            continue
        flush()
        block = format_finding(f)
        if f.fix is not None:
            block += f"\n  fix ({f.fix.applicability}): {printable(f.fix.title)}"
        blocks.append(block)
    flush()
    fixable = fixes_line(result, fix_command)
    if fixable:
        blocks.append(fixable)
    blocks.append(summary_line(result))
    return "\n\n".join(blocks) + "\n"


def fixes_line(result: LintResult, command: str = "glslcheck lint --fix") -> str:
    """How many findings have a fix and which command applies them ("" when none has)."""
    safe = sum(1 for f in result.findings if f.fix is not None and f.fix.applicability == "safe")
    unsafe = sum(1 for f in result.findings if f.fix is not None and f.fix.applicability != "safe")
    if not safe and not unsafe:
        return ""
    parts = []
    if safe:
        parts.append(
            f"{_plural(safe, 'finding')} with a safe fix: `{command}` applies each one it proves "
            "by rendering the shader before and after (`--diff` shows them first)"
        )
    if unsafe:
        parts.append(
            f"{_plural(unsafe, 'finding')} with an unsafe fix (applied with `--unsafe-fixes` too)"
        )
    return "; ".join(parts)


def _not_run_block(notes: list[Finding]) -> str:
    """The rules that could not run, one line per place and reason (the JSON keeps one record
    per rule): `Image.glsl:2:1: compile-error 11 rules could not run in 'mainImage' (line 2): it
    does not compile (uniform-outside-mainimage, length-comparison, ...)`."""
    groups: dict[tuple[str, str], list[str]] = {}
    for f in notes:
        rule, sep, rest = f.message.partition(" could not run ")
        key = (printable(str(f.loc)), printable(rest if sep else f.message))
        groups.setdefault(key, []).append(rule if sep else "")
    lines = []
    for (loc, rest), rules in groups.items():
        if len(rules) == 1 and rules[0]:
            lines.append(f"{loc}: compile-error {rules[0]} could not run {rest}")
        elif all(rules):
            lines.append(
                f"{loc}: compile-error {len(rules)} rules could not run {rest} ({', '.join(rules)})"
            )
        else:
            lines.extend(f"{loc}: compile-error {rest}" for _ in rules)
    return "\n".join(lines)


def finding_record(f: Finding) -> dict:
    loc = f.loc
    return {
        "path": f.path,
        "line": loc.line if loc else 1,
        "column": loc.column if loc else 1,
        "end_line": (loc.end_line or loc.line) if loc else 1,
        "end_column": (loc.end_column or loc.column + 1) if loc else 2,
        "rule": f.rule,
        "severity": f.severity,
        "penalty": f.penalty,
        "certainty": f.certainty,
        "message": f.message,
        "help": f.help,
        # the other places a finding is about (every evaluation of a repeated value)
        "notes": [
            {"line": n.loc.line, "column": n.loc.column, "message": n.message}
            for n in f.notes
            if n.loc is not None
        ],
        # the rewrite the rule offers (edits of the file; applied by `lint --fix` once proven)
        "fix": None
        if f.fix is None
        else {
            "title": f.fix.title,
            "applicability": f.fix.applicability,
            "why": f.fix.why,
            "edits": [
                {
                    "line": e.line,
                    "column": e.column,
                    "end_line": e.end_line,
                    "end_column": e.end_column,
                    "text": e.text,
                    "item": e.item,
                }
                for e in f.fix.edits
            ],
        },
    }


def json_report(result: LintResult) -> str:
    doc = {
        "findings": [finding_record(f) for f in result.findings],
        "summary": {
            "files": result.files,
            "findings": len(result.findings),
            "penalty": result.penalty,
            "possible_findings": sum(1 for f in result.findings if f.certainty == "possible"),
            "possible_penalty": result.possible_penalty,
        },
    }
    return _json_text(doc)


def artifact_uri(path: str, root: str | None = None) -> str:
    """A SARIF artifact URI: relative to `root` (default: the current directory) with `/`
    separators and percent-escapes; an absolute `file://` URI for a file outside `root`."""
    from pathlib import Path  # SARIF only: not on every lint's start-up
    from urllib.parse import quote

    real = Path(path).resolve()
    base = Path(root or os.getcwd()).resolve()
    try:
        rel = real.relative_to(base)
    except ValueError:
        return real.as_uri()  # percent-escapes the file name's bytes, undecodable ones too
    return quote(os.fsencode(rel.as_posix()))


def sarif_level(severity: str, certainty: str | None = None) -> str:
    """SARIF level: compile errors "error", certain deductions "warning", the rest "note"."""
    if certainty == "possible":
        return "note"
    return {"error": "error", "warning": "warning"}.get(severity, "note")


def _sarif_fix(fix: Fix, root: str | None) -> dict:
    """A SARIF `fix`: the rule's edits as replacements (an insertion is an empty region)."""
    return {
        "description": {
            "text": f"{fix.title} ({fix.applicability}: `glslcheck lint --fix` applies it once "
            "rendering proves it keeps the picture)"
        },
        "artifactChanges": [
            {
                "artifactLocation": {"uri": artifact_uri(fix.path, root)},
                "replacements": [
                    {
                        "deletedRegion": {
                            "startLine": e.line,
                            "startColumn": e.column,
                            "endLine": e.end_line,
                            "endColumn": e.end_column,
                        },
                        "insertedContent": {"text": e.text},
                    }
                    for e in fix.edits
                ],
            }
        ],
    }


def sarif_document(result: LintResult, root: str | None = None) -> dict:
    from ..base.version import __version__

    rules = list(all_rules().values())
    index = {r.name: i for i, r in enumerate(rules)}
    driver_rules = []
    for r in rules:
        driver_rules.append(
            {
                "id": r.name,
                "name": r.name,
                "shortDescription": {"text": r.summary},
                "fullDescription": {"text": r.section("What it does")},
                "help": {"text": r.doc, "markdown": r.doc},
                "defaultConfiguration": {"level": sarif_level(r.severity, r.certainty)},
                "properties": {
                    "penalty": r.penalty,
                    "certainty": r.certainty if r.penalty else None,
                    "tags": [r.kind],
                },
            }
        )
    results = []
    for f in result.findings:
        rec = finding_record(f)
        message = f.message + (f"\nhelp: {f.help}" if f.help else "")
        entry: dict[str, Any] = {
            "ruleId": f.rule,
            "level": sarif_level(f.severity, f.certainty),
            "message": {"text": message},
            "locations": [
                {
                    "physicalLocation": {
                        "artifactLocation": {"uri": artifact_uri(f.path, root)},
                        "region": {
                            "startLine": rec["line"],
                            "startColumn": rec["column"],
                            "endLine": rec["end_line"],
                            "endColumn": rec["end_column"],
                        },
                    }
                }
            ],
            "properties": {"penalty": f.penalty, "certainty": f.certainty},
        }
        if f.rule in index:
            entry["ruleIndex"] = index[f.rule]
        if f.fix is not None:
            entry["fixes"] = [_sarif_fix(f.fix, root)]
        results.append(entry)
    return {
        "$schema": SARIF_SCHEMA,
        "version": SARIF_VERSION,
        "runs": [
            {
                "tool": {
                    "driver": {
                        "name": "glslcheck",
                        "version": __version__,
                        "informationUri": "https://www.shadertoy.com/",
                        "rules": driver_rules,
                    }
                },
                "columnKind": "unicodeCodePoints",
                "results": results,
            }
        ],
    }


def sarif_report(result: LintResult) -> str:
    return _json_text(sarif_document(result))


def _escape_data(s: str) -> str:
    return s.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")


def _escape_property(s: str) -> str:
    return _escape_data(s).replace(":", "%3A").replace(",", "%2C")


def github_report(result: LintResult) -> str:
    out = []
    for f in result.findings:
        rec = finding_record(f)
        level = sarif_level(f.severity, f.certainty)
        command = {"error": "error", "warning": "warning"}.get(level, "notice")
        props = ",".join(
            f"{k}={_escape_property(str(v))}"
            for k, v in (
                ("file", posix_path(f.path)),
                ("line", rec["line"]),
                ("col", rec["column"]),
                ("endLine", rec["end_line"]),
                ("endColumn", rec["end_column"]),
                ("title", f.rule),
            )
        )
        message = f.message + (f"\nhelp: {f.help}" if f.help else "")
        out.append(_no_surrogates(f"::{command} {props}::{_escape_data(message)}"))
    return "".join(line + "\n" for line in out)


FORMATS: dict[str, Callable[[LintResult], str]] = {
    "text": text_report,
    "json": json_report,
    "sarif": sarif_report,
    "github": github_report,
}


def render(result: LintResult, fmt: str = "text") -> str:
    try:
        return FORMATS[fmt](result)
    except KeyError:
        raise ValueError(f"unknown format {fmt!r}; the formats are {', '.join(FORMATS)}") from None
