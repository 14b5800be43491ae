"""``optimize_desirability(..., constraints=...)``: the several-response optimum inside a region
that is not a box (the motion profile's v^2/a <= s with the stroke s = 0.02 m held), checked
against a dense grid of feasible points of the same overall desirability (predictions through
``FitResult.predict``, an independent route from the optimiser's closed-form quadratics)."""

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.optimize.desirability import (
    ResponseGoal,
    individual_desirability,
    optimize_desirability,
    overall_desirability,
)

EXPR = "v**2/a <= 0.02"


def _data(categoric=False):
    rng = np.random.default_rng(7)
    g = np.linspace(-1, 1, 5)
    C = np.array(np.meshgrid(g, g)).reshape(2, -1).T
    if categoric:
        C = np.vstack([C, C])
        lev = np.repeat(["rms", "rfcms"], 25)
    x1, x2 = C[:, 0], C[:, 1]
    df = pd.DataFrame({"v": 0.6 + 0.4 * x1, "a": 22.5 + 17.5 * x2})
    shift = np.where(lev == "rms", 0.3, -0.3) if categoric else 0.0
    df["y1"] = 5 + 2.0 * x1 + 0.5 * x2 - 0.6 * x1 ** 2 + 0.3 * x1 * x2 + shift + rng.normal(0, 0.02, len(C))
    df["y2"] = 3 + 0.4 * x1 + 1.2 * x2 + 0.5 * x2 ** 2 - shift + rng.normal(0, 0.02, len(C))
    if categoric:
        df["stage"] = lev
    return df


GOALS = [ResponseGoal("y1", "maximize", 3.0, 7.0), ResponseGoal("y2", "minimize", 2.0, 5.5, importance=2)]


def _fits(df, factors):
    return {r: rsm_lrg.fit(df, r, factors=factors) for r in ("y1", "y2")}


def _grid_D(fits, levels=(None,), n=401):
    """Best overall desirability over a dense feasible grid (n x n per level) by predict()."""
    v, a = (m.ravel() for m in np.meshgrid(np.linspace(0.2, 1.0, n), np.linspace(5.0, 40.0, n)))
    ok = v ** 2 / a <= 0.02
    best = -1.0
    for lv in levels:
        X = pd.DataFrame({"v": v[ok], "a": a[ok]})
        if lv is not None:
            X["stage"] = lv
        ds = [individual_desirability(fits[g.response].predict(X)["predicted"].to_numpy(), g) for g in GOALS]
        best = max(best, float(overall_desirability(ds, GOALS).max()))
    return best


def test_constrained_desirability_is_feasible_and_matches_a_dense_grid():
    fits = _fits(_data(), ["v", "a"])
    free = optimize_desirability(fits, GOALS)
    assert free.actual["v"] ** 2 / free.actual["a"] > 0.02  # the box optimum breaks the constraint
    r = optimize_desirability(fits, GOALS, constraints=[EXPR])
    v, a = r.actual["v"], r.actual["a"]
    assert v ** 2 / a <= 0.02 + 1e-9  # feasible to 1e-9
    assert r.desirability < free.desirability
    grid = _grid_D(fits)
    # the search can only beat the grid (or tie it); a 401 x 401 grid is within 1e-3 of the optimum
    assert r.desirability >= grid - 1e-9
    assert r.desirability == pytest.approx(grid, abs=1e-3)
    # the reported D is the D of the reported point (recomputed through predict)
    X = pd.DataFrame({"v": [v], "a": [a]})
    ds = [individual_desirability(fits[g.response].predict(X)["predicted"].to_numpy(), g) for g in GOALS]
    assert r.desirability == pytest.approx(float(overall_desirability(ds, GOALS)[0]), rel=1e-9)


def test_constrained_desirability_with_a_categoric_factor():
    df = _data(categoric=True)
    fits = _fits(df, ["v", "a", "stage"])
    r = optimize_desirability(fits, GOALS, constraints=EXPR)
    assert r.actual["v"] ** 2 / r.actual["a"] <= 0.02 + 1e-9
    assert r.actual["stage"] == "rms"  # y1 higher and y2 lower at rms (shift 0.3 each)
    grid = _grid_D(fits, levels=("rms", "rfcms"), n=301)
    assert r.desirability >= grid - 1e-9 and r.desirability == pytest.approx(grid, abs=1e-3)
    # held at the other level, the constraint still holds
    o = optimize_desirability(fits, GOALS, bounds={"stage": "rfcms"}, constraints=[EXPR])
    assert o.actual["stage"] == "rfcms" and o.actual["v"] ** 2 / o.actual["a"] <= 0.02 + 1e-9
    assert o.desirability < r.desirability


def test_infeasible_or_bad_constraints_are_clear_errors():
    fits = _fits(_data(), ["v", "a"])
    with pytest.raises(ValueError, match="no setting inside the factor ranges"):
        optimize_desirability(fits, GOALS, constraints=["v >= 2"])  # v runs 0.2..1.0
    with pytest.raises(ValueError, match="no feasible setting found inside the bounds and the constraints"):
        optimize_desirability(fits, GOALS, bounds={"v": (0.9, 1.0), "a": (5, 10)}, constraints=[EXPR])
    with pytest.raises(ValueError, match="unknown name"):
        optimize_desirability(fits, GOALS, constraints=["q <= 1"])
