"""Correlation kernels of the Gaussian-process engine (:mod:`rsm_lrg.model.pipelines.gp`), as R
``DiceKriging`` parameterises them (Roustant, Ginsbourger & Deville 2012, Table 1).

Every kernel is a tensor product over the factors of a one-dimensional correlation of the
difference ``h = x_j - x'_j`` [coded units] with its own length-scale ``theta_j`` [coded
units]:

* ``"gauss"``: ``exp(-h^2 / (2 theta^2))``
* ``"matern52"``: ``(1 + a + a^2/3) exp(-a)``, ``a = sqrt(5) |h| / theta``
* ``"matern32"``: ``(1 + a) exp(-a)``, ``a = sqrt(3) |h| / theta``

Besides the correlation matrix, :func:`log_derivative_theta` gives ``d log k / d log theta``
(the likelihood's analytic gradient) and :func:`log_derivative_x` gives ``d log k / d h``
(the surface's gradient); both are finite where ``k`` underflows.

>>> import numpy as np
>>> x = np.array([[0.0], [0.5]])
>>> float(np.round(correlation(x, x, np.array([1.0]), "gauss")[0, 1], 6))  # exp(-1/8)
0.882497
"""

from __future__ import annotations

import numpy as np

__all__ = ["KERNELS", "DICEKRIGING_NAMES", "COMPILED_PAIRS", "correlation", "log_derivative_theta",
           "log_derivative_x"]

#: The kernels, by their rsm-lrg names.
KERNELS = ("matern52", "matern32", "gauss")
#: The same kernels as ``DiceKriging::km(covtype=...)`` names them.
DICEKRIGING_NAMES = {"matern52": "matern5_2", "matern32": "matern3_2", "gauss": "gauss"}
_SCALE = {"matern52": np.sqrt(5.0), "matern32": np.sqrt(3.0)}
#: From this many pairs of settings on, :func:`correlation` runs the compiled loops of
#: :mod:`rsm_lrg.model.engines.gp_compiled` (one pass, the symmetric matrix's lower triangle
#: only) instead of NumPy's per-factor passes over the whole matrix.
COMPILED_PAIRS = 1 << 16


def _differences(x1: np.ndarray, x2: np.ndarray, j: int) -> np.ndarray:
    return x1[:, j][:, None] - x2[:, j][None, :]


def correlation(x1: np.ndarray, x2: np.ndarray, theta: np.ndarray, kernel: str) -> np.ndarray:
    """The correlation matrix ``R[i, l] = prod_j k(x1[i, j] - x2[l, j]; theta_j)``.

    Parameters
    ----------
    x1, x2 : (n1, k) and (n2, k) ndarray
        Settings [coded units].
    theta : (k,) ndarray
        Length-scales [coded units], positive.
    kernel : {"matern52", "matern32", "gauss"}

    Returns
    -------
    (n1, n2) ndarray
    """
    shape = (x1.shape[0], x2.shape[0])
    if shape[0] * shape[1] >= COMPILED_PAIRS:
        return _compiled_correlation(x1, x2, theta, kernel)
    total = np.zeros(shape)
    if kernel == "gauss":  # exp(-sum_j h_j^2 / (2 theta_j^2))
        for j in range(x1.shape[1]):
            h = _differences(x1, x2, j)
            h /= float(theta[j])
            h *= h
            total += h
        total *= -0.5
        return np.exp(total, out=total)
    poly = np.ones(shape)  # prod_j p(a_j) exp(-sum_j a_j): no logarithm per element
    for j in range(x1.shape[1]):
        a = _differences(x1, x2, j)
        np.abs(a, out=a)
        a *= _SCALE[kernel] / float(theta[j])
        total += a
        if kernel == "matern52":
            poly *= 1.0 + a * (1.0 + a / 3.0)
        else:
            poly *= 1.0 + a
    total *= -1.0
    np.exp(total, out=total)
    total *= poly
    return total


def _compiled_correlation(x1: np.ndarray, x2: np.ndarray, theta: np.ndarray, kernel: str) -> np.ndarray:
    from . import gp_compiled

    if x1 is x2:
        return gp_compiled.symmetric(x1, theta, kernel)
    return gp_compiled.cross(x1, x2, theta, kernel)


def log_derivative_theta(x1: np.ndarray, x2: np.ndarray, theta: np.ndarray, kernel: str, j: int) -> np.ndarray:
    """``d log R / d log theta_j`` elementwise (so ``dR/d log theta_j = R * this``)."""
    h = _differences(x1, x2, j)
    t = float(theta[j])
    if kernel == "gauss":
        return (h / t) ** 2
    a = _SCALE[kernel] * np.abs(h) / t
    if kernel == "matern52":
        return a * a * (1.0 + a) / (3.0 * (1.0 + a + a * a / 3.0))
    return a * a / (1.0 + a)


def log_derivative_x(x1: np.ndarray, x2: np.ndarray, theta: np.ndarray, kernel: str, j: int) -> np.ndarray:
    """``d log R / d x1_j`` elementwise [1/coded unit] (so ``dR/dx1_j = R * this``)."""
    h = _differences(x1, x2, j)
    t = float(theta[j])
    if kernel == "gauss":
        return -h / (t * t)
    c = _SCALE[kernel] / t
    a = c * np.abs(h)
    if kernel == "matern52":
        return -c * np.sign(h) * a * (1.0 + a) / (3.0 * (1.0 + a + a * a / 3.0))
    return -c * np.sign(h) * a / (1.0 + a)
