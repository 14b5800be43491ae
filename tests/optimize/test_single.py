"""Single-response optimiser: the paper's optimum, bounds, targets, goals, and a property
test that the optimum is never beaten by a dense grid / vertex enumeration."""

import itertools

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import rsm_lrg
from rsm_lrg.optimize import parse_goal


@pytest.fixture(scope="module")
def fitted():
    return rsm_lrg.fit(rsm_lrg.load_table4(), "tcr_c_per_min")


def test_paper_minimum(fitted):
    # Paper Sec. 4.3 / DIGEST: every factor at its low level, kappa = 0.022833 (exact to 6 digits).
    opt = rsm_lrg.optimize(fitted, goal="minimize")
    assert opt.coded == {"A": -1.0, "B": -1.0, "C": -1.0, "D": -1.0}
    assert opt.predicted == pytest.approx(0.0228333333, abs=1e-9)
    d = opt.to_dict()
    assert list(d)[:8] == ["response", "goal", "coded", "actual", "predicted", "confidence", "ci", "pi"]
    assert d["confidence"] == 0.95 and d["goal"] == "minimize"


def test_optimize_takes_a_fit_not_data():
    # issue 11: the optimize layer takes fitted results, never data (the caller fits first)
    data = rsm_lrg.load_table4()
    with pytest.raises(TypeError, match="fit first"):
        rsm_lrg.optimize(data, "minimize")
    opt = rsm_lrg.optimize(rsm_lrg.fit(data, "tcr_c_per_min"), "minimize")
    assert opt.predicted == pytest.approx(0.0228333333, abs=1e-9)  # paper Sec. 4.3 / DIGEST, 1e-9


def test_maximum_and_target(fitted):
    mx = fitted.optimize("maximize")
    grid = np.array(list(itertools.product(np.linspace(-1, 1, 21), repeat=4)))
    yg = fitted.predict_coded(grid)
    assert mx.predicted >= yg.max() - 1e-12
    tg = fitted.optimize(("target", 0.03))
    assert tg.goal == "target" and tg.target == 0.03
    assert tg.predicted == pytest.approx(0.03, abs=1e-9)
    assert fitted.optimize("target=0.03").predicted == pytest.approx(0.03, abs=1e-9)
    assert tg.warnings == ()


def test_unreachable_target_gives_the_nearest_extreme_and_says_so(fitted):
    # a target above the largest (below the smallest) prediction in the box: the optimum is the
    # box maximum (minimum) found by "maximize" ("minimize"), with a warning naming the gap
    for target, other in ((0.5, "maximize"), (0.0, "minimize")):
        tg = fitted.optimize(f"target={target}")
        assert tg.predicted == pytest.approx(fitted.optimize(other).predicted, rel=1e-9)
        assert len(tg.warnings) == 1 and "cannot be reached inside the region" in tg.warnings[0]
        assert "closest predicted value" in tg.summary() and tg.to_dict()["warnings"] == list(tg.warnings)


def test_bounds_in_actual_units(fitted):
    opt = fitted.optimize("minimize", bounds={"velocity_m_s": (0.45, 0.55), "D": (25, 35)})
    assert opt.actual["velocity_m_s"] == pytest.approx(0.45)
    assert opt.actual["acceleration_m_s2"] == pytest.approx(25)
    assert opt.bounds["velocity_m_s"] == pytest.approx((0.45, 0.55))
    with pytest.raises(ValueError, match="outside the design range"):
        fitted.optimize("minimize", bounds={"velocity_m_s": (0.3, 0.5)})
    wide = fitted.optimize("minimize", bounds={"velocity_m_s": (0.3, 0.5)}, allow_extrapolation=True)
    assert wide.warnings and wide.actual["velocity_m_s"] <= 0.4
    with pytest.raises(ValueError, match="no such factor"):
        fitted.optimize("minimize", bounds={"speed": (0.4, 0.5)})
    with pytest.raises(ValueError, match="LOW must be below HIGH"):
        fitted.optimize("minimize", bounds=["velocity_m_s=0.5:0.45"])


@pytest.mark.parametrize("bad", ["fastest", "target", "target=abc", "target=inf", 3])
def test_bad_goal(bad):
    with pytest.raises(ValueError):
        parse_goal(bad)


def test_blocked_fit_optimises_average_block():
    df = rsm_lrg.load_table4().copy()
    df["blk"] = np.arange(27) % 3
    r = rsm_lrg.fit(df, "tcr_c_per_min", block="blk")
    opt = r.optimize("minimize")
    x = np.array([[opt.coded[L] for L in r.space.letters]])
    assert opt.predicted == pytest.approx(float(r.predict_coded(x)[0]))


def _quad_fit(k, seed):
    """A fit whose coefficients are a random quadratic (exact data, no noise)."""
    rng = np.random.default_rng(seed)
    pts = np.array(list(itertools.product((-1.0, 0.0, 1.0), repeat=k)))
    from rsm_lrg.model.build.terms import design_matrix, model_terms

    letters = [chr(65 + i) for i in range(k)]
    terms = model_terms(letters, "quadratic")
    beta = rng.normal(size=len(terms))
    y = design_matrix(pts, terms) @ beta + 1e-3 * rng.normal(size=len(pts))
    df = pd.DataFrame(pts, columns=[f"x{i}" for i in range(k)])
    df["y"] = y
    return rsm_lrg.fit(df, "y", factors=[f"x{i}=-1:1" for i in range(k)])


@settings(max_examples=25, deadline=None)
@given(k=st.integers(2, 3), seed=st.integers(0, 10 ** 6), goal=st.sampled_from(["minimize", "maximize"]))
def test_never_beaten_by_dense_grid(k, seed, goal):
    r = _quad_fit(k, seed)
    opt = r.optimize(goal)
    n = 61 if k == 2 else 25
    grid = np.array(list(itertools.product(np.linspace(-1, 1, n), repeat=k)))
    yg = r.predict_coded(grid)
    tol = 1e-9 * (1 + np.abs(yg).max())
    if goal == "minimize":
        assert opt.predicted <= yg.min() + tol
    else:
        assert opt.predicted >= yg.max() - tol
    assert all(-1 <= v <= 1 for v in opt.coded.values())


@settings(max_examples=10, deadline=None)
@given(seed=st.integers(0, 10 ** 6))
def test_five_factors_never_beaten_by_vertices_and_random_points(seed):
    r = _quad_fit(5, seed)
    opt = r.optimize("minimize")
    rng = np.random.default_rng(seed + 1)
    pts = np.vstack([np.array(list(itertools.product((-1.0, 1.0), repeat=5))), rng.uniform(-1, 1, (4000, 5))])
    assert opt.predicted <= r.predict_coded(pts).min() + 1e-9


def test_cubic_model_uses_multistart():
    # no exact face enumeration for cubic terms: the multi-start must still beat a grid
    rng = np.random.default_rng(3)
    pts = rng.uniform(-1, 1, (40, 2))
    df = pd.DataFrame(pts, columns=["u", "v"])
    df["y"] = pts[:, 0] ** 3 - pts[:, 0] + 0.5 * pts[:, 1] ** 2 + 0.01 * rng.normal(size=40)
    r = rsm_lrg.fit(df, "y", factors=["u=-1:1", "v=-1:1"], model="cubic")
    opt = r.optimize("minimize")
    assert opt.method == "multistart"
    grid = np.array(list(itertools.product(np.linspace(-1, 1, 81), repeat=2)))
    assert opt.predicted <= r.predict_coded(grid).min() + 1e-9
