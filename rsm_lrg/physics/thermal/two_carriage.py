"""The rig of Section 4.1 as one heat network: both carriages (RMS and RFCMS) on one rail and base.

"In order to avoid the manufacturing errors from different rails, the two types of stages were
assembled on the same rail. [...] the two types of motion stages were driven simultaneously by the
link span" (Su, Zhang & Yang 2023, Section 4.1). So every test of Table 4 and Fig. 9 ran both
carriages together: the heat of the other stage reaches the measured carriage through the shared
rail and base. ``other_stage_running`` (a parameter, default true on that evidence) switches the
other stage's friction heat off for comparison.

Bodies (every value from :class:`~rsm_lrg.physics.params.LRGParams`, sourced or marked ASSUMPTION
in ``data/lrg_shs15v.toml``):

* **rail**: a 1-D fin along its whole length (cells of ``dx_m``), its mounting face on the base
  (``joint_conductance_w_m2k``), its top and sides convecting (Eq. 11 at the room's air speed)
  except where a carriage covers it (only the faces below the skirts), end faces convecting;
* **base**: one node (``base_heat_capacity_j_k``, ``base_loss_conductance_w_k``);
* **each carriage** (the RMS at ``-carriage_spacing_m/2``, the RFCMS at ``+carriage_spacing_m/2``):
  the carriage's steel, its balls, the rigid frame bolted on it, and the working stage (the RMS's
  bolted to the frame, the RFCMS's on its leaves with a node at their mid-length); the carriage,
  frame, leaves and stage convect at the air speed they see (:func:`..convection.relative_air_speed`;
  sides Eq. 11, front faces Churchill-Bernstein, :func:`..convection.moving_coefficients`); the
  clearance air between carriage and rail conducts; the ball contacts (Hertz/Yovanovich, both sides
  of each contact, :mod:`rsm_lrg.physics.contact`) tie the balls to the carriage and, spread over
  the rail length the rows sweep (rows plus stroke), to the rail;
* **heat**: the friction power of each carriage (Eq. 8 in watts) released at its contact
  interfaces, half on the carriage side and half on the rail side; each interface is eliminated
  exactly, so a share ``G_r/(G_b + G_r)`` goes straight into the raceway's body and the rest into
  the ball. **No drive or link heat**: the paper did not consider the motor's heat (Section 2.2)
  and no loss model of its drive (an Akribis ASD240 driver, Section 4.1) with its own evidence is at
  hand; the model therefore cannot produce a thickness effect through the stage (Table 4's A).

The network is linear, ``C θ' = −K θ + Σ b_j Q_j``; responses are exact in time from the modes of
``C^(-1/2) K C^(-1/2)`` in a fixed order of operations (:mod:`.fixed_order`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from .fixed_order import modal_sum, network_modes, solve_spd
from .geometry import GuideGeometry

__all__ = ["CarriageSetting", "TwoCarriageNetwork", "two_carriage_network", "cached_network", "STAGES", "two_carriage_rows",
           "clear_network_cache", "network_items",
           "ContactInterpolant"]

#: The two stages on the rail, in the order of their positions (RMS first).
STAGES = ("rms", "rfcms")


@dataclass(frozen=True)
class CarriageSetting:
    """How one stage runs during the test.

    Attributes
    ----------
    thickness_m : float
        Leaf thickness y [m] (the RFCMS; ignored for the RMS).
    stroke_m : float
        Stroke s [m]: the ball rows sweep ``row length + s`` of the rail.
    mean_square_speed_m2_s2 : float
        ``<v²>`` of the stage over its cycle [m²/s²] (:func:`rsm_lrg.physics.motion.mean_square_speed`);
        0: at rest (it then sees the room's air speed).
    """

    thickness_m: float
    stroke_m: float
    mean_square_speed_m2_s2: float

    def __post_init__(self) -> None:
        for name in ("thickness_m", "stroke_m", "mean_square_speed_m2_s2"):
            v = getattr(self, name)
            if not (isinstance(v, float) and math.isfinite(v) and v >= 0):
                raise ValueError(f"CarriageSetting.{name} must be a finite float >= 0, got {v!r}")


class TwoCarriageNetwork:
    """The rig's network with both carriages (built by :func:`two_carriage_network`).

    Attributes
    ----------
    K : ndarray (n, n)
        Conductance matrix [W/K] (symmetric positive definite).
    C : ndarray (n,)
        Heat capacities [J/K].
    sources : dict
        ``"rms"``, ``"rfcms"``: where each watt of that carriage's friction power enters [1]
        (each vector sums to 1).
    g_ambient : ndarray (n,)
        Conductance of every node to the air (or, for the base, to the room) [W/K].
    nodes : dict
        Index of every named body: ``"rms.carriage"``, ``"rms.balls"``, ``"rms.frame"``,
        ``"rms.stage"``, ``"rfcms.carriage"``, ..., ``"rfcms.leaves"``, ``"base"``; the rail's
        cells are ``rail_cells``.
    convection : dict
        Per stage: the air speed it sees [m/s], its Reynolds number and h_side, h_front [W/(m²·K)].
    contact_w_k : float
        The ball contacts' conductance of one side (ball centre to raceway body) [W/K].
    """

    def __init__(self, K: np.ndarray, C: np.ndarray, sources: dict, g_ambient: np.ndarray, nodes: dict,
                 rail_cells: np.ndarray, names: list, convection: dict, contact_w_k: float):
        self.K, self.C, self.sources, self.g_ambient = K, C, sources, g_ambient
        self.nodes, self.rail_cells, self.names = nodes, rail_cells, names
        self.convection, self.contact_w_k = convection, contact_w_k
        self._src = np.stack([sources[s] for s in STAGES], axis=1)
        self._modes: dict[int, tuple[np.ndarray, np.ndarray]] = {}
        self._steady = {s: solve_spd(K, sources[s]) for s in STAGES}

    def node(self, name: str) -> int:
        """Index of a named body (:attr:`nodes`)."""
        if name not in self.nodes:
            raise ValueError(f"node must be one of {', '.join(self.nodes)}, got {name!r}")
        return int(self.nodes[name])

    def steady_rise(self, source: str) -> np.ndarray:
        """Steady rise of every node per watt of ``source`` (``"rms"`` or ``"rfcms"``) [K/W]."""
        if source not in STAGES:
            raise ValueError(f"source must be 'rms' or 'rfcms', got {source!r}")
        return self._steady[source].copy()

    def heat_balance(self, source: str) -> float:
        """Heat leaving to the air and the room in the steady state per watt of ``source`` [1]:
        1 up to rounding (energy conservation, Eq. 7 at steady state)."""
        return float(np.sum(self.g_ambient * self.steady_rise(source)))

    def response(self, times_s, node: str, source: str) -> np.ndarray:
        """Rise per watt [K/W] of the body ``node`` at ``times_s`` [s] after a step of the friction
        power of ``source``, exact in time (``sum_k a_k (1 - exp(-mu_k t))``)."""
        i = self.node(node)
        if source not in STAGES:
            raise ValueError(f"source must be 'rms' or 'rfcms', got {source!r}")
        if i not in self._modes:
            mu, coef, _ = network_modes(self.K, self.C, self._src, i)
            self._modes[i] = (mu, coef)
        mu, coef = self._modes[i]
        t = np.asarray(times_s, float)
        if np.any(t < 0) or not np.all(np.isfinite(t)):
            raise ValueError("times_s must be finite and >= 0 [s].")
        return modal_sum(np.ascontiguousarray(coef[:, STAGES.index(source)]), mu, t)


def _overlap(edges: np.ndarray, lo: float, hi: float) -> np.ndarray:
    """Length of ``[lo, hi]`` inside each cell of ``edges`` [m]."""
    return np.clip(np.minimum(edges[1:], hi) - np.maximum(edges[:-1], lo), 0.0, None)


def _assemble(values, rms: CarriageSetting, rfcms: CarriageSetting, dx_m: float, fixed_only: bool = False) -> _Parts:
    """The network's parts (:func:`two_carriage_network`), the ball contacts apart; ``fixed_only``: only
    what does not depend on the settings ``rms``, ``rfcms`` (:func:`two_carriage_rows` adds the rest per
    row: the bodies' convection at the air speed they see, the leaves, the ball contacts)."""
    from .. import convection
    from .network import rig_bodies

    v = values
    if not (math.isfinite(dx_m) and 0 < dx_m <= 0.05):
        raise ValueError(f"dx_m must be in (0, 0.05] m, got {dx_m!r}.")
    g = GuideGeometry.from_params(v)
    L_r, spacing = g.rail_length_m, float(v["carriage_spacing_m"])
    L, Lrow = g.block_length_m, g.row_length_m
    for name, setting in zip(STAGES, (rms, rfcms) if not fixed_only else ()):
        half = spacing / 2 + (L + setting.stroke_m) / 2
        if half > L_r / 2 + 1e-12:
            raise ValueError(f"the {name.upper()} carriage runs off the rail: centres {spacing:g} m apart on a "
                             f"{L_r:g} m rail with a {L:g} m block and a {setting.stroke_m:g} m stroke")
    if not fixed_only and spacing < L + (rms.stroke_m + rfcms.stroke_m) / 2 - 1e-12:
        raise ValueError(f"the two carriages collide: centres {spacing:g} m apart, blocks {L:g} m long, strokes "
                         f"{rms.stroke_m:g} and {rfcms.stroke_m:g} m")
    rho, lam, cp = g.body_properties()
    w, hr, H1, d, gap = g.rail_width_m, g.rail_height_m, g.block_clearance_m, g.ball_diameter_m, g.clearance_m
    W, M = g.block_width_m, g.block_height_m
    # ---- rail cells along the whole rail -------------------------------------------------
    n_r = max(2, int(math.ceil(L_r / dx_m - 1e-9)))
    edges = np.linspace(-L_r / 2, L_r / 2, n_r + 1)
    dx = np.diff(edges)
    A_r = w * hr
    h_room = convection.moving_coefficients(v, float(v["air_velocity_m_s"]))
    centres = {"rms": -spacing / 2, "rfcms": spacing / 2}
    cover = np.zeros(n_r)
    for st in STAGES:
        cover += _overlap(edges, centres[st] - L / 2, centres[st] + L / 2)
    g_rail_amb = h_room.h_side * ((w + 2 * hr) * (dx - cover) + 2 * H1 * cover)
    g_rail_amb[0] += h_room.h_side * A_r
    g_rail_amb[-1] += h_room.h_side * A_r
    # ---- contacts: both sides of each contact (the interface eliminated) -------------------
    ratio = float(v["guide_conductivity_w_mk"]) / float(v["ball_conductivity_w_mk"])  # G_r / G_b
    to_race = ratio / (1.0 + ratio)
    # ---- the nodes --------------------------------------------------------------------------
    names = [f"rail[{k}]" for k in range(n_r)]
    nodes: dict[str, int] = {}

    def add(name: str) -> int:
        names.append(name)
        nodes[name] = len(names) - 1
        return nodes[name]

    base = add("base")
    per = {}
    for st in STAGES:
        per[st] = [add(f"{st}.carriage"), add(f"{st}.balls"), add(f"{st}.frame")]
        if st == "rfcms":
            per[st].append(add(f"{st}.leaves"))
        per[st].append(add(f"{st}.stage"))
    n = len(names)
    K = np.zeros((n, n))
    K1 = np.zeros((n, n))  # the ball contacts' links per W/K of ball_contact_conductance_w_k
    C = np.zeros(n)
    g_amb = np.zeros(n)
    sources = {st: np.zeros(n) for st in STAGES}

    # fixed_only: the bodies whose diagonal a row changes start from 0 in K; the fixed terms added to
    # their diagonal are logged in their order, for each row to add them after its own loss
    logged: dict[int, list[float]] = ({i: [] for st in STAGES for i in (per[st][0], *per[st][2:])} if fixed_only
                                      else {})

    def link(i: int, j: int, G: float, mat: np.ndarray = K) -> None:
        for q in (i, j):
            if mat is K and q in logged:
                logged[q].append(G)
        mat[i, i] += G
        mat[j, j] += G
        mat[i, j] -= G
        mat[j, i] -= G

    def loss(i: int, G: float) -> None:
        K[i, i] += G
        g_amb[i] += G

    cells = np.arange(n_r)
    C[cells] = rho[4] * cp[4] * A_r * dx
    for k in range(n_r):
        loss(k, float(g_rail_amb[k]))
        link(k, base, float(v["joint_conductance_w_m2k"]) * w * float(dx[k]))
    for k in range(n_r - 1):
        link(k, k + 1, lam[4] * A_r / (0.5 * (dx[k] + dx[k + 1])))
    C[base] = float(v["base_heat_capacity_j_k"])
    loss(base, float(v["base_loss_conductance_w_k"]))
    # the carriage's faces (the same areas as the guide-only network)
    hb = M - H1
    chan_w, chan_h = w + 2 * gap, hr - H1 + gap
    area_side = W * L + 2 * hb * L + (W - chan_w) * L
    area_front = 2 * (W * hb - chan_w * chan_h)
    air_w = (w - 2 * d) + 2 * (hr - H1 - d)
    g_air_per_m = g.air_conductivity_w_mk * air_w / gap
    conv = {}
    for st, setting in zip(STAGES, (rms, rfcms)):
        u = float(convection.relative_air_speed(float(v["air_velocity_m_s"]), setting.mean_square_speed_m2_s2))
        hm = convection.moving_coefficients(v, u) if not fixed_only else h_room
        conv[st] = {"air_speed_m_s": u, "reynolds": hm.reynolds, "h_side_w_m2k": hm.h_side,
                   "h_front_w_m2k": hm.h_front}
        rigid = st == "rms"
        y_leaf = float(v["hinge_thickness_m"]) if rigid else setting.thickness_m
        bodies = rig_bodies(dict(v, ball_contact_conductance_w_k=1.0), y_leaf, rigid=rigid, h_side_w_m2k=hm.h_side)
        scale = hm.h_side / h_room.h_side  # the frame's and stage's losses are given at the room's air speed
        car, balls, frame = per[st][:3]
        stage = per[st][-1]
        C[car] = g.carriage_steel_volume_m3 * g.steel_density_kg_m3 * g.steel_specific_heat_j_kgk
        if not fixed_only:
            loss(car, hm.h_side * area_side + hm.h_front * area_front)
        C[balls] = g.ball_mass_kg * g.ball_specific_heat_j_kgk
        # ball contacts: carriage side
        if not fixed_only:
            link(car, balls, 1.0, K1)
        sources[st][car] += 0.5 * to_race
        sources[st][balls] += 0.5 * (1.0 - to_race) * 2.0  # both sides' ball shares
        # rail side, spread over the length the rows sweep
        reach = (Lrow + setting.stroke_m) / 2
        sweep = _overlap(edges, centres[st] - reach, centres[st] + reach)
        total = sweep[0]
        for x in sweep[1:]:  # in cell order (two_carriage_rows adds them in the same order)
            total += x
        share = sweep / total
        for cell in np.flatnonzero(share > 0).tolist() if not fixed_only else ():
            link(balls, cell, float(share[cell]), K1)
            sources[st][cell] += 0.5 * to_race * float(share[cell])
        # the clearance air under the block (at its mean position)
        foot = _overlap(edges, centres[st] - L / 2, centres[st] + L / 2)
        for cell in np.flatnonzero(foot > 0).tolist():
            link(car, cell, g_air_per_m * float(foot[cell]))
        # frame, leaves, stage
        C[frame] = bodies.frame_capacity_j_k
        if not fixed_only:
            loss(frame, bodies.frame_loss_w_k * scale)
        link(car, frame, bodies.frame_joint_w_k)
        C[stage] = bodies.stage_capacity_j_k
        if not fixed_only:
            loss(stage, bodies.stage_loss_w_k * scale)
        if rigid:
            link(frame, stage, bodies.frame_joint_w_k)
        elif not fixed_only:
            leaves = per[st][3]
            C[leaves] = bodies.leaf_capacity_j_k
            loss(leaves, bodies.leaf_loss_w_k)
            link(frame, leaves, 2.0 * bodies.leaf_w_k)  # the leaves' node at mid-length
            link(leaves, stage, 2.0 * bodies.leaf_w_k)
    for q in logged:
        K[q, q] = 0.0
    return _Parts(K, K1, C, sources, g_amb, nodes, cells, names, conv, {q: tuple(a) for q, a in logged.items()})


@dataclass(frozen=True)
class _Parts:
    """The network without the ball contacts (``k_rest``) and the contacts' links per W/K (``k_contact``)."""

    k_rest: np.ndarray
    k_contact: np.ndarray
    capacity: np.ndarray
    sources: dict
    g_ambient: np.ndarray
    nodes: dict
    rail_cells: np.ndarray
    names: list
    convection: dict
    diag_terms: dict  # fixed_only: node -> the fixed terms of its diagonal, in their order


def two_carriage_network(values, rms: CarriageSetting, rfcms: CarriageSetting, *,
                         dx_m: float = 1e-2) -> TwoCarriageNetwork:
    """Build the rig's network with both carriages (see the module docstring).

    Parameters
    ----------
    values : mapping
        A full :meth:`rsm_lrg.physics.params.LRGParams.to_dict` (``ball_contact_conductance_w_k``:
        the contacts of one side, ball centre to raceway body, both sides of each contact [W/K]).
    rms, rfcms : CarriageSetting
        How each stage runs (its leaves, stroke and speed).
    dx_m : float
        Rail cell length [m].

    Returns
    -------
    TwoCarriageNetwork

    Examples
    --------
    The heat balance closes (every watt leaves to the air or the room):

    >>> from rsm_lrg.physics.params import LRGParams
    >>> run = CarriageSetting(3e-4, 0.05, 0.2)
    >>> net = two_carriage_network(LRGParams().to_dict(), run, run)
    >>> abs(net.heat_balance("rfcms") - 1.0) < 1e-12
    True
    """
    g = float(values["ball_contact_conductance_w_k"])
    if not (math.isfinite(g) and g > 0):
        raise ValueError(f"ball_contact_conductance_w_k must be a positive number [W/K], got {g!r}")
    items = tuple(sorted((k, x) for k, x in dict(values).items() if k != "ball_contact_conductance_w_k"))
    parts = _parts_cached(items, rms, rfcms, float(dx_m))
    return TwoCarriageNetwork(parts.k_rest + g * parts.k_contact, parts.capacity, parts.sources, parts.g_ambient,
                              parts.nodes, parts.rail_cells, parts.names, parts.convection, g)


@lru_cache(maxsize=1024)
def _parts_cached(items: tuple, rms: CarriageSetting, rfcms: CarriageSetting, dx_m: float) -> _Parts:
    return _assemble(dict(items), rms, rfcms, dx_m)


def clear_network_cache() -> None:
    """Forget the networks' parts (:func:`cached_network`) and the rows' templates
    (:func:`two_carriage_rows`) built in this process (for a timing that starts from nothing)."""
    _parts_cached.cache_clear()
    _row_template.cache_clear()


def cached_network(values, rms: CarriageSetting, rfcms: CarriageSetting, *, dx_m: float = 1e-2) -> TwoCarriageNetwork:
    """:func:`two_carriage_network` (its parts but the ball contacts are cached per parameters and
    settings: a calibration asks for the same rows many times)."""
    return two_carriage_network(values, rms, rfcms, dx_m=dx_m)


class ContactInterpolant:
    """Outputs of the network as smooth functions of the ball contacts' conductance g, for a
    calibration that asks for the same rows at many g: a Chebyshev interpolant in ln g on
    ``[g_lo, g_hi]`` [W/K] through ``n`` points of the first kind.

    The network is linear in g (``K = K_0 + g·K_1``, :func:`two_carriage_network`), so each output
    is a rational function of g whose poles lie at g < 0; in ln g they are at least π from the real
    axis and the interpolant converges geometrically (1e-12 relative with 32 points over a factor
    of 12, tested against the network). ``fn(g)`` returns the outputs (a 1-D array) at one g.

    >>> f = ContactInterpolant(lambda g: np.array([1.0 / (1.0 + g)]), 0.1, 1.2)
    >>> bool(abs(f(0.5)[0] - 1 / 1.5) < 1e-13)
    True
    """

    def __init__(self, fn, g_lo: float, g_hi: float, n: int = 32):
        if not (0 < g_lo < g_hi and n >= 2):
            raise ValueError("ContactInterpolant needs 0 < g_lo < g_hi and n >= 2")
        self.g_lo, self.g_hi = float(g_lo), float(g_hi)
        self._a, self._b = math.log(self.g_lo), math.log(self.g_hi)
        x = np.cos(np.pi * (np.arange(n) + 0.5) / n)
        vals = np.array([np.asarray(fn(math.exp(0.5 * (self._a + self._b) + 0.5 * (self._b - self._a) * xi)), float)
                         for xi in x])
        self._coef = np.polynomial.chebyshev.chebfit(x, vals, n - 1)

    def covers(self, g: float) -> bool:
        """Whether ``g`` [W/K] lies in the interpolated range."""
        return self.g_lo <= g <= self.g_hi

    def __call__(self, g: float) -> np.ndarray:
        if not self.covers(g):
            raise ValueError(f"g = {g!r} W/K is outside the interpolated range [{self.g_lo}, {self.g_hi}]")
        x = (2.0 * math.log(g) - self._a - self._b) / (self._b - self._a)
        t = np.cos(np.arange(self._coef.shape[0]) * math.acos(min(1.0, max(-1.0, x))))  # T_k(x)
        return np.asarray(t @ self._coef, float)


# ----------------------------------------------------------------------------------------
# many rows in one compiled loop
# ----------------------------------------------------------------------------------------
@dataclass(frozen=True)
class _RowTemplate:
    """What every row of one rig shares (:func:`two_carriage_rows`): the network without the
    parts that change with the row, where those parts go, and the constants they are made of."""

    k_base: np.ndarray
    c_base: np.ndarray
    src_base: np.ndarray
    k_pos: np.ndarray  # see _row_patches
    s_pos: np.ndarray  # (2 n_r, 2): the rail cells' share of each stage's heat
    c_pos: np.ndarray  # (1,): the RFCMS's leaves
    carriage: tuple  # node of each stage's carriage (STAGES order)
    diag_terms: tuple  # per stage: the fixed terms of the diagonal of its carriage, frame and stage
    leaf_terms: tuple  # the fixed terms of the RFCMS's leaves
    edges: np.ndarray
    centres: tuple
    row_length_m: float
    block_length_m: float
    rail_length_m: float
    spacing_m: float
    to_race: float
    area_side_m2: float
    area_front_m2: float
    h_room_side: float
    frame_loss_w_k: float
    stage_loss_w_k: float
    leaf_area_m2: float  # n 2 w l: both faces of the leaves
    air: tuple  # the convection's air parameters (convection.AIR_PARAMETERS)


@lru_cache(maxsize=64)
def _row_template(items: tuple, dx_m: float) -> _RowTemplate:
    from .. import convection

    v = dict(items)
    dummy = CarriageSetting(float(v["hinge_thickness_m"]), 0.0, 0.0)  # its parts are left out
    parts = _assemble(v, dummy, dummy, dx_m, fixed_only=True)
    nd = parts.nodes
    n_r = len(parts.rail_cells)
    g = GuideGeometry.from_params(v)
    w, hr, H1, gap = g.rail_width_m, g.rail_height_m, g.block_clearance_m, g.clearance_m
    W, M, L = g.block_width_m, g.block_height_m, g.block_length_m
    hb = M - H1
    chan_w, chan_h = w + 2 * gap, hr - H1 + gap
    # the entries a row sets, in the order _row_patches makes them (each the same sum, in the same order, as
    # two_carriage_network's k_rest + g k_contact)
    pos = []
    for st in STAGES:  # the bodies' diagonals: their loss at the row's air speed, then their links
        pos += [(nd[f"{st}.carriage"],) * 2, (nd[f"{st}.frame"],) * 2, (nd[f"{st}.stage"],) * 2]
    fr, lv, sg = nd["rfcms.frame"], nd["rfcms.leaves"], nd["rfcms.stage"]
    pos += [(lv, lv), (fr, lv), (lv, sg)]  # the leaves: diagonal, links to the frame and the stage
    for st in STAGES:  # the ball contacts: carriage side
        car, b = nd[f"{st}.carriage"], nd[f"{st}.balls"]
        pos += [(car, car), (car, b), (b, b)]
    pos += [(cell, cell) for cell in range(n_r)]  # rail side
    spos = []
    for col, st in enumerate(STAGES):
        b = nd[f"{st}.balls"]
        pos += [(b, cell) for cell in range(n_r)]
        spos += [(cell, col) for cell in range(n_r)]
    L_r, spacing = g.rail_length_m, float(v["carriage_spacing_m"])
    ratio = float(v["guide_conductivity_w_mk"]) / float(v["ball_conductivity_w_mk"])
    h_room = convection.moving_coefficients(v, float(v["air_velocity_m_s"]))
    terms = parts.diag_terms
    return _RowTemplate(
        k_base=parts.k_rest, c_base=parts.capacity, src_base=np.stack([parts.sources[s] for s in STAGES], axis=1),
        k_pos=np.array(pos, dtype=np.int64), s_pos=np.array(spos, dtype=np.int64),
        c_pos=np.array([lv], dtype=np.int64), carriage=tuple(nd[f"{s}.carriage"] for s in STAGES),
        diag_terms=tuple(tuple(terms[nd[f"{st}.{body}"]] for body in ("carriage", "frame", "stage")) for st in STAGES),
        leaf_terms=terms[lv],
        edges=np.linspace(-L_r / 2, L_r / 2, n_r + 1), centres=(-spacing / 2, spacing / 2),
        row_length_m=g.row_length_m, block_length_m=L, rail_length_m=L_r, spacing_m=spacing,
        to_race=ratio / (1.0 + ratio),
        area_side_m2=W * L + 2 * hb * L + (W - chan_w) * L, area_front_m2=2 * (W * hb - chan_w * chan_h),
        h_room_side=h_room.h_side, frame_loss_w_k=float(v["stage_loss_conductance_w_k"]),
        stage_loss_w_k=float(v["stage_loss_conductance_w_k"]),
        leaf_area_m2=float(v["hinge_count"]) * 2.0 * float(v["hinge_width_m"]) * float(v["hinge_length_m"]),
        air=tuple(float(v[k]) for k in convection.AIR_PARAMETERS))


#: Parameters the two-carriage network reads besides the guide's geometry
#: (:class:`~.geometry.GuideGeometry`) and the air (:data:`rsm_lrg.physics.convection.AIR_PARAMETERS`).
_NETWORK_PARAMETERS = ("ball_conductivity_w_mk", "base_heat_capacity_j_k", "base_loss_conductance_w_k", "block_length_m",
                       "block_width_m", "carriage_spacing_m", "frame_mass_fraction", "guide_conductivity_w_mk",
                       "hinge_conductivity_w_mk", "hinge_count", "hinge_density_kg_m3", "hinge_length_m",
                       "hinge_specific_heat_j_kgk", "hinge_thickness_m", "hinge_width_m", "joint_conductance_w_m2k",
                       "stage_loss_conductance_w_k", "stage_mass_kg", "stage_specific_heat_j_kgk")


def network_items(values) -> tuple:
    """The ``(name, value)`` pairs of the parameters ``values`` that the two-carriage network reads
    but the ball contacts' conductance, sorted: rows whose parameters differ elsewhere (the motion,
    the friction, the wear) share one network template (:func:`two_carriage_rows`).

    Parameters
    ----------
    values : mapping
        A full :meth:`rsm_lrg.physics.params.LRGParams.to_dict` (or more).

    Returns
    -------
    tuple of (str, value)

    >>> from rsm_lrg.physics.params import LRGParams
    >>> names = dict(network_items(LRGParams().to_dict()))
    >>> "carriage_spacing_m" in names, "mu_k" in names, "ball_contact_conductance_w_k" in names
    (True, False, False)
    """
    from dataclasses import fields

    from .. import convection
    from .geometry import PARAM_ALIASES

    geo = {f.name for f in fields(GuideGeometry)}
    keep = set(_NETWORK_PARAMETERS) | set(convection.AIR_PARAMETERS)
    return tuple(sorted((k, x) for k, x in dict(values).items()
                        if (k in keep or PARAM_ALIASES.get(k, k) in geo) and k != "ball_contact_conductance_w_k"))


def _row_checks(tpl: _RowTemplate, y: np.ndarray, s: np.ndarray, msq: np.ndarray, re: np.ndarray,
                pr: float) -> tuple[int, str]:
    """The first row (from 0) that :func:`two_carriage_network` would refuse, and why; ``(-1, "")``
    where none is."""
    from .. import convection

    rows = y.shape[0]
    first, why = rows, ""
    for name, x in (("thickness_m", y), ("stroke_m", s), ("mean_square_speed_m2_s2", msq)):
        bad = np.flatnonzero(~(np.isfinite(x) & (x >= 0)))
        if bad.size and bad[0] < first:
            first, why = int(bad[0]), f"CarriageSetting.{name} must be a finite float >= 0, got {float(x[bad[0]])!r}"
    L, L_r, spacing = tpl.block_length_m, tpl.rail_length_m, tpl.spacing_m
    off = np.flatnonzero(spacing / 2 + (L + s) / 2 > L_r / 2 + 1e-12)
    if off.size and off[0] < first:
        first, why = int(off[0]), (f"the RMS carriage runs off the rail: centres {spacing:g} m apart on a {L_r:g} m "
                                   f"rail with a {L:g} m block and a {float(s[off[0]]):g} m stroke")
    hit = np.flatnonzero(spacing < L + (s + s) / 2 - 1e-12)
    if hit.size and hit[0] < first:
        first, why = int(hit[0]), (f"the two carriages collide: centres {spacing:g} m apart, blocks {L:g} m long, "
                                   f"strokes {float(s[hit[0]]):g} and {float(s[hit[0]]):g} m")
    out = np.flatnonzero(~((re < convection.PARALLEL_PLATE_RE_MAX) & (re * pr >= 0.2)))
    if out.size and out[0] < first:
        first, why = int(out[0]), (f"Re = {float(re[out[0]]):.4g} is outside the convection correlations' range "
                                   f"(laminar flat plate Re < {convection.PARALLEL_PLATE_RE_MAX:g}, "
                                   f"Churchill-Bernstein Re Pr >= 0.2)")
    return (first, why) if first < rows else (-1, "")


def two_carriage_rows(values, thickness_m, stroke_m, mean_square_speed_m2_s2, observed, times_s, *,
                      dx_m: float = 1e-2) -> tuple[np.ndarray, np.ndarray]:
    """The rise per watt of a working carriage for many rows of the rig, each row the network
    :func:`two_carriage_network` builds for it with both stages running its setting, in one
    compiled loop (no Python object per row).

    What does not change from row to row (the rail, the base, the joints, the clearance air, the
    heat capacities, the carriage-side sources) is assembled once per parameter set; each row adds
    what its setting changes: the convection of every body at the air speed it sees (``<v²>``), the
    RFCMS's leaves (thickness), the ball contacts spread over the rail cells the rows sweep (stroke)
    and their heat; then its ``C^(-1/2) K C^(-1/2)`` is decomposed on its own in a fixed order of
    operations (:func:`.fixed_order.patched_rows`). The numbers equal those of
    :func:`two_carriage_network` to rounding (1e-11 relative, tested) and a row's numbers do not
    depend on the other rows.

    Parameters
    ----------
    values : mapping
        A full :meth:`rsm_lrg.physics.params.LRGParams.to_dict`.
    thickness_m, stroke_m, mean_square_speed_m2_s2 : array (rows,)
        Each row's setting (:class:`CarriageSetting`) [m], [m], [m²/s²].
    observed : bool array (rows,)
        True: the RMS's carriage is observed (the RMS is the working stage); false: the RFCMS's.
    times_s : array (rows, m)
        Times after the heat step [s].
    dx_m : float
        Rail cell length [m].

    Returns
    -------
    resp : ndarray (rows, 2, m)
        Rise per watt [K/W] of the observed carriage at ``times_s`` of the friction power of the
        RMS and of the RFCMS (:data:`STAGES` order).
    steady : ndarray (rows, 2)
        The steady rises per watt [K/W].

    Raises :class:`.fixed_order.RowError` (a ``ValueError``) naming the first row (from 0) that
    :func:`two_carriage_network` would refuse or whose decomposition fails.

    Examples
    --------
    >>> from rsm_lrg.physics.params import LRGParams
    >>> v = LRGParams().to_dict()
    >>> resp, steady = two_carriage_rows(v, [3e-4], [0.05], [0.2], [False], [[3000.0]])
    >>> net = two_carriage_network(v, *(CarriageSetting(3e-4, 0.05, 0.2),) * 2)
    >>> bool(abs(resp[0, 1, 0] / net.response([3000.0], "rfcms.carriage", "rfcms")[0] - 1) < 1e-11)
    True
    """
    from .. import convection
    from .fixed_order import RowError, patched_rows
    from .network import leaf_terms

    gk = float(values["ball_contact_conductance_w_k"])
    if not (math.isfinite(gk) and gk > 0):
        raise ValueError(f"ball_contact_conductance_w_k must be a positive number [W/K], got {gk!r}")
    if not (math.isfinite(dx_m) and 0 < dx_m <= 0.05):
        raise ValueError(f"dx_m must be in (0, 0.05] m, got {dx_m!r}.")
    t = np.atleast_2d(np.asarray(times_s, float))
    rows = t.shape[0]
    y, s, msq = (np.ascontiguousarray(np.broadcast_to(np.asarray(q, float), (rows,)))
                 for q in (thickness_m, stroke_m, mean_square_speed_m2_s2))
    obs = np.broadcast_to(np.asarray(observed, bool), (rows,))
    tpl = _row_template(network_items(values), float(dx_m))  # only these: a parameter missed fails loudly
    air_speed, lc, nu, eta, lam, cp = tpl.air
    with np.errstate(invalid="ignore"):
        u = convection.relative_air_speed(air_speed, msq)
        re = np.asarray(convection.reynolds(u, lc, nu), float)
    pr = float(convection.prandtl(cp, eta, lam))
    bad, why = _row_checks(tpl, y, s, msq, re, pr)
    ok = rows if bad < 0 else bad  # the rows before the first refused one are still solved: an earlier
    y, s, msq, re, t = y[:ok], s[:ok], msq[:ok], re[:ok], t[:ok]  # failing decomposition is named first
    k_add, c_add, s_add = _row_patches(tpl, gk, y, s, re, pr, lam, lc, leaf_terms(values, y))
    node = np.where(obs[:ok], tpl.carriage[0], tpl.carriage[1])
    resp, steady = patched_rows(tpl.k_base, tpl.c_base, tpl.src_base, tpl.k_pos, k_add, tpl.c_pos, c_add,
                                tpl.s_pos, s_add, node, t)  # a RowError here names a row before ``bad``
    if bad >= 0:
        raise RowError(bad, why)
    return resp, steady


def _row_patches(tpl: _RowTemplate, gk: float, y, s, re, pr: float, lam: float, lc: float, leaf):
    """Each row's entries of the network (the positions of :class:`_RowTemplate`): every one the
    same sum, in the same order, as :func:`two_carriage_network` makes it (``k_rest + g k_contact``),
    so each row's matrix is that network's to the last bit."""
    from .. import convection

    rows = y.shape[0]
    hs = np.asarray(convection.heat_transfer_coefficient(convection.nusselt_parallel_plate(re, pr), lam, lc), float)
    hf = np.asarray(convection.heat_transfer_coefficient(convection.nusselt_cross_flow(re, pr), lam, lc), float)
    hs, hf = np.broadcast_to(hs, (rows,)), np.broadcast_to(hf, (rows,))
    scale = hs / tpl.h_room_side  # the frame's and stage's losses are given at the room's air speed
    g_leaf, c_leaf = (np.broadcast_to(np.asarray(q, float), (rows,)) for q in leaf)
    two = 2.0 * g_leaf

    def summed(first, fixed, *row_terms):
        out = np.array(first, float, copy=True)
        for t in fixed:
            out += t
        for t in row_terms:
            out += t
        return out

    cols = []
    for k, (car, frame, stage) in enumerate(tpl.diag_terms):
        rigid = STAGES[k] == "rms"
        cols += [summed(hs * tpl.area_side_m2 + hf * tpl.area_front_m2, car),
                 summed(tpl.frame_loss_w_k * scale, frame, *(() if rigid else (two,))),
                 summed(tpl.stage_loss_w_k * scale, stage, *(() if rigid else (two,)))]
    cols += [summed(tpl.leaf_area_m2 * hs, tpl.leaf_terms, two, two), -two, -two]
    edges = tpl.edges
    n_r = edges.size - 1
    shares = []
    for centre in tpl.centres:
        reach = (tpl.row_length_m + s) / 2
        lo, hi = (centre - reach)[:, None], (centre + reach)[:, None]
        sweep = np.clip(np.minimum(edges[None, 1:], hi) - np.maximum(edges[None, :-1], lo), 0.0, None)
        total = sweep[:, 0].copy()
        for k in range(1, n_r):  # in cell order, as two_carriage_network; a row's share is its own
            total += sweep[:, k]
        share = sweep / total[:, None]
        kb = np.ones(rows)  # the balls' contact links: the carriage side (1), then the cells in order
        for k in range(n_r):
            kb += share[:, k]
        shares.append(share)
        cols += [np.full(rows, gk), np.full(rows, -gk), gk * kb]
    cell = shares[0] + shares[1]  # 0 + the RMS's share + the RFCMS's (each cell's, in stage order)
    cols += [gk * cell[:, k] for k in range(n_r)]
    for share in shares:
        cols += [gk * -share[:, k] for k in range(n_r)]
    s_add = np.concatenate([0.5 * tpl.to_race * share for share in shares], axis=1)
    k_add = np.stack([np.broadcast_to(np.asarray(c, float), (rows,)) for c in cols], axis=1)
    return k_add, c_leaf[:, None].copy(), np.ascontiguousarray(s_add)
