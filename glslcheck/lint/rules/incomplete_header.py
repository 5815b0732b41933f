"""A header that names its students but not the file, its purpose, or who did what.

## What it does
For a file whose top names a student (else it is `missing-header`), checks that the header
comments also
1. name the file: its file name with or without extension, its Shadertoy tab name
   (`Image.glsl`, `File: Image`, `Buffer A tab`, or a line starting with the name), or a
   `Title:` line; a file called after its lab (`Lab 3.txt`) is not named by a line `Lab 3`
   alone, which names the lab, but is by the course template's `Assignment: Lab 3` field,
   which says the file is that lab's (a `Class:`, `Assignment:` or `Due Date:` field under an
   `Author:` line is no contributor);
2. state its purpose: a `Purpose:`, `Description:`, `Brief:`, `Summary:` or `About:` label, a
   sentence starting "This file/shader/tab ...", or words after the name (`Image: lit spheres`);
3. say what each contributor did (`Ana Ruiz: lighting`, `Ben Li - optimization`,
   `Cy (comments)`). A single author did all of it: one name is enough. A license's
   `Copyright 2020 <name>` over a `Contributors:` list of others only (the instructor, a book)
   does not say what that author did.

One finding per file, at line 1, listing what is missing.

A possible deduction, not a certain one: the rubric asks for "author information" (-1 for each
omission), then "If you have a license, include the boiler plate template ... and add a separate
block with: 1) the name and purpose of the file; and 2) a list of contributors and what they
did." Whether that block is required without a license is a reading of an ambiguous sentence,
so a TA may deduct the point or not. With a license in the header (`Licensed under the Apache
License`, `Creative Commons`, `Permission is hereby granted`) the sentence is plain: the finding
is then a certain deduction, unless all the header lacks is the part of the author its license
names, left out of a contributor list of others: whether that list must give the author's own
part is a reading, and a possible deduction.

## Why is this bad?
The course's coding standards: "Add author information to the top of each code file (-1 for each
omission). If you have a license, include the boiler plate template (fill it in with your own
info) and add a separate block with: 1) the name and purpose of the file; and 2) a list of
contributors and what they did."

## Example
```glsl
// GLSL STARTER CODE BY DANIEL S. BUCKSTEIN
// Modified by Ana Ruiz and Ben Li
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
from ...shadertoy.sources import path_name
from .missing_header import (
    header_text,
    left_out,
    missing_parts,
    named_students,
    names_a_student,
)

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

    from ..engine import LintContext

NAME = "incomplete-header"
PENALTY = 1
STANDARD = "header"
SEVERITY = "warning"
NEEDS = "text"
CERTAINTY = "possible"

# A license's text (not "No license"): with one, the rubric's separate block is plainly required.
LICENSE_RE = compiled(
    r"(?<!no )\blicen[cs]ed\s+under\b|\b(?:apache|mit|bsd|gnu|gpl|mozilla)\b[^\n]{0,30}licen[cs]e"
    r"|creative\s+commons|permission\s+is\s+hereby\s+granted",
    re.I,
)


def _join(phrases: list[str]) -> str:
    return phrases[0] if len(phrases) == 1 else ", ".join(phrases[:-1]) + " and " + phrases[-1]


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    text = header_text(ctx)
    if text is None or not names_a_student(text):
        return  # missing-header's
    missing = missing_parts(ctx, max(len(named_students(text)), 1)) or []
    # the license names an author the contributor list leaves out: whether the list must give
    # the author's own part too is a reading (possible, license or not)
    only_left_out = not missing
    omitted = left_out(text)
    if omitted and not any("each contributor" in m for m in missing):
        missing.append(f"does not say what {_join(omitted)} did")
    if not missing:
        return
    licensed = LICENSE_RE.search(text) is not None and not (omitted and only_left_out)
    why = (
        "the header holds a license, so the rubric asks for this block"
        if licensed
        else "a possible deduction: its contributor list leaves out the author the license names"
        if omitted and only_left_out
        else "a possible deduction: the rubric asks for this block in the sentence about licenses"
    )
    name = path_name(ctx.source.path)
    yield Diagnostic(
        f"the header names its author but {_join(missing)} ({why})",
        ctx.location(1, 1),
        help=f"add a block such as `// {name}: <what it does>` and "
        "`// Contributors: <name>: <what they did>; ...`",
        certainty="certain" if licensed else None,
    )
