"""Exact mechanics of a fixed-guided leaf with held ends (issue 24, Build item 2).

The closed form of :mod:`rsm_lrg.physics.hinge` (beam-column solution with the axial force from
the stretch, one 1-D root) against an independent finite-difference solution of
``E·I·w'''' − N·w'' = 0`` on 400 intervals, N found by Brent's method from N = E·w·y·(½∫w'²)/l.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq

from rsm_lrg.physics import hinge
from rsm_lrg.physics.stepper import leaf_dpsi, leaf_psi

E, W, L = 211e9, 0.010, 0.020


def fd_leaf(y: float, delta: float, m: int = 400) -> tuple[float, float, float]:
    """Finite differences: (lateral force [N], clamp stress [Pa], tension [N]) of one leaf."""
    ei = E * W * y ** 3 / 12.0
    h = L / m

    def shape(n_ax: float) -> np.ndarray:
        # unknowns w_1..w_{m-1}; w_0 = 0, w_m = delta; ghosts w_-1 = w_1, w_{m+1} = w_{m-1}
        a = np.zeros((m - 1, m - 1))
        rhs = np.zeros(m - 1)
        c4 = np.array([1.0, -4.0, 6.0, -4.0, 1.0]) * ei / h ** 4
        c2 = np.array([0.0, 1.0, -2.0, 1.0, 0.0]) * n_ax / h ** 2
        cc = c4 - c2
        for i in range(1, m):
            for off, coef in zip(range(-2, 3), cc):
                j = i + off
                if j == -1:
                    j = 1
                if j == m + 1:
                    j = m - 1
                if j == 0:
                    continue
                if j == m:
                    rhs[i - 1] -= coef * delta
                    continue
                a[i - 1, j - 1] += coef
        w = np.concatenate([[0.0], np.linalg.solve(a, rhs), [delta]])
        return w

    def stretch(w: np.ndarray) -> float:
        return 0.5 * float(np.sum(np.diff(w) ** 2) / h)

    def gap(n_ax: float) -> float:
        return n_ax - E * W * y * stretch(shape(n_ax)) / L

    n_hi = E * W * y * 0.61 * delta ** 2 / L ** 2 + 1.0
    n_ax = brentq(gap, 0.0, n_hi, xtol=1e-12 * n_hi, rtol=1e-12)
    w = shape(n_ax)
    moment = ei * 2.0 * w[1] / h ** 2  # w''(0) with the ghost node w_-1 = w_1
    force = (n_ax * delta + 2.0 * moment) / L  # moments about a clamp
    stress = moment * (y / 2.0) / (W * y ** 3 / 12.0) + n_ax / (W * y)
    return force, stress, n_ax


@pytest.mark.slow
@pytest.mark.parametrize("y, ratio", [(1e-4, 0.3), (1e-4, 3.0), (1e-4, 10.0), (3e-4, 5.0), (5e-4, 2.0)])
def test_closed_form_matches_finite_differences(y, ratio):
    d = ratio * y
    f_fd, s_fd, n_fd = fd_leaf(y, d)
    k = float(hinge.hinge_stiffness(E, W, y, L))
    assert float(hinge.leaf_force(d, k, y)) == pytest.approx(f_fd, rel=2e-3)
    assert float(hinge.leaf_clamp_stress(E, y, L, d)) == pytest.approx(s_fd, rel=5e-3)
    assert float(hinge.leaf_axial_force(E, W, y, L, d)) == pytest.approx(n_fd, rel=2e-3)


def test_issue_24_leaf():
    """The issue's 0.1 mm leaf at δ = 1.0 mm: about 990 MPa at the clamp (the old summed
    stress said 484 MPa), past 65Mn's 785 MPa; the Ritz force is about 36 % stiffer."""
    s = float(hinge.leaf_clamp_stress(E, 1e-4, L, 1e-3))
    assert s == pytest.approx(990e6, rel=0.005)
    assert float(hinge.hinge_peak_stress(E, 1e-4, L, 1e-3)) == s
    k = float(hinge.hinge_stiffness(E, W, 1e-4, L))
    ritz = float(hinge.hinge_force(1e-3, k, hinge.hinge_membrane_stiffness(E, W, 1e-4, L)))
    assert ritz / float(hinge.leaf_force(1e-3, k, 1e-4)) == pytest.approx(1.364, abs=0.002)


@pytest.mark.parametrize("r", [1e-6, 1e-3, 0.05, 0.19, 0.3, 1.0, 7.0, 40.0])
def test_small_and_large_limits(r):
    phi = float(hinge.leaf_stiffening(r))
    u = float(hinge.leaf_tension_parameter(r))
    if r < 0.1:
        assert phi == pytest.approx(1.0 + 0.72 * r * r, rel=1e-4 * r * r + 1e-13)
        assert u == pytest.approx(3.0 / np.sqrt(5.0) * r, rel=0.01 * r * r + 1e-12)
    # u from δ/y and back: G(u) = (δ/y)² (the series and the direct formula agree at u = 0.2)
    rr, _ = hinge._ratio_of_u(np.array([u]))
    assert float(rr[0]) == pytest.approx(r, rel=1e-12)


def test_series_and_direct_formulas_meet():
    u = np.array([0.2 - 1e-12, 0.2 + 1e-12])
    for part in hinge._leaf_parts(u):
        assert part[0] == pytest.approx(part[1], rel=1e-10)


def test_deflection_inverts_the_force():
    rng = np.random.default_rng(3)
    y = rng.uniform(1e-4, 5e-4, 50)
    d = rng.uniform(-20, 20, 50) * y
    k = 4 * hinge.hinge_stiffness(E, W, y, L)
    f = hinge.leaf_force(d, k, y)
    assert np.allclose(hinge.leaf_deflection(f, k, y), d, rtol=1e-11, atol=0)
    assert np.all(np.sign(f) == np.sign(d))
    assert hinge.leaf_deflection(2.0, 100.0, 0.0) == pytest.approx(0.02, rel=1e-15)


def test_tabulated_law_of_the_integrator():
    r = np.concatenate([np.random.default_rng(5).uniform(0, 199.9, 2000), [0.0, 1e-9, 0.005, 0.01]])
    exact = r * np.asarray(hinge.leaf_stiffening(r))
    assert np.allclose(leaf_psi(r), exact, rtol=1e-9, atol=1e-15)
    assert np.allclose(leaf_psi(-r), -exact, rtol=1e-9, atol=1e-15)
    e = 1e-6
    num = (np.asarray(hinge.leaf_stiffening(r + e)) * (r + e) - np.asarray(hinge.leaf_stiffening(r)) * r) / e
    assert np.allclose(leaf_dpsi(r + e / 2), num, rtol=1e-5)
