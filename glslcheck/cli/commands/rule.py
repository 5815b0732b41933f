"""Explain a lint rule (from its docstring), or list every rule with --all."""

from __future__ import annotations

import argparse
import difflib

from ...base.diagnostics import InputError


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("name", nargs="?", metavar="NAME", help="a rule name, e.g. missing-comment")
    parser.add_argument("--all", action="store_true", help="list every rule")


def describe(rule) -> str:
    """A rule's full documentation as `glslcheck rule NAME` prints it."""
    penalty = (
        f"-{rule.penalty} point{'s' if rule.penalty != 1 else ''} per finding"
        + (
            " (a possible deduction: a reading of an ambiguous rubric sentence)"
            if rule.certainty == "possible"
            else ""
        )
        if rule.penalty
        else "no deduction"
    )
    head = f"{rule.name}: {rule.summary}"
    kind = f"{rule.kind} of the {rule.standard} standard" if rule.standard else rule.kind
    return (
        f"{head}\n{'=' * len(head)}\n{kind} ({rule.severity}, {penalty}; "
        f"reads the {rule.needs})\n\n{rule.doc}\n"
    )


def listing(rules) -> str:
    width = max(len(r.name) for r in rules)
    rows = [f"{'rule'.ljust(width)}  penalty  kind           summary"]
    for r in rules:
        rows.append(
            f"{r.name.ljust(width)}  {('-' + str(r.penalty)) if r.penalty else '0':>7}  "
            f"{r.kind:<13}  {r.summary}"
        )
    return "\n".join(rows) + "\n"


def run(args: argparse.Namespace) -> int:
    from ...lint.rules import all_rules

    rules = all_rules()
    if args.all:
        print(listing(list(rules.values())), end="")
        return 0
    if not args.name:
        raise InputError("glslcheck rule: error: give a rule name, or --all to list the rules")
    rule = rules.get(args.name)
    if rule is None:
        close = difflib.get_close_matches(args.name, list(rules), n=1)
        hint = f" (did you mean `{close[0]}`?)" if close else ""
        raise InputError(
            f"glslcheck rule: error: no rule named `{args.name}`{hint}; "
            "`glslcheck rule --all` lists them"
        )
    print(describe(rule), end="")
    return 0
