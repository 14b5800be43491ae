"""The mixture fit summary (``fit_summary(..., components=...)``) against R's ``lm``/``anova``.

Nested Scheffé models mean ⊂ linear ⊂ quadratic ⊂ special cubic ⊂ full cubic on the plasma
etch data (Myers & Montgomery, *Response Surface Methodology*, Table 12.4; replicated blends,
the full cubic aliased) and daewr's ``pest`` (13 unreplicated blends); ``r/mixture_fit_summary.R``
fits each with ``lm(y ~ -1 + ...)``, takes every sequential row from ``anova(previous, this)``
("Linear vs Mean" from ``anova(lm(y ~ 1), linear)``), lack of fit from the pure error of one mean
per blend, and writes ``r/mixture_fit_summary_expected.csv``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.model.choice.summary import fit_summary

HERE = Path(__file__).parents[1] / "r"
RTOL = 1e-9
SETS = {"etch": ("mixture_etch.csv", "erate"), "pest": ("mixture_pest.csv", "y")}
LABEL = {"mixture-linear": "Linear", "mixture-quadratic": "Quadratic", "special-cubic": "Special Cubic",
         "mixture-cubic": "Cubic"}
PREV = {"mixture-linear": "Mean", "mixture-quadratic": "Linear", "special-cubic": "Quadratic",
        "mixture-cubic": "Special Cubic"}


def _expected(set_name: str) -> dict:
    e = pd.read_csv(HERE / "mixture_fit_summary_expected.csv")
    e = e[e["set"] == set_name]
    return {(r.model, r.quantity): float(r.value) for r in e.itertuples(index=False)}


def _summary(set_name: str):
    path, y = SETS[set_name]
    return fit_summary(pd.read_csv(HERE / path), y, components=["x1", "x2", "x3"])


@pytest.mark.parametrize("set_name", sorted(SETS))
def test_sequential_ss_and_statistics_match_r(set_name):
    exp = _expected(set_name)
    s = _summary(set_name)
    seq = s.sequential.set_index("source")
    st = s.statistics.set_index("source")
    assert seq.loc["Mean vs Total", "sum_sq"] == pytest.approx(exp[("mean", "ss")], rel=RTOL)
    for model, label in LABEL.items():
        row = seq.loc[f"{label} vs {PREV[model]}"]
        assert row["sum_sq"] == pytest.approx(exp[(model, "seq_ss")], rel=RTOL)
        assert row["df"] == exp[(model, "seq_df")]
        assert row["f"] == pytest.approx(exp[(model, "seq_f")], rel=RTOL)
        assert row["p"] == pytest.approx(exp[(model, "seq_p")], rel=RTOL)
        for q in ("std_dev", "r2", "adj_r2", "pred_r2", "press"):
            assert st.loc[label, q] == pytest.approx(exp[(model, q)], rel=RTOL), (model, q)
    # the rows add up: Mean + sequential rows + Residual = Total (uncorrected)
    assert seq["sum_sq"].iloc[:-1].sum() == pytest.approx(seq.loc["Total", "sum_sq"], rel=1e-12)


def test_etch_lack_of_fit_and_suggestion():
    exp = _expected("etch")
    s = _summary("etch")
    lof = s.lack_of_fit.set_index("source")
    for model, label in LABEL.items():
        for q, col in (("lof_ss", "sum_sq"), ("lof_df", "df"), ("lof_f", "f"), ("lof_p", "p")):
            assert lof.loc[label, col] == pytest.approx(exp[(model, q)], rel=RTOL), (model, q)
    assert lof.loc["Pure Error", "sum_sq"] == pytest.approx(exp[("pure error", "ss")], rel=RTOL)
    # the 14 runs estimate only 2 of the 3 full-cubic delta terms (R: one NA coefficient)
    assert s.sequential.set_index("source").loc["Cubic vs Special Cubic", "aliased"]
    # special cubic: significant (p 2.4e-5), lack of fit not (p 0.14); the cubic is aliased
    assert s.suggested == "special-cubic"
    assert "Suggested model: Special Cubic" in s.summary()
    # the suggested model is what fit() fits under that name: same R²
    f = rsm_lrg.fit(pd.read_csv(HERE / "mixture_etch.csv"), "erate", components=["x1", "x2", "x3"],
                    model=s.suggested)
    assert f.statistics.r2 == pytest.approx(s.statistics.set_index("source").loc["Special Cubic", "r2"], rel=1e-12)


def test_pest_suggests_quadratic_without_pure_error():
    s = _summary("pest")
    assert s.suggested == "mixture-quadratic"  # special cubic p = 0.87
    assert len(s.lack_of_fit) == 0 and any("pure error" in n for n in s.notes)


def test_too_few_blends_stop_the_sequence_and_transform_applies():
    d = pd.read_csv(HERE / "mixture_etch.csv")
    blends = d.drop_duplicates(["x1", "x2", "x3"])
    assert len(blends) == 10  # the full cubic's 10 terms are counted estimable (one is aliased)
    s = fit_summary(d, "erate", components=["x1", "x2", "x3"])
    assert list(s.statistics["source"]) == ["Linear", "Quadratic", "Special Cubic", "Cubic"]
    small = blends.iloc[:6]  # the vertices and edge midpoints: the special cubic's 7 terms do not fit
    assert small[["x1", "x2", "x3"]].max(axis=1).min() == 0.5
    s6 = fit_summary(small, "erate", components=["x1", "x2", "x3"])
    assert list(s6.statistics["source"]) == ["Linear", "Quadratic"]
    assert any("not fitted" in n for n in s6.notes)
    lg = fit_summary(d, "erate", components=["x1", "x2", "x3"], transform="log")
    d2 = d.assign(erate=np.log(d["erate"]))
    ref = fit_summary(d2, "erate", components=["x1", "x2", "x3"])
    np.testing.assert_allclose(lg.sequential["sum_sq"], ref.sequential["sum_sq"], rtol=1e-12)


def test_bad_requests_are_refused():
    d = pd.read_csv(HERE / "mixture_etch.csv")
    with pytest.raises(ValueError, match="orders must be among"):
        fit_summary(d, "erate", components=["x1", "x2", "x3"], orders=("quadratic",))
    with pytest.raises(ValueError, match="mixture-linear"):
        fit_summary(d, "erate", components=["x1", "x2", "x3"], orders=("mixture-quadratic",))
    with pytest.raises(ValueError, match="block"):
        fit_summary(d.assign(b=1), "erate", components=["x1", "x2", "x3"], block="b")


def test_process_factors_each_model_is_the_fit_of_that_name():
    # Cornell's fish patties (mixexp fishp): 7 blends x 2^3 process settings. Every model of the
    # summary (each Scheffé model crossed with the process main effects) is the model fit() fits
    # under that name (fit() itself checked against R in test_mixture_fit.py).
    d = pd.read_csv(HERE / "mixture_fishp.csv")
    comps, proc = ["x1", "x2", "x3"], ["z1", "z2", "z3"]
    s = fit_summary(d, "y", components=comps, factors=proc)
    st = s.statistics.set_index("source")
    for model in ("mixture-linear", "mixture-quadratic", "special-cubic"):
        f = rsm_lrg.fit(d, "y", components=comps, factors=proc, model=model)
        for q in ("std_dev", "r2", "adj_r2", "pred_r2", "press"):
            assert st.loc[LABEL[model], q] == pytest.approx(getattr(f.statistics, q), rel=1e-9), (model, q)
    seq = s.sequential.set_index("source")
    assert seq.loc["Linear vs Mean", "df"] == 11 and seq.loc["Quadratic vs Linear", "df"] == 12
    # 7 blends cannot estimate the full cubic's delta terms: the cubic adds nothing, flagged aliased
    assert seq.loc["Cubic vs Special Cubic", "df"] == 0 and seq.loc["Cubic vs Special Cubic", "aliased"]
    assert s.suggested == "mixture-quadratic"
