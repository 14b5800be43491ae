"""The optimum of a fitted mixture model over the constrained simplex (and the process box).

The region (:func:`rsm_lrg.model.build.mixture_region.mixture_region`) is the polytope
``sum z = 1, G x <= h`` in coded units (L-pseudo components, coded process factors). Two
routes find the global optimum:

* **exact faces** (a model of at most second order in the coded factors: Scheffé linear
  or quadratic, a linear blending model crossed with process factors): on every face of the
  polytope, that is for every set ``S`` of at most ``k - 1`` rows of ``G`` held active
  together with the sum, the stationary point of the quadratic ``b'x + x'Bx`` on the face
  solves the KKT system

      [ 2B   A_S' ] [ x ]   [ -b  ]
      [ A_S   0   ] [ λ ] = [ h_S ]          (A_S: the sum row and the rows of S)

  and is kept when it lies in the region; the best of them is the global optimum (a
  continuous function on a polytope attains it on the relative interior of some face, where
  it is stationary). A target T is then hit exactly: the extreme nearest T, or a root of
  ``ŷ = T`` on the segment from the minimiser to the maximiser (the region is convex);
* **multistart** (special cubic, full cubic, mixture × process): SLSQP with the sum as an
  equality and ``G x <= h`` as linear inequalities (analytic gradients), from every vertex,
  the centroid, the midpoints of the edges between vertices (up to 2,000 pairs) and 64
  random blends of the vertices (Dirichlet weights, fixed seed); the best end point wins.

The prediction, confidence and prediction intervals at the optimum are
:meth:`rsm_lrg.model.FitResult.predict`'s.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..errors import ParameterError
from ..model.build.mixture_region import MixtureRegion, mixture_region

__all__ = ["optimize_mixture", "kkt_faces", "region_starts", "polish", "face_newton", "desirability_search",
           "limits_of", "SEED"]

#: Seed of the random blends among the starts.
SEED = 20240


def kkt_faces(b: np.ndarray, B: np.ndarray, region: MixtureRegion, sign: float) -> np.ndarray | None:
    """The global minimum of ``sign * (b'x + x'Bx)`` over ``region`` by enumerating its faces
    (see the module docstring); ``None`` when the region has too many faces
    (:data:`rsm_lrg.model.build.mixture_region.MAX_ACTIVE_SETS`)."""
    from ..model.build.mixture_region import MAX_ACTIVE_SETS

    if region.n_faces() > MAX_ACTIVE_SETS:
        return None
    k = region.k
    bs, Bs = sign * np.asarray(b, dtype=float), sign * np.asarray(B, dtype=float)
    E = region.E[None, :]
    best_x, best_v = None, math.inf
    for S in region.faces():
        A = np.vstack([E, region.G[list(S)]]) if S else E
        rhs = np.concatenate([[1.0], region.h[list(S)]]) if S else np.array([1.0])
        na = A.shape[0]
        K = np.block([[2.0 * Bs, A.T], [A, np.zeros((na, na))]])
        try:
            sol = np.linalg.solve(K, np.concatenate([-bs, rhs]))
        except np.linalg.LinAlgError:
            continue
        if not np.all(np.isfinite(sol)):
            continue
        resid = K @ sol - np.concatenate([-bs, rhs])
        if np.max(np.abs(resid)) > 1e-8 * (1.0 + np.max(np.abs(K)) * np.max(np.abs(sol))):
            continue  # (numerically) singular: a lower face holds the optimum
        x = sol[:k]
        if not region.contains(x)[0]:
            continue
        v = float(x @ bs + x @ Bs @ x)
        if best_x is None or v < best_v - 1e-14 * max(1.0, abs(best_v)):
            best_x, best_v = x, v
    return best_x


def region_starts(region: MixtureRegion, seed: int = SEED, n_random: int = 64) -> np.ndarray:
    """Start points of the multistart: the vertices, their centroid, edge midpoints (up to
    2,000 pairs of vertices) and ``n_random`` random convex combinations of the vertices."""
    V = region.vertices()
    pts = [V, V.mean(axis=0)[None, :]]
    n = len(V)
    if n > 1:
        pairs = [(i, j) for i in range(n) for j in range(i + 1, n)][:2000]
        pts.append(np.array([(V[i] + V[j]) / 2.0 for i, j in pairs]))
    rng = np.random.default_rng(seed)
    W = rng.dirichlet(np.ones(n), size=n_random)
    pts.append(W @ V)
    return np.vstack(pts)


def polish(obj: Any, starts: np.ndarray, region: MixtureRegion, maxiter: int = 400, *,
           jac: bool = True) -> list[np.ndarray]:
    """End points (and the starts) of SLSQP from each start: ``obj(x) -> (value, gradient)``
    (``jac=False``: ``obj(x) -> value``, differences taken by SciPy), the sum as an equality
    and ``G x <= h`` as inequalities; only points in the region are kept."""
    from scipy import optimize as so

    E, G, h = region.E, region.G, region.h
    cons = [{"type": "eq", "fun": lambda x: np.array([x @ E - 1.0]), "jac": lambda x: E[None, :]},
            {"type": "ineq", "fun": lambda x: h - G @ x, "jac": lambda x: -G}]
    out = []
    for x0 in starts:
        if region.contains(x0)[0]:
            out.append(np.asarray(x0, dtype=float))
        try:
            r = so.minimize(obj, x0, jac=jac, method="SLSQP", constraints=cons,
                            options={"ftol": 1e-15, "maxiter": maxiter})
        except (ValueError, FloatingPointError):
            continue
        if np.all(np.isfinite(r.x)) and region.contains(r.x, tol=1e-8)[0]:
            out.append(_project(r.x, region))
    return out


def face_newton(obj: Any, x: np.ndarray, region: MixtureRegion, steps: int = 8) -> np.ndarray:
    """Newton steps on the KKT conditions of the face active at ``x`` (rows within ``1e-7``
    of equality, with the sum): SLSQP stops about ``1e-8`` short of a stationary point of a
    cubic; a few Newton steps (Hessian by central differences of the analytic gradient) finish
    it. A step is kept only when it stays in the region and does not worsen the objective."""
    x = np.asarray(x, dtype=float)
    act = np.flatnonzero(region.G @ x - region.h >= -1e-7 * (1.0 + np.abs(region.h)))
    A = np.vstack([region.E[None, :], region.G[act]])
    if np.linalg.matrix_rank(A) < A.shape[0]:
        A = A[:1]  # degenerate vertex: keep the sum only (the step below must then stay feasible)
    b = A @ x
    k, na = region.k, A.shape[0]
    if na >= k:
        return x
    f = obj(x)[0]
    for _ in range(steps):
        g = obj(x)[1]
        eps = 1e-5
        H = np.empty((k, k))
        for i in range(k):
            e = np.zeros(k)
            e[i] = eps
            H[:, i] = (obj(x + e)[1] - obj(x - e)[1]) / (2 * eps)
        H = (H + H.T) / 2.0
        K = np.block([[H, A.T], [A, np.zeros((na, na))]])
        try:
            step = np.linalg.solve(K, np.concatenate([-g, b - A @ x]))[:k]
        except np.linalg.LinAlgError:
            break
        y = x + step
        if not np.all(np.isfinite(y)) or not region.contains(y, tol=1e-12)[0]:
            break
        fy = obj(y)[0]
        if fy > f + 1e-15 * max(1.0, abs(f)):
            break
        done = np.max(np.abs(step)) <= 1e-15
        x, f = y, fy
        if done:
            break
    return x


def _project(x: np.ndarray, region: MixtureRegion) -> np.ndarray:
    """``x`` with round-off removed: a coordinate within ``1e-8`` of one of its bounds (the
    tolerance :func:`polish` keeps) put on it, the components rescaled to sum to one, the residue of the sum given to the component
    farthest from its bounds."""
    x = np.array(x, dtype=float)
    lo, hi = _coordinate_bounds(region)
    x = np.where(np.abs(x - lo) <= 1e-8, lo, x)
    x = np.where(np.abs(x - hi) <= 1e-8, hi, x)
    x = np.clip(x, lo, hi)
    c = list(region.comps)
    x[c] = x[c] / math.fsum(x[c])
    slack = np.minimum(x[c] - lo[c], hi[c] - x[c])
    j = c[int(np.argmax(slack))]
    x[j] = 1.0 - math.fsum(x[i] for i in c if i != j)
    return x + 0.0


def _coordinate_bounds(region: MixtureRegion) -> tuple[np.ndarray, np.ndarray]:
    """Each coordinate's own bounds from the single-coordinate rows of ``G x <= h``."""
    lo, hi = np.full(region.k, -np.inf), np.full(region.k, np.inf)
    for g, h in zip(region.G, region.h):
        nz = np.flatnonzero(g)
        if nz.size == 1:
            j = int(nz[0])
            if g[j] > 0:
                hi[j] = min(hi[j], h / g[j])
            else:
                lo[j] = max(lo[j], h / g[j])
    return lo, hi


def optimize_mixture(fitted: Any, goal: Any = "minimize", bounds: Any = None, *, confidence: float = 0.95,
                     constraints: Any = None, seed: int = SEED) -> Any:
    """The optimum of a mixture fit over the constrained simplex (see the module docstring).

    Parameters
    ----------
    fitted : FitResult
        A Scheffé mixture fit (``fitted.mixture``).
    goal : str or tuple
        ``"minimize"``, ``"maximize"``, ``"target=V"`` or ``("target", V)`` (on the
        response's own scale, mapped through a transform as for every fit).
    bounds : mapping or list of str, optional
        Tighter limits, ``{name: (low, high)}`` or ``["NAME=LOW:HIGH"]``: components in
        real proportions (intersected with their bounds), process factors in actual units.
    confidence : float
        Level of the CI and PI (0.95).
    constraints : str or list of str, optional
        Linear inequalities on component names or letters (real proportions) and process
        factors: ``"A + B <= 0.6"``.

    Returns
    -------
    OptimumResult
        ``coded``: L-pseudo components (and coded process factors); ``actual``: real
        proportions summing to the total; ``bounds``: each factor's limits searched;
        ``method``: ``"exact-faces"`` or ``"multistart"``.
    """
    from scipy import optimize as so

    from ..model.build.terms import design_gradient, design_matrix
    from ..model.readings.canonical import quadratic_parts
    from .result import OptimumResult, optimum_notes

    if not 0.0 < confidence < 1.0:
        raise ParameterError("confidence", f"confidence must lie between 0 and 1, not {confidence!r}")
    goal_kind, goal_target, kind, target = fitted.goal_on_model_scale(goal)
    space = fitted.space
    region = mixture_region(space, bounds, constraints)
    terms = fitted.terms
    beta = fitted.coefficients["coded"].to_numpy(dtype=float)
    k = len(space)
    quadratic = all(t.order <= 2 for t in terms)
    if quadratic:
        b0, bq, Bq = quadratic_parts(dict(zip(fitted.coefficients.index, beta)), terms, k)

    def yhat(x: np.ndarray) -> float:
        return float(design_matrix(np.asarray(x, dtype=float)[None, :], terms)[0] @ beta)

    def grad_y(x: np.ndarray) -> np.ndarray:
        return np.asarray(design_gradient(np.asarray(x, dtype=float), terms).T @ beta, dtype=float)

    scale = float(np.max(np.abs(beta))) or 1.0
    if kind == "target":
        def obj(x: np.ndarray) -> tuple[float, np.ndarray]:
            r = (yhat(x) - target) / scale
            return r * r, 2.0 * r * grad_y(x) / scale
    else:
        sgn = (1.0 if kind == "minimize" else -1.0) / scale

        def obj(x: np.ndarray) -> tuple[float, np.ndarray]:
            return sgn * yhat(x), sgn * grad_y(x)

    best = None
    method = "multistart"
    n_starts = 0
    if quadratic:
        if kind == "target":
            xmin, xmax = kkt_faces(bq, Bq, region, 1.0), kkt_faces(bq, Bq, region, -1.0)
            if xmin is not None and xmax is not None:
                ymin, ymax = yhat(xmin), yhat(xmax)
                if target <= ymin:
                    best = xmin
                elif target >= ymax:
                    best = xmax
                else:
                    t = so.brentq(lambda s: yhat(xmin + s * (xmax - xmin)) - target, 0.0, 1.0, xtol=1e-15)
                    best = xmin + t * (xmax - xmin)
        else:
            best = kkt_faces(bq, Bq, region, 1.0 if kind == "minimize" else -1.0)
        if best is not None:
            method = "exact-faces"
    if best is None:
        starts = region_starts(region, seed)
        n_starts = len(starts)
        cands = polish(obj, starts, region)
        if not cands:
            raise ValueError("no blend in the region could be evaluated")
        vals = [obj(c)[0] for c in cands]
        best = face_newton(obj, cands[int(np.argmin(vals))], region)
    best = _project(best, region)
    pr = fitted.predict(best[None, :], interval="both", alpha=1.0 - confidence, coded=True).iloc[0]
    notes = optimum_notes(fitted, goal_target, float(pr["predicted"]),
                          kind == "target" and abs(yhat(best) - target) > 1e-3 * scale)
    actual = region.to_actual(best)
    notes += extrapolation_notes(fitted, actual)
    lims = limits_of(region)
    return OptimumResult(
        response=fitted.response, goal=goal_kind, target=goal_target,
        coded={L: float(v) for L, v in zip(space.letters, best)}, actual=actual,
        predicted=float(pr["predicted"]), confidence=float(confidence),
        ci=(float(pr["ci_low"]), float(pr["ci_high"])), pi=(float(pr["pi_low"]), float(pr["pi_high"])),
        se_fit=float(pr["se_fit"]), bounds=lims, warnings=tuple(notes), n_starts=n_starts, method=method,
        total=region.total, components=tuple(space.factors[j].name for j in region.comps))


def limits_of(region: MixtureRegion) -> dict:
    """``{name: (low, high)}`` of each factor over the region's vertices (actual units): the
    range a component can take in the constrained simplex."""
    A = [region.to_actual(v) for v in region.vertices()]
    return {f.name: (min(a[f.name] for a in A), max(a[f.name] for a in A)) for f in region.space.factors}


def extrapolation_notes(fitted: Any, actual: dict) -> list[str]:
    """A note for each component of ``actual`` outside the range of proportions in the data."""
    from ..present import format_g

    notes = []
    X = fitted.data
    for j in fitted.space.factors:
        name = j.name
        if name not in actual or X is None or name not in getattr(X, "columns", ()):
            continue
        col = np.asarray(X[name], dtype=float)
        col = col[np.isfinite(col)]
        if not col.size:
            continue
        lo, hi = float(col.min()), float(col.max())
        v = actual[name]
        tol = 1e-9 * max(abs(lo), abs(hi), 1.0)
        if v < lo - tol or v > hi + tol:
            notes.append(f"{name} = {format_g(v, 6, trim=True)} is outside the range of the data "
                         f"({format_g(lo, 6, trim=True)}..{format_g(hi, 6, trim=True)}): an extrapolation")
    return notes


def desirability_search(objective: Any, objective_many: Any, region: MixtureRegion, extra: list, *,
                        n_polish: int = 6, seed: int = SEED) -> tuple[np.ndarray, int]:
    """The point of ``region`` minimising ``objective`` (a decreasing function of ``D``, or 1 + a distance to the limits
    where D is 0: :mod:`rsm_lrg.optimize.desirability`): every start of :func:`region_starts`
    (256 random blends) and ``extra`` (each response's own optimum) screened at once with
    ``objective_many``, the best ``n_polish`` polished by SLSQP, the winner by Nelder–Mead
    in coordinates of the simplex's plane (a point outside the region scores +inf).
    Returns ``(x, number of starts)``."""
    from scipy import optimize as so

    S = region_starts(region, seed, n_random=256)
    if extra:
        S = np.vstack([S, np.array(extra, dtype=float)])
    S = S[region.contains(S)]
    vals = objective_many(S)
    cands = polish(objective, S[np.argsort(vals)[:n_polish]], region, maxiter=200, jac=False)
    cvals = [objective(c) for c in cands]
    best = cands[int(np.argmin(cvals))]
    best_v = float(min(cvals))
    N = null_basis(region.E)

    def inside(u: np.ndarray) -> float:
        x = best + N @ u
        return objective(x) if region.contains(x)[0] else math.inf

    r = so.minimize(inside, np.zeros(N.shape[1]), method="Nelder-Mead",
                    options={"xatol": 1e-10, "fatol": 1e-15, "maxiter": 400 * region.k,
                             "initial_simplex": _small_simplex(N.shape[1], 1e-3)})
    x = best + N @ r.x
    if region.contains(x)[0] and objective(x) < best_v:
        best = x
    return _project(best, region), len(S)


def null_basis(e: np.ndarray) -> np.ndarray:
    """An orthonormal basis (columns) of the vectors orthogonal to ``e``."""
    e = np.asarray(e, dtype=float)
    _, _, vt = np.linalg.svd(e[None, :])
    return np.asarray(vt[1:].T)


def _small_simplex(d: int, size: float) -> np.ndarray:
    return np.vstack([np.zeros(d), size * np.eye(d)])
