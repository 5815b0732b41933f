"""NumPy backend: the GLSL-to-Python transpiler and the runtime its output calls (``runtime``)."""

from .program import NumpyProgram, compile_numpy, load_module  # noqa: E402,F401
from .transpile import transpile, transpile_shader  # noqa: E402,F401
