"""Solver options of the 3-D finite-volume model: AMG-preconditioned CG (steady and transient)
against the sparse direct path, SPD check, energy balance, one set-up per transient, the
automatic choice and the pyamg fallback.

Reference for every agreement test: the sparse direct solution (SuperLU) of the SAME discrete
system, an independent route to the same numbers. Tolerance: the issue's 1e-8 of the rise
(max |difference| over all cells / max rise); the AMG solves stop at a relative residual of
1e-10, and the measured differences are 1e-13 .. 1e-9 (benchmarks/bench_thermal.py).

Inputs: paper Q = 0.4150 W (Eq. 8), h = 8.82 / 22.45 W/(m^2 K) (Eqs. 11-12, Section 3.1).
"""

import math

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from hypothesis import given, settings
from hypothesis import strategies as st

import rsm_lrg.physics.thermal.fv as fvmod
from rsm_lrg.physics.thermal import FVSystem, GuideGeometry, VoxelModel, voxelise
from rsm_lrg.physics.thermal.fv import AMGSolver

pytest.importorskip("pyamg")

Q, HS, HF = 0.4150, 8.82, 22.45
REL = 1e-8  # issue brief: AMG result = direct result to 1e-8 of the rise


def _guide(cell):
    return FVSystem(voxelise(GuideGeometry(), HS, HF, cell_size_m=cell))


@pytest.fixture(scope="module")
def fv4():
    return _guide(4e-3)


@pytest.fixture(scope="module")
def fv2():  # the default grid of voxelise (cell_size_m=2e-3)
    return _guide(2e-3)


@pytest.fixture(scope="module")
def fv1():  # finer grid: 18,114 cells in the quarter guide
    return _guide(1e-3)


# ------------------------------------------------------------------------------ SPD check
def test_conductance_matrix_is_spd_by_check_and_by_eigenvalues(fv4):
    info = fv4.check_spd()
    assert info["components"] == 1
    assert info["asymmetry"] == 0.0
    # independent route: a dense Cholesky factorisation of K (780 x 780) exists iff K is SPD
    K = fv4.K.toarray()
    assert np.array_equal(K, K.T)
    Lc = np.linalg.cholesky(K)
    assert np.all(np.diag(Lc) > 0)
    # column sums of K are the convective conductances (interior faces cancel): the identity
    # behind the energy-balance bound below
    assert np.allclose(np.asarray(fv4.K.sum(axis=0)).ravel(), fv4.g_conv, rtol=0, atol=1e-12 * abs(K).max())


def _two_blocks(cool_second):
    """A 1-cell block and a 2-cell block separated by an ambient cell; the second is cooled
    only if asked (uncooled, its two cells are a floating pair: K singular there)."""
    xe = np.array([0.0, 0.01, 0.02, 0.03, 0.04])
    ye = ze = np.array([0.0, 0.01])
    body = np.array([1, 0, 2, 2], dtype=np.int8).reshape(4, 1, 1)
    rho = np.array([0.0, 7830.0, 7830.0])
    lam = np.array([0.0, 44.0, 44.0])
    cp = np.array([0.0, 460.0, 460.0])
    ht = np.zeros((3, 6))
    ht[1] = 10.0
    ht[2] = 10.0 if cool_second else 0.0
    return VoxelModel(xe, ye, ze, body, rho, lam, cp, ht, 1, ((0.005, 0.005, 0.005),))


def test_check_spd_rejects_an_uncooled_island():
    FVSystem(_two_blocks(True)).check_spd()
    fv = FVSystem(_two_blocks(False))
    with pytest.raises(ValueError, match="no cooled face"):
        fv.check_spd()
    with pytest.raises(ValueError, match="no cooled face"):
        fv.steady(1.0, method="amg")


# --------------------------------------------------------------------------------- steady
@pytest.mark.parametrize("grid", ["fv2", "fv1"])
def test_amg_steady_equals_direct(grid, request):
    fv = request.getfixturevalue(grid)
    d = fv.steady(Q, method="direct")
    a = fv.steady(Q, method="amg", rtol=1e-10)
    assert a.info["method"] == "amg" and a.info["iterations"] > 0
    assert np.abs(a.theta_k - d.theta_k).max() < REL * d.max_rise_k
    assert a.mean_probe_rise_k == pytest.approx(d.mean_probe_rise_k, rel=REL)


@pytest.mark.parametrize("rtol", [1e-6, 1e-10])
def test_amg_energy_balance_within_the_residual_bound(fv1, rtol):
    # heat out - heat in = copies * (g_conv . theta - sum(b Q)) = -copies * 1^T r (column sums
    # of K = g_conv), and |1^T r| <= sqrt(n) ||r|| <= sqrt(n) rtol ||b Q||  (Cauchy-Schwarz)
    a = FVSystem(fv1.model).steady(Q, method="amg", rtol=rtol)
    bound = fv1.copies * math.sqrt(fv1.n) * rtol * np.linalg.norm(fv1.b * Q)
    assert abs(a.heat_out_w - Q) <= bound
    r = fv1.b * Q - fv1.K @ a.theta_k
    assert np.linalg.norm(r) <= rtol * np.linalg.norm(fv1.b * Q)
    assert a.heat_out_w - Q == pytest.approx(-fv1.copies * r.sum(), abs=1e-12 * Q)


def test_steady_hierarchy_is_cached(fv2):
    fv = FVSystem(fv2.model)
    for q in (Q, 2 * Q, 0.5 * Q):
        fv.steady(q, method="amg")
    assert fv.setups == {"lu": 0, "amg": 1}


# ------------------------------------------------------------------------------ transient
@pytest.mark.slow
@pytest.mark.parametrize("grid,scheme", [("fv4", "crank-nicolson"), ("fv2", "backward-euler"),
                                         ("fv2", "crank-nicolson")])
def test_amg_transient_equals_direct(grid, scheme, request):
    fv = request.getfixturevalue(grid)
    kw = dict(duration_s=5 * 3600.0, dt_s=60.0, scheme=scheme)
    d = fv.transient(Q, solver="direct", **kw)
    a = fv.transient(Q, solver="amg", rtol=1e-10, **kw)
    rise = d.theta_final_k.max()
    assert np.abs(a.theta_final_k - d.theta_final_k).max() < REL * rise
    assert np.abs(a.probe_rise_k - d.probe_rise_k).max() < REL * rise
    assert np.abs(a.max_rise_k - d.max_rise_k).max() < REL * rise


@pytest.mark.slow
def test_amg_transient_equals_direct_on_the_finer_grid(fv1):
    kw = dict(duration_s=5 * 3600.0, dt_s=60.0)
    d = fv1.transient(Q, solver="direct", **kw)
    a = fv1.transient(Q, solver="amg", **kw)
    rise = d.theta_final_k.max()
    assert np.abs(a.theta_final_k - d.theta_final_k).max() < REL * rise
    assert np.abs(a.probe_rise_k - d.probe_rise_k).max() < REL * rise


def test_one_hierarchy_per_transient_reused_every_step(fv2):
    fv = FVSystem(fv2.model)
    tr = fv.transient(Q, duration_s=5 * 3600.0, dt_s=60.0, solver="amg")
    assert fv.setups == {"lu": 0, "amg": 1}  # counted where the hierarchy is built
    assert tr.info["hierarchies"] == 1 and tr.info["setups"] == 1 and tr.info["factorisations"] == 0
    assert tr.info["n_steps"] == 300
    assert tr.info["iterations_total"] >= 300  # every step iterated on the same hierarchy
    fv.transient(Q, duration_s=3600.0, dt_s=60.0, solver="direct")
    assert fv.setups == {"lu": 1, "amg": 1}


def test_amg_transient_step_energy_balance(fv2):
    # backward Euler, one step at a time (theta0 carries the state): per step
    # Q dt = copies * (1^T C (theta1 - theta0) + dt g_conv . theta1) up to the residual bound
    fv, dt, rtol = fv2, 60.0, 1e-10
    theta = np.zeros(fv.n)
    for _ in range(5):
        tr = fv.transient(Q, duration_s=dt, dt_s=dt, theta0=theta, solver="amg", rtol=rtol)
        new = tr.theta_final_k
        stored = fv.copies * fv.C @ (new - theta)
        out = fv.copies * dt * fv.g_conv @ new
        rhs = fv.C / dt * theta + fv.b * Q
        bound = fv.copies * dt * math.sqrt(fv.n) * rtol * np.linalg.norm(rhs)
        assert abs(stored + out - Q * dt) <= bound
        theta = new


# ---------------------------------------------------------------------- automatic choice
def test_auto_is_direct_below_the_threshold_and_amg_above(fv2, monkeypatch):
    assert fv2.n <= fvmod.AUTO_AMG_CELLS
    assert fv2.steady(Q).info["method"] == "direct"
    assert fv2.transient(Q, duration_s=600.0, dt_s=60.0).info["solver"] == "direct"
    monkeypatch.setattr(fvmod, "AUTO_AMG_CELLS", 1000)
    fv = FVSystem(fv2.model)
    assert fv.steady(Q).info["method"] == "amg"
    tr = fv.transient(Q, duration_s=600.0, dt_s=60.0)
    assert tr.info["solver"] == "amg" and tr.info["hierarchies"] == 1


def test_without_pyamg_amg_is_a_clear_error_and_auto_falls_back(fv2, monkeypatch):
    monkeypatch.setitem(__import__("sys").modules, "pyamg", None)  # makes `import pyamg` fail
    assert not fvmod.have_pyamg()
    fv = FVSystem(fv2.model)
    with pytest.raises(ImportError, match="pip install pyamg"):
        fv.steady(Q, method="amg")
    monkeypatch.setattr(fvmod, "AUTO_AMG_CELLS", 1000)
    with pytest.warns(RuntimeWarning, match="pyamg is not installed"):
        st_ = fv.steady(Q)
    assert st_.info["method"] == "direct" and "fallback" in st_.info


def test_bad_solver_options(fv4):
    with pytest.raises(ValueError, match="method must be one of"):
        fv4.steady(Q, method="lu")
    with pytest.raises(ValueError, match="solver must be one of"):
        fv4.transient(Q, duration_s=600.0, dt_s=60.0, solver="gmres")
    with pytest.raises(ValueError, match="theta0"):
        fv4.transient(Q, duration_s=600.0, dt_s=60.0, theta0=np.zeros(3))


# ------------------------------------------------------- AMGSolver on random M-matrices
@settings(max_examples=25, deadline=None)
@given(n=st.integers(2, 400), seed=st.integers(0, 2**32 - 1), warm=st.booleans())
def test_amg_solver_matches_spsolve_on_random_spd_m_matrices(n, seed, warm):
    """Random weighted graph Laplacian + positive diagonal (a non-singular M-matrix);
    max_coarse=8 forces a real multilevel hierarchy. Reference: scipy spsolve."""
    rng = np.random.default_rng(seed)
    m = 3 * n
    i, j = rng.integers(0, n, m), rng.integers(0, n, m)
    keep = i != j
    w = rng.uniform(0.1, 10.0, keep.sum())
    W = sp.coo_matrix((w, (i[keep], j[keep])), shape=(n, n)).tocsr()
    W = W + W.T
    L = sp.diags(np.asarray(W.sum(axis=1)).ravel()) - W
    A = (L + sp.diags(rng.uniform(1e-3, 1.0, n))).tocsr()
    b = rng.normal(size=n)
    ref = spla.spsolve(A.tocsc(), b)
    solver = AMGSolver(A, max_coarse=8)
    x0 = ref + 1e-3 * rng.normal(size=n) if warm else None
    x, it = solver.solve(b, x0=x0, rtol=1e-12)
    assert np.linalg.norm(b - A @ x) <= 1e-12 * np.linalg.norm(b)
    assert np.abs(x - ref).max() <= 1e-8 * np.abs(ref).max()
