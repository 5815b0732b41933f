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
install when Playwright, Chromium, WebGL 2 or float render targets are missing.
"""

from __future__ import annotations

import atexit
import os
import shutil
import time
from importlib import resources

from ..diagnostics import InputError

ADVICE = ("install Chromium and Playwright's Python package (sudo apt-get install chromium; "
          "pip install 'glslcheck[webgl]'; `playwright install` is not needed)")
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
# Launching takes 1-4 s on an idle machine; a loaded shared one may need far more.
LAUNCH_TIMEOUT_MS = 120_000

_browser: "Browser | None" = None


class WebGLUnavailable(InputError):
    """No headless Chromium with WebGL 2 and float render targets (an environment problem)."""


def chromium_path() -> str | None:
    """The Chromium executable: $GLSLCHECK_CHROMIUM, else `chromium` on PATH."""
    given = os.environ.get(ENV_EXECUTABLE)
    if given:
        return given if os.access(given, os.X_OK) else None
    for name in CHROMIUM_NAMES:
        path = shutil.which(name)
        if path:
            return path
    return None


class Browser:
    """A headless Chromium, its page and the harness's WebGL2 context in that page."""

    def __init__(self) -> None:
        try:
            from playwright.sync_api import Error as PlaywrightError
            from playwright.sync_api import sync_playwright
        except ImportError as e:
            raise WebGLUnavailable(f"error: the WebGL backend needs Playwright ({e}); {ADVICE}") from None
        self.Error = PlaywrightError
        executable = chromium_path()
        if executable is None:
            raise WebGLUnavailable(f"error: no Chromium executable found (${ENV_EXECUTABLE} or "
                                   f"{' / '.join(CHROMIUM_NAMES)} on PATH); {ADVICE}")
        self.executable = executable
        self.pending_release: list[int] = []  # page programs whose WebGLProgram is gone
        start = time.perf_counter()
        self._playwright = None
        self._browser = None
        try:
            self._playwright = sync_playwright().start()
            self._browser = self._playwright.chromium.launch(
                executable_path=executable, headless=True, args=list(FLAGS), timeout=LAUNCH_TIMEOUT_MS)
            self.page = self._browser.new_page()
            self.page.evaluate(resources.files(__package__).joinpath("harness.js").read_text("utf-8"))
            error = self.page.evaluate("() => window.glslcheck.error")
        except PlaywrightError as e:
            self.close()
            first = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
            raise WebGLUnavailable(f"error: cannot start headless Chromium ({executable}): {first}; {ADVICE}") from None
        if error:
            self.close()
            raise WebGLUnavailable(f"error: headless Chromium ({executable}): {error}; {ADVICE}")
        self.info = self.page.evaluate("() => window.glslcheck.info()")
        self.startup_seconds = time.perf_counter() - start

    @property
    def version(self) -> str:
        return self._browser.version if self._browser is not None else ""

    def call(self, function: str, *args):
        """`window.glslcheck.<function>(*args)` in the page; its JSON result."""
        if self.pending_release:
            ids, self.pending_release = self.pending_release, []
            self.page.evaluate("(ids) => window.glslcheck.release(ids)", ids)
        return self.page.evaluate(f"(args) => window.glslcheck.{function}(...args)", list(args))

    def new_page(self, **options):
        """Another page of this browser (e.g. to load a report); the caller closes it."""
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


def get_browser() -> Browser:
    """The process-wide browser, started on first use (WebGLUnavailable when it cannot start)."""
    global _browser
    if _browser is None:
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
