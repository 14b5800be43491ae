"""The regression core (rsm_lrg.model.engines.least_squares) against independent routes.

References and tolerances:
* statsmodels 0.15 OLS of the same matrix (params, normalized_cov_params, ssr, hat
  diagonal, nested-model F tests via ``compare_f_test``): 1e-9 relative;
* ``numpy.linalg.lstsq`` (SVD): 1e-9 relative;
* the exact least-squares answer on rationals (``_exact.py``): 1e-9 relative;
* R 4.2.2 ``lm`` (``r/lm_accuracy.R`` -> ``r/lm_expected.csv``): 1e-9 relative;
* the chunked factorisation (any chunk size, any merge order) against one chunk: 1e-12
  relative (the same algebra, only the order of the rounding differs).
"""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from _exact import exact_lstsq, max_rel_error
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import rsm_lrg
from rsm_lrg.model.build.terms import design_matrix, model_terms
from rsm_lrg.model.engines.least_squares import Accumulator, least_squares

R_DIR = Path(__file__).parent / "r"


def _quadratic(n: int, k: int, seed: int, offset: float = 0.0):
    rng = np.random.default_rng(seed)
    x = rng.uniform(-1, 1, (n, k))
    terms = model_terms([chr(65 + i) for i in range(k)], "quadratic")
    X = design_matrix(x, terms)
    y = offset + X @ rng.normal(size=X.shape[1]) + rng.normal(0, 0.5, n)
    return X, y, [t.name for t in terms]


@pytest.fixture(scope="module")
def table4():
    return rsm_lrg.fit(rsm_lrg.load_table4(), "tcr_c_per_min")


def test_core_matches_statsmodels_ols(table4):
    import statsmodels.api as sm

    X, y = table4.design_matrix, table4.y
    ls = least_squares(X, y, table4.column_names)
    ols = sm.OLS(y, X).fit()
    np.testing.assert_allclose(ls.params, ols.params, rtol=1e-9, atol=1e-15)
    np.testing.assert_allclose(ls.cov_unscaled, ols.normalized_cov_params, rtol=1e-9,
                               atol=1e-13 * np.abs(ols.normalized_cov_params).max())  # zeros by symmetry: round-off
    assert ls.ss_res == pytest.approx(ols.ssr, rel=1e-9)
    assert ls.df_resid == ols.df_resid
    np.testing.assert_allclose(ls.hat, ols.get_influence().hat_matrix_diag, rtol=1e-9)
    np.testing.assert_allclose(ls.residuals, ols.resid, rtol=1e-9, atol=1e-12 * np.ptp(y))
    np.testing.assert_allclose(ls.std_errors, ols.bse, rtol=1e-9)
    infl = ols.get_influence()
    assert ls.press == pytest.approx(float(np.sum(infl.resid_press ** 2)), rel=1e-9)


def test_sums_of_squares_match_statsmodels_nested_fits():
    # sequential SS of a block of columns = ssr(before) - ssr(with it); partial SS of a group
    # = ssr(without it) - ssr(full) (statsmodels fits of each model, compare_f_test for F).
    import statsmodels.api as sm

    X, y, names = _quadratic(60, 3, seed=4)
    ls = least_squares(X, y, names)
    full = sm.OLS(y, X).fit()
    first = sm.OLS(y, X[:, :4]).fit()  # intercept + linear
    assert ls.sequential_ss(range(4, X.shape[1])) == pytest.approx(first.ssr - full.ssr, rel=1e-9)
    assert ls.residual_ss_after(4) == pytest.approx(first.ssr, rel=1e-9)
    group = [4, 5, 6]  # the three interactions, jointly
    reduced = sm.OLS(y, np.delete(X, group, axis=1)).fit()
    ss = ls.partial_ss(group)
    assert ss == pytest.approx(reduced.ssr - full.ssr, rel=1e-9)
    f, _, df = full.compare_f_test(reduced)
    assert (ss / df) / ls.sigma2 == pytest.approx(f, rel=1e-9)
    sub = ls.submodel([j for j in range(X.shape[1]) if j not in group])
    np.testing.assert_allclose(sub.params, reduced.params, rtol=1e-9, atol=1e-14)
    np.testing.assert_allclose(sub.cov_unscaled, reduced.normalized_cov_params, rtol=1e-9, atol=1e-14)
    assert sub.ss_res == pytest.approx(reduced.ssr, rel=1e-9)


def test_vif_matches_statsmodels_variance_inflation_factor():
    from statsmodels.stats.outliers_influence import variance_inflation_factor

    X, y, names = _quadratic(50, 3, seed=9)
    ls = least_squares(X, y, names)
    ref = [variance_inflation_factor(X, j) for j in range(1, X.shape[1])]
    np.testing.assert_allclose(ls.vif(range(1, X.shape[1])), ref, rtol=1e-9)


@pytest.mark.parametrize("seed", [0, 1])
def test_core_matches_numpy_lstsq(seed):
    X, y, names = _quadratic(80, 4, seed=seed)
    ls = least_squares(X, y, names)
    b, res, rank, _ = np.linalg.lstsq(X, y, rcond=None)
    np.testing.assert_allclose(ls.params, b, rtol=1e-9, atol=1e-13)
    assert ls.ss_res == pytest.approx(float(res[0]), rel=1e-9)
    assert ls.rank == rank == X.shape[1]


@pytest.mark.parametrize("offset", [0.0, 1e6, 1e9])
def test_core_matches_exact_rationals(offset):
    X, y, names = _quadratic(20, 2, seed=3, offset=offset)
    ls = least_squares(X, y, names, chunk_rows=7)
    assert max_rel_error(ls.params, exact_lstsq(X, y)) < 1e-9


@pytest.mark.parametrize("name", ["lm_scales", "lm_offset"])
def test_core_coefficients_against_r_lm(name):
    # R lm on the coded data (lm_expected.csv); for lm_offset R itself is ~7e-7 off the
    # exact answer, so there the core is checked against the exact answer and R within R's error.
    fitted = rsm_lrg.fit(pd.read_csv(R_DIR / f"{name}.csv"), "y", factors=["thickness_m", "freq_hz", "temp_c"])
    ls = fitted.least_squares
    ours = pd.Series(ls.params, index=ls.names)
    ref = pd.read_csv(R_DIR / "lm_expected.csv")
    ref = ref[ref.dataset == f"{name}_coded"].set_index("term")["estimate"]
    exact = exact_lstsq(fitted.design_matrix, fitted.y)
    assert max_rel_error(ls.params, exact) < 1e-9
    r_err = max_rel_error(ref[list(ls.names)], exact)
    np.testing.assert_allclose(ours[ref.index], ref, rtol=max(1e-9, 2 * r_err))


def _compare(a, b, rtol=1e-12):
    scale = max(np.abs(a.params).max(), 1.0)
    np.testing.assert_allclose(a.params, b.params, rtol=rtol, atol=rtol * scale)
    np.testing.assert_allclose(a.cov_unscaled, b.cov_unscaled, rtol=rtol, atol=rtol * np.abs(a.cov_unscaled).max())
    assert a.ss_res == pytest.approx(b.ss_res, rel=rtol)
    assert a.ss_total == pytest.approx(b.ss_total, rel=rtol)
    np.testing.assert_allclose(a.hat, b.hat, rtol=rtol, atol=rtol)
    spread = float(np.abs(a.residuals).max())
    np.testing.assert_allclose(a.residuals, b.residuals, rtol=0, atol=rtol * 10 * spread)
    assert a.press == pytest.approx(b.press, rel=rtol * 10)
    cols = range(1, a.p)
    np.testing.assert_allclose(a.vif(cols), b.vif(cols), rtol=rtol * 10)
    np.testing.assert_allclose([a.sequential_ss([j]) for j in cols], [b.sequential_ss([j]) for j in cols],
                               rtol=1e-9, atol=rtol * a.ss_total)
    np.testing.assert_allclose([a.partial_ss([j]) for j in cols], [b.partial_ss([j]) for j in cols],
                               rtol=1e-9, atol=rtol * a.ss_total)


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(n=st.integers(12, 200), chunk=st.integers(1, 64), seed=st.integers(0, 2 ** 16),
       offset_exp=st.integers(0, 9))
def test_chunked_factorisation_equals_one_chunk(n, chunk, seed, offset_exp):
    X, y, names = _quadratic(n, 2, seed=seed, offset=10.0 ** offset_exp)
    one = least_squares(X, y, names, chunk_rows=n)
    many = least_squares(X, y, names, chunk_rows=chunk)
    _compare(one, many)


@settings(max_examples=15, deadline=None)
@given(parts=st.lists(st.integers(1, 40), min_size=2, max_size=8), seed=st.integers(0, 2 ** 16))
def test_merged_partitions_equal_one_chunk(parts, seed):
    # a tree reduction over partitions (as over a Dask DataFrame's) gives the same factor
    n = sum(parts)
    X, y, names = _quadratic(max(n, 8), 2, seed=seed)
    n = X.shape[0]
    shift = float(np.mean(y[: parts[0]]))
    accs, s = [], 0
    for m in parts + [n - sum(parts)]:
        if m > 0:
            accs.append(Accumulator(p=X.shape[1], shift=shift).add(X[s:s + m], y[s:s + m]))
        s += m
    while len(accs) > 1:  # pairwise, like a tree
        accs = [accs[i].merge(accs[i + 1]) if i + 1 < len(accs) else accs[i] for i in range(0, len(accs), 2)]
    merged = accs[0].result(names)
    one = least_squares(X, y, names, chunk_rows=n)
    np.testing.assert_allclose(merged.params, one.params, rtol=1e-12, atol=1e-12 * np.abs(one.params).max())
    assert merged.rho ** 2 == pytest.approx(one.ss_res, rel=1e-10)


def test_fit_in_small_chunks_equals_fit_in_one(table4):
    d = rsm_lrg.load_table4()
    small = rsm_lrg.fit(d, "tcr_c_per_min", chunk_rows=4)
    # each column to 1e-12 of its largest entry (a coefficient that is zero by symmetry is round-off either way)
    for frame_a, frame_b in ((small.coefficients, table4.coefficients), (small.anova, table4.anova)):
        for c in frame_a.select_dtypes("number").columns:
            a, b = frame_a[c].to_numpy(float), frame_b[c].to_numpy(float)
            np.testing.assert_allclose(a, b, rtol=1e-12, atol=1e-12 * np.nanmax(np.abs(b)), equal_nan=True)
    assert small.statistics.press == pytest.approx(table4.statistics.press, rel=1e-12)
    np.testing.assert_allclose(small.hat, table4.hat, rtol=1e-12)


def test_design_matrix_is_not_held_by_the_fit(table4):
    r = rsm_lrg.fit(rsm_lrg.load_table4(), "tcr_c_per_min")
    assert "design_matrix" not in r.__dict__
    X = r.design_matrix
    assert X.shape == (27, 15) and r.design_matrix is X
    np.testing.assert_allclose(X @ r.least_squares.params, r.fitted, rtol=1e-12)


def test_rank_deficiency_is_found_once_and_named():
    X, y, names = _quadratic(30, 2, seed=1)
    X = np.column_stack([X, 2.0 * X[:, 1] - X[:, 2]])  # a combination of A and B
    ls = least_squares(X, y, names + ["E"])
    assert ls.rank == 6 and ls.aliased == ("E",) and ls.hat is None
    with pytest.raises(ValueError, match=r"term\(s\) E are aliased with earlier terms \(the design matrix has rank 6 < 7\)"):
        ls.require_full_rank()
    with pytest.raises(ValueError, match=r"term\(s\) E are aliased"):
        ls.params  # noqa: B018
    assert ls.alias_relations() == ["E = 2·A - B"]
    # the estimable sub-model is the fit without the aliased column
    sub = ls.submodel(ls.kept)
    np.testing.assert_allclose(sub.params, least_squares(X[:, :6], y).params, rtol=1e-9)


def test_fit_summary_sequential_ss_from_one_factorisation_match_statsmodels_anova_lm():
    # anova_lm comparing the fitted nested models (linear, 2FI, quadratic) gives the
    # sequential SS of fit_summary: 1e-9 relative.
    import statsmodels.api as sm
    from statsmodels.stats.anova import anova_lm

    from rsm_lrg.model.choice.summary import fit_summary

    d = rsm_lrg.load_table4()
    s = fit_summary(d, "tcr_c_per_min", orders=("linear", "2fi", "quadratic"))
    r = rsm_lrg.fit(d, "tcr_c_per_min")
    X, y = r.design_matrix, r.y
    fits = [sm.OLS(y, X[:, :m]).fit() for m in (1, 5, 11, 15)]
    table = anova_lm(*fits)
    seq = s.sequential.set_index("source")
    for row, src in zip(range(1, 4), ["Linear vs Mean", "2FI vs Linear", "Quadratic vs 2FI"]):
        assert seq.loc[src, "sum_sq"] == pytest.approx(table["ss_diff"].iloc[row], rel=1e-9)
    stats = s.statistics.set_index("source")
    assert stats.loc["Quadratic", "press"] == pytest.approx(r.statistics.press, rel=1e-12)


def test_core_against_r_rsm_on_a_ccd_with_replicates():
    # r/core_check.R (R 4.2.2, rsm 2.10.6) on r/core_ccd4.csv (coded data, offset 1e4; made by
    # r/make_data.py): coefficients, the sequential SS of rsm's summary (FO, TWI, PQ = the fit
    # summary's Linear, 2FI, Quadratic rows), residual / lack of fit / pure error SS, PRESS, the hat
    # diagonal and the VIF, all to 1e-9 relative.
    from rsm_lrg.model.choice.summary import fit_summary

    d = pd.read_csv(R_DIR / "core_ccd4.csv")
    ref = pd.read_csv(R_DIR / "core_expected.csv")
    val = {(q, nm): v for q, nm, v in ref.itertuples(index=False)}
    specs = [f"x{i}=-1:1" for i in range(1, 5)]
    r = rsm_lrg.fit(d, "y", factors=specs)
    np.testing.assert_allclose(r.coefficients["coded"], ref[ref.quantity == "coef"]["value"], rtol=1e-9)
    an = r.anova.set_index("source")
    for ours, theirs in (("Residual", "Residuals"), ("Lack of Fit", "Lack of fit"), ("Pure Error", "Pure error")):
        assert an.loc[ours, "sum_sq"] == pytest.approx(val[("ss", theirs)], rel=1e-9)
        assert an.loc[ours, "df"] == int(val[("df", theirs)])
    assert r.statistics.press == pytest.approx(val[("press", "PRESS")], rel=1e-9)
    np.testing.assert_allclose(r.hat, ref[ref.quantity == "hat"]["value"], rtol=1e-9)
    np.testing.assert_allclose(r.coefficients["vif"].iloc[1:], ref[ref.quantity == "vif"]["value"], rtol=1e-9)
    s = fit_summary(d, "y", factors=specs, orders=("linear", "2fi", "quadratic")).sequential.set_index("source")
    for ours, theirs in (("Linear vs Mean", "FO(x1, x2, x3, x4)"), ("2FI vs Linear", "TWI(x1, x2, x3, x4)"),
                         ("Quadratic vs 2FI", "PQ(x1, x2, x3, x4)")):
        assert s.loc[ours, "sum_sq"] == pytest.approx(val[("ss", theirs)], rel=1e-9)
        assert s.loc[ours, "df"] == int(val[("df", theirs)])
