"""Convection from the moving carriage to the air (Eqs. 10-12).

Su, Zhang & Yang (2023), *Machines* 11(3), 358, Section 2.2.3. SI floats or NumPy arrays in
and out.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "reynolds", "prandtl", "nusselt_parallel_plate", "nusselt_normal_plate",
    "heat_transfer_coefficient", "h_side", "h_front", "coefficients",
    "nusselt_cross_flow", "relative_air_speed", "moving_coefficients", "MovingConvection",
    "PARALLEL_PLATE_RE_MAX", "NORMAL_PLATE_RE_RANGE",
]

#: Laminar flat plate (Eq. 11): the boundary layer stays laminar below Re_x = 5e5
#: (Incropera et al., 6th ed., Section 7.2, Eq. 7.23; Pr >= 0.6).
PARALLEL_PLATE_RE_MAX = 5e5

#: Range of Reynolds numbers on which Eq. 12's constants were fitted: Hilpert's vertical plate in
#: cross flow, C = 0.228, m = 0.731 for 4e3 <= Re <= 1.5e4 (Incropera et al., 6th ed., Table 7.3).
#: The paper uses it at Re = 290, outside that range.
NORMAL_PLATE_RE_RANGE = (4e3, 1.5e4)


def reynolds(velocity, length, kinematic_viscosity):
    """Reynolds number ``Re = ω·L_c/φ`` [-] (Section 2.2.3).

    Examples
    --------
    >>> round(float(reynolds(0.3, 0.015, 15.5e-6)), 1)
    290.3
    """
    return np.asarray(velocity, dtype=float) * np.asarray(length, dtype=float) / np.asarray(kinematic_viscosity, dtype=float)


def prandtl(specific_heat, dynamic_viscosity, conductivity):
    """Prandtl number ``Pr = c·η/λ`` [-] (Section 2.2.3).

    Examples
    --------
    Air at 300 K (c 1005 J/(kg·K), η 18.4e-6 Pa·s, λ 0.0263 W/(m·K)):

    >>> round(float(prandtl(1005.0, 18.4e-6, 0.0263)), 3)
    0.703
    """
    return np.asarray(specific_heat, dtype=float) * np.asarray(dynamic_viscosity, dtype=float) / np.asarray(conductivity, dtype=float)


def nusselt_parallel_plate(re, pr):
    """Mean Nusselt number of a laminar flat plate in parallel flow (Blasius/Pohlhausen),
    ``Nu = 0.332·Re^(1/2)·Pr^(1/3)`` (Eq. 11): top and side faces of the carriage.

    Valid for laminar flow (Re < 5e5) and Pr ≳ 0.6. (The textbook *mean* Nusselt number over a
    plate has 0.664; 0.332 is the local value. The paper uses 0.332; kept as written.)

    Examples
    --------
    >>> round(float(nusselt_parallel_plate(290.32, 0.7031)), 3)
    5.03

    References
    ----------
    Su, Zhang & Yang (2023), Eq. 11; Incropera et al., Fundamentals of Heat and Mass
    Transfer, 6th ed., Eq. 7.23.
    """
    return 0.332 * np.sqrt(np.asarray(re, dtype=float)) * np.cbrt(np.asarray(pr, dtype=float))


def nusselt_normal_plate(re, pr):
    """Nusselt number of a plate normal to the flow ``Nu = 0.228·Re^0.731·Pr^(1/3)`` (Eq. 12):
    front faces of the carriage (perpendicular to the motion).

    Examples
    --------
    >>> round(float(nusselt_normal_plate(290.32, 0.7031)), 2)
    12.8

    References
    ----------
    Su, Zhang & Yang (2023), Eq. 12 (their refs. [11, 26]).
    """
    return 0.228 * np.asarray(re, dtype=float) ** 0.731 * np.cbrt(np.asarray(pr, dtype=float))


def heat_transfer_coefficient(nu, conductivity, length):
    """Convection coefficient ``h = Nu·λ/L_c`` [W/(m²·K)] (Eq. 10)."""
    return np.asarray(nu, dtype=float) * np.asarray(conductivity, dtype=float) / np.asarray(length, dtype=float)


def h_side(air_velocity=0.3, length=0.015, kinematic_viscosity=15.5e-6, dynamic_viscosity=18.4e-6,
           conductivity=0.0263, specific_heat=1005.0):
    """h of the top and side faces [W/(m²·K)] (Eqs. 10-11); defaults: the paper.

    Examples
    --------
    The paper's 8.82 W/(m²·K):

    >>> round(float(h_side()), 2)
    8.82
    """
    re = reynolds(air_velocity, length, kinematic_viscosity)
    pr = prandtl(specific_heat, dynamic_viscosity, conductivity)
    return heat_transfer_coefficient(nusselt_parallel_plate(re, pr), conductivity, length)


def h_front(air_velocity=0.3, length=0.015, kinematic_viscosity=15.5e-6, dynamic_viscosity=18.4e-6,
            conductivity=0.0263, specific_heat=1005.0):
    """h of the front faces [W/(m²·K)] (Eqs. 10, 12); defaults: the paper.

    Examples
    --------
    The paper's 22.45 W/(m²·K):

    >>> round(float(h_front()), 2)
    22.45
    """
    re = reynolds(air_velocity, length, kinematic_viscosity)
    pr = prandtl(specific_heat, dynamic_viscosity, conductivity)
    return heat_transfer_coefficient(nusselt_normal_plate(re, pr), conductivity, length)


#: The air parameters (:class:`rsm_lrg.physics.params.LRGParams` names) of Eqs. 10-12, in the
#: order :func:`h_side` and :func:`h_front` take them.
AIR_PARAMETERS = ("air_velocity_m_s", "char_length_m", "air_kinematic_viscosity_m2_s", "air_dynamic_viscosity_pa_s",
                  "air_conductivity_w_mk", "air_specific_heat_j_kgk")


def coefficients(values) -> tuple[float, float]:
    """``h_side`` and ``h_front`` [W/(m²·K)] (Eqs. 10-12) from a parameter mapping (the names of
    :class:`rsm_lrg.physics.params.LRGParams`, e.g. its ``to_dict()``).

    Examples
    --------
    >>> from rsm_lrg.physics.params import LRGParams
    >>> [round(h, 2) for h in coefficients(LRGParams().to_dict())]
    [8.82, 22.45]
    """
    args = tuple(values[k] for k in AIR_PARAMETERS)
    return float(h_side(*args)), float(h_front(*args))


def nusselt_cross_flow(re, pr):
    """Mean Nusselt number of a bluff body in cross flow by Churchill & Bernstein (1977),
    ``Nu = 0.3 + 0.62·Re^(1/2)·Pr^(1/3) / (1 + (0.4/Pr)^(2/3))^(1/4) · (1 + (Re/282000)^(5/8))^(4/5)``:
    the front faces of a moving body at the Reynolds numbers of the rig (about 300-800), where
    Eq. 12 is outside the range it was fitted on (:data:`NORMAL_PLATE_RE_RANGE`).

    Valid for Re·Pr >= 0.2 (all Re of laminar and turbulent cross flow). It is the correlation of
    a circular cylinder of diameter L_c; a flat front face is a bluff body of the same size, which
    is the approximation made here.

    Examples
    --------
    >>> round(float(nusselt_cross_flow(290.32, 0.7031)), 2)
    8.63

    References
    ----------
    Churchill & Bernstein (1977), *J. Heat Transfer* 99, 300-306; Incropera et al., 6th ed.,
    Eq. 7.54.
    """
    re = np.asarray(re, dtype=float)
    pr = np.asarray(pr, dtype=float)
    return 0.3 + (0.62 * np.sqrt(re) * np.cbrt(pr) / (1.0 + (0.4 / pr) ** (2.0 / 3.0)) ** 0.25
                  * (1.0 + (re / 282000.0) ** 0.625) ** 0.8)


def relative_air_speed(ambient_air_speed, mean_square_speed):
    """Air speed [m/s] a reciprocating body sees, ``sqrt(ω² + <v²>)``: the room's air speed ω
    (the paper's 0.3 m/s) and the body's root-mean-square speed over its cycle added in
    quadrature (ASSUMPTION: the two are uncorrelated; the rms weights the fast part of the stroke,
    which dominates the heat transfer). A body at rest sees ω.

    >>> round(float(relative_air_speed(0.3, 0.4 ** 2)), 3)
    0.5
    """
    return np.sqrt(np.asarray(ambient_air_speed, dtype=float) ** 2 + np.asarray(mean_square_speed, dtype=float))


class MovingConvection(tuple):
    """``(h_side, h_front, re, pr)`` of a body in air of the given speed (:func:`moving_coefficients`)."""

    __slots__ = ()

    @property
    def h_side(self) -> float:
        return float(self[0])

    @property
    def h_front(self) -> float:
        return float(self[1])

    @property
    def reynolds(self) -> float:
        return float(self[2])


def moving_coefficients(values, air_speed: float) -> MovingConvection:
    """h of the top and side faces (Eq. 11, laminar flat plate, inside its range Re < 5e5) and of
    the front faces (Churchill-Bernstein, :func:`nusselt_cross_flow`, instead of Eq. 12 outside its
    range) [W/(m²·K)] for air of speed ``air_speed`` [m/s] and the air of ``values`` (Eq. 10:
    ``h = Nu·λ/L_c``); returns them with Re and Pr.

    Raises ``ValueError`` where Re is outside Eq. 11's laminar range or Re·Pr < 0.2.

    >>> from rsm_lrg.physics.params import LRGParams
    >>> m = moving_coefficients(LRGParams().to_dict(), 0.3)
    >>> round(m.h_side, 2), round(m.h_front, 2), round(m.reynolds, 1)
    (8.82, 15.14, 290.3)
    """
    _, lc, nu, eta, lam, cp = (float(values[k]) for k in AIR_PARAMETERS)
    u = float(air_speed)
    re = float(reynolds(u, lc, nu))
    pr = float(prandtl(cp, eta, lam))
    if not (re < PARALLEL_PLATE_RE_MAX and re * pr >= 0.2):
        raise ValueError(f"Re = {re:.4g} is outside the convection correlations' range (laminar flat plate "
                         f"Re < {PARALLEL_PLATE_RE_MAX:g}, Churchill-Bernstein Re Pr >= 0.2)")
    hs = float(heat_transfer_coefficient(nusselt_parallel_plate(re, pr), lam, lc))
    hf = float(heat_transfer_coefficient(nusselt_cross_flow(re, pr), lam, lc))
    return MovingConvection((hs, hf, re, pr))
