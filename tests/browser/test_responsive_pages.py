"""Every page on a phone (390 px) and on a desktop (1280 px), in headless Chromium.

Issue 37: at 390 px every page scrolled sideways (444-513 px wide), summaries wrapped one
character per line and the profiler's four trace panels overlapped. Here, for each kind of page
(fit report interactive and static, ``fit --report``, several responses, mixture, split-plot,
the paper reproduction):

- the document is no wider than the viewport, and no element reaches past its right edge
  unless it sits in a box that scrolls sideways by itself (a wide table);
- a summary (``dl.facts``) shows each label above its value at 390 px, the value as wide as the
  column (not a column of single letters);
- the profiler's trace panels do not overlap; at 390 px they are stacked one per row, at
  1280 px side by side.

``python tests/browser/test_responsive_pages.py docs/screenshots`` writes the screenshots kept
in ``docs/screenshots/`` (both widths).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.cli import main

pytestmark = [pytest.mark.browser, pytest.mark.slow]

WIDTHS = (390, 1280)

#: Elements reaching past the right edge of the viewport that are not inside a box that
#: scrolls (or clips) sideways and itself fits: the page would scroll sideways because of them.
OVERFLOW_JS = """() => {
  const vw = document.documentElement.clientWidth, out = [];
  for (const e of document.querySelectorAll('body *')) {
    const r = e.getBoundingClientRect();
    if (r.width === 0 || r.right <= vw + 0.5) continue;
    let p = e.parentElement, boxed = false;
    while (p && p !== document.body) {
      const o = getComputedStyle(p).overflowX;
      if ((o === 'auto' || o === 'scroll' || o === 'hidden') && p.getBoundingClientRect().right <= vw + 0.5) {
        boxed = true; break;
      }
      p = p.parentElement;
    }
    if (!boxed) out.push(`${e.tagName.toLowerCase()}${e.id ? '#' + e.id : ''}.${e.className} right=${Math.round(r.right)}`);
  }
  return {scrollWidth: document.documentElement.scrollWidth, bodyWidth: document.body.scrollWidth,
          viewport: vw, wide: out.slice(0, 10)};
}"""

#: Each summary label (dt) and its value (dd): boxes in page pixels.
FACTS_JS = """() => Array.from(document.querySelectorAll('dl.facts dt')).map(dt => {
  const dd = dt.nextElementSibling, a = dt.getBoundingClientRect(), b = dd.getBoundingClientRect();
  return {label: dt.textContent, dt: [a.left, a.top, a.right, a.bottom], dd: [b.left, b.top, b.right, b.bottom],
          column: dt.parentElement.getBoundingClientRect().width};
})"""

#: The profiler's trace panels (Plotly's drag rectangle of each subplot).
PANELS_JS = """() => Array.from(document.querySelectorAll('#profile-plot .nsewdrag')).map(e => {
  const r = e.getBoundingClientRect(); return [r.left, r.top, r.right, r.bottom];
})"""


def _two_responses() -> pd.DataFrame:
    df = rsm_lrg.load_table4()
    rng = np.random.default_rng(1)
    df["wear_index"] = 3 + 2 * df.velocity_m_s - 0.01 * df.acceleration_m_s2 + rng.normal(0, 0.05, len(df))
    return df


@pytest.fixture(scope="module")
def pages(tmp_path_factory):
    """Every kind of page, written as a user writes it (the CLI), and the reproduction page."""
    tmp = tmp_path_factory.mktemp("responsive")
    data = tmp / "data"
    assert main(["datasets", "-o", str(data)]) == 0
    table4, etch, cake = str(data / "table4.csv"), str(data / "mixture_etch.csv"), str(data / "cake_split_plot.csv")
    two = tmp / "two.csv"
    _two_responses().to_csv(two, index=False)
    mix = ["--response", "erate", "--component", "x1", "--component", "x2", "--component", "x3",
           "--model", "mixture-quadratic"]
    split = ["--response", "y", "--factor", "x1", "--factor", "x2", "--whole-plot", "Ovenrun"]
    out = {}
    for name, argv in {
        "fit-interactive": ["report", table4, "--response", "tcr_c_per_min"],
        "fit-static": ["report", table4, "--response", "tcr_c_per_min", "--static"],
        "several-responses": ["report", str(two), "--response", "tcr_c_per_min", "--response", "wear_index"],
        "mixture": ["report", etch, *mix],
        "mixture-static": ["report", etch, *mix, "--static"],
        "split-plot": ["report", cake, *split],
        "split-plot-static": ["report", cake, *split, "--static"],
    }.items():
        out[name] = tmp / f"{name}.html"
        assert main([*argv, "-o", str(out[name])]) == 0, name
    out["fit-report"] = tmp / "fit-report.html"
    assert main(["fit", table4, "--response", "tcr_c_per_min", "--report", str(out["fit-report"])]) == 0
    return out


@pytest.fixture(scope="module")
def reproduction_page(tmp_path_factory):
    from rsm_lrg.paper import reproduce, write_reproduction

    return write_reproduction(reproduce(), tmp_path_factory.mktemp("repro"))


def _open(chromium, path: Path, width: int):
    ctx = chromium.new_context(viewport={"width": width, "height": 900}, offline=True)
    page = ctx.new_page()
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(Path(path).resolve().as_uri(), wait_until="load")
    page.evaluate("() => window.rsmReport && window.rsmReport.drawNow && window.rsmReport.drawNow()")
    page.wait_for_timeout(300)
    return ctx, page, errors


PAGES = ["fit-interactive", "fit-static", "fit-report", "several-responses", "mixture", "mixture-static",
         "split-plot", "split-plot-static"]


def _no_wider_than_the_screen(chromium, path, width):
    ctx, page, errors = _open(chromium, path, width)
    try:
        got = page.evaluate(OVERFLOW_JS)
        assert got["scrollWidth"] <= got["viewport"], got
        assert got["bodyWidth"] <= got["viewport"], got
        assert got["wide"] == [], got
        assert errors == []
        return page.evaluate("() => document.documentElement.scrollHeight")
    finally:
        ctx.close()


@pytest.mark.parametrize("width", WIDTHS)
@pytest.mark.parametrize("name", PAGES)
def test_page_is_no_wider_than_the_screen(chromium, pages, name, width):
    _no_wider_than_the_screen(chromium, pages[name], width)


@pytest.mark.parametrize("width", WIDTHS)
def test_reproduction_page_is_no_wider_than_the_screen(chromium, reproduction_page, width):
    height = _no_wider_than_the_screen(chromium, reproduction_page, width)
    if width == 390:  # one card per comparison row: was 40,582 px tall as a squeezed 7-column table
        assert height < 30_000


@pytest.mark.parametrize("name", PAGES)
def test_summary_is_label_over_value_on_a_phone(chromium, pages, name):
    ctx, page, _ = _open(chromium, pages[name], 390)
    try:
        facts = page.evaluate(FACTS_JS)
        assert facts, "the page has no summary"
        for f in facts:
            assert f["dd"][1] >= f["dt"][3] - 0.5, f"{f['label']}: the value is not below its label: {f}"
            assert f["dd"][2] - f["dd"][0] >= 0.9 * f["column"], f"{f['label']}: the value is squeezed: {f}"
    finally:
        ctx.close()


def _overlapping(boxes) -> list:
    bad = []
    for i, a in enumerate(boxes):
        for b in boxes[i + 1:]:
            if min(a[2], b[2]) - max(a[0], b[0]) > 0.5 and min(a[3], b[3]) - max(a[1], b[1]) > 0.5:
                bad.append((a, b))
    return bad


@pytest.mark.parametrize("width", WIDTHS)
@pytest.mark.parametrize("name", ["fit-interactive", "several-responses", "mixture", "split-plot"])
def test_profiler_panels_do_not_overlap(chromium, pages, name, width):
    ctx, page, _ = _open(chromium, pages[name], width)
    try:
        page.wait_for_selector("#profile-plot .nsewdrag", timeout=30_000)
        boxes = page.evaluate(PANELS_JS)
        controls = page.evaluate("() => document.querySelectorAll('#factor-controls [data-factor]').length")
        responses = page.evaluate("() => document.querySelectorAll('[data-prediction]').length")
        assert len(boxes) == controls * responses
        assert _overlapping(boxes) == []
        lefts = {round(b[0]) for b in boxes}
        if width == 390:  # stacked: one panel per row, each nearly as wide as the screen
            assert len(lefts) == 1, boxes
            assert all(b[2] - b[0] >= 250 for b in boxes), boxes
        else:  # side by side: one column per factor
            assert len(lefts) == controls, boxes
        assert max(b[2] for b in boxes) <= width
    finally:
        ctx.close()


@pytest.mark.parametrize("name", ["fit-interactive", "mixture"])
def test_profiler_restacks_when_the_window_narrows(chromium, pages, name):
    ctx, page, _ = _open(chromium, pages[name], 1280)
    try:
        page.wait_for_selector("#profile-plot .nsewdrag", timeout=30_000)
        assert len({round(b[0]) for b in page.evaluate(PANELS_JS)}) > 1
        page.set_viewport_size({"width": 390, "height": 900})
        page.wait_for_timeout(600)
        boxes = page.evaluate(PANELS_JS)
        assert len({round(b[0]) for b in boxes}) == 1 and _overlapping(boxes) == []
        assert page.evaluate("() => document.documentElement.scrollWidth") <= 390
    finally:
        ctx.close()


def test_controls_do_not_overlap_on_a_phone(chromium, pages):
    ctx, page, _ = _open(chromium, pages["several-responses"], 390)
    try:
        boxes = page.evaluate("""() => Array.from(document.querySelectorAll(
            '#factor-controls input, #factor-controls select, #factor-controls button')).map(e => {
            const r = e.getBoundingClientRect(); return [r.left, r.top, r.right, r.bottom]; })""")
        assert len(boxes) >= 8
        assert _overlapping(boxes) == []
    finally:
        ctx.close()


def test_number_box_shows_the_value_used(chromium, pages):
    # issue 37: a 5 typed into the 0.4 ... 0.6 box of velocity used 0.6 and kept showing 5
    ctx, page, _ = _open(chromium, pages["fit-interactive"], 390)
    try:
        box = page.query_selector('[data-factor-text="velocity_m_s"]')
        box.fill("5")
        box.dispatch_event("change")
        assert page.evaluate("() => document.activeElement === document.querySelector("
                             "'[data-factor-text=\"velocity_m_s\"]')")
        assert box.input_value() == "0.6"
        assert float(page.query_selector('[data-factor="velocity_m_s"]').input_value()) == 0.6
        box.fill("0.45")
        box.dispatch_event("change")
        assert box.input_value() == "0.45"
    finally:
        ctx.close()


def screenshots(out: str) -> None:
    """The screenshots kept in ``docs/screenshots/``: the top of the two-response report and
    its profiler, the static report and the reproduction page, at 390 and 1280 px."""
    import os
    import tempfile

    from conftest import CHROMIUM, CHROMIUM_ARGS
    from playwright.sync_api import sync_playwright

    from rsm_lrg.paper import reproduce, write_reproduction

    target = Path(out).resolve()
    target.mkdir(parents=True, exist_ok=True)
    here = os.getcwd()
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        os.chdir(tmp)  # the pages name their data as a user's would: table4.csv, not /tmp/...
        assert main(["datasets", "table4", "-o", "table4.csv"]) == 0
        _two_responses().to_csv("two.csv", index=False)
        assert main(["report", "two.csv", "--response", "tcr_c_per_min", "--response", "wear_index",
                     "-o", "report.html"]) == 0
        assert main(["report", "table4.csv", "--response", "tcr_c_per_min", "--static", "-o", "static.html"]) == 0
        os.chdir(here)
        repro = write_reproduction(reproduce(), tmp / "repro")
        with sync_playwright() as pw:
            browser = pw.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS, headless=True)
            for width in WIDTHS:
                for name, path, selector in (("report", tmp / "report.html", None),
                                             ("profiler", tmp / "report.html", "#profiler"),
                                             ("static", tmp / "static.html", None),
                                             ("reproduction", repro, "#comparison")):
                    page = browser.new_page(viewport={"width": width, "height": 1400 if width == 390 else 900})
                    page.goto(Path(path).as_uri(), wait_until="load")
                    page.evaluate("() => window.rsmReport && window.rsmReport.drawNow && window.rsmReport.drawNow()")
                    page.wait_for_timeout(500)
                    png = target / f"{name}-{width}.png"
                    if selector is None:
                        page.screenshot(path=str(png))
                    else:
                        el = page.query_selector(selector)
                        box = el.bounding_box()
                        page.screenshot(path=str(png), full_page=True,
                                        clip={"x": 0, "y": box["y"], "width": width,
                                              "height": min(box["height"], 2400)})
                    page.close()
            browser.close()


if __name__ == "__main__":
    import sys

    sys.path.insert(0, str(Path(__file__).parent))
    screenshots(sys.argv[1] if len(sys.argv) > 1 else "docs/screenshots")
