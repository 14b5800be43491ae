"""Parameters of the guide (THK SHS15V) and the motion stage, with units and sources.

The defaults live in ``data/lrg_shs15v.toml`` (shipped as ``rsm_lrg/data/lrg_shs15v.toml``):
one table per parameter with ``value``, ``unit``, ``source`` and, for the values the paper
does not give, ``assumption`` (the rationale). :class:`LRGParams` reads its defaults from
that file, so the file is the single source of the numbers.

Every name is flat and carries its unit (``preload_n``, ``hinge_width_m``, ``mu_k`` ...), so
the same names work as ``--param NAME=VALUE`` on the command line, as keys of a TOML
override file, and as DataFrame columns in the surrogate (:func:`check_values` validates a
whole column at once).

>>> p = LRGParams()
>>> round(p.normal_load_n, 2), round(p.f_mu_max_n, 3)
(173.65, 5.209)
>>> p.with_overrides(mu_k=0.01).mu_k
0.01
>>> LRGParams(mu_s=1.5)
Traceback (most recent call last):
...
ValueError: parameter mu_s must lie in [0, 1], got 1.5
"""

from __future__ import annotations

import dataclasses
import math
import tomllib
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..datasets import data_path

__all__ = [
    "LRGParams", "PARAM_INFO", "ASSUMPTIONS", "param_names", "load_params", "check_values",
    "parse_assignments", "DEFAULTS_FILE", "PHYSICAL_RANGES", "physical_range_text",
]

#: Name of the shipped defaults file.
DEFAULTS_FILE = "lrg_shs15v.toml"


def _read_spec(path: Path) -> dict[str, dict[str, Any]]:
    with open(path, "rb") as fh:
        raw = tomllib.load(fh)
    spec = {}
    for name, entry in raw.items():
        if not isinstance(entry, dict) or "value" not in entry:
            raise ValueError(f"{path}: table [{name}] has no 'value'")
        spec[name] = dict(entry)
    return spec


#: name -> {"value", "unit", "source", ["assumption"]} as shipped.
PARAM_INFO: dict[str, dict[str, Any]] = _read_spec(data_path(DEFAULTS_FILE))

#: name -> rationale, for the values the paper does not give.
ASSUMPTIONS: dict[str, str] = {k: v["assumption"] for k, v in PARAM_INFO.items() if "assumption" in v}


def _d(name: str):
    return field(default=PARAM_INFO[name]["value"], metadata={"unit": PARAM_INFO[name]["unit"]})


# Validation rules (name -> (kind, low, high)); every other float must be > 0.
_CLOSED_UNIT = {"mu_s", "mu_k"}
_OPEN_UNIT = {"frame_mass_fraction"}
_NONNEG = {"dwell_s", "jerk_time_s", "hinge_damping_ratio", "preload_n", "viscous_friction_n_s_m", "drive_heat_w",
           "overconstraint_misfit_m"}
_INTS = {"hinge_count", "ball_rows", "balls_per_row"}
_BOOLS = {"heat_in_calories", "hinge_membrane", "heat_balance", "two_carriage", "other_stage_running"}

#: Physical range of every numeric parameter, inclusive, in its unit: what a linear rolling
#: guide on a motion stage of this kind (and its air, steel and test) can physically be.
#: Far wider than any experiment (so that nothing sensible is refused), narrow enough to
#: stop a typo, a wrong unit (mm for m) or a number that would overflow the physics. Checked
#: with the rules above by :func:`check_values`: for ``--param``, TOML files, design
#: columns and calibration files alike.
PHYSICAL_RANGES: dict[str, tuple[float, float]] = {
    "preload_n": (0.0, 1e5), "stage_mass_kg": (1e-3, 1e3), "gravity_m_s2": (0.1, 100.0),
    "mu_s": (0.0, 1.0), "mu_k": (0.0, 1.0), "viscous_friction_n_s_m": (0.0, 1e4),
    "hinge_count": (1, 100), "hinge_thickness_m": (1e-6, 0.05), "hinge_width_m": (1e-4, 1.0),
    "hinge_length_m": (1e-4, 1.0), "hinge_modulus_pa": (1e6, 1.2e12), "hinge_damping_ratio": (0.0, 10.0),
    "frame_mass_fraction": (0.0, 1.0), "carriage_mass_kg": (1e-3, 1e3),
    "hinge_yield_pa": (1e6, 1e10), "hinge_tensile_strength_pa": (1e6, 1e10), "hinge_fatigue_limit_pa": (1e6, 1e10),
    "carriage_spacing_m": (1e-3, 2.0), "guide_modulus_pa": (1e9, 1.2e12), "guide_poisson": (0.0, 0.5),
    "ball_modulus_pa": (1e9, 1.2e12), "ball_poisson": (0.0, 0.5), "ball_conductivity_w_mk": (0.01, 5000.0), "hinge_conductivity_w_mk": (0.01, 5000.0),
    "drive_heat_w": (0.0, 1e3), "stage_loss_conductance_w_k": (1e-4, 1e3), "overconstraint_misfit_m": (0.0, 1e-3),
    "ball_contact_conductance_w_k": (1e-4, 1e4), "joint_conductance_w_m2k": (1.0, 1e7),
    "base_heat_capacity_j_k": (1e-3, 1e9), "base_loss_conductance_w_k": (1e-4, 1e4),
    "hinge_density_kg_m3": (100.0, 3e4), "hinge_specific_heat_j_kgk": (10.0, 2e4),
    "ball_radius_m": (1e-4, 0.05), "raceway_radius_m": (1e-4, 0.1), "ball_rows": (1, 16),
    "balls_per_row": (1, 1000), "contact_angle_deg": (0.0, 90.0),
    "velocity_m_s": (1e-4, 20.0), "thermal_equivalent_j_per_cal": (4.18, 4.21),
    "air_velocity_m_s": (1e-3, 100.0), "char_length_m": (1e-4, 10.0),
    "air_kinematic_viscosity_m2_s": (1e-7, 1e-3), "air_dynamic_viscosity_pa_s": (1e-7, 1e-2),
    "air_conductivity_w_mk": (1e-3, 1.0), "air_specific_heat_j_kgk": (100.0, 2e4),
    "wear_coefficient": (1e-12, 1.0), "hardness_hb": (1.0, 2000.0),
    "stroke_m": (1e-5, 10.0), "acceleration_m_s2": (1e-3, 1e4), "dwell_s": (0.0, 60.0),
    # jerk time: 0 (trapezoid) up to a second, the acceleration time of a slow stage (v/a of
    # 0.1 m/s at 0.1 m/s^2); the meaningful range is 0 to the acceleration time v/a
    "jerk_time_s": (0.0, 1.0),
    "ambient_c": (-100.0, 200.0), "test_duration_min": (1.0, 1e5),
    # geometry: up to about twice the largest miniature-to-large guides (THK SHS65: block
    # 126 x 255 x 90 mm, rail 63 x 53 mm; a 2 m rail is five times the rig's); larger guides
    # would also make the 3-D thermal model too large to solve in seconds
    "block_width_m": (1e-3, 0.25), "block_length_m": (1e-3, 0.5), "block_height_m": (1e-3, 0.2),
    "rail_width_m": (1e-3, 0.15), "rail_height_m": (1e-3, 0.15), "rail_mass_kg_per_m": (1e-3, 100.0),
    "rail_length_m": (1e-3, 2.0),
    "guide_density_kg_m3": (100.0, 3e4), "guide_conductivity_w_mk": (0.01, 5000.0),
    "guide_specific_heat_j_kgk": (10.0, 2e4), "ball_density_kg_m3": (100.0, 3e4),
    "stage_density_kg_m3": (100.0, 3e4), "stage_conductivity_w_mk": (0.01, 5000.0),
    "stage_specific_heat_j_kgk": (10.0, 2e4),
}


def physical_range_text(name: str) -> str:
    """``"[lo, hi] unit"`` of a parameter's :data:`PHYSICAL_RANGES` entry.

    >>> physical_range_text("preload_n")
    '[0, 100000] N'
    """
    lo, hi = PHYSICAL_RANGES[name]
    unit = PARAM_INFO[name]["unit"]
    return f"[{lo:g}, {hi:g}]" + ("" if unit in ("1", "") else f" {unit}")


@dataclass(frozen=True)
class LRGParams:
    """All inputs of the physics chain, SI units (degrees only for the contact angle, °C for
    the ambient, HB for the hardness). Defaults: the paper (Tables 1-3, Sections 2-4), the THK
    SHS15V catalog, and documented assumptions (:data:`ASSUMPTIONS`).

    Build a variant with :meth:`with_overrides` (or ``dataclasses.replace``), from a TOML file
    with :func:`load_params`, or from ``NAME=VALUE`` strings with :func:`parse_assignments`.
    Invalid values raise ``ValueError`` naming the parameter.

    Parameters
    ----------
    **values : float or int
        One keyword per field, each named with its unit (``preload_n`` [N], ``stage_mass_kg``
        [kg], ``hinge_thickness_m`` [m], ...); the unit, default and source of every field are in
        ``rsm_lrg/data/lrg_shs15v.toml`` and in ``LRGParams().to_frame()``.
    """

    # load and friction
    preload_n: float = _d("preload_n")
    stage_mass_kg: float = _d("stage_mass_kg")
    gravity_m_s2: float = _d("gravity_m_s2")
    mu_s: float = _d("mu_s")
    mu_k: float = _d("mu_k")
    viscous_friction_n_s_m: float = _d("viscous_friction_n_s_m")
    # flexure hinges
    hinge_count: int = _d("hinge_count")
    hinge_thickness_m: float = _d("hinge_thickness_m")
    hinge_width_m: float = _d("hinge_width_m")
    hinge_length_m: float = _d("hinge_length_m")
    hinge_modulus_pa: float = _d("hinge_modulus_pa")
    hinge_damping_ratio: float = _d("hinge_damping_ratio")
    hinge_membrane: bool = _d("hinge_membrane")
    hinge_yield_pa: float = _d("hinge_yield_pa")
    hinge_tensile_strength_pa: float = _d("hinge_tensile_strength_pa")
    hinge_fatigue_limit_pa: float = _d("hinge_fatigue_limit_pa")
    hinge_conductivity_w_mk: float = _d("hinge_conductivity_w_mk")
    drive_heat_w: float = _d("drive_heat_w")
    stage_loss_conductance_w_k: float = _d("stage_loss_conductance_w_k")
    overconstraint_misfit_m: float = _d("overconstraint_misfit_m")
    frame_mass_fraction: float = _d("frame_mass_fraction")
    carriage_mass_kg: float = _d("carriage_mass_kg")
    # one heat balance in watts (the rig's bodies)
    heat_balance: bool = _d("heat_balance")
    ball_contact_conductance_w_k: float = _d("ball_contact_conductance_w_k")
    # both carriages on one rail (Section 4.1; calibration model v6)
    two_carriage: bool = _d("two_carriage")
    other_stage_running: bool = _d("other_stage_running")
    carriage_spacing_m: float = _d("carriage_spacing_m")
    joint_conductance_w_m2k: float = _d("joint_conductance_w_m2k")
    base_heat_capacity_j_k: float = _d("base_heat_capacity_j_k")
    base_loss_conductance_w_k: float = _d("base_loss_conductance_w_k")
    hinge_density_kg_m3: float = _d("hinge_density_kg_m3")
    hinge_specific_heat_j_kgk: float = _d("hinge_specific_heat_j_kgk")
    # balls
    ball_radius_m: float = _d("ball_radius_m")
    raceway_radius_m: float = _d("raceway_radius_m")
    ball_rows: int = _d("ball_rows")
    balls_per_row: int = _d("balls_per_row")
    contact_angle_deg: float = _d("contact_angle_deg")
    # heat
    velocity_m_s: float = _d("velocity_m_s")
    thermal_equivalent_j_per_cal: float = _d("thermal_equivalent_j_per_cal")
    heat_in_calories: bool = _d("heat_in_calories")
    # convection
    air_velocity_m_s: float = _d("air_velocity_m_s")
    char_length_m: float = _d("char_length_m")
    air_kinematic_viscosity_m2_s: float = _d("air_kinematic_viscosity_m2_s")
    air_dynamic_viscosity_pa_s: float = _d("air_dynamic_viscosity_pa_s")
    air_conductivity_w_mk: float = _d("air_conductivity_w_mk")
    air_specific_heat_j_kgk: float = _d("air_specific_heat_j_kgk")
    # wear
    wear_coefficient: float = _d("wear_coefficient")
    hardness_hb: float = _d("hardness_hb")
    # motion
    stroke_m: float = _d("stroke_m")
    acceleration_m_s2: float = _d("acceleration_m_s2")
    dwell_s: float = _d("dwell_s")
    jerk_time_s: float = _d("jerk_time_s")
    # thermal environment and test
    ambient_c: float = _d("ambient_c")
    test_duration_min: float = _d("test_duration_min")
    # geometry
    block_width_m: float = _d("block_width_m")
    block_length_m: float = _d("block_length_m")
    block_height_m: float = _d("block_height_m")
    rail_width_m: float = _d("rail_width_m")
    rail_height_m: float = _d("rail_height_m")
    rail_mass_kg_per_m: float = _d("rail_mass_kg_per_m")
    rail_length_m: float = _d("rail_length_m")
    # materials
    guide_density_kg_m3: float = _d("guide_density_kg_m3")
    guide_conductivity_w_mk: float = _d("guide_conductivity_w_mk")
    guide_specific_heat_j_kgk: float = _d("guide_specific_heat_j_kgk")
    ball_density_kg_m3: float = _d("ball_density_kg_m3")
    guide_modulus_pa: float = _d("guide_modulus_pa")
    guide_poisson: float = _d("guide_poisson")
    ball_modulus_pa: float = _d("ball_modulus_pa")
    ball_poisson: float = _d("ball_poisson")
    ball_conductivity_w_mk: float = _d("ball_conductivity_w_mk")
    stage_density_kg_m3: float = _d("stage_density_kg_m3")
    stage_conductivity_w_mk: float = _d("stage_conductivity_w_mk")
    stage_specific_heat_j_kgk: float = _d("stage_specific_heat_j_kgk")

    def __post_init__(self):
        for f in dataclasses.fields(self):
            object.__setattr__(self, f.name, _coerce(f.name, getattr(self, f.name)))

    # ---- construction ------------------------------------------------------------------
    def with_overrides(self, **overrides: Any) -> LRGParams:
        """A copy with some values replaced; unknown names raise ``ValueError``.

        Parameters
        ----------
        **overrides
            ``name=value`` for the fields to replace (SI units, as the fields).

        Returns
        -------
        LRGParams
            The copy, checked.
        """
        _check_names(overrides)
        return dataclasses.replace(self, **overrides)

    def to_dict(self) -> dict[str, Any]:
        """Plain ``{name: value}`` (JSON-safe).

        Returns
        -------
        dict
            Plain JSON-safe data (numbers, strings, lists and dicts).
        """
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}

    def to_frame(self):
        """Tidy table: name, value, unit, source, assumption.

        Returns
        -------
        pandas.DataFrame
            The table described above.
        """
        import pandas as pd

        rows = []
        for name, value in self.to_dict().items():
            info = PARAM_INFO[name]
            rows.append({"name": name, "value": value, "unit": info["unit"], "source": info["source"],
                         "assumption": info.get("assumption", "")})
        return pd.DataFrame(rows)

    # ---- derived quantities (the paper's symbols) --------------------------------------
    @property
    def normal_load_n(self) -> float:
        """F_z = F0 + m_t·g [N] (Section 2.1, Eq. 2 and Eq. 8)."""
        return self.preload_n + self.stage_mass_kg * self.gravity_m_s2

    @property
    def f_mu_max_n(self) -> float:
        """f_µmax = µ_s·(F0 + m_t·g) [N] (Eq. 2)."""
        return self.mu_s * self.normal_load_n

    @property
    def n_balls(self) -> int:
        """Balls in the carriage (rows × balls per row)."""
        return self.ball_rows * self.balls_per_row

    @property
    def hinge_stiffness_n_m(self) -> float:
        """K_n of one hinge [N/m] (Eq. 1)."""
        return self.hinge_modulus_pa * self.hinge_width_m * self.hinge_thickness_m ** 3 / self.hinge_length_m ** 3

    @property
    def hinge_membrane_stiffness_n_m3(self) -> float:
        """k₃ of one leaf with held ends [N/m³] (0 without ``hinge_membrane``); see
        :func:`rsm_lrg.physics.hinge.hinge_membrane_stiffness`."""
        from .hinge import hinge_membrane_stiffness

        if not self.hinge_membrane:
            return 0.0
        return float(hinge_membrane_stiffness(self.hinge_modulus_pa, self.hinge_width_m, self.hinge_thickness_m,
                                              self.hinge_length_m))

    @property
    def frame_mass_kg(self) -> float:
        """Moving mass on the guide side of the hinges: frame share of m_t + carriage [kg]."""
        return self.frame_mass_fraction * self.stage_mass_kg + self.carriage_mass_kg

    @property
    def working_stage_mass_kg(self) -> float:
        """m_ws: the working-stage share of m_t [kg]."""
        return (1.0 - self.frame_mass_fraction) * self.stage_mass_kg


def param_names() -> list[str]:
    """The parameter names, in declaration order."""
    return [f.name for f in dataclasses.fields(LRGParams)]


_FIELDS = {f.name: f for f in dataclasses.fields(LRGParams)}


def _check_names(mapping: Mapping[str, Any], where: str = "") -> None:
    for k in mapping:
        if k not in _FIELDS:
            import difflib

            close = difflib.get_close_matches(str(k), list(_FIELDS), n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            raise ValueError(f"{where}unknown parameter {k!r}{hint}")


def _coerce(name: str, value: Any) -> Any:
    """Convert one scalar value to its field's type and validate it."""
    from ..io import quote_user_value as q

    if name in _BOOLS:
        if isinstance(value, (bool, np.bool_)):
            return bool(value)
        if isinstance(value, str) and value.strip().lower() in {"true", "1", "yes", "false", "0", "no"}:
            return value.strip().lower() in {"true", "1", "yes"}
        if isinstance(value, (int, np.integer)) and value in (0, 1):
            return bool(value)
        raise ValueError(f"parameter {name} must be true or false, got {q(value)}")
    if isinstance(value, (bool, np.bool_)):
        raise ValueError(f"parameter {name} must be a number, got {q(value)}")
    try:
        x = float(value)
    except OverflowError:
        x = math.inf
    except (TypeError, ValueError):
        raise ValueError(f"parameter {name} must be a number, got {q(value)}") from None
    if not math.isfinite(x):
        raise ValueError(f"parameter {name} must be finite, got {q(value)}")
    if name in _INTS:
        if x != int(x) or x < 1:
            raise ValueError(f"parameter {name} must be a whole number >= 1, got {q(value)}")
        check_values(name, x)
        return int(x)
    check_values(name, x)
    return x


#: The geometry a run must have, as the rules are printed in an error.
OFF_THE_RAIL = "the carriage must stay on the rail: stroke <= rail_length_m - block_length_m"
LEAF_TOO_THICK = "a leaf hinge must be thinner than its length (hinge_length_m)"


def off_the_rail(stroke_m, rail_length_m, block_length_m):
    """Where a stroke would take the carriage off the rail [bool, broadcast]: ``stroke_m >
    rail_length_m - block_length_m`` (every length in m)."""
    return np.asarray(stroke_m, dtype=float) > np.asarray(rail_length_m, dtype=float) - np.asarray(block_length_m, dtype=float)


def leaf_too_thick(thickness_m, hinge_length_m):
    """Where a leaf is not thinner than it is long [bool, broadcast] (Eq. 1 is a thin-beam law)."""
    return np.asarray(thickness_m, dtype=float) >= np.asarray(hinge_length_m, dtype=float)


def check_values(name: str, values) -> None:
    """Validate a scalar or a whole column of values of parameter ``name``.

    Raises ``ValueError`` naming the parameter (and, for arrays, the first bad row, 0-based).

    >>> check_values("stroke_m", [0.04, 0.06])
    >>> check_values("stroke_m", [0.04, -0.06])
    Traceback (most recent call last):
    ...
    ValueError: parameter stroke_m must be > 0, got -0.06 (row 1)
    """
    if name not in _FIELDS:
        _check_names({name: None})
    if name in _BOOLS:
        return
    a = np.asarray(values, dtype=float)
    scalar = a.ndim == 0
    a = np.atleast_1d(a)

    def fail(mask, rule):
        i = int(np.flatnonzero(mask)[0])
        where = "" if scalar else f" (row {i})"
        raise ValueError(f"parameter {name} must {rule}, got {a[i]:g}{where}")

    bad = ~np.isfinite(a)
    if bad.any():
        fail(bad, "be finite")
    if name in _CLOSED_UNIT:
        rule, bad = "lie in [0, 1]", (a < 0) | (a > 1)
    elif name in _OPEN_UNIT:
        rule, bad = "lie strictly between 0 and 1", (a <= 0) | (a >= 1)
    elif name in _NONNEG:
        rule, bad = "be >= 0", a < 0
    elif name == "ambient_c":
        rule, bad = "be above absolute zero (-273.15 degC)", a <= -273.15
    elif name == "contact_angle_deg":
        rule, bad = "lie strictly between 0 and 90 degrees", (a <= 0) | (a >= 90)
    elif name in _INTS:
        rule, bad = "be a whole number >= 1", (a < 1) | (a != np.round(a))
    else:
        rule, bad = "be > 0", a <= 0
    if bad.any():
        fail(bad, rule)
    if name in PHYSICAL_RANGES:
        lo, hi = PHYSICAL_RANGES[name]
        bad = (a < lo) | (a > hi)
        if bad.any():
            fail(bad, f"lie in its physical range {physical_range_text(name)}")


def parse_assignments(items: Iterable[str]) -> dict[str, Any]:
    """``["mu_k=0.01", "hinge_count=2"]`` -> ``{"mu_k": 0.01, "hinge_count": 2}``, validated.

    A name given twice raises ``ValueError`` (the later value would silently win).

    >>> parse_assignments(["mu_k=0.01", "heat_in_calories=false"])
    {'mu_k': 0.01, 'heat_in_calories': False}
    """
    out: dict[str, Any] = {}
    for item in items:
        if "=" not in item:
            from ..io import InputError, quote_user_value

            raise InputError(f"--param {quote_user_value(item, 60)}: expected NAME=VALUE")
        name, _, text = item.partition("=")
        name, text = name.strip(), text.strip()
        if name in out:  # the later one would silently win
            from ..io import InputError, quote_user_value

            raise InputError(f"--param {quote_user_value(item, 60)}: {name} is given more than once")
        try:
            _check_names({name: None})
            out[name] = _coerce(name, text)
        except ValueError as exc:
            from ..io import InputError, quote_user_value

            raise InputError(f"--param {quote_user_value(item, 60)}: {exc}") from None
    return out


def load_params(path: str | Path | None = None, base: LRGParams | None = None, **overrides: Any) -> LRGParams:
    """Parameters from a TOML file (flat ``name = value`` or ``[name] value = ...`` tables).

    Values not in the file keep those of ``base`` (default: the shipped defaults);
    ``overrides`` are applied last.
    """
    p = base or LRGParams()
    values: dict[str, Any] = {}
    if path is not None:
        from ..io import read_toml, show_path

        path = Path(path)
        raw = read_toml(path)
        try:
            _check_names(raw)
            for k, v in raw.items():
                if isinstance(v, dict):
                    extra = sorted(set(v) - {"value", "unit", "source", "assumption"})
                    if "value" not in v:
                        raise ValueError(f"table [{k}] has no value")
                    if extra:
                        raise ValueError(f"table [{k}] has an unknown key {extra[0]!r} "
                                         f"(known: value, unit, source, assumption)")
                    unit = v.get("unit")
                    own = PARAM_INFO[k]["unit"] if k in PARAM_INFO else None
                    if unit is not None and own is not None and (not isinstance(unit, str) or unit.strip() != own):
                        from ..io import quote_user_value

                        raise ValueError(f"table [{k}] unit {quote_user_value(unit)} is not the unit of {k}, "
                                         f"{own!r}; write the value {'as a plain number' if own in ('1', '') else 'in ' + own} "
                                         "(values are never converted)")
                    v = v["value"]
                if isinstance(v, str):  # a TOML value has its type: text is never read as a number
                    from ..io import quote_user_value

                    raise ValueError(f"{k} = {quote_user_value(v)} is text, not a "
                                     f"{'boolean' if k in _BOOLS else 'number'}; write it without quotes")
                values[k] = v
            values = {k: _coerce(k, v) for k, v in values.items()}
        except ValueError as exc:
            raise ValueError(f"{show_path(path)}: {exc}") from None
    values.update(overrides)
    return p.with_overrides(**values)
