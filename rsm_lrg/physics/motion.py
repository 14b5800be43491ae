"""Reciprocating point-to-point motion of the working stage (Eqs. 15-16).

One stroke moves the stage by ``s`` with a trapezoidal velocity profile: constant acceleration
``a`` up to the velocity ``v``, cruise, constant deceleration ``a`` to rest. When the stroke is
too short to reach ``v`` (``s < v²/a``) the profile is triangular with peak ``sqrt(a·s)``. A
cycle is: forward stroke, dwell, return stroke, dwell (``dwell`` ≥ 0 at each end).

Cycle-level quantities (:func:`stroke_time`, :func:`cycle_time`, :func:`peak_velocity`,
:func:`mean_speed`) broadcast over arrays of ``s``, ``v``, ``a``, ``dwell``;
:func:`reciprocating_profile` gives x, ẋ (Eq. 15) and ẍ (Eq. 16) at times ``t``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = [
    "is_triangular", "peak_velocity", "accel_time", "stroke_time", "cycle_time", "mean_speed",
    "mean_square_speed",
    "stroke_profile", "reciprocating_profile", "MotionProfile",
]


def _f(x):
    return np.asarray(x, dtype=float)


def is_triangular(stroke, velocity, acceleration):
    """True where the stroke is too short to reach ``velocity`` (``s < v²/a``)."""
    return _f(stroke) < _f(velocity) ** 2 / _f(acceleration)


def peak_velocity(stroke, velocity, acceleration):
    """Peak speed of a stroke [m/s]: ``min(v, sqrt(a·s))``.

    >>> float(peak_velocity(0.004, 0.5, 10.0))
    0.2
    """
    return np.minimum(_f(velocity), np.sqrt(_f(acceleration) * _f(stroke)))


def accel_time(stroke, velocity, acceleration):
    """Duration of the acceleration (and of the deceleration) ramp [s]."""
    return peak_velocity(stroke, velocity, acceleration) / _f(acceleration)


def stroke_time(stroke, velocity, acceleration):
    """Duration of one stroke [s]: ``s/v + v/a`` (trapezoid) or ``2·sqrt(s/a)`` (triangle).

    >>> round(float(stroke_time(0.075, 0.5, 10.0)), 6)
    0.2
    >>> round(float(stroke_time(0.004, 0.5, 10.0)), 6)
    0.04
    """
    vp = peak_velocity(stroke, velocity, acceleration)
    return _f(stroke) / vp + vp / _f(acceleration)


def cycle_time(stroke, velocity, acceleration, dwell=0.0):
    """Duration of one reciprocating cycle [s]: ``2·(stroke time + dwell)``.

    >>> round(float(cycle_time(0.075, 0.5, 10.0, 0.1)), 6)
    0.6
    """
    return 2.0 * (stroke_time(stroke, velocity, acceleration) + _f(dwell))


def mean_speed(stroke, velocity, acceleration, dwell=0.0):
    """Mean speed of the stage over a cycle [m/s]: ``2·s / cycle time``.

    >>> round(float(mean_speed(0.075, 0.5, 10.0)), 6)
    0.375
    """
    return 2.0 * _f(stroke) / cycle_time(stroke, velocity, acceleration, dwell)


def mean_square_speed(stroke, velocity, acceleration, dwell=0.0):
    """Mean of ẋ² over a reciprocating cycle [m²/s²] (trapezoidal or triangular profile).

    Per stroke ∫ẋ² dt = v_p·s − v_p³/(3a) with v_p the peak speed; twice per cycle. Times a
    viscous friction c_v it is the mean viscous friction power of a carriage that follows the
    stage (Eq. 8 with a speed-proportional friction force).

    >>> round(float(mean_square_speed(0.05, 0.5, 30.0)), 5)
    0.20238
    >>> round(float(mean_square_speed(0.004, 0.5, 10.0)), 6)   # triangle: (2/3)·a·s / 2
    0.013333
    """
    vp = peak_velocity(stroke, velocity, acceleration)
    per_stroke = vp * _f(stroke) - vp ** 3 / (3.0 * _f(acceleration))
    return 2.0 * per_stroke / cycle_time(stroke, velocity, acceleration, dwell)


def stroke_profile(tau, stroke, velocity, acceleration):
    """Position [m], velocity [m/s] and acceleration [m/s²] of one stroke from 0 to ``s``.

    ``tau`` is the time since the start of the stroke [s]; before 0 the stage is at 0, after
    the stroke time at ``s`` (at rest). All arguments broadcast.
    """
    tau, s, a = np.broadcast_arrays(_f(tau), _f(stroke), _f(acceleration))
    vp = peak_velocity(s, velocity, a)
    ta = vp / a
    ts = s / vp + ta
    tc = ts - ta  # start of the deceleration
    tt = np.clip(tau, 0.0, ts)
    x = np.where(tt < ta, 0.5 * a * tt ** 2,
                 np.where(tt < tc, 0.5 * a * ta ** 2 + vp * (tt - ta),
                          s - 0.5 * a * (ts - tt) ** 2))
    v = np.where(tt < ta, a * tt, np.where(tt < tc, vp, a * (ts - tt)))
    acc = np.where(tt < ta, a, np.where(tt < tc, 0.0, -a))
    outside = (tau < 0) | (tau >= ts)
    v = np.where(outside, 0.0, v)
    acc = np.where(outside, 0.0, acc)
    return x, v, acc


def reciprocating_profile(t, stroke, velocity, acceleration, dwell=0.0):
    """x(t) [m], ẋ(t) [m/s] (Eq. 15) and ẍ(t) [m/s²] (Eq. 16) of the reciprocating stage.

    The stage starts at rest at 0, strokes to ``s``, dwells, returns to 0, dwells; repeated.

    >>> x, v, a = reciprocating_profile([0.1, 0.2, 0.3], 0.075, 0.5, 10.0)
    >>> [round(float(xi), 4) for xi in x]
    [0.0375, 0.075, 0.0375]
    """
    t, s, dw = np.broadcast_arrays(_f(t), _f(stroke), _f(dwell))
    ts = stroke_time(s, velocity, acceleration)
    period = 2.0 * (ts + dw)
    tm = np.mod(t, period)
    back = tm >= ts + dw
    tau = np.where(back, tm - ts - dw, tm)
    x, v, acc = stroke_profile(tau, s, velocity, acceleration)
    sign = np.where(back, -1.0, 1.0)
    return np.where(back, s - x, x), sign * v, sign * acc


@dataclass(frozen=True)
class MotionProfile:
    """A reciprocating trapezoidal profile (stroke [m], velocity [m/s], acceleration [m/s²],
    dwell at each end [s]).

    >>> m = MotionProfile(0.04, 0.5, 10.0)
    >>> m.triangular, round(m.cycle_time, 4), round(m.peak_velocity, 4)
    (False, 0.26, 0.5)
    """

    stroke_m: float
    velocity_m_s: float
    acceleration_m_s2: float
    dwell_s: float = 0.0

    def __post_init__(self):
        for name in ("stroke_m", "velocity_m_s", "acceleration_m_s2"):
            x = float(getattr(self, name))
            if not np.isfinite(x) or x <= 0:
                raise ValueError(f"{name} must be > 0, got {getattr(self, name)!r}")
            object.__setattr__(self, name, x)
        d = float(self.dwell_s)
        if not np.isfinite(d) or d < 0:
            raise ValueError(f"dwell_s must be >= 0, got {self.dwell_s!r}")
        object.__setattr__(self, "dwell_s", d)

    @property
    def triangular(self) -> bool:
        return bool(is_triangular(self.stroke_m, self.velocity_m_s, self.acceleration_m_s2))

    @property
    def peak_velocity(self) -> float:
        return float(peak_velocity(self.stroke_m, self.velocity_m_s, self.acceleration_m_s2))

    @property
    def stroke_time(self) -> float:
        return float(stroke_time(self.stroke_m, self.velocity_m_s, self.acceleration_m_s2))

    @property
    def cycle_time(self) -> float:
        return float(cycle_time(self.stroke_m, self.velocity_m_s, self.acceleration_m_s2, self.dwell_s))

    @property
    def mean_speed(self) -> float:
        return float(mean_speed(self.stroke_m, self.velocity_m_s, self.acceleration_m_s2, self.dwell_s))

    def __call__(self, t):
        """(x, ẋ, ẍ) at times ``t`` [s]."""
        return reciprocating_profile(t, self.stroke_m, self.velocity_m_s, self.acceleration_m_s2, self.dwell_s)
