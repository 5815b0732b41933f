"""glslcheck's version, for every stage that prints or records it (reports, generated modules,
the compiled engine's cache key); the package root re-exports it as `glslcheck.__version__`."""

__version__ = "0.1.0"
