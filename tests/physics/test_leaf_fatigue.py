"""Leaf fatigue (rsm_lrg.physics.hinge.leaf_fatigue, the scan's fatigue part): the clamp stress split
into its reversing bending part and its steady tension, against independent routes."""

from __future__ import annotations

import numpy as np
import pytest

from rsm_lrg.physics import hinge
from rsm_lrg.physics.chain import leaf_yield_scan
from rsm_lrg.physics.params import LRGParams

E, W, L = 211e9, 0.010, 0.020  # paper Table 2 (65Mn); data/lrg_shs15v.toml (assumed leaf width, length)


@pytest.mark.parametrize("y", [1e-4, 3e-4, 5e-4])
def test_parts_sum_to_the_clamp_stress_and_the_tension_is_n_over_the_section(y):
    d = np.linspace(1e-7, 20 * y, 41)
    bend, tension = hinge.leaf_clamp_stress_parts(E, y, L, d)
    np.testing.assert_allclose(bend + tension, hinge.leaf_clamp_stress(E, y, L, d), rtol=1e-13)
    # the tension: the beam-column's axial force N over the section w*y (an independent expression)
    np.testing.assert_allclose(tension, hinge.leaf_axial_force(E, W, y, L, d) / (W * y), rtol=1e-12, atol=1e-6)


def test_small_deflection_is_eq_1s_fully_reversed_bending():
    # delta << y: no tension; the bending stress of Eq. 1's leaf, 3 E y delta / l^2 (Roark, fixed-guided beam)
    y, d = 3e-4, 1e-8
    sa, sm, util = hinge.leaf_fatigue(E, y, L, d, 490e6, 980e6)
    assert float(sa) == pytest.approx(3 * E * y * d / L ** 2, rel=1e-9)
    assert float(sm) < 1e-4 * float(sa)  # the tension grows as delta^2
    assert float(util) == pytest.approx(float(sa) / 490e6, rel=1e-5)


def test_goodman_utilisation_by_exact_arithmetic():
    # sigma_a / S_e + sigma_m / R_m (Shigley 10th ed., Eq. 6-41), with the parts computed above
    y, d = 1e-4, 8e-4
    bend, tension = hinge.leaf_clamp_stress_parts(E, y, L, d)
    _, _, util = hinge.leaf_fatigue(E, y, L, d, 400e6, 1000e6)
    assert float(util) == pytest.approx(float(bend) / 400e6 + float(tension) / 1000e6, rel=1e-15)


def test_the_scan_flags_fatigue_where_the_utilisation_reaches_one():
    p = LRGParams()
    r = leaf_yield_scan(p, levels=3)
    d = r.fatigue_dict()
    assert d["fatigue_limit_pa"] == 490e6 and d["tensile_strength_pa"] == 980e6
    assert d["n_points"] == 81 and 0 < d["n_fatigue"] < 81
    # the thinnest leaf fails most often; the thickest never
    counts = [b["n_fatigue"] for b in d["by_thickness"]]
    assert counts[0] >= counts[1] >= counts[2] == 0
    assert d["max_utilisation"] >= 1.0
    assert sum(k for _, k, _ in d["share"]["stroke_m"]) == d["n_fatigue"]
    assert "fail in fatigue" in r.fatigue_text()
    # a leaf twice as strong in fatigue fails less often
    r2 = leaf_yield_scan(p.with_overrides(hinge_fatigue_limit_pa=980e6), levels=3)
    assert r2.n_fatigue <= r.n_fatigue
