"""No comment credits the starter framework or the sources code was borrowed from.

## What it does
Looks through every comment of the file for a credit: a mention of the starter framework or the
instructor (`starter`, `framework`, `Buckstein`), a credit (`credit`, `adapted from`,
`based on`, `borrowed from`, `inspired by`, `source:`, `reference:`, `thanks to`) or a link
(`https://...`, `www....`). One finding per file, at line 1, when there is none.

This is a note, not a deduction: the linter cannot tell whether anything was borrowed. But the
course starter code is in every lab, and an uncited borrowing costs far more than a point.

## Why is this bad?
The course's coding standards: "Credit and provide a link to source materials (books, websites,
forums, etc.) in your work wherever code from there is borrowed, and credit your instructor for
the starter framework, even if it is adapted, modified or reworked (failure to cite sources and
claiming source materials as one's own results in an instant final grade of F in the course)."

## Example
```glsl
// Image.glsl: lit spheres (Lab 4)
// Contributors: Ana Ruiz: lighting; Ben Li: optimization
```

## Use instead
```glsl
// Image.glsl: lit spheres (Lab 4)
// Contributors: Ana Ruiz: lighting; Ben Li: optimization
// Starter framework by Daniel S. Buckstein (GPR-200); ray-sphere test adapted from
// "Ray Tracing in One Weekend", https://raytracing.github.io/
```
"""

from __future__ import annotations

import re

from ...base.diagnostics import Diagnostic
from ...base.regexes import compiled

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

    from ..engine import LintContext

NAME = "missing-credit"
PENALTY = 0
SEVERITY = "note"
NEEDS = "text"

_CREDIT = (
    r"\b(?:starter|framework|buckstein|credits?|credited|adapted|based\s+on|borrowed|courtesy"
    r"|inspired\s+by|derived\s+from|taken\s+from|thanks?\s+to|acknowledge?ments?"
    r"|(?:sources?|references?|refs?|citations?|cited?)\s*:)"
    r"|https?://|\bwww\."
)
CREDIT_RE = compiled(_CREDIT, re.I)
_CREDIT_LOWER_RE = compiled(_CREDIT)  # the same, case-sensitive: for lowercased ASCII text


def has_credit(text: str) -> bool:
    """Whether `text` holds a credit (`CREDIT_RE`). ASCII text is searched lowercased with the
    case-sensitive pattern: the same answer (the pattern's letters are lowercase ASCII, and in
    ASCII text `re.I` folds only A-Z), about four times faster, since case-insensitive matching
    folds each character once for every alternative it tries."""
    if text.isascii():
        return _CREDIT_LOWER_RE.search(text.lower()) is not None
    return CREDIT_RE.search(text) is not None


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    if not ctx.source.text.strip():
        return
    if any(has_credit(c.text) for c in ctx.comments if not c.is_directive):
        return
    yield Diagnostic(
        "no comment credits the starter framework or the sources code was borrowed from",
        ctx.location(1, 1),
        help="credit the instructor's starter framework and link every borrowed source, e.g. "
        "`// starter framework: Daniel S. Buckstein; sphere test adapted from <link>`",
    )
