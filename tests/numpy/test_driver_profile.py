"""The float->uint models of glslcheck/backends/driver_profile.py against what each kind of CPU
measured.

llvmpipe computes ``uint(x)`` of negative, NaN or huge ``x`` (undefined in GLSL ES 3.00) with
whatever instructions the CPU has, so one machine's answer cannot be pinned. These tables were
measured on real drivers (see each) and run on every machine: each model must reproduce its own
table, and `identify` must tell the tables apart, so a test run on an AVX2 machine also checks
the AVX-512 emulation and the other way round. The live driver is checked against its model in
tests/numpy/test_runtime_gl.py.
"""

from __future__ import annotations

import numpy as np
import pytest

from glslcheck.backends import driver_profile
from glslcheck.backends.driver_profile import FLOAT_TO_UINT, PROBE_INPUTS, float_to_uint, identify
from glslcheck.backends.numpy_engine.runtime import Runtime

NAN = float("nan")
INF = float("inf")

# Mesa 22.3.6, llvmpipe (LLVM 15.0.6, 256 bits), AMD EPYC with AVX2 and FMA, no AVX-512:
# tests/numpy/test_runtime_gl.py's uint cases on 2026-12-01, plus driver_profile.measure().
SSE_MEASURED = {
    3.7: 3,
    -0.5: 0,
    -0.99: 0,
    -1.0: 0xFFFFFFFF,
    -3.5: 0xFFFFFFFD,
    -1e9: 0xC4653600,
    -2147483648.0: 0x80000000,
    -3e9: 0x80000000,
    -5e9: 0x80000000,
    5e9: 0x80000000,
    3e9: 0xB2D05E00,
    4294967040.0: 0xFFFFFF00,
    4294967296.0: 0x80000000,
    2147483648.0: 0x80000000,
    2147483520.0: 0x7FFFFF80,
    NAN: 0x80000000,
    INF: 0x80000000,
    -INF: 0x80000000,
    1e20: 0x80000000,
    -1e20: 0x80000000,
}

# The same driver on an x86-64 machine with AVX-512: the values this project's
# test_runtime_gl.py pinned while its CI machines had AVX-512 (every run passed there).
AVX512_MEASURED = {
    -0.5: 0,
    -1.0: 0xFFFFFFFF,
    -3.5: 0xFFFFFFFF,
    5e9: 0xFFFFFFFF,
    NAN: 0xFFFFFFFF,
    3e9: 3000000000,
    4294967040.0: 4294967040,
    INF: 0xFFFFFFFF,
}


def _bits(model: str, table: dict) -> list[int]:
    return float_to_uint(np.array(list(table), dtype=np.float32), model).tolist()


@pytest.mark.parametrize("model, table", [("sse", SSE_MEASURED), ("avx512", AVX512_MEASURED)])
def test_model_reproduces_its_measurement(model, table):
    assert _bits(model, table) == list(table.values())


def test_identify_tells_the_measurements_apart():
    assert identify(SSE_MEASURED) == "sse"
    assert identify(AVX512_MEASURED) == "avx512"
    # a driver that follows none of the models is reported as unknown, not forced into one
    assert identify({-1.0: 12345}) is None


def test_probe_inputs_separate_every_model():
    """A probe render of PROBE_INPUTS names exactly one model, whichever the driver follows."""
    results = {
        name: float_to_uint(np.array(PROBE_INPUTS, dtype=np.float32), name).tolist()
        for name in FLOAT_TO_UINT
    }
    for name, bits in results.items():
        assert identify(bits) == name


def test_in_range_values_agree_in_every_model():
    x = np.array(
        [0.0, 0.5, 1.0, 2.7, 65535.9, 2147483520.0, 2147483648.0, 4294967040.0], dtype=np.float32
    )
    expected = np.trunc(x.astype(np.float64)).astype(np.uint32).tolist()
    for name in FLOAT_TO_UINT:
        assert float_to_uint(x, name).tolist() == expected, name


def test_runtime_follows_its_model_and_defaults_to_the_host():
    x = np.array([-3.5, NAN], dtype=np.float32)
    assert Runtime("float32", float_to_uint="sse").to_uint(x).tolist() == [0xFFFFFFFD, 0x80000000]
    assert Runtime("float32", float_to_uint="avx512").to_uint(x).tolist() == [0xFFFFFFFF] * 2
    assert Runtime("float32").float_to_uint == driver_profile.host_model()
    with pytest.raises(ValueError, match="float_to_uint"):
        Runtime("float32", float_to_uint="pentium")


def test_host_model_from_cpu_flags(monkeypatch):
    monkeypatch.setattr(driver_profile.platform, "machine", lambda: "x86_64")
    for flags, model in [
        ({"sse2", "avx2", "fma"}, "sse"),
        ({"avx2", "avx512f", "avx512vl"}, "avx512"),
        ({"avx512f"}, "sse"),
    ]:
        monkeypatch.setattr(driver_profile, "_cpu_flags", lambda flags=flags: flags)
        driver_profile.host_model.cache_clear()
        assert driver_profile.host_model() == model, flags
    driver_profile.host_model.cache_clear()
