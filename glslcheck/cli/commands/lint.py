"""Report every Lab 4 coding-standard deduction in shader files and folders, and fix them.

Exit status: 0 no findings, 1 findings, 2 usage, input or configuration errors. Without `--fix`
it never modifies a shader file. Every finding counts for the exit status, a possible deduction
(a reading of an ambiguous rubric sentence, `[possible]` in the text report) as much as a
certain one: the hook shows a student what may cost points before the TA does; a possible
deduction the student has decided against is silenced like any finding (`glslcheck:
ignore[incomplete-header]`, or `ignore` in the configuration). The summary counts the certain
and the possible points apart. Configuration: [tool.glslcheck] in the nearest pyproject.toml,
or glslcheck.toml (see `glslcheck rule --all` for the rules).

`--fix` applies the fixes the rules offer as safe once each is proven by rendering
(glslcheck/verification/fix_proof.py), writes each changed file (atomically, its line endings
kept; a file changed on disk since it was read is left alone), lints again and reports what
remains: exit 0 when nothing remains, 1 when findings remain. `--unsafe-fixes` also applies the
fixes offered as unsafe or not proven, as long as the file still compiles. `--diff` writes
nothing: it prints what `--fix` would change as a unified diff on standard output, exit 1 when
there is a change, 0 when there is none (as ruff's `--diff`). What was fixed and each fix not
applied, with why (the render's numbers for one that changes the picture), go to standard
error.
"""

from __future__ import annotations

import argparse
import sys

from ...base.diagnostics import InputError, printable


def _names(value: str) -> list[str]:
    return [n.strip() for n in value.split(",") if n.strip()]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("paths", nargs="*", metavar="PATH", help="shader files or folders")
    parser.add_argument(
        "--format",
        choices=("text", "json", "sarif", "github"),
        default="text",
        help="output format (default: text)",
    )
    parser.add_argument(
        "--select",
        type=_names,
        action="extend",
        metavar="RULE,...",
        help="only these rules (replaces the configuration's)",
    )
    parser.add_argument(
        "--ignore",
        type=_names,
        action="extend",
        metavar="RULE,...",
        help="not these rules (replaces the configuration's)",
    )
    parser.add_argument(
        "--output", "-o", metavar="FILE", help="write the report to FILE instead of standard output"
    )
    parser.add_argument(
        "--skip-non-shaders",
        action="store_true",
        help="leave out named files that are not shader files (.glsl, .frag, Shadertoy tab names, "
        "tab-patterns, .txt or extension-less files whose text is shader code); for git hooks "
        "given every staged file",
    )
    parser.add_argument(
        "--fix",
        action="store_true",
        help="apply the fixes proven safe: each rewritten file must compile, lose the "
        "finding, gain no other, and render the same as before (verify's frames and "
        "tolerance, NumPy backend)",
    )
    parser.add_argument(
        "--unsafe-fixes",
        action="store_true",
        help="with --fix or --diff: also apply the fixes that are offered as unsafe or not proven "
        "(the file must still compile)",
    )
    parser.add_argument(
        "--diff",
        action="store_true",
        help="print the changes --fix would make as a unified diff and write nothing (exit 1 when "
        "there is a change)",
    )
    parser.add_argument(
        "--staged",
        action="store_true",
        help="lint the staged (index) version of every staged shader file, "
        "as the commit will hold it "
        "(the pre-commit hook's mode; paths are relative to the top of the work tree)",
    )


def run(args: argparse.Namespace) -> int:
    from ...lint import lint_paths
    from ...lint.report import fixes_line, render, text_report

    overrides = {}
    if args.select is not None:
        overrides["select"] = args.select
    if args.ignore is not None:
        overrides["ignore"] = args.ignore
    fixing = args.fix or args.diff
    if args.unsafe_fixes and not fixing:
        raise InputError("glslcheck lint: error: --unsafe-fixes goes with --fix or --diff")
    if fixing and args.staged:
        raise InputError(
            "glslcheck lint: error: --staged lints the index and never rewrites it; run "
            "`glslcheck lint --fix PATH...` on the work tree, then stage the result"
        )
    if args.staged:
        if args.paths:
            raise InputError(
                "glslcheck lint: error: --staged lints the staged files; give no PATH with it"
            )
        from ...lint.staged import staged_checkout

        skipped: list[tuple[str, str]] = []
        passed_over: list[str] = []
        with staged_checkout(skipped, passed_over) as names:  # names: repository-relative
            result = lint_paths(names, overrides, skip_non_shaders=True)
            # the hook never rewrites the index: it names the command that fixes the work tree
            command = "glslcheck lint --fix " + " ".join(_quoted(result))
            if args.format == "text":
                text = text_report(result, command)
            else:
                text = render(result, args.format)
                fixable = fixes_line(result, command)
                if fixable:
                    print(printable(fixable), file=sys.stderr)
        if not result.files:
            _say_nothing_linted(passed_over + result.skipped, "staged file")
        for name, what in skipped:  # named as a shader, but no shader text in the commit
            print(
                printable(f"{name}: note: {what}, not a shader file; not linted"), file=sys.stderr
            )
    elif not args.paths:
        raise InputError("glslcheck lint: error: give at least one PATH (or --staged)")
    elif fixing:
        return _fix(args, overrides)
    else:
        result = lint_paths(args.paths, overrides, skip_non_shaders=args.skip_non_shaders)
        text = render(result, args.format)
        if not result.files:
            _say_nothing_linted(result.skipped, "file given")
    _write_report(args, text, result)
    return 1 if result.findings else 0


def _quoted(result) -> list[str]:
    """The files with a fix, as shell words (the command the hook's report names)."""
    import shlex

    paths = sorted({f.path for f in result.findings if f.fix is not None})
    return [shlex.quote(p) for p in paths]


def _fix(args: argparse.Namespace, overrides: dict) -> int:
    """`--fix` / `--diff`: plan and prove the fixes, then write them or print the diff."""
    from ...lint import lint_paths
    from ...lint.fixes.files import unified_diff, write_file
    from ...lint.report import render
    from ...verification.fix_proof import plan_fixes

    result = lint_paths(args.paths, overrides, skip_non_shaders=args.skip_non_shaders)
    plans = plan_fixes(result, overrides, unsafe=args.unsafe_fixes)
    changed = 0
    fixed = 0
    for plan in plans:
        if plan.error:
            print(printable(f"{plan.path}: note: no fix applied: {plan.error}"), file=sys.stderr)
            continue
        if plan.note:
            print(printable(f"{plan.path}: note: {plan.note}"), file=sys.stderr)
        for o in plan.outcomes:
            line = o.lines[0] if o.lines else 1
            if not o.applied and not o.tried:
                print(
                    printable(
                        f"{plan.path}:{line}: {o.rule}: unsafe fix not applied ({o.fix.title}): "
                        f"{o.reason.removeprefix('unsafe: ')}; `--unsafe-fixes` applies it"
                    ),
                    file=sys.stderr,
                )
            elif not o.applied:
                print(
                    printable(
                        f"{plan.path}:{line}: {o.rule}: not fixed, not proven safe "
                        f"({o.fix.title}): {o.reason}"
                    ),
                    file=sys.stderr,
                )
            elif o.reason:
                how, tail = (
                    ("unsafe fix applied", "; the shader renders the same here")
                    if o.renders_same
                    else ("fixed without proof", "")
                )
                print(
                    printable(
                        f"{plan.path}:{line}: {o.rule}: {how} ({o.fix.title}): {o.reason}{tail}"
                    ),
                    file=sys.stderr,
                )
        if plan.new_text is None or plan.original is None:
            continue
        if args.diff:
            sys.stdout.write(unified_diff(plan.original, plan.new_text))
        else:
            problem = write_file(plan.original, plan.new_text)
            if problem is not None:
                print(printable(f"{plan.path}: note: {problem}"), file=sys.stderr)
                continue
            new = plan.new_text.split("\n")
            code = [n for n in plan.new_lines if not new[n - 1].lstrip().startswith("//")]
            if code:
                lines = ", ".join(map(str, code))
                print(
                    printable(
                        f"{plan.path}: note: lines {lines} were added by the fixes; explain them "
                        "in a comment (fixes never write comments for you)"
                        if len(code) > 1
                        else f"{plan.path}: note: line {lines} was added by a fix; explain it in a "
                        "comment (fixes never write comments for you)"
                    ),
                    file=sys.stderr,
                )
        changed += 1
        fixed += sum(o.findings for o in plan.outcomes if o.applied)
    verb = "would fix" if args.diff else "fixed"
    refused = sum(1 for p in plans for o in p.outcomes if not o.applied)
    print(
        f"{verb} {fixed} finding{'s' if fixed != 1 else ''} in {changed} "
        f"file{'s' if changed != 1 else ''}; "
        f"{refused} fix{'es' if refused != 1 else ''} not applied",
        file=sys.stderr,
    )
    if args.diff:
        return 1 if changed else 0
    after = lint_paths(args.paths, overrides, skip_non_shaders=args.skip_non_shaders)
    _write_report(args, render(after, args.format), after)
    return 1 if after.findings else 0


def _write_report(args: argparse.Namespace, text: str, result) -> None:
    if args.output:
        from pathlib import Path  # only here: not on every lint's start-up

        out = Path(args.output)
        if out.exists() and _read_by_lint(out, result.paths):
            raise InputError(
                f"{args.output}: error: --output names a shader file lint reads; lint never "
                f"overwrites a shader"
            )
        from ...base.images import atomic_write

        with atomic_write(out, "report") as tmp:  # InputError (exit 2) when it cannot be written
            Path(tmp).write_text(text, encoding="utf-8")
    else:
        sys.stdout.write(text)


SHADER_FILES = (
    "a shader file is a .glsl or .frag file, a Shadertoy tab name (Image.txt, Common, Buffer A, "
    "...), or a .txt or extension-less file whose text is shader code (a mainImage, or GLSL "
    "declarations)"
)


def _say_nothing_linted(left_out: list[str], what: str) -> None:
    """On stderr: the files were all left out as not shader files, and how to include them."""
    if not left_out:
        return
    shown = ", ".join(left_out[:8]) + (
        f" and {len(left_out) - 8} more" if len(left_out) > 8 else ""
    )
    noun = f"{what}s" if len(left_out) > 1 else what
    print(
        printable(
            f"glslcheck lint: note: no shader file linted; {len(left_out)} {noun} left out as not "
            f"shader files: {shown}. {SHADER_FILES[0].upper()}{SHADER_FILES[1:]}; to lint other "
            "files, add a glob of their names to `tab-patterns` in glslcheck.toml (or "
            "[tool.glslcheck] in pyproject.toml)"
        ),
        file=sys.stderr,
    )


def _read_by_lint(out, linted: list[str]) -> bool:
    """Whether `out` is a linted file or a shader tab beside one (an Image tab's Common is read)."""
    from pathlib import Path

    from ...shadertoy.sources import tab_name

    target = out.resolve()
    if any(target == Path(p).resolve() for p in linted):
        return True
    shader_like = tab_name(target) is not None or target.suffix.lower() in (".glsl", ".frag")
    return shader_like and any(target.parent == Path(p).resolve().parent for p in linted)
