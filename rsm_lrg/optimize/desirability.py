"""Multi-response optimisation by desirability (Derringer & Suich 1980, as Stat-Ease documents it).

Each response i gets a goal and limits ``L_i < U_i`` and its individual desirability
``d_i ∈ [0, 1]`` (Stat-Ease, "Desirability Details" and "Weight"):

* **maximize**: 0 below L, ``((y - L)/(U - L))^w`` between, 1 above U;
* **minimize**: 1 below L, ``((U - y)/(U - L))^w`` between, 0 above U;
* **target T** (L ≤ T ≤ U): ``((y - L)/(T - L))^w1`` on [L, T], ``((U - y)/(U - T))^w2``
  on [T, U], 0 outside;
* **in range**: 1 on [L, U], 0 outside.

Weights ``w`` lie in [0.1, 10] (1 = linear ramp). The overall desirability is the
importance-weighted geometric mean (Stat-Ease, "Importance"; importance r_i ∈ 1..5):

    D = ( Π d_i^{r_i} )^{1 / Σ r_i},

where "in range" responses enter the product (0 or 1) but not the sum Σ r_i. Default
limits are the observed minimum and maximum of the response (Stat-Ease's default).

The search maximises D over the coded box [-1, 1]^k (or tighter bounds) from many starts:
the centre, the vertices (k ≤ 8), each response's single-response optimum and a scrambled
Sobol set; all are screened at once, the best six polished by L-BFGS-B and the winner by Nelder–Mead. Where D is 0 (flat) the objective is the summed
distance of the responses to their acceptable ranges, scaled by U - L, so the search
still moves towards the feasible region (Stat-Ease's "tail" serves the same purpose).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .single import parse_goal

__all__ = ["ResponseGoal", "individual_desirability", "overall_desirability", "optimize_desirability",
           "DesirabilityResult", "parse_response_goal", "log_individual_desirability", "log_overall_desirability"]

_GOALS = {"maximize": "maximize", "maximise": "maximize", "max": "maximize", "minimize": "minimize",
          "minimise": "minimize", "min": "minimize", "target": "target", "range": "range",
          "in_range": "range", "in-range": "range", "inrange": "range"}


@dataclass(frozen=True)
class ResponseGoal:
    """The goal for one response (frozen).

    Attributes
    ----------
    response : str
    goal : {"maximize", "minimize", "target", "range"}
    low, high : float or None
        Limits L and U [response units]; ``None``: observed min / max.
    target : float or None
        T for ``goal == "target"``.
    weight : float or (float, float)
        w (or (w1, w2) for a target), 0.1 .. 10.
    importance : int
        1 .. 5.
    """

    response: str
    goal: str = "maximize"
    low: float | None = None
    high: float | None = None
    target: float | None = None
    weight: Any = 1.0
    importance: float = 3

    def __post_init__(self):
        g = _GOALS.get(str(self.goal).strip().lower())
        if g is None:
            raise ValueError(f"response {self.response!r}: goal must be minimize, maximize, target=V or range, "
                             f"not {self.goal!r}")
        object.__setattr__(self, "goal", g)
        if g == "target" and self.target is None:
            raise ValueError(f"response {self.response!r}: a target goal needs a value (target=V)")
        w = self.weight if isinstance(self.weight, (tuple, list)) else (self.weight, self.weight)
        if len(w) != 2:
            raise ValueError(f"response {self.response!r}: weight must be a number or two numbers")
        w = tuple(float(v) for v in w)
        if not all(0.1 <= v <= 10.0 for v in w):
            raise ValueError(f"response {self.response!r}: weights must lie between 0.1 and 10 (got {self.weight!r})")
        object.__setattr__(self, "weight", w)
        imp = float(self.importance)
        if not (1 <= imp <= 5):
            raise ValueError(f"response {self.response!r}: importance must lie between 1 and 5 (got {self.importance!r})")
        object.__setattr__(self, "importance", imp)
        if self.low is not None and self.high is not None and not self.low < self.high:
            raise ValueError(f"response {self.response!r}: the lower limit must be below the upper limit "
                             f"(got {self.low:g} >= {self.high:g})")
        if g == "target" and self.low is not None and self.high is not None and not (self.low <= self.target <= self.high):
            raise ValueError(f"response {self.response!r}: the target {self.target:g} lies outside the limits "
                             f"{self.low:g}..{self.high:g}")

    def with_limits(self, low: float, high: float) -> ResponseGoal:
        """The goal with its missing limits filled in.

        Parameters
        ----------
        low, high : float
            Limits to use where the goal has none [response units] (a target stays inside them).

        Returns
        -------
        ResponseGoal
            A copy with both limits.
        """
        lo = self.low if self.low is not None else low
        hi = self.high if self.high is not None else high
        if self.goal == "target" and self.target is not None:  # keep the target inside the limits
            lo, hi = min(lo, self.target), max(hi, self.target)
        if not lo < hi:
            raise ValueError(f"response {self.response!r}: the limits {lo:g}..{hi:g} are empty "
                             "(give --limits LOW:HIGH)")
        return ResponseGoal(self.response, self.goal, float(lo), float(hi), self.target, self.weight, self.importance)

    def to_dict(self) -> dict:
        """The goal as plain data.

        Returns
        -------
        dict
            JSON-safe: numbers, strings, lists and dicts.
        """
        return {"response": self.response, "goal": self.goal, "low": self.low, "high": self.high,
                "target": self.target, "weight": list(self.weight), "importance": self.importance}


def parse_response_goal(response: str, goal: str = "maximize", *, weight=None, importance=None,
                        limits=None) -> ResponseGoal:
    """A :class:`ResponseGoal` from CLI-style strings: goal ``minimize|maximize|target=V|range``,
    weight ``"W"`` or ``"W1,W2"``, importance ``"R"``, limits ``"LOW:HIGH"``."""
    g = str(goal).strip().lower()
    target = None
    if g.startswith("target"):  # target=V: the single-response parser, named for this response
        try:
            g, target = parse_goal(goal)
        except ValueError as exc:
            raise ValueError(f"response {response!r}: {exc}") from None
    w: float | tuple[float, ...] = 1.0
    if weight is not None:
        try:
            parts = [float(v) for v in str(weight).split(",")]
        except ValueError:
            raise ValueError(f"response {response!r}: weight {weight!r} is not a number (or W1,W2)") from None
        w = parts[0] if len(parts) == 1 else tuple(parts)
    imp = 3 if importance is None else importance
    try:
        imp = float(imp)
    except ValueError:
        raise ValueError(f"response {response!r}: importance {importance!r} is not a number") from None
    lo = hi = None
    if limits is not None:
        s = str(limits)
        if ":" not in s:
            raise ValueError(f"response {response!r}: limits must be LOW:HIGH, not {limits!r}")
        a, b = s.split(":", 1)
        try:
            lo = float(a) if a.strip() else None
            hi = float(b) if b.strip() else None
        except ValueError:
            raise ValueError(f"response {response!r}: limits {limits!r} are not numbers") from None
    return ResponseGoal(response, g, lo, hi, target, w, imp)


def _ramp(y: np.ndarray, a: float, b: float) -> tuple[np.ndarray, np.ndarray]:
    """``(t, 1 - t)`` of the ramp ``t = (y - a) / (b - a)`` clipped to [0, 1], each computed
    directly: halves of the limits keep ``b - a`` finite for limits near the largest float
    (``-1e308..1e308``), and the shortfall ``1 - t = (b - y) / (b - a)`` keeps its digits
    where ``t`` rounds to 1 (a slope of 1e-308 per unit)."""
    den = 0.5 * b - 0.5 * a
    t = np.clip((0.5 * y - 0.5 * a) / den, 0.0, 1.0)
    s = np.clip((0.5 * b - 0.5 * y) / den, 0.0, 1.0)
    return t, s


def _log_power(t: np.ndarray, s: np.ndarray, w: float) -> np.ndarray:
    """``w log t`` with ``s = 1 - t`` (``log1p(-s)`` where ``t`` is near 1; ``-inf`` at 0)."""
    with np.errstate(divide="ignore"):
        return w * np.where(s < 0.5, np.log1p(-np.minimum(s, 0.5)), np.log(np.maximum(t, 0.0)))


def log_individual_desirability(y, goal: ResponseGoal) -> np.ndarray:
    """``log d_i`` for predicted values ``y`` (``-inf`` where ``d_i = 0``) [-].

    Computed from the shortfall ``1 - t`` of each ramp, so it keeps its digits where ``d_i``
    itself rounds to 1: with limits ``-1e308..1e308`` and a target 0.03, a prediction 0.0337 has
    ``d = 1 - 1.2e-311`` — 1.0 as a float, but ``log d`` is ``-1.2e-311`` and the search still
    tells it from the target itself (issue 36)."""
    y = np.asarray(y, dtype=float)
    L, U = goal.low, goal.high
    if L is None or U is None:
        raise ValueError(f"response {goal.response!r}: limits are not set")
    w1, w2 = goal.weight
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        if goal.goal == "maximize":
            t, sh = _ramp(y, L, U)
            ld = _log_power(t, sh, w1)
        elif goal.goal == "minimize":
            t, sh = _ramp(y, U, L)
            ld = _log_power(t, sh, w1)
        elif goal.goal == "range":
            ld = np.where((y >= L) & (y <= U), 0.0, -np.inf)
        else:
            T = goal.target
            if T is None:
                raise ValueError(f"response {goal.response!r}: the target is not set")
            if T > L:
                lo_part = _log_power(*_ramp(y, L, T), w1)
            else:
                lo_part = np.where(y >= L, 0.0, -np.inf)
            if U > T:
                hi_part = _log_power(*_ramp(y, U, T), w2)
            else:
                hi_part = np.where(y <= U, 0.0, -np.inf)
            ld = np.where(y <= T, lo_part, hi_part)
    return np.where(np.isfinite(y), ld, -np.inf)


def individual_desirability(y, goal: ResponseGoal) -> np.ndarray:
    """d_i for predicted values ``y`` (limits must be set; see the module docstring) [-].

    The ramps are taken with halves of the limits, so limits near the largest float
    (``-1e308..1e308``) do not overflow ``U - L`` (which made every ``d_i`` 0)."""
    y = np.asarray(y, dtype=float)
    L, U = goal.low, goal.high
    if L is None or U is None:
        raise ValueError(f"response {goal.response!r}: limits are not set")
    w1, w2 = goal.weight
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        if goal.goal == "maximize":
            d = _ramp(y, L, U)[0] ** w1
        elif goal.goal == "minimize":
            d = _ramp(y, U, L)[0] ** w1
        elif goal.goal == "range":
            d = ((y >= L) & (y <= U)).astype(float)
        else:
            T = goal.target
            if T is None:
                raise ValueError(f"response {goal.response!r}: the target is not set")
            lo_part = _ramp(y, L, T)[0] ** w1 if T > L else (y >= L).astype(float)
            hi_part = _ramp(y, U, T)[0] ** w2 if U > T else (y <= U).astype(float)
            d = np.where(y <= T, lo_part, hi_part)
    return np.where(np.isfinite(y), d, 0.0)


def log_overall_desirability(logds: Sequence, goals: Sequence[ResponseGoal]) -> np.ndarray:
    """``log D`` from the ``log d_i`` (:func:`log_individual_desirability`): the
    importance-weighted mean of the ``log d_i``; "in range" goals enter as 0 or ``-inf`` [-]."""
    logds = [np.asarray(v, dtype=float) for v in logds]
    total: float | np.ndarray = 0.0
    rsum = 0.0
    zero = np.zeros_like(logds[0], dtype=bool)
    for ld, g in zip(logds, goals):
        zero = zero | ~(ld > -np.inf)
        if g.goal == "range":
            continue
        total = total + g.importance * np.where(ld > -np.inf, ld, 0.0)
        rsum += g.importance
    out = total / rsum if rsum else np.zeros_like(logds[0])
    return np.where(zero, -np.inf, out)


def overall_desirability(ds: Sequence, goals: Sequence[ResponseGoal]) -> np.ndarray:
    """D = (Π d_i^{r_i})^{1/Σ r_i}; "in range" goals enter the product only [-]."""
    ds = [np.asarray(d, dtype=float) for d in ds]
    logs: float | np.ndarray = 0.0
    rsum = 0.0
    zero = np.zeros_like(ds[0], dtype=bool)
    for d, g in zip(ds, goals):
        zero = zero | (d <= 0)
        if g.goal == "range":
            continue
        with np.errstate(divide="ignore"):
            logs = logs + g.importance * np.log(np.where(d > 0, d, 1.0))
        rsum += g.importance
    if rsum == 0:
        return np.where(zero, 0.0, 1.0)
    return np.where(zero, 0.0, np.exp(logs / rsum))


@dataclass(frozen=True)
class DesirabilityResult:
    """The best compromise found (frozen).

    Attributes
    ----------
    responses : tuple of str
    goals : tuple of ResponseGoal
        With the limits used.
    coded, actual : dict
        Settings [coded units] / [actual units].
    predicted : dict
        ŷ per response (average block) [response units].
    individual : dict
        d_i per response [-].
    desirability : float
        D [-].
    bounds : dict
    n_starts : int
    """

    responses: tuple
    goals: tuple
    coded: dict
    actual: dict
    predicted: dict
    individual: dict
    desirability: float
    bounds: dict = field(default_factory=dict)
    n_starts: int = 0
    warnings: tuple = ()

    def to_dict(self) -> dict:
        return {"responses": list(self.responses), "goals": [g.to_dict() for g in self.goals],
                "coded": dict(self.coded), "actual": dict(self.actual), "predicted": dict(self.predicted),
                "desirability": self.desirability, "individual": dict(self.individual),
                "bounds": {k: list(v) for k, v in self.bounds.items()}, "warnings": list(self.warnings)}

    def summary(self) -> str:
        from ..present import format_g

        lines = [f"Desirability optimum (D = {self.desirability:.4f})"]
        for (L, c), (name, a) in zip(self.coded.items(), self.actual.items()):
            lines.append(f"  {L}: {name} = {a}   (categoric)" if isinstance(a, str)
                         else f"  {L}: {name} = {format_g(a, 6, trim=True)}   (coded {c:+.4f})")
        for g in self.goals:
            what = g.goal if g.goal != "target" else f"target {format_g(g.target, 6, trim=True)}"
            lines.append(f"  {g.response}: predicted {format_g(self.predicted[g.response], 6, trim=True)}, d = "
                         f"{self.individual[g.response]:.4f}  ({what}, limits {format_g(g.low, 6, trim=True)}..{format_g(g.high, 6, trim=True)}, "
                         f"weight {g.weight[0]:g}, importance {g.importance:g})")
        lines += [f"  warning: {w}" for w in self.warnings]
        return "\n".join(lines) + "\n"


def optimize_desirability(fits: Mapping[str, Any], goals: Sequence[ResponseGoal], bounds=None, *,
                          seed: int = 0, n_sobol: int = 256, n_polish: int = 6,
                          constraints=None) -> DesirabilityResult:
    """Maximise the overall desirability of several fitted responses.

    Parameters
    ----------
    fits : mapping
        ``{response: FitResult}``; all fits must share the same factors and
        coding. Each response may have its own model (order, reduced terms, transform); a
        transformed fit is back-transformed before its desirability is taken, and its default
        limits are the observed range on the original scale.
    goals : sequence of ResponseGoal
        One per response (limits default to the observed range of that response).
    bounds : mapping or list of str, optional
        Tighter factor bounds in actual units (see :func:`rsm_lrg.optimize.parse_bounds`).
    seed : int
        Seed of the Sobol start set.
    n_sobol : int
        Sobol starts (rounded up to a power of two); all starts are screened at once.
    n_polish : int
        The best starts polished by L-BFGS-B; the best result then by Nelder–Mead.
    constraints : str or list of str, optional
        Inequalities on the numeric factors in actual units, as for the designs and the
        single-response :func:`~rsm_lrg.optimize.optimize` (``"v**2/a <= s"``,
        ``"0.5*A + B <= 1.2"``): the optimum satisfies every one. The search is the same
        constrained search (:mod:`rsm_lrg.optimize.region`): the starts are screened feasible
        first, the best polished by SLSQP with the constraints, the winner by Nelder–Mead
        inside the region; a region with no feasible setting is a ``ValueError``.

    Returns
    -------
    DesirabilityResult
        The best setting (coded and actual), each response's prediction and individual
        desirability, and the overall desirability (their weighted geometric mean, 0 to 1).

    Notes
    -----
    With categoric factors every combination of their levels (those allowed by ``bounds``,
    e.g. ``{"stage": "rms"}``) is searched over the numeric factors, and the combination with
    the highest overall desirability wins (its levels are in ``actual``).
    """
    from ..model.results.glm_result import GLMResult

    glm = [str(n) for n, f in (fits or {}).items() if isinstance(f, GLMResult)]
    if glm:  # its model scale is the link scale, which the search would read as the response
        raise TypeError(f"response {glm[0]!r}: desirability with a generalised linear model (a probability or mean "
                        "count) is not available yet; optimise it alone with rsm_lrg.optimize(result, goal)")
    first = next(iter(fits.values()), None) if fits else None
    if first is not None and first.space.has_categoric:
        return _desirability_categoric(fits, goals, bounds, seed=seed, n_sobol=n_sobol, n_polish=n_polish,
                                       constraints=constraints)
    return _desirability_numeric(fits, goals, bounds, seed=seed, n_sobol=n_sobol, n_polish=n_polish,
                                 constraints=constraints)


def _desirability_categoric(fits, goals, bounds, *, seed, n_sobol, n_polish, constraints=None) -> DesirabilityResult:
    from dataclasses import replace

    from .single import LevelView, split_bounds

    space = next(iter(fits.values())).space
    numeric, held = split_bounds(space, bounds)
    best = None
    infeasible = None
    for combo in space.level_combinations():
        if not all(combo[k] in v for k, v in held.items()):
            continue
        views = {}
        for name, f in fits.items():
            views[name] = LevelView(f, combo)
        try:
            r = _desirability_numeric(views, goals, numeric, seed=seed, n_sobol=n_sobol, n_polish=n_polish,
                                      constraints=constraints)
        except ValueError as exc:  # no feasible setting at this level combination: try the others
            from .region import INFEASIBLE

            if str(exc) != INFEASIBLE:
                raise
            infeasible = exc
            continue
        if best is None or r.desirability > best[0].desirability:
            best = (r, combo)
    if best is None:
        raise infeasible if infeasible is not None else ValueError("no level combination is allowed by the bounds")
    r, combo = best
    letter = {f.name: f.letter for f in space.factors}
    actual = {n: (combo[n] if n in combo else r.actual[n]) for n in space.names}
    coded = {letter[n]: (combo[n] if n in combo else r.coded[letter[n]]) for n in space.names}
    bnds = {n: (tuple(held.get(n, space[n].levels)) if n in combo else r.bounds[n]) for n in space.names}
    return replace(r, actual=actual, coded=coded, bounds=bnds)


def _desirability_numeric(fits, goals, bounds, *, seed, n_sobol, n_polish, constraints=None) -> DesirabilityResult:
    """:func:`optimize_desirability` over numeric factors only."""
    from scipy import optimize as so
    from scipy.stats import qmc

    from ..model.build.terms import design_matrix
    from .region import feasible_mask, feasible_only, is_feasible, local_minima, parse_constraints, region_starts
    from .single import optimize as single_optimize
    from .single import parse_bounds

    if not goals:
        raise ValueError("give at least one response goal")
    names = [g.response for g in goals]
    if len(set(names)) != len(names):
        raise ValueError("each response may have one goal only")
    missing = [n for n in names if n not in fits]
    if missing:
        raise ValueError(f"no fitted model for response(s) {', '.join(map(repr, missing))}")
    first = fits[names[0]]
    space = first.space
    for n in names[1:]:
        if fits[n].space.to_list() != space.to_list():
            raise ValueError(f"responses {names[0]!r} and {n!r} were fitted on different factors or codings")
    def observed(f):
        return f.transform.inverse(np.asarray(f.y, dtype=float))  # the response as measured

    goals = [g.with_limits(float(np.nanmin(observed(fits[g.response]))), float(np.nanmax(observed(fits[g.response]))))
             for g in goals]
    mixture = first.space.has_components
    if mixture:  # the constrained simplex (rsm_lrg.optimize.mixture)
        from ..model.build.mixture_region import mixture_region

        region = mixture_region(space, bounds, constraints)
        lo, hi, notes, cons = -np.ones(len(space)), np.ones(len(space)), [], None
    else:
        lo, hi, notes = parse_bounds(space, bounds)
        cons = parse_constraints(constraints, space)
    k = len(space)
    polys = []
    inverses = []
    for g in goals:
        f = fits[g.response]
        tr = f.transform
        inverses.append(None if tr.identity else tr.inverse)
        if not hasattr(f, "coefficients"):  # no polynomial (a Gaussian process): the contract's surface
            polys.append(("c", f))
            continue
        beta = f.coefficients["coded"].to_numpy(dtype=float)
        if all(t.order <= 2 for t in f.terms):
            from ..model.readings.canonical import quadratic_parts

            polys.append(("q", quadratic_parts(dict(zip(f.coefficients.index, beta)), f.terms, k)))
        else:
            polys.append(("g", (f.terms, beta)))

    def preds(X):
        X = np.atleast_2d(np.asarray(X, dtype=float))
        out = []
        for (kind, par), inv in zip(polys, inverses):
            if kind == "q":
                b0, b, B = par
                v = b0 + X @ b + np.einsum("ij,jk,ik->i", X, B, X)
            elif kind == "c":
                v = np.asarray(par.predict_coded(X), dtype=float)
            else:
                v = design_matrix(X, par[0]) @ par[1]
            out.append(v if inv is None else inv(v))  # back to response units
        return out

    def D_of(X):
        ys = preds(X)
        return overall_desirability([individual_desirability(y, g) for y, g in zip(ys, goals)], goals), ys

    def objective_many(X):
        # minimised: where D > 0, u / (1 + u) with u = -log D (0 at D = 1, below 1; it keeps
        # the digits of a D that rounds to 1, which -D loses: limits -1e308..1e308 made every
        # setting "D = 1"); where D = 0, 1 + the distance to the limits
        ys = preds(X)
        logD = log_overall_desirability([log_individual_desirability(y, g) for y, g in zip(ys, goals)], goals)
        pen = np.zeros(len(logD))
        for y, g in zip(ys, goals):
            span = 2.0 * (0.5 * g.high - 0.5 * g.low)  # finite for limits near the largest float
            if g.goal == "maximize":
                pen += np.maximum(g.low - y, 0.0) / span
            elif g.goal == "minimize":
                pen += np.maximum(y - g.high, 0.0) / span
            else:
                pen += (np.maximum(g.low - y, 0.0) + np.maximum(y - g.high, 0.0)) / span
        pen = np.where(np.isfinite(pen), pen, 1e6)  # a back-transform undefined there
        with np.errstate(invalid="ignore", over="ignore"):
            u = -logD
            return np.where(logD > -np.inf, u / (1.0 + u), 1.0 + pen + 1e-12)

    def objective(x):
        return float(objective_many(np.asarray(x, dtype=float)[None, :])[0])

    if mixture:
        from .mixture import desirability_search, limits_of

        extra = []
        for g in goals:
            goal = g.goal if g.goal in ("maximize", "minimize") else (("target", g.target) if g.goal == "target" else None)
            if goal is not None:
                try:
                    o = single_optimize(fits[g.response], goal=goal, bounds=bounds, constraints=constraints)
                except ValueError:
                    continue
                extra.append([o.coded[L] for L in space.letters])
        x, n_starts = desirability_search(objective, objective_many, region, extra, n_polish=n_polish, seed=seed)
        return _result(names, goals, space, x, D_of, limits_of(region), n_starts, [],
                       "the region of the blends")
    starts = [np.clip(np.zeros(k), lo, hi), (lo + hi) / 2]
    if k <= 8:
        starts += [np.where(np.array(v) > 0, hi, lo) for v in itertools.product((0, 1), repeat=k)]
    for g in goals:
        goal = g.goal if g.goal in ("maximize", "minimize") else (("target", g.target) if g.goal == "target" else None)
        if goal is None:
            continue
        try:  # goals are on the response's scale: the optimiser maps them onto the fit's
            o = single_optimize(fits[g.response], goal=goal, bounds=bounds, constraints=constraints)
            starts.append(np.array([o.coded[L] for L in space.letters]))
        except ValueError:
            pass
    m = max(3, int(math.ceil(math.log2(max(n_sobol, 8)))))
    sob = qmc.Sobol(d=k, scramble=True, seed=seed).random_base2(m)
    starts += list(lo + sob * (hi - lo))
    starts += region_starts(cons, lo, hi, seed)
    S = np.clip(np.array(starts), lo, hi)
    # screen every start (vectorised), feasible ones first; polish the most promising ones
    vals = objective_many(S)
    ok = feasible_mask(S, cons)
    order = np.lexsort((vals, ~ok))[:n_polish]
    cands = local_minima(objective, S[order], lo, hi, cons, maxiter=200)
    cands = feasible_only(cands, cons)
    cvals = [objective(c) for c in cands]
    best_x = cands[int(np.argmin(cvals))]
    best_v = float(min(cvals))

    # D has kinks (limits, targets): finish with a derivative-free polish of the best point,
    # kept inside the box and the constraints (a point outside scores +inf)
    def inside(x):
        x = np.asarray(x, dtype=float)
        if np.any(x < lo) or np.any(x > hi) or not is_feasible(x, cons):
            return math.inf
        return objective(x)

    r2 = so.minimize(inside if cons is not None else objective, best_x, method="Nelder-Mead",
                     options={"xatol": 1e-10, "fatol": 1e-15, "maxiter": 400 * k})
    c = np.clip(r2.x, lo, hi)
    if objective(c) < best_v and is_feasible(c, cons):
        best_x, best_v = c, objective(c)
    bnds = {f.name: (float(f.decode(a)), float(f.decode(b))) for f, a, b in zip(space.factors, lo, hi)}
    return _result(names, goals, space, best_x + 0.0, D_of, bnds, len(starts), notes,
                   "the box and the constraints" if cons is not None else "the box")


def _result(names, goals, space, x, D_of, bnds, n_starts, notes, where) -> DesirabilityResult:
    """The :class:`DesirabilityResult` at the coded point ``x``."""
    D, ys = D_of(x)
    ds = [float(individual_desirability(y, g)[0]) for y, g in zip(ys, goals)]
    warns = list(notes)
    if D[0] <= 0:
        warns.append(f"no setting in {where} meets every response's limits (D = 0); the point shown is the closest")
    return DesirabilityResult(
        responses=tuple(names), goals=tuple(goals),
        coded={L: float(v) for L, v in zip(space.letters, x)},
        actual={f.name: float(f.decode(v)) for f, v in zip(space.factors, x)},
        predicted={g.response: float(y[0]) for g, y in zip(goals, ys)},
        individual=dict(zip(names, ds)), desirability=float(D[0]),
        bounds=bnds, n_starts=n_starts, warnings=tuple(warns),
    )
