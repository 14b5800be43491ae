"""Propagation of error (:mod:`rsm_lrg.optimize.poe`) against an independent finite-difference
propagation through the fitted surface: central differences of ``FitResult.predict`` (the
back-transformed prediction) along each factor's direction of variation, and of the
back-transform for the residual variance; agreement to 1e-6 relative."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.errors import ParameterError
from rsm_lrg.optimize.poe import propagation_of_error

R = Path(__file__).parents[1] / "model" / "r"
RTOL = 1e-6


def _fd_poe(fit, point: dict, sds: dict, directions: dict, sigma2: float) -> float:
    """√(Σ_i s_i² (∂ŷ/∂d_i)² + (dy/dη)² σ²) with every derivative a central difference
    (steps 1e-4 of the factor's half range; the surfaces are polynomials, so the truncation
    error is ~1e-8 relative)."""
    total = 0.0
    base = pd.DataFrame({k: [v] for k, v in point.items()})
    for name, sd in sds.items():
        d = directions[name]
        h = 1e-4 * max(fit.space[name].half_range, 1e-300)
        up, dn = base.copy(), base.copy()
        for col, w in d.items():
            up[col] = up[col] + h * w
            dn[col] = dn[col] - h * w
        dy = (float(fit.predict(up)["predicted"].iloc[0]) - float(fit.predict(dn)["predicted"].iloc[0])) / (2 * h)
        total += sd**2 * dy**2
    eta = float(fit.predict_model(base)["predicted"].iloc[0])
    he = 1e-5 * max(abs(eta), 1.0)
    tr = fit.transform
    slope = (float(tr.inverse(eta + he)) - float(tr.inverse(eta - he))) / (2 * he)
    return float(np.sqrt(total + slope**2 * sigma2))


def test_transformed_model():
    d = pd.read_csv(R / "heli.csv")
    fit = rsm_lrg.fit(d, "ave", factors=["A", "R", "W", "L"], transform="log")
    sds = {"A": 0.2, "R": 0.05, "W": 0.03, "L": 0.04}
    for point in ({"A": 12.4, "R": 2.5, "W": 1.1, "L": 1.6}, {"A": 11.0, "R": 2.0, "W": 0.9, "L": 2.1}):
        got = propagation_of_error(fit, point, sds)[0]
        exp = _fd_poe(fit, point, sds, {k: {k: 1.0} for k in sds}, fit.sigma2)
        assert got == pytest.approx(exp, rel=RTOL)
        # the factor variation matters: more than the residual alone
        assert got > propagation_of_error(fit, point, {})[0]


def test_categoric_model_at_a_level():
    d = pd.read_csv(R / "cat_bbd3x2.csv")
    fit = rsm_lrg.fit(d, "yield_pct", factors=["temp_c", "time_min", "conc_pct", "supplier"])
    sds = {"temp_c": 3.0, "time_min": 1.5, "conc_pct": 0.2}
    for level in ("north", "south"):
        point = {"temp_c": 150.0, "time_min": 33.0, "conc_pct": 6.0, "supplier": level}
        got = propagation_of_error(fit, point, sds)[0]
        exp = _fd_poe(fit, point, sds, {k: {k: 1.0} for k in sds}, fit.sigma2)
        assert got == pytest.approx(exp, rel=RTOL)
    with pytest.raises(ParameterError) as e:
        propagation_of_error(fit, point, {"supplier": 1.0})
    assert e.value.parameter == "factor_sd"


@pytest.mark.parametrize("data", ["mixture_etch.csv", "mixture_etch_l.csv"])
def test_mixture_keeps_the_total(data):
    """Each component's deviation less the mean deviation: the FD directions are P e_i (on the
    blend plane, so every predicted blend sums to the total)."""
    d = pd.read_csv(R / data)
    fit = rsm_lrg.fit(d, "erate", components=["x1", "x2", "x3"], model="special-cubic")
    comps = ["x1", "x2", "x3"]
    sds = {"x1": 0.06, "x2": 0.03, "x3": 0.045}
    dirs = {c: {o: (1.0 if o == c else 0.0) - 1.0 / 3.0 for o in comps} for c in comps}
    lows = d[comps].min()
    point = {"x1": 0.5 * (lows.x1 + 1 - lows.x2 - lows.x3), "x2": 0.0, "x3": 0.0}
    point["x2"] = lows.x2 + 0.3 * (1 - lows.sum())
    point["x3"] = 1.0 - point["x1"] - point["x2"]
    got = propagation_of_error(fit, point, sds)[0]
    exp = _fd_poe(fit, point, sds, dirs, fit.sigma2)
    assert got == pytest.approx(exp, rel=RTOL)


def test_reml_uses_both_components():
    d = pd.read_csv(R / "mixed_sp_bal.csv")
    factors = ["temp_c", "preload_kn", "speed_m_s", "lube_ml"]
    fit = rsm_lrg.fit(d, "wear_um", factors=factors, whole_plot="whole_plot")
    point = {f: float(d[f].mean()) for f in factors}
    sds = {"speed_m_s": 0.02}
    got = propagation_of_error(fit, point, sds)[0]
    exp = _fd_poe(fit, point, sds, {k: {k: 1.0} for k in sds}, fit.mixed.sigma2 + fit.mixed.sigma2_group)
    assert got == pytest.approx(exp, rel=RTOL)


@pytest.mark.parametrize("bad", [["nope=1"], ["A=-1"], ["A=inf"], ["A"], ["A=x"], ["A=1", "A=2"]])
def test_bad_factor_sd(bad):
    d = pd.read_csv(R / "heli.csv")
    fit = rsm_lrg.fit(d, "ave", factors=["A", "R", "W", "L"])
    with pytest.raises(ParameterError) as e:
        propagation_of_error(fit, {"A": 12.0, "R": 2.5, "W": 1.1, "L": 1.6}, bad)
    assert e.value.parameter == "factor_sd"
