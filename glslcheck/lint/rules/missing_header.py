"""A file whose top names no student: its author information is missing.

## What it does
Reads the comments at the top of the file, before its first line of code (a license block may
come first; `#define` lines do not end the header), and reports the file when they name no
student. A student is named by
- a label: `Author:`, `Authors:`, `Contributors:`, `Team:`, `Students:`, `Names:` (with the
  names after it or on the lines below), also after a word saying whose authorship it is
  (`Modification Author:`, `Lead author -`);
- an authorship phrase: `Made by`, `Written by`, `Modified by`, `Code extended by`,
  `Assignment by:`, `Rest of the code by ...`, `Collaborated with ...`; the name ends with its
  sentence (`written by Dylan Rubin. Sources used ...`: `Sources` is no part of it);
- a `Copyright <year> <name>` line of a license;
- a line of people's names (`// Eli Moore`, `// Jane Doe & John Smith`, `// Eli Moore,
  GPR-200`), or names after the lab they are for (`// GPR-200 Lab 4 - Eli Moore`), unless it
  sits under a heading that credits help or sources (`// Source assistance` / `// Jake Siede`);
  a title of capitalised words (`// Lighting - Phong Shading`, `// TYPE ALIASES`, `// Collision
  IDs`: an acronym with a suffix) is no name.
The instructor's starter line ("GLSL STARTER CODE BY DANIEL S. BUCKSTEIN"), thanks and source
credits ("Thanks to Dan Buckstein", "Got assistance from ...") name no author of the file, nor
does a `Created by` line right under a line crediting borrowed code by its link (`// Random
generator from https://...` / `// Created by dcerisano`: the author of the source; `Modified
by` there names the student), nor a starter's own credits (`// Originally by Nikos
Papadopoulos`, `// Heavily modified by Dr. Sajid Farooq`: a name with an instructor's title).

One finding per file, at line 1. It is a certain deduction: the rubric's "Add author
information to the top of each code file (-1 for each omission)" leaves no reading in which a
file with no student named at its top keeps the point. A file that names its students but not
the file's name and purpose, or not what each contributor did, is `incomplete-header` (a
possible deduction).

## Why is this bad?
The course's coding standards: "Add author information to the top of each code file (-1 for each
omission). If you have a license, include the boiler plate template (fill it in with your own
info) and add a separate block with: 1) the name and purpose of the file; and 2) a list of
contributors and what they did."

## Example
```glsl
// GLSL STARTER CODE BY DANIEL S. BUCKSTEIN

// lighting lab
void mainImage(out vec4 fragColor, in vec2 fragCoord)
```

## Use instead
```glsl
// GLSL STARTER CODE BY DANIEL S. BUCKSTEIN

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
STANDARD = "header"
SEVERITY = "warning"
NEEDS = "text"

_SEP = r"[:=\-\u2013\u2014|(]"
_PURPOSE_LABEL = compiled(
    r"^\W*(?:purpose|description|desc|brief|summary|about|overview|what it "
    r"does)\b\s*[:\-\u2013\u2014]",
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
# The header's other fields, which end a contributor list above them: the course template's
# `Class:`, `Assignment:`, `Date Assigned:`, `Due Date:` too.
_OTHER_LABEL = compiled(
    r"^\W*(?:file(?:name)?|tab|name|titt?le|purpose|description|brief|summary|about|license|copyright"
    r"|credits?|sources?|references?|version|course|instructor|class|section|semester|assignment"
    r"|(?:due\s+)?date(?:\s+(?:assigned|due|created|modified|submitted))?)\b\s*[:\-]",
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
_LICENSE_TEXT = compiled(
    r"^\W*(?:licen[cs]ed\s+under|permission\s+is\s+hereby|all\s+rights\s+reserved)", re.I
)
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


# A file named after its assignment (`Lab 3.txt`, `lab4`, `A3`): the name is the lab's too.
_ASSIGNMENT = compiled(r"(?:lab|assignment|project|homework|hw|a)[\s_-]*\d+", re.I)
_LAB_NUMBER = compiled(r"(?<![a-z])lab[\s_-]*0*(\d+)(?!\d)", re.I)  # `RLittleton_Lab4_Text`: 4
_TITLE = compiled(r"^\W*(?:titt?le|name)\s*[:\-]\s*\w", re.I | re.M)  # `Title: Lab 2 effects`


def names_file(text: str, path: str, tab: str) -> bool:
    if _TITLE.search(text):  # a title names the file as a TA reads it
        return True
    full, others = _names(path, tab)
    if re.search(rf"(?<![\w.]){_flex(full)}(?!\w)", text, re.I):
        return True
    for n in others:
        f = _flex(n) + _EXT  # `Image.glsl` names the Image tab kept in Image.txt too
        patterns: tuple[str, ...] = (
            rf"^\W*(?:file\s*(?:name)?|filename|tab|name|shader|pass)\s*{_SEP}\s*[\"'`]?{f}(?!\w)",
            rf"(?<!\w){f}\s+{_TAB_WORDS}\b",
            rf"\b{_TAB_WORDS}\s*[:\-]?\s*[\"'`]?{f}(?!\w)",
        )
        if not _ASSIGNMENT.match(n):  # `Lab 3` alone names the lab, even in `Lab 3.txt`
            patterns += (rf"^[\W_]*[\"'`]?{f}[\"'`]?\s*(?:$|{_SEP}|,)",)
        lab = _LAB_NUMBER.search(n)
        if lab:  # ... but the template's `Assignment: Lab 3` says the file is that lab's
            patterns += (rf"^\W*assignment\s*[:\-]\s*lab[\s_\-#]*0*{lab.group(1)}(?!\d)",)
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
    lists = _contributor_lists(text)
    entries = lists[False] or lists[True]
    if not entries:
        return "none"
    if len(entries) == 1 and not _NAME_LIST.search(entries[0]):
        return "ok"  # one author did all of it: no list of who did what to give
    return "ok" if all(_DID.search(e) for e in entries) else "bare"


def left_out(text: str) -> list[str]:
    """The students a license's `Copyright <year> <name>` line names whom the header's contributor
    list (`Contributors:` ...) leaves out: that list does not say what they did."""
    lines = text.split("\n")
    listed = ""  # the lines of the contributor lists, credits too (`Dan Buckstein - provided ...`)
    for i, line in enumerate(lines):
        m = _CONTRIB_LABEL.match(line)
        if m and not _COPYRIGHT.match(line):
            listed += " " + m.group("rest")
            for follow in lines[i + 1 :]:
                if not _LIST_MARK.sub("", follow).strip() or _CONTRIB_LABEL.match(follow):
                    break
                listed += " " + follow
    if not listed.strip():
        return []
    names = [
        m.group("name")
        for m in map(_COPYRIGHT_NAME.match, text.split("\n"))
        if m and not _INSTRUCTOR.search(m.group("name"))
    ]
    return [n for n in names if not any(w in listed for w in n.split() if len(w) > 2)]


def _contributor_lists(text: str) -> dict[bool, list[str]]:
    """The entries of the header's contributor lists, by whether a `Copyright` line gave them."""
    lines = text.split("\n")
    lists: dict[bool, list[str]] = {True: [], False: []}  # copyright line? -> entries
    for i, line in enumerate(lines):
        m = _CONTRIB_LABEL.match(line)
        if not m or _under_credit(lines, i):
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
                or _LICENSE_TEXT.match(follow)  # nor the license under a Copyright line
            ):
                break
            entries.append(body)
    return lists


# A person's name: two to four capitalised words (`Ana Ruiz`, `Demetrius J Nekos`, `Mr. Li`).
_PERSON = r"(?-i:[A-Z][\w'\u2019.-]*)(?:\s+(?-i:[A-Z][\w'\u2019.-]*)){1,3}"
_PERSON_AT = compiled(rf"\s*(?P<name>{_PERSON})")  # a name at the start of a list entry
# A line that is only names (`// Eli Moore`, `// Jane Doe & John Smith`), or names then a
# course, class or date after a comma or a dash (`// Eli Moore, GPR-200`).
_NAME_LINE = compiled(
    rf"^[\s*/#>\-\u2022]*(?P<name>{_PERSON}(?:\s*(?:,|&|\band\b)\s*{_PERSON})*)"
    r"\s*(?:$|[*/.;]+\s*$|(?:,|\s[-\u2013\u2014|]\s)[^a-z]*(?:\d|gpr|lab|class|course)[^\n]*$)"
)
# `Lab 4 - Eli Moore`: a name after the lab or assignment it is for.
_AFTER_LAB = compiled(
    rf"\b(?:lab|assignment|project|homework|hw)\s*#?\d+\s*(?:[-:|,\u2013\u2014]|by)\s*"
    rf"(?P<name>{_PERSON}(?:\s*(?:,|&|\band\b)\s*{_PERSON})*)\s*$",
    re.I,
)
# Words that make a capitalised line a title, not a person (`Lab Four`, `Shadertoy Code`).
_NOT_NAME_WORDS = compiled(
    r"\b(?:lab|labs|shader|shaders|shadertoy|code|image|common|buffer|graphics|lighting|starter"
    r"|sources?|notes?|class|assignment|project|effect|effects|functions?|utility|utilities|main"
    r"|scene|sphere|spheres|light|lights|ray|tracing|tracer|gpr|intro|introduction|part|final"
    r"|the|and|of|for|to|in|with|by|from|see|todo|test|gpu|glsl|struct|structs|camera|globals?"
    r"|phong|blinn|lambert\w*|shading|reflect\w*|diffuse|specular|ambient|attenuation|normals?"
    r"|colou?rs?|textures?|noise|march\w*|cube|maps?|helpers?|math|vectors?|constants?|variables?"
    r"|output|input|setup|version|license|licence|copyright)\b",
    re.I,
)
# Authorship: a label followed by names, or a phrase with `by`/`with` before them.
# A label may carry a word saying whose authorship it is (`Modification Author:`, `Lead author:`).
_AUTHOR_LABEL = compiled(
    r"^\W*@?(?:(?:modification|modifying|lead|co|student|project|lab|assignment|code|file)[\s-]+)?"
    r"(?:auth[oe]rs?|contributors?|team(?:\s+members)?|students?|names?|group(?:\s+members)?"
    r"|partners?|programmers?|developers?|creators?)\s*(?:[:\-]|\s(?:are|is)\b)\s*(?P<rest>.*)$",
    re.I,
)
_AUTHOR_PHRASE = compiled(
    rf"(?:\bby|\b(?:collaborat\w*|work\w*|together|partner\w*)\s+with)\s*:?\s*(?P<name>{_PERSON})",
    re.I,
)
# What a `by`/`with` phrase credits rather than authors: the starter code, sources, help.
_CREDIT_PHRASE = compiled(
    r"\b(?:starter|framework|provided|original(?:ly)?|inspired|adapted|based|taken|borrowed|courtesy"
    r"|thanks?|referenc\w*|tutorial|book|assist\w*|help\w*|source\w*|derived|from)\b",
    re.I,
)
_COPYRIGHT_NAME = compiled(
    rf"^\W*copyright\b(?:\s*(?:\(c\)|\u00a9))?(?:\s*\d{{4}}(?:\s*-\s*\d{{4}})?)?\s*,?\s*(?P<name>{_PERSON})",
    re.I,
)
_INSTRUCTOR = compiled(r"buckst[ei]{2}n", re.I)  # the instructor's name, however spelt
_HELP_HEADING = compiled(r"\b(?:assist\w*|help\w*|thanks?|sources?|credits?|references?)\b", re.I)


def _under_credit(lines: list[str], i: int) -> bool:
    """Whether line i is a `Created by` line right under a line that credits a source by its
    link (`// Random generator from https://...` / `// Created by dcerisano`): it names that
    source's author, not the file's (`Modified by` names who changed it: the student)."""
    above = lines[i - 1] if i > 0 else ""
    return (
        _LINK.search(above) is not None
        and has_credit(above)
        and _CREATED_BY.match(lines[i]) is not None
    )


_LINK = compiled(r"https?://|www\.", re.I)
_CREATED_BY = compiled(r"^\W*(?:created|written|made|authored)?\s*by\b", re.I)


# an instructor's title before a name (`Heavily modified by Dr. Sajid Farooq`): not a student
_TITLED = compiled(r"^\s*(?:dr|prof|professor)\b\.?", re.I)


# an acronym with a suffix (`Collision IDs`, `UVs`): a heading's word, not a name's
_ACRONYM_WORD = compiled(r"\b[A-Z]{2,}[a-z]+\b")


def _is_person(text: str) -> bool:
    return (
        not _INSTRUCTOR.search(text)
        and not _NOT_NAME_WORDS.search(text)
        and not _TITLED.match(text)
        and not _ACRONYM_WORD.search(text)
    )


def named_students(text: str) -> list[str]:
    """The students a header names (see the rule's doc), in order; empty when it names none."""
    names: list[str] = []
    lines = text.split("\n")
    for i, line in enumerate(lines):
        label = _AUTHOR_LABEL.match(line)
        if label:
            entries = [label.group("rest")]
            if not label.group("rest").strip():  # the names on the lines below the label
                for follow in lines[i + 1 :]:
                    if not follow.strip() or _OTHER_LABEL.match(follow):
                        break
                    entries.append(follow)
            for entry in entries:
                # `Ryan Littleton - using starter from Daniel Buckstein`: the part before the credit
                entry = _LIST_MARK.sub("", re.split(r"\s[-\u2013\u2014]\s|[(;/]", entry)[0])
                if entry.strip() and not _INSTRUCTOR.search(entry):
                    names.append(entry.strip())
            continue
        copyright_name = _COPYRIGHT_NAME.match(line)
        if copyright_name and not _INSTRUCTOR.search(copyright_name.group("name")):
            names.append(copyright_name.group("name"))
            continue
        phrase = _AUTHOR_PHRASE.search(line)
        if (
            phrase
            and not _CREDIT_PHRASE.search(line[: phrase.start()])
            and not _under_credit(lines, i)
        ):
            # a name ends at a sentence's end too (`by Dylan Rubin. Sources used ...`); an
            # initial or a title (`J.`, `Mr.`) has fewer than three small letters before its dot
            chunks = re.split(r"[,;&]|\band\b|(?<=[a-z]{3})\.\s", line[phrase.start("name") :])
            found = [
                m.group("name")
                for m in map(_PERSON_AT.match, chunks)
                if m and _is_person(m.group("name"))
            ]
            if found:
                names.extend(found)
                continue
        bare = _NAME_LINE.match(line) or _AFTER_LAB.search(line)
        above = next((x for x in reversed(lines[:i]) if x.strip()), "")
        if bare and not _HELP_HEADING.search(above):
            found = re.split(r"\s*(?:,|&|\band\b)\s*", bare.group("name"))
            # every one a person, not a heading in capitals (`TYPE ALIASES & UTILITY FUNCTIONS`)
            if all(_is_person(n) and not n.isupper() for n in found):
                names.extend(found)
    return names


def names_a_student(text: str) -> bool:
    """Whether a header names a student: `named_students`, or a contributor list
    (`contributors`: `By Ana: all of it`, `Copyright 2020 Morgan Reyes`)."""
    return bool(named_students(text)) or contributors(text) != "none"


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


def missing_parts(ctx, authors: int) -> list[str] | None:
    """What the header lacks besides its authors, as phrases; None when there is no header
    comment at all. `authors`: how many students it names (one did all of it: no roles needed)."""
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
    if who == "bare" or (who == "none" and authors > 1):
        missing.append("does not say what each contributor did")
    return missing


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    if not ctx.source.text.strip():
        return
    text = header_text(ctx)
    if text is not None and names_a_student(text):
        return  # what else the header lacks is incomplete-header's
    name = path_name(ctx.source.path)
    if text is None:
        message = "the file opens with no header comment: no student is named at its top"
    elif has_credit(text):
        message = (
            "the header credits the starter code or sources but names no student: the file's "
            "author information is missing"
        )
    else:
        message = "the header names no student: the file's author information is missing"
    # the template: the whole header, or after the existing one the parts it lacks, contributors
    # always (no student is named)
    missing = missing_parts(ctx, authors=0)
    if missing is not None:
        missing.append("lists no contributors with what each did")
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
