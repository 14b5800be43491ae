"""Kernels and trend bases of the GP engine (:mod:`rsm_lrg.model.engines.gp_kernels`,
:mod:`rsm_lrg.model.engines.gp_trend`): values against DiceKriging's formulas (Roustant et al. 2012,
Table 1), derivatives against central differences."""

import numpy as np
import pytest

from rsm_lrg.model.engines.gp_kernels import KERNELS, correlation, log_derivative_theta, log_derivative_x
from rsm_lrg.model.engines.gp_trend import TRENDS, trend_gradient, trend_matrix

RNG = np.random.default_rng(11)
X1 = RNG.uniform(-1, 1, (5, 3))
X2 = RNG.uniform(-1, 1, (4, 3))
THETA = np.array([0.4, 1.3, 0.8])


def _one_d(h, t, kernel):
    if kernel == "gauss":
        return np.exp(-h ** 2 / (2 * t ** 2))
    c = np.sqrt(5.0) if kernel == "matern52" else np.sqrt(3.0)
    a = c * np.abs(h) / t
    return (1 + a + a ** 2 / 3) * np.exp(-a) if kernel == "matern52" else (1 + a) * np.exp(-a)


@pytest.mark.parametrize("kernel", KERNELS)
def test_values_are_the_tensor_product(kernel):
    R = correlation(X1, X2, THETA, kernel)
    ref = np.ones((5, 4))
    for j in range(3):
        ref *= _one_d(X1[:, j][:, None] - X2[:, j][None, :], THETA[j], kernel)
    np.testing.assert_allclose(R, ref, rtol=1e-14)
    np.testing.assert_allclose(np.diag(correlation(X1, X1, THETA, kernel)), 1.0, rtol=0, atol=0)


@pytest.mark.parametrize("kernel", KERNELS)
@pytest.mark.parametrize("j", [0, 2])
def test_derivatives_match_central_differences(kernel, j):
    R = correlation(X1, X2, THETA, kernel)
    h = 1e-6
    up, dn = THETA.copy(), THETA.copy()
    up[j] *= np.exp(h)
    dn[j] *= np.exp(-h)
    num = (correlation(X1, X2, up, kernel) - correlation(X1, X2, dn, kernel)) / (2 * h)
    np.testing.assert_allclose(R * log_derivative_theta(X1, X2, THETA, kernel, j), num, rtol=1e-6, atol=1e-9)
    a, b = X1.copy(), X1.copy()
    a[:, j] += h
    b[:, j] -= h
    num = (correlation(a, X2, THETA, kernel) - correlation(b, X2, THETA, kernel)) / (2 * h)
    np.testing.assert_allclose(R * log_derivative_x(X1, X2, THETA, kernel, j), num, rtol=1e-6, atol=1e-9)


@pytest.mark.parametrize("trend", TRENDS)
def test_trend_gradient_matches_central_differences(trend):
    F, names = trend_matrix(X1, trend, ["A", "B", "C"])
    assert F.shape == (5, len(names)) and names[0] == "Intercept"
    for j in range(3):
        a, b = X1.copy(), X1.copy()
        a[:, j] += 1e-6
        b[:, j] -= 1e-6
        num = (trend_matrix(a, trend, ["A", "B", "C"])[0] - trend_matrix(b, trend, ["A", "B", "C"])[0]) / 2e-6
        np.testing.assert_allclose(trend_gradient(X1, trend, j), num, rtol=1e-7, atol=1e-8)
