"""Temperature change rate κ of the guide (Eq. 18).

Su, Zhang & Yang (2023), *Machines* 11(3), 358, Section 4.2.
"""

from __future__ import annotations

import numpy as np

__all__ = ["temperature_change_rate", "tcr_from_record"]


def temperature_change_rate(t0, t1, u0, u1):
    """``κ = (t1 − t0)/(u1 − u0)`` [°C/min] (Eq. 18).

    Parameters
    ----------
    t0, t1 : float or array
        Temperature at the start and at the end of the test [°C] (or a rise [K]).
    u0, u1 : float or array
        Start and end time of the test [min].

    Examples
    --------
    The confirmation run of Section 4.3: 1.2 °C in 50 min:

    >>> round(float(temperature_change_rate(25.0, 26.2, 0.0, 50.0)), 3)
    0.024
    """
    du = np.asarray(u1, dtype=float) - np.asarray(u0, dtype=float)
    if np.any(du <= 0):
        raise ValueError("the end time u1 must be later than the start time u0")
    return (np.asarray(t1, dtype=float) - np.asarray(t0, dtype=float)) / du


def tcr_from_record(times_min, temperatures, *, method="endpoints"):
    """κ [°C/min] from a temperature record (times in minutes, temperatures in °C).

    ``method="endpoints"`` is Eq. 18 on the first and last samples (the paper);
    ``"slope"`` is the least-squares slope over all samples (less sensitive to the ±0.1 °C
    noise of one thermocouple reading). ``temperatures`` may be 2-D (one record per row,
    samples along the last axis).

    Examples
    --------
    >>> tcr_from_record([0, 10, 20], [25.0, 25.3, 25.6])
    0.03
    """
    u = np.asarray(times_min, dtype=float)
    t = np.asarray(temperatures, dtype=float)
    if u.ndim != 1 or u.size < 2 or t.shape[-1] != u.size:
        raise ValueError("need at least two samples, with one time per temperature")
    if np.any(np.diff(u) <= 0):
        raise ValueError("times must increase strictly")
    if method == "endpoints":
        out = temperature_change_rate(t[..., 0], t[..., -1], u[0], u[-1])
    elif method == "slope":
        uc = u - u.mean()
        out = ((t - t.mean(axis=-1, keepdims=True)) * uc).sum(axis=-1) / (uc ** 2).sum()
    else:
        raise ValueError(f"method must be 'endpoints' or 'slope', not {method!r}")
    return float(round(out, 15)) if np.ndim(out) == 0 else out
