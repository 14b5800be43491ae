"""rsm_lrg.physics.thermal.fixed_order: the BLAS-free solve and eigen-decomposition agree
with LAPACK (an independent route) and are bit-identical for the same matrix."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rsm_lrg.physics.thermal.fixed_order import solve_spd, symmetric_eigen
from rsm_lrg.physics.thermal.geometry import GuideGeometry
from rsm_lrg.physics.thermal.network import ThermalNetwork


def spd(n, seed):
    rng = np.random.default_rng(seed)
    a = rng.normal(size=(n, n))
    return a @ a.T + n * np.eye(n), rng.normal(size=n)


@settings(max_examples=25, deadline=None)
@given(st.integers(1, 30), st.integers(0, 10**6))
def test_against_lapack(n, seed):
    a, b = spd(n, seed)
    # tolerance: backward-stable algorithms on a matrix of condition number < 1e3 (eigenvalues
    # of a a^T + n I lie in [n, ~5n]): 1e-12 relative to the largest entry
    np.testing.assert_allclose(solve_spd(a, b), np.linalg.solve(a, b), rtol=1e-12, atol=1e-13)
    e = symmetric_eigen(a)
    mu, v = np.linalg.eigh(a)
    np.testing.assert_allclose(e.values, mu, rtol=1e-12)
    # projections V^T x: eigenvectors have arbitrary signs, so compare |.| and the
    # reconstruction sum_k (v_k.x)(v_k.y)/mu_k = x^T A^-1 y, which is sign-free
    px, py = e.project(b, np.ones(n))
    assert abs(np.sum(px * py / e.values) - b @ np.linalg.solve(a, np.ones(n))) < 1e-11 * (1 + abs(b).sum())
    np.testing.assert_allclose(np.sort(np.abs(px)), np.sort(np.abs(v.T @ b)), atol=1e-11)
    np.testing.assert_allclose(np.sum(px**2), b @ b, rtol=1e-12)  # orthonormal eigenvectors


def test_network_matches_its_lapack_decomposition():
    # the network's stiff matrix (eigenvalues 6e-4 .. 14 1/s): absolute accuracy eps*||A||
    # gives ~5e-12 relative on the slowest mode, as LAPACK's own eigh
    net = ThermalNetwork(GuideGeometry(), 8.82, 22.45)
    s = 1 / np.sqrt(net.C)
    mu, v = np.linalg.eigh(s[:, None] * net.K * s[None, :])
    np.testing.assert_allclose(net.time_constants_s, 1 / mu, rtol=1e-10)
    t = np.arange(0, 361) * 60.0
    old = -np.expm1(-np.multiply.outer(t, mu)) @ ((s[:, None] * v)[0] * (v.T @ (s * net.b)) / mu)
    np.testing.assert_allclose(net.response(t)[1:], old[1:], rtol=1e-10)
    assert net.steady_rise_per_w == pytest.approx(np.linalg.solve(net.K, net.b)[0], rel=1e-11)
    # a response at a time does not depend on the other times asked for
    full = net.response(t)
    assert np.array_equal(net.response(t[::7]), full[::7])
    assert np.array_equal(net.response(t[-1:]), full[-1:])


def test_errors():
    with pytest.raises(ValueError, match="positive definite"):
        solve_spd([[1.0, 2.0], [2.0, 1.0]], [1.0, 1.0])
    with pytest.raises(ValueError, match="non-finite"):
        symmetric_eigen([[np.nan]])


@settings(max_examples=25, deadline=None)
@given(st.integers(2, 30), st.integers(0, 10**6))
def test_network_modes_against_lapack(n, seed):
    # a random conduction network (a graph Laplacian plus losses to the air, random capacities):
    # modal coefficients and steady rise against numpy's eigh of C^-1/2 K C^-1/2
    from rsm_lrg.physics.thermal.fixed_order import modal_sum, network_modes

    rng = np.random.default_rng(seed)
    w = np.triu(rng.uniform(0, 1, (n, n)) * (rng.uniform(size=(n, n)) < 0.5), 1)
    k = np.diag((w + w.T).sum(axis=1) + rng.uniform(0.01, 1, n)) - (w + w.T)
    cap = rng.uniform(0.1, 100, n)
    src = rng.uniform(0, 1, (n, 2))
    node = int(rng.integers(n))
    mu, coef, steady = network_modes(k, cap, src, node)
    s = 1 / np.sqrt(cap)
    lam, v = np.linalg.eigh(s[:, None] * k * s[None, :])
    np.testing.assert_allclose(mu, lam, rtol=1e-10)
    ref = (s[node] * v[node])[:, None] * (v.T @ (s[:, None] * src)) / lam[:, None]
    np.testing.assert_allclose(steady, np.linalg.solve(k, src)[node], rtol=1e-10)
    t = np.array([0.0, 1.0 / lam[-1], 1.0 / lam[0], 1e12])
    for c in range(2):
        got = modal_sum(coef[:, c], mu, t)
        want = -np.expm1(-np.multiply.outer(t, lam)) @ ref[:, c]
        np.testing.assert_allclose(got, want, rtol=1e-9, atol=1e-12 * abs(steady[c]))
        assert got[-1] == pytest.approx(steady[c], rel=1e-9)


def test_rig_rows_bad_input():
    from rsm_lrg.physics.thermal.fixed_order import network_modes

    with pytest.raises(ValueError, match="no path to ambient"):
        network_modes([[1.0, -1.0], [-1.0, 1.0]], [1.0, 1.0], [[1.0], [0.0]])
    with pytest.raises(ValueError, match="positive capacities"):
        network_modes([[1.0]], [0.0], [[1.0]])
