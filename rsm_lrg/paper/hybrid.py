"""Physics as the prior of the response surface (issue 34, item 4): the surrogate's κ at each run
as an offset, or as a covariate with a fitted slope, beside a low-order polynomial for the
discrepancy — Kennedy–O'Hagan in its simplest honest form — compared with the polynomials by
leave-one-out on Table 4.

The physics prior is the surrogate of calibration model v6's structure (both carriages on the
rail, one heat balance in watts, the other stage running, Section 4.1) at *a priori* parameter
values: the ball contacts' conductance from contact mechanics (Hertz/Yovanovich,
:data:`rsm_lrg.surrogate.calibrate.HERTZ_CONTACT_W_K`) and no viscous friction (the
parameters' defaults). Nothing of the prior is fitted to Table 4, so the leave-one-out of a
hybrid refits only its regression coefficients: the PRESS identity (each run's residual over
``1 - h_ii``) is that leave-one-out exactly, with no calibration to redo inside the folds. A
prior calibrated on Table 4 would leak the left-out run into every fold; that is why the shipped
calibration is not used here.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..surrogate.calibrate import HERTZ_CONTACT_W_K

__all__ = ["HybridComparison", "physics_prior", "hybrid_comparison", "PRIOR_CALIBRATION"]

#: The prior's settings: calibration model v6's structure, contact-mechanics conductance [W/K],
#: no viscous friction [N s/m] (no value taken from Table 4).
PRIOR_CALIBRATION = {"heat_balance": True, "two_carriage": True, "other_stage_running": True,
                     "ball_contact_conductance_w_k": HERTZ_CONTACT_W_K, "viscous_friction_n_s_m": 0.0}

_FACTORS = ("thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2")


@dataclass(frozen=True)
class HybridComparison:
    """Leave-one-out R² (1 − PRESS/SS_tot of κ) of the physics, the polynomials and the hybrids.

    Attributes
    ----------
    rows : tuple of (str, float, int)
        ``(model, LOO R², fitted coefficients)`` in the order of :func:`hybrid_comparison`.
    physics : numpy.ndarray
        The prior's κ at each run [°C/min].
    """

    rows: tuple
    physics: np.ndarray

    def r2(self, name: str) -> float:
        """The LOO R² of the model ``name``.

        Parameters
        ----------
        name : str
            A model of :attr:`rows`.

        Returns
        -------
        float
            1 − PRESS/SS_tot.
        """
        for n, r2, _ in self.rows:
            if n == name:
                return float(r2)
        raise KeyError(name)

    def to_dict(self) -> dict:
        """The comparison as JSON-ready data.

        Returns
        -------
        dict
            ``{"prior": ..., "models": [{"model", "loo_r2", "coefficients"}, ...]}``.
        """
        return {"prior": dict(PRIOR_CALIBRATION),
                "models": [{"model": n, "loo_r2": float(r), "coefficients": int(k)} for n, r, k in self.rows]}


def physics_prior(runs) -> np.ndarray:
    """The prior's κ [°C/min] at each run of ``runs`` (the RFCMS, 50 min, no noise).

    Parameters
    ----------
    runs : pandas.DataFrame
        Columns ``thickness_m`` [m], ``stroke_m`` [m], ``velocity_m_s`` [m/s] and
        ``acceleration_m_s2`` [m/s²].

    Returns
    -------
    numpy.ndarray
        κ of the surrogate with :data:`PRIOR_CALIBRATION` [°C/min].
    """
    from ..surrogate.execute import simulate

    rows = runs[list(_FACTORS)].copy()
    rows["stage"] = "rfcms"
    return np.asarray(simulate(rows, seed=0, noise_sd=0.0, calibration=PRIOR_CALIBRATION).tcr_c_per_min, float)


def hybrid_comparison(table4=None, physics: np.ndarray | None = None) -> HybridComparison:
    """LOO R² on Table 4 of: the physics alone (κ = a + b·prior), the paper's quadratic, linear
    + C² (the best small polynomial), the prior as an offset with a linear discrepancy, and the
    prior as a covariate beside linear and beside linear + C².

    Parameters
    ----------
    table4 : pandas.DataFrame, optional
        The runs (Table 4 by default) with ``tcr_c_per_min`` [°C/min].
    physics : numpy.ndarray, optional
        The prior at those runs (:func:`physics_prior` by default).

    Returns
    -------
    HybridComparison
        Each model fitted by :func:`rsm_lrg.fit` (the prior a numeric factor ``physics`` with a
        linear term only), its LOO R² from the fit's PRESS over κ's total sum of squares (for
        the offset model, the PRESS of y − prior over the same SS_tot of κ).
    """
    from ..datasets import load_table4
    from ..model import fit

    t4 = load_table4() if table4 is None else table4
    ph = physics_prior(t4) if physics is None else np.asarray(physics, float)
    y = t4["tcr_c_per_min"].to_numpy(float)
    ss = float(np.sum((y - y.mean()) ** 2))
    data = t4[list(_FACTORS)].assign(tcr_c_per_min=y, physics=ph, discrepancy=y - ph)
    lin, c2 = ["A", "B", "C", "D"], ["A", "B", "C", "D", "C^2"]
    specs = [
        ("physics alone (a + b·prior)", "tcr_c_per_min", ["physics"], ["A"]),
        ("quadratic (Eq. 19)", "tcr_c_per_min", list(_FACTORS),
         lin + ["AB", "AC", "AD", "BC", "BD", "CD", "A^2", "B^2", "C^2", "D^2"]),
        ("linear + C²", "tcr_c_per_min", list(_FACTORS), c2),
        ("prior offset + linear discrepancy", "discrepancy", list(_FACTORS), lin),
        ("linear + prior covariate", "tcr_c_per_min", [*_FACTORS, "physics"], lin + ["E"]),
        ("linear + C² + prior covariate", "tcr_c_per_min", [*_FACTORS, "physics"], c2 + ["E"]),
    ]
    rows = []
    for name, response, factors, terms in specs:
        r = fit(data[[*factors, response]], response, factors=factors, terms=terms)
        rows.append((name, 1.0 - float(r.statistics.press) / ss, len(r.terms)))
    return HybridComparison(rows=tuple(rows), physics=ph)
