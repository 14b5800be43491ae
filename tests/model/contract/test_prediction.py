"""The prediction contract (rsm_lrg.model.contract.prediction): every kind of fit satisfies
``FittedModel``, and its ``IntervalForm`` gives what ``predict`` gives."""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.model.contract import statistics
from rsm_lrg.model.contract.prediction import FittedModel, IntervalForm
from rsm_lrg.terms import design_matrix

R = Path(__file__).parents[1] / "r"
T4 = ["thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2"]


def _fits():
    t4 = rsm_lrg.load_table4()
    return {
        "ols": rsm_lrg.fit(t4, "tcr_c_per_min", factors=T4),
        "log": rsm_lrg.fit(t4, "tcr_c_per_min", factors=T4, transform="log"),
        "mixture": rsm_lrg.fit(pd.read_csv(R / "mixture_etch_l.csv"), "erate", components=["x1", "x2", "x3"],
                               model="special-cubic"),
        "whole_plot": rsm_lrg.fit(pd.read_csv(R / "mixed_sp_bal.csv"), "wear_um",
                                  factors=["temp_c", "preload_kn", "speed_m_s", "lube_ml"], whole_plot="whole_plot"),
        "random_block": rsm_lrg.fit(pd.read_csv(R / "mixed_pastry.csv"), "y", factors=["x1", "x2", "x3"],
                                    random_block="Block"),
    }


@pytest.fixture(scope="module")
def fits():
    return _fits()


@pytest.mark.parametrize("kind", ["ols", "log", "mixture", "whole_plot", "random_block"])
def test_every_kind_satisfies_the_contract(fits, kind):
    fit = fits[kind]
    assert isinstance(fit, FittedModel)
    assert isinstance(fit.interval_form, IntervalForm)


def test_ols_form_is_c_sigma2_and_n_minus_p(fits):
    fit = fits["ols"]
    form = fit.interval_form
    C = fit.cov_unscaled[np.ix_(fit.term_index, fit.term_index)] * fit.sigma2
    np.testing.assert_array_equal(form.cov_mean, C)
    assert form.s2_new == fit.sigma2 and form.s2_group == 0.0 and form.df == fit.df_resid
    assert not form.kenward_roger and "kr" not in form.to_dict()


@pytest.mark.parametrize("kind", ["whole_plot", "random_block"])
def test_kenward_roger_df_per_point_equals_the_one_df_test(fits, kind):
    """The df of the form (2 / A2 from quadratic forms) equal the one-df Kenward–Roger test of
    the contrast x b (pbkrtest's trace route, rsm_lrg.model.engines.mixed.kr_test) at random points."""
    fit = fits[kind]
    x = np.random.default_rng(3).uniform(-1, 1, (8, len(fit.space)))
    X = design_matrix(x, fit.terms)
    se, var_mean, var_new, df = fit.interval_form.at(X)
    for i in range(len(X)):
        _, df_test, _, q = fit.mixed.test(X[i][None, :])
        assert q == 1
        assert df[i] == pytest.approx(df_test, rel=1e-10)
    mm = fit.mixed
    np.testing.assert_allclose(var_mean, np.einsum("ij,jk,ik->i", X, mm.cov_adjusted, X), rtol=1e-12)
    np.testing.assert_allclose(var_new - var_mean, mm.sigma2_group + mm.sigma2, rtol=1e-12)
    np.testing.assert_allclose(se ** 2, np.einsum("ij,jk,ik->i", X, mm.cov, X), rtol=1e-12)
    out = fit.predict(x, coded=True, interval="both", alpha=0.1)
    t = statistics.stdtrit(df, 0.95)
    np.testing.assert_allclose(out["pi_high"] - out["predicted"], t * np.sqrt(var_new), rtol=1e-12)


def test_confirmation_interval_of_n_runs(fits):
    """The mean of n new runs: var_mean + s2_group + s2 / n (OLS: s2_group = 0)."""
    for kind in ("ols", "whole_plot"):
        form = fits[kind].interval_form
        X = design_matrix(np.zeros((1, len(fits[kind].space))), fits[kind].terms)
        var, df = form.mean_of_new_runs(X, 3)
        _, vm, _, df1 = form.at(X)
        assert var[0] == pytest.approx(vm[0] + form.s2_group + form.s2_residual / 3, rel=1e-14)
        assert df[0] == df1[0]
