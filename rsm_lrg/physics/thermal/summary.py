"""One call for the thermal results of the guide: :func:`thermal_summary`.

Runs the 3-D finite-volume model (steady state and an implicit transient from ambient) and
the reduced network for the same inputs, and reports what the paper reports (Section 3.1,
Fig. 5): the steady rise, the time to reach 95 % of it, the history at the thermocouples,
and the temperature change rate kappa of Eq. 18 over the test duration (Section 4.2).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

from ...errors import ParameterError
from .fv import FVSystem, time_to_fraction
from .geometry import GuideGeometry, voxelise
from .network import ThermalNetwork

__all__ = ["ThermalSummary", "thermal_summary", "PAPER_STEADY_RISE_K"]

#: Paper Section 3.1 (ANSYS): steady 29.038 degC at 25 degC ambient -> maximum rise 4.038 K.
PAPER_STEADY_RISE_K = 4.038


@dataclass(frozen=True)
class ThermalSummary:
    """Thermal results for one heat input (all rises relative to ambient).

    Attributes
    ----------
    heat_w : float                     total heat in the ball rows [W] (Eq. 8-9)
    h_side_w_m2k, h_front_w_m2k, h_rail_w_m2k, h_base_w_m2k : float   boundary coefficients
    ambient_c : float                  ambient temperature [degC]
    steady_rise_k_fv : float           steady rise at the thermocouples (mean of two) [K]
    steady_max_rise_k_fv : float       steady maximum rise anywhere (the ball rows) [K]
    steady_rise_k_network : float      steady thermocouple rise of the reduced network [K]
    time_to_95_percent_h : float       FV: first time the thermocouple rise reaches 95 % [h]
    time_to_95_percent_h_network : float
    tcr_c_per_min : float              Eq. 18 over ``duration_min`` from the FV history [degC/min]
    energy_balance_error : float       (convected - generated) / generated at steady state
    n_cells : int                      solid cells solved (the symmetric quarter by default)
    cell_size_m : float
    times_h, history_k_fv, history_k_network : tuple of float
        Thermocouple rise against time (Fig. 5), one sample per time step.
    """

    heat_w: float
    h_side_w_m2k: float
    h_front_w_m2k: float
    h_rail_w_m2k: float
    h_base_w_m2k: float
    ambient_c: float
    duration_min: float
    steady_rise_k_fv: float
    steady_max_rise_k_fv: float
    steady_rise_k_network: float
    time_to_95_percent_h: float
    time_to_95_percent_h_network: float
    tcr_c_per_min: float
    energy_balance_error: float
    n_cells: int
    cell_size_m: float
    times_h: tuple
    history_k_fv: tuple
    history_k_network: tuple

    @property
    def steady_temperature_c(self) -> float:
        """Steady thermocouple temperature [degC]."""
        return self.ambient_c + self.steady_rise_k_fv

    @property
    def relative_to_paper(self) -> float:
        """Steady maximum rise over the paper's FEM 4.038 K, minus one (scales with Q)."""
        return self.steady_max_rise_k_fv / PAPER_STEADY_RISE_K - 1.0

    def to_dict(self, histories: bool = False) -> dict:
        """Plain JSON-safe numbers; the histories only if ``histories``."""
        d = asdict(self)
        if not histories:
            for k in ("times_h", "history_k_fv", "history_k_network"):
                d.pop(k)
        else:
            for k in ("times_h", "history_k_fv", "history_k_network"):
                d[k] = list(d[k])
        d["steady_temperature_c"] = self.steady_temperature_c
        return d

    def to_frame(self):
        """Tidy history table: time [h], FV and network thermocouple rise [K], temperature [degC]."""
        import pandas as pd

        return pd.DataFrame({
            "time_h": self.times_h,
            "rise_k_fv": self.history_k_fv,
            "rise_k_network": self.history_k_network,
            "temperature_c_fv": np.asarray(self.history_k_fv) + self.ambient_c,
        })


def thermal_summary(
    heat_w: float,
    h_side_w_m2k: float,
    h_front_w_m2k: float,
    *,
    ambient_c: float = 25.0,
    duration_min: float = 50.0,
    horizon_h: float = 6.0,
    dt_s: float = 60.0,
    cell_size_m: float = 2e-3,
    h_rail_w_m2k: float | None = None,
    h_base_w_m2k: float = 0.0,
    scheme: str = "backward-euler",
    **geometry_overrides,
) -> ThermalSummary:
    """Steady and transient temperature rise of the SHS15V guide for a friction heat ``heat_w``.

    Parameters
    ----------
    heat_w : float
        Total heat generated in the ball rows [W] (Eq. 8; the paper's 0.4150 is Eq. 8 as
        written, i.e. divided by J = 4.184, which equals Phi = 5.6e5 W/m^3 times V_t).
    h_side_w_m2k, h_front_w_m2k : float
        Convection coefficients [W/(m^2 K)] of Eq. 11 (top, side, underside faces) and
        Eq. 12 (front/back faces); the paper: 8.82 and 22.45.
    ambient_c : float
        Ambient temperature [degC] (paper: 25).
    duration_min : float
        Test duration for kappa (Eq. 18) [min] (paper: ~50).
    horizon_h : float
        Length of the transient [h] (Fig. 5 spans about 5-6 h).
    dt_s : float
        Implicit time step [s] (60 s = the rig's 1-min sampling).
    cell_size_m : float
        FV cell size in the carriage region [m] (2 mm: ~3.7e3 cells, well under a second;
        1 mm: ~1.8e4 cells, a few seconds).
    h_rail_w_m2k, h_base_w_m2k : float
        Exposed rail faces (default: ``h_side_w_m2k``) and rail bottom (default 0,
        adiabatic); both ASSUMPTIONS, see :data:`rsm_lrg.physics.thermal.geometry.ASSUMPTIONS`.
    scheme : {"backward-euler", "crank-nicolson"}
    **geometry_overrides
        Any :class:`GuideGeometry` field (e.g. ``rail_length_m=0.6``).

    Returns
    -------
    ThermalSummary

    Examples
    --------
    >>> s = thermal_summary(0.4150, 8.82, 22.45, cell_size_m=4e-3)
    >>> round(s.steady_rise_k_fv, 2), round(s.tcr_c_per_min, 3)
    (2.82, 0.049)
    """
    for name, v in (("heat_w", heat_w), ("h_side_w_m2k", h_side_w_m2k), ("h_front_w_m2k", h_front_w_m2k),
                    ("ambient_c", ambient_c)):
        if not isinstance(v, (int, float)) or not math.isfinite(v):
            raise ValueError(f"{name} must be a finite number, got {v!r}.")
    if heat_w < 0:
        raise ValueError(f"heat_w must be >= 0 [W], got {heat_w!r}.")
    if not (math.isfinite(horizon_h) and horizon_h > 0):
        raise ValueError(f"horizon_h must be positive [h], got {horizon_h!r}.")
    if not (math.isfinite(duration_min) and 0 < duration_min <= horizon_h * 60):
        raise ParameterError("duration_min", f"duration_min must be in (0, horizon_h*60] min, got {duration_min!r}.")
    geometry = GuideGeometry().with_(**geometry_overrides)
    h_rail = h_side_w_m2k if h_rail_w_m2k is None else float(h_rail_w_m2k)
    model = voxelise(geometry, h_side_w_m2k, h_front_w_m2k, h_rail_w_m2k=h_rail,
                     h_base_w_m2k=h_base_w_m2k, cell_size_m=cell_size_m)
    fv = FVSystem(model)
    # linear in Q: solve per watt, then scale (also makes heat_w = 0 harmless)
    st = fv.steady(1.0)
    tr = fv.transient(1.0, duration_s=horizon_h * 3600.0, dt_s=dt_s, scheme=scheme)
    hist = tr.mean_probe_rise_k
    net = ThermalNetwork(geometry, h_side_w_m2k, h_front_w_m2k, h_rail_w_m2k=h_rail,
                         h_base_w_m2k=h_base_w_m2k)
    hist_net = net.response(tr.times_s)
    t95 = time_to_fraction(tr.times_s, hist, st.mean_probe_rise_k) / 3600.0
    t95n = time_to_fraction(tr.times_s, hist_net, net.steady_rise_per_w) / 3600.0
    t_end = duration_min * 60.0
    rise_end = float(np.interp(t_end, tr.times_s, hist))
    tcr = heat_w * (rise_end - hist[0]) / duration_min  # Eq. 18
    q = float(heat_w)
    return ThermalSummary(
        heat_w=q,
        h_side_w_m2k=float(h_side_w_m2k),
        h_front_w_m2k=float(h_front_w_m2k),
        h_rail_w_m2k=h_rail,
        h_base_w_m2k=float(h_base_w_m2k),
        ambient_c=float(ambient_c),
        duration_min=float(duration_min),
        steady_rise_k_fv=q * st.mean_probe_rise_k,
        steady_max_rise_k_fv=q * st.max_rise_k,
        steady_rise_k_network=q * net.steady_rise_per_w,
        time_to_95_percent_h=t95,
        time_to_95_percent_h_network=t95n,
        tcr_c_per_min=float(tcr),
        energy_balance_error=st.energy_balance_error,
        n_cells=fv.n,
        cell_size_m=float(cell_size_m),
        times_h=tuple((tr.times_s / 3600.0).tolist()),
        history_k_fv=tuple((q * hist).tolist()),
        history_k_network=tuple((q * hist_net).tolist()),
    )
