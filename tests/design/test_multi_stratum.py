"""Split-split-plot and strip-plot designs (issue 35, item 2): the GLS criterion recomputed from
dense incidence matrices, the nesting of the strata, the exchange against random restricted
designs and against the classic factorial arrangements, an exact 2 x 2 strip-plot optimum."""

import itertools
import math

import numpy as np
import pytest

from rsm_lrg.design.multi_stratum import split_split_plot, stratum_criteria, stratum_information, strip_plot
from rsm_lrg.design.split_plot import gls_information
from rsm_lrg.errors import ParameterError

SSP_FACTORS = ["T=100:200", "P=1:2", "x=0:1", "y=0:1"]


def _incidence(labels):
    """0/1 incidence matrix (n x groups) of a label column, by plain Python."""
    levels = sorted(set(labels.tolist()))
    return np.array([[1.0 if v == g else 0.0 for g in levels] for v in labels])


def _dense_d(coded, strata, model):
    """GLS D det(X'V^-1 X)^(1/p)/n with V = I + sum eta Z Z' built from incidence matrices and the
    model matrix written out column by column (intercept, mains, 2FI, squares)."""
    n, k = coded.shape
    cols = [np.ones(n)] + [coded[:, i] for i in range(k)]
    if model in ("2fi", "quadratic"):
        cols += [coded[:, i] * coded[:, j] for i in range(k) for j in range(i + 1, k)]
    if model == "quadratic":
        cols += [coded[:, i] ** 2 for i in range(k)]
    X = np.column_stack(cols)
    V = np.eye(n)
    for labels, eta in strata:
        Z = _incidence(np.asarray(labels))
        V = V + eta * Z @ Z.T
    sign, logdet = np.linalg.slogdet(X.T @ np.linalg.solve(V, X))
    return math.exp(logdet / X.shape[1]) / n if sign > 0 else 0.0


def _nesting_violations(d, stratum_of):
    """(factor, group column, group) triples where a factor is not constant within a group of its
    stratum, plus sub-plots that straddle whole plots."""
    bad = []
    cols = {"whole_plot": d.whole_plots, **d.strata}
    for j, name in enumerate(d.factors.names):
        col = stratum_of.get(name)
        if col is None:
            continue
        g = cols[col]
        for lab in np.unique(g):
            if len(np.unique(d.coded_runs[g == lab, j])) > 1:
                bad.append((name, col, int(lab)))
    if "subplot" in d.strata:
        for s in np.unique(d.strata["subplot"]):
            if len(np.unique(d.whole_plots[d.strata["subplot"] == s])) > 1:
                bad.append(("subplot", "whole_plot", int(s)))
    return bad


@pytest.fixture(scope="module")
def ssp():
    return split_split_plot(SSP_FACTORS, ["T"], ["P"], whole_plots=6, subplots=12, runs=36, model="quadratic",
                            variance_ratios={"whole_plot": 2.0, "subplot": 0.5}, seed=11, starts=3)


def test_split_split_plot_criterion_equals_dense_v(ssp):
    d = ssp
    want = _dense_d(d.coded_runs, [(d.whole_plots, 2.0), (d.strata["subplot"], 0.5)], "quadratic")
    assert d.options["criterion_value"] == pytest.approx(want, rel=1e-10)
    got = stratum_criteria(d, model="quadratic", variance_ratios={"whole_plot": 2.0, "subplot": 0.5})
    assert got["d_efficiency"] == pytest.approx(want, rel=1e-10)
    assert got["strata"] == {"whole_plot": {"groups": 6, "sizes": [6, 6], "variance_ratio": 2.0},
                             "subplot": {"groups": 12, "sizes": [3, 3], "variance_ratio": 0.5}}
    # a single stratum is the split-plot information of Goos & Vandebroek's closed form
    X = np.column_stack([np.ones(d.n_runs), d.coded_runs])
    assert np.allclose(stratum_information(X, {"whole_plot": d.whole_plots}, {"whole_plot": 2.0}),
                       gls_information(X, d.whole_plots, 2.0), rtol=1e-12, atol=1e-12)


def test_split_split_plot_nesting(ssp):
    d = ssp
    stratum_of = {"T": "whole_plot", "P": "subplot"}
    assert _nesting_violations(d, stratum_of) == []
    # the check fails on a violated design: one run's P changed inside its sub-plot, a sub-plot moved
    coded = d.coded_runs.copy()
    coded[0, 1] = -coded[0, 1] if coded[0, 1] != 0 else 1.0
    broken = type(d)(d.factors, d.kind, coded, d.std_order, d.run_order, options=d.options,
                     whole_plots=d.whole_plots, strata=d.strata)
    assert ("P", "subplot", int(d.strata["subplot"][0])) in _nesting_violations(broken, stratum_of)
    plots = d.whole_plots.copy()
    plots[0] = plots[-1]
    moved = type(d)(d.factors, d.kind, d.coded_runs, d.std_order, d.run_order, options=d.options,
                    whole_plots=plots, strata=d.strata)
    assert _nesting_violations(moved, stratum_of)
    # each whole plot holds 2 sub-plots, each sub-plot 3 runs, groups numbered in run order
    assert d.whole_plots.tolist() == sorted(d.whole_plots.tolist())
    assert d.strata["subplot"].tolist() == sorted(d.strata["subplot"].tolist())


def test_split_split_plot_beats_random_and_the_factorial_arrangement():
    rng = np.random.default_rng(0)
    d = split_split_plot(["A=-1:1", "B=-1:1", "C=-1:1"], ["A"], ["B"], whole_plots=4, subplots=8, runs=16,
                         model="2fi", seed=3, starts=4)
    best = _dense_d(d.coded_runs, [(d.whole_plots, 1.0), (d.strata["subplot"], 1.0)], "2fi")
    wp, sp = np.repeat(np.arange(4), 4), np.repeat(np.arange(8), 2)
    rand = []
    for _ in range(300):  # random restricted designs: one -1/0/1 level per group of each stratum
        D = np.column_stack([rng.choice([-1.0, 0.0, 1.0], 4)[wp], rng.choice([-1.0, 0.0, 1.0], 8)[sp],
                             rng.choice([-1.0, 0.0, 1.0], 16)])
        rand.append(_dense_d(D, [(wp, 1.0), (sp, 1.0)], "2fi"))
    assert best > max(rand)
    # the textbook arrangement: A = +-1 by whole plot (twice), B = +-1 by sub-plot, C = +-1 in each
    fact = np.array([[a, b, c] for a in (-1, 1, -1, 1) for b in (-1, 1) for c in (-1, 1)], dtype=float)
    assert best >= _dense_d(fact, [(wp, 1.0), (sp, 1.0)], "2fi") * (1 - 1e-9)


def test_strip_plot_exact_two_by_two():
    """R = C = 2, the 2FI model in a row factor and a column factor: X is the 4 x 4 Hadamard matrix
    (|det X| = 16 is the bound for entries in [-1, 1]); det V = 5 * 3 * 3 * 1 (the eigenvalues of
    I + J_r + J_c), so D = (256/45)^(1/4) / 4 exactly."""
    d = strip_plot(["A=0:1", "B=0:1"], ["A"], ["B"], rows=2, columns=2, model="2fi", seed=1, starts=2)
    assert d.options["criterion_value"] == pytest.approx((256 / 45) ** 0.25 / 4, rel=1e-12)
    assert sorted(map(tuple, np.abs(d.coded_runs).tolist())) == [(1.0, 1.0)] * 4


def test_strip_plot_criterion_nesting_and_random():
    d = strip_plot(["A=0:1", "B=0:1", "C=0:1", "E=0:1"], ["A", "B"], ["C"], rows=6, columns=4, model="2fi",
                   variance_ratios={"strip_row": 3.0, "strip_column": 0.5}, seed=5, starts=3)
    rows, cols = d.strata["strip_row"], d.strata["strip_column"]
    assert sorted(zip(rows.tolist(), cols.tolist())) == list(itertools.product(range(1, 7), range(1, 5)))
    assert _nesting_violations(d, {"A": "strip_row", "B": "strip_row", "C": "strip_column"}) == []
    want = _dense_d(d.coded_runs, [(rows, 3.0), (cols, 0.5)], "2fi")
    assert d.options["criterion_value"] == pytest.approx(want, rel=1e-10)
    rng = np.random.default_rng(1)
    r, c = np.repeat(np.arange(6), 4), np.tile(np.arange(4), 6)
    lv = [-1.0, 0.0, 1.0]
    rand = [_dense_d(np.column_stack([rng.choice(lv, 6)[r], rng.choice(lv, 6)[r], rng.choice(lv, 4)[c],
                                      rng.choice(lv, 24)]), [(r, 3.0), (c, 0.5)], "2fi") for _ in range(300)]
    assert want > max(rand)


@pytest.mark.parametrize("call, parameter", [
    (lambda: split_split_plot(SSP_FACTORS, ["T"], ["T"], 4, 8, 16, model="linear"), "hard_to_change"),
    (lambda: split_split_plot(SSP_FACTORS, ["Q"], ["P"], 4, 8, 16, model="linear"), "very_hard_to_change"),
    (lambda: split_split_plot(SSP_FACTORS, ["T"], ["P"], 1, 8, 16, model="linear"), "whole_plots"),
    (lambda: split_split_plot(SSP_FACTORS, ["T"], ["P"], 4, 2, 16, model="linear"), "subplots"),
    (lambda: split_split_plot(SSP_FACTORS, ["T"], ["P"], 4, 8, 6, model="linear"), "runs"),
    (lambda: strip_plot(SSP_FACTORS, ["T"], ["P"], 1, 4, model="linear"), "rows"),
    (lambda: strip_plot(SSP_FACTORS, ["T"], [], 4, 4, model="linear"), "column_factors"),
])
def test_bad_arguments_name_the_parameter(call, parameter):
    with pytest.raises(ParameterError) as exc:
        call()
    assert exc.value.parameter == parameter
