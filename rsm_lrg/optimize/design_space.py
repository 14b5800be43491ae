"""The design space: where every response stays inside its specification with a given
probability, and the largest operating window in which it does (ICH Q8's "design space";
JMP's Design Space Profiler).

For each response ``r`` with specification ``[L_r, U_r]`` (either side may be open) the
probability that a new run at the setting ``x`` is inside it is the posterior predictive
probability of the fitted model (the prediction contract's interval form,
:mod:`rsm_lrg.model.contract.prediction`)::

    p_r(x) = T_ν((U' - ŷ(x)) / s(x)) - T_ν((L' - ŷ(x)) / s(x)),   s(x)² = var_mean(x) + s2_new

(the contract's :meth:`~rsm_lrg.model.contract.prediction.FittedModel.predictive`; a Gaussian process:
the kriging mean, its variance plus the nugget, normal) on the model's scale (``L'``, ``U'`` the limits transformed as the response is; a limit outside
the transform's domain is open), ``T_ν`` Student's t distribution with the fit's degrees of
freedom (OLS n − p; REML the Kenward–Roger df of ``x``). For a linear model with normal errors
and the usual non-informative prior this *is* the predictive probability: it counts the
model's own uncertainty (the coefficients') and the run-to-run noise. The responses are taken
as independent (each fitted on its own; their residuals are not modelled jointly), so the
probability that every response is in its specification is ``p(x) = Π_r p_r(x)``.

With factor noise (``factor_sd``: one standard deviation per numeric factor, actual units),
``p(x)`` is averaged over ``draws`` normal perturbations of the setting, truncated to the
factor box (a draw outside it is drawn again), with the same seeded draws at every node
(common random numbers).

A mixture's region is its constrained simplex and its window bounds per component with the
total kept (:mod:`rsm_lrg.optimize.design_space_mixture`).

The **window** is a hyper-rectangle of grid nodes (``grid`` equally spaced levels per numeric
factor over its range) in which ``p ≥ probability`` at every node, found by growing a box from
each of the most probable nodes one grid step at a time on any face whose new nodes all keep
the target, until no face can grow; the window with the most nodes wins. It is therefore
maximal on the grid — no face can move out by one step without a node falling below the
target — though not necessarily the largest such box of all (a search over every box is
exponential in the number of factors).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import ParameterError
from ..factors import finite_float

__all__ = ["DesignSpace", "design_space", "parse_spec", "MAX_GRID_NODES", "largest_window"]

#: The most grid nodes a design-space search evaluates (grid^k): beyond, a smaller --grid.
MAX_GRID_NODES = 2_000_000
#: The most nodes whose windows are grown (the most probable ones).
N_STARTS = 25


def parse_spec(text: str) -> tuple[str, float | None, float | None]:
    """``"Y=LOW:HIGH"`` (either side may be empty: ``Y=:0.035``, ``Y=0.02:``) as ``(name,
    low, high)`` in the response's units.

    >>> parse_spec("tcr_c_per_min=:0.035")
    ('tcr_c_per_min', None, 0.035)
    """
    name, sep, rest = str(text).partition("=")
    lo_text, colon, hi_text = rest.partition(":")
    if not sep or not colon or not name.strip():
        raise ParameterError("spec", f"expected Y=LOW:HIGH (either side may be empty), got {text!r}")
    try:
        lo = finite_float(lo_text, "low") if lo_text.strip() else None
        hi = finite_float(hi_text, "high") if hi_text.strip() else None
    except ValueError:
        raise ParameterError("spec", f"{text!r}: the limits must be finite numbers") from None
    if lo is None and hi is None:
        raise ParameterError("spec", f"{text!r}: give at least one limit")
    if lo is not None and hi is not None and not lo < hi:
        raise ParameterError("spec", f"{text!r}: the low limit must be below the high limit")
    return name.strip(), lo, hi


@dataclass(frozen=True)
class DesignSpace:
    """The probability of meeting every specification over the factor region, and the largest
    operating window found (frozen).

    Attributes
    ----------
    specs : dict
        ``{response: (low, high)}`` (None: open) [response units].
    probability : float
        The target probability [-].
    factors : tuple of str
        The numeric factors searched (in order); ``held`` the categoric ones at their level.
    levels : tuple of ndarray
        The grid levels of each factor [actual units].
    grid_probability : ndarray
        ``p`` at every grid node (shape ``(grid,) * k``; a mixture: one value per blend of the
        constrained simplex lattice) [-].
    window : dict or None
        ``{factor: (low, high)}`` [actual units], or None when no node reaches the target.
        For a mixture (``region == "simplex"``): per-component bounds, the window being the
        blends inside them (the total kept; :mod:`rsm_lrg.optimize.design_space_mixture`).
    window_min_probability : float
        The smallest ``p`` over the window's nodes [-] (NaN without a window).
    best : dict
        The most probable grid node ``{factor: value}`` and ``best_probability`` its ``p``.
    maps : list of dict
        Per pair of factors: ``{"x", "y", "x_levels", "y_levels", "p"}``, the others held at
        the window's centre (or the best node).
    notes : tuple of str
    region : {"box", "simplex"}
        The factor box, or a mixture's constrained simplex.
    """

    specs: dict
    probability: float
    factors: tuple
    levels: tuple = field(repr=False)
    grid_probability: np.ndarray = field(repr=False)
    window: dict | None
    window_min_probability: float
    window_nodes: int
    best: dict
    best_probability: float
    held: dict = field(default_factory=dict)
    maps: list = field(default_factory=list, repr=False)
    notes: tuple = ()
    factor_sd: dict = field(default_factory=dict)
    draws: int = 0
    region: str = "box"

    def to_dict(self) -> dict:
        def num(v: Any) -> float | None:
            v = float(v)
            return v if math.isfinite(v) else None

        return {
            "specs": {r: {"low": lo, "high": hi} for r, (lo, hi) in self.specs.items()},
            "probability": self.probability,
            "factors": list(self.factors),
            "held": dict(self.held),
            "grid": len(self.levels[0]) if self.levels else 0,
            "window": None if self.window is None else {k: {"low": lo, "high": hi} for k, (lo, hi) in self.window.items()},
            "window_min_probability": num(self.window_min_probability),
            "window_nodes": self.window_nodes,
            "region": self.region,
            "best": dict(self.best),
            "best_probability": num(self.best_probability),
            "factor_sd": dict(self.factor_sd),
            "draws": self.draws,
            "maps": [{"x": m["x"], "y": m["y"], "x_levels": [float(v) for v in m["x_levels"]],
                      "y_levels": [float(v) for v in m["y_levels"]],
                      "p": [[num(v) for v in row] for row in m["p"]]} for m in self.maps],
            "notes": list(self.notes),
        }

    def summary(self) -> str:
        from ..present import format_g

        specs = ", ".join(f"{r} in [{'-inf' if lo is None else format_g(lo)}, {'+inf' if hi is None else format_g(hi)}]"
                          for r, (lo, hi) in self.specs.items())
        out = [f"Design space: P(every response in its specification) >= {self.probability:g}",
               f"Specifications: {specs}"]
        if self.held:
            out.append("Held: " + ", ".join(f"{k} = {v}" for k, v in self.held.items()))
        out.append("Most probable grid node: " + ", ".join(f"{k} = {format_g(v)}" for k, v in self.best.items())
                   + f" (p = {self.best_probability:.4f})")
        if self.window is None:
            out.append(f"No operating window: no grid node reaches p >= {self.probability:g}.")
        else:
            out.append(f"Largest operating window found ({self.window_nodes} grid nodes; p >= "
                       f"{self.window_min_probability:.4f} at every node):")
            out += [f"  {k}: {format_g(lo)} … {format_g(hi)}" for k, (lo, hi) in self.window.items()]
        out += [f"Note: {n}" for n in self.notes]
        return "\n".join(out) + "\n"

    def __str__(self) -> str:
        return self.summary()


def _model_limits(fit: Any, low: float | None, high: float | None) -> tuple[float, float]:
    """The specification on the model's scale (sorted; a limit outside the transform's domain,
    or an open one, is ±inf)."""
    tr = fit.transform
    if tr.identity:
        return (-math.inf if low is None else low), (math.inf if high is None else high)
    ends: list[float | None] = []
    for v in (low, high):
        if v is None:
            ends.append(None)
            continue
        with np.errstate(all="ignore"):
            z = float(np.asarray(tr.forward(np.array([v], dtype=float)))[0])
        ends.append(z if math.isfinite(z) else None)
    lo_z, hi_z = ends
    increasing = bool(tr.inverse(np.array([1.0]))[0] < tr.inverse(np.array([2.0]))[0])
    if not increasing:
        lo_z, hi_z = hi_z, lo_z
    return (-math.inf if lo_z is None else lo_z), (math.inf if hi_z is None else hi_z)


def _response_probability(fit: Any, coded: np.ndarray, limits: tuple[float, float]) -> np.ndarray:
    """``p_r`` at coded settings (n x k): the posterior predictive probability of the
    specification (module docstring)."""
    from scipy.special import stdtr

    yhat, var_new, df = fit.predictive(coded)
    s = np.sqrt(var_new)
    lo, hi = limits
    with np.errstate(divide="ignore", invalid="ignore"):
        up = np.where(np.isinf(hi), 1.0, stdtr(df, (hi - yhat) / s))
        down = np.where(np.isinf(lo), 0.0, stdtr(df, (lo - yhat) / s))
    return np.clip(up - down, 0.0, 1.0)


def design_space(fits: Mapping[str, Any], specs: Mapping[str, tuple[float | None, float | None]], *,
                 probability: float = 0.9, grid: int = 11, factor_sd: Mapping[str, float] | None = None,
                 draws: int = 1000, seed: int = 0, held: Mapping[str, str] | None = None) -> DesignSpace:
    """The probability that every response meets its specification over the factor box, and the
    largest operating window found (module docstring).

    Parameters
    ----------
    fits : mapping of str to FittedModel
        ``{response: fit}``, all over the same factors.
    specs : mapping
        ``{response: (low, high)}`` [response units]; None for an open side. A response of
        ``fits`` without a specification is not counted (a note says so).
    probability : float
        The target probability (0 < p < 1).
    grid : int
        Levels per numeric factor (3 to 201); ``grid^k`` nodes at most :data:`MAX_GRID_NODES`.
    factor_sd : mapping, optional
        ``{factor: SD}`` in actual units: the settings vary by that much from run to run.
    draws : int
        Draws of the factor noise per node (with ``factor_sd``).
    seed : int
        Seed of those draws.
    held : mapping, optional
        ``{categoric factor: level}`` (default: each categoric factor at its first level).

    Returns
    -------
    DesignSpace
    """
    if not specs:
        raise ParameterError("spec", "give a specification (Y=LOW:HIGH) for at least one response")
    unknown = [r for r in specs if r not in fits]
    if unknown:
        raise ParameterError("spec", f"{unknown[0]!r} is not a fitted response (responses: {', '.join(fits)})")
    if not (isinstance(probability, (int, float)) and 0.0 < float(probability) < 1.0):
        raise ParameterError("probability", f"probability must lie between 0 and 1, not {probability!r}")
    if isinstance(grid, bool) or not isinstance(grid, (int, np.integer)) or not 3 <= int(grid) <= 201:
        raise ParameterError("grid", f"grid must be a whole number from 3 to 201, not {grid!r}")
    if isinstance(draws, bool) or not isinstance(draws, (int, np.integer)) or not 1 <= int(draws) <= 100_000:
        raise ParameterError("draws", f"draws must be a whole number from 1 to 100000, not {draws!r}")
    first = next(iter(fits.values()))
    space = first.space
    for r, f in fits.items():
        if [g.name for g in f.space.factors] != space.names:
            raise ParameterError("response", f"{r!r} is fitted on other factors than {next(iter(fits))!r}")
    if space.has_components:
        return _mixture(fits, specs, space, float(probability), int(grid), factor_sd, held)
    numeric = [f for f in space.factors if f.kind != "categoric"]
    cats = [f for f in space.factors if f.kind == "categoric"]
    if not numeric:
        raise ParameterError("factor", "the design space needs at least one numeric factor")
    k = len(numeric)
    g = int(grid)
    if g ** k > MAX_GRID_NODES:
        raise ParameterError("grid", f"grid {g} in {k} factors is {g ** k:.3g} nodes; at most {MAX_GRID_NODES:,} "
                                     "(give a smaller grid)")
    held = dict(held or {})
    notes: list[str] = []
    levels_held: dict[str, str] = {}
    for f in cats:
        lv = held.pop(f.name, None)
        if lv is None:
            lv = str(f.levels[0])
            notes.append(f"categoric factor {f.name!r} held at its first level {lv!r}")
        elif str(lv) not in [str(v) for v in f.levels]:
            raise ParameterError("held", f"{lv!r} is not a level of {f.name!r} (levels: "
                                         f"{', '.join(str(v) for v in f.levels)})")
        levels_held[f.name] = str(lv)
    if held:
        raise ParameterError("held", f"{next(iter(held))!r} is not a categoric factor")
    sds = {str(k_): float(v) for k_, v in (factor_sd or {}).items()}
    for name, value in sds.items():
        f = next((x for x in numeric if x.name == name), None)
        if f is None:
            raise ParameterError("factor_sd", f"{name!r} is not a numeric factor")
        if not (math.isfinite(value) and 0.0 < value <= 1e6 * f.half_range):
            raise ParameterError("factor_sd", f"{name}: the SD must be a positive number (at most 1e6 half-ranges)")
    unused = [r for r in fits if r not in specs]
    if unused:
        notes.append("responses without a specification are not counted: " + ", ".join(unused))
    limits = {r: _model_limits(fits[r], lo, hi) for r, (lo, hi) in specs.items()}
    levels = tuple(np.linspace(f.low, f.high, g) for f in numeric)
    order = [space.names.index(f.name) for f in numeric]
    cat_pos = {space.names.index(f.name): f for f in cats}

    def coded_at(actual: np.ndarray) -> np.ndarray:
        """(n, k_numeric) actual settings -> (n, k_all) coded (categoric: the level index)."""
        out = np.empty((actual.shape[0], len(space.factors)))
        for j, (pos, f) in enumerate(zip(order, numeric)):
            out[:, pos] = (actual[:, j] - f.center) / f.half_range
        for pos, f in cat_pos.items():
            out[:, pos] = [str(v) for v in f.levels].index(levels_held[f.name])
        return out

    noise: np.ndarray | None = None
    sd = np.array([sds.get(f.name, 0.0) for f in numeric])
    lo_b = np.array([f.low for f in numeric])
    hi_b = np.array([f.high for f in numeric])
    if sds:
        noise = np.random.default_rng(seed).standard_normal((int(draws), k)) * sd
        notes.append(f"factor noise: normal with the given SDs, {int(draws)} draws per setting (common to every "
                     f"setting, seed {seed}), each perturbed setting truncated to the factor box (a coordinate "
                     "outside it is drawn again)")

    def prob(actual: np.ndarray) -> np.ndarray:
        if noise is None:
            c = coded_at(actual)
            return np.prod([_response_probability(fits[r], c, limits[r]) for r in specs], axis=0)
        total = np.zeros(actual.shape[0])
        for start in range(0, noise.shape[0], 64):
            d = noise[start:start + 64]
            pts = actual[:, None, :] + d[None, :, :]
            # truncation: a coordinate outside the box is drawn again (a truncated normal by
            # rejection), from a stream seeded by the seed and the block (deterministic)
            bad = (pts < lo_b) | (pts > hi_b)
            tries = 0
            local = np.random.default_rng([seed, start])
            while bad.any() and tries < 200:
                redraw = local.standard_normal(pts.shape) * sd
                pts = np.where(bad, actual[:, None, :] + redraw, pts)
                bad = (pts < lo_b) | (pts > hi_b)
                tries += 1
            pts = np.clip(pts, lo_b, hi_b)
            flat = pts.reshape(-1, k)
            c = coded_at(flat)
            p = np.prod([_response_probability(fits[r], c, limits[r]) for r in specs], axis=0)
            total += p.reshape(actual.shape[0], -1).sum(axis=1)
        return total / noise.shape[0]

    mesh = np.stack(np.meshgrid(*levels, indexing="ij"), axis=-1).reshape(-1, k)
    pgrid = np.concatenate([prob(mesh[s:s + 4096]) for s in range(0, mesh.shape[0], 4096)]).reshape((g,) * k)
    ok = pgrid >= float(probability)
    ib = np.unravel_index(int(np.argmax(pgrid)), pgrid.shape)
    best = {f.name: float(levels[j][ib[j]]) for j, f in enumerate(numeric)}
    window, wmin, wnodes = None, math.nan, 0
    if ok.any():
        box = _largest_window(ok, pgrid)
        sl = tuple(slice(a, b + 1) for a, b in box)
        window = {f.name: (float(levels[j][box[j][0]]), float(levels[j][box[j][1]])) for j, f in enumerate(numeric)}
        wmin = float(pgrid[sl].min())
        wnodes = int(np.prod([b - a + 1 for a, b in box]))
    centre = ({n: 0.5 * (a + b) for n, (a, b) in window.items()} if window is not None else dict(best))
    maps = []
    for a in range(k):
        for b in range(a + 1, k):
            base = np.array([centre[f.name] for f in numeric])
            xa, xb = np.meshgrid(levels[a], levels[b], indexing="xy")
            pts = np.repeat(base[None, :], xa.size, axis=0)
            pts[:, a] = xa.ravel()
            pts[:, b] = xb.ravel()
            maps.append({"x": numeric[a].name, "y": numeric[b].name, "x_levels": levels[a], "y_levels": levels[b],
                         "p": prob(pts).reshape(xa.shape)})
    notes.append("probability: posterior predictive of each fitted model (its coefficients' uncertainty and the "
                 "run-to-run noise; Student t with the fit's df), responses taken as independent")
    return DesignSpace(specs={r: (lo, hi) for r, (lo, hi) in specs.items()}, probability=float(probability),
                       factors=tuple(f.name for f in numeric), levels=levels, grid_probability=pgrid, window=window,
                       window_min_probability=wmin, window_nodes=wnodes, best=best,
                       best_probability=float(pgrid[ib]), held=levels_held, maps=maps, notes=tuple(notes),
                       factor_sd=sds, draws=int(draws) if sds else 0)


def _mixture(fits: Mapping[str, Any], specs: Mapping[str, tuple[float | None, float | None]], space: Any,
             probability: float, grid: int, factor_sd: Mapping[str, float] | None,
             held: Mapping[str, str] | None) -> DesignSpace:
    """:func:`design_space` of a mixture (:mod:`rsm_lrg.optimize.design_space_mixture`)."""
    from .design_space_mixture import check_mixture_options, mixture_design_space_parts

    check_mixture_options(space, factor_sd)
    if held:
        raise ParameterError("held", f"{next(iter(held))!r} is not a categoric factor")
    limits = {r: _model_limits(fits[r], lo, hi) for r, (lo, hi) in specs.items()}

    def prob(coded: np.ndarray) -> np.ndarray:
        return np.prod([_response_probability(fits[r], coded, limits[r]) for r in specs], axis=0)

    parts = mixture_design_space_parts(space, grid, probability, prob, MAX_GRID_NODES)
    notes = list(parts["notes"])
    unused = [r for r in fits if r not in specs]
    if unused:
        notes.append("responses without a specification are not counted: " + ", ".join(unused))
    notes.append("probability: posterior predictive of each fitted model (its coefficients' uncertainty and the "
                 "run-to-run noise; Student t with the fit's df), responses taken as independent")
    return DesignSpace(specs={r: (lo, hi) for r, (lo, hi) in specs.items()}, probability=probability,
                       factors=tuple(space.names), levels=parts["levels"], grid_probability=parts["p"],
                       window=parts["window"], window_min_probability=parts["window_min"],
                       window_nodes=parts["window_nodes"], best=parts["best"], best_probability=parts["best_p"],
                       maps=parts["maps"], notes=tuple(notes), region="simplex")


def _grow(ok: np.ndarray, start: Sequence[int]) -> list[tuple[int, int]]:
    """A box of grid indices grown from ``start`` one step at a time on any face whose new
    slab of nodes is all ``ok``, until no face can grow."""
    box = [(int(i), int(i)) for i in start]
    grown = True
    while grown:
        grown = False
        for j in range(ok.ndim):
            for side in (0, 1):
                a, b = box[j]
                new = a - 1 if side == 0 else b + 1
                if not 0 <= new < ok.shape[j]:
                    continue
                sl = tuple(slice(x, y + 1) if i != j else slice(new, new + 1) for i, (x, y) in enumerate(box))
                if ok[sl].all():
                    box[j] = (new, b) if side == 0 else (a, new)
                    grown = True
    return box


def _largest_window(ok: np.ndarray, p: np.ndarray) -> list[tuple[int, int]]:
    """The box with the most nodes among those grown from the :data:`N_STARTS` most probable
    ``ok`` nodes (ties: the larger smallest probability)."""
    flat = np.flatnonzero(ok.ravel())
    starts = flat[np.argsort(-p.ravel()[flat], kind="stable")[:N_STARTS]]
    best: list[tuple[int, int]] | None = None
    key = (-1, -math.inf)
    for s in starts:
        box = _grow(ok, [int(i) for i in np.unravel_index(int(s), ok.shape)])
        size = int(np.prod([b - a + 1 for a, b in box]))
        pmin = float(p[tuple(slice(a, b + 1) for a, b in box)].min())
        if (size, pmin) > key:
            best, key = box, (size, pmin)
    assert best is not None
    return best


def largest_window(ok: np.ndarray, p: np.ndarray) -> list[tuple[int, int]]:
    """The window search on any grid of probabilities ``p`` (``ok``: the nodes at the target):
    ``(first, last)`` grid indices per axis (module docstring; used by the surrogate's design
    space, :mod:`rsm_lrg.paper.surrogate_space`)."""
    return _largest_window(ok, p)
