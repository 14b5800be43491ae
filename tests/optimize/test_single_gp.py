"""``optimize`` on a Gaussian-process fit, through the prediction contract: the optimum of the
kriging mean on 20 Branin runs is no worse than a 201 x 201 grid of the same mean, its
analytic gradient (``GPResult.gradient``, not used by the search) vanishes along the free
coordinates, and its intervals are ``predict``'s."""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.optimize import optimize

BRANIN = Path(__file__).parents[1] / "model" / "r" / "gp_branin.csv"
FACTORS = ["x1=-5:10", "x2=0:15"]


@pytest.fixture(scope="module")
def gp():
    return rsm_lrg.fit(pd.read_csv(BRANIN), "y", factors=FACTORS, model="gp")


def _grid(gp, n=201):
    g = np.linspace(-1.0, 1.0, n)
    X = np.array(np.meshgrid(g, g)).reshape(2, -1).T
    return X, gp.predict_coded(X)


@pytest.mark.parametrize("goal", ["minimize", "maximize"])
def test_optimum_beats_a_grid_and_is_stationary(gp, goal):
    o = optimize(gp, goal)
    x = np.array([o.coded["A"], o.coded["B"]])
    X, y = _grid(gp)
    sign = 1.0 if goal == "minimize" else -1.0
    assert sign * o.predicted <= sign * (y.min() if goal == "minimize" else y.max()) + 1e-9
    grad = gp.gradient(x[None, :], coded=True).to_numpy()[0]
    scale = np.abs(y).max()
    for j in range(2):
        if abs(abs(x[j]) - 1.0) > 1e-9:  # a free coordinate: the mean's slope is zero there
            assert abs(grad[j]) < 1e-4 * scale, (j, grad)
        else:  # on a face: the slope points out of the box
            assert sign * grad[j] * np.sign(x[j]) <= 1e-9 * scale
    p = gp.predict(pd.DataFrame([o.actual]), interval="both").iloc[0]
    assert o.predicted == pytest.approx(p["predicted"], rel=1e-12, abs=1e-12)
    assert o.ci == pytest.approx((p["ci_low"], p["ci_high"]), rel=1e-12, abs=1e-12)
    assert o.pi == pytest.approx((p["pi_low"], p["pi_high"]), rel=1e-12, abs=1e-12)


def test_target_and_constraint(gp):
    o = optimize(gp, "target=50", constraints=["x1 + x2 <= 10"], bounds=["x1=-5:5"])
    assert o.actual["x1"] + o.actual["x2"] <= 10 + 1e-6 and -5 - 1e-12 <= o.actual["x1"] <= 5 + 1e-12
    assert o.predicted == pytest.approx(50.0, abs=1e-4)
