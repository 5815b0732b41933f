"""What the preprocessor hands the later stages: the expanded text (`PPResult`) with the map from
its offsets back to the user's files, the comments, the macros, and the directives' data.
"""

from __future__ import annotations

from bisect import bisect_right

from ...base.diagnostics import Diagnostic, Location
from ...base.records import field, record
from .units import Unit

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from .units import Comment


@record
class Macro:
    """A macro: `params` is None for an object-like macro; `body` holds the token texts."""

    name: str
    params: tuple[str, ...] | None
    body: tuple[str, ...]
    loc: Location | None = None  # where it was defined; None for a predefined macro
    predefined: bool = False
    tokens: list = field(default_factory=list, repr=False, compare=False)

    @property
    def dynamic(self) -> bool:  # __LINE__ and __FILE__
        return self.name in ("__LINE__", "__FILE__")


@record
class Segment:
    """A piece of the expanded text, from `out_start` on: text copied from `unit` (from `start`), or
    the expansion of the macro use `unit[start:end]`."""

    out_start: int
    unit: Unit
    start: int  # stripped offset; for a macro use, the start of the use
    end: int = -1  # -1: linear copy of the text; otherwise the end of the macro use


@record(slots=False)
class PPResult:
    """The preprocessed program and everything the later stages need from the directives."""

    text: str
    version: int | None
    extensions: list[tuple[str, str, Location]]
    pragmas: list[tuple[str, Location]]
    comments: list[Comment]
    macros: dict[str, Macro]
    diagnostics: list[Diagnostic] = field(default_factory=list)
    _seg_starts: list[int] = field(default_factory=list, repr=False)
    _segs: list[Segment] = field(default_factory=list, repr=False)

    def _seg(self, offset: int) -> tuple[Segment, int]:
        i = bisect_right(self._seg_starts, offset) - 1
        seg = self._segs[max(i, 0)]
        return seg, offset - seg.out_start

    def _seg_len(self, seg: Segment) -> int:
        i = bisect_right(self._seg_starts, seg.out_start)
        return (
            self._seg_starts[i] if i < len(self._seg_starts) else len(self.text)
        ) - seg.out_start

    def locate(self, offset: int) -> Location:
        """The user's file, line and column of `offset` in `text`: a point for copied text, the
        span of the whole (outermost) macro use for text that came from an expansion."""
        if not self._segs:
            return Location("<empty>", 1, 1)
        seg, delta = self._seg(offset)
        if seg.end >= 0:
            return seg.unit.span(seg.start, seg.end)
        return seg.unit.point(seg.start + delta)

    def locate_span(self, start: int, end: int) -> Location:
        """The span in the user's file of `text[start:end]` (a point when end <= start)."""
        if end <= start or not self._segs:
            return self.locate(start)
        # _seg and _seg_len, inlined: the parser locates every AST node through here. The
        # segments' starts increase strictly (each holds some text), from 0.
        starts = self._seg_starts
        i = bisect_right(starts, start) - 1
        seg = self._segs[i]
        if (
            seg.end < 0
            and i >= 0
            and end <= (starts[i + 1] if i + 1 < len(starts) else len(self.text))
        ):
            # Both ends in one copied piece of text: the common case of a token.
            shift = seg.start - seg.out_start
            return seg.unit.span(start + shift, end + shift)
        first = self.locate(start)
        last_seg, delta = self._seg(end - 1)
        if last_seg.end >= 0:
            last = last_seg.unit.span(last_seg.start, last_seg.end)
            return first.span_to(last)
        p = last_seg.unit.point(last_seg.start + delta)
        return Location(first.path, first.line, first.column, p.line, p.column + 1)
