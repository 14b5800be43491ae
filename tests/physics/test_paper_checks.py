"""Thermal and wear comparisons with the paper (issue 15, Build 4): rsm_lrg.physics.paper_checks."""

import pytest

from rsm_lrg.physics import paper_checks
from rsm_lrg.physics.params import LRGParams


def test_wear_readings_arithmetic():
    # Each reading is a ratio of sliding distances (Eq. 13 linear in L): exact algebra with
    # s = 0.075 m, r = 0.5893 (Section 3.2), mu_k/mu_s = 2/3 (Sections 2.1, 2.2.3). 1e-12 relative.
    s, r = 0.075, 0.5893
    got = {x.name: x for x in paper_checks.wear_readings()}
    expect = {"Eq. 14, one stroke from a relaxed hinge": s * (1 - r),
              "Eq. 17 as written (x_ws = s)": s * (1 - r),
              "steady reciprocation, mu_k = mu_s": s * (1 - r) / 2,
              "steady reciprocation, mu_k = 0.02, mu_s = 0.03": s * (1 - r) / (1 + 2 / 3),
              "stroke as amplitude +-s/2, steady reciprocation": s * (1 - r) / 4}
    assert set(got) == set(expect)
    p = LRGParams()
    for name, dd in expect.items():
        x = got[name]
        assert x.deflection_needed_m == pytest.approx(dd, rel=1e-12)
        # the leaf that gives it by Eqs. 1-2 (independent route: Hooke with Eq. 1)
        k = p.hinge_modulus_pa * p.hinge_width_m * x.thickness_needed_m ** 3 / p.hinge_length_m ** 3
        assert p.f_mu_max_n / (p.hinge_count * k) == pytest.approx(dd, rel=1e-9)
        # every reading needs a deflection beyond the small-deflection range (> 0.3 l) and a
        # stress above the yield of 65Mn, or, with held ends (exact beam-column law), a leaf
        # longer than 0.33 m: n leaves of that length carry f_mumax at that deflection
        assert x.deflection_over_length > 0.3 and x.bending_stress_pa > p.hinge_yield_pa
        assert x.held_ends_length_m > 0.33
        from rsm_lrg.physics import hinge

        kl = hinge.hinge_stiffness(p.hinge_modulus_pa, p.hinge_width_m, 1e-4, x.held_ends_length_m)
        assert p.hinge_count * float(hinge.leaf_force(dd, kl, 1e-4)) == pytest.approx(p.f_mu_max_n, rel=1e-9)


@pytest.mark.slow
def test_thermal_cases_compare_the_maximum_rise():
    # 0.16 m (THK's shortest SHS15 rail), adiabatic base: the maximum rise meets 4.038 K within
    # 5 % (measured 4.07 K) but 95 % comes at ~1.4 h, not ~5 h; the documented 0.4 m rail gives
    # 2.88 K (-29 %); a heat path below the rail lowers the rise further.
    cases = paper_checks.thermal_cases(rail_lengths=(0.16, 0.4), cell_size_m=2e-3)
    by = {(c.rail_length_m, c.boundary): c for c in cases}
    short = by[(0.16, "adiabatic base")]
    assert short.meets_rise and not short.meets_time and short.time_to_95_percent_h < 1.5
    assert by[(0.4, "adiabatic base")].relative_to_paper == pytest.approx(-0.29, abs=0.01)
    for L in (0.16, 0.4):
        rises = [by[(L, b)].steady_max_rise_k for b, _, _ in paper_checks.RAIL_BOUNDARIES]
        assert rises[0] > rises[1] > rises[2]
    assert all(c.cannot_meet for c in cases)      # no case meets both statements
