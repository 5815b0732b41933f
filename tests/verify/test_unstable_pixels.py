"""Unstable pixels: where float32 itself cannot compute a pixel, verify says so instead of
reporting a mismatch; a real difference in stable pixels stays a mismatch."""

from __future__ import annotations

import json

import numpy as np

from glslcheck.verification.compare import compare
from glslcheck.verification.verify import compile_backend, verify_frames

H, W = 30, 40


def _images():
    """float64 reference, GL and NumPy renders: identical except a 12x12 block (144 pixels,
    over the 1-pixel budget of 1,200 pixels) where both float32 renders lost precision."""
    ref = np.zeros((H, W, 4))
    ref[..., 0] = np.linspace(0, 1, W)[None, :]
    ref[..., 3] = 1.0
    gl, numpy = ref.astype(np.float32), ref.astype(np.float32)
    gl[5:17, 5:17, 1] = 0.30  # the reference says 0 there; the two float32 renders disagree
    numpy[5:17, 5:17, 1] = 0.60  # with it and with each other
    return ref, numpy, gl


def test_pixels_both_float32_renders_get_wrong_are_unstable_not_mismatched():
    ref, numpy, gl = _images()
    assert not compare(numpy, gl).match
    c = compare(numpy, gl, reference=ref)
    assert c.match and c.verdict == "match-unstable"
    assert c.unstable_pixels == 144 and c.mismatched_pixels == 0
    data = c.to_json()
    assert (
        data["match"] is True
        and data["verdict"] == "match-unstable"
        and data["unstable_pixels"] == 144
    )
    assert data["unstable_lines"] == []  # line attribution needs probe's tracing mode (TODO)
    json.dumps(data, allow_nan=False)


def test_a_real_difference_in_stable_pixels_stays_a_mismatch():
    ref, numpy, gl = _images()
    numpy[20:30, 20:40, 2] = 0.8  # injected: only the NumPy render departs from the reference
    c = compare(numpy, gl, reference=ref)
    assert not c.match and c.verdict == "mismatch"
    assert c.unstable_pixels == 144 and c.mismatched_pixels == 200


def test_nan_in_both_float32_renders_only_is_unstable():
    ref, numpy, gl = _images()
    numpy[0, 0, 0] = np.nan
    gl[0, 0, 0] = np.inf
    c = compare(numpy, gl, reference=ref)
    assert (
        c.nan_mismatched_pixels == 0 and c.unstable_pixels == 145 and c.verdict == "match-unstable"
    )


FAR_CAMERA = """
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 uv = (2.0 * fragCoord - iResolution.xy) / iResolution.y;
    vec3 ro = vec3(0.0, 0.0, 2000.0);
    vec3 rd = normalize(vec3(uv * 0.0006, -1.0));
    float b = dot(ro, rd);
    float cc = dot(ro, ro) - 1.0;
    float h = b * b - cc;
    fragColor = vec4(vec3(h < 0.0 ? 0.0 : 0.5 + 0.5 * sqrt(max(h, 0.0))), 1.0);
}"""


def test_verify_reports_a_verdict_on_an_ill_conditioned_shader(gl, make_shader):
    """A camera 2000 units from a unit sphere: float32 loses most of h's bits. The NumPy backend
    now rounds as llvmpipe does, so the frame matches (or matches once unstable pixels are set
    apart); either way the JSON says which."""
    shader = make_shader(FAR_CAMERA)
    (r,) = verify_frames(shader, size=(64, 36))
    data = r.comparison.to_json()
    assert data["match"] and data["verdict"] in ("match", "match-unstable")


def test_unstable_lines_name_the_statement_that_loses_precision(gl, make_shader, monkeypatch):
    """The far camera's float32 renders are far from float64 where `b * b - cc` cancels
    (`float h = ...`; its operands keep all their bits). Made to disagree with each
    other there, the two renders give unstable pixels, and verify's attribution (probe's float64
    shadow on a sample of them) names that line with the bits it keeps."""
    from glslcheck.verification import verify
    from glslcheck.verification.verify import FrameSpec, unstable_lines

    shader = make_shader(FAR_CAMERA)
    size = (64, 36)
    numpy_side, gl_side = compile_backend(shader, "numpy"), compile_backend(shader, "gl")
    ref = numpy_side.render(size=size, precision="float64")
    gl_img = gl_side.render(size=size)
    far = np.abs(gl_img[..., 0] - ref[..., 0]) > 0.05  # where float32 itself fails
    assert far.sum() > 10
    numpy_img = gl_img.copy()
    numpy_img[..., 0] = np.where(far, 1.0 - numpy_img[..., 0], numpy_img[..., 0])
    c = compare(numpy_img, gl_img, reference=ref)
    assert 10 < c.unstable_pixels <= int(far.sum())  # (flipping a value near 0.5 changes little)
    lines = unstable_lines(
        shader, c, size, FrameSpec(time=0.0, frame=0), (0.0, 0.0, 0.0, 0.0), None
    )
    assert lines, "no line named"
    top = lines[0]
    line = next(i for i, t in enumerate(FAR_CAMERA.split("\n"), 1) if "float h = b * b - cc;" in t)
    assert top["line"] == line and "b * b - cc" in top["code"], lines
    assert top["bits"] < 16 and 0 < top["pixels"] <= c.unstable_pixels
    assert set(top) == {"file", "line", "code", "bits", "pixels", "sampled"}
    assert top["sampled"] == min(verify.UNSTABLE_PROBES, c.unstable_pixels)
    # a step budget one pixel exhausts: one pixel is traced and stands for all of them
    monkeypatch.setattr(verify, "UNSTABLE_STEPS", 1)
    [one] = unstable_lines(
        shader, c, size, FrameSpec(time=0.0, frame=0), (0.0, 0.0, 0.0, 0.0), None
    )
    assert one["sampled"] == 1 and one["pixels"] == c.unstable_pixels and one["line"] == line
