"""Per-run diagnostics against statsmodels' OLSInfluence, Box–Cox against scipy's
boxcox_llf profile and MLE, a planted outlier, and log-normal data that call for a log."""

import numpy as np
import pytest
import statsmodels.api as sm
from scipy import stats
from statsmodels.stats.outliers_influence import OLSInfluence

import rsm_lrg
from rsm_lrg.model.diagnostics import box_cox, box_cox_ss, diagnostics


@pytest.fixture(scope="module")
def paper():
    return rsm_lrg.fit(rsm_lrg.load_table4(), "tcr_c_per_min")


def test_per_run_values_match_statsmodels(paper):
    d = diagnostics(paper).table
    infl = OLSInfluence(sm.OLS(paper.y, paper.design_matrix).fit())
    np.testing.assert_allclose(d.leverage, infl.hat_matrix_diag, rtol=1e-10)
    np.testing.assert_allclose(d.externally_studentized, infl.resid_studentized_external, rtol=1e-9)
    np.testing.assert_allclose(d.studentized, infl.resid_studentized_internal, rtol=1e-9)
    np.testing.assert_allclose(d.cooks_distance, infl.cooks_distance[0], rtol=1e-9)
    np.testing.assert_allclose(d.dffits, infl.dffits[0], rtol=1e-9)
    assert d.run_order.tolist() == rsm_lrg.load_table4()["order"].tolist()
    np.testing.assert_allclose(d.predicted + d.residual, paper.y, rtol=1e-12)


def test_planted_outlier_is_flagged(paper):
    df = rsm_lrg.load_table4()
    df.loc[4, "tcr_c_per_min"] += 0.02  # about 11 residual standard deviations
    dg = diagnostics(rsm_lrg.fit(df, "tcr_c_per_min"))
    assert 5 in dg.flagged_runs
    row = dg.table.iloc[4]
    assert row.flag_outlier and abs(row.externally_studentized) > dg.limits["externally_studentized"]
    # limits as documented: 2p/n and 2 sqrt(p/n), Bonferroni t, F median
    assert dg.limits["leverage"] == pytest.approx(2 * 15 / 27)
    assert dg.limits["dffits"] == pytest.approx(2 * np.sqrt(15 / 27))
    assert dg.limits["externally_studentized"] == pytest.approx(stats.t.ppf(1 - 0.05 / 54, 11))
    assert dg.limits["cooks_distance"] == pytest.approx(stats.f.ppf(0.5, 15, 12))


def test_box_cox_profile_equals_scipy_boxcox_llf_for_the_mean_model():
    # For an intercept-only model -n/2 ln SS(λ) and scipy.stats.boxcox_llf differ by a constant,
    # and both give the same λ̂ as scipy.stats.boxcox (1e-6).
    y = np.random.default_rng(3).lognormal(1.0, 0.4, size=40)
    lam = np.linspace(-2, 2, 41)
    prof = -len(y) / 2 * np.log(box_cox_ss(np.ones((len(y), 1)), y, lam))
    llf = np.array([stats.boxcox_llf(l, y) for l in lam])
    diff = prof - llf
    assert np.ptp(diff) < 1e-9 * np.abs(diff).max()
    _, lam_scipy = stats.boxcox(y)
    from scipy.optimize import minimize_scalar
    lam_ours = minimize_scalar(lambda l: box_cox_ss(np.ones((len(y), 1)), y, [l])[0], bounds=(-3, 3),
                               method="bounded", options={"xatol": 1e-10}).x
    assert lam_ours == pytest.approx(lam_scipy, abs=1e-5)


def test_log_normal_regression_recommends_log():
    rng = np.random.default_rng(11)
    d = rsm_lrg.central_composite({"a": (-1, 1), "b": (-1, 1)}, center=(3, 3), seed=1).actual
    d["y"] = np.exp(1.0 + 1.5 * d["a"] - 1.0 * d["b"] + rng.normal(0, 0.05, len(d)))
    r = rsm_lrg.fit(d, "y", factors=["a=-1:1", "b=-1:1"], model="linear")
    bc = box_cox(r)
    assert bc.ci[0] <= 0.0 <= bc.ci[1]
    assert bc.recommended == "log" and bc.recommended_lambda == 0.0
    # Montgomery's interval rule holds at the ends: SS(end) = SS(λ̂)(1 + t²/ν)
    t = stats.t.ppf(0.975, r.df_resid)
    ss_min = box_cox_ss(r.design_matrix, r.y, [bc.lambda_best])[0]
    for end in bc.ci:
        assert box_cox_ss(r.design_matrix, r.y, [end])[0] == pytest.approx(ss_min * (1 + t * t / r.df_resid), rel=1e-6)


def test_non_positive_response_has_no_box_cox(paper):
    df = rsm_lrg.load_table4()
    df.loc[2, "tcr_c_per_min"] = -0.001
    dg = diagnostics(rsm_lrg.fit(df, "tcr_c_per_min"))
    assert dg.box_cox is None and "<= 0" in dg.note
    with pytest.raises(ValueError, match="row 3"):
        box_cox(rsm_lrg.fit(df, "tcr_c_per_min"))
    out = dg.to_dict()
    assert set(out) == {"runs", "limits", "box_cox", "note"} and len(out["runs"]) == 27
    assert "Limits" in dg.summary()
