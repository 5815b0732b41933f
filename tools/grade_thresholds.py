#!/usr/bin/env python3
"""The figures behind grade's verdict scale (docs/grading.md): how far from lab_shaders/07_final
the pictures a class hands in land, in verify's terms (match) and in PSNR.

    python tools/grade_thresholds.py [--size 320x180] [--time 1.7]

Three groups, each rendered by the NumPy backend and compared with verification/compare.py:

1. the final part with one parameter changed (what a team may choose differently and still
   have done the part): the highlight exponent, the ambient level, the key light moved or dimmed,
   Phong's reflection vector for Blinn-Phong's halfway vector;
2. the final part with a lighting bug or a missing term: Lambert's clamp dropped, no
   attenuation, no specular term, a flat background;
3. every other part of the lab against the final one (the highest PSNR of them is printed).
"""

from __future__ import annotations

import argparse
import shutil
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import glslcheck  # noqa: E402
from glslcheck.base.limits import parse_size  # noqa: E402
from glslcheck.verification.compare import compare  # noqa: E402
from glslcheck.verification.grade.closeness import verdict  # noqa: E402

FINAL = ROOT / "lab_shaders" / "07_final"
CLAMPED = "max(dot(normal, lightDir), 0.0) * attenuated"
SPECULAR = "pow(max(dot(normal, halfway), 0.0), alphaPrime)"
CHANGES = {
    "parameter": [
        ("exponent alpha 32 -> 16", "Image.glsl", "4.0 * 32.0", "4.0 * 16.0"),
        ("exponent alpha 32 -> 64", "Image.glsl", "4.0 * 32.0", "4.0 * 64.0"),
        (
            "ambient 0.2 -> 0.25",
            "Image.glsl",
            "kAmbientIntensity = 0.2;",
            "kAmbientIntensity = 0.25;",
        ),
        (
            "ambient 0.2 -> 0.22",
            "Image.glsl",
            "kAmbientIntensity = 0.2;",
            "kAmbientIntensity = 0.22;",
        ),
        ("key light moved by 0.1", "Image.glsl", "vec3(1.3, 0.75, -2.5)", "vec3(1.4, 0.8, -2.5)"),
        (
            "key light intensity 9 -> 8",
            "Image.glsl",
            "vec3(1.0, 0.5, 0.2), 9.0",
            "vec3(1.0, 0.5, 0.2), 8.0",
        ),
        (
            "Phong instead of Blinn-Phong",
            "Common.glsl",
            SPECULAR,
            "pow(max(dot(reflect(-lightDir, normal), viewDir), 0.0), alphaPrime * 0.25)",
        ),
    ],
    "bug": [
        ("Lambert's clamp dropped", "Common.glsl", CLAMPED, "dot(normal, lightDir) * attenuated"),
        ("no attenuation", "Common.glsl", CLAMPED, "max(dot(normal, lightDir), 0.0)"),
        ("no specular term", "Common.glsl", SPECULAR, "0.0"),
        ("flat background", "Image.glsl", "viewport.y * 0.5 + 0.5", "0.5"),
    ],
}


def render(folder, size, time):
    return glslcheck.compile(str(folder)).render(size=size, time=time)


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--size", type=parse_size, default=(320, 180))
    p.add_argument("--time", type=float, default=1.7)
    args = p.parse_args()
    ref = render(FINAL, args.size, args.time)
    print(f"against lab_shaders/07_final at {args.size[0]}x{args.size[1]}, iTime {args.time:g}")
    print("| group | change | verify match | PSNR dB | pixels over 2/255 | verdict |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for group, changes in CHANGES.items():
            for i, (name, tab, old, new) in enumerate(changes):
                folder = Path(tmp) / f"{group}{i}"
                shutil.copytree(FINAL, folder)
                text = (folder / tab).read_text()
                assert old in text, name
                (folder / tab).write_text(text.replace(old, new))
                c = compare(render(folder, args.size, args.time), ref)
                share = (c.mismatched_pixels + c.edge_pixels) / (args.size[0] * args.size[1])
                print(
                    f"| {group} | {name} | {c.match} | {c.psnr_db:.1f} | "
                    f"{100 * share:.1f}% | {verdict(c)} |"
                )
    best = None
    for part in sorted((ROOT / "lab_shaders").iterdir()):
        if part.is_dir() and part != FINAL:
            c = compare(render(part, args.size, args.time), ref)
            if best is None or c.psnr_db > best[1]:
                best = (part.name, c.psnr_db, verdict(c))
    print(
        f"| other part | the closest of the 16 others: {best[0]} | False | "
        f"{best[1]:.1f} | | {best[2]} |"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
