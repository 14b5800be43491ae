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


def test_surrogate_page_shows_the_variance_attribution(visit, tmp_path, capsys):
    """``design-space --surrogate -o``: the page carries the attribution of every setting, as
    the JSON gives it: one table row per grid node with its shares (calibration, tolerances, run
    noise, interaction), the largest marked as the dominant source and named, the count of the
    settings each source dominates, and the stacked-bar figure drawn."""
    import json

    from rsm_lrg.cli import main
    from rsm_lrg.report.html import fmt_num

    page = tmp_path / "surrogate.html"
    argv = ["design-space", "--surrogate", "--factor", "velocity_m_s=0.4:0.6", "--factor", "acceleration_m_s2=20:40",
            "--spec", "tcr_c_per_min=:0.045", "--grid", "2", "--draws", "6", "--seed", "3",
            "--param-sd", "thickness_m=5e-6", "--json", "-", "-o", str(page)]
    assert main(argv) == 0
    nodes = json.loads(capsys.readouterr().out)["surrogate"]["nodes"]
    v = visit(page, screenshot_name="design_space_surrogate.png")
    assert v.console_errors == [] and v.foreign_requests == [] and v.scripts == 0
    assert "attribution" in v.ids and len(v.images) == 2  # the map and the attribution's bars
    assert all(i["complete"] and i["naturalWidth"] > 0 for i in v.images)
    rows = v.page.evaluate("""() => Array.from(document.querySelectorAll('.attribution-table tbody tr')).map(r => ({
        cells: Array.from(r.cells).map(c => c.innerText.trim()),
        shares: Object.fromEntries(Array.from(r.querySelectorAll('td[data-source]')).map(
            c => [c.dataset.source, c.innerText.trim()])),
        marked: Array.from(r.querySelectorAll('td.dominant')).map(c => c.dataset.source),
        dominant: r.querySelector('td.dominant-source').innerText.trim()}))""")
    assert len(rows) == len(nodes) == 4
    label = {"parameters": "calibration", "tolerances": "tolerances", "noise": "run noise"}
    counts = dict.fromkeys(label.values(), 0)
    for row, nd in zip(rows, nodes):
        a = nd["attribution"]["tcr_c_per_min"]
        assert row["shares"] == {k: f"{a[k]:.3f}" for k in ("parameters", "tolerances", "noise", "interaction")}
        top = max(("parameters", "tolerances", "noise"), key=lambda k: a[k])
        assert row["marked"] == [top] and row["dominant"] == label[top] == label[a["dominant"]]
        assert row["cells"][2] == f"{nd['p']:.3f} ± {nd['p_se']:.3f}"
        assert row["cells"][3] == fmt_num(nd["limits"]["tcr_c_per_min"]["upper"])  # κ's limit met with p 0.9
        counts[label[top]] += 1
    shown = v.page.evaluate("() => Object.fromEntries(Array.from(document.querySelectorAll('.dominant-count')).map("
                            "e => [e.dataset.source, Number(e.innerText)]))")
    assert shown == counts
