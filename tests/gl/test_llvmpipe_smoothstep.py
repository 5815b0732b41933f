"""A constant times a smoothstep, rendered by llvmpipe and by both CPU engines bit for bit.

Mesa lowers ``smoothstep(e0, e1, x)`` to ``t * (t * (3 - 2t))`` and nir_opt_algebraic sinks a
constant into that product where both products are used once: ``#k * smoothstep(..)`` is
``(t*k) * (t*(3 - 2t))`` (nir_fold/smoothstep_products.py). Where either is used twice
(the same call written twice, a local read twice) the written order stays.

Written for llvmpipe of the emulated Mesa (the `llvmpipe` fixture of tests/conftest.py skips
elsewhere, naming the driver)."""

from __future__ import annotations

import pytest

# glossy_mirror's roughness as a smoothstep of a dot product, read by a product too; varying
# edges through a local read once; the constant on the right. w: the product read twice, and a
# smoothstep written twice: the written order.
SCALED_SMOOTHSTEPS = """void mainImage(out vec4 c, in vec2 p) {
    vec2 uv = (2.0 * p - iResolution.xy) / iResolution.y;
    vec3 dir = normalize(vec3(uv.x, uv.y - 0.3, -2.0));
    vec3 side = normalize(vec3(sin(0.5 * iTime), 0.6, cos(0.5 * iTime)));
    float a = fract(p.x * 0.01371 + p.y * 0.00917), b = sin(p.y * 0.0917 + p.x * 0.0311);
    float d = fract(p.x * 0.01377 + p.y * 0.0311);
    float rough = 1.0 + 24.0 * smoothstep(0.0, 1.0, dot(-dir, side) * 2.0);
    vec3 wide = dir * rough;
    float s = smoothstep(d * 0.5, b, a);
    float once = 24.0 * smoothstep(0.2, 0.8, d);
    float twice = 7.3 * smoothstep(0.0, 1.0, a);
    float w = twice * b + twice + 3.7 * smoothstep(0.3, 0.7, b) + smoothstep(0.3, 0.7, b);
    c = vec4(rough + wide.x, 3.7 * s - a, smoothstep(0.0, 1.0, b) * 1.7 + once, w);
}"""
# a vector smoothstep scaled by a vector constant and by a scalar one, each written whole
SCALED_VECTORS = """void mainImage(out vec4 c, in vec2 p) {
    float a = fract(p.x * 0.01371 + p.y * 0.00917), b = sin(p.y * 0.0917 + p.x * 0.0311);
    vec2 v = vec2(2.5, 0.5) * smoothstep(0.1, 0.9, vec2(a, fract(b * 7.0)));
    c = vec4(v, 3.1 * smoothstep(vec2(0.2), vec2(0.7, 0.9), vec2(b, a)));
}"""


@pytest.mark.parametrize("backend", ["numpy", "compiled"])
@pytest.mark.parametrize("time", [0.0, 1.3])
@pytest.mark.parametrize("text", [SCALED_SMOOTHSTEPS, SCALED_VECTORS], ids=["scalars", "vectors"])
def test_a_constant_sinks_into_a_smoothstep_used_once(
    renders_as_llvmpipe, make_shader, backend, time, text
):
    """Measured without nir_fold.smoothstep_products, in both engines alike: the scalars
    differed from llvmpipe in 0 (iTime 0: the roughness clamps to 1 there) or 1133 (iTime
    1.3), 1349 and 3576 of the 14,400 pixels in x, y and z, w equal; the vectors in 3940 (x)
    and 847 (z; y's constant 0.5 scales exactly)."""
    renders_as_llvmpipe(make_shader(text), backend, time=time)
