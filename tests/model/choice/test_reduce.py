"""Backward elimination with hierarchy: the paper's reduction (issue 6), AICc against
statsmodels' log-likelihood, and hypothesis checks of the hierarchy and the stop rule."""

import math

import numpy as np
import pytest
import statsmodels.api as sm
from hypothesis import given, settings
from hypothesis import strategies as st

import rsm_lrg
from rsm_lrg.model.build.terms import design_matrix, model_terms, parse_term
from rsm_lrg.model.choice.reduce import aicc, reduce_terms, removable


def test_table4_alpha_out_01_keeps_the_issue_terms():
    # Issue 6 (Done when): on Table 4 at alpha_out = 0.1 the p-value route keeps A, B, C, D, AC, C², D².
    r = reduce_terms(rsm_lrg.load_table4(), "tcr_c_per_min", alpha_out=0.1, criterion="p")
    assert r.kept == ("Intercept", "A", "B", "C", "D", "AC", "C^2", "D^2")
    assert set(r.removed) == {"AB", "BC", "A^2", "CD", "BD", "B^2", "AD"}
    assert (r.steps["p"] > 0.1).all()
    assert r.to_dict()["kept"][1:] == ["A", "B", "C", "D", "AC", "C^2", "D^2"]


def test_aicc_matches_statsmodels_loglik():
    # Independent route: AICc = -2 llf + 2K + 2K(K+1)/(n-K-1), K = p + 1 (Burnham & Anderson Eq. 2.14).
    df = rsm_lrg.load_table4()
    r = rsm_lrg.fit(df, "tcr_c_per_min")
    ols = sm.OLS(r.y, r.design_matrix).fit()
    n, p = r.design_matrix.shape
    K = p + 1
    ref = -2 * ols.llf + 2 * K + 2 * K * (K + 1) / (n - K - 1)
    assert aicc(ols.ssr, n, p) == pytest.approx(ref, rel=1e-12)


def test_aicc_route_is_hierarchical_and_lowers_aicc():
    r = reduce_terms(rsm_lrg.load_table4(), "tcr_c_per_min", criterion="aicc")
    assert (r.steps["aicc_after"] < r.steps["aicc_before"]).all()
    kept = [parse_term(t, "ABCD") for t in r.kept]
    names = set(r.kept)  # every factor of a kept term is kept
    for t in kept:
        for i, p in enumerate(t.powers):
            if p:
                assert "ABCD"[i] in names


def test_removable_respects_hierarchy():
    assert [t.name for t in removable(model_terms("ABC", "cubic"))] == [
        t.name for t in model_terms("ABC", "cubic") if t.order == 3]
    assert [t.name for t in removable(model_terms("AB", "linear"))] == ["A", "B"]


@settings(max_examples=20, deadline=None)
@given(st.integers(0, 10_000), st.sampled_from([0.05, 0.1, 0.2]))
def test_random_data_hierarchy_and_stop_rule(seed, alpha):
    rng = np.random.default_rng(seed)
    d = rsm_lrg.box_behnken({"a": (0, 1), "b": (0, 1), "c": (0, 1)}, center=3, seed=2).actual
    c = (d.to_numpy() - 0.5) / 0.5
    d["y"] = rng.normal(size=len(d)) + rng.normal() * c[:, 0] + rng.normal() * c[:, 0] * c[:, 1] + rng.normal() * c[:, 2] ** 2
    r = reduce_terms(d, "y", alpha_out=alpha)
    kept = [parse_term(t, "ABC") for t in r.kept]
    # hierarchy: any kept term's every divisor is kept
    keptp = {t.powers for t in kept}
    for t in kept:
        for s in model_terms("ABC", "quadratic"):
            if s.order and s.powers != t.powers and all(a <= b for a, b in zip(s.powers, t.powers)):
                assert s.powers in keptp
    # stop rule, checked by an independent statsmodels refit: every removable term has p <= alpha
    ols = sm.OLS(d.y.to_numpy(), design_matrix(c, kept)).fit()
    for t in removable(kept):
        assert ols.pvalues[kept.index(t)] <= alpha + 1e-12


def test_errors():
    df = rsm_lrg.load_table4()
    with pytest.raises(ValueError, match="criterion"):
        reduce_terms(df, "tcr_c_per_min", criterion="bic")
    with pytest.raises(ValueError, match="alpha_out"):
        reduce_terms(df, "tcr_c_per_min", alpha_out=1.5)
    assert math.isinf(aicc(1.0, 3, 5))


def test_fit_reduce_cli_and_method(capsys):
    import json

    from rsm_lrg.cli import main

    assert main(["fit", "data/table4.csv", "--response", "tcr_c_per_min", "--reduce", "--alpha-out", "0.1",
                 "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    kept = ["Intercept", "A", "B", "C", "D", "AC", "C^2", "D^2"]
    assert list(d["coefficients"]["coded"]) == kept and list(d["coefficients"]["actual"])[:1] == ["Intercept"]
    assert [r["source"] for r in d["anova"]][1:8] == kept[1:]
    assert d["reduction"]["kept"] == kept
    r = rsm_lrg.fit(rsm_lrg.load_table4(), "tcr_c_per_min").reduce(alpha_out=0.1)
    assert r.term_names == kept
    assert main(["fit", "data/table4.csv", "--response", "tcr_c_per_min", "--transform", "log", "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["transform"] == {"name": "log", "lambda": 0.0, "constant": 0.0}
