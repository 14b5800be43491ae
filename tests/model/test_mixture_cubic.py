"""The Scheffé full cubic (``mixture-cubic``, terms ``AB(A-B)``) and ``--terms`` with those
keys, against R's ``lm`` on published data not used to build the code.

Data (Lawson, *Design and Analysis of Experiments with R*, 2015, ch. 11; R package daewr,
``data/pest.rda`` and ``data/polvdat.rda``): ``r/mixture_pest.csv`` (pesticide formulation,
13 blends of three components) and ``r/mixture_polvdat.csv`` (vinyl formulation in the
constrained region x2 >= 0.1, x3 >= 0.05; centroid replicated three times; fitted on
L-pseudo components). ``r/mixture_cubic.R`` fits them with ``lm(y ~ -1 + X)``, the cubic
columns ``x_i x_j (x_i - x_j)`` as mixexp's ``cubic``, and writes
``r/mixture_cubic_expected.csv``.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.model.build.mixture import pseudo_to_actual
from rsm_lrg.model.build.spec import SpecError
from rsm_lrg.terms import design_gradient, design_matrix, parse_term

HERE = Path(__file__).parent / "r"
SETS = {"pest": ("mixture_pest.csv", ["x1", "x2", "x3"]),
        "polvdat": ("mixture_polvdat.csv", ["x1=0:0.8", "x2=0.1:0.95", "x3=0.05:0.5"])}
SUBSET = "A B C AB AC BC AB(A-B) AC(A-C)"
RTOL = 1e-9


def _fit(set_name, model, **kw):
    path, comps = SETS[set_name]
    terms = SUBSET if model == "terms" else None
    return rsm_lrg.fit(pd.read_csv(HERE / path), "y", components=comps,
                       model="mixture-cubic", terms=terms, **kw)


def _close(got, want, scale):
    assert math.isfinite(got)
    assert abs(got - want) <= RTOL * max(abs(want), scale), (got, want)


@pytest.mark.parametrize("set_name", list(SETS))
@pytest.mark.parametrize("model", ["mixture-cubic", "terms"])
def test_agrees_with_r_lm(set_name, model):
    exp = pd.read_csv(HERE / "mixture_cubic_expected.csv")
    exp = exp[(exp["set"] == set_name) & (exp["model"] == model)]
    r = _fit(set_name, model)
    coef = r.coefficients
    anova = r.anova.set_index("source")
    total = float(anova.loc["Cor Total", "sum_sq"])
    bscale = max(abs(float(v)) for v in exp.loc[exp["quantity"] == "actual", "value"]) if model != "terms" else 0
    seen = set()
    for row in exp.itertuples(index=False):
        q, term, v = row.quantity, row.term, float(row.value)
        if q == "coef":
            _close(float(coef.loc[term, "coded"]), v, 0.0)
        elif q == "se":
            _close(float(coef.loc[term, "std_error"]), v, 0.0)
        elif q == "actual":
            _close(r.actual_coefficients[term], v, 1e-12 * bscale)
        elif q == "actual_se":
            _close(r.actual_std_errors[term], v, 0.0)
        elif q == "anova":
            if term in ("Lack of Fit", "Pure Error") and "Pure Error" not in anova.index:
                assert term == "Lack of Fit" or v == 0.0  # no replicates: no pure error, no lack-of-fit row
                continue
            if term == "Lack of Fit" and term not in anova.index:  # as many terms as blends: no df
                assert abs(v) <= 1e-9 * total
                continue
            _close(float(anova.loc[term, "sum_sq"]), v, 1e-12 * total)
        elif q == "stat" and not math.isfinite(v):  # a blend with leverage 1 (polvdat's cubic): PRESS undefined
            assert math.isnan(float(getattr(r.statistics, term)))
        elif q == "stat":
            _close(float(getattr(r.statistics, term)), v, 0.0)
        else:
            raise AssertionError(q)
        seen.add((q, term))
    names = SUBSET.split() if model == "terms" else ["A", "B", "C", "AB", "AC", "BC", "ABC", "AB(A-B)",
                                                       "AC(A-C)", "BC(B-C)"]
    assert list(coef.index) == names
    assert {("coef", n) for n in names} <= seen and {("se", n) for n in names} <= seen
    assert {("anova", n) for n in names[3:]} <= seen and ("stat", "pred_r2") in seen
    assert list(anova.index)[:2] == ["Model", "Linear Mixture"] and list(anova.index)[-1] == "Cor Total"
    assert int(anova.loc["Model", "df"]) == len(names) - 1


def test_full_cubic_actual_polynomial_predicts_as_the_model():
    """The real-proportion full cubic (keys A, AB, AB(A-B), ABC) reproduces the prediction at
    random blends of the constrained region; so does the expansion with a process factor."""
    r = _fit("polvdat", "mixture-cubic")
    rng = np.random.default_rng(2)
    x = np.array([0.0, 0.1, 0.05]) + 0.85 * rng.dirichlet(np.ones(3), size=60)
    pts = pd.DataFrame(x, columns=["x1", "x2", "x3"])
    cols = {L: x[:, i] for i, L in enumerate("ABC")}
    X = design_matrix(x, [parse_term(k, "ABC") for k in r.actual_coefficients])
    by_poly = X @ np.array(list(r.actual_coefficients.values()))
    np.testing.assert_allclose(by_poly, r.predict(pts)["predicted"].to_numpy(), rtol=1e-10)
    assert set(r.actual_coefficients) == set(r.coefficients.index)
    assert r.actual_coefficients["AB(A-B)"] == pytest.approx(
        float(r.coefficients.loc["AB(A-B)", "coded"]) / 0.85 ** 3, rel=1e-12)
    assert cols  # the columns above are the real proportions


def test_crossed_full_cubic_with_a_process_factor():
    """AB(A-B)D: parsed, fitted, and its real-unit expansion (process factor at 20 +- 5)
    predicts as the model."""
    d = pd.read_csv(HERE / "mixture_pest.csv")
    rng = np.random.default_rng(4)
    d = pd.concat([d.assign(t=15.0), d.assign(t=25.0)], ignore_index=True)
    d["y"] = d["y"] + 0.1 * (d["t"] - 20) * d["x1"] * d["x2"] * (d["x1"] - d["x2"]) + rng.normal(0, 0.1, len(d))
    r = rsm_lrg.fit(d, "y", components=["x1", "x2", "x3"], factors=["t"], model="mixture-cubic",
                    terms="A B C AB AC BC AB(A-B) AD BD CD AB(A-B)D")
    assert "AB(A-B)D" in r.coefficients.index
    x = rng.dirichlet(np.ones(3), size=30)
    t = rng.uniform(15, 25, size=30)
    pts = pd.DataFrame({"x1": x[:, 0], "x2": x[:, 1], "x3": x[:, 2], "t": t})
    act = r.actual_coefficients
    X = design_matrix(np.column_stack([x, t]), [parse_term(k, "ABCD") for k in act])
    np.testing.assert_allclose(X @ np.array(list(act.values())), r.predict(pts)["predicted"].to_numpy(), rtol=1e-10)


def test_change_of_basis_of_a_cubic_term_by_hand():
    """d x'_A x'_B (x'_A - x'_B), x' = (x - L)/R, two components with L = (0.2, 0.2), R = 0.6:
    with u = x - L, u_A + u_B = R, so u_A u_B (u_A - u_B) = u_A u_B (x_A - x_B); expanded,
    d/R^3 [x_A x_B (x_A - x_B) - 0.2 (x_A^2 - x_B^2) + 0.04 (x_A - x_B)] and on x_A + x_B = 1:
    x_A^2 - x_B^2 = x_A - x_B, so the linear terms carry d/R^3 (-0.2 + 0.04) (+ for A, - for B)."""
    d = pd.DataFrame({"a": [0.2, 0.35, 0.5, 0.65, 0.8, 0.5], "b": [0.8, 0.65, 0.5, 0.35, 0.2, 0.5],
                      "y": [1.0, 2.0, 3.0, 2.5, 2.0, 3.1]})
    r = rsm_lrg.fit(d, "y", components=["a=0.2:0.8", "b=0.2:0.8"], model="mixture-cubic")
    assert list(r.coefficients.index) == ["A", "B", "AB", "AB(A-B)"]
    act = pseudo_to_actual({"A": 0.0, "B": 0.0, "AB": 0.0, "AB(A-B)": 1.0}, r.terms, r.space)
    R3 = 0.6 ** 3
    assert act["AB(A-B)"] == pytest.approx(1 / R3, rel=1e-12)
    assert act["A"] == pytest.approx(-0.16 / R3, rel=1e-12)
    assert act["B"] == pytest.approx(0.16 / R3, rel=1e-12)
    assert abs(act.get("AB", 0.0)) <= 1e-12 / R3


def test_term_parsing_and_gradient():
    t = parse_term("AB(A-B)", "ABC")
    assert t.powers == (1, 1, 0) and t.diff == (0, 1) and t.order == 3 and t.name == "AB(A-B)"
    assert parse_term("BC(B-C)D", "ABCD").name == "BC(B-C)D"
    for bad in ("BA(B-A)", "AB(B-A)", "AB(A-C)", "AB(A-B)A", "AB(A-B"):
        with pytest.raises(ValueError):
            parse_term(bad, "ABC")
    x = np.array([0.2, 0.5, 0.3])
    g = design_gradient(x, [t])[0]
    h = 1e-6
    num = [(design_matrix(x + h * e, [t])[0, 0] - design_matrix(x - h * e, [t])[0, 0]) / (2 * h) for e in np.eye(3)]
    np.testing.assert_allclose(g, num, rtol=1e-7, atol=1e-10)


def test_refusals():
    path, comps = SETS["pest"]
    d = pd.read_csv(HERE / path)
    with pytest.raises(SpecError, match="not a Scheffé mixture term"):
        rsm_lrg.fit(d, "y", components=comps, model="mixture-cubic", terms="A B C AB(A-B)C")
    few = d.iloc[:9]
    with pytest.raises(ValueError, match="9 distinct blends cannot fit 10 terms"):
        rsm_lrg.fit(few, "y", components=comps, model="mixture-cubic")


def test_backward_elimination_keeps_ab_while_its_cubic_term_stays():
    """AB(A-B) holds AB: AB may leave only after it (hierarchy), and the linear terms stay."""
    from rsm_lrg.model.choice.reduce import removable

    terms = [parse_term(n, "ABC") for n in ["A", "B", "C", "AB", "AC", "AB(A-B)"]]
    assert [t.name for t in removable(terms)] == ["AC", "AB(A-B)"]
    r = _fit("pest", "mixture-cubic", reduce=True)
    order = list(r.reduction.steps["term"])
    for pair, cubic in (("AB", "AB(A-B)"), ("AC", "AC(A-C)"), ("BC", "BC(B-C)")):
        if pair in order:
            assert cubic in order and order.index(cubic) < order.index(pair)
        else:
            assert pair in r.coefficients.index
    assert {"A", "B", "C"} <= set(r.coefficients.index)
