"""The not-a-knot cubic spline of :mod:`rsm_lrg.physics.spline` (the leaf force table's)."""

import numpy as np
import pytest

from rsm_lrg.physics import hinge
from rsm_lrg.physics.spline import not_a_knot_coefficients, solve_tridiagonal


def _evaluate(c, x, q):
    i = np.clip(np.searchsorted(x, q, side="right") - 1, 0, len(x) - 2)
    t = q - x[i]
    value = c[3, i] + t * (c[2, i] + t * (c[1, i] + t * c[0, i]))
    slope = c[2, i] + t * (2 * c[1, i] + 3 * t * c[0, i])
    return value, slope


def test_leaf_force_table_agrees_with_scipy_cubic_spline():
    # Reference: scipy.interpolate.CubicSpline (not-a-knot, LAPACK gbsv) on the same mirrored
    # points of the leaf force law as leaf_force_table; psi and its slope (the two the stage
    # integrator reads) at 200,000 points, relative to their own size: 1e-14 asked, about 1e-15 seen
    interpolate = pytest.importorskip("scipy.interpolate")
    step = 0.01
    r = np.arange(0.0, hinge.LEAF_TABLE_MAX_RATIO + 0.5 * step, step)
    psi = r * np.atleast_1d(hinge.leaf_stiffening(r))
    x = np.concatenate([-r[:0:-1], r])
    y = np.concatenate([-psi[:0:-1], psi])
    ours = not_a_knot_coefficients(x, y)
    ref = interpolate.CubicSpline(x, y).c
    q = np.random.default_rng(0).uniform(-199.99, 199.99, 200_000)
    v, dv = _evaluate(ours, x, q)
    rv, rdv = _evaluate(ref, x, q)
    assert np.max(np.abs(v - rv) / np.abs(rv)) < 1e-14
    assert np.max(np.abs(dv - rdv) / np.abs(rdv)) < 1e-14
    # the derivatives at the knots (what the system solves for)
    assert np.max(np.abs(ours[2] - ref[2]) / np.abs(ref[2])) < 1e-14
    # and leaf_force_table is this spline on r >= 0, in its (n, 4) layout
    tab, st = hinge.leaf_force_table()
    assert st == step and tab.shape == (len(r) - 1, 4)
    assert np.array_equal(tab, np.ascontiguousarray(ours[:, len(r) - 1:][::-1].T))


@pytest.mark.parametrize("n", [4, 5, 6, 7, 8, 33, 200, 1001])
def test_random_knots_against_scipy_and_a_40_digit_solve(n):
    # References: scipy.interpolate.CubicSpline; and the same not-a-knot system (de Boor 2001,
    # Ch. IV) solved by mpmath's LU in 40 digits: our knot derivatives are within a few ulps of
    # the exact ones, as SciPy's are
    interpolate = pytest.importorskip("scipy.interpolate")
    rng = np.random.default_rng(n)
    x = np.sort(rng.uniform(0.0, 10.0, n))
    y = rng.normal(size=n)
    ours = not_a_knot_coefficients(x, y)
    ref = interpolate.CubicSpline(x, y).c
    q = np.linspace(x[0], x[-1], 5001)
    v, dv = _evaluate(ours, x, q)
    rv, rdv = _evaluate(ref, x, q)
    assert np.max(np.abs(v - rv)) < 1e-13 * np.max(np.abs(rv))
    assert np.max(np.abs(dv - rdv)) < 1e-13 * np.max(np.abs(rdv))
    if n <= 33:
        mpmath = pytest.importorskip("mpmath")
        s = _exact_knot_slopes(mpmath, x, y)
        err, scipy_err = np.max(np.abs(ours[2] - s[:-1])), np.max(np.abs(ref[2] - s[:-1]))
        assert err <= max(4 * scipy_err, 1e-15 * np.max(np.abs(s)))


def _exact_knot_slopes(mpmath, x, y):
    with mpmath.workdps(40):
        n = len(x)
        X = [mpmath.mpf(float(v)) for v in x]
        Y = [mpmath.mpf(float(v)) for v in y]
        dx = [X[i + 1] - X[i] for i in range(n - 1)]
        sl = [(Y[i + 1] - Y[i]) / dx[i] for i in range(n - 1)]
        a = mpmath.zeros(n, n)
        b = mpmath.zeros(n, 1)
        for i in range(1, n - 1):
            a[i, i - 1], a[i, i], a[i, i + 1] = dx[i], 2 * (dx[i - 1] + dx[i]), dx[i - 1]
            b[i] = 3 * (dx[i] * sl[i - 1] + dx[i - 1] * sl[i])
        d = X[2] - X[0]
        a[0, 0], a[0, 1] = dx[1], d
        b[0] = ((dx[0] + 2 * d) * dx[1] * sl[0] + dx[0] ** 2 * sl[1]) / d
        d = X[-1] - X[-3]
        a[n - 1, n - 1], a[n - 1, n - 2] = dx[-2], d
        b[n - 1] = (dx[-1] ** 2 * sl[-2] + (2 * d + dx[-1]) * dx[-2] * sl[-1]) / d
        return np.array([float(v) for v in mpmath.lu_solve(a, b)])


def test_cubic_reproduced_exactly():
    # not-a-knot reproduces any cubic (de Boor 2001, Ch. IV): y = 2x^3 - x + 1 on uneven knots
    x = np.array([0.0, 0.5, 1.25, 2.0, 3.5, 4.0])
    c = not_a_knot_coefficients(x, 2 * x ** 3 - x + 1)
    assert np.allclose(c[0], 2.0, rtol=0, atol=1e-12)
    assert np.allclose(c[2], 6 * x[:-1] ** 2 - 1, rtol=0, atol=1e-12)


@pytest.mark.parametrize("n", [1, 2, 3, 8, 9, 100, 1023, 1025])
def test_solve_tridiagonal_against_dense(n):
    rng = np.random.default_rng(n)
    lo, up = rng.uniform(-1, 1, n), rng.uniform(-1, 1, n)
    di = 2.5 + rng.uniform(0, 1, n)
    rhs = rng.normal(size=n)
    m = np.diag(di) + np.diag(lo[1:], -1) + np.diag(up[:-1], 1)
    np.testing.assert_allclose(solve_tridiagonal(lo, di, up, rhs), np.linalg.solve(m, rhs), rtol=1e-13, atol=1e-14)


def test_bad_input_refused():
    with pytest.raises(ValueError, match="n >= 4"):
        not_a_knot_coefficients([0.0, 1.0, 2.0], [0.0, 1.0, 2.0])
    with pytest.raises(ValueError, match="strictly increasing"):
        not_a_knot_coefficients([0.0, 1.0, 1.0, 2.0], [0.0, 1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="one length"):
        solve_tridiagonal([0.0], [1.0, 2.0], [0.0, 0.0], [1.0, 1.0])
