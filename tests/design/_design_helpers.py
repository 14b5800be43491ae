"""Shared numerics for the design tests: model columns and block orthogonality."""

from itertools import combinations

import numpy as np


def quadratic_columns(X: np.ndarray) -> dict[str, np.ndarray]:
    """Linear, two-factor-interaction and pure quadratic columns of coded runs X."""
    k = X.shape[1]
    cols = {f"x{i + 1}": X[:, i] for i in range(k)}
    for i, j in combinations(range(k), 2):
        cols[f"x{i + 1}x{j + 1}"] = X[:, i] * X[:, j]
    for i in range(k):
        cols[f"x{i + 1}^2"] = X[:, i] ** 2
    return cols


def block_orthogonality(X: np.ndarray, blocks: np.ndarray) -> float:
    """Largest |<centred block indicator, centred model column>| over blocks and columns.

    Zero means the blocks are orthogonal to every term of the full quadratic model
    (Box & Hunter 1957; Myers, Montgomery & Anderson-Cook 2009, section 7.3.4).
    """
    worst = 0.0
    for b in np.unique(blocks):
        z = (blocks == b).astype(float)
        z -= z.mean()
        for col in quadratic_columns(X).values():
            worst = max(worst, abs(float(np.dot(z, col - col.mean()))))
    return worst


def multiset(rows: np.ndarray) -> list[tuple]:
    return sorted(tuple(float(v) + 0.0 for v in np.round(r, 9)) for r in rows)
