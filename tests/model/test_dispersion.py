"""The ln s (dispersion) model against R: ``r/dispersion.R`` fits ``lm(log(s) ~ ...)`` on the
table of replicated settings of ``r/dispersion_cure.csv`` (a data set made for this test, see
the script's header) and stores ``r/dispersion_expected.csv``; coefficients, standard errors,
partial sums of squares and R² must agree to 1e-10. The unreplicated settings are left out
and named."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.errors import ParameterError

fit_dispersion = rsm_lrg.fit_dispersion

R = Path(__file__).parent / "r"
DATA = pd.read_csv(R / "dispersion_cure.csv")
EXPECTED = pd.read_csv(R / "dispersion_expected.csv")
FACTORS = ["temp_c", "time_min"]


@pytest.mark.parametrize("model", ["linear", "2fi"])
def test_ln_s_model_equals_r_lm_on_the_settings(model):
    disp = fit_dispersion(DATA, "yield_pct", factors=FACTORS, model=model)
    exp = EXPECTED[EXPECTED.model == model]

    def want(what):
        e = exp[exp.what == what]
        return dict(zip(e.name, e.value))

    coef = disp.result.coefficients["coded"]
    for name, v in want("coef").items():
        assert coef[name] == pytest.approx(v, rel=1e-10, abs=1e-12), name
    se = disp.to_dict()["std_errors"]["coded"]
    for name, v in want("se").items():
        assert se[name] == pytest.approx(v, rel=1e-10), name
    anova = {r["source"]: r["sum_sq"] for r in disp.to_dict()["anova"]}
    for name, v in want("ss").items():
        assert anova["Residual" if name == "Residuals" else name] == pytest.approx(v, rel=1e-10), name
    assert disp.to_dict()["r2"] == pytest.approx(want("r2")["r2"], rel=1e-12)
    assert disp.to_dict()["settings_used"] == int(want("n")["settings"]) == 8


def test_unreplicated_settings_are_named_and_s_is_the_replicates_sd():
    disp = fit_dispersion(DATA, "yield_pct", factors=FACTORS)
    left = sorted((s["temp_c"], s["time_min"], s["runs"], s["reason"]) for s in disp.left_out)
    assert left == [(165, 25, 1, "unreplicated"), (190, 30, 1, "unreplicated")]
    at = disp.settings.set_index(["temp_c", "time_min"])
    ys = DATA[(DATA.temp_c == 170) & (DATA.time_min == 20)].yield_pct.to_numpy()
    assert at.loc[(170, 20), "runs"] == 3
    assert at.loc[(170, 20), "s"] == pytest.approx(float(np.sqrt(((ys - ys.mean()) ** 2).sum() / 2)), rel=1e-14)
    text = disp.summary()
    assert "8 replicated settings" in text and "2 unreplicated" in text and "temp_c=165, time_min=25" in text
    # predictions back-transform: s = exp(b0 + b1 A + b2 B) at the coded corner (A, B) = (1, -1)
    b = disp.result.coefficients["coded"]
    s = disp.predict_s(pd.DataFrame({"temp_c": [190.0], "time_min": [10.0]}))
    assert s[0] == pytest.approx(np.exp(b["Intercept"] + b["A"] - b["B"]), rel=1e-12)


def test_too_few_replicated_settings_is_a_parameter_error():
    d = DATA.drop_duplicates(FACTORS).reset_index(drop=True)  # every setting once
    with pytest.raises(ParameterError, match="0 replicated setting") as e:
        fit_dispersion(d, "yield_pct", factors=FACTORS)
    assert e.value.parameter == "response"
    few = DATA[DATA.time_min != 30]  # 6 settings replicated... a quadratic in ln s needs 6 terms
    with pytest.raises(ParameterError) as e:
        fit_dispersion(few, "yield_pct", factors=FACTORS, model="cubic")
    assert e.value.parameter == "dispersion_model"


def test_the_spread_model_codes_the_factors_as_the_mean():
    mean = rsm_lrg.fit(DATA, "yield_pct", factors=FACTORS, model="quadratic")
    disp = fit_dispersion(DATA, "yield_pct", factors=mean.space)
    assert disp.result.space.to_list() == mean.space.to_list()
