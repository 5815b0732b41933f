"""A path tracer's first sphere hit through calls, measured on llvmpipe (p03-fdS3zw's shape): Mesa
inlines ``iSphere(ro, rd, sph)`` and ``nSphere(ro + t*rd, sph)`` into the caller, so the
camera's and the sphere's constants meet in NIR's constant rules across the calls. The camera
``ww = normalize(ta - ro)`` with ``ta - ro = (0, 0, 8)`` folds to the constants (0, 0, 1), (-1,
0, 0), (0, 1, 0), so ``rd = normalize(p.x*uu + p.y*vv + 3.0*ww)`` is ``v * rsq`` with v's z the
constant 3.0: rd.z is ``3.0 * rsq``. The sphere's ``b = dot(ro - sph.xyz, rd)`` with ro and sph
constant multiplies rd.z by the constant -9.0, and ``#a * (b * #c) -> (a*c) * b`` (no "used
once" condition) gives ``-27.0 * rsq``; rd.x and rd.y, read elsewhere too, keep ``1.78 * (v.x *
rsq)`` (read once, the product sink makes it ``(1.78 * v.x) * rsq``). The normal ``(pos -
sph.xyz) / sph.w`` with pos ``ro + t*rd`` (an argument used once) sinks the sphere's constant
into the argument's sum, the product kept whole (``(a + b) + #c -> (a + #c) + b``): ``(ro -
sph.xyz) + t*rd``. Each shader writes the operands the driver computed to other channels, and
the test computes Mesa's order and the written one from them in NumPy float32. Both CPU engines
follow the first (nir_fold/ray_dots.py: the hidden ray arguments), also in the first copy of
an unrolled loop with the sphere a global an init function sets to constants (p03-fdS3zw's
traceEyePath); not yet the read-once product sink nor the normal's sink across the call
(docs/llvmpipe.md, "A camera's constant component reaches a sphere's hit"). Written for
llvmpipe of Mesa 22.3."""

from __future__ import annotations

import numpy as np
import pytest
from image_bits import SIZE, assert_same, differing_pixels, render

F = np.float32

# Two rows share a camera ray (q's y is fragCoord.y halved): the even rows write b and the
# ray's v.x, v.y, the odd ones rsq and rd.x, rd.y, so rd.x and rd.y are read twice.
SPHERE_B = """float sphereB(in vec3 ro, in vec3 rd, in vec4 sph) {
    vec3 oc = ro - sph.xyz;
    return dot(oc, rd);
}
float hitB(in vec3 ro, in vec3 rd) { return sphereB(ro, rd, vec4(1.0, 1.0, 1.0, 1.0)); }
void mainImage(out vec4 c, in vec2 fragCoord) {
    vec2 q = vec2(fragCoord.x, floor(fragCoord.y * 0.5));
    vec2 p = q * vec2(0.0123, 0.0241) - vec2(1.0, 0.55) + 0.01 * sin(q.yx);
    vec3 ro = vec3(2.78, 2.73, -8.0);
    vec3 ww = normalize(vec3(2.78, 2.73, 0.0) - ro);
    vec3 uu = normalize(cross(ww, vec3(0.0, 1.0, 0.0)));
    vec3 vv = normalize(cross(uu, ww));
    vec3 v = p.x * uu + p.y * vv + 3.0 * ww;
    vec3 rd = normalize(v);
    float b = hitB(ro, rd);
    if (mod(fragCoord.y, 2.0) < 1.0) c = vec4(b, v.x, v.y, 1.0);
    else c = vec4(inversesqrt(dot(v, v)), rd.x, rd.y, 1.0);
}"""
# p03-fdS3zw's shape: the sphere a global an init function sets to constants, the hits in an
# unrolled loop that writes rd after them (its first copy sees the camera's ray; the later ones
# a ray without constants). x and y: the first copy's b of each sphere (-b where missed).
LOOP = """vec4 movingSphere;
void initSphere(float time) {
    time = 0.0;
    movingSphere = vec4(1.0 + abs(sin(time * 1.3)), 1.0 + abs(2.0 * sin(time)),
                        7.0 - abs(6.0 * cos(time * 0.4)), 1.0);
}
float sphereB(in vec3 ro, in vec3 rd, in vec4 sph) {
    vec3 oc = ro - sph.xyz;
    float b = dot(oc, rd);
    float c = dot(oc, oc) - sph.w * sph.w;
    float h = b * b - c;
    if (h < 0.0) return -b;
    return b;
}
vec2 hit(in vec3 ro, in vec3 rd) {
    return vec2(sphereB(ro, rd, movingSphere), sphereB(ro, rd, vec4(3.0, 7.5, 2.5, 0.5)));
}
vec3 trace(in vec3 ro, in vec3 rd) {
    vec3 o = vec3(0.0);
    for (int j = 0; j < 3; ++j) {
        vec2 t = hit(ro, rd);
        if (j == 0) o.xy = t;
        o.z += step(0.0, t.x);
        rd = normalize(vec3(t.x, t.y, t.x * t.y));
    }
    return o;
}
void mainImage(out vec4 c, in vec2 fragCoord) {
    vec2 p = -1.0 + 2.0 * fragCoord / iResolution.xy + 0.01 * sin(fragCoord.yx);
    p.x *= iResolution.x / iResolution.y;
    vec3 ro = vec3(2.78, 2.73, -8.0);
    vec3 ww = normalize(vec3(2.78, 2.73, 0.0) - ro);
    vec3 uu = normalize(cross(ww, vec3(0.0, 1.0, 0.0)));
    vec3 vv = normalize(cross(uu, ww));
    initSphere(iTime);
    vec3 rd = normalize(p.x * uu + p.y * vv + 3.0 * ww);
    c = vec4(trace(ro, rd), 1.0);
}"""
ENGINE_SHADERS = {"sphere_b": SPHERE_B, "loop": LOOP}
# rd.x read once (the bottom half) and rd.y read once (the top half), each times a constant.
READ_ONCE = """void mainImage(out vec4 c, in vec2 fragCoord) {
    vec2 p = -1.0 + 2.0 * fragCoord / iResolution.xy + 0.01 * sin(fragCoord.yx);
    vec3 v = vec3(-p.x, p.y, 3.0);
    vec3 rd = normalize(v);
    if (fragCoord.y < 45.0) c = vec4(1.78 * rd.x, v.x, inversesqrt(dot(v, v)), 1.0);
    else c = vec4(1.73 * rd.y, v.y, inversesqrt(dot(v, v)), 1.0);
}"""
# The bottom half writes the normal's x and its operands, the top half its y.
NORMAL = """vec3 nSphere(in vec3 pos, in vec4 sph) { return (pos - sph.xyz) / sph.w; }
void mainImage(out vec4 c, in vec2 fragCoord) {
    vec3 ro = vec3(fragCoord * 0.037, 2.0) + sin(fragCoord.yxy);
    vec3 rd = normalize(vec3(cos(fragCoord * 0.11), 1.5));
    float t = 3.0 + fract(fragCoord.x * 0.173);
    vec3 n = nSphere(ro + t * rd, vec4(1.0, 1.0, 1.0, 1.0));
    if (fragCoord.y < 45.0) c = vec4(n.x, ro.x, t * rd.x, 1.0);
    else c = vec4(n.y, ro.y, t * rd.y, 1.0);
}"""


def _bits(values):
    return np.asarray(values, F).view(np.int32)


def test_llvmpipe_merges_the_cameras_constant_into_the_spheres(llvmpipe, make_shader):
    """b through two calls is ``1.78*rd.x + (1.73*rd.y + -27.0*rsq)`` (dot summed right to
    left) on every value: the sphere's -9.0 and the ray's 3.0 merged, rd.x and rd.y as written
    (read twice; merged into v.x and v.y, the values differ)."""
    got = render(make_shader(SPHERE_B), "gl", frame=0)[::-1]  # (row 0 the bottom)
    even, odd = got[0::2].reshape(-1, 4), got[1::2].reshape(-1, 4)
    b, vx, vy = even[:, 0], even[:, 1], even[:, 2]
    r, rx, ry = odd[:, 0], odd[:, 1], odd[:, 2]
    assert (_bits(vx * r) == _bits(rx)).all() and (_bits(vy * r) == _bits(ry)).all()
    mesa = F(1.78) * rx + (F(1.73) * ry + F(-27.0) * r)
    written = F(1.78) * rx + (F(1.73) * ry + F(-9.0) * (F(3.0) * r))
    into_v = (F(1.78) * vx) * r + ((F(1.73) * vy) * r + F(-27.0) * r)
    assert (_bits(mesa) != _bits(written)).any() and (_bits(mesa) != _bits(into_v)).any()
    assert (_bits(b) == _bits(mesa)).all()


def test_llvmpipe_merges_into_a_component_read_once(llvmpipe, make_shader):
    """Where rd.x feeds one product, ``1.78 * rd.x`` is ``(1.78 * v.x) * rsq`` (the product
    sink, rd.x used once), unlike b above, where rd.x is read twice."""
    got = render(make_shader(READ_ONCE), "gl", frame=0)
    k = np.where(np.arange(got.shape[0])[:, None] >= got.shape[0] // 2, F(1.78), F(1.73))
    k = np.broadcast_to(k, got.shape[:2]).reshape(-1)  # (row 0 the top: fragCoord.y < 45 below)
    x, v, r = (got[..., i].reshape(-1) for i in range(3))
    mesa, written = (k * v) * r, k * (v * r)
    assert (_bits(mesa) != _bits(written)).any()
    assert (_bits(x) == _bits(mesa)).all()


def test_llvmpipe_sinks_the_spheres_constant_into_the_argument(llvmpipe, make_shader):
    """``nSphere(ro + t*rd, sph)`` is ``(ro - sph.xyz) + t*rd`` on every value (the division
    by 1.0 dropped), not ``(ro + t*rd) - sph.xyz``."""
    got = render(make_shader(NORMAL), "gl", frame=0).reshape(-1, 4)
    n, ro, trd = got[:, 0], got[:, 1], got[:, 2]
    mesa, written = (ro - F(1.0)) + trd, (ro + trd) - F(1.0)
    assert (_bits(mesa) != _bits(written)).any()
    assert (_bits(n) == _bits(mesa)).all()


@pytest.mark.parametrize("name", sorted(ENGINE_SHADERS))
def test_numpy_merges_the_cameras_constant_into_the_spheres(
    renders_as_llvmpipe, make_shader, monkeypatch, name
):
    """The NumPy engine gives the driver's bits, and without the hidden ray arguments it does
    not (the merge is what these shapes test)."""
    from glslcheck.backends.cpu_core.nir_fold import ray_dots

    shader = make_shader(ENGINE_SHADERS[name])
    _, want = renders_as_llvmpipe(shader, "numpy", name=name, frame=0)
    monkeypatch.setattr(ray_dots, "_live", lambda tr: set())
    assert differing_pixels(render(make_shader(ENGINE_SHADERS[name]), "numpy", frame=0), want)


@pytest.mark.parametrize("lanes", [0, 8])
@pytest.mark.parametrize("name", sorted(ENGINE_SHADERS))
def test_compiled_merges_the_cameras_constant_into_the_spheres(
    llvmpipe, numba, make_shader, name, lanes
):
    """The compiled engine per pixel and in lockstep (its `lanes`), against the driver."""
    from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate

    shader = make_shader(ENGINE_SHADERS[name])
    want = render(shader, "gl", frame=0)
    got = CompiledProgram(*generate(shader, lanes=lanes)).render(size=SIZE, time=0.0, frame=0)
    assert_same(got, want, what=f"{name}, lanes {lanes}", names=("compiled", "llvmpipe"))
