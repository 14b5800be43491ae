"""Reduced thermal network of the guide: lumped carriage, distributed ball rows, 1-D rail fin.

Derived (not fitted) from the same :class:`~rsm_lrg.physics.thermal.geometry.GuideGeometry`
and boundary conditions as the 3-D finite-volume model:

* **carriage**: one node (Biot number h L / lambda ~ 0.01, Incropera 6th ed. Section 5.1),
  heat capacity of the steel, convection ``sum h A`` over its top, side and underside faces
  (Eq. 11) and front/back faces (Eq. 12);
* **ball rows**: one node per rail cell under the rows, holding the balls' heat capacity and
  the source Q (Eq. 9); linked to the carriage and to the rail by conduction across the
  clearance, ``lambda_b d / (g/2)`` per row and unit length;
* **rail**: a 1-D finite-volume fin (Incropera Section 3.6.1, Eq. 3.61 with its heat
  capacity) from the carriage centre to the rail end; under the carriage it is covered
  (only the faces below the block's skirts convect) and tied to the carriage through the
  clearance air; beyond the carriage its top and sides convect; convective end face.

The problem is symmetric about x = 0, so half is solved.  It is linear, so the response to
a step of heat Q is ``Q`` times a unit response, which is computed exactly in time from the
eigen-decomposition of the symmetric matrix ``C^(-1/2) K C^(-1/2)``:

    theta(t) = C^(-1/2) V diag((1 - exp(-mu t)) / mu) V^T C^(-1/2) b Q.

The decomposition, the steady solve and the sums over the modes use
:mod:`.fixed_order` (no BLAS/LAPACK), so a response is bit-identical whatever the number of
linear-algebra threads, the process it runs in, or the other times asked for with it.

:func:`network_response` caches it per (geometry, h); :func:`network_rise` scales it for
arrays of Q (and groups rows by their h), which is what the virtual-run surrogate needs.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from .fixed_order import solve_spd, symmetric_eigen
from .geometry import GuideGeometry

__all__ = ["ThermalNetwork", "network_response", "network_rise", "fin_conductance"]


def fin_conductance(h_w_m2k, perimeter_m, conductivity_w_mk, area_m2, length_m, *, tip_h_w_m2k=0.0):
    """Conductance [W/K] of a straight fin of uniform section, base to ambient.

    Incropera, DeWitt, Bergman & Lavine, *Fundamentals of Heat and Mass Transfer*, 6th ed.,
    Table 3.4 case A (convective tip) and case B (adiabatic tip, ``tip_h_w_m2k=0``):
    ``q_f / theta_b = M (sinh mL + (h/mk) cosh mL) / (cosh mL + (h/mk) sinh mL)`` with
    ``m = sqrt(hP/(kA))``, ``M = sqrt(hPkA)``; an infinite fin (case D) gives ``M``.

    >>> round(fin_conductance(8.82, 0.041, 37.46, 1.95e-4, 1e9), 4)  # infinite rail
    0.0514
    """
    if min(h_w_m2k, perimeter_m, conductivity_w_mk, area_m2, length_m) <= 0:
        raise ValueError("fin_conductance needs positive h, perimeter, conductivity, area and length.")
    m = math.sqrt(h_w_m2k * perimeter_m / (conductivity_w_mk * area_m2))
    M = math.sqrt(h_w_m2k * perimeter_m * conductivity_w_mk * area_m2)
    mL = m * length_m
    if mL > 30:
        return M
    r = tip_h_w_m2k / (m * conductivity_w_mk)
    return M * (math.sinh(mL) + r * math.cosh(mL)) / (math.cosh(mL) + r * math.sinh(mL))


def _rail_edges(g: GuideGeometry, dx_m: float) -> np.ndarray:
    pts = sorted({0.0, g.row_length_m / 2, g.block_length_m / 2, g.rail_length_m / 2})
    edges = [0.0]
    for a, b in zip(pts[:-1], pts[1:]):
        n = max(1, int(math.ceil((b - a) / dx_m - 1e-9)))
        edges.extend(np.linspace(a, b, n + 1)[1:])
    return np.asarray(edges)


class ThermalNetwork:
    """The reduced network for one geometry and one set of convection coefficients.

    Parameters
    ----------
    geometry : GuideGeometry
    h_side_w_m2k, h_front_w_m2k : float
        Eq. 11 and Eq. 12 coefficients [W/(m^2 K)].
    h_rail_w_m2k : float, optional
        Exposed rail faces; default ``h_side_w_m2k`` (same ASSUMPTION as the FV model).
    h_base_w_m2k : float
        Rail bottom (default 0, adiabatic).
    dx_m : float
        Cell length of the 1-D rail [m].

    Attributes
    ----------
    K : ndarray (n, n)  conductance matrix [W/K] of the half model
    C : ndarray (n,)    heat capacities [J/K]
    b : ndarray (n,)    source per watt of the whole guide
    names : list of str
    """

    def __init__(self, geometry: GuideGeometry, h_side_w_m2k: float, h_front_w_m2k: float, *,
                 h_rail_w_m2k: float | None = None, h_base_w_m2k: float = 0.0, dx_m: float = 2e-3):
        if h_rail_w_m2k is None:
            h_rail_w_m2k = h_side_w_m2k
        for name, v in (("h_side_w_m2k", h_side_w_m2k), ("h_front_w_m2k", h_front_w_m2k),
                        ("h_rail_w_m2k", h_rail_w_m2k), ("h_base_w_m2k", h_base_w_m2k)):
            if not (math.isfinite(v) and v >= 0):
                raise ValueError(f"{name} must be a finite number >= 0 [W/(m^2 K)], got {v!r}.")
        if not (math.isfinite(dx_m) and 0 < dx_m <= 0.05):
            raise ValueError(f"dx_m must be in (0, 0.05] m, got {dx_m!r}.")
        g = geometry
        self.geometry = g
        W, L, M, H1 = g.block_width_m, g.block_length_m, g.block_height_m, g.block_clearance_m
        w, hr, gap, d, Lrow = g.rail_width_m, g.rail_height_m, g.clearance_m, g.ball_diameter_m, g.row_length_m
        rho, lam, cp = g.body_properties()
        steel_rc = g.steel_density_kg_m3 * g.steel_specific_heat_j_kgk

        # ---- rail cells (half rail) -------------------------------------------------
        xe = _rail_edges(g, dx_m)
        dx = np.diff(xe)
        xc = 0.5 * (xe[1:] + xe[:-1])
        nr = len(dx)
        under_block = xc < L / 2
        under_rows = xc < Lrow / 2
        A_r = w * hr  # homogenised rectangle (fill fraction is in rho and lambda)
        lam_r = lam[4]
        C_rail = rho[4] * cp[4] * A_r * dx
        # convection per unit length
        gconv_rail = np.where(
            under_block,
            h_rail_w_m2k * 2 * H1,  # rail sides below the skirts
            h_rail_w_m2k * (w + 2 * hr),  # top and both sides
        ) + h_base_w_m2k * w
        G_rail_amb = gconv_rail * dx
        G_rail_amb[-1] += h_rail_w_m2k * A_r  # rail end face
        G_axial = lam_r * A_r / (0.5 * dx[:-1] + 0.5 * dx[1:])

        # ---- ball nodes ------------------------------------------------------------
        nb = int(under_rows.sum())
        lam_b = g.ball_row_conductivity_w_mk
        g_row_side = lam_b * d / (gap / 2)  # per row, per unit length, strip centre -> one face
        G_ball_car = g.n_rows * g_row_side * dx[:nb]
        G_ball_rail = g.n_rows * g_row_side * dx[:nb]
        C_ball = g.ball_mass_kg * g.ball_specific_heat_j_kgk * dx[:nb] / Lrow

        # ---- clearance air: carriage <-> rail (parallel to the balls) -----------------
        lam_air = g.air_conductivity_w_mk
        air_w = (w - 2 * d) + 2 * (hr - H1 - d)  # rail head perimeter not under balls
        g_air = lam_air * air_w / gap + np.where(under_rows, 0.0, g.n_rows * lam_air * d / gap)
        G_air = np.where(under_block, g_air * dx, 0.0)

        # ---- carriage (half) ---------------------------------------------------------
        hb = M - H1
        chan_w, chan_h = w + 2 * gap, hr - H1 + gap
        area_side = W * L + 2 * hb * L + (W - chan_w) * L  # top, two sides, underside
        area_front = 2 * (W * hb - chan_w * chan_h)
        G_car_amb = 0.5 * (h_side_w_m2k * area_side + h_front_w_m2k * area_front)
        C_car = 0.5 * g.carriage_steel_volume_m3 * steel_rc

        # ---- assemble: node 0 carriage, 1..nb balls, then rail ------------------------
        n = 1 + nb + nr
        K = np.zeros((n, n))
        C = np.zeros(n)
        b = np.zeros(n)

        def link(i, j, G):
            K[i, i] += G
            K[j, j] += G
            K[i, j] -= G
            K[j, i] -= G

        C[0] = C_car
        K[0, 0] += G_car_amb
        ib = 1 + np.arange(nb)
        ir = 1 + nb + np.arange(nr)
        C[ib] = C_ball
        C[ir] = C_rail
        b[ib] = dx[:nb] / Lrow  # sums to 1/2: half of every watt
        for k in range(nb):
            link(0, ib[k], G_ball_car[k])
            link(ib[k], ir[k], G_ball_rail[k])
        for k in range(nr):
            K[ir[k], ir[k]] += G_rail_amb[k]
            if G_air[k] > 0:
                link(0, ir[k], G_air[k])
        for k in range(nr - 1):
            link(ir[k], ir[k + 1], G_axial[k])
        self.K, self.C, self.b = K, C, b
        self.names = ["carriage"] + [f"balls[{k}]" for k in range(nb)] + [f"rail[{k}]" for k in range(nr)]
        self.rail_x_m = xc
        self.carriage_convection_w_k = 2 * G_car_amb
        # modal decomposition (exact in time), in a fixed order of floating-point operations
        # (no BLAS/LAPACK: their threading changes the last bits; see .fixed_order)
        s = 1.0 / np.sqrt(C)
        eig = symmetric_eigen(s[:, None] * K * s[None, :])
        mu = eig.values
        if mu.min() <= 0:
            raise ValueError("the network has no path to ambient (all h = 0): no steady state.")
        self._mu = mu
        self._eig = eig
        self._s = s
        self._load = eig.project(s * b)[0]  # V^T C^-1/2 b
        self._coef: dict[int, np.ndarray] = {}
        self._steady = solve_spd(K, b)

    # ------------------------------------------------------------------------------
    @property
    def steady_rise_per_w(self) -> float:
        """Steady carriage (thermocouple) rise per watt [K/W]."""
        return float(self._steady[0])

    @property
    def max_steady_rise_per_w(self) -> float:
        """Steady rise of the hottest node per watt [K/W] (a ball row)."""
        return float(self._steady.max())

    @property
    def time_constants_s(self) -> np.ndarray:
        """Time constants 1/mu of the network's modes [s], slowest first."""
        return 1.0 / self._mu

    def modal_coefficients(self, node: int = 0) -> np.ndarray:
        """Coefficients a_k [K/W] of ``node``'s unit response ``sum_k a_k (1 - exp(-mu_k t))``,
        in the order of :attr:`time_constants_s`."""
        node = int(node)
        if not 0 <= node < self._mu.size:
            raise ValueError(f"node must be in [0, {self._mu.size}), got {node}.")
        if node not in self._coef:
            unit = np.zeros(self._mu.size)
            unit[node] = 1.0
            coef = self._s[node] * self._eig.project(unit)[0] * self._load / self._mu
            coef.setflags(write=False)
            self._coef[node] = coef
        return self._coef[node]

    def response(self, times_s, node: int = 0) -> np.ndarray:
        """Rise per watt [K/W] of ``node`` (0 = carriage) at ``times_s`` after a heat step.

        Each time's value is the sum over the modes in a fixed order of element-wise
        operations: it does not depend on the other times asked for, on the number of
        BLAS threads or on the process."""
        t = np.asarray(times_s, float)
        if np.any(t < 0) or not np.all(np.isfinite(t)):
            raise ValueError("times_s must be finite and >= 0 [s].")
        t = np.ascontiguousarray(t)
        coef = self.modal_coefficients(node)
        out = np.zeros(t.shape)
        for a, mu in zip(coef.tolist(), self._mu.tolist()):
            out -= a * np.expm1(-mu * t)
        return out


    def lagged_response(self, times_s, tau_s, node: int = 0) -> np.ndarray:
        """Rise per watt [K/W] of ``node`` at ``times_s`` when the heat reaches the network
        through a first-order lag of time constant ``tau_s`` [s]: the input is
        ``1 - exp(-t/tau)`` instead of a step (a heat source behind a lumped body of heat
        capacity C and conductance G: tau = C/G).

        For each mode a_k (1 - exp(-mu t)) the convolution with the lagged input is exact:
        ``a_k [(1 - e^(-lam t)) - lam (e^(-lam t) - e^(-mu t)) / (mu - lam)]``, lam = 1/tau
        (the limit ``lam t e^(-lam t)`` replaces the quotient where mu = lam). ``tau_s = 0``
        is the step response (:meth:`response`). ``tau_s`` broadcasts against ``times_s``.

        Examples
        --------
        A slower input gives a smaller rise at every time, and the same steady rise:

        >>> from rsm_lrg.physics.thermal.geometry import GuideGeometry
        >>> net = ThermalNetwork(GuideGeometry(), 8.82, 22.45)
        >>> bool(net.lagged_response(3000.0, 1200.0) < net.response(3000.0))
        True
        >>> bool(abs(net.lagged_response(1e8, 1200.0) / net.steady_rise_per_w - 1) < 1e-9)
        True
        """
        t = np.asarray(times_s, float)
        tau = np.asarray(tau_s, float)
        if np.any(t < 0) or not np.all(np.isfinite(t)):
            raise ValueError("times_s must be finite and >= 0 [s].")
        if np.any(tau < 0) or not np.all(np.isfinite(tau)):
            raise ValueError("tau_s must be finite and >= 0 [s].")
        t, tau = np.broadcast_arrays(t, tau)
        step = tau <= 0
        lam = np.where(step, 1.0, 1.0 / np.where(step, 1.0, tau))
        coef = self.modal_coefficients(node)
        out = np.zeros(t.shape)
        el = np.exp(-lam * t)
        for a, mu in zip(coef.tolist(), self._mu.tolist()):
            em = np.exp(-mu * t)
            d = mu - lam
            near = np.abs(d) <= 1e-9 * np.maximum(mu, lam)
            with np.errstate(divide="ignore", invalid="ignore"):
                q = np.where(near, lam * t * el, lam * (el - em) / np.where(near, 1.0, d))
            lagged = (1.0 - el) - q
            out += a * np.where(step, -np.expm1(-mu * t), lagged)
        return out


@lru_cache(maxsize=256)
def _network(geometry, h_side, h_front, h_rail, h_base, dx_m):
    return ThermalNetwork(geometry, h_side, h_front, h_rail_w_m2k=h_rail, h_base_w_m2k=h_base, dx_m=dx_m)


def network_response(times_s, h_side_w_m2k: float = 8.82, h_front_w_m2k: float = 22.45, *,
                     h_rail_w_m2k: float | None = None, h_base_w_m2k: float = 0.0,
                     geometry: GuideGeometry | None = None, dx_m: float = 2e-3) -> np.ndarray:
    """Thermocouple (carriage) temperature rise per watt [K/W] at ``times_s`` [s].

    Cached per (geometry, h): repeated calls cost one matrix product.  Multiply by Q [W]
    for the rise; by linearity, add the ambient temperature for T.

    >>> r = network_response([0.0, 3600.0, 1e6])
    >>> float(r[0]), bool(r[1] < r[2])
    (0.0, True)
    """
    geometry = geometry or GuideGeometry()
    net = _network(geometry, float(h_side_w_m2k), float(h_front_w_m2k),
                   None if h_rail_w_m2k is None else float(h_rail_w_m2k), float(h_base_w_m2k), float(dx_m))
    return net.response(times_s)


def network_rise(heat_w, times_s, h_side_w_m2k=8.82, h_front_w_m2k=22.45, *, h_rail_w_m2k=None,
                 h_base_w_m2k=0.0, geometry: GuideGeometry | None = None, dx_m: float = 2e-3) -> np.ndarray:
    """Thermocouple rise [K] for many rows at once: shape ``(n_rows, n_times)``.

    ``heat_w`` [W] is an array of n rows; ``h_side_w_m2k``, ``h_front_w_m2k`` and
    ``h_rail_w_m2k`` may be scalars or arrays of n rows.  Rows sharing the same h share one
    unit response (:func:`network_response`), which is scaled by their Q.

    >>> network_rise([0.415, 0.830], [1e7]).round(3)
    array([[2.795],
           [5.589]])
    """
    q = np.atleast_1d(np.asarray(heat_w, float))
    if q.ndim != 1 or not np.all(np.isfinite(q)):
        raise ValueError("heat_w must be a finite number or 1-D array of numbers [W].")
    t = np.atleast_1d(np.asarray(times_s, float))
    n = len(q)
    hs = np.broadcast_to(np.asarray(h_side_w_m2k, float), (n,))
    hf = np.broadcast_to(np.asarray(h_front_w_m2k, float), (n,))
    hr = hs if h_rail_w_m2k is None else np.broadcast_to(np.asarray(h_rail_w_m2k, float), (n,))
    keys = np.stack([hs, hf, hr], axis=1)
    uniq, inv = np.unique(keys, axis=0, return_inverse=True)
    inv = inv.reshape(-1)
    out = np.empty((n, len(t)))
    for k, (a, bb, c) in enumerate(uniq):
        resp = network_response(t, a, bb, h_rail_w_m2k=c, h_base_w_m2k=h_base_w_m2k,
                                geometry=geometry, dx_m=dx_m)
        rows = inv == k
        out[rows] = q[rows, None] * resp[None, :]
    return out
