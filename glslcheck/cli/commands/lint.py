"""Report every Lab 4 coding-standard deduction in shader files and folders.

Exit status: 0 no findings, 1 findings, 2 usage, input or configuration errors. Never modifies
a shader file. Every finding counts for the exit status, a possible deduction (a reading of an
ambiguous rubric sentence, `[possible]` in the text report) as much as a certain one: the hook
shows a student what may cost points before the TA does; a possible deduction the student has
decided against is silenced like any finding (`glslcheck: ignore[incomplete-header]`, or
`ignore` in the configuration). The summary counts the certain and the possible points apart.
Configuration: [tool.glslcheck] in the nearest pyproject.toml, or glslcheck.toml (see
`glslcheck rule --all` for the rules).
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
        "--staged",
        action="store_true",
        help="lint the staged (index) version of every staged shader file, "
        "as the commit will hold it "
        "(the pre-commit hook's mode; paths are relative to the top of the work tree)",
    )


def run(args: argparse.Namespace) -> int:
    from ...lint import lint_paths
    from ...lint.report import render

    overrides = {}
    if args.select is not None:
        overrides["select"] = args.select
    if args.ignore is not None:
        overrides["ignore"] = args.ignore
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
            text = render(result, args.format)
        if not result.files:
            _say_nothing_linted(passed_over + result.skipped, "staged file")
        for name, what in skipped:  # named as a shader, but no shader text in the commit
            print(
                printable(f"{name}: note: {what}, not a shader file; not linted"), file=sys.stderr
            )
    elif not args.paths:
        raise InputError("glslcheck lint: error: give at least one PATH (or --staged)")
    else:
        result = lint_paths(args.paths, overrides, skip_non_shaders=args.skip_non_shaders)
        text = render(result, args.format)
        if not result.files:
            _say_nothing_linted(result.skipped, "file given")
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
    return 1 if result.findings else 0


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
