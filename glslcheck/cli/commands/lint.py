"""Report every Lab 4 coding-standard deduction in shader files and folders.

Exit status: 0 no findings, 1 findings, 2 usage, input or configuration errors. Never modifies
a shader file. Configuration: [tool.glslcheck] in the nearest pyproject.toml, or glslcheck.toml
(see `glslcheck rule --all` for the rules).
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
        "tab-patterns); for git hooks given every staged file",
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
        with staged_checkout(skipped) as names:  # messages name the repository-relative paths
            result = lint_paths(names, overrides, skip_non_shaders=True)
            text = render(result, args.format)
        for name, what in skipped:  # named as a shader, but no shader text in the commit
            print(
                printable(f"{name}: note: {what}, not a shader file; not linted"), file=sys.stderr
            )
    elif not args.paths:
        raise InputError("glslcheck lint: error: give at least one PATH (or --staged)")
    else:
        result = lint_paths(args.paths, overrides, skip_non_shaders=args.skip_non_shaders)
        text = render(result, args.format)
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


def _read_by_lint(out, linted: list[str]) -> bool:
    """Whether `out` is a linted file or a shader tab beside one (an Image tab's Common is read)."""
    from pathlib import Path

    from ...shadertoy.sources import tab_name

    target = out.resolve()
    if any(target == Path(p).resolve() for p in linted):
        return True
    shader_like = tab_name(target) is not None or target.suffix.lower() in (".glsl", ".frag")
    return shader_like and any(target.parent == Path(p).resolve().parent for p in linted)
