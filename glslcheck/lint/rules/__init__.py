"""The rule registry: the one table of every lint rule, and the checked view of a rule module.

A rule is a module in this package that declares

    NAME      the stable rule name users write in `--select` and `glslcheck: ignore[...]`;
              it names the pattern, not the fix ("ignore missing-comment" reads naturally)
    PENALTY   points the course deducts per finding: 1 for a course rule, 0 for worth-knowing
    SEVERITY  "warning" for a course rule (PENALTY > 0), "note" for worth-knowing (PENALTY 0)
    CERTAINTY optional, for a course rule: "certain" (the default: the rubric's text makes each
              finding a deduction) or "possible" (a reading of an ambiguous sentence of the
              rubric: a TA may deduct it or not); a finding may say otherwise
              (`Diagnostic.certainty`)
    STANDARD  for a course rule, the coding standard of the rubric it deducts under:
              "comments", "header", "uniforms", "efficiency" or "correctness" (the
              rubric's "correct and stable final product")
    NEEDS     "text" (runs on every file), "ast" (runs only when the engine has a parse tree
              and semantic model for the file) or "suppressions" (runs last, reading which
              suppressions were used)
    READS     optional, for an "ast" rule in a program with compile errors: "functions" (the
              default: it reads types, so it runs on the functions that check), "names" (names
              and scopes only: it runs on every function) or "program" (it needs the whole
              program to be right, so it does not run at all)
    a docstring: one summary line, then the sections `## What it does`, `## Why is this bad?`,
              `## Example` and `## Use instead` (docs/rules.md and `glslcheck rule` show it)
    check(ctx: LintContext) -> Iterable[Diagnostic]   (`glslcheck.lint.engine.LintContext`);
              a finding's message, location, help and notes come from the Diagnostic, its rule,
              severity and penalty from the module (the engine sets them); a course rule marks
              advice that costs nothing with `severity="note"`

and has a row in `RULE_TABLE` below. Nothing else registers a rule.
"""

from __future__ import annotations

import importlib
from functools import cache
from types import ModuleType

from ...base.records import record

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Callable, Iterable

# Every rule: (NAME, module in this package). The order is the order docs and `--all` list them.
RULE_TABLE: tuple[tuple[str, str], ...] = (
    ("compile-error", "compile_error"),
    ("missing-comment", "missing_comment"),
    ("missing-header", "missing_header"),
    ("incomplete-header", "incomplete_header"),
    ("missing-credit", "missing_credit"),
    ("unused-suppression", "unused_suppression"),
    ("uniform-outside-mainimage", "uniform_outside_mainimage"),
    ("length-comparison", "length_comparison"),
    ("sqrt-comparison", "sqrt_comparison"),
    ("squared-square-root", "squared_square_root"),
    ("pow-small-exponent", "pow_small_exponent"),
    ("pow-negative-base", "pow_negative_base"),
    ("unguarded-sqrt", "unguarded_sqrt"),
    ("repeated-expression", "repeated_expression"),
    ("repeated-across-calls", "repeated_across_calls"),
    ("loop-invariant", "loop_invariant"),
    ("cell-search-loop", "cell_search_loop"),
    ("branch-replaceable", "branch_replaceable"),
    ("normalize-known-length", "normalize_known_length"),
    ("length-computed-twice", "length_computed_twice"),
    ("unit-length", "unit_length"),
    ("no-op-arithmetic", "no_op_arithmetic"),
    ("hand-written-builtin", "hand_written_builtin"),
    ("unreachable-code", "unreachable_code"),
    ("unset-array-elements", "unset_array_elements"),
    ("out-parameter-read", "out_parameter_read"),
    ("uninitialized-read", "uninitialized_read"),
    ("unused-variable", "unused_variable"),
    ("unused-function", "unused_function"),
)

SECTIONS = ("What it does", "Why is this bad?", "Example", "Use instead")
SEVERITIES = {"error": "compile error", "warning": "course rule", "note": "worth knowing"}
CERTAINTIES = ("certain", "possible")
STANDARDS = ("comments", "header", "uniforms", "efficiency", "correctness")
NEEDS = ("text", "ast", "suppressions")
READS = ("functions", "names", "program")


@record(frozen=True)
class Rule:
    """A rule module's declarations, checked."""

    name: str
    penalty: int
    severity: str
    needs: str
    summary: str  # the docstring's first line
    doc: str  # the docstring after the summary line (markdown)
    check: Callable[..., Iterable]
    module: ModuleType
    reads: str = "functions"
    certainty: str = "certain"
    standard: str | None = None  # a course rule's coding standard (STANDARDS)

    @property
    def kind(self) -> str:
        return SEVERITIES[self.severity]

    def section(self, title: str) -> str:
        return doc_sections(self.doc).get(title, "")


def doc_sections(doc: str) -> dict[str, str]:
    """`## Title` sections of a rule docstring: title -> body (stripped). What splitting at
    `^## (.+?)\\s*$` (multi-line) gives, found line by line: the regex engine would scan every
    character of every rule's docstring at each lint's start."""
    sections: dict[str, str] = {}
    title = None
    body: list[str] = []
    for line in doc.split("\n"):
        if line.startswith("## ") and len(line) > 3:
            if title is not None:
                sections[title] = "\n".join(body).strip()
            rest = line[3:]
            title = rest.rstrip() or rest[0]  # `.+?` takes at least one character
            body = []
        elif title is not None:
            body.append(line)
    if title is not None:
        sections[title] = "\n".join(body).strip()
    return sections


def _load(name: str, module_name: str) -> Rule:
    mod = importlib.import_module(f"{__name__}.{module_name}")
    where = f"{mod.__name__}"
    doc = (mod.__doc__ or "").strip()
    summary, _, body = doc.partition("\n")
    problems = []
    if getattr(mod, "NAME", None) != name:
        problems.append(f"NAME is {getattr(mod, 'NAME', None)!r}, the table says {name!r}")
    penalty = getattr(mod, "PENALTY", None)
    severity = getattr(mod, "SEVERITY", None)
    if not isinstance(penalty, int) or penalty < 0:
        problems.append(f"PENALTY must be an int >= 0, not {penalty!r}")
    if severity not in SEVERITIES:
        problems.append(f"SEVERITY must be one of {', '.join(SEVERITIES)}, not {severity!r}")
    elif isinstance(penalty, int) and (severity == "warning") != (penalty > 0):
        problems.append(
            "a course rule (PENALTY > 0) is a warning, a worth-knowing one (PENALTY 0) a note"
        )
    if getattr(mod, "NEEDS", None) not in NEEDS:
        problems.append(f"NEEDS must be one of {', '.join(NEEDS)}")
    if getattr(mod, "CERTAINTY", "certain") not in CERTAINTIES:
        problems.append(f"CERTAINTY must be one of {', '.join(CERTAINTIES)}")
    standard = getattr(mod, "STANDARD", None)
    if isinstance(penalty, int) and penalty > 0 and standard not in STANDARDS:
        problems.append(f"a course rule declares STANDARD, one of {', '.join(STANDARDS)}")
    elif not (isinstance(penalty, int) and penalty > 0) and standard is not None:
        problems.append("only a course rule (PENALTY > 0) declares a STANDARD")
    if getattr(mod, "READS", "functions") not in READS:
        problems.append(f"READS must be one of {', '.join(READS)}")
    if not callable(getattr(mod, "check", None)):
        problems.append("no check(ctx) function")
    sections = doc_sections(body)  # once, not once per section name: this runs at every start-up
    missing = [s for s in SECTIONS if s not in sections]
    if missing:
        problems.append(f"the docstring lacks the section(s) {', '.join(missing)}")
    if problems:
        raise TypeError(f"lint rule {where}: " + "; ".join(problems))
    assert isinstance(penalty, int) and isinstance(severity, str)  # else a problem above
    return Rule(
        name,
        penalty,
        severity,
        mod.NEEDS,
        summary.strip(),
        body.strip(),
        mod.check,
        mod,
        getattr(mod, "READS", "functions"),
        getattr(mod, "CERTAINTY", "certain"),
        standard,
    )


@cache
def all_rules() -> dict[str, Rule]:
    """Every rule by name, in table order (modules are imported and checked on first use)."""
    return {name: _load(name, module) for name, module in RULE_TABLE}


def rule_names() -> frozenset[str]:
    return frozenset(name for name, _ in RULE_TABLE)


def get_rule(name: str) -> Rule | None:
    return all_rules().get(name)
