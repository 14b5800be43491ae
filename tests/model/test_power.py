"""Power by simulation (issue 35, item 4; :mod:`rsm_lrg.model.power`): the Monte Carlo power of
OLS equals the exact noncentral-F power, and the split-plot (REML + Kenward–Roger) and logistic
(GLM likelihood-ratio) powers equal an independent simulation in R (``r/power.R``: lme4 +
pbkrtest, glm + drop1), each within Monte Carlo error; a seed gives the same numbers whatever
the number of workers."""

import itertools
import math

import numpy as np
import pytest
from scipy import stats

from rsm_lrg.errors import ParameterError
from rsm_lrg.model.evaluate import evaluate_design
from rsm_lrg.model.power import simulate_power

#: ``Rscript tests/model/r/power.R 3000`` (R 4, lme4, pbkrtest; set.seed(20261128)) and
#: ``Rscript tests/model/r/power.R 3000 20261129``, their printed figures pooled (6000 draws):
#: split plot A 0.184000 / 0.173333, B 0.784000 / 0.775667, C 0.773000 / 0.772000; logistic
#: A 0.359000 / 0.362333, B 0.369000 / 0.354333, C 0.364667 / 0.355667, separated 0.003667 / 0.006000.
#: (Exact for comparison: B and C, tested within whole plots on 22 df when the whole-plot variance is
#: estimated inside its bound, have power P(F'(1, 22, 8) > F(0.95; 1, 22)) = 0.7713.)
R_DRAWS = 6000
R_SPLIT_PLOT = {"A": 0.178667, "B": 0.779833, "C": 0.772500}
R_LOGISTIC = {"A": 0.360667, "B": 0.361667, "C": 0.360167}
R_LOGISTIC_SEPARATED = 0.004833


def _factorial(k: int, reps: int = 1) -> np.ndarray:
    return np.vstack([np.array(list(itertools.product([-1.0, 1.0], repeat=k)))] * reps)


def _split_plot() -> tuple[np.ndarray, list[int]]:
    """8 whole plots of 4 runs: A (whole plot) -1, +1 alternately; B, C a 2^2 in each (as power.R)."""
    rows, plots = [], []
    for w, a in enumerate([-1.0, 1.0] * 4):
        for b, c in itertools.product([-1.0, 1.0], repeat=2):
            rows.append([a, b, c])
            plots.append(w + 1)
    return np.array(rows), plots


def _within(p_py: float, draws: int, p_ref: float, ref_draws: float, k: float = 3.0) -> bool:
    """|p_py - p_ref| within k Monte Carlo standard errors of the difference."""
    se = math.sqrt(p_ref * (1.0 - p_ref) * (1.0 / draws + (1.0 / ref_draws if ref_draws else 0.0)))
    return abs(p_py - p_ref) <= k * se


def test_ols_monte_carlo_power_equals_the_noncentral_f_power():
    X = _factorial(4)
    sim = simulate_power(X, "2fi", effect_sd=1.5, draws=6000, seed=11)
    n, p = 16, 11
    # the exact power, by the noncentral t (an independent route from evaluate's noncentral F):
    # coefficient 0.75, se 1/4, df 5; P(|T'| > t_crit)
    tcrit = stats.t.ppf(0.975, n - p)
    delta = 0.75 / math.sqrt(1.0 / n)
    exact = stats.nct.sf(tcrit, n - p, delta) + stats.nct.cdf(-tcrit, n - p, delta)
    np.testing.assert_allclose(sim.terms["parametric"], exact, rtol=1e-9)
    ev = evaluate_design(X, "2fi", effect_sd=1.5, potential=None)
    np.testing.assert_allclose(sim.terms["parametric"], ev.terms["power"].iloc[1:], rtol=1e-12)
    assert list(sim.terms.index) == list(ev.terms.index[1:])
    for term, r in sim.terms.iterrows():
        assert _within(r.power, 6000, exact, 0), (term, r.power, exact)
    # the ten terms together: their mean within 3 SE of the mean (the draws' tests are independent
    # across orthogonal columns)
    assert abs(sim.terms["power"].mean() - exact) <= 3 * math.sqrt(exact * (1 - exact) / (6000 * 10))
    np.testing.assert_allclose(sim.terms["coefficient"], 0.75)
    assert sim.family == "gaussian" and sim.separated == 0 and sim.failed == 0


def test_ols_power_with_blocks_and_a_smaller_effect():
    # a 2^3 in two blocks (ABC confounded): blocks fitted, not simulated; the power is unchanged
    X = _factorial(3, 2)
    from rsm_lrg.design.core import Design
    from rsm_lrg.factors import FactorSpace

    space = FactorSpace.from_ranges([("x1", -1.0, 1.0), ("x2", -1.0, 1.0), ("x3", -1.0, 1.0)])
    blocks = np.where(np.prod(X, axis=1) > 0, 1, 2)
    d = Design(space, "custom", X, np.arange(1, 17), np.arange(1, 17), blocks=blocks)
    sim = simulate_power(d, "linear", effect_sd=1.0, draws=5000, seed=2)
    ev = evaluate_design(d, "linear", effect_sd=1.0, potential=None)
    np.testing.assert_allclose(sim.terms["parametric"], ev.terms["power"].iloc[1:], rtol=1e-12)
    for term, r in sim.terms.iterrows():
        assert _within(r.power, 5000, r.parametric, 0), (term, r.power, r.parametric)


def test_split_plot_power_equals_r_lmer_kenward_roger():
    X, plots = _split_plot()
    # seed 1 (the command's default); seed 7's 200 draws give B 0.69, 2.8 SE low, and so does the
    # exact split-plot ANOVA F test on those same draws: the draws, not the analysis
    sim = simulate_power(X, "linear", effect_sd=1.0, draws=200, seed=1, whole_plots=plots, variance_ratio=1.0)
    assert sim.whole_plots == 8 and sim.variance_ratio == 1.0 and "Kenward" in sim.analysis
    assert sim.terms["parametric"].isna().all()  # no formula for KR power
    for term, r in sim.terms.iterrows():
        assert _within(r.power, 200, R_SPLIT_PLOT[term], R_DRAWS), (term, r.power, R_SPLIT_PLOT[term])
    # the whole-plot factor is tested against the whole plots: far less power than a sub-plot factor
    assert sim.terms.loc["A", "power"] < sim.terms.loc["B", "power"] - 0.3


def test_logistic_power_equals_r_glm_likelihood_ratio():
    X = _factorial(3, 6)
    sim = simulate_power(X, "linear", effect_sd=1.0, draws=200, seed=5, family="binomial", baseline=0.3)
    assert sim.baseline == 0.3 and "likelihood-ratio" in sim.analysis
    for term, r in sim.terms.iterrows():
        assert _within(r.power, 200, R_LOGISTIC[term], R_DRAWS), (term, r.power, R_LOGISTIC[term])
    assert sim.separated <= 200 * R_LOGISTIC_SEPARATED + 3 * math.sqrt(200 * R_LOGISTIC_SEPARATED) + 1


@pytest.mark.parametrize("route", ["ols", "reml"])
def test_same_seed_same_numbers_for_any_worker_count(route):
    if route == "ols":
        X, kw = _factorial(3, 2), {"draws": 5000}  # two least-squares blocks of draws
    else:
        X, plots = _split_plot()
        kw = {"draws": 30, "whole_plots": plots}  # two blocks of refits (25 + 5)
    one = simulate_power(X, "linear", seed=3, workers=1, **kw)
    two = simulate_power(X, "linear", seed=3, workers=2, **kw)
    assert one.to_dict() == two.to_dict()
    assert one.workers == 1 and two.workers == 2
    if route == "ols":  # another seed, other numbers
        assert simulate_power(X, "linear", seed=4, workers=1, **kw).to_dict() != one.to_dict()


def test_draw_i_is_the_ith_child_of_the_seed_sequence():
    # each draw refitted by hand (numpy lstsq, scipy's t): draw i's noise is the i-th child of
    # SeedSequence(seed).spawn(draws), so the counts of 40 draws are the hand-made ones
    X = _factorial(3, 2)
    sim = simulate_power(X, "linear", effect_sd=1.5, draws=40, seed=21)
    M = np.column_stack([np.ones(16), X])
    beta = np.r_[0.0, 0.75, 0.75, 0.75]
    tcrit = stats.t.ppf(0.975, 12)
    C = np.linalg.inv(M.T @ M)
    hits = np.zeros(3)
    for child in np.random.SeedSequence(21).spawn(40):
        y = M @ beta + np.random.default_rng(child).standard_normal(16)
        b, rss, *_ = np.linalg.lstsq(M, y, rcond=None)
        t = b[1:] / np.sqrt(np.diag(C)[1:] * rss[0] / 12)
        hits += np.abs(t) > tcrit
    np.testing.assert_array_equal(sim.terms["power"].to_numpy() * 40, hits)


@pytest.mark.parametrize("kw, parameter", [
    ({"draws": 0}, "draws"),
    ({"draws": 1.5}, "draws"),
    ({"family": "binomial", "baseline": 1.5}, "baseline"),
    ({"family": "binomial", "baseline": 0.0}, "baseline"),
    ({"baseline": 0.3}, "baseline"),
    ({"family": "poisson"}, "family"),
    ({"effect_sd": -1.0}, "effect_sd"),
    ({"alpha": 1.0}, "alpha"),
    ({"workers": 0}, "workers"),
    ({"seed": -1}, "seed"),
    ({"variance_ratio": 1.0}, "variance_ratio"),
])
def test_bad_arguments_name_their_parameter(kw, parameter):
    with pytest.raises(ParameterError) as exc:
        simulate_power(_factorial(3), "linear", **kw)
    assert exc.value.parameter == parameter


def test_binomial_with_whole_plots_and_designs_without_residual_df_are_refused():
    X, plots = _split_plot()
    with pytest.raises(ParameterError) as exc:
        simulate_power(X, "linear", family="binomial", whole_plots=plots)
    assert exc.value.parameter == "family"
    with pytest.raises(ValueError, match="no residual degrees of freedom"):
        simulate_power(_factorial(3), "2fi", terms="A B C AB AC BC ABC")
    with pytest.raises(ValueError, match="not estimable"):
        simulate_power(_factorial(2), "quadratic")
