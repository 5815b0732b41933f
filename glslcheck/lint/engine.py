"""The lint engine: which files, which rules, in which order; findings out, nothing written.

    lint_paths(paths, config_overrides) -> LintResult      files and folders, as the CLI takes them
    lint_source(source, config, ...)     -> list[Finding]  one file

For each file the engine scans the text once (`textscan`), builds a `LintContext`, runs the
enabled rules in phases by their `NEEDS` — "text", then "ast" (only when the file has a parse
tree: `ctx.ast is not None`), then "suppressions" — turns each `Diagnostic` a rule yields into
a `Finding` (the rule's name, severity and penalty), and drops the findings a
`glslcheck: ignore[...]` comment silences. Reporting is `report.py`'s job; the engine never
modifies a file.

A file that does not compile still gets every finding the linter can make: its compile errors
come first (rule `compile-error`, severity error, no penalty), the AST rules run on every
function that checks (a function with an error is left out; the uniform rule, which needs only
names and scopes, reads it too), and one `compile-error` note per rule names the functions it
could not run in. A syntax error drops the one top-level declaration it is in (a function keeps
its prototype, so its callers still check) and the parse is tried again (`program_tree`).
"""

from __future__ import annotations

import os
import re

from ..base.diagnostics import Diagnostic, Location, register_source, source_line
from ..base.records import field, record
from ..shadertoy.sources import (
    BUFFER_TABS,
    Shader,
    Source,
    check_path,
    find_shaders,
    path_name,
    posix_path,
)
from .config import COMMAND_LINE, ConfigFinder, LintConfig, apply_overrides
from .fixes import Fix
from .rules import Rule, all_rules, rule_names
from .suppress import Suppression, find_suppressions, is_suppressed
from .textscan import Comment, LineKind, TextScan, scan

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterable, Mapping, Sequence
    from typing import Any

    from ..semantics.model import Model

PHASES = ("text", "ast", "suppressions")


@record
class Finding(Diagnostic):
    """A lint rule hit: a Diagnostic (rule = rule NAME, loc in the user's file), its penalty and
    the fix its rule offers (`fixes.Fix`, or None). A deduction (penalty > 0) has a `certainty`:
    "certain" (the rubric's text makes it one) or "possible" (a reading of an ambiguous rubric
    sentence); anything else has None."""

    penalty: int = 0
    fix: Fix | None = None

    @property
    def path(self) -> str:
        return self.loc.path if self.loc is not None else ""


@record
class LintResult:
    """What one lint run found: every unsuppressed finding and how many files were linted."""

    findings: list[Finding]
    files: int
    paths: list[str] = field(default_factory=list)  # the linted files, in order
    skipped: list[str] = field(default_factory=list)  # named files left out: not shader files

    @property
    def penalty(self) -> int:
        """The points the certain deductions cost."""
        return sum(f.penalty for f in self.findings if f.certainty != "possible")

    @property
    def possible_penalty(self) -> int:
        """The points the possible deductions may cost on top of `penalty`."""
        return sum(f.penalty for f in self.findings if f.certainty == "possible")


@record
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
    model: Model | None = None  # the semantic model (scopes, types) of `ast`
    suppressions: list[Suppression] = field(default_factory=list)
    rules_run: frozenset[str] = frozenset()  # rules whose findings were checked for suppression
    known_rules: frozenset[str] = frozenset()
    compile_errors: list[Diagnostic] = field(default_factory=list)  # this file's, in line order
    dropped: list[tuple[str, int, int, str]] = field(default_factory=list)  # by syntax recovery

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


@record
class ProgramTree:
    """What the AST rules of one file read: the tree and model of its program (None when not even
    recovery gave a tree), the program's compile errors, and the declarations recovery dropped
    (path, first line, last line, name)."""

    ast: Any = None
    model: Model | None = None
    errors: list[Diagnostic] = field(default_factory=list)
    dropped: list[tuple[str, int, int, str]] = field(default_factory=list)


def syntax_tree(source: Source, shader: Shader | None) -> tuple[Any, Any]:
    """The parse tree and semantic model that NEEDS = "ast" rules read, or (None, None); see
    `program_tree` (this is its tree and model when the program compiles)."""
    tree = program_tree(source, shader)
    return (tree.ast, tree.model) if not tree.errors else (None, None)


def program_tree(source: Source, shader: Shader | None) -> ProgramTree:
    """The tree, model and compile errors of the program `source` belongs to.

    A pass tab (Image, Buffer A..D, or a plain GLSL file) is parsed and checked as Shadertoy
    compiles it: Common first, then the tab. A Common tab is linted inside the first pass that
    includes it (Image, else a Buffer), so its functions are seen with their callers; alone
    when the shader has no pass tab. The tree covers every file of the program: AST rules report
    only nodes whose `loc.path` is the linted file. A program is parsed and checked once for all
    its files (a small cache keyed by the texts). A syntax error drops its top-level declaration
    and the parse is retried (at most `_MAX_RECOVERIES` times); type errors are collected by the
    checker, which goes on with the next statement.
    """
    if shader is None:
        return ProgramTree()
    tab = source.tab
    if tab == "Common":
        tab = next((t for t in _PASS_TABS if t in shader.tabs), "Common")
    elif tab not in _PASS_TABS:
        return ProgramTree()  # Sound and Cube A tabs are not rendered by glslcheck
    try:
        units = shader.units_for(tab)
    except Exception:  # noqa: BLE001 - an odd shader folder: lint the text only
        return ProgramTree()
    key = (tab, tuple((u.path, u.text) for u in units))
    if key in _TREES:
        return _TREES[key]
    tree = _build_tree(units, tab)
    for u in units:  # recovery parsed blanked copies: quote the user's own text
        register_source(u.path, u.text)
    if len(_TREES) >= 8:
        _TREES.clear()
    _TREES[key] = tree
    return tree


_MAX_RECOVERIES = 8


def _build_tree(units: list[Source], tab: str) -> ProgramTree:
    from ..base.diagnostics import GlslError
    from ..base.records import replace
    from ..frontend.parser import parse_units
    from ..semantics import check
    from .recover import RENAMED, drop_declaration, rename_reserved

    errors: list[Diagnostic] = []
    renamed: list[Diagnostic] = []  # reserved words used as names: reported, the code read whole
    dropped: list[tuple[str, int, int, str]] = []
    for _ in range(_MAX_RECOVERIES + 1):
        try:
            parsed = parse_units(units)
            break
        except GlslError as e:
            found = [d for d in e.diagnostics if d.severity == "error"]
            loc = next((d.loc for d in e.diagnostics if d.loc is not None), None)
            spelt = rename_reserved(units, loc) if loc is not None else None
            if spelt is not None:
                units, name = spelt
                said = f"the rest of the file is linted with it read as '{name}'"
                renamed.extend(
                    replace(d, rule=RENAMED, notes=[*d.notes, Diagnostic(said, loc, "note")])
                    for d in found
                )
                continue
            errors.extend(found)
            units, region = (
                drop_declaration(units, loc, dropped) if loc is not None else (units, None)
            )
            if region is None:
                return ProgramTree(errors=renamed + errors, dropped=dropped)
            dropped.append(region)
        except RecursionError:
            return ProgramTree(errors=renamed + errors, dropped=dropped)
    else:
        return ProgramTree(errors=renamed + errors, dropped=dropped)
    try:
        model = check(parsed, tab, collect=True)
    except (GlslError, RecursionError) as e:
        found = list(getattr(e, "diagnostics", []))
        return ProgramTree(errors=renamed + errors + found, dropped=dropped)
    if dropped:  # a kept prototype has no body: "declared but not defined" is not the user's error
        texts = {u.path: u.text.split("\n") for u in units}
        model.diagnostics = [d for d in model.diagnostics if not _in_dropped(d, dropped, texts)]
    model.diagnostics[:0] = errors
    return ProgramTree(model.ast, model, renamed + model.errors, dropped)


def _in_dropped(
    d: Diagnostic, dropped: list[tuple[str, int, int, str]], texts: dict[str, list[str]]
) -> bool:
    """Whether a check error comes from recovery: inside a dropped declaration, or a call of a
    function whose body was dropped (its kept prototype has no definition)."""
    if d.loc is None:
        return False
    if any(d.loc.path == path and first <= d.loc.line <= last for path, first, last, _ in dropped):
        return True
    lines = texts.get(d.loc.path, [])
    at = lines[d.loc.line - 1][d.loc.column - 1 :] if 0 < d.loc.line <= len(lines) else ""
    return "definition" in d.message and any(
        re.match(rf"{re.escape(name)}\s*\(", at) for *_, name in dropped
    )


_PASS_TABS = ("Image", *BUFFER_TABS, "GLSL")  # Common is linted inside the first one present
_TREES: dict[tuple, ProgramTree] = {}  # program_tree's cache: (tab, files' texts) -> tree


def lint_source(
    source: Source,
    config: LintConfig | None = None,
    shader: Shader | None = None,
    ast: Any = None,
    model: Model | None = None,
    *,
    errors: Sequence[Diagnostic] = (),
    dropped: Sequence[tuple[str, int, int, str]] = (),
    honour_suppressions: bool = True,
) -> list[Finding]:
    """Lint one file; its compile errors (`errors`, of the program: this file's are reported)
    first, then every finding in line order. `dropped`: declarations syntax recovery took out.
    `honour_suppressions=False` keeps the findings the file's `glslcheck: ignore` comments
    would silence (a grader counts the course's deductions, not the ones a file opts out of)."""
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
        compile_errors=[d for d in errors if d.loc is not None and d.loc.path == source.path],
        dropped=[d for d in dropped if d[0] == source.path],
    )
    ctx.suppressions = find_suppressions(source.path, text_scan.comments)
    findings: list[Finding] = []
    ran: set[str] = set()
    for phase in PHASES:
        if phase == "suppressions":
            ctx.rules_run = frozenset(ran)
        for rule in rules.values():
            if rule.needs != phase or not config.enabled(rule.name):
                continue
            if phase == "ast" and config.enabled(COMPILE_ERROR) and (_blocking(ctx) or ctx.dropped):
                findings.extend(_not_run(rule, ctx))
            if phase == "ast" and (
                ctx.ast is None or (rule.reads == "program" and _has_errors(ctx))
            ):
                continue
            ran.add(rule.name)
            for d in rule.check(ctx):
                f = _finding(rule, d, ctx)
                if not (honour_suppressions and is_suppressed(f, ctx.suppressions)):
                    findings.append(f)
    order = {name: i for i, name in enumerate(rules)}  # ties in registry-table order
    # compile errors first, then which rules could not run, then the findings in line order
    first = {(COMPILE_ERROR, "error"): 0, (COMPILE_ERROR, "note"): 1}

    def sort_key(f: Finding) -> tuple[int, int, int, int]:
        loc = f.loc
        assert loc is not None  # _finding gives every finding a location
        return (first.get((f.rule, f.severity), 2), loc.line, loc.column, order[f.rule])

    findings.sort(key=sort_key)
    return findings


COMPILE_ERROR = "compile-error"
# the help of a note that a rule could not run on all of a file (_not_run)
NOT_RUN_HELP = "fix the compile errors above, then lint again for this rule's findings there"


def _has_errors(ctx: LintContext) -> bool:
    return bool(_blocking(ctx) or ctx.dropped or (ctx.model is not None and ctx.model.errors))


def _blocking(ctx: LintContext) -> list[Diagnostic]:
    """This file's compile errors but the reserved words recovery renamed: the code they are
    in was read whole, and every rule ran on it."""
    from .recover import RENAMED

    return [d for d in ctx.compile_errors if d.rule != RENAMED]


def _not_run(rule: Rule, ctx: LintContext) -> list[Finding]:
    """One note when the AST rule `rule` could not run on all of this file: on which functions
    (they do not compile), or on the whole file (no tree, or a rule that reads the whole
    program, which has errors)."""
    blocking = _blocking(ctx)
    first = blocking[0] if blocking else None
    if ctx.ast is None or (rule.reads == "program" and _has_errors(ctx)):
        if first is None:
            return []
        why = (
            "the file does not parse"
            if ctx.ast is None
            else "it reads the whole program, which does not compile"
        )
        where, loc = "on this file", first.loc
    else:
        from ..semantics.analysis import program_facts

        broken = [] if rule.reads == "names" else program_facts(ctx.model).broken_in_file(ctx.path)
        places = [(d.proto.name, d.loc.line) for d in broken]
        places += [(name, line) for _, line, _, name in ctx.dropped]
        if not places:
            return []
        places.sort(key=lambda p: p[1])
        where = "in " + ", ".join(f"'{name}' (line {line})" for name, line in places)
        why = "it does not compile" if len(places) == 1 else "they do not compile"
        loc = ctx.location(places[0][1])
    return [
        Finding(
            message=f"{rule.name} could not run {where}: {why}",
            loc=loc,
            severity="note",
            rule=COMPILE_ERROR,
            help=NOT_RUN_HELP,
            penalty=0,
        )
    ]


def _finding(rule: Rule, d: Diagnostic, ctx: LintContext) -> Finding:
    loc = d.loc or ctx.location(1)
    if loc.end_line is None or loc.end_column is None:
        loc = ctx.location(loc.line, loc.column, loc.end_line, loc.end_column)
    advisory = d.severity == "note" and rule.severity == "warning"  # a course rule's advice
    penalty = 0 if advisory else rule.penalty
    return Finding(
        message=d.message,
        loc=loc,
        severity="note" if advisory else rule.severity,
        rule=rule.name,
        help=d.help,
        notes=list(d.notes),
        penalty=penalty,
        certainty=(d.certainty or rule.certainty) if penalty else None,
        fix=getattr(d, "fix", None),
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
    skipped: list[str] = []
    if skip_non_shaders:
        kept = [p for p in wanted if os.path.isdir(p) or is_shader_file(p, finder.for_file(p))]
        skipped = [p for p in wanted if p not in kept]
        wanted = kept
    if not wanted:
        return LintResult([], 0, [], skipped)
    files = {os.path.realpath(p) for p in wanted if not os.path.isdir(p)}
    folders = [os.path.realpath(p) for p in wanted if os.path.isdir(p)]
    linted: list[str] = []
    seen: set[str] = set()
    work: list[list[tuple[Shader, Source, LintConfig]]] = []  # per shader: its files to lint
    for shader in find_shaders(wanted):
        todo = []
        for source in shader.sources():
            real = os.path.realpath(source.path)
            if real in seen or not (real in files or any(_within(real, d) for d in folders)):
                continue
            seen.add(real)
            linted.append(source.path)
            todo.append(
                (shader, source, finder.for_file(source.path))
            )  # InputError: bad configuration
        if todo:
            work.append(todo)
    return LintResult(lint_work(work), len(linted), linted, skipped)


def _within(path: str, folder: str) -> bool:
    """`Path(path).is_relative_to(folder)` for two resolved (absolute, normalised) paths."""
    return path == folder or path.startswith(folder if folder.endswith("/") else folder + "/")


def lint_work(work: list[list[tuple[Shader, Source, LintConfig]]]) -> list[Finding]:
    """The findings of each (shader, file, configuration), in order; on two cores when the run is
    large enough (lint/parallel.py: the same findings either way)."""
    if len(work) < 2:
        return _lint_files(work)
    from ..base.diagnostics import SOURCE_LINES  # the texts reports quote: the child's come back
    from .parallel import run_split

    sizes = [sum(len(s.text) for s in todo[0][0].sources()) for todo in work]
    return run_split(work, sizes, _lint_files, _load_for_workers, SOURCE_LINES)


def _load_for_workers() -> None:
    """What every program's lint needs, loaded once before the work is split (fork shares it)."""
    from .. import semantics  # noqa: F401
    from ..frontend import parser as parse  # noqa: F401
    from ..semantics.analysis import program_facts  # noqa: F401
    from . import recover  # noqa: F401

    parse.get_parser()


def _lint_files(work: list[list[tuple[Shader, Source, LintConfig]]]) -> list[Finding]:
    findings: list[Finding] = []
    for todo in work:
        for shader, source, config in todo:
            tree = program_tree(source, shader)
            findings.extend(
                lint_source(
                    source,
                    config,
                    shader,
                    tree.ast,
                    tree.model,
                    errors=tree.errors,
                    dropped=tree.dropped,
                )
            )
    return findings


def is_shader_file(path: str, config: LintConfig, text: str | None = None) -> bool:
    """Whether a file is a shader file: .glsl/.frag, a Shadertoy tab name, a tab-pattern, or a
    `.txt` or extension-less file whose text is shader code (`text` when given, else the file's
    start; see sources.looks_like_shader)."""
    from fnmatch import fnmatch

    from ..shadertoy.sources import looks_like_shader, name_says_shader, sniff_shader_file

    by_name = name_says_shader(path)
    if by_name:
        return True
    posix = posix_path(path)
    if any(fnmatch(posix, pat) or fnmatch(path_name(posix), pat) for pat in config.tab_patterns):
        return True
    if by_name is None:
        return looks_like_shader(text) if text is not None else sniff_shader_file(path)
    return False


def iter_rules(names: Iterable[str] | None = None) -> list[Rule]:
    """Registered rules (all, or the named ones in table order)."""
    rules = all_rules()
    if names is None:
        return list(rules.values())
    wanted = set(names)
    return [r for r in rules.values() if r.name in wanted]
