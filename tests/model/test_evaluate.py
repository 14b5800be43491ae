"""Design evaluation: SPV at the centre against exact results (Box–Behnken intercept = centre
mean; Box & Hunter's closed form for rotatable CCDs), rotatability, VIF against statsmodels,
power by the noncentral F against a Monte-Carlo simulation and the orthogonal closed form."""

import numpy as np
import pytest
import statsmodels.api as sm
from scipy import stats
from statsmodels.stats.outliers_influence import variance_inflation_factor

import rsm_lrg
from rsm_lrg.design import read_design
from rsm_lrg.model.evaluate import evaluate_design
from rsm_lrg.model.terms import design_matrix, model_terms


def test_paper_bbd_spv_at_centre_is_n_over_n0():
    # In a Box–Behnken design b0 is the mean of the n0 centre runs (the paper's intercept
    # 0.03367 is the mean of 0.033, 0.034, 0.034), so SPV(0) = n / n0 = 27 / 3 = 9 exactly.
    e = evaluate_design(read_design("designs/paper-bbd4.csv"))
    assert e.spv_center == pytest.approx(9.0, rel=1e-12)
    assert e.df == {"model": 14, "residual": 12, "lack_of_fit": 10, "pure_error": 2, "blocks": 0}
    bbd3 = rsm_lrg.box_behnken({"a": (0, 1), "b": (0, 1), "c": (0, 1)}, center=3, randomize=False)
    assert evaluate_design(bbd3).spv_center == pytest.approx(15 / 3, rel=1e-12)
    # leverages sum to p (trace of the hat matrix)
    assert e.leverage.sum() == pytest.approx(15.0, rel=1e-12)
    # FDS curve is nondecreasing and brackets the region's SPV
    assert np.all(np.diff(e.fds.variance) >= 0)
    assert e.fds.spv.iloc[0] == pytest.approx(e.spv_region["min"]) and e.fds.spv.iloc[-1] == pytest.approx(e.spv_region["max"])


@pytest.mark.parametrize("k,n0", [(2, 5), (3, 6), (4, 7)])
def test_rotatable_ccd_spv_centre_closed_form_and_rotatability(k, n0):
    # Box & Hunter (1957) / Myers, Montgomery & Anderson-Cook Sec. 8.2: for a rotatable design
    # with moments λ2 = Σx²/N, λ4 = Σx_i²x_j²/N, SPV(0) = (k+2)λ4 / ((k+2)λ4 - kλ2²).
    # k = 2, n0 = 5 gives 2.6 (Var(b0) = 0.2σ², Montgomery Example 11.2).
    d = rsm_lrg.central_composite({f"x{i}": (-1, 1) for i in range(k)}, center=(n0, 0), randomize=False)
    X = d.coded_runs
    N = len(X)
    lam2 = np.sum(X[:, 0] ** 2) / N
    lam4 = np.sum(X[:, 0] ** 2 * X[:, 1] ** 2) / N
    ref = (k + 2) * lam4 / ((k + 2) * lam4 - k * lam2 ** 2)
    e = evaluate_design(d)
    assert e.spv_center == pytest.approx(ref, rel=1e-10)
    if k == 2:
        assert e.spv_center == pytest.approx(2.6, rel=1e-10)
    # rotatable: equal SPV on a sphere (1e-9)
    u = np.random.default_rng(0).normal(size=(50, k))
    u = 0.8 * u / np.linalg.norm(u, axis=1, keepdims=True)
    Z = design_matrix(u, model_terms(d.factors.letters, "quadratic"))
    Xm = design_matrix(X, model_terms(d.factors.letters, "quadratic"))
    v = N * np.einsum("ij,jk,ik->i", Z, np.linalg.inv(Xm.T @ Xm), Z)
    assert np.ptp(v) < 1e-9 * v.max()


def test_vif_matches_statsmodels():
    e = evaluate_design(read_design("designs/paper-bbd4.csv"))
    d = read_design("designs/paper-bbd4.csv")
    X = design_matrix(d.coded_runs, model_terms("ABCD", "quadratic"))
    for j, name in enumerate(e.terms.index):
        if j == 0:
            continue
        assert e.terms.loc[name, "vif"] == pytest.approx(variance_inflation_factor(X, j), rel=1e-9), name
    assert e.terms.loc["A^2", "vif"] == pytest.approx(1.25, rel=1e-12)


def test_power_noncentral_f_against_orthogonal_closed_form_and_simulation():
    d = rsm_lrg.full_factorial({"a": (-1, 1), "b": (-1, 1), "c": (-1, 1)}, levels=2, center=4, randomize=False)
    e = evaluate_design(d, "linear")
    # orthogonal 2^3 + 4 centres: C_jj = 1/8, λ = (2/2)² · 8 = 8, ν = 12 - 4 = 8
    ref = stats.ncf.sf(stats.f.ppf(0.95, 1, 8), 1, 8, 8.0)
    assert e.terms.loc["A", "power"] == pytest.approx(ref, rel=1e-12)
    # Monte-Carlo: effect of 2σ over -1..+1 (coefficient σ), 4000 data sets; 4 standard errors
    rng = np.random.default_rng(5)
    X = design_matrix(d.coded_runs, model_terms("ABC", "linear"))
    reps = 4000
    Y = X[:, [1]] * 1.0 + rng.normal(size=(len(X), reps))  # every column one data set
    beta, *_ = np.linalg.lstsq(X, Y, rcond=None)
    s2 = np.sum((Y - X @ beta) ** 2, axis=0) / (len(X) - 4)
    C11 = np.linalg.inv(X.T @ X)[1, 1]
    pvals = 2 * stats.t.sf(np.abs(beta[1] / np.sqrt(s2 * C11)), len(X) - 4)
    hits = int(np.sum(pvals < 0.05))
    # statsmodels on the first data set agrees with the vectorised t test
    assert sm.OLS(Y[:, 0], X).fit().pvalues[1] == pytest.approx(pvals[0], rel=1e-9)
    se = np.sqrt(ref * (1 - ref) / reps)
    assert hits / reps == pytest.approx(ref, abs=4 * se)


def test_aliased_model_is_reported():
    e = evaluate_design(read_design("designs/paper-bbd4.csv"), "cubic")
    assert e.aliased
    assert "Aliased" in e.summary()
    with pytest.raises(ValueError, match="region"):
        evaluate_design(read_design("designs/paper-bbd4.csv"), region="ball")
