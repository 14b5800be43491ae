"""Issue 4 "Done when" checks against the paper, with the shipped calibration
(data/calibration.toml): Table 4 fit, Fig. 9, a virtual Box-Behnken study."""

import numpy as np
import pandas as pd
import pytest

from rsm_lrg.datasets import data_path, load_table4
from rsm_lrg.surrogate import simulate
from rsm_lrg.surrogate.calibrate import load_calibration

PAPER_BOX = ["thickness_m=0.0001:0.0005", "stroke_m=0.04:0.06", "velocity_m_s=0.4:0.6", "acceleration_m_s2=20:40"]


@pytest.fixture(scope="module")
def cal():
    return load_calibration(data_path("calibration.toml"))


@pytest.fixture(scope="module")
def table4_runs():
    t4 = load_table4()
    return t4, simulate(t4, noise_sd=0)


def test_shipped_calibration_copies_are_identical():
    from pathlib import Path

    top = Path(__file__).resolve().parents[2] / "data" / "calibration.toml"
    assert top.read_bytes() == data_path("calibration.toml").read_bytes()


def test_calibration_is_physical(cal):
    assert 1 <= len(cal.parameters) <= 3
    for p in cal.parameters:
        assert p.lower <= p.value <= p.upper and p.unit and p.meaning
    assert cal.data == "table4.csv" and len(cal.data_sha256) == 64


def test_stored_figures_are_what_the_surrogate_gives_now(cal, table4_runs):
    # the file's R2 and predictions are reproduced by simulate() with the default calibration
    t4, runs = table4_runs
    obs = t4.tcr_c_per_min.to_numpy()
    pred = runs.tcr_c_per_min.to_numpy()
    r2 = 1 - np.sum((obs - pred) ** 2) / np.sum((obs - obs.mean()) ** 2)
    np.testing.assert_allclose(pred, cal.predicted, rtol=1e-6)
    assert r2 == pytest.approx(cal.r2, abs=1e-6)


def test_calibrated_fit_to_table4_reached_figures(cal):
    # Figures reached with two calibrated parameters (Table 4, 27 runs, noise-free; issue 34: both
    # carriages on one rail and base, no drive heat, the ball contacts within 3x of contact mechanics;
    # v6-alone, the other stage at rest, chosen by AICc over v6 in every fold): R2 0.576, leave-one-out
    # R2 0.536 with every fold recalibrated from scratch and the model chosen inside every fold.
    # Pinned here so they cannot silently get worse.
    assert cal.model == "v6-alone" and cal.selected_from == ("v6", "v6-alone")
    assert len(cal.loo_models) == cal.n == 27
    assert cal.r2 >= 0.575
    assert cal.loo_r2 >= 0.535
    v = cal.parameter_values()
    assert v["two_carriage"] is True and v["heat_balance"] is True
    assert not any(k.startswith("drive_") for k in v)


@pytest.mark.slow
@pytest.mark.parametrize("fold", [6])
def test_a_loo_fold_is_a_calibration_from_scratch(cal, fold):
    # issue 24 "Done when": calibrate on the other 26 runs, then simulate with that calibration,
    # predicts the run left out as the shipped file's loo_predicted says (1e-3 relative). Fold 6
    # is the run the earlier, leaking LOO moved most (0.0477 -> 0.0471).
    from rsm_lrg.surrogate.calibrate import calibrate

    t4 = load_table4()
    rest = t4.drop(index=fold).reset_index(drop=True)
    # the same procedure as the shipped file's: its model, or its AICc choice among its candidates
    c26 = calibrate(rest[["thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2", "tcr_c_per_min"]],
                    loo=False, model=cal.model, select=list(cal.selected_from) or None)
    if cal.loo_models:
        assert c26.model == cal.selected_from[cal.loo_models[fold]]
    got = simulate(t4.iloc[[fold]][["thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2"]], noise_sd=0,
                   calibration=c26)
    assert float(got.tcr_c_per_min.iloc[0]) == pytest.approx(cal.loo_predicted[fold], rel=1e-3)


@pytest.mark.slow
def test_the_readme_calibrate_command_reproduces_the_shipped_file(cal, tmp_path):
    # issue 24 "Done when" (issue 34: the candidates v6, v6-alone): the README's `rsm-lrg calibrate
    # data/table4.csv --response tcr_c_per_min --select v6,v6-alone -o data/calibration.toml --force` regenerates the
    # shipped file (here written elsewhere; every number compared, to what another CPU's
    # last bits can move through the least squares)
    from rsm_lrg.cli import main

    out = tmp_path / "calibration.toml"
    assert main(["calibrate", str(data_path("table4.csv")), "--response", "tcr_c_per_min", "--select",
                 "v6,v6-alone", "-o", str(out), "--no-progress"]) == 0
    new = load_calibration(out)
    assert (new.model, new.selected_from, new.loo_models, new.data_sha256) == (
        cal.model, cal.selected_from, cal.loo_models, cal.data_sha256)
    for a, b in zip(new.parameters, cal.parameters):
        assert a.name == b.name and a.value == pytest.approx(b.value, rel=1e-6)
        assert (a.ci_low, a.ci_high) == pytest.approx((b.ci_low, b.ci_high), rel=1e-5, nan_ok=True)
    assert (new.r2, new.loo_r2) == pytest.approx((cal.r2, cal.loo_r2), abs=1e-8)
    np.testing.assert_allclose(new.loo_predicted, cal.loo_predicted, rtol=1e-6)
    np.testing.assert_allclose(new.predicted, cal.predicted, rtol=1e-6)


@pytest.mark.xfail(strict=True, reason="issue 34: without the drive heat (which the paper rules out, Section 2.2) the "
                   "friction heat of the two-carriage rig has no thickness effect; leave-one-out R2 0.536")
def test_calibrated_fit_to_table4_issue_target_loo(cal):
    # issue 4 "Done when": leave-one-out R2 >= 0.75 against Table 4; issue 15: >= 0.84, above
    # the paper's own quadratic (Eq. 19 refitted: PRESS R2 0.818, DIGEST Section 5)
    assert cal.loo_r2 >= 0.84


@pytest.mark.xfail(strict=True, reason="issue 34: without the drive heat the physics fits Table 4 with R2 0.576")
def test_calibrated_fit_to_table4_issue_target_r2(cal):
    # issue 4 "Done when": R2 >= 0.85; issue 15: R2 >= 0.86 (no longer an expected failure:
    # the drive's friction heat conducted through the leaves gives the thickness effect)
    assert cal.r2 >= 0.86


@pytest.mark.xfail(strict=True, reason="issue 34: the ball contacts' conductance runs to its bound, three times the "
                   "Hertz/Yovanovich estimate (freed, to 20 W/K): the data want the friction heat out of the carriage "
                   "faster than contact mechanics allows")
def test_calibrated_parameters_are_inside_their_bounds_with_standard_errors(cal):
    # issue 15 "Done when": at most 3 parameters, none at a bound, each with a standard error
    import math

    assert len(cal.parameters) <= 3
    for p in cal.parameters:
        assert not p.at_bound and p.lower < p.value < p.upper
        assert math.isfinite(p.std_error) and 0 < p.std_error < abs(p.value)
    # issue 24: the stage parameter is not a node of the calibrator's grid (0, 2.5, 5, ... N s/m)
    # and carries a profile-likelihood interval around it (the Jacobian's s.e. is not its error)
    cv = next(p for p in cal.parameters if p.name == "viscous_friction_n_s_m")
    nodes = np.linspace(cv.lower, cv.upper, 13)
    assert np.min(np.abs(nodes - cv.value)) > 1e-3 * (cv.upper - cv.lower)
    assert cv.ci_method == "profile likelihood" and cv.ci_low < cv.value < cv.ci_high


def test_the_block_friction_is_off_its_bounds_and_off_the_grid(cal):
    # issue 34 (priority 4): no fitted parameter on a grid node; c_v inside its bounds with a
    # profile-likelihood interval around it (the contact conductance is at its 3x bound: xfail above)
    cv = next(p for p in cal.parameters if p.name == "viscous_friction_n_s_m")
    assert not cv.at_bound and cv.lower < cv.value < cv.upper
    nodes = np.linspace(cv.lower, cv.upper, 13)
    assert np.min(np.abs(nodes - cv.value)) > 1e-3 * (cv.upper - cv.lower)
    assert cv.ci_method == "profile likelihood" and cv.ci_low < cv.value < cv.ci_high
    g = next(p for p in cal.parameters if p.name == "ball_contact_conductance_w_k")
    assert g.upper == pytest.approx(3 * 0.3504) and g.value <= g.upper


def test_earlier_calibration_stays_loadable():
    # issue 15: the calibration shipped before (model v2) is kept as data/calibration_v2.toml
    v2 = load_calibration(data_path("calibration_v2.toml"))
    assert v2.model == "v2" and v2.r2 == pytest.approx(0.8285009144173278, rel=1e-12)
    assert v2.parameter_values()["hinge_membrane"] is False


def test_where_leaves_yield_in_the_table3_box_with_the_shipped_calibration():
    # issue 24: the 16 corners and the centre of the Table 3 box with the shipped calibration:
    # `hinge_yields` is true exactly where the exact clamp stress passes 65Mn's 785 MPa
    # (GB/T 1222-2016); the 0.3 and 0.5 mm leaves stay far below it, the 0.1 mm leaf passes it
    # at its fast corners (a limit of the design; the rows are kept and flagged)
    import itertools

    levels = [(1e-4, 5e-4), (0.04, 0.06), (0.4, 0.6), (20.0, 40.0)]
    rows = list(itertools.product(*levels)) + [(3e-4, 0.05, 0.5, 30.0)]
    d = pd.DataFrame(rows, columns=["thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2"])
    out = simulate(d, noise_sd=0)
    assert (out.hinge_yields == (out.hinge_peak_stress_pa > 785e6)).all()
    thick = out.thickness_m >= 3e-4
    assert not out.hinge_yields[thick].any() and out.hinge_yields[~thick].any()
    assert (out.hinge_peak_stress_pa[thick] < 0.5 * 785e6).all()


def test_uncalibrated_centre_run(cal):
    # Table 4 centre runs (0.034, 0.033, 0.034; Eq. 19 intercept 0.03367 degC/min), +-30 %
    d = pd.DataFrame({"thickness_m": [3e-4], "stroke_m": [0.05], "velocity_m_s": [0.5], "acceleration_m_s2": [30.0]})
    assert simulate(d, noise_sd=0, calibration=None).tcr_c_per_min[0] == pytest.approx(0.03367, rel=0.30)


def _fig9(**columns):
    # Section 4.2 / Fig. 9: v = 0.5 m/s, a = 10 m/s^2, strokes 0.075 / 0.06 / 0.04 m; the
    # paper does not give the hinge of the comparative test: Table 3 centre, 0.3 mm
    rows = [dict(thickness_m=3e-4, stroke_m=s, velocity_m_s=0.5, acceleration_m_s2=10.0, stage=st, **columns)
            for s in (0.075, 0.06, 0.04) for st in ("rfcms", "rms")]
    out = simulate(pd.DataFrame(rows), noise_sd=0)
    return out[out.stage == "rfcms"].reset_index(), out[out.stage == "rms"].reset_index()


@pytest.mark.xfail(strict=True, reason="issue 34, said plainly: with the friction heat alone (no drive heat, Section "
                   "2.2) both guides slide the same within a few tenths of a percent and the RMS's working stage, "
                   "bolted to its carriage, draws more heat away than the RFCMS's behind its leaves: the model puts "
                   "the RFCMS carriage 11 % warmer (0.0300 against 0.0269 degC/min at 0.075 m); the ordering v5 gave "
                   "rested on the drive heat")
def test_fig9_rms_hotter_than_rfcms():
    # Fig. 9 (measured): the RMS's TCR above the RFCMS's at every stroke
    rf, rms = _fig9()
    assert (rms.tcr_c_per_min > rf.tcr_c_per_min).all()


@pytest.mark.xfail(strict=True, reason="issue 15, model finding: with the default trapezoidal profile (jerk_time_s = "
                   "0: a step of the acceleration at each ramp), the elastic hinge at a flexure's damping (zeta "
                   "0.02) and the calibrated block friction the steps excite the frame's "
                   "hinge mode, the frame overshoots each stroke end and its carriage slides 0.04-0.2 % MORE "
                   "than the RMS's, so it wears that much more. A jerk-limited S-curve with jerk_time_s >= 10 ms "
                   "(about half the hinge period) restores the ordering (test_fig9_with_jerk_limited_strokes); the "
                   "paper does not give its profile. The paper's FEM (Section 3.2) has the RFCMS wearing 41 % "
                   "less, which needs a 7.7-31 mm hinge deflection (physics.paper_checks.wear_readings)")
def test_fig9_rms_wears_more_than_rfcms():
    rf, rms = _fig9()
    assert (rms.wear_volume_m3_per_h > rf.wear_volume_m3_per_h).all()


def test_fig9_with_jerk_limited_strokes():
    # Fig. 9 with S-curve strokes of jerk time 10 ms (jerk_time_s, default 0; Lambrechts et al.
    # 2005): the frame no longer overshoots the stroke ends, the RFCMS carriage slides
    # 0.10 / 0.03 / 0.23 % less than the RMS's 2 s (measured, vectorised integrator; the
    # event-driven reference agrees to 5e-6 relative, tests/physics/test_jerk_time.py), so the
    # RMS is both hotter (Fig. 9, measured) and wears more (Section 3.2, FEM) at every stroke.
    # Same shipped calibration, noise-free; both stages run the same profile.
    rf, rms = _fig9(jerk_time_s=0.01)
    assert (rms.wear_volume_m3_per_h > rf.wear_volume_m3_per_h).all()
    # issue 34: the temperature ordering no longer holds (the friction heat alone, see the xfail above)
    assert (rms.tcr_c_per_min < rf.tcr_c_per_min).all()
    np.testing.assert_allclose(rf.cycle_time_s, [0.42, 0.36, 0.28], rtol=1e-12)   # 2 (s/v + v/a + t_j)
    np.testing.assert_allclose(rms.cycle_time_s, rf.cycle_time_s, rtol=0)


def test_fig9_wear_of_the_two_stages_differs_by_the_hinge_swing_only():
    # what the physics does say (kinematic bound, tests/physics/test_dynamics.py): the carriage
    # sliding, and with the same load the Archard wear (Eq. 13), of the RFCMS is within 4 peak
    # leaf deflections per cycle of the RMS's 2 s; at 0.3 mm that is below 0.5 %
    rf, rms = _fig9()
    assert np.all(np.abs(rf.wear_volume_m3_per_h / rms.wear_volume_m3_per_h - 1) < 0.005)


@pytest.fixture(scope="module")
def virtual_study():
    # design -> simulate with the rig's reading noise -> fit (Section 4.3, Table 5)
    from rsm_lrg import box_behnken, fit

    design = box_behnken(PAPER_BOX, center=3, seed=2023).to_frame()
    runs = simulate(design, seed=2023)
    res = fit(runs, "tcr_c_per_min", factors=PAPER_BOX)
    return res, res.anova.set_index("source")


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason="issue 34: without the drive heat the model's thickness effect is negative "
                   "(coded A -0.0012 on Table 4's settings against the paper's +0.0037), so the virtual study's "
                   "minimum is at the thick leaf (A = +1); velocity is still the strongest factor and A and D "
                   "significant")
def test_virtual_box_behnken_study_finds_what_the_paper_found(virtual_study):
    res, an = virtual_study
    F = an.loc[["A", "B", "C", "D"], "f"]
    assert F.idxmax() == "C"                                   # velocity the strongest
    assert an.loc["A", "p"] < 0.05 and an.loc["D", "p"] < 0.05  # thickness, acceleration significant
    opt = res.optimize(goal="minimize")
    assert opt.coded == {"A": -1.0, "B": -1.0, "C": -1.0, "D": -1.0}   # minimum at the low corner


@pytest.mark.slow
def test_virtual_box_behnken_study_stroke_weakest(virtual_study):
    # Table 5: stroke the weakest factor. With the viscous friction acting on the carriage the
    # surrogate's F order is C > A > D > B at this seed (C > A > D > B or C > D > A > B over
    # seeds 1-7, stroke weakest at all of them; the paper's order is C > D > A > B).
    _, an = virtual_study
    assert an.loc[["A", "B", "C", "D"], "f"].idxmin() == "B"
