"""Both stages of the rig at every Table 3 setting: friction heat, carriage and working-stage rises.

The rig of Section 4.1 (:mod:`.thermal.two_carriage`): the RMS and the RFCMS on one rail and base,
driven together by the link span. For each of the 3⁴ = 81 settings of Table 3 (the three levels of
thickness, stroke, velocity and acceleration) both stages' friction power (Eq. 8 in watts,
cycle-averaged from the stage dynamics, :func:`.dynamics.cycle_metrics`, plus the block's viscous
friction) heats the network for the test's duration; the report gives each carriage's and each
working stage's rise at the end of the test, the RFCMS carriage's κ (Eq. 18), the heat balance of
every network, and the ball contacts' conductance from contact mechanics beside the one used.

>>> r = rig_report(levels=((3e-4,), (0.05,), (0.5,), (30.0,)))
>>> len(r.rows), r.max_heat_balance_error < 1e-12, r.max_stage_rise_k < STAGE_RISE_LIMIT_K
(1, True, True)
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import Any

import numpy as np

from . import dynamics, motion
from .contact import BallContactConductance, ball_contact_conductance
from .params import LRGParams

__all__ = ["RigRow", "RigReport", "rig_report", "TABLE3_LEVELS", "STAGE_RISE_LIMIT_K"]

#: The three levels of each factor of Table 3 (thickness [m], stroke [m], velocity [m/s],
#: acceleration [m/s²]).
TABLE3_LEVELS = ((1e-4, 3e-4, 5e-4), (0.04, 0.05, 0.06), (0.4, 0.5, 0.6), (20.0, 30.0, 40.0))

#: Plausibility limit of a working stage's rise in a 50-min test [K]: the carriage itself rises
#: 1-2.5 K (Fig. 9, Table 4: κ 0.026-0.051 °C/min) and the paper's FEM steady rise is 4.0 K; a
#: stage beyond 5 K would need a heat source the paper does not have.
STAGE_RISE_LIMIT_K = 5.0


@dataclass(frozen=True)
class RigRow:
    """One Table 3 setting; rises [K] at the end of the test, powers [W], κ [°C/min]."""

    thickness_m: float
    stroke_m: float
    velocity_m_s: float
    acceleration_m_s2: float
    power_rfcms_w: float
    power_rms_w: float
    rfcms_carriage_rise_k: float
    rfcms_stage_rise_k: float
    rms_carriage_rise_k: float
    rms_stage_rise_k: float
    rfcms_tcr_c_per_min: float
    rms_tcr_c_per_min: float

    def to_dict(self) -> dict[str, float]:
        return dict(self.__dict__)


@dataclass(frozen=True)
class RigReport:
    """The rig at every Table 3 setting (:func:`rig_report`)."""

    rows: tuple
    duration_min: float
    other_stage_running: bool
    contact: BallContactConductance
    contact_used_w_k: float
    viscous_friction_n_s_m: float
    max_heat_balance_error: float
    convection: dict

    @property
    def max_stage_rise_k(self) -> float:
        """Largest working-stage rise of either stage over the settings [K]."""
        return max(max(r.rfcms_stage_rise_k, r.rms_stage_rise_k) for r in self.rows)

    def to_dict(self) -> dict[str, Any]:
        c = self.contact
        return {"stages": ["rms", "rfcms"], "one_rail_one_base": True,
                "other_stage_running": self.other_stage_running,
                "evidence": "Section 4.1: 'the two types of stages were assembled on the same rail' and 'were "
                            "driven simultaneously by the link span'",
                "drive_heat": "none: the paper did not consider the motor's heat (Section 2.2) and no loss model "
                              "of the drive with its own evidence is at hand",
                "duration_min": self.duration_min, "viscous_friction_n_s_m": self.viscous_friction_n_s_m,
                "contact": {"hertz_a_m": c.contact.a_m, "hertz_b_m": c.contact.b_m,
                            "hertz_pressure_pa": c.contact.pressure_pa, "n_contacts": c.n_contacts,
                            "estimate_w_k": c.series_w_k, "used_w_k": self.contact_used_w_k,
                            "used_over_estimate": self.contact_used_w_k / c.series_w_k,
                            "to_race_share": c.to_race_share},
                "convection": self.convection,
                "max_heat_balance_error": self.max_heat_balance_error,
                "stage_rise_limit_k": STAGE_RISE_LIMIT_K, "max_stage_rise_k": self.max_stage_rise_k,
                "rows": [r.to_dict() for r in self.rows]}

    def to_text(self) -> str:
        c = self.contact
        rf = np.array([r.rfcms_stage_rise_k for r in self.rows])
        rm = np.array([r.rms_stage_rise_k for r in self.rows])
        car = np.array([r.rfcms_carriage_rise_k for r in self.rows])
        lines = [f"the rig (Section 4.1): RMS and RFCMS on one rail and base, the other stage "
                 f"{'running' if self.other_stage_running else 'at rest'} during the test, no drive heat; "
                 f"{len(self.rows)} Table 3 settings, {self.duration_min:g} min",
                 f"  ball contacts, one side: Hertz a = {c.contact.a_m * 1e3:.3f} mm, b = {c.contact.b_m * 1e3:.3f} mm, "
                 f"p0 = {c.contact.pressure_pa / 1e6:.0f} MPa; Yovanovich both sides {c.series_w_k:.3f} W/K "
                 f"(used {self.contact_used_w_k:.3f} W/K, {self.contact_used_w_k / c.series_w_k:.2f}x)",
                 f"  RFCMS carriage rise {car.min():.2f}-{car.max():.2f} K; working stage rise RFCMS "
                 f"{rf.min():.2f}-{rf.max():.2f} K, RMS {rm.min():.2f}-{rm.max():.2f} K (limit "
                 f"{STAGE_RISE_LIMIT_K:g} K); heat balance closes to {self.max_heat_balance_error:.1e}"]
        return "\n".join(lines)


def rig_report(params: LRGParams | None = None, *, levels=TABLE3_LEVELS, duration_min: float | None = None,
               dx_m: float = 1e-2) -> RigReport:
    """Both stages at every combination of ``levels`` (default the 81 settings of Table 3).

    Parameters
    ----------
    params : LRGParams
        The parameters (``ball_contact_conductance_w_k``, ``viscous_friction_n_s_m``,
        ``other_stage_running``, ``carriage_spacing_m``, ...); a calibration's values are passed here.
    levels : four sequences
        Thicknesses [m], strokes [m], velocities [m/s], accelerations [m/s²].
    duration_min : float
        Test duration [min] (default ``test_duration_min``).

    Returns
    -------
    RigReport
    """
    from .thermal.two_carriage import STAGES, CarriageSetting, cached_network

    p = params or LRGParams()
    dur = float(p.test_duration_min if duration_min is None else duration_min)
    v = p.to_dict()
    grid = list(itertools.product(*[list(map(float, lv)) for lv in levels]))
    if not grid:
        raise ValueError("levels must give at least one setting")
    y, s, vel, acc = (np.array(c) for c in zip(*grid))
    n = len(grid)
    cm = dynamics.cycle_metrics(np.concatenate([s, s]), np.concatenate([vel, vel]), np.concatenate([acc, acc]),
                                stage=["rfcms"] * n + ["rms"] * n, params=p, method="auto",
                                hinge_thickness_m=np.concatenate([y, y]))
    power = np.asarray(cm.mean_friction_power_w, float)
    p_rf, p_rm = power[:n], power[n:]
    running = bool(p.other_stage_running)
    msq = np.asarray(motion.mean_square_speed(s, vel, acc, p.dwell_s, p.jerk_time_s), float)
    rows = []
    worst = 0.0
    conv: dict = {}
    t = np.array([dur * 60.0])
    for i in range(n):
        run = CarriageSetting(float(y[i]), float(s[i]), float(msq[i]))
        net = cached_network(v, run, run, dx_m=dx_m)
        worst = max(worst, *(abs(net.heat_balance(st) - 1.0) for st in STAGES))
        if i == 0 or float(net.convection["rfcms"]["reynolds"]) > conv.get("reynolds_max", 0.0):
            conv = {"reynolds_max": float(net.convection["rfcms"]["reynolds"]),
                    "air_speed_max_m_s": float(net.convection["rfcms"]["air_speed_m_s"]),
                    "sides": "Eq. 11 (laminar flat plate, Re < 5e5, Pr >= 0.6; Incropera Eq. 7.23)",
                    "fronts": "Churchill-Bernstein (Re Pr >= 0.2; Incropera Eq. 7.54): Eq. 12 is fitted on "
                              "4e3 <= Re <= 1.5e4 (Hilpert's vertical plate, Incropera Table 7.3)",
                    "air_speed": "sqrt(omega^2 + <v^2>) on the moving bodies; the rail and base at omega"}
        rises = {}
        for body in ("rfcms.carriage", "rfcms.stage", "rms.carriage", "rms.stage"):
            own = "rfcms" if body.startswith("rfcms") else "rms"
            other = "rms" if own == "rfcms" else "rfcms"
            q_own = p_rf[i] if own == "rfcms" else p_rm[i]
            q_oth = (p_rm[i] if own == "rfcms" else p_rf[i]) if running else 0.0
            rises[body] = float(q_own * net.response(t, body, own)[0] + q_oth * net.response(t, body, other)[0])
        rows.append(RigRow(float(y[i]), float(s[i]), float(vel[i]), float(acc[i]), float(p_rf[i]), float(p_rm[i]),
                           rises["rfcms.carriage"], rises["rfcms.stage"], rises["rms.carriage"], rises["rms.stage"],
                           rises["rfcms.carriage"] / dur, rises["rms.carriage"] / dur))
    return RigReport(tuple(rows), dur, running, ball_contact_conductance(v), float(p.ball_contact_conductance_w_k),
                     float(p.viscous_friction_n_s_m), worst, conv)
