"""The reciprocating trapezoidal profile against its exact kinematics."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rsm_lrg.physics import motion


def test_trapezoid_exact_numbers():
    # exact: s/v + v/a = 0.15 + 0.05 = 0.2 s per stroke; mean speed 2s / 2T = 0.375 m/s
    assert motion.stroke_time(0.075, 0.5, 10.0) == pytest.approx(0.2, rel=1e-14)
    assert motion.cycle_time(0.075, 0.5, 10.0, dwell=0.05) == pytest.approx(0.5, rel=1e-14)
    assert motion.mean_speed(0.075, 0.5, 10.0) == pytest.approx(0.375, rel=1e-14)
    assert not motion.is_triangular(0.075, 0.5, 10.0)


def test_triangular_case():
    # s < v^2/a: peak sqrt(a s), stroke time 2 sqrt(s/a) (exact)
    s, v, a = 0.01, 0.5, 10.0
    assert motion.is_triangular(s, v, a)
    assert motion.peak_velocity(s, v, a) == pytest.approx(np.sqrt(a * s), rel=1e-14)
    assert motion.stroke_time(s, v, a) == pytest.approx(2 * np.sqrt(s / a), rel=1e-14)
    # boundary s = v^2/a: both formulas agree
    assert motion.stroke_time(0.025, 0.5, 10.0) == pytest.approx(2 * np.sqrt(0.025 / 10.0), rel=1e-12)


@pytest.mark.parametrize("s,v,a,dw", [(0.075, 0.5, 10.0, 0.0), (0.04, 0.6, 40.0, 0.1), (0.005, 0.5, 10.0, 0.02)])
def test_profile_integrals(s, v, a, dw):
    T = float(motion.cycle_time(s, v, a, dw))
    t = np.linspace(0.0, T, 200_001)
    x, vel, acc = motion.reciprocating_profile(t, s, v, a, dw)
    dt = t[1] - t[0]
    # distance per stroke equals s: integral of |v| over a cycle is 2 s (trapezoid, 1e-6 rel)
    assert np.trapezoid(np.abs(vel), t) == pytest.approx(2 * s, rel=1e-6)
    # x is the integral of v, v the integral of a (exact kinematics; discretisation 1e-5)
    assert np.max(np.abs(x - np.concatenate([[0], np.cumsum(0.5 * (vel[1:] + vel[:-1]) * dt)]))) < 1e-6 * s + 1e-12
    assert np.max(np.abs(vel - np.concatenate([[0], np.cumsum(0.5 * (acc[1:] + acc[:-1]) * dt)]))) < 1e-3 * v
    assert x.min() >= -1e-15 and x.max() <= s + 1e-15
    assert np.max(np.abs(vel)) <= min(v, np.sqrt(a * s)) + 1e-12
    assert np.trapezoid(np.abs(vel), t) / T == pytest.approx(motion.mean_speed(s, v, a, dw), rel=1e-6)
    # periodic
    x2, _, _ = motion.reciprocating_profile(t + T, s, v, a, dw)
    assert np.allclose(x, x2, atol=1e-12)


def test_dwell_holds_position():
    s, v, a, dw = 0.05, 0.5, 20.0, 0.1
    ts = float(motion.stroke_time(s, v, a))
    t = np.linspace(ts + 1e-6, ts + dw - 1e-6, 11)
    x, vel, acc = motion.reciprocating_profile(t, s, v, a, dw)
    assert np.allclose(x, s) and np.all(vel == 0) and np.all(acc == 0)


@given(s=st.floats(1e-3, 0.2), v=st.floats(0.05, 2.0), a=st.floats(1.0, 100.0))
@settings(max_examples=60)
def test_vectorised_cycle_quantities(s, v, a):
    S = np.array([s, 2 * s])
    T = motion.cycle_time(S, v, a)
    assert T.shape == (2,) and T[1] > T[0]
    assert motion.mean_speed(s, v, a) <= v
    x_end, v_end, _ = motion.stroke_profile(motion.stroke_time(s, v, a), s, v, a)
    assert x_end == pytest.approx(s, rel=1e-12) and v_end == 0


def test_motion_profile_validation():
    m = motion.MotionProfile(0.075, 0.5, 10.0)
    assert m.cycle_time == pytest.approx(0.4) and m.mean_speed == pytest.approx(0.375)
    with pytest.raises(ValueError, match="stroke_m"):
        motion.MotionProfile(0.0, 0.5, 10.0)
    with pytest.raises(ValueError, match="dwell_s"):
        motion.MotionProfile(0.1, 0.5, 10.0, -1.0)
