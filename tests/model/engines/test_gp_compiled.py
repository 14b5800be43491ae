"""The compiled loops of the GP engine (:mod:`rsm_lrg.model.engines.gp_compiled`) against the
NumPy code they replace on many runs: the correlation matrix, the likelihood's gradient (and
central differences of the likelihood itself), the inverse, the mean-only prediction, and the
subsample search with its polish on every run."""

import numpy as np
import pandas as pd
import pytest

from rsm_lrg.model.engines import gp_kernels
from rsm_lrg.model.engines.gp_core import POTRI_RUNS, inverse_lower
from rsm_lrg.model.engines.gp_kernels import KERNELS, correlation
from rsm_lrg.model.pipelines import gp as gp_pipeline
from rsm_lrg.model.pipelines.gp import MULTISTART_RUNS, ProfileLikelihood, fit_gp


def _numpy_only(monkeypatch):
    monkeypatch.setattr(gp_kernels, "COMPILED_PAIRS", 1 << 62)
    monkeypatch.setattr(gp_pipeline, "COMPILED_PAIRS", 1 << 62)


@pytest.mark.parametrize("kernel", KERNELS)
def test_compiled_correlation_equals_numpy(kernel, monkeypatch):
    rng = np.random.default_rng(3)
    x = rng.uniform(-1, 1, (300, 3))
    xn = rng.uniform(-1, 1, (250, 3))
    theta = np.array([0.3, 0.9, 2.0])
    fast_sym, fast_cross = correlation(x, x, theta, kernel), correlation(xn, x, theta, kernel)
    _numpy_only(monkeypatch)
    slow_sym, slow_cross = correlation(x, x, theta, kernel), correlation(xn, x, theta, kernel)
    # the runs' matrix (the likelihood's): the same operations per pair, bit for bit
    assert np.array_equal(fast_sym, slow_sym)
    # the predictions': the vectorised exponential (within an ulp of the C library's) and
    # a * (1/3) for a / 3: a few units in the last place, and not all bit for bit
    np.testing.assert_allclose(fast_cross, slow_cross, rtol=2e-15, atol=1e-300)
    if kernel == "matern52":
        assert not np.array_equal(fast_cross, slow_cross)
    assert np.array_equal(fast_sym, fast_sym.T) and np.all(np.diag(fast_sym) == 1.0)


@pytest.mark.parametrize("kernel", KERNELS)
@pytest.mark.parametrize("form", ["concentrated", "variance_free", "all_fixed_noise"])
def test_compiled_gradient_equals_numpy_and_differences(kernel, form, monkeypatch):
    rng = np.random.default_rng(5)
    n = 260  # 260² pairs: the compiled path
    x = rng.uniform(-1, 1, (n, 3))
    y = np.sin(3 * x[:, 0]) + x[:, 1] * x[:, 2] + 0.01 * rng.standard_normal(n)
    F = np.column_stack([np.ones(n), x])
    conc, scale, noise = {"concentrated": (True, None, "estimate"), "variance_free": (False, None, "estimate"),
                          "all_fixed_noise": (False, 2.0, 1e-3)}[form]
    lik = ProfileLikelihood(x, y, F, kernel, theta=None, concentrated=conc, scale=scale, noise=noise)
    p = np.log([0.5, 0.8, 1.4])
    if form == "variance_free":
        p = np.r_[p, 0.3]
    if noise == "estimate":
        p = np.r_[p, np.log(1e-2)]
    assert n * n >= gp_pipeline.COMPILED_PAIRS
    f_fast, g_fast = lik(p)
    e = 1e-6
    fd = np.array([(lik(p + e * d)[0] - lik(p - e * d)[0]) / (2 * e) for d in np.eye(p.size)])
    _numpy_only(monkeypatch)
    f_slow, g_slow = lik(p)
    assert f_fast == pytest.approx(f_slow, rel=1e-13)
    np.testing.assert_allclose(g_fast, g_slow, rtol=1e-9, atol=1e-9 * np.max(np.abs(g_slow)))
    np.testing.assert_allclose(g_fast, fd, rtol=1e-5, atol=1e-6 * np.max(np.abs(g_slow)))


@pytest.mark.parametrize("n", [POTRI_RUNS - 1, POTRI_RUNS])
def test_inverse_lower_both_routes(n):
    rng = np.random.default_rng(n)
    a = rng.standard_normal((n, n))
    m = a @ a.T / n + np.eye(n)
    got = np.tril(inverse_lower(np.linalg.cholesky(m)))
    np.testing.assert_allclose(got, np.tril(np.linalg.inv(m)), rtol=1e-9, atol=1e-12)


@pytest.fixture(scope="module")
def big_fit():
    rng = np.random.default_rng(11)
    n = MULTISTART_RUNS + 40
    df = pd.DataFrame({"a": rng.uniform(0, 1, n), "b": rng.uniform(0, 1, n)})
    df["y"] = np.sin(6 * df.a) * np.cos(3 * df.b) + df.b ** 2
    return fit_gp(df, "y", starts=2, seed=4)


@pytest.mark.slow  # a fit on 340 runs
def test_mean_only_prediction_equals_the_chunked_one(big_fit):
    pts = np.random.default_rng(2).uniform(-1, 1, (400, 2))
    assert pts.shape[0] * big_fit.n >= gp_kernels.COMPILED_PAIRS
    fast = big_fit.predict_coded(pts)
    mean, _ = big_fit.mean_sd(pts)  # cross-correlations stored, BLAS products
    # two summation orders of sum_l k_l alpha_l (the weights alpha of an interpolating GP are
    # large and of both signs): each within n eps sum_l |k_l alpha_l| of the exact sum
    terms = big_fit.variance * np.abs(correlation(pts, big_fit.x, big_fit.length_scales, big_fit.kernel)) @ np.abs(
        big_fit.core.alpha)
    assert np.all(np.abs(fast - mean) <= 2 * big_fit.n * np.finfo(float).eps * terms)


@pytest.mark.slow  # a fit on 340 runs
def test_subsample_search_polished_on_every_run(big_fit):
    r = big_fit
    assert r.search == {"subsample": MULTISTART_RUNS, "polished": 1, "evaluations_subsample": r.search[
        "evaluations_subsample"], "evaluations_all": r.search["evaluations_all"]}
    assert r.search["evaluations_subsample"] > 0 and r.search["evaluations_all"] > 0
    assert any("random subsample of 300 runs and the best polished on all 340" in s for s in r.notes)
    assert r.to_dict()["gp"]["search"]["polished"] == 1
    # the polish is a maximum on all runs: no length-scale moved by 1% gives a higher likelihood
    lik = ProfileLikelihood(r.x, r.y, np.ones((r.n, 1)), r.kernel, theta=None, concentrated=True, scale=None,
                            noise=0.0)
    best = -lik(np.log(r.length_scales))[0]
    assert best == pytest.approx(r.log_likelihood, rel=1e-7)  # sigma2 R vs R: the same to conditioning
    for d in np.vstack([np.eye(2), -np.eye(2)]) * 0.01:
        assert -lik(np.log(r.length_scales) + d)[0] <= best + 1e-9
