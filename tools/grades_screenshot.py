#!/usr/bin/env python3
"""Write a demo class's grades page and the screenshot the README and docs/grading.md show
(docs/grades.png), as tools/report_screenshot.py does for the report page.

    python tools/grades_screenshot.py [--out build/grades.html] [--png docs/grades.png]

The class is made from the lab's own parts, each team a git repository in a temporary folder
whose branch lab4-main holds Image.txt and Common.txt: the final part as it is, with a wider
highlight (a parameter of the team's own), with Lambert's clamp dropped, with the background
gradient read from iResolution in a helper, with a missing semicolon, and a team that never
pushed the branch. `glslcheck grade --roster` grades it against lab_shaders/07_final; the page
is loaded in the WebGL backend's headless Chromium (any console error, page error or network
request fails the run) and the top of it kept as the PNG.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from glslcheck.cli.main import main as glslcheck  # noqa: E402
from glslcheck.verification.report import load_in_browser  # noqa: E402

FINAL = ROOT / "lab_shaders" / "07_final"
GRADIENT = "vec3 background = mix(kBackgroundBottom, kBackgroundTop, viewport.y * 0.5 + 0.5);"
HELPER = """// Vertical gradient behind the spheres, from the pixel's height on the canvas.
vec3 backgroundAt(in vec2 fragCoord)
{
    // 0 at the bottom row, 1 at the top: the gradient's mix factor
    return mix(kBackgroundBottom, kBackgroundTop, fragCoord.y / iResolution.y);
}

"""
BRANCH = "lab4-main"
CLAMPED = "max(dot(normal, lightDir), 0.0) * attenuated"
TEAMS = {  # team: (contributors, [(tab, old, new) edits of the final part], branch pushed)
    "moon-lab": ("Ada Lovelace; Bo Chen", [], BRANCH),
    "wide-highlights": ("Cy Diaz; Di Evans", [("Image", "4.0 * 32.0", "4.0 * 16.0")], BRANCH),
    "dark-side": (
        "Ed Fox; Fay Gold",
        [("Common", CLAMPED, "dot(normal, lightDir) * attenuated")],
        BRANCH,
    ),
    "helpers": (
        "Gus Hale; Ivy Ito",
        [
            ("Image", GRADIENT, "vec3 background = backgroundAt(fragCoord);"),
            ("Image", "// Shadertoy entry point", HELPER + "// Shadertoy entry point"),
        ],
        BRANCH,
    ),
    "semicolon": (
        "Jo King",
        [("Image", "sRay ray = calcRay(viewport);", "sRay ray = calcRay(viewport)")],
        BRANCH,
    ),
    "no-push": ("Kim Lee; Lu Moss", [], "main"),
}


def git(cwd: Path, *args: str) -> None:
    subprocess.run(
        ["git", "-c", "user.name=TA", "-c", "user.email=ta@example.org", *args],
        cwd=cwd,
        check=True,
        capture_output=True,
    )


def make_class(base: Path) -> Path:
    lines = ["team,contributors,repo,branch"]
    for team, (people, edits, branch) in TEAMS.items():
        repo = base / team
        repo.mkdir()
        git(repo, "init", "-q", "-b", "main")
        (repo / "README.md").write_text("GPR-200 coursework\n")
        git(repo, "add", "-A")
        git(repo, "commit", "-q", "-m", "start")
        if branch != "main":
            git(repo, "checkout", "-q", "-b", branch)
        texts = {tab: (FINAL / f"{tab}.glsl").read_text() for tab in ("Image", "Common")}
        for tab, old, new in edits:
            assert old in texts[tab], (team, old)
            texts[tab] = texts[tab].replace(old, new)
        for tab, text in texts.items():
            (repo / f"{tab}.txt").write_text(text)
        git(repo, "add", "-A")
        git(repo, "commit", "-q", "-m", "lab 4")
        lines.append(f'{team},"{people}",{team},{BRANCH}')
    roster = base / "roster.csv"
    roster.write_text("\n".join(lines) + "\n")
    return roster


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--out", default=str(ROOT / "build" / "grades.html"))
    p.add_argument("--png", default=str(ROOT / "docs" / "grades.png"))
    p.add_argument("--height", type=int, default=1500, help="pixels of the page's top kept")
    args = p.parse_args()
    os.chdir(ROOT)  # the page names the reference as given: relative to the repository
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="glslcheck-class-") as tmp:
        roster = make_class(Path(tmp))
        glslcheck(
            [
                "grade",
                "--roster",
                str(roster),
                "--reference",
                "lab_shaders/07_final",
                "-o",
                args.out,
                "--title",
                "Lab 4 grades (demo class)",
            ]
        )
    full = Path(args.out).with_suffix(".png")
    problems = load_in_browser(args.out, screenshot=full, height=args.height)
    for line in problems:
        print(line, file=sys.stderr)
    from PIL import Image

    with Image.open(full) as im:
        im.convert("RGB").save(args.png, optimize=True)
    print(f"{args.out}: {args.png} written; {len(problems)} browser problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
