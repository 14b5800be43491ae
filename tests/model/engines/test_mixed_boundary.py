"""REML on the boundary: a variance component estimated at zero stays in the Kenward–Roger
computation, as pbkrtest and lmerTest keep it (issue 31).

Reference numbers: ``tests/model/r/mixed_boundary.R`` (R 4.2.2, lme4 1.1-31, pbkrtest 0.5.2,
lmerTest 3.1-3; the script is kept beside its outputs ``mixed_boundary_*_expected.csv``) on
three data sets none of which was used to tune anything:

* ``mixed_apple`` — Lawson (2015), *Design and Analysis of Experiments with R*, daewr
  ``apple``: 4 random blocks of 6 apple-slice runs, A (4 levels) x B (3 levels); lme4 puts the
  block variance at exactly 0;
* ``mixed_sp_zero`` / ``mixed_sp_small`` — made by ``make_mixed.py``: 8 whole plots x 4 runs,
  quadratic in 4 factors, with no whole-plot effect and with a small one (sd 0.5); REML puts
  the whole-plot variance at 0 in both.

Before, rsm-lrg dropped the zero component and reported the OLS tests (den df = n - p):
the whole-plot factor A of ``mixed_sp_zero`` was tested on 15 df, pbkrtest says 1.35.
"""

import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from _r_names import source

import rsm_lrg
from rsm_lrg.model.contract import statistics as special

R = Path(__file__).parents[1] / "r"
SP = ("wear_um", ["temp_c", "preload_kn", "speed_m_s", "lube_ml"], {"whole_plot": "whole_plot"}, {})
CASES = {
    "mixed_apple": ("rating", ["A=cat", "B=cat"], {"random_block": "Block"}, {"terms": "A B AB"}),
    "mixed_sp_zero": SP,
    "mixed_sp_small": SP,
}
RTOL_KR = 1e-6


def _fit(name):
    response, factors, random, extra = CASES[name]
    return rsm_lrg.fit(pd.read_csv(R / f"{name}.csv"), response, factors=factors, **random, **extra)


@pytest.mark.parametrize("name", list(CASES))
def test_zero_component_tests_match_pbkrtest(name):
    res = _fit(name)
    assert res.mixed.boundary and res.mixed.sigma2_group == 0.0
    exp = pd.read_csv(R / "mixed_boundary_kr_expected.csv")
    exp = exp[exp.dataset == name]
    ours = {t["term"]: t for t in res.to_dict()["tests"]}  # what `fit --json` writes
    assert len(ours) == len(exp) == len(res.model_terms)
    for row in exp.itertuples():
        t = ours[source(row.term)]
        assert t["num_df"] == row.num_df
        for key, want in (("den_df", row.den_df), ("f", row.f), ("p", row.p)):
            np.testing.assert_allclose(t[key], want, rtol=RTOL_KR, err_msg=f"{row.term} {key}")
        # lmerTest's Kenward-Roger anova is a second route to the same numbers
        np.testing.assert_allclose(t["den_df"], row.den_df_lmertest, rtol=1e-6, err_msg=row.term)


@pytest.mark.parametrize("name", list(CASES))
def test_residual_variance_matches_lme4(name):
    res = _fit(name)
    exp = pd.read_csv(R / "mixed_boundary_vc_expected.csv").set_index(["dataset", "component"])
    np.testing.assert_allclose(res.mixed.sigma2, exp.loc[(name, "residual"), "lmer"], rtol=1e-7)


@pytest.mark.parametrize("name", ["mixed_sp_zero", "mixed_sp_small"])
def test_prediction_se_and_df_match_lmertest(name):
    """The mean at five coded points: Kenward–Roger standard error sqrt(x'Φ_A x) and den df
    equal lmerTest's ``contest1D(ddf = "Kenward-Roger")``; the CI and PI of ``predict`` use them."""
    res = _fit(name)
    exp = pd.read_csv(R / "mixed_boundary_pred_expected.csv")
    exp = exp[exp.dataset == name]
    pts = exp[["A", "B", "C", "D"]].reset_index(drop=True)
    var_a, df = res.kr_mean(pts, coded=True)
    np.testing.assert_allclose(np.sqrt(var_a), exp.std_error, rtol=1e-6)
    np.testing.assert_allclose(df, exp.den_df, rtol=1e-6)
    out = res.predict(pts, coded=True, interval="both")
    np.testing.assert_allclose(out["predicted"], exp.estimate, rtol=1e-7)
    t = special.stdtrit(df, 0.975)
    np.testing.assert_allclose(out["ci_high"] - out["predicted"], t * np.sqrt(var_a), rtol=1e-10)
    np.testing.assert_allclose(out["pi_high"] - out["predicted"], t * np.sqrt(var_a + res.mixed.sigma2), rtol=1e-10)


def _dense_w(res):
    """W = I⁻¹, the inverse of the REML expected information I_rs = ½ tr(P G_r P G_s) (Kenward–
    Roger's W = 2 (tr P G_r P G_s)⁻¹), with dense n x n matrices (P = Σ⁻¹ - Σ⁻¹X(X'Σ⁻¹X)⁻¹X'Σ⁻¹, G = (ZZ', I)), at s2_group = 0."""
    mm = res.mixed
    X, codes, s2 = mm.X, mm.codes, mm.sigma2
    n = X.shape[0]
    ZZ = (codes[:, None] == codes[None, :]).astype(float)
    Si = np.eye(n) / s2
    P = Si - Si @ X @ np.linalg.solve(X.T @ Si @ X, X.T @ Si)
    G = (ZZ, np.eye(n))
    info = np.array([[0.5 * np.trace(P @ a @ P @ b) for b in G] for a in G])
    return np.linalg.inv(info)


@pytest.mark.parametrize("name", list(CASES))
def test_residual_variance_interval_keeps_the_zero_component(name):
    """The residual variance's Wald interval (log scale) takes its standard error from the
    information of both components, the zero one included (dense route)."""
    res = _fit(name)
    W = _dense_w(res)
    np.testing.assert_allclose(res.mixed.parts.W, W, rtol=1e-8)
    s2 = res.mixed.sigma2
    z = float(special.stdtrit(math.inf, 0.975))
    se_log = math.sqrt(W[1, 1]) / s2
    vc = res.to_dict()["variance_components"]
    kind = "block" if "random_block" in CASES[name][2] else "whole_plot"
    assert vc[kind]["variance"] == 0.0 and vc[kind]["ci_low"] is None
    np.testing.assert_allclose([vc["residual"]["ci_low"], vc["residual"]["ci_high"]],
                               [s2 * math.exp(-z * se_log), s2 * math.exp(z * se_log)], rtol=1e-8)


def test_whole_plot_factor_is_not_tested_as_ols():
    """The point of a split-plot analysis: the whole-plot factor A keeps its few den df."""
    res = _fit("mixed_sp_zero")
    ols = rsm_lrg.fit(pd.read_csv(R / "mixed_sp_zero.csv"), SP[0], factors=SP[1])
    den = {t.term: t.den_df for t in res.tests}
    assert den["A"] < 2.0 < ols.df_resid
    # the coefficients and their GLS standard errors are the OLS ones at s2_group = 0
    np.testing.assert_allclose(res.coefficients["coded"], ols.coefficients["coded"], rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(res.coefficients["std_error"], ols.coefficients["std_error"], rtol=1e-10)
    assert any("boundary" in n and "not the OLS tests" in n for n in res.notes)
