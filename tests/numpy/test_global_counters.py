"""Globals changed in the functions mainImage calls (tests/gl/global_counters, compared with
llvmpipe bit for bit in tests/gl/test_llvmpipe_global_counters.py): every one renders from the
command line, and a counter advanced once has its value."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from glslcheck.cli.main import main

HERE = Path(__file__).resolve().parents[1] / "gl" / "global_counters"


@pytest.mark.parametrize("name", sorted(p.stem for p in HERE.glob("*.glsl")))
def test_global_counter_renders(tmp_path, name):
    out = tmp_path / "out.npy"
    size = ["--size", "8x4", "--backend", "numpy"]
    assert main(["render", str(HERE / f"{name}.glsl"), "-o", str(out), *size]) == 0
    assert np.load(out).shape == (4, 8, 4)


def test_counter_advanced_once_is_one(tmp_path):
    """called_once.glsl: color = vec3(fragCoord * 0.01, 1.0) * gCount after ``gCount += 1.0``
    from 0, so the fragment coordinates scaled (exact products by 1.0: computed here)."""
    out = tmp_path / "out.npy"
    args = ["render", str(HERE / "called_once.glsl"), "-o", str(out), "--size", "8x4"]
    assert main([*args, "--backend", "numpy"]) == 0
    got = np.load(out)
    x = np.arange(8, dtype=np.float32) + np.float32(0.5)
    y = (np.arange(4, dtype=np.float32) + np.float32(0.5))[::-1]  # (the first row is the top)
    assert (got[..., 0] == x[None, :] * np.float32(0.01)).all()
    assert (got[..., 1] == y[:, None] * np.float32(0.01)).all()
    assert (got[..., 2] == 1.0).all()
