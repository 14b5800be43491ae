"""Calibration of the surrogate's unknown parameters to measured runs (Table 4).

At most three parameters that the paper does not give, each with a physical meaning and
bounds, are fitted by bounded nonlinear least squares (:func:`scipy.optimize.least_squares`,
trust-region reflective) to the measured response of noise-free virtual runs at the measured
settings. Reported: R², RMSE, standard errors from the Jacobian at the optimum
(``s²·(JᵀJ)⁻¹``, s² = SSR/(n − p)), and leave-one-out cross-validation (each run refitted
without it and predicted; LOO R² = 1 − PRESS/SS_tot). No offsets or correction terms:
every parameter enters through a mechanism of :mod:`rsm_lrg.surrogate.runs`.

The result is written to a TOML file (``data/calibration.toml`` ships with the package and
is what :func:`rsm_lrg.simulate` uses by default).
"""

from __future__ import annotations

import dataclasses
import hashlib
import itertools
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ParameterError
from ..present import format_g

__all__ = [
    "CALIBRATION_FILE", "DEFAULT_PARAMETERS", "ParameterSpec", "ParameterEstimate",
    "Calibration", "calibrate", "load_calibration", "resolve_calibration", "calibration_toml",
    "OTHER_PARAMETERS", "file_sha256", "documented_bounds", "MODELS", "CalibrationModel", "DEFAULT_MODEL",
    "PAPER_PRESS_R2",
    "DRIVE_FRICTION", "DRIVE_VISCOUS", "BALL_CONTACT", "aicc", "profile_interval",
]

#: The paper's quadratic (Eq. 19) predicts unseen runs with R² 0.818 (PRESS 2.079e-4 against
#: SS_tot; Table 5 refitted, ../shared/paper/DIGEST.md Section 5): the yardstick of ``loo_r2``.
PAPER_PRESS_R2 = 0.818

#: Name of the shipped calibration file.
CALIBRATION_FILE = "calibration.toml"


@dataclass(frozen=True)
class ParameterSpec:
    """A parameter to calibrate: name, bounds and starting value, in its unit."""

    name: str
    lower: float
    upper: float
    start: float
    unit: str
    meaning: str


#: The parameters calibrated by default (at most three; see the module docstring).
DEFAULT_PARAMETERS = (
    ParameterSpec("heat_partition", 0.01, 1.0, 0.5, "1",
                  "share of the friction heat of Eq. 8 (as written, divided by J) that enters "
                  "the guide; the rest goes into the stage, the lubricant and the seals"),
    ParameterSpec("viscous_friction_n_s_m", 0.0, 30.0, 3.0, "N s/m",
                  "speed-proportional friction of the lubricated, sealed block (LuGre sigma_2): "
                  "the force c_v * v acts on the sliding carriage in the stage dynamics and its "
                  "work adds to the Coulomb heat of Eq. 8"),
    ParameterSpec("hinge_damping_ratio", 0.01, 3.0, 0.5, "1",
                  "effective damping ratio of the frame on its hinges (structure, bolted "
                  "joints, lubricant film), zeta = C_n / (2 sqrt(n K_n m_f)); the paper does "
                  "not give C_n; sets how much the frame rings and overshoots after each stop"),
)

#: Thickness mechanisms (one physical parameter each, :mod:`rsm_lrg.surrogate.runs`).
DRIVE_HEAT = ParameterSpec(
    "drive_heat_w", 0.0, 2.0, 0.2, "W",
    "heat the drive puts into the working stage; the stage loses it to the air (G_s = "
    "stage_loss_conductance_w_k) and conducts the rest through the leaves, G = n lambda w y / l "
    "(proportional to the leaf thickness y), into the carriage: P_d G/(G + G_s); the RMS's rigid "
    "joint passes all of it")
OVERCONSTRAINT = ParameterSpec(
    "overconstraint_misfit_m", 0.0, 2e-5, 2e-6, "m",
    "misfit of the stage's and frame's clamping faces in the leaves' stiff in-plane direction; "
    "loads the guide through the leaves with n E y w^3/l^3 e (proportional to y), added to "
    "F0 + m_t g in the friction of Eqs. 2 and 8 (RFCMS only)")
DRIVE_FRICTION = ParameterSpec(
    "drive_friction_n", 0.0, 20.0, 1.0, "N",
    "Coulomb friction force of the drive element fixed to the working stage (nut, coupling, "
    "cable carrier): its heat F_d <|v|> (<|v|> = 2 s / T, the stage's mean speed) enters the "
    "working stage, which loses it to the air (G_s) and conducts the rest through the leaves "
    "(G = n lambda w y / l, proportional to y) into the carriage, P G/(G + G_s), behind the "
    "stage's heat capacity (tau = m_ws c/(G + G_s)); the RMS's rigid joint passes all of it. "
    "Upper bound 20 N: four times the guide's own breakaway force (Eq. 2, 5.2 N) -- a drive "
    "dragging more would defeat the stage's fine positioning")
DRIVE_VISCOUS = ParameterSpec(
    "drive_viscous_n_s_m", 0.0, 30.0, 1.0, "N s/m",
    "speed-proportional friction of the drive element fixed to the working stage (lubricated nut, "
    "seal, or the eddy-current drag of a linear motor): its heat c_d <v^2> enters the working "
    "stage, which loses it to the air (G_s) and conducts the rest through the leaves (G = n "
    "lambda w y / l, proportional to y) into the carriage, P G/(G + G_s), behind the stage's heat "
    "capacity (tau = m_ws c/(G + G_s)); the RMS's rigid joint passes all of it. Bounds those of "
    "the block's own viscous friction c_v")
VISCOUS = DEFAULT_PARAMETERS[1]
BALL_CONTACT = ParameterSpec(
    "ball_contact_conductance_w_k", 0.01, 20.0, 0.62, "W/K",
    "conductance between the ball contacts and the carriage (the same to the rail), all contacts of a side: "
    "with the rig's other bodies (frame, leaves, working stage, rail, base; data/lrg_shs15v.toml) it sets "
    "which share of the friction heat (in watts) reaches the carriage. Hertzian constriction estimate 0.62 W/K "
    "(1/(4 lambda a) per contact, a ~ 0.05 mm); bounds from 1/60 of it (a dry, barely touching contact) to "
    "30 times it (the perfect contact of the paper's FEM gives about 20)")


#: The ball contacts' conductance of one side from contact mechanics at the default parameters
#: (:func:`rsm_lrg.physics.contact.ball_contact_conductance`: Hertz ellipse of a 3.41 N ball
#: load, Yovanovich constriction on both sides of each of the 72 contacts) [W/K]; a test checks
#: it against the physics.
HERTZ_CONTACT_W_K = 0.3504

BALL_CONTACT_HERTZ = ParameterSpec(
    "ball_contact_conductance_w_k", HERTZ_CONTACT_W_K / 3.0, 3.0 * HERTZ_CONTACT_W_K, HERTZ_CONTACT_W_K, "W/K",
    "conductance of the ball contacts of one side (ball centre to raceway body, all 72 contacts; the heat "
    "released at a contact splits between ball and raceway by their constriction conductances): held within "
    "3x of the contact-mechanics estimate 0.350 W/K (Hertz ellipse a = 0.115 mm, b = 0.018 mm under 3.41 N; "
    "Yovanovich's K(e)/(2 pi lambda a) on both sides of each contact), since grease menisci and the "
    "roughness can raise it and a thin lubricant film lower it")


@dataclass(frozen=True)
class CalibrationModel:
    """A calibration model: the physics it fixes and the parameters it calibrates."""

    name: str
    fixed: tuple  # ((name, value), ...) LRGParams overrides
    parameters: tuple  # ParameterSpec
    description: str


#: The calibration models (``rsm-lrg calibrate --model NAME``; the ``model`` key of a file).
MODELS = {
    "v2": CalibrationModel(
        "v2", (("hinge_membrane", False),), DEFAULT_PARAMETERS,
        "small-deflection hinge of Eq. 1 (no membrane stiffening), frame damping calibrated; the "
        "calibration shipped before issue 15 (R2 0.829, leave-one-out 0.791, damping at its bound)"),
    "v3": CalibrationModel(
        "v3", (), (DEFAULT_PARAMETERS[0], VISCOUS, DRIVE_HEAT),
        "elastic hinge with held ends (membrane stiffening, frame damping fixed at 0.02) and the "
        "thickness mechanism 'leaf conduction' (drive heat through the leaves, conductance ~ y)"),
    "v3-overconstraint": CalibrationModel(
        "v3-overconstraint", (), (DEFAULT_PARAMETERS[0], VISCOUS, OVERCONSTRAINT),
        "elastic hinge with held ends and the thickness mechanism 'over-constraint' (a clamping "
        "misfit loads the guide through the leaves' stiff direction, stiffness ~ y)"),
    "v4": CalibrationModel(
        "v4", (), (DEFAULT_PARAMETERS[0], VISCOUS, DRIVE_VISCOUS),
        "elastic hinge with held ends (frame damping fixed at 0.02) and the thickness mechanism "
        "'drive friction through the leaves': the heat of the drive element's viscous friction, "
        "c_d <v^2>, enters the working stage and reaches the carriage through the leaves "
        "(conductance ~ y) behind the stage's heat capacity"),
    "v5": CalibrationModel(
        "v5", (("heat_balance", True),), (VISCOUS, DRIVE_VISCOUS, BALL_CONTACT),
        "one heat balance in watts: the friction power at the ball contacts and the drive element's viscous "
        "heat c_d <v^2> entering the working stage flow through one network of the rig's bodies (carriage, "
        "balls, rail, base, frame, leaves, working stage); no heat share: what reaches the carriage follows "
        "from the conductances, the ball contacts' calibrated"),
    "v5-nodrive": CalibrationModel(
        "v5-nodrive", (("heat_balance", True),), (VISCOUS, BALL_CONTACT),
        "as v5 without a drive heat (the paper's Section 2.2: motor heat not considered): friction heat alone"),
    "v6": CalibrationModel(
        "v6", (("heat_balance", True), ("two_carriage", True), ("other_stage_running", True)),
        (VISCOUS, BALL_CONTACT_HERTZ),
        "the rig of Section 4.1: both carriages (RMS and RFCMS) on one rail and base, run together by the "
        "link span (Section 4.1), each carriage's friction power at its ball contacts (Hertz/Yovanovich "
        "conductance, fitted within 3x of the estimate), no drive heat (Section 2.2)"),
    "v6-alone": CalibrationModel(
        "v6-alone", (("heat_balance", True), ("two_carriage", True), ("other_stage_running", False)),
        (VISCOUS, BALL_CONTACT_HERTZ),
        "as v6 with the other stage at rest during the test (contrary to Section 4.1; the comparison "
        "candidate of the mechanism choice)"),
    "v4-coulomb": CalibrationModel(
        "v4-coulomb", (), (DEFAULT_PARAMETERS[0], VISCOUS, DRIVE_FRICTION),
        "as v4, with the drive element's Coulomb friction, F_d <|v|>, instead of its viscous friction"),
}

#: The model ``rsm-lrg calibrate`` uses by default.
DEFAULT_MODEL = "v5"

#: Other parameters one may calibrate instead (``--parameter NAME``).
OTHER_PARAMETERS = (
    ParameterSpec("hinge_length_m", 0.005, 0.06, 0.02, "m",
                  "free length l of each leaf hinge (Eq. 1: K_n = E w y^3 / l^3); the paper "
                  "does not give it; sets how far the frame lags the working stage"),
    ParameterSpec("hinge_width_m", 0.002, 0.03, 0.01, "m",
                  "width w of each leaf hinge (Eq. 1); the paper does not give it"),
    ParameterSpec("frame_mass_fraction", 0.05, 0.95, 0.5, "1",
                  "share of the stage mass m_t in the rigid frame; the paper does not give it"),
)


@dataclass(frozen=True)
class ParameterEstimate:
    """A calibrated parameter: value, standard error, bounds, unit, meaning.

    Parameters
    ----------
    name : str
        The parameter.
    value, std_error : float
        The estimate and its standard error [unit].
    lower, upper : float
        The bounds of the search [unit].
    unit, meaning : str
        Its unit and what it is.
    at_bound : bool, default False
        Whether the estimate sits on a bound.
    ci_low, ci_high : float
        The 95 % interval [unit] (NaN when not computed).
    ci_method : str
        How the interval was computed.
    """

    name: str
    value: float
    std_error: float
    lower: float
    upper: float
    unit: str = ""
    meaning: str = ""
    at_bound: bool = False
    ci_low: float = math.nan
    ci_high: float = math.nan
    ci_method: str = ""

    def to_dict(self) -> dict:
        """The estimate as plain data.

        Returns
        -------
        dict
            JSON-safe: numbers, strings, lists and dicts.
        """
        return {"name": self.name, "value": self.value, "std_error": self.std_error, "lower": self.lower,
                "upper": self.upper, "unit": self.unit, "meaning": self.meaning, "at_bound": self.at_bound,
                "ci_low": self.ci_low, "ci_high": self.ci_high, "ci_method": self.ci_method}


@dataclass(frozen=True)
class Calibration:
    """Calibrated parameters and how well they reproduce the data.

    Attributes
    ----------
    parameters : tuple of ParameterEstimate
    response : str
        The measured column fitted (``tcr_c_per_min``).
    n : int
        Number of runs.
    r2, rmse : float
        In-sample R² and RMSE [response units] of the noise-free surrogate.
    loo_r2, loo_rmse : float or None
        Leave-one-out R² (1 − PRESS/SS_tot) and RMSE, if computed.
    data : str
        Where the data came from (file name) and ``data_sha256`` its SHA-256.
    observed, predicted, loo_predicted : tuple of float
        Per run (``loo_predicted`` empty if LOO was not run).
    """

    parameters: tuple
    response: str
    n: int
    r2: float
    rmse: float
    loo_r2: float | None = None
    loo_rmse: float | None = None
    data: str = ""
    data_sha256: str = ""
    observed: tuple = field(default=(), repr=False)
    predicted: tuple = field(default=(), repr=False)
    loo_predicted: tuple = field(default=(), repr=False)
    method: str = "scipy.optimize.least_squares (trf, bounded), noise-free virtual runs"
    uncalibrated_r2: float | None = None
    model: str = ""
    selected_from: tuple = ()
    loo_models: tuple = field(default=(), repr=False)

    def fixed_values(self) -> dict:
        """The physics the calibration's ``model`` fixes (``{}`` without a model).

        Returns
        -------
        dict
            ``{name: value}`` in the parameters' own units (SI).
        """
        return dict(MODELS[self.model].fixed) if self.model else {}

    def parameter_values(self) -> dict:
        """``{name: value}`` as :func:`rsm_lrg.surrogate.runs.evaluate_rows` takes it: the
        model's fixed physics and the calibrated parameters.

        Returns
        -------
        dict
            ``{name: value}`` in the parameters' own units (SI).
        """
        out = self.fixed_values()
        out.update({p.name: p.value for p in self.parameters})
        return out

    def to_dict(self) -> dict:
        """The calibration as plain data.

        Returns
        -------
        dict
            JSON-safe: numbers, strings, lists and dicts.
        """
        return {
            "response": self.response, "n": self.n, "r2": self.r2, "rmse": self.rmse,
            "loo_r2": self.loo_r2, "loo_rmse": self.loo_rmse, "uncalibrated_r2": self.uncalibrated_r2,
            "paper_press_r2": PAPER_PRESS_R2, "model": self.model,
            "data": self.data, "data_sha256": self.data_sha256, "method": self.method,
            "parameters": [p.to_dict() for p in self.parameters],
            "observed": list(self.observed), "predicted": list(self.predicted),
            "loo_predicted": list(self.loo_predicted),
            "selected_from": list(self.selected_from),
            "loo_models": [self.selected_from[k] for k in self.loo_models] if self.selected_from else [],
        }

    def to_frame(self):
        """One row per parameter: name, value, std_error, lower, upper, unit, meaning.

        Returns
        -------
        pandas.DataFrame
            The table described above.
        """
        import pandas as pd

        return pd.DataFrame([p.to_dict() for p in self.parameters])

    def summary(self) -> str:
        """A few lines of text for people.

        Returns
        -------
        str
            The text, several lines.
        """
        lines = [f"calibration of {len(self.parameters)} parameters to {self.response} ({self.n} runs, {self.data})"
                 + (f", model {self.model}" if self.model else "")]
        for p in self.parameters:
            flag = "  (at a bound)" if p.at_bound else ""
            lines.append(f"  {p.name:<24} {format_g(p.value, 6, trim=True):>12} ± {format_g(p.std_error, 3, trim=True):<10} "
                         f"{p.unit:<6} bounds [{format_g(p.lower, 6, trim=True)}, {format_g(p.upper, 6, trim=True)}]{flag}")
            if p.ci_method:
                lines.append(f"  {'':<24} 95 % {p.ci_method} interval [{format_g(p.ci_low, 4, trim=True)}, "
                             f"{format_g(p.ci_high, 4, trim=True)}]")
        lines.append(f"  R2 {self.r2:.4f}   RMSE {format_g(self.rmse, 4, trim=True)}")
        if self.loo_r2 is not None:
            lines.append(f"  leave-one-out R2 {self.loo_r2:.4f}   RMSE {format_g(self.loo_rmse, 4, trim=True)}   (the paper's quadratic, "
                         f"Eq. 19: PRESS R2 {PAPER_PRESS_R2:.3f})")
        if self.selected_from:
            line = (f"  model chosen by AICc among {', '.join(self.selected_from)}")
            if self.loo_models:
                counts = ", ".join(f"{m} {sum(1 for k in self.loo_models if self.selected_from[k] == m)}"
                                   for m in self.selected_from)
                line += f"; inside the leave-one-out folds: {counts} of {len(self.loo_models)}"
            lines.append(line)
        if self.uncalibrated_r2 is not None:
            lines.append(f"  raw physics (uncalibrated) R2 {self.uncalibrated_r2:.4f}")
        return "\n".join(lines)


# ----------------------------------------------------------------------------------------
# fitting
# ----------------------------------------------------------------------------------------
def _specs(parameters, model: str = DEFAULT_MODEL) -> tuple:
    if parameters is None:
        return MODELS[model].parameters
    out = []
    by_name = {s.name: s for s in DEFAULT_PARAMETERS + OTHER_PARAMETERS + (DRIVE_HEAT, OVERCONSTRAINT,
                                                                             DRIVE_FRICTION, DRIVE_VISCOUS,
                                                                             BALL_CONTACT)}
    for p in parameters:
        if isinstance(p, ParameterSpec):
            out.append(p)
        elif isinstance(p, str) and p in by_name:
            out.append(by_name[p])
        else:
            raise ParameterError("parameters", f"unknown calibration parameter {p!r}; one of {', '.join(by_name)} "
                             f"(or a ParameterSpec)")
    if not 1 <= len(out) <= 3:
        raise ParameterError("parameters", f"calibrate at most three parameters (got {len(out)})")
    names = [s.name for s in out]
    if len(set(names)) != len(names):
        twice = next(n for n in names if names.count(n) > 1)
        raise ValueError(f"the calibration parameter {twice} is given twice")
    from ..physics.params import PHYSICAL_RANGES, param_names

    for s in out:
        vals = (s.lower, s.upper, s.start)
        if not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in vals):
            raise ValueError(f"parameter {s.name}: lower, upper and start must be finite numbers")
        if not (s.lower < s.upper and s.lower <= s.start <= s.upper):
            raise ValueError(f"parameter {s.name}: need lower < upper and start within the bounds")
        if s.name in PHYSICAL_RANGES:
            plo, phi = PHYSICAL_RANGES[s.name]
        elif s.name == "heat_partition":
            plo, phi = 0.0, 1.0
        elif s.name in ("drive_friction_n", "drive_viscous_n_s_m"):
            plo, phi = 0.0, 1e4
        elif s.name not in param_names():
            raise ParameterError("parameters", f"unknown calibration parameter {s.name!r}")
        else:
            continue
        if s.lower < plo or s.upper > phi:
            raise ValueError(f"parameter {s.name}: bounds [{s.lower:g}, {s.upper:g}] reach outside its physical "
                             f"range [{plo:g}, {phi:g}]")
    return tuple(out)


def _r2(obs, pred) -> float:
    ss = float(np.sum((obs - np.mean(obs)) ** 2))
    return 1.0 - float(np.sum((obs - pred) ** 2)) / ss if ss > 0 else float("nan")


#: Calibratable parameters that do not enter the stage dynamics (cheap to vary).
_HEAT_ONLY = ("heat_partition", "drive_heat_w", "drive_friction_n", "drive_viscous_n_s_m",
              "ball_contact_conductance_w_k")


def calibrate(data, response: str = "tcr_c_per_min", *, parameters=None, params=None,
              duration_min: float = 50.0, loo: bool = True, source: str = "",
              data_sha256: str = "", grid_points: int | None = None, progress: bool = False,
              model: str = DEFAULT_MODEL, select=None) -> Calibration:
    """Fit the surrogate's unknown parameters to measured runs.

    Parameters
    ----------
    data : pandas.DataFrame
        Measured runs: the design columns (``thickness_m``, ``stroke_m``, ``velocity_m_s``,
        ``acceleration_m_s2``, optional ``stage`` and parameter columns) and ``response``.
    response : str
        Column of the measured response; ``tcr_c_per_min`` (κ [°C/min], Eq. 18) or any
        other output of :func:`rsm_lrg.simulate`.
    parameters : sequence of str or ParameterSpec, optional
        One to three parameters (default: those of ``model``).
    model : str
        A key of :data:`MODELS`: the physics it fixes (``v2``: the small-deflection hinge)
        and its default parameters. ``v4`` (default): elastic hinge with held ends and the
        heat of the drive's viscous friction conducted through the leaves; ``v4-coulomb`` its
        Coulomb friction; ``v3`` a constant drive heat; ``v3-overconstraint`` the
        over-constraint load instead.
    params : LRGParams, optional
        Base physical parameters.
    duration_min : float
        Test duration of the runs [min] (the paper: about 50).
    loo : bool
        Also run leave-one-out cross-validation: every fold recalibrated from scratch on the
        other runs by exactly the procedure below (grid, refinement, final fit), and the run
        left out predicted with that fold's parameters.
    grid_points : int, optional
        Points per axis of the profile grid over the stage parameters (see the code comment);
        default 13 for one stage parameter, 7 per axis for two.
    source, data_sha256 : str
        Recorded with the result.
    progress : bool
        Show a progress bar (tqdm) on stderr, one step per least-squares fit or grid point
        (the CLI shows it; a full calibration with leave-one-out takes minutes).
    select : sequence of str, optional
        Candidate models (keys of :data:`MODELS`, each with its own parameters; ``model``
        and ``parameters`` are then ignored): each is calibrated and the one of smallest
        AICc, ``n ln(SSR/n) + 2k + 2k(k+1)/(n-k-1)`` (Hurvich & Tsai 1989), is returned. The
        choice is part of the procedure that leave-one-out repeats: in every fold each
        candidate is recalibrated from scratch on the other runs and the fold's own AICc
        choice predicts the run left out (``loo_models``), so the LOO figure includes the
        optimism of choosing a mechanism.

    Returns
    -------
    Calibration
    """
    from scipy.optimize import least_squares

    from ..physics.params import LRGParams
    from .design_input import OUTPUT_COLUMNS, read_design_arrays
    from .runs import check_duration, evaluate_rows

    if select is not None:
        models = [str(m) for m in select]
        if not models or len(set(models)) != len(models):
            raise ParameterError("select", "select needs one or more different calibration models")
        parameters = None
    else:
        models = [model]
    for m in models:
        if m not in MODELS:
            raise ValueError(f"unknown calibration model {m!r}; choose one of {', '.join(MODELS)}")
    duration_min = check_duration(duration_min)
    if response not in data.columns:
        from ..io import quote_user_value

        shown = ", ".join(quote_user_value(str(c), 30) for c in list(data.columns)[:8])
        more = f" and {data.shape[1] - 8} more" if data.shape[1] > 8 else ""
        raise ValueError(f"column {quote_user_value(str(response))} not found (columns: {shown}{more})")
    if response not in OUTPUT_COLUMNS:
        raise ValueError(f"the surrogate does not produce {response!r}; choose one of {', '.join(OUTPUT_COLUMNS)}")
    from ..io import float_column

    obs = float_column(data, response).to_numpy()
    n = obs.size
    probs = [_problem(m, parameters, data, response, params, duration_min, grid_points, obs, least_squares,
                      LRGParams, read_design_arrays, evaluate_rows) for m in models]
    from .progress import progress_bar

    steps = 0
    for pr in probs:
        per_fit = len(pr.grid) + 2
        steps += per_fit * (1 + (n if loo else 0)) + (2 if len(pr.stage_idx) == 1 else 0)
    bar = progress_bar(steps, bool(progress), desc="calibration fits", unit="fit")
    try:
        if len(probs) == 1:
            pr = probs[0]
            cal = _calibrate_steps(pr.specs, pr.grid, pr.stage_idx, pr.x0, pr.lo, pr.hi, pr.scale, pr.fit,
                                   pr.predict, obs, n, loo, bar, pr.arrays, pr.p, duration_min, response, source,
                                   data_sha256, evaluate_rows)
            return dataclasses.replace(cal, model=pr.model)
        bests = [_fit_from_scratch(None, pr.specs, pr.grid, pr.stage_idx, pr.x0, pr.lo, pr.hi, pr.fit, pr.predict,
                                   obs, bar) for pr in probs]
        k = int(np.argmin([aicc(2.0 * b.cost, n, len(pr.specs)) for b, pr in zip(bests, probs)]))
        pr = probs[k]
        cal = _calibrate_steps(pr.specs, pr.grid, pr.stage_idx, pr.x0, pr.lo, pr.hi, pr.scale, pr.fit, pr.predict,
                               obs, n, False, bar, pr.arrays, pr.p, duration_min, response, source, data_sha256,
                               evaluate_rows, best=bests[k])
        cal = dataclasses.replace(cal, model=pr.model, selected_from=tuple(models))
        if loo:
            lp, chosen = np.empty(n), []
            for i in range(n):
                keep = np.delete(np.arange(n), i)
                fits = [_fit_from_scratch(keep, q.specs, q.grid, q.stage_idx, q.x0, q.lo, q.hi, q.fit, q.predict,
                                          obs, bar) for q in probs]
                kk = int(np.argmin([aicc(2.0 * f.cost, n - 1, len(q.specs)) for f, q in zip(fits, probs)]))
                lp[i] = probs[kk].predict(fits[kk].x, np.array([i]))[0]
                chosen.append(kk)
            cal = dataclasses.replace(cal, loo_predicted=tuple(float(x) for x in lp), loo_r2=_r2(obs, lp),
                                      loo_rmse=float(np.sqrt(np.mean((obs - lp) ** 2))), loo_models=tuple(chosen))
        return cal
    finally:
        bar.close()


def aicc(ssr: float, n: int, k: int) -> float:
    """Small-sample Akaike criterion of a least-squares fit, ``n ln(SSR/n) + 2k +
    2k(k+1)/(n-k-1)`` (Hurvich & Tsai 1989, Biometrika 76:297; constants dropped): the
    smaller, the better; it charges each parameter what it gains on average by chance.

    >>> round(aicc(1.0, 20, 2) - aicc(1.0, 20, 1), 4)   # one more parameter, same SSR
    2.4837
    """
    if not n - k - 1 > 0:
        raise ValueError(f"AICc needs n > k + 1 (n = {n}, k = {k})")
    return n * math.log(max(ssr, 1e-300) / n) + 2 * k + 2 * k * (k + 1) / (n - k - 1)


@dataclass(frozen=True)
class _Problem:
    model: str
    specs: tuple
    grid: list
    stage_idx: list
    x0: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    scale: np.ndarray
    fit: Any
    predict: Any
    arrays: Any
    p: Any


def _problem(model, parameters, data, response, params, duration_min, grid_points, obs, least_squares, LRGParams,
             read_design_arrays, evaluate_rows) -> _Problem:
    """The calibration problem of one model: its parameters, bounds, profile grid, and the
    prediction and least-squares closures."""
    specs = _specs(parameters, model)
    if dict(MODELS[model].fixed).get("heat_balance") and any(sp.name == "heat_partition" for sp in specs):
        raise ValueError(f"heat_partition is not a parameter of model {model}: with one heat balance in watts the "
                         "share of the friction heat that reaches the carriage follows from the conductances "
                         "(calibrate ball_contact_conductance_w_k, or use --model v4)")
    n = obs.size
    if n <= len(specs) + 1:
        k = len(specs)
        raise ValueError(f"{n} run{' is' if n == 1 else 's are'} too few to calibrate {k} parameter{'s' if k != 1 else ''}")
    p = params if params is not None else LRGParams()
    if MODELS[model].fixed:
        p = p.with_overrides(**dict(MODELS[model].fixed))
    arrays = read_design_arrays(data.drop(columns=[response]), p)

    def predict(theta, idx=None):
        # always all rows (the dynamics of a row set is memoised), then the subset
        cal = {s.name: float(t) for s, t in zip(specs, theta)}
        out = evaluate_rows(arrays, params=p, calibration=cal, duration_min=duration_min, memo=True)[response]
        return out if idx is None else out[idx]

    lo = np.array([s.lower for s in specs])
    hi = np.array([s.upper for s in specs])
    x0 = np.array([s.start for s in specs])
    scale = hi - lo

    def fit(idx, start, free=None):
        o = obs if idx is None else obs[idx]
        free = np.ones(len(specs), dtype=bool) if free is None else free

        def fun(th):
            full = np.array(start, dtype=float)
            full[free] = th
            return predict(full, idx) - o

        r = least_squares(fun, np.asarray(start, float)[free], bounds=(lo[free], hi[free]), x_scale=scale[free],
                          diff_step=1e-3, xtol=1e-8, ftol=1e-10, gtol=1e-10, method="trf")
        full = np.array(start, dtype=float)
        full[free] = r.x
        r.x = full
        return r

    # The stick-slip dynamics make kappa a rough function of the stage parameters (a small
    # change can add or remove a stop per cycle), so a local search alone can stall: first
    # a profile over a grid of the (one or two) stage parameters with the others fitted (or
    # just evaluated, when every parameter is a stage parameter), then all parameters
    # together from the best grid point.
    stage_idx = [i for i, sp in enumerate(specs) if sp.name not in _HEAT_ONLY]
    grid = []
    if 1 <= len(stage_idx) <= 2:
        m = int(grid_points) if grid_points is not None else (13 if len(stage_idx) == 1 else 7)
        axes = [np.geomspace(lo[i], hi[i], m) if lo[i] > 0 else np.linspace(lo[i], hi[i], m) for i in stage_idx]
        grid = list(itertools.product(*axes))
    return _Problem(model, specs, grid, stage_idx, x0, lo, hi, scale, fit, predict, arrays, p)


def _fit_from_scratch(idx, specs, grid, stage_idx, x0, lo, hi, fit, predict, obs, bar):
    """One calibration on the runs ``idx`` (None: all): the profile grid over the stage
    parameters, for one stage parameter a bounded Brent refinement of its profile between the
    neighbours of the best grid point (so no grid node is returned as an estimate), then all
    parameters together by least squares from there. Returns the least-squares result."""
    from scipy.optimize import minimize_scalar

    o = obs if idx is None else obs[idx]
    free = np.ones(len(specs), dtype=bool)
    free[stage_idx] = False
    best_cost, best_start, best_k = np.inf, x0, 0
    for kk, point in enumerate(grid):
        st0 = x0.copy()
        st0[stage_idx] = point
        if free.any():
            r = fit(idx, st0, free)
            cost, st0 = r.cost, r.x
        else:
            cost = 0.5 * float(np.sum((predict(st0, idx) - o) ** 2))
        if cost < best_cost:
            best_cost, best_start, best_k = cost, st0, kk
        bar.update(1)
    start = best_start
    if len(stage_idx) == 1 and grid:
        i = stage_idx[0]
        nodes = [g[0] for g in grid]
        a_, b_ = nodes[max(best_k - 1, 0)], nodes[min(best_k + 1, len(nodes) - 1)]
        cache = {}

        def profile(t):
            st = best_start.copy()
            st[i] = t
            if free.any():
                r = fit(idx, st, free)
                cache[t] = r.x
                return r.cost
            cache[t] = st
            return 0.5 * float(np.sum((predict(st, idx) - o) ** 2))

        res = minimize_scalar(profile, bounds=(a_, b_), method="bounded",
                              options={"xatol": 1e-5 * (hi[i] - lo[i])})
        if res.fun < best_cost:
            start = cache[res.x]
    bar.update(1)
    best = fit(idx, start)
    if not best.cost <= 0.5 * float(np.sum((predict(start, idx) - o) ** 2)):
        best.x, best.cost = start, 0.5 * float(np.sum((predict(start, idx) - o) ** 2))
    bar.update(1)
    return best


def _profile_interval(i, specs, theta, cost_min, lo, hi, fit, predict, obs, n, bar, level=0.95):
    """Profile-likelihood interval of parameter ``i``: where the least-squares cost with
    parameter i fixed and the others refitted stays below ``cost_min·(1 + F(level; 1, n−p)/(n−p))``
    (Bates & Watts 1988, Section 6.1). Ends found by Brent's root search; a bound where the
    profile stays below the threshold up to it."""
    from scipy.optimize import brentq
    from scipy.stats import f as fdist

    p_ = len(specs)
    thr = cost_min * (1.0 + float(fdist.ppf(level, 1, n - p_)) / (n - p_))
    free = np.ones(p_, dtype=bool)
    free[i] = False

    def g(t):
        st = np.array(theta, dtype=float)
        st[i] = t
        c = fit(None, st, free).cost if free.any() else 0.5 * float(np.sum((predict(st) - obs) ** 2))
        return c - thr

    ends = []
    for edge in (lo[i], hi[i]):
        if g(edge) <= 0:
            ends.append(float(edge))
        else:
            ends.append(float(brentq(g, theta[i], edge, xtol=1e-4 * (hi[i] - lo[i]))))
        bar.update(1)
    return min(ends), max(ends)


def profile_interval(data, cal: Calibration, name: str, *, level: float = 0.95,
                     duration_min: float = 50.0) -> tuple[float, float]:
    """Profile-likelihood interval [lower, upper] of the calibrated parameter ``name`` of
    ``cal`` on the runs ``data`` (those it was fitted to): the parameter fixed at each trial
    value, the others refitted by least squares from ``cal``'s optimum, the ends where the cost
    passes ``SSR_min/2 · (1 + F(level; 1, n−p)/(n−p))`` (Bates & Watts 1988, Section 6.1); a
    bound where the profile stays below it. ``calibrate`` computes it for the stage parameter;
    this gives it for any parameter of a calibration (minutes: every trial value is a fit).
    """
    from scipy.optimize import least_squares

    from ..io import float_column
    from ..physics.params import LRGParams
    from .design_input import read_design_arrays
    from .runs import check_duration, evaluate_rows

    if not cal.model:
        raise ValueError("the calibration names no model; profile intervals need one")
    names = [q.name for q in cal.parameters]
    if name not in names:
        raise ValueError(f"{name!r} is not a parameter of this calibration ({', '.join(names)})")
    obs = float_column(data, cal.response).to_numpy()
    pr = _problem(cal.model, names, data, cal.response, None, check_duration(duration_min), None, obs,
                  least_squares, LRGParams, read_design_arrays, evaluate_rows)
    theta = np.array([q.value for q in cal.parameters])
    cost = 0.5 * float(np.sum((pr.predict(theta) - obs) ** 2))

    class _NoBar:
        def update(self, k: int) -> None:
            pass

    return _profile_interval(names.index(name), pr.specs, theta, cost, pr.lo, pr.hi, pr.fit, pr.predict, obs,
                             obs.size, _NoBar(), level=level)


def _calibrate_steps(specs, grid, stage_idx, x0, lo, hi, scale, fit, predict, obs, n, loo, bar, arrays, p,
                     duration_min, response, source, data_sha256, evaluate_rows, best=None):
    """The calibration (:func:`_fit_from_scratch`), the profile interval of a single stage
    parameter and leave-one-out with every fold recalibrated from scratch."""
    if best is None:
        best = _fit_from_scratch(None, specs, grid, stage_idx, x0, lo, hi, fit, predict, obs, bar)
    theta = best.x
    pred = predict(theta)
    resid = obs - pred
    dof = n - len(specs)
    s2 = float(resid @ resid) / dof
    J = best.jac
    try:
        cov = s2 * np.linalg.inv(J.T @ J)
        se = np.sqrt(np.clip(np.diag(cov), 0, None))
    except np.linalg.LinAlgError:
        se = np.full(len(specs), np.nan)
    at_bound = (np.isclose(theta, lo, rtol=0, atol=1e-6 * scale) | np.isclose(theta, hi, rtol=0, atol=1e-6 * scale))
    ci = {}
    if len(stage_idx) == 1:
        i = stage_idx[0]
        ci[i] = _profile_interval(i, specs, theta, 0.5 * float(resid @ resid), lo, hi, fit, predict, obs, n, bar)
    ests = tuple(ParameterEstimate(s.name, float(t), float(e), s.lower, s.upper, s.unit, s.meaning, bool(b),
                                   *(ci[k] + ("profile likelihood",) if k in ci else ()))
                 for k, (s, t, e, b) in enumerate(zip(specs, theta, se, at_bound)))
    raw = evaluate_rows(arrays, params=p, calibration={}, duration_min=duration_min)[response]
    loo_pred = ()
    loo_r2 = loo_rmse = None
    if loo:
        lp = np.empty(n)
        for i in range(n):
            keep = np.delete(np.arange(n), i)
            r = _fit_from_scratch(keep, specs, grid, stage_idx, x0, lo, hi, fit, predict, obs, bar)
            lp[i] = predict(r.x, np.array([i]))[0]
        loo_pred = tuple(float(x) for x in lp)
        loo_r2 = _r2(obs, lp)
        loo_rmse = float(np.sqrt(np.mean((obs - lp) ** 2)))
    return Calibration(
        parameters=ests, response=response, n=n, r2=_r2(obs, pred),
        rmse=float(np.sqrt(np.mean(resid ** 2))), loo_r2=loo_r2, loo_rmse=loo_rmse,
        data=str(source), data_sha256=data_sha256, observed=tuple(map(float, obs)),
        predicted=tuple(map(float, pred)), loo_predicted=loo_pred, uncalibrated_r2=_r2(obs, raw),
        method=("grid + bounded Brent profile refinement + scipy.optimize.least_squares (trf, bounded), "
                "noise-free virtual runs; leave-one-out folds recalibrated from scratch"),
    )


def _subset(arrays, idx):
    from .design_input import DesignArrays

    idx = np.asarray(idx)
    return DesignArrays(idx.size, {k: v[idx] for k, v in arrays.columns.items()}, arrays.rigid[idx],
                        arrays.param_columns)


# ----------------------------------------------------------------------------------------
# file I/O
# ----------------------------------------------------------------------------------------
def _comment_text(text: str) -> str:
    """``text`` made safe for a TOML comment: control characters (a newline in a file name
    would end the comment and break the file) written as ``\\n``, ``\\uXXXX``."""
    out = []
    for ch in str(text):
        if ch == "\n":
            out.append("\\n")
        elif ch == "\r":
            out.append("\\r")
        elif (ord(ch) < 0x20 and ch != "\t") or ord(ch) == 0x7F or 0xD800 <= ord(ch) <= 0xDFFF:
            out.append(f"\\u{ord(ch):04x}")
        else:
            out.append(ch)
    return "".join(out)


def calibration_toml(cal: Calibration, command: str = "") -> str:
    """The TOML text of a calibration (what :func:`load_calibration` reads)."""
    from ..io import toml_value

    lines = [
        "# Calibration of the rsm-lrg virtual-run surrogate (rsm_lrg.surrogate).",
        "# Written by `rsm-lrg calibrate`; read by `rsm-lrg simulate` and rsm_lrg.simulate().",
        "# Each [parameters.NAME] has a physical meaning, bounds and a standard error from the",
        "# Jacobian; no offsets or correction terms. Regenerate with:",
        f"#   {_comment_text(command) or 'rsm-lrg calibrate data/table4.csv --response tcr_c_per_min -o data/calibration.toml --force'}",
        "",
        "[calibration]",
    ]
    for k in ("model", "response", "n", "r2", "rmse", "loo_r2", "loo_rmse", "uncalibrated_r2", "data", "data_sha256",
              "method"):
        v = getattr(cal, k)
        if v is None or (k == "model" and not v):
            continue
        lines.append(f"{k} = {toml_value(v)}")
    if cal.selected_from:
        lines.append(f"selected_from = {toml_value(','.join(cal.selected_from))}")
    lines.append("")
    for p in cal.parameters:
        lines.append(f"[parameters.{p.name}]")
        for k in ("value", "std_error", "lower", "upper", "unit", "meaning", "at_bound"):
            lines.append(f"{k} = {toml_value(getattr(p, k))}")
        if p.ci_method:
            for k in ("ci_low", "ci_high", "ci_method"):
                lines.append(f"{k} = {toml_value(getattr(p, k))}")
        lines.append("")
    lines.append("[runs]")
    lines.append(f"observed = {toml_value(list(cal.observed))}")
    lines.append(f"predicted = {toml_value(list(cal.predicted))}")
    if cal.loo_predicted:
        lines.append(f"loo_predicted = {toml_value(list(cal.loo_predicted))}")
    if cal.loo_models:
        lines.append(f"loo_model_index = {toml_value([int(k) for k in cal.loo_models])}")
    return "\n".join(lines) + "\n"


#: Keys of a calibration file, with their types (what :func:`calibration_toml` writes).
_HEAD_KEYS = {"model": str, "response": str, "n": int, "r2": float, "rmse": float, "loo_r2": float, "loo_rmse": float,
              "uncalibrated_r2": float, "data": str, "data_sha256": str, "method": str, "command": str,
              "selected_from": str}
_PARAM_KEYS = {"value": float, "std_error": float, "lower": float, "upper": float, "unit": str,
               "meaning": str, "at_bound": bool, "ci_low": float, "ci_high": float, "ci_method": str}
_RUN_KEYS = ("observed", "predicted", "loo_predicted", "loo_model_index")


#: LRGParams switches (true/false): fixed by a calibration model, never a calibrated number.
_SWITCHES = ("hinge_membrane", "heat_in_calories", "heat_balance", "two_carriage", "other_stage_running")


def documented_bounds(name: str) -> tuple[float, float, str]:
    """``(lower, upper, where)``: the documented range of a calibratable parameter -- the
    bounds of its :class:`ParameterSpec` (:data:`DEFAULT_PARAMETERS`,
    :data:`OTHER_PARAMETERS`), else the physical range of
    :data:`rsm_lrg.physics.params.PHYSICAL_RANGES` (``heat_partition``: (0, 1])."""
    from ..physics.params import PHYSICAL_RANGES

    for s in DEFAULT_PARAMETERS + OTHER_PARAMETERS + (DRIVE_HEAT, OVERCONSTRAINT, DRIVE_FRICTION, DRIVE_VISCOUS,
                                                      BALL_CONTACT):
        if s.name == name:
            return s.lower, s.upper, "documented in rsm_lrg.surrogate.calibrate"
    if name in PHYSICAL_RANGES:
        lo, hi = PHYSICAL_RANGES[name]
        return float(lo), float(hi), "its physical range"
    return 0.0, 1.0, "a share of the heat"


def _typed(where: str, key: str, v, kind):
    """A TOML value of the expected kind, or ValueError naming ``where`` and ``key``."""
    from ..io import quote_user_value

    if kind is float:
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise ValueError(f"{where} {key} must be a number, not {quote_user_value(v)}")
        return float(v)
    if kind is int:
        if isinstance(v, bool) or not isinstance(v, int) or v < 0:
            raise ValueError(f"{where} {key} must be a whole number >= 0, not {quote_user_value(v)}")
        return int(v)
    if kind is bool:
        if not isinstance(v, bool):
            raise ValueError(f"{where} {key} must be true or false, not {quote_user_value(v)}")
        return v
    if not isinstance(v, str):
        raise ValueError(f"{where} {key} must be a string, not {quote_user_value(v)}")
    return v


def _check_unit(where: str, name: str, unit: str | None) -> None:
    """A ``unit`` written beside a value must be the parameter's own unit (the value is read
    in it): ``unit = "mm"`` for a parameter in m would otherwise be ignored silently and the
    value taken 1000 times too large."""
    from ..io import quote_user_value
    from ..physics.params import PARAM_INFO
    from .runs import SURROGATE_PARAMETERS

    if unit is None:
        return
    own = PARAM_INFO[name]["unit"] if name in PARAM_INFO else SURROGATE_PARAMETERS[name][1] \
        if name in SURROGATE_PARAMETERS else None
    if own is not None and unit.strip() != own:
        raise ValueError(f"{where} unit {quote_user_value(unit)} is not the unit of {name}, "
                         f"{quote_user_value(own)}; write the value {'as a plain number' if own in ('1', '') else 'in ' + own} "
                         "(values are never converted)")


def _unknown_key(where: str, key, allowed) -> ValueError:
    import difflib

    from ..io import quote_user_value

    close = difflib.get_close_matches(str(key), list(allowed), n=1)
    hint = f" (did you mean {close[0]!r}?)" if close else ""
    if not close and len(allowed) <= 12:
        hint = f" (known: {', '.join(allowed)})"
    if where == "[parameters]":
        return ValueError(f"unknown parameter {quote_user_value(key)}{hint}")
    return ValueError(f"{where} has an unknown key {quote_user_value(key)}{hint}")


def load_calibration(path) -> Calibration:
    """Read a calibration TOML file (as written by :func:`calibration_toml`).

    Every table and key is checked: an unknown key (a typo), a value of the wrong type, a
    missing ``value`` or a value outside the parameter's documented range
    (:func:`documented_bounds`, and the file's own ``lower``/``upper``) raise ``ValueError``
    naming the file, the table and the key.

    Parameters
    ----------
    path : str or pathlib.Path
        The TOML file.

    Returns
    -------
    Calibration
        The calibration, checked.
    """
    from ..io import read_toml, show_path
    from ..physics.params import param_names
    from .design_input import OUTPUT_COLUMNS
    from .runs import SURROGATE_PARAMETERS

    path = Path(path)
    raw = read_toml(path, "calibration file")
    try:
        return _calibration_from_toml(raw, param_names(), SURROGATE_PARAMETERS, OUTPUT_COLUMNS)
    except ValueError as exc:
        raise ValueError(f"{show_path(path)}: {exc}") from None


def _calibration_from_toml(raw: dict, lrg_names, surrogate_names, outputs) -> Calibration:
    from ..io import quote_user_value

    for k in raw:
        if k not in ("calibration", "parameters", "runs"):
            raise _unknown_key("the file", k, ("calibration", "parameters", "runs"))
    head = raw.get("calibration", {})
    if not isinstance(head, dict):
        raise ValueError("'calibration' must be a table [calibration]")
    h = {}
    for k, v in head.items():
        if k not in _HEAD_KEYS:
            raise _unknown_key("[calibration]", k, _HEAD_KEYS)
        h[k] = _typed("[calibration]", k, v, _HEAD_KEYS[k])
    if "model" in h and h["model"] not in MODELS:
        raise ValueError(f"[calibration] model {quote_user_value(h['model'])} is not one of {', '.join(MODELS)}")
    if "response" in h and h["response"] not in outputs:
        raise ValueError(f"[calibration] response {quote_user_value(h['response'])} is not an output of the "
                         f"surrogate ({', '.join(outputs)})")
    pars = raw.get("parameters")
    if not isinstance(pars, dict) or not pars:
        raise ValueError("no [parameters.NAME] tables")
    known = set(lrg_names) | set(surrogate_names)
    ests = []
    for name, t in pars.items():
        if name not in known:
            raise _unknown_key("[parameters]", name, sorted(known))
        where = f"[parameters.{name}]"
        if not isinstance(t, dict):
            raise ValueError(f"{where} must be a table with value = NUMBER, not {quote_user_value(t)}")
        if name in _SWITCHES:  # documented_bounds would call it 'a share of the heat'
            raise ValueError(f"{where}: {name} is a switch of the physics, not a calibrated number; the "
                             f"[calibration] model sets it ({', '.join(MODELS)})")
        for k in t:
            if k not in _PARAM_KEYS:
                raise _unknown_key(where, k, _PARAM_KEYS)
        if "value" not in t:
            raise ValueError(f"{where} has no value")
        f = {k: _typed(where, k, v, _PARAM_KEYS[k]) for k, v in t.items()}
        _check_unit(where, name, f.get("unit"))
        v = f["value"]
        lo, hi, what = documented_bounds(name)
        if not math.isfinite(v) or not lo <= v <= hi:
            raise ValueError(f"{where} value {v:g} is outside its bounds [{lo:g}, {hi:g}] ({what})")
        if name in lrg_names:
            from ..physics.params import check_values

            try:
                check_values(name, v)
            except ValueError as exc:
                raise ValueError(f"{where} value: {exc}") from None
        flo, fhi = f.get("lower", lo), f.get("upper", hi)
        if math.isnan(flo) or math.isnan(fhi) or flo > fhi:
            raise ValueError(f"{where} lower {flo:g} and upper {fhi:g} are not a range")
        if not flo <= v <= fhi:
            raise ValueError(f"{where} value {v:g} is outside the file's own bounds [{flo:g}, {fhi:g}]")
        se = f.get("std_error", math.nan)
        if se < 0:
            raise ValueError(f"{where} std_error must be >= 0 (or nan), not {se:g}")
        ests.append(ParameterEstimate(name, v, se, flo, fhi, f.get("unit", ""), f.get("meaning", ""),
                                      f.get("at_bound", False), f.get("ci_low", math.nan), f.get("ci_high", math.nan),
                                      f.get("ci_method", "")))
    runs = raw.get("runs", {})
    if not isinstance(runs, dict):
        raise ValueError("'runs' must be a table [runs]")
    lists = {}
    for k, v in runs.items():
        if k not in _RUN_KEYS:
            raise _unknown_key("[runs]", k, _RUN_KEYS)
        if not isinstance(v, list) or any(isinstance(x, bool) or not isinstance(x, (int, float)) for x in v):
            raise ValueError(f"[runs] {k} must be a list of numbers")
        lists[k] = tuple(float(x) for x in v)
    selected = tuple(x for x in h.get("selected_from", "").split(",") if x)
    for m in selected:
        if m not in MODELS:
            raise ValueError(f"[calibration] selected_from names {quote_user_value(m)}, not one of {', '.join(MODELS)}")
    idx = lists.get("loo_model_index", ())
    if any(not float(k).is_integer() or not 0 <= k < len(selected) for k in idx):
        raise ValueError(f"[runs] loo_model_index must hold indices into selected_from (0 to {len(selected) - 1})")
    return Calibration(
        selected_from=selected, loo_models=tuple(int(k) for k in idx),
        parameters=tuple(ests), response=h.get("response", "tcr_c_per_min"), n=h.get("n", 0),
        r2=h.get("r2", math.nan), rmse=h.get("rmse", math.nan), loo_r2=h.get("loo_r2"),
        loo_rmse=h.get("loo_rmse"), data=h.get("data", ""), data_sha256=h.get("data_sha256", ""),
        observed=lists.get("observed", ()), predicted=lists.get("predicted", ()),
        loo_predicted=lists.get("loo_predicted", ()), method=h.get("method", ""),
        uncalibrated_r2=h.get("uncalibrated_r2"), model=h.get("model", ""),
    )


def resolve_calibration(spec) -> Calibration | None:
    """``"default"`` (the shipped file, if any), ``None``/``False`` (raw physics), a path, a
    mapping ``{name: value}`` or a :class:`Calibration`."""
    if spec is None or spec is False:
        return None
    if isinstance(spec, Calibration):
        return spec
    if isinstance(spec, str) and spec == "default":
        from ..datasets import data_path

        try:
            return load_calibration(data_path(CALIBRATION_FILE))
        except FileNotFoundError:
            return None
    if isinstance(spec, Mapping):
        from ..physics.params import param_names
        from .runs import SURROGATE_PARAMETERS

        known = set(param_names()) | set(SURROGATE_PARAMETERS)
        ests = []
        for k, v in spec.items():
            if k not in known:
                raise ValueError(f"calibration: unknown parameter {k!r}")
            if k in _SWITCHES and isinstance(v, (bool, np.bool_)):  # a switch of the physics
                ests.append(ParameterEstimate(str(k), bool(v), math.nan, 0.0, 1.0))
                continue
            if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)):
                raise ValueError(f"calibration: {k} must be a number, not {type(v).__name__}")
            lo, hi, what = documented_bounds(str(k))
            if not (math.isfinite(float(v)) and lo <= float(v) <= hi):
                raise ValueError(f"calibration: {k} = {float(v):g} is outside its bounds [{lo:g}, {hi:g}] ({what})")
            ests.append(ParameterEstimate(str(k), float(v), math.nan, lo, hi))
        return Calibration(tuple(ests), "tcr_c_per_min", 0, math.nan, math.nan)
    if isinstance(spec, (str, Path)):
        return load_calibration(spec)
    raise TypeError(f"calibration must be 'default', None, a path, a mapping or a Calibration, not {type(spec).__name__}")


def file_sha256(path) -> str:
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()
