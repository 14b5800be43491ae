"""The finite-volume solver against problems with exact solutions.

References: Incropera, DeWitt, Bergman & Lavine, *Fundamentals of Heat and Mass Transfer*,
6th ed. (Wiley, 2007):
  - Section 3.5.1 (plane wall with uniform generation; symmetric case, Eqs. 3.42-3.43:
    T(x) - T_s = q L^2 / (2k) (1 - x^2/L^2), and the surface energy balance T_s = T_inf + q L / h),
  - Section 3.6.2, Table 3.4 (fins of uniform cross-section: case A convective tip, case B
    adiabatic tip, case D infinite fin),
  - Section 5.3 (general lumped capacitance with generation: rho V c dT/dt = E_g - h A (T - T_inf),
    so theta = E_g / (h A) (1 - exp(-t / tau)), tau = rho V c / (h A)).
"""

import math

import numpy as np
import pytest

from rsm_lrg.physics.thermal import FVSystem, VoxelModel, fin_conductance

LAM, RHO, CP = 44.0, 7830.0, 460.0  # GCr15, paper Table 2


def _props(*bodies):
    """rho, lam, cp arrays for body codes 1..n given (rho, lam, cp) tuples."""
    rho = np.zeros(len(bodies) + 1)
    lam = np.zeros_like(rho)
    cp = np.zeros_like(rho)
    for i, (r, l, c) in enumerate(bodies, start=1):
        rho[i], lam[i], cp[i] = r, l, c
    return rho, lam, cp


def _slab(n, half_length, h):
    """Slab -L..L along x, one cell thick in y and z (adiabatic there), convection h on both ends."""
    xe = np.linspace(-half_length, half_length, n + 1)
    ye = ze = np.array([0.0, 0.01])
    body = np.ones((n, 1, 1), dtype=np.int8)
    rho, lam, cp = _props((RHO, LAM, CP))
    ht = np.zeros((2, 6))
    ht[1, :2] = h
    return VoxelModel(xe, ye, ze, body, rho, lam, cp, ht, 1, ((0.0, 0.005, 0.005),))


def _slab_error(n, h):
    L, Q = 0.01, 2.0
    fv = FVSystem(_slab(n, L, h))
    st = fv.steady(Q)
    V = 2 * L * 0.01 * 0.01
    q = Q / V
    xc = 0.5 * (np.linspace(-L, L, n + 1)[1:] + np.linspace(-L, L, n + 1)[:-1])
    exact = q * (L**2 - xc**2) / (2 * LAM) + q * L / h  # Incropera Sec. 3.5.1
    return np.abs(st.theta_k - exact).max() / exact.max(), st


@pytest.mark.parametrize("h", [50.0, 1e12])  # convective ends; h -> infinity = fixed T_s = T_inf
def test_slab_with_source_converges_at_second_order(h):
    e1, st = _slab_error(20, h)
    e2, _ = _slab_error(40, h)
    assert e1 < 1e-2  # 20 cells: within 1 % of the parabola
    assert 3.5 < e1 / e2 < 4.5  # error ~ dx^2 (ratio 4 on halving)
    assert abs(st.energy_balance_error) < 1e-10


def test_slab_is_exact_at_the_centre_with_convective_ends():
    # A parabola is reproduced exactly by the central 3-point stencil; the only error is the
    # half-cell at the Robin face, which vanishes when h dominates it: check the centre
    # rise against q L^2/(2k) + q L / h within 0.5 % at 40 cells.
    e, st = _slab_error(40, 50.0)
    assert e < 5e-3


def _fin(n, length, h, tip_h):
    """Square bar 2 mm x 2 mm; a thin, very conductive heater cell at x < 0 feeds the base."""
    a = 2e-3
    xe = np.concatenate([[-1e-5], np.linspace(0.0, length, n + 1)])
    ye = ze = np.array([0.0, a])
    body = np.full((n + 1, 1, 1), 2, dtype=np.int8)
    body[0] = 1  # heater
    rho, lam, cp = _props((1.0, 1e7, 1.0), (RHO, LAM, CP))
    ht = np.zeros((3, 6))
    ht[2, 2:] = h
    ht[2, 1] = tip_h
    return VoxelModel(xe, ye, ze, body, rho, lam, cp, ht, 1, ((-0.5e-5, a / 2, a / 2),)), a


@pytest.mark.parametrize("tip_h", [0.0, 100.0])
def test_fin_base_conductance_matches_table_3_4(tip_h):
    h, L, Q = 25.0, 0.1, 0.05
    model, a = _fin(400, L, h, tip_h)
    st = FVSystem(model).steady(Q)
    G_fv = Q / st.probe_rise_k[0]
    # the FV side faces include the half-cell conduction a/(2k) in series with 1/h
    h_eff = 1.0 / (a / (2 * LAM) + 1.0 / h)
    tip_eff = 0.0 if tip_h == 0 else 1.0 / (a / (2 * LAM) + 1.0 / tip_h)
    G_exact = fin_conductance(h_eff, 4 * a, LAM, a * a, L, tip_h_w_m2k=tip_eff)
    # Table 3.4 for x measured from the base face; the FV base cell centre sits dx/2 inside
    assert G_fv == pytest.approx(G_exact, rel=5e-3)


def test_fin_profile_is_exponential_for_a_long_fin():
    # Table 3.4 case D: theta/theta_b = exp(-m x) for mL >> 1
    h, Q, n, L = 25.0, 0.05, 600, 0.3
    model, a = _fin(n, L, h, 0.0)
    fv = FVSystem(model)
    st = fv.steady(Q)
    theta = st.theta_k[1:]
    xc = (np.arange(n) + 0.5) * L / n
    h_eff = 1.0 / (a / (2 * LAM) + 1.0 / h)
    m = math.sqrt(h_eff * 4 * a / (LAM * a * a))
    assert m * L > 8
    ratio = theta / theta[0]
    expected = np.exp(-m * (xc - xc[0]))
    near = xc < 3 / m
    np.testing.assert_allclose(ratio[near], expected[near], rtol=1e-3)


def test_fin_conductance_limits():
    # Table 3.4: adiabatic tip -> M tanh(mL); infinite -> M = sqrt(hPkA)
    h, P, k, A = 8.82, 0.041, 37.46, 1.95e-4
    M = math.sqrt(h * P * k * A)
    m = math.sqrt(h * P / (k * A))
    assert fin_conductance(h, P, k, A, 0.2) == pytest.approx(M * math.tanh(m * 0.2), rel=1e-12)
    assert fin_conductance(h, P, k, A, 50.0) == pytest.approx(M, rel=1e-12)
    # a convective tip conducts more than an adiabatic one
    assert fin_conductance(h, P, k, A, 0.2, tip_h_w_m2k=h) > fin_conductance(h, P, k, A, 0.2)
    with pytest.raises(ValueError, match="positive"):
        fin_conductance(-1.0, P, k, A, 0.2)


def _cube(n=4, a=0.01, h=10.0):
    xe = np.linspace(0, a, n + 1)
    body = np.ones((n, n, n), dtype=np.int8)
    rho, lam, cp = _props((RHO, 1e4, CP))  # very conductive: Biot = h a / k ~ 1e-5
    ht = np.zeros((2, 6))
    ht[1] = h
    return VoxelModel(xe, xe, xe, body, rho, lam, cp, ht, 1, ((a / 2, a / 2, a / 2),))


def test_lumped_body_exponential_transient():
    a, h, Q = 0.01, 10.0, 0.1
    fv = FVSystem(_cube(a=a, h=h))
    hA = 1.0 / (a / 4 / (2 * 1e4) + 1.0 / h) * 6 * a * a  # faces incl. the (tiny) half-cell
    tau = RHO * CP * a**3 / hA
    dt = tau / 200
    tr_be = fv.transient(Q, duration_s=3 * tau // dt * dt, dt_s=dt)
    tr_cn = fv.transient(Q, duration_s=3 * tau // dt * dt, dt_s=dt, scheme="crank-nicolson")
    t = tr_be.times_s
    exact = Q / hA * (1 - np.exp(-t / tau))  # Incropera Sec. 5.3 with generation
    # backward Euler: the exact discrete recursion of one lumped node, theta_n = (1 - (1 + dt/tau)^-n)
    be_discrete = Q / hA * (1 - (1 + dt / tau) ** (-np.arange(len(t))))
    np.testing.assert_allclose(tr_be.probe_rise_k[:, 0], be_discrete, rtol=1e-4, atol=1e-9)
    # both schemes approach the exponential: BE to O(dt/tau), CN to O((dt/tau)^2)
    assert np.abs(tr_be.probe_rise_k[:, 0] - exact).max() < 5e-3 * exact[-1]
    assert np.abs(tr_cn.probe_rise_k[:, 0] - exact).max() < 1e-4 * exact[-1]
    assert fv.steady(Q).probe_rise_k[0] == pytest.approx(Q / hA, rel=1e-4)
