#!/usr/bin/env python3
"""Four compilers' verdicts on the same Shadertoy programs: glslcheck, glslangValidator, Mesa,
ANGLE.

A shader is accepted by a judge when every program Shadertoy compiles from it (Common alone,
then Common + each pass tab; glslcheck.semantics.agreement.passes) is accepted:
- glslcheck: preprocess + parse + check without an error (`our_errors`);
- glslangValidator: each wrapped program compiles (`glslang_errors`, no linking);
- Mesa: the GL driver (llvmpipe, `#version 300 es`) compiles and links it with a vertex shader;
- ANGLE: WebGL 2 in headless Chromium compiles and links it (`webgl_diagnostics`), which is what
  a Shadertoy user's browser does.

Corpora: tests/check/invalid (every fixture is invalid: the rejection rate is the figure),
tests/webgl/invalid (what ANGLE alone rejects, now rules of our checker), the valid shaders
(tests/corpus, lab_shaders: the acceptance rate), and the mutants of tools/mutation_agreement.py
(pairwise agreement). Every shader where ANGLE and another judge disagree is listed with both sides'
first message.

    python tools/webgl_agreement.py [--mutants N] [--seed S]
"""

from __future__ import annotations

import argparse
import itertools
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tools"))

from glslcheck.base.diagnostics import GlslError, register_source  # noqa: E402
from glslcheck.semantics.agreement import glslang_errors, our_errors, passes  # noqa: E402
from glslcheck.shadertoy.sources import Shader, Source  # noqa: E402
from glslcheck.shadertoy.wrapper import build_program  # noqa: E402

JUDGES = ("glslcheck", "glslang", "mesa", "angle")


def mesa_errors(shader: Shader) -> list[str]:
    from glslcheck.backends.gl import get_context
    from glslcheck.backends.gl.program import _compile

    out = []
    for tab in passes(shader):
        try:
            _compile(get_context(), build_program(shader, tab)).gl_program.release()
        except GlslError as e:
            out += [f"[{tab}] {d.message}" for d in e.diagnostics]
    return out


def angle_errors(shader: Shader) -> list[str]:
    from glslcheck.backends.webgl import webgl_diagnostics

    return [
        f"[{tab}] {d.message}" for tab in passes(shader) for d in webgl_diagnostics(shader, tab)
    ]


def verdicts(shader: Shader) -> dict[str, list[str]]:
    """Each judge's error messages (empty = accepted)."""
    for src in shader.tabs.values():
        register_source(src.path, src.text)
    try:
        ours = [d.message for d in our_errors(shader)]
    except Exception as e:  # a crash is a finding, not a verdict to hide
        ours = [f"CRASH {type(e).__name__}: {e}"]
    return {
        "glslcheck": ours,
        "glslang": glslang_errors(shader),
        "mesa": mesa_errors(shader),
        "angle": angle_errors(shader),
    }


def invalid_fixtures(folder: Path) -> list[tuple[str, Shader]]:
    out = []
    for path in sorted(folder.glob("*.glsl")):
        text = path.read_text(encoding="utf-8")
        lines = text.splitlines()
        tab = "Common" if len(lines) > 1 and lines[1].strip() == "// tab: Common" else "Image"
        shader = Shader(root=str(path))
        shader.tabs[tab] = Source(str(path), text, tab)
        out.append((path.stem, shader))
    return out


def summarise(name: str, results: list[tuple[str, dict[str, list[str]]]]) -> list[str]:
    n = len(results)
    lines = [f"## {name}: {n} shaders", ""]
    lines.append("| judge | rejects |")
    lines.append("|---|---|")
    for j in JUDGES:
        lines.append(
            f"| {j} | {sum(bool(v[j]) for _, v in results)} "
            f"({100 * sum(bool(v[j]) for _, v in results) / max(n, 1):.1f}%) |"
        )
    lines += ["", "| pair | agree |", "|---|---|"]
    for a, b in itertools.combinations(JUDGES, 2):
        agree = sum(bool(v[a]) == bool(v[b]) for _, v in results)
        lines.append(f"| {a} / {b} | {agree}/{n} ({100 * agree / max(n, 1):.1f}%) |")
    odd = [(k, v) for k, v in results if len({bool(v[j]) for j in JUDGES}) > 1]
    if odd:
        lines += [
            "",
            "Shaders the judges disagree on (first message of each judge that rejects):",
            "",
        ]
        for k, v in odd:
            said = "; ".join(f"{j}: {v[j][0][:110]!r}" for j in JUDGES if v[j])
            accept = ", ".join(j for j in JUDGES if not v[j])
            lines.append(f"- `{k}`: accepted by {accept}; {said}")
    return lines + [""]


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument(
        "--mutants",
        type=int,
        default=200,
        help="mutants of tools/mutation_agreement.py (default 200)",
    )
    p.add_argument("--seed", type=int, default=1)
    args = p.parse_args(argv)
    from mutation_agreement import mutants, valid_shaders

    from glslcheck.backends.webgl import get_browser

    browser = get_browser()
    print(f"ANGLE: {browser.info['renderer']}, Chromium {browser.version}\n")
    out: list[str] = []
    for folder in ("tests/check/invalid", "tests/webgl/invalid"):
        out += summarise(folder, [(k, verdicts(s)) for k, s in invalid_fixtures(ROOT / folder)])
    out += summarise(
        "valid shaders (tests/corpus, lab_shaders)",
        [(Path(s.root).name, verdicts(s)) for s in valid_shaders()],
    )
    if args.mutants:
        chosen = mutants(args.mutants, args.seed)
        out += summarise(
            f"mutants (seed {args.seed})",
            [(f"{Path(root).name} [{tab}] {desc}", verdicts(s)) for root, tab, desc, s in chosen],
        )
    print("\n".join(out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
