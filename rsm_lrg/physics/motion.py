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
    "mean_square_speed", "stroke_kinks", "scurve_stroke",
    "stroke_profile", "reciprocating_profile", "MotionProfile",
]


def _f(x):
    return np.asarray(x, dtype=float)


def is_triangular(stroke, velocity, acceleration):
    """True where the stroke is too short to reach ``velocity`` (``s < v²/a``)."""
    return _f(stroke) < _f(velocity) ** 2 / _f(acceleration)


def peak_velocity(stroke, velocity, acceleration, jerk_time=0.0):
    """Peak speed of a stroke [m/s]: ``min(v, sqrt(a·s))`` (trapezoid, ``jerk_time`` 0).

    With a jerk time t_j > 0 (S-curve): the trapezoid's speed averaged over the window of width
    t_j centred on the middle of its stroke, ``(x_T(t_s/2 + t_j/2) − x_T(t_s/2 − t_j/2))/t_j``
    (``v`` where the cruise lasts at least t_j).

    >>> float(peak_velocity(0.004, 0.5, 10.0))
    0.2
    >>> round(float(peak_velocity(0.004, 0.5, 10.0, jerk_time=0.04)), 6)   # window = whole stroke
    0.1
    """
    vp = np.minimum(_f(velocity), np.sqrt(_f(acceleration) * _f(stroke)))
    tj = _f(jerk_time)
    if not np.any(tj > 0):
        return vp
    s, a = _f(stroke), _f(acceleration)
    ta = vp / a
    ts = s / vp + ta
    tjs = np.where(tj > 0, tj, 1.0)
    mid = 0.5 * ts
    lo, _, _, _ = _trap(mid - 0.5 * tjs, s, vp, a, ta, ts)
    hi, _, _, _ = _trap(mid + 0.5 * tjs, s, vp, a, ta, ts)
    return np.where(tj > 0, (hi - lo) / tjs, vp)


def accel_time(stroke, velocity, acceleration):
    """Duration of the acceleration (and of the deceleration) ramp [s]."""
    return peak_velocity(stroke, velocity, acceleration) / _f(acceleration)


def stroke_time(stroke, velocity, acceleration, jerk_time=0.0):
    """Duration of one stroke [s]: ``s/v + v/a`` (trapezoid) or ``2·sqrt(s/a)`` (triangle),
    plus the jerk time t_j of an S-curve stroke (0: the trapezoid).

    >>> round(float(stroke_time(0.075, 0.5, 10.0)), 6)
    0.2
    >>> round(float(stroke_time(0.004, 0.5, 10.0)), 6)
    0.04
    """
    vp = peak_velocity(stroke, velocity, acceleration)
    out = _f(stroke) / vp + vp / _f(acceleration)
    tj = _f(jerk_time)
    return out + tj if np.any(tj != 0) else out


def cycle_time(stroke, velocity, acceleration, dwell=0.0, jerk_time=0.0):
    """Duration of one reciprocating cycle [s]: ``2·(stroke time + dwell)`` (the stroke time
    includes the jerk time t_j of an S-curve).

    >>> round(float(cycle_time(0.075, 0.5, 10.0, 0.1)), 6)
    0.6
    >>> round(float(cycle_time(0.075, 0.5, 10.0, 0.0, jerk_time=0.01)), 6)
    0.42
    """
    return 2.0 * (stroke_time(stroke, velocity, acceleration, jerk_time) + _f(dwell))


def mean_speed(stroke, velocity, acceleration, dwell=0.0, jerk_time=0.0):
    """Mean speed of the stage over a cycle [m/s]: ``2·s / cycle time``.

    >>> round(float(mean_speed(0.075, 0.5, 10.0)), 6)
    0.375
    """
    return 2.0 * _f(stroke) / cycle_time(stroke, velocity, acceleration, dwell, jerk_time)


#: 3-point Gauss-Legendre nodes on [0, 1] and weights (exact for polynomials of degree 5).
_GL_X = 0.5 + 0.5 * np.array([-np.sqrt(0.6), 0.0, np.sqrt(0.6)])
_GL_W = np.array([5.0, 8.0, 5.0]) / 18.0


def mean_square_speed(stroke, velocity, acceleration, dwell=0.0, jerk_time=0.0):
    """Mean of ẋ² over a reciprocating cycle [m²/s²] (trapezoidal, triangular or S-curve profile).

    Trapezoid / triangle: per stroke ∫ẋ² dt = v_p·s − v_p³/(3a) with v_p the peak speed; twice
    per cycle. S-curve (jerk time t_j > 0): ẋ_J is piecewise quadratic between the kinks of
    :func:`stroke_kinks`, so ∫ẋ_J² dt is summed exactly by 3-point Gauss-Legendre quadrature
    on each piece. Times a viscous friction c_v it is the mean viscous friction power of a
    carriage that follows the stage (Eq. 8 with a speed-proportional friction force).

    >>> round(float(mean_square_speed(0.05, 0.5, 30.0)), 5)
    0.20238
    >>> round(float(mean_square_speed(0.004, 0.5, 10.0)), 6)   # triangle: (2/3)·a·s / 2
    0.013333
    """
    vp = peak_velocity(stroke, velocity, acceleration)
    per_stroke = vp * _f(stroke) - vp * vp * vp / (3.0 * _f(acceleration))
    tj = _f(jerk_time)
    if np.any(tj > 0):
        per_stroke = np.where(tj > 0, _scurve_square_integral(stroke, velocity, acceleration, tj), per_stroke)
    return 2.0 * per_stroke / cycle_time(stroke, velocity, acceleration, dwell, jerk_time)


def stroke_kinks(stroke, velocity, acceleration, jerk_time=0.0):
    """Times [s] since the start of a stroke where ẍ has a step (trapezoid) or a kink
    (S-curve): ``0, t_a, t_s − t_a, t_s`` and, for t_j > 0, the same plus t_j (sorted, last
    axis; 4 or 8 entries, some may coincide).

    >>> [round(float(x), 3) for x in stroke_kinks(0.075, 0.5, 10.0, 0.01)]
    [0.0, 0.01, 0.05, 0.06, 0.15, 0.16, 0.2, 0.21]
    """
    s, a = np.broadcast_arrays(_f(stroke), _f(acceleration))
    vp = peak_velocity(s, velocity, a)
    ta = vp / a
    ts = s / vp + ta
    base = np.stack(np.broadcast_arrays(0.0 * ts, ta, ts - ta, ts), axis=-1)
    tj = _f(jerk_time)
    if not np.any(tj > 0):
        return base
    return np.sort(np.concatenate([base, base + np.expand_dims(np.broadcast_to(tj, ts.shape), -1)], axis=-1),
                   axis=-1)


def _scurve_square_integral(stroke, velocity, acceleration, jerk_time):
    """∫ẋ_J² dτ over one S-curve stroke [m²/s] (exact: Gauss-Legendre on each piece)."""
    s, v, a, tj = np.broadcast_arrays(_f(stroke), _f(velocity), _f(acceleration), _f(jerk_time))
    kinks = stroke_kinks(s, v, a, tj)
    vp = peak_velocity(s, v, a)
    ta = vp / a
    ts = s / vp + ta
    tjs = np.where(tj > 0, tj, 1.0)
    total = np.zeros(s.shape)
    for i in range(kinks.shape[-1] - 1):
        t0, t1 = kinks[..., i], kinks[..., i + 1]
        for xg, wg in zip(_GL_X, _GL_W):
            tau = t0 + xg * (t1 - t0)
            x1, _, _, _ = _trap(tau, s, vp, a, ta, ts)
            x0, _, _, _ = _trap(tau - tjs, s, vp, a, ta, ts)
            total = total + wg * (t1 - t0) * ((x1 - x0) / tjs) ** 2
    return total


def _trap(tau, s, vp, a, ta, ts):
    """Trapezoidal stroke at ``tau`` (any real; 0 before, ``s`` after): position, velocity,
    acceleration and the time integral of the position from 0, F(τ) = ∫_0^τ x_T du (closed
    form, piecewise cubic; F(t_s) = s·t_s/2 by the stroke's symmetry)."""
    tt = np.clip(tau, 0.0, ts)
    tc = ts - ta
    x = np.where(tt < ta, 0.5 * a * tt ** 2,
                 np.where(tt < tc, 0.5 * a * ta ** 2 + vp * (tt - ta), s - 0.5 * a * (ts - tt) ** 2))
    v = np.where(tt < ta, a * tt, np.where(tt < tc, vp, a * (ts - tt)))
    acc = np.where(tt < ta, a, np.where(tt < tc, 0.0, -a))
    outside = (tau < 0) | (tau >= ts)
    v = np.where(outside, 0.0, v)
    acc = np.where(outside, 0.0, acc)
    r = ts - tt
    F = np.where(tt < ta, a * tt * tt * tt / 6.0,
                 np.where(tt < tc, a * ta * ta * ta / 6.0 + 0.5 * a * ta ** 2 * (tt - ta) + 0.5 * vp * (tt - ta) ** 2,
                          0.5 * s * ts - s * r + a * r * r * r / 6.0))
    F = F + s * np.maximum(tau - ts, 0.0)
    return x, v, acc, F


def scurve_stroke(tau, stroke, velocity, acceleration, jerk_time):
    """Position [m], velocity [m/s] and acceleration [m/s²] of one S-curve stroke from 0 to
    ``s``: the trapezoidal stroke convolved with a box of width ``jerk_time`` t_j > 0 [s].

    ``tau`` is the time since the start of the stroke [s]; before 0 the stage is at 0, from
    ``stroke time + t_j`` on at ``s`` (at rest). All arguments broadcast.

    >>> x, v, acc = scurve_stroke([0.0, 0.105, 0.21], 0.075, 0.5, 10.0, 0.01)
    >>> [round(float(xi), 6) for xi in x], [round(float(vi), 6) for vi in v]
    ([0.0, 0.0375, 0.075], [0.0, 0.5, 0.0])
    """
    tau, s, v, a, tj = np.broadcast_arrays(_f(tau), _f(stroke), _f(velocity), _f(acceleration), _f(jerk_time))
    if np.any(tj <= 0):
        raise ValueError("scurve_stroke needs a jerk time > 0 (use stroke_profile for the trapezoid)")
    vp = peak_velocity(s, v, a)
    ta = vp / a
    ts = s / vp + ta
    x1, v1, a1, F1 = _trap(tau, s, vp, a, ta, ts)
    x0, v0, a0, F0 = _trap(tau - tj, s, vp, a, ta, ts)
    # the difference quotient of F cancels digits near the ends of the stroke: it may pass
    # 0 or s by a few ulps of F (seen: 5e-14 m past s), so it is held to the stroke
    x = np.clip((F1 - F0) / tj, 0.0, s)
    vel = (x1 - x0) / tj
    acc = (v1 - v0) / tj
    before, after = tau <= 0, tau >= ts + tj
    x = np.where(before, 0.0, np.where(after, s, x))
    vel = np.where(before | after, 0.0, vel)
    acc = np.where(before | after, 0.0, acc)
    return x, vel, acc


def stroke_profile(tau, stroke, velocity, acceleration, jerk_time=0.0):
    """Position [m], velocity [m/s] and acceleration [m/s²] of one stroke from 0 to ``s``.

    ``tau`` is the time since the start of the stroke [s]; before 0 the stage is at 0, after
    the stroke time at ``s`` (at rest). All arguments broadcast. ``jerk_time`` > 0: the
    S-curve stroke of :func:`scurve_stroke` (where it is > 0).
    """
    tj = _f(jerk_time)
    if np.any(tj > 0):
        xt, vt, at = stroke_profile(tau, stroke, velocity, acceleration)
        tjs = np.where(tj > 0, tj, 1.0)
        xj, vj, aj = scurve_stroke(tau, stroke, velocity, acceleration, tjs)
        on = np.broadcast_to(tj > 0, np.shape(xj))
        return np.where(on, xj, xt), np.where(on, vj, vt), np.where(on, aj, at)
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


def reciprocating_profile(t, stroke, velocity, acceleration, dwell=0.0, jerk_time=0.0):
    """x(t) [m], ẋ(t) [m/s] (Eq. 15) and ẍ(t) [m/s²] (Eq. 16) of the reciprocating stage.

    The stage starts at rest at 0, strokes to ``s``, dwells, returns to 0, dwells; repeated.
    ``jerk_time`` > 0: S-curve strokes (:func:`scurve_stroke`), each ``jerk_time`` longer.

    >>> x, v, a = reciprocating_profile([0.1, 0.2, 0.3], 0.075, 0.5, 10.0)
    >>> [round(float(xi), 4) for xi in x]
    [0.0375, 0.075, 0.0375]
    """
    t, s, dw = np.broadcast_arrays(_f(t), _f(stroke), _f(dwell))
    ts = stroke_time(s, velocity, acceleration, jerk_time)
    period = 2.0 * (ts + dw)
    tm = np.mod(t, period)
    back = tm >= ts + dw
    tau = np.where(back, tm - ts - dw, tm)
    x, v, acc = stroke_profile(tau, s, velocity, acceleration, jerk_time)
    sign = np.where(back, -1.0, 1.0)
    return np.where(back, s - x, x), sign * v, sign * acc


@dataclass(frozen=True)
class MotionProfile:
    """A reciprocating trapezoidal profile (stroke [m], velocity [m/s], acceleration [m/s²],
    dwell at each end [s]; jerk time [s], > 0 for S-curve strokes).

    >>> m = MotionProfile(0.04, 0.5, 10.0)
    >>> m.triangular, round(m.cycle_time, 4), round(m.peak_velocity, 4)
    (False, 0.26, 0.5)
    """

    stroke_m: float
    velocity_m_s: float
    acceleration_m_s2: float
    dwell_s: float = 0.0
    jerk_time_s: float = 0.0

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
        j = float(self.jerk_time_s)
        if not np.isfinite(j) or j < 0:
            raise ValueError(f"jerk_time_s must be >= 0, got {self.jerk_time_s!r}")
        object.__setattr__(self, "jerk_time_s", j)

    @property
    def triangular(self) -> bool:
        return bool(is_triangular(self.stroke_m, self.velocity_m_s, self.acceleration_m_s2))

    @property
    def peak_velocity(self) -> float:
        return float(peak_velocity(self.stroke_m, self.velocity_m_s, self.acceleration_m_s2, self.jerk_time_s))

    @property
    def stroke_time(self) -> float:
        return float(stroke_time(self.stroke_m, self.velocity_m_s, self.acceleration_m_s2, self.jerk_time_s))

    @property
    def cycle_time(self) -> float:
        return float(cycle_time(self.stroke_m, self.velocity_m_s, self.acceleration_m_s2, self.dwell_s,
                                self.jerk_time_s))

    @property
    def mean_speed(self) -> float:
        return float(mean_speed(self.stroke_m, self.velocity_m_s, self.acceleration_m_s2, self.dwell_s,
                                self.jerk_time_s))

    @property
    def mean_square_speed(self) -> float:
        return float(mean_square_speed(self.stroke_m, self.velocity_m_s, self.acceleration_m_s2, self.dwell_s,
                                       self.jerk_time_s))

    def __call__(self, t):
        """(x, ẋ, ẍ) at times ``t`` [s]."""
        return reciprocating_profile(t, self.stroke_m, self.velocity_m_s, self.acceleration_m_s2, self.dwell_s,
                                     self.jerk_time_s)
