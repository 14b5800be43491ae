"""Fit summary: sequential SS, lack of fit per order, statistics, suggestion.

References: R rsm output for Lawson's Treb and cement data (see _published.py), the paper's
Table 5 (DIGEST), and an independent route (statsmodels OLS residual sums of squares of the
nested models).
"""

import numpy as np
import pandas as pd
import pytest
import statsmodels.api as sm
from _published import CEMENT1, MONTGOMERY_11_2, TREB, TREB_FACTORS
from hypothesis import given, settings
from hypothesis import strategies as st

import rsm_lrg
from rsm_lrg.model.build.terms import design_matrix, model_terms
from rsm_lrg.model.choice.summary import fit_summary


def _seq(s, label):
    return s.sequential.set_index("source").loc[label]


def test_treb_sequential_ss_matches_r_rsm_anova():
    # R rsm anova(treb.quad): FO 7299.0 (3), TWI 428.8 (3), PQ 351.5 (3); printed to 4
    # significant figures -> tolerance 0.05.
    s = fit_summary(TREB, "y", factors=TREB_FACTORS)
    assert _seq(s, "Linear vs Mean").sum_sq == pytest.approx(7299.0, abs=0.05)
    # R prints 428.8 for the exact 4 (6.25² + 4.75² + 6.75²) = 428.75 (orthogonal BBD columns)
    assert _seq(s, "2FI vs Linear").sum_sq == pytest.approx(428.75, rel=1e-12)
    assert _seq(s, "2FI vs Linear").sum_sq == pytest.approx(428.8, abs=0.05 + 1e-9)
    assert _seq(s, "Quadratic vs 2FI").sum_sq == pytest.approx(351.5, abs=0.05)
    assert [int(_seq(s, k).df) for k in ("Linear vs Mean", "2FI vs Linear", "Quadratic vs 2FI")] == [3, 3, 3]
    # R rsm lack-of-fit of the second-order model: SS 14.5 on 3 df, F 1.6111, p 0.4051312;
    # pure error 6.0 on 2 df (printed digits).
    lof = s.lack_of_fit.set_index("source")
    assert lof.loc["Quadratic", "sum_sq"] == pytest.approx(14.5, abs=0.05)
    assert int(lof.loc["Quadratic", "df"]) == 3
    assert lof.loc["Quadratic", "f"] == pytest.approx(1.6111, abs=5e-5)
    assert lof.loc["Quadratic", "p"] == pytest.approx(0.4051312, abs=5e-7)
    assert lof.loc["Pure Error", "sum_sq"] == pytest.approx(6.0, abs=1e-9) and int(lof.loc["Pure Error", "df"]) == 2
    # R: Multiple R-squared 0.9975, Adjusted 0.9929 for the quadratic
    st_ = s.statistics.set_index("source")
    assert st_.loc["Quadratic", "r2"] == pytest.approx(0.9975, abs=5e-5)
    assert st_.loc["Quadratic", "adj_r2"] == pytest.approx(0.9929, abs=5e-5)
    assert s.suggested == "quadratic"
    assert bool(_seq(s, "Cubic vs Quadratic").aliased)


def test_cement_cube_block_flags_the_squares_aliased():
    # R anova on block 1 of daewr::cement: FO 465.12 (3 df), TWI 0.25 (3 df), PQ 37.88 on
    # 1 df only (aliased squares), Residuals 5.79 (3 df); printed to 2 decimals -> 5e-3.
    s = fit_summary(CEMENT1, "y", orders=("linear", "2fi", "quadratic"))
    assert _seq(s, "Linear vs Mean").sum_sq == pytest.approx(465.12, abs=5e-3)
    assert _seq(s, "2FI vs Linear").sum_sq == pytest.approx(0.25, abs=5e-3)
    q = _seq(s, "Quadratic vs 2FI")
    assert q.sum_sq == pytest.approx(37.88, abs=5e-3) and int(q.df) == 1 and bool(q.aliased)
    res = s.sequential.set_index("source").loc["Residual"]
    assert res.sum_sq == pytest.approx(5.79, abs=5e-3) and int(res.df) == 3
    assert s.suggested == "linear" or s.suggested == "mean"  # the aliased quadratic is never suggested
    assert s.suggested != "quadratic"


def test_paper_table4_quadratic_row_reproduces_table5():
    # Paper Table 5 (DIGEST checked): lack of fit F 10.75, p 0.0880 on (10, 2) df; R² 0.968,
    # pred R² 0.818, PRESS 2.079e-4 (rounded as printed).
    s = fit_summary(rsm_lrg.load_table4(), "tcr_c_per_min")
    lof = s.lack_of_fit.set_index("source").loc["Quadratic"]
    assert lof.f == pytest.approx(10.75, abs=5e-3) and lof.p == pytest.approx(0.0880, abs=5e-5)
    assert int(lof.df) == 10
    st_ = s.statistics.set_index("source").loc["Quadratic"]
    assert st_.r2 == pytest.approx(0.968, abs=5e-4)
    assert st_.pred_r2 == pytest.approx(0.818, abs=5e-4)
    assert st_.press == pytest.approx(2.079e-4, abs=5e-8)
    # independent route within the package: the quadratic statistics equal fit()'s (1e-12)
    r = rsm_lrg.fit(rsm_lrg.load_table4(), "tcr_c_per_min")
    for k in ("r2", "adj_r2", "pred_r2", "press", "std_dev"):
        assert st_[k] == pytest.approx(r.statistics[k], rel=1e-10), k
    assert s.suggested == "quadratic"
    d = s.to_dict()
    assert set(d) == {"response", "n", "block", "sequential", "lack_of_fit", "statistics", "suggested", "alpha", "notes"}


def test_sequential_ss_against_statsmodels_nested_fits():
    # Independent route: SS(order | lower) = ssr(lower) - ssr(order) from statsmodels OLS (1e-9 rel).
    df = MONTGOMERY_11_2
    s = fit_summary(df, "y", factors=["x1=-1:1", "x2=-1:1"], orders=("linear", "2fi", "quadratic"))
    x = df[["x1", "x2"]].to_numpy()
    ssr = {"mean": float(np.sum((df.y - df.y.mean()) ** 2))}
    for m in ("linear", "2fi", "quadratic"):
        ssr[m] = sm.OLS(df.y.to_numpy(), design_matrix(x, model_terms("AB", m))).fit().ssr
    for lab, lo, hi in (("Linear vs Mean", "mean", "linear"), ("2FI vs Linear", "linear", "2fi"),
                        ("Quadratic vs 2FI", "2fi", "quadratic")):
        assert _seq(s, lab).sum_sq == pytest.approx(ssr[lo] - ssr[hi], rel=1e-9)
    assert s.suggested == "quadratic"


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 10_000))
def test_sequential_ss_add_up_to_the_corrected_total(seed):
    rng = np.random.default_rng(seed)
    d = rsm_lrg.box_behnken({"a": (0, 1), "b": (0, 1), "c": (0, 1)}, center=3, seed=1).actual
    d["y"] = rng.normal(size=len(d)) + 3 * d["a"]
    s = fit_summary(d, "y")
    seq = s.sequential.set_index("source")
    parts = seq.drop(index=["Mean vs Total", "Total"])["sum_sq"].sum()
    assert parts == pytest.approx(float(np.sum((d.y - d.y.mean()) ** 2)), rel=1e-9)
    assert seq.loc["Total", "sum_sq"] == pytest.approx(float(d.y @ d.y), rel=1e-12)
    assert s.suggested in ("mean", "linear", "2fi", "quadratic")


def test_blocks_enter_first_and_text_face():
    df = pd.DataFrame({
        "Time": [80, 80, 90, 90, 85, 85, 85, 85, 85, 85, 92.07, 77.93, 85, 85],
        "Temp": [170, 180, 170, 180, 175, 175, 175, 175, 175, 175, 175, 175, 182.07, 167.93],
        "Block": ["B1"] * 7 + ["B2"] * 7,
        "Yield": [80.5, 81.5, 82.0, 83.5, 83.9, 84.3, 84.0, 79.7, 79.8, 79.5, 78.4, 75.6, 78.5, 77.0],
    })
    s = fit_summary(df, "Yield", factors=["Time=80:90", "Temp=170:180"], block="Block")
    assert "Block vs Mean" in set(s.sequential.source)
    # R rsm (vignette, CR2.rsm): lack of fit p ≈ 0.69 for the blocked second-order model
    assert s.lack_of_fit.set_index("source").loc["Quadratic", "p"] == pytest.approx(0.69, abs=0.005)
    text = s.summary()
    assert "Suggested model" in text and "Aliased" in text


def test_bad_alpha_and_orders():
    with pytest.raises(ValueError, match="alpha"):
        fit_summary(TREB, "y", alpha=2)
    with pytest.raises(ValueError, match="orders"):
        fit_summary(TREB, "y", orders=("quartic",))
