"""The `glslcheck` command line: argument parsing only; each subcommand lives in
`glslcheck/cli/commands/<name>.py` with `add_arguments(parser)` and `run(args) -> int` and calls
the library. Subcommand modules are imported lazily so one CLI call stays fast.

Exit codes everywhere: 0 clean, 1 findings or errors in the shader, 2 usage or I/O errors.
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys

from ..base import config
from ..base.diagnostics import GlslError, InputError, format_text, printable

# What `glslcheck --help` says first: for the user, not the module's design.
DESCRIPTION = (
    "Check Shadertoy GLSL against the GPR-200 Lab 4 coding standards, render it on the CPU, "
    "and verify the CPU render against OpenGL and WebGL. "
    "Exit codes: 0 clean, 1 findings or errors in a shader, 2 usage or I/O errors."
)

# (name, module, one-line help), in the order `--help` lists them.
COMMANDS = [
    ("parse", "parse", "parse shaders and report syntax errors"),
    ("check", "check", "parse and type-check shaders (GLSL ES 3.00 and Shadertoy rules)"),
    ("lint", "lint", "report every Lab 4 coding-standard deduction"),
    ("rule", "rule", "explain a lint rule"),
    ("install-hook", "install_hook", "install a git pre-commit hook that runs glslcheck lint"),
    ("transpile", "transpile", "write the NumPy Python module for a shader"),
    ("render", "render", "render a shader on the CPU (NumPy) or with OpenGL"),
    ("verify", "verify", "render with NumPy and OpenGL and compare"),
    ("bench", "bench", "time against error for precision modes and samples per pixel"),
    (
        "probe",
        "probe",
        "trace one pixel statement by statement, or find where NaN pixels came from",
    ),
    (
        "report",
        "report",
        "one HTML page: source and findings, every backend's render, differences, verdicts",
    ),
    ("grade", "grade", "grade a class: deductions, renders and closeness to a reference"),
]


def _terminal_columns() -> int:
    """shutil.get_terminal_size().columns, found the same way (COLUMNS, the terminal, 80)
    without importing shutil and its compression modules on every call of the hook."""
    try:
        columns = int(os.environ["COLUMNS"])
    except (KeyError, ValueError):
        columns = 0
    if columns <= 0:
        try:
            stdout = sys.__stdout__
            if stdout is not None:
                columns = os.get_terminal_size(stdout.fileno()).columns
        except (AttributeError, ValueError, OSError):
            columns = 0
    return columns or 80


class _Formatter(argparse.HelpFormatter):
    def __init__(
        self,
        prog: str,
        indent_increment: int = 2,
        max_help_position: int = 24,
        width: int | None = None,
    ):
        super().__init__(
            prog,
            indent_increment,
            max_help_position,
            _terminal_columns() - 2 if width is None else width,
        )


class _Parser(argparse.ArgumentParser):
    def __init__(self, *args, **kwargs) -> None:
        kwargs.setdefault("formatter_class", _Formatter)
        super().__init__(*args, **kwargs)

    def error(self, message: str):  # usage errors exit 2 without a traceback
        self.print_usage(sys.stderr)
        self.exit(2, f"{self.prog}: error: {message}\n")


def build_parser(only: str | None = None) -> argparse.ArgumentParser:
    parser = _Parser(prog="glslcheck", description=DESCRIPTION)
    from ..base.version import __version__

    parser.add_argument("--version", action="version", version=f"glslcheck {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    for name, module, help_ in COMMANDS:
        if only is not None and name != only:
            # A known command needs only its own parser (each parser costs argparse's gettext
            # look-ups, milliseconds of every hook run); an unknown one lists them all.
            if not any(only == c[0] for c in COMMANDS):
                sub.add_parser(name, help=help_)
            continue
        try:
            mod = importlib.import_module(f"glslcheck.cli.commands.{module}")
        except ModuleNotFoundError as e:
            if e.name == f"glslcheck.cli.commands.{module}":
                continue
            raise
        p = sub.add_parser(name, help=help_, description=(mod.__doc__ or help_).strip())
        mod.add_arguments(p)
        if name in _RENDERING:
            p.add_argument(
                "--parallel",
                choices=config.PARALLEL_MODES,
                default=None,
                help="NumPy tiles on worker processes, on threads, or auto: "
                "threads until a program "
                "has rendered for a second, then processes (default: $GLSLCHECK_PARALLEL or auto)",
            )
            p.add_argument(
                "--jit",
                choices=config.JIT_MODES,
                default=None,
                help="llvmpipe's sin, cos, exp2, log2, pow... by compiled kernels (the optional "
                "numba extra): "
                "on, off, or auto: once a process has spent in that math what loading them "
                "costs (default: $GLSLCHECK_JIT or auto)",
            )
        if name in _BUDGETED:
            from .commands.args import add_frame_budget

            add_frame_budget(p)
        p.set_defaults(_run=mod.run)
    return parser


_RENDERING = (
    "render",
    "verify",
    "bench",
    "report",
    "grade",
)  # the commands that run the NumPy renderer
_BUDGETED = _RENDERING + (
    "probe",
)  # and those that take --frame-budget (probe's --nan renders a frame)


def main(argv: list[str] | None = None) -> int:
    """Run the command line `argv`. Without `argv` this is the `glslcheck` command itself, the
    whole process: after the command, everything it made is moved out of the garbage
    collector's reach (`gc.freeze`), so the interpreter's last collection at exit does not walk
    the parser tables, trees and rules once more; the memory is the operating system's to free
    a moment later. The process also collects its youngest generation every 100,000 new objects
    instead of every 700: importing the command, loading the parser tables and building the
    trees make objects by the ten thousand and almost no garbage, and each collection walks
    them. At 100,000 the cyclic garbage of the programs linted before (their trees, models and
    facts) waits for a later collection, or for the exit: on the lab's lint in one process that
    saves about 2% of the instructions for about 2.5 MB more peak memory (cachegrind); 50,000
    saved nothing. Called with `argv` (tests, other programs), the collector is left as it is."""
    if argv is not None:
        return _main(argv)
    import gc

    # what stdout's encoding cannot write (an undecodable byte of a file name under a strict
    # UTF-8 PYTHONIOENCODING, any non-ASCII under an ASCII one) is written as a backslash escape
    if hasattr(sys.stdout, "reconfigure"):
        sys.stdout.reconfigure(errors="backslashreplace")
    gc.set_threshold(100_000, *gc.get_threshold()[1:])
    code = _main(sys.argv[1:])
    gc.freeze()
    _exit_if_abandoned(code)
    return code


def _exit_if_abandoned(code: int) -> None:
    """End the process now when the compiled engine left a frame or numba's compile running (over
    budget or interrupted): those threads cannot be stopped, and the interpreter's shutdown
    would wait for them or pull the runtime from under them (an LLVM abort mid-compile)."""
    if "glslcheck.backends.compiled_engine.engine" not in sys.modules:
        return
    from ..backends.compiled_engine.workers import abandoned

    if abandoned():
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except (OSError, ValueError):
                pass
        os._exit(code)


def _main(argv: list[str]) -> int:
    # Only import the chosen subcommand's module (startup time matters for hooks).
    only = argv[0] if argv and not argv[0].startswith("-") else None
    parser = build_parser(only)
    try:
        args = parser.parse_args(argv)
    except SystemExit as e:  # usage errors (2) and --help/--version (0) return, not raise
        return int(e.code or 0)
    if not getattr(args, "_run", None):
        parser.print_help(sys.stderr)
        return 2
    if args.command in _RENDERING:
        from ..backends.numpy_engine.workers import tune_malloc

        try:  # a bad variable the option would override is no error
            for given, read in ((args.parallel, config.parallel), (args.jit, config.jit)):
                if not given:
                    read()
        except InputError as e:
            print(f"glslcheck: {e}", file=sys.stderr)
            return 2
        tune_malloc()  # tile temporaries reuse freed memory instead of page-faulting (workers.py)
    if args.command not in _BUDGETED:
        return _run(args)
    from .commands.args import environment

    budget = getattr(args, "frame_budget", None)
    # read by every NumPy program made below; as they were after: main() may run again in-process
    with environment(
        GLSLCHECK_PARALLEL=getattr(args, "parallel", None),
        GLSLCHECK_JIT=getattr(args, "jit", None),
        GLSLCHECK_FRAME_SECONDS=None if budget is None else repr(budget),
    ):
        return _run(args)


def _run(args) -> int:
    try:
        code = int(args._run(args) or 0)
        sys.stdout.flush()  # a full disk or a closed pipe shows here, not at interpreter exit
        return code
    except InputError as e:
        print(printable(str(e)), file=sys.stderr)
        return 2
    except GlslError as e:
        for d in e.diagnostics:
            print(format_text(d), file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("glslcheck: interrupted", file=sys.stderr)
        return 2
    # A safety net, not the fix: each stage bounds its own recursion and memory.
    except RecursionError:
        print(
            f"{_first_path(args)}:1:1: error: the program is nested too deeply to analyse",
            file=sys.stderr,
        )
        return 1
    except MemoryError:
        print(
            f"{_first_path(args)}: error: glslcheck ran out of memory on this shader"
            " (a smaller --size or a smaller file helps)",
            file=sys.stderr,
        )
        return 2
    except BrokenPipeError:
        _discard_stdout()
        return 1
    except (
        OSError
    ) as e:  # writing the report to stdout (`lint > /dev/full`); files raise InputError
        if e.filename:
            print(f"{e.filename}: error: {e.strerror or e}", file=sys.stderr)
        else:
            _discard_stdout()
            print(
                f"glslcheck: error: cannot write to standard output ({e.strerror or e})",
                file=sys.stderr,
            )
        return 2


def _discard_stdout() -> None:
    """Point stdout at /dev/null, so the interpreter's last flush of what could not be written
    fails no second time ("Exception ignored ... OSError" and exit 120)."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError, AttributeError):  # stdout is not a file (captured in tests)
        pass


def _first_path(args) -> str:
    """The first shader path of a command's arguments, for the safety net's messages."""
    paths = getattr(args, "paths", None) or [
        getattr(args, "shader", None) or getattr(args, "path", None)
    ]
    return str(paths[0]) if paths and paths[0] else "glslcheck"


if __name__ == "__main__":
    sys.exit(main())
