"""Flexure hinge stiffness and deflection, maximum static friction (Eqs. 1-2).

Su, Zhang & Yang (2023), *Machines* 11(3), 358, Section 2.1. All functions take SI floats or
NumPy arrays (broadcast together) and return the same.

Eq. 1, ``K_n = E·w·y³/l³``, is the stiffness of a leaf spring guided at both ends (a
fixed-guided beam, ``12·E·I/l³`` with ``I = w·y³/12``), the leaf of a parallelogram flexure;
a cantilever leaf would be four times softer (``3·E·I/l³``).
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = [
    "normal_load", "max_static_friction", "hinge_stiffness", "hinge_deflection",
    "hinge_thickness_for_deflection", "hinge_bending_stress", "STANDARD_GRAVITY",
    "MEMBRANE_COEFFICIENT", "hinge_membrane_stiffness", "hinge_force", "hinge_deflection_nonlinear",
    "hinge_membrane_stress", "hinge_peak_stress", "leaf_tension_parameter", "leaf_stiffening",
    "leaf_force", "leaf_deflection", "leaf_clamp_stress", "leaf_axial_force", "LEAF_TABLE_MAX_RATIO",
    "leaf_force_table", "leaf_clamp_stress_parts", "leaf_fatigue",
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
    # cubes by multiplication: NumPy's vectorised pow may round an element differently by its
    # position in the array, which would make a row's result depend on its batch
    y = np.asarray(thickness, dtype=float)
    ell = np.asarray(length, dtype=float)
    return np.asarray(modulus, dtype=float) * np.asarray(width, dtype=float) * (y * y * y) / (ell * ell * ell)


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


# ------------------------------------------------------------------------------------------
# large deflection of a leaf whose ends are held: membrane (stretching) stiffening
# ------------------------------------------------------------------------------------------
#: Coefficient of the membrane force of a fixed-guided leaf with axially held ends,
#: ``F_m = (π⁴/128)·E·w·y·δ³/l³`` (Rayleigh-Ritz with the leaf's own deflected shape, see
#: :func:`hinge_membrane_stiffness`).
MEMBRANE_COEFFICIENT = np.pi ** 4 / 128.0


def hinge_membrane_stiffness(modulus, width, thickness, length):
    """Cubic (membrane) stiffness of one leaf whose ends are held ``k₃ = (π⁴/128)·E·w·y/l³`` [N/m³].

    A leaf clamped in the frame at one end and in the stage at the other, with the distance
    between the clamps fixed (both ends bolted, the parallelogram's other leaves hold the
    stage's height), cannot shorten when it bends: it stretches. With the fixed-guided
    shape ``u(x) = (δ/2)·(1 − cos(πx/l))`` (zero slope at both clamps) the stretch is
    ``Δl = ½∫u'² dx = π²δ²/(16 l)``, the axial force ``N = E·w·y·Δl/l`` and the stretching
    energy ``U = ½·E·w·y·Δl²/l``; its derivative gives the lateral force
    ``F_m = dU/dδ = (π⁴/128)·E·w·y·δ³/l³`` on top of the bending force K_n·δ of Eq. 1:

        F(δ) = K_n·δ + k₃·δ³   (per leaf; the stage has n leaves).

    The same Ritz shape gives 12.2·E·I/l³ for the bending part against the exact 12·E·I/l³ of
    Eq. 1 (1.5 %), so the cubic coefficient carries about that error. The stretching ratio
    k₃δ²/K_n = 0.76·(δ/y)² says when it matters: once the deflection exceeds the thickness —
    always for the 0.1-0.5 mm leaves of Table 3 at millimetre deflections.

    Parameters
    ----------
    modulus, width, thickness, length : float or array
        E [Pa], w [m], y [m], l [m] as in :func:`hinge_stiffness`.

    Examples
    --------
    >>> k3 = hinge_membrane_stiffness(211e9, 0.010, 0.0001, 0.020)
    >>> f"{float(k3):.4g}"                        # N/m^3
    '2.007e+10'
    >>> round(float(k3 * 1e-3 ** 2 / hinge_stiffness(211e9, 0.010, 0.0001, 0.020)), 1)  # at 1 mm
    76.1

    References
    ----------
    Timoshenko, S.P. & Woinowsky-Krieger, S., *Theory of Plates and Shells*, 2nd ed. (1959),
    Section 3 (bending of a strip with immovable edges: membrane tension from the stretch
    ½∫u'²); Younis, M.I., *MEMS Linear and Nonlinear Statics and Dynamics* (Springer 2011),
    Section 4.3 (mid-plane stretching of beams with immovable ends, the cubic hardening force);
    Awtar, S., Slocum, A.H. & Sevincer, E. (2007), J. Mech. Des. 129, 625-639 (load-stiffening
    of parallelogram flexures by axial force).
    """
    return (MEMBRANE_COEFFICIENT * np.asarray(modulus, dtype=float) * np.asarray(width, dtype=float)
            * np.asarray(thickness, dtype=float) / (np.asarray(length, dtype=float) * np.asarray(length, dtype=float)
                                                    * np.asarray(length, dtype=float)))


def hinge_force(deflection, stiffness, membrane_stiffness=0.0):
    """Restoring force ``F = K·δ + k₃·δ³`` [N] (per leaf, or for n leaves with n·K, n·k₃).

    >>> round(float(hinge_force(1e-3, 263.75, 2.007e10)), 3)
    20.334
    """
    d = np.asarray(deflection, dtype=float)
    return np.asarray(stiffness, dtype=float) * d + np.asarray(membrane_stiffness, dtype=float) * d ** 3


def hinge_deflection_nonlinear(force, stiffness, membrane_stiffness=0.0):
    """Deflection δ [m] where ``K·δ + k₃·δ³ = F`` (the unique real root, sign of F).

    Cardano's formula for the depressed cubic ``δ³ + p·δ − q = 0`` with ``p = K/k₃ > 0``,
    ``q = F/k₃``: ``δ = u − p/(3u)``, ``u = ∛(q/2 + √D)``, ``D = q²/4 + p³/27``; where the
    membrane term is negligible at this force (k₃δ² < 10⁻⁶·K, where Cardano cancels) the
    series ``(F/K)·(1 − k₃F²/K³)``, and ``F/K`` where k₃ = 0 (Eq. 2).

    Examples
    --------
    >>> round(float(hinge_deflection_nonlinear(5.209, 4 * 263.75)) * 1e3, 4)    # linear, mm
    4.9374
    >>> d = hinge_deflection_nonlinear(5.209, 4 * 263.75, 4 * 2.007e10)
    >>> round(float(d) * 1e3, 4), round(float(hinge_force(d, 4 * 263.75, 4 * 2.007e10)), 6)
    (0.3909, 5.209)
    """
    f = np.asarray(force, dtype=float)
    k = np.asarray(stiffness, dtype=float)
    k3 = np.asarray(membrane_stiffness, dtype=float)
    f, k, k3 = np.broadcast_arrays(f, k, k3)
    lin = f / k
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        p = k / k3
        q = np.abs(f) / k3
        sd = np.sqrt(q * q / 4.0 + p ** 3 / 27.0)
        # δ = ∛(q/2 + √D) − ∛(√D − q/2); the second term by its conjugate: (p/3)/∛(q/2 + √D)
        u = np.cbrt(q / 2.0 + sd)
        root = np.sign(f) * (u - p / (3.0 * u))
    # where the membrane term is negligible at this force, Cardano cancels: use the series
    small = ~(k3 > 0) | (k3 * lin ** 2 < 1e-6 * k)
    series = lin * (1.0 - k3 * lin ** 2 / k)
    out = np.where(k3 > 0, np.where(small, series, root), lin)
    return out if out.ndim else out[()]


def hinge_membrane_stress(modulus, length, deflection):
    """Axial (membrane) stress of a leaf with held ends ``σ_m = E·π²·δ²/(16·l²)`` [Pa].

    The stretch ``Δl/l = π²δ²/(16 l²)`` of :func:`hinge_membrane_stiffness` times E; uniform
    over the section, it adds to the bending stress on the tensile face.

    >>> round(float(hinge_membrane_stress(211e9, 0.020, 1e-3)) / 1e6, 1)    # MPa
    325.4
    """
    d = np.asarray(deflection, dtype=float)
    return np.asarray(modulus, dtype=float) * np.pi ** 2 * d ** 2 / (16.0 * np.asarray(length, dtype=float) ** 2)


def hinge_peak_stress(modulus, thickness, length, deflection, membrane=True):
    """Largest normal stress in a leaf [Pa], at its clamps.

    With held ends (``membrane=True``) the exact beam-column stress of
    :func:`leaf_clamp_stress`; without, the small-deflection bending stress ``3·E·y·δ/l²``
    (:func:`hinge_bending_stress`). (Before model v5 this added the Ritz membrane stress to the
    small-deflection bending stress: at δ = 10·y that is half the exact clamp stress, because the
    tension concentrates the curvature at the clamps.)

    >>> round(float(hinge_peak_stress(211e9, 0.0001, 0.020, 1e-3)) / 1e6)   # MPa
    990
    """
    if membrane:
        return leaf_clamp_stress(modulus, thickness, length, deflection)
    return hinge_bending_stress(modulus, thickness, length, deflection)


# ------------------------------------------------------------------------------------------
# exact large deflection of a fixed-guided leaf with held ends: the beam-column solution
# ------------------------------------------------------------------------------------------
# A leaf of length l, clamped at x = 0 and at x = l (slope 0 at both ends), one end displaced
# laterally by δ, the distance between the clamps held (the axial tension N comes from the
# stretch). With k² = N·l²/(E·I) and u = k/2, E·I·w⁗ − N·w″ = 0 gives, about the midpoint
# ξ = x/l − 1/2,
#     w = δ/2 + B·ξ + C·sinh(k·ξ),   B = −C·k·cosh u,   C = δ / (2·(sinh u − u·cosh u)),
# the lateral force (shear plus the tension's lateral component, constant along the leaf)
#     F = (E·I·δ/l³)·4u³/(u − tanh u) = K_n·δ·φ(u),   φ(u) = u³ / (3·(u − tanh u))   (φ(0) = 1),
# the clamp moment M = (2·E·I·δ/l²)·u²·tanh u/(u − tanh u), and the stretch ½∫w′² dx, which
# with N = E·w·y·stretch/l closes the problem:
#     (δ/y)² = G(u) = 2·(u − tanh u)² / (3·(1 + ½·sech²u − 3·tanh u/(2u))).
# Everything depends on δ/y alone: the force law of every leaf is K_n·δ·φ(u(δ/y)).
# For small u the cancelling differences are replaced by their Taylor series (to u¹², error
# below 1e-13 for u < 0.2)
# (the series and the element-wise kernels are in :mod:`.leafcore`).


def _leaf_parts(u: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """S(u) = 3·(u − tanh u)/u³ = 1/φ(u), D(u)/u⁴ with D = 1 + ½·sech²u − 3·tanh u/(2u), and
    tanh(u)/u, for u ≥ 0 (arrays; element by element in compiled code, :mod:`.leafcore`, so a
    value does not depend on its position in an array)."""
    from .leafcore import leaf_parts

    return leaf_parts(u)


def _ratio_of_u(u: Any) -> tuple[np.ndarray, np.ndarray]:
    """δ/y = sqrt(G(u)) and the stiffening φ(u) of the beam-column leaf."""
    S, Dq, _ = _leaf_parts(u)
    u = np.asarray(u, dtype=float)
    return u * S * np.sqrt(2.0 / (27.0 * Dq)), 1.0 / S


def leaf_tension_parameter(ratio: Any) -> Any:
    """Tension parameter u = (l/2)·sqrt(N/(E·I)) [-] of a fixed-guided leaf with held ends
    displaced by δ = ``ratio``·y (ratio = δ/y, dimensionless): the root of ``G(u) = (δ/y)²``
    (G increases from 0; ``u ≈ 1.342·δ/y`` for small δ/y, ``u ≈ 1 + 1.225·δ/y`` for large).

    >>> round(float(leaf_tension_parameter(10.0)), 3)
    12.488
    """
    from .leafcore import tension_parameter

    out = tension_parameter(ratio)
    return out if out.ndim else out[()]


def leaf_stiffening(ratio: Any) -> Any:
    """Secant stiffening φ = F/(K_n·δ) [-] of a fixed-guided leaf with held ends at
    δ/y = ``ratio`` (1 at small deflection; ``1 + 0.72·(δ/y)²`` for small δ/y, where the Ritz
    cosine shape of :func:`hinge_membrane_stiffness` gives ``1 + 0.761·(δ/y)²``).

    >>> round(float(leaf_stiffening(10.0)), 2)
    56.51
    """
    out = _ratio_of_u(leaf_tension_parameter(ratio))[1]
    return out if out.ndim else out[()]


def leaf_force(deflection: Any, stiffness: Any, thickness: Any) -> Any:
    """Lateral force of fixed-guided leaves with held ends ``F = K·δ·φ(δ/y)`` [N] (exact
    beam-column solution, :func:`leaf_stiffening`); ``stiffness`` K [N/m] is K_n of Eq. 1 (one
    leaf) or n·K_n, δ [m], y the leaf thickness [m].

    >>> round(float(leaf_force(1e-3, 263.75, 1e-4)), 3)      # one 0.1 mm leaf at 1 mm
    14.905
    """
    d = np.asarray(deflection, dtype=float)
    y = np.asarray(thickness, dtype=float)
    out = np.asarray(stiffness, dtype=float) * d * leaf_stiffening(d / y)
    return out if np.ndim(out) else out[()]


def leaf_deflection(force: Any, stiffness: Any, thickness: Any) -> Any:
    """Deflection δ [m] of leaves with held ends under the lateral force ``force`` [N] (the
    inverse of :func:`leaf_force`; sign of the force). Where ``thickness`` is 0 or not finite:
    the small-deflection hinge, ``F/K`` (Eq. 2).

    >>> round(float(leaf_deflection(14.905, 263.75, 1e-4)) * 1e3, 4)
    1.0
    """
    f, k, y = np.broadcast_arrays(np.asarray(force, dtype=float), np.asarray(stiffness, dtype=float),
                                  np.asarray(thickness, dtype=float))
    ok = np.isfinite(y) & (y > 0)
    ys = np.where(ok, y, 1.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        q = np.where(ok, np.abs(f) / (k * ys), 0.0)  # (δ/y)·φ, increasing in u

    from .leafcore import parameter_for_load

    u = parameter_for_load(q)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.where(ok, np.sign(f) * ys * _ratio_of_u(u)[0], f / k)
    return out if out.ndim else out[()]


def leaf_axial_force(modulus: Any, width: Any, thickness: Any, length: Any, deflection: Any) -> Any:
    """Axial tension N [N] of a fixed-guided leaf with held ends at deflection δ [m]:
    ``N = 4·E·I·u²/l²`` (I = w·y³/12, u of :func:`leaf_tension_parameter`)."""
    y = np.asarray(thickness, dtype=float)
    u = leaf_tension_parameter(np.asarray(deflection, dtype=float) / y)
    ell = np.asarray(length, dtype=float)
    return 4.0 * np.asarray(modulus, dtype=float) * np.asarray(width, dtype=float) * (y * y * y) / 12.0 * u * u / ell ** 2


def leaf_clamp_stress(modulus: Any, thickness: Any, length: Any, deflection: Any) -> Any:
    """Largest normal stress of a fixed-guided leaf with held ends [Pa]: at the clamps, the
    bending stress of the beam-column moment plus the uniform tension,

        σ = (E·y·δ/l²)·3·(tanh u/u)/S(u) + E·y²·u²/(3·l²),   S(u) = 3·(u − tanh u)/u³,

    (E [Pa], y, l, δ [m]; u of :func:`leaf_tension_parameter` at δ/y). For small δ/y the
    bending stress of Eq. 1's leaf, ``3·E·y·δ/l²``. Checked against a finite-difference solution
    of ``E·I·w⁗ − N·w″ = 0`` with N from the stretch (``tests/physics/test_leaf_beam_column.py``).

    >>> round(float(leaf_clamp_stress(211e9, 0.0001, 0.020, 1e-3)) / 1e6)   # MPa, δ = 10·y
    990
    >>> round(float(leaf_clamp_stress(211e9, 3e-4, 0.02, 1e-7) / hinge_bending_stress(211e9, 3e-4, 0.02, 1e-7)), 6)
    1.0
    """
    E = np.asarray(modulus, dtype=float)
    y = np.asarray(thickness, dtype=float)
    ell = np.asarray(length, dtype=float)
    d = np.abs(np.asarray(deflection, dtype=float))
    u = leaf_tension_parameter(d / y)
    S, _, tu = _leaf_parts(u)
    out = E * y * d / ell ** 2 * 3.0 * tu / S + E * y * y * u * u / (3.0 * ell ** 2)
    return out if np.ndim(out) else out[()]


def leaf_clamp_stress_parts(modulus: Any, thickness: Any, length: Any, deflection: Any) -> tuple[Any, Any]:
    """The two parts of :func:`leaf_clamp_stress` [Pa]: the bending stress of the beam-column
    clamp moment, ``(E·y·δ/l²)·3·(tanh u/u)/S(u)`` (its sign follows the deflection's on a given
    face), and the uniform tension ``E·y²·u²/(3·l²)`` (the same for ±δ). Their sum is the clamp
    stress.

    >>> b, t = leaf_clamp_stress_parts(211e9, 0.0001, 0.020, 1e-3)
    >>> round(float((b + t) / leaf_clamp_stress(211e9, 0.0001, 0.020, 1e-3)), 12)
    1.0
    """
    E = np.asarray(modulus, dtype=float)
    y = np.asarray(thickness, dtype=float)
    ell = np.asarray(length, dtype=float)
    d = np.abs(np.asarray(deflection, dtype=float))
    u = leaf_tension_parameter(d / y)
    S, _, tu = _leaf_parts(u)
    bend = E * y * d / ell ** 2 * 3.0 * tu / S
    tension = E * y * y * u * u / (3.0 * ell ** 2)
    return (bend if np.ndim(bend) else bend[()]), (tension if np.ndim(tension) else tension[()])


def leaf_fatigue(modulus: Any, thickness: Any, length: Any, peak_deflection: Any, fatigue_limit: Any,
                 tensile_strength: Any) -> tuple[Any, Any, Any]:
    """Stress amplitude σ_a, mean σ_m [Pa] and modified-Goodman utilisation ``σ_a/S_e + σ_m/R_m``
    [1] at the clamps of a fixed-guided leaf with held ends whose deflection swings between
    ``-peak_deflection`` and ``+peak_deflection`` [m] (the periodic reciprocating state is
    antisymmetric, δ(t + T/2) = −δ(t)): on each face the bending part changes sign with δ and the
    tension does not, so ``σ_a`` is the bending part and ``σ_m`` the tension at the peak
    (:func:`leaf_clamp_stress_parts`). A utilisation of 1 or more: the leaf fails in fatigue
    (finite life; Shigley's Mechanical Engineering Design, 10th ed., Eq. 6-41).

    ``fatigue_limit`` S_e and ``tensile_strength`` R_m [Pa] (``hinge_fatigue_limit_pa``,
    ``hinge_tensile_strength_pa``).

    >>> sa, sm, u = leaf_fatigue(211e9, 1e-4, 0.02, 1e-3, 490e6, 980e6)
    >>> round(float(sa) / 1e6), round(float(sm) / 1e6), round(float(u), 3)
    (716, 274, 1.741)
    """
    bend, tension = leaf_clamp_stress_parts(modulus, thickness, length, peak_deflection)
    util = bend / np.asarray(fatigue_limit, dtype=float) + tension / np.asarray(tensile_strength, dtype=float)
    return bend, tension, util


#: Largest δ/y of the tabulated force law (:func:`leaf_force_table`), far beyond any leaf that
#: does not yield.
LEAF_TABLE_MAX_RATIO = 200.0


def leaf_force_table(step: float = 0.01) -> tuple[np.ndarray, float]:
    """The force law ψ(r) = r·φ(r) of a leaf with held ends (F = K·y·ψ(δ/y)) tabulated for the
    stage integrator: coefficients of a C² cubic spline (not-a-knot ends, :mod:`.spline`; SciPy's
    ``CubicSpline`` bit for bit), shape (n, 4), on r_i = i·``step`` up to
    :data:`LEAF_TABLE_MAX_RATIO`: on [r_i, r_i + step] ``ψ = c0 + c1·t + c2·t² + c3·t³``,
    t = r − r_i. ψ is odd in r (the spline is built on the mirrored points, so its end condition
    at 0 is the symmetric one); its error against :func:`leaf_stiffening` is below 1e-9 relative
    (``tests/physics/test_leaf_beam_column.py``)."""
    from .spline import not_a_knot_coefficients

    r = np.arange(0.0, LEAF_TABLE_MAX_RATIO + 0.5 * step, step)
    psi = r * np.atleast_1d(leaf_stiffening(r))
    x = np.concatenate([-r[:0:-1], r])
    yv = np.concatenate([-psi[:0:-1], psi])
    c = not_a_knot_coefficients(x, yv)[:, len(r) - 1:]
    return np.ascontiguousarray(c[::-1].T), float(step)
