"""Eqs. 1-2, 8-13, 17-18 against the paper's numbers (DIGEST.md 'checked' values) and exact
identities; vectorised use; hypothesis properties."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rsm_lrg.physics import convection, heat, hinge, tcr, wear

F_Z = hinge.normal_load(171.0, 0.27)


def test_load_and_breakaway_friction():
    # Paper Section 2.1: F0 + m_t g = 173.65 N, f_mu_max = 5.209 N (4 significant digits).
    assert F_Z == pytest.approx(173.65, abs=0.005)
    assert hinge.max_static_friction(0.03, 171.0, 0.27) == pytest.approx(5.209, abs=5e-4)
    # g = 9.81 gives the same printed numbers
    assert hinge.normal_load(171.0, 0.27, 9.81) == pytest.approx(173.65, abs=0.005)


def test_friction_heat_paper_and_watts():
    # Paper Eq. 8: Q = 0.4150 (mu_k 0.02, v 0.5 m/s, J 4.184); within 0.05 %.
    q = heat.friction_heat(0.02, F_Z, 0.5)
    assert q == pytest.approx(0.4150, rel=5e-4)
    # exact identity: the plain-watts switch is J times larger
    assert heat.friction_heat(0.02, F_Z, 0.5, in_calories=False) == pytest.approx(q * 4.184, rel=1e-14)


def test_heat_source_intensity():
    # Paper Section 3.1: 5.6e5 W/m^3; DIGEST checked 5.597e5 with 4 x 18 balls, V_t 7.415e-7 m^3.
    vt = heat.ball_volume(1.3497e-3, 4 * 18)
    assert vt == pytest.approx(7.415e-7, rel=1e-3)
    phi = heat.heat_source_intensity(heat.friction_heat(0.02, F_Z, 0.5), vt)
    assert phi == pytest.approx(5.597e5, rel=1e-3)
    assert phi == pytest.approx(5.6e5, rel=0.01)   # the acceptance: within 1 %


def test_convection_paper_numbers():
    # Paper Section 2.2.3 / 3.1: Re 290.3, Pr 0.703, h 8.82 and 22.45 W/(m^2 K); within 0.5 %.
    re = convection.reynolds(0.3, 0.015, 15.5e-6)
    pr = convection.prandtl(1005.0, 18.4e-6, 0.0263)
    assert re == pytest.approx(290.3, rel=5e-4)
    assert pr == pytest.approx(0.703, rel=5e-4)
    hs = convection.heat_transfer_coefficient(convection.nusselt_parallel_plate(re, pr), 0.0263, 0.015)
    hf = convection.heat_transfer_coefficient(convection.nusselt_normal_plate(re, pr), 0.0263, 0.015)
    assert hs == pytest.approx(8.82, rel=5e-3) and hf == pytest.approx(22.45, rel=5e-3)
    assert convection.h_side() == pytest.approx(hs) and convection.h_front() == pytest.approx(hf)


def test_vectorised_shapes():
    v = np.linspace(0.1, 1.0, 100_000)
    q = heat.friction_heat(0.02, F_Z, v)
    assert q.shape == v.shape and np.allclose(q, 0.02 * F_Z * v / 4.184)
    y = np.array([1e-4, 3e-4, 5e-4])
    k = hinge.hinge_stiffness(211e9, 0.01, y, 0.02)
    assert k.shape == (3,)
    assert np.allclose(hinge.hinge_thickness_for_deflection(hinge.hinge_deflection(5.209, 4, k), 5.209, 4,
                                                            211e9, 0.01, 0.02), y, rtol=1e-12)


@given(y=st.floats(1e-5, 2e-3), factor=st.floats(0.1, 10.0))
def test_stiffness_scales_with_thickness_cubed(y, factor):
    # Eq. 1: K_n proportional to y^3 (exact up to rounding).
    k1 = hinge.hinge_stiffness(211e9, 0.01, y, 0.02)
    k2 = hinge.hinge_stiffness(211e9, 0.01, y * factor, 0.02)
    assert k2 / k1 == pytest.approx(factor ** 3, rel=1e-12)


@given(y1=st.floats(1e-5, 1e-3), y2=st.floats(1e-5, 1e-3))
def test_deflection_decreases_with_thickness(y1, y2):
    d1, d2 = (hinge.hinge_deflection(5.209, 4, hinge.hinge_stiffness(211e9, 0.01, y, 0.02)) for y in (y1, y2))
    assert (d1 >= d2) == (y1 <= y2) or d1 == d2


def test_brinell_and_ball_force():
    # 1 HB = 1 kgf/mm^2 = 9.80665 MPa (definition); F_i = F/(Z sin 45 deg).
    assert wear.brinell_to_pa(1.0) == 9.80665e6
    assert wear.ball_normal_force(F_Z, 72, 45.0) == pytest.approx(F_Z / (72 * np.sqrt(0.5)), rel=1e-14)


@given(dist=st.floats(0.0, 1e3), factor=st.floats(0.0, 100.0))
def test_archard_is_linear_in_distance(dist, factor):
    v1 = wear.archard_wear_volume(4e-5, 3.4, dist, 5.13e9)
    v2 = wear.archard_wear_volume(4e-5, 3.4, dist * factor, 5.13e9)
    assert v2 == pytest.approx(v1 * factor, rel=1e-12, abs=1e-300)


@given(x=st.floats(1e-3, 0.2), y=st.floats(5e-5, 1e-3))
@settings(max_examples=50)
def test_eq17_is_eq13_with_eq14(x, y):
    k = hinge.hinge_stiffness(211e9, 0.01, y, 0.02)
    dd = hinge.hinge_deflection(5.209, 4, k)
    v17 = wear.rfcms_wear_volume(4e-5, 3.4, x, 4, k, 5.209, 5.13e9)
    v13 = wear.archard_wear_volume(4e-5, 3.4, wear.rfcms_sliding_distance(x, dd), 5.13e9)
    assert v17 == pytest.approx(v13, rel=1e-9, abs=1e-30)
    assert v17 <= wear.archard_wear_volume(4e-5, 3.4, x, 5.13e9)   # RFCMS never above RMS by Eq. 14


def test_inverse_wear_question():
    # DIGEST Section 3: 58.93 % at 0.075 m needs dd = 30.8 mm by Eq. 14 (exact: 0.4107 * 75 mm).
    dd = wear.deflection_for_wear_ratio(0.5893, 0.075)
    assert dd == pytest.approx(0.0308, abs=5e-5)
    assert wear.wear_ratio(wear.rfcms_sliding_distance(0.075, dd), 0.075) == pytest.approx(0.5893, rel=1e-12)
    # reciprocating reading: half of it
    assert wear.deflection_for_wear_ratio(0.5893, 0.075, reciprocating=True) == pytest.approx(dd / 2)
    # leaf thickness for it with the assumed 10 mm x 20 mm 65Mn leaf: exact inverse of Eqs. 1-2
    y = hinge.hinge_thickness_for_deflection(dd, 5.209, 4, 211e9, 0.01, 0.02)
    assert hinge.hinge_deflection(5.209, 4, hinge.hinge_stiffness(211e9, 0.01, y, 0.02)) == pytest.approx(dd, rel=1e-12)
    with pytest.raises(ValueError):
        wear.deflection_for_wear_ratio(1.5, 0.075)


def test_wear_rate_per_hour():
    # exact: 0.15 m per 0.4 s cycle is 1350 m/h
    r = wear.wear_rate_per_hour(4e-5, 3.4, 0.15, 0.4, 5.13e9)
    assert r == pytest.approx(4e-5 * 3.4 * 1350.0 / 5.13e9, rel=1e-14)


def test_tcr():
    # Paper Section 4.3: 1.2 degC in 50 min -> 0.024 degC/min (Eq. 18).
    assert tcr.temperature_change_rate(25.0, 26.2, 0, 50) == pytest.approx(0.024, rel=1e-12)
    t = np.arange(0, 51, 1.0)
    rec = 25 + 0.03 * t
    assert tcr.tcr_from_record(t, rec) == pytest.approx(0.03, rel=1e-12)
    assert tcr.tcr_from_record(t, rec, method="slope") == pytest.approx(0.03, rel=1e-12)
    two = np.vstack([rec, 25 + 0.01 * t])
    assert np.allclose(tcr.tcr_from_record(t, two), [0.03, 0.01])
    with pytest.raises(ValueError):
        tcr.temperature_change_rate(25, 26, 10, 10)
    with pytest.raises(ValueError):
        tcr.tcr_from_record([0, 0, 1], [1, 2, 3])
