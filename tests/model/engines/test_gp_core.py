"""The kriging core (:mod:`rsm_lrg.model.engines.gp_core`): the jitter ladder and the GLS trend."""

import numpy as np
import pytest

from rsm_lrg.model.engines.gp_core import cholesky_jitter, kriging_core


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
