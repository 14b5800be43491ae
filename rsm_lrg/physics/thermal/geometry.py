"""Geometry and materials of the THK SHS15V linear rolling guide, and its voxelisation.

Coordinates: ``x`` along the rail, ``y`` across it, ``z`` up from the rail's bottom (the
mounting face).  The carriage is centred on the rail at ``x = 0``.

Every number below is either

* **catalogue** - THK SHS15V block and SHS15 rail (as quoted in issue 3 of this project:
  block 34 mm wide x 64.4 mm long, 24 mm high over the rail base, 0.19 kg; rail
  15 mm x 13 mm, 1.3 kg/m),
* **paper** - Su, Zhang & Yang (2023), Table 1 (ball radius 1.3497 mm, 18 balls per row,
  4 rows) and Table 2 (GCr15 rail/carriage 7830 kg/m^3, 44 W/(m K), 460 J/(kg K); 40Cr
  balls 7870, 44, 460), Section 2.2 (air: lambda 0.0263 W/(m K), c 1005 J/(kg K),
  eta 18.4e-6 Pa s, nu 15.5e-6 m^2/s),
* **derived** - computed from the two above (carriage clearance around the rail from the
  catalogue mass, rail fill fraction from the catalogue rail mass), or
* **ASSUMPTION** - a value neither source gives, chosen and justified here; each one is
  listed in :data:`ASSUMPTIONS` and in the final report of the thermal work.

The simplified carriage (the paper's FEM also removed holes and fillets, Section 3.1) is an
inverted channel ("U") of the catalogue envelope (34 mm x 19.7 mm x 64.4 mm) wrapping the
rail head with a uniform clearance ``g``; ``g`` is *derived* so that the steel volume times
7830 kg/m^3 equals the catalogue block mass less the balls.  The four ball rows are the
heat-source volumes (Eq. 9): strips one ball diameter wide, bridging the clearance between
the carriage and the rail at the four raceways, 18 ball diameters long.  The rest of the
clearance is still air (conduction only).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import asdict, dataclass, field, fields, replace
from typing import Any

import numpy as np

__all__ = [
    "GuideGeometry",
    "VoxelModel",
    "voxelise",
    "ASSUMPTIONS",
    "AMBIENT",
    "CARRIAGE",
    "BALLS",
    "GAP",
    "RAIL",
    "BODY_NAMES",
    "graded_cells",
    "PARAM_ALIASES",
]

#: :class:`rsm_lrg.physics.params.LRGParams` name -> :class:`GuideGeometry` field, where the
#: names differ (every other shared name is the same in both).
PARAM_ALIASES = {
    "ball_rows": "n_rows", "carriage_mass_kg": "block_mass_kg",
    "guide_density_kg_m3": "steel_density_kg_m3", "guide_conductivity_w_mk": "steel_conductivity_w_mk",
    "guide_specific_heat_j_kgk": "steel_specific_heat_j_kgk",
}

# Body codes used in the voxel array (0 = surrounding air, not part of the solution).
AMBIENT, CARRIAGE, BALLS, GAP, RAIL = 0, 1, 2, 3, 4
BODY_NAMES = {AMBIENT: "ambient", CARRIAGE: "carriage", BALLS: "balls", GAP: "gap", RAIL: "rail"}

#: Face directions, in the order used by every ``h`` table: -x, +x, -y, +y, -z, +z.
DIRECTIONS = ("-x", "+x", "-y", "+y", "-z", "+z")

ASSUMPTIONS = {
    "rail_length_m": (
        "0.4 m, carriage centred. The rig (Section 4.1) runs two stages on one rail with "
        "strokes up to 0.075 m; two 64.4 mm blocks plus their strokes need >= 0.28 m, and "
        "0.4 m is a THK standard length (160 + 4 x 60 mm). The paper's FEM (one carriage) "
        "does not state it. Longer rail -> lower rise (fin effect saturates near 0.5 m)."
    ),
    "block_clearance_m": (
        "4.3 mm between the carriage underside and the rail's mounting face (THK catalogue "
        "dimension H1 for size 15, quoted from memory, not from the paper or the issue)."
    ),
    "carriage_section": (
        "Inverted-U carriage of the catalogue envelope; uniform clearance around the rail "
        "head derived from the catalogue mass (the real block's missing steel is in return "
        "holes, end plates and reliefs)."
    ),
    "ball_rows": (
        "Four strips (one ball diameter x clearance x 18 ball diameters) at the raceways: two "
        "on the rail head top at its edges, two on its sides centred 4 mm below the top "
        "(position ASSUMED; with a near-isothermal carriage it hardly matters). Heat "
        "capacity = the real balls' (homogenised density), source Q spread uniformly (Eq. 9)."
    ),
    "ball_row_conductivity_w_mk": (
        "44 W/(m K) (40Cr, Table 2): perfect ball-raceway thermal contact, as ANSYS "
        "'frictional' contact with program-controlled conductance gives in the paper's FEM. "
        "Hertzian point contacts (a ~ 0.1 mm) would give ~2.5 W/(m K) effective: a larger "
        "ball/raceway temperature and a slightly higher carriage rise."
    ),
    "rail_fill": (
        "Rail modelled as its 15 x 13 mm rectangle with density and conductivity scaled by "
        "the fill fraction (1.3 kg/m) / (7830 kg/m^3 x 15 mm x 13 mm) = 0.851 (raceway "
        "grooves, bolt holes)."
    ),
    "h_rail_w_m2k": (
        "Exposed rail faces (top, sides, ends) use the paper's h for horizontal and side "
        "faces (Eq. 11, 8.82 W/(m^2 K)): Section 2.2 applies it to the 'horizontal and side "
        "surfaces of the LRG'. Natural convection (Churchill-Chu, dT ~ 3 K) would give "
        "~6 W/(m^2 K); radiation is neglected as in the paper."
    ),
    "h_base_w_m2k": (
        "Rail bottom adiabatic (0): the paper's FEM contains only carriage, rail and balls; "
        "a bolted base would add a heat path and lower the rise."
    ),
    "gap_air": (
        "Clearance not occupied by balls: still air, conduction only (lambda 0.0263 W/(m K), "
        "rho = eta/nu = 1.187 kg/m^3, c 1005 J/(kg K), Section 2.2), no convection."
    ),
    "carriage_faces": (
        "Top, side and underside (skirt) faces: h_side (Eq. 11, 'horizontal and side "
        "surfaces'); front/back faces: h_front (Eq. 12)."
    ),
    "thermocouples": (
        "Two thermocouples on the +y side face of the carriage at mid-height of the block "
        "side, x = -L/4 and +L/4 (Section 4.1: 'mounted on the side of the slide carriage', "
        "averaged); the reading is the temperature of the surface cell."
    ),
}


@dataclass(frozen=True)
class GuideGeometry:
    """Dimensions [m], masses [kg] and materials of the SHS15V guide (see module docstring).

    Parameters
    ----------
    block_width_m, block_length_m : float
        Catalogue block width W = 0.034 m and length L = 0.0644 m.
    block_height_m : float
        Catalogue overall height M = 0.024 m (rail bottom to block top).
    block_clearance_m : float
        Underside of the block above the rail bottom (ASSUMPTION, 4.3 mm).
    block_mass_kg : float
        Catalogue block mass 0.19 kg (includes the balls).
    rail_width_m, rail_height_m : float
        Catalogue rail section 0.015 m x 0.013 m.
    rail_mass_kg_per_m : float
        Catalogue rail mass 1.3 kg/m.
    rail_length_m : float
        Rail length (ASSUMPTION, 0.4 m).
    n_rows, balls_per_row, ball_radius_m : int, int, float
        Paper Table 1: 4 rows, 18 balls, 1.3497 mm.
    lower_row_depth_m : float
        Depth of the lower (side) ball rows' centre below the rail top (ASSUMPTION, 4 mm).
    steel_* , ball_* , air_* : float
        Table 2 and Section 2.2 properties (rho [kg/m^3], lambda [W/(m K)], c [J/(kg K)]).
    ball_row_conductivity_w_mk : float
        Effective conductivity of the ball rows (ASSUMPTION, 44 = perfect contact).
    thermocouple_x_m : tuple of float
        x of the thermocouples on the +y side face (ASSUMPTION, +-L/4).
    """

    block_width_m: float = 0.034
    block_length_m: float = 0.0644
    block_height_m: float = 0.024
    block_clearance_m: float = 0.0043
    block_mass_kg: float = 0.19
    rail_width_m: float = 0.015
    rail_height_m: float = 0.013
    rail_mass_kg_per_m: float = 1.3
    rail_length_m: float = 0.4
    n_rows: int = 4
    balls_per_row: int = 18
    ball_radius_m: float = 1.3497e-3
    lower_row_depth_m: float = 0.004
    steel_density_kg_m3: float = 7830.0
    steel_conductivity_w_mk: float = 44.0
    steel_specific_heat_j_kgk: float = 460.0
    ball_density_kg_m3: float = 7870.0
    ball_conductivity_w_mk: float = 44.0
    ball_specific_heat_j_kgk: float = 460.0
    ball_row_conductivity_w_mk: float = 44.0
    air_conductivity_w_mk: float = 0.0263
    air_density_kg_m3: float = 18.4e-6 / 15.5e-6
    air_specific_heat_j_kgk: float = 1005.0
    thermocouple_x_m: tuple = (-0.0644 / 4, 0.0644 / 4)

    def __post_init__(self):
        for f in fields(self):
            v = getattr(self, f.name)
            if f.name == "thermocouple_x_m":
                if len(v) == 0:
                    raise ValueError("thermocouple_x_m must list at least one position [m].")
                for xv in v:
                    if not math.isfinite(float(xv)) or abs(float(xv)) > self.block_length_m / 2:
                        raise ValueError(
                            f"thermocouple_x_m={xv!r} must lie on the carriage side face "
                            f"(|x| <= {self.block_length_m / 2} m)."
                        )
                continue
            if not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0:
                raise ValueError(f"{f.name} must be a positive finite number, got {v!r}.")
        if self.n_rows != 4:
            raise ValueError("n_rows must be 4 (the SHS guide has four ball rows).")
        if self.rail_height_m >= self.block_height_m or self.block_clearance_m >= self.rail_height_m:
            raise ValueError(
                "need block_clearance_m < rail_height_m < block_height_m "
                f"(got {self.block_clearance_m}, {self.rail_height_m}, {self.block_height_m})."
            )
        if self.rail_length_m < self.block_length_m:
            raise ValueError(
                f"rail_length_m={self.rail_length_m} must be at least the block length "
                f"{self.block_length_m} m."
            )
        if self.row_length_m > self.block_length_m:
            raise ValueError("the ball rows (balls_per_row x ball diameter) are longer than the block.")
        if self.rail_fill > 1.0 + 1e-12:
            raise ValueError("rail_mass_kg_per_m exceeds a solid rail of rail_width_m x rail_height_m.")
        g = self.clearance_m  # raises if the mass cannot be matched
        if self.lower_row_depth_m + self.ball_diameter_m / 2 > self.rail_height_m - self.block_clearance_m:
            raise ValueError("lower_row_depth_m puts the lower ball rows below the carriage.")
        if 2 * self.ball_diameter_m > self.rail_width_m or g <= 0:
            raise ValueError("ball rows do not fit on the rail head.")

    # ----------------------------------------------------------------- derived numbers
    @property
    def ball_diameter_m(self) -> float:
        return 2.0 * self.ball_radius_m

    @property
    def row_length_m(self) -> float:
        """Loaded ball row length: balls_per_row touching balls [m]."""
        return self.balls_per_row * self.ball_diameter_m

    @property
    def ball_volume_m3(self) -> float:
        """Total ball volume V_t of Eq. 9 [m^3] (4 x 18 balls: 7.415e-7)."""
        return self.n_rows * self.balls_per_row * 4.0 / 3.0 * math.pi * self.ball_radius_m**3

    @property
    def ball_mass_kg(self) -> float:
        return self.ball_volume_m3 * self.ball_density_kg_m3

    @property
    def rail_fill(self) -> float:
        """Fill fraction of the rail rectangle (derived from the catalogue 1.3 kg/m)."""
        return self.rail_mass_kg_per_m / (
            self.steel_density_kg_m3 * self.rail_width_m * self.rail_height_m
        )

    @property
    def carriage_steel_volume_m3(self) -> float:
        """Steel volume of the carriage: (catalogue mass - balls) / rho [m^3]."""
        return (self.block_mass_kg - self.ball_mass_kg) / self.steel_density_kg_m3

    @property
    def clearance_m(self) -> float:
        """Uniform clearance g between the channel and the rail head [m] (derived).

        Solves ``W*(M-H1) - (w + 2g)*(h - H1 + g) = V_steel / L`` for g.
        """
        W, L = self.block_width_m, self.block_length_m
        hb = self.block_height_m - self.block_clearance_m
        d = self.rail_height_m - self.block_clearance_m
        w = self.rail_width_m
        channel = W * hb - self.carriage_steel_volume_m3 / L
        # (w + 2g)(d + g) = channel  ->  2g^2 + (w + 2d) g + w d - channel = 0
        a, b, c = 2.0, w + 2 * d, w * d - channel
        disc = b * b - 4 * a * c
        if channel <= w * d or disc < 0:
            raise ValueError(
                f"block_mass_kg (carriage_mass_kg) {self.block_mass_kg:g} kg is too large for the block "
                "envelope: the carriage cannot wrap the rail (no positive clearance matches the mass)."
            )
        g = (-b + math.sqrt(disc)) / (2 * a)
        if w + 2 * g >= W or self.rail_height_m + g >= self.block_height_m:
            raise ValueError(
                f"block_mass_kg (carriage_mass_kg) {self.block_mass_kg:g} kg is too small for the block "
                f"envelope: the derived clearance ({g * 1e3:.2f} mm) leaves no carriage wall."
            )
        return g

    @property
    def thermocouple_z_m(self) -> float:
        """Mid-height of the carriage side face [m] (ASSUMPTION)."""
        return 0.5 * (self.block_clearance_m + self.block_height_m)

    @staticmethod
    def fields_from_params(values: Mapping[str, Any]) -> dict:
        """The :class:`GuideGeometry` keyword arguments among physical parameters.

        ``values`` is a mapping of :class:`~rsm_lrg.physics.params.LRGParams` names (e.g.
        ``LRGParams().to_dict()``); names are mapped by :data:`PARAM_ALIASES`, integer fields
        are cast to int, and parameters the geometry does not use are left out.

        >>> from rsm_lrg.physics.params import LRGParams
        >>> kw = GuideGeometry.fields_from_params(LRGParams().to_dict())
        >>> kw["n_rows"], kw["block_mass_kg"], "mu_k" in kw
        (4, 0.19, False)
        """
        out = {}
        by_name = {f.name: f for f in fields(GuideGeometry)}
        for name, value in dict(values).items():
            target = PARAM_ALIASES.get(name, name)
            f = by_name.get(target)
            if f is None or target == "thermocouple_x_m":
                continue
            out[target] = int(value) if f.type in ("int", int) else float(value)
        return out

    @classmethod
    def from_params(cls, values, **overrides) -> GuideGeometry:
        """The geometry of a parameter set (:meth:`fields_from_params`), then ``overrides``."""
        return cls(**{**cls.fields_from_params(values), **overrides})

    def with_(self, **overrides) -> GuideGeometry:
        """Return a copy with some fields replaced (unknown names raise ValueError)."""
        names = {f.name for f in fields(self)}
        bad = sorted(set(overrides) - names)
        if bad:
            raise ValueError(f"unknown geometry parameter(s) {bad}; known: {sorted(names)}")
        return replace(self, **overrides)

    def to_dict(self) -> dict:
        d = asdict(self)
        d["thermocouple_x_m"] = list(self.thermocouple_x_m)
        d.update(
            clearance_m=self.clearance_m,
            rail_fill=self.rail_fill,
            ball_volume_m3=self.ball_volume_m3,
            row_length_m=self.row_length_m,
        )
        return d

    # ----------------------------------------------------------------- the solid boxes
    def boxes(self):
        """Axis-aligned boxes ``(body, (x0, x1), (y0, y1), (z0, z1))`` in painting order.

        Later boxes overwrite earlier ones: carriage envelope, channel (air gap), rail,
        ball rows.
        """
        W, L, M, H1 = self.block_width_m, self.block_length_m, self.block_height_m, self.block_clearance_m
        w, h, Lr = self.rail_width_m, self.rail_height_m, self.rail_length_m
        g, d, Lrow = self.clearance_m, self.ball_diameter_m, self.row_length_m
        zl = h - self.lower_row_depth_m
        out = [
            (CARRIAGE, (-L / 2, L / 2), (-W / 2, W / 2), (H1, M)),
            (GAP, (-L / 2, L / 2), (-w / 2 - g, w / 2 + g), (H1, h + g)),
            (RAIL, (-Lr / 2, Lr / 2), (-w / 2, w / 2), (0.0, h)),
            # upper rows: on the rail head top, at its two edges
            (BALLS, (-Lrow / 2, Lrow / 2), (-w / 2, -w / 2 + d), (h, h + g)),
            (BALLS, (-Lrow / 2, Lrow / 2), (w / 2 - d, w / 2), (h, h + g)),
            # lower rows: on the rail sides
            (BALLS, (-Lrow / 2, Lrow / 2), (-w / 2 - g, -w / 2), (zl - d / 2, zl + d / 2)),
            (BALLS, (-Lrow / 2, Lrow / 2), (w / 2, w / 2 + g), (zl - d / 2, zl + d / 2)),
        ]
        return out

    def body_properties(self):
        """Per-body (rho [kg/m^3], lambda [W/(m K)], c [J/(kg K)]) arrays indexed by body code.

        Ball rows: density homogenised so that the strips hold the real balls' mass.
        Rail: density and conductivity times the fill fraction.
        """
        strip_volume = self.ball_strip_volume_m3
        rho = np.zeros(5)
        lam = np.zeros(5)
        cp = np.zeros(5)
        rho[CARRIAGE], lam[CARRIAGE], cp[CARRIAGE] = (
            self.steel_density_kg_m3, self.steel_conductivity_w_mk, self.steel_specific_heat_j_kgk)
        rho[BALLS] = self.ball_density_kg_m3 * self.ball_volume_m3 / strip_volume
        lam[BALLS], cp[BALLS] = self.ball_row_conductivity_w_mk, self.ball_specific_heat_j_kgk
        rho[GAP], lam[GAP], cp[GAP] = (
            self.air_density_kg_m3, self.air_conductivity_w_mk, self.air_specific_heat_j_kgk)
        phi = self.rail_fill
        rho[RAIL], lam[RAIL], cp[RAIL] = (
            phi * self.steel_density_kg_m3, phi * self.steel_conductivity_w_mk,
            self.steel_specific_heat_j_kgk)
        return rho, lam, cp

    @property
    def ball_strip_volume_m3(self) -> float:
        """Volume of the four ball-row strips (the FV source volume) [m^3]."""
        return self.n_rows * self.ball_diameter_m * self.clearance_m * self.row_length_m

    def breakpoints(self):
        """Sorted unique box edges per axis (the grid conforms to all of them)."""
        xs, ys, zs = set(), set(), set()
        for _, (x0, x1), (y0, y1), (z0, z1) in self.boxes():
            xs.update((x0, x1))
            ys.update((y0, y1))
            zs.update((z0, z1))
        r = lambda s: np.array(sorted({round(v, 12) for v in s}))  # noqa: E731
        return r(xs), r(ys), r(zs)


def graded_cells(length: float, h0: float, ratio: float, hmax: float) -> np.ndarray:
    """Cell sizes filling ``length`` [m], starting at ``h0`` and growing by ``ratio`` up to ``hmax``.

    The sizes are rescaled so that they sum exactly to ``length``.
    """
    if length <= 0:
        return np.zeros(0)
    sizes = []
    s, total = h0, 0.0
    while total + s < length - 1e-15:
        sizes.append(s)
        total += s
        s = min(s * ratio, hmax)
    if not sizes:
        return np.array([length])
    rest = length - total
    if rest < 0.5 * sizes[-1]:
        sizes[-1] += rest
    else:
        sizes.append(rest)
    a = np.array(sizes)
    return a * (length / a.sum())


def _axis_cells(points, h, graded_from=None, ratio=1.2, hmax=None):
    """Cell edges through all ``points``; every interval split into ceil(len/h) equal cells.

    ``graded_from``: set of interval indices to grade (fine next to the carriage, coarse at
    the rail ends); ``(index, side)`` pairs say at which end the fine cells are.
    """
    edges = [points[0]]
    graded_from = dict(graded_from or {})
    for i in range(len(points) - 1):
        a, b = points[i], points[i + 1]
        ln = b - a
        if i in graded_from and hmax is not None and hmax > h:
            sizes = graded_cells(ln, h, ratio, hmax)
            if graded_from[i] == "right":  # fine cells at the right end
                sizes = sizes[::-1]
        else:
            n = max(1, int(math.ceil(ln / h - 1e-9)))
            sizes = np.full(n, ln / n)
        edges.extend(a + np.cumsum(sizes))
        edges[-1] = b
    return np.asarray(edges)


@dataclass(frozen=True)
class VoxelModel:
    """A structured (tensor-product) grid with one body code per cell.

    Attributes
    ----------
    x_edges, y_edges, z_edges : ndarray
        Cell edges [m] along each axis.
    body : ndarray of int, shape (nx, ny, nz)
        Body code per cell; 0 = ambient (not solved).
    rho, lam, cp : ndarray
        Density [kg/m^3], conductivity [W/(m K)], specific heat [J/(kg K)] per body code.
    h_table : ndarray, shape (n_bodies, 6)
        Convection coefficient [W/(m^2 K)] on a face of a cell of body ``b`` that looks
        onto ambient in direction -x, +x, -y, +y, -z, +z (domain borders count as ambient).
    source_body : int
        Body whose cells carry the heat source (uniform per volume, Eq. 9).
    probes : tuple of (x, y, z)
        Points [m] whose containing cells are reported (thermocouples).
    mirror_faces : tuple of int
        Directions (0..5 as in :data:`DIRECTIONS`) whose domain border is a symmetry plane
        (adiabatic); the full body is ``2 ** len(mirror_faces)`` copies of the grid.
    """

    x_edges: np.ndarray
    y_edges: np.ndarray
    z_edges: np.ndarray
    body: np.ndarray
    rho: np.ndarray
    lam: np.ndarray
    cp: np.ndarray
    h_table: np.ndarray
    source_body: int
    probes: tuple = field(default_factory=tuple)
    mirror_faces: tuple = ()

    @property
    def copies(self) -> int:
        """How many mirror copies of the grid make the whole body."""
        return 2 ** len(self.mirror_faces)

    @property
    def shape(self):
        return self.body.shape

    @property
    def n_active(self) -> int:
        return int(np.count_nonzero(self.body))

    def cell_index(self, point):
        """(i, j, k) of the cell containing ``point`` [m]."""
        idx = []
        for e, p in zip((self.x_edges, self.y_edges, self.z_edges), point):
            if p < e[0] - 1e-12 or p > e[-1] + 1e-12:
                raise ValueError(f"probe point {point} lies outside the grid.")
            idx.append(int(np.clip(np.searchsorted(e, p, side="right") - 1, 0, len(e) - 2)))
        return tuple(idx)


#: Most cells (of the bounding grid, solid or not) of the 3-D model: 1 mm cells on the
#: SHS15V (about 5e4) solve in a few seconds; far more would run for minutes.
MAX_FV_CELLS = 150_000


def voxelise(
    geometry: GuideGeometry,
    h_side_w_m2k: float,
    h_front_w_m2k: float,
    *,
    h_rail_w_m2k: float | None = None,
    h_base_w_m2k: float = 0.0,
    cell_size_m: float = 2e-3,
    rail_cell_max_m: float = 0.01,
    growth: float = 1.2,
    symmetric: bool = True,
) -> VoxelModel:
    """Voxelise the guide on a grid conforming to every edge of :meth:`GuideGeometry.boxes`.

    Parameters
    ----------
    geometry : GuideGeometry
    h_side_w_m2k, h_front_w_m2k : float
        Eq. 11 (top/side/underside faces of the carriage) and Eq. 12 (front/back faces)
        convection coefficients [W/(m^2 K)].
    h_rail_w_m2k : float, optional
        Exposed rail faces [W/(m^2 K)]; default ``h_side_w_m2k`` (ASSUMPTION, see
        :data:`ASSUMPTIONS`).
    h_base_w_m2k : float
        Rail bottom face [W/(m^2 K)]; default 0 = adiabatic (ASSUMPTION).
    cell_size_m : float
        Largest cell edge [m] in the carriage region.
    rail_cell_max_m : float
        Largest cell along the rail away from the carriage [m] (cells grow by ``growth``).
    symmetric : bool
        Solve one quarter (x >= 0, y >= 0) with adiabatic symmetry planes x = 0 and y = 0
        (the geometry, the loads and the boundary conditions are symmetric in both); the
        thermocouple at -x reads the same as its mirror.
    """
    for name, v in (("h_side_w_m2k", h_side_w_m2k), ("h_front_w_m2k", h_front_w_m2k),
                    ("h_base_w_m2k", h_base_w_m2k)):
        if not math.isfinite(v) or v < 0:
            raise ValueError(f"{name} must be a finite number >= 0 [W/(m^2 K)], got {v!r}.")
    if h_rail_w_m2k is None:
        h_rail_w_m2k = h_side_w_m2k
    if not math.isfinite(h_rail_w_m2k) or h_rail_w_m2k < 0:
        raise ValueError(f"h_rail_w_m2k must be a finite number >= 0, got {h_rail_w_m2k!r}.")
    if not (math.isfinite(cell_size_m) and 0 < cell_size_m <= 0.01):
        raise ValueError(f"cell_size_m must be in (0, 0.01] m, got {cell_size_m!r}.")
    if not growth >= 1.0:
        raise ValueError(f"growth must be >= 1, got {growth!r}.")
    xb, yb, zb = geometry.breakpoints()
    if symmetric:
        xb = np.concatenate([[0.0], xb[xb > 1e-12]])
        yb = np.concatenate([[0.0], yb[yb > 1e-12]])
        graded = {len(xb) - 2: "left"}
    else:
        # the first and last x intervals are bare rail: grade them
        graded = {0: "right", len(xb) - 2: "left"}
    xe = _axis_cells(xb, cell_size_m, graded, growth, max(rail_cell_max_m, cell_size_m))
    ye = _axis_cells(yb, cell_size_m)
    ze = _axis_cells(zb, cell_size_m)
    n_box = (len(xe) - 1) * (len(ye) - 1) * (len(ze) - 1)
    if n_box > MAX_FV_CELLS:  # refused before anything of that size is allocated
        raise ValueError(f"the 3-D thermal model would need {n_box} cells (limit {MAX_FV_CELLS}) with "
                         f"cell_size_m={cell_size_m:g}: the guide is too large for it (block "
                         f"{geometry.block_length_m:g} x {geometry.block_width_m:g} x {geometry.block_height_m:g} m, "
                         f"rail {geometry.rail_length_m:g} m)")
    xc, yc, zc = 0.5 * (xe[1:] + xe[:-1]), 0.5 * (ye[1:] + ye[:-1]), 0.5 * (ze[1:] + ze[:-1])
    body = np.zeros((len(xc), len(yc), len(zc)), dtype=np.int8)
    for code, (x0, x1), (y0, y1), (z0, z1) in geometry.boxes():
        mx = (xc > x0) & (xc < x1)
        my = (yc > y0) & (yc < y1)
        mz = (zc > z0) & (zc < z1)
        body[np.ix_(mx, my, mz)] = code
    rho, lam, cp = geometry.body_properties()
    h = np.zeros((5, 6))
    h[CARRIAGE] = [h_front_w_m2k, h_front_w_m2k, h_side_w_m2k, h_side_w_m2k, h_side_w_m2k, h_side_w_m2k]
    # ball-row ends are inside the end plates in reality; they never touch ambient here
    h[BALLS] = h[CARRIAGE]
    h[RAIL] = [h_rail_w_m2k] * 4 + [h_base_w_m2k, h_rail_w_m2k]
    eps = 1e-9
    probes = tuple(
        (abs(float(x)) if symmetric else float(x), geometry.block_width_m / 2 - eps,
         geometry.thermocouple_z_m)
        for x in geometry.thermocouple_x_m
    )
    mirror = (0, 2) if symmetric else ()
    return VoxelModel(xe, ye, ze, body, rho, lam, cp, h, BALLS, probes, mirror)
