"""Tolerance intervals of :mod:`rsm_lrg.model.contract.tolerance` beyond the R comparison
(test_tolerance_r.py): the textbook factors, REML fits (Kenward–Roger df, both variance
components), a transformed response, bad input."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.errors import ParameterError
from rsm_lrg.model.contract.tolerance import tolerance_bounds, tolerance_factor

R = Path(__file__).parents[1] / "r"


def test_normal_sample_factors():
    """Intercept-only model (n* = n, df = n - 1): NIST/SEMATECH e-Handbook Sec. 7.2.6.3, one-sided
    k for n = 20, P = 0.99, C = 0.95 is 3.295 (3 decimals as tabulated); two-sided (Howe's table,
    which Wallis' factor equals for one mean to the table's 3 decimals) 3.615."""
    k1 = tolerance_factor([20.0], 19.0, 0.99, 0.95, side=1)[0]
    k2 = tolerance_factor([20.0], 19.0, 0.99, 0.95, side=2)[0]
    assert abs(k1 - 3.295) < 5e-4
    assert abs(k2 - 3.615) < 2e-3


def test_one_sided_factor_against_mpmath():
    """The non-central t quantile checked independently: P(T' <= K sqrt(n*)) = C with the
    non-central t's CDF integrated by mpmath (30 digits), to 1e-10."""
    mpmath = pytest.importorskip("mpmath")
    mpmath.mp.dps = 30
    n_star, df, P, C = 7.3, 11.0, 0.95, 0.9
    k = float(tolerance_factor([n_star], df, P, C, side=1)[0])
    delta = mpmath.sqrt(n_star) * mpmath.sqrt(2) * mpmath.erfinv(2 * mpmath.mpf(P) - 1)
    t = k * mpmath.sqrt(n_star)

    def density(v):  # T' = (Z + delta) / sqrt(V/df), V ~ chi2(df): integrate over V
        chi = mpmath.exp((df / 2 - 1) * mpmath.log(v) - v / 2 - (df / 2) * mpmath.log(2) - mpmath.loggamma(df / 2))
        return chi * mpmath.ncdf(t * mpmath.sqrt(v / df) - delta)

    cdf = mpmath.quad(density, [0, df, 4 * df, mpmath.inf])
    assert abs(float(cdf) - C) < 1e-10


def test_bad_proportion_names_tolerance():
    d = pd.read_csv(R / "heli.csv")
    f = rsm_lrg.fit(d, "ave", factors=["A", "R", "W", "L"])
    for bad in (0.0, 1.0, 1.5, float("nan"), "x"):
        with pytest.raises(ParameterError) as e:
            f.predict(d.iloc[:2], tolerance=bad)
        assert e.value.parameter == "tolerance"


def test_no_residual_df_gives_nan():
    lo, hi = tolerance_bounds([1.0], [0.1], [float("nan")], float("nan"), 0.9, 0.95)
    assert np.isnan(lo).all() and np.isnan(hi).all()


@pytest.mark.parametrize("name, response, factors, random", [
    ("mixed_sp_bal", "wear_um", ["temp_c", "preload_kn", "speed_m_s", "lube_ml"], {"whole_plot": "whole_plot"}),
    ("mixed_pastry", "y", ["x1", "x2", "x3"], {"random_block": "Block"}),
])
def test_reml_uses_kr_df_and_both_components(name, response, factors, random):
    """REML: TI = ŷ ± K √(σ²_group + σ²) with n* = (σ²_group + σ²) / x'Φ_A x and ν the KR den
    df of the mean at x (recomputed here from kr_mean and the variance components); wider than
    the OLS TI of the same data and model, which ignores the whole-plot variance."""
    d = pd.read_csv(R / f"{name}.csv")
    reml = rsm_lrg.fit(d, response, factors=factors, **random)
    ols = rsm_lrg.fit(d, response, factors=factors)
    pts = d[factors].iloc[::3]
    got = reml.predict(pts, interval="both", tolerance=0.9)
    var_a, kdf = reml.kr_mean(pts)
    v_new = reml.mixed.sigma2_group + reml.mixed.sigma2
    assert reml.mixed.sigma2_group > 0
    k = tolerance_factor(v_new / var_a, kdf, 0.9, 0.95, side=2)
    np.testing.assert_allclose(got.ti_high - got.predicted, k * np.sqrt(v_new), rtol=1e-12)
    np.testing.assert_allclose(got.predicted - got.ti_low, k * np.sqrt(v_new), rtol=1e-12)
    k1 = tolerance_factor(v_new / var_a, kdf, 0.9, 0.95, side=1)
    np.testing.assert_allclose(got.ti_one_sided_high - got.predicted, k1 * np.sqrt(v_new), rtol=1e-12)
    assert (kdf < ols.df_resid).all()
    o = ols.predict(pts, tolerance=0.9)
    assert ((got.ti_high - got.ti_low).to_numpy() > (o.ti_high - o.ti_low).to_numpy()).all()
    # the PI of the same fit sits inside the TI for P = 0.99
    t99 = reml.predict(pts, interval="both", tolerance=0.99)
    assert (t99.ti_low < t99.pi_low).all() and (t99.ti_high > t99.pi_high).all()


def test_inverse_transform_swaps_ends():
    """A decreasing transform: the model-scale upper bound becomes the response's lower one;
    the interval still holds the prediction and is back-transformed end for end."""
    d = pd.read_csv(R / "heli.csv")
    f = rsm_lrg.fit(d, "ave", factors=["A", "R", "W", "L"], transform="inverse")
    m = f.predict_model(d.iloc[:4])
    t = f.predict(d.iloc[:4], tolerance=0.9)
    assert (t.ti_low < t.predicted).all() and (t.predicted < t.ti_high).all()
    assert (t.ti_one_sided_low > t.ti_low).all()
    from rsm_lrg.model.contract.tolerance import add_tolerance_interval

    mm = add_tolerance_interval(f, m.copy(), d.iloc[:4], 0.9, 0.05)
    np.testing.assert_allclose(t.ti_low, 1.0 / mm.ti_high, rtol=1e-14)
    np.testing.assert_allclose(t.ti_high, 1.0 / mm.ti_low, rtol=1e-14)
