"""Grading a class (`glslcheck grade`): for each team's hand-in, the tab files and whether they
compile, the course's deductions, renders at chosen times, and how close each is to a
reference solution; out as a terminal table, CSV, JSON and one HTML page.

    from glslcheck.verification.grade import Options, from_paths, grade_class, read_roster
    grades = grade_class(read_roster("roster.csv"), Options(times=(0.0, 1.7)),
                         reference="lab_shaders/07_final")
    grades[0].verdict, grades[0].points, grades[0].deductions

Modules: `submissions` (folders, files, git branches, the roster; where the tab files are),
`grading` (one submission), `closeness` (the verdict scale and what one render shows),
`records` (the data), `run` (the class, in parallel), `outputs` (table, CSV, JSON), `page`
(HTML), `images` (the PNG files of --images).
"""

from .closeness import CLOSE, CLOSE_PSNR_DB, DIFFERENT, SAME, VERDICTS
from .grading import (
    DEFAULT_SIZE,
    DEFAULT_TIMES,
    Options,
    Reference,
    grade_submission,
    render_reference,
)
from .images import write_images
from .outputs import CSV_COLUMNS, ranked, table, to_csv, to_json
from .page import page_html
from .records import SCHEMA_VERSION, Deduction, Frame, Grade, SourceError
from .run import GradeProgress, grade_class
from .submissions import (
    Submission,
    SubmissionError,
    find_tab_files,
    from_paths,
    read_roster,
    submission_shader,
)

__all__ = [
    "CLOSE",
    "CLOSE_PSNR_DB",
    "CSV_COLUMNS",
    "DEFAULT_SIZE",
    "DEFAULT_TIMES",
    "DIFFERENT",
    "SAME",
    "SCHEMA_VERSION",
    "VERDICTS",
    "Deduction",
    "Frame",
    "Grade",
    "GradeProgress",
    "Options",
    "Reference",
    "SourceError",
    "Submission",
    "SubmissionError",
    "find_tab_files",
    "from_paths",
    "grade_class",
    "grade_submission",
    "page_html",
    "ranked",
    "read_roster",
    "render_reference",
    "submission_shader",
    "table",
    "to_csv",
    "to_json",
    "write_images",
]
