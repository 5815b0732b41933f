"""verify names the GL driver, and says so when the NumPy backend's bit-exact emulation was copied
from another one (glslcheck/backends/driver_profile.py: llvmpipe of Mesa EMULATED_MESA)."""

from __future__ import annotations

import dataclasses
from types import SimpleNamespace

from glslcheck.backends import driver_profile
from glslcheck.verification.verify import compile_backend, verify_frames


def _ctx(renderer: str, version: str) -> SimpleNamespace:
    return SimpleNamespace(info={"GL_RENDERER": renderer, "GL_VERSION": version})


def test_the_mesa_version_is_read_from_gl_version():
    newer = _ctx("llvmpipe (LLVM 17.0.6, 256 bits)", "4.5 (Core Profile) Mesa 24.0.5")
    assert driver_profile.driver_name(newer) == ("llvmpipe (LLVM 17.0.6, 256 bits)", "24.0.5")
    assert not driver_profile.is_emulated(*driver_profile.driver_name(newer))
    note = driver_profile.emulation_note(newer)
    assert "Mesa 24.0.5" in note and f"Mesa {driver_profile.EMULATED_MESA}" in note
    same = _ctx(
        "llvmpipe (LLVM 15.0.6, 256 bits)",
        f"4.5 (Core Profile) Mesa {driver_profile.EMULATED_MESA}.0",
    )
    assert driver_profile.is_emulated(*driver_profile.driver_name(same))
    assert driver_profile.emulation_note(same) is None
    other = _ctx("NVIDIA GeForce RTX 3060/PCIe/SSE2", "4.6.0 NVIDIA 535.54.03")
    assert (
        driver_profile.driver_name(other)[1] is None
        and driver_profile.emulation_note(other) is not None
    )
    # the same Mesa version on another driver (a GPU's) is not the emulated llvmpipe either
    assert not driver_profile.is_emulated("AMD Radeon RX 6600 (radeonsi, navi23)", "22.3.6")


class _OtherMesa:
    """The live context, reporting another Mesa release in GL_VERSION (the rest is the driver's)."""

    def __init__(self, ctx):
        self._ctx = ctx
        self.info = dict(ctx.info, GL_VERSION="4.5 (Core Profile) Mesa 99.1.0")

    def __getattr__(self, name):
        return getattr(self._ctx, name)


def test_a_mismatch_on_another_mesa_says_the_emulation_was_copied_from_another(
    llvmpipe, make_shader
):
    red = make_shader("void mainImage(out vec4 c, in vec2 p) { c = vec4(1.0, 0.0, 0.0, 1.0); }")
    green = make_shader("void mainImage(out vec4 c, in vec2 p) { c = vec4(0.0, 1.0, 0.0, 1.0); }")
    numpy = compile_backend(red, "numpy")
    live = compile_backend(green, "gl")
    (ours,) = verify_frames(red, size=(8, 4), programs=[numpy, live])
    assert not ours.match and ours.notes == ()  # the emulated driver: a mismatch is a mismatch
    assert ours.comparison.to_json()["driver"]["emulated"] is True
    assert ours.comparison.to_json()["driver"]["mesa"].startswith(driver_profile.EMULATED_MESA)
    impl = getattr(live, "impl", live)
    moved = dataclasses.replace(impl, ctx=_OtherMesa(impl.ctx))
    (other,) = verify_frames(red, size=(8, 4), programs=[numpy, moved])
    assert other.comparison.to_json()["driver"] == {
        "renderer": impl.ctx.info["GL_RENDERER"],
        "mesa": "99.1.0",
        "emulated": False,
    }
    assert any(
        "Mesa 99.1.0" in n and f"Mesa {driver_profile.EMULATED_MESA}" in n for n in other.notes
    )
