"""Single-response optimisation of a fitted surface inside the factor box.

Goals: ``"minimize"``, ``"maximize"`` or a target ``T`` (minimise ``(ŷ - T)²``). The
search runs in coded units over the box [-1, 1]^k, or over tighter bounds given in actual
units. Two routes are combined so that the global optimum is found:

* for a second-order (or lower) model, an exact enumeration of the faces of the box: for
  every split of the factors into "at the lower bound", "at the upper bound" and "free",
  the stationary point of the quadratic restricted to that face is solved from a small
  linear system and kept if it lies in the box. The best of these is the global optimum
  of a quadratic on a box (used up to 8 factors, 3^8 faces). A target T is then hit
  exactly: the extreme nearest T, or a root of ŷ = T on the segment from the minimiser to
  the maximiser. One local polish from the centre runs as a cross-check;
* a deterministic multi-start of ``scipy.optimize.minimize`` (L-BFGS-B with the analytic
  gradient) from the centre, the vertices (k <= 6), the stationary point when it lies in
  the box, and a scrambled Sobol set with a fixed seed, for cubic models and more than 8
  factors.

With blocks the prediction is for the average block (sum-to-zero effects, block effect 0).
The paper's optimum (Sec. 4.3): minimising κ on Table 4 gives every factor at its low
level, κ = 0.02283 °C/min.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from ..errors import ParameterError
from ..model.build.goals import parse_goal
from ..model.readings.levels import LevelView  # the optimisers' view of a fit at one level combination
from .result import OptimumResult, optimum_notes

__all__ = ["optimize", "OptimumResult", "parse_goal", "parse_bounds"]

def parse_bounds(space, bounds, *, allow_extrapolation: bool = False):
    """Coded lower/upper bounds from ``{name or letter: (low, high)}`` in actual units
    (or ``["NAME=LOW:HIGH", ...]``); factors not named keep [-1, 1].

    Returns ``(lo, hi, warnings)``. A bound beyond the factor's design range is an error
    unless ``allow_extrapolation`` (then it is kept and a warning is returned).

    Parameters
    ----------
    space : FactorSpace
        The factors.
    bounds : mapping or list of str, optional
        ``{name or letter: (low, high)}`` in actual units, or ``["NAME=LOW:HIGH", ...]``.
    allow_extrapolation : bool, default False
        Allow bounds beyond the design range (with a warning).

    Returns
    -------
    tuple
        ``(lo, hi, warnings)``: coded bounds (arrays) and the warnings.
    """
    from ..factors import parse_factor_spec

    k = len(space)
    lo, hi = -np.ones(k), np.ones(k)
    notes: list[str] = []
    if bounds is None:
        return lo, hi, notes
    if not isinstance(bounds, Mapping):
        items = {}
        for s in bounds:
            name, a, b = parse_factor_spec(s)
            if a is None:
                raise ParameterError("bound", f"bound {s!r}: expected NAME=LOW:HIGH")
            if name in items:
                raise ParameterError("bound", f"bound for {name!r} is given more than once")
            items[name] = (a, b)
        bounds = items
    for key, pair in bounds.items():
        try:
            f = space[key]
        except KeyError:
            raise ParameterError("bound", f"bound for {key!r}: no such factor (factors: {', '.join(space.names)})") from None
        try:
            a, b = (float(v) for v in pair)
        except (TypeError, ValueError):
            raise ParameterError("bound", f"bound for {key!r}: expected (LOW, HIGH), got {pair!r}") from None
        if not (math.isfinite(a) and math.isfinite(b)):
            raise ParameterError("bound", f"bound for {f.name!r}: LOW and HIGH must be finite numbers")
        if not a < b:
            raise ParameterError("bound", f"bound for {f.name!r}: LOW must be below HIGH (got {a:g} >= {b:g})")
        span = f.high - f.low
        if a < f.low - 1e-9 * span or b > f.high + 1e-9 * span:
            msg = (f"bound for {f.name!r} ({a:g}..{b:g}) reaches outside the design range "
                   f"{f.low:g}..{f.high:g}")
            if not allow_extrapolation:
                raise ValueError(msg + "; give a bound inside the design range (in Python, "
                                 "allow_extrapolation=True searches outside it)")
            notes.append(msg + ": the optimum may be an extrapolation")
        i = space.names.index(f.name)
        lo[i], hi[i] = f.encode(a), f.encode(b)
        if not allow_extrapolation:
            lo[i], hi[i] = max(lo[i], -1.0), min(hi[i], 1.0)
    return lo, hi, notes


def _exact_quadratic(b, B, lo, hi, sign):
    """Global minimum of ``sign * (x'b + x'Bx)`` over the box by enumerating faces."""
    k = b.size
    bs, Bs = sign * b, sign * B
    best_x, best_v = None, math.inf
    for state in itertools.product((0, 1, 2), repeat=k):  # 0 free, 1 lower, 2 upper
        st = np.array(state)
        x = np.where(st == 1, lo, np.where(st == 2, hi, 0.0))
        free = np.flatnonzero(st == 0)
        if free.size:
            fixed = np.flatnonzero(st != 0)
            H = 2.0 * Bs[np.ix_(free, free)]
            rhs = -(bs[free] + 2.0 * Bs[np.ix_(free, fixed)] @ x[fixed])
            try:
                xf = np.linalg.solve(H, rhs)
            except np.linalg.LinAlgError:
                continue
            if not np.all(np.isfinite(xf)) or np.linalg.norm(H @ xf - rhs) > 1e-9 * (np.linalg.norm(rhs) + np.abs(H).max()):
                continue
            tol = 1e-9
            if np.any(xf < lo[free] - tol) or np.any(xf > hi[free] + tol):
                continue
            x[free] = np.clip(xf, lo[free], hi[free])
        v = float(x @ bs + x @ Bs @ x)
        if best_x is None or v < best_v - 1e-15 * max(1.0, abs(best_v)):
            best_x, best_v = x, v
    return best_x


def optimize(fitted, goal="minimize", bounds=None, *, confidence: float = 0.95,
             allow_extrapolation: bool = False, seed: int = 0, constraints=None) -> OptimumResult:
    """Optimise a fitted response inside the factor box (and over every combination of the
    levels of its categoric factors).

    With categoric factors the numeric surface at each combination of levels is optimised
    as below, and the best combination wins; ``by_level`` of the result lists the best
    setting of every combination. A categoric factor is held at one level (or a subset)
    with ``bounds={"stage": "rms"}`` or ``["stage=rms"]`` (``"stage=rms,mixed"``).

    Parameters
    ----------
    fitted : FitResult
        A fit (from :func:`rsm_lrg.fit`). The optimize layer takes fitted results, never
        data: fit first, ``rsm_lrg.optimize(rsm_lrg.fit(data, response), goal)``.
    goal : str or tuple
        ``"minimize"``, ``"maximize"``, ``"target=V"`` or ``("target", V)``.
    bounds : mapping or list of str, optional
        Tighter bounds in actual units, ``{name: (low, high)}`` or ``["NAME=LOW:HIGH"]``.
        Bounds must lie inside the design range unless ``allow_extrapolation=True``
        (then a warning is recorded in the result).
    confidence : float
        Level of the confidence and prediction intervals (0.95).
    seed : int
        Seed of the Sobol start set (the search is deterministic for a given seed).
    constraints : str or list of str, optional
        Inequalities on the numeric factors in actual units, as for the designs
        (:class:`rsm_lrg.design.constraints.Constraints`: ``"velocity_m_s**2/acceleration_m_s2
        <= stroke_m"``, ``"0.5*A + B <= 1.2"``): the optimum satisfies every one (SLSQP from
        feasible starts; the exact face enumeration is used only where it is feasible).

    Returns
    -------
    OptimumResult
    """
    from ..model.results.glm_result import GLMResult
    from ..model.results.result import FitResult

    if not isinstance(fitted, (FitResult, GLMResult, LevelView)) and _is_surface(fitted):
        # another kind of fitted model (a Gaussian process): through the prediction contract only
        if not 0.0 < confidence < 1.0:
            raise ParameterError("confidence", f"confidence must lie between 0 and 1, not {confidence!r}")
        return _optimize_contract(fitted, goal, bounds, confidence=confidence,
                                  allow_extrapolation=allow_extrapolation, seed=seed,
                                  constraints=_constraint_texts(constraints))
    if not isinstance(fitted, (FitResult, GLMResult, LevelView)):  # a fit, or one at a level combination
        raise TypeError(f"optimize() takes a fitted result (FitResult), not {type(fitted).__name__}: fit first, "
                        "e.g. rsm_lrg.optimize(rsm_lrg.fit(data, response), goal)")
    if not 0.0 < confidence < 1.0:
        raise ParameterError("confidence", f"confidence must lie between 0 and 1, not {confidence!r}")
    exprs = _constraint_texts(constraints)
    if fitted.space.has_components:  # the constrained simplex (rsm_lrg.optimize.mixture)
        from .mixture import optimize_mixture

        return optimize_mixture(fitted, goal, bounds, confidence=confidence, constraints=exprs)
    if fitted.space.has_categoric:
        return _optimize_categoric(fitted, goal, bounds, confidence=confidence,
                                   allow_extrapolation=allow_extrapolation, seed=seed, constraints=exprs)
    return _optimize_numeric(fitted, goal, bounds, confidence=confidence, allow_extrapolation=allow_extrapolation,
                             seed=seed, constraints=exprs)


def _is_surface(fitted: Any) -> bool:
    """A fitted model that answers the prediction contract's surface (``space``,
    ``predict_coded``, ``predict`` and ``goal_on_model_scale``) without polynomial terms."""
    return all(hasattr(fitted, a) for a in ("space", "predict_coded", "predict", "goal_on_model_scale", "transform"))


#: Sobol starts of the multistart search on a surface that is not a polynomial (2^m points).
CONTRACT_STARTS_LOG2 = 6


def _optimize_contract(fitted: Any, goal: Any, bounds: Any, *, confidence: float, allow_extrapolation: bool,
                       seed: int, constraints: Any = ()) -> OptimumResult:
    """:func:`optimize` for a model known by the prediction contract alone (a Gaussian process:
    no terms, no stationary point): multistart L-BFGS-B (SLSQP inside constraints) on
    ``predict_coded`` from the best points of a scrambled Sobol sample of the region, the box's
    centre and corners; the intervals from ``predict``."""
    from scipy.stats import qmc

    from .region import feasible_only, local_minima, parse_constraints, region_starts

    space = fitted.space
    if space.has_components or space.has_categoric:
        raise ParameterError("model", "optimize on this kind of model takes numeric factors only")
    goal_kind, goal_target, kind, target = fitted.goal_on_model_scale(goal)
    lo, hi, notes = parse_bounds(space, bounds, allow_extrapolation=allow_extrapolation)
    cons = parse_constraints(list(constraints or []), space)
    k = len(space)
    sample = lo + qmc.Sobol(d=k, scramble=True, seed=seed).random_base2(max(CONTRACT_STARTS_LOG2, k + 2)) * (hi - lo)
    ys = fitted.predict_coded(sample)
    scale = float(np.max(np.abs(ys))) or 1.0

    def value(X: np.ndarray) -> np.ndarray:
        y = np.asarray(fitted.predict_coded(np.atleast_2d(X)), dtype=float)
        if kind == "target":
            return ((y - target) / scale) ** 2
        return (1.0 if kind == "minimize" else -1.0) * y / scale

    def obj(x: np.ndarray) -> float:
        return float(value(np.asarray(x, dtype=float))[0])

    v = value(sample)
    starts = [np.clip(np.zeros(k), lo, hi), (lo + hi) / 2.0]
    if k <= 6:
        starts += [np.where(np.array(b) > 0, hi, lo) for b in itertools.product((0, 1), repeat=k)]
    starts += list(sample[np.argsort(v)[:8]])
    starts += region_starts(cons, lo, hi, seed)
    candidates = feasible_only(local_minima(obj, starts, lo, hi, cons, jac=False), cons)
    if not candidates:
        raise ParameterError("constraints", "no feasible setting found inside the bounds and the constraints")
    values = value(np.array(candidates))
    best = np.asarray(candidates[int(np.argmin(values))], dtype=float)
    span = hi - lo
    best = np.where(np.abs(best - lo) <= 1e-9 * span, lo, best)
    best = np.where(np.abs(best - hi) <= 1e-9 * span, hi, best) + 0.0
    pr = fitted.predict(best[None, :], interval="both", alpha=1.0 - confidence, coded=True).iloc[0]
    missed = kind == "target" and abs(float(fitted.predict_coded(best[None, :])[0]) - target) > 1e-3 * scale
    notes += optimum_notes(fitted, goal_target, float(pr["predicted"]), missed)
    coded = {L: float(x) for L, x in zip(space.letters, best)}
    actual = {f.name: float(f.decode(x)) for f, x in zip(space.factors, best)}
    bnds = {f.name: (float(f.decode(a)), float(f.decode(b))) for f, a, b in zip(space.factors, lo, hi)}
    return OptimumResult(
        response=fitted.response, goal=goal_kind, target=goal_target, coded=coded, actual=actual,
        predicted=float(pr["predicted"]), confidence=float(confidence),
        ci=(float(pr["ci_low"]), float(pr["ci_high"])), pi=(float(pr["pi_low"]), float(pr["pi_high"])),
        se_fit=float(pr["se_fit"]), bounds=bnds, warnings=tuple(notes), n_starts=len(starts), method="multistart",
    )


def _constraint_texts(constraints) -> list[str]:
    from .region import constraint_texts

    return constraint_texts(constraints)


def _optimize_numeric(fitted, goal, bounds, *, confidence: float, allow_extrapolation: bool,
                      seed: int, constraints=()) -> OptimumResult:
    """:func:`optimize` for a fit (or a :class:`LevelView`) whose factors are all numeric."""
    from scipy import optimize as so

    from ..model.build.terms import design_gradient, design_matrix
    from ..model.readings.canonical import quadratic_parts
    from .region import feasible_only, is_feasible, local_minima, parse_constraints, region_starts

    # the goal as asked (response units) and on the model's scale (a transform maps it)
    goal_kind, goal_target, kind, target = fitted.goal_on_model_scale(goal)
    space = fitted.space
    lo, hi, notes = parse_bounds(space, bounds, allow_extrapolation=allow_extrapolation)
    cons = parse_constraints(list(constraints or []), space)
    terms = fitted.terms
    beta = fitted.coefficients["coded"].to_numpy(dtype=float)
    k = len(space)

    quadratic = all(t.order <= 2 for t in terms)
    if quadratic:  # closed form b0 + x'b + x'Bx (fast, exact)
        coefs = dict(zip(fitted.coefficients.index, beta))
        b0, bq, Bq = quadratic_parts(coefs, terms, k)

        def yhat(x):
            return float(b0 + x @ bq + x @ Bq @ x)

        def grad_y(x):
            return bq + 2.0 * Bq @ x
    else:
        def yhat(x):
            return float(design_matrix(x, terms)[0] @ beta)

        def grad_y(x):
            return design_gradient(x, terms).T @ beta

    scale = float(np.max(np.abs(beta))) or 1.0  # objective of order 1 for the optimiser
    if kind == "target":
        def obj(x):
            r = (yhat(x) - target) / scale
            return r * r, 2.0 * r * grad_y(x) / scale
    else:
        sgn = (1.0 if kind == "minimize" else -1.0) / scale

        def obj(x):
            return sgn * yhat(x), sgn * grad_y(x)

    candidates = []
    method = "multistart"
    if quadratic and k <= 8:
        if kind == "target":
            # exact: the extreme nearest the target, or a root of y - T on the segment
            # from the minimiser to the maximiser (the box is convex, y continuous)
            xmin = _exact_quadratic(bq, Bq, lo, hi, 1.0)
            xmax = _exact_quadratic(bq, Bq, lo, hi, -1.0)
            if xmin is not None and xmax is not None:
                ymin, ymax = yhat(xmin), yhat(xmax)
                if target <= ymin:
                    candidates.append(xmin)
                elif target >= ymax:
                    candidates.append(xmax)
                else:
                    g = lambda t: yhat(xmin + t * (xmax - xmin)) - target  # noqa: E731
                    t = so.brentq(g, 0.0, 1.0, xtol=1e-15)
                    candidates.append(xmin + t * (xmax - xmin))
        else:
            xe = _exact_quadratic(bq, Bq, lo, hi, 1.0 if kind == "minimize" else -1.0)
            if xe is not None:
                candidates.append(xe)
        if candidates:
            method = "exact-faces+multistart"

    if cons is not None:  # the face enumeration ignores the constraints: keep its point only if feasible
        candidates = [c for c in candidates if is_feasible(c, cons)]
        method = "exact-faces+multistart" if candidates else "multistart"
    exact = bool(candidates) and cons is None
    starts = [np.clip(np.zeros(k), lo, hi)]
    if not exact:
        starts.append((lo + hi) / 2.0)
    if k <= 6 and not exact:
        starts += [np.where(np.array(v) > 0, hi, lo) for v in itertools.product((0, 1), repeat=k)]
    sp = fitted.stationary_point
    if sp.coded is not None:
        xs = np.array([sp.coded[L] for L in space.letters])
        if np.all(xs >= lo) and np.all(xs <= hi):
            starts.append(xs)
    if not exact:  # the face enumeration is already the global optimum; else multi-start
        from scipy.stats import qmc  # only here: scipy.stats takes about a second to import

        m = max(3, int(math.ceil(math.log2(max(8, 4 * k)))))
        sob = qmc.Sobol(d=k, scramble=True, seed=seed).random_base2(m)
        starts += list(lo + sob * (hi - lo))
    starts += region_starts(cons, lo, hi, seed)  # feasible starts from the region sample too
    candidates += local_minima(obj, starts, lo, hi, cons, jac=True)
    candidates = feasible_only(candidates, cons)

    values = np.array([obj(c)[0] for c in candidates])
    i_best = int(np.argmin(values))
    if method != "multistart" and values[0] <= values[i_best] + 1e-12 * max(abs(values[i_best]), 1.0):
        i_best = 0  # prefer the exact face solution over a numerically equal local one
    best = candidates[i_best]
    # snap to the bounds within round-off
    span = hi - lo
    best = np.where(np.abs(best - lo) <= 1e-9 * span, lo, best)
    best = np.where(np.abs(best - hi) <= 1e-9 * span, hi, best)
    best = best + 0.0

    alpha = 1.0 - confidence
    pr = fitted.predict(best[None, :], interval="both", alpha=alpha, coded=True).iloc[0]
    missed = kind == "target" and abs(yhat(best) - target) > 1e-3 * scale  # judged on the model's scale
    notes += optimum_notes(fitted, goal_target, float(pr["predicted"]), missed)
    coded = {L: float(v) for L, v in zip(space.letters, best)}
    actual = {f.name: float(f.decode(v)) for f, v in zip(space.factors, best)}
    bnds = {f.name: (float(f.decode(a)), float(f.decode(b))) for f, a, b in zip(space.factors, lo, hi)}
    return OptimumResult(
        response=fitted.response, goal=goal_kind, target=goal_target, coded=coded, actual=actual,
        predicted=float(pr["predicted"]), confidence=float(confidence),
        ci=(float(pr["ci_low"]), float(pr["ci_high"])), pi=(float(pr["pi_low"]), float(pr["pi_high"])),
        se_fit=float(pr["se_fit"]), bounds=bnds, warnings=tuple(notes), n_starts=len(starts), method=method,
    )


# ----------------------------------------------------------------------------------------
# categoric factors: the numeric surface at each combination of levels
# ----------------------------------------------------------------------------------------
def split_bounds(space, bounds) -> tuple[Any, dict]:
    """Numeric bounds (as :func:`parse_bounds` takes them) and ``{categoric name: [levels]}``
    from ``{name: (low, high) | level | [levels]}`` or ``["NAME=LOW:HIGH", "stage=rms", ...]``."""
    if bounds is None:
        return None, {}
    items = bounds.items() if isinstance(bounds, Mapping) else [_split_spec(s) for s in bounds]
    numeric: dict = {}
    levels: dict = {}
    seen: set = set()
    for key, val in items:
        try:
            f = space[key]
        except KeyError:
            raise ParameterError("bound", f"bound for {key!r}: no such factor (factors: {', '.join(space.names)})") from None
        if f.name in seen:
            raise ParameterError("bound", f"bound for {f.name!r} is given more than once")
        seen.add(f.name)
        if f.kind == "categoric":
            vals = [val] if isinstance(val, str) or not hasattr(val, "__iter__") else list(val)
            levels[f.name] = [f.levels[f.index(v)] for v in vals]
        else:
            if isinstance(val, str):
                from ..factors import parse_factor_spec

                _, a, b = parse_factor_spec(f"{f.name}={val}")
                val = (a, b)
            numeric[f.name] = val
    return numeric, levels


def _split_spec(spec: str) -> tuple[str, str | list[str]]:
    if not isinstance(spec, str) or "=" not in spec:
        raise ParameterError("bound", f"bound {spec!r}: expected NAME=LOW:HIGH (numeric) or NAME=LEVEL[,LEVEL...] (categoric)")
    name, val = spec.split("=", 1)
    name, val = name.strip(), val.strip()
    if ":" in val:
        return name, val
    return name, [v.strip() for v in val.split(",")]


def _optimize_categoric(fitted, goal, bounds, *, confidence, allow_extrapolation, seed,
                        constraints=()) -> OptimumResult:
    kind, target = parse_goal(goal)
    space = fitted.space
    numeric, held = split_bounds(space, bounds)
    combos = [c for c in space.level_combinations() if all(c[k] in v for k, v in held.items())]
    best, rows = None, []
    for combo in combos:
        if not space.numeric:
            raise ValueError("every factor is categoric: compare the level predictions instead (no numeric optimum)")
        view = LevelView(fitted, combo)
        r = _optimize_numeric(view, goal, numeric, confidence=confidence, allow_extrapolation=allow_extrapolation,
                              seed=seed, constraints=constraints)
        if kind == "minimize":
            score = r.predicted
        elif kind == "maximize":
            score = -r.predicted
        else:
            assert target is not None  # parse_goal gives "target" with its value
            score = abs(r.predicted - target)
        rows.append({"level": dict(combo), "actual": {**r.actual, **combo}, "predicted": r.predicted})
        if best is None or score < best[0]:
            best = (score, combo, r)
    if best is None:
        raise ValueError("no combination of the categoric levels is inside the bounds")
    _, combo, r = best
    order = space.names
    letter = {f.name: f.letter for f in space.factors}
    actual = {n: (combo[n] if n in combo else r.actual[n]) for n in order}
    coded = {letter[n]: (combo[n] if n in combo else r.coded[letter[n]]) for n in order}
    bnds = {n: (list(held.get(n, space[n].levels)) if n in combo else r.bounds[n]) for n in order}
    from dataclasses import replace

    return replace(r, coded=coded, actual=actual, bounds=bnds, by_level=tuple(rows))
