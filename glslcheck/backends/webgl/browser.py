"""The browser: one headless Chromium per process, driven by Playwright, holding one WebGL2 page.

Why Playwright (its Python package, launched with the Debian `chromium` executable, so nothing
is downloaded at run time; `playwright install` is never needed): it speaks the DevTools
protocol to the browser over a pipe, with no HTTP server, no WebDriver binary that must match the
browser's version (selenium needs Debian's `chromium-driver`, one more package to keep in step),
and it owns the browser's lifetime: its driver process kills the browser when our process goes
away, even without a clean shutdown, so no browser is left behind. Its sync API runs
`page.evaluate` in our own thread, which is all this backend needs.

The page is `about:blank`; `harness.js` (this package) is evaluated into it once and keeps the
WebGL2 context, the compiled programs and the float render target. Chromium's flags:
`--headless=new`; `--use-angle=swiftshader --enable-unsafe-swiftshader`: WebGL through ANGLE on
SwiftShader's Vulkan, the same software GPU on every machine (a developer's real GPU would make
renders machine-dependent); `--disable-background-networking --disable-component-update
--disable-sync --no-first-run`: nothing tries the network (these machines have none, and a
browser that waits for it is slow to start). No `--disable-gpu`: SwiftShader runs in the GPU
process. `--no-sandbox` is Playwright's default (we run as root in CI); Playwright makes and
removes its own `--user-data-dir`.

`get_browser()` starts the browser on first use and keeps it; `close_browser()` (registered with
atexit) ends it. WebGLUnavailable (an InputError: exit 2, never a traceback) says what to
install when Playwright, Chromium, WebGL 2 or float render targets are missing, and why an
installed Chromium failed to start (`launch_failure`).
"""

from __future__ import annotations

import atexit
import os
import re
import shutil
import signal
import time
from collections import OrderedDict
from importlib import resources
from pathlib import Path

from ...base import config
from ...base.diagnostics import InputError

ADVICE = (
    "install Chromium and Playwright's Python package (sudo apt-get install chromium; "
    "pip install 'glslcheck[webgl]'; `playwright install` is not needed)"
)
CHROMIUM_NAMES = ("chromium", "chromium-browser")
# Set GLSLCHECK_CHROMIUM to use another Chromium build.
ENV_EXECUTABLE = "GLSLCHECK_CHROMIUM"
FLAGS = (
    "--headless=new",
    "--use-angle=swiftshader",
    "--enable-unsafe-swiftshader",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
)
ENV_TIMEOUT = "GLSLCHECK_WEBGL_TIMEOUT"
# Launching takes 1-4 s on an idle machine; a loaded shared one may need far more.
LAUNCH_TIMEOUT_MS = 120_000

_browser: Browser | None = None


class WebGLUnavailable(InputError):
    """No headless Chromium with WebGL 2 and float render targets (an environment problem)."""


class WebGLTimeout(Exception):
    """A call into the page ran longer than `call_timeout()` seconds; the browser was ended."""

    def __init__(self, seconds: float):
        super().__init__(f"it ran for more than {seconds:g} s")
        self.seconds = seconds


def call_timeout() -> float:
    """Seconds one compile or render may take in the browser: $GLSLCHECK_WEBGL_TIMEOUT, else 60
    (a 800x450 frame of lab 07_final takes 2.7 s on a 2-core machine at load 11)."""
    return config.webgl_timeout()


def chromium_path() -> str | None:
    """The Chromium executable: $GLSLCHECK_CHROMIUM, else `chromium` on PATH."""
    try:
        given = config.chromium()
    except InputError:
        return None  # named but not runnable: Browser's error names the variable
    if given:
        return given
    for name in CHROMIUM_NAMES:
        path = shutil.which(name)
        if path:
            return path
    return None


def launch_failure(executable: str, error: str) -> str:
    """The message for a Chromium at `executable` that failed to start with Playwright's `error`:
    its first line, how the browser process ended (from Playwright's call log) and, under an
    address-space limit (`ulimit -v`), that limit: Chromium reserves far more address space than
    it uses, and no limit a machine can give is enough. The executable is there: no advice to
    install it."""
    lines = error.strip().splitlines()
    first = lines[0] if lines else "no reason given"
    message = f"error: headless Chromium ({executable}) failed to start: {first}"
    ended = re.search(r"<process did exit: exitCode=(\w+), signal=(\w+)>", error)
    if ended and ended.group(2) != "null":
        message += f"; the browser process was ended by {ended.group(2)}"
    elif ended and ended.group(1) != "null":
        message += f"; the browser process exited with code {ended.group(1)}"
    try:
        import resource

        soft, _ = resource.getrlimit(resource.RLIMIT_AS)
    except (ImportError, OSError, ValueError):  # not POSIX
        soft = -1
    if soft >= 0 and soft != getattr(resource, "RLIM_INFINITY", -1):
        message += (
            f"; this process runs under an address-space limit (ulimit -v {soft // 1024}), which "
            "Chromium cannot start under: it reserves far more address space than it uses"
        )
    return message


class Browser:
    """A headless Chromium, its page and the harness's WebGL2 context in that page."""

    def __init__(self) -> None:
        try:
            from playwright.sync_api import Error as PlaywrightError
            from playwright.sync_api import sync_playwright
        except ImportError as e:
            raise WebGLUnavailable(
                f"error: the WebGL backend needs Playwright ({e}); {ADVICE}"
            ) from None
        from playwright.sync_api import TimeoutError as PlaywrightTimeout

        self.Error = PlaywrightError
        self.TimeoutError = PlaywrightTimeout
        executable = chromium_path()
        if executable is None:
            raise WebGLUnavailable(
                f"error: no Chromium executable found (${ENV_EXECUTABLE} or "
                f"{' / '.join(CHROMIUM_NAMES)} on PATH); {ADVICE}"
            )
        self.executable = executable
        self.pending_release: list[int] = []  # page programs whose WebGLProgram is gone
        # Channel textures the page holds (key -> bytes), least recently used first.
        self.textures: OrderedDict[str, int] = OrderedDict()
        start = time.perf_counter()
        self._playwright = None
        self._browser = None
        before = _browser_roots()
        try:
            self._playwright = sync_playwright().start()
            self._browser = self._playwright.chromium.launch(
                executable_path=executable,
                headless=True,
                args=list(FLAGS),
                timeout=LAUNCH_TIMEOUT_MS,
            )
            self.page = self._browser.new_page()
            self.page.evaluate(
                resources.files(__package__).joinpath("harness.js").read_text("utf-8")
            )
            error = self.page.evaluate("() => window.glslcheck.error")
        except PlaywrightError as e:
            self.close()
            raise WebGLUnavailable(launch_failure(executable, str(e))) from None
        if error:
            self.close()
            raise WebGLUnavailable(f"error: headless Chromium ({executable}): {error}; {ADVICE}")
        self.info = self.page.evaluate("() => window.glslcheck.info()")
        self._roots = (
            _browser_roots() - before
        )  # this browser's main process (for a timeout's kill)
        self.startup_seconds = time.perf_counter() - start

    @property
    def closed(self) -> bool:
        return self._browser is None

    @property
    def version(self) -> str:
        return self._browser.version if self._browser is not None else ""

    def call(self, function: str, *args):
        """`window.glslcheck.<function>(*args)` in the page; its JSON result.

        A call that runs longer than `call_timeout()` (an endless loop in a shader blocks the
        page in readPixels; SwiftShader has no watchdog that stops it) raises WebGLTimeout and
        ends this browser: its page cannot be used again. The call runs as the predicate of
        `wait_for_function`, whose timeout the driver enforces outside the blocked page; the
        result is kept in the page and fetched by one more evaluate.
        """
        if self.pending_release:
            ids, self.pending_release = self.pending_release, []
            self.page.evaluate("(ids) => window.glslcheck.release(ids)", ids)
        timeout = call_timeout()
        try:
            self.page.wait_for_function(
                f"(args) => {{ window.glslcheck.out = window.glslcheck.{function}(...args); "
                "return true; }",
                arg=list(args),
                timeout=timeout * 1000.0,
            )
        except self.TimeoutError:
            # A page blocked in the GPU process makes Playwright's graceful close wait 30 s: end
            # this browser's processes first (by their ids), then close what is left.
            _kill_trees(self._roots)
            self.close()
            raise WebGLTimeout(timeout) from None
        return self.page.evaluate(
            "() => { const out = window.glslcheck.out; window.glslcheck.out = null; return out; }"
        )

    def new_page(self, **options):
        """Another page of this browser (e.g. to load a report); the caller closes it."""
        assert self._browser is not None, "the browser is closed"
        return self._browser.new_page(**options)

    def close(self) -> None:
        """Close the browser and Playwright's driver (each at most once; errors ignored)."""
        browser, self._browser = self._browser, None
        playwright, self._playwright = self._playwright, None
        for step in (browser.close if browser else None, playwright.stop if playwright else None):
            if step is None:
                continue
            try:
                step()
            except Exception:  # already gone (a crash, or an interrupted run): nothing to end
                pass


BROWSER_NAMES = {"chromium", "chrome"}


def _process_tree() -> tuple[dict[int, list[int]], dict[int, str]]:
    """(children of each pid, command name of each pid) from Linux's /proc; empty elsewhere."""
    children: dict[int, list[int]] = {}
    comm: dict[int, str] = {}
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            head, tail = stat.read_text().rsplit(")", 1)
        except (OSError, ValueError):
            continue
        pid = int(stat.parent.name)
        comm[pid] = head.split("(", 1)[1]
        children.setdefault(int(tail.split()[1]), []).append(pid)
    return children, comm


def _browser_roots() -> set[int]:
    """Our descendants that are a browser's main process (a browser whose parent is not one)."""
    children, comm = _process_tree()
    roots, todo = set(), [os.getpid()]
    while todo:
        parent = todo.pop()
        for c in children.get(parent, []):
            todo.append(c)
            if comm.get(c) in BROWSER_NAMES and comm.get(parent) not in BROWSER_NAMES:
                roots.add(c)
    return roots


def _kill_trees(roots: set[int]) -> None:
    """SIGKILL each of `roots` and every process under it (our own browser's processes only)."""
    children, _ = _process_tree()
    todo, found = list(roots), []
    while todo:
        pid = todo.pop()
        found.append(pid)
        todo.extend(children.get(pid, []))
    for pid in found:
        try:
            os.kill(pid, signal.SIGKILL)
        except OSError:
            pass


def get_browser() -> Browser:
    """The process-wide browser, started on first use (WebGLUnavailable when it cannot start)."""
    global _browser
    if _browser is None or _browser.closed:
        _browser = Browser()
    return _browser


def browser_started() -> bool:
    return _browser is not None


def close_browser() -> None:
    """End the process-wide browser, if any (also run at exit)."""
    global _browser
    browser, _browser = _browser, None
    if browser is not None:
        browser.close()


atexit.register(close_browser)
