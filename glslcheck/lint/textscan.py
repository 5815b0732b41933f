"""The text view of a shader for lint rules that need no parse tree: comments and line kinds.

`scan(text)` splits a file into its comments (`//` line comments, with GLSL ES 3.00's
backslash line continuation, and `/* */` block comments spanning lines) and classifies every
line once, so each text rule reads the same answer:

    blank      whitespace only (outside any comment)
    comment    comment text only (also every line a block comment occupies)
    code       code and no comment; preprocessor lines (`#define` ...) are code too
    trailing   code, then a comment on the same line (`x = 1.0; // why`)
    leading    a comment, then code on the same line (`/* why */ x = 1.0;`, or code after a
               block comment's closing `*/`)
    brace      only braces and an optional `;` (`{`, `}`, `};`, `} {`) and no comment
    brace-comment  a brace line with a comment (`{ // shade each light`)
    directive  only a glslcheck directive comment (`// glslcheck: ignore[...]`): such a comment
               is an instruction to the linter, not an explanation, so it counts as no comment

GLSL has no string literals, so `//` and `/*` always open a comment outside one.
"""

from __future__ import annotations

from enum import Enum

from ..base.records import record
from ..base.regexes import compiled


class LineKind(str, Enum):  # noqa: UP042 (StrEnum formats differently in f-strings)
    BLANK = "blank"
    COMMENT = "comment"
    CODE = "code"
    TRAILING = "trailing"
    LEADING = "leading"
    BRACE = "brace"
    BRACE_COMMENT = "brace-comment"
    DIRECTIVE = "directive"

    @property
    def has_code(self) -> bool:
        return self is CODE or self is TRAILING or self is LEADING

    def __str__(self) -> str:
        return self.value


# The members as module globals, for the per-line loops: `LineKind.CODE` is a look-up on the
# enum's class, several times slower than reading a global, and the text rules read several per
# line of every file.
BLANK, COMMENT, CODE, TRAILING, LEADING, BRACE, BRACE_COMMENT, DIRECTIVE = LineKind

# A glslcheck directive inside a comment: `glslcheck: ignore[a, b]` or `glslcheck: ignore-file[a]`.
# Prose such as "checked with glslcheck: ..." is no directive: the verb starts with `ignore` or is
# followed by brackets.
DIRECTIVE_RE = compiled(
    r"glslcheck\s*:\s*(?P<verb>ignore[A-Za-z-]*|[A-Za-z-]+(?=\s*\[))\s*(?:\[(?P<names>[^\]]*)\])?"
)
_ONLY_DIRECTIVES_RE = compiled(r"^\s*(?:glslcheck\s*:\s*[A-Za-z-]*\s*(?:\[[^\]]*\])?[\s,;.]*)+$")
_BRACE_ONLY_RE = compiled(r"^\s*(?:[{}]\s*)+;?\s*$")


@record(frozen=True)
class Comment:
    """One comment: `text` without its delimiters; 1-based position of its first and last char +
    1."""

    text: str
    line: int
    column: int
    end_line: int
    end_column: int
    block: bool  # /* */ rather than //

    @property
    def is_directive(self) -> bool:
        """Whether the comment holds only glslcheck directives (no explanation for a reader)."""
        return bool(_ONLY_DIRECTIVES_RE.match(self.text))


@record
class TextScan:
    """The scan of one file: its lines, comments, each line's kind and its code with comments
    blanked."""

    lines: list[str]
    comments: list[Comment]
    line_kinds: list[LineKind]  # index 0 is line 1
    code_lines: list[str]  # each line with comment characters replaced by spaces (columns kept)

    def kind(self, line: int) -> LineKind:
        return self.line_kinds[line - 1]

    def comments_on(self, line: int) -> list[Comment]:
        return [c for c in self.comments if c.line <= line <= c.end_line]


_COMMENT_START_RE = compiled(r"/[/*]")
_NON_SPACE_RE = compiled(r"\S")  # the characters str.isspace() rejects


def scan(text: str) -> TextScan:
    """Split `text` (line endings already `\\n`) into comments and classified lines.

    Each line is cut at the comment delimiters found by `str.find` and a regex, not read one
    character at a time: scanning is most of the text rules' time on a pre-commit run."""
    lines = text.split("\n")
    if lines and lines[-1] == "" and text.endswith("\n"):
        lines.pop()
    comments: list[Comment] = []
    code_lines: list[str] = []
    # Per line: columns (0-based) of the first code char and of the first real comment char.
    first_code: list[int | None] = [None] * len(lines)
    first_comment: list[int | None] = [None] * len(lines)
    in_directive_comment = [False] * len(lines)

    state = "code"  # "code" | "line" | "block"
    start: tuple[int, int] = (0, 0)
    buf: list[str] = []
    touched: list[int] = []  # lines the current comment occupies

    def close(end_row: int, end_col: int, block: bool) -> None:
        c = Comment("".join(buf), start[0] + 1, start[1] + 1, end_row + 1, end_col + 1, block)
        comments.append(c)
        for row in touched:
            if c.is_directive:
                in_directive_comment[row] = True
            else:
                col = start[1] if row == start[0] else 0
                first = first_comment[row]
                if first is None or col < first:
                    first_comment[row] = col

    find_start = _COMMENT_START_RE.search
    find_code = _NON_SPACE_RE.search
    for row, line in enumerate(lines):
        col = 0
        n = len(line)
        code: list[str] = []  # the line's pieces, comments (delimiters included) as spaces
        if state != "code":
            touched.append(row)
        while col < n:
            if state == "code":
                m = find_start(line, col)
                end = m.start() if m else n
                if first_code[row] is None:
                    c = find_code(line, col, end)
                    if c:
                        first_code[row] = c.start()
                code.append(line[col:end])
                if m is None:
                    col = n
                    continue
                state = "line" if m.group() == "//" else "block"
                start, buf, touched = (row, end), [], [row]
                code.append("  ")
                col = end + 2
            elif state == "line":
                buf.append(line[col:])
                code.append(" " * (n - col))
                col = n
            else:  # block
                end = line.find("*/", col)
                if end < 0:
                    buf.append(line[col:])
                    code.append(" " * (n - col))
                    col = n
                    continue
                buf.append(line[col:end])
                code.append(" " * (end + 2 - col))
                close(row, end + 2, True)
                state = "code"
                col = end + 2
        code_lines.append("".join(code))
        if state == "line":
            if line.endswith("\\"):  # GLSL ES 3.00 line continuation: the comment goes on
                buf.append("\n")
            else:
                close(row, n, False)
                state = "code"
        elif state == "block":
            buf.append("\n")
    if state != "code" and lines:  # an unterminated comment runs to the end of the file
        close(len(lines) - 1, len(lines[-1]), state == "block")

    kinds = [
        _classify(code_lines[i], first_code[i], first_comment[i], in_directive_comment[i])
        for i in range(len(lines))
    ]
    return TextScan(lines, comments, kinds, code_lines)


def _classify(
    code: str, code_col: int | None, comment_col: int | None, directive: bool
) -> LineKind:
    if code_col is None:
        if comment_col is not None:
            return COMMENT
        return DIRECTIVE if directive else BLANK
    if _BRACE_ONLY_RE.match(code):
        return BRACE if comment_col is None else BRACE_COMMENT
    if comment_col is None:
        return CODE
    return LEADING if comment_col < code_col else TRAILING


_IF_RE = compiled(r"^\s*#\s*(ifdef|ifndef|if|elif|else|endif|define|undef)\b\s*(.*)$")
_DEFINED_RE = compiled(r"^!?\s*defined\s*\(?\s*(\w+)\s*\)?\s*$")


def inactive_lines(lines: list[str], defined: set[str] | None = None) -> set[int]:
    """1-based lines inside `#if` branches the preprocessor skips: what it does not compile is
    not linted as code. Decided only where sure (`#ifdef`, `#ifndef`, `#if defined(X)`,
    `#if 0`/`#if 1`, with the macros this file defines or undefines above); any other `#if` is
    taken as active on every branch."""
    names = set(defined or ())
    out: set[int] = set()
    stack: list[tuple[bool, bool, bool]] = []  # (this branch active, a branch was taken, sure)
    for number, line in enumerate(lines, start=1):
        m = _IF_RE.match(line) if "#" in line else None  # most lines: no directive to match
        active = not stack or all(a for a, _, _ in stack)
        if m is None:
            if not active:
                out.add(number)
            continue
        word, rest = m.group(1), m.group(2).split("//")[0].strip()
        if word in ("define", "undef"):
            if active:
                name = rest.split("(")[0].split()[0] if rest.split() else ""
                (names.add if word == "define" else names.discard)(name)
            else:
                out.add(number)
            continue
        if word in ("ifdef", "ifndef", "if"):
            value = _condition(word, rest, names)
            stack.append((value is not False, value is True, value is not None))
        elif word in ("elif", "else") and stack:
            _, taken, sure = stack[-1]
            value = True if word == "else" else _condition("if", rest, names)
            if not sure or value is None:
                stack[-1] = (True, taken, False)
            else:
                stack[-1] = (not taken and value, taken or value, True)
        elif word == "endif" and stack:
            stack.pop()
        if not all(a for a, _, _ in stack) and word not in (
            "if",
            "ifdef",
            "ifndef",
            "elif",
            "else",
        ):
            out.add(number)
    return out


def _condition(word: str, rest: str, names: set[str]) -> bool | None:
    """The value of a `#if`-family condition when sure, else None."""
    if word in ("ifdef", "ifndef"):
        name = rest.split()[0] if rest.split() else ""
        return (name in names) == (word == "ifdef")
    m = _DEFINED_RE.match(rest)
    if m:
        return (m.group(1) in names) != rest.lstrip().startswith("!")
    if rest in ("0", "1"):
        return rest == "1"
    return None
