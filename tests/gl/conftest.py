"""Fixtures of the GL tests."""

from __future__ import annotations

import pytest

from glslcheck import driver_profile


@pytest.fixture
def llvmpipe(gl):
    """The GL context, for the tests that compare the NumPy backend with the driver bit for bit.

    They were written for llvmpipe of Mesa 22.3 (`driver_profile.EMULATED_MESA`; measured with
    22.3.6 and LLVM 15.0.6): the NumPy backend's float32 mode copies that release's algorithms
    (gallivm's sin/exp2/log2, nir_opt_algebraic's rewrites, nir_lower_flrp's choice). Another
    Mesa may compute other bits. That is a failure, not a skip, also on CI: CI's Mesa is the one
    the project promises to match, so a CI image with another Mesa means the emulation must be
    measured and copied again for it (and EMULATED_MESA moved), not that the tests stop checking."""
    renderer, mesa = driver_profile.driver_name(gl)
    if not driver_profile.is_emulated(renderer, mesa):
        pytest.fail(f"these bit-exact tests were written for llvmpipe of Mesa {driver_profile.EMULATED_MESA}; "
                    f"this GL driver is {renderer}, Mesa {mesa or 'unknown'}: the NumPy emulation "
                    "(glslcheck/driver_profile.py, numpy_backend/runtime.py, nir_fold.py) must be re-measured "
                    "for it before these results mean anything")
    return gl
