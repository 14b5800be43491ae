"""The GLM engine and result (:mod:`rsm_lrg.model.pipelines.glm`, :mod:`rsm_lrg.model.results.glm_result`,
:mod:`rsm_lrg.model.engines.glm_family`): separation, input checks, the result's faces, and identities
that hold whatever the data (agreement with R is in ``test_glm_r.py``)."""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.errors import ParameterError
from rsm_lrg.model.build.spec import SpecError
from rsm_lrg.model.engines.glm_family import FAMILIES, LINKS, family
from rsm_lrg.model.pipelines.glm import SeparationError

R = Path(__file__).parents[1] / "r"


def _budworm():
    return pd.read_csv(R / "glm_budworm.csv")


def _binary(seed=3, n=80):
    rng = np.random.default_rng(seed)
    x1, x2 = rng.uniform(10, 30, n), rng.uniform(0.5, 2.5, n)
    eta = -0.4 + 0.15 * (x1 - 20) - 1.1 * (x2 - 1.5)
    y = (rng.uniform(size=n) < 1 / (1 + np.exp(-eta))).astype(int)
    return pd.DataFrame({"temp": x1, "dose": x2, "ok": y})


# -- separation ---------------------------------------------------------------------------
def test_complete_separation_is_refused_naming_rows():
    df = pd.DataFrame({"x": [1, 2, 3, 4, 5, 6], "y": [0, 0, 0, 1, 1, 1]})
    with pytest.raises(SeparationError, match="completely separated") as exc:
        rsm_lrg.fit(df, "y", factors=["x"], model="linear", family="binomial")
    assert exc.value.complete and exc.value.rows == (1, 2, 3, 4, 5, 6)
    assert "infinite" in str(exc.value) and isinstance(exc.value, ValueError)


def test_quasi_complete_separation_is_refused():
    df = pd.DataFrame({"x": [1, 2, 3, 3, 3, 4], "y": [0, 0, 0, 1, 0, 1]})
    with pytest.raises(SeparationError, match="quasi-completely separated") as exc:
        rsm_lrg.fit(df, "y", factors=["x"], model="linear", family="binomial", link="probit")
    assert not exc.value.complete
    assert set(exc.value.rows) >= {1, 2, 6} and not {3, 4, 5} & set(exc.value.rows)


def test_separation_by_an_interaction_is_found_in_a_factorial():
    # 2^2 factorial, replicated: y = 1 exactly where A and B have the same sign (the AB term separates)
    df = pd.DataFrame({"a": [-1, 1, -1, 1] * 3, "b": [-1, -1, 1, 1] * 3, "y": [1, 0, 0, 1] * 3})
    with pytest.raises(SeparationError, match="AB"):
        rsm_lrg.fit(df, "y", factors=["a", "b"], model="2fi", family="binomial")
    # without the interaction the same runs fit (coefficients zero by symmetry)
    r = rsm_lrg.fit(df, "y", factors=["a", "b"], model="linear", family="binomial")
    assert np.allclose(r.coefficients["coded"], 0.0, atol=1e-12)


def test_separation_of_grouped_binomial_data():
    df = _budworm()
    df.loc[df.ldose <= 2, "numdead"] = 0
    df.loc[df.ldose > 2, "numdead"] = 20
    with pytest.raises(SeparationError):
        rsm_lrg.fit(df, "numdead", factors=["ldose"], model="linear", family="binomial", trials="n")


def test_zero_counts_separated_in_poisson():
    df = pd.DataFrame({"g": ["a"] * 4 + ["b"] * 4, "y": [0, 0, 0, 0, 1, 3, 2, 4]})
    with pytest.raises(SeparationError, match="zero counts") as exc:
        rsm_lrg.fit(df, "y", factors=["g=cat"], model="linear", family="poisson")
    assert exc.value.rows == (1, 2, 3, 4)


def test_no_separation_when_outcomes_overlap():
    r = rsm_lrg.fit(_binary(), "ok", model="quadratic", family="binomial")
    assert np.isfinite(r.coefficients["std_error"]).all()


# -- input checks -------------------------------------------------------------------------
@pytest.mark.parametrize("kwargs,param", [
    ({"family": "gamma"}, "family"), ({"family": "binomial", "link": "log"}, "link"),
    ({"family": "poisson", "link": "logit"}, "link"), ({"family": "binomial", "link": "identity"}, "link"),
    ({"link": "logit"}, "family"), ({"family": "poisson", "trials": "n"}, "trials"),
    ({"family": "binomial", "trials": "nope"}, "trials"), ({"family": "binomial", "trials": "numdead"}, "trials"),
    ({"family": "binomial", "trials": "n", "block": "sex"}, "block"),
    ({"family": "binomial", "trials": "n", "transform": "log"}, "transform"),
    ({"family": "binomial", "trials": "n", "whole_plot": "sex"}, "whole_plot"),
])
def test_bad_options_name_their_parameter(kwargs, param):
    with pytest.raises(ParameterError) as exc:
        rsm_lrg.fit(_budworm(), "numdead", factors=["ldose"], model="linear", **kwargs)
    assert exc.value.parameter == param


def test_trials_column_cannot_be_a_factor():
    with pytest.raises(ParameterError, match="trials column") as exc:
        rsm_lrg.fit(_budworm(), "numdead", factors=["ldose", "n"], model="linear", family="binomial", trials="n")
    assert exc.value.parameter == "trials"


@pytest.mark.parametrize("change,message", [
    (("numdead", 4, 21), r"row 5: 21 is not a count of successes between 0 and the 20 trials"),
    (("numdead", 2, 2.5), r"row 3: 2.5 is not a count of successes"),
    (("n", 1, 0), r"trials column 'n', row 2: 0 is not a whole number of trials"),
    (("n", 1, None), r"trials column 'n', row 2: is empty"),
])
def test_bad_trial_cells_name_the_row(change, message):
    df = _budworm().astype({"numdead": float, "n": float})
    col, i, v = change
    df.loc[i, col] = v
    with pytest.raises(ValueError, match=message):
        rsm_lrg.fit(df, "numdead", factors=["ldose"], model="linear", family="binomial", trials="n")


def test_binary_and_count_responses_are_checked_by_row():
    df = _binary()
    df.loc[6, "ok"] = 2
    with pytest.raises(ValueError, match=r"response 'ok', row 7: 2 is not 0 or 1"):
        rsm_lrg.fit(df, "ok", model="linear", family="binomial")
    df.loc[6, "ok"] = -1
    with pytest.raises(ValueError, match=r"row 7: -1 is not a count"):
        rsm_lrg.fit(df, "ok", model="linear", family="poisson")


def test_empty_response_rows_are_left_out_and_noted():
    df = _binary()
    df["ok"] = df["ok"].astype(float)
    df.loc[[4, 9], "ok"] = np.nan
    r = rsm_lrg.fit(df, "ok", factors=["temp=10:30", "dose=0.5:2.5"], model="linear", family="binomial")
    assert r.omitted_rows == (5, 10) and any("rows 5, 10" in n for n in r.notes)
    # same data, same coding (given levels) -> same fit
    full = rsm_lrg.fit(df.dropna().reset_index(drop=True), "ok", factors=["temp=10:30", "dose=0.5:2.5"],
                       model="linear", family="binomial")
    np.testing.assert_allclose(r.params, full.params, rtol=1e-13)


# -- identities -----------------------------------------------------------------------------
@pytest.mark.parametrize("link", FAMILIES["binomial"])
def test_grouped_fit_equals_the_fit_of_its_single_runs(link):
    df = _budworm()
    grouped = rsm_lrg.fit(df, "numdead", factors=["ldose", "sex=cat:F,M"], model="2fi", family="binomial",
                          link=link, trials="n")
    rows = []
    for r in df.itertuples():
        rows += [{"ldose": r.ldose, "sex": r.sex, "dead": 1}] * r.numdead
        rows += [{"ldose": r.ldose, "sex": r.sex, "dead": 0}] * (r.n - r.numdead)
    single = rsm_lrg.fit(pd.DataFrame(rows), "dead", factors=["ldose", "sex=cat:F,M"], model="2fi",
                         family="binomial", link=link)
    np.testing.assert_allclose(single.params, grouped.params, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(single.coefficients["std_error"], grouped.coefficients["std_error"], rtol=1e-9)
    # likelihood-ratio tests are differences of deviances: the same for both layouts
    np.testing.assert_allclose(single.anova["chi_square"], grouped.anova["chi_square"], rtol=1e-8)


def test_linear_predictor_in_actual_units_equals_coded():
    r = rsm_lrg.fit(_binary(), "ok", model="quadratic", family="binomial", link="probit")
    pts = pd.DataFrame({"temp": [12.0, 20.0, 27.5], "dose": [0.7, 1.9, 2.2]})
    a = r.actual_coefficients
    t, d = pts.temp.to_numpy(), pts.dose.to_numpy()
    eta = (a["Intercept"] + a["A"] * t + a["B"] * d + a["AB"] * t * d + a["A^2"] * t ** 2 + a["B^2"] * d ** 2)
    np.testing.assert_allclose(eta, r.predict(pts)["link"].to_numpy(), rtol=1e-10)


def test_predictions_are_on_the_response_scale_with_link_scale_intervals():
    r = rsm_lrg.fit(_binary(), "ok", model="linear", family="binomial")
    pts = pd.DataFrame({"temp": [10.0, 20.0, 30.0], "dose": [2.5, 1.5, 0.5]})
    p = r.predict(pts, interval="both", alpha=0.1)
    assert list(p.columns[:4]) == ["predicted", "se_fit", "link", "se_link"]
    assert ((p.ci_low > 0) & (p.ci_low < p.predicted) & (p.predicted < p.ci_high) & (p.ci_high < 1)).all()
    z = 1.6448536269514722  # the 95 % normal quantile (alpha 0.1, two-sided)
    np.testing.assert_allclose(p.ci_high, 1 / (1 + np.exp(-(p.link + z * p.se_link))), rtol=1e-12)
    assert p.pi_low.isna().all() and p.pi_high.isna().all()
    assert any("No prediction interval" in n for n in r.notes)
    np.testing.assert_allclose(r.predict(pts)["predicted"], r.predict_coded(r.coded_points(pts)), rtol=1e-14)
    with pytest.raises(ParameterError):
        r.predict(pts, alpha=1.5)
    with pytest.raises(ValueError, match="interval must be"):
        r.predict(pts, interval="tolerance")


def test_poisson_mean_and_rate_scale():
    rng = np.random.default_rng(8)
    x = rng.uniform(0, 4, 60)
    y = rng.poisson(np.exp(0.5 + 0.4 * x))
    r = rsm_lrg.fit(pd.DataFrame({"x": x, "cfu": y}), "cfu", model="linear", family="poisson")
    # the log link's score equations: fitted counts sum to the observed total
    assert r.fitted.sum() == pytest.approx(y.sum(), rel=1e-12)
    p = r.predict({"x": [0.0, 4.0]}, interval="confidence")
    assert (p.predicted > 0).all() and (p.ci_low > 0).all()
    np.testing.assert_allclose(p.se_fit, p.predicted * p.se_link, rtol=1e-12)  # delta method, log link


def test_to_dict_has_the_keys_of_every_fit_and_the_glm_ones():
    import json

    r = rsm_lrg.fit(_budworm(), "numdead", factors=["ldose", "sex=cat:F,M"], model="2fi", family="binomial",
                    trials="n")
    d = json.loads(json.dumps(r.to_dict()))
    assert set(d["coefficients"]["coded"]) == {"Intercept", "A", "B[F]", "AB[F]"}
    assert set(d["std_errors"]["coded"]) == set(d["coefficients"]["coded"])
    assert set(d["coefficients"]["actual"]) == set(d["std_errors"]["actual"])
    assert d["deviance"] == pytest.approx(r.deviance) and d["family"] == "binomial" and d["link"] == "logit"
    assert [row["source"] for row in d["anova"]] == ["Model", "A", "B", "AB"]
    assert all({"source", "df", "chi_square", "p"} <= set(row) for row in d["anova"])
    assert d["trials"] == "n" and d["statistics"]["aicc"] > d["statistics"]["aic"]
    assert "Analysis of deviance" in r.summary() and "B[F]" in r.summary()


def test_family_objects():
    assert set(LINKS) == {lk for links in FAMILIES.values() for lk in links}
    for name, links in FAMILIES.items():
        for lk in links:
            f = family(name, lk)
            mu = np.array([0.05, 0.3, 0.5, 0.9]) if name == "binomial" else np.array([0.2, 3.0, 40.0])
            np.testing.assert_allclose(f.linkinv(f.linkfun(mu)), mu, rtol=1e-13)
            eta = f.linkfun(mu)
            h = 1e-6
            np.testing.assert_allclose(f.mu_eta(eta), (f.linkinv(eta + h) - f.linkinv(eta - h)) / (2 * h), rtol=1e-6)


def test_cli_choices_agree_with_the_families():
    from rsm_lrg.cli.glm_fit import FAMILY_NAMES, LINK_NAMES

    assert FAMILY_NAMES == tuple(FAMILIES) and LINK_NAMES == LINKS


def test_spec_errors_are_spec_errors():
    with pytest.raises(SpecError):
        rsm_lrg.fit(_budworm(), "numdead", factors=["ldose"], terms="A Z", family="binomial", trials="n")


def test_no_intercept_model_equals_r():
    # R 4.2.2: d <- read.csv("tests/model/r/glm_birthwt.csv"); X <- data.frame(A = d$age / 45, B = d$lwt / 250,
    # low = d$low) (a model without an intercept codes x / max|x|); m <- glm(low ~ 0 + A + B + I(A^2),
    # binomial("probit"), X), restarted from its own estimate as in glm.R; summary(m), deviance,
    # null.deviance, drop1(m, test = "LRT"), anova(m, test = "LRT"), printed to 11-13 digits
    r = rsm_lrg.fit(pd.read_csv(R / "glm_birthwt.csv"), "low", factors=["age", "lwt"], terms="A B A^2",
                    intercept=False, family="binomial", link="probit")
    np.testing.assert_allclose(r.params, [3.103324887590, -1.933847695403, -3.967389270055], rtol=1e-10)
    np.testing.assert_allclose(r.coefficients["std_error"], [1.7822659076947, 0.8722560692351, 2.0388448758620],
                               rtol=1e-10)
    assert (r.deviance, r.null_deviance) == (pytest.approx(226.1320473861, rel=1e-11),
                                             pytest.approx(262.0096342517, rel=1e-11))
    np.testing.assert_allclose(r.anova["chi_square"][1:], [3.2386253822, 5.3289300564, 4.1504734500], rtol=1e-9)
    np.testing.assert_allclose(r.sequential_anova["chi_square"], [29.8794738237, 1.8476395919, 4.1504734500],
                               rtol=1e-9)


def test_top_level_names():
    assert rsm_lrg.GLMResult.__name__ == "GLMResult" and issubclass(rsm_lrg.SeparationError, ValueError)
    assert isinstance(rsm_lrg.fit(_budworm(), "numdead", factors=["ldose"], model="linear", family="binomial",
                                  trials="n"), rsm_lrg.GLMResult)


def test_to_frame_per_run():
    r = rsm_lrg.fit(_budworm(), "numdead", factors=["ldose", "sex=cat:F,M"], model="2fi", family="binomial",
                    trials="n")
    f = r.to_frame()
    assert len(f) == 12 and {"fitted", "deviance_residual", "pearson_residual", "leverage"} <= set(f.columns)
    assert (f.deviance_residual ** 2).sum() == pytest.approx(r.deviance, rel=1e-12)
    assert (f.pearson_residual ** 2).sum() == pytest.approx(r.statistics["pearson_chi2"], rel=1e-12)
    assert f.leverage.sum() == pytest.approx(r.n_params, rel=1e-10)  # the trace of the weighted hat matrix
    np.testing.assert_allclose(f.fitted, r.predict(_budworm())["predicted"], rtol=1e-12)
