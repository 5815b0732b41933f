"""A small class built from the lab's own parts (lab_shaders/), each team a local git repository
whose branch `lab4-main` holds one text file per Shadertoy tab, as the assignment asks:

- correct-a: the final part as handed in (Image.txt, Common.txt at the top of the repository);
- correct-b: the same in a folder `lab4/`, beside a README.txt (which is not a shader);
- lighting-bug: the final part with Lambert's clamp dropped, max(0, N.L) -> N.L: lights behind
  a surface darken it;
- uniforms-in-helper: the background gradient moved into a helper that reads iResolution
  itself (the same picture, a coding-standard deduction);
- no-compile: a statement without its semicolon in the Image tab;
- missing-branch: the team pushed to `main` only.
"""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
FINAL = ROOT / "lab_shaders" / "07_final"
BRANCH = "lab4-main"
CLAMP = "max(dot(normal, lightDir), 0.0) * attenuated"
GRADIENT = "vec3 background = mix(kBackgroundBottom, kBackgroundTop, viewport.y * 0.5 + 0.5);"
HELPER = """// Vertical gradient behind the spheres, from the pixel's height on the canvas.
vec3 backgroundAt(in vec2 fragCoord)
{
    // 0 at the bottom row, 1 at the top: the gradient's mix factor
    return mix(kBackgroundBottom, kBackgroundTop, fragCoord.y / iResolution.y);
}

"""
ENTRY = "// Shadertoy entry point"


def git(cwd: Path, *args: str) -> str:
    if shutil.which("git") is None:
        pytest.fail("git is needed to build the class of repositories")
    return subprocess.run(
        ["git", "-c", "user.name=TA", "-c", "user.email=ta@example.org", *args],
        cwd=cwd,
        check=True,
        capture_output=True,
        text=True,
    ).stdout


def make_repo(folder: Path, files: dict[str, str], branch: str = BRANCH) -> Path:
    """A repository with a first commit on `main` and `files` on `branch`."""
    folder.mkdir(parents=True)
    git(folder, "init", "-q", "-b", "main")
    (folder / "README.md").write_text("GPR-200 coursework\n")
    git(folder, "add", "-A")
    git(folder, "commit", "-q", "-m", "start")
    if branch != "main":
        git(folder, "checkout", "-q", "-b", branch)
    for name, text in files.items():
        path = folder / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    git(folder, "add", "-A")
    git(folder, "commit", "-q", "-m", "lab 4")
    git(folder, "checkout", "-q", "main")  # the clone must take the branch, not the work tree
    return folder


def final_tabs(prefix: str = "", image=None, common=None) -> dict[str, str]:
    image_text = (FINAL / "Image.glsl").read_text()
    common_text = (FINAL / "Common.glsl").read_text()
    return {
        f"{prefix}Image.txt": image(image_text) if image else image_text,
        f"{prefix}Common.txt": common(common_text) if common else common_text,
    }


def _with_helper(text: str) -> str:
    assert GRADIENT in text and ENTRY in text
    text = text.replace(GRADIENT, "vec3 background = backgroundAt(fragCoord);")
    return text.replace(ENTRY, HELPER + ENTRY)


def _without_semicolon(text: str) -> str:
    assert "sRay ray = calcRay(viewport);" in text
    return text.replace("sRay ray = calcRay(viewport);", "sRay ray = calcRay(viewport)")


@pytest.fixture(scope="session")
def lab_class(tmp_path_factory) -> dict:
    """{"roster": path of the roster CSV, "repos": team -> repository folder}."""
    base = tmp_path_factory.mktemp("class")
    teams = {
        "correct-a": (final_tabs(), BRANCH),
        "correct-b": ({**final_tabs("lab4/"), "README.txt": "Lab 4 by team B.\n"}, BRANCH),
        "lighting-bug": (
            final_tabs(common=lambda t: t.replace(CLAMP, "dot(normal, lightDir) * attenuated")),
            BRANCH,
        ),
        "uniforms-in-helper": (final_tabs(image=_with_helper), BRANCH),
        "no-compile": (final_tabs(image=_without_semicolon), BRANCH),
        "missing-branch": (final_tabs(), "main"),
    }
    repos = {}
    lines = ["team,contributors,repo,branch"]
    for team, (files, branch) in teams.items():
        repos[team] = make_repo(base / "repos" / team, files, branch)
        lines.append(f'{team},"Ada {team}; Bo {team}",repos/{team},{BRANCH}')
    roster = base / "roster.csv"
    roster.write_text("\n".join(lines) + "\n")
    return {"roster": roster, "repos": repos, "base": base}
