"""A file that does not open with a header naming it, its purpose and its contributors.

## What it does
Reads the comments at the top of the file, before its first line of code (a license block may
come first; `#define` lines do not end the header), and checks that they
1. name the file: its file name with or without extension, its Shadertoy tab name
   (`Image.glsl`, `File: Image`, `Buffer A tab`, or a line starting with the name), or a
   `Title:` line;
2. state its purpose: a `Purpose:`, `Description:`, `Brief:`, `Summary:` or `About:` label, a
   sentence starting "This file/shader/tab ...", or words after the name (`Image: lit spheres`);
3. list the contributors with what each did: an `Author(s):`, `Contributors:`, `By`,
   `Written by`, `Created by`, `Modified by`, `Edited by` or `Team:` label (also inside a
   license block), each entry saying what that person did (`Ana Ruiz: lighting`,
   `Ben Li - optimization`, `Cy (comments)`). A single author did all of it: one name is enough.
   The instructor's starter line ("GLSL STARTER CODE BY ...") credits the framework; it names
   no author of the file.

One finding per file, at line 1, saying every part that is missing. Which omissions cost the
point: the rubric asks for "author information" at the top of each file, made of 1) the name
and purpose of the file and 2) the contributors and what they did, "-1 for each omission". A TA
deducts one point for a file whose author information is incomplete, whichever part is
missing: a file with no author at all (nothing, or only the starter credit) and a file that
names its students but not itself or its purpose both cost that point, and the message lists
what to add. A complete header with one author and no role list costs nothing.

## Why is this bad?
The course's coding standards: "Add author information to the top of each code file (-1 for each
omission). If you have a license, include the boiler plate template (fill it in with your own
info) and add a separate block with: 1) the name and purpose of the file; and 2) a list of
contributors and what they did."

## Example
```glsl
// lighting lab
void mainImage(out vec4 fragColor, in vec2 fragCoord)
```

## Use instead
```glsl
// Image.glsl: draws lit spheres with Lambert, Phong and Blinn-Phong shading (Lab 4)
// Contributors:
//   Ana Ruiz: sphere ray-tracing, point lights
//   Ben Li: Blinn-Phong, optimization pass, comments
void mainImage(out vec4 fragColor, in vec2 fragCoord)
```
"""

from __future__ import annotations

import re

from ...base.diagnostics import Diagnostic
from ...base.regexes import compiled
from ...shadertoy.sources import path_name, path_stem, tab_name
from ..fixes import Fixable
from ..fixes.header import header_fix
from ..textscan import BLANK, COMMENT, DIRECTIVE
from .missing_credit import has_credit

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

    from ..engine import LintContext

NAME = "missing-header"
PENALTY = 1
SEVERITY = "warning"
NEEDS = "text"

_SEP = r"[:=\-\u2013\u2014|(]"
_PURPOSE_LABEL = compiled(
    r"^\W*(?:purpose|description|desc|brief|summary|about|overview|what it does)\b\s*[:\-\u2013\u2014]",
    re.I | re.M,
)
_DOXYGEN_BRIEF = compiled(r"^\W*[@\\](?:brief|details)\s+\w", re.I | re.M)
_PURPOSE_SENTENCE = compiled(
    r"\bthis\s+(?:file|shader|tab|pass|buffer|program|code)\s+(?:is\s+|will\s+)?(?!except\b)[a-z]+",
    re.I,
)
_CONTRIB_LABEL = compiled(
    r"^\W*(?:auth[oe]rs?|copyright(?:\s+(?:\(c\)|\u00a9))?(?:\s+\d{4}(?:\s*-\s*\d{4})?)?|contributors?|contributions|team(?:\s+members)?|programmers?|developers?"
    r"|(?:written|created|made|modified|edited|coded|programmed)\s+by|by)\b\s*:?\s*(?P<rest>.*)$",
    re.I,
)
_OTHER_LABEL = compiled(
    r"^\W*(?:file(?:name)?|tab|name|titt?le|purpose|description|brief|summary|about|license|copyright"
    r"|credits?|sources?|references?|date|version|course|instructor)\b\s*[:\-]",
    re.I,
)
_DID = compiled(
    r"[:(\u2013\u2014]|\s-\s|\b(?:implement\w*|wrote|written|add(?:ed|s|ing)?|made|creat\w+|did|does"
    r"|work(?:ed|s|ing)?|design\w*|modif\w+|refactor\w*|optimi[sz]\w*|comment\w*|document\w*"
    r"|fix\w*|set\s+up|cod(?:ed|ing|e)|program\w*|buil[td]\w*|test\w*|debug\w*|help\w*|lead|led"
    r"|lighting|shading|render\w*|math|structs?)\b",
    re.I,
)
_WORD_BREAK = compiled(r"[\s_\-]+")
_COPYRIGHT = compiled(r"^\W*copyright\b", re.I)
_LIST_MARK = compiled(r"^[\s*/#>\-\u2022\d.)]*")  # a list item's bullet or number
_NAME_LIST = compiled(r",|&|\band\b")  # more than one name in an entry
_TAB_WORDS = r"(?:tab|pass|buffer|shader|file)"
_EXT = r"(?:\.(?:glsl|frag|txt))?"


def _flex(name: str) -> str:
    """A regex for a name whose words may be joined by spaces, `_` or `-` (any case)."""
    return r"[\s_\-]*".join(re.escape(w) for w in _WORD_BREAK.split(name.strip()) if w)


def _names(path: str, tab: str) -> tuple[str, list[str]]:
    """The file's name with extension, and the other names that name it (stem, tab name)."""
    others = [path_stem(path)]
    for t in (tab, tab_name(path)):
        if t and t != "GLSL" and t not in others:
            others.append(t)
    return path_name(path), others


_TITLE = compiled(r"^\W*(?:titt?le|name)\s*[:\-]\s*\w", re.I | re.M)  # `Title: Lab 2 effects`


def names_file(text: str, path: str, tab: str) -> bool:
    if _TITLE.search(text):  # a title names the file as a TA reads it
        return True
    full, others = _names(path, tab)
    if re.search(rf"(?<![\w.]){_flex(full)}(?!\w)", text, re.I):
        return True
    for n in others:
        f = _flex(n) + _EXT  # `Image.glsl` names the Image tab kept in Image.txt too
        patterns = (
            rf"^\W*(?:file\s*(?:name)?|filename|tab|name|shader|pass)\s*{_SEP}\s*[\"'`]?{f}(?!\w)",
            rf"^[\W_]*[\"'`]?{f}[\"'`]?\s*(?:$|{_SEP}|,)",
            rf"(?<!\w){f}\s+{_TAB_WORDS}\b",
            rf"\b{_TAB_WORDS}\s*[:\-]?\s*[\"'`]?{f}(?!\w)",
        )
        if any(re.search(pat, text, re.I | re.M) for pat in patterns):
            return True
    return False


def states_purpose(text: str, path: str, tab: str) -> bool:
    if _PURPOSE_LABEL.search(text) or _PURPOSE_SENTENCE.search(text) or _DOXYGEN_BRIEF.search(text):
        return True
    full, others = _names(path, tab)
    for n in (full, *others):
        # words after the name on its line: `Image.glsl - draws lit spheres`
        if re.search(
            rf"(?<!\w){_flex(n)}{_EXT}(?:\s+{_TAB_WORDS})?[\"'`]?\s*{_SEP}\s*\w+\W+\w+", text, re.I
        ):
            return True
    return False


def contributors(text: str) -> str:
    """ "ok", "none" (no contributor list), or "bare" (names without what each did). A license's
    `Copyright <year> <names>` lines name authors only when no other list does."""
    lines = text.split("\n")
    lists: dict[bool, list[str]] = {True: [], False: []}  # copyright line? -> entries
    for i, line in enumerate(lines):
        m = _CONTRIB_LABEL.match(line)
        if not m:
            continue
        entries = lists[bool(_COPYRIGHT.match(line))]
        rest = m.group("rest").strip()
        if rest:
            entries.extend(e for e in re.split(r";", rest) if e.strip() and not has_credit(e))
        for follow in lines[i + 1 :]:
            body = _LIST_MARK.sub("", follow).strip()
            if (
                not body
                or _CONTRIB_LABEL.match(follow)
                or _OTHER_LABEL.match(follow)
                or has_credit(follow)  # a credit line is no contributor
            ):
                break
            entries.append(body)
    entries = lists[False] or lists[True]
    if not entries:
        return "none"
    if len(entries) == 1 and not _NAME_LIST.search(entries[0]):
        return "ok"  # one author did all of it: no list of who did what to give
    return "ok" if all(_DID.search(e) for e in entries) else "bare"


def header_text(ctx) -> str | None:
    """The text of the comments before the first code line (directives left out), or None."""
    # authors written after a `#define` are still header: a directive line is no code
    lines = ctx.lines
    first_code = next(
        (
            i
            for i, k in enumerate(ctx.line_kinds, start=1)
            if k is not BLANK
            and k is not COMMENT
            and k is not DIRECTIVE  # code, or a brace
            and not lines[i - 1].lstrip().startswith("#")
        ),
        len(ctx.line_kinds) + 1,
    )
    parts: list[str] = []
    last = None
    for c in ctx.comments:
        if c.line >= first_code or c.is_directive:
            continue
        if last is not None and c.line > last + 1:
            parts.append("")  # a blank line between comments ends a list (contributors)
        parts.append(c.text)
        last = c.end_line
    return "\n".join(parts) if parts else None


def missing_parts(ctx) -> list[str] | None:
    """What the header lacks, as phrases; None when there is no header comment at all."""
    text = header_text(ctx)
    if text is None:
        return None
    path, tab = ctx.source.path, ctx.source.tab
    missing = []
    if not names_file(text, path, tab):
        missing.append(f"does not name the file (`{path_name(path)}`)")
    if not states_purpose(text, path, tab):
        missing.append("states no purpose")
    who = contributors(text)
    if who == "none" and has_credit(text):
        missing.append(
            "lists no contributors with what each did (a starter-code credit names no author)"
        )
    elif who == "none":
        missing.append("lists no contributors with what each did")
    elif who == "bare":
        missing.append("lists contributors without what each did")
    return missing


def _join(phrases: list[str]) -> str:
    return phrases[0] if len(phrases) == 1 else ", ".join(phrases[:-1]) + " and " + phrases[-1]


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    if not ctx.source.text.strip():
        return
    missing = missing_parts(ctx)
    name = path_name(ctx.source.path)
    if missing is None:
        message = (
            "the file opens with no header comment (it should name the file, state its purpose "
            "and list the contributors with what each did)"
        )
    elif missing:
        message = "the header " + _join(missing)
    else:
        return
    yield Fixable(
        message,
        ctx.location(1, 1),
        help=f"open the file with a comment such as `// {name}: <what it does>` and "
        "`// Contributors: <name>: <what they did>; ...`",
        fix=header_fix(ctx, missing, _header_end(ctx)),
    )


def _header_end(ctx) -> int | None:
    """The last line of the header's comments (before the first code line), or None."""
    first_code = next(
        (
            i
            for i, k in enumerate(ctx.line_kinds, start=1)
            if k not in (BLANK, COMMENT, DIRECTIVE)
            and not ctx.lines[i - 1].lstrip().startswith("#")
        ),
        len(ctx.line_kinds) + 1,
    )
    ends = [c.end_line for c in ctx.comments if c.line < first_code and not c.is_directive]
    return max(ends) if ends else None
