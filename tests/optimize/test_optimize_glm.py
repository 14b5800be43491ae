"""The optimum of a generalised linear model's probability (mean count) (issue 35, item 1):
``rsm_lrg.optimize(glm_result, goal)`` against an independent grid search of
``GLMResult.predict`` over the factor box, refined by Nelder–Mead on the predicted probability
itself (not on the linear predictor the optimiser uses)."""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from scipy.optimize import minimize

import rsm_lrg

R = Path(__file__).parents[1] / "model" / "r"


def _logistic_quadratic(seed=5, n=200):
    rng = np.random.default_rng(seed)
    t, c = rng.uniform(150, 250, n), rng.uniform(1, 5, n)
    a, b = (t - 200) / 50, (c - 3) / 2
    eta = 1.0 + 0.6 * a - 0.4 * b - 1.5 * a * a - 0.9 * b * b + 0.5 * a * b
    y = (rng.uniform(size=n) < 1 / (1 + np.exp(-eta))).astype(int)
    return pd.DataFrame({"temp": t, "conc": c, "pass": y})


def _grid_optimum(res, sign, target=None, m=401):
    """Best coded point of the predicted probability on an m x m grid of the coded box, then
    Nelder-Mead from there on the prediction itself (clipped to the box)."""
    g = np.linspace(-1, 1, m)
    X = np.array(np.meshgrid(g, g)).reshape(2, -1).T

    def f(x):
        p = res.predict(np.clip(np.atleast_2d(x), -1, 1), coded=True)["predicted"].to_numpy()
        return (p - target) ** 2 if target is not None else sign * p

    i = int(np.argmin(f(X)))
    fine = minimize(lambda x: float(f(x)[0]), X[i], method="Nelder-Mead",
                    options={"xatol": 1e-10, "fatol": 1e-15, "maxiter": 4000})
    x = np.clip(fine.x, -1, 1)
    return x, float(res.predict(x[None, :], coded=True)["predicted"].iloc[0])


@pytest.mark.parametrize("link", ["logit", "probit"])
@pytest.mark.parametrize("goal,sign", [("maximize", -1.0), ("minimize", 1.0)])
def test_optimum_of_a_logistic_model_equals_a_grid_search(link, goal, sign):
    res = rsm_lrg.fit(_logistic_quadratic(), "pass", family="binomial", link=link)
    opt = rsm_lrg.optimize(res, goal)
    x, p = _grid_optimum(res, sign)
    assert opt.predicted == pytest.approx(p, rel=1e-9, abs=1e-12)
    np.testing.assert_allclose([opt.coded["A"], opt.coded["B"]], x, atol=1e-5)
    lo, hi = opt.ci
    assert 0 < lo < opt.predicted < hi < 1
    assert np.isnan(opt.pi).all()  # a GLM has no prediction interval


def test_target_probability_is_reached_and_refused_outside_0_1():
    res = rsm_lrg.fit(_logistic_quadratic(), "pass", family="binomial")
    opt = res.optimize("target=0.5")
    assert opt.predicted == pytest.approx(0.5, abs=1e-9)
    with pytest.raises(ValueError, match="strictly between 0 and 1"):
        res.optimize("target=1.2")


def test_optimum_over_a_categoric_factor_equals_a_grid_search():
    res = rsm_lrg.fit(pd.read_csv(R / "glm_budworm.csv"), "numdead", factors=["ldose=1:4", "sex=cat:F,M"],
                      model="2fi", family="binomial", link="probit", trials="n")
    opt = rsm_lrg.optimize(res, "minimize")
    grid = pd.DataFrame({"ldose": np.tile(np.linspace(1, 4, 3001), 2), "sex": ["F"] * 3001 + ["M"] * 3001})
    p = res.predict(grid)["predicted"]
    best = grid.iloc[int(np.argmin(p))]
    assert opt.predicted == pytest.approx(float(p.min()), rel=1e-9)
    assert (opt.actual["sex"], opt.actual["ldose"]) == (best.sex, pytest.approx(best.ldose))


def test_poisson_mean_count_minimum():
    rng = np.random.default_rng(11)
    x1, x2 = rng.uniform(0, 1, 120), rng.uniform(0, 1, 120)
    mu = np.exp(2.0 - 1.2 * x1 + 0.5 * x2 + 1.5 * (x1 - 0.6) ** 2 + 1.0 * (x2 - 0.3) ** 2)
    df = pd.DataFrame({"ph": x1, "salt": x2, "cfu": rng.poisson(mu)})
    res = rsm_lrg.fit(df, "cfu", family="poisson")
    opt = rsm_lrg.optimize(res, "minimize")
    x, m = _grid_optimum(res, 1.0)
    assert opt.predicted == pytest.approx(m, rel=1e-9)
    np.testing.assert_allclose([opt.coded["A"], opt.coded["B"]], x, atol=1e-5)


def test_desirability_with_a_glm_is_refused_not_computed_on_the_link_scale():
    from rsm_lrg.optimize.desirability import ResponseGoal, optimize_desirability

    df = _logistic_quadratic()
    df["cost"] = 3 + (df.temp - 200) / 50
    g = rsm_lrg.fit(df, "pass", factors=["temp", "conc"], family="binomial")
    o = rsm_lrg.fit(df, "cost", factors=["temp", "conc"], model="linear")
    with pytest.raises(TypeError, match="response 'pass': desirability with a generalised linear model"):
        optimize_desirability({"pass": g, "cost": o}, [ResponseGoal("pass", "maximize", low=0.5, high=0.9),
                                                      ResponseGoal("cost", "minimize", low=2.0, high=4.0)])


def test_desirability_with_a_categoric_glm_is_refused_too():
    from rsm_lrg.optimize.desirability import ResponseGoal, optimize_desirability

    df = pd.read_csv(R / "glm_budworm.csv")
    g = rsm_lrg.fit(df, "numdead", factors=["ldose", "sex=cat:F,M"], model="2fi", family="binomial", trials="n")
    with pytest.raises(TypeError, match="response 'numdead'"):
        optimize_desirability({"numdead": g}, [ResponseGoal("numdead", "maximize", low=0.2, high=0.8)])
