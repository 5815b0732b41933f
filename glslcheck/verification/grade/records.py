"""What grading one submission finds, as plain data: pickled back from the worker processes,
turned into the terminal table, the CSV, the JSON (SCHEMA_VERSION; docs/grading.md documents
every field) and the HTML page."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from .closeness import VERDICTS

SCHEMA_VERSION = 1
GRADED, FAILED = "graded", "failed"
CERTAIN, POSSIBLE = "certain", "possible"


@dataclass
class Deduction:
    """A lint finding that costs points (the rubric's -1 per instance), where the team's file has
    it."""

    rule: str
    message: str
    file: str  # as the team names it: relative to the top of their repository or folder
    line: int
    column: int
    penalty: int
    certainty: str = CERTAIN  # "possible" when the linter says the rule may be wrong here
    code: str = ""  # the source line

    def to_json(self) -> dict:
        return {
            "rule": self.rule,
            "message": self.message,
            "file": self.file,
            "line": self.line,
            "column": self.column,
            "penalty": self.penalty,
            "certainty": self.certainty,
            "code": self.code,
        }


@dataclass
class SourceError:
    """A compile error (or a render's runtime error) at file:line:col of the team's file."""

    message: str
    file: str = ""
    line: int = 0
    column: int = 0
    code: str = ""

    def __str__(self) -> str:
        where = f"{self.file}:{self.line}:{self.column}: " if self.file else ""
        return f"{where}{self.message}"

    def to_json(self) -> dict:
        return {
            "file": self.file or None,
            "line": self.line or None,
            "column": self.column or None,
            "message": self.message,
            "code": self.code,
        }


@dataclass
class Frame:
    """One render of the submission at one time, and how it compares with the reference's."""

    time: float
    nonfinite_pixels: int
    flat: bool
    thumbnail: bytes = b""  # PNG, base/images.THUMBNAIL_WIDTH across
    render: bytes = b""  # PNG at the graded size (Options.full_images)
    verdict: str | None = None  # closeness.VERDICTS; None without a reference
    psnr_db: float | None = None  # math.inf for identical pictures
    max_abs_error: float | None = None
    mean_abs_error: float | None = None
    over_tolerance: float | None = None  # share of pixels off by more than verify's 2/255
    diff_thumbnail: bytes = b""
    diff: bytes = b""  # the diff image at the graded size (Options.full_images)
    engine: str = ""  # the engine that rendered it (Program.engine: "numpy", "compiled lanes8")

    def to_json(self) -> dict:
        psnr = self.psnr_db
        return {
            "time": self.time,
            "engine": self.engine or None,
            "nonfinite_pixels": self.nonfinite_pixels,
            "flat": self.flat,
            "verdict": self.verdict,
            "psnr_db": None if psnr is None or math.isinf(psnr) else round(psnr, 3),
            "max_abs_error": self.max_abs_error,
            "mean_abs_error": self.mean_abs_error,
            "over_tolerance": self.over_tolerance,
        }


@dataclass
class Grade:
    """Everything grade says about one team's submission."""

    team: str
    source: str
    branch: str | None = None
    contributors: list[str] = field(default_factory=list)
    status: str = GRADED
    reason: str = ""  # why it could not be graded (status "failed")
    shader: str = ""  # the folder or file graded, as the team names it
    tabs: list[str] = field(default_factory=list)
    compiles: bool | None = None
    errors: list[SourceError] = field(default_factory=list)
    deductions: list[Deduction] = field(default_factory=list)
    suppressions: list[str] = field(default_factory=list)  # "file:line: rules" the team silenced
    frames: list[Frame] = field(default_factory=list)
    verdict: str | None = None  # the worst frame's, None without a reference or renders
    animates: bool | None = None
    problems: list[str] = field(default_factory=list)  # what the renders show by themselves
    seconds: float = 0.0
    images: dict[str, str] = field(default_factory=dict)  # written files, by frame and kind

    @property
    def certain_points(self) -> int:
        return sum(d.penalty for d in self.deductions if d.certainty != POSSIBLE)

    @property
    def possible_points(self) -> int:
        return sum(d.penalty for d in self.deductions if d.certainty == POSSIBLE)

    @property
    def points(self) -> int:
        return self.certain_points + self.possible_points

    def rank_key(self) -> tuple:
        """Best first: graded before failed, then the closest picture on the verdict scale,
        then the fewest points deducted (certain ones first), then fewer render problems, then
        the higher worst-frame PSNR, then the team's name."""
        place = VERDICTS.index(self.verdict) if self.verdict in VERDICTS else len(VERDICTS)
        return (
            self.status != GRADED,
            place,
            self.certain_points,
            self.possible_points,
            len(self.problems),
            -self.min_psnr_db if self.min_psnr_db is not None else math.inf,
            self.team.lower(),
        )

    @property
    def min_psnr_db(self) -> float | None:
        """The worst frame's PSNR against the reference (None without one)."""
        values = [f.psnr_db for f in self.frames if f.psnr_db is not None]
        return min(values) if values else None

    def to_json(self) -> dict:
        return {
            "team": self.team,
            "contributors": list(self.contributors),
            "source": self.source,
            "branch": self.branch,
            "status": self.status,
            "reason": self.reason or None,
            "shader": self.shader or None,
            "tabs": list(self.tabs),
            "compiles": self.compiles,
            "errors": [e.to_json() for e in self.errors],
            "deductions": [d.to_json() for d in self.deductions],
            "points": {
                "certain": -self.certain_points,
                "possible": -self.possible_points,
                "total": -self.points,
            },
            "suppressions": list(self.suppressions),
            "frames": [f.to_json() for f in self.frames],
            "verdict": self.verdict,
            "animates": self.animates,
            "problems": list(self.problems),
            "seconds": round(self.seconds, 3),
            "images": dict(self.images),
        }
