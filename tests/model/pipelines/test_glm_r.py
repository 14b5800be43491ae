"""Generalised linear models against R's ``glm`` (issue 35, item 1).

Reference numbers: ``tests/model/r/glm.R`` (R 4.2.2; the script is kept beside its output,
``glm_*_expected.csv``), run on five published data sets none of which was used to tune the
code: ``mtcars`` (binomial 0/1, logit), ``MASS::birthwt`` (binomial 0/1, quadratic; logit,
probit, cloglog), the budworm data of Venables & Ripley (2002, sec. 7.2; successes of 20
trials, numeric x categoric; logit, probit, cloglog), ``warpbreaks`` (poisson, two categoric
factors and their interaction) and ``pscl::bioChemists`` (poisson, quadratic in two numeric
factors, 915 runs). R's glm is run to the maximum-likelihood estimate (epsilon 1e-14).

Tolerance: 1e-8 relative (the issue's bar) on every coefficient, Wald standard error, z and
p; the residual and null deviance, Pearson chi-square, log-likelihood, AIC and BIC; each row
of ``drop1(test = "LRT")`` (our ``anova``) and ``anova(test = "LRT")`` (our
``sequential_anova``); and predictions with their standard errors and 95 % intervals at new
points. A p-value or chi-square near zero is compared with an absolute floor of 1e-12.
"""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from _r_names import ours, source

import rsm_lrg

R = Path(__file__).parents[1] / "r"
RTOL = 1e-8
CASES = {
    "mtcars": ("am", ["hp", "wt"], None, "linear", {"hp": [100, 150, 250], "wt": [2.5, 3.2, 3.6]}),
    "birthwt": ("low", ["age", "lwt"], None, "quadratic", {"age": [18, 25, 35], "lwt": [100, 130, 200]}),
    "budworm": ("numdead", ["ldose", "sex=cat:F,M"], "n", "2fi",
                {"ldose": [1.5, 3, 4.5], "sex": ["F", "M", "F"]}),
    "warpbreaks": ("breaks", ["wool=cat:A,B", "tension=cat:L,M,H"], None, "2fi",
                   {"wool": ["A", "B", "B"], "tension": ["M", "L", "H"]}),
    "biochem": ("art", ["ment", "phd"], None, "quadratic", {"ment": [2, 10, 40], "phd": [1.5, 3, 4.2]}),
}
FITS = sorted({(r.dataset, r.family, r.link) for r in pd.read_csv(R / "glm_coef_expected.csv").itertuples()})


def _fit(name, family, link):
    response, factors, trials, model, _ = CASES[name]
    return rsm_lrg.fit(pd.read_csv(R / f"glm_{name}.csv"), response, factors=factors, model=model, family=family,
                       link=link, trials=trials)


def _expected(kind, name, family, link):
    exp = pd.read_csv(R / f"glm_{kind}_expected.csv")
    return exp[(exp.dataset == name) & (exp.family == family) & (exp.link == link)]


def test_every_family_and_link_is_checked():
    assert {(f, lk) for _, f, lk in FITS} == {("binomial", "logit"), ("binomial", "probit"),
                                              ("binomial", "cloglog"), ("poisson", "log")}
    assert {d for d, _, _ in FITS} == set(CASES)


@pytest.mark.parametrize("name,family,link", FITS)
def test_coefficients_and_wald_errors_match_r(name, family, link):
    res = _fit(name, family, link)
    exp = _expected("coef", name, family, link)
    assert len(exp) == len(res.coefficients)
    for row in exp.itertuples():
        col = ours(row.column, res.space)
        got = res.coefficients.loc[col]
        np.testing.assert_allclose(got["coded"], row.estimate, rtol=RTOL, atol=1e-12, err_msg=col)
        np.testing.assert_allclose(got["std_error"], row.std_error, rtol=RTOL, err_msg=col)
        np.testing.assert_allclose(got["z"], row.z, rtol=RTOL, atol=1e-12, err_msg=col)
        np.testing.assert_allclose(got["p"], row.p, rtol=RTOL, atol=1e-12, err_msg=col)


@pytest.mark.parametrize("name,family,link", FITS)
def test_deviance_and_goodness_of_fit_match_r(name, family, link):
    res = _fit(name, family, link)
    st = res.statistics
    for row in _expected("stats", name, family, link).itertuples():
        np.testing.assert_allclose(st[row.stat], row.value, rtol=RTOL, err_msg=row.stat)
    assert res.to_dict()["deviance"] == pytest.approx(st["deviance"], rel=1e-15)


@pytest.mark.parametrize("name,family,link", FITS)
def test_analysis_of_deviance_matches_r_drop1(name, family, link):
    res = _fit(name, family, link)
    got = res.anova.set_index("source")
    exp = _expected("drop1", name, family, link)
    assert list(got.index) == ["Model"] + [source(s) for s in exp.source]
    for row in exp.itertuples():
        r = got.loc[source(row.source)]
        assert r["df"] == row.df
        np.testing.assert_allclose(r["chi_square"], row.chi_square, rtol=RTOL, atol=1e-12, err_msg=row.source)
        np.testing.assert_allclose(r["p"], row.p, rtol=RTOL, atol=1e-12, err_msg=row.source)
        np.testing.assert_allclose(r["resid_deviance"], row.resid_deviance, rtol=RTOL, err_msg=row.source)
    model = got.loc["Model"]
    assert model["chi_square"] == pytest.approx(res.null_deviance - res.deviance, rel=1e-12)


@pytest.mark.parametrize("name,family,link", FITS)
def test_sequential_analysis_of_deviance_matches_r_anova(name, family, link):
    res = _fit(name, family, link)
    got = res.sequential_anova.set_index("source")
    exp = _expected("anova", name, family, link)
    assert list(got.index) == [source(s) for s in exp.source]
    for row in exp.itertuples():
        r = got.loc[source(row.source)]
        assert (r["df"], r["resid_df"]) == (row.df, row.resid_df)
        np.testing.assert_allclose(r["chi_square"], row.chi_square, rtol=RTOL, atol=1e-12, err_msg=row.source)
        np.testing.assert_allclose(r["p"], row.p, rtol=RTOL, atol=1e-12, err_msg=row.source)
        np.testing.assert_allclose(r["resid_deviance"], row.resid_deviance, rtol=RTOL, err_msg=row.source)


@pytest.mark.parametrize("name,family,link", FITS)
def test_predictions_with_intervals_match_r(name, family, link):
    res = _fit(name, family, link)
    pred = res.predict(pd.DataFrame(CASES[name][4]), interval="confidence")
    exp = _expected("pred", name, family, link).sort_values("row")
    for col, rcol in (("link", "link_fit"), ("se_link", "link_se"), ("predicted", "fit"), ("se_fit", "se_fit"),
                      ("ci_low", "ci_low"), ("ci_high", "ci_high")):
        np.testing.assert_allclose(pred[col].to_numpy(), exp[rcol].to_numpy(), rtol=RTOL, err_msg=col)
