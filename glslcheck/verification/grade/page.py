"""The grades page: one self-contained HTML file with a row per team, sortable, openable from
disk (no network: inline CSS and script, every image a PNG data URI).

Each row: rank, team (contributors, repository and branch), status, the verdict against the
reference with the lowest PSNR of the frames, the points deducted, the thumbnails of the renders
(the reference's in the first row of the table head) with the diff image under each, and what
the TA should read: the reason a submission failed, the render problems, the compile errors and
every deduction with its file:line and source line (folded, opened with a click). Clicking a
column head sorts by it (again: the other way). Escaping and the inline images are the report
page's (glslcheck/verification/report.py); docs/grading.md explains the scale.
"""

from __future__ import annotations

import base64
import math

from ...base.version import __version__
from ..report import CSS as REPORT_CSS
from ..report import escape
from .closeness import CLOSE, CLOSE_PSNR_DB, DIFFERENT, SAME, VERDICTS
from .grading import Options, Reference
from .outputs import ranked
from .records import GRADED, POSSIBLE, Grade

CSS = (
    REPORT_CSS
    + """
body { max-width: none; }
table.grades { width: 100%; } table.grades td { vertical-align: top; }
table.grades th[data-key] { cursor: pointer; user-select: none; white-space: nowrap; }
table.grades th[data-dir="asc"]::after { content: " \\25B2"; }
table.grades th[data-dir="desc"]::after { content: " \\25BC"; }
tr.reference td { background: #f6f8fa; }
.thumbs { display: flex; gap: 6px; } .thumbs figure { text-align: center; }
.thumbs img { width: 160px; image-rendering: auto; border: 1px solid #d8dee4; display: block; }
.thumbs figcaption { max-width: 160px; }
.team { font-weight: 600; } .small { font-size: 12px; color: #57606a; }
details summary { cursor: pointer; } details pre { margin: 2px 0 6px; background: #fff;
  border: 1px solid #d8dee4; padding: 2px 6px; font-size: 12px; white-space: pre-wrap; }
.reason { color: #a40e26; }
table.grades .badge { white-space: nowrap; }
table.grades td.read { min-width: 240px; max-width: 460px; overflow-wrap: anywhere; }
"""
)

SCRIPT = """
document.querySelectorAll("table.grades th[data-key]").forEach(function (th) {
  th.addEventListener("click", function () {
    var table = th.closest("table"), body = table.tBodies[0], i = th.cellIndex;
    var dir = th.dataset.dir === "asc" ? "desc" : "asc";
    table.querySelectorAll("th[data-key]").forEach(function (o) { delete o.dataset.dir; });
    th.dataset.dir = dir;
    var numeric = th.dataset.key === "num";
    var rows = Array.prototype.slice.call(body.rows);
    rows.sort(function (a, b) {
      var x = a.cells[i].dataset.sort, y = b.cells[i].dataset.sort;
      var c = numeric ? parseFloat(x) - parseFloat(y) : x.localeCompare(y);
      return dir === "asc" ? c : -c;
    });
    rows.forEach(function (r) { body.appendChild(r); });
  });
});
"""

_BADGE = {SAME: "ok", CLOSE: "warn", DIFFERENT: "bad"}
OPEN_DEDUCTIONS = 5  # a row shows this many deductions unfolded


def _uri(png: bytes) -> str:
    return "data:image/png;base64," + base64.b64encode(png).decode("ascii")


def _thumbs(pngs: list[tuple[str, bytes, bytes]]) -> str:
    figs = []
    for caption, image, diff in pngs:
        imgs = f'<img alt="render, {escape(caption)}" src="{_uri(image)}">' if image else ""
        if diff:
            imgs += f'<img alt="difference, {escape(caption)}" src="{_uri(diff)}">'
        figs.append(f"<figure>{imgs}<figcaption>{escape(caption)}</figcaption></figure>")
    return '<div class="thumbs">' + "".join(figs) + "</div>"


def _psnr(g: Grade) -> tuple[str, float]:
    v = g.min_psnr_db
    if v is None:
        return "-", -1.0
    return ("inf" if math.isinf(v) else f"{v:.1f} dB"), (1e9 if math.isinf(v) else v)


def _details(g: Grade) -> str:
    out = []
    if g.reason:
        out.append(f'<p class="reason">{escape(g.reason)}</p>')
    out += [f"<p>{escape(p)}</p>" for p in g.problems]
    if g.errors:
        items = "".join(
            f"<li><code>{escape(e.file)}:{e.line}:{e.column}</code> {escape(e.message)}"
            + (f"<pre>{escape(e.code)}</pre>" if e.code else "")
            + "</li>"
            for e in g.errors
        )
        out.append(
            f"<details open><summary>{len(g.errors)} error{'s' * (len(g.errors) != 1)}"
            f'</summary><ul class="diags">{items}</ul></details>'
        )
    if g.deductions:
        items = "".join(
            f"<li><code>{escape(d.file)}:{d.line}:{d.column}</code> -{d.penalty} "
            f"<b>{escape(d.rule)}</b>{' (possible)' if d.certainty == POSSIBLE else ''}: "
            f"{escape(d.message)}<pre>{escape(d.code)}</pre></li>"
            for d in g.deductions
        )
        label = f"{len(g.deductions)} deduction{'s' * (len(g.deductions) != 1)}"
        # a few are read at a glance; a long list stays folded until asked for
        out.append(
            f"<details{' open' * (len(g.deductions) <= OPEN_DEDUCTIONS)}><summary>{label}"
            f'</summary><ul class="diags">{items}</ul></details>'
        )
    if g.suppressions:
        items = "".join(f"<li><code>{escape(s)}</code></li>" for s in g.suppressions)
        out.append(
            "<details><summary>ignore comments in the code (counted anyway)</summary>"
            f'<ul class="diags">{items}</ul></details>'
        )
    if g.tabs:
        out.append(f'<p class="small">tabs: {escape(", ".join(g.tabs))}</p>')
    return "".join(out) or "-"


def _row(rank: int, g: Grade) -> str:
    psnr_text, psnr_key = _psnr(g)
    place = VERDICTS.index(g.verdict) if g.verdict in VERDICTS else len(VERDICTS)
    verdict = (
        f'<span class="badge {_BADGE[g.verdict]}">{escape(g.verdict)}</span>'
        if g.verdict
        else '<span class="badge off">-</span>'
    )
    status = (
        '<span class="badge ok">graded</span>'
        if g.status == GRADED
        else '<span class="badge bad">failed</span>'
    )
    points = f"-{g.points}" if g.points else "0"
    if g.possible_points:
        points += (
            f'<div class="small">{g.certain_points} certain, {g.possible_points} possible</div>'
        )
    who = escape(", ".join(g.contributors)) if g.contributors else ""
    where = escape(g.source) + (f" @ {escape(g.branch)}" if g.branch else "")
    frames = [
        (
            f"iTime {f.time:g}" + (f": {f.verdict}" if f.verdict else ""),
            f.thumbnail,
            f.diff_thumbnail,
        )
        for f in g.frames
    ]
    thumbs = _thumbs(frames) if frames else '<span class="small">no renders</span>'
    return (
        f'<tr id="team-{escape(g.team)}">'
        f'<td class="num" data-sort="{rank}">{rank}</td>'
        f'<td data-sort="{escape(g.team.lower())}"><div class="team">{escape(g.team)}</div>'
        f'<div class="small">{who}</div><div class="small">{where}</div></td>'
        f'<td data-sort="{g.status}">{status}</td>'
        f'<td data-sort="{place}">{verdict}<div class="small">{psnr_text}</div></td>'
        f'<td class="num" data-sort="{g.points}">{points}</td>'
        f'<td data-sort="{len(g.frames)}">{thumbs}</td>'
        f'<td class="read" data-sort="{len(g.problems) + len(g.errors)}">{_details(g)}</td></tr>'
    )


def page_html(
    grades: list[Grade], options: Options, reference: Reference | None, title: str
) -> str:
    """The whole page (see the module docstring)."""
    w, h = options.size
    times = ", ".join(f"{t:g}" for t in options.times)
    graded = sum(g.status == GRADED for g in grades)
    head = (
        '<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8">'
        '<meta name="viewport" content="width=device-width, initial-scale=1">'
        f"<title>{escape(title)}</title><style>{CSS}</style></head><body>"
    )
    meta = (
        f'<p class="meta">glslcheck {escape(__version__)}: {len(grades)} submission'
        f"{'s' * (len(grades) != 1)}, {graded} graded; "
        f"renders at {w}x{h} by {escape(options.backend)}, "
        f"iTime {escape(times)}. Points: the course's coding standards, -1 per instance "
        "(<code>glslcheck rule NAME</code> explains each). "
        "Verdict against the reference, per frame, "
        f"the worst shown: <b>{SAME}</b> = glslcheck verify's match "
        "(differences the display cannot "
        f"show or sub-pixel edge shifts), <b>{CLOSE}</b> = PSNR at least {CLOSE_PSNR_DB:g} dB "
        f"(the same scene with a parameter changed), <b>{DIFFERENT}</b> = below (docs/grading.md). "
        "Under each render its difference from the reference: black equal, red to white larger, "
        "magenta NaN/Inf in one image only. Click a column head to sort.</p>"
    )
    cols = [
        ("#", "num"),
        ("team", "text"),
        ("status", "text"),
        ("verdict", "num"),
        ("points", "num"),
        ("renders", "num"),
        ("what to read", "num"),
    ]
    header = "".join(f'<th data-key="{k}">{escape(c)}</th>' for c, k in cols)
    ref_row = ""
    if reference is not None:
        ref = _thumbs(
            [(f"iTime {t:g}", p, b"") for t, p in zip(options.times, reference.thumbnails)]
        )
        moves = {True: "animates", False: "does not animate", None: ""}[reference.animates]
        ref_row = (
            f'<tr class="reference"><td></td><td colspan="4"><div class="team">reference</div>'
            f'<div class="small">{escape(reference.name)}; {moves}</div></td>'
            f"<td>{ref}</td><td></td></tr>"
        )
    rows = "".join(_row(i, g) for i, g in enumerate(ranked(grades), 1))
    body = (
        f"<h1>{escape(title)}</h1>{meta}"
        f'<table class="grades"><thead><tr>{header}</tr>{ref_row}</thead>'
        f"<tbody>{rows}</tbody></table>"
        f"<script>{SCRIPT}</script>"
    )
    return head + body + "\n</body></html>\n"
