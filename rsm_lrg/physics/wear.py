"""Archard wear of the guide for the RFCMS and the rigid stage (Eqs. 13-17).

Su, Zhang & Yang (2023), *Machines* 11(3), 358, Sections 2.3 and 3.2. SI floats or NumPy
arrays in and out.

Sliding distance of the carriage per stroke, derived for this module (see
:mod:`rsm_lrg.physics.dynamics` for the dynamics that confirm it in the quasi-static limit):

- Eq. 14 ``L = x_ws − Δδ`` is one stroke that starts from a relaxed hinge: the stage moves
  Δδ before the hinge force reaches f_µmax and the frame breaks away.
- In steady reciprocation the frame stops at the end of each stroke with the hinge still
  bent (Δδ_k = µ_k·F_z/(n·K_n), the force of kinetic friction, which static friction then
  holds). The reversed stroke must first unbend it and bend it the other way to the breakaway
  deflection Δδ = µ_s·F_z/(n·K_n), so ``L = x_ws − Δδ_k − Δδ``; with µ_k = µ_s that is
  ``x_ws − 2·Δδ``.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "BRINELL_TO_PA", "brinell_to_pa", "ball_normal_force", "archard_wear_volume",
    "rfcms_sliding_distance", "reciprocating_sliding_distance", "rfcms_wear_volume",
    "wear_rate_per_hour", "wear_ratio", "deflection_for_wear_ratio",
]

#: 1 HB = 1 kgf/mm² = 9.80665e6 Pa.
BRINELL_TO_PA = 9.80665e6


def brinell_to_pa(hb):
    """Brinell hardness number to pascal (1 HB = 1 kgf/mm² = 9.80665e6 Pa).

    Examples
    --------
    The paper's 523 HBS:

    >>> f"{float(brinell_to_pa(523)):.4e}"
    '5.1289e+09'
    """
    return np.asarray(hb, dtype=float) * BRINELL_TO_PA


def ball_normal_force(load, n_balls, contact_angle_deg=45.0):
    """Normal contact force of one ball ``F_i = F / (Z·sin α)`` [N] (input of Eq. 13).

    The load F on the carriage shared equally by the Z loaded balls, each contact inclined
    at the contact angle α to the raceway's side (α = 45°, four-way equal load: every row
    carries; Table 1). For α = 45° sin and cos coincide, so the convention of α does not
    change the number.

    Examples
    --------
    F_z = 173.65 N over 4 × 18 balls at 45°:

    >>> round(float(ball_normal_force(173.65, 72, 45.0)), 3)
    3.411

    References
    ----------
    Su, Zhang & Yang (2023), Eq. 13 and ref. [30]; Harris & Kotzalas, Rolling Bearing Analysis,
    5th ed., Ch. 7 (load distribution, Q = F/(Z·sin α) for equal sharing).
    """
    alpha = np.deg2rad(np.asarray(contact_angle_deg, dtype=float))
    return np.asarray(load, dtype=float) / (np.asarray(n_balls, dtype=float) * np.sin(alpha))


def archard_wear_volume(k_a, force, distance, hardness_pa):
    """Archard adhesive wear volume ``V = K_a·F_i·L / H`` [m³] (Eq. 13).

    Parameters
    ----------
    k_a : float or array
        Adhesive wear coefficient [-] (4e-5, Rabinowicz 1980).
    force : float or array
        Normal contact force F_i [N].
    distance : float or array
        Sliding distance L [m].
    hardness_pa : float or array
        Hardness H of the softer body [Pa] (:func:`brinell_to_pa`).

    Examples
    --------
    One ball (3.411 N) over 1 m of sliding on 523 HB steel:

    >>> f"{float(archard_wear_volume(4e-5, 3.411, 1.0, brinell_to_pa(523))):.4e}"
    '2.6603e-14'

    References
    ----------
    Archard, J. Appl. Phys. 24 (1953) 981; Su, Zhang & Yang (2023), Eq. 13.
    """
    return (np.asarray(k_a, dtype=float) * np.asarray(force, dtype=float)
            * np.asarray(distance, dtype=float) / np.asarray(hardness_pa, dtype=float))


def rfcms_sliding_distance(stroke, deflection):
    """Carriage sliding distance of the RFCMS ``L = x_ws − Δδ`` [m] (Eq. 14), floored at 0.

    One stroke from a relaxed hinge. For steady reciprocation use
    :func:`reciprocating_sliding_distance`.

    Examples
    --------
    >>> round(float(rfcms_sliding_distance(0.075, 0.0308)), 4)
    0.0442
    """
    return np.maximum(np.asarray(stroke, dtype=float) - np.asarray(deflection, dtype=float), 0.0)


def reciprocating_sliding_distance(stroke, breakaway_deflection, rest_deflection=None):
    """Carriage sliding distance per stroke in steady quasi-static reciprocation [m].

    ``L = x_ws − Δδ_rest − Δδ`` floored at 0, where Δδ = µ_s·F_z/(n·K_n) is the breakaway
    deflection (Eq. 2) and Δδ_rest = µ_k·F_z/(n·K_n) the deflection the frame keeps after
    sliding stops (default: Δδ, i.e. ``x_ws − 2·Δδ``). Derivation in the module docstring;
    checked against the stick-slip dynamics in ``tests/physics/test_dynamics.py``.

    Examples
    --------
    >>> round(float(reciprocating_sliding_distance(0.075, 0.01)), 4)
    0.055
    """
    d = np.asarray(breakaway_deflection, dtype=float)
    r = d if rest_deflection is None else np.asarray(rest_deflection, dtype=float)
    return np.maximum(np.asarray(stroke, dtype=float) - d - r, 0.0)


def rfcms_wear_volume(k_a, force, stroke, n_hinges, stiffness, f_mu_max, hardness_pa):
    """Wear volume of the guide under an RFCMS, one stroke from rest [m³] (Eq. 17).

    ``V = K_a·F_i·(n·K_n·x_ws − f_µmax) / (n·K_n·H)`` — Eq. 13 with Eq. 14 and Eq. 2
    (floored at zero when the stroke stays inside the hinge's deflection).

    Examples
    --------
    Equals Eq. 13 with L = x_ws − Δδ:

    >>> v17 = rfcms_wear_volume(4e-5, 3.411, 0.075, 4, 7121.25, 5.209, 5.1289e9)
    >>> v13 = archard_wear_volume(4e-5, 3.411, 0.075 - 5.209 / (4 * 7121.25), 5.1289e9)
    >>> bool(abs(v17 - v13) < 1e-25)
    True
    """
    nk = np.asarray(n_hinges, dtype=float) * np.asarray(stiffness, dtype=float)
    l_slide = np.maximum(nk * np.asarray(stroke, dtype=float) - np.asarray(f_mu_max, dtype=float), 0.0) / nk
    return archard_wear_volume(k_a, force, l_slide, hardness_pa)


def wear_rate_per_hour(k_a, force, sliding_per_cycle, cycle_time, hardness_pa):
    """Archard wear volume per hour of running [m³/h] (Eq. 13 with L = sliding per hour).

    Examples
    --------
    >>> f"{float(wear_rate_per_hour(4e-5, 3.411, 0.15, 0.4, brinell_to_pa(523))):.4e}"
    '3.5914e-11'
    """
    per_hour = np.asarray(sliding_per_cycle, dtype=float) * 3600.0 / np.asarray(cycle_time, dtype=float)
    return archard_wear_volume(k_a, force, per_hour, hardness_pa)


def wear_ratio(sliding_rfcms, sliding_rms):
    """RFCMS wear over RMS wear at the same motion, load and time [-] (Section 3.2).

    With Eq. 13 and equal K_a, F_i, H and time, the ratio of wear volumes is the ratio of
    sliding distances.

    Examples
    --------
    >>> round(float(wear_ratio(0.075 - 0.0308, 0.075)), 4)
    0.5893
    """
    return np.asarray(sliding_rfcms, dtype=float) / np.asarray(sliding_rms, dtype=float)


def deflection_for_wear_ratio(ratio, stroke, *, reciprocating=False):
    """Inverse question: the hinge deflection Δδ [m] that gives an RFCMS/RMS wear ratio.

    By Eq. 14 (one stroke from rest, the paper's reading) ``Δδ = (1 − r)·x_ws``; in steady
    quasi-static reciprocation with µ_k = µ_s (``L = x_ws − 2·Δδ``) ``Δδ = (1 − r)·x_ws/2``.

    Examples
    --------
    The paper's 58.93 % at a 0.075 m stroke (Section 3.2):

    >>> round(float(deflection_for_wear_ratio(0.5893, 0.075)) * 1e3, 2)   # mm
    30.8
    >>> round(float(deflection_for_wear_ratio(0.5893, 0.075, reciprocating=True)) * 1e3, 2)
    15.4
    """
    r = np.asarray(ratio, dtype=float)
    if np.any((r < 0) | (r > 1)):
        raise ValueError("the wear ratio must lie in [0, 1]")
    d = (1.0 - r) * np.asarray(stroke, dtype=float)
    return d / 2.0 if reciprocating else d
