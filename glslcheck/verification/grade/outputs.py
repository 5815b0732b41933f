"""The grades as text: the terminal table, the CSV file and the JSON document.

The table and the CSV have one row per team, best first (`Grade.rank_key`): rank, team, status,
the verdict against the reference, the points deducted (certain and possible apart), the
number of tab files, compile errors and render problems, and the reason a submission failed.
The JSON holds everything (docs/grading.md: "JSON schema").
"""

from __future__ import annotations

import csv
import io
import json
import math

from .grading import Options
from .records import SCHEMA_VERSION, Grade

CSV_COLUMNS = (
    "rank",
    "team",
    "contributors",
    "source",
    "branch",
    "status",
    "verdict",
    "min_psnr_db",
    "points_certain",
    "points_possible",
    "points_total",
    "deductions",
    "tabs",
    "compile_errors",
    "problems",
    "reason",
)


def ranked(grades: list[Grade]) -> list[Grade]:
    return sorted(grades, key=Grade.rank_key)


def _psnr_text(v: float | None) -> str:
    if v is None:
        return ""
    return "inf" if math.isinf(v) else f"{v:.1f}"


def _rules(g: Grade) -> str:
    counts: dict[str, int] = {}
    for d in g.deductions:
        counts[d.rule] = counts.get(d.rule, 0) + d.penalty
    return "; ".join(f"{rule} -{n}" for rule, n in counts.items())


def csv_rows(grades: list[Grade]) -> list[dict]:
    rows = []
    for rank, g in enumerate(ranked(grades), 1):
        rows.append(
            {
                "rank": rank,
                "team": g.team,
                "contributors": "; ".join(g.contributors),
                "source": g.source,
                "branch": g.branch or "",
                "status": g.status,
                "verdict": g.verdict or "",
                "min_psnr_db": _psnr_text(g.min_psnr_db),
                "points_certain": -g.certain_points,
                "points_possible": -g.possible_points,
                "points_total": -g.points,
                "deductions": _rules(g),
                "tabs": len(g.tabs),
                "compile_errors": len(g.errors) if g.compiles is False else 0,
                "problems": "; ".join(g.problems),
                "reason": g.reason,
            }
        )
    return rows


def to_csv(grades: list[Grade]) -> str:
    buffer = io.StringIO()
    writer = csv.DictWriter(buffer, CSV_COLUMNS, lineterminator="\n")
    writer.writeheader()
    writer.writerows(csv_rows(grades))
    return buffer.getvalue()


def to_json(grades: list[Grade], options: Options, reference: str | None) -> str:
    doc = {
        "schema": SCHEMA_VERSION,
        "size": list(options.size),
        "times": list(options.times),
        "backend": options.backend,
        "reference": reference,
        "teams": [g.to_json() | {"rank": i} for i, g in enumerate(ranked(grades), 1)],
    }
    return json.dumps(doc, indent=2, ensure_ascii=False) + "\n"


def table(grades: list[Grade], reference: str | None) -> str:
    """The terminal table, then each team's deductions and errors with file:line."""
    head = ["#", "team", "status", "verdict", "PSNR", "points", "tabs", "problems / reason"]
    rows = []
    for rank, g in enumerate(ranked(grades), 1):
        points = f"-{g.points}" if g.points else "0"
        if g.possible_points:
            points += f" ({g.possible_points} possible)"
        note = g.reason if g.reason else "; ".join(g.problems)
        rows.append(
            [
                str(rank),
                g.team,
                g.status,
                g.verdict or ("-" if reference else "no reference"),
                _psnr_text(g.min_psnr_db) or "-",
                points,
                str(len(g.tabs)),
                note or "-",
            ]
        )
    widths = [max(len(r[i]) for r in [head, *rows]) for i in range(len(head) - 1)]
    lines = []
    for r in [head, *rows]:
        cells = [
            c.ljust(w) if i not in (0, 4, 6) else c.rjust(w)
            for i, (c, w) in enumerate(zip(r, widths))
        ]
        lines.append("  ".join([*cells, r[-1]]).rstrip())
    out = ["\n".join(lines)]
    for g in ranked(grades):
        details = [f"  {e}" for e in (g.errors if g.compiles is False or g.reason else [])]
        details += [
            f"  {d.file}:{d.line}:{d.column}: -{d.penalty} [{d.rule}]"
            + (" (possible)" if d.certainty == "possible" else "")
            + f" {d.message}"
            for d in g.deductions
        ]
        details += [f"  {s} (counted anyway)" for s in g.suppressions]
        if details:
            out.append(f"{g.team}:\n" + "\n".join(details))
    return "\n\n".join(out) + "\n"
