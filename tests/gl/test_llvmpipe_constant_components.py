"""A vector built with a constant component, measured on llvmpipe: NIR splits vectors into
components, so that component's constant takes part in the constant rules of every operation
on the vector.

A path tracer's camera, ``vec3 orig = vec3(off, -6.0)`` with ``w = normalize(orig)`` and
``ll = orig - ... - 7.0 * w``: w's z is ``-6.0 * rsq(dot(orig, orig))``, and ``7.0 * w``'s z
merges the two constants (``#a * (b * #c) -> (a*c) * b``, constant_merge.py's rule) into
``-42.0 * rsq``; ``dir = ll + s * h + t * v - orig`` subtracts the constant -6.0 again in z,
which sinks through the sums (sink.py's rule) and cancels the -6.0 inside ll. Each shader
writes the operands the driver computed to the other channels, and the test computes Mesa's
order and the written one from them in NumPy float32. Measured (160x90): the product, Mesa's
order on 14,400 of 14,400 values, the written one on 11,688; the camera ray's z, Mesa's on
14,310 of 14,310, the written one on 169; with ll read a second time (the sum its z ends in
used twice) the -6.0 still cancels: Mesa's on 14,151 of 14,151, the written one on 1,585.
Both CPU engines (nir_fold/constant_components.py) render these shaders, and a negated
component times a constant, as the driver does; the camera split into a function returning a
struct and one reading its fields too (cpu_core/call_fold.py: the written order differed from
the driver in z on 14,231 of 14,400 pixels), and p05-3lccz8's camera, whose get_ray returns a
struct (the call as written differed in z on 2,114 pixels), also with the lens offset drawn
from a loop that advances a global seed (1,534 pixels). Written for llvmpipe of Mesa 22.3."""

from __future__ import annotations

import numpy as np
import pytest
from image_bits import SIZE, assert_same, render

F = np.float32
CAMERA = """
    vec2 off = vec2(-6.0, 3.0) - abs(iMouse.xy) / iResolution.xy * vec2(-12.0, 4.0)
        + fragCoord * 0.001;
    vec3 orig = vec3(off, -6.0);
    vec3 w = normalize(orig);
"""


def _bits(values):
    return np.asarray(values, F).view(np.int32)


PRODUCT = (
    "void mainImage(out vec4 c, in vec2 fragCoord) {"
    + CAMERA
    + "    c = vec4(7.0 * w.z, inversesqrt(dot(orig, orig)), 0.0, 1.0);\n}"
)
# The first column writes h, v and rsq (the camera is uniform), the others z, t and s; READ_LL
# is a second read of ll, in the bottom row's alpha.
RAY = """void mainImage(out vec4 c, in vec2 fragCoord) {
    vec2 off = vec2(-6.0, 3.0) - abs(iMouse.xy) / iResolution.xy * vec2(-12.0, 4.0);
    vec3 orig = vec3(off, -6.0);
    vec3 w = normalize(orig);
    vec3 u = normalize(cross(vec3(0.0, 1.0, 0.0), w));
    vec3 v = cross(w, u);
    vec3 hor = 12.44 * u;
    vec3 ver = 3.75 * v;
    vec3 ll = orig - hor / 2.0 - ver / 2.0 - 7.0 * w;
    vec2 st = fragCoord / iResolution.xy;
    vec3 dir = ll + st.x * hor + st.y * ver - orig;
    c = vec4(dir.z, st.y, st.x, 1.0);READ_LL
    if (fragCoord.x < 1.0) c = vec4(hor.z, ver.z, inversesqrt(dot(orig, orig)), 1.0);
}"""
RAYS = {"ll_read_once": "", "ll_read_twice": "\n    if (fragCoord.y < 1.0) c.w = ll.z;"}
# A negated component times a constant: ``-x * #c`` is ``-(x * #c)``, x's constant merged.
NEGATED = (
    "void mainImage(out vec4 c, in vec2 fragCoord) {"
    + CAMERA
    + "    vec3 a = 7.0 * w;\n    vec3 b = w * 0.5 + 2.0;\n"
    + "    c = vec4(a.z, b.z, -w.z * 3.0, 1.0);\n}"
)
# The camera through a function returning a struct and one taking it (p05-3lccz8's shape): NIR
# inlines both, so the call's -6.0 takes part in the callees' constant rules (call_fold.py).
THROUGH_CALLS = """struct cam { vec3 o; vec3 ll; vec3 h; vec3 v; };
cam make(vec3 orig, float fd) {
    cam r;
    vec3 w = normalize(orig);
    vec3 u = normalize(cross(vec3(0.0, 1.0, 0.0), w));
    r.o = orig;
    r.h = 12.44 * u;
    r.v = 3.75 * cross(w, u);
    r.ll = orig - r.h / 2.0 - r.v / 2.0 - fd * w;
    return r;
}
vec3 ray(cam k, float s, float t) { return k.ll + s * k.h + t * k.v - k.o; }
void mainImage(out vec4 c, in vec2 fragCoord) {
    vec2 off = vec2(-6.0, 3.0) - abs(iMouse.xy) / iResolution.xy * vec2(-12.0, 4.0);
    cam k = make(vec3(off, -6.0), 7.0);
    vec2 st = fragCoord / iResolution.xy;
    c = vec4(ray(k, st.x, st.y), 1.0);
}"""
# p05-3lccz8's camera: a maker returning a struct (radians and tan of its constant 30.0, the
# -6.0 of orig), and get_ray returning a struct `ray` from the camera's fields; NIR inlines both
# and the -6.0 cancels in the ray's z as above (the engines build the struct from its members'
# terms: call_fold.py). The driver's tan(radians(30.0)/2.0) folded at compile time has the bits
# of the engines' run-time tan here (see the tan test below: not for every constant).
CAMERA_MAKER = """struct camera {
    vec3 origin; vec3 lower_left_corner; vec3 horizontal; vec3 vertical; vec3 u, v, w;
    float lens_radius;
};
struct ray { vec3 origin; vec3 dir; };
camera cameraCreator(vec3 orig, vec3 lookat, vec3 up, float vfov, float aspect_ratio,
                     float aperture, float focus_dist) {
    camera outCam;
    float theta = radians(vfov);
    float h = tan(theta / 2.0);
    float viewport_height = 2.0 * h;
    float viewport_width = aspect_ratio * viewport_height;
    vec3 w = normalize(orig - lookat);
    vec3 u = normalize(cross(up, w));
    vec3 v = cross(w, u);
    outCam.origin = orig;
    outCam.horizontal = focus_dist * viewport_width * u;
    outCam.vertical = focus_dist * viewport_height * v;
    outCam.lower_left_corner = orig - outCam.horizontal / 2.0 - outCam.vertical / 2.0
        - focus_dist * w;
    outCam.lens_radius = aperture / 2.0;
    outCam.u = u;
    outCam.v = v;
    outCam.w = w;
    return outCam;
}
"""
CAMERA_AT = """
    float aspect = iResolution.x / iResolution.y;
    vec2 off = vec2(-6, 3) - abs(iMouse.xy) / iResolution.xy * vec2(-12.0, 4.0);
    float aperture = 0.4;
    float focus_dist = 7.0;
    camera cam = cameraCreator(vec3(off, -6), vec3(0), vec3(0, 1, 0), 30.0, aspect, aperture,
        focus_dist);
    vec2 uv = fragCoord.xy / iResolution.xy;
"""
STRUCT_CAMERA = (
    CAMERA_MAKER
    + """ray get_ray(camera cam, float s, float t) {
    return ray(cam.origin, cam.lower_left_corner + s * cam.horizontal + t * cam.vertical
        - cam.origin);
}
void mainImage(out vec4 c, in vec2 fragCoord) {"""
    + CAMERA_AT
    + """    ray r = get_ray(cam, uv.x, uv.y);
    c = vec4(r.dir, 1.0);
}"""
)
# The whole of p05-3lccz8's get_ray: the lens offset drawn by random_in_unit_disk() (a loop
# that advances the global seed) is an unknown value inside the folded terms, the call made
# once where get_ray's arguments have been read; get_ray called in the sample loop, whose
# hash2 advances the seed too (call_fold.py's opaque calls).
LENS_CAMERA = (
    CAMERA_MAKER
    + """uint base_hash(uvec2 p) {
    p = 1103515245U * ((p >> 1U) ^ (p.yx));
    uint h32 = 1103515245U * ((p.x) ^ (p.y >> 3U));
    return h32 ^ (h32 >> 16);
}
float g_seed = 0.0;
vec2 hash2(inout float seed) {
    uint n = base_hash(floatBitsToUint(vec2(seed += 0.1, seed += 0.1)));
    uvec2 rz = uvec2(n, n * 48271U);
    return vec2(rz.xy & uvec2(0x7fffffffU)) / float(0x7fffffff);
}
vec3 random_in_unit_disk() {
    while (true) {
        vec3 p = vec3(hash2(g_seed) - vec2(0.5), 0.0);
        if (dot(p, p) >= 1.0) continue;
        return p;
    }
}
ray get_ray(camera cam, float s, float t) {
    vec3 rd = cam.lens_radius * random_in_unit_disk();
    vec3 offset = cam.u * rd[0] + cam.v * rd[1];
    return ray(cam.origin + offset,
        cam.lower_left_corner + s * cam.horizontal + t * cam.vertical - cam.origin - offset);
}
void mainImage(out vec4 c, in vec2 fragCoord) {
    g_seed = float(base_hash(floatBitsToUint(fragCoord))) / float(0xffffffffU) + iTime;"""
    + CAMERA_AT
    + """    vec3 acc = vec3(0.0);
    for (int i = 0; i < 4; ++i) {
        vec2 sloc = 2.0 * (hash2(g_seed) / iResolution.xy) + uv;
        ray r = get_ray(cam, sloc.x, sloc.y);
        acc += r.dir;
    }
    c = vec4(acc, 1.0);
}"""
)


def _tan_constants() -> list[float]:
    """Angles in degrees: every 5 from 5 to 175 and 60 drawn uniformly from 1 to 179 (float32)."""
    drawn = np.random.default_rng(1).uniform(1.0, 179.0, 60)
    return [float(F(v)) for v in np.concatenate([np.arange(5.0, 176.0, 5.0), drawn])]


TAN_VFOVS = _tan_constants()
# Pixel column i: 2.0 * tan(radians(vfov) / 2.0) of constant i passed to a function (folded at
# compile time after inlining), and of the same value through a uniform's max (at run time).
TAN_CONSTANTS = (
    "float vh(float vfov) { float h = tan(radians(vfov) / 2.0); return 2.0 * h; }\n"
    "void mainImage(out vec4 c, in vec2 fragCoord) {\n    c = vec4(0.0);\n"
    + "\n".join(
        f"    if (int(fragCoord.x) == {i}) c = vec4(vh({v!r}), vh(max(abs(iMouse.x), {v!r})),"
        " 0.0, 1.0);"
        for i, v in enumerate(TAN_VFOVS)
    )
    + "\n}"
)

SHADERS = {
    "product": PRODUCT,
    "through_calls": THROUGH_CALLS,
    "struct_camera": STRUCT_CAMERA,
    "lens_camera": LENS_CAMERA,
    "tan_constants": TAN_CONSTANTS,
    "negated_product": NEGATED,
    **{"ray_" + k: RAY.replace("READ_LL", v) for k, v in RAYS.items()},
}


def test_llvmpipe_merges_a_product_into_a_constant_component(llvmpipe, make_shader):
    """``7.0 * normalize(vec3(off, -6.0)).z`` is ``-42.0 * rsq``, not ``7.0 * (-6.0 * rsq)``
    (the rsq read back through an ``inversesqrt`` NIR's CSE shares with the normalize)."""
    got = render(make_shader(PRODUCT), "gl", frame=0).reshape(-1, 4)
    r = got[:, 1]
    mesa, written = F(-42.0) * r, F(7.0) * (F(-6.0) * r)
    assert (_bits(mesa) != _bits(written)).any()
    assert (_bits(got[:, 0]) == _bits(mesa)).all()


@pytest.mark.parametrize("read", sorted(RAYS))
def test_llvmpipe_cancels_a_constant_component_through_sums(llvmpipe, make_shader, read):
    """The camera ray's z, ``((ll + s*h) + t*v) - orig`` with ll's z ``((-6 - h/2) - v/2) -
    7*w``, is ``(((-(h/2) - v/2) - (-42*rsq)) + s*h) + t*v``: the two -6.0 cancel, also
    where ll is read again."""
    got = render(make_shader(RAY.replace("READ_LL", RAYS[read])), "gl", frame=0)
    hz, vz, r = got[0, 0, :3]
    z, t, s = (got[:-1, 1:, k] for k in range(3))  # (the bottom row may hold ll.z)
    half = F(0.5)
    mesa = ((((-(hz * half)) - vz * half) - F(-42.0) * r) + s * hz) + t * vz
    written = (
        ((((F(-6.0) - hz * half) - vz * half) - F(7.0) * (F(-6.0) * r)) + s * hz) + t * vz
    ) - F(-6.0)
    assert (_bits(mesa) != _bits(written)).any()
    assert (_bits(z) == _bits(mesa)).all()


@pytest.mark.parametrize("name", sorted(SHADERS))
@pytest.mark.parametrize("backend", ["numpy", "compiled"])
def test_engines_follow_constant_components_as_mesa(
    renders_as_llvmpipe, make_shader, backend, name
):
    renders_as_llvmpipe(make_shader(SHADERS[name]), backend, name=name, frame=0)


@pytest.mark.parametrize("lanes", [0, 8])
@pytest.mark.parametrize("name", sorted(SHADERS))
def test_compiled_follows_constant_components_as_mesa(llvmpipe, numba, make_shader, name, lanes):
    """The compiled engine per pixel and in lockstep (its `lanes`), against the driver."""
    from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate

    shader = make_shader(SHADERS[name])
    want = render(shader, "gl", frame=0)
    got = CompiledProgram(*generate(shader, lanes=lanes)).render(size=SIZE, time=0.0, frame=0)
    assert_same(got, want, what=f"{name}, lanes {lanes}", names=("compiled", "llvmpipe"))


def test_llvmpipe_folds_tan_of_a_constant_argument_with_the_host_sinf(llvmpipe, make_shader):
    """``2.0 * tan(radians(vfov) / 2.0)`` in a function called with a constant vfov (p05-3lccz8's
    cameraCreator) is folded at compile time, after inlining, as the C library's float32
    ``sinf(x) / cosf(x)`` (Mesa's GLSL tan is sin/cos; nir_opt_constant_folding computes fsin
    and fcos with the host's sinf and cosf), not as gallivm's tan at run time (TAN_CONSTANTS:
    the folded value and the run-time one of each constant)."""
    import ctypes
    import ctypes.util
    import math

    libm = ctypes.CDLL(ctypes.util.find_library("m"))
    for name in ("sinf", "cosf"):
        getattr(libm, name).restype = ctypes.c_float
        getattr(libm, name).argtypes = [ctypes.c_float]
    got = render(make_shader(TAN_CONSTANTS), "gl", frame=0)[0, : len(TAN_VFOVS)]
    x = [F(F(v) * F(math.pi / 180.0)) / F(2.0) for v in TAN_VFOVS]  # (radians: x * (pi/180))
    host = [F(2.0) * (F(libm.sinf(float(a))) / F(libm.cosf(float(a)))) for a in x]
    assert (_bits(got[:, 0]) != _bits(got[:, 1])).any()  # (the run-time tan differs)
    assert (_bits(got[:, 0]) == _bits(host)).all()
