"""Optimal split-plot designs (issue 23): rsm_lrg.design.split_plot and the GLS information.

The independent route: the model matrix built column by column with plain numpy
(tests/design/_design_helpers.quadratic_columns), ``V`` as a dense block-diagonal matrix and
``X' V^-1 X`` by a dense inverse; none of rsm_lrg's model-matrix or GLS code is used for it.
"""

import math

import numpy as np
import pytest
from _design_helpers import quadratic_columns
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rsm_lrg.design import Design, criterion_value, read_design, split_plot
from rsm_lrg.design.split_plot import gls_criteria, gls_information, plot_sizes
from rsm_lrg.errors import ParameterError
from rsm_lrg.terms import model_terms

FOUR = ["T=150:250", "P=1:3", "v=0.1:0.5", "a=1:5"]


def _X(coded: np.ndarray) -> np.ndarray:
    """Intercept + linear + 2FI + squares, plain numpy."""
    return np.column_stack([np.ones(len(coded))] + list(quadratic_columns(coded).values()))


def _V(plots: np.ndarray, eta: float) -> np.ndarray:
    """Dense ``I + eta * [same whole plot]``."""
    plots = np.asarray(plots)
    return np.eye(len(plots)) + eta * (plots[:, None] == plots[None, :])


def _d(coded: np.ndarray, plots: np.ndarray, eta: float) -> float:
    """GLS D ``det(X'V^-1 X)^(1/p) / n`` by dense linear algebra."""
    X = _X(coded)
    M = X.T @ np.linalg.inv(_V(plots, eta)) @ X
    sign, logdet = np.linalg.slogdet(M)
    return math.exp(logdet / X.shape[1]) / len(coded) if sign > 0 else 0.0


@pytest.fixture(scope="module")
def four():
    return split_plot(FOUR, ["T", "P"], whole_plots=8, runs=32, model="quadratic", criterion="D",
                      variance_ratio=1.0, seed=11)


def test_done_when_beats_200_random_designs(four):
    """Issue 23's check: 4 factors, 2 hard to change, 8 whole plots of 4 runs, quadratic:
    the full model (15 parameters) is estimable and the design beats the best of 200 random
    designs of the same structure on the GLS D-criterion (eta = 1)."""
    coded, plots = four.coded_runs, four.whole_plots
    X = _X(coded)
    assert X.shape == (32, 15) and np.linalg.matrix_rank(X) == 15
    d_opt = _d(coded, plots, 1.0)
    rng = np.random.default_rng(2023)
    structure = np.repeat(np.arange(8), 4)
    best = 0.0
    for r in range(200):
        # half on the -1/0/+1 grid (the levels of the optimum), half uniform on the cube
        draw = (lambda size: rng.integers(-1, 2, size).astype(float)) if r % 2 else (
            lambda size: rng.uniform(-1.0, 1.0, size))
        wp = draw((8, 2))[structure]
        sp = draw((32, 2))
        best = max(best, _d(np.column_stack([wp, sp]), structure, 1.0))
    assert best > 0
    assert d_opt > best, (d_opt, best)
    assert d_opt > 1.05 * best  # not a near tie: the search wins clearly


def test_whole_plot_factors_constant_and_plots_contiguous(four):
    df = four.to_frame()
    assert list(df.columns[:3]) == ["std_order", "run_order", "whole_plot"]
    for _, g in df.groupby("whole_plot"):
        assert g["T"].nunique() == 1 and g["P"].nunique() == 1
        assert len(g) == 4
        # contiguous in run order
        assert g["run_order"].max() - g["run_order"].min() == 3
    # numbered 1..W in run order
    assert df["whole_plot"].tolist() == sorted(df["whole_plot"].tolist())
    assert set(df["whole_plot"]) == set(range(1, 9))
    # the easy factors do vary within whole plots
    assert any(g["v"].nunique() > 1 for _, g in df.groupby("whole_plot"))


def test_reported_criterion_equals_independent_route(four):
    assert four.options["criterion_value"] == pytest.approx(_d(four.coded_runs, four.whole_plots, 1.0), rel=1e-10)
    g = gls_criteria(four, model="quadratic", variance_ratio=1.0)
    assert g["d_efficiency"] == pytest.approx(four.options["criterion_value"], rel=1e-12)
    assert g["whole_plots"] == 8 and g["plot_sizes"] == [4, 4] and g["p"] == 15 and g["estimable"]


def test_csv_round_trip_keeps_whole_plots(four, tmp_path):
    path = tmp_path / "sp.csv"
    four.to_csv(path)
    back = read_design(path)
    assert np.array_equal(back.whole_plots, four.whole_plots)
    assert np.allclose(back.coded_runs, four.coded_runs)
    assert gls_criteria(back, variance_ratio=1.0)["d_efficiency"] == pytest.approx(
        four.options["criterion_value"], rel=1e-9)


def test_same_seed_same_design_and_run_order_randomised():
    a = split_plot(FOUR, ["T", "P"], 8, 32, seed=4, starts=2)
    b = split_plot(FOUR, ["T", "P"], 8, 32, seed=4, starts=2)
    assert a.csv_text() == b.csv_text()
    assert not np.array_equal(a.std_order, np.arange(1, 33))  # randomised
    c = split_plot(FOUR, ["T", "P"], 8, 32, seed=4, starts=2, randomize=False)
    assert np.array_equal(c.std_order, np.arange(1, 33))
    assert c.options["randomize"] is False


@pytest.mark.parametrize("sizes", [[3, 3, 3], [4, 2, 1, 5], [1, 1]])
def test_gls_information_equals_dense_inverse(sizes):
    rng = np.random.default_rng(len(sizes))
    plots = np.repeat(np.arange(len(sizes)), sizes)
    X = rng.normal(size=(len(plots), 4))
    for eta in (0.0, 0.3, 1.0, 25.0):
        dense = X.T @ np.linalg.inv(_V(plots, eta)) @ X
        assert np.allclose(gls_information(X, plots, eta), dense, rtol=1e-12, atol=1e-12)


def test_eta_zero_is_the_completely_randomised_criterion():
    """At eta = 0 the GLS information is X'X: the reported D equals the OLS D of the same
    runs (with the whole-plot restriction still in the design)."""
    d = split_plot(FOUR, ["T", "P"], 8, 32, variance_ratio=0.0, seed=2, starts=4)
    terms = model_terms(d.factors.letters, "quadratic")
    assert d.options["criterion_value"] == pytest.approx(criterion_value(d.coded_runs, terms, "D"), rel=1e-12)
    assert d.options["criterion_value"] == pytest.approx(_d(d.coded_runs, d.whole_plots, 0.0), rel=1e-10)
    for _, g in d.to_frame().groupby("whole_plot"):
        assert g["T"].nunique() == 1 and g["P"].nunique() == 1


@pytest.mark.slow
def test_larger_eta_changes_the_design_sensibly():
    """Each design is the better one under its own variance ratio (cross-evaluated by the dense
    route), and with a large whole-plot variance the GLS D of any design falls."""
    low = split_plot(FOUR, ["T", "P"], 8, 32, variance_ratio=0.0, seed=5)
    high = split_plot(FOUR, ["T", "P"], 8, 32, variance_ratio=10.0, seed=5)
    assert _d(high.coded_runs, high.whole_plots, 10.0) > _d(low.coded_runs, low.whole_plots, 10.0)
    assert _d(low.coded_runs, low.whole_plots, 0.0) > _d(high.coded_runs, high.whole_plots, 0.0)
    assert _d(high.coded_runs, high.whole_plots, 10.0) < _d(high.coded_runs, high.whole_plots, 1.0)


def test_unequal_whole_plots_distributed_and_said():
    assert plot_sizes(30, 8) == [4] * 6 + [3] * 2
    d = split_plot(FOUR, ["T", "P"], 8, 30, seed=1, starts=2)
    counts = np.unique(d.whole_plots, return_counts=True)[1]
    assert sorted(counts.tolist()) == [3, 3, 4, 4, 4, 4, 4, 4]
    assert "do not divide" in d.options["note"] and "do not divide" in d.summary()
    assert d.options["criterion_value"] == pytest.approx(_d(d.coded_runs, d.whole_plots, 1.0), rel=1e-10)


def test_categoric_hard_to_change_and_constraint():
    cons = ["v + 0.1*a <= 0.8"]
    d = split_plot(["T=150:250", "oil=cat:A,B,C", "v=0.1:0.5", "a=1:5"], ["oil", "T"], whole_plots=9, runs=27,
                   model="quadratic", criterion="I", constraints=cons, seed=3, starts=2)
    df = d.to_frame()
    for _, g in df.groupby("whole_plot"):
        assert g["oil"].nunique() == 1 and g["T"].nunique() == 1
    assert set(df["oil"]) == {"A", "B", "C"}
    assert (df["v"] + 0.1 * df["a"] <= 0.8 + 1e-9).all()
    assert math.isfinite(d.options["criterion_value"]) and d.options["criterion"] == "I"
    assert d.options["constraints"] == cons


@settings(max_examples=6, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(k_hard=st.integers(1, 2), plots=st.integers(4, 6), per=st.integers(2, 4),
       eta=st.sampled_from([0.0, 0.5, 1.0, 4.0]), seed=st.integers(0, 2 ** 16))
def test_property_whole_plots_and_criterion(k_hard, plots, per, eta, seed):
    names = ["A", "B", "C"][:k_hard]
    d = split_plot(["A=0:1", "B=0:1", "C=0:1"], names, whole_plots=plots, runs=plots * per, model="linear",
                   variance_ratio=eta, seed=seed, starts=1)
    df = d.to_frame()
    for _, g in df.groupby("whole_plot"):
        assert len(g) == per
        for n in names:
            assert g[n].nunique() == 1
    X = np.column_stack([np.ones(d.n_runs), d.coded_runs])
    M = X.T @ np.linalg.inv(_V(d.whole_plots, eta)) @ X
    assert d.options["criterion_value"] == pytest.approx(np.linalg.det(M) ** (1 / 4) / d.n_runs, rel=1e-9)


@pytest.mark.parametrize("kwargs, parameter, match", [
    (dict(hard_to_change=["Q"]), "hard_to_change", "^'Q' is not among"),
    (dict(hard_to_change=[]), "hard_to_change", "^name at least one"),
    (dict(whole_plots=5), "whole_plots", "^5 whole plots cannot estimate"),
    (dict(runs=14), "runs", "^14 runs cannot estimate the 15"),
    (dict(runs=32, whole_plots=33), "runs", "^32 runs cannot fill 33"),
    (dict(variance_ratio=-1.0), "variance_ratio", "finite number >= 0"),
    (dict(variance_ratio=math.inf), "variance_ratio", "finite number >= 0"),
    (dict(variance_ratio=math.nan), "variance_ratio", "finite number >= 0"),
])
def test_errors(kwargs, parameter, match):
    """A bad argument is a ParameterError naming it (the CLI shows its option in front)."""
    args = dict(factors=FOUR, hard_to_change=["T", "P"], whole_plots=8, runs=32, seed=1, starts=1)
    args.update(kwargs)
    with pytest.raises(ParameterError, match=match) as info:
        split_plot(**args)
    assert info.value.parameter == parameter


def test_design_rejects_bad_whole_plot_labels():
    with pytest.raises(ValueError, match="whole_plots"):
        Design(split_plot(FOUR, ["T"], 16, 32, model="linear", seed=1, starts=1).factors, "custom",
               np.zeros((2, 4)), [1, 2], [1, 2], whole_plots=[0, 1])


def _grid_optimum(eta: float, W: int = 3, m: int = 3) -> float:
    """The best GLS D of every split-plot design on the -1/0/+1 grid with one whole-plot factor
    A, one sub-plot factor B, W whole plots of m runs and the quadratic model: exhaustive up to
    the criterion's symmetries (the order of the whole plots, of the runs within one)."""
    import itertools

    plots = np.repeat(np.arange(W), m)
    Vi = np.linalg.inv(_V(plots, eta))
    lv = (-1.0, 0.0, 1.0)
    within = list(itertools.combinations_with_replacement(lv, m))  # one whole plot's B settings
    B = np.array([np.concatenate(c) for c in itertools.product(within, repeat=W)])
    best = -np.inf
    for wp in itertools.combinations_with_replacement(lv, W):
        A = np.broadcast_to(np.repeat(wp, m), B.shape)
        X = np.stack([np.ones_like(B), A, B, A * B, A * A, B * B], axis=2)
        sign, logdet = np.linalg.slogdet(np.einsum("nip,ij,njq->npq", X, Vi, X))
        best = max(best, float(np.max(np.where(sign > 0, logdet, -np.inf))))
    return math.exp(best / 6) / (W * m)


@pytest.mark.parametrize("eta", [0.0, 1.0, 5.0])
def test_reaches_the_exhaustive_grid_optimum(eta):
    """Against exhaustive search: 1 whole-plot and 1 sub-plot factor, 3 whole plots of 3 runs,
    quadratic model (6 coefficients): the search reaches the best grid design's GLS D."""
    d = split_plot(["A=-1:1", "B=-1:1"], ["A"], whole_plots=3, runs=9, variance_ratio=eta, seed=1)
    assert d.options["criterion_value"] >= _grid_optimum(eta) * (1 - 1e-12)
