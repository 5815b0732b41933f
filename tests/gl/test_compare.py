"""The tolerance model of glslcheck/verification/compare.py on synthetic images (no GL needed)."""

import json

import numpy as np
import pytest
from PIL import Image

from glslcheck.verification.compare import JSON_KEYS, compare, write_diff_png

H, W = 90, 160


def _gradient():
    y, x = np.mgrid[0:H, 0:W].astype(np.float32)
    img = np.ones((H, W, 4), np.float32)
    img[..., 0], img[..., 1], img[..., 2] = x / W, y / H, 0.3
    return img


def _disc(radius):
    y, x = np.mgrid[0:H, 0:W]
    inside = np.hypot(x + 0.5 - W / 2, y + 0.5 - H / 2) < radius
    img = np.ones((H, W, 4), np.float32)
    img[..., :3] = np.where(inside[..., None], [0.9, 0.6, 0.1], [0.1, 0.2, 0.4])
    return img


def test_equal_images_match():
    c = compare(_gradient(), _gradient())
    assert c.match and c.max_abs_error == 0 and c.mismatched_pixels == 0 and c.edge_pixels == 0
    assert c.to_json()["psnr_db"] is None  # infinite PSNR; JSON has no inf
    assert c.bbox is None and c.worst == []


def test_noise_under_one_level_matches():
    rng = np.random.default_rng(1)
    a = _gradient()
    b = a + ((rng.random(a.shape) * 2 - 1) / 255).astype(np.float32)
    c = compare(a, b)
    assert c.match and 0 < c.max_abs_error <= 1 / 255 + 1e-6 and c.psnr_db > 45


def test_offset_block_mismatches_and_is_located():
    a = _gradient()
    b = a.copy()
    b[20:50, 40:70, :3] += 0.1
    c = compare(a, b)
    assert not c.match
    assert c.mismatched_pixels >= 28 * 28  # the rim may count as a moved edge, the inside never
    assert c.bbox == (40, 20, 70, 50)
    worst = c.worst[0]
    assert worst.kind == "mismatch" and worst.error == pytest.approx(0.1, abs=1e-5)
    assert worst.frag_coord == (worst.x + 0.5, H - worst.y - 0.5)


def test_values_beyond_the_display_range_are_clamped():
    a = _gradient()
    a[..., 0] = 3.5
    b = a.copy()
    b[..., 0] = 7.0  # both show full red
    assert compare(a, b).match


def test_nan_in_both_is_equal_nan_in_one_is_a_mismatch():
    a = _gradient()
    a[5, 6, 1] = np.nan
    a[7, 8, 2] = np.inf
    both = compare(a, a.copy())
    assert both.match and both.nan_numpy == 2 and both.nan_gl == 2 and both.max_abs_error == 0
    one = compare(a, _gradient())
    assert not one.match
    assert (one.nan_numpy, one.nan_gl, one.mismatched_pixels, one.nan_mismatched_pixels) == (
        2,
        0,
        2,
        2,
    )
    assert one.worst[0].kind == "nan"
    b = a.copy()
    b[7, 8, 2] = -np.inf  # +Inf against -Inf: different
    assert not compare(a, b).match


def test_silhouette_differences_are_edges():
    c = compare(_disc(30.0), _disc(30.4))
    assert c.mismatched_pixels == 0 and c.edge_pixels > 0 and c.match
    assert c.max_abs_error > 0.5


def test_too_many_edges_fail():
    # A stripe pattern that shifts by one pixel: every stripe boundary flips.
    x = np.arange(W)
    a = np.ones((H, W, 4), np.float32)
    b = a.copy()
    a[..., :3] = ((x // 2) % 2)[None, :, None]
    b[..., :3] = (((x + 1) // 2) % 2)[None, :, None]
    c = compare(a, b)
    assert c.edge_pixels > 0.005 * H * W and not c.match
    assert c.mismatched_pixels <= H  # only the first column, where no neighbour shows the shift


def test_wrong_colour_on_an_edge_is_not_an_edge():
    a = _disc(30.0)
    b = _disc(30.0)
    b[45, 40:120, :3] = [0.0, 1.0, 0.0]  # a green line crossing the silhouette
    c = compare(a, b)
    assert c.mismatched_pixels == 80 and c.edge_pixels == 0


def test_json_keys_are_exact():
    data = compare(_gradient(), _disc(10)).to_json()
    assert (
        tuple(data)
        == JSON_KEYS
        == (
            "match",
            "verdict",
            "size",
            "max_abs_error",
            "mean_abs_error",
            "psnr_db",
            "mismatched_pixels",
            "edge_pixels",
            "nan_numpy",
            "nan_gl",
            "unstable_pixels",
            "unstable_lines",
            "undefined_pixels",
            "undefined_lines",
            "driver",
        )
    )
    assert data["size"] == [W, H]
    json.dumps(data, allow_nan=False)


def test_uint8_images_and_size_check():
    a = (_gradient() * 255).round().astype(np.uint8)
    assert compare(a, a).match
    with pytest.raises(ValueError):
        compare(_gradient(), _gradient()[:-1])


def test_diff_png_has_the_image_size_and_colours(tmp_path):
    a = _disc(30.0)
    b = _disc(30.4)
    b[10:20, 10:20, :3] += 0.5
    b[2, 3, 0] = np.nan
    path = tmp_path / "diff.png"
    comp = write_diff_png((a, b), path)
    img = np.asarray(Image.open(path))
    assert img.shape == (H, W, 3)
    assert tuple(img[2, 3]) == (255, 0, 255)  # NaN in one image
    assert tuple(img[0, 100]) == (0, 0, 0)  # equal
    assert img[15, 15, 0] == 255 and img[15, 15, 1] > 0  # 0.5 error: yellow-ish
    assert np.all(img[comp.edge_mask] == (0, 200, 255))
