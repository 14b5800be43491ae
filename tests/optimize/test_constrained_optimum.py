"""``optimize(..., constraints=...)``: the optimum of a fitted surface inside a region that is
not a box (the motion profile's s >= v^2/a), checked against a fine grid of feasible points."""

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.optimize import optimize

EXPR = "v**2/a <= s"


@pytest.fixture(scope="module")
def res():
    rng = np.random.default_rng(3)
    g = np.array([-1.0, 0.0, 1.0])
    C = np.array(np.meshgrid(g, g, g)).reshape(3, -1).T
    v, a, s = 0.6 + 0.4 * C[:, 0], 22.5 + 17.5 * C[:, 1], 0.06 + 0.04 * C[:, 2]
    y = 1 + 2 * C[:, 0] - 0.5 * C[:, 1] + 0.3 * C[:, 2] + 0.4 * C[:, 0] * C[:, 1] + 0.2 * C[:, 0] ** 2 \
        + rng.normal(0, 0.02, len(C))
    return rsm_lrg.fit(pd.DataFrame({"v": v, "a": a, "s": s, "y": y}), "y", factors=["v", "a", "s"])


def _grid_best(res, goal):
    g = np.linspace(0, 1, 61)
    V, A, S = (m.ravel() for m in np.meshgrid(0.2 + 0.8 * g, 5 + 35 * g, 0.02 + 0.08 * g))
    ok = V ** 2 / A <= S
    p = res.predict(pd.DataFrame({"v": V[ok], "a": A[ok], "s": S[ok]}))["predicted"].to_numpy()
    return p.max() if goal == "maximize" else p.min()


@pytest.mark.parametrize("goal", ["maximize", "minimize"])
def test_constrained_optimum_is_feasible_and_no_worse_than_a_grid(res, goal):
    o = optimize(res, goal, constraints=[EXPR])
    v, a, s = o.actual["v"], o.actual["a"], o.actual["s"]
    assert v ** 2 / a <= s * (1 + 1e-7)
    best = _grid_best(res, goal)
    if goal == "maximize":
        assert o.predicted >= best - 1e-9
    else:
        assert o.predicted <= best + 1e-9


def test_the_constraint_binds_where_the_box_optimum_is_infeasible(res):
    free = optimize(res, "maximize")
    assert free.actual["v"] ** 2 / free.actual["a"] > free.actual["s"]  # the box optimum breaks it
    held = optimize(res, "maximize", constraints=EXPR)
    assert held.predicted < free.predicted
    assert held.actual["v"] ** 2 / held.actual["a"] == pytest.approx(held.actual["s"], rel=1e-6)


def test_bad_constraint_is_an_error(res):
    with pytest.raises(ValueError, match="unknown name"):
        optimize(res, "maximize", constraints=["q <= 1"])
