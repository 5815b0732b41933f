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
the test computes Mesa's order and the written one from them in NumPy float32. The CPU
engines do not follow these across the calls yet (docs/llvmpipe.md, "A camera's constant
component reaches a sphere's hit"). Written for llvmpipe of Mesa 22.3."""

from __future__ import annotations

import numpy as np
from image_bits import render

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
