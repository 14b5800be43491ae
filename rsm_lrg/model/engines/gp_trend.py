"""Trend bases of the Gaussian-process engine (:mod:`rsm_lrg.model.pipelines.gp`): the regression
functions ``f(x)`` of universal kriging on the coded factors, and their derivatives.

* ``"constant"``: ``1`` (ordinary kriging)
* ``"linear"``: ``1, x_1, ..., x_k``
* ``"quadratic"``: ``1``, the ``x_j``, the products ``x_j x_l`` (``j < l``), the squares
  ``x_j^2``: the full quadratic of the paper's Eq. 19.

>>> import numpy as np
>>> F, names = trend_matrix(np.array([[0.5, -1.0]]), "quadratic", ["A", "B"])
>>> names
['Intercept', 'A', 'B', 'AB', 'A^2', 'B^2']
>>> F.tolist()
[[1.0, 0.5, -1.0, -0.5, 0.25, 1.0]]
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

__all__ = ["TRENDS", "trend_matrix", "trend_gradient", "trend_size"]

#: The trends, by name.
TRENDS = ("constant", "linear", "quadratic")


def _pairs(k: int) -> list[tuple[int, int]]:
    return [(j, m) for j in range(k) for m in range(j + 1, k)]


def trend_size(k: int, trend: str) -> int:
    """Number of trend columns for ``k`` factors."""
    return {"constant": 1, "linear": 1 + k, "quadratic": 1 + 2 * k + k * (k - 1) // 2}[trend]


def trend_matrix(x: np.ndarray, trend: str, letters: Sequence[str]) -> tuple[np.ndarray, list[str]]:
    """The trend matrix ``F`` (n x p) at coded settings ``x`` (n x k) and its column names."""
    n, k = x.shape
    cols = [np.ones(n)]
    names = ["Intercept"]
    if trend in ("linear", "quadratic"):
        cols += [x[:, j] for j in range(k)]
        names += list(letters[:k])
    if trend == "quadratic":
        for j, m in _pairs(k):
            cols.append(x[:, j] * x[:, m])
            names.append(letters[j] + letters[m])
        cols += [x[:, j] ** 2 for j in range(k)]
        names += [f"{letters[j]}^2" for j in range(k)]
    return np.column_stack(cols), names


def trend_gradient(x: np.ndarray, trend: str, j: int) -> np.ndarray:
    """``dF/dx_j`` (n x p) at coded settings ``x`` [1/coded unit]."""
    n, k = x.shape
    out = np.zeros((n, trend_size(k, trend)))
    if trend == "constant":
        return out
    out[:, 1 + j] = 1.0
    if trend == "quadratic":
        for c, (a, b) in enumerate(_pairs(k)):
            if a == j:
                out[:, 1 + k + c] = x[:, b]
            elif b == j:
                out[:, 1 + k + c] = x[:, a]
        out[:, 1 + k + len(_pairs(k)) + j] = 2.0 * x[:, j]
    return out
