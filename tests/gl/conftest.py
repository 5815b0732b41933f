"""Fixtures of the GL tests: `gl` and `llvmpipe` are in tests/conftest.py (the texture tests
in tests/channels compare bit for bit with llvmpipe too)."""
