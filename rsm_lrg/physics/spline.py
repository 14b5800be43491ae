"""The not-a-knot cubic interpolating spline in NumPy (what :func:`.hinge.leaf_force_table`
tabulates), so that the stage integrator does not import ``scipy.interpolate`` (about 0.35 s of
CPU at start-up).

The spline is the one of :class:`scipy.interpolate.CubicSpline` with its default end condition
(``bc_type="not-a-knot"``), bit for bit: the same tridiagonal system for the first derivatives
at the knots (de Boor 2001, *A Practical Guide to Splines*, rev. ed., Springer, Chapter IV: the
slope form of the C² conditions, with the not-a-knot end rows), the same right-hand sides, the
same solve and the same coefficients from the slopes. SciPy solves the system with LAPACK's
``dgtsv`` (``scipy.linalg.solve_banded`` with one band each side); :func:`solve_tridiagonal` is
that routine's algorithm (Gaussian elimination with partial pivoting by rows, then the back
substitution) written out operation for operation in Python floats, each ``+``, ``*`` and ``/``
one IEEE-754 operation as in the compiled routine, so the slopes and the coefficients are
SciPy's to the last bit (``tests/physics/test_spline.py``: the leaf table and random knots
compared with ``array_equal``). The loop is sequential (each pivot depends on the last): the
leaf table's 40,001 knots take about 0.06 s of CPU, against the 0.35 s of importing SciPy's
interpolation package. The stage integrator's unsettled rows (irregular stick-slip, see
``periodicity_error_m``) amplify any change in the table's last bits, so it is the same table
that keeps ``simulate``'s numbers what they were with SciPy's spline.
"""

from __future__ import annotations

import numpy as np

__all__ = ["not_a_knot_coefficients", "solve_tridiagonal"]


def solve_tridiagonal(lower, diag, upper, rhs) -> np.ndarray:
    """Solve the tridiagonal system ``lower[i]·x[i-1] + diag[i]·x[i] + upper[i]·x[i+1] = rhs[i]``
    as LAPACK's ``dgtsv`` does (reference LAPACK 3.x, one right-hand side): Gaussian elimination
    with partial pivoting (rows ``i`` and ``i+1`` swapped where ``|lower[i+1]| > |diag[i]|``, the
    fill-in kept on a second super-diagonal), then the back substitution, each operation in the
    routine's order, so the result is the compiled routine's bit for bit.

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

    Raises
    ------
    ValueError
        Arrays of different lengths or empty, or an exactly singular system (a zero pivot).

    >>> solve_tridiagonal([0.0, 1.0, 1.0], [4.0, 4.0, 4.0], [1.0, 1.0, 0.0], [5.0, 6.0, 5.0]).tolist()
    [1.0, 1.0, 1.0]
    """
    d = np.array(diag, dtype=float)
    n = d.shape[0]
    lo, up, b = (np.array(v, dtype=float) for v in (lower, upper, rhs))
    if lo.shape != (n,) or up.shape != (n,) or b.shape != (n,) or n == 0 or d.ndim != 1:
        raise ValueError("solve_tridiagonal needs four arrays of one length n >= 1")
    dl: list[float] = lo[1:].tolist()
    du: list[float] = up[:-1].tolist()
    dd: list[float] = d.tolist()
    x: list[float] = b.tolist()
    for i in range(n - 1):
        di, li = dd[i], dl[i]
        if abs(di) >= abs(li):  # no interchange
            if di == 0.0:
                raise ValueError(f"solve_tridiagonal: the system is singular (zero pivot at row {i})")
            fact = li / di
            dd[i + 1] = dd[i + 1] - fact * du[i]
            x[i + 1] = x[i + 1] - fact * x[i]
            dl[i] = 0.0
        else:  # interchange rows i and i+1; dl[i] becomes the fill-in of the second super-diagonal
            fact = di / li
            dd[i] = li
            temp = dd[i + 1]
            dd[i + 1] = du[i] - fact * temp
            if i < n - 2:
                dl[i] = du[i + 1]
                du[i + 1] = -fact * dl[i]
            du[i] = temp
            temp = x[i]
            x[i] = x[i + 1]
            x[i + 1] = temp - fact * x[i + 1]
    if dd[n - 1] == 0.0:
        raise ValueError(f"solve_tridiagonal: the system is singular (zero pivot at row {n - 1})")
    x[n - 1] = x[n - 1] / dd[n - 1]
    if n > 1:
        x[n - 2] = (x[n - 2] - du[n - 2] * x[n - 1]) / dd[n - 2]
    for i in range(n - 3, -1, -1):
        x[i] = (x[i] - du[i] * x[i + 1] - dl[i] * x[i + 2]) / dd[i]
    return np.array(x)


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
    s = solve_tridiagonal(lower, diag, upper, rhs)
    t = (s[:-1] + s[1:] - 2 * slope) / dx
    return np.stack((t / dx, (slope - s[:-1]) / dx - t, s[:-1], y[:-1]))
