"""The not-a-knot cubic interpolating spline in NumPy (what :func:`.hinge.leaf_force_table`
tabulates), so that the stage integrator does not import ``scipy.interpolate`` (about 0.35 s of
CPU at start-up).

The spline is the one of :class:`scipy.interpolate.CubicSpline` with its default end condition
(``bc_type="not-a-knot"``): the same tridiagonal system for the first derivatives at the knots
(de Boor 2001, *A Practical Guide to Splines*, rev. ed., Springer, Chapter IV: the slope
form of the C² conditions, with the not-a-knot end rows), the same right-hand sides and the same
coefficients from them. Only the solve differs: SciPy factors the band matrix with LAPACK's
``gbsv`` (partial pivoting); here the two end rows, which are not diagonally dominant, are first
combined with their neighbours (one step of Gaussian elimination each), and the remaining
diagonally dominant system is solved by cyclic (odd-even) reduction, a loop of about log2(n)
vectorised steps (the whole table of 80,001 knots in a few milliseconds).

The knot slopes agree with SciPy's to about 1e-15 relative and are as close as SciPy's to a
40-digit solve; the spline's values and slopes between the knots agree to the same 1e-15
(``tests/physics/test_spline.py``, on the leaf force law and on random data). The cubic and
quadratic coefficients on their own differ more relative to themselves (up to 1e-6 for the
cubic one on the leaf table's 0.01 steps): both codes form them from differences of nearly
equal slopes, which cancel, and the difference they make to a value is of the slopes' order.
"""

from __future__ import annotations

import numpy as np

__all__ = ["not_a_knot_coefficients", "solve_tridiagonal"]


def solve_tridiagonal(lower, diag, upper, rhs) -> np.ndarray:
    """Solve the tridiagonal system ``lower[i]·x[i-1] + diag[i]·x[i] + upper[i]·x[i+1] = rhs[i]``
    by cyclic (odd-even) reduction, without pivoting: for diagonally dominant matrices.

    Parameters
    ----------
    lower, diag, upper : array_like (n,)
        The sub-diagonal (``lower[0]`` unused), the diagonal and the super-diagonal
        (``upper[n-1]`` unused).
    rhs : array_like (n,)
        The right-hand side.

    Returns
    -------
    numpy.ndarray (n,)
        The solution.

    >>> solve_tridiagonal([0.0, 1.0, 1.0], [4.0, 4.0, 4.0], [1.0, 1.0, 0.0], [5.0, 6.0, 5.0]).tolist()
    [1.0, 1.0, 1.0]
    """
    a = np.array(lower, dtype=float)
    b = np.array(diag, dtype=float)
    c = np.array(upper, dtype=float)
    d = np.array(rhs, dtype=float)
    n = b.shape[0]
    if a.shape != (n,) or c.shape != (n,) or d.shape != (n,) or n == 0:
        raise ValueError("solve_tridiagonal needs four arrays of one length n >= 1")
    a[0] = 0.0
    c[-1] = 0.0
    return _reduce(a, b, c, d)


def _reduce(a: np.ndarray, b: np.ndarray, c: np.ndarray, d: np.ndarray) -> np.ndarray:
    n = b.shape[0]
    if n == 1:
        return d / b
    ne, no = (n + 1) // 2, n // 2  # equations kept (even rows) and eliminated (odd rows)
    ae, be, ce, de = a[0::2], b[0::2], c[0::2], d[0::2]
    ao, bo, co, do = a[1::2], b[1::2], c[1::2], d[1::2]
    # even row 2k loses x[2k-1] (odd row k-1, left) and x[2k+1] (odd row k, right)
    left = np.zeros(ne)
    left[1:] = -ae[1:] / bo[:ne - 1]
    right = np.zeros(ne)
    right[:no] = -ce[:no] / bo
    nb = be.copy()
    nb[1:] += left[1:] * co[:ne - 1]
    nb[:no] += right[:no] * ao
    nd = de.copy()
    nd[1:] += left[1:] * do[:ne - 1]
    nd[:no] += right[:no] * do
    na = np.zeros(ne)
    na[1:] = left[1:] * ao[:ne - 1]
    nc = np.zeros(ne)
    nc[:no] = right[:no] * co
    xe = _reduce(na, nb, nc, nd)
    x = np.empty(n)
    x[0::2] = xe
    nxt = np.zeros(no)  # x[2k+2], 0 past the end (its coefficient is 0 there)
    nxt[:ne - 1] = xe[1:][:no]
    x[1::2] = (do - ao * xe[:no] - co * nxt) / bo
    return x


def not_a_knot_coefficients(x, y) -> np.ndarray:
    """Coefficients of the cubic spline through ``(x, y)`` with not-a-knot ends (the default of
    :class:`scipy.interpolate.CubicSpline`).

    Parameters
    ----------
    x : array_like (n,)
        Knots, strictly increasing, n >= 4.
    y : array_like (n,)
        Values at the knots.

    Returns
    -------
    numpy.ndarray (4, n - 1)
        ``c`` with ``S(t) = c[0]·t³ + c[1]·t² + c[2]·t + c[3]`` on ``[x[i], x[i+1]]``,
        ``t = x − x[i]`` (the layout of ``CubicSpline.c``).

    >>> c = not_a_knot_coefficients([0.0, 1.0, 2.0, 3.0], [0.0, 1.0, 8.0, 27.0])  # x³ exactly
    >>> [round(float(v), 12) for v in c[:, 1]]
    [1.0, 3.0, 3.0, 1.0]
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    n = x.shape[0]
    if x.ndim != 1 or y.shape != (n,) or n < 4:
        raise ValueError("not_a_knot_coefficients needs x and y of one length n >= 4")
    dx = np.diff(x)
    if not np.all(dx > 0):
        raise ValueError("not_a_knot_coefficients needs strictly increasing x")
    slope = np.diff(y) / dx
    # CubicSpline's system for the first derivatives s (its band matrix and right-hand side)
    lower = np.zeros(n)
    diag = np.empty(n)
    upper = np.zeros(n)
    rhs = np.empty(n)
    diag[1:-1] = 2 * (dx[:-1] + dx[1:])
    upper[1:-1] = dx[:-1]
    lower[1:-1] = dx[1:]
    rhs[1:-1] = 3 * (dx[1:] * slope[:-1] + dx[:-1] * slope[1:])
    d0 = x[2] - x[0]
    diag[0], upper[0] = dx[1], d0
    rhs[0] = ((dx[0] + 2 * d0) * dx[1] * slope[0] + dx[0] ** 2 * slope[1]) / d0
    d1 = x[-1] - x[-3]
    diag[-1], lower[-1] = dx[-2], d1
    rhs[-1] = (dx[-1] ** 2 * slope[-2] + (2 * d1 + dx[-1]) * dx[-2] * slope[-1]) / d1
    # the end rows hold s0 (s[n-1]) with a weight no larger than s1's (s[n-2]'s): eliminate
    # s0 from row 1 with row 0 (s[n-1] from row n-2 with row n-1), solve rows 1..n-2 (diagonally
    # dominant now), then s0 and s[n-1] from their rows
    f0 = lower[1] / diag[0]
    f1 = upper[-2] / diag[-1]
    a = lower[1:-1].copy()
    b = diag[1:-1].copy()
    c = upper[1:-1].copy()
    d = rhs[1:-1].copy()
    b[0] -= f0 * upper[0]
    d[0] -= f0 * rhs[0]
    b[-1] -= f1 * lower[-1]
    d[-1] -= f1 * rhs[-1]
    a[0] = 0.0
    c[-1] = 0.0
    s = np.empty(n)
    s[1:-1] = _reduce(a, b, c, d)
    s[0] = (rhs[0] - upper[0] * s[1]) / diag[0]
    s[-1] = (rhs[-1] - lower[-1] * s[-2]) / diag[-1]
    t = (s[:-1] + s[1:] - 2 * slope) / dx
    return np.stack((t / dx, (slope - s[:-1]) / dx - t, s[:-1], y[:-1]))
