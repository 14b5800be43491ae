"""The optimum of a fitted mixture model over a constrained simplex (rsm_lrg.optimize.mixture)
against optima computed here by independent routes:

* quadratic models: every face of the region in *reduced* coordinates (the last component
  eliminated, ``x_q = 1 - sum others``), each face parametrised by a null-space basis of its
  active rows (``scipy.linalg.null_space``) and the quadratic's stationary point solved on
  it; the best feasible point is the exact global optimum (the package instead solves the
  Lagrange/KKT system in full coordinates);
* special cubic models: a fine lattice of the simplex (step 1/240 for three components,
  1/72 for four) kept to the region, the best lattice points refined by SLSQP in reduced
  coordinates.

Data: blends of a simplex-centroid design with axial and interior check blends, and of a
constrained region, with responses drawn from random Scheffé polynomials plus noise (several
seeds; not tuned), fitted by ``rsm_lrg.fit``.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pandas as pd
import pytest
from scipy import optimize as so
from scipy.linalg import null_space

import rsm_lrg

NAMES3 = ["oil", "additive", "thickener"]
NAMES4 = ["oil", "additive", "thickener", "filler"]


def _blends(q: int, rng: np.random.Generator) -> np.ndarray:
    """Simplex-centroid blends, axial check blends and 8 random interior blends."""
    pts = []
    for r in range(1, q + 1):
        for S in itertools.combinations(range(q), r):
            x = np.zeros(q)
            x[list(S)] = 1.0 / r
            pts.append(x)
    for i in range(q):
        x = np.full(q, 1.0 / (2 * q))
        x[i] = (q + 1) / (2 * q)
        pts.append(x)
    pts += list(rng.dirichlet(np.ones(q), size=8))
    return np.array(pts)


def _data(q: int, seed: int, lower=None) -> tuple[pd.DataFrame, list[str]]:
    rng = np.random.default_rng(seed)
    names = (NAMES3 if q == 3 else NAMES4)[:q]
    Z = _blends(q, rng)
    L = np.zeros(q) if lower is None else np.asarray(lower, dtype=float)
    X = L + Z * (1.0 - L.sum())  # real proportions over the L-simplex
    y = Z @ rng.normal(50, 15, q)
    for i, j in itertools.combinations(range(q), 2):
        y = y + rng.normal(0, 40) * Z[:, i] * Z[:, j]
    for i, j, k in itertools.combinations(range(q), 3):
        y = y + rng.normal(0, 200) * Z[:, i] * Z[:, j] * Z[:, k]
    y = y + rng.normal(0, 1.0, len(y))
    df = pd.DataFrame(X, columns=names)
    df["y"] = y
    specs = [f"{n}={lo}:1" for n, lo in zip(names, L)] if lower is not None else names
    return df, specs


# -- the independent optimum -------------------------------------------------------------------

def _region_rows(fit, bounds: dict, constraints: list[tuple[dict, float]]):
    """Rows ``A x <= c`` on real proportions (the component bounds and linear constraints)."""
    comps = [f for f in fit.space.factors]
    q = len(comps)
    A, c = [], []
    for j, f in enumerate(comps):
        lo, hi = f.lower, min(f.upper, f.total)
        if f.name in bounds:
            lo, hi = max(lo, bounds[f.name][0]), min(hi, bounds[f.name][1])
        e = np.zeros(q)
        e[j] = 1.0
        A += [-e, e]
        c += [-lo, hi]
    for coef, rhs in constraints:
        A.append(np.array([coef.get(f.name, 0.0) for f in comps]))
        c.append(rhs)
    return np.array(A), np.array(c)


def _reduced(A, c, T):
    """The rows in reduced coordinates u = x[:-1] (x_q = T - sum u): ``Ar u <= cr``."""
    Ar = A[:, :-1] - A[:, -1:]
    cr = c - A[:, -1] * T
    return Ar, cr


def _full(u, T):
    return np.append(u, T - np.sum(u))


def _predict(fit, X):
    # the polynomial itself, also where SLSQP steps a little outside the simplex (FitResult.predict
    # refuses a blend with a share below 0 or above the total: issue 36)
    coded = np.asarray(fit.space.encode(pd.DataFrame(np.atleast_2d(X), columns=fit.space.names)), dtype=float)
    return fit.predict_coded(coded)


def _quadratic_in_u(fit, T):
    """``(c0, g, H)`` with ŷ(u) = c0 + g·u + u'Hu/2, recovered exactly from predictions at a
    stencil (the model is quadratic in the proportions)."""
    q = len(fit.space)
    base = np.full(q - 1, T / q)
    h = 0.05 * T
    f0 = _predict(fit, _full(base, T))[0]
    g = np.zeros(q - 1)
    H = np.zeros((q - 1, q - 1))
    E = np.eye(q - 1) * h
    fp = [_predict(fit, _full(base + E[i], T))[0] for i in range(q - 1)]
    fm = [_predict(fit, _full(base - E[i], T))[0] for i in range(q - 1)]
    for i in range(q - 1):
        g[i] = (fp[i] - fm[i]) / (2 * h)
        H[i, i] = (fp[i] - 2 * f0 + fm[i]) / h ** 2
        for j in range(i + 1, q - 1):
            fpp = _predict(fit, _full(base + E[i] + E[j], T))[0]
            H[i, j] = H[j, i] = (fpp - fp[i] - fp[j] + f0) / h ** 2
    c0 = f0 - g @ base + 0.5 * base @ H @ base
    g = g - H @ base
    return c0, g, H


def _exact_quadratic(fit, sign, bounds, constraints):
    T = fit.space.factors[0].total
    A, c = _region_rows(fit, bounds, constraints)
    Ar, cr = _reduced(A, c, T)
    c0, g, H = _quadratic_in_u(fit, T)
    d = Ar.shape[1]
    best = None
    for s in range(d + 1):
        for S in itertools.combinations(range(len(cr)), s):
            S = list(S)
            if S:
                u0 = np.linalg.lstsq(Ar[S], cr[S], rcond=None)[0]
                if np.max(np.abs(Ar[S] @ u0 - cr[S])) > 1e-10:
                    continue
                M = null_space(Ar[S])
            else:
                u0, M = np.zeros(d), np.eye(d)
            if M.shape[1]:
                Hw = M.T @ H @ M
                gw = M.T @ (g + H @ u0)
                if abs(np.linalg.det(Hw)) < 1e-9 * max(1.0, np.abs(Hw).max()) ** M.shape[1]:
                    continue
                u = u0 + M @ np.linalg.solve(Hw, -gw)
            else:
                u = u0
            if np.all(Ar @ u <= cr + 1e-9):
                v = sign * (c0 + g @ u + 0.5 * u @ H @ u)
                if best is None or v < best[0]:
                    best = (v, _full(u, T))
    return best[1]


def _simplex_lattice(q, m):
    for comp in itertools.product(range(m + 1), repeat=q - 1):
        if sum(comp) <= m:
            yield np.array([*comp, m - sum(comp)], dtype=float) / m


def _grid_refined(fit, sign, bounds, constraints):
    T = fit.space.factors[0].total
    q = len(fit.space)
    A, c = _region_rows(fit, bounds, constraints)
    Ar, cr = _reduced(A, c, T)
    P = np.array(list(_simplex_lattice(q, 240 if q == 3 else 72))) * T
    P = P[np.all(P @ A.T <= c + 1e-12, axis=1)]
    vals = sign * _predict(fit, P)
    best = None
    for i in np.argsort(vals)[:8]:
        r = so.minimize(lambda u: sign * _predict(fit, _full(u, T))[0], P[i, :-1], method="SLSQP",
                        constraints=[{"type": "ineq", "fun": lambda u: cr - Ar @ u}],
                        options={"ftol": 1e-15, "maxiter": 500})
        u = r.x
        near = np.flatnonzero(Ar @ u - cr >= -1e-8)  # put the rows SLSQP left within 1e-8 exactly active
        if near.size:
            u = u - np.linalg.pinv(Ar[near]) @ (Ar[near] @ u - cr[near])
        if not np.all(Ar @ u <= cr + 1e-12):
            u = P[i, :-1]
        v = sign * _predict(fit, _full(u, T))[0]
        if best is None or v < best[0]:
            best = (v, _full(u, T))
    return best[1]


# -- the cases -----------------------------------------------------------------------------------

CASES = {
    # name: (q, lower bounds or None, bounds {name: (lo, hi)}, constraints [({name: coef}, rhs)] as text too)
    "q3-simplex": (3, None, {}, []),
    "q3-constrained": (3, [0.1, 0.05, 0.0], {"oil": (0.1, 0.7), "thickener": (0.0, 0.5)},
                       [({"oil": 1.0, "additive": 1.0}, 0.8)]),
    "q4-simplex": (4, None, {}, []),
    "q4-constrained": (4, [0.1, 0.05, 0.0, 0.1], {"oil": (0.1, 0.6), "filler": (0.1, 0.4)},
                       [({"oil": 1.0, "additive": 1.0}, 0.7), ({"thickener": -1.0, "oil": 0.5}, 0.1)]),
}


def _texts(constraints):
    return [" + ".join(f"{v:g}*{k}" for k, v in coef.items()) + f" <= {rhs:g}" for coef, rhs in constraints]


def _check(fit, case, goal, want_x):
    q, lower, bounds, constraints = CASES[case]
    got = rsm_lrg.optimize(fit, goal=goal, bounds={k: v for k, v in bounds.items()} or None,
                           constraints=_texts(constraints) or None)
    x = np.array([got.actual[n] for n in fit.space.names])
    assert abs(math.fsum(x) - 1.0) <= 1e-12
    A, c = _region_rows(fit, bounds, constraints)
    assert np.all(A @ x <= c + 1e-12), (A @ x - c)
    y_want = _predict(fit, want_x)[0]
    scale = float(np.ptp(fit.y))
    sign = 1.0 if goal == "minimize" else -1.0
    # never worse than the independent optimum, and equal to it
    assert sign * (got.predicted - y_want) <= 1e-9 * scale, (got.predicted, y_want)
    assert abs(got.predicted - y_want) <= 1e-9 * scale, (got.predicted, y_want)
    assert np.max(np.abs(x - want_x)) <= 1e-5, (x, want_x)
    return got


@pytest.mark.parametrize("case", list(CASES))
@pytest.mark.parametrize("seed", [1, 2, 3])
@pytest.mark.parametrize("goal", ["maximize", "minimize"])
def test_quadratic_equals_exact_face_enumeration(case, seed, goal):
    q, lower, bounds, constraints = CASES[case]
    df, specs = _data(q, seed, lower)
    fit = rsm_lrg.fit(df, "y", components=specs, model="mixture-quadratic")
    want = _exact_quadratic(fit, 1.0 if goal == "minimize" else -1.0, bounds, constraints)
    got = _check(fit, case, goal, want)
    assert got.method == "exact-faces"


@pytest.mark.slow
@pytest.mark.parametrize("case", list(CASES))
@pytest.mark.parametrize("seed", [1, 2])
@pytest.mark.parametrize("goal", ["maximize", "minimize"])
def test_special_cubic_equals_grid_plus_refinement(case, seed, goal):
    q, lower, bounds, constraints = CASES[case]
    df, specs = _data(q, seed, lower)
    fit = rsm_lrg.fit(df, "y", components=specs, model="special-cubic")
    want = _grid_refined(fit, 1.0 if goal == "minimize" else -1.0, bounds, constraints)
    got = _check(fit, case, goal, want)
    assert got.method == "multistart"


def test_target_is_hit_on_the_simplex():
    df, specs = _data(3, 5)
    fit = rsm_lrg.fit(df, "y", components=specs, model="mixture-quadratic")
    lo = rsm_lrg.optimize(fit, goal="minimize").predicted
    hi = rsm_lrg.optimize(fit, goal="maximize").predicted
    t = lo + 0.3 * (hi - lo)
    got = rsm_lrg.optimize(fit, goal=f"target={t}")
    assert abs(got.predicted - t) <= 1e-9 * (hi - lo)
    assert abs(sum(got.actual.values()) - 1.0) <= 1e-12
    assert not got.warnings


def test_intervals_are_the_fit_s_prediction_at_the_blend():
    df, specs = _data(4, 7, [0.1, 0.05, 0.0, 0.1])
    fit = rsm_lrg.fit(df, "y", components=specs, model="mixture-quadratic")
    got = rsm_lrg.optimize(fit, goal="maximize", confidence=0.9)
    pr = fit.predict(pd.DataFrame([got.actual]), interval="both", alpha=0.1).iloc[0]
    for a, b in ((got.predicted, pr["predicted"]), (got.ci[0], pr["ci_low"]), (got.pi[1], pr["pi_high"])):
        assert a == pytest.approx(b, rel=1e-12)
    assert got.to_dict()["total"] == pytest.approx(1.0)


def test_mixture_process_optimum_covers_the_process_box():
    """Scheffé quadratic × linear process (ABC terms × D): the multistart optimum is no worse
    than the best of the exact quadratic optima at a fine set of process levels."""
    rng = np.random.default_rng(11)
    Z = _blends(3, rng)
    rows = []
    for d in (-1.0, 0.0, 1.0):
        for z in Z:
            y = 40 * z[0] + 55 * z[1] + 30 * z[2] + 60 * z[0] * z[1] - 30 * z[1] * z[2] + d * (8 * z[0] - 5 * z[2])
            rows.append([*z, 10 + 5 * d, y + rng.normal(0, 0.5)])
    df = pd.DataFrame(rows, columns=[*NAMES3, "temp", "y"])
    fit = rsm_lrg.fit(df, "y", components=NAMES3, factors=["temp"], model="mixture-quadratic")
    got = rsm_lrg.optimize(fit, goal="maximize")
    assert abs(sum(got.actual[n] for n in NAMES3) - 1.0) <= 1e-12
    assert 5.0 - 1e-12 <= got.actual["temp"] <= 15.0 + 1e-12
    best = -np.inf
    for t in np.linspace(5.0, 15.0, 41):
        P = np.array(list(_simplex_lattice(3, 120)))
        frame = pd.DataFrame(P, columns=NAMES3).assign(temp=t)
        best = max(best, float(fit.predict(frame)["predicted"].max()))
    assert got.predicted >= best - 1e-9 * float(np.ptp(fit.y))


def test_bad_region_is_named():
    df, specs = _data(3, 1)
    fit = rsm_lrg.fit(df, "y", components=specs, model="mixture-quadratic")
    with pytest.raises(ValueError, match="empty"):
        rsm_lrg.optimize(fit, goal="maximize", constraints=["oil + additive >= 1.5"])
    with pytest.raises(ValueError, match="not linear"):
        rsm_lrg.optimize(fit, goal="maximize", constraints=["oil*additive <= 0.1"])
    with pytest.raises(ValueError, match="no such"):
        rsm_lrg.optimize(fit, goal="maximize", bounds={"nope": (0, 1)})


@pytest.mark.parametrize("goal", ["maximize", "minimize"])
def test_full_cubic_equals_grid_plus_refinement(goal):
    """The Scheffé full cubic (terms x_i x_j (x_i - x_j)) on the constrained three-component case."""
    q, lower, bounds, constraints = CASES["q3-constrained"]
    df, specs = _data(q, 4, lower)
    fit = rsm_lrg.fit(df, "y", components=specs, model="mixture-cubic")
    assert any("(" in t for t in fit.coefficients.index)
    want = _grid_refined(fit, 1.0 if goal == "minimize" else -1.0, bounds, constraints)
    got = _check(fit, "q3-constrained", goal, want)
    assert got.method == "multistart"
