"""The simulator (:mod:`rsm_lrg.optimize.simulator`) against exact probabilities: a linear
model with normal factor noise and no model uncertainty (the response is then exactly normal),
the posterior predictive t of the model's own uncertainty, the truncated normal's mean; within
three Monte Carlo standard errors."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from scipy import stats

import rsm_lrg
from rsm_lrg.errors import ParameterError
from rsm_lrg.optimize.poe import propagation_of_error
from rsm_lrg.optimize.simulator import MAX_DRAWS, simulate, simulate_runs

R = Path(__file__).parents[1] / "model" / "r"


@pytest.fixture(scope="module")
def linear():
    rng = np.random.default_rng(20261128)
    X = rng.uniform(-1, 1, (16, 3))
    y = 10 + 2.0 * X[:, 0] - 1.0 * X[:, 1] + 0.5 * X[:, 2] + rng.normal(0, 0.4, 16)
    d = pd.DataFrame({"a": 50 + 10 * X[:, 0], "b": 5 + 2 * X[:, 1], "c": 1 + 0.5 * X[:, 2], "y": y})
    return rsm_lrg.fit(d, "y", factors=["a=40:60", "b=3:7", "c=0.5:1.5"], model="linear")


def _within(p_hat: float, p: float, n: int) -> None:
    se = math.sqrt(p * (1 - p) / n)
    assert abs(p_hat - p) <= 3 * se, (p_hat, p, se)


def test_defect_rate_equals_exact_normal(linear):
    """y = b0 + sum b_i (x_i - c_i)/h_i + e, x_i ~ N(setting, s_i²), e ~ N(0, σ²): normal with
    variance sum (b_i/h_i)² s_i² + σ² (the truncation at 20 SDs is immaterial), N = 10⁶."""
    setting = {"a": 50.0, "b": 5.0, "c": 1.0}
    sds = {"a": 0.5, "b": 0.1, "c": 0.02}
    b = linear.coefficients["coded"]
    half = {"a": 10.0, "b": 2.0, "c": 0.5}
    var = sum((b[L] / half[n]) ** 2 * sds[n] ** 2 for L, n in zip("ABC", "abc")) + linear.sigma2
    mu = float(linear.predict(setting)["predicted"].iloc[0])
    lo, hi = mu - 1.1, mu + 0.8
    n = 10**6
    r = simulate(linear, setting, draws=n, seed=7, factor_sd=sds, spec={"y": (lo, hi)}, model_uncertainty=False)
    sd = math.sqrt(var)
    p = stats.norm.cdf((lo - mu) / sd) + stats.norm.sf((hi - mu) / sd)
    _within(r.responses["y"]["ppm"] / 1e6, p, n)
    _within(r.responses["y"]["ppm_below"] / 1e6, stats.norm.cdf((lo - mu) / sd), n)
    assert r.ppm_any == r.responses["y"]["ppm"]
    assert r.responses["y"]["sd"] == pytest.approx(sd, rel=5e-3)
    # the first-order POE is exact for a linear model
    assert propagation_of_error(linear, setting, sds)[0] == pytest.approx(sd, rel=1e-12)
    cpk = min(hi - r.responses["y"]["mean"], r.responses["y"]["mean"] - lo) / (3 * r.responses["y"]["sd"])
    assert r.responses["y"]["cpk"] == pytest.approx(cpk, rel=1e-12)


def test_model_uncertainty_is_the_posterior_predictive(linear):
    """No factor noise: y = ŷ + t_ν √(se² + s²) (multivariate t coefficients and the residual
    scaled by the same χ² draw), so P(outside) is a t probability and the 2.5 and 97.5 %
    quantiles are the 95 % prediction interval."""
    setting = {"a": 55.0, "b": 4.0, "c": 1.2}
    pr = linear.predict(setting, interval="prediction")
    mu, se = float(pr.predicted.iloc[0]), float(pr.se_fit.iloc[0])
    S = math.sqrt(se**2 + linear.sigma2)
    nu = linear.df_resid
    lo, hi = mu - 0.9, mu + 1.2
    n = 10**6
    r, runs = simulate_runs(linear, setting, draws=n, seed=11, spec=[f"y={lo}:{hi}"])
    p = stats.t.cdf((lo - mu) / S, nu) + stats.t.sf((hi - mu) / S, nu)
    _within(r.responses["y"]["ppm"] / 1e6, p, n)
    q = r.responses["y"]["quantiles"]
    dens = stats.t.pdf(stats.t.ppf(0.975, nu), nu) / S
    q_se = math.sqrt(0.025 * 0.975 / n) / dens  # the MC SE of a sample quantile
    assert abs(q["2.5%"] - float(pr.pi_low.iloc[0])) < 4 * q_se
    assert abs(q["97.5%"] - float(pr.pi_high.iloc[0])) < 4 * q_se
    # without model uncertainty: normal with the residual SD only
    r0 = simulate(linear, setting, draws=n, seed=11, spec={"y": (lo, hi)}, model_uncertainty=False)
    s = math.sqrt(linear.sigma2)
    _within(r0.responses["y"]["ppm"] / 1e6, stats.norm.cdf((lo - mu) / s) + stats.norm.sf((hi - mu) / s), n)


def test_truncated_to_the_region(linear):
    """At the low edge of a: x_a = 40 + |N(0, 5²)| (half-normal), so the mean response rises
    by b_A/h_A · 5 √(2/π); no draw of a leaves the box."""
    setting = {"a": 40.0, "b": 5.0, "c": 1.0}
    n = 400_000
    r = simulate(linear, setting, draws=n, seed=3, factor_sd={"a": 5.0}, model_uncertainty=False)
    mu = float(linear.predict(setting)["predicted"].iloc[0])
    shift = linear.coefficients["coded"]["A"] / 10.0 * 5.0 * math.sqrt(2 / math.pi)
    var = (linear.coefficients["coded"]["A"] / 10.0 * 5.0) ** 2 * (1 - 2 / math.pi) + linear.sigma2
    assert abs(r.responses["y"]["mean"] - (mu + shift)) < 4 * math.sqrt(var / n)
    with pytest.raises(ParameterError) as e:
        simulate(linear, {"a": 39.0, "b": 5.0, "c": 1.0}, draws=10, seed=1, factor_sd={"a": 1.0})
    assert e.value.parameter == "setting"


def test_same_seed_same_numbers(linear):
    kw = dict(draws=70_000, factor_sd={"a": 1.0, "c": 0.1}, spec={"y": (None, 11.0)})  # two blocks
    a = simulate(linear, {"a": 50, "b": 5, "c": 1}, seed=5, **kw).to_dict()
    b = simulate(linear, {"a": 50, "b": 5, "c": 1}, seed=5, **kw).to_dict()
    c = simulate(linear, {"a": 50, "b": 5, "c": 1}, seed=6, **kw).to_dict()
    assert a == b
    assert a != c
    assert a["responses"]["y"]["spec"] == [None, 11.0]


def _mixture_fit():
    """A simplex-lattice {3, 2} with the centroid, twice, on y = 100 x1 + 50 x2 + 80 x3 + 200 x1 x2
    + N(0, 0.5²): the factor variation dominates the residual."""
    pts = [(1, 0, 0), (0, 1, 0), (0, 0, 1), (.5, .5, 0), (.5, 0, .5), (0, .5, .5), (1 / 3, 1 / 3, 1 / 3)] * 2
    X = np.array(pts, dtype=float)
    rng = np.random.default_rng(4)
    y = 100 * X[:, 0] + 50 * X[:, 1] + 80 * X[:, 2] + 200 * X[:, 0] * X[:, 1] + rng.normal(0, 0.5, len(X))
    d = pd.DataFrame({"x1": X[:, 0], "x2": X[:, 1], "x3": X[:, 2], "y": y})
    return rsm_lrg.fit(d, "y", components=["x1", "x2", "x3"], model="mixture-quadratic")


@pytest.mark.parametrize("transform", [None, "log"])
def test_mixture_agrees_with_poe(transform):
    """Small component SDs: the simulated SD (no model uncertainty) is the first-order POE to
    within the MC error and the curvature (1 %); on the log scale for a log model (POE_y / ŷ);
    the blends drawn keep the total (every prediction is made, none refused)."""
    fit = _mixture_fit()
    if transform:
        fit = rsm_lrg.fit(fit.data, "y", components=["x1", "x2", "x3"], model="mixture-quadratic", transform="log")
    setting = {"x1": 0.3, "x2": 0.4, "x3": 0.3}
    sds = {"x1": 0.03, "x2": 0.02, "x3": 0.02}
    poe, resid = propagation_of_error(fit, setting, sds)[0], propagation_of_error(fit, setting, {})[0]
    assert poe > 2 * resid
    r, runs = simulate_runs(fit, setting, draws=200_000, seed=2, factor_sd=sds, model_uncertainty=False)
    if transform:
        y_hat = float(fit.predict(setting)["predicted"].iloc[0])
        assert np.log(runs["y"]).std() == pytest.approx(poe / y_hat, rel=1e-2)
    else:
        assert r.responses["y"]["sd"] == pytest.approx(poe, rel=1e-2)
    assert r.responses["y"]["invalid"] == 0


def test_reml_and_categoric_run():
    d = pd.read_csv(R / "mixed_sp_bal.csv")
    factors = ["temp_c", "preload_kn", "speed_m_s", "lube_ml"]
    fit = rsm_lrg.fit(d, "wear_um", factors=factors, whole_plot="whole_plot")
    setting = {f: float(d[f].mean()) for f in factors}
    r = simulate(fit, setting, draws=50_000, seed=1, model_uncertainty=False)
    s = math.sqrt(fit.mixed.sigma2 + fit.mixed.sigma2_group)
    assert r.responses["wear_um"]["sd"] == pytest.approx(s, rel=2e-2)
    c = pd.read_csv(R / "cat_bbd3x2.csv")
    cf = rsm_lrg.fit(c, "yield_pct", factors=["temp_c", "time_min", "conc_pct", "supplier"])
    r = simulate(cf, {"temp_c": 150, "time_min": 30, "conc_pct": 5, "supplier": "south"}, draws=1000, seed=1,
                 factor_sd={"temp_c": 2.0})
    assert math.isfinite(r.responses["yield_pct"]["mean"])


@pytest.mark.parametrize("draws", [0, -5, 10**12, MAX_DRAWS + 1, 2.5, "many"])
def test_absurd_draws_refused(linear, draws):
    with pytest.raises(ParameterError) as e:
        simulate(linear, {"a": 50, "b": 5, "c": 1}, draws=draws, seed=1)
    assert e.value.parameter == "draws"


@pytest.mark.parametrize("spec", [["z=1:2"], ["y=2:1"], ["y=:"], ["y=a:2"], ["y"], ["y=1:2", "y=0:3"]])
def test_bad_spec(linear, spec):
    with pytest.raises(ParameterError) as e:
        simulate(linear, {"a": 50, "b": 5, "c": 1}, draws=10, seed=1, spec=spec)
    assert e.value.parameter == "spec"


def test_same_numbers_on_two_workers(linear):
    """Blocks drawn in a pool of two processes give the runs drawn in this process, bit for bit."""
    from concurrent.futures import ProcessPoolExecutor

    kw = dict(draws=5 * 65536 + 17, seed=9, factor_sd={"a": 1.0}, spec={"y": (9.0, 11.0)})
    a, runs_a = simulate_runs(linear, {"a": 50, "b": 5, "c": 1}, **kw)
    with ProcessPoolExecutor(max_workers=2) as pool:
        b, runs_b = simulate_runs(linear, {"a": 50, "b": 5, "c": 1}, executor=pool, **kw)
    np.testing.assert_array_equal(runs_a["y"], runs_b["y"])
    assert a.to_dict() == b.to_dict()


def test_streamed_statistics_equal_the_kept_runs(linear, monkeypatch, capsys):
    """Above MAX_KEPT runs the statistics are streamed: the quantiles are the kept runs' to the
    last bit (also when the histogram must be split again inside a bin: MAX_BIN_VALUES set to 8
    forces several levels), the counts equal, the mean and SD to rounding."""
    from rsm_lrg.optimize import simulator as sim

    kw = dict(draws=3 * 65536 + 17, seed=9, factor_sd={"a": 1.0}, spec={"y": (9.0, 11.0)})
    setting = {"a": 50, "b": 5, "c": 1}
    kept, runs = simulate_runs(linear, setting, **kw)
    assert runs["y"].size == kw["draws"]
    for max_bin in (sim.MAX_BIN_VALUES, 8):
        monkeypatch.setattr(sim, "MAX_BIN_VALUES", max_bin)
        streamed, none = simulate_runs(linear, setting, stream=True, progress=True, **kw)
        assert none == {}
        a, b = kept.responses["y"], streamed.responses["y"]
        assert b["quantiles"] == a["quantiles"] == {f"{100 * q:g}%": float(x) for q, x in
                                                    zip(sim.QUANTILES, np.quantile(runs["y"], sim.QUANTILES))}
        for key in ("ppm", "ppm_below", "ppm_above", "ppm_se", "invalid"):
            assert b[key] == a[key], key
        assert b["mean"] == pytest.approx(a["mean"], rel=1e-14) and b["sd"] == pytest.approx(a["sd"], rel=1e-12)
        assert streamed.ppm_any == kept.ppm_any and any("not kept" in n for n in streamed.notes)
        assert "simulated runs (moments)" in capsys.readouterr().err  # the progress bar
    # a response whose runs are all equal (no noise, no uncertainty): every quantile is that value
    flat = simulate(linear, setting, draws=1000, seed=1, model_uncertainty=False, stream=True)
    assert flat.responses["y"]["sd"] > 0  # the residual noise is still drawn
    assert MAX_DRAWS >= 10**8


@pytest.mark.slow
def test_streamed_numbers_do_not_depend_on_the_workers(linear, monkeypatch):
    """The streamed simulation in this process, on a pool of two processes and on a real local
    Dask cluster of two workers: bit-identical results (the blocks, not the workers, define the
    stream; the merge is in block order). Tasks of two blocks: three tasks per pass."""
    from concurrent.futures import ProcessPoolExecutor

    from rsm_lrg.optimize import simulator as sim

    distributed = pytest.importorskip("distributed")
    monkeypatch.setattr(sim, "TASK_BLOCKS", 2)
    kw = dict(draws=4 * 65536 + 3, seed=4, factor_sd={"b": 0.2}, spec={"y": (None, 11.5)}, stream=True)
    setting = {"a": 50, "b": 5, "c": 1}
    here = simulate(linear, setting, **kw).to_dict()
    with ProcessPoolExecutor(max_workers=2) as pool:
        assert simulate(linear, setting, executor=pool, **kw).to_dict() == here
    with distributed.LocalCluster(processes=True, n_workers=2, threads_per_worker=1, host="127.0.0.1",
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        assert simulate(linear, setting, executor=client.get_executor(), **kw).to_dict() == here
