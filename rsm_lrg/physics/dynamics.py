"""Dynamics of the rigid-flexible coupling motion stage (Section 2.1, Fig. 1b).

Model
-----
The working stage follows the commanded reciprocating profile x_ws(t) (:mod:`.motion`; a
position-controlled drive). The rigid frame (mass m_f: its share of m_t plus the carriage) is
tied to it by n hinges of stiffness K_n (Eq. 1) and damping C_n, and rides on the guide with
Coulomb friction with stiction:

    m_f·ẍ_rf = n·K_n·(x_ws − x_rf) + C_n·(ẋ_ws − ẋ_rf) − f_µ − c_v·ẋ_rf,

sliding: ``f_µ = µ_k·F_z·sign(ẋ_rf)``; stuck (ẋ_rf = 0): the frame stays put while the hinge
force ``|F_h| ≤ f_µmax = µ_s·F_z`` (Eq. 2) and breaks away when it exceeds it. This is the
stick-slip state machine of Karnopp (1985) / Leine et al. (1998) ("switch model"), without a
velocity band: stop and breakaway are explicit events. F_z = F0 + m_t·g (the paper's load).
C_n = 2·ζ·sqrt(n·K_n·m_f) with the assumed modal damping ratio ζ. With leaves whose ends are
held (``hinge_membrane``, the default) the hinge force n·K_n·(x_ws − x_rf) is replaced by the
exact beam-column law of :func:`.hinge.leaf_force` (stiffening with the deflection). c_v is the viscous
(speed-proportional) friction of the lubricated, sealed block (``viscous_friction_n_s_m``,
0 in the paper's Coulomb-only model); it acts only while the carriage slides and its work
``∫c_v·ẋ_rf² dt`` is heat like the Coulomb work.

The rigid stage (RMS) is the stiff limit: the frame is the stage, so the carriage slides the
full stroke, ``2·s`` per cycle, and the friction work is ``µ_k·F_z·2·s``.

Three routes, checked against each other in ``tests/physics/test_dynamics.py``:

- :func:`simulate_stage` — the reference: event-driven integration (scipy ``solve_ivp``,
  DOP853, split at every kink of the profile, events at breakaway and stop) for one
  parameter set, to its periodic steady state, with the time history.
- :func:`cycle_metrics` with ``method="integrate"`` — the compiled stepper of :mod:`.stepper`
  (each row alone, order-8 Runge-Kutta steps of error-controlled length between the kinks of
  the profile, stops and breakaways located inside a step; a row's result does not depend on
  the rows integrated with it); for 10⁵-row virtual runs. ``integrator="compiled"`` keeps the
  same steps in equal lengths (the reference of the benchmark and of the equality test),
  ``integrator="fixed_step"`` the earlier vectorised NumPy integrator (exact linear steps with
  the hinge's tangent, ``ω·Δt ≤ h``).
- ``method="quasi_static"`` — the slow-motion limit, analytic: per stroke the stage first
  unbends the hinge from its rest deflection µ_k·F_z/(n·K_n) and bends it to the breakaway
  deflection Δδ = µ_s·F_z/(n·K_n); then the frame follows, so the carriage slides
  ``s − Δδ − µ_k·F_z/(n·K_n)`` per stroke (``s − 2·Δδ`` for µ_k = µ_s; Eq. 14's ``s − Δδ`` is
  the first stroke from a relaxed hinge). Valid when the hinge's natural period is short
  against the acceleration ramp (``ω_n·v/a ≫ 1``) and the frame's inertial force m_f·a is
  small against the hinge's travel (``m_f·a/(n·K_n) ≪ s``); ``method="auto"`` uses it where
  :func:`quasi_static_valid` holds and integrates the other rows.

Per cycle (in the periodic steady state): sliding distance of the carriage [m], friction work
``µ_k·F_z·sliding`` [J], peak hinge deflection [m], mean friction power [W].

References
----------
Karnopp, D. (1985), ASME J. Dyn. Syst. Meas. Control 107, 100-103 (stick-slip switch model).
Leine, R.I., van Campen, D.H., de Kraker, A., van den Steen, L. (1998), Nonlinear Dynamics 16,
41-54 (switch model, event-driven stick-slip).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, fields
from typing import Any

import numpy as np

from . import motion
from .hinge import hinge_stiffness, leaf_deflection
from .params import LRGParams, check_values, param_names
from .stepper import integrate_rows, leaf_dpsi, leaf_psi

__all__ = [
    "StageConstants", "stage_constants", "natural_frequency", "quasi_static_valid",
    "quasi_static_sliding_per_stroke", "CycleMetrics", "cycle_metrics", "StageHistory",
    "simulate_stage", "overconstraint_load", "carriage_load",
]

_MOTION_KEYS = ("stroke_m", "velocity_m_s", "acceleration_m_s2", "dwell_s")

#: Parameters that only the RFCMS uses (RMS rows may leave them empty).
_HINGE_SIDE = {"hinge_thickness_m", "hinge_width_m", "hinge_length_m", "hinge_modulus_pa", "hinge_count",
               "hinge_damping_ratio", "frame_mass_fraction", "overconstraint_misfit_m", "hinge_conductivity_w_mk",
               "hinge_yield_pa"}


# ------------------------------------------------------------------------------------------
# constants of the two-mass model
# ------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class StageConstants:
    """Arrays (or floats) of the model constants, one per row.

    k_n_m : total hinge stiffness n·K_n [N/m]; c_ns_m : C_n [N·s/m]; mass_kg : frame mass
    m_f [kg]; f_static_n : µ_s·F_z [N]; f_kinetic_n : µ_k·F_z [N]; viscous_ns_m : viscous
    friction c_v of the block [N·s/m]; leaf_thickness_m : thickness y of leaves with held ends
    [m], 0 for the small-deflection hinge of Eq. 1 (with held ends the hinge force is the exact
    beam-column law ``n·K_n·z·φ(z/y)`` of :func:`.hinge.leaf_force`, else ``n·K_n·z``).

    F_z includes the over-constraint load of the leaves (``overconstraint_misfit_m``).
    """

    k_n_m: Any
    c_ns_m: Any
    mass_kg: Any
    f_static_n: Any
    f_kinetic_n: Any
    viscous_ns_m: Any = 0.0
    leaf_thickness_m: Any = 0.0


def _columns(params: LRGParams | None, columns: dict[str, Any]) -> dict[str, Any]:
    p = params or LRGParams()
    names = set(param_names())
    out = p.to_dict()
    for k, v in columns.items():
        if k not in names:
            p.with_overrides(**{k: None})  # raises the "unknown parameter" error
        check_values(k, v)
        out[k] = np.asarray(v, dtype=float) if np.ndim(v) else v
    return out


def stage_constants(params: LRGParams | None = None, **columns) -> StageConstants:
    """Model constants from parameters; any parameter may be given as an array column.

    >>> c = stage_constants()
    >>> round(float(c.k_n_m)), round(float(c.f_static_n), 3), round(float(c.mass_kg), 3)
    (28485, 5.209, 0.325)
    """
    v = _columns(params, columns)
    k = v["hinge_count"] * hinge_stiffness(v["hinge_modulus_pa"], v["hinge_width_m"],
                                           v["hinge_thickness_m"], v["hinge_length_m"])
    yl = np.asarray(v["hinge_thickness_m"], dtype=float) * float(bool(v["hinge_membrane"]))
    m = v["frame_mass_fraction"] * np.asarray(v["stage_mass_kg"], dtype=float) + v["carriage_mass_kg"]
    load = carriage_load(v)
    c = 2.0 * np.asarray(v["hinge_damping_ratio"], dtype=float) * np.sqrt(k * m)
    return StageConstants(k, c, m, v["mu_s"] * load, v["mu_k"] * load, v["viscous_friction_n_s_m"], yl)


def overconstraint_load(values) -> Any:
    """Load that a clamping misfit e drives through the leaves' stiff in-plane direction into
    the guide, ``n·E·y·w³/l³·e`` [N] (in-plane bending of a fixed-guided leaf, Eq. 1 with w and
    y exchanged; proportional to the leaf thickness y).

    ``values``: a parameter dict (``LRGParams.to_dict()``, entries may be array columns).

    >>> round(float(overconstraint_load(dict(LRGParams().to_dict(), overconstraint_misfit_m=3e-6))), 2)
    94.95
    """
    v = values
    e = np.asarray(v["overconstraint_misfit_m"], dtype=float)
    return (v["hinge_count"] * hinge_stiffness(v["hinge_modulus_pa"], v["hinge_thickness_m"], v["hinge_width_m"],
                                               v["hinge_length_m"]) * e)


def carriage_load(values) -> Any:
    """Normal load of the carriage [N]: the paper's ``F0 + m_t·g`` (Eq. 2) plus the
    over-constraint load of :func:`overconstraint_load` (0 by default)."""
    v = values
    return (v["preload_n"] + np.asarray(v["stage_mass_kg"], dtype=float) * v["gravity_m_s2"]
            + overconstraint_load(v))


def natural_frequency(k_total, mass):
    """Natural angular frequency of the frame on its hinges ``ω_n = sqrt(n·K_n/m_f)`` [rad/s].

    >>> round(float(natural_frequency(28485.0, 0.325)), 1)
    296.1
    """
    return np.sqrt(np.asarray(k_total, dtype=float) / np.asarray(mass, dtype=float))


def quasi_static_valid(const: StageConstants, stroke, velocity, acceleration, *, fraction=None):
    """Where the quasi-static per-stroke sliding is accurate (boolean array).

    The hinge's whole lag, ``(f_µmax + µ_k·F_z + c_v·v + m_f·a)/(n·K_n)`` — breakaway, rest,
    viscous and inertial deflection — must stay below ``fraction`` of the stroke. Then neither the
    oscillation excited at the ramps (amplitude ≲ m_f·a/(n·K_n)) nor the stick-slip spread of
    the rest deflection (≤ (µ_s − µ_k)·F_z/(n·K_n)) can change the sliding per stroke by more
    than about ``fraction`` of it.
    """
    k, yl = np.asarray(const.k_n_m, dtype=float), np.asarray(const.leaf_thickness_m, dtype=float)
    if fraction is None:
        # 1 % for the small-deflection hinge (as calibrated in model v2); 0.2 % for leaves with
        # held ends: the stiffened hinge rings after each stop at a flexure's damping and the
        # frame overshoots by up to 1 % of the sliding on the Table 4 rows, which the
        # quasi-static limit misses (measured against the integrator)
        fraction = np.where(yl > 0, 0.002, 0.01)
    dyn = (np.asarray(const.viscous_ns_m, dtype=float) * np.asarray(velocity, dtype=float)
           + np.asarray(const.mass_kg) * np.asarray(acceleration, dtype=float))
    # with a stiffening hinge the deflections of the parts add to more than the deflection of
    # their sum: an upper bound of the lag
    lag = sum(leaf_deflection(f, k, yl) for f in (const.f_static_n, const.f_kinetic_n, dyn))
    return lag <= fraction * np.asarray(stroke, dtype=float)


def quasi_static_sliding_per_stroke(stroke, k_total, f_static, f_kinetic, leaf_thickness=0.0):
    """Carriage sliding per stroke in slow steady reciprocation [m].

    ``max(s − (f_µmax + µ_k·F_z)/(n·K_n), 0)``: the hinge goes from its rest deflection
    (kinetic friction held by stiction) through zero to the breakaway deflection before the
    frame moves (derivation in the module docstring and in :mod:`.wear`). With membrane
    leaves whose ends are held (``leaf_thickness`` y > 0) each deflection solves the exact
    beam-column law ``n·K_n·δ·φ(δ/y) = f`` (:func:`.hinge.leaf_deflection`).

    >>> round(float(quasi_static_sliding_per_stroke(0.075, 28485.0, 5.209, 3.473)) * 1e3, 4)  # mm
    74.6952
    """
    lag = (leaf_deflection(f_static, k_total, leaf_thickness)
           + leaf_deflection(f_kinetic, k_total, leaf_thickness))
    return np.maximum(np.asarray(stroke, dtype=float) - lag, 0.0)


# ------------------------------------------------------------------------------------------
# results
# ------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class CycleMetrics:
    """Per-cycle quantities in the periodic steady state (arrays, one entry per row).

    sliding_distance_m : carriage sliding distance per cycle [m] (integrated rows: mean of the
        last two cycles, equal to the last one once the response is periodic)
    friction_work_j : friction work per cycle, µ_k·F_z·sliding [J]
    peak_deflection_m : largest |x_ws − x_rf| over the cycle [m] (0 for the RMS)
    mean_friction_power_w : (friction work + viscous work) / cycle time [W]
    cycle_time_s : duration of the cycle [s]
    periodicity_error_m : |sliding of the last cycle − the one before| [m] (convergence check)
    method : "rms", "quasi_static" or "integrate" per row
    viscous_work_j : work of the block's viscous friction per cycle, ``∫c_v·ẋ_rf² dt`` [J]
        (0 without viscous friction; exact for the RMS, the stage's ∫c_v·ẋ_ws² dt scaled by the
        sliding share for quasi-static rows, trapezoidal in time for integrated rows)
    """

    sliding_distance_m: np.ndarray
    friction_work_j: np.ndarray
    peak_deflection_m: np.ndarray
    mean_friction_power_w: np.ndarray
    cycle_time_s: np.ndarray
    periodicity_error_m: np.ndarray
    method: np.ndarray | None = field(default=None)
    viscous_work_j: np.ndarray | None = field(default=None)

    def to_dict(self) -> dict[str, Any]:
        return {f.name: np.asarray(getattr(self, f.name)).tolist() for f in fields(self)}

    def to_frame(self):
        import pandas as pd

        return pd.DataFrame({f.name: np.atleast_1d(getattr(self, f.name)) for f in fields(self)})


def _stiction(fs: Any, fk: Any) -> np.ndarray:
    """The force a stuck frame holds [N]: ``max(µ_s, µ_k)·F_z``.

    With µ_k > µ_s the switch model has no slip between µ_s·F_z and µ_k·F_z: a frame breaking
    away there decelerates at once (the kinetic friction exceeds the force that moves it) and a
    frame sliding backwards would too; Filippov's convex combination of the two sliding fields
    keeps ẋ_rf = 0, so the frame stays stuck until the hinge force passes µ_k·F_z (Leine et al.
    1998, Section 3). The integrators would otherwise chatter between breakaway and stop in
    steps of machine length. Equal to µ_s·F_z, bit for bit, wherever µ_k ≤ µ_s.
    """
    return np.maximum(fs, fk)


def _stage_is_rigid(stage) -> np.ndarray:
    """True where ``stage`` is the RMS: a boolean array of ``stage``'s shape from booleans
    (True = RMS, also as an object array such as a pandas object column) or the labels
    ``"rfcms"``/``"rms"`` (any case)."""
    s = np.asarray(stage)
    if s.dtype == object and s.size and all(isinstance(x, (bool, np.bool_)) for x in s.flat):
        s = s.astype(bool)
    if s.dtype == bool:
        return s
    low = np.char.lower(np.asarray(s, dtype=str))
    bad = ~np.isin(low, ["rfcms", "rms"])
    if bad.any():
        i = int(np.flatnonzero(np.atleast_1d(bad))[0])
        given = np.ravel(np.asarray(stage, dtype=object))[i]  # the caller's own value
        raise ValueError(f"stage must be 'rfcms' or 'rms', got {given!r} (row {i})")
    return low == "rms"


def cycle_metrics(stroke=None, velocity=None, acceleration=None, *, stage="rfcms",
                  params: LRGParams | None = None, method="auto", n_cycles=3, max_cycles=40,
                  rtol=1e-8, h=0.3, max_steps_per_cycle=200_000, integrator="adaptive", h_rk=0.6,
                  tol_rk=1e-6,
                  **columns) -> CycleMetrics:
    """Per-cycle sliding, friction work and peak hinge deflection, vectorised over rows.

    Parameters
    ----------
    stroke, velocity, acceleration : float or array
        Motion of the working stage [m], [m/s], [m/s²] (default: ``params``).
    stage : "rfcms", "rms", or array of them (or bool array, True = RMS)
    params : LRGParams
        Base parameters (default: the shipped defaults).
    method : "auto", "integrate" or "quasi_static"
        ``auto``: quasi-static where :func:`quasi_static_valid`, integration elsewhere.
    n_cycles, max_cycles, rtol : int, int, float
        Integration runs from rest for at least ``n_cycles`` and at most ``max_cycles``
        cycles, until two successive cycles' sliding agree within ``rtol`` (every row); the
        last cycle is reported and ``periodicity_error_m`` says how well it converged. The
        defaults (1e-8, 40) put sliding and viscous work within 1e-6 of the periodic state on
        all but a few of the rows that have one (``benchmarks/bench_dynamics.py
        --convergence``: 1 and 7 of 1,837 box rows); the earlier 1e-5 and 12 cycles left 956
        rows beyond 1e-6 (up to 2.4e-3), because some rows drift for ten cycles or more.
    h : float
        Largest ω_n·Δt of the fixed-step NumPy integrator (``integrator="fixed_step"``; exact
        linear steps between events with the hinge's tangent; 0.3 agrees with the event-driven
        reference to ~1e-5 relative on the linear hinge, see the tests).
    integrator : "adaptive", "compiled" or "fixed_step"
        ``adaptive`` (default): :mod:`.stepper`, DOP853's order-8 pair in steps whose length
        its error estimate controls, dense output for stops and the peak, compiled per row
        (numba); about 1.9× faster per cycle than ``compiled``, the reference: the same
        tableau in equal steps ω·Δt = ``h_rk`` per segment of the profile. Both reach the same
        periodic state (``tests/physics/test_stepper.py``); what limits the accuracy is the
        cycle criterion (``rtol``, ``max_cycles``), not the step (:mod:`.stepper`,
        ``benchmarks/bench_dynamics.py --convergence``, ``benchmarks/bench_simulate.py``);
        ``fixed_step``: the earlier vectorised NumPy integrator.
    h_rk : float
        ω·Δt of the equal steps of ``integrator="compiled"`` (ω at a bound of the hinge's tangent
        stiffness, :func:`_omega_step`; 0.6 agrees with the event-driven reference to 3e-7
        relative in sliding distance), and of the breakaway checks of a stuck frame in
        ``"adaptive"``.
    tol_rk : float
        Local error per step of ``integrator="adaptive"``, relative to the breakaway deflection
        and its speed (1e-6: sliding and viscous work within 1e-6 of the reference wherever the
        cycles settle, ``tests/physics/test_stepper.py``).

    With µ_k > µ_s a stuck frame holds ``max(µ_s, µ_k)·F_z`` (Filippov's solution of the switch
    model: between the two neither slip direction can start), in every route.
    **columns
        Any parameter as a scalar or an array column (``hinge_thickness_m=...``,
        ``dwell_s=...``, ``mu_k=...``), validated like the parameters.

    Notes
    -----
    Rows with identical inputs are integrated once (designed experiments repeat settings).
    Cost: about N = max(ω_n·T)/h steps per cycle, each a few dozen NumPy operations over the
    (distinct) rows — see ``benchmarks/bench_dynamics.py``.

    Examples
    --------
    >>> m = cycle_metrics(0.075, 0.5, 10.0, stage=["rfcms", "rms"], hinge_thickness_m=0.0003)
    >>> float(m.sliding_distance_m[1]), round(float(m.sliding_distance_m[0] / m.sliding_distance_m[1]), 4)
    (0.15, 1.0021)
    >>> m = cycle_metrics(0.075, 0.5, 10.0, hinge_thickness_m=0.0003, params=LRGParams(hinge_membrane=False))
    >>> bool(m.sliding_distance_m < 0.15)     # the small-deflection hinge of Eq. 1 alone
    True
    """
    p = params or LRGParams()
    stroke = p.stroke_m if stroke is None else stroke
    velocity = p.velocity_m_s if velocity is None else velocity
    acceleration = p.acceleration_m_s2 if acceleration is None else acceleration
    for name, val in (("stroke_m", stroke), ("velocity_m_s", velocity), ("acceleration_m_s2", acceleration)):
        check_values(name, val)
    if method not in ("auto", "integrate", "quasi_static"):
        raise ValueError(f"method must be 'auto', 'integrate' or 'quasi_static', not {method!r}")
    if integrator not in ("adaptive", "compiled", "fixed_step"):
        raise ValueError(f"integrator must be 'adaptive', 'compiled' or 'fixed_step', not {integrator!r}")
    if int(n_cycles) < 2:
        raise ValueError("n_cycles must be at least 2")
    dwell = columns.pop("dwell_s", p.dwell_s)
    check_values("dwell_s", dwell)
    jerk = columns.pop("jerk_time_s", p.jerk_time_s)
    check_values("jerk_time_s", jerk)
    stage_rigid = _stage_is_rigid(stage)
    if np.ndim(stage) and columns:
        # RMS rows ignore the hinge and frame columns (they may be empty/NaN there)
        shape0 = np.broadcast_shapes(np.shape(stroke), np.shape(velocity), np.shape(acceleration),
                                     np.shape(stage), *(np.shape(x) for x in columns.values()))
        rig = np.broadcast_to(stage_rigid, shape0)
        if rig.any():
            base = p.to_dict()
            columns = {k: (np.where(rig, base[k], np.broadcast_to(np.asarray(x, dtype=float), shape0))
                           if k in _HINGE_SIDE and np.ndim(x) else x) for k, x in columns.items()}
    const = stage_constants(p, **columns)
    arrays = np.broadcast_arrays(np.asarray(stroke, float), np.asarray(velocity, float),
                                 np.asarray(acceleration, float), np.asarray(dwell, float),
                                 *(np.asarray(getattr(const, f.name), float) for f in fields(const)),
                                 stage_rigid, np.asarray(jerk, float))
    shape = arrays[0].shape
    n = int(np.prod(shape)) if shape else 1
    s, v, a, dw, k, c, m, fs, fk, cv, yl = (np.ravel(x).astype(float) for x in arrays[:11])
    rigid = np.ravel(arrays[11]).copy()
    tj = np.ravel(arrays[12]).astype(float)
    fs = _stiction(fs, fk)

    T = motion.cycle_time(s, v, a, dw, tj)
    stage_visc = cv * motion.mean_square_speed(s, v, a, dw, tj) * T  # ∫c_v·ẋ_ws² dt per cycle
    slide = np.empty(n)
    visc = np.zeros(n)
    peak = np.zeros(n)
    err = np.zeros(n)
    how = np.full(n, "integrate", dtype=object)

    slide[rigid] = 2.0 * s[rigid]
    how[rigid] = "rms"
    cst = StageConstants(k, c, m, fs, fk, cv, yl)
    if method == "quasi_static":
        qs = ~rigid
    elif method == "auto":
        qs = ~rigid & quasi_static_valid(cst, s, v, a)
    else:
        qs = np.zeros(n, dtype=bool)
    slide[qs] = 2.0 * quasi_static_sliding_per_stroke(s[qs], k[qs], fs[qs], fk[qs], yl[qs])
    peak[qs] = leaf_deflection(np.maximum(fs[qs], fk[qs] + m[qs] * a[qs]), k[qs], yl[qs])
    how[qs] = "quasi_static"
    visc[rigid] = stage_visc[rigid]
    visc[qs] = stage_visc[qs] * slide[qs] / (2.0 * s[qs])
    todo = np.flatnonzero(~rigid & ~qs)
    if todo.size:
        key = np.column_stack([x[todo] for x in (s, v, a, dw, k, c, m, fs, fk, cv, yl, tj)])
        uniq, inv = np.unique(key, axis=0, return_inverse=True)
        inv = np.ravel(inv)
        if integrator in ("adaptive", "compiled"):
            d, pk, e, vw = _integrate_compiled(uniq, int(n_cycles), float(h_rk), int(max_steps_per_cycle),
                                               int(max_cycles), float(rtol),
                                               "adaptive" if integrator == "adaptive" else "fixed", float(tol_rk))
        else:
            d, pk, e, vw = _integrate_grouped(uniq, int(n_cycles), float(h), int(max_steps_per_cycle),
                                              int(max_cycles), float(rtol))
        slide[todo], peak[todo], err[todo], visc[todo] = d[inv], pk[inv], e[inv], vw[inv]
    work = fk * slide

    def r(x):
        return x.reshape(shape) if shape else x.reshape(())[()]

    return CycleMetrics(r(slide), r(work), r(peak), r((work + visc) / T), r(T), r(err), r(how), r(visc))


def _integrate_compiled(rows, n_cycles, h, max_steps, max_cycles, rtol, method="adaptive", tol=1e-6):
    """Integrate distinct rows with the compiled stepper (:func:`.stepper.integrate_rows`)."""
    s, v, a, dw, k, c, m, fs, fk, cv, yl, tj = rows.T
    w = _omega_step(s, v, a, k, m, fs, cv, yl)
    T = motion.cycle_time(s, v, a, dw, tj)
    need = w * T / h
    if np.any(need > max_steps):
        i = int(np.argmax(need))
        raise ValueError(
            f"the stage dynamics need {int(np.ceil(need[i]))} steps per cycle (limit {max_steps}) at stroke "
            f"{s[i]:.3g} m, velocity {v[i]:.3g} m/s, acceleration {a[i]:.3g} m/s^2: a {T[i]:.3g} s cycle is too "
            f"long for the hinge period ({2 * np.pi / w[i]:.3g} s) outside the quasi-static limit")
    return integrate_rows(s, v, a, dw, tj, k, c, m, fs, fk, cv, yl, w, h=h, n_cycles=n_cycles,
                          max_cycles=max_cycles, rtol=rtol, method=method, tol=tol)


def _integrate_grouped(rows, n_cycles, h, max_steps, max_cycles, rtol):
    """Integrate rows in groups of similar stiffness (steps per cycle within a factor 2)."""
    s, v, a, dw, k, c, m, fs, fk, cv, yl, tj = rows.T
    need = _omega_step(s, v, a, k, m, fs, cv, yl) * motion.cycle_time(s, v, a, dw, tj) / h
    grp = np.floor(np.log2(np.maximum(need, 1.0))).astype(int)
    out = [np.empty(len(rows)) for _ in range(4)]
    for g in np.unique(grp):
        i = np.flatnonzero(grp == g)
        res = _integrate_rows(*rows[i].T[:11], n_cycles, h, max_steps, max_cycles, rtol, tj=rows[i].T[11])
        for o, r in zip(out, res):
            o[i] = r
    return tuple(out)


def _propagator(w, zeta, tau):
    """Exact 2×2 propagator of ż = v, v̇ = −ω²z − 2ζω·v over ``tau`` (any ζ ≥ 0)."""
    one = 1.0 - zeta ** 2
    one = np.where(np.abs(one) < 1e-9, 1e-9, one)
    wd = w * np.sqrt(one + 0j)
    e = np.exp(-zeta * w * tau)
    cs, sn = np.cos(wd * tau), np.sin(wd * tau)
    p11 = (e * (cs + zeta * w / wd * sn)).real
    p12 = (e * sn / wd).real
    p21 = (-e * w ** 2 / wd * sn).real
    p22 = (e * (cs - zeta * w / wd * sn)).real
    return p11, p12, p21, p22


def _stage_xv(t, s, vp, a, ta, ts, dw, T):
    """Exact stage position and velocity of the reciprocating profile at times ``t`` (rows)."""
    tm = np.mod(t, T)
    back = tm >= ts + dw
    tau = np.minimum(np.where(back, tm - ts - dw, tm), ts)
    up = np.minimum(tau, ta)
    down = np.maximum(tau - (ts - ta), 0.0)
    x = vp * (tau - up - down) + 0.5 * a * up ** 2 + (vp * down - 0.5 * a * down ** 2)
    v = np.minimum(np.minimum(a * tau, a * (ts - tau)), vp)
    return np.where(back, s - x, x), np.where(back, -v, v)


def _stage_xv_j(t, s, v, vp, a, ta, ts, tj, dw, T):
    """Stage position and velocity at times ``t`` (rows) with S-curve strokes where the jerk
    time ``tj`` > 0 (:func:`.motion.scurve_stroke`, period ``T`` = 2·(t_s + t_j + dwell)) and
    the trapezoid of :func:`_stage_xv` (bit for bit) where it is 0."""
    x, vv = _stage_xv(t, s, vp, a, ta, ts, dw, T)
    on = tj > 0
    tm = np.mod(t, T)
    tsj = ts + tj
    back = tm >= tsj + dw
    tau = np.where(back, tm - tsj - dw, tm)
    xj, vj, _ = motion.scurve_stroke(tau, s, v, a, np.where(on, tj, 1.0))
    return (np.where(on, np.where(back, s - xj, xj), x), np.where(on, np.where(back, -vj, vj), vv))


def _hinge_force(z, k, yl):
    """Hinge force [N] at the deflection z [m]: ``n·K_n·z`` where ``yl`` is 0 (Eq. 1), else the
    exact beam-column law of leaves with held ends ``n·K_n·y·ψ(z/y)`` (tabulated,
    :func:`.stepper.leaf_psi`)."""
    z = np.asarray(z, dtype=float)
    yl = np.asarray(yl, dtype=float)
    held = yl > 0
    ys = np.where(held, yl, 1.0)
    return np.where(held, k * ys * leaf_psi(z / ys), k * z)


def _hinge_tangent(z, k, yl):
    """Tangent stiffness dF/dz [N/m] of :func:`_hinge_force`."""
    yl = np.asarray(yl, dtype=float)
    held = yl > 0
    ys = np.where(held, yl, 1.0)
    return np.where(held, k * leaf_dpsi(np.asarray(z, dtype=float) / ys), k)


def _omega_step(s, v, a, k, m, fs, cv, yl):
    """Angular frequency [rad/s] that sets a row's time step: ``sqrt(n·K_n/m_f)`` for a linear
    hinge; for leaves with held ends the tangent ``sqrt(k_t(δ_e)/m_f)`` at the deflection δ_e
    that three times the largest quasi-static hinge force (breakaway, inertia and viscous
    friction, ``3·(f_µmax + m_f·a + c_v·v)``) would give: a bound of the overshoot after a stop."""
    yl = np.asarray(yl, dtype=float)
    if not np.any(yl > 0):
        return np.sqrt(k / m)
    de = leaf_deflection(3.0 * (fs + m * a + cv * v), k, yl)
    return np.sqrt(_hinge_tangent(de, k, yl) / m)


def _tangent(z, k, yl, c, cv, m):
    """Tangent linearisation of the hinge force F(z) at z: ω and ζ of the tangent stiffness
    k_t = F′(z) and the force offset per mass ``−(F(z) − k_t·z)/m`` as the right-hand side's
    constant (``ext``)."""
    kt = _hinge_tangent(z, k, yl)
    w = np.sqrt(kt / m)
    zeta = (c + cv) / (2.0 * np.sqrt(kt * m))
    return w, zeta, (kt * z - _hinge_force(z, k, yl)) / m


def _slide(z, wrel, sigma, accel, w, zeta, fk_m, p11, p12, p21, p22, cv_m=0.0, vstage=0.0, tau=0.0, ext=0.0,
           jerk=None):
    """Exact sliding step over ``tau`` of the relative coordinate z = x_ws − x_rf, wrel = ż.

    While sliding, ``z̈ + 2ζω·ż + ω²·z = a + σ·f_k/m + (c_v/m)·ẋ_ws(t)`` with the stage
    velocity ẋ_ws = vstage + a·t linear in the step; ζ includes c_v (the viscous friction
    damps the relative motion too). The particular solution is ``A + B·t`` with
    ``B = (c_v/m)·a/ω²`` and ``A = (a + σ·f_k/m + (c_v/m)·vstage − 2ζω·B)/ω²``; the rest is the
    homogeneous propagator ``p``. Returns z and ż at the end of the step. A stiffening hinge
    enters through its tangent at the start of the step (ω, ζ of :func:`_tangent` and the
    constant ``ext``): exact for the linear hinge, second order in the step for the cubic.

    ``jerk`` (S-curve strokes): the stage acceleration ``accel + jerk·t`` is linear in the step
    (ẋ_ws quadratic); the particular solution gains ``C·t²`` with ``C = (c_v/m)·jerk/(2ω²)``,
    ``B = (jerk + (c_v/m)·a − 4ζω·C)/ω²`` and ``A`` loses ``2·C/ω²``. With ``jerk`` 0 the
    result is that of ``jerk=None`` bit for bit (every added term is an exact zero).
    """
    if jerk is not None:
        C = 0.5 * cv_m * jerk / w ** 2
        B = (jerk + cv_m * accel - 4.0 * zeta * w * C) / w ** 2
        A = (accel + fk_m * sigma + cv_m * vstage + ext - 2.0 * zeta * w * B - 2.0 * C) / w ** 2
        zr = z - A
        wr = wrel - B
        return A + B * tau + C * tau * tau + p11 * zr + p12 * wr, B + 2.0 * C * tau + p21 * zr + p22 * wr
    B = cv_m * accel / w ** 2
    A = (accel + fk_m * sigma + cv_m * vstage + ext - 2.0 * zeta * w * B) / w ** 2
    zr = z - A
    wr = wrel - B
    return A + B * tau + p11 * zr + p12 * wr, B + p21 * zr + p22 * wr


def _integrate_rows(s, v, a, dw, k, c, m, fs, fk, cv, yl, n_cycles, h, max_steps, max_cycles=12, rtol=1e-5,
                    tj=None):
    """Stick-slip integration of many rows at once with exact linear steps.

    Each row uses its own step Δt = T/N_i, N_i = max(ceil(ω_n·T/h), 200); the loop runs to the
    largest N_i and rows that have finished their cycle wait (masked). While
    sliding, the relative motion z = x_ws − x_rf is advanced with the exact propagator of the
    damped hinge under the step-average stage acceleration and the kinetic friction; while
    stuck the frame stays put. Breakaway is located inside the step (quadratic stage motion,
    |F_h| = f_µmax), a stop (ẋ_rf reaching 0) by linear interpolation of ẋ_rf.
    Cycles are integrated from rest until the sliding of two successive cycles agrees within
    ``rtol`` (at least ``n_cycles``, at most ``max_cycles``); settled rows leave the loop.
    The block's viscous friction c_v acts on the sliding frame (exact in the step, see
    :func:`_slide`); its work ∫c_v·ẋ_rf² dt is summed by the trapezoidal rule. Leaves with held
    ends (k₃ > 0) stiffen: every step is taken with the hinge's tangent at its start
    (:func:`_tangent`), the step size from :func:`_omega_step`.
    Rows with a jerk time ``tj`` > 0 follow S-curve strokes (:func:`_stage_xv_j`): in each step
    the stage moves on the cubic that matches its exact position and velocity at both ends
    (Hermite; exact between the kinks of the S-curve, whose acceleration is piecewise linear),
    with the linear acceleration in the sliding step (:func:`_slide` with ``jerk``) and the
    breakaway time refined on the cubic by Newton steps. Rows with ``tj`` 0 are integrated
    exactly as without it.
    Returns (mean sliding per cycle over the last two cycles, peak deflection of the last
    cycle, |difference of the last two cycles' sliding|, viscous work per cycle, mean of the
    last two cycles).
    """
    n = len(s)
    out_d, out_p, out_e, out_v = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    jerky = tj is not None and bool(np.any(np.asarray(tj) > 0))
    tj = np.zeros(n) if tj is None else np.asarray(tj, dtype=float)
    T = motion.cycle_time(s, v, a, dw, tj) if jerky else motion.cycle_time(s, v, a, dw)
    vp = motion.peak_velocity(s, v, a)
    ta = vp / a
    ts = s / vp + ta
    w = np.sqrt(k / m)
    zeta = (c + cv) / (2.0 * np.sqrt(k * m))  # hinge damping and viscous friction, while sliding
    cv_m = cv / m
    membrane = bool(np.any(yl > 0))
    # each row its own number of steps per cycle (so that its result does not depend on the
    # rows integrated with it); the loop runs to the largest, finished rows wait
    Ni = np.maximum(np.ceil(_omega_step(s, v, a, k, m, fs, cv, yl) * T / h), 200.0)
    N = int(np.max(Ni))
    if N > max_steps:
        i = int(np.argmax(Ni))
        raise ValueError(
            f"the stage dynamics need {N} steps per cycle (limit {max_steps}) at stroke {s[i]:.3g} m, "
            f"velocity {v[i]:.3g} m/s, acceleration {a[i]:.3g} m/s^2: a {T[i]:.3g} s cycle is too long for "
            f"the hinge period ({2 * np.pi / w[i]:.3g} s) outside the quasi-static limit")
    dt = T / Ni
    p11, p12, p21, p22 = _propagator(w, zeta, dt)
    fk_m = fk / m
    rows = np.arange(n)
    xf = np.zeros(n)
    u = np.zeros(n)
    stuck = np.ones(n, dtype=bool)
    dist = np.zeros(n)
    prev = np.zeros(n)
    vwork = np.zeros(n)
    vprev = np.zeros(n)
    peak = np.zeros(n)
    x0, v0 = np.zeros(n), np.zeros(n)
    cyc = 0
    while True:
        dist_start = dist.copy()
        vwork_start = vwork.copy()
        peak[:] = 0.0
        for j in range(N):
            act = j < Ni
            t = (cyc * Ni + np.minimum(j, Ni - 1) + 1) * dt
            if jerky:
                x1, v1 = _stage_xv_j(t, s, v, vp, a, ta, ts, tj, dw, T)
            else:
                x1, v1 = _stage_xv(t, s, vp, a, ta, ts, dw, T)
            acc = (v1 - v0) / dt
            if jerky:  # cubic stage motion in the step (Hermite), S-curve rows only
                jon = tj > 0
                jrk = np.where(jon, 6.0 * (acc - 2.0 * (x1 - x0 - v0 * dt) / dt ** 2) / dt, 0.0)
                alpha = np.where(jon, acc - 0.5 * jrk * dt, acc)
            else:
                jrk, alpha = None, acc
            xf_old = xf.copy()
            u_old = u
            stuck_old = stuck
            sl = ~stuck
            z0 = x0 - xf
            if membrane:  # tangent of the stiffening hinge at the start of the step
                wt, zt, ext = _tangent(z0, k, yl, c, cv, m)
                P = _propagator(wt, zt, dt)
            else:
                wt, zt, ext, P = w, zeta, 0.0, (p11, p12, p21, p22)
            # sliding rows: one exact step
            zn, wn = _slide(z0, v0 - u, np.sign(u), alpha, wt, zt, fk_m, *P, cv_m, v0, dt, ext, jrk)
            un = v1 - wn
            stop = sl & (un * u <= 0.0)
            go = sl & ~stop
            xf = np.where(go, x1 - zn, xf)
            if stop.any():
                # ẋ_rf reaches 0 inside the step (linear interpolation of ẋ_rf)
                i = np.flatnonzero(stop)
                frac = u[i] / (u[i] - un[i])
                xf[i] += 0.5 * u[i] * frac * dt[i]
            u = np.where(go, un, 0.0)
            # rows stuck at the start of the step: break away inside it?
            f1 = _hinge_force(x1 - xf, k, yl) + c * v1
            brk = stuck & (np.abs(f1) > fs)
            stuck = (stuck & ~brk) | stop
            if brk.any():
                i = np.flatnonzero(brk)
                sig = np.sign(f1[i])
                # F_h(τ) = F(z0) + k_t·(v0·τ + a·τ²/2) + c(v0 + a·τ) = σ·f_µmax, z0 = x0 − x_f
                # (k_t = n·K_n + 3·n·k₃·z0², the tangent; exact for the linear hinge)
                ai, v0i = acc[i], v0[i]
                zi = x0[i] - xf[i]
                ki = _hinge_tangent(zi, k[i], yl[i])
                fz = _hinge_force(zi, k[i], yl[i])
                tau = _first_root(0.5 * ki * ai, ki * v0i + c[i] * ai,
                                  fz + c[i] * v0i - sig * fs[i], dt[i])
                ji = None
                if jerky:  # S-curve rows: the stage moves on a cubic, refine the root on it
                    ji, al = jrk[i], alpha[i]
                    f0 = fz + c[i] * v0i - sig * fs[i]
                    tn = tau
                    for _ in range(4):
                        g = f0 + ki * (v0i * tn + 0.5 * al * tn ** 2 + ji * tn ** 3 / 6.0) + c[i] * (
                            al * tn + 0.5 * ji * tn ** 2)
                        dg = ki * (v0i + al * tn + 0.5 * ji * tn ** 2) + c[i] * (al + ji * tn)
                        with np.errstate(divide="ignore", invalid="ignore"):
                            tn = np.clip(tn - np.where(dg != 0, g / dg, 0.0), 0.0, dt[i])
                    jon_i = tj[i] > 0
                    tau = np.where(jon_i, tn, tau)
                    ai = np.where(jon_i, al, ai)
                xs_t = x0[i] + v0i * tau + 0.5 * ai * tau ** 2
                if ji is not None:
                    xs_t = xs_t + ji * tau ** 3 / 6.0
                if membrane:
                    wb, zb, eb = _tangent(xs_t - xf[i], k[i], yl[i], c[i], cv[i], m[i])
                else:
                    wb, zb, eb = w[i], zeta[i], 0.0
                Q = _propagator(wb, zb, dt[i] - tau)
                if ji is None:
                    zn_b, wn_b = _slide(xs_t - xf[i], v0i + ai * tau, sig, ai, wb, zb, fk_m[i], *Q,
                                        cv_m[i], v0i + ai * tau, dt[i] - tau, eb)
                else:
                    vs_t = v0i + ai * tau + 0.5 * ji * tau ** 2
                    zn_b, wn_b = _slide(xs_t - xf[i], vs_t, sig, ai + ji * tau, wb, zb, fk_m[i], *Q,
                                        cv_m[i], vs_t, dt[i] - tau, eb, ji)
                un_b = v1[i] - wn_b
                ok = un_b * sig > 0.0
                xf[i] = np.where(ok, x1[i] - zn_b, xf[i])
                u[i] = np.where(ok, un_b, 0.0)
                stuck[i[ok]] = False
            if not act.all():  # rows that have finished this cycle keep their state
                xf = np.where(act, xf, xf_old)
                u = np.where(act, u, u_old)
                stuck = np.where(act, stuck, stuck_old)
                x1 = np.where(act, x1, x0)
                v1 = np.where(act, v1, v0)
            dist += np.abs(xf - xf_old)
            vwork += np.where(act, 0.5 * cv * (u_old ** 2 + u ** 2) * dt, 0.0)
            np.maximum(peak, np.abs(x1 - xf), out=peak)
            x0, v0 = x1, v1
        this = dist - dist_start
        err = np.abs(this - prev)
        mean2 = 0.5 * (this + prev)
        prev = this
        vthis = vwork - vwork_start
        vmean2 = 0.5 * (vthis + vprev)
        vprev = vthis
        cyc += 1
        if cyc < n_cycles:
            continue
        done = (err <= rtol * np.maximum(this, 1e-300)) | (cyc >= max_cycles)
        out_d[rows[done]], out_p[rows[done]], out_e[rows[done]] = mean2[done], peak[done], err[done]
        out_v[rows[done]] = vmean2[done]
        if done.all():
            break
        keep = ~done
        (rows, s, v, a, dw, k, c, m, fs, T, vp, ta, ts, w, zeta, dt, p11, p12, p21, p22, fk_m, xf, u,
         stuck, dist, prev, peak, x0, v0, cv, cv_m, vwork, vprev, Ni, yl, tj) = (x[keep] for x in (
            rows, s, v, a, dw, k, c, m, fs, T, vp, ta, ts, w, zeta, dt, p11, p12, p21, p22, fk_m, xf, u,
            stuck, dist, prev, peak, x0, v0, cv, cv_m, vwork, vprev, Ni, yl, tj))
        N = int(np.max(Ni))
    # a row that has not settled (period-2 stick-slip, say) reports the mean of its last two cycles
    return out_d, out_p, out_e, out_v


def _first_root(A, B, C, dt):
    """Smallest root in [0, dt] of A·τ² + B·τ + C (C and the value at dt differ in sign)."""
    disc = np.sqrt(np.maximum(B * B - 4 * A * C, 0.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        q = -0.5 * (B + np.where(B >= 0, disc, -disc))
        r1 = np.where(q != 0, C / q, np.inf)
        r2 = np.where(A != 0, q / A, np.inf)
    lin = np.where(B != 0, -C / np.where(B != 0, B, 1.0), 0.0)
    cand = np.where(np.abs(A) * dt < 1e-12 * np.maximum(np.abs(B), 1e-300), lin, np.inf)
    best = np.full_like(dt, np.inf)
    for r in (r1, r2, cand):
        good = np.isfinite(r) & (r >= -1e-15 * dt) & (r <= dt * (1 + 1e-12))
        best = np.where(good & (r < best), r, best)
    return np.clip(np.where(np.isfinite(best), best, 0.0), 0.0, dt)


# ------------------------------------------------------------------------------------------
# reference: event-driven integration of one parameter set
# ------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class StageHistory:
    """Time history of :func:`simulate_stage` and the metrics of its last cycle."""

    t: np.ndarray
    x_stage: np.ndarray
    x_frame: np.ndarray
    v_frame: np.ndarray
    sliding_per_cycle_m: np.ndarray  # one entry per simulated cycle
    peak_deflection_m: float  # over the last cycle
    friction_work_j: float  # last cycle
    cycle_time_s: float
    events: int
    viscous_work_j: float = 0.0  # last cycle, ∫c_v·ẋ_rf² dt


    @property
    def sliding_distance_m(self) -> float:
        return float(self.sliding_per_cycle_m[-1])

    @property
    def mean_friction_power_w(self) -> float:
        return (self.friction_work_j + self.viscous_work_j) / self.cycle_time_s

    def to_frame(self):
        import pandas as pd

        return pd.DataFrame({"t_s": self.t, "x_stage_m": self.x_stage, "x_frame_m": self.x_frame,
                             "v_frame_m_s": self.v_frame})


def _breakpoints(s, v, a, dw, n_cycles, tj=0.0):
    if tj > 0:  # S-curve: the kinks of both strokes (motion.stroke_kinks)
        kinks = [float(x) for x in motion.stroke_kinks(s, v, a, tj)]
        ts = float(motion.stroke_time(s, v, a, tj))
        one = kinks + [ts + dw + x for x in kinks]
        T = 2 * (ts + dw)
        pts = sorted({round(c * T + x, 15) for c in range(n_cycles) for x in one} | {n_cycles * T})
        return np.array(pts), T
    ta = float(motion.accel_time(s, v, a))
    ts = float(motion.stroke_time(s, v, a))
    one = [0.0, ta, ts - ta, ts, ts + dw, ts + dw + ta, 2 * ts + dw - ta, 2 * ts + dw]
    T = 2 * (ts + dw)
    pts = sorted({round(c * T + x, 15) for c in range(n_cycles) for x in one} | {n_cycles * T})
    return np.array(pts), T


@dataclass
class _Event:
    """A :func:`scipy.integrate.solve_ivp` event: ``fn(t, y)`` crosses zero. solve_ivp reads
    ``terminal`` (stop the integration there) and ``direction`` (+1 rising, -1 falling, 0
    both) off the callable."""

    fn: Callable[[float, np.ndarray], float]
    terminal: bool = True
    direction: float = 0.0

    def __call__(self, t: float, y: np.ndarray) -> float:
        return self.fn(t, y)


def simulate_stage(params: LRGParams | None = None, *, n_cycles=4, stroke=None, velocity=None,
                   acceleration=None, rigid=False, rtol=1e-10, samples_per_cycle=2000) -> StageHistory:
    """Event-driven reference solution of the RFCMS (or the RMS with ``rigid=True``).

    Integrates ``n_cycles`` cycles from rest with scipy's DOP853 between the kinks of the
    motion profile, with events at breakaway (|F_h| = f_µmax) and at stop (ẋ_rf = 0).
    The stage follows S-curve strokes where ``params.jerk_time_s`` > 0 (closed form of
    :func:`.motion.scurve_stroke`; the kinks of its acceleration are breakpoints).
    """
    from scipy.integrate import solve_ivp

    p = params or LRGParams()
    s = float(p.stroke_m if stroke is None else stroke)
    v = float(p.velocity_m_s if velocity is None else velocity)
    a = float(p.acceleration_m_s2 if acceleration is None else acceleration)
    for name, val in (("stroke_m", s), ("velocity_m_s", v), ("acceleration_m_s2", a)):
        check_values(name, val)
    dw = p.dwell_s
    cst = stage_constants(p)
    k, c, m, fs, fk, cv, yl = (float(getattr(cst, f.name)) for f in fields(cst))
    fs = float(_stiction(fs, fk))

    def hf(z):
        return k * z if yl <= 0 else k * yl * float(leaf_psi(z / yl))
    tj = float(p.jerk_time_s)
    bps, T = _breakpoints(s, v, a, dw, n_cycles, tj)

    vp = float(motion.peak_velocity(s, v, a))
    ta_, ts_ = vp / a, s / vp + vp / a

    def trap(u):  # trapezoidal stroke: position and its time integral from 0 (motion._trap)
        tt = min(max(u, 0.0), ts_)
        r = ts_ - tt
        if tt < ta_:
            x, F = 0.5 * a * tt * tt, a * tt ** 3 / 6.0
        elif tt < ts_ - ta_:
            x = 0.5 * a * ta_ * ta_ + vp * (tt - ta_)
            F = a * ta_ ** 3 / 6.0 + 0.5 * a * ta_ * ta_ * (tt - ta_) + 0.5 * vp * (tt - ta_) ** 2
        else:
            x, F = s - 0.5 * a * r * r, 0.5 * s * ts_ - s * r + a * r ** 3 / 6.0
        return x, F + s * max(u - ts_, 0.0)

    def stage_j(t):  # scalar closed form of motion.reciprocating_profile with S-curve strokes
        tsj = ts_ + tj
        tm = math.fmod(t, T)
        back = tm >= tsj + dw
        tau = tm - tsj - dw if back else tm
        if tau <= 0.0:
            x, vv = 0.0, 0.0
        elif tau >= tsj:
            x, vv = s, 0.0
        else:
            x1, F1 = trap(tau)
            x0, F0 = trap(tau - tj)
            x, vv = (F1 - F0) / tj, (x1 - x0) / tj
        return (s - x, -vv) if back else (x, vv)

    def stage_t(t):  # scalar closed form of motion.reciprocating_profile (fast in the ODE loop)
        tm = math.fmod(t, T)
        back = tm >= ts_ + dw
        tau = min(tm - ts_ - dw if back else tm, ts_)
        if tau < 0.0:
            tau = 0.0
        up = min(tau, ta_)
        down = max(tau - (ts_ - ta_), 0.0)
        x = vp * (tau - up - down) + 0.5 * a * up * up + vp * down - 0.5 * a * down * down
        vv = min(a * tau, a * (ts_ - tau), vp)
        return (s - x, -vv) if back else (x, vv)

    stage = stage_j if tj > 0 else stage_t
    grid = np.linspace(0.0, n_cycles * T, n_cycles * samples_per_cycle + 1)
    if rigid:
        xs, vs, _ = motion.reciprocating_profile(grid, s, v, a, dw, tj)
        per = np.full(n_cycles, 2 * s)
        visc = cv * float(motion.mean_square_speed(s, v, a, dw, tj)) * T
        return StageHistory(grid, xs, xs.copy(), vs, per, 0.0, fk * 2 * s, T, 0, visc)

    # state: x_f, u, distance, viscous work; mode: 0 stuck, +1 / -1 sliding
    y = np.zeros(4)
    mode = 0
    t = 0.0
    ts_out, xf_out, u_out = [0.0], [0.0], [0.0]
    cycle_marks = {}
    n_events = 0
    seg = 0
    end = n_cycles * T

    def rhs_slide(sign):
        def f(tt, yy):
            xs, vs = stage(tt)
            z = xs - yy[0]
            fh = hf(z) + c * (vs - yy[1])
            return [yy[1], (fh - sign * fk - cv * yy[1]) / m, sign * yy[1], cv * yy[1] ** 2]
        return f

    def stopped(tt, yy):
        return yy[1]

    def breaks_up(tt, yy):
        xs, vs = stage(tt)
        return hf(xs - yy[0]) + c * vs - fs

    def breaks_down(tt, yy):
        xs, vs = stage(tt)
        return hf(xs - yy[0]) + c * vs + fs

    ev_stop = _Event(stopped)
    ev_break_up = _Event(breaks_up, direction=1.0)
    ev_break_dn = _Event(breaks_down, direction=-1.0)

    while t < end - 1e-15:
        while seg < len(bps) - 1 and bps[seg + 1] <= t + 1e-15:
            seg += 1
        t_next = bps[seg + 1] if seg < len(bps) - 1 else end
        if mode == 0:
            xs, vs = stage(t)
            fh = hf(xs - y[0]) + c * vs
            if abs(fh) > fs * (1 + 1e-12):
                mode = 1 if fh > 0 else -1
                n_events += 1
                continue
            sol = solve_ivp(lambda tt, yy: [0.0, 0.0, 0.0, 0.0], (t, t_next), y, method="DOP853",
                            events=[ev_break_up, ev_break_dn], rtol=rtol, atol=1e-14,
                            max_step=(t_next - t) / 4 + 1e-12)
        else:
            ev_stop.direction = -mode
            sol = solve_ivp(rhs_slide(mode), (t, t_next), y, method="DOP853", events=[ev_stop],
                            rtol=rtol, atol=1e-14, dense_output=True, max_step=(t_next - t) / 8 + 1e-12)
        hit = sol.status == 1
        t_new = float(sol.t[-1])
        y = np.array(sol.y[:, -1])
        # dense samples for the history
        mask = (grid > t) & (grid <= t_new)
        if mask.any():
            if mode == 0:
                ts_out.extend(grid[mask])
                xf_out.extend([y[0]] * int(mask.sum()))
                u_out.extend([0.0] * int(mask.sum()))
            else:
                yy = sol.sol(grid[mask])
                ts_out.extend(grid[mask])
                xf_out.extend(yy[0])
                u_out.extend(yy[1])
        if hit:
            n_events += 1
            if mode == 0:
                xs, vs = stage(t_new)
                fh = hf(xs - y[0]) + c * vs
                mode = 1 if fh > 0 else -1
            else:
                y[1] = 0.0
                mode = 0
        t = t_new
        for cyc in range(1, n_cycles + 1):
            if cyc not in cycle_marks and t >= cyc * T - 1e-12:
                cycle_marks[cyc] = (y[2], y[3])
    marks = [(0.0, 0.0)] + [cycle_marks.get(cc, (y[2], y[3])) for cc in range(1, n_cycles + 1)]
    per = np.diff([mk[0] for mk in marks])
    visc_last = marks[-1][1] - marks[-2][1]
    tt = np.array(ts_out)
    xs_h, _, _ = motion.reciprocating_profile(tt, s, v, a, dw, tj)
    xf_h = np.array(xf_out)
    last = tt >= (n_cycles - 1) * T - 1e-12
    peak = float(np.max(np.abs(xs_h[last] - xf_h[last])))
    return StageHistory(tt, xs_h, xf_h, np.array(u_out), per, peak, fk * float(per[-1]), T, n_events,
                        float(visc_last))
