"""The NumPy backend's modules import each other one way: no cycle, and the modules that render
frames (program.py, workers.py and tiles.py, which both of the others use) name what they use
at the top of the file, never inside a function.

The import graph is read from the source (the AST), not from `sys.modules`: an import inside a
function counts as much as one at the top, since it closes a circle just the same when it runs.
Edges to the package itself (`glslcheck/backends/numpy_engine/__init__.py`, which re-exports the API)
are left out: every submodule's import passes through it first, so it is in no circle of
submodules. Subpackages (a `transpile/` folder, say) are walked too.
"""

from __future__ import annotations

import ast
import os

import glslcheck.backends.numpy_engine as backend

PACKAGE = "glslcheck.backends.numpy_engine"
ROOT = os.path.dirname(backend.__file__)
FRAME_LAYER = {f"{PACKAGE}.{m}" for m in ("program", "workers", "tiles")}


def _modules() -> dict[str, str]:
    """Module name -> file, for every module of the backend."""
    out = {}
    for folder, _, files in os.walk(ROOT):
        for f in files:
            if not f.endswith(".py"):
                continue
            rel = os.path.relpath(os.path.join(folder, f), ROOT)[:-3].split(os.sep)
            if rel[-1] == "__init__":
                rel = rel[:-1]
            out[".".join([PACKAGE, *rel])] = os.path.join(folder, f)
    return out


def _imports(name: str, path: str, modules: dict[str, str]) -> list[tuple[str, int, bool]]:
    """(imported backend module, line, at module level) of each import in module `name`."""
    tree = ast.parse(open(path, encoding="utf-8").read(), path)
    package = name if path.endswith("__init__.py") else name.rpartition(".")[0]
    in_function: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            in_function.update(id(n) for n in ast.walk(node) if n is not node)
    found = []
    for node in ast.walk(tree):
        targets = []
        if isinstance(node, ast.Import):
            targets = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = package
            for _ in range(node.level - 1):
                base = base.rpartition(".")[0]
            base = (f"{base}.{node.module}" if node.module else base) if node.level else node.module
            # `from . import workers` imports a submodule; `from .tiles import State` a name of one
            targets = [f"{base}.{a.name}" if f"{base}.{a.name}" in modules else base for a in node.names]
        for t in targets:
            while t not in modules and "." in t:  # `import a.b.c` of a module a.b: the module
                t = t.rpartition(".")[0]
            if t in modules and t != PACKAGE and t != name:
                found.append((t, node.lineno, id(node) not in in_function))
    return found


def _graph() -> dict[str, list[tuple[str, int, bool]]]:
    modules = _modules()
    return {name: _imports(name, path, modules) for name, path in modules.items()}


def _cycle(graph: dict[str, list[tuple[str, int, bool]]]) -> list[str] | None:
    """One import cycle (its modules in order), or None."""
    state: dict[str, int] = {}  # 1: on the current path, 2: done
    path: list[str] = []

    def visit(m: str) -> list[str] | None:
        state[m] = 1
        path.append(m)
        for t, _, _ in graph.get(m, ()):
            if state.get(t) == 1:
                return path[path.index(t):] + [t]
            if t not in state:
                found = visit(t)
                if found:
                    return found
        path.pop()
        state[m] = 2
        return None

    for m in sorted(graph):
        if m not in state:
            found = visit(m)
            if found:
                return found
    return None


def test_the_graph_sees_the_imports_it_is_about():
    # the reader must find the backend's known imports, or the tests below would pass on nothing
    edges = {(m, t) for m, imports in _graph().items() for t, _, _ in imports}
    assert {(f"{PACKAGE}.program", f"{PACKAGE}.workers"), (f"{PACKAGE}.program", f"{PACKAGE}.tiles"),
            (f"{PACKAGE}.workers", f"{PACKAGE}.tiles")} <= edges
    assert _cycle({"a": [("b", 1, True)], "b": [("c", 1, False)], "c": [("a", 1, True)]}) == ["a", "b", "c", "a"]


def test_the_numpy_backend_has_no_import_cycle():
    assert _cycle(_graph()) is None


def test_the_frame_modules_import_each_other_at_the_top():
    late = [f"{os.path.relpath(_modules()[m], ROOT)}:{line} imports {t} inside a function"
            for m, imports in _graph().items() if m in FRAME_LAYER
            for t, line, top in imports if t in FRAME_LAYER and not top]
    assert not late
