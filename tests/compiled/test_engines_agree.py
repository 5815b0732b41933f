"""Both CPU engines give one answer on every shader the project measures itself on.

The lab shaders, the render benchmark's scenes and the real corpora of tools/real_verify.py
(texts/, holdout_texts/, fbm_texts/ and pathtracers_texts/, fetched by `python
tools/real_verify.py [--set NAME] fetch`) are rendered by the NumPy backend and by the
compiled engine, per pixel and 8 pixels in lockstep, as verify renders them, at the tool's
default frames (several iTime values, iFrame as an animation has it, the mouse button down and
released: engines_agree.frames), and compared bit for bit (tools/engines_agree.py, one process
a shader): an engine may refuse a shader with an error at a line (or lockstep leave it to the
per-pixel module), never render other bits. The corpora are third-party texts, never committed:
where they are not fetched (a fresh checkout, CI) their shaders skip with the command that
fetches them, and the lab and the scenes, which are in the repository, still run.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import engines_agree  # noqa: E402

LANES = (0, 8)
TIMEOUT = 900.0  # seconds a shader may take (two cold numba compiles on a loaded machine)
# Differences measured by tools/engines_agree.py and not fixed yet, each with its cause (strict:
# a fixed one must leave the list). Mesa's rewrites are nir_fold's decisions in both engines
# (docs/compiled-engine.md).
KNOWN: dict[str, str] = {}

CASES = [
    pytest.param(
        group,
        path,
        id=f"{group}-{path.stem}",
        marks=[pytest.mark.xfail(reason=KNOWN[path.stem], strict=True)]
        if path.stem in KNOWN
        else [],
    )
    for group in engines_agree.GROUPS
    for path in engines_agree.shaders(group)
]


@pytest.mark.parametrize(("group", "path"), CASES)
def test_numpy_and_compiled_render_the_same_bits(numba, group, path):
    if not path.exists():
        fetch = "python tools/real_verify.py" + ("" if group == "main" else f" --set {group}")
        pytest.skip(f"{path.relative_to(ROOT)} is not fetched ({fetch} fetch)")
    job = dict(path=str(path), size=engines_agree.SIZE, times=engines_agree.TIMES)
    cmd = [sys.executable, engines_agree.__file__, "_one", json.dumps(dict(job, lanes=LANES))]
    rows = engines_agree.run_child(cmd, TIMEOUT, LANES)
    bad = [r for r in rows if r["verdict"] not in ("identical", "refused", "per pixel")]
    assert not bad, "; ".join(f"lanes {r['lanes']}: {r['verdict']}: {r['reason']}" for r in bad)
    for r in rows:  # a refusal names the file, line and column of what it refuses
        if r["verdict"] == "refused":
            assert r["reason"].split(": ", 1)[1].count(":") >= 3, r["reason"]
