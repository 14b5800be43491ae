"""Hertz contact of a ball in a groove and the constriction conductance of its contacts
(rsm_lrg.physics.contact), against independent routes."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from rsm_lrg.physics.contact import (
    ball_contact_conductance,
    elliptic_constriction_resistance,
    hertz_ball_groove,
    hertz_ball_groove_approx,
)
from rsm_lrg.physics.params import LRGParams

MAT = dict(ball_modulus_pa=211e9, ball_poisson=0.277, race_modulus_pa=219e9, race_poisson=0.3)  # paper Table 2


@pytest.mark.parametrize("load", [0.5, 3.411, 20.0])
@pytest.mark.parametrize("groove", [1.38e-3, 1.4307e-3, 1.5e-3])
def test_exact_hertz_matches_hamrock_brewe_within_their_stated_accuracy(load, groove):
    # Hamrock & Brewe (1983) state their curve fits within about 3 % of the exact solution
    exact = hertz_ball_groove(load, 1.3497e-3, groove, **MAT)
    approx = hertz_ball_groove_approx(load, 1.3497e-3, groove, **MAT)
    assert exact.a_m == pytest.approx(approx.a_m, rel=0.03)
    assert exact.b_m == pytest.approx(approx.b_m, rel=0.03)
    assert exact.kappa == pytest.approx(approx.kappa, rel=0.03)


def test_a_ball_on_an_almost_flat_groove_is_the_classical_circular_contact():
    # Hertz, sphere on a flat: a^3 = 3 F R / (4 E*), 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2 (Johnson 1985, Eq. 4.22)
    r, f = 1.3497e-3, 3.411
    c = hertz_ball_groove(f, r, 1e3, **MAT)
    e_star = 1.0 / ((1 - 0.277 ** 2) / 211e9 + (1 - 0.3 ** 2) / 219e9)
    assert c.a_m == pytest.approx((3 * f * r / (4 * e_star)) ** (1 / 3), rel=1e-5)
    assert c.kappa == pytest.approx(1.0, abs=1e-4)
    # largest pressure of a circular contact: 3F/(2 pi a^2)
    assert c.pressure_pa == pytest.approx(3 * f / (2 * math.pi * c.a_m ** 2), rel=1e-4)


def test_constriction_of_an_ellipse_by_numerical_quadrature():
    # K(e) = int_0^{pi/2} dt / sqrt(1 - e^2 sin^2 t), quadrature independent of scipy.special
    a, b, lam = 1.15e-4, 1.79e-5, 44.0
    e2 = 1 - (b / a) ** 2
    k, _ = quad(lambda t: 1 / math.sqrt(1 - e2 * math.sin(t) ** 2), 0, math.pi / 2, epsabs=0.0, epsrel=1e-13, limit=200)
    assert elliptic_constriction_resistance(a, b, lam) == pytest.approx(k / (2 * math.pi * lam * a), rel=1e-12)
    # circle: Holm's 1/(4 lambda a), exactly
    assert elliptic_constriction_resistance(a, a, lam) == pytest.approx(1 / (4 * lam * a), rel=1e-14)
    # slender limit: K -> ln(4 a / b) (Abramowitz & Stegun 17.3.26)
    assert elliptic_constriction_resistance(1.0, 1e-4, 1.0) == pytest.approx(math.log(4e4) / (2 * math.pi), rel=1e-7)


def test_both_sides_of_each_contact_in_series():
    v = LRGParams().to_dict()
    c = ball_contact_conductance(v)
    r_one = elliptic_constriction_resistance(c.contact.a_m, c.contact.b_m, 44.0)
    # 72 contacts in parallel, each the ball's and the raceway's constriction in series (Table 2: both 44 W/(m K))
    assert c.series_w_k == pytest.approx(72 / (2 * r_one), rel=1e-12)
    assert c.to_race_share == pytest.approx(0.5, rel=1e-12)
    # the estimate quoted in data/lrg_shs15v.toml and the README
    assert c.series_w_k == pytest.approx(0.350, abs=5e-4)
    assert v["ball_contact_conductance_w_k"] == pytest.approx(c.series_w_k, rel=2e-3)
    # a softer raceway takes less of the interface's heat
    c2 = ball_contact_conductance(dict(v, guide_conductivity_w_mk=22.0))
    assert c2.to_race_share == pytest.approx(1 / 3, rel=1e-12)


def test_bad_geometry_is_refused():
    with pytest.raises(ValueError, match="groove radius must exceed"):
        hertz_ball_groove(1.0, 1.5e-3, 1.4e-3, **MAT)
    with pytest.raises(ValueError, match="positive force"):
        hertz_ball_groove(0.0, 1.3e-3, 1.4e-3, **MAT)
    assert np.isfinite(hertz_ball_groove(1e-3, 1.3e-3, 1.4e-3, **MAT).a_m)
