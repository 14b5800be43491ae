"""Flexure hinge stiffness and deflection, maximum static friction (Eqs. 1-2).

Su, Zhang & Yang (2023), *Machines* 11(3), 358, Section 2.1. All functions take SI floats or
NumPy arrays (broadcast together) and return the same.

Eq. 1, ``K_n = E·w·y³/l³``, is the stiffness of a leaf spring guided at both ends (a
fixed-guided beam, ``12·E·I/l³`` with ``I = w·y³/12``), the leaf of a parallelogram flexure;
a cantilever leaf would be four times softer (``3·E·I/l³``).
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "normal_load", "max_static_friction", "hinge_stiffness", "hinge_deflection",
    "hinge_thickness_for_deflection", "hinge_bending_stress", "STANDARD_GRAVITY",
]

#: Standard gravity [m/s²] (CGPM 1901).
STANDARD_GRAVITY = 9.80665


def normal_load(preload, mass, g=STANDARD_GRAVITY):
    """Load on the carriage ``F_z = F0 + m_t·g`` [N] (Section 2.1, Eqs. 2 and 8).

    Parameters
    ----------
    preload : float or array
        Initial preload F0 of the guide [N].
    mass : float or array
        Total mass m_t of the stage [kg].
    g : float
        Gravitational acceleration [m/s²].

    Examples
    --------
    The paper's 173.65 N (F0 = 171 N, m_t = 0.27 kg):

    >>> round(float(normal_load(171.0, 0.27)), 2)
    173.65

    References
    ----------
    Su, Zhang & Yang (2023), Machines 11, 358, Section 2.1.
    """
    return np.asarray(preload, dtype=float) + np.asarray(mass, dtype=float) * g + 0.0


def max_static_friction(mu_s, preload, mass, g=STANDARD_GRAVITY):
    """Maximum static friction of the guide ``f_µmax = µ_s·(F0 + m_t·g)`` [N] (Eq. 2).

    Parameters
    ----------
    mu_s : float or array
        Static friction coefficient [-].
    preload : float or array
        Preload F0 [N].
    mass : float or array
        Total stage mass m_t [kg].
    g : float
        Gravitational acceleration [m/s²].

    Examples
    --------
    The paper's 5.209 N (µ_s = 0.03):

    >>> round(float(max_static_friction(0.03, 171.0, 0.27)), 3)
    5.209
    """
    return np.asarray(mu_s, dtype=float) * normal_load(preload, mass, g)


def hinge_stiffness(modulus, width, thickness, length):
    """Stiffness of one flexure hinge ``K_n = E·w·y³/l³`` [N/m] (Eq. 1).

    Parameters
    ----------
    modulus : float or array
        Young's modulus E of the hinge material [Pa] (65Mn: 211e9, Table 2).
    width : float or array
        Leaf width w [m].
    thickness : float or array
        Leaf thickness y [m] (Table 3: 0.1-0.5 mm).
    length : float or array
        Free leaf length l [m].

    Notes
    -----
    Small-deflection beam theory: valid while the deflection stays well below the leaf
    length (a few tenths of it) and the bending stress below the elastic limit
    (:func:`hinge_bending_stress`).

    Examples
    --------
    A 65Mn leaf 10 mm wide, 20 mm long, 0.3 mm thick; stiffness scales with y³:

    >>> k = hinge_stiffness(211e9, 0.010, 0.0003, 0.020)
    >>> round(float(k), 1)
    7121.2
    >>> round(float(hinge_stiffness(211e9, 0.010, 0.0006, 0.020) / k), 6)
    8.0

    References
    ----------
    Su, Zhang & Yang (2023), Eq. 1 (their ref. [23]); fixed-guided beam, Roark's Formulas
    for Stress and Strain, 8th ed., Table 8.1 case 1e.
    """
    return (np.asarray(modulus, dtype=float) * np.asarray(width, dtype=float)
            * np.asarray(thickness, dtype=float) ** 3 / np.asarray(length, dtype=float) ** 3)


def hinge_deflection(force, n_hinges, stiffness):
    """Hinge deflection ``Δδ = f / (n·K_n)`` [m] (Eq. 2, Hooke's law; with f = f_µmax).

    Examples
    --------
    >>> round(float(hinge_deflection(5.209, 4, 7121.25)) * 1e3, 4)   # mm
    0.1829
    """
    return np.asarray(force, dtype=float) / (np.asarray(n_hinges, dtype=float) * np.asarray(stiffness, dtype=float))


def hinge_thickness_for_deflection(deflection, force, n_hinges, modulus, width, length):
    """Inverse of Eqs. 1-2: leaf thickness y [m] giving deflection Δδ under force f.

    ``y = (f·l³ / (n·Δδ·E·w))^(1/3)``.

    Examples
    --------
    The paper's 58.93 % wear ratio read through Eq. 14 needs Δδ ≈ 30.8 mm; with a 10 mm wide,
    20 mm long 65Mn leaf that is a 0.054 mm thick leaf (and a deflection 1.5 times the leaf
    length, far outside Eq. 1's small-deflection range):

    >>> round(float(hinge_thickness_for_deflection(0.0308, 5.209, 4, 211e9, 0.010, 0.020)) * 1e3, 4)
    0.0543
    """
    num = np.asarray(force, dtype=float) * np.asarray(length, dtype=float) ** 3
    den = (np.asarray(n_hinges, dtype=float) * np.asarray(deflection, dtype=float)
           * np.asarray(modulus, dtype=float) * np.asarray(width, dtype=float))
    return np.cbrt(num / den)


def hinge_bending_stress(modulus, thickness, length, deflection):
    """Peak bending stress of a fixed-guided leaf ``σ = 3·E·y·Δδ/l²`` [Pa].

    From ``M = 6·E·I·Δδ/l²`` at the clamped ends and ``σ = M·(y/2)/I``.

    Examples
    --------
    >>> round(float(hinge_bending_stress(211e9, 0.0001, 0.020, 4.94e-3)) / 1e6)   # MPa
    782
    """
    return (3.0 * np.asarray(modulus, dtype=float) * np.asarray(thickness, dtype=float)
            * np.asarray(deflection, dtype=float) / np.asarray(length, dtype=float) ** 2)
