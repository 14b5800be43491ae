"""The design-space page in real Chromium: no script, no request, every map drawn, user text
inert, the window table as computed; and at a phone's width (390 px) the page does not scroll
sideways."""

import pytest

import rsm_lrg
from rsm_lrg.optimize.design_space import design_space
from rsm_lrg.report.design_space_page import write_design_space_page

pytestmark = [pytest.mark.browser, pytest.mark.slow]


def test_page_shows_the_maps_and_the_window(visit, chromium, tmp_path):
    df = rsm_lrg.load_table4().rename(columns={"stroke_m": "<b>stroke</b>"})
    fit = rsm_lrg.fit(df, "tcr_c_per_min")
    ds = design_space({"tcr_c_per_min": fit}, {"tcr_c_per_min": (None, 0.035)}, grid=7)
    path = write_design_space_page(ds, tmp_path / "ds.html", source_name="<script>alert(1)</script>")
    v = visit(path, screenshot_name="design_space.png")
    assert v.console_errors == [] and v.foreign_requests == [] and v.dialogs == [] and v.scripts == 0
    assert len(v.images) == 6 and all(i["complete"] and i["naturalWidth"] > 0 for i in v.images)
    assert {"summary", "window", "maps", "notes", "window-table"} <= v.ids
    assert "<b>stroke</b>" in v.text and "<script>alert(1)</script>" in v.text  # shown as text
    rows = v.page.evaluate("() => Array.from(document.querySelectorAll('#window-table tbody tr')).map("
                           "r => r.cells[0].innerText)")
    assert rows == list(ds.window)
    ctx = chromium.new_context(viewport={"width": 390, "height": 800}, offline=True)
    try:
        page = ctx.new_page()
        page.goto(path.resolve().as_uri(), wait_until="load")
        width = page.evaluate("() => document.documentElement.scrollWidth")
        page.screenshot(path=str(tmp_path / "design_space_390.png"), full_page=True)
    finally:
        ctx.close()
    assert width <= 390
