"""Optimising on an interval bound or on the propagation of error (Design-Expert's "use
interval" and "minimise POE" in numerical optimisation).

Per response a goal (``minimize``, ``maximize``, ``target=V``, ``range`` — or ``poe``: make
the propagation of error, :mod:`rsm_lrg.optimize.poe`, as small as possible) and optionally an
interval (``ci``, ``pi`` or ``ti``: the confidence interval for the mean, the prediction
interval for one run, the tolerance interval for a proportion P of runs; all at confidence C).
The value the goal judges is then the interval's **worse end**:

* maximize: the lower bound is maximised; minimize: the upper bound is minimised;
* target=V: the larger distance of the two bounds from V is minimised (both bounds as near the
  target as they can be); range: both bounds must lie inside the limits.

One response without ``limits`` is optimised on that value directly; several responses (or a
response with limits) by Derringer–Suich desirability, each ``d`` computed on the worse end
(for a target or a range: the smaller ``d`` of the two bounds) and, for ``poe``, on the POE
minimised between its limits (default: the smallest and largest POE over the design's runs).
The optimum reports the mean, the interval and the bound optimised.

The search is over the numeric factors' box (``bounds``, ``constraints`` as for
:func:`rsm_lrg.optimize.optimize`): the centre, the vertices (k <= 6) and a scrambled Sobol
set are screened in one batch, the best few polished together by a batched compass search
inside the box (:func:`compass_search`; derivative-free, as the objective has kinks where an
interval end crosses a limit). Categoric factors are held at each allowed combination of
levels in turn (``bounds`` may hold one: ``stage=rms``) and the best combination wins.
A mixture is searched on its L-pseudo components, the last one closing the blend (every
component inside its bounds, the total kept); ``bounds`` and ``constraints`` are not yet taken
for a mixture (a ValueError says so).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import ParameterError

__all__ = ["INTERVALS", "RobustOptimum", "optimize_robust", "parse_interval", "parse_robust_goal", "compass_search"]

#: The interval names and the prediction columns of their ends.
INTERVALS = {"ci": ("ci_low", "ci_high"), "pi": ("pi_low", "pi_high"), "ti": ("ti_low", "ti_high")}
#: The POE goal's name.
POE = "poe"


def parse_interval(value: Any) -> str | None:
    """``"ci"``, ``"pi"``, ``"ti"`` or None (``"mean"``/``"none"``); else a ParameterError
    (parameter ``interval``)."""
    if value is None:
        return None
    v = str(value).strip().lower()
    if v in ("", "none", "mean"):
        return None
    if v not in INTERVALS:
        raise ParameterError("interval", f"interval must be ci, pi or ti (or mean), not {value!r}")
    return v


@dataclass(frozen=True)
class RobustOptimum:
    """The optimum on interval bounds and/or POE (frozen).

    Attributes
    ----------
    actual, coded : dict
        The setting [actual units] / [coded units].
    responses : dict
        Per response: ``goal``, ``interval`` (None: the mean), ``predicted`` (the mean),
        ``low``/``high`` (the interval's ends; None without one), ``optimised`` (which value the
        goal judged: ``"mean"``, ``"ci_low"``, ..., ``"poe"``), ``value`` (that value), ``poe``
        (with factor SDs), ``d`` (with desirability) [response units].
    desirability : float or None
        D, when several responses or limits were given.
    confidence, tolerance : float
    factor_sd : dict
    """

    actual: dict
    coded: dict
    responses: dict
    desirability: float | None
    confidence: float
    tolerance: float | None
    factor_sd: dict
    n_starts: int = 0
    warnings: tuple = field(default=())

    def to_dict(self) -> dict:
        return {"actual": dict(self.actual), "coded": dict(self.coded),
                "responses": {k: dict(v) for k, v in self.responses.items()}, "desirability": self.desirability,
                "confidence": self.confidence, "tolerance": self.tolerance, "factor_sd": dict(self.factor_sd),
                "n_starts": self.n_starts, "warnings": list(self.warnings)}

    def summary(self) -> str:
        from ..present import format_g

        def g(v):
            return "-" if v is None else format_g(v, 6, trim=True)

        head = "Optimum on interval bounds / POE" + (f" (D = {self.desirability:.4f})" if self.desirability is not None
                                                    else "")
        lines = [head]
        for (L, c), (name, a) in zip(self.coded.items(), self.actual.items()):
            lines.append(f"  {L}: {name} = {a}   (categoric)" if isinstance(a, str)
                         else f"  {L}: {name} = {g(a)}   (coded {c:+.4f})")
        pc = f"{100 * self.confidence:g} %"
        for r, v in self.responses.items():
            what = v["goal"] + ("" if v["interval"] is None else f" on the {v['interval'].upper()}")
            line = f"  {r}: {what}: mean {g(v['predicted'])}"
            if v["interval"] is not None:
                ti = f" for {100 * self.tolerance:g} % of runs" if v["interval"] == "ti" and self.tolerance else ""
                line += f", {pc} {v['interval'].upper()}{ti} {g(v['low'])} .. {g(v['high'])}"
            if v.get("poe") is not None:
                line += f", POE {g(v['poe'])}"
            line += f"; optimised {v['optimised']} = {g(v['value'])}"
            if v.get("d") is not None:
                line += f", d = {v['d']:.4f}"
            lines.append(line)
        lines += [f"  warning: {w}" for w in self.warnings]
        return "\n".join(lines) + "\n"


class _Objective:
    """The values the goals judge at coded points (a categoric factor's coordinate is its level index)."""

    def __init__(self, fits, goals, intervals, sds, confidence, tolerance) -> None:
        self.fits, self.goals, self.intervals = fits, goals, intervals
        self.sds, self.alpha, self.tolerance = sds, 1.0 - confidence, tolerance
        first = next(iter(fits.values()))
        self.space = first.space

    def frame(self, X: np.ndarray) -> Any:
        import pandas as pd

        X = np.atleast_2d(X)
        return pd.DataFrame({f.name: f.decode(X[:, j]) for j, f in enumerate(self.space.factors)})

    def table(self, X: np.ndarray) -> dict:
        """Per response: the prediction frame (``predicted`` and the interval ends) and ``poe``."""
        from .poe import propagation_of_error

        frame = self.frame(X)
        out = {}
        for g in self.goals:
            r = g.response
            iv = self.intervals.get(r)
            p = self.fits[r].predict(frame, interval="both" if iv in ("ci", "pi") else None, alpha=self.alpha,
                                     tolerance=self.tolerance if iv == "ti" else None)
            if self.sds:
                p["poe"] = propagation_of_error(self.fits[r], frame, self.sds)
            out[r] = p
        return out


def _judged(goal: Any, interval: str | None, p: Any, poe: bool) -> tuple[str, np.ndarray, np.ndarray | None]:
    """``(name, value, second)``: the value a goal judges (and for target/range the other end)."""
    if poe:
        return "poe", p["poe"].to_numpy(), None
    if interval is None:
        return "mean", p["predicted"].to_numpy(), None
    lo, hi = INTERVALS[interval]
    if goal.goal == "maximize":
        return lo, p[lo].to_numpy(), None
    if goal.goal == "minimize":
        return hi, p[hi].to_numpy(), None
    return f"{lo}/{hi}", p[lo].to_numpy(), p[hi].to_numpy()


def optimize_robust(fits: Mapping[str, Any], goals: Sequence[Any], *, poe: Sequence[str] = (), intervals: Mapping[str, Any] | None = None,
                    factor_sd: Mapping[str, Any] | Sequence[str] | None = None, confidence: float = 0.95,
                    tolerance: float = 0.99, bounds: Any = None, constraints: Any = None,
                    desirability: bool | None = None, seed: int = 0, n_sobol: int = 128,
                    n_polish: int = 4) -> RobustOptimum:
    """The optimum of goals judged on interval ends or on the POE (see the module docstring).

    Parameters
    ----------
    fits : mapping of response -> FitResult
    goals : sequence of ResponseGoal
        :class:`rsm_lrg.optimize.desirability.ResponseGoal` per response (from
        :func:`parse_robust_goal`, which also says whether the goal is ``poe``).
    poe : sequence of str
        The responses whose goal (``minimize``) applies to their POE rather than to the response.
    intervals : mapping, optional
        ``{response: "ci" | "pi" | "ti" | None}``.
    factor_sd : mapping or list of str, optional
        ``{factor: SD}`` [actual units] (needed by a ``poe`` goal; reported with every response).
    confidence : float
        C of the intervals.
    tolerance : float
        P of the tolerance interval.
    bounds, constraints
        As for :func:`rsm_lrg.optimize.optimize`.
    desirability : bool, optional
        Force (or forbid) desirability; default: with several responses or any limits.
    seed, n_sobol, n_polish
        The start set and the number of starts polished.
    """
    from scipy.stats import qmc

    from .desirability import individual_desirability, overall_desirability
    from .poe import mixture_components, parse_factor_sd
    from .region import feasible_mask, parse_constraints
    from .single import parse_bounds, split_bounds

    if not goals:
        raise ValueError("give at least one response goal")
    ivs = {r: parse_interval(v) for r, v in (intervals or {}).items()}
    first = fits[goals[0].response]
    space = first.space
    if first.mixture and (bounds or constraints):
        raise ParameterError("bound", "bounds and constraints are not yet taken by the interval/POE optimum of a "
                                      "mixture (the components' own bounds are)")
    if not 0.0 < float(confidence) < 1.0:
        raise ParameterError("confidence", f"confidence must lie strictly between 0 and 1, not {confidence!r}")
    sds = parse_factor_sd(space, factor_sd)
    poes = set(poe)
    if poes and not sds:
        raise ParameterError("factor_sd", "factor_sd: the poe goal needs the factors' SDs (NAME=SD)")
    for g in goals:
        if g.response in poes and ivs.get(g.response):
            raise ParameterError("interval", f"interval for {g.response!r}: a poe goal takes no interval")
    obj = _Objective(fits, goals, ivs, sds, float(confidence), float(tolerance))
    use_d = desirability if desirability is not None else (len(goals) > 1 or any(
        g.low is not None or g.high is not None for g in goals))
    k = len(space)
    numeric_bounds, held = split_bounds(space, bounds)
    lo, hi, notes = parse_bounds(space, numeric_bounds)
    cons = parse_constraints(constraints, space)
    cats = [j for j, f in enumerate(space.factors) if f.kind == "categoric"]
    combos = [c for c in space.level_combinations() if all(c[n] in v for n, v in held.items())]
    if not combos:
        raise ParameterError("bound", "no level combination is allowed by the bounds")

    if use_d:  # limits: the observed range of the response (of the POE at the runs for a poe goal)
        runs = np.column_stack([first.coded[L].to_numpy(dtype=float) for L in space.letters])
        at_runs = obj.table(runs)
        lim = []
        for g in goals:
            v = at_runs[g.response]["poe" if g.response in poes else "predicted"].to_numpy()
            if g.response not in poes:
                f = fits[g.response]
                v = f.transform.inverse(np.asarray(f.y, dtype=float))
            lim.append(g.with_limits(float(np.nanmin(v)), float(np.nanmax(v))))
        goals = lim

    def score(X: np.ndarray) -> tuple[np.ndarray, list, dict]:
        t = obj.table(X)
        ds: list[np.ndarray] = []
        for g in goals if use_d else ():
            _, v, w = _judged(g, ivs.get(g.response), t[g.response], g.response in poes)
            d = individual_desirability(v, g)
            if w is not None:
                d = np.minimum(d, individual_desirability(w, g))
            ds.append(d)
        if use_d:
            return -overall_desirability(ds, goals), ds, t
        g = goals[0]
        _, v, w = _judged(g, ivs.get(g.response), t[g.response], g.response in poes)
        if g.goal == "maximize":
            val = -v
        elif g.goal == "minimize":
            val = v
        else:  # target: the larger distance of the ends from the target
            T = float(g.target) if g.target is not None else 0.0
            val = np.abs(v - T) if w is None else np.maximum(np.abs(v - T), np.abs(w - T))
        return val, ds, t

    comps = mixture_components(space) if first.mixture else []
    if comps:  # L-pseudo components: each in [0, (U - L)/R], the last one the rest of the total
        for j in comps:
            f = space.factors[j]
            lo[j], hi[j] = 0.0, min(1.0, (f.upper - f.lower) / f.pseudo_range)

    def complete(X: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The blend closed by its last component, and whether it lies inside the bounds."""
        X = np.array(np.atleast_2d(X), dtype=float)
        if not comps:
            return X, np.ones(len(X), dtype=bool)
        X[:, comps[-1]] = 1.0 - X[:, comps[:-1]].sum(axis=1)
        last = X[:, comps[-1]]
        return X, (last >= lo[comps[-1]] - 1e-12) & (last <= hi[comps[-1]] + 1e-12)

    def f_many(X: np.ndarray) -> np.ndarray:
        X, ok = complete(X)
        val = np.full(len(X), np.inf)
        if ok.any():
            v = score(X[ok])[0]
            val[ok] = np.where(np.isfinite(v), v, np.inf)
        if cons is not None:
            val = np.where(feasible_mask(X, cons), val, np.inf)
        return val

    best_x, best_v, n_starts = None, math.inf, 0
    for combo in combos:  # categoric factors: each allowed combination of levels, held (lo = hi)
        lo_c, hi_c = lo.copy(), hi.copy()
        for j in cats:
            f = space.factors[j]
            lo_c[j] = hi_c[j] = float(f.index(combo[f.name]))
        starts = [np.clip(np.zeros(k), lo_c, hi_c), (lo_c + hi_c) / 2]
        if comps:  # the centroid of the blends
            c = np.clip(np.zeros(k), lo_c, hi_c)
            c[comps] = 1.0 / len(comps)
            starts.append(np.clip(c, lo_c, hi_c))
        if k - len(cats) <= 6:
            starts += [np.where(np.array(v) > 0, hi_c, lo_c) for v in itertools.product((0, 1), repeat=k)
                       if not any(v[j] for j in cats)]
        m = max(3, int(math.ceil(math.log2(max(n_sobol, 8)))))
        starts += list(lo_c + qmc.Sobol(d=k, scramble=True, seed=seed).random_base2(m) * (hi_c - lo_c))
        S = np.array(starts)
        n_starts += len(S)
        vals = f_many(S)
        keep = [i for i in np.argsort(vals)[:n_polish] if np.isfinite(vals[i])]
        if not keep:
            continue
        x, v = compass_search(f_many, S[keep], vals[keep], lo_c, hi_c)
        if best_x is None or v < best_v:
            best_x, best_v = x, v
    if best_x is None:
        from .region import INFEASIBLE

        raise ValueError(INFEASIBLE)
    best_x = complete(best_x)[0][0]
    val, ds, t = score(best_x[None, :])
    responses = {}
    for i, g in enumerate(goals):
        p = t[g.response].iloc[0]
        iv = ivs.get(g.response)
        name, v, w = _judged(g, iv, t[g.response], g.response in poes)
        ends = INTERVALS[iv] if iv else (None, None)
        goal_text = POE if g.response in poes else (g.goal if g.goal != "target" else f"target={g.target:g}")
        responses[g.response] = {
            "goal": goal_text, "interval": iv, "predicted": float(p["predicted"]),
            "low": float(p[ends[0]]) if ends[0] else None, "high": float(p[ends[1]]) if ends[1] else None,
            "optimised": name, "value": float(v[0]) if w is None else [float(v[0]), float(w[0])],
            "poe": float(p["poe"]) if "poe" in p.index else None,
            "d": float(ds[i][0]) if use_d else None}
    D = float(-val[0]) if use_d else None
    warns = list(notes)
    if use_d and D is not None and D <= 0:
        warns.append("no setting in the box meets every response's limits on the judged values (D = 0)")
    actual = {f.name: (f.levels[int(round(x))] if f.kind == "categoric" else float(f.decode(x)))
              for f, x in zip(space.factors, best_x)}
    return RobustOptimum(actual=actual, coded={L: float(x) for L, x in zip(space.letters, best_x)}, responses=responses,
                         desirability=D, confidence=float(confidence),
                         tolerance=float(tolerance) if any(v == "ti" for v in ivs.values()) else None,
                         factor_sd=sds, n_starts=n_starts, warnings=tuple(warns))


def compass_search(f_many: Any, X0: np.ndarray, v0: np.ndarray, lo: np.ndarray, hi: np.ndarray, *,
                   step: float = 0.25, tol: float = 1e-7, max_rounds: int = 400) -> tuple[np.ndarray, float]:
    """Minimise ``f_many`` (a batch of coded points in, values out) from the rows of ``X0`` by
    a compass search inside the box, all starts at once: each round evaluates every start's
    2k neighbours ``x ± h e_i`` (clipped to the box) in one batch; a start moves to its best
    neighbour when that improves, else its step halves, down to ``tol`` (coded units).
    Derivative-free (an interval end or a desirability has kinks) and cheap per round.

    Returns
    -------
    (ndarray, float)
        The best point [coded units] and its value.
    """
    X = np.array(X0, dtype=float)
    v = np.array(v0, dtype=float)
    n, k = X.shape
    h = np.full(n, float(step))
    E = np.vstack([np.eye(k), -np.eye(k)])
    for _ in range(max_rounds):
        active = h >= tol
        if not active.any():
            break
        idx = np.flatnonzero(active)
        cand = np.clip(X[idx, None, :] + h[idx, None, None] * E[None, :, :], lo, hi)
        cv = np.asarray(f_many(cand.reshape(-1, k)), dtype=float).reshape(len(idx), 2 * k)
        j = np.argmin(cv, axis=1)
        better = cv[np.arange(len(idx)), j] < v[idx]
        for a, i in enumerate(idx):
            if better[a]:
                X[i], v[i] = cand[a, j[a]], cv[a, j[a]]
            else:
                h[i] /= 2.0
    b = int(np.argmin(v))
    return X[b] + 0.0, float(v[b])


def parse_robust_goal(response: str, goal: str | None, **kwargs: Any) -> tuple[Any, bool]:
    """``(ResponseGoal, is_poe)`` from a goal string: ``poe`` is "minimise the POE" (a
    minimize goal on the POE); the others as
    :func:`rsm_lrg.optimize.desirability.parse_response_goal` (``kwargs``: weight, importance,
    limits)."""
    from .desirability import parse_response_goal

    text = "minimize" if goal is None else str(goal)
    if text.strip().lower() == POE:
        return parse_response_goal(response, "minimize", **kwargs), True
    return parse_response_goal(response, text, **kwargs), False
