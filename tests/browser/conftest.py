"""Open a report in real headless Chromium (Debian's /usr/bin/chromium) through Playwright.

Playwright's own browser download cannot work here, so the Debian binary is launched with
``executable_path``. Every test under ``tests/browser`` (whatever fixtures it uses) is
skipped, with the reason, when that binary is absent, when Playwright cannot be imported,
or when the browser does not start (``.ci/run`` installs it). Set
``RSM_LRG_REQUIRE_BROWSER=1`` to make these a failure instead of a skip (for CI, where the
browser must be there).
"""

from __future__ import annotations

import os
import shutil
from dataclasses import dataclass, field
from pathlib import Path

import pytest

CHROMIUM = os.environ.get("RSM_LRG_CHROMIUM", "/usr/bin/chromium")  # override for another binary
CHROMIUM_ARGS = [
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
]


@dataclass
class PageVisit:
    """What happened while a page was open."""

    url: str
    console: list = field(default_factory=list)      # (type, text)
    page_errors: list = field(default_factory=list)  # uncaught exceptions
    requests: list = field(default_factory=list)     # every URL the page asked for
    dialogs: list = field(default_factory=list)      # alert/confirm/prompt messages
    images: list = field(default_factory=list)       # {src_prefix, naturalWidth, naturalHeight, complete}
    svg_boxes: list = field(default_factory=list)    # inline <svg> bounding boxes
    ids: set = field(default_factory=set)
    scripts: int = 0
    text: str = ""
    screenshot: Path | None = None

    @property
    def console_errors(self):
        return [t for k, t in self.console if k == "error"] + list(self.page_errors)

    @property
    def foreign_requests(self):
        """Requests other than the page itself and data: URIs."""
        return [u for u in self.requests if u != self.url and not u.startswith("data:")]


def _require() -> bool:
    return os.environ.get("RSM_LRG_REQUIRE_BROWSER", "").strip() not in ("", "0")


def _skip_or_fail(reason: str):
    if _require():
        pytest.fail(f"{reason} (RSM_LRG_REQUIRE_BROWSER is set)", pytrace=False)
    pytest.skip(reason)


def _why_unavailable() -> str | None:
    """Why the browser tests cannot run here, or None."""
    if not chromium_available():
        return f"{CHROMIUM} is not installed (Debian package 'chromium'; .ci/run installs it)"
    try:
        import playwright.sync_api  # noqa: F401
    except Exception as exc:  # ImportError, or a broken binary dependency (greenlet, ...)
        first = (str(exc).splitlines() or [""])[0][:200]
        return f"Playwright for Python cannot be imported ({type(exc).__name__}: {first})"
    return None


def pytest_collection_modifyitems(config, items):
    why = _why_unavailable()
    if why is None or _require():
        return
    here = Path(__file__).parent.resolve()
    mark = pytest.mark.skip(reason=why)
    for item in items:
        if here in Path(str(item.fspath)).resolve().parents:
            item.add_marker(mark)


def _launch():
    from playwright.sync_api import sync_playwright

    pw = sync_playwright().start()
    try:
        browser = pw.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS, headless=True)
    except Exception:
        pw.stop()
        raise
    return pw, browser


@pytest.fixture(scope="session")
def chromium():
    why = _why_unavailable()
    if why is not None:
        _skip_or_fail(why)
    try:
        pw, browser = _launch()
    except Exception as exc:  # e.g. missing shared libraries of the binary
        first = (str(exc).strip().splitlines() or [""])[0][:200]
        _skip_or_fail(f"{CHROMIUM} does not start under Playwright ({type(exc).__name__}: {first})")
    yield browser
    browser.close()
    pw.stop()


@pytest.fixture
def visit(chromium, tmp_path):
    """``visit(path) -> PageVisit``: open a local HTML file and record what it does."""

    contexts = []

    def _visit(path: Path, *, screenshot_name: str = "page.png", settle_ms: int = 300) -> PageVisit:
        path = Path(path).resolve()
        url = path.as_uri()
        ctx = chromium.new_context(viewport={"width": 1280, "height": 900}, offline=True)
        contexts.append(ctx)
        page = ctx.new_page()
        v = PageVisit(url=url)
        page.on("console", lambda m: v.console.append((m.type, m.text)))
        page.on("pageerror", lambda e: v.page_errors.append(str(e)))
        page.on("request", lambda r: v.requests.append(r.url))

        def on_dialog(d):
            v.dialogs.append(d.message)
            d.dismiss()

        page.on("dialog", on_dialog)

        # Anything that is neither the page nor a data: URI is aborted (and recorded above).
        def guard(route):
            u = route.request.url
            if u == url or u.startswith("data:"):
                route.continue_()
            else:
                route.abort()

        page.route("**/*", guard)
        page.goto(url, wait_until="load")
        page.wait_for_timeout(settle_ms)
        v.images = page.evaluate(
            """() => Array.from(document.images).map(i => ({
                   src: i.getAttribute('src').slice(0, 40), complete: i.complete,
                   naturalWidth: i.naturalWidth, naturalHeight: i.naturalHeight}))"""
        )
        v.svg_boxes = page.evaluate(
            """() => Array.from(document.querySelectorAll('svg')).map(s => {
                   const r = s.getBoundingClientRect(); return [r.width, r.height]; })"""
        )
        v.ids = set(page.evaluate("() => Array.from(document.querySelectorAll('[id]')).map(e => e.id)"))
        v.scripts = page.evaluate("() => document.querySelectorAll('script').length")
        v.text = page.evaluate("() => document.body.innerText")
        shot = tmp_path / screenshot_name
        page.screenshot(path=str(shot), full_page=True)
        v.screenshot = shot
        v.page = page  # for extra queries in a test
        return v

    yield _visit
    for c in contexts:
        c.close()


def chromium_available() -> bool:
    """True when the Chromium binary exists and is executable."""
    return os.path.exists(CHROMIUM) and shutil.which(CHROMIUM) is not None
