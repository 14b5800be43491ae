"""The Gaussian process against R DiceKriging 1.6.0 (``tests/model/r/gp.R``, stored outputs
``gp_estimates_expected.csv`` and ``gp_predict_expected.csv``; the designs from
``make_gp.py``: Branin on 20 runs, the borehole function on 60, a noisy Hartmann-3 on 40,
200 noise-free ``simulate`` runs of the paper's Table 3 box (response ``tcr_c_per_min``), each
with 100 new points, none tuned on).

* With the hyper-parameters fixed to ``km``'s estimates, the predictions and kriging
  standard deviations at the 100 new points equal ``predict.km(type="UK")`` to 1e-8
  relative (``predict.km``'s sd includes the nugget: it is ``sqrt(se_fit^2 + nugget)``), and
  the log-likelihood equals ``logLik`` to 1e-9 absolute.
* With the hyper-parameters estimated, the concentrated log-likelihood is at least
  ``km``'s (the best of 20 seeded runs of its L-BFGS-B) minus 1e-6.
* With km's own length-scale bounds (``LOOP_THETA_BOUNDS``: at most 2 x the design's range,
  ``covParametersBounds``; the loop's), the estimates are km's: the length-scales to 1e-5
  relative (where km stops at its bound, to rounding) and the log-likelihood to 1e-6; with the
  default bounds (10 x the range) the likelihood rises above km's where km stops at its bound.
"""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.model.pipelines.gp import LOOP_THETA_BOUNDS

HERE = Path(__file__).parents[1] / "r"
CASES = {  # case: (data set, kernel, trend, nugget estimated)
    "branin_matern52_constant": ("branin", "matern52", "constant", False),
    "branin_gauss_quadratic": ("branin", "gauss", "quadratic", False),
    "borehole_matern32_linear": ("borehole", "matern32", "linear", False),
    "hartmann3_matern52_constant_nugget": ("hartmann3", "matern52", "constant", True),
    "surrogate_matern52_linear": ("surrogate", "matern52", "linear", False),
}
#: Relative tolerance of the kriging sd. 1e-8, except on the Gaussian kernel with a quadratic
#: trend, whose covariance matrix has condition number 2.8e7: at its worst point (sd 1e-4 of
#: the process sd, so the variance is a difference of numbers 1e8 apart) R and rsm-lrg are
#: both within 9e-9 of the value computed with 40 digits (mpmath), and 1.7e-8 from each other.
SD_RTOL = {"branin_gauss_quadratic": 2e-8}


def _case(case: str):
    data, kernel, trend, nugget = CASES[case]
    boxes = pd.read_csv(HERE / "gp_boxes.csv")
    box = boxes[boxes.dataset == data]
    factors = [f"{r.factor}={r.low!r}:{r.high!r}" for r in box.itertuples()]
    runs = pd.read_csv(HERE / f"gp_{data}.csv")
    new = pd.read_csv(HERE / f"gp_{data}_new.csv")
    est = pd.read_csv(HERE / "gp_estimates_expected.csv")
    e = est[est.case == case].set_index("parameter")["value"]
    theta = [float(e[f"theta_{f}"]) for f in box.factor]
    return runs, new, factors, kernel, trend, nugget, e, theta


@pytest.mark.parametrize("case", list(CASES))
def test_fixed_hyperparameters_equal_predict_km(case):
    runs, new, factors, kernel, trend, _, e, theta = _case(case)
    r = rsm_lrg.fit(runs, "y", factors=factors, model="gp", kernel=kernel, trend=trend, length_scales=theta,
                    variance=float(e["sigma2"]), nugget=float(e["nugget"]))
    assert r.core.jitter == 0.0
    ref = pd.read_csv(HERE / "gp_predict_expected.csv")
    ref = ref[ref.case == case]
    p = r.predict(new)
    np.testing.assert_allclose(p["predicted"], ref["mean"], rtol=1e-8, atol=0)
    sd_km = np.sqrt(p["se_fit"].to_numpy() ** 2 + r.nugget)
    np.testing.assert_allclose(sd_km, ref["sd"], rtol=SD_RTOL.get(case, 1e-8), atol=0)
    assert r.log_likelihood == pytest.approx(float(e["loglik"]), abs=1e-9)


@pytest.mark.parametrize("case", [pytest.param(c, marks=pytest.mark.slow) if c.startswith("surrogate") else c
                                  for c in CASES])
def test_estimated_likelihood_at_least_km(case):
    runs, _, factors, kernel, trend, nugget, e, _ = _case(case)
    r = rsm_lrg.fit(runs, "y", factors=factors, model="gp", kernel=kernel, trend=trend,
                    nugget="estimate" if nugget else None)
    assert r.estimated == {"length_scales": True, "variance": True, "nugget": nugget}
    assert r.log_likelihood >= float(e["loglik"]) - 1e-6


@pytest.mark.parametrize("case", [pytest.param(c, marks=pytest.mark.slow) if c.startswith("surrogate") else c
                                  for c in CASES])
def test_with_kms_bounds_the_estimates_are_kms(case):
    runs, _, factors, kernel, trend, nugget, e, theta = _case(case)
    r = rsm_lrg.fit(runs, "y", factors=factors, model="gp", kernel=kernel, trend=trend,
                    nugget="estimate" if nugget else None, length_scale_bounds=LOOP_THETA_BOUNDS)
    assert r.search["length_scale_bounds"] == [1e-3, 2.0]
    np.testing.assert_allclose(r.length_scales, theta, rtol=1e-5)
    assert r.log_likelihood == pytest.approx(float(e["loglik"]), abs=1e-6)
    upper = LOOP_THETA_BOUNDS[1] * np.ptp(r.x, axis=0)
    at_bound = np.isclose(theta, upper, rtol=1e-12)
    np.testing.assert_allclose(r.length_scales[at_bound], upper[at_bound], rtol=1e-14)
    wide = rsm_lrg.fit(runs, "y", factors=factors, model="gp", kernel=kernel, trend=trend,
                       nugget="estimate" if nugget else None)
    if at_bound.any():  # the bound held km back: beyond it the likelihood is higher
        assert wide.log_likelihood > float(e["loglik"]) + 1e-4
    else:
        assert wide.log_likelihood == pytest.approx(float(e["loglik"]), abs=1e-6)
