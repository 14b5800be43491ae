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
    # the compiled loops: fused multiply-adds, the vectorised exponential (within an ulp of the
    # C library's): the exponent t of each pair carries a rounding of a few t eps in either
    # code, so each correlation is within 2 (1 + t) eps (relative) of the exact one, as NumPy's
    # is; against 40-digit values on 600 pairs
    import mpmath

    eps = np.finfo(float).eps
    expo = _exponents(xn, x, theta, kernel)
    assert np.all(np.abs(fast_cross - slow_cross) <= 4 * (1 + expo) * eps * slow_cross)
    assert not np.array_equal(fast_cross, slow_cross)
    expo_sym = _exponents(x, x, theta, kernel)
    assert np.all(np.abs(fast_sym - slow_sym) <= 4 * (1 + expo_sym) * eps * slow_sym)
    mpmath.mp.dps = 40
    pick = np.random.default_rng(4).choice(fast_cross.size, 600, replace=False)
    for f in pick:
        i, l = divmod(int(f), x.shape[0])
        exact = _exact_correlation(xn[i], x[l], theta, kernel)
        for got in (fast_cross[i, l], slow_cross[i, l]):
            assert abs(got - exact) <= 2 * (1 + expo[i, l]) * eps * exact
    assert np.array_equal(fast_sym, fast_sym.T) and np.all(np.diag(fast_sym) == 1.0)


def _exponents(x1, x2, theta, kernel):
    """The exponent of each pair's exponential (sum of |h| sqrt(5) / theta, or of h^2 / (2 theta^2))."""
    h = np.abs(x1[:, None, :] - x2[None, :, :]) / theta
    if kernel == "gauss":
        return 0.5 * np.sum(h * h, axis=2)
    return np.sqrt(5.0 if kernel == "matern52" else 3.0) * np.sum(h, axis=2)


def _exact_correlation(a, b, theta, kernel):
    """The correlation of settings a and b in 40-digit arithmetic (Roustant et al. 2012, Table 1)."""
    import mpmath

    total, poly = mpmath.mpf(0), mpmath.mpf(1)
    for aj, bj, tj in zip(a, b, theta):
        h = abs(mpmath.mpf(float(aj)) - mpmath.mpf(float(bj))) / mpmath.mpf(float(tj))
        if kernel == "gauss":
            total += h * h / 2
            continue
        s = mpmath.sqrt(5 if kernel == "matern52" else 3) * h
        total += s
        poly *= 1 + s + s * s / 3 if kernel == "matern52" else 1 + s
    return float(mpmath.exp(-total) * poly)


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
    assert r.search == {"length_scale_bounds": [1e-3, 10.0], "subsample": MULTISTART_RUNS, "polished": 1,
                        "evaluations_subsample": r.search[
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
    # the result's factorisation (the polish's last one, scaled by the variance) is the one of
    # its hyper-parameters
    from rsm_lrg.model.engines.gp_core import kriging_core

    # (the two factors of this ill-conditioned matrix differ by rounding; what they give does not)
    want = kriging_core(r.x, r.y, np.ones((r.n, 1)), r.kernel, r.length_scales, r.variance, r.nugget)
    sigma = r.variance * correlation(r.x, r.x, r.length_scales, r.kernel) + r.nugget * np.eye(r.n)
    np.testing.assert_allclose(r.core.chol @ r.core.chol.T, sigma, rtol=0, atol=1e-13 * r.variance)
    assert r.core.logdet == pytest.approx(want.logdet, rel=1e-7)  # as above: the same to conditioning
    assert r.core.quad == pytest.approx(want.quad, rel=1e-7)
    pts = np.random.default_rng(3).uniform(-1, 1, (50, 2))
    cross = r.variance * correlation(pts, r.x, r.length_scales, r.kernel)
    np.testing.assert_allclose(r.predict_coded(pts), want.beta[0] + cross @ want.alpha, rtol=0,
                               atol=1e-9 * float(np.ptp(r.y)))


def test_vectorised_exponential_within_an_ulp_of_the_exact_one():
    import math

    import mpmath

    from rsm_lrg.model.engines import gp_compiled

    fns = gp_compiled.kernels()
    rng = np.random.default_rng(8)
    t = np.concatenate([[0.0, 5e-324, 1e-300, 1e-17, 0.5 * math.log(2), math.log(2), 700.0, 708.0],
                        rng.uniform(0, 1e-3, 200), rng.uniform(0, 40, 2000), rng.uniform(0, 708, 500)])
    buf = np.empty((5, t.size))
    buf[0] = t
    fns["exp_row"](t.size, buf, buf.view(np.int64))
    got = buf[2] * buf[4]
    lib = np.array([math.exp(-v) for v in t])
    assert np.max(np.abs(got - lib) / lib) <= 2.3e-16  # both within an ulp of the exact value
    mpmath.mp.dps = 40
    worst = max(abs(float((mpmath.mpf(g) - mpmath.exp(-mpmath.mpf(v))) / mpmath.exp(-mpmath.mpf(v))))
                for g, v in zip(got[::5], t[::5]))
    assert worst <= 1.2e-16


def test_correlations_beyond_the_normal_numbers_take_the_c_library(monkeypatch):
    rng = np.random.default_rng(9)
    x = rng.uniform(-1, 1, (300, 2))
    xn = rng.uniform(-1, 1, (250, 2))
    theta = np.array([2e-3, 3e-3])  # most pairs' exponents beyond 708: tiny or zero correlations
    fast = correlation(xn, x, theta, "matern32")
    _numpy_only(monkeypatch)
    slow = correlation(xn, x, theta, "matern32")
    assert np.sum(slow == 0.0) > 1000 and np.array_equal(fast == 0.0, slow == 0.0)
    expo = _exponents(xn, x, theta, "matern32")
    assert np.any((expo > 708) & (slow > 0))  # pairs the C library's exponential took
    # exp(-t) below the normal numbers keeps fewer bits: an absolute unit of the subnormals
    # (times the Matérn polynomial) added to the relative bound
    poly = np.prod(1.0 + np.sqrt(3.0) * np.abs(xn[:, None, :] - x[None, :, :]) / theta, axis=2)
    tiny = np.nextafter(0.0, 1.0)
    assert np.all(np.abs(fast - slow) <= 4 * (1 + expo) * np.finfo(float).eps * slow + 4 * tiny * poly)
    # the mean takes the same correlations (the tiles with such pairs finished before the sums)
    from rsm_lrg.model.engines import gp_compiled

    w = rng.standard_normal(300)
    np.testing.assert_allclose(gp_compiled.mean(xn, x, theta, "matern32", w), fast @ w, rtol=0,
                               atol=2 * 300 * np.finfo(float).eps * float(np.max(np.abs(fast) @ np.abs(w))))


@pytest.mark.parametrize("kernel", KERNELS)
def test_the_same_numbers_on_any_number_of_threads(kernel, monkeypatch):
    import threading

    from rsm_lrg.model.engines import gp_compiled

    rng = np.random.default_rng(10)
    x = rng.uniform(-1, 1, (300, 3))
    pts = rng.uniform(-1, 1, (257, 3))
    theta = np.array([0.4, 0.8, 1.5])
    w = rng.standard_normal(300)
    monkeypatch.setattr(gp_compiled, "PAIRS_PER_THREAD", 1)
    monkeypatch.setattr(gp_compiled.os, "sched_getaffinity", lambda pid: set(range(4)), raising=False)
    R = correlation(x, x, theta, kernel)
    minv = np.linalg.inv(R + 1e-2 * np.eye(300))
    before = threading.active_count()
    got = {}
    for count in ("1", "3"):
        monkeypatch.setenv("RSM_LRG_GP_THREADS", count)
        assert gp_compiled.threads(10 ** 6) == int(count)
        sums = np.empty(3)
        total = gp_compiled.gradient_sums(x, theta, kernel, R, minv, w, 0.7, sums)
        got[count] = (gp_compiled.mean(pts, x, theta, kernel, w), gp_compiled.cross(pts, x, theta, kernel),
                      gp_compiled.symmetric(x, theta, kernel), sums, total)
        assert threading.active_count() == before  # every thread joined: a later fork copies none
    for a, b in zip(got["1"], got["3"]):
        assert np.array_equal(a, b)
    assert np.array_equal(got["1"][2], R)
    # the mean: each point's sum in the order of the runs
    np.testing.assert_allclose(got["1"][0], got["1"][1] @ w, rtol=0,
                               atol=2 * 300 * np.finfo(float).eps * float(np.max(np.abs(got["1"][1]) @ np.abs(w))))


def test_kriging_sd_chunks_on_threads_give_the_same_numbers(big_fit_small, monkeypatch):
    from rsm_lrg.model.engines import gp_compiled
    from rsm_lrg.model.results import gp_result

    pts = np.random.default_rng(12).uniform(-1, 1, (700, 2))
    monkeypatch.setattr(gp_result, "PREDICT_CHUNK", 100)
    monkeypatch.setattr(gp_compiled, "PAIRS_PER_THREAD", 1)
    monkeypatch.setattr(gp_compiled.os, "sched_getaffinity", lambda pid: set(range(4)), raising=False)
    monkeypatch.setenv("RSM_LRG_GP_THREADS", "1")
    one = big_fit_small.mean_sd(pts)
    monkeypatch.setenv("RSM_LRG_GP_THREADS", "3")
    three = big_fit_small.mean_sd(pts)
    assert np.array_equal(one[0], three[0]) and np.array_equal(one[1], three[1])


@pytest.fixture(scope="module")
def big_fit_small():
    rng = np.random.default_rng(13)
    df = pd.DataFrame({"a": rng.uniform(0, 1, 120), "b": rng.uniform(0, 1, 120)})
    df["y"] = np.sin(6 * df.a) * np.cos(3 * df.b)
    return fit_gp(df, "y", length_scales=[0.4, 0.6])


def test_matern52_on_many_factors_stays_finite():
    # 240 factors with exponents near 708: each factor's polynomial near 26, their product
    # near 1e330 in the (a + 3/2)^2 + 3/4 form without the loops' 2^-5 per pass
    from rsm_lrg.model.engines import gp_compiled

    rng = np.random.default_rng(13)
    x, pts = rng.uniform(-1, 1, (40, 240)), rng.uniform(-1, 1, (30, 240))
    theta = np.full(240, 0.5)
    expo = _exponents(pts, x, theta, "matern52")
    assert expo.min() < 708 < expo.max()
    fast = gp_compiled.cross(pts, x, theta, "matern52")
    slow = correlation(pts, x, theta, "matern52")  # NumPy's (too few pairs for the loops)
    assert np.all(np.isfinite(fast)) and np.array_equal(fast == 0, slow == 0)
    assert np.all(np.abs(fast - slow) <= 4 * (1 + expo) * np.finfo(float).eps * slow)
    w = rng.standard_normal(40)
    np.testing.assert_allclose(gp_compiled.mean(pts, x, theta, "matern52", w), slow @ w, rtol=0,
                               atol=(2 * 40 + 4 * (1 + expo.max())) * np.finfo(float).eps
                               * float(np.max(np.abs(slow) @ np.abs(w))))


def test_two_threads_asking_first_compile_once():
    # a fresh process: two threads call kernels() at the same moment (Dask's threads may); the
    # compilation runs under a lock (without it the second thread jitted the first's dispatchers)
    import subprocess
    import sys

    code = (
        "import threading\n"
        "from rsm_lrg.model.engines import gp_compiled\n"
        "go = threading.Barrier(2)\n"
        "got = []\n"
        "def ask():\n"
        "    go.wait()\n"
        "    got.append(gp_compiled.kernels())\n"
        "ts = [threading.Thread(target=ask) for _ in range(2)]\n"
        "[t.start() for t in ts]\n"
        "[t.join() for t in ts]\n"
        "assert len(got) == 2 and got[0] is got[1], got\n"
        "print('ok')\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0 and done.stdout.strip() == "ok", done.stderr[-2000:]
