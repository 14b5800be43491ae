"""The row model: one test of the rig (Section 4 of Su, Zhang & Yang 2023), vectorised.

For every row of a design (arrays, never one Python call per row):

1. **Motion** (:mod:`rsm_lrg.physics.motion`): the reciprocating trapezoidal profile of the
   working stage from stroke s, velocity v and acceleration a (Eqs. 15-16); cycle time.
2. **Stage dynamics** (:func:`rsm_lrg.physics.dynamics.cycle_metrics`): the two-mass RFCMS
   with the hinge of thickness y (Eq. 1) and stick-slip friction on the guide, in its
   periodic steady state; the RMS (``stage = rms``) slides the full stroke. Gives the
   carriage sliding distance per cycle and the friction work µ_k·F_z·L.
3. **Friction heat** (Eq. 8 mechanism): friction force × carriage sliding speed, averaged
   over the cycle: P = (µ_k·F_z·L + ∫c_v·ẋ_rf² dt)/T_cycle — the Coulomb work and the work of
   the block's viscous (speed-proportional) friction ``viscous_friction_n_s_m`` (0 in the raw
   physics; it also acts on the carriage in step 2). Divided by
   J = 4.184 as the paper's Eq. 8 does when ``heat_in_calories`` (the default, as in the
   paper); times the share ``heat_partition`` that enters the guide (1 in the raw physics).
4. **Thermal model** (:func:`rsm_lrg.physics.thermal.network.network_response`): the
   carriage (thermocouple) temperature rise per watt after a heat step, exact in time,
   linear in Q; the convection coefficients of Eqs. 10-12. With ``heat_balance`` (calibration
   model v5) one heat balance in watts instead: no division by J and no ``heat_partition``;
   the friction power enters the ball contacts and the drive heat the working stage of one
   network of the rig's bodies (:func:`rsm_lrg.physics.thermal.network.rig_network`, one per
   leaf thickness and stage kind), and what reaches the carriage follows from its conductances.
5. **The rig's record**: readings every minute from 0 to the test duration on two
   thermocouples, each with Gaussian reading noise (:mod:`.noise`), averaged; κ by Eq. 18
   from the first and the last reading.
6. **Wear** (Eq. 13, Archard): K_a·F_i·(sliding per hour)/H, F_i the ball normal force.
"""

from __future__ import annotations

import dataclasses
import math
from functools import lru_cache

import numpy as np

from ..errors import ParameterError

__all__ = ["evaluate_rows", "SURROGATE_PARAMETERS", "thermal_unit_response", "MAX_DURATION_MIN",
           "check_duration", "NETWORK_ROUTE", "clear_row_caches"]

#: Longest test [min] (69 days; the rig's tests last about 50 min, the guide is steady after
#: a few hours): the upper end of ``test_duration_min``'s physical range.
MAX_DURATION_MIN = 1e5


def check_duration(value, name: str = "duration_min") -> float:
    """``value`` as a test duration [min] in [1, :data:`MAX_DURATION_MIN`], or ``ValueError``
    naming ``name`` (two readings one minute apart at least; a longer test is refused before
    anything is computed)."""
    try:
        v = float(value)
    except (TypeError, ValueError, OverflowError):
        raise ParameterError(name, f"{name} must be a number of minutes, got {value!r}") from None
    if isinstance(value, bool) or not (1.0 <= v <= MAX_DURATION_MIN):
        raise ParameterError(name, f"{name} must lie in [1, {MAX_DURATION_MIN:g}] min (a test has at least two readings "
                         f"one minute apart and lasts at most {MAX_DURATION_MIN / 1440:.0f} days), got {v:g}")
    return v

#: Parameters of the surrogate that are not in :class:`~rsm_lrg.physics.params.LRGParams`:
#: name -> (raw-physics value, unit, meaning).
SURROGATE_PARAMETERS = {
    "heat_partition": (1.0, "1", "share of the friction heat (Eq. 8) that enters the guide; "
                                 "the rest leaves through the stage, the lubricant and the seals"),
    "drive_friction_n": (0.0, "N", "Coulomb friction force of the drive element fixed to the working "
                                   "stage (nut, coupling, cable carrier) whose heat F_d <|v|> enters the "
                                   "working stage; conducted to the carriage like drive_heat_w"),
    "drive_viscous_n_s_m": (0.0, "N s/m", "speed-proportional (viscous) friction of the drive element fixed to "
                                          "the working stage, whose heat c_d <v^2> enters the working stage; "
                                          "conducted to the carriage like drive_heat_w"),
}

#: Parameters that enter the convection coefficients (Eqs. 10-12).
_CONVECTION = ("air_velocity_m_s", "char_length_m", "air_kinematic_viscosity_m2_s",
               "air_dynamic_viscosity_pa_s", "air_conductivity_w_mk", "air_specific_heat_j_kgk")


# ----------------------------------------------------------------------------------------
# thermal unit response (cached per thermal parameter set)
# ----------------------------------------------------------------------------------------
def _thermal_items(values: dict) -> tuple:
    """The (name, value) pairs of a parameter dict that the thermal model uses."""
    from ..physics.thermal.geometry import PARAM_ALIASES, GuideGeometry

    geo = {f.name for f in dataclasses.fields(GuideGeometry)}
    return tuple((name, float(values[name])) for name in sorted(values)
                 if PARAM_ALIASES.get(name, name) in geo or name in _CONVECTION)


@lru_cache(maxsize=64)
def _network_cached(items: tuple):
    from ..physics.thermal.network import ThermalNetwork

    geometry, hs, hf = _geometry_and_h(items)
    return ThermalNetwork(geometry, hs, hf)


def thermal_unit_response(values: dict, duration_min: float):
    """Thermocouple rise per watt [K/W] at every minute 0..ceil(duration), and the steady rise
    per watt [K/W], for the parameters ``values`` (a full ``LRGParams.to_dict()``)."""
    net = _network_cached(_thermal_items(values))
    minutes = np.arange(int(math.ceil(duration_min)) + 1, dtype=float)
    return net.response(minutes * 60.0), float(net.steady_rise_per_w)


def _rise_at(values: dict, dur: np.ndarray):
    """Unit rise [K/W] at the durations ``dur`` [min] (the record's readings are one minute
    apart: linear between the readings at floor and ceil of each duration) and the steady
    rise per watt. Only the minutes needed are evaluated, each on its own (the value of a
    row does not depend on the other rows; no array as long as the test)."""
    net = _network_cached(_thermal_items(values))
    knots = np.unique(np.concatenate([np.floor(dur), np.ceil(dur)]))
    hist = net.response(knots * 60.0)
    return np.interp(dur, knots, hist), float(net.steady_rise_per_w)


@lru_cache(maxsize=64)
def _geometry_and_h(items: tuple):
    """The guide's geometry and the convection coefficients h_side, h_front (Eqs. 10-12)
    (without building the guide-only network, which the rig's heat balance does not use)."""
    from ..physics import convection
    from ..physics.thermal.geometry import GuideGeometry

    v = dict(items)
    return GuideGeometry.from_params(v), *convection.coefficients(v)


def _rig_rise_rows(values: dict, dur: np.ndarray, y: np.ndarray, rigid: bool):
    """One heat balance in watts (:func:`rsm_lrg.physics.thermal.network.rig_network`) for
    rows of one rig whose leaves differ: the carriage's rise per watt [K/W] at the durations
    ``dur`` [min] (linear between whole minutes, as :func:`_rise_at`) for a watt at the ball
    contacts and for a watt entering the working stage, and the two steady rises per watt, for
    leaves of thickness ``y`` [m] (``rigid``: the RMS), each row's network on its own
    (:func:`rsm_lrg.physics.thermal.network.rig_responses`, one compiled loop)."""
    from ..physics.thermal.network import leaf_terms, rig_bodies, rig_responses

    geometry, hs, hf = _geometry_and_h(_thermal_items(values))
    rig = rig_bodies(values, float(y[0]), rigid=rigid, h_side_w_m2k=hs)
    g_leaf, c_leaf = leaf_terms(values, y)
    lo, hi = np.floor(dur), np.ceil(dur)
    resp, steady = rig_responses(geometry, hs, hf, rig, g_leaf, c_leaf, np.stack([lo, hi], axis=1) * 60.0)
    w = np.where(hi > lo, dur - lo, 0.0)
    unit = resp[:, :, 0] + w[:, None] * (resp[:, :, 1] - resp[:, :, 0])
    return unit[:, 0], unit[:, 1], steady[:, 0], steady[:, 1]


#: Range of the ball contacts' conductance [W/K] over which a calibration reads the two-carriage
#: network from an interpolant in ln g (:class:`rsm_lrg.physics.thermal.two_carriage.ContactInterpolant`):
#: it holds the bounds of calibration model v6 (a third to three times the contact-mechanics
#: estimate 0.350 W/K).
CONTACT_INTERP_W_K = (0.1, 1.2)

#: Parameters that do not enter the two-carriage network (the interpolants are shared across them).
_NOT_NETWORK = frozenset(("ball_contact_conductance_w_k", "viscous_friction_n_s_m", "mu_s", "mu_k",
                          "hinge_damping_ratio", "hinge_yield_pa", "hinge_fatigue_limit_pa",
                          "hinge_tensile_strength_pa", "wear_coefficient", "hardness_hb", "hinge_modulus_pa",
                          "hinge_membrane", "preload_n", "gravity_m_s2", "overconstraint_misfit_m"))

_INTERP: dict = {}
_ROWS: dict = {}
_INTERP_SIZE = 4096

#: How the two-carriage network of a batch's rows is solved: ``"compiled"`` (the default: every
#: distinct row in one compiled loop, :func:`rsm_lrg.physics.thermal.two_carriage.two_carriage_rows`)
#: or ``"dense"`` (each row its own :func:`~rsm_lrg.physics.thermal.two_carriage.two_carriage_network`
#: object, the route before; kept to compare the two, ``benchmarks/bench_simulate.py``). Both give the
#: same numbers; clear the row caches (:func:`clear_row_caches`) when switching to time them.
NETWORK_ROUTE = "compiled"


def clear_row_caches() -> None:
    """Forget the two-carriage rows, interpolants and stage dynamics remembered in this process (the
    results do not change: a timing starts from nothing)."""
    from ..physics.thermal.two_carriage import clear_network_cache

    _ROWS.clear()
    _INTERP.clear()
    _MEMO.clear()
    clear_network_cache()


def _network_items(values: dict) -> tuple:
    """The (name, value) pairs of ``values`` that enter the two-carriage network (a cache key)."""
    return tuple(sorted((k, x) for k, x in values.items() if k not in _NOT_NETWORK))


def _two_carriage_row(values: dict, dur: float, y: float, s: float, msq: float, rigid: bool,
                      interpolate: bool = False, items: tuple | None = None):
    """:func:`_two_carriage_exact`, or (``interpolate``, for a calibration that asks for the same
    rows at many contact conductances) its Chebyshev interpolant in ln g over
    :data:`CONTACT_INTERP_W_K`, built once per row and network parameters (equal to the network to
    about 1e-12 relative; outside the range the network itself). ``items``: the precomputed
    :func:`_network_items` of ``values``."""
    g = float(values["ball_contact_conductance_w_k"])
    if not (interpolate and CONTACT_INTERP_W_K[0] <= g <= CONTACT_INTERP_W_K[1]):
        row_key = (_network_items(values) if items is None else items, g, dur, y, s, msq, rigid)
        hit = _ROWS.get(row_key)
        if hit is None:  # a design's repeated settings, across its batches
            hit = _two_carriage_exact(values, dur, y, s, msq, rigid)
            if len(_ROWS) >= _INTERP_SIZE:
                _ROWS.pop(next(iter(_ROWS)))
            _ROWS[row_key] = hit
        return hit
    from ..physics.thermal.two_carriage import ContactInterpolant

    key = (_network_items(values) if items is None else items, dur, y, s, msq, rigid)
    f = _INTERP.get(key)
    if f is None:
        f = ContactInterpolant(lambda gg: np.array(_two_carriage_exact(
            dict(values, ball_contact_conductance_w_k=gg), dur, y, s, msq, rigid)), *CONTACT_INTERP_W_K)
        if len(_INTERP) >= _INTERP_SIZE:
            _INTERP.pop(next(iter(_INTERP)))
        _INTERP[key] = f
    return tuple(float(x) for x in f(g))


def _two_carriage_exact(values: dict, dur: float, y: float, s: float, msq: float, rigid: bool):
    """Both carriages on one rail (:mod:`rsm_lrg.physics.thermal.two_carriage`, model v6): the
    working carriage's rise per watt [K/W] at the duration ``dur`` [min] (linear between whole
    minutes, as :func:`_rise_at`) of its own friction power and of the other stage's, and the two
    steady rises per watt. Both stages run the same stroke ``s`` [m] and speed (``msq`` = <v²>
    [m²/s²]; one link span drives both, Section 4.1); the RFCMS has leaves of thickness ``y`` [m]."""
    from ..physics.thermal.fixed_order import RowError

    try:
        out = _two_carriage_many(values, np.array([dur]), np.array([y]), np.array([s]), np.array([msq]),
                                 np.array([rigid]))
    except RowError as exc:
        raise ValueError(exc.reason) from None
    return tuple(float(x) for x in out[0])


def _two_carriage_many(values: dict, dur: np.ndarray, y: np.ndarray, s: np.ndarray, msq: np.ndarray,
                       rigid: np.ndarray) -> np.ndarray:
    """:func:`_two_carriage_exact` of many rows with the parameters ``values``, in one compiled loop
    (:func:`rsm_lrg.physics.thermal.two_carriage.two_carriage_rows`; each row's numbers do not depend
    on the others): an array (rows, 4) of the self and other rises and the two steady rises. Raises
    ``RowError`` naming the first row (from 0) that fails."""
    from ..physics.thermal.fixed_order import RowError
    from ..physics.thermal.two_carriage import STAGES, CarriageSetting, cached_network, two_carriage_rows

    lo, hi = np.floor(dur), np.ceil(dur)
    w = np.where(hi > lo, dur - lo, 0.0)
    times = np.stack([lo, hi], axis=1) * 60.0
    if NETWORK_ROUTE == "dense":  # each row its own network object (before issue 34's item 5)
        resp, steady = np.empty((dur.shape[0], 2, 2)), np.empty((dur.shape[0], 2))
        for i in range(dur.shape[0]):
            try:
                run = CarriageSetting(float(y[i]), float(s[i]), float(msq[i]))
                net = cached_network(values, run, run)
            except ValueError as exc:
                raise RowError(i, str(exc)) from None
            node = "rms.carriage" if rigid[i] else "rfcms.carriage"
            for c, src in enumerate(STAGES):
                resp[i, c] = net.response(times[i], node, src)
                steady[i, c] = net.steady_rise(src)[net.node(node)]
    elif NETWORK_ROUTE == "compiled":
        resp, steady = two_carriage_rows(values, y, s, msq, rigid, times)
    else:
        raise ValueError(f"NETWORK_ROUTE must be 'compiled' or 'dense', got {NETWORK_ROUTE!r}")
    me = np.where(rigid, 0, 1)
    r = np.arange(dur.shape[0])
    r_self, r_other = resp[r, me], resp[r, 1 - me]
    return np.stack([r_self[:, 0] + w * (r_self[:, 1] - r_self[:, 0]), r_other[:, 0] + w * (r_other[:, 1] - r_other[:, 0]),
                     steady[r, me], steady[r, 1 - me]], axis=1)


def _two_carriage_batch(base: dict, row_keys: np.ndarray, first: np.ndarray, names: list,
                        n: int) -> tuple[np.ndarray, int, str]:
    """The network parts (rows of ``row_keys``: dur, y, s, msq, rigid, then the values of the parameter
    columns ``names``) of a batch's distinct rows (``first``: the batch row each stands for), each looked up
    in (or added to) the shared cache of rows, the rest solved together per parameter set
    (:func:`_two_carriage_many`). Returns the parts (len(first), 4) and the first failing batch row
    with its reason (``-1, ""`` where none fails)."""
    from ..physics.thermal.fixed_order import RowError
    from ..physics.thermal.two_carriage import network_items

    parts = np.full((len(first), 4), np.nan)
    todo: dict = {}  # network parameters -> [(distinct row, key)]
    sets: dict = {}  # parameter values -> (network parameters and contact conductance, the values)
    enter = {k for k, _ in network_items(dict.fromkeys(names, 0.0))} | {"ball_contact_conductance_w_k"}
    cols = [j for j, k in enumerate(names) if k in enter]  # the other columns do not change the network
    for g in range(len(first)):
        over = tuple(float(row_keys[g, 5 + j]) for j in cols)
        if over not in sets:
            vals = dict(base, **{names[j]: x for j, x in zip(cols, over)})
            sets[over] = ((network_items(vals), float(vals["ball_contact_conductance_w_k"])), vals)
        net, _ = sets[over]
        dur, y, s, msq, rigid = (float(x) for x in row_keys[g, :5])
        key = (*net, dur, y, s, msq, bool(rigid))
        hit = _ROWS.get(key)
        if hit is not None:  # a design's repeated settings, across its batches
            parts[g] = hit
        else:
            todo.setdefault(net, []).append((g, key, over))
    bad, why = n, ""
    for rows in todo.values():  # rows whose parameters differ only outside the network: one loop
        idx = np.array([g for g, _, _ in rows])
        vals = sets[rows[0][2]][1]
        k = row_keys[idx]
        try:
            parts[idx] = _two_carriage_many(vals, k[:, 0], k[:, 1], k[:, 2], k[:, 3], k[:, 4] != 0)
        except RowError as exc:
            if int(first[idx[exc.row]]) < bad:
                bad, why = int(first[idx[exc.row]]), exc.reason
            continue
        except ValueError as exc:  # the parameter set itself
            if int(first[idx[0]]) < bad:
                bad, why = int(first[idx[0]]), str(exc)
            continue
        for g, key, _ in rows:
            if len(_ROWS) >= _INTERP_SIZE:
                _ROWS.pop(next(iter(_ROWS)))
            _ROWS[key] = tuple(float(x) for x in parts[g])
    return parts, (bad if bad < n else -1), why


def _lagged_rise_at(values: dict, dur: np.ndarray, tau: np.ndarray, unit: np.ndarray, q: np.ndarray):
    """Unit rise [K/W] at the durations ``dur`` [min] of a heat that arrives through the lag
    ``tau`` [s] (the drive heat behind the working stage's heat capacity), read like
    :func:`_rise_at` (linear between whole minutes); ``unit`` (the step's) where ``tau`` is
    0 or no drive heat flows (nothing to compute)."""
    out = np.array(unit, float)
    need = (tau > 0) & (q != 0)
    if not need.any():
        return out
    net = _network_cached(_thermal_items(values))
    d, t = dur[need], tau[need]
    lo, hi = np.floor(d), np.ceil(d)
    r_lo = net.lagged_response(lo * 60.0, t)
    r_hi = net.lagged_response(hi * 60.0, t)
    w = np.where(hi > lo, d - lo, 0.0)
    out[need] = r_lo + w * (r_hi - r_lo)
    return out


# ----------------------------------------------------------------------------------------
# stage dynamics (a row's result does not depend on its batch)
# ----------------------------------------------------------------------------------------
def _cycle_metrics(s, v, a, rigid, p, cols, memo=False):
    """Sliding per cycle [m], cycle time [s], viscous work per cycle [J] and peak hinge
    deflection [m] of every row, from
    :func:`rsm_lrg.physics.dynamics.cycle_metrics` (``method="auto"``: the quasi-static limit
    where it is valid, the vectorised stick-slip integration elsewhere; RMS rows slide 2·s).

    The integrator gives every row its own number of steps per cycle, so a row's result does
    not depend on the rows integrated with it; batches are still cut at fixed row indices
    (:data:`rsm_lrg.surrogate.execute.DEFAULT_BATCH_ROWS`) whatever the executor or the
    number of workers.
    """
    from ..physics import dynamics

    key = None
    if memo and s.size <= _MEMO_MAX_ROWS:  # calibration repeats the same rows: memoise
        pk = tuple((k, x) for k, x in p.to_dict().items() if k not in _NOT_DYNAMICS)  # without heat-only fields
        key = (pk, s.tobytes(), v.tobytes(), a.tobytes(), rigid.tobytes(),
               tuple((k, np.asarray(x, float).tobytes()) for k, x in sorted(cols.items())))
        hit = _MEMO.get(key)
        if hit is not None:
            return tuple(x.copy() for x in hit)
    m = dynamics.cycle_metrics(s, v, a, stage=rigid, params=p, method="auto", max_steps_per_cycle=_MAX_STEPS,
                               **cols)
    out = tuple(np.asarray(x, float) for x in (m.sliding_distance_m, m.cycle_time_s, m.viscous_work_j,
                                               m.peak_deflection_m))
    if key is not None:
        if len(_MEMO) >= _MEMO_SIZE:
            _MEMO.pop(next(iter(_MEMO)))
        _MEMO[key] = tuple(x.copy() for x in out)
    return out


#: Most integration steps per cycle of a row (the paper's rows need 40-600): a row needing
#: more -- a hinge period a thousand times shorter than the cycle where the quasi-static limit
#: does not hold, e.g. a 10 um stroke -- is refused with its settings named, rather than
#: integrated for minutes.
_MAX_STEPS = 10_000

#: Parameters that do not enter the stage dynamics (calibrating them reuses the memo).
_NOT_DYNAMICS = ("drive_heat_w", "stage_loss_conductance_w_k", "hinge_yield_pa", "hinge_conductivity_w_mk",
                 "stage_specific_heat_j_kgk", "heat_balance", "ball_contact_conductance_w_k",
                 "joint_conductance_w_m2k", "base_heat_capacity_j_k", "base_loss_conductance_w_k",
                 "hinge_density_kg_m3", "hinge_specific_heat_j_kgk", "two_carriage", "other_stage_running",
                 "carriage_spacing_m", "hinge_fatigue_limit_pa", "hinge_tensile_strength_pa", "guide_modulus_pa",
                 "guide_poisson", "ball_modulus_pa", "ball_poisson", "ball_conductivity_w_mk")



#: Memo of the dynamics of small batches (calibration evaluates the same rows many times,
#: with only the heat and thermal parameters changing).
_MEMO: dict = {}
_MEMO_SIZE = 256
_MEMO_MAX_ROWS = 2000


# ----------------------------------------------------------------------------------------
# the row model
# ----------------------------------------------------------------------------------------
def evaluate_rows(arrays, *, params=None, calibration=None, row_start: int = 0, seed: int = 0,
                  noise_sd: float = 0.0, duration_min: float = 50.0, memo: bool = False) -> dict:
    """Responses of a batch of rows (see the module docstring).

    Parameters
    ----------
    arrays : rsm_lrg.surrogate.design_input.DesignArrays
        The checked rows.
    params : LRGParams
        Base parameters.
    calibration : dict
        ``{name: value}`` of calibrated parameters: LRGParams names (override ``params``)
        and :data:`SURROGATE_PARAMETERS`. A design column of the same name wins.
    row_start : int
        Index of the batch's first row in the whole design (keys the noise streams).
    seed : int
        Noise seed (see :mod:`.noise`).
    noise_sd : float
        SD of each thermocouple reading's noise [°C]; 0: deterministic.
    duration_min : float
        Test duration [min] where the design has no ``test_duration_min`` column.
    memo : bool
        Remember the stage dynamics of these rows (calibration re-evaluates the same rows
        with only the heat parameters changed).

    Returns
    -------
    dict of numpy arrays: ``tcr_c_per_min``, ``temperature_rise_k``, ``steady_rise_k``,
    ``wear_volume_m3_per_h``, ``sliding_distance_m_per_cycle``, ``heat_w``, ``cycle_time_s``.
    """
    from ..physics.jit import few_rows

    with few_rows(arrays.n):  # a one-row batch: the kernels without numba's start-up (same numbers)
        return _evaluate_rows(arrays, params=params, calibration=calibration, row_start=row_start, seed=seed,
                              noise_sd=noise_sd, duration_min=duration_min, memo=memo)


def _evaluate_rows(arrays, *, params, calibration, row_start: int, seed: int, noise_sd: float,
                   duration_min: float, memo: bool) -> dict:
    from ..physics import dynamics, heat, hinge, wear
    from ..physics.params import LRGParams, param_names
    from .noise import reading_noise

    duration_min = check_duration(duration_min)
    p = params if params is not None else LRGParams()
    cal = dict(calibration or {})
    extra = {k: float(cal.pop(k, d[0])) for k, d in SURROGATE_PARAMETERS.items()}
    known = set(param_names())
    unknown = [k for k in cal if k not in known]
    if unknown:
        raise ValueError(f"calibration: unknown parameter {unknown[0]!r}")
    if cal:
        p = p.with_overrides(**cal)
    n = arrays.n
    c = arrays.columns
    s, v, a = c["stroke_m"], c["velocity_m_s"], c["acceleration_m_s2"]
    rigid = arrays.rigid
    pcols = {k: c[k] for k in arrays.param_columns}
    for k in list(pcols):
        if k in SURROGATE_PARAMETERS:
            extra[k] = pcols.pop(k)
    y = np.where(rigid & ~np.isfinite(c["thickness_m"]), p.hinge_thickness_m, c["thickness_m"])
    dyn_cols = {k: x for k, x in pcols.items() if k not in ("test_duration_min", "ambient_c")}
    dyn_cols["hinge_thickness_m"] = y

    def col(name):
        return pcols[name] if name in pcols else getattr(p, name)

    # 1-2: motion and stage dynamics
    slide, T, visc, peak = _cycle_metrics(s, v, a, rigid, p, dyn_cols, memo=memo)
    hv = dict(p.to_dict(), **{k: x for k, x in dyn_cols.items()})
    # the carriage's load: F0 + m_t g, plus the leaves' over-constraint load (RFCMS only)
    load = dynamics.carriage_load(dict(hv, overconstraint_misfit_m=np.where(
        rigid, 0.0, np.asarray(hv["overconstraint_misfit_m"], float))))
    # 3: friction heat, cycle-averaged (Eq. 8 mechanism): Coulomb work + viscous work
    power = (col("mu_k") * load * slide + visc) / T
    balance = bool(p.heat_balance)
    if balance and np.any(np.asarray(extra["heat_partition"]) != 1.0):
        raise ValueError("heat_partition must stay 1 with heat_balance = true: the share of the friction heat "
                         "that reaches the carriage follows from the network's conductances")
    q = power if balance else (power / p.thermal_equivalent_j_per_cal if p.heat_in_calories else power)
    q = q * extra["heat_partition"]
    q_fric = np.broadcast_to(q, (n,)).astype(float)
    # drive heat (a constant drive_heat_w, the drive element's Coulomb friction F_d <|v|> with
    # the working stage's mean speed 2 s / T, its viscous friction c_d <v^2>) through the joint
    # between stage and carriage: the leaves (RFCMS), rigid (RMS); it arrives behind the working
    # stage's heat capacity
    g_joint = np.where(rigid, np.inf, heat.leaf_conductance(hv["hinge_count"], hv["hinge_conductivity_w_mk"],
                                                            hv["hinge_width_m"], y, hv["hinge_length_m"]))
    p_drive = np.asarray(hv["drive_heat_w"], float) + extra["drive_friction_n"] * 2.0 * s / T
    if np.any(extra["drive_viscous_n_s_m"] != 0):
        from ..physics import motion

        p_drive = p_drive + extra["drive_viscous_n_s_m"] * motion.mean_square_speed(s, v, a, col("dwell_s"),
                                                                                  col("jerk_time_s"))
    p_drive = np.broadcast_to(np.asarray(p_drive, float), (n,)).astype(float)
    q_drive = p_drive if balance else np.broadcast_to(
        heat.drive_heat_to_carriage(p_drive, g_joint, hv["stage_loss_conductance_w_k"]), (n,)).astype(float)
    tau_stage = np.broadcast_to(heat.stage_time_constant(
        (1.0 - np.asarray(hv["frame_mass_fraction"], float)) * np.asarray(hv["stage_mass_kg"], float)
        * np.asarray(hv["stage_specific_heat_j_kgk"], float), g_joint, hv["stage_loss_conductance_w_k"]),
        (n,)).astype(float)
    q = q_fric + q_drive
    # peak stress of the leaves (bending + membrane) against the yield strength
    stress = np.where(rigid, 0.0, hinge.hinge_peak_stress(hv["hinge_modulus_pa"], y, hv["hinge_length_m"], peak,
                                                          membrane=bool(p.hinge_membrane)))

    # 4-5: thermal record
    dur = np.broadcast_to(np.asarray(pcols.get("test_duration_min", duration_min), float), (n,))
    end_idx = np.ceil(dur - 1e-9).astype(np.int64)
    unit_end = np.empty(n)
    steady = np.empty(n)
    base = p.to_dict()
    th_names = [k for k, _ in _thermal_items(base) if k in pcols]
    if th_names:
        keys = np.stack([np.broadcast_to(pcols[k], (n,)) for k in th_names], axis=1)
        uniq, inv = np.unique(keys, axis=0, return_inverse=True)
        inv = inv.reshape(-1)
    else:
        uniq, inv = np.zeros((1, 0)), np.zeros(n, dtype=int)
    lag_end = np.empty(n)
    steady_drive = np.empty(n)
    two = bool(p.two_carriage)
    if two:  # both carriages on one rail (model v6): the other stage's friction heat, no drive heat
        if not balance:
            raise ValueError("two_carriage = true needs heat_balance = true (one heat balance in watts)")
        if np.any(p_drive != 0):
            raise ValueError("the two-carriage rig has no drive heat (no loss model of the drive with its own "
                             "evidence; Section 2.2): set drive_heat_w, drive_friction_n and drive_viscous_n_s_m to 0")
        q_drive = np.zeros(n)  # from here on: the other stage's friction power [W]
        q = q_fric
        if bool(p.other_stage_running):
            o_slide, o_T, o_visc, _ = _cycle_metrics(s, v, a, ~rigid, p, dyn_cols, memo=memo)
            o_load = dynamics.carriage_load(dict(hv, overconstraint_misfit_m=np.where(
                ~rigid, 0.0, np.asarray(hv["overconstraint_misfit_m"], float))))
            q_drive = np.broadcast_to((col("mu_k") * o_load * o_slide + o_visc) / o_T, (n,)).astype(float)
        from ..physics import motion

        msq = np.broadcast_to(motion.mean_square_speed(s, v, a, col("dwell_s"), col("jerk_time_s")), (n,))
        base2 = p.to_dict()
        items0 = _network_items(base2) if not pcols else None
        # rows with the same settings and parameters share one network solution (replicates, a grid)
        names_t = sorted(pcols)
        keys_t = np.stack([dur, y, np.broadcast_to(s, (n,)), msq, rigid.astype(float)]
                          + [np.broadcast_to(np.asarray(pcols[k], float), (n,)) for k in names_t], axis=1)
        uniq_t, first_t, inv_t = np.unique(keys_t, axis=0, return_index=True, return_inverse=True)
        inv_t = inv_t.reshape(-1)
        if memo:  # a calibration: the same rows at many contact conductances (interpolants in ln g)
            parts_t = np.empty((len(uniq_t), 4))
            for g in np.argsort(first_t, kind="stable").tolist():  # in row order: the first bad row is named
                i = int(first_t[g])
                vals = dict(base2, **{k: float(np.broadcast_to(pcols[k], (n,))[i]) for k in names_t})
                try:
                    parts_t[g] = _two_carriage_row(vals, float(dur[i]), float(y[i]), float(s[i]), float(msq[i]),
                                                   bool(rigid[i]), memo, items0)
                except ValueError as exc:
                    raise ValueError(f"row {row_start + i + 1}: {exc}") from None
        else:  # every distinct row's network in one compiled loop
            order = np.argsort(first_t, kind="stable")
            parts_o, bad, why = _two_carriage_batch(base2, uniq_t[order], first_t[order], names_t, n)
            if bad >= 0:
                raise ValueError(f"row {row_start + bad + 1}: {why}")
            parts_t = np.empty_like(parts_o)
            parts_t[order] = parts_o
        unit_end[:], lag_end[:], steady[:], steady_drive[:] = parts_t[inv_t].T
    if balance and not two:  # each row its own rig network (rig_responses), grouped by stage kind and per-row parameters
        from ..physics.thermal.fixed_order import RowError

        names_b = sorted(pcols)
        keys_b = np.stack([rigid.astype(float)] + [np.broadcast_to(np.asarray(pcols[k], float), (n,))
                                                   for k in names_b], axis=1)
        uniq_b, inv_b = np.unique(keys_b, axis=0, return_inverse=True)
        inv_b = inv_b.reshape(-1)
        for g, row in enumerate(uniq_b):
            idx = np.flatnonzero(inv_b == g)
            vals = dict(base, **{k: float(x) for k, x in zip(names_b, row[1:].tolist())})
            try:
                unit_end[idx], lag_end[idx], steady[idx], steady_drive[idx] = _rig_rise_rows(
                    vals, dur[idx], y[idx], bool(row[0]))
            except RowError as exc:
                raise ValueError(f"row {row_start + int(idx[exc.row]) + 1}: {exc.reason}") from None
            except ValueError as exc:
                raise ValueError(f"row {row_start + int(idx[0]) + 1}: {exc}") from None
    for g, row in enumerate(uniq if not balance else ()):
        vals = dict(base, **dict(zip(th_names, row)))
        m = inv == g
        try:
            unit_end[m], steady[m] = _rise_at(vals, dur[m])
            lag_end[m] = _lagged_rise_at(vals, dur[m], tau_stage[m], unit_end[m], q_drive[m])
        except ValueError as exc:
            if not th_names:  # the base parameters themselves
                raise
            i = int(np.flatnonzero(m)[0])
            raise ValueError(f"row {row_start + i + 1}: {exc}") from None
    rise_true = q_fric * unit_end + q_drive * lag_end
    if noise_sd > 0:
        rows = np.arange(row_start, row_start + n, dtype=np.uint64)
        z0 = reading_noise(seed, rows, [0])[:, 0, :].mean(axis=1)
        z1 = np.empty(n)
        for e in np.unique(end_idx):
            m = end_idx == e
            z1[m] = reading_noise(seed, rows[m], [int(e)])[:, 0, :].mean(axis=1)
        rise = rise_true + noise_sd * (z1 - z0)
    else:
        rise = rise_true
    tcr = rise / dur

    # 6: wear (Eq. 13)
    fi = wear.ball_normal_force(load, np.asarray(col("ball_rows")) * np.asarray(col("balls_per_row")),
                                col("contact_angle_deg"))
    vw = wear.wear_rate_per_hour(col("wear_coefficient"), fi, slide, T, wear.brinell_to_pa(col("hardness_hb")))
    b = lambda x: np.broadcast_to(np.asarray(x, float), (n,)).copy()  # noqa: E731
    out = {
        "tcr_c_per_min": b(tcr), "temperature_rise_k": b(rise),
        "steady_rise_k": b(q_fric * steady + q_drive * steady_drive if balance else q * steady),
        "wear_volume_m3_per_h": b(vw), "sliding_distance_m_per_cycle": b(slide),
        "heat_w": b(q), "cycle_time_s": b(T),
        "hinge_peak_stress_pa": b(stress),
        "hinge_yields": np.broadcast_to(stress > np.asarray(hv["hinge_yield_pa"], float), (n,)).copy(),
    }
    for k, x in out.items():  # the physics must not overflow or divide by zero silently
        bad = ~np.isfinite(x)
        if bad.any():
            i = int(np.flatnonzero(bad)[0])
            raise ValueError(f"row {row_start + i + 1}: the surrogate gives a non-finite {k} ({x[i]:g}); "
                             f"the row's settings or parameters are outside what the physics can handle")
    return out
