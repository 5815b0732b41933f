"""A value merged out of a branch NIR keeps: llvmpipe stores it under the exec mask, and a
derivative taken inside the branch reads that store in the lanes outside it.

Mesa 22.3 flattens a divergent `if` into selects (nir_opt_peephole_select) when its body costs
at most 8 ALU instructions (a negation, an `abs`, a vector constructor free; `dFdx` counted);
a costlier one (an `atan` is 29 or 50) stays a branch. Out of SSA, a value the branch leaves in
a variable read after it (a phi's source) is coalesced into the phi's register, and llvmpipe
writes registers under the mask, so `an` of `float an = atan(...); col = vec3(dFdx(an), ...,
an);` lives in col.z's register: a lane outside the branch holds what that register holds
there (zero: llvmpipe's registers start at zero, and a constant `col` had before is copied in
only after the branch, on the else side; col's old value when that was computed and is not read
after `an` is). In a flattened branch `an` is an SSA value computed in every lane.

Both CPU engines copy it (nir_fold.merged_register) where a local is so merged. The first test
measures the rule on the driver alone (every value from the driver: the branch's condition,
the old value and `an` computed everywhere come from a second shader); the second compares
each engine with the driver.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from PIL import Image

from glslcheck.verification.verify import compile_backend

SIZE = (40, 24)

SHADER = """void mainImage(out vec4 c, in vec2 f) {
    vec2 r = f / iResolution.xy - 0.5;
    vec3 col = OLD;
    if (length(r) < 0.3) {
        float an = VALUE;
        STORE;
    }
    c = vec4(col, 1.0);
}"""

# the same values without the branch: its condition, `an` computed in every lane, col's old z
PROBE = """void mainImage(out vec4 c, in vec2 f) {
    vec2 r = f / iResolution.xy - 0.5;
    vec3 col = OLD;
    c = vec4(length(r) < 0.3 ? 1.0 : 0.0, VALUE, col.z, 1.0);
}"""

ATAN2 = "atan(r.y, r.x) + 1.5"
CONSTANT = "vec3(5.0, 6.0, 7.0)"
COMPUTED = "vec3(r.x, r.y, sin(r.x * 7.0) + 9.0)"
STORE = "col = vec3(dFdx(an), dFdy(an), an)"
# (value, col's old value, the store, what a lane outside the branch holds for `an`)
CASES = {
    "atan2_over_a_constant": (ATAN2, CONSTANT, STORE, "zero"),
    "atan_over_a_constant": ("atan(r.y / r.x) + 1.5", CONSTANT, STORE, "zero"),
    "atan2_over_a_computed_value": (ATAN2, COMPUTED, STORE, "old"),
    # col.z's old value read after `an` is computed: the two interfere, `an` gets the register
    "atan2_over_a_value_read_after_it": (
        ATAN2,
        COMPUTED,
        "float t = col.z * 2.0; col = vec3(dFdx(an), t, an)",
        "zero",
    ),
    # the else arm writes col: col's old value is no phi's source, the then arm runs first
    "atan2_with_an_else_writing_it": (
        ATAN2,
        COMPUTED,
        STORE + "; } else { col = vec3(r.y, 0.5, r.x * 3.0)",
        "zero",
    ),
    "atan2_with_an_else_reading_it": (
        ATAN2,
        COMPUTED,
        STORE + "; } else { col.x = col.z * 0.5",
        "old",
    ),
    # `an` declared before the branch (7.0, read by no one) and assigned in it: the same
    "atan2_assigned_over_a_constant": (ATAN2, CONSTANT, STORE, "zero"),
    "atan2_assigned_over_a_computed_value": (ATAN2, COMPUTED, STORE, "old"),
    # 7 instructions and two derivatives: 9, kept
    "nine_instructions": ("sin(sin(r.y * 9.0) * 2.0) * 3.0 + r.x * r.y", CONSTANT, STORE, "zero"),
    # 6 and two derivatives: 8, flattened
    "eight_instructions": ("sin(sin(r.y * 9.0) * 2.0) * 3.0 + r.x", CONSTANT, STORE, "own"),
}


def _render(make_shader, text: str, backend: str) -> np.ndarray:
    """The float32 image in gl_FragCoord order: [y][x] with y up."""
    image = compile_backend(make_shader(text), backend).render(size=SIZE)
    return np.asarray(image, np.float32)[::-1]


def _case_texts(name: str) -> tuple[str, str]:
    value, old, store, _ = CASES[name]
    text = SHADER.replace("VALUE", value).replace("OLD", old).replace("STORE", store)
    if "_assigned_" in name:
        text = text.replace(f"float an = {value}", f"an = {value}")
        text = text.replace(f"vec3 col = {old};", f"vec3 col = {old};\n    float an = 7.0;")
    return text, PROBE.replace("VALUE", value).replace("OLD", old)


def _split(inside: np.ndarray, axis: int) -> np.ndarray:
    """Pixels inside the branch whose partner across the 2x2 quad along `axis` (1: x, 0: y)
    is outside it."""
    partner = inside.reshape(inside.shape[0] // 2, 2, inside.shape[1] // 2, 2)
    partner = np.flip(partner, axis=3 if axis == 1 else 1).reshape(inside.shape)
    return inside & ~partner


@pytest.mark.parametrize("name", sorted(CASES))
def test_a_lane_outside_a_kept_branch_holds_the_register_of_the_merged_value(
    llvmpipe, make_shader, name
):
    text, probe_text = _case_texts(name)
    got = _render(make_shader, text, "gl")
    probe = _render(make_shader, probe_text, "gl")
    inside = probe[..., 0] == 1.0
    held = {"zero": np.zeros_like(probe[..., 1]), "old": probe[..., 2], "own": probe[..., 1]}
    held = held[CASES[name][3]]
    an = got[..., 2]
    # fine dFdx at (x, y): v(x | 1, y) - v(x & ~1, y), the outside partner's v its register
    partner = held.reshape(SIZE[1], SIZE[0] // 2, 2)[:, :, ::-1].reshape(SIZE[1], SIZE[0])
    odd = (np.arange(SIZE[0]) % 2 == 1)[None, :]
    want = np.where(odd, an - partner, partner - an).astype(np.float32)
    split = _split(inside, axis=1)
    assert split.sum() >= 8, "the branch splits too few quads to measure"
    dfdx = got[..., 0]
    assert (dfdx[split].view(np.int32) == want[split].view(np.int32)).all(), np.argwhere(
        split & (dfdx != want)
    ).tolist()


# what nir_fold.merged_register declines: a partial write of col in the else arm
NOT_COPIED = {"atan2_with_an_else_reading_it"}


@pytest.mark.parametrize("backend", ["numpy", "compiled"])
@pytest.mark.parametrize("name", sorted(set(CASES) - NOT_COPIED))
def test_both_engines_hold_what_llvmpipe_holds_outside_a_kept_branch(
    renders_as_llvmpipe, make_shader, backend, name
):
    """nir_fold.merged_register: each engine writes the local under the branch's mask over
    zero or col's old value, bit for bit llvmpipe's image. Measured before it: 28 of the 960
    pixels differed in each engine for every kept case (the quads the branch splits)."""
    text, _ = _case_texts(name)
    renders_as_llvmpipe(make_shader(text), backend, name=name, size=SIZE)


OUT_PARAMETER = """void shade(out vec3 col, vec2 r) {
    col = vec3(5.0, 6.0, 7.0);
    if (length(r) < 0.3) {
        float an = atan(r.y, r.x) + 1.5;
        col = vec3(dFdx(an), dFdy(an), an);
    }
}
void mainImage(out vec4 c, in vec2 f) {
    vec3 col;
    shade(col, f / iResolution.xy - 0.5);
    c = vec4(col, 1.0);
}"""


@pytest.mark.parametrize("backend", ["numpy", "compiled"])
def test_a_merge_into_a_functions_out_parameter_differs_only_in_split_quads(
    llvmpipe, make_shader, request, backend
):
    """Not copied: the variable merged into is another function's out parameter (llvmpipe's
    register once NIR inlines the call; merged_register declines, it does not follow the
    caller). The engines then read `an` computed in every lane: they differ from llvmpipe in
    the pixels of the branch whose quad partner is outside it, and nowhere else."""
    if backend == "compiled":
        request.getfixturevalue("numba")
    want = _render(make_shader, OUT_PARAMETER, "gl")
    got = _render(make_shader, OUT_PARAMETER, backend)
    probe = PROBE.replace("VALUE", ATAN2).replace("OLD", CONSTANT)
    inside = _render(make_shader, probe, "gl")[..., 0] == 1.0
    differ = (got.view(np.int32) != want.view(np.int32)).any(axis=-1)
    allowed = _split(inside, axis=1) | _split(inside, axis=0)
    assert not (differ & ~allowed).any(), np.argwhere(differ & ~allowed).tolist()


ENTRY_OUTPUT = """void mainImage(out vec4 c, in vec2 f) {
    vec2 r = f / iResolution.xy - 0.5;
    OLD
    if (length(r) < 0.3) {
        float an = atan(r.y, r.x) + 1.5;
        c = vec4(dFdx(an), dFdy(an), an, 1.0);
    }
}"""


@pytest.mark.parametrize("backend", ["numpy", "compiled"])
@pytest.mark.parametrize(
    "old",
    ["c = vec4(0.0);", "c = vec4(r, sin(r.x * 7.0) + 9.0, 1.0);", ""],
    ids=["constant", "computed", "unwritten"],
)
def test_a_local_merged_into_the_entrys_output_is_held_as_llvmpipe_holds_it(
    renders_as_llvmpipe, make_shader, backend, old
):
    """The entry's out parameter is read after the branch (it is the output): its register
    holds zero over a constant or unwritten old value, the old value over a computed one."""
    shader = make_shader(ENTRY_OUTPUT.replace("OLD", old))
    renders_as_llvmpipe(shader, backend, name=f"ENTRY_OUTPUT over {old!r}", size=SIZE)


LOOKUP = """void mainImage(out vec4 c, in vec2 f) {
    vec2 r = f / iResolution.xy - 0.5;
    vec3 col = vec3(0.0);
    if (length(r) < 0.3) {
        float an = VALUE;
        col = vec3(texture(iChannel0, vec2(an, r.y * 0.5)).x, 0.0, an);
    }
    c = vec4(col, 1.0);
}"""


@pytest.mark.parametrize("backend", ["numpy", "compiled"])
@pytest.mark.parametrize("value", ["atan(r.y, r.x) * 0.3 + 1.5", "r.x * r.y * 3.0 + 1.5"])
def test_a_lookups_implicit_lod_reads_the_register_too(
    renders_as_llvmpipe, tmp_path, backend, value
):
    """A texture lookup keeps the branch (a tex instruction is never flattened), and its
    implicit LOD reads `an`'s register in the quad's lanes outside the branch as dFdx does.
    Measured before the rule: 28 of the 960 pixels differed in each engine, for both values."""
    rng = np.random.default_rng(10)
    Image.fromarray(rng.integers(0, 256, (64, 64, 4), dtype=np.uint8), "RGBA").save(
        tmp_path / "tex.png"
    )
    (tmp_path / "Image.glsl").write_text(LOOKUP.replace("VALUE", value))
    (tmp_path / "channels.json").write_text(
        json.dumps({"Image": {"iChannel0": {"texture": "tex.png"}}})
    )
    renders_as_llvmpipe(str(tmp_path), backend, name=f"LOOKUP of {value}", size=SIZE)
