"""Locations and diagnostics: the one location type and the data every stage reports.

Detection is separate from reporting: a stage produces `Diagnostic` values (rule, message,
location, severity, help); `format_text` turns one into the compiler-style text a user reads,
with the source line and a caret. Every `Location` points into the user's own file, also after
preprocessing and the Shadertoy wrapper.
"""

from __future__ import annotations

from .records import field, field_names, record

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Callable


@record(frozen=True)
class Location:
    """A span in a user's file: 1-based lines and columns, end exclusive-ish (points at the last
    char + 1)."""

    __slots__ = ("_pending",)  # a `pending_location`'s span, until it is computed

    path: str
    line: int
    column: int
    end_line: int | None = None
    end_column: int | None = None

    def __str__(self) -> str:
        return f"{self.path}:{self.line}:{self.column}"

    def start(self) -> Location:
        return Location(self.path, self.line, self.column)

    def span_to(self, other: Location) -> Location:
        """The span from this location's start to `other`'s end."""
        return Location(
            self.path,
            self.line,
            self.column,
            other.end_line if other.end_line is not None else other.line,
            other.end_column if other.end_column is not None else other.column,
        )


class _PendingLocation(Location):
    """A `Location` not computed yet (see `pending_location`): its fields' slots are unset, so
    the first read of one comes to `__getattr__`, which computes them, stores them and turns the
    object into a plain `Location` (the same slots: `__class__` can be assigned). Equality,
    hashing, `repr`, `str` and pickling compute it first, so a pending location is everywhere
    what the `Location` it stands for is."""

    __slots__ = ()

    def __getattr__(self, name: str):
        # Reached only when a slot is unset: before the location is computed.
        if name not in _FIELDS:
            raise AttributeError(f"'Location' object has no attribute {name!r}")
        return getattr(self._compute(), name)

    def _compute(self) -> Location:
        locate, start, end = self._pending
        loc = locate(start, end)
        for name, set_slot in _FIELD_SETTERS:
            set_slot(self, getattr(loc, name))
        _del_pending(self)
        object.__setattr__(self, "__class__", Location)
        return self

    def __eq__(self, other):
        return self._compute() == other

    def __hash__(self) -> int:
        return hash(self._compute())

    def __reduce__(self):
        return self._compute().__reduce__()

    def __repr__(self) -> str:
        return repr(self._compute())


_FIELDS = frozenset(field_names(Location))
_FIELD_SETTERS = tuple((name, Location.__dict__[name].__set__) for name in field_names(Location))
_new_pending = _PendingLocation.__new__
_set_pending = Location.__dict__["_pending"].__set__
_del_pending = Location.__dict__["_pending"].__delete__


def pending_location(locate: Callable[[int, int], Location], start: int, end: int) -> Location:
    """`locate(start, end)`, computed when one of its fields is first read (the parser
    locates every node's span, and a lint reads only some of them)."""
    loc = _new_pending(_PendingLocation)
    _set_pending(loc, (locate, start, end))
    return loc


@record
class Diagnostic:
    """One finding: a syntax error, a type error, or a lint rule hit."""

    message: str
    loc: Location | None
    severity: str = "error"  # "error" | "warning" | "note"
    rule: str = "syntax"
    help: str | None = None
    notes: list[Diagnostic] = field(default_factory=list)
    # a lint deduction's certainty when it differs from its rule's ("certain" or "possible")
    certainty: str | None = None


class GlslError(Exception):
    """Raised by a stage that cannot go on; carries the diagnostics to report (exit 1)."""

    def __init__(self, diagnostics: list[Diagnostic] | Diagnostic):
        if isinstance(diagnostics, Diagnostic):
            diagnostics = [diagnostics]
        self.diagnostics = diagnostics
        super().__init__("; ".join(d.message for d in diagnostics))

    def __reduce__(self):  # pickled by its diagnostics (errors come back from render workers)
        return (type(self), (self.diagnostics,))


class InputError(Exception):
    """A missing, unreadable or undecodable input, or bad usage (exit 2)."""


SOURCE_LINES: dict[str, list[str]] = {}  # path -> its lines, for quoting them in messages


def register_source(path: str, text: str) -> None:
    """Remember a file's text so diagnostics can quote its lines."""
    SOURCE_LINES[path] = text.splitlines()


def source_line(path: str, line: int) -> str | None:
    lines = SOURCE_LINES.get(path)
    if lines is None or not (1 <= line <= len(lines)):
        return None
    return lines[line - 1]


# A quoted source line longer than this is cut to a window around the span: a finding on a
# minified one-line shader must not print the whole file once per finding.
MAX_QUOTE = 400


def printable(text: str) -> str:
    """`text` with every control character but tab written as an escape (`\\x1b`, `\\u202e`): a
    shader's comment or a file name must not move the cursor, recolour the terminal, reorder
    what is shown (bidi controls) or start a new line that reads as another finding."""
    if text.isprintable():
        return text
    out = []
    for ch in text:
        if ch == "\t" or ch.isprintable():
            out.append(ch)
        else:
            code = ord(ch)
            out.append(
                f"\\x{code:02x}"
                if code < 0x100
                else f"\\u{code:04x}"
                if code < 0x10000
                else f"\\U{code:08x}"
            )
    return "".join(out)


def _quote(text: str, loc: Location) -> tuple[str, str]:
    """The source line as shown (printable, cut to MAX_QUOTE characters around the span with
    `...` at a cut) and the caret line under it: spaces (tabs kept, so the caret aligns), then
    ^~~~ under the span on the first line."""
    col = max(loc.column, 1)
    if loc.end_line == loc.line and loc.end_column and loc.end_column > col:
        width = loc.end_column - col
    else:
        width = 1
    start, end, before, after = 0, len(text), "", ""
    if len(text) > MAX_QUOTE:
        start = max(0, min(col - 1 - MAX_QUOTE // 4, len(text) - MAX_QUOTE))
        end = start + MAX_QUOTE
        before, after = ("..." if start else ""), ("..." if end < len(text) else "")
    head = [printable(ch) for ch in text[start : col - 1]]
    prefix = " " * len(before) + "".join(ch if ch == "\t" else " " * len(ch) for ch in head)
    span = text[col - 1 : min(col - 1 + width, end)]
    past_end = (
        0 if after else width - len(text[col - 1 : col - 1 + width])
    )  # a span beyond the line
    shown = before + printable(text[start:end]) + after
    return shown, prefix + "^" + "~" * max(len(printable(span)) + past_end - 1, 0)


def format_text(d: Diagnostic, show_rule: bool = False) -> str:
    """`path:line:col: severity: message`, the source line, a caret, and `help:`."""
    head = f"{printable(str(d.loc))}: " if d.loc else ""
    kind = f"{d.rule}" if show_rule else d.severity
    out = [f"{head}{kind}: {printable(d.message)}"]
    if d.loc is not None:
        text = source_line(d.loc.path, d.loc.line)
        if text is not None:
            shown, caret = _quote(text.rstrip("\r\n"), d.loc)
            out.append("    " + shown)
            out.append("    " + caret)
    for n in d.notes:
        out.append(format_text(n))
    if d.help:
        out.append(f"  help: {printable(d.help)}")
    return "\n".join(out)
