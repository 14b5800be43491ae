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
    with pytest.raises(ParameterError) as e:
        suggest(rsm_lrg.fit(d, "y", factors=BRANIN), "minimize")
    assert e.value.parameter == "model"
    for kw, name in (({"criterion": "qei"}, "criterion"), ({"runs": 0}, "runs"), ({"goal": "up"}, "goal")):
        args = {"goal": "minimize", **kw}
        with pytest.raises(ParameterError) as e:
            suggest(branin_fit, **args)
        assert e.value.parameter == name
