"""Which runs next (:mod:`rsm_lrg.optimize.next_runs`): the criteria against numerical
integration over the normal, the Kriging Believer batch, the region, and the refusals."""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from scipy import integrate, stats

import rsm_lrg
from rsm_lrg.errors import ParameterError
from rsm_lrg.optimize.next_runs import criterion_values, suggest

DATA = Path(__file__).parents[1] / "model" / "r"
BRANIN = ["x1=-5:10", "x2=0:15"]


@pytest.fixture(scope="module")
def branin_fit():
    d = pd.read_csv(DATA / "gp_branin.csv")
    return rsm_lrg.fit(d, "y", factors=BRANIN, model="gp")


def _expect(f, m, s, kinks):
    """E[f(Y)], Y ~ N(m, s^2), by adaptive quadrature split at the kinks of f."""
    lo, hi = m - 12 * s, m + 12 * s
    cuts = [lo] + sorted(k for k in kinks if lo < k < hi) + [hi]
    return sum(integrate.quad(lambda y: f(y) * stats.norm.pdf(y, m, s), a, b, limit=200, epsabs=1e-14,
                              epsrel=1e-12)[0] for a, b in zip(cuts[:-1], cuts[1:]))


@pytest.mark.parametrize("m, s", [(1.0, 0.5), (-0.3, 2.0), (2.5, 0.1), (0.0, 1e-3)])
def test_criteria_equal_their_integrals(m, s):
    best = 0.8
    # minimize: E[max(best - Y, 0)] and P(Y < best)
    ei = criterion_values(np.array([m]), np.array([s]), "minimize", None, best, "ei")[0]
    assert ei == pytest.approx(_expect(lambda y: max(best - y, 0.0), m, s, [best]), rel=1e-8, abs=1e-14)
    pi = criterion_values(np.array([m]), np.array([s]), "minimize", None, best, "pi")[0]
    assert pi == pytest.approx(stats.norm.cdf(best, m, s), rel=1e-10, abs=1e-15)
    # maximize: E[max(Y - best, 0)]
    ei = criterion_values(np.array([m]), np.array([s]), "maximize", None, best, "ei")[0]
    assert ei == pytest.approx(_expect(lambda y: max(y - best, 0.0), m, s, [best]), rel=1e-8, abs=1e-14)
    # target V: E[max(d - |Y - V|, 0)] with d the best distance so far
    V, d = 1.2, 0.7
    ei = criterion_values(np.array([m]), np.array([s]), "target", V, d, "ei")[0]
    assert ei == pytest.approx(_expect(lambda y: max(d - abs(y - V), 0.0), m, s, [V - d, V, V + d]), rel=1e-7, abs=1e-13)
    pi = criterion_values(np.array([m]), np.array([s]), "target", V, d, "pi")[0]
    assert pi == pytest.approx(stats.norm.cdf(V + d, m, s) - stats.norm.cdf(V - d, m, s), rel=1e-9, abs=1e-15)
    lcb = criterion_values(np.array([m]), np.array([s]), "minimize", None, best, "lcb")[0]
    assert lcb == pytest.approx(-(m - 2 * s))


def test_zero_sd_gives_the_plain_improvement():
    v = criterion_values(np.array([0.2, 1.5]), np.array([0.0, 0.0]), "minimize", None, 1.0, "ei")
    np.testing.assert_allclose(v, [0.8, 0.0])


def test_ei_batch_by_kriging_believer(branin_fit):
    s = suggest(branin_fit, "minimize", runs=3, seed=2)
    assert len(s.design) == 3 and s.design.kind == "suggest"
    x = s.design.coded_runs
    assert np.all(np.abs(x) <= 1.0)
    # distinct settings, each with a positive expected improvement when chosen
    assert len({tuple(np.round(r, 6)) for r in x}) == 3 and (s.table["criterion"] > 0).all()
    assert s.incumbent == pytest.approx(branin_fit.y.min())
    # the first choice maximises EI over a fine grid (within the grid's spacing)
    g = np.linspace(-1, 1, 201)
    G = np.array([(a, b) for a in g for b in g])
    m, sd = branin_fit.mean_sd(G)
    assert s.table["criterion"].iloc[0] >= criterion_values(m, sd, "minimize", None, s.incumbent, "ei").max() * (1 - 1e-3)
    # same seed, same runs
    np.testing.assert_array_equal(suggest(branin_fit, "minimize", runs=3, seed=2).design.coded_runs, x)


def test_variance_batch_spreads_out(branin_fit):
    s = suggest(branin_fit, "minimize", runs=4, criterion="variance", seed=1)
    x = s.design.coded_runs
    d = np.min([np.linalg.norm(x[i] - x[j]) for i in range(4) for j in range(i)])
    assert d > 0.3  # believed runs remove the variance around them


@pytest.mark.slow
def test_bounds_and_constraints_are_kept(branin_fit):
    s = suggest(branin_fit, "target=50", runs=2, bounds=["x1=-5:2"], constraints=["x1 + x2 <= 10"], seed=3)
    t = s.table
    assert (t["x1"] <= 2 + 1e-9).all() and (t["x1"] + t["x2"] <= 10 + 1e-6).all()
    assert np.abs(t["predicted"] - 50).min() < 5


def test_noisy_runs_use_the_predicted_incumbent():
    d = pd.read_csv(DATA / "gp_hartmann3.csv")
    r = rsm_lrg.fit(d, "y", factors=["x1=0:1", "x2=0:1", "x3=0:1"], model="gp", nugget="estimate")
    s = suggest(r, "minimize", runs=1, seed=0)
    assert s.incumbent == pytest.approx(r.mean_sd(r.x)[0].min())
    assert any("Picheny" in n for n in s.notes)


def test_refusals(branin_fit):
    d = pd.read_csv(DATA / "gp_branin.csv")
    # a polynomial with no residual degrees of freedom (6 terms, 6 runs): no standard error
    with pytest.raises(ParameterError, match="no residual variance") as e:
        suggest(rsm_lrg.fit(d.iloc[:6], "y", factors=BRANIN, model="quadratic"), "minimize")
    assert e.value.parameter == "model"
    # a categoric factor: the search is over a box of numeric factors
    c = d.assign(kind=np.where(np.arange(len(d)) % 2 == 0, "p", "q"))
    with pytest.raises(ParameterError, match="'kind' is categoric") as e:
        suggest(rsm_lrg.fit(c, "y", factors=[*BRANIN, "kind"], model="linear"), "minimize")
    assert e.value.parameter == "model"
    etch = pd.read_csv(Path(__file__).parents[2] / "data" / "mixture_etch.csv")
    with pytest.raises(ParameterError, match="'x1' is a mixture component"):
        suggest(rsm_lrg.fit(etch, "erate", components=["x1", "x2", "x3"], model="mixture-quadratic"), "maximize")
    for kw, name in (({"criterion": "qei"}, "criterion"), ({"runs": 0}, "runs"), ({"goal": "up"}, "goal")):
        args = {"goal": "minimize", **kw}
        with pytest.raises(ParameterError) as e:
            suggest(branin_fit, **args)
        assert e.value.parameter == name


# -- a polynomial through the prediction contract (PolynomialEmulator) ------------------------

def _noisy_quadratic(seed=4, reps=2):
    """A replicated 3^2 factorial of a bowl with its minimum at coded (0.3, -0.2), and noise."""
    rng = np.random.default_rng(seed)
    a = np.tile(np.repeat([-1.0, 0.0, 1.0], 3), reps)
    b = np.tile(np.tile([-1.0, 0.0, 1.0], 3), reps)
    y = (a - 0.3) ** 2 + 0.5 * (b + 0.2) ** 2 + 0.2 * a * b + rng.normal(0.0, 0.05, a.size)
    return pd.DataFrame({"a": 50 + 10 * a, "b": 2 + b, "y": y}), ["a=40:60", "b=1:3"]


def test_polynomial_emulator_is_the_fits_prediction_and_least_squares_refit():
    from rsm_lrg.optimize.next_runs import PolynomialEmulator
    from rsm_lrg.terms import design_matrix

    d, factors = _noisy_quadratic()
    fit = rsm_lrg.fit(d, "y", factors=factors, model="quadratic")
    em = PolynomialEmulator(fit)
    pts = np.random.default_rng(1).uniform(-1, 1, (25, 2))
    m, sd = em.mean_sd(pts)
    p = fit.predict(pts, coded=True)
    assert m == pytest.approx(p["predicted"].to_numpy(), rel=1e-12, abs=1e-12)
    assert sd == pytest.approx(p["se_fit"].to_numpy(), rel=1e-12)
    # two extra runs by recursive least squares equal a least-squares refit of the augmented
    # model matrix (numpy.linalg.lstsq), the residual variance held at the fit's
    new = np.array([[0.5, -0.5], [-0.8, 0.9]])
    vals = np.array([0.7, 1.9])
    em2 = em.with_runs(new, vals)
    X = np.vstack([design_matrix(em.x, fit.terms), design_matrix(new, fit.terms)])
    yy = np.r_[d["y"].to_numpy(), vals]
    beta = np.linalg.lstsq(X, yy, rcond=None)[0]
    F = design_matrix(pts, fit.terms)
    m2, sd2 = em2.mean_sd(pts)
    s2 = fit.interval_form.s2_residual
    assert m2 == pytest.approx(F @ beta, rel=1e-10, abs=1e-12)
    assert sd2 == pytest.approx(np.sqrt(s2 * np.einsum("ij,jk,ik->i", F, np.linalg.inv(X.T @ X), F)), rel=1e-10)
    assert em.mean_sd(pts)[1] == pytest.approx(sd, rel=0, abs=0)  # the first emulator is unchanged
    assert em2.x.shape == (em.x.shape[0] + 2, 2)


def test_polynomial_ei_reaches_the_criterions_maximum():
    d, factors = _noisy_quadratic()
    fit = rsm_lrg.fit(d, "y", factors=factors, model="quadratic")
    s = suggest(fit, "minimize", seed=2)
    from rsm_lrg.optimize.next_runs import PolynomialEmulator

    em = PolynomialEmulator(fit)
    # the incumbent is the best predicted mean at the runs (noisy runs)
    assert s.incumbent == pytest.approx(float(np.min(fit.predict(em.x, coded=True)["predicted"])), rel=1e-12)
    g = np.linspace(-1, 1, 401)
    grid = np.column_stack([np.repeat(g, g.size), np.tile(g, g.size)])
    m, sd = em.mean_sd(grid)
    top = criterion_values(m, sd, "minimize", None, s.incumbent, "ei").max()
    assert s.table["criterion"].iloc[0] >= top * (1 - 1e-9)
    # EI on a well-determined bowl picks near the fitted minimum (the stationary point)
    x0 = s.design.coded_runs[0]
    assert np.hypot(*(x0 - grid[np.argmin(m)])) < 0.05
    assert any("standard error of the mean" in n for n in s.notes)


def test_polynomial_variance_batch_is_wynns_sequential_d_optimal_augmentation():
    from rsm_lrg.terms import design_matrix

    d, factors = _noisy_quadratic(reps=1)
    fit = rsm_lrg.fit(d, "y", factors=factors, model="quadratic")
    s = suggest(fit, "minimize", runs=3, criterion="variance", seed=5)
    # independently: add, one at a time, the grid point of largest x'(X'X)^-1 x (Wynn 1970),
    # with the residual variance held
    g = np.linspace(-1, 1, 201)
    grid = np.column_stack([np.repeat(g, g.size), np.tile(g, g.size)])
    X = design_matrix(np.column_stack([(d["a"] - 50) / 10, d["b"] - 2]).astype(float), fit.terms)
    F = design_matrix(grid, fit.terms)
    s2 = fit.interval_form.s2_residual
    for i in range(3):
        var = s2 * np.einsum("ij,jk,ik->i", F, np.linalg.inv(X.T @ X), F)
        assert s.table["criterion"].iloc[i] == pytest.approx(var.max(), rel=1e-9)
        xi = s.design.coded_runs[i]
        X = np.vstack([X, design_matrix(xi[None, :], fit.terms)])
    assert any("Wynn 1970" in n for n in s.notes)


def test_polynomial_with_a_transform_reads_the_goal_on_the_models_scale():
    d, factors = _noisy_quadratic()
    d["y"] = np.exp(d["y"])
    fit = rsm_lrg.fit(d, "y", factors=factors, model="quadratic", transform="log")
    s = suggest(fit, "maximize", criterion="lcb", seed=1)
    assert s.goal == ("maximize", None)
    assert any("on the model's scale (log)" in n for n in s.notes)
    # lcb for a maximisation is m + 2 sd on log y: its maximum over the box, at a grid's best or above
    from rsm_lrg.optimize.next_runs import PolynomialEmulator

    g = np.linspace(-1, 1, 201)
    m, sd = PolynomialEmulator(fit).mean_sd(np.column_stack([np.repeat(g, g.size), np.tile(g, g.size)]))
    assert s.table["criterion"].iloc[0] >= (m + 2 * sd).max() - 1e-9
