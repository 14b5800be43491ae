"""Response transforms: the fit equals a fit of the transformed column, predictions and
intervals come back in response units, the round trip is exact, bad values name the row."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import rsm_lrg
from rsm_lrg.model.build.transform import parse_transform
from rsm_lrg.model.fit import fit_transformed

PAPER_OPT = {"thickness_m": [0.0001], "stroke_m": [0.04], "velocity_m_s": [0.4], "acceleration_m_s2": [20.0]}


@pytest.mark.parametrize("spec,g", [("log", np.log), ("sqrt", np.sqrt), ("inverse", lambda y: 1 / y),
                                    ("log10", np.log10), ("power=-0.5", lambda y: y ** -0.5)])
def test_fit_equals_fit_of_transformed_column(spec, g):
    df = rsm_lrg.load_table4()
    t = fit_transformed(df, "tcr_c_per_min", spec)
    ref_df = df.copy()
    ref_df["tcr_c_per_min"] = g(ref_df["tcr_c_per_min"])
    ref = rsm_lrg.fit(ref_df, "tcr_c_per_min")
    np.testing.assert_allclose(t.coefficients["coded"], ref.coefficients["coded"], rtol=1e-10)
    p = t.predict(PAPER_OPT, interval="both")
    pr = ref.predict(PAPER_OPT, interval="both")
    np.testing.assert_allclose(g(p["predicted"].to_numpy()), pr["predicted"].to_numpy(), rtol=1e-10)
    # interval ends back-transformed and ordered, bracketing the prediction
    assert (p["pi_low"] <= p["predicted"]).all() and (p["predicted"] <= p["pi_high"]).all()
    assert (p["ci_low"] <= p["predicted"]).all() and (p["predicted"] <= p["ci_high"]).all()
    np.testing.assert_allclose(sorted(g(p[["pi_low", "pi_high"]].to_numpy()[0])),
                               sorted(pr[["pi_low", "pi_high"]].to_numpy()[0]), rtol=1e-10)
    d = t.to_dict()
    assert d["response"] == "tcr_c_per_min" and d["transform"]["name"] in ("log", "sqrt", "inverse", "log10", "power")


def test_power_one_is_no_transform():
    df = rsm_lrg.load_table4()
    t = fit_transformed(df, "tcr_c_per_min", "power=1")
    assert t.transform.name == "none"
    r = rsm_lrg.fit(df, "tcr_c_per_min")
    np.testing.assert_allclose(t.predict(PAPER_OPT)["predicted"], r.predict(PAPER_OPT)["predicted"], rtol=1e-12)


@given(st.sampled_from(["log", "sqrt", "inverse", "log10", "power=0.33", "power=-2", "power=2.5"]),
       st.floats(1e-3, 1e3), st.floats(0, 5))
def test_round_trip(spec, y, k):
    t = parse_transform(spec, constant=k)
    assert float(t.inverse(t.forward(y))) == pytest.approx(y, rel=1e-9, abs=1e-9)


def test_bad_values_and_specs():
    df = rsm_lrg.load_table4()
    df.loc[6, "tcr_c_per_min"] = 0.0
    with pytest.raises(ValueError, match="row 7"):
        fit_transformed(df, "tcr_c_per_min", "log")
    fit_transformed(df, "tcr_c_per_min", "log", constant=0.01)  # a constant makes it valid
    fit_transformed(df, "tcr_c_per_min", "sqrt")  # 0 is allowed for a square root
    for bad in ("cube", "power", "power=x", "power=inf"):
        with pytest.raises(ValueError, match="transform|power"):
            parse_transform(bad)


@pytest.mark.parametrize("constant, label", [(2.0, "log (+2)"), (-0.01, "log (-0.01)"), (0.0, "log")])
def test_label_shows_the_constant_with_its_own_sign(constant, label):
    # the label read 'log (+-0.01)' for a negative constant (exact text)
    from rsm_lrg.model.build.transform import parse_transform

    assert parse_transform("log", constant).label == label
