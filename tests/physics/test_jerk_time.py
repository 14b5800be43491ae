"""Optional jerk-limited (S-curve) strokes, parameter ``jerk_time_s``.

Reference numbers: exact kinematics of the box-convolved trapezoid (checked here by numerical
integration), the event-driven reference :func:`simulate_stage` (DOP853, breakpoints at the
S-curve's kinks), and, for ``jerk_time_s`` = 0, the numbers of the trapezoid-only code
(commit 89d203b, before the parameter existed).
"""

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from rsm_lrg.physics import dynamics, motion
from rsm_lrg.physics.params import ASSUMPTIONS, PARAM_INFO, PHYSICAL_RANGES, LRGParams

STROKES = np.array([0.075, 0.06, 0.04])  # Fig. 9 (Section 4.2)


# ---- the parameter --------------------------------------------------------------------
def test_parameter_is_documented_and_off_by_default():
    info = PARAM_INFO["jerk_time_s"]
    assert info["value"] == 0.0 and info["unit"] == "s" and info["source"] == "ASSUMPTION"
    assert "Lambrechts" in ASSUMPTIONS["jerk_time_s"] and "not stated" in ASSUMPTIONS["jerk_time_s"]
    assert LRGParams().jerk_time_s == 0.0 and PHYSICAL_RANGES["jerk_time_s"] == (0.0, 1.0)
    assert LRGParams(jerk_time_s=0.01).jerk_time_s == 0.01
    with pytest.raises(ValueError, match="jerk_time_s must be >= 0"):
        LRGParams(jerk_time_s=-0.001)
    with pytest.raises(ValueError, match="physical range"):
        LRGParams(jerk_time_s=2.0)
    with pytest.raises(ValueError, match="jerk_time_s"):
        motion.MotionProfile(0.075, 0.5, 10.0, jerk_time_s=-1.0)


# ---- the S-curve stroke ---------------------------------------------------------------
@pytest.mark.slow
@given(s=st.floats(1e-3, 0.2), v=st.floats(0.05, 2.0), a=st.floats(1.0, 100.0), frac=st.floats(0.05, 2.0))
@example(s=0.17508166158463365, v=0.05, a=76.62737912821143, frac=0.3859379730542597)  # passed s by 5e-14 m
@settings(max_examples=40, deadline=None)
def test_scurve_stroke_kinematics(s, v, a, frac):
    # t_j from 5 % to twice the trapezoid's ramp time (also longer than a triangle's stroke);
    # sampled finely enough to resolve the jerk ramps (at least 20 samples per t_j)
    tj = frac * float(motion.accel_time(s, v, a))
    T = float(motion.stroke_time(s, v, a, tj))
    assert T == pytest.approx(float(motion.stroke_time(s, v, a)) + tj, rel=1e-14)
    t = np.linspace(-0.1 * T, 1.1 * T, int(min(4e5, max(4e4, 24 * T / tj))) + 1)
    x, vel, acc = motion.scurve_stroke(t, s, v, a, tj)
    dt = t[1] - t[0]
    # displaces exactly s, starts and ends at rest
    assert x[-1] == s and x[0] == 0.0 and vel[0] == vel[-1] == 0.0 and acc[0] == acc[-1] == 0.0
    assert float(motion.scurve_stroke(T, s, v, a, tj)[0]) == s
    # monotone, within [0, s]; acceleration bounded by a; speed bounded by the peak speed
    assert np.all(np.diff(x) >= -1e-15 * s) and x.min() >= 0.0 and x.max() <= s * (1 + 1e-14)
    assert np.max(np.abs(acc)) <= a * (1 + 1e-9)  # round-off of (ẋ_T(τ) − ẋ_T(τ−t_j))/t_j
    vp = float(motion.peak_velocity(s, v, a, tj))
    assert np.max(vel) <= vp * (1 + 1e-9) and np.max(vel) >= vp * (1 - 1e-6)
    # velocity and acceleration continuous: no jump larger than the jerk a/t_j (2a/t_j where
    # ramps overlap) allows over one sample
    assert np.max(np.abs(np.diff(vel))) <= a * dt * (1 + 1e-6) + 1e-9 * vp
    assert np.max(np.abs(np.diff(acc))) <= 2 * a / tj * dt * (1 + 1e-6) + 1e-9 * a
    # x is the integral of v, v the integral of a (trapezoidal rule: exact on the linear pieces
    # of ẍ, an error of at most (jump of the jerk)·dt²/8 at each of the 8 kinks)
    xi = np.concatenate([[0.0], np.cumsum(0.5 * (vel[1:] + vel[:-1]) * dt)])
    vi = np.concatenate([[0.0], np.cumsum(0.5 * (acc[1:] + acc[:-1]) * dt)])
    assert np.max(np.abs(x - xi)) <= 1e-6 * s
    assert np.max(np.abs(vel - vi)) <= 8 * (2 * a / tj) * dt ** 2 / 8 + 1e-9 * vp
    # mean square speed: exact quadrature against the sampled integral
    msq = float(motion.mean_square_speed(s, v, a, 0.0, tj)) * float(motion.cycle_time(s, v, a, 0.0, tj)) / 2
    assert msq == pytest.approx(np.trapezoid(vel ** 2, t), rel=1e-6)


def test_scurve_exact_numbers():
    # s = 0.075, v = 0.5, a = 10, t_j = 0.01: cruise 0.1 s >= t_j, so the peak stays 0.5 m/s; the
    # stroke lasts 0.2 + 0.01 s
    assert float(motion.peak_velocity(0.075, 0.5, 10.0, 0.01)) == pytest.approx(0.5, rel=1e-14)
    assert float(motion.cycle_time(0.075, 0.5, 10.0, 0.05, 0.01)) == pytest.approx(0.52, rel=1e-14)
    assert float(motion.mean_speed(0.075, 0.5, 10.0, 0.0, 0.01)) == pytest.approx(0.15 / 0.42, rel=1e-14)
    ks = motion.stroke_kinks(0.075, 0.5, 10.0, 0.01)
    np.testing.assert_allclose(ks, [0, 0.01, 0.05, 0.06, 0.15, 0.16, 0.2, 0.21], atol=1e-15)
    # window of the whole stroke: the mean speed of the trapezoid (s / t_s)
    assert float(motion.peak_velocity(0.004, 0.5, 10.0, 0.04)) == pytest.approx(0.1, rel=1e-12)
    # ∫ẋ_J² per stroke in closed form where t_j <= the ramp time and <= the cruise time (derived
    # by hand: the box lowers the speed at each of the two corners at the peak speed by an area
    # a·t_j²/24 (half the kink a times the box's variance t_j²/12), so ∫ẋ² loses 2·v·a·t_j²/24
    # there; the quadratic pieces add a²·t_j³/120 at each of the four corners):
    # v·s − v³/(3a) − v·a·t_j²/6 + a²·t_j³/30
    for s, v, a, tj in ((0.075, 0.5, 10.0, 0.01), (0.06, 0.6, 40.0, 0.005), (0.04, 0.5, 10.0, 0.03)):
        per_stroke = float(motion.mean_square_speed(s, v, a, 0.0, tj)) * float(motion.cycle_time(s, v, a, 0.0, tj)) / 2
        assert per_stroke == pytest.approx(v * s - v ** 3 / (3 * a) - v * a * tj ** 2 / 6 + a ** 2 * tj ** 3 / 30,
                                           rel=1e-13)
    m = motion.MotionProfile(0.075, 0.5, 10.0, 0.0, 0.01)
    assert m.cycle_time == pytest.approx(0.42) and m.peak_velocity == pytest.approx(0.5)
    x, vel, acc = m(np.array([0.105, 0.21 + 0.105]))
    np.testing.assert_allclose(x, [0.0375, 0.0375], rtol=1e-12)
    np.testing.assert_allclose(vel, [0.5, -0.5], rtol=1e-12)


def test_reciprocating_scurve_is_periodic_and_mixes_with_trapezoid_rows():
    s, v, a, dw, tj = 0.05, 0.5, 20.0, 0.03, 0.008
    T = float(motion.cycle_time(s, v, a, dw, tj))
    t = np.linspace(0.0, T, 5001)
    x, vel, _ = motion.reciprocating_profile(t, s, v, a, dw, tj)
    x2, vel2, _ = motion.reciprocating_profile(t + T, s, v, a, dw, tj)
    assert np.allclose(x, x2, atol=1e-12) and np.allclose(vel, vel2, atol=1e-10)
    assert np.trapezoid(np.abs(vel), t) == pytest.approx(2 * s, rel=1e-6)
    # an array of jerk times: rows with 0 are the trapezoid bit for bit
    xs, vs, accs = motion.stroke_profile(0.03, [0.05, 0.05], v, a, [0.0, tj])
    xt, vt, at = motion.stroke_profile(0.03, 0.05, v, a)
    assert xs[0] == xt and vs[0] == vt and accs[0] == at and xs[1] != xt


# ---- jerk time 0 is the code of before --------------------------------------------------
def test_zero_jerk_time_gives_the_numbers_of_the_trapezoid_code():
    # jerk_time_s 0 (scalar or column) is the trapezoid, bit for bit; the RMS row is exact
    p = LRGParams(viscous_friction_n_s_m=2.5)
    base = dynamics.cycle_metrics(STROKES, 0.5, 10.0, stage=["rfcms", "rfcms", "rms"], params=p, method="integrate")
    for extra in ({"jerk_time_s": 0.0}, {"jerk_time_s": np.zeros(3)}):
        m = dynamics.cycle_metrics(STROKES, 0.5, 10.0, stage=["rfcms", "rfcms", "rms"], params=p,
                                   method="integrate", **extra)
        for f in ("sliding_distance_m", "viscous_work_j", "peak_deflection_m"):
            assert np.array_equal(getattr(m, f), getattr(base, f)), f
    assert base.sliding_distance_m[2] == 0.08
    assert base.viscous_work_j[2] == pytest.approx(0.07916666666666668, rel=1e-13)
    assert float(motion.mean_square_speed(0.06, 0.5, 10.0, 0.02)) == pytest.approx(0.13596491228070176, rel=1e-15)


@pytest.mark.slow
def test_trapezoid_rows_are_unchanged_in_a_batch_with_scurve_rows():
    p = LRGParams(viscous_friction_n_s_m=2.5)
    alone = dynamics.cycle_metrics(STROKES, 0.5, 10.0, params=p, method="integrate")
    mixed = dynamics.cycle_metrics(np.r_[STROKES, STROKES], 0.5, 10.0, params=p, method="integrate",
                                   jerk_time_s=np.r_[np.zeros(3), np.full(3, 0.01)])
    for f in ("sliding_distance_m", "viscous_work_j", "peak_deflection_m", "cycle_time_s"):
        assert np.array_equal(getattr(mixed, f)[:3], getattr(alone, f)), f
    only = dynamics.cycle_metrics(STROKES, 0.5, 10.0, params=p.with_overrides(jerk_time_s=0.01), method="integrate")
    for f in ("sliding_distance_m", "viscous_work_j", "peak_deflection_m", "cycle_time_s"):
        assert np.array_equal(getattr(mixed, f)[3:], getattr(only, f)), f


# ---- the dynamics with S-curve strokes --------------------------------------------------
@pytest.mark.slow
@pytest.mark.parametrize("tj", [0.005, 0.01, 0.02])
def test_vectorised_scurve_matches_event_driven_reference(tj):
    # Reference: simulate_stage (DOP853 rtol 1e-10, exact events, S-curve kinks as breakpoints),
    # 5 cycles from rest, mean of the last two cycles. The compiled stepper (segments between
    # the S-curve's kinks, same 5 cycles) at its default h_rk = 0.6: 1e-6; the fixed-step NumPy
    # integrator (Hermite-cubic stage motion per step) at h = 0.3: 2e-5, at h = 0.1: 2e-6.
    p = LRGParams(viscous_friction_n_s_m=2.5, jerk_time_s=tj)
    ref = []
    for s in STROKES:
        h = dynamics.simulate_stage(p, n_cycles=5, stroke=s, velocity=0.5, acceleration=10.0,
                                    samples_per_cycle=50)
        assert h.cycle_time_s == pytest.approx(float(motion.cycle_time(s, 0.5, 10.0, 0.0, tj)), rel=1e-14)
        ref.append(h.sliding_per_cycle_m[-2:].mean())
    m = dynamics.cycle_metrics(STROKES, 0.5, 10.0, params=p, method="integrate", n_cycles=5, max_cycles=5)
    np.testing.assert_allclose(m.sliding_distance_m, ref, rtol=1e-6)
    for hh, tol in ((0.3, 2e-5), (0.1, 2e-6)):
        m = dynamics.cycle_metrics(STROKES, 0.5, 10.0, params=p, method="integrate", n_cycles=5, max_cycles=5, h=hh,
                                   integrator="fixed_step")
        np.testing.assert_allclose(m.sliding_distance_m, ref, rtol=tol)
        np.testing.assert_allclose(m.cycle_time_s, motion.cycle_time(STROKES, 0.5, 10.0, 0.0, tj), rtol=1e-15)


def test_rms_with_scurve_strokes_is_exact():
    # the RMS slides 2 s per cycle; its viscous work is c_v ∫ẋ² dt of the S-curve cycle
    p = LRGParams(viscous_friction_n_s_m=2.5, jerk_time_s=0.01)
    m = dynamics.cycle_metrics(0.06, 0.5, 10.0, stage="rms", params=p)
    T = float(motion.cycle_time(0.06, 0.5, 10.0, 0.0, 0.01))
    t = np.linspace(0.0, T, 200_001)
    _, vel, _ = motion.reciprocating_profile(t, 0.06, 0.5, 10.0, 0.0, 0.01)
    assert m.sliding_distance_m == 0.12 and m.cycle_time_s == pytest.approx(0.36, rel=1e-14)
    assert m.viscous_work_j == pytest.approx(2.5 * np.trapezoid(vel ** 2, t), rel=1e-7)
    h = dynamics.simulate_stage(p, n_cycles=2, stroke=0.06, rigid=True, samples_per_cycle=100)
    assert h.viscous_work_j == pytest.approx(float(m.viscous_work_j), rel=1e-14) and h.cycle_time_s == pytest.approx(T)


@pytest.mark.slow
def test_jerk_limit_removes_the_ringing_overshoot():
    # Model finding (issue 15 follow-up): at a flexure's damping (zeta 0.02) and c_v 2.5 N s/m
    # the trapezoid's acceleration steps excite the frame's ~47 Hz hinge mode and the RFCMS
    # carriage slides MORE than 2 s per cycle at every Fig. 9 stroke; a jerk time of 10 ms
    # (about half the hinge period, 20 % of the 50 ms ramp) makes it slide less at every stroke.
    p = LRGParams(viscous_friction_n_s_m=2.5)
    trap = dynamics.cycle_metrics(STROKES, 0.5, 10.0, params=p, method="integrate")
    assert np.all(trap.sliding_distance_m > 2 * STROKES)
    smooth = dynamics.cycle_metrics(STROKES, 0.5, 10.0, params=p, method="integrate", jerk_time_s=0.01)
    assert np.all(smooth.sliding_distance_m < 2 * STROKES)
