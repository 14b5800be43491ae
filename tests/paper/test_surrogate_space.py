"""The design space through the physics (:mod:`rsm_lrg.paper.surrogate_space`).

* With the raw physics and nothing but the reading noise, κ at a setting is the noise-free κ
  plus a normal error of SD ``noise_sd / duration`` (the difference of two two-sensor averages
  over the test, :func:`rsm_lrg.simulate`), so the probability of ``κ ≤ U`` is exactly
  ``Φ((U - κ0) / σ)``: the Monte Carlo fraction must agree within 3.5 standard errors.
* The first-order shares' estimator recovers the known Sobol indices of an analytic function.
* The calibrated parameters are drawn as the calibration file states them (the split normal's
  quantiles; the at-bound conductance uniformly over its range), and the same seed gives the
  same numbers on one worker and on two.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest
from scipy import stats

import rsm_lrg
from rsm_lrg.errors import ParameterError
from rsm_lrg.paper.surrogate_space import (
    first_order_shares,
    parameter_draws,
    surrogate_design_space,
)
from rsm_lrg.surrogate import DEFAULT_NOISE_SD, load_calibration


def test_noise_only_probability_is_the_exact_normal_one():
    v = [0.49, 0.50, 0.51]
    rows = pd.DataFrame({"thickness_m": 3e-4, "stroke_m": 0.05, "velocity_m_s": v, "acceleration_m_s2": 30.0})
    k0 = rsm_lrg.simulate(rows, noise_sd=0, calibration=None)["tcr_c_per_min"].to_numpy()
    upper = float(k0[1])
    n = 400
    r = surrogate_design_space({"velocity_m_s": (0.49, 0.51)}, {"tcr_c_per_min": (None, upper)}, grid=3, draws=n,
                               calibration=None, seed=5, probability=0.3)
    sigma = DEFAULT_NOISE_SD / 50.0
    exact = stats.norm.cdf((upper - k0) / sigma)
    got = np.array([nd["p"] for nd in r.nodes])
    se = np.sqrt(exact * (1 - exact) / n)
    assert np.all(np.abs(got - exact) <= 3.5 * se), (got, exact)
    assert 0.05 < exact[2] < 0.3 < exact[1] < exact[0] < 0.95  # not a degenerate check
    # noise is all that varies: its share is 1, and its variance the documented one
    for nd in r.nodes:
        a = nd["attribution"]["tcr_c_per_min"]
        assert a["noise"] == pytest.approx(1.0) and a["parameters"] == 0.0 and a["dominant"] == "noise"
        assert math.sqrt(a["variance"]) == pytest.approx(sigma, rel=0.15)
    assert r.space.window == {"velocity_m_s": (0.49, 0.50)}  # p >= 0.3 at the two slower settings only
    # the limit met with the target probability: the 0.3-quantile of the node's runs; the spec is met with p >= 0.3
    # exactly where it is at least that limit, and that limit against the exact normal quantile
    for nd, k in zip(r.nodes, k0):
        lim = nd["limits"]["tcr_c_per_min"]["upper"]
        assert (nd["p"] >= 0.3) == (upper >= lim)
        assert lim == pytest.approx(k + sigma * stats.norm.ppf(0.3), abs=4 * sigma / math.sqrt(n) / 0.35)
    assert "Lowest upper limit of tcr_c_per_min met with probability 0.3" in r.summary()


def test_first_order_shares_recover_known_indices():
    # the estimator (Saltelli 2010 (b), centred) on f = 2 X + Z + X Z with X, Z ~ U(-1, 1) independent: V = 4/3 + 1/3 + 1/9 = 16/9;
    # S_X = (4/3)/(16/9) = 0.75, S_Z = (1/3)/(16/9) = 0.1875; noise N(0, 0.5) adds 0.25
    rng = np.random.default_rng(1)
    n = 200_000
    xa, za, xb, zb = (rng.uniform(-1, 1, n) for _ in range(4))

    def f(x, z):
        return 2 * x + z + x * z

    eps = 0.5 * rng.standard_normal(n)
    total, share = first_order_shares(f(xa, za), eps, f(xb, zb),
                                      {"parameters": f(xb, za), "tolerances": f(xa, zb)})
    v = 16 / 9 + 0.25
    assert total == pytest.approx(v, rel=0.01)
    assert share["parameters"] == pytest.approx((4 / 3) / v, abs=0.01)
    assert share["tolerances"] == pytest.approx((1 / 3) / v, abs=0.01)
    assert share["noise"] == pytest.approx(0.25 / v, abs=0.01)


def test_calibrated_parameters_are_drawn_as_stated():
    from rsm_lrg.datasets import data_path
    from rsm_lrg.paper.surrogate_space import draw_values

    cal = load_calibration(data_path("calibration.toml"))
    specs = {s["name"]: s for s in parameter_draws(cal)}
    cv = specs["viscous_friction_n_s_m"]
    est = next(p for p in cal.parameters if p.name == "viscous_friction_n_s_m")
    assert cv["distribution"] == "split-normal"
    x = draw_values(cv, np.random.default_rng(0), 200_000)
    # 2.5 % below ci_low and 2.5 % above ci_high, less what the bound 0 cuts off below (the lower half,
    # probability 1/2, crosses 0 with probability 2 Φ(-value / σ_low)); 30 is far away
    cut = 0.5 * 2 * stats.norm.cdf(-est.value / cv["sd_low"])
    assert 0.001 < cut < 0.01
    assert np.mean(x < est.ci_low) == pytest.approx((0.025 - cut) / (1 - cut), abs=0.0015)
    assert np.mean(x > est.ci_high) == pytest.approx(0.025 / (1 - cut), abs=0.0015)
    assert np.median(x) == pytest.approx(est.value, abs=0.02)
    assert x.min() >= 0.0
    h = specs["ball_contact_conductance_w_k"]
    assert h["distribution"] == "uniform" and "known only by a bound" in h["description"]
    y = draw_values(h, np.random.default_rng(0), 10_000)
    assert y.min() >= h["lower"] and y.max() <= h["upper"]


def test_same_seed_same_numbers_on_one_and_two_workers():
    kw = dict(grid=2, draws=6, seed=11, param_sd={"thickness_m": 5e-6})
    box = {"velocity_m_s": (0.4, 0.6)}
    spec = {"tcr_c_per_min": (None, 0.045)}
    one = surrogate_design_space(box, spec, **kw).to_dict()
    two = surrogate_design_space(box, spec, workers=2, **kw).to_dict()
    for d in (one, two):
        d["surrogate"].pop("seconds")
        d["surrogate"].pop("workers")
    assert one == two
    assert one["surrogate"]["runs"] == 2 * 6 * 5


@pytest.mark.parametrize("kw, parameter", [
    (dict(factors={"leaf": (1.0, 2.0)}), "factors"),
    (dict(param_sd={"viscous_friction_n_s_m": 1.0}), "param_sd"),
    (dict(param_sd={"nonsense": 1.0}), "param_sd"),
    (dict(specs={"kappa": (None, 1.0)}), "spec"),
    (dict(draws=3), "draws"),
])
def test_bad_arguments_name_the_parameter(kw, parameter):
    args = dict(factors={"velocity_m_s": (0.4, 0.6)}, specs={"tcr_c_per_min": (None, 0.045)}, grid=2, draws=4)
    args.update(kw)
    with pytest.raises(ParameterError) as e:
        surrogate_design_space(args.pop("factors"), args.pop("specs"), **args)
    assert e.value.parameter == parameter
