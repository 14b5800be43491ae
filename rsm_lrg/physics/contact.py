"""Contact mechanics of a ball in a groove, and the thermal conductance of its contacts.

* **Hertz** (Harris & Kotzalas, *Rolling Bearing Analysis*, 5th ed. 2006, Ch. 6; Johnson,
  *Contact Mechanics*, 1985, Section 4.2): a ball of radius R_b pressed with Q [N] into a
  straight groove of radius R_g (Table 1: 1.3497 and 1.4307 mm) touches on an ellipse whose
  semi-axes a (across the groove) and b (along the rail) follow from the curvature sum
  ``Σρ = 2/R_b − 1/R_g``, the curvature difference ``F(ρ) = (1/R_b − (1/R_b − 1/R_g))/Σρ`` and
  the ellipticity κ = a/b that solves ``F(ρ) = ((κ² + 1)·E(e) − 2·K(e)) / ((κ² − 1)·E(e))``,
  ``e² = 1 − 1/κ²`` (K, E complete elliptic integrals):
  ``a = (3·κ²·E(e)·Q·η / (π·Σρ))^(1/3)``, ``b = a/κ``, ``η = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂``.
* **Constriction** (Yovanovich & Marotta 2003, "Thermal spreading and contact resistance", in
  Bejan & Kraus, *Heat Transfer Handbook*, Ch. 4; Holm, *Electric Contacts*, 1967): an
  isothermal elliptical spot of semi-axes a ≥ b on a half-space of conductivity λ has
  ``R = K(e)/(2·π·λ·a)`` [K/W] (a circle: ``1/(4·λ·a)``). Heat crossing a contact meets
  **both** sides: the ball's constriction and the raceway's, in series.

Every ball has two contacts, one with the carriage's groove and one with the rail's. The friction
heat is released at the contact interfaces; the interface (no heat capacity) is eliminated
exactly (a star of two conductances): the heat released at a carriage-side contact goes
``G_r/(G_b + G_r)`` straight into the carriage and ``G_b/(G_b + G_r)`` into the ball, and the
ball is tied to the carriage by ``G_b·G_r/(G_b + G_r)`` (the same on the rail side).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

__all__ = ["HertzContact", "hertz_ball_groove", "hertz_ball_groove_approx", "elliptic_constriction_resistance",
           "BallContactConductance", "ball_contact_conductance"]


@dataclass(frozen=True)
class HertzContact:
    """The Hertzian contact ellipse of one ball in a groove.

    Attributes
    ----------
    a_m, b_m : float
        Semi-axes [m], a across the groove (the larger), b along the rail.
    kappa : float
        Ellipticity a/b [1].
    pressure_pa : float
        Largest contact pressure ``3Q/(2πab)`` [Pa].
    """

    a_m: float
    b_m: float
    kappa: float
    pressure_pa: float


def _curvatures(ball_radius_m: float, groove_radius_m: float) -> tuple[float, float]:
    if not (0 < ball_radius_m < groove_radius_m):
        raise ValueError("the groove radius must exceed the ball radius (a conforming groove), got "
                         f"{ball_radius_m!r} and {groove_radius_m!r} m")
    rho_x = 1.0 / ball_radius_m  # along the rail: the ball on a straight raceway
    rho_y = 1.0 / ball_radius_m - 1.0 / groove_radius_m  # across: the ball in the concave groove
    return rho_x, rho_y


def _compliance(e1: float, nu1: float, e2: float, nu2: float) -> float:
    return (1.0 - nu1 ** 2) / e1 + (1.0 - nu2 ** 2) / e2


def hertz_ball_groove(load_n: float, ball_radius_m: float, groove_radius_m: float, *, ball_modulus_pa: float,
                      ball_poisson: float, race_modulus_pa: float, race_poisson: float) -> HertzContact:
    """Hertzian contact of a ball in a straight groove, exact (elliptic integrals).

    Parameters
    ----------
    load_n : float
        Normal force of the ball on the groove Q [N] (Eq. 13's F_i).
    ball_radius_m, groove_radius_m : float
        Ball and groove radii [m] (Table 1).
    ball_modulus_pa, ball_poisson, race_modulus_pa, race_poisson : float
        Young's moduli [Pa] and Poisson ratios [1] (Table 2).

    Returns
    -------
    HertzContact

    Examples
    --------
    The guide's ball (Table 1) under 3.41 N (173.65 N over 72 balls at 45°, Eq. 13):

    >>> c = hertz_ball_groove(3.411, 1.3497e-3, 1.4307e-3, ball_modulus_pa=211e9, ball_poisson=0.277,
    ...                       race_modulus_pa=219e9, race_poisson=0.3)
    >>> round(c.a_m * 1e6, 1), round(c.b_m * 1e6, 1), round(c.kappa, 2)
    (114.7, 17.9, 6.42)

    References
    ----------
    Harris & Kotzalas (2006), *Rolling Bearing Analysis*, 5th ed., Ch. 6 (Eqs. for Σρ, F(ρ),
    a*, b*); Johnson (1985), *Contact Mechanics*, Section 4.2.
    """
    from scipy.optimize import brentq
    from scipy.special import ellipe, ellipk

    if not (load_n > 0 and math.isfinite(load_n)):
        raise ValueError(f"load_n must be a positive force [N], got {load_n!r}")
    rho_x, rho_y = _curvatures(ball_radius_m, groove_radius_m)
    s = rho_x + rho_y
    f_rho = (rho_x - rho_y) / s

    def g(kappa: float) -> float:
        m = 1.0 - 1.0 / kappa ** 2
        k, e = float(ellipk(m)), float(ellipe(m))
        return ((kappa ** 2 + 1.0) * e - 2.0 * k) / ((kappa ** 2 - 1.0) * e) - f_rho

    kappa = float(brentq(g, 1.0 + 1e-9, 1e4, xtol=1e-14, rtol=1e-14))
    m = 1.0 - 1.0 / kappa ** 2
    eta = _compliance(ball_modulus_pa, ball_poisson, race_modulus_pa, race_poisson)
    a = (3.0 * kappa ** 2 * float(ellipe(m)) * load_n * eta / (math.pi * s)) ** (1.0 / 3.0)
    b = a / kappa
    return HertzContact(a, b, kappa, 3.0 * load_n / (2.0 * math.pi * a * b))


def hertz_ball_groove_approx(load_n: float, ball_radius_m: float, groove_radius_m: float, *, ball_modulus_pa: float,
                             ball_poisson: float, race_modulus_pa: float, race_poisson: float) -> HertzContact:
    """The same contact by Hamrock & Brewe's curve fits (an independent route, within about 3 %):
    ``κ ≈ 1.0339·(R_y/R_x)^0.636``, ``E ≈ 1.0003 + 0.5968·R_x/R_y``,
    ``a = (6·κ²·E·Q·R/(π·E'))^(1/3)``, ``b = (6·E·Q·R/(π·κ·E'))^(1/3)``, ``1/R = 1/R_x + 1/R_y``,
    ``E' = 2/η``.

    References
    ----------
    Hamrock & Brewe (1983), "Simplified solution for stresses and deformations", *J. Lubrication
    Technology* 105(2), 171-177; Hamrock, Schmid & Jacobson, *Fundamentals of Machine Elements*,
    Eqs. 8.58-8.61.
    """
    rho_x, rho_y = _curvatures(ball_radius_m, groove_radius_m)
    r_x, r_y = 1.0 / rho_x, 1.0 / rho_y
    kappa = 1.0339 * (r_y / r_x) ** 0.636
    e_int = 1.0003 + 0.5968 * r_x / r_y
    r = 1.0 / (rho_x + rho_y)
    e_red = 2.0 / _compliance(ball_modulus_pa, ball_poisson, race_modulus_pa, race_poisson)
    a = (6.0 * kappa ** 2 * e_int * load_n * r / (math.pi * e_red)) ** (1.0 / 3.0)
    b = (6.0 * e_int * load_n * r / (math.pi * kappa * e_red)) ** (1.0 / 3.0)
    return HertzContact(a, b, a / b, 3.0 * load_n / (2.0 * math.pi * a * b))


def elliptic_constriction_resistance(a_m: float, b_m: float, conductivity_w_mk: float) -> float:
    """Constriction resistance [K/W] of an isothermal elliptical contact spot (semi-axes
    ``a_m`` ≥ ``b_m`` [m]) on a half-space of conductivity ``conductivity_w_mk`` [W/(m·K)]:
    ``R = K(e)/(2·π·λ·a)``, ``e² = 1 − b²/a²``; a circle gives Holm's ``1/(4·λ·a)``.

    >>> round(elliptic_constriction_resistance(1e-4, 1e-4, 44.0) * 4 * 44.0 * 1e-4, 12)
    1.0

    References
    ----------
    Yovanovich & Marotta (2003), in Bejan & Kraus, *Heat Transfer Handbook*, Ch. 4
    (isothermal elliptical contact area on a half-space); Holm (1967), *Electric Contacts*.
    """
    from scipy.special import ellipk

    if not (a_m > 0 and b_m > 0 and conductivity_w_mk > 0):
        raise ValueError("the contact's semi-axes and the conductivity must be positive")
    a, b = max(a_m, b_m), min(a_m, b_m)
    return float(ellipk(1.0 - (b / a) ** 2)) / (2.0 * math.pi * conductivity_w_mk * a)


@dataclass(frozen=True)
class BallContactConductance:
    """The ball contacts of one side (carriage or rail) of the whole guide, from contact mechanics.

    Attributes
    ----------
    contact : HertzContact
        One ball's contact ellipse.
    n_contacts : int
        Loaded balls, one contact each on this side.
    ball_side_w_k, race_side_w_k : float
        Constriction conductances [W/K] of all contacts, ball side and raceway side.
    series_w_k : float
        Both sides in series, ball centre to raceway body [W/K]: the estimate a fitted
        ``ball_contact_conductance_w_k`` is held within 3× of.
    to_race_share : float
        Share of the heat released at a contact interface that goes straight into the raceway's
        body, ``G_r/(G_b + G_r)`` [1] (the rest enters the ball).
    """

    contact: HertzContact
    n_contacts: int
    ball_side_w_k: float
    race_side_w_k: float
    series_w_k: float
    to_race_share: float


def ball_contact_conductance(values: Any, load_n: float | None = None) -> BallContactConductance:
    """Hertz/Yovanovich conductance of the ball contacts of one side from the parameters
    ``values`` (a :meth:`rsm_lrg.physics.params.LRGParams.to_dict`): the load
    ``F0 + m_t·g`` (or ``load_n`` [N]) shared by the ``ball_rows × balls_per_row`` balls at
    the contact angle (Eq. 13's F_i), balls of 40Cr and raceways of GCr15 (Table 2: E, ν, λ).

    >>> from rsm_lrg.physics.params import LRGParams
    >>> c = ball_contact_conductance(LRGParams().to_dict())
    >>> round(c.series_w_k, 3), round(c.to_race_share, 3), c.n_contacts
    (0.35, 0.5, 72)
    """
    from .wear import ball_normal_force

    v = values
    if load_n is None:
        load_n = float(v["preload_n"]) + float(v["stage_mass_kg"]) * float(v["gravity_m_s2"])
    z = int(v["ball_rows"]) * int(v["balls_per_row"])
    q = float(ball_normal_force(load_n, z, float(v["contact_angle_deg"])))
    c = hertz_ball_groove(q, float(v["ball_radius_m"]), float(v["raceway_radius_m"]),
                          ball_modulus_pa=float(v["ball_modulus_pa"]), ball_poisson=float(v["ball_poisson"]),
                          race_modulus_pa=float(v["guide_modulus_pa"]), race_poisson=float(v["guide_poisson"]))
    g_b = z / elliptic_constriction_resistance(c.a_m, c.b_m, float(v["ball_conductivity_w_mk"]))
    g_r = z / elliptic_constriction_resistance(c.a_m, c.b_m, float(v["guide_conductivity_w_mk"]))
    return BallContactConductance(c, z, g_b, g_r, g_b * g_r / (g_b + g_r), g_r / (g_b + g_r))
