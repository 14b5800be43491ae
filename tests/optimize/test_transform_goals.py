"""Goals on a transformed response (issue 21): the Python API and the CLI give the same
optimum for every transform and goal, and it is the optimum of the back-transformed surface.

Independent route: the back-transformed prediction evaluated on a 21^4 grid of the coded box
(numpy only: the model matrix times the coded coefficients, then g^-1); the optimiser must do
at least as well as the best grid node, and a reachable target must be hit without a warning.
"""

from __future__ import annotations

import itertools
import json

import numpy as np
import pytest

import rsm_lrg
from rsm_lrg.cli import main
from rsm_lrg.model.build.terms import design_matrix

TRANSFORMS = ["log", "log10", "sqrt", "inverse", "power=-0.5"]
GOALS = ["maximize", "minimize", "target=0.03"]


@pytest.fixture(scope="module")
def table4():
    return rsm_lrg.load_table4()


@pytest.fixture(scope="module")
def grid():
    g = np.linspace(-1.0, 1.0, 21)
    return np.array(list(itertools.product(g, repeat=4)))


def _grid_values(fit, grid):
    z = design_matrix(grid, fit.terms) @ fit.coefficients["coded"].to_numpy()
    return fit.transform.inverse(z)


@pytest.mark.parametrize("transform", TRANSFORMS)
@pytest.mark.parametrize("goal", GOALS)
def test_api_equals_cli_and_is_the_true_optimum(table4, grid, transform, goal, tmp_path, capsys):
    fit = rsm_lrg.fit(table4, "tcr_c_per_min", transform=transform)
    best = fit.optimize(goal=goal)
    also = rsm_lrg.optimize(fit, goal=goal)
    assert best.predicted == also.predicted
    out = tmp_path / "o.json"
    assert main(["optimize", "data/table4.csv", "--response", "tcr_c_per_min", "--transform", transform,
                 "--goal", goal, "--json", str(out)]) == 0
    capsys.readouterr()
    cli = json.loads(out.read_text())
    assert cli["predicted"] == pytest.approx(best.predicted, rel=1e-9)
    for k, v in best.coded.items():
        assert cli["coded"][k] == pytest.approx(v, abs=1e-7)
    # the prediction is on the response's scale: the back-transformed surface at the optimum
    x = np.array([[best.coded[L] for L in fit.space.letters]])
    assert best.predicted == pytest.approx(float(_grid_values(fit, x)[0]), rel=1e-12)
    values = _grid_values(fit, grid)
    if goal == "maximize":
        assert best.predicted >= np.nanmax(values) * (1 - 1e-12)
        assert best.goal == "maximize"
    elif goal == "minimize":
        assert best.predicted <= np.nanmin(values) * (1 + 1e-12)
    else:
        assert np.nanmin(values) < 0.03 < np.nanmax(values)  # reachable
        assert best.predicted == pytest.approx(0.03, rel=1e-6)
        assert best.target == 0.03 and best.goal == "target"
        assert not [w for w in best.warnings if "cannot be reached" in w]
        assert not [w for w in cli["warnings"] if "cannot be reached" in w]
    lo, hi = best.ci
    assert lo <= best.predicted <= hi


def test_inverse_maximum_is_the_maximum(table4):
    """The case the issue reported: the API returned the minimum (0.02244) for a maximum."""
    fit = rsm_lrg.fit_transformed(table4, "tcr_c_per_min", "inverse")
    mx = rsm_lrg.optimize(fit, goal="maximize").predicted
    mn = rsm_lrg.optimize(fit, goal="minimize").predicted
    assert mx > 0.05 > 0.025 > mn


def test_desirability_reads_goals_on_the_response_scale(table4):
    from rsm_lrg.optimize.desirability import ResponseGoal, optimize_desirability

    fits = {"tcr_c_per_min": rsm_lrg.fit(table4, "tcr_c_per_min", transform="inverse")}
    # limits above anything reachable: the desirability rises with y everywhere (no saturation)
    r = optimize_desirability(fits, [ResponseGoal("tcr_c_per_min", "maximize", low=0.01, high=0.2)])
    assert r.predicted["tcr_c_per_min"] == pytest.approx(fits["tcr_c_per_min"].optimize(goal="maximize").predicted,
                                                         rel=1e-6)


def test_unreachable_target_is_said_on_the_response_scale(table4):
    fit = rsm_lrg.fit(table4, "tcr_c_per_min", transform="log")
    best = fit.optimize(goal="target=0.5")
    msg = [w for w in best.warnings if "cannot be reached" in w]
    assert msg and "0.5" in msg[0] and "-0.69" not in msg[0]
