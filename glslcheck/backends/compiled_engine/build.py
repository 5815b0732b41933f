"""`python -m glslcheck.backends.compiled_engine.build MODULE.py PATH`: compile one generated
module into numba's cache, in a process of its own (CompiledProgram.build_apart, which stops it
when it runs past its budget). PATH is the shader file the module's errors name. Exit 0 once
the machine code is in the cache; a failure's message goes to stderr, exit 1."""

from __future__ import annotations

import sys


def main(argv: list[str]) -> int:
    from .engine import CompiledProgram

    file, path = argv
    with open(file, encoding="utf-8") as f:
        source = f.read()
    try:
        CompiledProgram(source, path).load(bounded=False)
    except Exception as e:  # noqa: BLE001 - reported to the parent, which decides
        print(f"{type(e).__name__}: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
