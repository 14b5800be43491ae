"""The equivalent-estimation split-plot central composite design (after Vining, Kowalski &
Montgomery 2005): checked by its defining property, independently of the construction's
algebra — the column space of the quadratic model matrix ``X`` is invariant under
``V = I + η Z Z'``, so OLS and GLS estimates coincide for every η."""

import math

import numpy as np
import pandas as pd
import pytest
from _design_helpers import quadratic_columns

import rsm_lrg
from rsm_lrg.design import read_design
from rsm_lrg.design.split_plot import equivalent_alpha, split_plot_ccd
from rsm_lrg.errors import ParameterError


def _factors(kw: int, ks: int) -> tuple[list[str], list[str]]:
    hard = [f"w{i}=0:{10 * (i + 1)}" for i in range(kw)]
    easy = [f"s{j}=-1:{j + 2}" for j in range(ks)]
    return hard + easy, [h.split("=")[0] for h in hard]


def _model(coded: np.ndarray) -> np.ndarray:
    """Full quadratic model matrix by the test helper (not the package's builder)."""
    return np.column_stack([np.ones(len(coded)), *quadratic_columns(coded).values()])


def _ols_gls_gap(X: np.ndarray, plots: np.ndarray, eta: float, y: np.ndarray) -> float:
    V = np.eye(len(X)) + eta * (plots[:, None] == plots[None, :])
    Vi = np.linalg.inv(V)
    ols = np.linalg.solve(X.T @ X, X.T @ y)
    gls = np.linalg.solve(X.T @ Vi @ X, X.T @ Vi @ y)
    return float(np.max(np.abs(ols - gls)) / np.max(np.abs(ols)))


def _invariance_gap(X: np.ndarray, plots: np.ndarray) -> float:
    """|| (I - P_X) Z Z' X || / || Z Z' X ||: zero iff col(X) is invariant under Z Z'."""
    ZZ = (plots[:, None] == plots[None, :]).astype(float)
    Q, _ = np.linalg.qr(X)
    B = ZZ @ X
    return float(np.linalg.norm(B - Q @ (Q.T @ B)) / np.linalg.norm(B))


@pytest.mark.parametrize("kw", [1, 2])
@pytest.mark.parametrize("ks", [1, 2, 3])
def test_ols_equals_gls_for_every_eta(kw, ks):
    factors, hard = _factors(kw, ks)
    d = split_plot_ccd(factors, hard, seed=kw * 10 + ks)
    X = _model(d.coded_runs)
    plots = np.asarray(d.whole_plots)
    assert np.linalg.matrix_rank(X) == X.shape[1]  # estimates the full quadratic
    assert _invariance_gap(X, plots) < 1e-12
    rng = np.random.default_rng(ks)
    for eta in (0.1, 1.0, 10.0, 1000.0):
        assert _ols_gls_gap(X, plots, eta, rng.normal(size=len(X))) < 1e-10
    # whole-plot factors constant within every whole plot, sub-plot factors not
    frame = pd.DataFrame(d.coded_runs, columns=d.factors.names).assign(wp=plots)
    spread = frame.groupby("wp").agg(lambda c: c.max() - c.min())
    assert (spread[hard].to_numpy() == 0).all()
    assert (spread.drop(columns=hard).to_numpy().max(axis=0) > 0).all()
    # run counts as documented: W = 2^kw + 2 kw + 1 whole plots of m = max(2^ks, 2 ks + 1)
    m = max(2 ** ks, 2 * ks + 1)
    W = 2 ** kw + 2 * kw + 1
    assert d.n_runs == m * W and np.bincount(plots)[1:].tolist() == [m] * W
    a_w, a_s = d.options["alpha_whole_plot"], d.options["alpha_sub_plot"]
    assert a_w == pytest.approx(math.sqrt(kw + 2 ** (ks - 1))) and a_s == pytest.approx(a_w)


def test_the_property_can_fail():
    """Controls: moving the sub-plot star distance off the condition, or dropping a centre
    run (unequal whole plots), breaks equivalent estimation — the checks above can fail."""
    factors, hard = _factors(1, 2)
    d = split_plot_ccd(factors, hard, randomize=False)
    plots = np.asarray(d.whole_plots)
    coded = d.coded_runs.copy()
    star = np.abs(coded[:, 1:]).max(axis=1) > 1.0 + 1e-9
    coded[star, 1:] *= 1.1
    y = np.random.default_rng(0).normal(size=len(coded))
    assert _invariance_gap(_model(coded), plots) > 1e-3
    assert _ols_gls_gap(_model(coded), plots, 1.0, y) > 1e-4
    keep = np.ones(len(coded), dtype=bool)
    keep[np.flatnonzero((d.coded_runs == 0).all(axis=1))[0]] = False
    X = _model(d.coded_runs[keep])
    assert _invariance_gap(X, plots[keep]) > 1e-3


@pytest.mark.parametrize("alpha", [1.2, 2.0, 3.0])
def test_given_whole_plot_alpha_sets_the_sub_plot_alpha(alpha):
    factors, hard = _factors(1, 2)
    d = split_plot_ccd(factors, hard, alpha=alpha, center_whole_plots=2, seed=3)
    a_w, a_s = equivalent_alpha(1, 2, alpha)
    assert d.options["alpha_whole_plot"] == a_w == alpha
    assert a_s ** 2 == pytest.approx(2 * alpha ** 2 / (alpha ** 2 - 1))
    X, plots = _model(d.coded_runs), np.asarray(d.whole_plots)
    assert plots.max() == 2 + 2 + 2 and _invariance_gap(X, plots) < 1e-12
    assert _ols_gls_gap(X, plots, 5.0, np.random.default_rng(1).normal(size=len(X))) < 1e-10


def test_reml_fit_equals_ols_fit_on_the_design(tmp_path):
    """End to end: the REML fit (whatever η it estimates) gives the OLS coefficients."""
    factors, hard = _factors(2, 2)
    d = split_plot_ccd(factors, hard, seed=7)
    path = tmp_path / "d.csv"
    path.write_text(d.csv_text())
    data = pd.read_csv(path)
    rng = np.random.default_rng(2)
    c = d.coded_runs
    wp = rng.normal(0, 1.0, int(data.whole_plot.max()))[data.whole_plot - 1]
    data["y"] = 5 + c[:, 0] - 2 * c[:, 2] + c[:, 1] * c[:, 3] + c[:, 2] ** 2 + wp + rng.normal(0, 0.5, len(c))
    names = [f.split("=")[0] for f in factors]
    ols = rsm_lrg.fit(data, "y", factors=read_design(path).factors)
    reml = rsm_lrg.fit(data, "y", factors=read_design(path).factors, whole_plot="whole_plot", hard_to_change=hard)
    assert reml.mixed.eta > 0.1
    np.testing.assert_allclose(np.asarray(reml.mixed.beta), np.asarray(ols.least_squares.params), rtol=1e-9,
                               atol=1e-9)
    assert names[:2] == hard


@pytest.mark.parametrize("kw, parameter, match", [
    ({"hard_to_change": []}, "hard_to_change", "name at least one"),
    ({"hard_to_change": ["zz"]}, "hard_to_change", "'zz' is not among the factors"),
    ({"hard_to_change": ["w0", "s0"]}, "hard_to_change", "1 to 5 hard-to-change and 1 to 5 other factors"),
    ({"hard_to_change": ["w0"], "alpha": 1.0}, "alpha", r"must exceed sqrt\(1\)"),
    ({"hard_to_change": ["w0"], "center_whole_plots": 0}, "center_whole_plots", "must be a whole number >= 1"),
])
def test_refusals(kw, parameter, match):
    """A bad argument is a ParameterError naming it (the CLI puts the option in front)."""
    with pytest.raises(ParameterError, match=match) as info:
        split_plot_ccd(["w0=0:1", "s0=0:1"], **kw)
    assert info.value.parameter == parameter
