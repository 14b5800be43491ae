"""Desirability (Derringer–Suich as Stat-Ease documents it): the ramps by hand, the
importance-weighted geometric mean, D in [0, 1], and the multi-start search."""

import itertools

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import rsm_lrg
from rsm_lrg.optimize.desirability import (
    ResponseGoal,
    individual_desirability,
    log_individual_desirability,
    optimize_desirability,
    overall_desirability,
    parse_response_goal,
)


def test_linear_ramps_by_hand():
    # Stat-Ease "Desirability Details": with weight 1 d is the linear ramp between the limits.
    mx = ResponseGoal("y", "maximize", 0.0, 10.0)
    assert individual_desirability([-1, 0, 2.5, 10, 12], mx).tolist() == [0.0, 0.0, 0.25, 1.0, 1.0]
    mn = ResponseGoal("y", "minimize", 0.0, 10.0)
    assert individual_desirability([-1, 2.5, 12], mn).tolist() == [1.0, 0.75, 0.0]
    tg = ResponseGoal("y", "target", 0.0, 10.0, target=4.0)
    assert individual_desirability([2.0, 4.0, 7.0, 11.0], tg).tolist() == [0.5, 1.0, 0.5, 0.0]
    rg = ResponseGoal("y", "range", 0.0, 10.0)
    assert individual_desirability([-0.1, 5, 10.1], rg).tolist() == [0.0, 1.0, 0.0]
    # Stat-Ease "Weight": d = ramp^w
    w = ResponseGoal("y", "maximize", 0.0, 10.0, weight=3)
    assert individual_desirability([5.0], w)[0] == pytest.approx(0.5 ** 3, rel=1e-15)
    # a single response: D equals its d
    assert overall_desirability([np.array([0.25])], [mx])[0] == pytest.approx(0.25, rel=1e-15)


def test_importance_weighted_geometric_mean_by_hand():
    # Stat-Ease "Importance": D = (Π d_i^r_i)^(1/Σ r_i); "in range" not counted in Σ r_i.
    g = [ResponseGoal("a", "maximize", 0, 1, importance=5), ResponseGoal("b", "maximize", 0, 1, importance=1),
         ResponseGoal("c", "range", 0, 1, importance=3)]
    D = overall_desirability([np.array([0.5]), np.array([0.8]), np.array([1.0])], g)[0]
    assert D == pytest.approx((0.5 ** 5 * 0.8) ** (1 / 6), rel=1e-14)
    D0 = overall_desirability([np.array([0.5]), np.array([0.8]), np.array([0.0])], g)[0]
    assert D0 == 0.0


@given(st.lists(st.floats(-1e3, 1e3), min_size=1, max_size=4), st.floats(0.1, 10), st.integers(1, 5),
       st.sampled_from(["maximize", "minimize", "target", "range"]))
def test_d_and_D_lie_in_unit_interval(ys, w, r, goal):
    g = ResponseGoal("y", goal, -100.0, 100.0, target=10.0 if goal == "target" else None, weight=w, importance=r)
    d = individual_desirability(ys, g)
    assert np.all((d >= 0) & (d <= 1))
    D = overall_desirability([d, d[::-1]], [g, g])
    assert np.all((D >= 0) & (D <= 1))


def test_search_beats_a_grid_on_two_paper_responses():
    df = rsm_lrg.load_table4()
    fac = ["thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2"]
    df["y2"] = 1000 * df.tcr_c_per_min + 100 * df.stroke_m  # a second response with its own optimum
    fits = {"tcr_c_per_min": rsm_lrg.fit(df, "tcr_c_per_min", factors=fac), "y2": rsm_lrg.fit(df, "y2", factors=fac)}
    goals = [ResponseGoal("tcr_c_per_min", "minimize"), ResponseGoal("y2", "target", target=35.0, importance=5)]
    res = optimize_desirability(fits, goals)
    assert 0 < res.desirability <= 1
    # no grid point of the coded box (7^4) beats it
    grid = np.array(list(itertools.product(np.linspace(-1, 1, 7), repeat=4)))
    ys = [fits[g.response].predict(grid, coded=True)["predicted"].to_numpy() for g in res.goals]
    Dg = overall_desirability([individual_desirability(y, g) for y, g in zip(ys, res.goals)], res.goals)
    assert res.desirability >= Dg.max() - 1e-9
    # the reported d's and D are consistent with the predictions
    x = np.array([list(res.coded.values())])
    for g in res.goals:
        y = fits[g.response].predict(x, coded=True)["predicted"].iloc[0]
        assert res.predicted[g.response] == pytest.approx(y, rel=1e-10)
        assert res.individual[g.response] == pytest.approx(individual_desirability([y], g)[0], rel=1e-10)
    d = res.to_dict()
    assert {"desirability", "individual", "predicted", "coded", "actual"} <= set(d)


def test_single_response_matches_single_optimum():
    fit = rsm_lrg.fit(rsm_lrg.load_table4(), "tcr_c_per_min")
    # limits wider than the box's range: the desirability maximum is the response minimum
    g = ResponseGoal("tcr_c_per_min", "minimize", 0.0, 0.1)
    res = optimize_desirability({"tcr_c_per_min": fit}, [g])
    assert res.predicted["tcr_c_per_min"] == pytest.approx(0.0228333, abs=1e-6)  # paper optimum
    assert res.desirability == pytest.approx((0.1 - 0.0228333) / 0.1, abs=1e-6)


def test_errors():
    with pytest.raises(ValueError, match="weights"):
        ResponseGoal("y", "maximize", weight=20)
    with pytest.raises(ValueError, match="importance"):
        ResponseGoal("y", "maximize", importance=6)
    with pytest.raises(ValueError, match="outside the limits"):
        ResponseGoal("y", "target", 0, 1, target=3)
    with pytest.raises(ValueError, match="goal"):
        parse_response_goal("y", "biggest")
    g = parse_response_goal("y", "target=3", weight="2,0.5", importance="4", limits="1:5")
    assert g.weight == (2.0, 0.5) and g.importance == 4 and (g.low, g.high, g.target) == (1.0, 5.0, 3.0)


def test_cli_multi_response_and_single_unchanged(capsys, tmp_path):
    import json

    from rsm_lrg.cli import main

    df = rsm_lrg.load_table4()
    df["y2"] = 1000 * df.tcr_c_per_min + 100 * df.stroke_m
    path = tmp_path / "two.csv"
    df.to_csv(path, index=False)
    assert main(["optimize", str(path), "--response", "tcr_c_per_min", "--goal", "minimize",
                 "--response", "y2", "--goal", "target=35", "--importance", "3", "--importance", "5",
                 "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert 0 < d["desirability"] <= 1 and set(d["individual"]) == {"tcr_c_per_min", "y2"}
    assert list(d["coded"]) == ["A", "B", "C", "D"]  # the other response is not a factor
    # single response: the INTERFACE JSON, unchanged
    assert main(["optimize", "data/table4.csv", "--response", "tcr_c_per_min", "--json", "-"]) == 0
    s = json.loads(capsys.readouterr().out)
    assert list(s)[:8] == ["response", "goal", "coded", "actual", "predicted", "confidence", "ci", "pi"]
    assert s["predicted"] == pytest.approx(0.0228333, abs=1e-6)


def test_transformed_fit_is_back_transformed_and_limits_are_on_the_original_scale():
    # Montgomery, DAE (8th ed.), Example 11.2 yield fitted to ln(y): the desirability uses
    # exp(ẑ) and the default limits are the observed range of y itself (75.6 .. 80.3).
    import numpy as np

    import rsm_lrg
    from rsm_lrg.optimize.desirability import optimize_desirability, parse_response_goal
    from tests.model._published import MONTGOMERY_11_2

    f = ["x1=-1:1", "x2=-1:1"]
    tf = rsm_lrg.fit_transformed(MONTGOMERY_11_2, "y", "log", factors=f)
    res = optimize_desirability({"y": tf}, [parse_response_goal("y", "maximize")])
    g = res.goals[0]
    assert (g.low, g.high) == (pytest.approx(75.6, rel=1e-12), pytest.approx(80.3, rel=1e-12))
    x = np.array([[res.coded["A"], res.coded["B"]]])
    assert res.predicted["y"] == pytest.approx(float(tf.predict(x, coded=True)["predicted"].iloc[0]), rel=1e-12)
    assert res.individual["y"] == pytest.approx((res.predicted["y"] - 75.6) / (80.3 - 75.6), rel=1e-9)


# -- limits near the largest float (issue 36) --------------------------------------------------
def test_huge_limits_neither_overflow_nor_flatten_the_ramps():
    """``U - L`` of -1e308..1e308 overflows: every d was 0 (maximize) — the ramps take halves."""
    g = ResponseGoal("y", "maximize", -1e308, 1e308)
    np.testing.assert_array_equal(individual_desirability([-1e308, 0.0, 1e308], g), [0.0, 0.5, 1.0])
    g = ResponseGoal("y", "minimize", -1.7e308, 1.7e308)
    np.testing.assert_array_equal(individual_desirability([-1.7e308, 0.0, 1.7e308], g), [1.0, 0.5, 0.0])
    # near a target d rounds to 1; log d keeps the shortfall (T - y) / (T - L) = 0.0037 / 1e308
    g = ResponseGoal("y", "target", -1e308, 1e308, target=0.03)
    assert individual_desirability([0.0337], g)[0] == 1.0
    ld = log_individual_desirability([0.0337, 0.03, 0.0263], g)
    assert ld[1] == 0.0 and ld[0] < 0.0 and ld[2] < 0.0
    assert ld[0] == pytest.approx(-0.0037 / 1e308, rel=1e-3)
    # ordinary limits: log d is log of d
    g = ResponseGoal("y", "target", 0.02, 0.05, target=0.03, weight=(2.0, 0.5))
    y = np.linspace(0.021, 0.049, 15)
    np.testing.assert_allclose(np.exp(log_individual_desirability(y, g)), individual_desirability(y, g), rtol=1e-13)


def test_target_with_huge_limits_is_met_where_it_can_be(capsys):
    """``optimize --goal target=0.03 --limits -1e308:1e308`` reported D = 1 "on target" at a
    prediction of 0.0337, since every d rounded to 1; the target is reachable (Table 4's
    predictions span 0.028..0.045), so the optimum predicts it."""
    import json

    from rsm_lrg.cli import main

    assert main(["optimize", "data/table4.csv", "--response", "tcr_c_per_min", "--goal", "target=0.03",
                 "--limits", "-1e308:1e308", "--json", "-"]) == 0
    js = json.loads(capsys.readouterr().out)
    assert js["predicted"]["tcr_c_per_min"] == pytest.approx(0.03, abs=1e-9)
    assert js["desirability"] == 1.0
