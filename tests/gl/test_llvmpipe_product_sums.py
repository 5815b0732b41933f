"""A term added to a sum of two products, ``(p1 + p2) + e``, rendered by llvmpipe and by both CPU
engines bit for bit.

nir_opt_algebraic reassociates ``(a*b + c*d) + e`` into ``(a*b + e) + c*d`` when e is no
product (nir_fold/product_sums.py): a path tracer's seed ``p.x*0.0123 + p.y*0.457 + iTime``
is ``(p.x*0.0123 + iTime) + p.y*0.457``, and a hash of it turns the last bit into another
random direction. Each shader writes the sum to the first channel and two opaque values u and
v (fract of the pixel's coordinates) to the next two; :func:`test_llvmpipe_orders_the_sum`
compares the driver's sum with two orders computed here in NumPy float32 from u, v and the
pixel's coordinates: Mesa's and the other one (the written order where the rule applies,
the reassociated one where it does not), and checks the two differ on some pixels (else the
comparison proves nothing). Measured on llvmpipe of Mesa 22.3 at 160x90, iTime 1.7: each shape
below matches its order on 14,400 of 14,400 values and the other order on 9,000 to 13,000.
Written for llvmpipe of Mesa 22.3 (the `llvmpipe` fixture skips elsewhere).
"""

from __future__ import annotations

import numpy as np
import pytest
from image_bits import SIZE, render

F = np.float32
TIME = 1.7
HEAD = """void mainImage(out vec4 c, in vec2 p) {
    float u = fract(p.x * 0.1371 + p.y * 0.0917) * 40.0, v = fract(p.x * 0.0371 + p.y * 0.917);
    float s = 0.0;
"""
TAIL = "\n    c = vec4(s, u, v, 1.0);\n}"


def _fract(x):
    return (x - np.floor(x)).astype(F)


def _terms(u, v):
    """The terms the shapes add, as llvmpipe computes them (float32), per pixel."""
    cols, rows = np.meshgrid(np.arange(SIZE[0]), np.arange(SIZE[1]))
    x = (cols + 0.5).astype(F).reshape(-1)
    y = (SIZE[1] - rows - 0.5).astype(F).reshape(-1)
    t = F(TIME)
    ratio = F(SIZE[0]) / F(SIZE[1])
    return {
        "a": x * F(0.0123),
        "b": y * F(0.457),
        "t": t,
        "ft": _fract(F(1.12) * t),
        "uv": u * v,
        "uy": u * y,
        "x": x,
        "x37": x * F(0.37),
        "px": (x / F(7.0)) * ratio,
        "py": (y / F(7.0)) * F(3.43),
        "v": v,
    }


# name -> (the body that sets s, (Mesa's order, the other order) as functions of the terms)
SHAPES = {
    "seed_of_a_uniform": (
        "s = p.x * 0.0123 + p.y * 0.457 + iTime;",
        (lambda k: (k["a"] + k["t"]) + k["b"], lambda k: (k["a"] + k["b"]) + k["t"]),
    ),
    "uniform_expression": (
        "s = p.x * 0.0123 + p.y * 0.457 + fract(1.12 * iTime);",
        (lambda k: (k["a"] + k["ft"]) + k["b"], lambda k: (k["a"] + k["b"]) + k["ft"]),
    ),
    "opaque_value_of_the_pixel": (
        "s = u * v + p.y * 0.457 + v;",
        (lambda k: (k["uv"] + k["v"]) + k["b"], lambda k: (k["uv"] + k["b"]) + k["v"]),
    ),
    "subtractions": (
        "s = u * v - p.y * 0.457 - iTime;",
        (lambda k: (k["uv"] - k["t"]) - k["b"], lambda k: (k["uv"] - k["b"]) - k["t"]),
    ),
    "term_before_the_sum": (
        "s = iTime + (u * v + p.x * 0.37);",
        (lambda k: (k["uv"] + k["t"]) + k["x37"], lambda k: k["t"] + (k["uv"] + k["x37"])),
    ),
    "sum_held_in_a_local": (
        "float k = p.x * 0.0123 + p.y * 0.457; s = k + iTime;",
        (lambda k: (k["a"] + k["t"]) + k["b"], lambda k: (k["a"] + k["b"]) + k["t"]),
    ),
    "factorable_sum_reassociated_first": (
        "s = u * v + u * p.y + iTime;",
        (lambda k: (k["uv"] + k["t"]) + k["uy"], lambda k: (k["uv"] + k["uy"]) + k["t"]),
    ),
    "component_multiplied_before": (
        "vec2 q = p / 7.0; q.x *= iResolution.x / iResolution.y;"
        " s = q.x + q.y * 3.43 + fract(1.12 * iTime);",
        (lambda k: (k["px"] + k["ft"]) + k["py"], lambda k: (k["px"] + k["py"]) + k["ft"]),
    ),
    "vector_sum": (
        "vec2 w = p * 0.0123 + p.yx * 0.457 + iTime; s = w.x;",
        (lambda k: (k["a"] + k["t"]) + k["b"], lambda k: (k["a"] + k["b"]) + k["t"]),
    ),
    "kept_beside_a_product": (
        "s = p.x * 0.0123 + p.y * 0.457 + iTime * iTime;",
        (
            lambda k: (k["a"] + k["b"]) + k["t"] * k["t"],
            lambda k: (k["a"] + k["t"] * k["t"]) + k["b"],
        ),
    ),
    "kept_without_two_products": (
        "s = p.x + p.y * 0.457 + iTime;",
        (lambda k: (k["x"] + k["b"]) + k["t"], lambda k: (k["x"] + k["t"]) + k["b"]),
    ),
    "kept_after_three_products": (
        "s = u * v + p.x * 0.37 + p.y * 0.457 + iTime;",
        (
            lambda k: ((k["uv"] + k["x37"]) + k["b"]) + k["t"],
            lambda k: ((k["uv"] + k["t"]) + k["x37"]) + k["b"],
        ),
    ),
    "kept_when_the_sum_is_read_twice": (
        "float k = u * v + p.y * 0.457; s = k + iTime; if (k < -1.0) s = 0.0;",
        (lambda k: (k["uv"] + k["b"]) + k["t"], lambda k: (k["uv"] + k["t"]) + k["b"]),
    ),
}


def _shader(make_shader, name):
    return make_shader(HEAD + "    " + SHAPES[name][0] + TAIL)


@pytest.mark.parametrize("name", sorted(SHAPES))
def test_llvmpipe_orders_the_sum(llvmpipe, make_shader, name):
    """The driver's sum is Mesa's order on every pixel, and the shape tells the orders apart."""
    got = render(_shader(make_shader, name), "gl", time=TIME).reshape(-1, 4)
    mesa, other = SHAPES[name][1]
    k = _terms(got[:, 1], got[:, 2])
    want, other_value = np.asarray(mesa(k), F), np.asarray(other(k), F)
    assert (want.view(np.int32) != other_value.view(np.int32)).any(), name
    assert (got[:, 0].view(np.int32) == want.view(np.int32)).all(), name


@pytest.mark.parametrize("name", sorted(SHAPES))
@pytest.mark.parametrize("backend", ["numpy", "compiled"])
def test_engines_order_the_sum_as_mesa(renders_as_llvmpipe, make_shader, backend, name):
    renders_as_llvmpipe(_shader(make_shader, name), backend, name=name, time=TIME)
