"""Tolerance intervals against R ``tolerance::regtol.int`` (version 3.0.0): the stored output
``r/tolerance_expected.csv`` of ``r/tolerance.R`` (three data sets not used to develop
:mod:`rsm_lrg.model.contract.tolerance`; see the script's header). Both sides, P in {0.90, 0.99},
confidence in {0.95, 0.90}, at the design points and at new settings; the bounds must agree to
1e-9 relative to the response's scale (R's non-central quantiles are bisected to 1e-13 relative
and SciPy's come from Boost, so the two agree to about 1e-12 here). The CI and PI are unchanged
by asking for the tolerance interval.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg

R = Path(__file__).parents[1] / "r"
#: The agreement asked for, relative to the largest |bound| of the data set.
RTOL = 1e-9


def _heli():
    d = pd.read_csv(R / "heli.csv")
    f = rsm_lrg.fit(d, "ave", factors=["A", "R", "W", "L"])
    new = pd.DataFrame({"A": [12.4, 11.0, 13.9], "R": [2.5, 2.0, 2.9], "W": [1.1, 0.9, 1.3], "L": [1.6, 1.4, 2.1]})
    return f, pd.concat([d[f.factors], new], ignore_index=True), None


def _scales():
    d = pd.read_csv(R / "lm_scales.csv")
    f = rsm_lrg.fit(d, "y", factors=["thickness_m", "freq_hz", "temp_c"], transform="log")
    new = pd.DataFrame({"thickness_m": [2.5e-4, 3.1e-4], "freq_hz": [2.0e6, 3.5e6], "temp_c": [60.0, 80.0]})
    return f, pd.concat([d[f.factors], new], ignore_index=True), np.exp


def _etch():
    d = pd.read_csv(R / "mixture_etch.csv")
    f = rsm_lrg.fit(d, "erate", components=["x1", "x2", "x3"], model="mixture-quadratic")
    new = pd.DataFrame({"x1": [0.2, 0.5, 0.1], "x2": [0.3, 0.25, 0.1], "x3": [0.5, 0.25, 0.8]})
    return f, pd.concat([d[f.factors], new], ignore_index=True), None


SETS = {"heli": _heli, "scales": _scales, "etch": _etch}
EXPECTED = pd.read_csv(R / "tolerance_expected.csv")


@pytest.mark.parametrize("name", list(SETS))
@pytest.mark.parametrize("side", [1, 2])
@pytest.mark.parametrize("P", [0.90, 0.99])
@pytest.mark.parametrize("alpha", [0.05, 0.10])
def test_regtol_int(name, side, P, alpha):
    fit, points, back = SETS[name]()
    exp = EXPECTED[(EXPECTED.set == name) & (EXPECTED.side == side) & np.isclose(EXPECTED.P, P)
                   & np.isclose(EXPECTED.alpha, alpha)].sort_values("point")
    assert len(exp) == len(points)
    got = fit.predict(points, interval="both", alpha=alpha, tolerance=P)
    lo, hi = ("ti_low", "ti_high") if side == 2 else ("ti_one_sided_low", "ti_one_sided_high")
    lower, upper = exp.lower.to_numpy(), exp.upper.to_numpy()
    if back is not None:  # R bounds are on lm's scale (log y): rsm-lrg back-transforms them
        lower, upper = back(lower), back(upper)
    scale = float(np.max(np.abs(np.r_[lower, upper])))
    np.testing.assert_allclose(got[lo].to_numpy(), lower, rtol=0, atol=RTOL * scale)
    np.testing.assert_allclose(got[hi].to_numpy(), upper, rtol=0, atol=RTOL * scale)


@pytest.mark.parametrize("name", list(SETS))
def test_ci_pi_unchanged(name):
    fit, points, _ = SETS[name]()
    plain = fit.predict(points, interval="both")
    with_ti = fit.predict(points, interval="both", tolerance=0.95)
    for col in plain.columns:
        np.testing.assert_array_equal(with_ti[col].to_numpy(), plain[col].to_numpy())


@pytest.mark.parametrize("name", list(SETS))
def test_nesting(name):
    """The two-sided TI for P holds at least P of the runs: it is wider than the one-sided
    bound for the same P on each side, and a TI for P = 0.99 is wider than the 95 % PI (at the
    design points: far outside the region, where se_fit is large, Wallis' approximate two-sided
    factor can fall below the exact one-sided one, in R as here)."""
    fit, points, _ = SETS[name]()
    t = fit.predict(points.iloc[: fit.n], interval="both", tolerance=0.99)
    assert (t.ti_low < t.ti_one_sided_low).all() and (t.ti_high > t.ti_one_sided_high).all()
    assert (t.ti_low < t.pi_low).all() and (t.ti_high > t.pi_high).all()
    assert not math.isnan(float(t.ti_low.sum()))
