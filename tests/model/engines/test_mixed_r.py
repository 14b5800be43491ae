"""REML fits with a random intercept against R: nlme, lme4 and pbkrtest.

Reference numbers: ``tests/model/r/mixed.R`` (R 4.2.2, nlme 3.1-162, lme4 1.1-31, pbkrtest
0.5.2; the script is kept beside its output ``mixed_*_expected.csv``) on five data sets none
of which was used to tune anything:

* ``mixed_cakeb`` — Lawson (2015), *Design and Analysis of Experiments with R*, ch. 10, daewr
  ``cakeb``: a split-plot response surface, 4 oven runs (whole plots) of 3, 3, 2, 3 cakes,
  oven temperature hard to change; quadratic model (unbalanced, 1 whole-plot error df);
* ``mixed_pastry`` — Lawson ch. 10, daewr ``pastry``: a blocked response surface in 3 factors,
  7 blocks of 4 taken as random (``random_block``); quadratic;
* ``mixed_cookie`` — Lawson ch. 8, daewr ``splitPdes``: a balanced split-plot factorial with
  categoric factors (whole plot = batch x shortening; tray temperature and bake temperature
  within), 3-level and 2-level terms, all interactions: den df must equal the containment df;
* ``mixed_sp_bal`` / ``mixed_sp_unbal`` — made by ``make_mixed.py``: 8 whole plots x 4 runs
  with 2 hard-to-change and 2 easy factors (quadratic), and 10 whole plots of 2 to 5 runs with a
  3-level categoric easy factor (quadratic).

Tolerances: coefficients, standard errors and variance components 1e-6 relative to nlme's REML
(run with tight convergence; lme4 agrees with nlme to ~1e-6 on cakeb's flat likelihood,
better elsewhere), Kenward–Roger den df, F and p 1e-5 relative to pbkrtest's ``KRmodcomp``
(computed on lme4's fit, whose own convergence limits the agreement to ~1e-7).
"""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from _r_names import ours, source

import rsm_lrg

R = Path(__file__).parents[1] / "r"
CASES = {
    "mixed_cakeb": ("y", ["x1", "x2"], {"whole_plot": "Ovenrun"}, {}),
    "mixed_pastry": ("y", ["x1", "x2", "x3"], {"random_block": "Block"}, {}),
    "mixed_cookie": ("y", ["short", "trayT", "bakeT"], {"whole_plot": "wp"}, {"terms": "A B C AB AC BC ABC"}),
    "mixed_sp_bal": ("wear_um", ["temp_c", "preload_kn", "speed_m_s", "lube_ml"], {"whole_plot": "whole_plot"}, {}),
    "mixed_sp_unbal": ("wear_um", ["temp_c", "preload_kn", "speed_m_s", "lube"], {"whole_plot": "whole_plot"}, {}),
}
RTOL_EST = 1e-6
RTOL_KR = 1e-5
_FITS: dict = {}


def _fit(name):
    if name not in _FITS:
        response, factors, random, extra = CASES[name]
        _FITS[name] = rsm_lrg.fit(pd.read_csv(R / f"{name}.csv"), response, factors=factors, **random, **extra)
    return _FITS[name]


@pytest.mark.parametrize("name", list(CASES))
def test_coefficients_and_gls_errors_match_nlme(name):
    res = _fit(name)
    exp = pd.read_csv(R / "mixed_coef_expected.csv")
    exp = exp[exp.dataset == name]
    assert len(exp) == len(res.coefficients)
    scale = float(np.max(np.abs(exp.estimate)))
    for row in exp.itertuples():
        col = ours(row.column, res.space)
        np.testing.assert_allclose(res.coefficients.loc[col, "coded"], row.estimate, rtol=RTOL_EST,
                                   atol=RTOL_EST * scale, err_msg=col)
        np.testing.assert_allclose(res.coefficients.loc[col, "std_error"], row.std_error, rtol=RTOL_EST, err_msg=col)
        # the JSON's std_errors are the GLS ones
        np.testing.assert_allclose(res.to_dict()["std_errors"]["coded"][col], row.std_error, rtol=RTOL_EST)


@pytest.mark.parametrize("name", list(CASES))
def test_variance_components_match_nlme(name):
    res = _fit(name)
    exp = pd.read_csv(R / "mixed_vc_expected.csv").set_index(["dataset", "component"])
    vc = res.mixed.variance_components
    kind = "whole_plot" if "whole_plot" in CASES[name][2] else "block"
    np.testing.assert_allclose(vc[kind].variance, exp.loc[(name, "group"), "nlme"], rtol=RTOL_EST)
    np.testing.assert_allclose(vc["residual"].variance, exp.loc[(name, "residual"), "nlme"], rtol=RTOL_EST)
    np.testing.assert_allclose(res.sigma2, exp.loc[(name, "residual"), "nlme"], rtol=RTOL_EST)
    js = res.to_dict()["variance_components"]
    assert set(js) == {kind, "residual"}
    assert js[kind]["ci_low"] < js[kind]["variance"] < js[kind]["ci_high"]


@pytest.mark.parametrize("name", list(CASES))
def test_kenward_roger_tests_match_pbkrtest(name):
    res = _fit(name)
    exp = pd.read_csv(R / "mixed_kr_expected.csv")
    exp = exp[exp.dataset == name]
    ours = {t["term"]: t for t in res.to_dict()["tests"]}
    assert len(ours) == len(exp) == len(res.model_terms)  # one row per term, no intercept
    for row in exp.itertuples():
        t = ours[source(row.term)]
        assert t["num_df"] == row.num_df
        np.testing.assert_allclose(t["den_df"], row.den_df, rtol=RTOL_KR, err_msg=row.term)
        np.testing.assert_allclose(t["f"], row.f, rtol=RTOL_KR, err_msg=row.term)
        np.testing.assert_allclose(t["p"], row.p, rtol=RTOL_KR, err_msg=row.term)


def test_balanced_split_plot_den_df_are_containment():
    """Cookie split-plot (4 whole plots = 2 batches x 2 shortenings; 6 runs each): the
    whole-plot factor is tested on 4 - 2 = 2 df, everything within plots on
    24 - 4 - (12 - 2) = 10 df, as the classical split-plot ANOVA has them."""
    res = _fit("mixed_cookie")
    den = {t.term: t.den_df for t in res.tests}
    assert den.pop("A") == pytest.approx(2.0, rel=1e-9)
    for term, df in den.items():
        assert df == pytest.approx(10.0, rel=1e-9), term
