"""Exact least squares on rationals: the reference for the numerical-accuracy tests.

Every float is a rational number, so the least-squares coefficients of the float data are
a rational vector: the solution of the normal equations ``X'X b = X'y`` computed in
:class:`fractions.Fraction` arithmetic (Gauss–Jordan elimination, no rounding anywhere).
"""

from fractions import Fraction

import numpy as np


def gauss_jordan(M: list[list[Fraction]]) -> list[list[Fraction]]:
    """Reduce the augmented rows ``[A | B]`` (A square, full rank) to ``[I | A^-1 B]`` in
    place, in exact arithmetic; returns ``M``."""
    p = len(M)
    for c in range(p):
        piv = next(r for r in range(c, p) if M[r][c] != 0)
        M[c], M[piv] = M[piv], M[c]
        inv = 1 / M[c][c]
        M[c] = [v * inv for v in M[c]]
        for r in range(p):
            if r != c and M[r][c] != 0:
                f = M[r][c]
                M[r] = [a - f * b for a, b in zip(M[r], M[c])]
    return M


def exact_normal(X: list[list[Fraction]], y: list[Fraction]) -> list[Fraction]:
    """Exact least-squares coefficients of rational rows ``X`` and responses ``y`` (the normal
    equations solved by :func:`gauss_jordan`)."""
    n, p = len(X), len(X[0])
    M = [[sum((X[i][a] * X[i][b] for i in range(n)), Fraction(0)) for b in range(p)]
         + [sum((X[i][a] * y[i] for i in range(n)), Fraction(0))] for a in range(p)]
    return [row[p] for row in gauss_jordan(M)]


def exact_lstsq(X, y) -> list[Fraction]:
    """Exact least-squares coefficients of the float data ``X`` (n x p, full rank) and ``y``."""
    return exact_normal([[Fraction(float(v)) for v in row] for row in np.asarray(X, dtype=float)],
                        [Fraction(float(v)) for v in np.asarray(y, dtype=float)])


def max_rel_error(approx, exact) -> float:
    """Largest ``|approx_j - exact_j| / |exact_j|`` (exact arithmetic until the last step)."""
    out = 0.0
    for a, e in zip(approx, exact):
        d = abs(Fraction(float(a)) - e)
        out = max(out, float(d / abs(e)) if e != 0 else float(d))
    return out
