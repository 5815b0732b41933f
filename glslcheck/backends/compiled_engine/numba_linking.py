"""A generated module's machine code emitted once, by its entries, the functions that run it.

numba compiles each @njit function into a code library of its own and finalizes it at once: the
library's module passes (LLVM's O3 pipeline), then its machine code, which the cache writes too
(object code and bitcode). A caller links each callee's optimized module in as `linkonce_odr`
and optimizes and emits the whole again. Only a module's entries (`render_rows`,
`globals_template`: the functions with a Python wrapper) are ever called from Python, and their
machine code holds every function they call. `replace()` (installed by numba_patches) finalizes the
other functions of a generated module (`module_text`'s `jit`: no Python wrapper; a module named
`MODULE_PREFIX`...) as numba does up to the module passes (their callees linked in, then optimized:
the IR their callers link in), but adds nothing to the execution engine: no machine code, and no
cache entry (nothing to write; a module loaded from the cache runs its entries' code, which needs
none of theirs). Every other library (the scalar runtime's, lanes_math's, any other program's) is
numba's own. Only for the numba versions this was checked against (`CHECKED`); `numba_own()`
suspends it (the reference the tests compare with).

What a caller links in is the optimizer's output; under numba's own it is that module after
the execution engine's code generation rewrote its IR in place (loop strength reduction, loop
preheaders), so an entry's machine code can differ where that changed LLVM's inlining: the same
operations, the same bits. Skipping the callees' module passes too (the entries optimize what
they link in anyway) gave code that ran slower (docs/performance.md, "Compile time").
"""

from __future__ import annotations

import contextlib
import threading
import weakref
from collections.abc import Iterator
from typing import Any

from .numba_swaps import swap

CHECKED = ("0.68.",)  # the numba versions whose CPUContext.get_executable and cache this wraps
MODULE_PREFIX = "glslcheck_compiled_m"  # the generated modules' names (engine.CompiledProgram)
_STATE: dict[str, Any] = {}
_LOCK = threading.Lock()
_LINKED: weakref.WeakSet = weakref.WeakSet()  # the libraries finalized here (linking only)
_ENVS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # such a library -> (name, env)


def _linking_only(library: Any, fndesc: Any) -> bool:
    """Whether library is a generated module's function with no Python wrapper, not finalized."""
    if getattr(library, "_finalized", True) or not str(fndesc.modname).startswith(MODULE_PREFIX):
        return False
    if _STATE.get("suspended"):
        return False
    try:
        library._final_module.get_function(fndesc.llvm_cpython_wrapper_name)
    except NameError:
        return True
    return False


def _finalize_linking(library: Any) -> None:
    """numba's CPUCodeLibrary.finalize without the execution engine's module and its machine
    code: the callees' modules linked in (each finalized first), the module passes, the check."""
    from numba.core.compiler_lock import require_global_compiler_lock

    require_global_compiler_lock()
    seen = set()
    for lib in library._linking_libraries:
        if lib not in seen:
            library._reload_init.update(lib._reload_init)
            seen.add(lib)
            library._final_module.link_in(lib._get_module_for_linking(), preserve=True)
    library._optimize_final_module()  # the IR its callers link in (numba's passes, numba's order)
    library._final_module.verify()
    library._finalize_dynamic_globals()
    library._verify_declare_only_symbols()
    library._finalized = True
    _LINKED.add(library)


def linked_only(library: Any) -> bool:
    """Whether library was finalized here: linked and optimized, without machine code."""
    return library in _LINKED


def _linked_envs(library: Any) -> list[tuple[str, Any]]:
    """The environments of the linking-only libraries library links in, transitively."""
    out, todo, seen = [], list(library._linking_libraries), set()
    while todo:
        lib = todo.pop()
        if id(lib) in seen or lib not in _LINKED:
            continue
        seen.add(id(lib))
        if lib in _ENVS:
            out.append(_ENVS[lib])
        todo += lib._linking_libraries
    return out


def _wrapped_get_executable(numba_get_executable: Any) -> Any:
    def get_executable(self: Any, library: Any, fndesc: Any, env: Any) -> Any:
        if not _linking_only(library, fndesc):
            cfunc = numba_get_executable(self, library, fndesc, env)
            # the environment pointers of the functions linked in, which their own libraries
            # never set (nothing of theirs is in the execution engine): numba's cache load does
            # the same for an entry's referenced environments (CompileResult._rebuild)
            engine = library.codegen._engine
            for name, linked_env in _linked_envs(library):
                if engine.get_global_value_address(name):
                    library.codegen.set_env(name, linked_env)
            return cfunc
        from numba import _dynfunc

        _finalize_linking(library)
        _ENVS[library] = (self.get_env_name(fndesc), env)
        # what numba's own gives such a function: a Python function of no code (its wrapper's
        # address, 0: no_cpython_wrapper), keeping the library alive
        doc = f"compiled wrapper for {fndesc.qualname!r}"
        name = fndesc.qualname.split(".")[-1]
        return _dynfunc.make_function(fndesc.lookup_module(), name, doc, 0, env, (library,))

    return get_executable


def _wrapped_check_cachable(numba_check_cachable: Any) -> Any:
    def check_cachable(self: Any, cres: Any) -> bool:
        if getattr(cres, "library", None) in _LINKED:
            return False  # no machine code of its own to write (its callers' holds it)
        return numba_check_cachable(self, cres)

    return check_cachable


def replace() -> bool:
    """Put the linking-only finalize in place for the generated modules' callees
    (numba_patches.install: once, on the `CHECKED` versions); False when this numba lacks what
    it wraps."""
    from numba.core import caching, codegen, cpu

    context = getattr(cpu, "CPUContext", None)
    impl = getattr(caching, "CompileResultCacheImpl", None)
    library = getattr(codegen, "CPUCodeLibrary", None)
    needed = (
        "_get_module_for_linking",
        "_optimize_final_module",
        "_finalize_dynamic_globals",
        "_verify_declare_only_symbols",
    )
    if (
        context is None
        or impl is None
        or library is None
        or not hasattr(context, "get_executable")
        or not all(hasattr(library, n) for n in needed)
    ):
        return False
    swap(context, "get_executable", _wrapped_get_executable(context.get_executable))
    swap(impl, "check_cachable", _wrapped_check_cachable(impl.check_cachable))
    return True


@contextlib.contextmanager
def numba_own() -> Iterator[None]:
    """numba's own finalize of every library compiled inside (the reference of the tests)."""
    with _LOCK:
        before = _STATE.get("suspended", False)
        _STATE["suspended"] = True
    try:
        yield
    finally:
        with _LOCK:
            _STATE["suspended"] = before
