"""Optimising on interval ends and on the POE (:mod:`rsm_lrg.optimize.robust`): the optimum
found is at least as good as every node of a dense grid over the box (9⁴ nodes for the paper's
four factors), the value it reports is the interval end it optimised, and the POE optimum is
the smallest POE on the grid."""

from __future__ import annotations

import itertools
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.errors import ParameterError
from rsm_lrg.optimize.desirability import individual_desirability
from rsm_lrg.optimize.poe import propagation_of_error
from rsm_lrg.optimize.robust import optimize_robust, parse_robust_goal

ROOT = Path(__file__).parents[2]
Y = "tcr_c_per_min"


@pytest.fixture(scope="module")
def paper():
    return rsm_lrg.fit(pd.read_csv(ROOT / "data" / "table4.csv"), Y)


def _grid(fit, n=9):
    g = np.linspace(-1, 1, n)
    X = np.array(list(itertools.product(g, repeat=len(fit.space))))
    return pd.DataFrame({f.name: f.decode(X[:, j]) for j, f in enumerate(fit.space.factors)})


@pytest.mark.parametrize("goal, interval, column, sign", [
    ("minimize", "ci", "ci_high", 1), ("minimize", "ti", "ti_high", 1), ("maximize", "pi", "pi_low", -1),
    ("minimize", None, "predicted", 1),
])
def test_interval_end_is_optimal_on_the_grid(paper, goal, interval, column, sign):
    g, _ = parse_robust_goal(Y, goal)
    r = optimize_robust({Y: paper}, [g], intervals={Y: interval}, tolerance=0.99)
    got = r.responses[Y]
    grid = paper.predict(_grid(paper), interval="both", tolerance=0.99)
    at = paper.predict(pd.DataFrame({k: [v] for k, v in r.actual.items()}), interval="both", tolerance=0.99).iloc[0]
    assert got["value"] == pytest.approx(float(at[column]), rel=1e-12)
    assert got["predicted"] == pytest.approx(float(at["predicted"]), rel=1e-12)
    assert got["optimised"] == ("mean" if interval is None else column)
    best_on_grid = float((sign * grid[column].to_numpy()).min())
    assert sign * got["value"] <= best_on_grid + 1e-12 * abs(best_on_grid)
    if interval == "ci":  # the CI's upper end is least away from the mean's minimum (the corner)
        assert r.coded["A"] > -0.9


def test_poe_goal_is_the_smallest_poe(paper):
    sds = {"velocity_m_s": 0.02, "acceleration_m_s2": 1.0}
    g, is_poe = parse_robust_goal(Y, "poe")
    assert is_poe
    r = optimize_robust({Y: paper}, [g], poe=[Y], factor_sd=sds)
    grid = propagation_of_error(paper, _grid(paper), sds)
    assert r.responses[Y]["poe"] <= grid.min() + 1e-15
    assert r.responses[Y]["optimised"] == "poe"


def test_desirability_on_interval_ends():
    """Two responses of the helicopter data (R rsm's heli): maximise ave on its PI's lower end
    and keep logSD in range on both CI ends; each d is computed on the end it names, and D is at
    least the best D of a 5⁴ grid."""
    from rsm_lrg.optimize.desirability import overall_desirability

    d = pd.read_csv(ROOT / "tests" / "model" / "r" / "heli.csv")
    fits = {r: rsm_lrg.fit(d, r, factors=["A", "R", "W", "L"]) for r in ("ave", "logSD")}
    g1, _ = parse_robust_goal("ave", "maximize", limits="360:400")
    g2, _ = parse_robust_goal("logSD", "minimize", limits="40:90")
    r = optimize_robust(fits, [g1, g2], intervals={"ave": "pi", "logSD": "ci"})
    assert r.desirability is not None and r.desirability > 0
    point = pd.DataFrame({k: [v] for k, v in r.actual.items()})
    p1 = fits["ave"].predict(point, interval="both").iloc[0]
    p2 = fits["logSD"].predict(point, interval="both").iloc[0]
    assert r.responses["ave"]["d"] == pytest.approx(float(individual_desirability([p1.pi_low], g1)[0]), rel=1e-12)
    assert r.responses["logSD"]["d"] == pytest.approx(float(individual_desirability([p2.ci_high], g2)[0]), rel=1e-12)
    grid = _grid(fits["ave"], 5)
    q1 = fits["ave"].predict(grid, interval="both")
    q2 = fits["logSD"].predict(grid, interval="both")
    D = overall_desirability([individual_desirability(q1.pi_low, g1), individual_desirability(q2.ci_high, g2)],
                             [g1, g2])
    assert r.desirability >= D.max() - 1e-12


def test_categoric_levels_are_searched():
    """cat_bbd3x2 (three numeric factors and a supplier): the PI's lower end is maximised over
    both suppliers (at least the best node of a 9³ grid at each level), or at the level held."""
    d = pd.read_csv(ROOT / "tests" / "model" / "r" / "cat_bbd3x2.csv")
    fit = rsm_lrg.fit(d, "yield_pct", factors=["temp_c", "time_min", "conc_pct", "supplier"])
    g, _ = parse_robust_goal("yield_pct", "maximize")
    r = optimize_robust({"yield_pct": fit}, [g], intervals={"yield_pct": "pi"})
    lv = np.linspace(-1, 1, 9)
    X = np.array(list(itertools.product(lv, repeat=3)))
    nums = [f for f in fit.space.factors if f.kind != "categoric"]
    best = {}
    for level in ("north", "south"):
        grid = pd.DataFrame({f.name: f.decode(X[:, j]) for j, f in enumerate(nums)})
        grid["supplier"] = level
        best[level] = float(fit.predict(grid, interval="both").pi_low.max())
    assert r.responses["yield_pct"]["value"] >= max(best.values()) - 1e-12
    assert r.actual["supplier"] == max(best, key=best.get)
    other = min(best, key=best.get)
    held = optimize_robust({"yield_pct": fit}, [g], intervals={"yield_pct": "pi"}, bounds=[f"supplier={other}"])
    assert held.actual["supplier"] == other
    assert held.responses["yield_pct"]["value"] >= best[other] - 1e-12


def test_bad_requests(paper):
    g, _ = parse_robust_goal(Y, "poe")
    with pytest.raises(ParameterError) as e:
        optimize_robust({Y: paper}, [g], poe=[Y])
    assert e.value.parameter == "factor_sd"
    with pytest.raises(ParameterError) as e:
        optimize_robust({Y: paper}, [g], poe=[Y], factor_sd={"stroke_m": 0.001}, intervals={Y: "ci"})
    assert e.value.parameter == "interval"
    g, _ = parse_robust_goal(Y, "minimize")
    with pytest.raises(ParameterError) as e:
        optimize_robust({Y: paper}, [g], intervals={Y: "xi"})
    assert e.value.parameter == "interval"
    etch = rsm_lrg.fit(pd.read_csv(ROOT / "tests" / "model" / "r" / "mixture_etch.csv"), "erate",
                       components=["x1", "x2", "x3"], model="mixture-quadratic")
    g, _ = parse_robust_goal("erate", "maximize")
    with pytest.raises(ParameterError) as e:
        optimize_robust({"erate": etch}, [g], intervals={"erate": "ci"}, bounds=["x1=0.2:0.5"])
    assert e.value.parameter == "bound"


@pytest.mark.parametrize("data", ["mixture_etch.csv", "mixture_etch_l.csv"])
def test_mixture_on_the_simplex(data):
    """The etch mixture (and its L-pseudo twin): the CI's lower end is maximised over the blends
    (at least the best of a 0.01 simplex lattice inside the bounds), the blend keeps its total
    and its bounds; the mean's optimum lies on an edge, the CI's inside."""
    d = pd.read_csv(ROOT / "tests" / "model" / "r" / data)
    fit = rsm_lrg.fit(d, "erate", components=["x1", "x2", "x3"], model="mixture-quadratic")
    g, _ = parse_robust_goal("erate", "maximize")
    r = optimize_robust({"erate": fit}, [g], intervals={"erate": "ci"})
    comps = [f for f in fit.space.factors]
    total, low = comps[0].total, [f.lower for f in comps]
    step = np.arange(0, 101) / 100
    a, b = np.meshgrid(step, step)
    keep = a + b <= 1
    P = np.column_stack([a[keep], b[keep], 1 - a[keep] - b[keep]])
    R = total - sum(low)
    grid = pd.DataFrame({f.name: low[j] + R * P[:, j] for j, f in enumerate(comps)})
    inside = np.all([(grid[f.name] <= f.upper + 1e-12).to_numpy() for f in comps], axis=0)
    best = float(fit.predict(grid[inside], interval="confidence").ci_low.max())
    assert r.responses["erate"]["value"] >= best - 1e-9
    assert sum(r.actual.values()) == pytest.approx(total, abs=1e-12)
    assert all(f.lower - 1e-12 <= r.actual[f.name] <= f.upper + 1e-12 for f in comps)
    assert min(r.actual.values()) > min(low) + 0.05
