"""The kriging core (:mod:`rsm_lrg.model.engines.gp_core`): the jitter ladder and the GLS trend."""

import numpy as np
import pytest

from rsm_lrg.model.engines.gp_core import cholesky_in_place, cholesky_jitter, kriging_core


def test_no_jitter_when_the_matrix_factorises():
    L, jit = cholesky_jitter(np.array([[2.0, 0.5], [0.5, 1.0]]), 1.0)
    assert jit == 0.0
    np.testing.assert_allclose(L @ L.T, [[2.0, 0.5], [0.5, 1.0]], rtol=1e-15)


def test_smallest_jitter_that_works_is_used_and_reported():
    m = np.ones((3, 3))  # rank one: singular
    L, jit = cholesky_jitter(m, 4.0)
    assert jit == 1e-12
    np.testing.assert_allclose(L @ L.T, m + 4e-12 * np.eye(3), rtol=1e-10)
    with pytest.raises(np.linalg.LinAlgError):
        cholesky_jitter(-np.eye(2), 1.0)


def test_cholesky_in_place_is_numpys_factor_to_rounding_in_the_same_memory():
    rng = np.random.default_rng(4)
    a = rng.standard_normal((40, 40))
    m = a @ a.T + 40 * np.eye(40)
    want = np.linalg.cholesky(m)
    work = m.copy()
    got = cholesky_in_place(work)
    assert got is work  # no copy
    assert np.all(np.triu(got, 1) == 0.0)  # a lower factor, the upper triangle zeroed
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-13 * np.max(np.abs(want)))
    np.testing.assert_allclose(got @ got.T, m, rtol=1e-14, atol=1e-12)
    assert cholesky_in_place(np.ones((3, 3))) is None  # singular: None, the caller rebuilds
    assert cholesky_in_place(-np.eye(2)) is None
    with pytest.raises(ValueError, match="C-contiguous"):
        cholesky_in_place(np.asfortranarray(m))


def test_gls_trend_and_aliased_columns():
    x = np.array([[-1.0], [0.0], [1.0], [0.5]])
    y = np.array([1.0, 2.0, 3.5, 2.6])
    F = np.column_stack([np.ones(4), x[:, 0]])
    c = kriging_core(x, y, F, "matern52", np.array([0.7]), 2.0, 0.1)
    from rsm_lrg.model.engines.gp_kernels import correlation

    S = 2.0 * correlation(x, x, np.array([0.7]), "matern52") + 0.1 * np.eye(4)
    Si = np.linalg.inv(S)
    beta = np.linalg.solve(F.T @ Si @ F, F.T @ Si @ y)
    np.testing.assert_allclose(c.beta, beta, rtol=1e-12)
    np.testing.assert_allclose(c.alpha, Si @ (y - F @ beta), rtol=1e-10)
    assert c.logdet == pytest.approx(np.linalg.slogdet(S)[1], rel=1e-12)
    with pytest.raises(ValueError, match="aliased"):
        kriging_core(x, y, np.column_stack([F, 2 * F[:, 1]]), "matern52", np.array([0.7]), 2.0, 0.1)


def test_scaled_core_equals_the_factorisation_of_the_scaled_covariance():
    rng = np.random.default_rng(6)
    x = rng.uniform(-1, 1, (60, 2))
    y = np.sin(3 * x[:, 0]) + x[:, 1]
    F = np.column_stack([np.ones(60), x])
    theta = np.array([0.6, 1.1])
    one = kriging_core(x, y, F, "matern32", theta, 1.0, 1e-3)
    s = 7.3
    got, want = one.scaled(s), kriging_core(x, y, F, "matern32", theta, s, s * 1e-3)
    for name in ("chol", "beta", "alpha", "ft", "r_f"):
        np.testing.assert_allclose(getattr(got, name), getattr(want, name), rtol=1e-10,
                                   atol=1e-12 * np.max(np.abs(getattr(want, name))))
    assert got.quad == pytest.approx(want.quad, rel=1e-10)
    assert got.logdet == pytest.approx(want.logdet, rel=1e-12)
    assert got.log_likelihood == pytest.approx(want.log_likelihood, rel=1e-12)
    assert got.jitter == one.jitter == 0.0


def test_core_from_cholesky_is_kriging_core_bit_for_bit():
    from rsm_lrg.model.engines.gp_core import core_from_cholesky
    from rsm_lrg.model.engines.gp_kernels import correlation

    rng = np.random.default_rng(7)
    x = rng.uniform(-1, 1, (30, 2))
    y = x[:, 0] ** 2 - x[:, 1]
    F = np.ones((30, 1))
    theta = np.array([0.5, 0.9])
    sigma = 2.0 * correlation(x, x, theta, "gauss")
    sigma[np.diag_indices_from(sigma)] += 1e-4
    chol, jit = cholesky_jitter(sigma, 2.0)
    got, want = core_from_cholesky(chol, jit, F, y), kriging_core(x, y, F, "gauss", theta, 2.0, 1e-4)
    for name in ("chol", "beta", "alpha", "ft", "r_f"):
        assert np.array_equal(getattr(got, name), getattr(want, name))
    assert (got.quad, got.logdet, got.jitter) == (want.quad, want.logdet, want.jitter)
