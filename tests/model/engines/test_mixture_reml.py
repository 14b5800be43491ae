"""Scheffé mixture and mixture-process models with whole plots fitted by REML (issue 35,
item 3): the vinyl split-plot of Kowalski, Cornell & Vining (2002), daewr's ``vinyl`` data,
against R.

Reference numbers: ``tests/model/r/mixture_vinyl.R`` (R 4.2.2, lme4 1.1-31, nlme 3.1-162,
pbkrtest 0.5.2; the script is kept beside its outputs ``mixture_vinyl_*_expected.csv``): 10
whole plots, each one blend of three plasticisers run at the four points of the 2^2 factorial
in extrusion rate and drying temperature. Two models on the L-pseudo components A, B, C (the
observed minima as lower bounds) and the process factors D, E: Kowalski et al.'s
``(A + B + C)(1 + D + E + DE)`` (12 terms) and rsm-lrg's ``mixture-linear`` model crossed with
the process main effects (9 terms). With two random effects, ``mixture_ssp`` (made by
``r/make_mixture_ssp.py``, simulated): 4 days x 3 batches (one blend each) x the 2^2 process
factorial, the quadratic Scheffé model crossed with the process main effects, random days and
batches. Fixed effects, standard errors and variance components to
1e-6 relative (lme4 with bobyqa's rhoend 1e-12; nlme's ``lme`` as a second route, which agrees
with lme4 to about 2e-7), Kenward–Roger den df, F and p to 1e-5 relative to pbkrtest's
``KRmodcomp``: ``Linear Mixture`` is the test of equal linear blending coefficients (the
contrasts A - C, B - C), every other term its own coefficient.
"""

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.errors import ParameterError

R = Path(__file__).parents[1] / "r"
DATA = R / "mixture_vinyl.csv"
MODELS = {"kcv": {"model": "mixture-linear", "terms": "A B C AD AE BD BE CD CE ADE BDE CDE", "whole_plot": "WP"},
          "cross": {"model": "mixture-linear", "whole_plot": "WP"},
          "ssp": {"model": "mixture-quadratic", "random_effects": ["day", "batch"]}}
FILES = {"ssp": R / "mixture_ssp.csv"}
RTOL_EST = 1e-6
RTOL_KR = 1e-5
_FITS: dict = {}


def _fit(name):
    if name not in _FITS:
        _FITS[name] = rsm_lrg.fit(pd.read_csv(FILES.get(name, DATA)), "y", components=["x1", "x2", "x3"],
                                  factors=["z1", "z2"], **MODELS[name])
    return _FITS[name]


@pytest.mark.parametrize("name", list(MODELS))
def test_fixed_effects_and_errors_match_lme4_and_nlme(name):
    res = _fit(name)
    exp = pd.read_csv(R / "mixture_vinyl_coef_expected.csv")
    exp = exp[exp.model == name]
    coef = res.coefficients
    assert sorted(coef.index) == sorted(exp.column)
    exp = exp.set_index("column").loc[coef.index]
    np.testing.assert_allclose(coef.coded, exp.estimate, rtol=RTOL_EST, atol=1e-12)
    np.testing.assert_allclose(coef.std_error, exp.std_error, rtol=RTOL_EST)
    np.testing.assert_allclose(coef.coded, exp.estimate_nlme, rtol=RTOL_EST, atol=1e-12)
    np.testing.assert_allclose(coef.std_error, exp.std_error_nlme, rtol=RTOL_EST)


@pytest.mark.parametrize("name", list(MODELS))
def test_variance_components_match_lme4_and_nlme(name):
    vc = _fit(name).to_dict()["variance_components"]
    exp = pd.read_csv(R / "mixture_vinyl_vc_expected.csv")
    exp = exp[exp.model == name]
    assert set(vc) == set(exp.component)
    for row in exp.itertuples():
        np.testing.assert_allclose(vc[row.component]["variance"], row.variance, rtol=RTOL_EST, err_msg=row.component)
        np.testing.assert_allclose(vc[row.component]["variance"], row.variance_nlme, rtol=RTOL_EST,
                                   err_msg=row.component)


@pytest.mark.parametrize("name", list(MODELS))
def test_kenward_roger_tests_match_pbkrtest(name):
    res = _fit(name)
    exp = pd.read_csv(R / "mixture_vinyl_kr_expected.csv")
    exp = exp[exp.model == name]
    tests = {t["term"]: t for t in res.to_dict()["tests"]}
    assert list(tests)[0] == "Linear Mixture" and sorted(tests) == sorted(exp.term)  # then the non-linear terms
    for row in exp.itertuples():
        t = tests[row.term]
        assert t["num_df"] == row.num_df
        for key, want in (("den_df", row.den_df), ("f", row.f), ("p", row.p)):
            np.testing.assert_allclose(t[key], want, rtol=RTOL_KR, err_msg=f"{row.term} {key}")
    anova = res.anova.set_index("source")
    np.testing.assert_allclose(anova.loc["Linear Mixture", "f"], exp.f.iloc[0], rtol=RTOL_KR)


def test_one_random_effect_is_the_whole_plot_fit():
    """``random_effects=["WP"]`` is the whole-plot fit (its component named as the column)."""
    a = _fit("cross")
    b = rsm_lrg.fit(pd.read_csv(DATA), "y", components=["x1", "x2", "x3"], factors=["z1", "z2"],
                    model="mixture-linear", random_effects=["WP"])
    np.testing.assert_allclose(b.coefficients.std_error, a.coefficients.std_error, rtol=1e-12)
    assert b.to_dict()["variance_components"]["WP"]["variance"] == pytest.approx(
        a.to_dict()["variance_components"]["whole_plot"]["variance"], rel=1e-12)


def test_reduce_of_a_reml_mixture_fit_is_refused():
    with pytest.raises(ParameterError, match="not reduced"):
        rsm_lrg.fit(pd.read_csv(DATA), "y", components=["x1", "x2", "x3"], factors=["z1", "z2"],
                    model="mixture-linear", whole_plot="WP", reduce="backward")


def test_the_blend_is_the_whole_plot_factor_and_ols_differs():
    """The note names the components as constant within every whole plot, and the REML
    standard errors of the blend terms are the larger whole-plot ones (the OLS fit of the same
    model understates them: 0.63 against 1.13 for A)."""
    res = _fit("kcv")
    assert any("whole-plot factors): x1, x2, x3" in n for n in res.notes)
    ols = rsm_lrg.fit(pd.read_csv(DATA), "y", components=["x1", "x2", "x3"], factors=["z1", "z2"],
                      model="mixture-linear", terms=MODELS["kcv"]["terms"])
    assert res.coefficients.std_error["A"] > 1.7 * ols.coefficients.std_error["A"]
    assert res.coefficients.std_error["AD"] < ols.coefficients.std_error["AD"]
    np.testing.assert_allclose(res.coefficients.coded, ols.coefficients.coded, rtol=1e-9, atol=1e-12)  # balanced


def test_prediction_is_a_blend_and_the_interval_adds_the_whole_plot_variance():
    res = _fit("cross")
    out = res.predict(pd.DataFrame({"x1": [0.66], "x2": [0.125], "x3": [0.215], "z1": [1.0], "z2": [-1.0]}),
                      interval="prediction")
    assert out.pi_low.iloc[0] < out.predicted.iloc[0] < out.pi_high.iloc[0]
    with pytest.raises(ValueError, match="sum"):
        res.predict(pd.DataFrame({"x1": [0.9], "x2": [0.125], "x3": [0.215], "z1": [1.0], "z2": [-1.0]}))


def test_hard_to_change_components_checked():
    d = pd.read_csv(DATA)
    rsm_lrg.fit(d, "y", components=["x1", "x2", "x3"], factors=["z1", "z2"], whole_plot="WP",
                hard_to_change=["x1", "x2", "x3"], model="mixture-linear")
    with pytest.raises(ValueError, match="'z1' varies inside whole plot 1"):
        rsm_lrg.fit(d, "y", components=["x1", "x2", "x3"], factors=["z1", "z2"], whole_plot="WP",
                    hard_to_change="z1", model="mixture-linear")


def test_too_few_whole_plots_for_the_blend_terms_is_refused():
    d = pd.read_csv(DATA)
    d = d[d.WP <= 3]  # three whole plots, three blends: no whole-plot error left
    with pytest.raises((ValueError, ParameterError), match="whole plots"):
        rsm_lrg.fit(d, "y", components=["x1", "x2", "x3"], factors=["z1", "z2"], whole_plot="WP",
                    model="mixture-linear")


def test_cli_fit_component_whole_plot_json(tmp_path):
    out = tmp_path / "fit.json"
    cmd = [sys.executable, "-m", "rsm_lrg", "fit", str(DATA), "--response", "y", "--component", "x1",
           "--component", "x2", "--component", "x3", "--factor", "z1", "--factor", "z2", "--model",
           "mixture-linear", "--whole-plot", "WP", "--json", str(out)]
    run = subprocess.run(cmd, capture_output=True, text=True, cwd=Path(__file__).parents[3])
    assert run.returncode == 0, run.stderr
    assert "Linear Mixture" in run.stdout and "Kenward" in run.stdout
    got = json.loads(out.read_text())
    exp = pd.read_csv(R / "mixture_vinyl_vc_expected.csv")
    want = float(exp[(exp.model == "cross") & (exp.component == "whole_plot")].variance.iloc[0])
    np.testing.assert_allclose(got["variance_components"]["whole_plot"]["variance"], want, rtol=RTOL_EST)


def test_refit_from_the_fitted_space():
    """A refit given the fitted mixture space (as the report and ``FitResult.reduce`` pass it)."""
    res = _fit("cross")
    again = rsm_lrg.fit(pd.read_csv(DATA), "y", factors=res.space, model="mixture-linear", whole_plot="WP")
    np.testing.assert_allclose(again.coefficients.coded, res.coefficients.coded, rtol=0, atol=0)
