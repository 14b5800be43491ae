"""The surrogate with both carriages on one rail (two_carriage = true, calibration model v6)."""

import numpy as np
import pandas as pd
import pytest

from rsm_lrg import simulate
from rsm_lrg.physics.contact import ball_contact_conductance
from rsm_lrg.physics.params import LRGParams
from rsm_lrg.physics.rig import rig_report
from rsm_lrg.surrogate.calibrate import BALL_CONTACT_HERTZ, HERTZ_CONTACT_W_K, MODELS

CAL = {"heat_balance": True, "two_carriage": True, "viscous_friction_n_s_m": 1.5,
       "ball_contact_conductance_w_k": 0.7}
ROWS = pd.DataFrame({"thickness_m": [1e-4, 5e-4, 3e-4, 3e-4], "stroke_m": [0.04, 0.06, 0.05, 0.05],
                     "velocity_m_s": [0.6, 0.4, 0.5, 0.5], "acceleration_m_s2": [40.0, 20.0, 30.0, 30.0],
                     "stage": ["rfcms", "rfcms", "rfcms", "rms"]})


def test_the_contact_bounds_are_within_3x_of_contact_mechanics():
    est = ball_contact_conductance(LRGParams().to_dict()).series_w_k
    assert HERTZ_CONTACT_W_K == pytest.approx(est, rel=1e-3)
    assert BALL_CONTACT_HERTZ.lower == pytest.approx(est / 3, rel=1e-3)
    assert BALL_CONTACT_HERTZ.upper == pytest.approx(3 * est, rel=1e-3)
    for m in ("v6", "v6-alone"):
        assert len(MODELS[m].parameters) <= 3
        assert dict(MODELS[m].fixed)["two_carriage"] is True


def test_surrogate_equals_the_physics_rig_report():
    # an independent route: rig_report computes both stages' friction power from cycle_metrics and the
    # rises from the network's responses; the surrogate from its own row model (Eq. 18 over 50 min)
    out = simulate(ROWS, noise_sd=0, calibration=CAL)
    p = LRGParams().with_overrides(**CAL)
    for i, row in ROWS.iterrows():
        r = rig_report(p, levels=((row.thickness_m,), (row.stroke_m,), (row.velocity_m_s,),
                                  (row.acceleration_m_s2,))).rows[0]
        want = r.rfcms_tcr_c_per_min if row.stage == "rfcms" else r.rms_tcr_c_per_min
        assert out.tcr_c_per_min[i] == pytest.approx(want, rel=1e-9)
        assert out.heat_w[i] == pytest.approx(r.power_rfcms_w if row.stage == "rfcms" else r.power_rms_w, rel=1e-9)


def test_the_other_stage_adds_its_heat_and_at_rest_gives_none():
    on = simulate(ROWS, noise_sd=0, calibration=CAL)
    off = simulate(ROWS, noise_sd=0, calibration=dict(CAL, other_stage_running=False))
    assert np.all(off.tcr_c_per_min < on.tcr_c_per_min)
    assert np.array_equal(off.heat_w, on.heat_w)  # heat_w: the row's own friction power


def test_no_drive_heat_in_the_two_carriage_rig():
    with pytest.raises(ValueError, match="no drive heat"):
        simulate(ROWS, noise_sd=0, calibration=dict(CAL, drive_viscous_n_s_m=1.0))
    with pytest.raises(ValueError, match="heat_balance"):
        simulate(ROWS, noise_sd=0, calibration=dict(CAL, heat_balance=False))


def test_the_calibration_reads_the_network_from_an_interpolant_equal_to_it():
    # calibrate evaluates the same rows at many contact conductances (evaluate_rows(memo=True)): the
    # network's outputs from a Chebyshev interpolant in ln g, against the network itself (memo=False)
    from rsm_lrg.surrogate.design_input import read_design_arrays
    from rsm_lrg.surrogate.runs import CONTACT_INTERP_W_K, evaluate_rows

    p = LRGParams().with_overrides(heat_balance=True, two_carriage=True)
    arr = read_design_arrays(ROWS, p)
    for g in np.geomspace(*CONTACT_INTERP_W_K, 5):
        cal = {"ball_contact_conductance_w_k": float(g), "viscous_friction_n_s_m": 2.0}
        a = evaluate_rows(arr, params=p, calibration=cal, memo=True)
        b = evaluate_rows(arr, params=p, calibration=cal, memo=False)
        for k in ("tcr_c_per_min", "steady_rise_k", "temperature_rise_k"):
            np.testing.assert_allclose(a[k], b[k], rtol=1e-10)
    assert HERTZ_CONTACT_W_K / 3 > CONTACT_INTERP_W_K[0] and 3 * HERTZ_CONTACT_W_K < CONTACT_INTERP_W_K[1]


def test_replicated_rows_share_one_solution_equal_to_each_alone():
    # a design repeating settings (in any order) gives every row what that row gives alone, and the
    # first bad row by position is named even when its settings sort after another bad row's
    rows = ROWS.iloc[[3, 0, 2, 0, 1, 3, 2]].reset_index(drop=True)
    out = simulate(rows, noise_sd=0, calibration=CAL)
    for i in range(len(rows)):
        one = simulate(rows.iloc[[i]].reset_index(drop=True), noise_sd=0, calibration=CAL)
        assert out.tcr_c_per_min[i] == one.tcr_c_per_min[0] and out.steady_rise_k[i] == one.steady_rise_k[0]
    bad = ROWS.copy()
    bad["carriage_spacing_m"] = [0.2, 0.01, 0.001, 0.2]  # rows 2 and 3 collide; row 3 sorts first (y)
    with pytest.raises(ValueError, match=r"^row 2: the two carriages collide"):
        simulate(bad, noise_sd=0, calibration=CAL)


@pytest.mark.parametrize("running", [True, False])
def test_the_compiled_rows_give_what_each_row_s_own_network_gives(monkeypatch, running):
    # runs.NETWORK_ROUTE "dense": each distinct row its own two_carriage_network object (the route before the
    # compiled rows); random rows of the Table 3 box, both stages, the other stage running or at rest
    from rsm_lrg.surrogate import runs

    rng = np.random.default_rng(8)
    n = 24
    rows = pd.DataFrame({"thickness_m": rng.uniform(1e-4, 5e-4, n), "stroke_m": rng.uniform(0.04, 0.06, n),
                         "velocity_m_s": rng.uniform(0.4, 0.6, n), "acceleration_m_s2": rng.uniform(20, 40, n),
                         "stage": np.where(np.arange(n) % 3 == 0, "rms", "rfcms"),
                         "test_duration_min": rng.uniform(5, 60, n)})
    cal = dict(CAL, other_stage_running=running)
    runs.clear_row_caches()
    new = simulate(rows, noise_sd=0.03, seed=4, calibration=cal)
    monkeypatch.setattr(runs, "NETWORK_ROUTE", "dense")
    runs.clear_row_caches()
    old = simulate(rows, noise_sd=0.03, seed=4, calibration=cal)
    runs.clear_row_caches()
    for col in ("tcr_c_per_min", "temperature_rise_k", "steady_rise_k"):
        np.testing.assert_allclose(new[col], old[col], rtol=1e-12, atol=0)
