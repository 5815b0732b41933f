"""The figures of `glslcheck lint --fix` over the real student files and the lab (docs/fixes.md).

    python tools/fix_figures.py [--unsafe] [--no-gl]

Copies each corpus into a temporary folder (tests/real_lint/texts: git-ignored, fetched by
`tools/real_lint.py populate`; lab_shaders), then, per corpus:

1. lints it and plans the fixes (`verification.fix_proof.plan_fixes`, as `lint --fix` does;
   with `--unsafe` as `lint --fix --unsafe-fixes`), and prints for each rule the findings with
   a fix offered, offered as safe, proven safe and applied;
2. writes the fixed files and lints again: per rule, the findings before, the findings the fixes
   applied to, the findings after, and how many of those after are not accounted for (after >
   before - applied), `missing-comment` on lines the fixes added counted apart (the student
   explains them);
3. renders every fixed file's shader on the NumPy backend before and after at verify's frame
   and compares them with verify's tolerance (a second computation of what the proof checked,
   from the written files), and, unless `--no-gl`, runs `verify` (NumPy against OpenGL) on
   the fixed shader and on the original and prints both verdicts.

Nothing in the repository is written.
"""

from __future__ import annotations

import argparse
import os
import shutil
import sys
import tempfile
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from glslcheck.base.diagnostics import GlslError, InputError  # noqa: E402
from glslcheck.lint import lint_paths  # noqa: E402
from glslcheck.lint.fixes.files import write_file  # noqa: E402
from glslcheck.shadertoy.sources import Shader, find_shaders  # noqa: E402
from glslcheck.shadertoy.wrapper import DEFAULT_SIZE  # noqa: E402
from glslcheck.verification.compare import compare  # noqa: E402
from glslcheck.verification.fix_proof import plan_fixes, renderable  # noqa: E402
from glslcheck.verification.verify import compile_backend, frame_specs, verify  # noqa: E402

CORPORA = (("real student files", ROOT / "tests/real_lint/texts"), ("lab", ROOT / "lab_shaders"))


def render(shader, channels=None):
    """The frames verify renders (the channels unbound as the proof renders a file without its
    textures, when `channels` is []), or the first line of why the shader does not render."""
    if channels is not None:
        shader = Shader(tabs=dict(shader.tabs), root=shader.root, channels=channels)
    try:
        program = compile_backend(shader, "numpy")
        return [
            program.render(size=DEFAULT_SIZE, time=s.time, frame=s.frame) for s in frame_specs()
        ]
    except (GlslError, InputError) as e:
        return str(e).split("\n")[0]


def shader_of(path: str):
    for shader in find_shaders([str(Path(path).parent)]):
        if any(os.path.realpath(s.path) == os.path.realpath(path) for s in shader.sources()):
            return shader
    return find_shaders([path])[0]


def gl_verdict(shader) -> str:
    try:
        return "match" if all(c.match for c in verify(shader)) else "mismatch"
    except Exception as e:  # noqa: BLE001 - a verdict to print, whatever stopped it
        return f"does not verify ({type(e).__name__}: {str(e).splitlines()[0][:60]})"


def run(name: str, source: Path, unsafe: bool, gl: bool) -> None:
    print(f"\n## {name} ({source.relative_to(ROOT)})\n")
    if not source.exists():
        print("missing: run `python tools/real_lint.py populate` first")
        return
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp) / source.name
        shutil.copytree(source, work)
        originals = {}
        before = lint_paths([str(work)])
        plans = plan_fixes(before, unsafe=unsafe)
        offered, safe = Counter(), Counter()
        for f in before.findings:
            if f.fix is not None:
                offered[f.rule] += 1
                safe[f.rule] += f.fix.applicability == "safe"
        proven, applied, unbound = Counter(), Counter(), Counter()
        reasons = Counter()
        for plan in plans:
            for o in plan.outcomes:
                proven[o.rule] += o.findings if o.proven else 0
                unbound[o.rule] += o.findings if o.proven and plan.note else 0
                applied[o.rule] += o.findings if o.applied else 0
                if not o.applied:
                    reasons[_kind(o.reason)] += o.findings
        added = {}
        for plan in plans:
            if plan.new_text is None or plan.original is None:
                continue
            originals[plan.path] = shader_of(plan.path)
            problem = write_file(plan.original, plan.new_text)
            if problem:
                print(f"{plan.path}: {problem}")
                continue
            added[plan.path] = set(plan.new_lines)
        after = lint_paths([str(work)])
        rules = sorted(set(offered) | {f.rule for f in before.findings})
        print(
            "| rule | findings | fix offered | offered safe | proven safe (of which with the "
            "channels unbound) | applied |"
        )
        print("|---|---:|---:|---:|---:|---:|")
        count_before = Counter(f.rule for f in before.findings)
        for rule in rules:
            if offered[rule]:
                print(
                    f"| {rule} | {count_before[rule]} | {offered[rule]} | {safe[rule]} | "
                    f"{proven[rule]} ({unbound[rule]}) | {applied[rule]} |"
                )
        o, s, p, u, a = (sum(c.values()) for c in (offered, safe, proven, unbound, applied))
        print(f"| all | {len(before.findings)} | {o} | {s} | {p} ({u}) | {a} |")
        print("\nwhy the others were not applied (findings):")
        for why, n in reasons.most_common():
            print(f"- {why}: {n}")
        count_after = Counter(f.rule for f in after.findings)
        on_added = sum(
            1
            for f in after.findings
            if f.rule == "missing-comment" and f.loc.line in added.get(f.path, ())
        )
        print(
            f"\nafter --fix{' --unsafe-fixes' if unsafe else ''}: {len(before.findings)} findings "
            f"before, {sum(applied.values())} fixed, {len(after.findings)} after"
        )
        unexplained = []
        for rule in sorted(set(count_before) | set(count_after)):
            expected = count_before[rule] - applied[rule]
            extra = count_after[rule] - expected - (on_added if rule == "missing-comment" else 0)
            if extra > 0:  # a fixed finding still reported, or a new one
                unexplained.append(f"{rule} +{extra}")
        print(
            f"findings not accounted for: {', '.join(unexplained) or 'none'}; missing-comment on "
            f"lines the fixes added (the student's to explain): {on_added}"
        )
        same = unrendered = 0
        for path, shader in originals.items():
            fixed_shader = shader_of(path)
            proof_shader = renderable(shader, DEFAULT_SIZE)[0]  # as the proof rendered it
            old_imgs = render(shader, proof_shader.channels)
            new_imgs = render(fixed_shader, proof_shader.channels)
            if isinstance(old_imgs, str) or isinstance(new_imgs, str):
                ok = "does not render before" if isinstance(old_imgs, str) else "does not render"
                unrendered += 1
            else:
                ok = all(compare(a, b).match for a, b in zip(old_imgs, new_imgs))
                same += ok
            line = f"- {Path(path).relative_to(work)}: renders the same as before: {ok}"
            if gl:
                line += f"; verify (NumPy vs OpenGL): before {gl_verdict(shader)}, after "
                line += gl_verdict(fixed_shader)
            print(line)
        print(
            f"\n{same} of {len(originals)} fixed files render as their originals did "
            f"({unrendered} do not render, before the fixes or after)"
        )


def _kind(reason: str) -> str:
    """A refusal's kind, for the table (the reason's first words, numbers left out)."""
    for key in (
        "unsafe",
        "does not render",
        "does not compile",
        "changes the picture",
        "a new finding",
        "still reports",
        "proven alone",
        "edits do not apply",
    ):
        if key in reason:
            return key
    return reason[:60]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--unsafe", action="store_true", help="as lint --fix --unsafe-fixes")
    parser.add_argument("--no-gl", action="store_true", help="skip verify against OpenGL")
    args = parser.parse_args()
    for name, source in CORPORA:
        run(name, source, args.unsafe, not args.no_gl)


if __name__ == "__main__":
    main()
