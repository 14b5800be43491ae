"""Categoric factors beyond the R check: specs, errors, equations, reduction, summary, and
optimisation over levels checked by enumerating the levels by hand on a fine grid."""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.factors import FactorSpace, parse_factor
from rsm_lrg.model.fit import actual_equations

R = Path(__file__).parent / "r"


@pytest.fixture(scope="module")
def ccd():
    return pd.read_csv(R / "cat_ccd2x3.csv")


@pytest.fixture(scope="module")
def res(ccd):
    return rsm_lrg.fit(ccd, "wear_um", factors=["speed_m_s", "load_n", "lubricant"])


def test_specs_give_the_same_fit(ccd, res):
    by_spec = rsm_lrg.fit(ccd, "wear_um", factors=["speed_m_s", "load_n", "lubricant=cat"])
    by_map = rsm_lrg.fit(ccd, "wear_um", factors={"speed_m_s": None, "load_n": None, "lubricant": "categoric"})
    for other in (by_spec, by_map):
        np.testing.assert_allclose(other.coefficients["coded"], res.coefficients["coded"], rtol=1e-13)
    # levels in another order: same predictions, other labels (the last level is the omitted one)
    reord = rsm_lrg.fit(ccd, "wear_um", factors=["speed_m_s", "load_n", "lubricant=cat:grease,mineral,synthetic"])
    assert "C[grease]" in reord.coefficients.index and "C[synthetic]" not in reord.coefficients.index
    np.testing.assert_allclose(reord.fitted, res.fitted, rtol=1e-12)
    assert reord.anova.set_index("source").loc["C", "df"] == 2


def test_numeric_column_made_categoric():
    df = pd.DataFrame({"x": np.tile([-1.0, 0.0, 1.0], 6), "batch": np.repeat([3, 1, 2], 6)})
    df["y"] = 1 + df.x + 0.5 * df.x ** 2 + df.batch.map({3: 0.2, 1: -0.1, 2: 0.4}) + np.linspace(0, 0.01, 18)
    r = rsm_lrg.fit(df, "y", factors=["x", "batch=cat"])
    assert r.space["batch"].levels == ("3", "1", "2")
    assert r.to_dict()["factors"][1]["levels"] == ["3", "1", "2"]
    r2 = rsm_lrg.fit(df, "y", factors=["x", "batch"])  # a numeric name without =cat stays numeric
    assert r2.space["batch"].kind == "numeric"


def test_letters_go_to_numeric_factors_first(ccd):
    r = rsm_lrg.fit(ccd, "wear_um", factors=["lubricant", "speed_m_s", "load_n"])
    assert [(f.letter, f.name) for f in r.space] == [("A", "speed_m_s"), ("B", "load_n"), ("C", "lubricant")]


@pytest.mark.parametrize("spec, message", [
    ("lubricant=cat:mineral,synthetic", "row 23: holds 'grease', not one of the levels"),
    ("lubricant=cat:a,a", "given twice"),
    ("lubricant=cat:a", "two or more"),
])
def test_bad_categoric_specs(ccd, spec, message):
    with pytest.raises(ValueError, match=message):
        rsm_lrg.fit(ccd, "wear_um", factors=["speed_m_s", "load_n", spec])


def test_empty_level_cell_names_the_row(ccd):
    bad = ccd.copy()
    bad.loc[4, "lubricant"] = None
    with pytest.raises(ValueError, match="column 'lubricant', row 5: is empty"):
        rsm_lrg.fit(bad, "wear_um", factors=["speed_m_s", "load_n", "lubricant"])


def test_unknown_level_in_prediction(res):
    with pytest.raises(ValueError, match="holds 'oil', not one of the levels"):
        res.predict(pd.DataFrame({"speed_m_s": [0.5], "load_n": [800], "lubricant": ["oil"]}))


def test_parse_factor():
    assert parse_factor("s=cat:a, b ,c") == ("categoric", "s", ("a", "b", "c"))
    assert FactorSpace.from_specs(["s=cat:a,b", "v=1:2"]).letters == ["A", "B"]
    assert FactorSpace.from_specs(["s=cat:a,b", "v=1:2"]).names == ["v", "s"]


def test_actual_equations_reproduce_predictions(res, ccd):
    # the per-level equation in actual units, evaluated by hand, equals predict()
    pts = pd.DataFrame({"speed_m_s": [0.43, 0.55, 0.6], "load_n": [650.0, 910.0, 1000.0]})
    for setting, eq in actual_equations(res):
        v, w = pts.speed_m_s.to_numpy(), pts.load_n.to_numpy()
        mono = {"Intercept": 1.0, "A": v, "B": w, "AB": v * w, "A^2": v ** 2, "B^2": w ** 2}
        by_hand = sum(c * mono[k] for k, c in eq.items())
        got = res.predict(pts.assign(lubricant=setting["lubricant"]))["predicted"].to_numpy()
        np.testing.assert_allclose(by_hand, got, rtol=1e-10)
    text = res.summary()
    for lv in ("mineral", "synthetic", "grease"):
        assert f"lubricant = {lv}:" in text
    assert "C[mineral]" in text and "levels mineral, synthetic, grease" in text


def test_reduce_removes_a_multi_df_term_whole(res):
    red = res.reduce(alpha_out=0.1)
    # BC (2 df, p = 0.86 in R) leaves as one term; A^2 (p = 0.57) leaves; C stays under AC
    assert "BC" not in red.term_names and "A^2" not in red.term_names
    assert "AC" in red.term_names and "C" in red.term_names
    assert red.anova.set_index("source").loc["AC", "df"] == 2


def test_fit_summary_with_categoric(ccd):
    from rsm_lrg.model.choice.summary import fit_summary

    s = fit_summary(ccd, "wear_um", factors=["speed_m_s", "load_n", "lubricant"])
    seq = s.sequential.set_index("source")
    # linear: A, B and C (2 df); 2FI: AB, AC (2), BC (2); quadratic: A^2, B^2
    assert seq.loc["Linear vs Mean", "df"] == 4 and seq.loc["2FI vs Linear", "df"] == 5
    assert seq.loc["Quadratic vs 2FI", "df"] == 2
    assert s.suggested == "quadratic"


@pytest.mark.parametrize("goal", ["minimize", "maximize", "target=2.5"])
def test_optimum_picks_the_true_best_level(res, goal):
    best = res.optimize(goal)
    # by hand: every level on a 201 x 201 grid of the numeric box
    g = np.linspace(0, 1, 201)
    A, B = np.meshgrid(0.4 + 0.2 * g, 600 + 400 * g)
    score = {}
    for lv in res.space["lubricant"].levels:
        p = res.predict(pd.DataFrame({"speed_m_s": A.ravel(), "load_n": B.ravel(), "lubricant": lv}))["predicted"]
        p = p.to_numpy()
        s = p if goal == "minimize" else -p if goal == "maximize" else np.abs(p - 2.5)
        score[lv] = s.min()
    want = min(score, key=score.get)
    if goal.startswith("target"):
        assert abs(best.predicted - 2.5) < 1e-6
    else:
        assert best.actual["lubricant"] == want
        s_best = best.predicted if goal == "minimize" else -best.predicted
        assert s_best <= score[want] + 1e-9
    assert len(best.by_level) == 3
    assert best.to_dict()["actual"]["lubricant"] in ("mineral", "synthetic", "grease")


def test_bound_holds_a_level(res):
    o = res.optimize("maximize", bounds={"lubricant": "grease", "speed_m_s": (0.45, 0.55)})
    assert o.actual["lubricant"] == "grease" and 0.45 <= o.actual["speed_m_s"] <= 0.55
    assert [r["level"] for r in o.by_level] == [{"lubricant": "grease"}]
    with pytest.raises(ValueError, match="not one of its levels"):
        res.optimize("maximize", bounds=["lubricant=oil"])


def test_confirm_takes_a_level(res):
    from rsm_lrg.optimize.confirm import confirm

    c = confirm(res, {"speed_m_s": 0.5, "load_n": 800, "lubricant": "synthetic"}, [2.9])
    p = res.predict(pd.DataFrame({"speed_m_s": [0.5], "load_n": [800], "lubricant": ["synthetic"]}))
    assert c.predicted == pytest.approx(float(p["predicted"].iloc[0]), rel=1e-12)
    assert c.actual["lubricant"] == "synthetic"


def test_numeric_fit_unchanged_by_the_categoric_code():
    r = rsm_lrg.fit(rsm_lrg.load_table4(), "tcr_c_per_min")
    assert list(r.coefficients.index) == ["Intercept", "A", "B", "C", "D", "AB", "AC", "AD", "BC", "BD", "CD",
                                          "A^2", "B^2", "C^2", "D^2"]
    assert all(f.kind == "numeric" for f in r.space)


def test_generalised_vif_matches_the_correlation_matrix_route():
    # Fox & Monette (1992): GVIF_S = det(R_SS) det(R_OO) / det(R), R the correlation matrix of
    # the model columns without the intercept; computed here directly with NumPy
    df = pd.read_csv(R / "cat_f2x2x3.csv").iloc[:-5]  # unbalanced: drop a few runs
    r = rsm_lrg.fit(df, "y", factors=["x1", "x2", "stage", "material"])
    X = r.design_matrix[:, 1:]
    Rm = np.corrcoef(X, rowvar=False)
    pos = 1
    for t in r.terms[1:]:
        s = list(range(pos - 1, pos - 1 + t.df))
        o = [j for j in range(X.shape[1]) if j not in s]
        want = np.linalg.det(Rm[np.ix_(s, s)]) * np.linalg.det(Rm[np.ix_(o, o)]) / np.linalg.det(Rm)
        np.testing.assert_allclose(r.term_vif[t.name], want, rtol=1e-9, err_msg=t.name)
        if t.df == 1:
            np.testing.assert_allclose(r.coefficients.loc[t.columns[0], "vif"], want, rtol=1e-9)
        pos += t.df
    assert "Generalised VIF" in r.summary() and "term_vif" in r.to_dict()
