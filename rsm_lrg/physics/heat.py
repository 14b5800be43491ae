"""Friction heat of the guide and its heat-source intensity (Eqs. 8-9).

Su, Zhang & Yang (2023), *Machines* 11(3), 358, Section 2.2.3.
"""

from __future__ import annotations

import numpy as np

__all__ = ["friction_heat", "ball_volume", "heat_source_intensity", "JOULES_PER_CALORIE", "leaf_conductance",
           "drive_heat_to_carriage", "stage_time_constant"]

#: The paper's thermal equivalent J [J/cal] (thermochemical calorie).
JOULES_PER_CALORIE = 4.184


def friction_heat(mu_k, load, velocity, thermal_equivalent=JOULES_PER_CALORIE, *, in_calories=True):
    """Friction heat of the carriage ``Q = µ_k·F_z·v / J`` (Eq. 8).

    Parameters
    ----------
    mu_k : float or array
        Kinetic friction coefficient [-].
    load : float or array
        Load on the carriage F_z = F0 + m_t·g [N].
    velocity : float or array
        Carriage velocity v [m/s].
    thermal_equivalent : float
        J [J/cal]; the paper uses 4.184.
    in_calories : bool
        ``True`` (default, the paper): divide by J, as Eq. 8 is written. ``False``: the plain
        friction power µ_k·F_z·v [W].

    Returns
    -------
    float or array
        Q [cal/s] when ``in_calories`` (numerically what the paper calls the heat and feeds to
        Eq. 9 and the FEM as W), else [W].

    Notes
    -----
    µ_k·F_z·v is already a power in watts; dividing by J converts it to calories per second, so
    the paper's Q (0.4150) is 4.184 times smaller than the friction power (1.7364 W). The paper
    then uses Q as watts in Φ = Q/V_t, so its heat source, and every temperature rise computed
    from it, is 1/4.184 of what the friction power alone would give. Keep the default to
    reproduce the paper (5.6e5 W/m³, 4.038 K); use ``in_calories=False`` for the physical
    power, and say which one a result uses.

    Examples
    --------
    The paper's Q = 0.4150 (µ_k 0.02, F_z 173.65 N, v 0.5 m/s):

    >>> round(float(friction_heat(0.02, 173.6478, 0.5)), 4)
    0.415
    >>> round(float(friction_heat(0.02, 173.6478, 0.5, in_calories=False)), 4)   # W
    1.7365

    References
    ----------
    Su, Zhang & Yang (2023), Eq. 8.
    """
    q = np.asarray(mu_k, dtype=float) * np.asarray(load, dtype=float) * np.asarray(velocity, dtype=float)
    return q / thermal_equivalent if in_calories else q + 0.0


def ball_volume(radius, n_balls=1):
    """Total volume of ``n_balls`` balls ``V_t = n·(4/3)·π·r³`` [m³] (Eq. 9).

    Examples
    --------
    4 rows × 18 balls of radius 1.3497 mm (Table 1):

    >>> f"{float(ball_volume(1.3497e-3, 72)):.4g}"
    '7.415e-07'
    """
    return np.asarray(n_balls, dtype=float) * (4.0 / 3.0) * np.pi * np.asarray(radius, dtype=float) ** 3


def heat_source_intensity(heat, volume):
    """Internal heat-source intensity ``Φ = Q / V_t`` [W/m³] (Eq. 9).

    Examples
    --------
    The paper's "5.6 × 10⁵ W/m³":

    >>> f"{float(heat_source_intensity(0.41503, 7.4151e-7)):.4g}"
    '5.597e+05'
    """
    return np.asarray(heat, dtype=float) / np.asarray(volume, dtype=float)


def leaf_conductance(n_leaves, conductivity, width, thickness, length):
    """Conduction of n parallel leaves along their length ``G = n·λ·w·y/l`` [W/K] (Fourier, Eq. 3).

    Examples
    --------
    Four 65Mn leaves (λ = 48 W/(m·K), Table 2), 10 mm wide, 20 mm long, 0.3 mm thick:

    >>> round(float(leaf_conductance(4, 48.0, 0.010, 0.0003, 0.020)), 4)
    0.0288
    """
    return (np.asarray(n_leaves, dtype=float) * np.asarray(conductivity, dtype=float) * np.asarray(width, dtype=float)
            * np.asarray(thickness, dtype=float) / np.asarray(length, dtype=float))


def drive_heat_to_carriage(drive_heat, joint_conductance, stage_conductance):
    """Share of the drive's heat in the working stage that reaches the carriage [W].

    The stage (one lumped node, Biot ≪ 1) receives P_d and loses it to the air through G_s
    and into the frame and carriage through the joint G_c (the leaves of the RFCMS; for the
    RMS a rigid bolted joint, ``joint_conductance = inf``): in steady state the carriage gets
    ``P_d·G_c/(G_c + G_s)``, all of it for a rigid joint. The carriage is held near ambient by
    its own convection, so its temperature is neglected against the stage's in this split.

    Examples
    --------
    >>> round(float(drive_heat_to_carriage(0.2, 0.0288, 0.08)), 4), float(drive_heat_to_carriage(0.2, np.inf, 0.08))
    (0.053, 0.2)
    """
    g = np.asarray(joint_conductance, dtype=float)
    gs = np.asarray(stage_conductance, dtype=float)
    with np.errstate(invalid="ignore"):
        share = np.where(np.isinf(g), 1.0, g / (g + gs))
    return np.asarray(drive_heat, dtype=float) * share


def stage_time_constant(heat_capacity, joint_conductance, stage_conductance):
    """Time constant of the working stage's temperature ``tau = C/(G_c + G_s)`` [s].

    The lumped stage of :func:`drive_heat_to_carriage` (heat capacity C = m_ws·c [J/K],
    Table 2: 6061-T6, c = 896 J/(kg·K)) reaches its steady temperature, and passes its
    steady share of the drive heat to the carriage, as ``1 - exp(-t/tau)`` after the drive
    starts. A rigid joint (``joint_conductance = inf``, the RMS) gives 0: the heat arrives
    as a step.

    Examples
    --------
    0.135 kg of aluminium on four 0.3 mm leaves (G_c = 0.0288 W/K) and G_s = 0.08 W/K:
    about 18.5 min.

    >>> round(float(stage_time_constant(0.135 * 896, 0.0288, 0.08)) / 60, 1)
    18.5
    >>> float(stage_time_constant(121.0, np.inf, 0.08))
    0.0
    """
    g = np.asarray(joint_conductance, dtype=float)
    total = g + np.asarray(stage_conductance, dtype=float)
    with np.errstate(divide="ignore"):
        return np.where(np.isinf(total), 0.0, np.asarray(heat_capacity, dtype=float) / np.where(np.isinf(total), 1.0,
                                                                                               total))
