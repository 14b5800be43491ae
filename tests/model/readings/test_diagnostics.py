"""Per-run diagnostics against statsmodels' OLSInfluence, Box–Cox against scipy's
boxcox_llf profile and MLE, a planted outlier, and log-normal data that call for a log."""

import numpy as np
import pytest
import statsmodels.api as sm
from scipy import stats
from statsmodels.stats.outliers_influence import OLSInfluence

import rsm_lrg
from rsm_lrg.model.readings.diagnostics import box_cox, box_cox_ss, diagnostics


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
    # default rule (likelihood ratio) at the ends: n ln(SS(end)/SS(λ̂)) = χ²(0.95; 1)
    ss_min = box_cox_ss(r.design_matrix, r.y, [bc.lambda_best])[0]
    for end in bc.ci:
        ss_end = box_cox_ss(r.design_matrix, r.y, [end])[0]
        assert r.n * np.log(ss_end / ss_min) == pytest.approx(stats.chi2.ppf(0.95, 1), rel=1e-6)
    # Design-Expert's rule at the ends: ln SS(end) = ln SS_min(grid) + t²(0.025, ν)/ν
    de = box_cox(r, rule="design-expert")
    t = stats.t.ppf(0.975, r.df_resid)
    grid_min = box_cox_ss(r.design_matrix, r.y, np.round(np.arange(-3, 3.000001, 0.01), 10)).min()
    for end in de.ci:
        ss_end = box_cox_ss(r.design_matrix, r.y, [end])[0]
        assert np.log(ss_end) == pytest.approx(np.log(grid_min) + t * t / r.df_resid, rel=1e-9)


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


#: Box & Cox (1964), J. R. Stat. Soc. B 26, Table 1: survival times (10 h units) of animals,
#: 3 poisons x 4 treatments x 4 animals (R: ``boot::poisons``), in data order (poison cycles
#: fastest within treatment).
POISONS_TIME = [0.31, 0.45, 0.46, 0.43, 0.36, 0.29, 0.40, 0.23, 0.22, 0.21, 0.18, 0.23,
                0.82, 1.10, 0.88, 0.72, 0.92, 0.61, 0.49, 1.24, 0.30, 0.37, 0.38, 0.29,
                0.43, 0.45, 0.63, 0.76, 0.44, 0.35, 0.31, 0.40, 0.23, 0.25, 0.24, 0.22,
                0.45, 0.71, 0.66, 0.62, 0.56, 1.02, 0.71, 0.38, 0.30, 0.36, 0.31, 0.33]


def _poisons_fit():
    import pandas as pd

    df = pd.DataFrame({"poison": np.tile(np.repeat([1, 2, 3], 4), 4), "treat": np.repeat([1, 2, 3, 4], 12),
                       "time": POISONS_TIME})
    # additive two-way model: poison (3 levels) by A, A^2; treatment (4 levels) by B, B^2, B^3
    return rsm_lrg.fit(df, "time", factors=["poison=1:3", "treat=1:4"], model="cubic",
                       terms=["A", "B", "A^2", "B^2", "B^3"])


def test_box_cox_poisons_likelihood_rule_matches_box_cox_1964_and_r_mass():
    # Box & Cox (1964), Sec. 6: λ̂ = -0.75 for the additive model (the reciprocal, "rate of
    # dying", is within the interval). R 4.2 MASS::boxcox(time ~ poison + treat, lambda =
    # seq(-3, 3, 1e-4)): maximum at -0.7502, 95 % interval (loglik > max - χ²(0.95;1)/2)
    # -1.1380 .. -0.3561 on that grid (tolerance 1e-4, the grid step).
    r = _poisons_fit()
    bc = box_cox(r)
    assert bc.rule == "likelihood" and "maximum likelihood" in bc.rule_text and "χ²₁" in bc.rule_text
    assert bc.lambda_best == pytest.approx(-0.75, abs=5e-3)
    assert bc.lambda_best == pytest.approx(-0.7502, abs=1e-4)
    assert bc.ci[0] == pytest.approx(-1.1380, abs=1e-4) and bc.ci[1] == pytest.approx(-0.3561, abs=1e-4)
    assert bc.recommended == "inverse"
    assert "maximum likelihood" in r.diagnostics().summary()


def test_box_cox_poisons_design_expert_rule_against_an_independent_profile():
    # Independent route: transform with scipy.stats.boxcox's (y^λ - 1)/λ, scale by the
    # geometric mean, residual SS by numpy lstsq; Design-Expert's rule: grid minimum on
    # -3..3 step 0.01, interval ln SS <= ln SS_min + t²(0.025, ν)/ν (ν = 42).
    from scipy.optimize import brentq

    r = _poisons_fit()
    y = np.asarray(POISONS_TIME)
    X = r.design_matrix
    gm = np.exp(np.mean(np.log(y)))

    def ss(lam):
        z = stats.boxcox(y, lmbda=lam) / gm ** (lam - 1)
        res = z - X @ np.linalg.lstsq(X, z, rcond=None)[0]
        return float(res @ res)

    grid = np.round(np.arange(-3, 3.000001, 0.01), 10)
    prof = np.array([ss(l) for l in grid])
    best = grid[np.argmin(prof)]
    t = stats.t.ppf(0.975, 42)
    cut = np.log(prof.min()) + t * t / 42
    lo = brentq(lambda l: np.log(ss(l)) - cut, -3, best)
    hi = brentq(lambda l: np.log(ss(l)) - cut, best, 3)
    de = box_cox(r, rule="design-expert")
    assert de.rule == "design-expert" and "Design-Expert" in de.rule_text
    assert de.lambda_best == best == pytest.approx(-0.75, abs=1e-12)
    assert de.ci[0] == pytest.approx(lo, abs=1e-8) and de.ci[1] == pytest.approx(hi, abs=1e-8)
    # the t rule is wider than the likelihood interval here (-1.178 .. -0.315 vs -1.138 .. -0.356)
    ml = box_cox(r)
    assert de.ci[0] < ml.ci[0] and de.ci[1] > ml.ci[1]
    assert r.diagnostics(boxcox_rule="design-expert").box_cox.rule == "design-expert"
    with pytest.raises(ValueError, match="rule"):
        box_cox(r, rule="minitab")


def test_box_cox_of_a_transformed_fit_is_of_the_measured_response():
    """A fit of log κ (every κ positive, every log κ negative) has its Box–Cox profile: the
    profile of the response as measured with the same model matrix, the same λ̂ and interval as
    the untransformed fit's (issue 25: it said "the response has values <= 0"); with a
    constant k the profile is of y + k."""
    df = rsm_lrg.load_table4()
    plain = rsm_lrg.fit(df, "tcr_c_per_min")
    logged = rsm_lrg.fit(df, "tcr_c_per_min", transform="log")
    assert (logged.y < 0).all()
    d = diagnostics(logged)
    assert d.box_cox is not None and d.note == ""
    a, b = box_cox(plain), d.box_cox
    assert b.lambda_best == a.lambda_best and np.isfinite(a.lambda_best)
    np.testing.assert_allclose(np.asarray(b.ci, float), np.asarray(a.ci, float), rtol=1e-12)  # NaN/inf alike
    shifted = rsm_lrg.fit(df.assign(y=df["tcr_c_per_min"] - 0.01).drop(columns="tcr_c_per_min"), "y", transform="log", transform_constant=0.01)
    assert box_cox(shifted).lambda_best == pytest.approx(a.lambda_best, rel=1e-6)  # (y - 0.01) + 0.01 rounds
    assert (a.current, b.current) == (1.0, 0.0)  # the λ each model was fitted on


@pytest.mark.parametrize("unit", [1e-12, 1e-3, 60.0, 1e6, 1e8, 1e12])
def test_box_cox_lambda_does_not_depend_on_the_response_unit(unit):
    # issue 36: Table 4's response in other units moved λ̂ (-2.779 to -1.915 at 1e8) and its
    # interval; the profile is now taken of y / ẏ (geometric-mean scaling), scale-free
    d = rsm_lrg.load_table4()
    ref = rsm_lrg.fit(d, "tcr_c_per_min").diagnostics().box_cox
    got = rsm_lrg.fit(d.assign(tcr_c_per_min=d["tcr_c_per_min"] * unit), "tcr_c_per_min").diagnostics().box_cox
    assert got.lambda_best == pytest.approx(ref.lambda_best, abs=1e-6)
    assert got.ci[1] == pytest.approx(ref.ci[1], abs=1e-6)
