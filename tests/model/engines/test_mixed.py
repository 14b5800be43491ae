"""REML with one random intercept (rsm_lrg.model.engines.mixed) on the one FitResult: properties that
need no R — the optimum is a stationary point of the profiled REML likelihood, the boundary
case equals ordinary least squares, predictions, actual units, reduction, invariances and the
refusals. The agreement with R (nlme, lme4, pbkrtest) is tests/model/engines/test_mixed_r.py."""

import json
import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.model.engines.mixed import fit_reml, group_codes, whiten

R = Path(__file__).parents[1] / "r"
BAL = ("wear_um", ["temp_c", "preload_kn", "speed_m_s", "lube_ml"])


def _bal(**kw):
    d = pd.read_csv(R / "mixed_sp_bal.csv")
    return rsm_lrg.fit(d, BAL[0], factors=BAL[1], whole_plot="whole_plot", **kw), d


def _m2l(X, y, codes, eta):
    """-2 REML log-likelihood (profiled over s2) by dense linear algebra, an independent route."""
    n, p = X.shape
    V = np.eye(n) + eta * (codes[:, None] == codes[None, :])
    Vi = np.linalg.inv(V)
    A = X.T @ Vi @ X
    b = np.linalg.solve(A, X.T @ Vi @ y)
    r = y - X @ b
    return (n - p) * math.log(r @ Vi @ r) + np.linalg.slogdet(V)[1] + np.linalg.slogdet(A)[1]


def test_reml_optimum_is_the_minimum_of_the_dense_profile():
    res, d = _bal()
    X, y, codes, eta = res.design_matrix, res.y, res.mixed.codes, res.mixed.eta
    assert eta > 0
    f0 = _m2l(X, y, codes, eta)
    for fac in (0.9, 0.99, 1.01, 1.1):
        assert _m2l(X, y, codes, eta * fac) > f0
    assert _m2l(X, y, codes, 0.0) > f0
    # the GLS coefficients by dense algebra at the same eta
    Vi = np.linalg.inv(np.eye(len(y)) + eta * (codes[:, None] == codes[None, :]))
    b = np.linalg.solve(X.T @ Vi @ X, X.T @ Vi @ y)
    np.testing.assert_allclose(res.coefficients["coded"].to_numpy(), b, rtol=1e-10, atol=1e-10 * np.abs(b).max())
    s2 = float((y - X @ b) @ Vi @ (y - X @ b)) / (len(y) - X.shape[1])
    assert res.sigma2 == pytest.approx(s2, rel=1e-10)
    np.testing.assert_allclose(res.coefficients["std_error"], np.sqrt(np.diag(np.linalg.inv(X.T @ Vi @ X)) * s2),
                               rtol=1e-10)


def test_whitening_gives_v_inverse():
    rng = np.random.default_rng(1)
    codes = np.array([0, 0, 0, 1, 1, 2, 2, 2, 2])
    X = rng.normal(size=(9, 3))
    Xw, _ = whiten(X, np.zeros(9), codes, 2.5)
    V = np.eye(9) + 2.5 * (codes[:, None] == codes[None, :])
    np.testing.assert_allclose(Xw.T @ Xw, X.T @ np.linalg.solve(V, X), rtol=1e-12)


def test_zero_whole_plot_variance_keeps_the_ols_estimates():
    """mixed_sp_zero.csv has no whole-plot variation: REML puts the component at 0 (the
    boundary); coefficients and standard errors are then the OLS ones, while the tests keep the
    zero component (pbkrtest's numbers: tests/model/engines/test_mixed_boundary.py)."""
    d = pd.read_csv(R / "mixed_sp_zero.csv")
    res = rsm_lrg.fit(d, BAL[0], factors=BAL[1], whole_plot="whole_plot")
    ols = rsm_lrg.fit(d, BAL[0], factors=BAL[1])
    assert res.mixed.eta == 0.0 and res.mixed.boundary
    vc = res.to_dict()["variance_components"]
    assert vc["whole_plot"]["variance"] == 0.0 and vc["whole_plot"]["ci_low"] is None
    np.testing.assert_allclose(res.coefficients["coded"], ols.coefficients["coded"], rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(res.coefficients["std_error"], ols.coefficients["std_error"], rtol=1e-10)
    assert any("boundary" in n for n in res.notes)
    # the profile's minimum over eta > 0 is not below the boundary's
    X, y, codes = res.design_matrix, res.y, res.mixed.codes
    assert all(_m2l(X, y, codes, e) >= _m2l(X, y, codes, 0.0) for e in (1e-6, 1e-3, 0.1, 1.0))


def test_predictions_and_intervals():
    res, d = _bal()
    pts = pd.DataFrame({"temp_c": [180.0, 250.0], "preload_kn": [3.0, 6.0], "speed_m_s": [0.3, 0.6], "lube_ml": [2, 1]})
    out = res.predict(pts, interval="both")
    X = rsm_lrg.model.build.terms.design_matrix(res.space.encode(pts).to_numpy(dtype=float), res.terms)
    np.testing.assert_allclose(out["predicted"], X @ res.coefficients["coded"].to_numpy(), rtol=1e-12)
    np.testing.assert_allclose(out["se_fit"], np.sqrt(np.einsum("ij,jk,ik->i", X, res.mixed.cov, X)), rtol=1e-10)
    var_a, df = res.kr_mean(pts)
    assert np.all(var_a >= out["se_fit"] ** 2 * (1 - 1e-12))  # Kenward-Roger inflates the variance
    t = rsm_lrg.model.contract.statistics.stdtrit(df, 0.975)
    np.testing.assert_allclose(out["ci_high"] - out["predicted"], t * np.sqrt(var_a), rtol=1e-10)
    half_pi = t * np.sqrt(var_a + res.mixed.sigma2_group + res.mixed.sigma2)  # a new run in a new whole plot
    np.testing.assert_allclose(out["pi_high"] - out["predicted"], half_pi, rtol=1e-10)


def test_actual_units_and_their_errors():
    """Actual-unit coefficients and standard errors against GLS on the actual-unit model
    matrix at the same variance ratio (the change of basis is linear)."""
    res, d = _bal()
    x = d[BAL[1]].to_numpy(dtype=float)
    cols = [np.ones(len(d))] + [x[:, j] for j in range(4)]
    names = ["Intercept", "temp_c", "preload_kn", "speed_m_s", "lube_ml"]
    for i in range(4):
        for j in range(i + 1, 4):
            cols.append(x[:, i] * x[:, j])
            names.append(f"{BAL[1][i]} * {BAL[1][j]}")
    for j in range(4):
        cols.append(x[:, j] ** 2)
        names.append(f"{BAL[1][j]}^2")
    Xa = np.column_stack(cols)
    codes = res.mixed.codes
    Vi = np.linalg.inv(np.eye(len(d)) + res.mixed.eta * (codes[:, None] == codes[None, :]))
    C = np.linalg.inv(Xa.T @ Vi @ Xa)
    b = C @ Xa.T @ Vi @ res.y
    ours = list(res.actual_coefficients.values())
    np.testing.assert_allclose(ours, b, rtol=1e-7)
    np.testing.assert_allclose(list(res.actual_std_errors.values()), np.sqrt(np.diag(C) * res.sigma2), rtol=1e-7)


def test_row_order_and_labels_do_not_matter():
    res, d = _bal()
    perm = np.random.default_rng(3).permutation(len(d))
    d2 = d.iloc[perm].reset_index(drop=True)
    d2["whole_plot"] = d2["whole_plot"].map(lambda s: f"plot-{s}")
    res2 = rsm_lrg.fit(d2, BAL[0], factors=BAL[1], whole_plot="whole_plot")
    np.testing.assert_allclose(res2.coefficients["coded"], res.coefficients["coded"], rtol=1e-9, atol=1e-12)
    assert res2.mixed.eta == pytest.approx(res.mixed.eta, rel=1e-9)
    for a, b in zip(res.tests, res2.tests):
        assert (a.term, a.num_df) == (b.term, b.num_df)
        assert a.den_df == pytest.approx(b.den_df, rel=1e-7) and a.f == pytest.approx(b.f, rel=1e-8)


def test_residuals_blups_and_frame():
    res, d = _bal()
    mm = res.mixed
    np.testing.assert_allclose(res.fitted + res.residuals, res.y, rtol=1e-12)
    np.testing.assert_allclose(mm.marginal_residuals - mm.conditional_residuals, mm.blups[mm.codes], atol=1e-12)
    # BLUP: u_i = s2_wp 1' V_i^-1 r_i / s2 (shrunken group mean of the marginal residuals)
    r = mm.marginal_residuals
    for g in range(mm.n_groups):
        m = int(np.sum(mm.codes == g))
        assert mm.blups[g] == pytest.approx(mm.eta * r[mm.codes == g].sum() / (1 + mm.eta * m), rel=1e-10)
    frame = res.to_frame()
    for c in ("marginal_residual", "conditional_residual", "marginal_fitted", "whole_plot"):
        assert c in frame.columns
    diag = res.diagnostics().to_dict()
    assert "marginal_residual" in diag["runs"][0] and diag["box_cox"] is None


def test_json_anova_is_the_kenward_roger_tests():
    res, _ = _bal()
    js = res.to_dict()
    assert [r["source"] for r in js["anova"]] == [t["term"] for t in js["tests"]]
    assert all(r["sum_sq"] is None and r["f"] == t["f"] and r["den_df"] == t["den_df"] for r, t in zip(js["anova"], js["tests"]))
    assert js["whole_plot"] == "whole_plot" and js["method"] == "REML"
    assert [t["term"] for t in js["tests"]] == [t.name for t in res.model_terms]
    assert set(js["tests"][0]) == {"term", "num_df", "den_df", "f", "p"}
    json.dumps(js, allow_nan=False)
    assert math.isnan(res.statistics.r2) and math.isnan(res.statistics.press)
    assert res.statistics.std_dev == pytest.approx(math.sqrt(res.mixed.sigma2))
    assert "REML variance components" in res.summary() and "Kenward-Roger" in res.summary()


def test_reduce_by_kenward_roger_p_values():
    res, d = _bal()
    red = rsm_lrg.fit(d, BAL[0], factors=BAL[1], whole_plot="whole_plot", reduce=True)
    assert red.mixed is not None and red.reduction is not None and red.reduction.removed
    first = red.reduction.steps.iloc[0]
    # the first removal is the removable term with the largest KR p-value of the full REML fit
    from rsm_lrg.model.choice.reduce import removable

    p = {t.term: t.p for t in res.tests}
    cand = {t.name: p[t.name] for t in removable(list(res.terms))}
    assert first["term"] == max(cand, key=cand.get) and first["p"] == pytest.approx(max(cand.values()), rel=1e-9)
    assert all(t.p <= 0.1 for t in red.tests if t.term in {s.name for s in removable(list(red.terms))})
    # FitResult.reduce refits with the same whole plots
    assert res.reduce().terms == red.terms


def test_random_block_is_the_same_machinery():
    d = pd.read_csv(R / "mixed_pastry.csv")
    a = rsm_lrg.fit(d, "y", factors=["x1", "x2", "x3"], random_block="Block")
    b = rsm_lrg.fit(d, "y", factors=["x1", "x2", "x3"], whole_plot="Block")
    np.testing.assert_allclose(a.coefficients["coded"], b.coefficients["coded"], rtol=1e-12)
    assert set(a.to_dict()["variance_components"]) == {"block", "residual"}
    assert a.to_dict()["random_block"] == "Block"


@pytest.mark.parametrize("kw, match", [
    ({"whole_plot": "wp"}, "whole-plot column 'wp' not found"),
    ({"whole_plot": "wear_um"}, "both the response and the whole-plot"),
    ({"whole_plot": "whole_plot", "block": "whole_plot"}, "fixed blocks together"),
    ({"whole_plot": "whole_plot", "random_block": "whole_plot"}, "not both"),
])
def test_refusals(kw, match):
    d = pd.read_csv(R / "mixed_sp_bal.csv")
    with pytest.raises(ValueError, match=match):
        rsm_lrg.fit(d, BAL[0], factors=BAL[1], **kw)


def test_a_single_whole_plot_is_refused():
    d = pd.read_csv(R / "mixed_sp_bal.csv").assign(whole_plot="X")
    with pytest.raises(ValueError, match=r"whole-plot column 'whole_plot' has a single level \('X'\)"):
        rsm_lrg.fit(d, BAL[0], factors=BAL[1], whole_plot="whole_plot")


def test_empty_whole_plot_cell_names_the_row():
    d = pd.read_csv(R / "mixed_sp_bal.csv")
    d.loc[6, "whole_plot"] = None
    with pytest.raises(ValueError, match=r"whole-plot column 'whole_plot', row 7: is empty"):
        rsm_lrg.fit(d, BAL[0], factors=BAL[1], whole_plot="whole_plot")


def test_too_few_whole_plots_names_the_terms():
    """Quadratic in two whole-plot factors: 6 whole-plot terms (Intercept, A, B, AB, A^2, B^2)
    need at least 7 whole plots; 6 are refused, naming them."""
    d = pd.read_csv(R / "mixed_sp_bal.csv")
    d = d[~d.whole_plot.isin(["W7", "W8"])]
    with pytest.raises(ValueError, match=r"6 whole plots cannot estimate the 6 whole-plot terms \(Intercept, A, B, AB, "
                                         r"A\^2, B\^2\)"):
        rsm_lrg.fit(d, BAL[0], factors=BAL[1], whole_plot="whole_plot")


def test_one_run_whole_plots_name_the_plot():
    d = pd.read_csv(R / "mixed_sp_bal.csv")
    d = d.assign(whole_plot=[f"R{i}" for i in range(len(d))])  # every run its own whole plot
    with pytest.raises(ValueError, match=r"whole plot 'R0' has one run and the model needs more"):
        rsm_lrg.fit(d, BAL[0], factors=BAL[1], model="linear", whole_plot="whole_plot")


def test_exact_fit_is_refused():
    d = pd.read_csv(R / "mixed_sp_bal.csv")
    d[BAL[0]] = 3.0 + d.temp_c / 100 - 2 * d.speed_m_s  # a linear response without error
    with pytest.raises(ValueError, match="fits the data exactly"):
        rsm_lrg.fit(d, BAL[0], factors=BAL[1], model="linear", whole_plot="whole_plot")


def test_group_codes_keep_first_appearance():
    codes, labels = group_codes(["b", "a", "b", "c"])
    assert codes.tolist() == [0, 1, 0, 2] and labels == ("b", "a", "c")


def test_fit_reml_direct_matches_result():
    res, d = _bal()
    mm, reg = fit_reml(res.design_matrix, res.y, res.mixed.codes, res.mixed.labels, list(res.column_names),
                       column="whole_plot")
    np.testing.assert_allclose(reg.params, res.coefficients["coded"], rtol=1e-12)
    assert mm.m2loglik == pytest.approx(res.mixed.m2loglik)


def test_hard_to_change_factors_are_checked_per_whole_plot():
    """A hard-to-change factor that varies inside a whole plot is refused naming the whole
    plot and its rows; the accepted ones leave the fit unchanged and are named in the notes."""
    plain, d = _bal()
    assert "Factors constant within every whole plot (whole-plot factors): temp_c, preload_kn." in plain.notes
    checked = rsm_lrg.fit(d, BAL[0], factors=BAL[1], whole_plot="whole_plot", hard_to_change=["temp_c", "preload_kn"])
    np.testing.assert_array_equal(checked.mixed.beta, plain.mixed.beta)
    assert "Hard-to-change factors (checked constant within every whole plot): temp_c, preload_kn." in checked.notes
    rows = np.flatnonzero(d.whole_plot == "W3") + 1
    with pytest.raises(ValueError, match=r"hard-to-change factor 'speed_m_s' varies inside whole plot 'W1' \(rows 1-4\)"):
        rsm_lrg.fit(d, BAL[0], factors=BAL[1], whole_plot="whole_plot", hard_to_change="speed_m_s")
    moved = d.copy()
    moved.loc[rows[-1] - 1, "temp_c"] += 1.0  # one run of whole plot W3 at another temperature
    with pytest.raises(ValueError, match=rf"'temp_c' varies inside whole plot 'W3' \(rows {rows[0]}-{rows[-1]}\)"):
        rsm_lrg.fit(moved, BAL[0], factors=BAL[1], whole_plot="whole_plot", hard_to_change=["preload_kn", "temp_c"])
    notes = rsm_lrg.fit(moved, BAL[0], factors=BAL[1], whole_plot="whole_plot", model="linear").notes
    assert "Factors constant within every whole plot (whole-plot factors): preload_kn." in notes
    with pytest.raises(ValueError, match="give whole_plot too"):
        rsm_lrg.fit(d, BAL[0], factors=BAL[1], hard_to_change="temp_c")
