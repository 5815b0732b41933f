"""Applying fixes' edits to a text, and following its lines from the old text to the new."""

from __future__ import annotations

from bisect import bisect_right

from . import Edit, Fix

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Callable, Iterable, Sequence


class EditError(ValueError):
    """Edits that cannot be applied: out of the text, or two of them changing the same text."""


def line_starts(text: str) -> list[int]:
    """The offset of each line's first character (index 0 is line 1)."""
    starts = [0]
    i = text.find("\n")
    while i >= 0:
        starts.append(i + 1)
        i = text.find("\n", i + 1)
    return starts


def offset(starts: list[int], text: str, line: int, column: int) -> int:
    """The offset of 1-based (line, column); EditError outside the text."""
    if not 1 <= line <= len(starts):
        raise EditError(f"line {line} is outside the text ({len(starts)} lines)")
    start = starts[line - 1]
    end = starts[line] - 1 if line < len(starts) else len(text)
    if not 1 <= column <= end - start + 1:
        raise EditError(f"column {column} is outside line {line}")
    return start + column - 1


def _spans(text: str, edits: Iterable[Edit]) -> list[tuple[int, int, Edit]]:
    """(start offset, end offset, edit) of each distinct edit, in the order they are made:
    by place, insertions before a span at one place, else in the order given."""
    starts = line_starts(text)
    spans: list[tuple[int, int, int, Edit]] = []
    seen: set[Edit] = set()
    for order, e in enumerate(edits):
        if e in seen:
            continue
        seen.add(e)
        a, b = (
            offset(starts, text, e.line, e.column),
            offset(starts, text, e.end_line, e.end_column),
        )
        if b < a:
            raise EditError(f"an edit ends before it starts at {e.line}:{e.column}")
        spans.append((a, b, order, e))
    spans.sort(key=lambda s: (s[0], s[1] != s[0], s[2]))
    return [(a, b, e) for a, b, _, e in spans]


def apply_edits(text: str, edits: Iterable[Edit]) -> str:
    """`text` with `edits` made (identical edits once; insertions at one place in the order
    given, `item` insertions joined with ", "). EditError when two edits change the same text."""
    out: list[str] = []
    pos = 0
    previous_item_at = -1
    for a, b, e in _spans(text, edits):
        if a < pos:
            raise EditError(f"two fixes change the text at {e.line}:{e.column}")
        out.append(text[pos:a])
        if e.item and previous_item_at == a:
            out.append(", ")
        out.append(e.text)
        if e.item:
            previous_item_at = a
        pos = b
    out.append(text[pos:])
    return "".join(out)


def position_map(text: str, edits: Iterable[Edit]) -> Callable[[int, int], tuple[int, int]]:
    """Where a (line, column) of `text` is once `edits` are made: text after an insertion point
    follows the inserted text; a place inside a replaced span goes to the start of its
    replacement."""
    spans = _spans(text, edits)
    new = apply_edits(text, [e for _, _, e in spans])
    old_starts, new_starts = line_starts(text), line_starts(new)
    moves: list[tuple[int, int, int, int]] = []  # old start, old end, new start, shift after
    shift = 0
    previous_item_at = -1
    for a, b, e in spans:
        joined = 2 if e.item and previous_item_at == a else 0
        if e.item:
            previous_item_at = a
        moves.append((a, b, a + shift + joined, shift + joined + len(e.text) - (b - a)))
        shift = moves[-1][3]

    def where(line: int, column: int) -> tuple[int, int]:
        o = offset(old_starts, text, line, column)
        n = o
        for a, b, start, after in moves:
            if b <= o:  # before o (an insertion at o too: the old text follows it)
                n = o + after
                continue
            if a <= o:
                n = start
            break
        i = bisect_right(new_starts, n) - 1
        return i + 1, n - new_starts[i] + 1

    return where


def apply_fixes(text: str, fixes: Sequence[Fix]) -> str:
    return apply_edits(text, [e for f in fixes for e in f.edits])


def line_map(old: str, new: str) -> dict[int, int]:
    """new line -> old line for the lines of `new` that come from a line of `old` (unchanged,
    or changed in place); a line a fix added has no entry."""
    from difflib import SequenceMatcher

    a, b = old.split("\n"), new.split("\n")
    found: dict[int, int] = {}
    for tag, i1, i2, j1, j2 in SequenceMatcher(None, a, b, autojunk=False).get_opcodes():
        if tag == "equal" or (tag == "replace" and i2 - i1 == j2 - j1):
            for k in range(j2 - j1):
                found[j1 + k + 1] = i1 + k + 1
        elif tag == "replace":  # a statement rewritten over more or fewer lines: its last lines
            for k in range(min(i2 - i1, j2 - j1)):
                found[j2 - k] = i2 - k
    return found
