"""The profiler page computes what ``FitResult.predict`` computes, for every kind of model
(issue 31): OLS, transformed, blocked, categoric, mixture, mixture–process, REML whole plot,
REML random block (positive and zero variance component), and Gaussian processes (issue 33:
the page computes the kriging mean and variance from ``GPResult.kriging_form``).

The page reads the fit's interval form (:class:`rsm_lrg.model.contract.prediction.IntervalForm`) and
nothing else about its kind: for a REML fit it computes the Kenward–Roger df of each point and
the t quantile itself. At 50 random settings per kind, the page's prediction, CI and PI equal
``predict(..., interval="both")`` to 1e-9 relative (Chromium); and at the optimum the page,
the static section's numbers (``predict``) and ``rsm_lrg.optimize`` agree.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.factors import MixtureComponent
from rsm_lrg.report.interactive import write_interactive_report

pytestmark = [pytest.mark.browser, pytest.mark.slow]

R = Path(__file__).parents[1] / "model" / "r"
T4 = ["thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2"]
RTOL = 1e-9
COLS = ("predicted", "ci_low", "ci_high", "pi_low", "pi_high")


def _mixture_process() -> pd.DataFrame:
    rng = np.random.default_rng(31)
    blends = [(1, 0, 0), (0, 1, 0), (0, 0, 1), (.5, .5, 0), (.5, 0, .5), (0, .5, .5), (1 / 3, 1 / 3, 1 / 3),
              (2 / 3, 1 / 6, 1 / 6), (1 / 6, 2 / 3, 1 / 6), (1 / 6, 1 / 6, 2 / 3)]
    rows = []
    for t in (20.0, 40.0):
        for a, b, c in blends:
            y = 10 * a + 14 * b + 8 * c + 6 * a * b - 4 * b * c + 0.05 * (t - 30) * (a - c) + rng.normal(0, 0.2)
            rows.append({"x1": a, "x2": b, "x3": c, "temp": t, "y": y})
    return pd.DataFrame(rows)


def _kinds() -> dict:
    t4 = rsm_lrg.load_table4()
    blocked = t4.assign(day=np.where(np.arange(len(t4)) < 14, "one", "two"))
    cat = t4.assign(stage=np.random.default_rng(2).choice(["rfcms", "rms", "mix"], len(t4)))
    y = "tcr_c_per_min"
    return {
        "ols": rsm_lrg.fit(t4, y, factors=T4),
        "transformed": rsm_lrg.fit(t4, y, factors=T4, transform="log"),
        "blocked": rsm_lrg.fit(blocked, y, factors=T4, block="day"),
        "categoric": rsm_lrg.fit(cat, y, factors=T4 + ["stage"], model="2fi"),
        "mixture": rsm_lrg.fit(pd.read_csv(R / "mixture_etch_l.csv"), "erate", components=["x1", "x2", "x3"],
                               model="special-cubic"),
        "mixture_process": rsm_lrg.fit(_mixture_process(), "y", components=["x1", "x2", "x3"], factors=["temp"],
                                       model="mixture-quadratic"),
        "reml_whole_plot": rsm_lrg.fit(pd.read_csv(R / "mixed_sp_bal.csv"), "wear_um",
                                       factors=["temp_c", "preload_kn", "speed_m_s", "lube_ml"],
                                       whole_plot="whole_plot"),
        "reml_random_block": rsm_lrg.fit(pd.read_csv(R / "mixed_pastry.csv"), "y", factors=["x1", "x2", "x3"],
                                         random_block="Block"),
        "reml_zero_component": rsm_lrg.fit(pd.read_csv(R / "mixed_sp_small.csv"), "wear_um",
                                           factors=["temp_c", "preload_kn", "speed_m_s", "lube_ml"],
                                           whole_plot="whole_plot"),
        # Gaussian processes (issue 33): the page computes the kriging mean and variance itself
        "gp": rsm_lrg.fit(pd.read_csv(R / "gp_branin.csv"), "y", factors=["x1=-5:10", "x2=0:15"], model="gp"),
        "gp_noisy_quadratic_trend": rsm_lrg.fit(pd.read_csv(R / "gp_hartmann3.csv"), "y",
                                                factors=["x1=0:1", "x2=0:1", "x3=0:1"], model="gp", kernel="gauss",
                                                trend="quadratic", nugget="estimate"),
        "gp_matern32_linear": rsm_lrg.fit(pd.read_csv(R / "gp_branin.csv"), "y", factors=["x1=-5:10", "x2=0:15"],
                                          model="gp", kernel="matern32", trend="linear"),
    }


@pytest.fixture(scope="module")
def kinds():
    return _kinds()


def _random_settings(fit, n: int, rng) -> pd.DataFrame:
    """``n`` random settings in actual units: uniform in each numeric factor's range, a random
    level of each categoric factor, a random blend inside the components' bounds."""
    cols: dict = {}
    comps = [f for f in fit.space.factors if isinstance(f, MixtureComponent)]
    if comps:
        f0 = comps[0]
        z = rng.dirichlet(np.ones(len(comps)), n)  # L-pseudo components on the simplex
        for j, f in enumerate(comps):
            cols[f.name] = f.lower + z[:, j] * f0.pseudo_range
    for f in fit.space.factors:
        if isinstance(f, MixtureComponent):
            continue
        if f.kind == "categoric":
            cols[f.name] = [str(v) for v in rng.choice([str(v) for v in f.levels], n)]
        else:
            cols[f.name] = rng.uniform(f.low, f.high, n)
    return pd.DataFrame(cols)


KINDS = ["ols", "transformed", "blocked", "categoric", "mixture", "mixture_process", "reml_whole_plot",
         "reml_random_block", "reml_zero_component", "gp", "gp_noisy_quadratic_trend", "gp_matern32_linear"]


@pytest.mark.parametrize("kind", KINDS)
def test_page_predictions_equal_predict_at_50_random_settings(chromium, kinds, kind, tmp_path):
    fit = kinds[kind]
    path = write_interactive_report({fit.response: fit}, tmp_path / f"{kind}.html", source_name=kind)
    ctx = chromium.new_context(viewport={"width": 1280, "height": 900}, offline=True)
    try:
        page = ctx.new_page()
        errors: list = []
        page.on("pageerror", lambda e: errors.append(str(e)))
        page.goto(path.resolve().as_uri(), wait_until="load")
        page.wait_for_function("() => window.rsmReport !== undefined")
        pts = _random_settings(fit, 50, np.random.default_rng(KINDS.index(kind)))
        settings = [{k: (v if isinstance(v, str) else float(v)) for k, v in row.items()}
                    for row in pts.to_dict(orient="records")]
        got = page.evaluate("([r, ss]) => ss.map(s => { const p = window.rsmReport.predict(r, s); "
                            "return [p.predicted, p.ci_low, p.ci_high, p.pi_low, p.pi_high]; })",
                            [fit.response, settings])
        want = fit.predict(pts, interval="both")[list(COLS)].to_numpy(dtype=float)
        np.testing.assert_allclose(np.array(got, dtype=float), want, rtol=RTOL, atol=0, err_msg=kind)
        # and what the profiler shows at its starting setting (the data-* attributes)
        shown = page.evaluate("() => { const e = document.querySelector('[data-prediction]'); return {"
                              "s: window.rsmReport.setting(), v: [e.dataset.value, e.dataset.ciLow, e.dataset.ciHigh,"
                              " e.dataset.piLow, e.dataset.piHigh].map(Number)}; }")
        at = pd.DataFrame({k: [v] for k, v in shown["s"].items()})
        np.testing.assert_allclose(shown["v"], fit.predict(at, interval="both")[list(COLS)].to_numpy()[0],
                                   rtol=RTOL, atol=0)
        assert errors == []
    finally:
        ctx.close()


@pytest.mark.parametrize("kind", ["reml_whole_plot", "reml_random_block", "transformed", "gp"])
def test_page_static_section_and_optimize_agree_at_the_optimum(chromium, kinds, kind, tmp_path):
    """At the optimum: rsm_lrg.optimize's CI/PI, predict's (the static section's numbers) and
    the page's agree (the split-plot profiler once showed OLS-width intervals there)."""
    fit = kinds[kind]
    opt = rsm_lrg.optimize(fit, goal="minimize")
    d = opt.to_dict()
    setting = {k: (v if isinstance(v, str) else float(v)) for k, v in d["actual"].items()}
    ref = fit.predict(pd.DataFrame({k: [v] for k, v in setting.items()}), interval="both").iloc[0]
    path = write_interactive_report({fit.response: fit}, tmp_path / "opt.html", goals=["minimize"])
    ctx = chromium.new_context(viewport={"width": 1280, "height": 900}, offline=True)
    try:
        page = ctx.new_page()
        page.goto(path.resolve().as_uri(), wait_until="load")
        page.wait_for_function("() => window.rsmReport !== undefined")
        got = page.evaluate("([r, s]) => { const p = window.rsmReport.predict(r, s); "
                            "return [p.predicted, p.ci_low, p.ci_high, p.pi_low, p.pi_high]; }", [fit.response, setting])
    finally:
        ctx.close()
    np.testing.assert_allclose(got, ref[list(COLS)].to_numpy(dtype=float), rtol=RTOL)
    np.testing.assert_allclose(d["ci"] + d["pi"], ref[["ci_low", "ci_high", "pi_low", "pi_high"]].to_numpy(dtype=float),
                               rtol=1e-9)


def test_gp_page_shows_its_leave_one_out_beside_the_polynomials(chromium, kinds, tmp_path):
    """Issue 33, item 4: the GP's page puts its leave-one-out beside the polynomials' PRESS,
    readable on a desktop and a phone (the table scrolls inside its frame, not the page)."""
    from rsm_lrg.model.choice.loo_compare import compare_with_polynomials

    fit = kinds["gp"]
    cmp = compare_with_polynomials(pd.read_csv(R / "gp_branin.csv"), fit)
    path = write_interactive_report({fit.response: fit}, tmp_path / "loo.html", loo={fit.response: cmp})
    for width in (1280, 375):
        ctx = chromium.new_context(viewport={"width": width, "height": 800}, offline=True)
        try:
            page = ctx.new_page()
            errors: list = []
            page.on("pageerror", lambda e, errors=errors: errors.append(str(e)))
            page.goto(path.resolve().as_uri(), wait_until="load")
            assert page.locator("table.loo-comparison").is_visible()
            rows = page.evaluate("() => [...document.querySelectorAll('table.loo-comparison tbody tr')]"
                                 ".map(tr => [...tr.cells].map(c => c.textContent.trim()))")
            assert [r[0] for r in rows] == list(cmp.table["model"])
            assert [r[4] for r in rows if r[4]] == ["Smallest PRESS"] and rows[-1][4] == "Smallest PRESS"
            right = page.evaluate("() => document.querySelector('table.loo-comparison').closest('.table-wrap')"
                                  ".getBoundingClientRect().right")
            assert right <= width
            assert errors == []
        finally:
            ctx.close()
