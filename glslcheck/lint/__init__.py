"""The course linter: Lab 4 coding-standard rules over Shadertoy GLSL, and their reports.

    lint_paths(paths, config_overrides=None) -> LintResult(findings, files)
    lint_source(source, config=None, shader=None, ast=None, model=None) -> list[Finding]

The package owns: the engine (`engine`: files, rules, phases, suppression), configuration
(`config`), suppression comments (`suppress`), the text view rules share (`textscan`), the
rule registry and one module per rule (`rules/`), the output formats (`report`), and the
fixes rules offer (`fixes/`: edits of the source text, and the files they are written to; whether
a fix keeps the picture is proven by rendering, in verification/fix_proof.py).
"""

from .config import LintConfig
from .engine import Finding, LintContext, LintResult, lint_paths, lint_source
from .rules import Rule, all_rules, get_rule

__all__ = [
    "Finding",
    "LintConfig",
    "LintContext",
    "LintResult",
    "Rule",
    "all_rules",
    "get_rule",
    "lint_paths",
    "lint_source",
]
