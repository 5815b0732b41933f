#!/usr/bin/env python3
"""Mutation agreement: does glslcheck accept and reject exactly what glslangValidator does?

Takes the valid shaders (tests/corpus/*, lab_shaders/*/), makes small programmatic mutations of
one tab at a time - drop a token, duplicate a token, swap two identifiers, change a literal's
type (1.0 -> 1, 2 -> 2.0), replace a called function's name by another one - and judges each
mutant with glslcheck (preprocess + parse + check, every pass) and with glslangValidator (every
program Shadertoy builds). Prints the agreement rate and every disagreement.

A disagreement is "explained" only when glslcheck rejects for one of the documented reasons in
`EXPLAINED` (glslangValidator without linking misses link-time errors, or does not check a
spec rule); those are listed too, never silently dropped.

    python tools/mutation_agreement.py [--limit N] [--seed S] [--jobs J]
"""

from __future__ import annotations

import argparse
import random
import re
import sys
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from glslcheck.base.diagnostics import register_source  # noqa: E402
from glslcheck.semantics.agreement import glslang_errors, our_errors  # noqa: E402
from glslcheck.shadertoy.sources import Shader, Source, find_shaders  # noqa: E402

# Messages of glslcheck errors that glslangValidator (compile only, no -l) does not report, and why.
EXPLAINED = {
    "has no definition": "link-time error: glslangValidator without -l does not link (see "
    "test_known_differences)",
    "recursion is not allowed": "link-time error: glslang detects recursion only when linking",
    "the case label is": "spec 6.2 requires case labels of the switch value's type; "
    "glslang does not check",
}

_TOKEN = re.compile(
    r"(?P<skip>//[^\n]*|/\*.*?\*/|^[ \t]*#[^\n]*|\s+)"
    r"|(?P<float>(\d+\.\d*|\.\d+)([eE][+-]?\d+)?[fF]?|\d+[eE][+-]?\d+[fF]?)"
    r"|(?P<int>0[xX][0-9a-fA-F]+[uU]?|\d+[uU]?)"
    r"|(?P<ident>[A-Za-z_]\w*)"
    r"|(?P<op><<=|>>=|\+\+|--|<<|>>|<=|>=|==|!=|&&|\|\||\^\^|[-+*/%]=|[&|^]=|.)",
    re.S | re.M,
)
KEYWORDS = {
    "const",
    "uniform",
    "in",
    "out",
    "inout",
    "if",
    "else",
    "for",
    "while",
    "do",
    "return",
    "break",
    "continue",
    "switch",
    "case",
    "default",
    "struct",
    "discard",
    "true",
    "false",
    "highp",
    "mediump",
    "lowp",
    "precision",
    "void",
    "float",
    "int",
    "uint",
    "bool",
}


@dataclass
class Token:
    kind: str
    text: str
    start: int
    end: int


def tokens(text: str) -> list[Token]:
    out = []
    for m in _TOKEN.finditer(text):
        kind = m.lastgroup
        if kind == "skip":
            continue
        out.append(Token(kind, m.group(), m.start(), m.end()))
    return out


def _replace(text: str, tok: Token, new: str) -> str:
    return text[: tok.start] + new + text[tok.end :]


def mutations(text: str, rng: random.Random, rounds: int = 3) -> list[tuple[str, str]]:
    """(description, mutated text) candidates of every kind for one tab text: `rounds` of each
    token mutation, and as many of the type-changing ones (literal types, swapped names)."""
    toks = tokens(text)
    if not toks:
        return []
    out: list[tuple[str, str]] = []
    line = lambda t: text.count("\n", 0, t.start) + 1  # noqa: E731
    for _ in range(rounds):
        t = rng.choice(toks)
        out.append((f"drop '{t.text}' at line {line(t)}", _replace(text, t, "")))
        t = rng.choice(toks)
        out.append(
            (f"duplicate '{t.text}' at line {line(t)}", _replace(text, t, t.text + " " + t.text))
        )
    idents = [t for t in toks if t.kind == "ident" and t.text not in KEYWORDS]
    if len(idents) >= 2:
        for _ in range(rounds):
            a, b = rng.sample(idents, 2)
            if a.text == b.text:
                continue
            first, second = sorted((a, b), key=lambda t: t.start)
            new = (
                text[: first.start]
                + second.text
                + text[first.end : second.start]
                + first.text
                + text[second.end :]
            )
            out.append(
                (
                    f"swap '{first.text}' (line {line(first)}) and '{second.text}' (line "
                    f"{line(second)})",
                    new,
                )
            )
    floats = [t for t in toks if t.kind == "float" and re.fullmatch(r"\d+\.0*", t.text)]
    ints = [t for t in toks if t.kind == "int" and t.text.isdigit()]
    for _ in range(rounds):
        if floats:
            t = rng.choice(floats)
            out.append(
                (
                    f"float literal {t.text} -> int at line {line(t)}",
                    _replace(text, t, t.text.split(".")[0]),
                )
            )
        if ints:
            t = rng.choice(ints)
            out.append(
                (
                    f"int literal {t.text} -> float at line {line(t)}",
                    _replace(text, t, t.text + ".0"),
                )
            )
    calls = [
        t
        for i, t in enumerate(toks[:-1])
        if t.kind == "ident" and toks[i + 1].text == "(" and t.text not in KEYWORDS
    ]
    names = sorted({t.text for t in calls})
    if len(names) >= 2:
        for _ in range(rounds):
            t = rng.choice(calls)
            other = rng.choice([n for n in names if n != t.text])
            out.append(
                (
                    f"call {other}() instead of {t.text}() at line {line(t)}",
                    _replace(text, t, other),
                )
            )
    return out


@dataclass
class Disagreement:
    shader: str
    tab: str
    mutation: str
    ours: list[str]
    glslang: list[str]
    explained: str | None = None

    def describe(self) -> str:
        side = (
            "glslcheck rejects, glslang accepts"
            if self.ours
            else "glslcheck accepts, glslang rejects"
        )
        why = f"\n    explained: {self.explained}" if self.explained else ""
        return (
            f"{self.shader} [{self.tab}] {self.mutation}: {side}\n    glslcheck: {self.ours[:2]}\n"
            f"    glslang: {self.glslang[:2]}{why}"
        )


@dataclass
class Report:
    total: int = 0
    agree: int = 0
    rejected: int = 0
    disagreements: list[Disagreement] = field(default_factory=list)

    @property
    def rate(self) -> float:
        return self.agree / self.total if self.total else 1.0

    @property
    def explained_rate(self) -> float:
        ok = self.agree + sum(1 for d in self.disagreements if d.explained)
        return ok / self.total if self.total else 1.0


def valid_shaders() -> list[Shader]:
    paths = sorted(p for p in (ROOT / "tests" / "corpus").glob("*") if not p.name.startswith("."))
    paths += sorted(p for p in (ROOT / "lab_shaders").glob("*/") if p.is_dir())
    return find_shaders([str(p) for p in paths])


def mutants(limit: int, seed: int) -> list[tuple[str, str, str, Shader]]:
    rng = random.Random(seed)
    pool: list[tuple[str, str, str, Shader]] = []
    shaders = valid_shaders()
    n_tabs = sum(len(s.tabs) for s in shaders) or 1
    rounds = max(2, -(-limit // (n_tabs * 5)))  # about 5 mutants per round and tab
    for shader in shaders:
        for tab, src in shader.tabs.items():
            for desc, text in mutations(src.text, rng, rounds):
                if text == src.text:
                    continue
                m = Shader(root=shader.root)
                for t, s in shader.tabs.items():
                    m.tabs[t] = Source(s.path, text if t == tab else s.text, s.tab)
                pool.append((shader.root, tab, desc, m))
    rng.shuffle(pool)
    return pool[:limit]


def run(limit: int = 400, seed: int = 1, jobs: int = 8) -> Report:
    chosen = mutants(limit, seed)
    # glslangValidator runs in parallel (subprocesses); glslcheck's parser is not thread-safe.
    with ThreadPoolExecutor(max_workers=jobs) as pool:
        theirs = list(pool.map(lambda item: glslang_errors(item[3]), chosen))
    report = Report()
    for (root, tab, desc, shader), glslang in zip(chosen, theirs):
        for src in shader.tabs.values():
            register_source(src.path, src.text)
        try:
            ours = [d.message for d in our_errors(shader)]
        except Exception as e:  # a crash is a bug: report it as a disagreement, never hide it
            ours = [f"CRASH {type(e).__name__}: {e}"]
            glslang = glslang or ["(glslcheck crashed)"]
            report.total += 1
            report.disagreements.append(Disagreement(Path(root).name, tab, desc, ours, glslang))
            continue
        report.total += 1
        report.rejected += bool(glslang)
        if bool(ours) == bool(glslang):
            report.agree += 1
            continue
        d = Disagreement(Path(root).name, tab, desc, ours, glslang)
        if ours and not glslang:
            reasons = {why for msg in ours for key, why in EXPLAINED.items() if key in msg}
            if reasons and all(any(k in msg for k in EXPLAINED) for msg in ours):
                d.explained = "; ".join(sorted(reasons))
        report.disagreements.append(d)
    return report


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--limit", type=int, default=600, help="number of mutants (default 600)")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--jobs", type=int, default=8, help="parallel glslangValidator processes")
    args = p.parse_args(argv)
    report = run(args.limit, args.seed, args.jobs)
    for d in report.disagreements:
        print(d.describe())
    print(f"mutants: {report.total} ({report.rejected} rejected by glslangValidator)")
    print(
        f"agreement: {report.agree}/{report.total} = {100 * report.rate:.1f}%"
        f" (with {len([d for d in report.disagreements if d.explained])} explained differences: "
        f"{100 * report.explained_rate:.1f}%)"
    )
    return 0 if report.explained_rate >= 0.98 else 1


if __name__ == "__main__":
    sys.exit(main())
