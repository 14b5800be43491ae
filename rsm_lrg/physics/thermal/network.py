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
from dataclasses import dataclass, fields, replace
from functools import lru_cache

import numpy as np

from .fixed_order import ChainNetwork, chain_network, chain_rows, modal_sum, network_modes, solve_spd
from .geometry import GuideGeometry

__all__ = ["ThermalNetwork", "network_response", "network_rise", "fin_conductance", "RigBodies", "HeatPaths",
           "rig_bodies", "rig_network", "RIG_SOURCES",
           "leaf_terms", "rig_responses"]

#: Heat inputs of the rig network (:class:`RigBodies`): ``"balls"`` (friction at the ball
#: contacts, Eq. 8 in watts) and ``"stage"`` (heat entering the working stage, e.g. through
#: the drive's link span, Section 4.1).
RIG_SOURCES = ("balls", "stage")


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


@dataclass(frozen=True)
class RigBodies:
    """The bodies around the guide in the rig (Section 4.1), for one heat balance in watts.

    Every value is for the whole rig (the network halves it for its half model), in W/K or
    J/K; :func:`rig_bodies` derives them from the parameters (``data/lrg_shs15v.toml``: each
    with its source or marked ASSUMPTION).

    Attributes
    ----------
    ball_contact_w_k : float
        Conductance between the ball contacts and the carriage, and (the same) between them
        and the rail, all rows together [W/K]: Hertzian constriction, replaces the perfect
        ball-row contact of the paper's FEM.
    frame_joint_w_k : float
        Bolted joint carriage -> rigid frame (and, in the RMS, frame -> working stage) [W/K].
    frame_capacity_j_k, frame_loss_w_k : float
        Heat capacity of the rigid frame [J/K] and its loss to the air [W/K].
    leaf_w_k : float
        End-to-end conduction of the n leaves, ``n lambda w y / l`` [W/K] (Eq. 3); ``inf``:
        the RMS, no leaves (the stage is bolted, ``frame_joint_w_k``).
    leaf_capacity_j_k, leaf_loss_w_k : float
        Heat capacity [J/K] and loss to the air (both faces) [W/K] of the leaves.
    stage_capacity_j_k, stage_loss_w_k : float
        The working stage [J/K], [W/K].
    rail_base_w_m2k : float
        Contact conductance per area of the rail's mounting face on the base [W/(m^2 K)].
    base_capacity_j_k, base_loss_w_k : float
        The base the rail is bolted to [J/K], [W/K].
    """

    ball_contact_w_k: float
    frame_joint_w_k: float
    frame_capacity_j_k: float
    frame_loss_w_k: float
    leaf_w_k: float
    leaf_capacity_j_k: float
    leaf_loss_w_k: float
    stage_capacity_j_k: float
    stage_loss_w_k: float
    rail_base_w_m2k: float
    base_capacity_j_k: float
    base_loss_w_k: float

    def __post_init__(self) -> None:
        for f in fields(self):
            v = getattr(self, f.name)
            ok = (v > 0 and (math.isfinite(v) or f.name == "leaf_w_k")) if isinstance(v, float) else False
            if not ok:
                raise ValueError(f"RigBodies.{f.name} must be a positive number, got {v!r}.")

    @property
    def rigid(self) -> bool:
        """The RMS: the working stage bolted to the frame, no leaves."""
        return math.isinf(self.leaf_w_k)


@dataclass(frozen=True)
class HeatPaths:
    """Where each watt of a source goes in the steady state of the rig network.

    ``to_ambient`` maps each body (``carriage``, ``balls``, ``rail``, ``frame``, ``leaves``,
    ``stage``, ``base``) to the share of the source's heat it gives to the air; the shares sum
    to 1 (energy balance). ``into_carriage`` and ``into_rail`` are the shares that leave the
    ball contacts into the carriage and into the rail (friction source; they sum to 1);
    ``carriage_rise_per_w`` the thermocouple's steady rise per watt [K/W].
    """

    source: str
    to_ambient: dict
    into_carriage: float
    into_rail: float
    carriage_rise_per_w: float


@dataclass(frozen=True)
class _Assembly:
    K: np.ndarray
    C: np.ndarray
    sources: dict
    g_ambient: np.ndarray
    ball_links: tuple
    names: list
    rail_x_m: np.ndarray
    carriage_convection_w_k: float
    nodes: dict


def _assemble(geometry: GuideGeometry, h_side_w_m2k: float, h_front_w_m2k: float, h_rail_w_m2k: float | None,
              h_base_w_m2k: float, dx_m: float, rig: RigBodies | None, leaf_links: bool) -> _Assembly:
    """Conductances, capacities and sources of the network (:class:`ThermalNetwork`);
    ``leaf_links=False``: without the leaves' two links (a template for :func:`rig_responses`)."""
    if h_rail_w_m2k is None:
        h_rail_w_m2k = h_side_w_m2k
    for name, v in (("h_side_w_m2k", h_side_w_m2k), ("h_front_w_m2k", h_front_w_m2k),
                    ("h_rail_w_m2k", h_rail_w_m2k), ("h_base_w_m2k", h_base_w_m2k)):
        if not (math.isfinite(v) and v >= 0):
            raise ValueError(f"{name} must be a finite number >= 0 [W/(m^2 K)], got {v!r}.")
    if not (math.isfinite(dx_m) and 0 < dx_m <= 0.05):
        raise ValueError(f"dx_m must be in (0, 0.05] m, got {dx_m!r}.")
    g = geometry
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
    if rig is not None:  # Hertzian contacts (whole guide) spread along the rows, half model
        G_ball_car = rig.ball_contact_w_k * dx[:nb] / Lrow
    G_ball_rail = G_ball_car.copy()
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

    # ---- assemble: node 0 carriage, 1..nb balls, then rail, then the rig's bodies -----
    extra = [] if rig is None else (["frame"] + ([] if rig.rigid else ["leaves"]) + ["stage", "base"])
    n = 1 + nb + nr + len(extra)
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
    g_amb = np.zeros(n)  # conductance of every node to the air [W/K]
    g_amb[0] = G_car_amb
    g_amb[ir] = G_rail_amb
    sources = {"balls": b}
    if rig is not None:
        idx = {name: 1 + nb + nr + k for k, name in enumerate(extra)}
        fr, st, ba = idx["frame"], idx["stage"], idx["base"]
        C[fr], C[st], C[ba] = 0.5 * rig.frame_capacity_j_k, 0.5 * rig.stage_capacity_j_k, 0.5 * rig.base_capacity_j_k
        for node, loss in ((fr, rig.frame_loss_w_k), (st, rig.stage_loss_w_k), (ba, rig.base_loss_w_k)):
            K[node, node] += 0.5 * loss
            g_amb[node] = 0.5 * loss
        link(0, fr, 0.5 * rig.frame_joint_w_k)
        if rig.rigid:
            link(fr, st, 0.5 * rig.frame_joint_w_k)
        else:  # the leaves' node at their mid-length: half their conduction on each side
            lf = idx["leaves"]
            C[lf] = 0.5 * rig.leaf_capacity_j_k
            K[lf, lf] += 0.5 * rig.leaf_loss_w_k
            g_amb[lf] = 0.5 * rig.leaf_loss_w_k
            if leaf_links:  # rig_responses adds these two per row
                link(fr, lf, rig.leaf_w_k)  # 0.5 (half model) x 2 (half the length)
                link(lf, st, rig.leaf_w_k)
        for k in range(nr):  # the rail's mounting face on the base
            link(ir[k], ba, rig.rail_base_w_m2k * w * dx[k])
        b_stage = np.zeros(n)
        b_stage[st] = 0.5
        sources["stage"] = b_stage
    names = (["carriage"] + [f"balls[{k}]" for k in range(nb)] + [f"rail[{k}]" for k in range(nr)] + extra)
    nodes = {} if rig is None else idx
    return _Assembly(K, C, sources, g_amb, (ib, ir[:nb], G_ball_car, G_ball_rail), names, xc, 2 * G_car_amb, nodes)


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
                 h_rail_w_m2k: float | None = None, h_base_w_m2k: float = 0.0, dx_m: float = 2e-3,
                 rig: RigBodies | None = None):
        asm = _assemble(geometry, h_side_w_m2k, h_front_w_m2k, h_rail_w_m2k, h_base_w_m2k, dx_m, rig, True)
        self.geometry = geometry
        self.K, self.C, self.b = asm.K, asm.C, asm.sources["balls"]
        self.sources = asm.sources
        self.rig = rig
        self.g_ambient = asm.g_ambient
        self._ball_links = asm.ball_links
        self.names = asm.names
        self.rail_x_m = asm.rail_x_m
        self.carriage_convection_w_k = asm.carriage_convection_w_k
        self.h_side_w_m2k, self.h_front_w_m2k = float(h_side_w_m2k), float(h_front_w_m2k)
        # modal decomposition (exact in time), in a fixed order of floating-point operations
        # (no BLAS/LAPACK: their threading changes the last bits; see .fixed_order)
        self._src_names = list(asm.sources)
        self._src = np.stack([asm.sources[k] for k in self._src_names], axis=1)
        self._coef: dict[tuple[int, str], np.ndarray] = {}
        self._modes(0)
        self._steadies = {name: solve_spd(self.K, vec) for name, vec in asm.sources.items()}
        self._steady = self._steadies["balls"]

    def _modes(self, node: int) -> None:
        """Rates and, per source, the modal coefficients of ``node``'s unit response
        (:func:`.fixed_order.network_modes`: what :func:`rig_responses` computes per row)."""
        mu, coef, _ = network_modes(self.K, self.C, self._src, node)
        self._mu = mu
        for k, name in enumerate(self._src_names):
            c = np.ascontiguousarray(coef[:, k])
            c.setflags(write=False)
            self._coef[(node, name)] = c

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

    def _source(self, source: str) -> str:
        if source not in self.sources:
            raise ValueError(f"source must be one of {', '.join(self.sources)}, got {source!r}.")
        return source

    def modal_coefficients(self, node: int = 0, source: str = "balls") -> np.ndarray:
        """Coefficients a_k [K/W] of ``node``'s unit response ``sum_k a_k (1 - exp(-mu_k t))``
        to a watt of ``source`` (:attr:`sources`), in the order of :attr:`time_constants_s`."""
        node = int(node)
        if not 0 <= node < self._mu.size:
            raise ValueError(f"node must be in [0, {self._mu.size}), got {node}.")
        key = (node, self._source(source))
        if key not in self._coef:
            self._modes(node)
        return self._coef[key]

    def steady_rise(self, source: str = "balls") -> np.ndarray:
        """Steady rise of every node per watt of ``source`` [K/W] (read-only copy)."""
        return self._steadies[self._source(source)].copy()

    def heat_paths(self, source: str = "balls") -> HeatPaths:
        """Where each watt of ``source`` leaves the network in the steady state (the energy
        balance: the shares sum to 1) and, for the ball contacts, which share flows into the
        carriage and which into the rail. The shares follow from the conductances alone."""
        th = self._steadies[self._source(source)]
        total = 2.0 * float(self.sources[source].sum())  # the half model: 1 W in all
        groups: dict[str, float] = {}
        for name, flow in zip(self.names, (self.g_ambient * th).tolist()):
            key = name.split("[")[0]
            groups[key] = groups.get(key, 0.0) + 2.0 * flow / total
        ib, ir, gc, gr = self._ball_links
        into_c = 2.0 * float(np.sum(gc * (th[ib] - th[0])))
        into_r = 2.0 * float(np.sum(gr * (th[ib] - th[ir])))
        gen = into_c + into_r
        share_c = into_c / gen if source == "balls" else math.nan
        share_r = into_r / gen if source == "balls" else math.nan
        return HeatPaths(source, groups, share_c, share_r, float(th[0]))

    def response(self, times_s, node: int = 0, source: str = "balls") -> np.ndarray:
        """Rise per watt [K/W] of ``node`` (0 = carriage) at ``times_s`` after a heat step of
        ``source`` (``"balls"``: the friction at the ball contacts; ``"stage"``: heat entering
        the working stage, rig networks only).

        Each time's value is the sum over the modes in a fixed order of element-wise
        operations: it does not depend on the other times asked for, on the number of
        BLAS threads or on the process."""
        t = np.asarray(times_s, float)
        if np.any(t < 0) or not np.all(np.isfinite(t)):
            raise ValueError("times_s must be finite and >= 0 [s].")
        return modal_sum(self.modal_coefficients(node, source), self._mu, t)

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


def rig_bodies(values, thickness_m: float, *, rigid: bool = False, h_side_w_m2k: float = 8.82) -> RigBodies:
    """The rig's bodies (:class:`RigBodies`) from the parameters ``values`` (a full
    :meth:`rsm_lrg.physics.params.LRGParams.to_dict`), for leaves of thickness ``thickness_m``
    [m] (``rigid``: the RMS, no leaves).

    * ball contacts: ``ball_contact_conductance_w_k`` (each side);
    * frame: ``frame_mass_fraction * stage_mass_kg`` of 6061-T6 (Table 2), bolted to the
      carriage's top face (``block_width_m * block_length_m``) with the contact conductance
      ``joint_conductance_w_m2k``; it loses ``stage_loss_conductance_w_k`` to the air (a block
      of the working stage's size);
    * leaves: ``hinge_count`` leaves of 65Mn (Table 2), ``n lambda w y / l`` end to end (Eq. 3),
      heat capacity ``n rho c w y l``, both faces convecting at ``h_side_w_m2k`` (Eq. 11);
    * working stage: the rest of ``stage_mass_kg``, ``stage_loss_conductance_w_k``;
    * base: ``base_heat_capacity_j_k``, ``base_loss_conductance_w_k``; the rail's mounting
      face on it with ``joint_conductance_w_m2k``.

    >>> from rsm_lrg.physics.params import LRGParams
    >>> r = rig_bodies(LRGParams().to_dict(), 3e-4)
    >>> round(r.leaf_w_k, 4), r.rigid, rig_bodies(LRGParams().to_dict(), 3e-4, rigid=True).rigid
    (0.0288, False, True)
    """
    v = values
    # the RMS has no leaves: its network does not depend on a thickness, so the leaves' (unused)
    # entries take the parameter set's own and every RMS row shares one network
    y = float(v["hinge_thickness_m"]) if rigid else float(thickness_m)
    n, w, lh = float(v["hinge_count"]), float(v["hinge_width_m"]), float(v["hinge_length_m"])
    m_frame = float(v["frame_mass_fraction"]) * float(v["stage_mass_kg"])
    m_stage = float(v["stage_mass_kg"]) - m_frame
    c_al = float(v["stage_specific_heat_j_kgk"])
    hj = float(v["joint_conductance_w_m2k"])
    g_leaf, c_leaf = leaf_terms(v, y)
    leaf = math.inf if rigid else float(g_leaf)
    return RigBodies(
        ball_contact_w_k=float(v["ball_contact_conductance_w_k"]),
        frame_joint_w_k=hj * float(v["block_width_m"]) * float(v["block_length_m"]),
        frame_capacity_j_k=m_frame * c_al if m_frame > 0 else 1e-6,
        frame_loss_w_k=float(v["stage_loss_conductance_w_k"]),
        leaf_w_k=leaf,
        leaf_capacity_j_k=float(c_leaf),
        leaf_loss_w_k=n * 2.0 * w * lh * float(h_side_w_m2k),
        stage_capacity_j_k=m_stage * c_al if m_stage > 0 else 1e-6,
        stage_loss_w_k=float(v["stage_loss_conductance_w_k"]),
        rail_base_w_m2k=hj,
        base_capacity_j_k=float(v["base_heat_capacity_j_k"]),
        base_loss_w_k=float(v["base_loss_conductance_w_k"]),
    )


def leaf_terms(values, thickness_m):
    """End-to-end conduction ``n lambda w y / l`` [W/K] (Eq. 3) and heat capacity
    ``n rho c w y l`` [J/K] of the ``hinge_count`` leaves of thickness ``thickness_m`` [m]
    (a number or an array), from the parameters ``values`` (:func:`rig_bodies`).

    >>> from rsm_lrg.physics.params import LRGParams
    >>> g, c = leaf_terms(LRGParams().to_dict(), np.array([1e-4, 3e-4]))
    >>> (g / g[0]).tolist(), (c / c[0]).tolist()
    ([1.0, 3.0], [1.0, 3.0])
    """
    v = values
    y = np.asarray(thickness_m, float)
    n, w, lh = float(v["hinge_count"]), float(v["hinge_width_m"]), float(v["hinge_length_m"])
    g = n * float(v["hinge_conductivity_w_mk"]) * w * y / lh
    c = n * float(v["hinge_density_kg_m3"]) * float(v["hinge_specific_heat_j_kgk"]) * w * y * lh
    return g, c


def rig_responses(geometry: GuideGeometry, h_side_w_m2k: float, h_front_w_m2k: float, rig: RigBodies,
                  leaf_w_k, leaf_capacity_j_k, times_s, *, dx_m: float = 1e-2) -> tuple[np.ndarray, np.ndarray]:
    """The carriage's rise per watt of each source (:data:`RIG_SOURCES`) for many rows of one
    rig whose leaves differ (a design of many thicknesses), in one compiled loop.

    Row ``r`` is the network :func:`rig_network` builds for ``rig`` with its leaves' conduction
    ``leaf_w_k[r]`` [W/K] and heat capacity ``leaf_capacity_j_k[r]`` [J/K] (:func:`leaf_terms`;
    ignored for the RMS): the same assembly, split into the guide's core, reduced to
    tridiagonal form once per rig, and the chain stage - leaves - frame hanging from the
    carriage, which alone changes with the thickness (:func:`.fixed_order.chain_rows`: a QL
    iteration and a tridiagonal solve per row, in one compiled loop). It equals
    :func:`rig_network`'s dense decomposition to rounding (1e-11 relative, tested), and each
    row is bit-identical whatever the other rows, the process or the number of threads.

    Parameters
    ----------
    times_s : array (rows, m)
        Times after the heat step of each row [s].

    Returns
    -------
    resp : ndarray (rows, 2, m)
        Rise per watt [K/W] at ``times_s`` of a watt at the ball contacts and a watt entering
        the working stage.
    steady : ndarray (rows, 2)
        The steady rises per watt [K/W].

    Examples
    --------
    >>> from rsm_lrg.physics.params import LRGParams
    >>> from rsm_lrg.physics.thermal.geometry import GuideGeometry
    >>> v = LRGParams().to_dict()
    >>> rig = rig_bodies(v, 3e-4)
    >>> g, c = leaf_terms(v, np.array([1e-4, 3e-4]))
    >>> resp, steady = rig_responses(GuideGeometry(), 8.82, 22.45, rig, g, c, [[3000.0], [3000.0]])
    >>> net = rig_network(GuideGeometry(), 8.82, 22.45, rig)
    >>> float(resp[1, 0, 0] / net.response([3000.0])[0]), float(steady[1, 1] / net.steady_rise("stage")[0])
    (1.0, 1.0)
    """
    t = np.atleast_2d(np.asarray(times_s, float))
    if np.any(t < 0) or not np.all(np.isfinite(t)):
        raise ValueError("times_s must be finite and >= 0 [s].")
    if not rig.rigid:  # the template has no leaf links and each row sets the capacity: one per rig
        rig = replace(rig, leaf_w_k=1.0, leaf_capacity_j_k=1.0)
    tpl = _rig_chain(geometry, float(h_side_w_m2k), float(h_front_w_m2k), rig, float(dx_m))
    rows = t.shape[0]
    kd, ko, cc = (np.broadcast_to(q, (rows, q.size)) for q in (tpl.k_diag, tpl.k_link, tpl.capacity))
    if not rig.rigid:  # the leaves (chain node 1) linked to the stage (0) and the frame (2), per row
        g = np.broadcast_to(np.asarray(leaf_w_k, float), (rows,))
        zero = np.zeros(rows)
        kd = kd + np.stack([g, g + g, g], axis=1)
        ko = np.stack([zero - g, zero - g, ko[:, 2]], axis=1)
        cc = np.stack([cc[:, 0], 0.5 * np.broadcast_to(np.asarray(leaf_capacity_j_k, float), (rows,)), cc[:, 2]],
                      axis=1)
    return chain_rows(tpl.core, kd, ko, cc, tpl.chain_sources, t)


@dataclass(frozen=True)
class _RigChain:
    core: ChainNetwork
    k_diag: np.ndarray
    k_link: np.ndarray
    capacity: np.ndarray
    chain_sources: np.ndarray


@lru_cache(maxsize=64)
def _rig_chain(geometry, h_side, h_front, rig, dx_m) -> _RigChain:
    """The rig's network split into the core (guide, frame joint, base; the carriage its hub)
    and the chain stage - leaves - frame (RMS: stage - frame) that hangs from the carriage, the
    leaves' links left out (``_assemble(..., leaf_links=False)``)."""
    asm = _assemble(geometry, h_side, h_front, None, 0.0, dx_m, rig, False)
    nodes = asm.nodes
    chain = [nodes["stage"]] + ([] if rig.rigid else [nodes["leaves"]]) + [nodes["frame"]]
    core = [i for i in range(len(asm.C)) if i not in chain]
    K = asm.K
    # a chain: each node linked only to its neighbours, the last to the carriage (core node 0)
    links = np.zeros_like(K)
    for i, j in zip(chain[:-1], chain[1:]):
        links[i, j] = links[j, i] = 1
    links[chain[-1], 0] = links[0, chain[-1]] = 1
    off = K[np.ix_(chain, range(len(asm.C)))] * (1 - np.eye(len(asm.C))[chain])
    if np.any((off != 0) & (links[chain] == 0)):
        raise ValueError("the rig's bodies do not hang from the carriage as a chain")
    k_link = np.array([K[i, j] for i, j in zip(chain[:-1], chain[1:])] + [K[chain[-1], 0]])
    if not rig.rigid:
        k_link[:2] = 0.0  # the leaves' links are made per row
    core_net = chain_network(K[np.ix_(core, core)], asm.C[core], asm.sources["balls"][core][:, None])
    return _RigChain(core_net, np.array([K[i, i] for i in chain]), k_link, asm.C[chain].copy(),
                     asm.sources["stage"][chain][:, None].copy())


@lru_cache(maxsize=512)
def _rig_network(geometry, h_side, h_front, rig, dx_m):
    return ThermalNetwork(geometry, h_side, h_front, dx_m=dx_m, rig=rig)


def rig_network(geometry: GuideGeometry, h_side_w_m2k: float, h_front_w_m2k: float, rig: RigBodies, *,
                dx_m: float = 1e-2) -> ThermalNetwork:
    """The guide's network with the rig's bodies (one heat balance in watts), cached per
    (geometry, h, bodies, dx). ``dx_m`` 10 mm: the rail's 1-D cells (the carriage's rise at
    50 min is 0.2 % above that of 1 mm cells, tests/physics/thermal/test_rig_network.py). A
    design of many thicknesses goes through :func:`rig_responses` instead: the same numbers,
    without an object per thickness."""
    return _rig_network(geometry, float(h_side_w_m2k), float(h_front_w_m2k), rig, float(dx_m))
