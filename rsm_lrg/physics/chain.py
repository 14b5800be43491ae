"""The paper's physics chain for one parameter set: what ``rsm-lrg physics`` prints.

load (Eq. 2) → friction heat and source (Eqs. 8-9) → convection (Eqs. 10-12) → hinges at the
three Table 3 thicknesses (Eqs. 1-2) → thermal model (Eqs. 6-7, :mod:`.thermal`) → wear of the
RFCMS against the RMS (Eqs. 13-17 with the stage dynamics of :mod:`.dynamics`).

>>> r = physics_chain(thermal=False)
>>> round(r.normal_load_n, 2), round(r.f_mu_max_n, 3), round(r.heat_w, 4)
(173.65, 5.209, 0.415)
>>> sorted(r.to_dict())[:3]
['f_mu_max_n', 'h_front_w_m2k', 'h_side_w_m2k']
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import ParameterError
from . import convection, dynamics, heat, hinge, motion, wear
from .params import LRGParams

__all__ = ["PhysicsResult", "HingeRow", "physics_chain", "TABLE3_THICKNESSES_M", "PAPER_VALUES",
           "PAPER_WEAR_RATIO", "TABLE3_BOX", "LeafYieldScan", "leaf_yield_scan", "FATIGUE_CRITERION"]

#: Hinge thicknesses of Table 3 (low, centre, high) [m].
TABLE3_THICKNESSES_M = (0.0001, 0.0003, 0.0005)

#: The factor box of Table 3 (low, high) in SI units: thickness, stroke, velocity, acceleration.
TABLE3_BOX = {"thickness_m": (1e-4, 5e-4), "stroke_m": (0.04, 0.06), "velocity_m_s": (0.4, 0.6),
              "acceleration_m_s2": (20.0, 40.0)}

#: What the model does where a leaf would yield (printed with the scan).
YIELD_BEHAVIOUR = ("the model keeps the elastic beam-column law there and flags the rows (simulate: hinge_yields, "
                   "a warning on stderr); a real leaf would take a permanent set, so the rows' dynamics, heat and "
                   "wear are outside the model's validity")

#: The fatigue criterion of :func:`.hinge.leaf_fatigue`.
FATIGUE_CRITERION = ("modified Goodman at the leaf clamps, sigma_a/S_e + sigma_m/R_m >= 1 (Shigley, 10th ed., "
                     "Eq. 6-41), sigma_a the bending and sigma_m the tension part of the beam-column clamp stress "
                     "over the deflection's swing +-peak")

#: RFCMS/RMS wear volume per unit time from the paper's FEM (Section 3.2).
PAPER_WEAR_RATIO = 0.5893

#: The paper's numbers (Sections 2-3), for side-by-side printing.
PAPER_VALUES = {
    "normal_load_n": 173.65, "f_mu_max_n": 5.209, "heat_w": 0.4150, "heat_source_w_m3": 5.6e5,
    "reynolds": 290.3, "prandtl": 0.703, "h_side_w_m2k": 8.82, "h_front_w_m2k": 22.45,
    "steady_rise_k_fv": 4.038, "rfcms_over_rms": PAPER_WEAR_RATIO,
}

_THERMAL_KEYS = ("steady_rise_k_fv", "steady_rise_k_network", "time_to_95_percent_h", "tcr_c_per_min")


@dataclass(frozen=True)
class HingeRow:
    """One hinge thickness: stiffness of one hinge K_n [N/m] (Eq. 1) and deflection at
    breakaway Δδ = f_µmax/(n·K_n) [m] (Eq. 2); and, from the stage dynamics at the
    parameters' motion (:func:`.dynamics.cycle_metrics`), the largest deflection of a leaf
    over the periodic cycle [m], its small-deflection bending stress ``3·E·y·δ/l²`` [Pa], the
    clamp stress of the exact beam-column leaf with held ends [Pa] (bending plus tension,
    :func:`.hinge.hinge_peak_stress`), the material's yield strength [Pa] and whether the leaf
    would yield there (``yields``: a physical limit of the design; the model keeps the elastic
    law beyond it and flags the row)."""

    thickness_m: float
    stiffness_n_m: float
    deflection_m: float
    peak_deflection_m: float = float("nan")
    peak_bending_stress_pa: float = float("nan")
    peak_stress_pa: float = float("nan")
    yield_strength_pa: float = float("nan")

    @property
    def yields(self) -> bool:
        return bool(self.peak_stress_pa > self.yield_strength_pa)

    def to_dict(self) -> dict[str, float]:
        return {"thickness_m": self.thickness_m, "stiffness_n_m": self.stiffness_n_m,
                "deflection_m": self.deflection_m, "peak_deflection_m": self.peak_deflection_m,
                "peak_bending_stress_pa": self.peak_bending_stress_pa, "peak_stress_pa": self.peak_stress_pa,
                "yield_strength_pa": self.yield_strength_pa, "yields": self.yields}


@dataclass(frozen=True)
class LeafYieldScan:
    """Where in the Table 3 box a leaf would yield: the exact beam-column clamp stress
    (:func:`.hinge.hinge_peak_stress`) at the peak leaf deflection over the periodic cycle
    (:func:`.dynamics.cycle_metrics`) on a full grid of ``levels`` equally spaced values per
    factor of :data:`TABLE3_BOX`, against ``hinge_yield_pa``.

    Settings where a leaf deflects beyond the tabulated law (``n_beyond_model``) count as
    yielding, with the stress at that limit (a lower bound). ``region`` gives bounds that every
    yielding point satisfies (thickness at most, stroke,
    velocity and acceleration at least; ``None`` where nothing yields): necessary conditions,
    not sufficient ones. ``by_thickness`` lists, per thickness level, the points that yield,
    the points scanned and the largest stress [Pa].
    """

    levels: int
    n_points: int
    n_yield: int
    n_beyond_model: int
    viscous_friction_n_s_m: float
    yield_strength_pa: float
    max_stress_pa: float
    max_at: dict
    region: dict | None
    by_thickness: tuple
    fatigue_limit_pa: float = float("nan")
    tensile_strength_pa: float = float("nan")
    n_fatigue: int = 0
    max_utilisation: float = float("nan")
    fatigue_by_thickness: tuple = ()
    fatigue_share: dict = field(default_factory=dict)
    n_irregular: int = 0

    def fatigue_dict(self) -> dict[str, Any]:
        """Where a leaf would fail in fatigue (the ``leaf_fatigue`` key of ``physics --json``)."""
        return {"fatigue_limit_pa": self.fatigue_limit_pa, "tensile_strength_pa": self.tensile_strength_pa,
                "criterion": FATIGUE_CRITERION, "levels": self.levels, "n_points": self.n_points,
                "n_fatigue": self.n_fatigue, "max_utilisation": self.max_utilisation,
                "n_irregular": self.n_irregular,
                "by_thickness": [{"thickness_m": t, "n_fatigue": k, "n_points": m, "max_amplitude_pa": sa}
                                 for t, k, m, sa in self.fatigue_by_thickness],
                "share": {k: [list(x) for x in v] for k, v in self.fatigue_share.items()}}

    def fatigue_text(self) -> str:
        lines = [f"leaf fatigue over the Table 3 box ({self.n_points} settings; {FATIGUE_CRITERION}, S_e = "
                 f"{self.fatigue_limit_pa / 1e6:.0f} MPa, R_m = {self.tensile_strength_pa / 1e6:.0f} MPa): "
                 f"{self.n_fatigue} settings fail, largest utilisation {self.max_utilisation:.2f}"]
        for t, k, m, sa in self.fatigue_by_thickness:
            lines.append(f"  {t * 1e3:.2f} mm leaf: {k} of {m} fail in fatigue, largest amplitude {sa / 1e6:.0f} MPa")
        for name, unit in (("acceleration_m_s2", "m/s^2"), ("velocity_m_s", "m/s"), ("stroke_m", "m")):
            if name in self.fatigue_share:
                parts = ", ".join(f"{x:g} {unit} {k}/{m}" for x, k, m in self.fatigue_share[name])
                lines.append(f"    by {name.split('_')[0]} (all thicknesses): {parts}")
        if self.n_irregular:
            lines.append(f"  {self.n_irregular} settings have no periodic state within the integrated cycles: their "
                         "amplitude is that of the last cycles integrated (at most 40), not an envelope over 200 cycles")
        return "\n".join(lines)

    def to_dict(self) -> dict[str, Any]:
        return {"box": {k: list(v) for k, v in TABLE3_BOX.items()}, "levels": self.levels,
                "n_points": self.n_points, "n_yield": self.n_yield, "n_beyond_model": self.n_beyond_model,
                "viscous_friction_n_s_m": self.viscous_friction_n_s_m, "yield_strength_pa": self.yield_strength_pa,
                "max_stress_pa": self.max_stress_pa, "max_at": dict(self.max_at),
                "region": None if self.region is None else dict(self.region),
                "by_thickness": [{"thickness_m": t, "n_yield": k, "n_points": m, "max_stress_pa": sm}
                                 for t, k, m, sm in self.by_thickness],
                "model_there": YIELD_BEHAVIOUR}

    def to_text(self) -> str:
        lines = [f"leaf yield over the Table 3 box ({self.levels} levels per factor, {self.n_points} settings, "
                 f"exact beam-column clamp stress at the cycle's peak deflection, block viscous friction "
                 f"{self.viscous_friction_n_s_m:g} N s/m; yield {self.yield_strength_pa / 1e6:.0f} MPa): "
                 f"{self.n_yield} settings yield"]
        if self.n_beyond_model:
            lines.append(f"  {self.n_beyond_model} of them deflect beyond the tabulated leaf law (200 thicknesses); "
                         "their stress is a lower bound")
        for t, k, m, sm in self.by_thickness:
            lines.append(f"  {t * 1e3:.2f} mm leaf: {k} of {m} yield, largest stress {sm / 1e6:.0f} MPa")
        a = self.max_at
        lines.append(f"  largest {self.max_stress_pa / 1e6:.0f} MPa at y = {a['thickness_m'] * 1e3:.2f} mm, "
                     f"s = {a['stroke_m']:g} m, v = {a['velocity_m_s']:g} m/s, a = {a['acceleration_m_s2']:g} m/s^2")
        if self.region is not None:
            r = self.region
            lines.append(f"  every yielding setting has y <= {r['thickness_m_max'] * 1e3:.2f} mm, s >= "
                         f"{r['stroke_m_min']:g} m, v >= {r['velocity_m_s_min']:g} m/s, a >= "
                         f"{r['acceleration_m_s2_min']:g} m/s^2; of those leaves' settings, yielding:")
            for name, unit in (("acceleration_m_s2", "m/s^2"), ("velocity_m_s", "m/s"), ("stroke_m", "m")):
                parts = ", ".join(f"{x:g} {unit} {k}/{m}" for x, k, m in r[f"share_by_{name}"])
                lines.append(f"    by {name.split('_')[0]}: {parts}")
            lines.append(f"  where a leaf yields, {YIELD_BEHAVIOUR}")
        return "\n".join(lines)


def leaf_yield_scan(params: LRGParams | None = None, *, levels: int = 5) -> LeafYieldScan:
    """Scan the Table 3 box for leaves past yield (:class:`LeafYieldScan`).

    ``params`` gives everything but the four factors (default: the shipped defaults; the
    shipped calibration's ``viscous_friction_n_s_m`` changes the peak deflections, pass it to
    scan the calibrated model). The RFCMS only (the RMS has no leaves).
    """
    p = params or LRGParams()
    if not (isinstance(levels, int) and 2 <= levels <= 21):
        raise ParameterError("levels", f"levels must be a whole number in [2, 21], got {levels!r}")
    axes = [np.linspace(lo, hi, levels) for lo, hi in TABLE3_BOX.values()]
    y, s, v, a = (g.ravel() for g in np.meshgrid(*axes, indexing="ij"))
    beyond = np.zeros(y.size, dtype=bool)
    irregular = np.zeros(y.size, dtype=bool)
    try:
        cm = dynamics.cycle_metrics(s, v, a, params=p, method="auto", hinge_thickness_m=y)
        pk = np.asarray(cm.peak_deflection_m, dtype=float)
        irregular = np.asarray(cm.periodicity_error_m, float) > 1e-6 * np.asarray(cm.sliding_distance_m, float)
    except ValueError as exc:  # some rows leave the tabulated leaf law: find them, one row at a time
        if "leaf model" not in str(exc):
            raise
        pk = np.empty(y.size)
        for i in range(y.size):
            try:
                pk[i] = float(np.asarray(dynamics.cycle_metrics(s[i], v[i], a[i], params=p, method="auto",
                                                                hinge_thickness_m=y[i]).peak_deflection_m))
            except ValueError as exc_i:
                if "leaf model" not in str(exc_i):
                    raise
                # deflected beyond LEAF_TABLE_MAX_RATIO thicknesses: far past yield; the stress at
                # that deflection is a lower bound of the leaf's
                beyond[i] = True
                pk[i] = hinge.LEAF_TABLE_MAX_RATIO * y[i]
    st = np.asarray(hinge.hinge_peak_stress(p.hinge_modulus_pa, y, p.hinge_length_m, pk,
                                            membrane=p.hinge_membrane), dtype=float)
    ylds = (st > p.hinge_yield_pa) | beyond
    k = int(np.argmax(st))
    max_at = {"thickness_m": float(y[k]), "stroke_m": float(s[k]), "velocity_m_s": float(v[k]),
              "acceleration_m_s2": float(a[k])}
    region: dict[str, Any] | None = None
    if ylds.any():
        region = {"thickness_m_max": float(y[ylds].max()), "stroke_m_min": float(s[ylds].min()),
                  "velocity_m_s_min": float(v[ylds].min()), "acceleration_m_s2_min": float(a[ylds].min())}
        thin = y <= region["thickness_m_max"]  # the leaves that yield somewhere: where in (s, v, a)
        for name, col, ax in (("stroke_m", s, axes[1]), ("velocity_m_s", v, axes[2]),
                              ("acceleration_m_s2", a, axes[3])):
            region[f"share_by_{name}"] = [[float(x), int((ylds & thin & (col == x)).sum()),
                                           int((thin & (col == x)).sum())] for x in ax]
    by = tuple((float(t), int(ylds[y == t].sum()), int((y == t).sum()), float(st[y == t].max())) for t in axes[0])
    sa, _, util = (np.asarray(x, float) for x in hinge.leaf_fatigue(
        p.hinge_modulus_pa, y, p.hinge_length_m, pk, p.hinge_fatigue_limit_pa, p.hinge_tensile_strength_pa))
    if not p.hinge_membrane:  # no tension: the bending stress of Eq. 1's leaf, fully reversed
        sa = np.asarray(hinge.hinge_bending_stress(p.hinge_modulus_pa, y, p.hinge_length_m, pk), float)
        util = sa / p.hinge_fatigue_limit_pa
    fails = (util >= 1.0) | beyond
    fby = tuple((float(t), int(fails[y == t].sum()), int((y == t).sum()), float(sa[y == t].max())) for t in axes[0])
    share = {name: [(float(x), int((fails & (col == x)).sum()), int((col == x).sum())) for x in ax]
             for name, col, ax in (("stroke_m", s, axes[1]), ("velocity_m_s", v, axes[2]),
                                   ("acceleration_m_s2", a, axes[3]))}
    return LeafYieldScan(levels, int(y.size), int(ylds.sum()), int(beyond.sum()), float(p.viscous_friction_n_s_m),
                         float(p.hinge_yield_pa), float(st[k]), max_at, region, by, float(p.hinge_fatigue_limit_pa),
                         float(p.hinge_tensile_strength_pa), int(fails.sum()), float(util.max()), fby, share,
                         int(irregular.sum()))


@dataclass(frozen=True)
class PhysicsResult:
    """The chain's numbers. ``to_dict()`` is the ``physics --json`` document of INTERFACE.md
    (exactly those keys); ``details`` holds the rest (wear volumes, the Eq. 14 and quasi-static
    readings, the inverse question, dynamics per cycle) and ``to_dict(extended=True)`` adds it.

    Parameters
    ----------
    normal_load_n : float
        Normal load on the guide [N].
    f_mu_max_n : float
        Maximum static friction force (Eq. 2) [N].
    heat_w : float
        Friction heat (Eq. 8) [W].
    heat_source_w_m3 : float
        Heat-source intensity (Eq. 9) [W/m³].
    reynolds, prandtl : float
        Reynolds and Prandtl numbers of the air flow (Eqs. 10-11) [-].
    h_side_w_m2k, h_front_w_m2k : float
        Convection coefficients of the side and front faces (Eq. 12) [W/(m² K)].
    hinge : tuple of HingeRow
        Per leaf thickness [m]: the hinge stiffness [N/m] and deflection [m] (Eq. 1).
    thermal : dict
        ``steady_rise_k_fv``, ``steady_rise_k_network`` [K], ``time_to_95_percent_h`` [h],
        ``tcr_c_per_min`` [°C/min] (Eq. 18).
    rfcms_over_rms : float
        Wear of the RFCMS over that of the RMS [-].
    params : LRGParams
        The inputs.
    details : dict
        The rest (wear volumes, Eq. 14 readings, dynamics per cycle).
    leaf_yield : LeafYieldScan, optional
        The leaves' yield check over the thicknesses.
    rig : object, optional
        The test rig's reading, when computed.
    """

    normal_load_n: float
    f_mu_max_n: float
    heat_w: float
    heat_source_w_m3: float
    reynolds: float
    prandtl: float
    h_side_w_m2k: float
    h_front_w_m2k: float
    hinge: tuple[HingeRow, ...]
    thermal: dict[str, float | None]
    rfcms_over_rms: float
    params: LRGParams = field(repr=False)
    details: dict[str, Any] = field(default_factory=dict, repr=False)
    leaf_yield: LeafYieldScan | None = None
    rig: Any = None

    def to_dict(self, extended: bool = False) -> dict[str, Any]:
        """The ``physics --json`` document of INTERFACE.md.

        Parameters
        ----------
        extended : bool, default False
            Add ``details`` (wear volumes, the Eq. 14 and quasi-static readings, dynamics per
            cycle).

        Returns
        -------
        dict
            Plain JSON-safe data, SI units (the keys name them: ``_n``, ``_w``, ``_k`` ...).
        """
        out = {
            "normal_load_n": self.normal_load_n, "f_mu_max_n": self.f_mu_max_n,
            "heat_w": self.heat_w, "heat_source_w_m3": self.heat_source_w_m3,
            "reynolds": self.reynolds, "prandtl": self.prandtl,
            "h_side_w_m2k": self.h_side_w_m2k, "h_front_w_m2k": self.h_front_w_m2k,
            "hinge": [h.to_dict() for h in self.hinge],
            "thermal": {k: self.thermal.get(k) for k in _THERMAL_KEYS},
            "wear": {"rfcms_over_rms": self.rfcms_over_rms},
            "leaf_yield": None if self.leaf_yield is None else self.leaf_yield.to_dict(),
            "leaf_fatigue": None if self.leaf_yield is None else self.leaf_yield.fatigue_dict(),
            "rig": None if self.rig is None else self.rig.to_dict(),
        }
        if extended:
            out["details"] = dict(self.details)
        return out

    def to_frame(self):
        """Tidy table: quantity, value, unit, paper.

        Returns
        -------
        pandas.DataFrame
            The table described above.
        """
        import pandas as pd

        return pd.DataFrame(self._rows(), columns=["quantity", "value", "unit", "paper"])

    def _rows(self):
        P = PAPER_VALUES
        rows = [
            ("normal_load_n", self.normal_load_n, "N", P["normal_load_n"]),
            ("f_mu_max_n", self.f_mu_max_n, "N", P["f_mu_max_n"]),
            ("heat_w", self.heat_w, "cal/s (paper's W)" if self.params.heat_in_calories else "W", P["heat_w"]),
            ("heat_source_w_m3", self.heat_source_w_m3, "W/m^3", P["heat_source_w_m3"]),
            ("reynolds", self.reynolds, "-", P["reynolds"]),
            ("prandtl", self.prandtl, "-", P["prandtl"]),
            ("h_side_w_m2k", self.h_side_w_m2k, "W/(m^2 K)", P["h_side_w_m2k"]),
            ("h_front_w_m2k", self.h_front_w_m2k, "W/(m^2 K)", P["h_front_w_m2k"]),
        ]
        for h in self.hinge:
            mm = f"{h.thickness_m * 1e3:g} mm"
            rows.append((f"hinge {mm}: stiffness_n_m", h.stiffness_n_m, "N/m", None))
            rows.append((f"hinge {mm}: deflection_m", h.deflection_m, "m", None))
            rows.append((f"hinge {mm}: peak_deflection_m", h.peak_deflection_m, "m", None))
            rows.append((f"hinge {mm}: peak_bending_stress_pa", h.peak_bending_stress_pa, "Pa", None))
            rows.append((f"hinge {mm}: peak_stress_pa" + (" (YIELDS)" if h.yields else ""), h.peak_stress_pa,
                         "Pa", None))
        units = {"steady_rise_k_fv": "K", "steady_rise_k_network": "K", "time_to_95_percent_h": "h",
                 "tcr_c_per_min": "degC/min"}
        for k in _THERMAL_KEYS:
            rows.append((f"thermal: {k}", self.thermal.get(k), units[k], P.get(k)))
        rows.append(("wear: rfcms_over_rms", self.rfcms_over_rms, "-", P["rfcms_over_rms"]))
        d = self.details
        for k, unit in (("rfcms_over_rms_eq14", "-"), ("rfcms_over_rms_quasi_static", "-"),
                        ("sliding_rfcms_m_per_cycle", "m"), ("sliding_rms_m_per_cycle", "m"),
                        ("wear_rfcms_m3_per_h", "m^3/h"), ("wear_rms_m3_per_h", "m^3/h"),
                        ("peak_hinge_deflection_m", "m"), ("hinge_natural_frequency_hz", "Hz"),
                        ("deflection_for_paper_ratio_m", "m"), ("thickness_for_paper_ratio_m", "m")):
            if k in d:
                rows.append((f"wear: {k}", d[k], unit, 0.0308 if k == "deflection_for_paper_ratio_m" else None))
        return rows

    def to_text(self) -> str:
        """A readable table (quantity, value, unit, the paper's value).

        Returns
        -------
        str
            Text for people, several lines.
        """
        rows = self._rows()
        w = max(len(r[0]) for r in rows)
        lines = [f"{'quantity':<{w}}  {'value':>12}  {'unit':<18}  paper",
                 f"{'-' * w}  {'-' * 12}  {'-' * 18}  -----"]
        for name, value, unit, paper in rows:
            val = "n/a" if value is None else f"{value:12.5g}"
            pap = "" if paper is None else f"{paper:g}"
            lines.append(f"{name:<{w}}  {val:>12}  {unit:<18}  {pap}")
        if self.details.get("thermal_skipped"):
            lines.append("(thermal: n/a = not computed, thermal=False / --no-thermal)")
        elif any(self.thermal.get(k) is None for k in _THERMAL_KEYS):
            lines.append("(thermal: n/a = rsm_lrg.physics.thermal.thermal_summary is not available)")
        ylds = [f"{h.thickness_m * 1e3:g} mm" for h in self.hinge if h.yields]
        if ylds:
            lines.append(f"WARNING: the leaf of {', '.join(ylds)} would yield at this motion (peak stress above "
                         f"hinge_yield_pa = {self.params.hinge_yield_pa:.4g} Pa); its dynamics are not elastic")
        if self.leaf_yield is not None:
            lines.append(self.leaf_yield.to_text())
            lines.append(self.leaf_yield.fatigue_text())
        if self.rig is not None:
            lines.append(self.rig.to_text())
        lines.append("heat_w follows Eq. 8 as written (divided by J = 4.184)" if self.params.heat_in_calories
                     else "heat_w is the friction power in W (heat_in_calories = false)")
        return "\n".join(lines)


def _thermal(p: LRGParams, heat_w: float, h_side: float, h_front: float) -> dict[str, float | None]:
    """The four thermal numbers from :func:`rsm_lrg.physics.thermal.thermal_summary`, passing
    every parameter that is also a field of its geometry."""
    from .thermal import GuideGeometry, thermal_summary

    extra = GuideGeometry.fields_from_params(p.to_dict())
    # 6 h in 1-min steps (Fig. 5); a longer test stretches the horizon with the same
    # number of implicit steps (360)
    horizon_h = max(6.0, p.test_duration_min / 60.0)
    res = thermal_summary(heat_w, h_side, h_front, ambient_c=p.ambient_c, horizon_h=horizon_h,
                          dt_s=60.0 * horizon_h / 6.0, duration_min=p.test_duration_min, **extra)
    return {k: (None if getattr(res, k, None) is None else float(getattr(res, k))) for k in _THERMAL_KEYS}


def _peak_deflections(p: LRGParams, thicknesses):
    """Peak leaf deflection [m] over the periodic cycle at the parameters' motion, one per
    thickness (integrated; the quasi-static limit where the integration would need too many
    steps)."""
    try:
        cm = dynamics.cycle_metrics(p.stroke_m, p.velocity_m_s, p.acceleration_m_s2, params=p, method="integrate",
                                    hinge_thickness_m=thicknesses)
    except ValueError as exc:
        if "steps per cycle" not in str(exc):
            raise
        cm = dynamics.cycle_metrics(p.stroke_m, p.velocity_m_s, p.acceleration_m_s2, params=p, method="auto",
                                    hinge_thickness_m=thicknesses)
    return np.atleast_1d(np.asarray(cm.peak_deflection_m, dtype=float))


def _check_geometry(p: LRGParams) -> None:
    """The checks :func:`rsm_lrg.simulate` makes of every run, for one parameter set: the
    carriage stays on the rail, a leaf is thinner than it is long."""
    from .params import LEAF_TOO_THICK, OFF_THE_RAIL, leaf_too_thick, off_the_rail

    if off_the_rail(p.stroke_m, p.rail_length_m, p.block_length_m):
        raise ValueError(f"stroke_m = {p.stroke_m:g} m: {OFF_THE_RAIL} = {p.rail_length_m - p.block_length_m:g} m")
    if leaf_too_thick(p.hinge_thickness_m, p.hinge_length_m):
        raise ValueError(f"hinge_thickness_m = {p.hinge_thickness_m:g} m, hinge_length_m = {p.hinge_length_m:g} m: "
                         f"{LEAF_TOO_THICK}")


def physics_chain(params: LRGParams | None = None, *, thermal: bool = True,
                  thicknesses=TABLE3_THICKNESSES_M, yield_scan: bool = True, rig: bool = True,
                  **overrides) -> PhysicsResult:
    """Run the chain for ``params`` (default: the shipped defaults) with ``overrides``.

    Parameters
    ----------
    params : LRGParams
    thermal : bool
        Run the thermal model (``False``: the four thermal numbers are ``None``).
    thicknesses : sequence of float
        Hinge thicknesses for the ``hinge`` rows [m] (Table 3).
    yield_scan : bool
        Scan the Table 3 box for leaves past yield and for fatigue (:func:`leaf_yield_scan`, 625
        settings); ``False``: ``leaf_yield`` is ``None``.
    rig : bool
        Both stages on one rail at the 81 settings of Table 3 (:func:`.rig.rig_report`: carriage
        and working-stage rises, contact conductance, heat balance; needs ``thermal``); ``False``
        or ``thermal=False``: ``rig`` is ``None``.
    **overrides
        Any parameter by name (``mu_k=0.01``).

    Returns
    -------
    PhysicsResult
        Every quantity of the chain in SI units; ``to_dict()`` is the ``physics --json``
        document.

    Notes
    -----
    ``rfcms_over_rms`` is the ratio of carriage sliding per cycle (= of Archard wear per hour,
    Eq. 13) of the RFCMS over the RMS at the same motion (``stroke_m``, ``velocity_m_s``,
    ``acceleration_m_s2``, ``dwell_s``) and hinge thickness ``hinge_thickness_m``, from the
    stick-slip dynamics in their periodic steady state (:func:`.dynamics.cycle_metrics`).
    ``details`` also gives the paper's reading, Eq. 14 for one stroke (``(s − Δδ)/s``), the
    quasi-static reciprocating value, and the inverse question: the Δδ that the paper's
    58.93 % implies by Eq. 14 and the leaf thickness that would give it with the assumed
    hinge width and length.
    """
    p = (params or LRGParams()).with_overrides(**overrides) if overrides else (params or LRGParams())
    _check_geometry(p)
    load = float(hinge.normal_load(p.preload_n, p.stage_mass_kg, p.gravity_m_s2))
    fmax = float(p.mu_s * load)
    q = float(heat.friction_heat(p.mu_k, load, p.velocity_m_s, p.thermal_equivalent_j_per_cal,
                                 in_calories=p.heat_in_calories))
    vt = float(heat.ball_volume(p.ball_radius_m, p.n_balls))
    phi = float(heat.heat_source_intensity(q, vt))
    re = float(convection.reynolds(p.air_velocity_m_s, p.char_length_m, p.air_kinematic_viscosity_m2_s))
    pr = float(convection.prandtl(p.air_specific_heat_j_kgk, p.air_dynamic_viscosity_pa_s, p.air_conductivity_w_mk))
    hs, hf = convection.coefficients(p.to_dict())
    rows = []
    ys = np.asarray(list(thicknesses), dtype=float)
    peaks = _peak_deflections(p, ys) if ys.size else ys
    for y, pk in zip(ys, peaks):
        k = float(hinge.hinge_stiffness(p.hinge_modulus_pa, p.hinge_width_m, y, p.hinge_length_m))
        sb = float(hinge.hinge_bending_stress(p.hinge_modulus_pa, y, p.hinge_length_m, pk))
        st = float(hinge.hinge_peak_stress(p.hinge_modulus_pa, y, p.hinge_length_m, pk, membrane=p.hinge_membrane))
        rows.append(HingeRow(float(y), k, float(hinge.hinge_deflection(fmax, p.hinge_count, k)), float(pk), sb, st,
                             float(p.hinge_yield_pa)))

    # wear: dynamics at the parameters' motion and thickness
    try:
        cm = dynamics.cycle_metrics(p.stroke_m, p.velocity_m_s, p.acceleration_m_s2, stage=["rfcms", "rms"],
                                    params=p, method="integrate")
    except ValueError as exc:  # too many steps per cycle: a stiff hinge, use the quasi-static limit
        if "steps per cycle" not in str(exc):
            raise
        cm = dynamics.cycle_metrics(p.stroke_m, p.velocity_m_s, p.acceleration_m_s2, stage=["rfcms", "rms"],
                                    params=p, method="auto")
    l_rf, l_rms = (float(x) for x in cm.sliding_distance_m)
    ratio = l_rf / l_rms
    k_here = p.hinge_stiffness_n_m
    dd = float(hinge.hinge_deflection(fmax, p.hinge_count, k_here))
    dd_k = float(hinge.hinge_deflection(p.mu_k * load, p.hinge_count, k_here))
    f_i = float(wear.ball_normal_force(load, p.n_balls, p.contact_angle_deg))
    hb = float(wear.brinell_to_pa(p.hardness_hb))
    t_cyc = float(motion.cycle_time(p.stroke_m, p.velocity_m_s, p.acceleration_m_s2, p.dwell_s, p.jerk_time_s))
    dd_paper = float(wear.deflection_for_wear_ratio(PAPER_WEAR_RATIO, p.stroke_m))
    details = {
        "rfcms_over_rms_eq14": float(wear.rfcms_sliding_distance(p.stroke_m, dd) / p.stroke_m),
        "rfcms_over_rms_quasi_static": float(wear.reciprocating_sliding_distance(p.stroke_m, dd, dd_k) / p.stroke_m),
        "sliding_rfcms_m_per_cycle": l_rf,
        "sliding_rms_m_per_cycle": l_rms,
        "friction_work_rfcms_j_per_cycle": float(cm.friction_work_j[0]),
        "friction_work_rms_j_per_cycle": float(cm.friction_work_j[1]),
        "mean_friction_power_rfcms_w": float(cm.mean_friction_power_w[0]),
        "mean_friction_power_rms_w": float(cm.mean_friction_power_w[1]),
        "peak_hinge_deflection_m": float(cm.peak_deflection_m[0]),
        "hinge_natural_frequency_hz": float(dynamics.natural_frequency(p.hinge_count * k_here, p.frame_mass_kg)) / (2 * np.pi),
        "cycle_time_s": t_cyc,
        "ball_normal_force_n": f_i,
        "wear_rfcms_m3_per_h": float(wear.wear_rate_per_hour(p.wear_coefficient, f_i, l_rf, t_cyc, hb)),
        "wear_rms_m3_per_h": float(wear.wear_rate_per_hour(p.wear_coefficient, f_i, l_rms, t_cyc, hb)),
        "deflection_for_paper_ratio_m": dd_paper,
        # no static friction (mu_s = 0): no leaf deflects at breakaway, none gives the ratio (None, not 0)
        "thickness_for_paper_ratio_m": float(hinge.hinge_thickness_for_deflection(
            dd_paper, fmax, p.hinge_count, p.hinge_modulus_pa, p.hinge_width_m, p.hinge_length_m))
        if fmax > 0 else None,
        "heat_friction_power_w": float(heat.friction_heat(p.mu_k, load, p.velocity_m_s, in_calories=False)),
        "ball_volume_m3": vt,
    }
    th: dict[str, float | None] = _thermal(p, q, hs, hf) if thermal else {k: None for k in _THERMAL_KEYS}
    if not thermal:
        details["thermal_skipped"] = True
    scan = leaf_yield_scan(p) if yield_scan else None
    rig_rep = None
    if rig and thermal:
        from .rig import rig_report

        rig_rep = rig_report(p)
    return PhysicsResult(load, fmax, q, phi, re, pr, hs, hf, tuple(rows), th, ratio, p, details, scan, rig_rep)
