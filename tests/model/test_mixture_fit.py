"""Scheffé mixture fits (rsm_lrg.model.build.mixture) against R's ``lm`` on published data.

Data: the plasma etch-rate mixture experiment of Myers & Montgomery, *Response Surface
Methodology* (2002), Table 12.4, as shipped in R mixexp's ``etch`` data set (three components,
14 runs; vertices and centroid replicated), in ``r/mixture_etch.csv``; and the same blends
moved into the constrained region x_i >= L_i, L = (0.1, 0.2, 0.05), in
``r/mixture_etch_l.csv``, fitted on L-pseudo components. ``r/mixture.R`` fits both with
``lm(y ~ -1 + ...)`` (pseudo components, and real proportions for the actual coefficients)
and writes ``r/mixture_expected.csv``.
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

HERE = Path(__file__).parent / "r"
SETS = {"etch": ("mixture_etch.csv", ["x1", "x2", "x3"]),
        "etch_l": ("mixture_etch_l.csv", ["x1=0.1:1", "x2=0.2:1", "x3=0.05:1"])}
MODELS = ["mixture-linear", "mixture-quadratic", "special-cubic"]
RTOL = 1e-9


def _expected():
    return pd.read_csv(HERE / "mixture_expected.csv")


def _fit(set_name, model):
    path, comps = SETS[set_name]
    return rsm_lrg.fit(pd.read_csv(HERE / path), "erate", components=comps, model=model)


def _close(got, want, scale):
    assert math.isfinite(got)
    assert abs(got - want) <= RTOL * max(abs(want), scale), (got, want)


@pytest.mark.parametrize("set_name", list(SETS))
@pytest.mark.parametrize("model", MODELS)
def test_agrees_with_r_lm(set_name, model):
    exp = _expected()
    exp = exp[(exp["set"] == set_name) & (exp["model"] == model)]
    r = _fit(set_name, model)
    coef = r.coefficients
    anova = r.anova.set_index("source")
    total = float(anova.loc["Cor Total", "sum_sq"])
    bscale = float(coef["coded"].abs().max())
    pred = r.predict(pd.DataFrame({"x1": [0.3], "x2": [0.3], "x3": [0.4]}), interval="prediction").iloc[0]
    pred_cols = {"fit": "predicted", "pi_low": "pi_low", "pi_high": "pi_high"}
    checked = 0
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
            if term == "Lack of Fit" and term not in anova.index:
                assert abs(v) <= 1e-9 * total
                continue
            _close(float(anova.loc[term, "sum_sq"]), v, 1e-12 * total)
        elif q == "stat":
            _close(float(getattr(r.statistics, term)), v, 0.0)
        elif q == "predict":
            _close(float(pred[pred_cols[term]]), v, 0.0)
        else:
            raise AssertionError(q)
        checked += 1
    assert checked >= 12
    # the ANOVA's shape: Model, Linear Mixture (q - 1 df), non-linear terms, Residual, ..., Cor Total
    nonlin = [t.name for t in r.terms if t.order > 1]
    assert list(anova.index) == ["Model", "Linear Mixture", *nonlin, "Residual", "Lack of Fit", "Pure Error",
                                 "Cor Total"]
    assert int(anova.loc["Linear Mixture", "df"]) == 2
    assert int(anova.loc["Model", "df"]) == len(r.terms) - 1
    assert int(anova.loc["Cor Total", "df"]) == r.n - 1
    assert int(anova.loc["Pure Error", "df"]) == 14 - 10  # 10 distinct blends


def test_pseudo_coding_and_intercept_free():
    r = _fit("etch_l", "mixture-quadratic")
    comps = r.space.factors
    assert [f.letter for f in comps] == ["A", "B", "C"]
    assert all(abs(f.total - 1.0) < 1e-12 and abs(f.pseudo_range - 0.65) < 1e-12 for f in comps)  # T: median row sum
    pseudo = r.coded.to_numpy()
    assert np.allclose(pseudo.sum(axis=1), 1.0, atol=1e-12)  # L-pseudo components sum to one
    assert not r.intercept and r.mixture and "Intercept" not in r.coefficients.index
    d = r.to_dict()
    assert list(d["coefficients"]["coded"]) == ["A", "B", "C", "AB", "AC", "BC"]
    assert d["factors"][0]["component"] is True and d["factors"][0]["lower"] == 0.1
    # the unconstrained and the constrained sets are the same blends in pseudo coding: same ANOVA
    base = _fit("etch", "mixture-quadratic")
    np.testing.assert_allclose(r.anova["sum_sq"], base.anova["sum_sq"], rtol=1e-9)


def test_actual_polynomial_predicts_as_the_model():
    """The real-proportion polynomial reproduces the fitted prediction at random blends of the region."""
    r = _fit("etch_l", "special-cubic")
    rng = np.random.default_rng(7)
    w = rng.dirichlet(np.ones(3), size=50)
    x = np.array([0.1, 0.2, 0.05]) + 0.65 * w
    pts = pd.DataFrame(x, columns=["x1", "x2", "x3"])
    pred = r.predict(pts)["predicted"].to_numpy()
    act = r.actual_coefficients
    letters = {"A": 0, "B": 1, "C": 2}
    by_poly = sum(c * np.prod(x[:, [letters[ch] for ch in k]], axis=1) for k, c in act.items())
    np.testing.assert_allclose(by_poly, pred, rtol=1e-10)


def test_change_of_basis_exact_on_a_small_case():
    """b_A x'_A + b_B x'_B + b_AB x'_A x'_B with x' = (x - L)/R, folded with x_A + x_B = T, by hand."""
    d = pd.DataFrame({"a": [0.2, 0.5, 0.8, 0.2, 0.8], "b": [0.8, 0.5, 0.2, 0.8, 0.2],
                      "y": [1.0, 3.0, 2.0, 1.5, 2.5]})
    r = rsm_lrg.fit(d, "y", components=["a=0.2:0.8", "b=0.2:0.8"], model="mixture-quadratic")
    R = 0.6
    bA, bB, bAB = (float(r.coefficients.loc[k, "coded"]) for k in ("A", "B", "AB"))
    # bAB (a - .2)(b - .2)/R^2 = bAB/R^2 (ab - .2a - .2b + .04); .04 = .04 (a + b)
    want_AB = bAB / R ** 2
    want_A = bA / R - bAB / R ** 2 * 0.2 + bAB / R ** 2 * 0.04 - bA * 0.2 / R - bB * 0.2 / R
    act = pseudo_to_actual({"A": bA, "B": bB, "AB": bAB}, r.terms, r.space)
    assert act["AB"] == pytest.approx(want_AB, rel=1e-12)
    assert act["A"] == pytest.approx(want_A, rel=1e-12)


def test_transform_and_terms():
    path, comps = SETS["etch"]
    d = pd.read_csv(HERE / path)
    r = rsm_lrg.fit(d, "erate", components=comps, model="mixture-quadratic", terms="A B C AB", transform="log")
    assert list(r.coefficients.index) == ["A", "B", "C", "AB"]
    assert r.transform.name == "log"
    assert r.predict(d.iloc[:1])["predicted"].iloc[0] > 0


@pytest.mark.parametrize("change, match", [
    (lambda d: d.assign(x1=d["x1"].where(d.index != 4, 0.6)), r"row 5: the components sum to 1\.1"),
    (lambda d: d.assign(x1=d["x1"].where(d.index != 2, -0.0001), x3=d["x3"].where(d.index != 2, 1.0001)),
     r"row 3: component 'x1' is negative"),
])
def test_bad_rows_named(change, match):
    path, comps = SETS["etch"]
    with pytest.raises(ValueError, match=match):
        rsm_lrg.fit(change(pd.read_csv(HERE / path)), "erate", components=comps, model="mixture-linear")


def test_refusals():
    path, comps = SETS["etch_l"]
    d = pd.read_csv(HERE / path)
    with pytest.raises(ValueError, match=r"row 2: component 'x1' is 0.1.*outside its bounds 0.2"):
        rsm_lrg.fit(d, "erate", components=["x1=0.2:1", "x2=0.2:1", "x3"], model="mixture-linear")
    with pytest.raises(ValueError, match=r"term\(s\) BC\(B-C\) are aliased"):  # 10 blends on 3 lines: no full cubic
        rsm_lrg.fit(d, "erate", components=comps, model="mixture-cubic")
    with pytest.raises(SpecError, match="not a Scheffé mixture term"):
        rsm_lrg.fit(d, "erate", components=comps, model="mixture-quadratic", terms="A B C A^2")
    with pytest.raises(SpecError, match=r"linear blending term \(missing C\)"):
        rsm_lrg.fit(d, "erate", components=comps, model="mixture-quadratic", terms="A B AB")
    with pytest.raises(SpecError, match="Scheffé model"):
        rsm_lrg.fit(d, "erate", components=comps, model="quadratic")
    with pytest.raises(SpecError, match="needs the mixture components"):
        rsm_lrg.fit(d, "erate", model="special-cubic")
    few = d.iloc[[0, 1, 2, 3, 4, 5, 7, 8]]  # six distinct blends
    with pytest.raises(ValueError, match="6 distinct blends cannot fit 7 terms"):
        rsm_lrg.fit(few, "erate", components=comps, model="special-cubic")
    with pytest.raises(ValueError, match="lower bounds sum to 1"):
        rsm_lrg.fit(d, "erate", components=["x1=0.5:1", "x2=0.5:1", "x3=0:1"], model="mixture-linear")


def test_mixture_process_agrees_with_r():
    """Cornell's fish patties (mixexp ``fishp``): Scheffé quadratic x linear process, 24 terms."""
    exp = _expected()
    exp = exp[exp["set"] == "fishp"]
    d = pd.read_csv(HERE / "mixture_fishp.csv")
    r = rsm_lrg.fit(d, "y", components=["x1", "x2", "x3"], factors=["z1", "z2", "z3"], model="mixture-quadratic")
    assert len(r.terms) == 24 and {"AD", "ABD", "BCF"} <= set(r.coefficients.index)
    anova = r.anova.set_index("source")
    total = float(anova.loc["Cor Total", "sum_sq"])
    for row in exp.itertuples(index=False):
        q, term, v = row.quantity, row.term, float(row.value)
        if q == "coef":
            got = r.coefficients.loc[term, "coded"]
        elif q == "se":
            got = r.coefficients.loc[term, "std_error"]
        elif q == "anova":
            got = anova.loc[term, "sum_sq"]
        else:
            got = getattr(r.statistics, term)
        _close(float(got), v, 1e-12 * total if q == "anova" else 0.0)
    assert int(anova.loc["Linear Mixture", "df"]) == 2 and "Pure Error" not in anova.index  # no replicates
    # the actual polynomial (z in actual units; here coded = actual) predicts as the model
    rng = np.random.default_rng(3)
    x = rng.dirichlet(np.ones(3), size=40)
    z = rng.uniform(-1, 1, size=(40, 3))
    pts = pd.DataFrame(np.hstack([x, z]), columns=["x1", "x2", "x3", "z1", "z2", "z3"])
    cols = {L: pts.iloc[:, i].to_numpy() for i, L in enumerate("ABCDEF")}
    by_poly = sum(c * np.prod([cols[ch] for ch in k], axis=0) for k, c in r.actual_coefficients.items())
    np.testing.assert_allclose(by_poly, r.predict(pts)["predicted"].to_numpy(), rtol=1e-10)


def test_mixture_process_actual_with_a_shifted_process_factor():
    """A process factor in actual units (z = 20 + 5 z_coded): the expansion folds its constant into the blend."""
    d = pd.read_csv(HERE / "mixture_fishp.csv").assign(t=lambda f: 20.0 + 5.0 * f["z1"])
    r = rsm_lrg.fit(d, "y", components=["x1", "x2", "x3"], factors=["t", "z2"], model="mixture-linear")
    rng = np.random.default_rng(5)
    x = rng.dirichlet(np.ones(3), size=30)
    t = rng.uniform(15, 25, size=30)
    z2 = rng.uniform(-1, 1, size=30)
    pts = pd.DataFrame({"x1": x[:, 0], "x2": x[:, 1], "x3": x[:, 2], "t": t, "z2": z2})
    cols = {"A": x[:, 0], "B": x[:, 1], "C": x[:, 2], "D": t, "E": z2}
    act = r.actual_coefficients
    assert set(act) == {"A", "B", "C", "AD", "BD", "CD", "AE", "BE", "CE"}
    by_poly = sum(c * np.prod([cols[ch] for ch in k], axis=0) for k, c in act.items())
    np.testing.assert_allclose(by_poly, r.predict(pts)["predicted"].to_numpy(), rtol=1e-10)
    with pytest.raises(SpecError, match="term D has no mixture component"):
        rsm_lrg.fit(d, "y", components=["x1", "x2", "x3"], factors=["t"], model="mixture-linear", terms="A B C D")


def test_backward_elimination_keeps_the_blending_terms():
    """fishp, quadratic x linear process, reduced at alpha 0.1: the linear blending terms stay,
    each step removed a term whose p exceeded 0.1, and every term that could still leave
    (hierarchy kept) has p <= 0.1 in the final ANOVA; the final fit equals the fit of the
    kept terms."""
    from rsm_lrg.model.choice.reduce import removable

    d = pd.read_csv(HERE / "mixture_fishp.csv")
    kw = {"components": ["x1", "x2", "x3"], "factors": ["z1", "z2", "z3"], "model": "mixture-quadratic"}
    r = rsm_lrg.fit(d, "y", reduce=True, **kw)
    assert r.reduction.removed and {"A", "B", "C"} <= set(r.coefficients.index)
    assert (r.reduction.steps["p"] > 0.1).all()
    anova = r.anova.set_index("source")
    for t in removable(r.terms):
        if t.order > 1:
            assert anova.loc[t.name, "p"] <= 0.1
    again = rsm_lrg.fit(d, "y", terms=list(r.coefficients.index), **kw)
    np.testing.assert_allclose(again.coefficients["coded"], r.coefficients["coded"], rtol=1e-12)
    assert r.model == "mixture-quadratic" and "reduced" in r.label


@pytest.mark.parametrize("model", MODELS)
def test_pseudo_origin_does_not_change_the_model(model):
    """A full Scheffé model spans the same functions on the simplex whatever the L-pseudo
    origin: these are the same for L = 0 and for random admissible lower bounds: predictions, the rows of the ANOVA that
    speak of the whole model (Model, Linear Mixture, Residual, Lack of Fit, Pure Error, Cor
    Total) and the real-proportion coefficients. (The pseudo coefficients and the partial SS
    of single non-linear terms depend on the coding, as in Design-Expert.)"""
    d = pd.read_csv(HERE / "mixture_etch_l.csv")
    base = rsm_lrg.fit(d, "erate", components=["x1=0:1", "x2=0:1", "x3=0:1"], model=model)
    rng = np.random.default_rng(11)
    mins = d[["x1", "x2", "x3"]].min().to_numpy()
    for _ in range(5):
        L = [float(v) for v in mins * rng.uniform(0, 1, size=3)]
        comps = [f"x{i + 1}={L[i]!r}:1" for i in range(3)]
        r = rsm_lrg.fit(d, "erate", components=comps, model=model)
        whole = ["Model", "Linear Mixture", "Residual", "Lack of Fit", "Pure Error", "Cor Total"]
        got, want = (x.anova.set_index("source").loc[whole, "sum_sq"] for x in (r, base))
        np.testing.assert_allclose(got, want, rtol=1e-9, atol=1e-12 * 5e5)
        np.testing.assert_allclose(r.fitted, base.fitted, rtol=1e-11)
        a, b = r.actual_coefficients, base.actual_coefficients
        assert set(a) == set(b)
        scale = max(abs(v) for v in b.values())
        for k in b:
            assert abs(a[k] - b[k]) <= 1e-9 * scale, (k, a[k], b[k])


def test_dask_input_refused():
    dd = pytest.importorskip("dask.dataframe")
    d = dd.from_pandas(pd.read_csv(HERE / "mixture_etch.csv"), npartitions=2)
    with pytest.raises(SpecError, match="one in-memory table"):
        rsm_lrg.fit(d, "erate", components=["x1", "x2", "x3"], model="mixture-linear")


def test_result_reduce_refits_on_its_own_components():
    d = pd.read_csv(HERE / "mixture_fishp.csv")
    kw = {"components": ["x1", "x2", "x3"], "factors": ["z1", "z2", "z3"], "model": "mixture-quadratic"}
    full = rsm_lrg.fit(d, "y", **kw)
    r = full.reduce(alpha_out=0.1)
    direct = rsm_lrg.fit(d, "y", reduce=True, **kw)
    assert list(r.coefficients.index) == list(direct.coefficients.index)
    np.testing.assert_allclose(r.coefficients["coded"], direct.coefficients["coded"], rtol=1e-12)


def test_predict_refuses_a_blend_with_a_negative_share_or_one_above_the_total():
    # issue 36: 2 - 1 + 0 sums to the total 1, and predict returned numbers for it
    from rsm_lrg.datasets import data_path

    res = rsm_lrg.fit(pd.read_csv(data_path("mixture_etch.csv")), "erate", components=["x1", "x2", "x3"],
                      model="mixture-quadratic")
    assert np.isfinite(res.predict(pd.DataFrame({"x1": [0.5], "x2": [0.5], "x3": [0.0]}))["predicted"]).all()
    with pytest.raises(ValueError, match=r"component 'x1' is above the total 1 \(2\)"):
        res.predict(pd.DataFrame({"x1": [2.0], "x2": [-1.0], "x3": [0.0]}))
    with pytest.raises(ValueError, match=r"prediction point 2: component 'x2' is negative \(-0.5\)"):
        res.predict(pd.DataFrame({"x1": [0.2, 0.8], "x2": [0.3, -0.5], "x3": [0.5, 0.7]}))
