"""Exact least squares on rationals: the reference for the numerical-accuracy tests.

Every float is a rational number, so the least-squares coefficients of the float data are
a rational vector: the solution of the normal equations ``X'X b = X'y`` computed in
:class:`fractions.Fraction` arithmetic (Gauss–Jordan elimination, no rounding anywhere).
"""

from fractions import Fraction

import numpy as np


def exact_lstsq(X, y) -> list[Fraction]:
    """Exact least-squares coefficients of the float data ``X`` (n x p, full rank) and ``y``."""
    Xf = [[Fraction(float(v)) for v in row] for row in np.asarray(X, dtype=float)]
    yf = [Fraction(float(v)) for v in np.asarray(y, dtype=float)]
    n, p = len(Xf), len(Xf[0])
    A = [[sum(Xf[i][a] * Xf[i][b] for i in range(n)) for b in range(p)] + [sum(Xf[i][a] * yf[i] for i in range(n))]
         for a in range(p)]
    for c in range(p):
        piv = next(r for r in range(c, p) if A[r][c] != 0)
        A[c], A[piv] = A[piv], A[c]
        inv = 1 / A[c][c]
        A[c] = [v * inv for v in A[c]]
        for r in range(p):
            if r != c and A[r][c] != 0:
                f = A[r][c]
                A[r] = [a - f * b for a, b in zip(A[r], A[c])]
    return [A[i][p] for i in range(p)]


def max_rel_error(approx, exact) -> float:
    """Largest ``|approx_j - exact_j| / |exact_j|`` (exact arithmetic until the last step)."""
    out = 0.0
    for a, e in zip(approx, exact):
        d = abs(Fraction(float(a)) - e)
        out = max(out, float(d / abs(e)) if e != 0 else float(d))
    return out
