"""The lint engine: which files, which rules, in which order; findings out, nothing written.

    lint_paths(paths, config_overrides) -> LintResult      files and folders, as the CLI takes them
    lint_source(source, config, ...)     -> list[Finding]  one file

For each file the engine scans the text once (`textscan`), builds a `LintContext`, runs the
enabled rules in phases by their `NEEDS` — "text", then "ast" (only when the file has a parse
tree: `ctx.ast is not None`), then "suppressions" — turns each `Diagnostic` a rule yields into
a `Finding` (the rule's name, severity and penalty), and drops the findings a
`glslcheck: ignore[...]` comment silences. Reporting is `report.py`'s job; the engine never
modifies a file.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Iterable, Mapping, Sequence

from ..diagnostics import Diagnostic, Location, register_source, source_line
from ..sources import Shader, Source, check_path, find_shaders
from .config import COMMAND_LINE, ConfigFinder, LintConfig, apply_overrides
from .rules import Rule, all_rules, rule_names
from .suppress import Suppression, find_suppressions, is_suppressed
from .textscan import Comment, LineKind, TextScan, scan

PHASES = ("text", "ast", "suppressions")


@dataclass(slots=True)
class Finding(Diagnostic):
    """A lint rule hit: a Diagnostic (rule = rule NAME, loc in the user's file) and its penalty."""

    penalty: int = 0

    @property
    def path(self) -> str:
        return self.loc.path if self.loc is not None else ""


@dataclass(slots=True)
class LintResult:
    """What one lint run found: every unsuppressed finding and how many files were linted."""

    findings: list[Finding]
    files: int
    paths: list[str] = field(default_factory=list)  # the linted files, in order

    @property
    def penalty(self) -> int:
        return sum(f.penalty for f in self.findings)


@dataclass(slots=True)
class LintContext:
    """Everything a rule's check(ctx) may read about one file."""

    source: Source
    lines: list[str]
    line_kinds: list[LineKind]  # index 0 is line 1
    comments: list[Comment]
    config: LintConfig
    scan: TextScan
    shader: Shader | None = None  # the shader the file belongs to (its other tabs), when known
    ast: Any = None  # the parse tree (NEEDS = "ast" rules run only when it is not None)
    model: Any = None  # the semantic model (scopes, types) of `ast`
    suppressions: list[Suppression] = field(default_factory=list)
    rules_run: frozenset[str] = frozenset()  # rules whose findings were checked for suppression
    known_rules: frozenset[str] = frozenset()

    @property
    def path(self) -> str:
        return self.source.path

    def location(
        self,
        line: int,
        column: int | None = None,
        end_line: int | None = None,
        end_column: int | None = None,
    ) -> Location:
        """A span in this file. Defaults: from the line's first non-blank char to its end."""
        text = self.lines[line - 1] if 1 <= line <= len(self.lines) else ""
        if column is None:
            stripped = len(text) - len(text.lstrip())
            column = stripped + 1 if text.strip() else 1
        if end_line is None:
            end_line = line
        if end_column is None:
            end_text = self.lines[end_line - 1] if 1 <= end_line <= len(self.lines) else ""
            end_column = max(len(end_text.rstrip()) + 1, column + 1 if end_line == line else 1)
        return Location(self.path, line, column, end_line, end_column)


def syntax_tree(source: Source, shader: Shader | None) -> tuple[Any, Any]:
    """The parse tree and semantic model that NEEDS = "ast" rules read, or (None, None).

    A pass tab (Image, Buffer A..D, or a plain GLSL file) is parsed and checked as Shadertoy
    compiles it: Common first, then the tab. A Common tab is linted inside the first pass that
    includes it (Image, else a Buffer), so its functions are seen with their callers; alone
    when the shader has no pass tab. The tree covers every file of the program: AST rules report
    only nodes whose `loc.path` is the linted file. A program is parsed and checked once for all
    its files (a small cache keyed by the texts). A file that does not parse or check gets
    (None, None): its errors are `glslcheck check`'s to report, and the text rules still run.
    """
    if shader is None:
        return None, None
    tab = source.tab
    if tab == "Common":
        tab = next((t for t in _PASS_TABS if t in shader.tabs), "Common")
    elif tab not in _PASS_TABS:
        return None, None  # Sound and Cube A tabs are not rendered by glslcheck
    try:
        units = shader.units_for(tab)
    except Exception:  # noqa: BLE001 - an odd shader folder: lint the text only
        return None, None
    key = (tab, tuple((u.path, u.text) for u in units))
    if key in _TREES:
        return _TREES[key]
    from ..check import check
    from ..diagnostics import GlslError
    from ..parse import parse_units

    try:
        model = check(parse_units(units), tab, collect=True)
        tree = (None, None) if model.errors else (model.ast, model)
    except (GlslError, RecursionError):
        tree = (None, None)
    if len(_TREES) >= 8:
        _TREES.clear()
    _TREES[key] = tree
    return tree


_PASS_TABS = ("Image", "Buffer A", "Buffer B", "Buffer C", "Buffer D", "GLSL")
_TREES: dict[tuple, tuple[Any, Any]] = {}  # syntax_tree's cache: (tab, files' texts) -> tree


def lint_source(
    source: Source,
    config: LintConfig | None = None,
    shader: Shader | None = None,
    ast: Any = None,
    model: Any = None,
) -> list[Finding]:
    """Lint one file; findings in line order."""
    config = config or LintConfig()
    rules = all_rules()
    if source_line(source.path, 1) is None:
        register_source(source.path, source.text)  # so reports can quote the file
    text_scan = scan(source.text)
    ctx = LintContext(
        source=source,
        lines=text_scan.lines,
        line_kinds=text_scan.line_kinds,
        comments=text_scan.comments,
        config=config,
        scan=text_scan,
        shader=shader,
        ast=ast,
        model=model,
        known_rules=frozenset(rules),
    )
    ctx.suppressions = find_suppressions(source.path, text_scan.comments)
    findings: list[Finding] = []
    ran: set[str] = set()
    for phase in PHASES:
        if phase == "ast" and ctx.ast is None:
            continue
        if phase == "suppressions":
            ctx.rules_run = frozenset(ran)
        for rule in rules.values():
            if rule.needs != phase or not config.enabled(rule.name):
                continue
            ran.add(rule.name)
            for d in rule.check(ctx):
                f = _finding(rule, d, ctx)
                if not is_suppressed(f, ctx.suppressions):
                    findings.append(f)
    order = {name: i for i, name in enumerate(rules)}  # ties in registry-table order
    findings.sort(key=lambda f: (f.loc.line, f.loc.column, order[f.rule]))
    return findings


def _finding(rule: Rule, d: Diagnostic, ctx: LintContext) -> Finding:
    loc = d.loc or ctx.location(1)
    if loc.end_line is None or loc.end_column is None:
        loc = ctx.location(loc.line, loc.column, loc.end_line, loc.end_column)
    return Finding(
        message=d.message,
        loc=loc,
        severity=rule.severity,
        rule=rule.name,
        help=d.help,
        notes=list(d.notes),
        penalty=rule.penalty,
    )


def check_overrides(config_overrides: Mapping[str, Any] | None) -> Mapping[str, Any]:
    """Validate command-line settings (InputError naming the unknown rule or bad value)."""
    overrides = dict(config_overrides or {})
    apply_overrides(LintConfig(), overrides, rule_names(), COMMAND_LINE)
    return overrides


def lint_paths(
    paths: Sequence[str | os.PathLike],
    config_overrides: Mapping[str, Any] | None = None,
    *,
    skip_non_shaders: bool = False,
) -> LintResult:
    """Lint files and folders. Each file gets its nearest configuration with `config_overrides`
    (settings keys: "select", "ignore", "comment-span", "tab-patterns") on top.

    A named file is linted itself (a sibling Common tab it is loaded with is context, not a
    target); a named folder has every shader file in it linted. Each file is linted once.
    `skip_non_shaders` drops named files that are not shader files (for hooks given every staged
    file). Raises InputError for unreadable input or bad configuration.
    """
    finder = ConfigFinder(check_overrides(config_overrides), rule_names())
    wanted = [str(p) for p in paths]
    for p in wanted:
        check_path(p)  # a symlink loop is named as one before any path is resolved
    if skip_non_shaders:
        wanted = [p for p in wanted if Path(p).is_dir() or is_shader_name(p, finder.for_file(p))]
    if not wanted:
        return LintResult([], 0, [])
    files = {Path(p).resolve() for p in wanted if not Path(p).is_dir()}
    folders = [Path(p).resolve() for p in wanted if Path(p).is_dir()]
    findings: list[Finding] = []
    linted: list[str] = []
    seen: set[Path] = set()
    for shader in find_shaders(wanted):
        for source in shader.sources():
            real = Path(source.path).resolve()
            if real in seen or not (real in files or any(real.is_relative_to(d) for d in folders)):
                continue
            seen.add(real)
            linted.append(source.path)
            ast, model = syntax_tree(source, shader)
            findings.extend(lint_source(source, finder.for_file(source.path), shader, ast, model))
    return LintResult(findings, len(linted), linted)


def is_shader_name(path: str, config: LintConfig) -> bool:
    """Whether a file name is a shader file: .glsl/.frag, a Shadertoy tab name, or a tab-pattern."""
    from fnmatch import fnmatch

    from ..sources import tab_name

    p = Path(path)
    if p.suffix.lower() in (".glsl", ".frag"):
        return True
    if p.suffix.lower() in (".txt", "") and tab_name(p) is not None:
        return True
    posix = p.as_posix()
    return any(fnmatch(posix, pat) or fnmatch(p.name, pat) for pat in config.tab_patterns)


def iter_rules(names: Iterable[str] | None = None) -> list[Rule]:
    """Registered rules (all, or the named ones in table order)."""
    rules = all_rules()
    if names is None:
        return list(rules.values())
    wanted = set(names)
    return [r for r in rules.values() if r.name in wanted]
