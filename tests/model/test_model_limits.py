"""Hostile input to the model layer (issue 10, item 11): each class fails fast with a
ValueError whose sentence names the column and the reason (the CLI prints it as one
`error:` line, exit 2)."""

import itertools
import warnings
from math import comb

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.model.build.terms import MODELS, check_model_size, model_terms, n_model_terms
from rsm_lrg.model.choice.reduce import reduce_terms
from rsm_lrg.model.choice.summary import fit_summary
from rsm_lrg.model.evaluate import evaluate_design


def grid3(y=None, seed=0):
    g = np.array(list(itertools.product([-1.0, 0.0, 1.0], repeat=3)))
    d = pd.DataFrame(g * [1.0, 2.0, 3.0] + [5.0, 6.0, 7.0], columns=["a", "b", "c"])
    d["y"] = np.random.default_rng(seed).normal(size=len(d)) if y is None else y
    return d


def test_constant_response_is_refused():
    d = grid3(3.2)
    for call in (lambda: rsm_lrg.fit(d, "y"), lambda: fit_summary(d, "y"), lambda: reduce_terms(d, "y")):
        with pytest.raises(ValueError, match=r"response 'y' is constant \(all 3.2\): nothing to model"):
            call()
    with pytest.raises(ValueError, match="is constant"):
        rsm_lrg.fit(d.assign(blk=np.arange(len(d)) % 2), "y", factors=["a", "b", "c"], block="blk")


@pytest.mark.parametrize("column,value,match", [
    ("y", 1e300, r"response 'y' holds 1e\+300, beyond the ±1e\+100"),
    ("y", -1e200, r"response 'y' holds 1e\+200"),
    ("a", 1e300, r"factor 'a' reaches 1e\+300"),
    ("b", -np.finfo(float).max, r"factor 'b' reaches 1.8e\+308"),
])
def test_huge_numbers_are_refused(column, value, match):
    d = grid3()
    d.loc[3, column] = value
    with pytest.raises(ValueError, match=match):
        rsm_lrg.fit(d, "y")


def test_tiny_spreads_are_refused():
    d = grid3()
    with pytest.raises(ValueError, match=r"factor 'a' spans only 2e-200"):
        rsm_lrg.fit(d.assign(a=d["a"] * 1e-200), "y")
    with pytest.raises(ValueError, match=r"response 'y' varies only by .*e-30\d, below the 1e-100"):
        rsm_lrg.fit(d.assign(y=d["y"] * 1e-300), "y")
    # small but ordinary numbers are fine: every statistic is finite
    r = rsm_lrg.fit(d.assign(a=d["a"] * 1e-40, y=d["y"] * 1e-60), "y")
    assert np.isfinite(r.statistics.r2) and np.isfinite(list(r.actual_coefficients.values())).all()
    # the extremes accepted still give finite actual-units coefficients for a cubic:
    # factor values near 1e50 with a span near 1e-50 would not, so the factor limits are 1e±50
    with pytest.raises(ValueError, match=r"factor 'c' reaches 1e\+60, beyond the ±1e\+50"):
        rsm_lrg.fit(d.assign(c=d["c"] * 1e59), "y")
    e = d.assign(a=d["a"] * 1e45, b=(d["b"] - 6) * 1e-40, y=d["y"] * 1e90)
    r = rsm_lrg.fit(e, "y")
    assert np.isfinite(list(r.actual_coefficients.values())).all()


def test_term_count_is_combinatorial():
    # C(k+3, 3) monomials of degree <= 3 (cubic), C(k+2, 2) (quadratic), 1 + k + C(k, 2) (2FI)
    for k in range(1, 8):
        for m in MODELS:
            assert n_model_terms(k, m) == len(model_terms([chr(65 + i) for i in range(k)], m))
    assert n_model_terms(16, "cubic") == comb(19, 3) == 969
    assert n_model_terms(3000, "quadratic") == comb(3002, 2)


def test_far_too_large_model_is_refused_by_its_count():
    rng = np.random.default_rng(1)
    d = pd.DataFrame(rng.normal(size=(40, 17)), columns=[f"f{i}" for i in range(16)] + ["y"])
    with pytest.raises(ValueError, match=r"40 runs cannot fit 969 terms \(the cubic model in 16 factors"):
        rsm_lrg.fit(d, "y", model="cubic")
    with pytest.raises(ValueError, match="cannot fit 969 terms"):
        reduce_terms(d, "y", model="cubic")
    with pytest.raises(ValueError, match=r"4504501 terms, beyond the 5000"):
        check_model_size(10 ** 7, 3000, "quadratic")


def test_evaluate_raises_no_numpy_warnings():
    # issue 10 item 11: `evaluate` leaked a NumPy RuntimeWarning; every design and model here,
    # estimable or not, must evaluate without one
    corners = np.array(list(itertools.product([-1.0, 1.0], repeat=3)))
    designs = [np.vstack([corners, corners]), np.vstack([corners, np.zeros((3, 3))]), corners[:4],
               rsm_lrg.box_behnken({"a": (0, 1), "b": (0, 1), "c": (0, 1)}, center=3, randomize=False),
               rsm_lrg.central_composite({"a": (0, 1), "b": (0, 1)}, center=(3, 3), blocks=2, randomize=False),
               # coded settings squeezed into 0.5 +- 1e-8: the VIF's centred cross-products used to
               # come out negative by cancellation ("invalid value encountered in sqrt")
               0.5 + 1e-8 * np.random.default_rng(0).uniform(-1, 1, (11, 3))]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for d in designs:
            for m in MODELS:
                for region in ("cube", "sphere"):
                    evaluate_design(d, m, region=region, n_region=256)


def test_exact_fit_is_flagged():
    # y is exactly a quadratic of the settings: the residual is round-off, and the text says so
    g = np.array(list(itertools.product([-1.0, 0.0, 1.0], repeat=2)))
    d = pd.DataFrame(g, columns=["a", "b"])
    d["y"] = 1 + d.a + 2 * d.b + 0.5 * d.a * d.b + d.a ** 2 - d.b ** 2
    r = rsm_lrg.fit(d, "y")
    assert any("fits the data exactly" in n for n in r.notes)
    assert not any("fits the data exactly" in n for n in rsm_lrg.fit(grid3(), "y").notes)


def test_evaluate_refuses_far_too_large_models_by_their_count():
    # a cubic in 25 factors (3276 terms) on 100 runs used to spend over a minute naming 3176
    # aliased terms; it is refused from the count. A small unestimable model still names its
    # aliased terms (the replicated 2^3 with a cubic: 20 terms, 16 runs).
    X = np.random.default_rng(0).uniform(-1, 1, (100, 25))
    with pytest.raises(ValueError, match=r"100 runs cannot fit 3276 terms \(the cubic model in 25 factors"):
        evaluate_design(X, "cubic")
    corners = np.array(list(itertools.product([-1.0, 1.0], repeat=3)))
    assert "A^3" in evaluate_design(np.vstack([corners, corners]), "cubic").aliased


@pytest.mark.slow
def test_fit_summary_counts_orders_beyond_the_term_limit():
    # 60 factors: the cubic has C(63, 3) = 39711 terms, beyond MAX_TERMS: it is not built,
    # a note says so, and the lower orders are compared as usual
    rng = np.random.default_rng(0)
    d = pd.DataFrame(rng.uniform(-1, 1, (200, 60)), columns=[f"f{i}" for i in range(60)])
    d["y"] = rng.normal(size=200)
    s = fit_summary(d, "y")
    assert list(s.statistics.source) == ["Linear", "2FI", "Quadratic"]
    assert any("39711 terms and was not fitted" in n for n in s.notes)


def test_prediction_far_outside_is_refused_without_overflow():
    r = rsm_lrg.fit(rsm_lrg.load_table4(), "tcr_c_per_min")
    base = {"thickness_m": [2e-4], "stroke_m": [0.04], "velocity_m_s": [0.4], "acceleration_m_s2": [20.0]}
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for v in (1e300, np.finfo(float).max):
            with pytest.raises(ValueError, match=r"prediction point 1: factor 'thickness_m' is more than 1e\+50"):
                r.predict({**base, "thickness_m": [v]}, interval="both")
        assert np.isfinite(r.predict(base, interval="both").to_numpy()).all()
