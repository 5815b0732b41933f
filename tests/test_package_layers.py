"""The package's floor plan: each stage imports only the stages below it, and nothing circles.

The import graph is read from the source (the AST) of every module of glslcheck/, imports inside
functions included: such an import closes a circle just the same when it runs. Importing
`a.b.c` also runs the packages `a` and `a.b`, so an import counts as one of each package above
its target too (except the importer's own packages, which are loaded already).
"""

from __future__ import annotations

import ast
import os
import sys

import glslcheck
from glslcheck.base.recursion import deep_recursion

ROOT = os.path.dirname(glslcheck.__file__)

# Lowest first; packages on one floor may not import each other.
LAYERS = [
    ["glslcheck.base"],
    ["glslcheck.shadertoy"],
    ["glslcheck.language"],
    ["glslcheck.frontend"],
    ["glslcheck.semantics"],
    ["glslcheck.lint", "glslcheck.backends"],
    ["glslcheck.verification"],
    ["glslcheck.cli"],
    ["glslcheck", "glslcheck.__main__"],
]
# Floors inside glslcheck.backends, lowest first, read as LAYERS are: the two CPU engines are
# siblings over what they share (cpu_core, llvmpipe_math, driver_profile) and never import each
# other; gl and webgl are siblings over driver_log; tiered and multipass run the engines'
# programs; the registry names every backend.
BACKEND_FLOORS = [
    [
        "glslcheck.backends.interface",
        "glslcheck.backends.driver_profile",
        "glslcheck.backends.driver_log",
        "glslcheck.backends.llvmpipe_math",
    ],
    ["glslcheck.backends.cpu_core"],
    [
        "glslcheck.backends.numpy_engine",
        "glslcheck.backends.compiled_engine",
        "glslcheck.backends.gl",
        "glslcheck.backends.webgl",
    ],
    ["glslcheck.backends.tiered", "glslcheck.backends.multipass"],
    ["glslcheck.backends.registry"],
]
# Written by tools, not by hand: exempt from the size limit.
GENERATED = {"glslcheck.base._init_code", "glslcheck.base._regex_code"}
MAX_LINES = 1000


def _modules() -> dict[str, str]:
    out = {}
    for folder, dirs, files in os.walk(ROOT):
        dirs[:] = [d for d in dirs if d != "__pycache__"]
        for f in files:
            if f.endswith(".py"):
                rel = os.path.relpath(os.path.join(folder, f), ROOT)[:-3].split(os.sep)
                if rel[-1] == "__init__":
                    rel = rel[:-1]
                out[".".join(["glslcheck", *rel])] = os.path.join(folder, f)
    return out


MODULES = _modules()


def _ancestors(name: str) -> list[str]:
    parts = name.split(".")
    return [".".join(parts[:k]) for k in range(1, len(parts))]


def _imports(name: str, top_level_only: bool = False) -> list[tuple[str, int, list[str]]]:
    """(imported module, line, the names taken from it) for each import in module `name`
    (`top_level_only`: those outside functions)."""
    path = MODULES[name]
    tree = ast.parse(open(path, encoding="utf-8").read(), path)
    package = name if path.endswith("__init__.py") else name.rpartition(".")[0]
    in_function: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            in_function.update(id(n) for n in ast.walk(node) if n is not node)
    found = []
    for node in ast.walk(tree):
        if top_level_only and id(node) in in_function:
            continue
        if isinstance(node, ast.Import):
            pairs = [(a.name, []) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = package
            for _ in range(node.level - 1):
                base = base.rpartition(".")[0]
            base = (f"{base}.{node.module}" if node.module else base) if node.level else node.module
            pairs = [
                (f"{base}.{a.name}", []) if f"{base}.{a.name}" in MODULES else (base, [a.name])
                for a in node.names
            ]
        else:
            continue
        for target, names in pairs:
            while target not in MODULES and "." in target:
                target = target.rpartition(".")[0]
            if target in MODULES and target != name:
                found.append((target, node.lineno, names))
    return found


def _edges() -> dict[str, set[str]]:
    """Module -> the modules importing it runs (its target and the target's packages)."""
    edges: dict[str, set[str]] = {}
    for name in MODULES:
        own = set(_ancestors(name))
        out = edges.setdefault(name, set())
        for target, _, _ in _imports(name):
            for m in [*_ancestors(target), target]:
                if m in MODULES and m not in own and m != name:
                    out.add(m)
    return edges


def _layer(name: str, layers: list[list[str]] = LAYERS) -> tuple[int, str]:
    """(floor, the package of `layers` that holds `name`); (-1, "") when none does."""
    best = (-1, "")
    for floor, packages in enumerate(layers):
        for p in packages:
            if (name == p or name.startswith(p + ".")) and len(p) > len(best[1]):
                best = (floor, p)
    return best


def test_every_module_is_on_a_floor():
    assert [m for m in MODULES if _layer(m)[0] < 0] == []


def _breaks(imports: dict[str, list[tuple[str, int, list[str]]]], layers: list[list[str]]):
    """Each import of `imports` (module -> its _imports) that runs up or sideways on `layers`,
    as `file:line: ...`; a module or target on none of the floors is not judged here."""
    bad = []
    for name in sorted(imports):
        floor, home = _layer(name, layers)
        if floor < 0:
            continue
        for target, line, _ in imports[name]:
            if name.startswith(target + "."):
                continue  # its own package
            t_floor, t_home = _layer(target, layers)
            if t_floor > floor or (t_floor == floor and t_home != home):
                bad.append(
                    f"{MODULES.get(name, name)}:{line}: {name} imports {target} ({t_home} is not "
                    f"below {home})"
                )
    return bad


def test_no_import_runs_up_or_sideways():
    assert _breaks({m: _imports(m) for m in MODULES}, LAYERS) == []


def test_every_backend_module_is_on_a_backend_floor():
    inside = [m for m in MODULES if m.startswith("glslcheck.backends.")]
    assert inside and [m for m in inside if _layer(m, BACKEND_FLOORS)[0] < 0] == []


def test_no_backend_imports_a_sibling_or_a_higher_floor():
    """numpy_engine and compiled_engine share through cpu_core, never through each other."""
    inside = [m for m in MODULES if m.startswith("glslcheck.backends.")]
    assert _breaks({m: _imports(m) for m in inside}, BACKEND_FLOORS) == []


def test_the_floor_checker_finds_a_sideways_and_an_upward_import():
    engine, numpy = "glslcheck.backends.compiled_engine.codegen", "glslcheck.backends.numpy_engine"
    imports = {
        engine: [(f"{numpy}.transpile", 7, []), ("glslcheck.backends.cpu_core.facts", 8, [])],
        "glslcheck.backends.cpu_core.facts": [("glslcheck.backends.tiered", 9, [])],
        "glslcheck.backends.tiered": [
            (f"{numpy}.program", 3, []),
            ("glslcheck.base.config", 4, []),
        ],
    }
    bad = _breaks(imports, BACKEND_FLOORS)
    assert [b.split(": ", 1)[0].rpartition(":")[2] for b in bad] == ["7", "9"]
    assert f"({numpy} is not below glslcheck.backends.compiled_engine)" in bad[0]
    assert "(glslcheck.backends.tiered is not below glslcheck.backends.cpu_core)" in bad[1]


def _circles(edges: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components of more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in edges.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                out.append(sorted(component))

    with deep_recursion():  # (the walk recurses along chains of imports)
        for v in sorted(edges):
            if v not in index:
                visit(v)
    return out


def test_no_import_circle():
    assert _circles(_edges()) == []


def test_the_circle_finder_finds_a_circle():
    assert _circles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]


def test_no_private_name_is_imported_from_another_package():
    bad = []
    for name in sorted(MODULES):
        package = name if MODULES[name].endswith("__init__.py") else name.rpartition(".")[0]
        for target, line, names in _imports(name):
            t_package = (
                target if MODULES[target].endswith("__init__.py") else target.rpartition(".")[0]
            )
            private = [n for n in names if n.startswith("_") and not n.startswith("__")]
            if private and t_package != package:
                bad.append(f"{MODULES[name]}:{line}: {', '.join(private)} from {target}")
    assert bad == []


def test_no_hand_written_module_is_over_a_thousand_lines():
    long = {
        m: n
        for m in MODULES
        if m not in GENERATED
        and (n := sum(1 for _ in open(MODULES[m], encoding="utf-8"))) > MAX_LINES
    }
    assert long == {}


def test_the_reader_sees_imports_inside_functions():
    # the registry imports each backend's record only when asked (importlib); multipass is imported
    # inside a function: the graph must hold it, or the circle test would pass on nothing
    inside = {t for t, _, _ in _imports("glslcheck.backends.registry")}
    top = {t for t, _, _ in _imports("glslcheck.backends.registry", top_level_only=True)}
    assert "glslcheck.backends.multipass" in inside - top


def test_the_frame_modules_import_each_other_at_the_top():
    """The NumPy engine's modules that render frames (program and workers, and tiles, which both
    use) name what they use of each other at the top of the file, never inside a function."""
    frame = {f"glslcheck.backends.numpy_engine.{m}" for m in ("program", "workers", "tiles")}
    late = [
        f"{MODULES[m]}:{line} imports {t} inside a function"
        for m in sorted(frame)
        for t, line, _ in _imports(m)
        if t in frame and (t, line) not in {(u, n) for u, n, _ in _imports(m, top_level_only=True)}
    ]
    assert late == []


def test_no_module_is_named_after_a_standard_library_module():
    assert [m for m in MODULES if m.rpartition(".")[2] in sys.stdlib_module_names] == []
