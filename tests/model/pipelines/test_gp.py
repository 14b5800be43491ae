"""The Gaussian-process engine (:mod:`rsm_lrg.model.pipelines.gp`, :mod:`rsm_lrg.model.results.gp_result`):
closed-form leave-one-out against explicit refits, analytic gradients against finite
differences, the prediction API, draws, the JSON and the refusals. The comparison with R
DiceKriging is in ``test_gp_r.py``."""

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.errors import ParameterError
from rsm_lrg.model.engines.gp_trend import trend_matrix
from rsm_lrg.model.pipelines.gp import ProfileLikelihood

HERE = Path(__file__).parents[1] / "r"
BRANIN = ["x1=-5:10", "x2=0:15"]
HART = ["x1=0:1", "x2=0:1", "x3=0:1"]


@pytest.fixture(scope="module")
def branin():
    return pd.read_csv(HERE / "gp_branin.csv")


@pytest.fixture(scope="module")
def hartmann():
    return pd.read_csv(HERE / "gp_hartmann3.csv")


@pytest.fixture(scope="module")
def branin_fit(branin):
    return rsm_lrg.fit(branin, "y", factors=BRANIN, model="gp", kernel="matern52", trend="linear")


@pytest.fixture(scope="module")
def hartmann_fit(hartmann):
    return rsm_lrg.fit(hartmann, "y", factors=HART, model="gp", kernel="gauss", nugget="estimate")


@pytest.mark.parametrize("which", ["branin", "hartmann"])
def test_closed_form_loo_equals_explicit_refits(which, branin, hartmann, branin_fit, hartmann_fit):
    # Dubrule (1983): each run predicted from the others, trend re-estimated by GLS, the
    # covariance parameters fixed; 20 refits (Branin) and 40 (Hartmann-3, nugget estimated)
    data, fitted, factors = (branin, branin_fit, BRANIN) if which == "branin" else (hartmann, hartmann_fit, HART)
    names = [f.split("=")[0] for f in factors]
    pred, sd = [], []
    for i in range(len(data)):
        r = rsm_lrg.fit(data.drop(index=i), "y", factors=factors, model="gp", kernel=fitted.kernel,
                        trend=fitted.trend, length_scales=fitted.length_scales, variance=fitted.variance,
                        nugget=fitted.nugget)
        p = r.predict(data.loc[[i], names])
        pred.append(float(p["predicted"].iloc[0]))
        sd.append(float(np.sqrt(p["se_fit"].iloc[0] ** 2 + fitted.nugget)))
    loo = fitted.loo
    scale = float(np.std(data["y"]))
    np.testing.assert_allclose(loo.predicted, pred, rtol=1e-9, atol=1e-9 * scale)
    np.testing.assert_allclose(loo.sd, sd, rtol=1e-9)
    res = data["y"].to_numpy() - np.array(pred)
    q2 = 1 - np.sum(res ** 2) / np.sum((data["y"] - data["y"].mean()) ** 2)
    assert loo.q2 == pytest.approx(q2, rel=1e-9)
    np.testing.assert_allclose(loo.standardized, res / np.array(sd), rtol=1e-8, atol=1e-9)


@pytest.mark.parametrize("kernel", ["matern52", "matern32", "gauss"])
@pytest.mark.parametrize("mode", ["concentrated", "nugget", "fixed-nugget", "fixed-variance"])
def test_likelihood_gradient_matches_finite_differences(kernel, mode, hartmann):
    x = (hartmann[["x1", "x2", "x3"]].to_numpy() - 0.5) * 2
    y = hartmann["y"].to_numpy()
    F, _ = trend_matrix(x, "linear", ["A", "B", "C"])
    kw = {"concentrated": dict(concentrated=True, scale=None, noise=0.0),
          "nugget": dict(concentrated=True, scale=None, noise="estimate"),
          "fixed-nugget": dict(concentrated=False, scale=None, noise=0.01),
          "fixed-variance": dict(concentrated=False, scale=0.8, noise="estimate")}[mode]
    lik = ProfileLikelihood(x, y, F, kernel, theta=None, **kw)
    p = np.log([0.7, 0.5, 0.4])
    if mode in ("nugget", "fixed-variance"):
        p = np.r_[p, np.log(0.02)]
    if mode == "fixed-nugget":
        p = np.r_[p, np.log(0.9)]
    f0, g = lik(p)
    h = 1e-6
    num = [(lik(p + h * e)[0] - lik(p - h * e)[0]) / (2 * h) for e in np.eye(p.size)]
    np.testing.assert_allclose(g, num, rtol=1e-5, atol=1e-6)


@pytest.mark.parametrize("kernel", ["matern52", "matern32", "gauss"])
@pytest.mark.parametrize("trend", ["constant", "linear", "quadratic"])
def test_surface_gradient_matches_finite_differences(kernel, trend, branin):
    r = rsm_lrg.fit(branin, "y", factors=BRANIN, model="gp", kernel=kernel, trend=trend, length_scales=[0.6, 1.1],
                    variance=1e4)
    pts = pd.DataFrame({"x1": [-2.0, 3.3, 8.1], "x2": [1.5, 7.7, 12.0]})
    g = r.gradient(pts)
    for name, h in (("x1", 1e-5), ("x2", 1e-5)):
        up, dn = pts.copy(), pts.copy()
        up[name] += h
        dn[name] -= h
        num = (r.predict(up)["predicted"] - r.predict(dn)["predicted"]) / (2 * h)
        np.testing.assert_allclose(g[name], num, rtol=1e-6, atol=1e-6 * np.abs(num).max())


def test_interpolates_deterministic_runs(branin, branin_fit):
    p = branin_fit.predict(branin[["x1", "x2"]])
    np.testing.assert_allclose(p["predicted"], branin["y"], rtol=1e-8, atol=1e-8)
    assert p["se_fit"].max() < 1e-4 * np.sqrt(branin_fit.variance)
    assert branin_fit.nugget == 0.0 and not branin_fit.estimated["nugget"]
    assert any("nugget fixed at 0" in n for n in branin_fit.notes)


def test_predict_api(branin_fit):
    pts = pd.DataFrame({"x1": [0.0, 5.0], "x2": [3.0, 9.0]}, index=[7, 9])
    p = branin_fit.predict(pts, interval="both", alpha=0.1)
    assert list(p.columns) == ["predicted", "se_fit", "ci_low", "ci_high", "pi_low", "pi_high"]
    assert list(p.index) == [7, 9]
    z = 1.6448536269514722  # normal 95 % quantile
    np.testing.assert_allclose(p["ci_high"] - p["predicted"], z * p["se_fit"], rtol=1e-12)
    coded = branin_fit.predict(pd.DataFrame({"A": [-1 / 3, 1 / 3], "B": [-0.6, 0.2]}), coded=True)
    np.testing.assert_allclose(coded["predicted"], p["predicted"], rtol=1e-12)
    m = branin_fit.predict({"x1": 0.0, "x2": 3.0})
    assert m["predicted"].iloc[0] == pytest.approx(p["predicted"].iloc[0], rel=1e-12)
    a = branin_fit.predict(np.array([[0.0, 3.0], [5.0, 9.0]]), interval="confidence")
    np.testing.assert_allclose(a["ci_low"], p["predicted"] - 1.959963984540054 * p["se_fit"], rtol=1e-12)
    with pytest.raises(ParameterError):
        branin_fit.predict(pts, alpha=1.5)
    with pytest.raises(ValueError, match="interval"):
        branin_fit.predict(pts, interval="tolerance")
    with pytest.raises(ValueError, match="lack the factor"):
        branin_fit.predict(pd.DataFrame({"x1": [0.0]}))


def test_prediction_interval_adds_the_nugget(hartmann_fit):
    assert hartmann_fit.estimated["nugget"] and hartmann_fit.nugget > 0
    p = hartmann_fit.predict(pd.DataFrame({"x1": [0.3], "x2": [0.6], "x3": [0.5]}), interval="both")
    half_pi = (p["pi_high"] - p["predicted"]).iloc[0] / 1.959963984540054
    assert half_pi == pytest.approx(np.sqrt(p["se_fit"].iloc[0] ** 2 + hartmann_fit.nugget), rel=1e-12)


def test_draws_follow_the_posterior(branin_fit):
    pts = pd.DataFrame({"x1": [-1.0, 0.0, 2.5], "x2": [4.0, 5.0, 11.0]})
    cov = branin_fit.covariance(pts)
    p = branin_fit.predict(pts)
    np.testing.assert_allclose(np.sqrt(np.diag(cov)), p["se_fit"], rtol=1e-9)
    d = branin_fit.draws(pts, 4000, seed=5)
    assert d.shape == (4000, 3)
    np.testing.assert_allclose(d.mean(axis=0), p["predicted"], atol=4 * p["se_fit"].max() / np.sqrt(4000) * 3)
    np.testing.assert_array_equal(branin_fit.draws(pts, 3, seed=1), branin_fit.draws(pts, 3, seed=1))


def test_same_seed_same_fit(branin):
    a = rsm_lrg.fit(branin, "y", factors=BRANIN, model="gp", seed=11)
    b = rsm_lrg.fit(branin, "y", factors=BRANIN, model="gp", seed=11)
    np.testing.assert_array_equal(a.length_scales, b.length_scales)
    assert a.starts == 10 and a.seed == 11


def test_replicates_estimate_the_nugget_and_refuse_zero(branin):
    twice = pd.concat([branin, branin.assign(y=branin.y + np.linspace(-1, 1, len(branin)))], ignore_index=True)
    r = rsm_lrg.fit(twice, "y", factors=BRANIN, model="gp", trend="constant")
    assert r.estimated["nugget"] and r.nugget > 0
    assert any("nugget estimated" in n for n in r.notes)
    with pytest.raises(ParameterError, match="share|more than one run") as e:
        rsm_lrg.fit(twice, "y", factors=BRANIN, model="gp", nugget=0)
    assert e.value.parameter == "nugget"


def test_to_dict_and_summary(hartmann_fit):
    d = json.loads(json.dumps(hartmann_fit.to_dict()))
    assert d["model"] == "gp" and d["n"] == 40
    assert set(d["gp"]) >= {"kernel", "length_scales", "variance", "nugget", "trend", "log_likelihood"}
    assert d["gp"]["length_scales"]["coded"]["x2"] == pytest.approx(hartmann_fit.length_scales[1])
    assert d["gp"]["length_scales"]["actual"]["x2"] == pytest.approx(hartmann_fit.length_scales[1] * 0.5)
    assert d["gp"]["log_likelihood"] == pytest.approx(hartmann_fit.log_likelihood)
    assert set(d["loo"]) >= {"q2", "rmse", "standardized_residuals"} and len(d["loo"]["standardized_residuals"]) == 40
    text = hartmann_fit.summary()
    assert "Kernel: gauss" in text and "Leave-one-out" in text and "Nugget (estimated)" in text


@pytest.mark.parametrize("kw, parameter", [
    ({"kernel": "exp"}, "kernel"), ({"trend": "cubic"}, "trend"), ({"nugget": -1.0}, "nugget"),
    ({"nugget": "lots"}, "nugget"), ({"length_scales": [1.0]}, "length_scales"),
    ({"length_scales": [1.0, -2.0]}, "length_scales"), ({"variance": 0.0}, "variance"),
    ({"block": "x1"}, "block"), ({"transform": "log"}, "transform"), ({"terms": "A B"}, "terms"),
    ({"reduce": True}, "reduce"), ({"components": ["x1", "x2"]}, "components"),
    ({"length_scale_bounds": (2.0, 1.0)}, "length_scale_bounds"), ({"length_scale_bounds": (0.0, 1.0)},
                                                                    "length_scale_bounds"),
    ({"length_scale_bounds": (0.1, np.inf)}, "length_scale_bounds"), ({"length_scale_bounds": 2.0},
                                                                       "length_scale_bounds"),
    ({"length_scale_bounds": ("a", 2)}, "length_scale_bounds"),
])
def test_bad_options_name_their_parameter(branin, kw, parameter):
    with pytest.raises(ParameterError) as e:
        rsm_lrg.fit(branin, "y", factors=BRANIN, model="gp", **kw)
    assert e.value.parameter == parameter


def test_length_scale_bounds_hold_and_are_recorded(branin, hartmann):
    # bounds that exclude the usual starting box: every start and the optimum inside them
    r = rsm_lrg.fit(branin, "y", factors=BRANIN, model="gp", length_scale_bounds=(0.01, 0.05))
    span = np.ptp(r.x, axis=0)
    assert np.all(r.length_scales >= 0.01 * span * (1 - 1e-12)) and np.all(r.length_scales <= 0.05 * span * (1 + 1e-12))
    assert r.search["length_scale_bounds"] == [0.01, 0.05]
    assert r.to_dict()["gp"]["search"]["length_scale_bounds"] == [0.01, 0.05]
    # on these runs the likelihood's maximum lies inside (0.01, 2) x the range: the same fit
    inner = rsm_lrg.fit(hartmann, "y", factors=HART, model="gp", nugget="estimate", length_scale_bounds=(0.01, 2.0))
    wide = rsm_lrg.fit(hartmann, "y", factors=HART, model="gp", nugget="estimate")
    assert np.all(wide.length_scales < 2.0 * np.ptp(wide.x, axis=0))
    np.testing.assert_allclose(inner.length_scales, wide.length_scales, rtol=1e-5)
    # fixed length-scales: no bounds used
    fixed = rsm_lrg.fit(branin, "y", factors=BRANIN, model="gp", length_scales=[1.0, 2.0], variance=1e4)
    assert fixed.search == {}


def test_length_scale_bounds_only_with_a_gp(branin):
    from rsm_lrg.model.build.spec import SpecError

    with pytest.raises(SpecError) as e:
        rsm_lrg.fit(branin, "y", factors=BRANIN, model="quadratic", length_scale_bounds=(0.01, 2.0))
    assert e.value.parameter == "length_scale_bounds"


def test_categoric_factor_refused(branin):
    d = branin.assign(kind=np.where(np.arange(len(branin)) % 2, "a", "b"))
    with pytest.raises(ParameterError, match="categoric") as e:
        rsm_lrg.fit(d, "y", factors=["x1", "x2", "kind"], model="gp")
    assert e.value.parameter == "factors"


def test_too_few_runs_for_the_trend(branin):
    with pytest.raises(ParameterError, match="needs at least") as e:
        rsm_lrg.fit(branin.head(6), "y", factors=BRANIN, model="gp", trend="quadratic")
    assert e.value.parameter == "trend"


def test_with_runs_believing_the_mean_keeps_the_mean(branin_fit):
    # Kriging Believer (Ginsbourger et al. 2010): a run at its predicted mean leaves the mean
    # surface as it was (hyper-parameters held) and takes the variance there to zero
    at = pd.DataFrame({"x1": [1.0], "x2": [6.0]})
    m = branin_fit.predict(at)["predicted"].to_numpy()
    b = branin_fit.with_runs(at, m)
    assert b.n == branin_fit.n + 1 and not any(b.estimated.values())
    pts = pd.DataFrame({"x1": [-3.0, 4.0, 9.0], "x2": [2.0, 8.0, 14.0]})
    np.testing.assert_allclose(b.predict(pts)["predicted"], branin_fit.predict(pts)["predicted"], rtol=1e-8)
    assert b.predict(at)["se_fit"].iloc[0] < 1e-5 * np.sqrt(b.variance)
    assert (b.predict(pts)["se_fit"] <= branin_fit.predict(pts)["se_fit"] + 1e-9).all()


@pytest.mark.slow
def test_many_runs_search_starts_on_a_subsample():
    # above MULTISTART_RUNS runs the starts run on a subsample and the best two are polished on
    # all runs: the result is a stationary point of the full likelihood, and the notes say so
    from rsm_lrg.model.pipelines.gp import MULTISTART_RUNS

    rng = np.random.default_rng(3)
    n = MULTISTART_RUNS + 20
    d = pd.DataFrame({"a": rng.uniform(0, 1, n), "b": rng.uniform(0, 1, n)})
    d["y"] = np.sin(6 * d.a) * np.cos(3 * d.b)
    d["y"] += rng.normal(0, 0.05, n)
    r = rsm_lrg.fit(d, "y", factors=["a=0:1", "b=0:1"], model="gp", kernel="matern52", nugget="estimate", seed=1)
    assert any("subsample" in note for note in r.notes)
    x = (d[["a", "b"]].to_numpy() - 0.5) * 2
    lik = ProfileLikelihood(x, d["y"].to_numpy(), np.ones((n, 1)), "matern52", theta=None, concentrated=True,
                            scale=None, noise="estimate")
    p = np.r_[np.log(r.length_scales), np.log(r.nugget / r.variance)]
    f, g = lik(p)
    assert r.core.jitter == 0.0 and -f == pytest.approx(r.log_likelihood, abs=1e-8)
    assert np.max(np.abs(g)) < 1e-3  # every parameter inside its bounds here


def _noisy_330():
    rng = np.random.default_rng(5)
    n = 330
    d = pd.DataFrame({"a": rng.uniform(0, 1, n), "b": rng.uniform(0, 1, n), "c": rng.uniform(0, 1, n)})
    d["y"] = np.sin(6 * d.a) * np.cos(3 * d.b) + d.c ** 2 + rng.normal(0, 0.02, n)
    return d


def test_polish_on_all_runs_keeps_the_previous_optimum(monkeypatch):
    # above MULTISTART_RUNS the polish factorises in place (SciPy dpotrf) and stops after an
    # iteration gaining < POLISH_GAIN = 1e-7 (was numpy.linalg.cholesky and 1e-9): on this
    # seeded, well-conditioned case (condition number 1.2e7) the log-likelihood is the previous
    # release's (680.5096239010596 with eecc25c, 15 evaluations on all runs; now 14) to 1e-6,
    # the old stop rule gains nothing that matters, and an independent factorisation at the
    # estimates (kriging_core: numpy.linalg.cholesky) gives the same likelihood
    from rsm_lrg.model.engines.gp_core import kriging_core
    from rsm_lrg.model.pipelines import gp as gp_pipeline

    d = _noisy_330()
    factors = ["a=0:1", "b=0:1", "c=0:1"]
    r = rsm_lrg.fit(d, "y", factors=factors, model="gp", nugget="estimate", seed=1)
    assert r.search["subsample"] == gp_pipeline.MULTISTART_RUNS and r.search["evaluations_all"] > 0
    previous = 680.5096239010596
    assert r.log_likelihood >= previous - 1e-6
    assert r.log_likelihood == pytest.approx(previous, abs=1e-6)
    again = kriging_core(r.x, r.y, np.ones((r.n, 1)), "matern52", r.length_scales, r.variance, r.nugget)
    assert again.log_likelihood == pytest.approx(r.log_likelihood, abs=1e-8)
    monkeypatch.setattr(gp_pipeline, "POLISH_GAIN", 1e-9)
    tight = rsm_lrg.fit(d, "y", factors=factors, model="gp", nugget="estimate", seed=1)
    assert tight.search["evaluations_all"] >= r.search["evaluations_all"]
    assert r.log_likelihood >= tight.log_likelihood - 1e-8


def test_polish_likelihood_rebuilds_a_singular_matrix_before_the_jitter():
    # in place, a failed factorisation overwrites the matrix: it is rebuilt and the jitter
    # ladder of cholesky_jitter runs on it, as below MULTISTART_RUNS
    from rsm_lrg.model.engines.gp_core import kriging_core
    from rsm_lrg.model.pipelines.gp import MULTISTART_RUNS

    rng = np.random.default_rng(2)
    half = (MULTISTART_RUNS + 20) // 2
    x = rng.uniform(-1, 1, (half, 2))
    x = np.vstack([x, x])  # every setting twice: R is singular, no nugget
    y = np.r_[np.sin(3 * x[:half, 0]), np.sin(3 * x[:half, 0])] + x[:, 1]
    F = np.ones((x.shape[0], 1))
    lik = ProfileLikelihood(x, y, F, "matern52", theta=None, concentrated=True, scale=None, noise=0.0)
    p = np.log([0.7, 1.3])
    f, g = lik(p)
    chol, jit = lik.factor_at(p)
    assert jit > 0 and np.all(np.isfinite(g))
    ref = kriging_core(x, y, F, "matern52", np.exp(p), 1.0, 0.0)  # numpy.linalg.cholesky and the ladder
    assert ref.jitter == jit
    n = y.size
    assert -f == pytest.approx(-0.5 * (n * np.log(2 * np.pi * ref.quad / n) + ref.logdet + n), abs=1e-9)
