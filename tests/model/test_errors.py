"""Bad input gives a ValueError with a sentence naming the column, row or terms."""

import numpy as np
import pandas as pd
import pytest

import rsm_lrg


def table4():
    return rsm_lrg.load_table4()


def test_too_few_runs():
    df = table4().iloc[:10]
    with pytest.raises(ValueError, match="10 runs cannot fit 15 terms"):
        rsm_lrg.fit(df, "tcr_c_per_min")


def test_aliased_terms_are_named():
    df = table4().copy()
    df["dup"] = df["stroke_m"] * 2.0  # a factor identical (coded) to stroke
    with pytest.raises(ValueError, match=r"term\(s\) E are aliased"):
        rsm_lrg.fit(df, "tcr_c_per_min", factors=["thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2", "dup"], model="linear")


def test_constant_factor():
    df = table4().copy()
    df["const"] = 1.0
    # inferred factors: a constant column is left out and said (issue 36); named, it is refused
    res = rsm_lrg.fit(df, "tcr_c_per_min")
    assert "const" not in res.space.names and any("'const' (1 on every row)" in str(n) for n in res.input_notes)
    with pytest.raises(ValueError, match="'const' is constant"):
        rsm_lrg.fit(df, "tcr_c_per_min", factors=["thickness_m", "const=0:2"], model="linear")


def test_text_and_inf_name_the_row():
    df = table4().astype({"velocity_m_s": object})
    df.loc[4, "velocity_m_s"] = "fast"
    with pytest.raises(ValueError, match=r"'velocity_m_s', row 5"):
        rsm_lrg.fit(df, "tcr_c_per_min", factors=["thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2"])
    df = table4()
    df.loc[2, "tcr_c_per_min"] = np.inf
    with pytest.raises(ValueError, match=r"'tcr_c_per_min', row 3"):
        rsm_lrg.fit(df, "tcr_c_per_min")


def test_unknown_columns_and_model():
    with pytest.raises(ValueError, match="response column 'nope'"):
        rsm_lrg.fit(table4(), "nope")
    with pytest.raises(ValueError, match="'nope' is not in the data"):
        rsm_lrg.fit(table4(), "tcr_c_per_min", factors=["nope"])
    with pytest.raises(ValueError, match="unknown model"):
        rsm_lrg.fit(table4(), "tcr_c_per_min", model="quartic")
    with pytest.raises(ValueError, match="single level"):
        rsm_lrg.fit(table4().assign(b=1), "tcr_c_per_min", block="b")


def test_no_replicates_says_why():
    df = table4().drop_duplicates(subset=["thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2"])
    r = rsm_lrg.fit(df, "tcr_c_per_min")
    assert "Lack of Fit" not in set(r.anova.source) and "Pure Error" not in set(r.anova.source)
    assert "no factor setting is replicated" in r.summary()


def test_linear_model_has_null_stationary_point():
    r = rsm_lrg.fit(table4(), "tcr_c_per_min", model="linear")
    sp = r.to_dict()["stationary_point"]
    assert sp["coded"] is None and sp["actual"] is None and sp["eigenvalues"] is None and sp["kind"] is None
    assert list(r.coefficients.index) == ["Intercept", "A", "B", "C", "D"]
    r2 = rsm_lrg.fit(table4(), "tcr_c_per_min", model="2fi")
    assert len(r2.coefficients) == 11


def test_input_frame_not_modified():
    df = table4()
    before = df.copy()
    rsm_lrg.fit(df, "tcr_c_per_min")
    pd.testing.assert_frame_equal(df, before)


def test_result_is_frozen():
    import dataclasses

    r = rsm_lrg.fit(table4(), "tcr_c_per_min")
    with pytest.raises(dataclasses.FrozenInstanceError):
        r.model = "linear"


def _frame(kind):
    import pandas as pd

    d = table4().copy()
    if kind == "object-with-a-numeric-string":
        d["stroke_m"] = d["stroke_m"].astype(object)
        d.loc[3, "stroke_m"] = str(d.loc[3, "stroke_m"])
    elif kind == "categorical-of-numbers":
        d["stroke_m"] = pd.Categorical(d["stroke_m"])
    elif kind == "response-true":
        d["tcr_c_per_min"] = d["tcr_c_per_min"].astype(object)
        d.loc[2, "tcr_c_per_min"] = True
    elif kind == "complex-factor":
        d["stroke_m"] = d["stroke_m"].astype(complex)
    elif kind == "duplicate-factor-name":
        d.columns = ["order", "thickness_m", "thickness_m", "velocity_m_s", "acceleration_m_s2", "tcr_c_per_min"]
    elif kind == "duplicate-response-name":
        d.columns = ["order", "thickness_m", "tcr_c_per_min", "velocity_m_s", "acceleration_m_s2", "tcr_c_per_min"]
    elif kind == "nfc-alike-names":
        d = d.assign(**{"caf\u00e9": 1.0 + d.index % 2, "cafe\u0301": 2.0 + d.index % 3})
    elif kind == "empty":
        d = d.iloc[0:0]
    return d


@pytest.mark.parametrize(("kind", "words"), [
    ("object-with-a-numeric-string", ["'stroke_m'", "row 4", "Python objects"]),
    ("categorical-of-numbers", ["'stroke_m'", "Categorical"]),
    ("response-true", ["'tcr_c_per_min', row 3", "truth value"]),
    ("complex-factor", ["'stroke_m'", "complex"]),
    ("duplicate-factor-name", ["'thickness_m'", "more than once"]),
    ("duplicate-response-name", ["'tcr_c_per_min'", "more than once"]),
    ("nfc-alike-names", ["caf", "Unicode NFC"]),
    ("empty", ["no rows"]),
])
def test_the_pandas_api_refuses_what_it_once_dropped_or_guessed(kind, words):
    # issue 36: each of these fitted silently without a factor, fitted True as 1, dropped an
    # imaginary part, or ended in AttributeError / "constant (nan)"; now a ValueError naming it
    from rsm_lrg.model.choice.summary import fit_summary

    for call in (lambda d: rsm_lrg.fit(d, "tcr_c_per_min"), lambda d: fit_summary(d, "tcr_c_per_min")):
        with pytest.raises(ValueError) as info:
            call(_frame(kind))
        for w in words:
            assert w in str(info.value), (kind, str(info.value))


def test_a_whole_plot_column_of_lists_is_refused_by_row():
    d = table4().copy()
    d["wp"] = [[i % 3] for i in range(len(d))]
    with pytest.raises(ValueError, match=r"column 'wp', row 1: holds a list, not a label"):
        rsm_lrg.fit(d, "tcr_c_per_min", whole_plot="wp")
