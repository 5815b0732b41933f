"""Four small path tracers in the shapes public ones draw their random numbers in, verified
against llvmpipe: a global seed advanced by ``vec2(seed += 0.1, seed += 0.1)`` into a sin hash
(path_tracers/global_seed_sin_hash.glsl), and an ``inout`` seed advanced so into
floatBitsToUint and an integer hash, through a bounce loop of a constant count left by a
return (path_tracers/inout_seed_bits_hash.glsl), its seed a local passed down or a global
passed to the ``inout`` parameter (path_tracers/global_seed_bits_hash.glsl); and an ``inout``
seed into a sin hash drawn in one of two arms of an ``if`` in a bounce loop left by a return
(path_tracers/bounce_arms_sin_hash.glsl).

Mesa inlines every function and unrolls the bounce loop, and nir_opt_algebraic merges the
seed's constants across calls and copies (nir_fold/repeated_sums.py, in the order
nir_fold/sum_order.py simulates): into the arms of an ``if``, and into the first copy only
of a loop whose body writes the seed in arms (a later copy starts from their phi); a hash
turns the last bit of the seed into a different random direction, so the whole render differs
where one constant is merged otherwise. Written for llvmpipe of Mesa 22.3 (the `llvmpipe`
fixture skips elsewhere)."""

from __future__ import annotations

from pathlib import Path

import pytest

from glslcheck.shadertoy.sources import load_shader
from glslcheck.verification.verify import verify

HERE = Path(__file__).resolve().parent / "path_tracers"


# every reproducer in the folder (tests/compiled/test_compiled_render.py renders the same ones)
NAMES = sorted(p.stem for p in HERE.glob("*.glsl"))


@pytest.mark.parametrize("name", NAMES)
def test_path_tracer_matches_llvmpipe(llvmpipe, name):
    """Verify's frames (iTime 0 and 1.3, iFrame 60, mouse down) match with no pixel over the
    tolerance (about a thousand differed while the chains were not followed)."""
    frames = verify(
        load_shader(HERE / f"{name}.glsl"),
        size=(160, 90),
        times=[0.0, 1.3],
        frame=60,
        mouse=(40.0, 20.0, 40.0, 20.0),
    )
    assert [f.mismatched_pixels for f in frames] == [0, 0]
    assert all(f.match for f in frames)
