"""Categoric factors against R's ``lm`` with sum-to-zero (``contr.sum``) coding.

Reference numbers: ``tests/model/r/categoric.R`` (R 4.2.2; the script is kept beside its
output, ``categoric_*_expected.csv``) on three data sets made by
``tests/model/r/make_categoric.py``: a Box–Behnken design crossed with a 2-level factor, a
face-centred CCD crossed with a 3-level factor (one run without a response), and a 3x3
factorial crossed with a 2-level and a 3-level factor (categoric x categoric interactions).
Tolerance: 1e-9 relative (the issue's bar) on every coefficient, standard error, ANOVA row
(multi-df categoric rows, lack of fit, pure error), PRESS and R², and on predictions with
their confidence and prediction intervals.
"""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from _r_names import ours, source

import rsm_lrg

R = Path(__file__).parent / "r"
CASES = {
    "cat_bbd3x2": ("yield_pct", ["temp_c", "time_min", "conc_pct", "supplier"]),
    "cat_ccd2x3": ("wear_um", ["speed_m_s", "load_n", "lubricant"]),
    "cat_f2x2x3": ("y", ["x1", "x2", "stage", "material"]),
}
NEW = {
    "cat_bbd3x2": {"temp_c": [140, 165], "time_min": [25, 38], "conc_pct": [6.5, 3.5], "supplier": ["south", "north"]},
    "cat_ccd2x3": {"speed_m_s": [0.45, 0.58, 0.5], "load_n": [700, 950, 800],
                   "lubricant": ["grease", "mineral", "synthetic"]},
    "cat_f2x2x3": {"x1": [1.5, 2.7], "x2": [37, 44], "stage": ["rms", "rfcms"], "material": ["polymer", "bronze"]},
}
RTOL = 1e-9


def _fit(name):
    response, factors = CASES[name]
    return rsm_lrg.fit(pd.read_csv(R / f"{name}.csv"), response, factors=factors)


@pytest.mark.parametrize("name", list(CASES))
def test_coefficients_and_errors_match_r(name):
    res = _fit(name)
    exp = pd.read_csv(R / "categoric_coef_expected.csv")
    exp = exp[exp.dataset == name]
    assert len(exp) == len(res.coefficients)
    for row in exp.itertuples():
        col = ours(row.column, res.space)
        np.testing.assert_allclose(res.coefficients.loc[col, "coded"], row.estimate, rtol=RTOL, atol=1e-12, err_msg=col)
        np.testing.assert_allclose(res.coefficients.loc[col, "std_error"], row.std_error, rtol=RTOL, err_msg=col)


@pytest.mark.parametrize("name", list(CASES))
def test_anova_rows_match_r(name):
    res = _fit(name)
    exp = pd.read_csv(R / "categoric_anova_expected.csv")
    exp = exp[exp.dataset == name]
    ours = res.anova.set_index("source")
    for row in exp.itertuples():
        src = source(row.source)
        assert int(ours.loc[src, "df"]) == row.df, src
        np.testing.assert_allclose(ours.loc[src, "sum_sq"], row.sum_sq, rtol=RTOL, err_msg=src)
        if not np.isnan(row.f):
            np.testing.assert_allclose(ours.loc[src, "f"], row.f, rtol=RTOL, err_msg=src)
            np.testing.assert_allclose(ours.loc[src, "p"], row.p, rtol=1e-8, err_msg=src)
    multi = [t for t in res.terms if t.df > 1]
    if name != "cat_bbd3x2":
        assert multi and all(int(ours.loc[t.name, "df"]) == t.df for t in multi)


@pytest.mark.parametrize("name", list(CASES))
def test_press_r2_and_predictions_match_r(name):
    res = _fit(name)
    st = pd.read_csv(R / "categoric_stats_expected.csv")
    st = dict(st[st.dataset == name][["stat", "value"]].itertuples(index=False))
    np.testing.assert_allclose(res.statistics.press, st["press"], rtol=RTOL)
    np.testing.assert_allclose(res.statistics.r2, st["r2"], rtol=RTOL)
    np.testing.assert_allclose(res.statistics.adj_r2, st["adj_r2"], rtol=RTOL)
    np.testing.assert_allclose(res.statistics.pred_r2, st["pred_r2"], rtol=RTOL)
    np.testing.assert_allclose(np.sqrt(res.sigma2), st["sigma"], rtol=RTOL)
    pr = pd.read_csv(R / "categoric_pred_expected.csv")
    pr = pr[pr.dataset == name]
    got = res.predict(pd.DataFrame(NEW[name]), interval="both")
    for col, rcol in [("predicted", "fit"), ("ci_low", "ci_low"), ("ci_high", "ci_high"), ("pi_low", "pi_low"),
                      ("pi_high", "pi_high")]:
        np.testing.assert_allclose(got[col].to_numpy(), pr[rcol].to_numpy(), rtol=RTOL, err_msg=col)


def test_levels_and_json_faces():
    res = _fit("cat_ccd2x3")
    d = res.to_dict()
    assert d["factors"][2] == {"letter": "C", "name": "lubricant", "kind": "categoric",
                               "levels": ["mineral", "synthetic", "grease"]}
    assert d["factors"][0]["kind"] == "numeric"
    assert {"C[mineral]", "C[synthetic]", "AC[mineral]", "AC[synthetic]"} <= set(d["coefficients"]["coded"])
    assert "C[grease]" not in d["coefficients"]["coded"]  # the last level is minus the sum of the others
    rows = {r["source"]: r for r in d["anova"]}
    assert rows["C"]["df"] == 2 and rows["AC"]["df"] == 2
    assert d["omitted_rows"] == [8]


def test_effects_sum_to_zero_and_predictions_per_level():
    # the effect of the last level is minus the sum of the others: predictions at each level
    # differ from their mean by exactly the level effects (a check by hand, no R)
    res = _fit("cat_ccd2x3")
    levels = res.space["lubricant"].levels
    pts = pd.DataFrame({"speed_m_s": [0.5] * 3, "load_n": [800] * 3, "lubricant": list(levels)})
    pred = res.predict(pts)["predicted"].to_numpy()
    c = res.coefficients["coded"]
    eff = np.array([c["C[mineral]"], c["C[synthetic]"], -(c["C[mineral]"] + c["C[synthetic]"])])
    np.testing.assert_allclose(pred - pred.mean(), eff, rtol=0, atol=1e-12)
