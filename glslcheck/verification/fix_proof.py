"""Proving lint fixes by rendering: a fix is safe only when the picture stays the same.

`plan_fixes(result, ...)` takes a lint run (`LintResult`, whose findings carry the fixes their
rules offer: glslcheck/lint/fixes) and decides, file by file, which fixes to apply. A fix is
*proven* when, with its edits made,

1. the file still parses and checks (no compile error),
2. its rule no longer reports the findings it fixes,
3. no other finding appears: findings are matched by rule and place, a place followed through
   the edits (`edits.position_map`), then a finding that moved with the code a fix moved by
   rule and message; `missing-comment` is judged on the file with a placeholder comment over
   each run of lines the fixes added (comments are never written for the student: those lines
   are theirs to explain, and explaining them also covers what their own comments no longer
   reach), and
4. the NumPy backend renders the shader the same before and after, at the frames `verify` uses
   (`verify.frame_specs()`: iTime 0, iFrame 0) and its size (800x450), within verify's
   tolerance (`compare.compare`: 2/255 per channel, edge and scattered-pixel budgets, no NaN
   difference). A fix that changes a pixel beyond that is refused, with the numbers. A file
   whose only trouble is an iChannel no channels.json binds (a student's file without its
   textures) is rendered with its channels unbound, as Shadertoy renders an empty channel, and
   the plan says so (`renderable`).

Each offered fix is first proven alone; the proven ones that do not touch the same text are then
proven together, and when together they fail, added one by one (a fix that fails with the
others is left for the next pass). After a pass the file is linted again and the fixes offered
on the new text (those that overlapped, and names made fresh again) get another pass, up to
`MAX_PASSES`. Every render is compared with the original's, so passes do not drift. The files of
one shader are fixed one after another, each proven with the fixes of those before it.

`--fix` applies the fixes offered as safe and proven; `--unsafe-fixes` also applies the others
(offered unsafe, or not proven), as long as the file still compiles.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

import numpy as np

from ..base.diagnostics import GlslError, InputError, register_source
from ..lint.config import ConfigFinder
from ..lint.engine import Finding, LintResult, check_overrides, lint_source, program_tree
from ..lint.fixes import Fix
from ..lint.fixes.edits import EditError, apply_fixes, line_map, position_map
from ..lint.fixes.files import FileText, read_file
from ..lint.rules import rule_names
from ..lint.rules._comment_kinds import TRIVIAL_RE
from ..lint.textscan import TextScan
from ..lint.textscan import scan as scan_text
from ..shadertoy.sources import Shader, Source, find_shaders, tab_name
from ..shadertoy.wrapper import DEFAULT_SIZE
from .compare import Comparison, compare
from .verify import compile_backend, frame_specs

MAX_PASSES = 4
EXPECTED_ON_NEW_LINES = "missing-comment"  # a line a fix adds is the student's to explain


@dataclass
class Proof:
    """What one set of fixes did to a file: whether it compiles, is proven, and why not."""

    compiles: bool
    proven: bool
    reason: str = ""
    comparison: Comparison | None = None
    text: str = ""
    new_lines: list[int] = field(default_factory=list)  # lines the fixes added, to explain


@dataclass
class Outcome:
    """One offered fix in the end: applied or not, proven or not, and why."""

    fix: Fix
    rule: str
    findings: int  # the findings it fixes
    applied: bool = False
    proven: bool = False
    reason: str = ""
    lines: tuple[int, ...] = ()  # its findings' lines in the file as it was read
    # proven (or tried to be): not an unsafe fix left out without --unsafe-fixes
    tried: bool = False
    renders_same: bool = False  # an unsafe fix applied: whether the render stayed the same


@dataclass
class FilePlan:
    """The fixes of one file: the text to write (None: nothing to change) and every outcome."""

    path: str
    original: FileText | None
    new_text: str | None = None
    outcomes: list[Outcome] = field(default_factory=list)
    error: str = ""  # why the file's fixes could not be tried at all
    new_lines: list[int] = field(default_factory=list)
    note: str = ""  # how the proof rendered the shader, when not as verify does


def plan_fixes(
    result: LintResult,
    overrides: dict | None = None,
    *,
    unsafe: bool = False,
    size: tuple[int, int] = DEFAULT_SIZE,
) -> list[FilePlan]:
    """The plan of every linted file with an offered fix (see the module docstring). `overrides`
    are the command line's rule settings: they choose which findings are fixed; the proof looks
    for new findings of every rule the file's configuration enables."""
    wanted = {f.path for f in result.findings if f.fix is not None}
    if not wanted:
        return []
    choose = ConfigFinder(check_overrides(overrides), rule_names())
    every = ConfigFinder(check_overrides({}), rule_names())
    plans: list[FilePlan] = []
    for shader in _shaders(sorted(wanted)):
        renders = None
        note = ""
        for source in shader.sources():
            if source.path not in wanted:
                continue
            wanted.discard(source.path)
            if renders is None:
                shader, renders, note = renderable(shader, size)
            plan = _plan_file(
                shader,
                source,
                choose.for_file(source.path),
                every.for_file(source.path),
                renders,
                unsafe,
                size,
            )
            plan.note = note if any(o.proven for o in plan.outcomes) else ""
            plans.append(plan)
            if plan.new_text is not None:
                shader = _with_text(shader, source, plan.new_text)
        for source in shader.sources():
            register_source(source.path, source.text)
    for path in sorted(wanted):  # a fixable file find_shaders did not give back (a JSON tab)
        plans.append(FilePlan(path, None, error="not a shader file fixes can rewrite"))
    for plan in plans:
        if plan.original is not None:
            register_source(plan.path, plan.original.text)  # reports quote the file as it was
    return plans


def _renders(shader: Shader, size) -> list[np.ndarray] | str:
    """The shader's frames, or why it does not render."""
    try:
        program = compile_backend(shader, "numpy")
        return [
            program.render(
                size=size,
                time=spec.time,
                frame=spec.frame,
                time_delta=spec.time_delta,
                frame_rate=spec.frame_rate,
            )
            for spec in frame_specs()
        ]
    except (GlslError, InputError) as e:
        return str(e).split("\n")[0]


def _shaders(paths: list[str]) -> list[Shader]:
    """The shaders the files belong to, each once: a Shadertoy tab with the other tabs of its
    folder (an Image is proven with its Common, and their fixes one after the other), any other
    file alone."""
    import os

    found: list[Shader] = []
    seen: set[str] = set()
    for path in paths:
        if path in seen:
            continue
        folder = os.path.dirname(path) or "."
        for shader in find_shaders([folder] if tab_name(path) is not None else [path]):
            files = {s.path for s in shader.sources()}
            if path in files:
                seen.update(files)
                found.append(shader)
                break
        else:
            found.extend(find_shaders([path]))
            seen.add(path)
    return found


def renderable(shader: Shader, size) -> tuple[Shader, list[np.ndarray] | str, str]:
    """(the shader as the proof renders it, its frames or why it does not render, a note). A
    shader whose only trouble is a channel read that no channels.json binds (a student's file
    without its textures) is rendered with every channel unbound, as Shadertoy renders a channel
    without an input ((0, 0, 0, 1)) and as glslcheck renders Shadertoy's exports."""
    renders = _renders(shader, size)
    if not isinstance(renders, str) or shader.channels is not None:
        return shader, renders, ""
    try:
        compile_backend(shader, "numpy")
    except GlslError as e:
        if not e.diagnostics or any(d.rule != "unbound-channel" for d in e.diagnostics):
            return shader, renders, ""
    except InputError:
        return shader, renders, ""
    empty = Shader(tabs=dict(shader.tabs), root=shader.root, channels=[])
    again = _renders(empty, size)
    if isinstance(again, str):  # say why it does not render even so
        return shader, f"{renders.split(': ')[0]}, and with the channels unbound: {again}", ""
    return empty, again, EMPTY_CHANNELS


EMPTY_CHANNELS = (
    "proven with its iChannels unbound ((0, 0, 0, 1), as Shadertoy reads a channel without an "
    "input): no channels.json binds the ones it reads"
)


def _with_text(shader: Shader, source: Source, text: str) -> Shader:
    tabs = {
        t: (Source(s.path, text, s.tab) if s.path == source.path else s)
        for t, s in shader.tabs.items()
    }
    return Shader(tabs=tabs, root=shader.root, channels=shader.channels)


def _lint(shader: Shader, source: Source, config) -> list[Finding]:
    tree = program_tree(source, shader)
    return lint_source(
        source, config, shader, tree.ast, tree.model, errors=tree.errors, dropped=tree.dropped
    )


def _key(fix: Fix, rule: str) -> tuple[str, str]:
    return (rule, fix.title)


def _line(f: Finding) -> int:
    """The line a finding is on (the linter gives every finding a location)."""
    assert f.loc is not None
    return f.loc.line


def _plan_file(shader, source, choose, every, renders, unsafe, size) -> FilePlan:
    try:
        original = read_file(source.path)
    except InputError as e:
        return FilePlan(source.path, None, error=str(e))
    plan = FilePlan(source.path, original)
    if original.text != source.text:
        plan.error = "changed on disk since it was linted; left alone (lint it again)"
        return plan
    outcomes: dict[tuple[str, str], Outcome] = {}
    base = source.text
    added: list[int] = []
    to_original = {n: n for n in range(1, base.count("\n") + 2)}  # line now -> line read
    for _ in range(MAX_PASSES):
        current = _with_text(shader, source, base)
        here = Source(source.path, base, source.tab)
        offered: dict[Fix, list[Finding]] = {}
        for f in _lint(current, here, choose):
            if f.fix is not None and f.fix.path == source.path:
                offered.setdefault(f.fix, []).append(f)
        before = _lint(current, here, every)
        tried = []
        for fix, found in offered.items():
            rule = found[0].rule
            key = _key(fix, rule)
            if key in outcomes and (outcomes[key].applied or outcomes[key].reason):
                continue
            lines = tuple(sorted({to_original.get(_line(f), 0) for f in found} - {0}))
            outcome = outcomes.setdefault(key, Outcome(fix, rule, len(found), lines=lines))
            outcome.fix = fix
            if fix.applicability != "safe" and not unsafe:
                outcome.reason = f"unsafe: {fix.why}" if fix.why else "unsafe"
                continue
            outcome.tried = True
            tried.append((fix, found, outcome))
        if not tried:
            break
        accepted = []
        for fix, found, outcome in tried:
            proof = _prove(current, here, [fix], found, before, every, renders, size)
            outcome.proven = proof.proven and fix.applicability == "safe"
            outcome.renders_same = proof.proven
            why = [f"unsafe: {fix.why}"] if fix.applicability != "safe" and fix.why else []
            outcome.reason = "; ".join(why + ([proof.reason] if proof.reason else []))
            if proof.proven or (unsafe and proof.compiles):
                accepted.append((fix, found, outcome))
        chosen: list[tuple[Fix, list[Finding], Outcome]] = []
        for item in accepted:
            if any(item[0].overlaps(c[0]) for c in chosen):
                continue  # the next pass offers it again on the new text
            chosen.append(item)
        if not chosen:
            break
        proof = _prove_all(current, here, chosen, before, every, renders, size)
        if not (proof.proven or (unsafe and proof.compiles)):
            together = [chosen[0]]
            for item in chosen[1:]:
                trial = together + [item]
                p = _prove_all(current, here, trial, before, every, renders, size)
                if p.proven or (unsafe and p.compiles):
                    together, proof = trial, p
            if len(together) == 1:
                proof = _prove_all(current, here, together, before, every, renders, size)
            chosen = together
        for _fix, _found, outcome in chosen:
            outcome.applied = True
        # the lines fixes added so far, followed into the new text
        mapping = line_map(base, proof.text)
        kept = [n for n, old in mapping.items() if old in added]
        added = proof.new_lines + kept
        to_original = {n: to_original[o] for n, o in mapping.items() if o in to_original}
        base = proof.text
    applied = {(o.rule, line) for o in outcomes.values() if o.applied for line in o.lines}
    plan.outcomes = []
    for outcome in outcomes.values():
        if not outcome.applied and not outcome.reason:
            if any((outcome.rule, line) in applied for line in outcome.lines):
                continue  # offered again on the text a later pass had (a name made fresh)
            outcome.reason = (
                "proven alone, but it changes the same text as the fixes applied, or fails with "
                f"them, in {MAX_PASSES} passes"
            )
        plan.outcomes.append(outcome)
    if base != source.text:
        plan.new_text = base
        plan.new_lines = sorted(set(added))
    return plan


def _prove_all(shader, source, items, before, every, renders, size) -> Proof:
    """`_prove` of several (fix, findings, outcome) together."""
    fixes = [fix for fix, _, _ in items]
    fixed = [f for _, found, _ in items for f in found]
    return _prove(shader, source, fixes, fixed, before, every, renders, size)


def _prove(shader, source, fixes, fixed, before, every, renders, size) -> Proof:
    """Make `fixes` on `source` (of `shader`) and check the four conditions of the module
    docstring; `fixed` are the findings they fix, `before` every finding of the text now."""
    try:
        text = apply_fixes(source.text, fixes)
    except EditError as e:
        return Proof(False, False, f"its edits do not apply: {e}")
    new_source = Source(source.path, text, source.tab)
    new_shader = _with_text(shader, source, text)
    after = _lint(new_shader, new_source, every)
    errors = _errors(after)
    had_errors = _errors(before)
    if len(errors) > len(had_errors) or (errors and not had_errors):
        return Proof(False, False, f"the rewritten file does not compile: {errors[0].message}")
    mapping = line_map(source.text, text)
    new_lines = [n for n in range(1, text.count("\n") + 2) if n not in mapping]
    moved = position_map(source.text, [e for f in fixes for e in f.edits])
    reason = _findings_changed(fixed, before, after, moved, mapping) or _comments_changed(
        source.text, text, new_lines, every, shader, source
    )
    if had_errors:
        reason = reason or "the file does not compile, before the fix as after: nothing renders"
    elif isinstance(renders, str):
        reason = reason or f"the shader does not render: {renders}"
    if reason:
        return Proof(True, False, reason, None, text, new_lines)
    after_renders = _renders(new_shader, size)
    if isinstance(after_renders, str):
        reason = f"the rewritten shader does not render: {after_renders}"
        return Proof(True, False, reason, None, text, new_lines)
    for spec, old_img, new_img in zip(frame_specs(), renders, after_renders):
        c = compare(old_img, new_img)
        if not c.match:
            return Proof(True, False, _changed(c, spec.time), c, text, new_lines)
    return Proof(True, True, "", None, text, new_lines)


def _errors(findings: list[Finding]) -> list[Finding]:
    return [f for f in findings if f.rule == "compile-error" and f.severity == "error"]


def _findings_changed(fixed, before, after, moved, mapping: dict[int, int]) -> str:
    """Why the findings after the edits are not those before less the fixed ones: the rule still
    reports one it fixes, or another finding appeared; "" when they are the same. Findings are
    matched by rule and place (a place before the edits followed through them: `moved`), then a
    finding that moved with the code the fix moved by rule and message (a uniform read in the
    local a fix declared). `missing-comment` findings are left to `_comments_changed`."""
    gone: dict[tuple[str, int, int], int] = {}
    for f in fixed:
        k = (f.rule, f.loc.line, f.loc.column)
        gone[k] = gone.get(k, 0) + 1
    left: dict[tuple[str, tuple[int, int]], list[Finding]] = {}
    for f in before:
        g = (f.rule, f.loc.line, f.loc.column)
        if gone.get(g, 0) > 0:
            gone[g] -= 1
            continue
        left.setdefault((f.rule, moved(f.loc.line, f.loc.column)), []).append(f)
    unmatched = []
    for f in after:
        if f.rule == EXPECTED_ON_NEW_LINES:
            continue
        found = left.get((f.rule, (f.loc.line, f.loc.column)))
        if found:
            found.pop()
        else:
            unmatched.append(f)
    rest: dict[tuple[str, str], int] = {}
    for fs in left.values():
        for f in fs:
            rest[(f.rule, f.message)] = rest.get((f.rule, f.message), 0) + 1
    rules = {f.rule for f in fixed}
    for f in unmatched:
        if rest.get((f.rule, f.message), 0) > 0:
            rest[(f.rule, f.message)] -= 1
            continue
        if f.rule in rules:
            return f"{f.rule} still reports line {f.loc.line}: {f.message}"
        return f"a new finding: {f.rule} at line {f.loc.line}: {f.message}"
    return ""


def _comments_changed(old: str, new: str, new_lines: list[int], every, shader, source) -> str:
    """A `missing-comment` finding the edits brought, other than those a comment over the lines
    they added clears (the line is the student's to explain, and explaining it also covers what
    their own comment no longer reaches): the new text is linted with a placeholder comment over
    each run of added lines, and its missing-comment findings must be among the old ones."""
    lines = new.split("\n")
    out: list[str] = []
    for i, line in enumerate(lines, start=1):
        if i in new_lines and (i - 1) not in new_lines:
            indent = line[: len(line) - len(line.lstrip())]
            out.append(f"{indent}// the student's explanation of the next line")
        out.append(line)
    variant = "\n".join(out)
    mapping = line_map(old, variant)
    before = _lint(shader, Source(source.path, old, source.tab), every)
    explained = _with_text(shader, source, variant)
    after = _lint(explained, Source(source.path, variant, source.tab), every)
    had = {n for f in before if f.rule == EXPECTED_ON_NEW_LINES for n in _uncovered(f)}
    lines_of = scan_text(variant)
    for f in after:
        if f.rule != EXPECTED_ON_NEW_LINES:
            continue
        lost = [
            n for n in _uncovered(f) if mapping.get(n) not in had and _needs_comment(lines_of, n)
        ]
        if lost:
            return (
                f"a new finding: {f.rule} at line {_line(f)}: {f.message} (line {lost[0]} "
                "was explained before the fix)"
            )
    return ""


_RUN = re.compile(r"\(lines? (\d+)(?:-(\d+))?\)$")


def _needs_comment(text: TextScan, line: int) -> bool:
    """Whether a line holds code a comment must explain: not a blank, brace or comment line nor
    a statement that needs none (`return c;`). A run read whole (a function with no comment, one
    run from its signature to its end) spans such lines; read group by group at its blank lines
    (a mostly uncommented file, which a fix's lines can make one no longer) it does not."""
    return text.kind(line).has_code and not TRIVIAL_RE.match(text.code_lines[line - 1])


def _uncovered(f: Finding) -> range:
    """The code lines a missing-comment finding is about: its message ends with them, `(lines
    43-44)` (its location is the run's first line only)."""
    m = _RUN.search(f.message)
    if m is None:
        return range(_line(f), _line(f) + 1)
    first = int(m.group(1))
    return range(first, int(m.group(2) or first) + 1)


def _changed(c: Comparison, time: float) -> str:
    """What a refused fix changed in the picture, with verify's numbers."""
    w, h = c.size
    parts = [
        f"changes the picture at iTime {time:g} ({w}x{h}): {c.mismatched_pixels} pixels beyond "
        f"verify's tolerance of {c.abs_tol * 255:.0f}/255 (budget {c.mismatch_budget:.0f})",
        f"{c.edge_pixels} edge pixels (budget {c.edge_budget:.0f})",
        f"largest difference {c.max_abs_error:.4f}",
    ]
    if c.nan_mismatched_pixels:
        parts.append(f"{c.nan_mismatched_pixels} pixels NaN in one render only")
    if c.worst:
        p = c.worst[0]
        parts.append(f"worst at pixel {p.x},{p.y}")
    return ", ".join(parts)
