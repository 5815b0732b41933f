"""The runtime's cheaper selects keep every bit: `runtime_values.where` (a bit select in place of
np.where's loop), `mix` in the "select" form on it, the rows fmul zeroes for a constant zero
operand, and `a[i].f` transpiled as the field's array indexed.

Each is checked against the computation it replaces (np.where itself, the unmoved program),
bit for bit, NaN payloads, signed zeros and infinities included.
"""

from __future__ import annotations

import numpy as np
import pytest

from glslcheck.backends.numpy_engine.program import compile_numpy
from glslcheck.backends.numpy_engine.runtime import Runtime
from glslcheck.backends.numpy_engine.runtime_values import where

LANES = 5000  # above where's size threshold: the bit select runs

# float32 values a select must copy exactly: quiet and signalling-pattern NaNs with payloads,
# both zeros, both infinities, a subnormal
SPECIAL = np.array(
    [0x7FC00001, 0xFFC12345, 0x7F800001, 0x80000000, 0x00000000, 0x7F800000, 0xFF800000, 1],
    dtype=np.uint32,
).view(np.float32)


def _bits(x: np.ndarray) -> np.ndarray:
    x = np.ascontiguousarray(x)
    return x.view({1: np.uint8, 2: np.uint16, 4: np.uint32, 8: np.uint64}[x.dtype.itemsize])


def _values(rng, shape, dtype):
    if np.dtype(dtype) == np.bool_:
        return rng.random(shape) < 0.5
    if np.dtype(dtype).kind == "f":
        v = rng.standard_normal(shape).astype(dtype)
        flat = v.reshape(-1)
        n = min(len(flat), len(SPECIAL))
        with np.errstate(invalid="ignore"):  # (a signalling-pattern NaN cast to float64)
            flat[:n] = SPECIAL[:n].astype(dtype)
        return v
    info = np.iinfo(dtype)
    return rng.integers(info.min, info.max, shape, dtype=dtype, endpoint=True)


MASKS = {
    "scattered": lambda rng: rng.random(LANES) < 0.3,
    "runs": lambda rng: (np.arange(LANES) % 800) < 240,
    "none": lambda rng: np.zeros(LANES, dtype=bool),
    "all": lambda rng: np.ones(LANES, dtype=bool),
}
SHAPES = [  # (cond, a, b): lanes last; (k, 1) is one value for every lane
    ((LANES,), (LANES,), (LANES,)),
    ((LANES,), (3, LANES), (3, LANES)),
    ((LANES,), (3, 1), (3, LANES)),
    ((LANES,), (3, LANES), (3, 1)),
    ((3, LANES), (3, LANES), (3, 1)),
    ((LANES,), (1,), (LANES,)),
    ((LANES,), (3, 1), (3, 1)),
    ((4,), (4,), (4,)),  # small: np.where itself
]


@pytest.mark.parametrize("dtype", [np.float32, np.float64, np.int32, np.uint32, np.bool_])
@pytest.mark.parametrize("mask", sorted(MASKS))
@pytest.mark.parametrize("shapes", SHAPES, ids=str)
def test_where_is_np_where_bit_for_bit(dtype, mask, shapes):
    rng = np.random.default_rng(len(mask) * 31 + len(shapes[1]))
    cs, sa, sb = shapes
    cond = np.broadcast_to(MASKS[mask](rng), cs[:-1] + (LANES,)) if cs[-1] == LANES else None
    cond = rng.random(cs) < 0.5 if cond is None else np.ascontiguousarray(cond)
    a, b = _values(rng, sa, dtype), _values(rng, sb, dtype)
    got, want = where(cond, a, b), np.where(cond, a, b)
    assert got.dtype == want.dtype and got.shape == want.shape
    assert np.array_equal(_bits(got), _bits(want))


@pytest.mark.parametrize("cond_lanes", [LANES, 1])
def test_where_of_values_broadcast_over_the_lanes_keeps_np_where_s_shape(cond_lanes):
    rng = np.random.default_rng(4)
    cond = rng.random(cond_lanes) < 0.5
    a = np.broadcast_to(np.array([[1.5], [np.nan], [-0.0]], np.float32), (3, LANES))
    for b in (np.broadcast_to(np.array([[2.5], [3.0], [0.0]], np.float32), (3, LANES)), a):
        got, want = where(cond, a, b), np.where(cond, a, b)
        assert got.shape == want.shape
        assert np.array_equal(_bits(got), _bits(want))


def test_where_of_one_value_on_both_sides_is_that_value_per_lane_and_no_constant():
    rt = Runtime("float32")
    k = np.array([[np.nan], [-0.0], [2.5]], dtype=np.float32)
    cond = np.random.default_rng(1).random(LANES) < 0.5
    got = where(cond, k, k.copy())
    assert np.array_equal(_bits(got), _bits(np.where(cond, k, k)))
    # a lane-uniform writable array counts as a compile-time constant in fmul (its zero
    # components folded); a select's result is a run-time value, as np.where's was
    assert not rt._const(got) and not rt._const(np.where(cond, k, k))
    with pytest.raises(ValueError):
        got[0, 0] = 1.0  # read-only: callers never write into a value they did not make


def test_a_b2f_mix_selects_and_ignores_the_other_side_nan_included():
    rt = Runtime("float32")
    rng = np.random.default_rng(2)
    w = (rng.random(LANES) < 0.4).astype(np.float32)  # a b2f weight: 0 or 1
    x = np.full((3, LANES), np.nan, dtype=np.float32)
    y = rng.standard_normal((3, LANES)).astype(np.float32)
    got = rt.mix(x, y, w, "select")
    assert np.array_equal(_bits(got), _bits(np.where(w == 1, y, x)))
    assert np.isfinite(got[:, w == 1]).all() and np.isnan(got[:, w == 0]).all()
    # any other form interpolates: a weight of 1 still reads the NaN side
    assert np.isnan(rt.mix(x, y, w, "fast")).all()


@pytest.mark.parametrize(
    "z, other_shape",
    [
        ([[0.0], [1.5], [0.0]], (3, LANES)),  # some rows zero
        ([[0.0], [0.0], [0.0]], (3, LANES)),
        ([[-0.0], [2.0], [3.0]], (3, LANES)),  # -0.0 is a zero too: the product is +0.0
        ([0.0], (3, LANES)),  # a float constant times a vector
        ([0.0], (LANES,)),
        ([-0.0], (LANES,)),
    ],
    ids=str,
)
def test_fmul_zeroes_the_rows_of_a_constant_zero_as_a_select_did(z, other_shape):
    rt = Runtime("float32")
    rt.fold_constants = True
    z = np.array(z, dtype=np.float32)
    other = np.random.default_rng(3).standard_normal(other_shape).astype(np.float32)
    other.reshape(-1)[: len(SPECIAL)] = SPECIAL  # NaN and Inf: 0 * them is NaN in IEEE
    with np.errstate(invalid="ignore"):
        want = np.where(z == 0, np.float32(0.0), z * other)
        for a, b in ((z, other), (other, z)):
            got = rt.fmul(a, b)
            assert got.shape == want.shape
            assert np.array_equal(_bits(got), _bits(want))


# An array of structs read at a lane-varying index (out of range on some lanes: clamped) and
# at a constant one, field by field, against the same reads through a copied element.
FIELDS = """
struct Light { vec3 center; vec3 color; float power; };
const Light kLights[3] = Light[3](Light(vec3(1.0, 2.0, 3.0), vec3(0.5), 2.0),
                                  Light(vec3(-1.0, 0.0, 1.0), vec3(0.1, 0.2, 0.3), 4.0),
                                  Light(vec3(0.0, -2.0, 5.0), vec3(1.0, 0.0, 0.5), 8.0));
void mainImage(out vec4 o, in vec2 f) {
    Light lights[3] = kLights;
    lights[1].power = f.y;
    int i = int(f.x) % 5 - 1;
    READ
}
"""
DIRECT = "o = vec4(lights[i].center * lights[i].power + lights[2].color, lights[i].color.g);"
COPIED = """Light l = lights[i]; Light m = lights[2];
    o = vec4(l.center * l.power + m.color, l.color.g);"""


def test_a_field_of_an_indexed_struct_array_reads_the_same_as_a_copied_element(make_shader):
    direct = compile_numpy(make_shader(FIELDS.replace("READ", DIRECT)))
    copied = compile_numpy(make_shader(FIELDS.replace("READ", COPIED)))
    assert 'rt.index(rt.field(v_lights, "m_center"), v_i)' in direct.source
    assert "rt.field(v_lights" not in copied.source
    size = (16, 4)
    a, b = direct.render(size=size), copied.render(size=size)
    assert np.array_equal(a, b) and np.isfinite(a).all()
    assert len(np.unique(a[..., 0])) > 3  # the index varies over the lanes


# A mix whose weight is a product of step() and float(bool) (NIR: b2f, a select), with NaN on
# the side the weight drops on some lanes; WEIGHT is the weight as written, or through a local
# (the "select" form of rt.mix, the path before the bools were used directly).
B2F = """
void mainImage(out vec4 o, in vec2 f) {
    vec3 nan = vec3(sqrt(f.x - 9.5));
    vec3 lit = vec3(f.x * 0.1, f.y * 0.2, 0.3);
    float t = f.x - f.y;
    WEIGHT
    o = vec4(mix(nan, lit, w), 1.0);
}
"""
DIRECT_W = "#define w (step(0.0, t) * float(f.x > 9.5))"
LOCAL_W = "float w = step(0.0, t); w = w * float(f.x > 9.5);"


@pytest.mark.parametrize("precision", ["float32", "float64"])
def test_a_b2f_weight_of_steps_and_bools_selects_on_the_bools(make_shader, precision):
    direct = compile_numpy(make_shader(B2F.replace("WEIGHT", DIRECT_W)))
    local = compile_numpy(make_shader(B2F.replace("WEIGHT", LOCAL_W)))
    assert "rt.mix_b2f(" in direct.source and "rt.step_mask(" in direct.source
    assert "rt.mix_b2f(" not in local.source and "'select'" in local.source
    size = (16, 8)
    a = direct.render(size=size, precision=precision)
    b = local.render(size=size, precision=precision)
    assert np.array_equal(_bits(a), _bits(b))
    if precision == "float32":  # the select drops the NaN side where the weight is 1
        assert np.isfinite(a).any() and np.isnan(a).any()


def test_a_weight_that_is_arithmetic_to_nir_is_no_select(make_shader):
    # 1.0 - step(): NIR interpolates (docs/llvmpipe.md "mix weights that select")
    prog = compile_numpy(make_shader(B2F.replace("WEIGHT", "float w = 1.0 - step(t, 0.0);")))
    assert "rt.mix_b2f(" not in prog.source
    img = prog.render(size=(16, 8))
    assert np.isnan(img[..., :3]).all(axis=-1)[:, :9].all()  # x + w * (y - x): NaN read
