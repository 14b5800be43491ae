"""The not-a-knot cubic spline of :mod:`rsm_lrg.physics.spline` (the leaf force table's)."""

import numpy as np
import pytest

from rsm_lrg.physics import hinge
from rsm_lrg.physics.spline import not_a_knot_coefficients, solve_tridiagonal


def test_leaf_force_table_is_scipys_cubic_spline_bit_for_bit():
    # Reference: scipy.interpolate.CubicSpline (not-a-knot; LAPACK dgtsv through solve_banded) on
    # the same mirrored points of the leaf force law as leaf_force_table: every coefficient equal
    # to the last bit (the stage integrator's unsettled rows amplify any last-bit change)
    interpolate = pytest.importorskip("scipy.interpolate")
    step = 0.01
    r = np.arange(0.0, hinge.LEAF_TABLE_MAX_RATIO + 0.5 * step, step)
    psi = r * np.atleast_1d(hinge.leaf_stiffening(r))
    x = np.concatenate([-r[:0:-1], r])
    y = np.concatenate([-psi[:0:-1], psi])
    ours = not_a_knot_coefficients(x, y)
    ref = interpolate.CubicSpline(x, y).c
    assert np.array_equal(ours, ref)
    # and leaf_force_table is this spline on r >= 0, in its (n, 4) layout
    tab, st = hinge.leaf_force_table()
    assert st == step and tab.shape == (len(r) - 1, 4)
    assert np.array_equal(tab, np.ascontiguousarray(ours[:, len(r) - 1:][::-1].T))


@pytest.mark.parametrize("n", [4, 5, 6, 7, 8, 33, 200, 1001])
def test_random_knots_against_scipy_and_a_40_digit_solve(n):
    # References: scipy.interpolate.CubicSpline, bit for bit (clustered and spread knots, so that
    # the end rows pivot in some draws); and the same not-a-knot system (de Boor 2001, Ch. IV)
    # solved by mpmath's LU in 40 digits: the knot derivatives within a few ulps of the exact ones
    interpolate = pytest.importorskip("scipy.interpolate")
    mpmath = pytest.importorskip("mpmath")
    for draw in range(10):
        rng = np.random.default_rng(100 * n + draw)
        x = np.sort(rng.uniform(0.0, 10.0, n) ** (1 + 3 * (draw % 2)))
        y = rng.normal(size=n)
        ours = not_a_knot_coefficients(x, y)
        assert np.array_equal(ours, interpolate.CubicSpline(x, y).c), draw
        if n <= 33 and draw < 2:
            s = _exact_knot_slopes(mpmath, x, y)
            assert np.max(np.abs(ours[2] - s[:-1])) <= 1e-11 * np.max(np.abs(s))


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


@pytest.mark.parametrize("n", [1, 2, 3, 8, 9, 100, 1023])
def test_solve_tridiagonal_is_lapack_dgtsv_bit_for_bit(n):
    # Reference: LAPACK's dgtsv (SciPy's solve_banded with (1, 1)) on systems that need row
    # interchanges (diagonals smaller than the sub-diagonal) and on dominant ones; and a dense solve
    linalg = pytest.importorskip("scipy.linalg")
    for dominant in (False, True):
        rng = np.random.default_rng(n + 7 * dominant)
        lo, up = rng.uniform(-1, 1, n), rng.uniform(-1, 1, n)
        di = 2.5 + rng.uniform(0, 1, n) if dominant else rng.uniform(-1, 1, n)
        rhs = rng.normal(size=n)
        ab = np.zeros((3, n))
        ab[0, 1:], ab[1], ab[2, :-1] = up[:-1], di, lo[1:]
        ours = solve_tridiagonal(lo, di, up, rhs)
        assert np.array_equal(ours, linalg.solve_banded((1, 1), ab, rhs)), dominant
        m = np.diag(di) + np.diag(lo[1:], -1) + np.diag(up[:-1], 1)
        np.testing.assert_allclose(m @ ours, rhs, rtol=0, atol=1e-9 * np.linalg.cond(m))


def test_bad_input_refused():
    with pytest.raises(ValueError, match="n >= 4"):
        not_a_knot_coefficients([0.0, 1.0, 2.0], [0.0, 1.0, 2.0])
    with pytest.raises(ValueError, match="strictly increasing"):
        not_a_knot_coefficients([0.0, 1.0, 1.0, 2.0], [0.0, 1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="one length"):
        solve_tridiagonal([0.0], [1.0, 2.0], [0.0, 0.0], [1.0, 1.0])
    with pytest.raises(ValueError, match="singular"):
        solve_tridiagonal([0.0, 0.0], [0.0, 1.0], [1.0, 0.0], [1.0, 1.0])
