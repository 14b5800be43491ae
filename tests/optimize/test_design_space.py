"""The design space (rsm_lrg.optimize.design_space): the probability of meeting every
specification against an independent posterior-predictive simulation, and the operating
window's two properties (every node at the target; no face can grow by one grid step)."""

import math

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.errors import ParameterError
from rsm_lrg.optimize.design_space import design_space, parse_spec

T4 = ["thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2"]
Y = "tcr_c_per_min"


@pytest.fixture(scope="module")
def t4():
    return rsm_lrg.load_table4()


def _simulated(fit, x_actual: dict, low, high, n=200_000, seed=5) -> tuple[float, float]:
    """P(new run in [low, high]) by simulating the posterior predictive of an OLS fit under the
    non-informative prior: σ² = SSE/χ²_ν, β | σ² ~ N(b, σ²(X'X)⁻¹), y ~ N(xβ, σ²) on the
    model's scale, back-transformed. Returns (p, Monte Carlo SE)."""
    rng = np.random.default_rng(seed)
    idx = fit.term_index
    C = fit.cov_unscaled[np.ix_(idx, idx)]
    b = fit.coefficients["coded"].to_numpy()
    nu = fit.df_resid
    s2 = fit.sigma2 * nu / rng.chisquare(nu, n)
    L = np.linalg.cholesky(C)
    beta = b + (rng.standard_normal((n, len(b))) @ L.T) * np.sqrt(s2)[:, None]
    x = fit.space.encode(pd.DataFrame({k: [v] for k, v in x_actual.items()})).to_numpy(dtype=float)
    row = rsm_lrg.model.design_matrix(x, fit.terms)[0]
    z = beta @ row + rng.standard_normal(n) * np.sqrt(s2)
    y = fit.transform.inverse(z) if not fit.transform.identity else z
    inside = np.ones(n, dtype=bool)
    if low is not None:
        inside &= y >= low
    if high is not None:
        inside &= y <= high
    p = float(inside.mean())
    return p, math.sqrt(max(p * (1 - p), 1.0 / n) / n)


@pytest.mark.parametrize("transform, spec", [(None, (None, 0.035)), ("log", (0.02, 0.04)), ("inverse", (0.025, None))])
def test_probability_equals_a_posterior_predictive_simulation(t4, transform, spec):
    fit = rsm_lrg.fit(t4, Y, factors=T4, transform=transform)
    ds = design_space({Y: fit}, {Y: spec}, probability=0.5, grid=3)
    lv = ds.levels
    for node in [(0, 0, 0, 0), (1, 1, 1, 1), (2, 0, 2, 1), (0, 2, 1, 2)]:
        setting = {n: float(lv[j][node[j]]) for j, n in enumerate(ds.factors)}
        p_sim, se = _simulated(fit, setting, *spec)
        assert ds.grid_probability[node] == pytest.approx(p_sim, abs=4 * se + 1e-12), setting


@pytest.mark.parametrize("k, grid", [(2, 25), (4, 9)])
def test_window_is_at_the_target_and_cannot_grow(t4, k, grid):
    """Every node of the window meets the target; moving any face out by one grid step takes
    in a node below it (or leaves the region) — on a 2-factor and a 4-factor case."""
    if k == 4:
        fit = rsm_lrg.fit(t4, Y, factors=T4)
    else:  # the runs at the middle stroke: a 2-factor model in thickness and velocity
        mid = t4[t4.stroke_m == 0.05].reset_index(drop=True)
        fit = rsm_lrg.fit(mid, Y, factors=["thickness_m", "velocity_m_s"], model="2fi")
    target = 0.8
    ds = design_space({Y: fit}, {Y: (None, 0.033)}, probability=target, grid=grid)
    assert ds.window is not None
    p = ds.grid_probability
    box = [(int(np.argmin(np.abs(lv - lo))), int(np.argmin(np.abs(lv - hi))))
           for lv, (lo, hi) in zip(ds.levels, ds.window.values())]
    inside = p[tuple(slice(a, b + 1) for a, b in box)]
    assert inside.min() >= target and inside.min() == pytest.approx(ds.window_min_probability)
    assert ds.window_nodes == inside.size
    for j in range(p.ndim):
        for new in (box[j][0] - 1, box[j][1] + 1):
            if not 0 <= new < p.shape[j]:
                continue  # the region's edge
            slab = tuple(slice(a, b + 1) if i != j else slice(new, new + 1) for i, (a, b) in enumerate(box))
            assert p[slab].min() < target, (j, new)


def test_no_window_when_no_node_reaches_the_target(t4):
    fit = rsm_lrg.fit(t4, Y, factors=T4)
    ds = design_space({Y: fit}, {Y: (None, 0.01)}, probability=0.9, grid=5)
    assert ds.window is None and ds.window_nodes == 0 and "No operating window" in ds.summary()
    assert ds.to_dict()["window"] is None


def test_two_responses_multiply(t4):
    df = t4.assign(other=t4[Y] * 2 + 0.01)
    f1 = rsm_lrg.fit(df, Y, factors=T4)
    f2 = rsm_lrg.fit(df, "other", factors=T4)
    a = design_space({Y: f1}, {Y: (None, 0.035)}, grid=3).grid_probability
    b = design_space({"other": f2}, {"other": (0.05, None)}, grid=3).grid_probability
    both = design_space({Y: f1, "other": f2}, {Y: (None, 0.035), "other": (0.05, None)}, grid=3)
    np.testing.assert_allclose(both.grid_probability, a * b, rtol=1e-12)


def test_factor_noise_is_seeded_and_lowers_the_edge(t4):
    fit = rsm_lrg.fit(t4, Y, factors=T4)
    kw = dict(probability=0.9, grid=3, factor_sd={"velocity_m_s": 0.03}, draws=300)
    a = design_space({Y: fit}, {Y: (None, 0.035)}, seed=1, **kw)
    b = design_space({Y: fit}, {Y: (None, 0.035)}, seed=1, **kw)
    np.testing.assert_array_equal(a.grid_probability, b.grid_probability)
    plain = design_space({Y: fit}, {Y: (None, 0.035)}, probability=0.9, grid=3)
    # at the high-velocity face the noise can only move runs inward, where κ is lower: no loss there
    # in this model; at the centre (a steep region) the noise costs probability
    assert a.grid_probability[1, 1, 1, 1] <= plain.grid_probability[1, 1, 1, 1] + 1e-12
    assert "truncated to the factor box" in " ".join(a.notes)


@pytest.mark.parametrize("kwargs, parameter", [
    ({"probability": 1.0}, "probability"), ({"grid": 2}, "grid"), ({"grid": 201 ** 1}, None),
    ({"factor_sd": {"nope": 1.0}}, "factor_sd"), ({"factor_sd": {"stroke_m": -1.0}}, "factor_sd"),
    ({"draws": 0}, "draws"), ({"held": {"stroke_m": "x"}}, "held"),
])
def test_bad_arguments_name_their_parameter(t4, kwargs, parameter):
    fit = rsm_lrg.fit(t4, Y, factors=T4)
    if parameter is None:  # 201^4 nodes: refused by size, naming grid
        with pytest.raises(ParameterError) as info:
            design_space({Y: fit}, {Y: (None, 0.035)}, **kwargs)
        assert info.value.parameter == "grid"
        return
    with pytest.raises(ParameterError) as info:
        design_space({Y: fit}, {Y: (None, 0.035)}, **kwargs)
    assert info.value.parameter == parameter


@pytest.mark.parametrize("text, want", [("y=:1", ("y", None, 1.0)), ("y=0.5:", ("y", 0.5, None)),
                                        ("a b=1:2", ("a b", 1.0, 2.0))])
def test_parse_spec(text, want):
    assert parse_spec(text) == want


@pytest.mark.parametrize("text", ["y", "y=1", "y=:", "y=2:1", "y=nan:1", "=1:2"])
def test_parse_spec_refuses(text):
    with pytest.raises(ParameterError):
        parse_spec(text)


def test_reml_fit_uses_its_kenward_roger_predictive():
    """A split-plot REML fit: p at each node equals the t probability with the contract's
    variance of a new run in a new whole plot and the Kenward–Roger df of that node (from
    ``predict``'s PI and ``kr_mean``)."""
    from pathlib import Path

    from scipy import stats

    d = pd.read_csv(Path(__file__).parents[1] / "model" / "r" / "mixed_sp_bal.csv")
    fit = rsm_lrg.fit(d, "wear_um", factors=["temp_c", "preload_kn", "speed_m_s", "lube_ml"], whole_plot="whole_plot")
    ds = design_space({"wear_um": fit}, {"wear_um": (48.0, 56.0)}, probability=0.5, grid=3)
    for node in [(0, 0, 0, 0), (1, 2, 0, 1), (2, 1, 2, 2)]:
        pt = pd.DataFrame({n: [float(ds.levels[j][node[j]])] for j, n in enumerate(ds.factors)})
        out = fit.predict(pt, interval="prediction").iloc[0]
        _, df = fit.kr_mean(pt)
        t = stats.t(df[0])
        s = (out["pi_high"] - out["predicted"]) / t.ppf(0.975)
        want = t.cdf((56.0 - out["predicted"]) / s) - t.cdf((48.0 - out["predicted"]) / s)
        assert ds.grid_probability[node] == pytest.approx(want, rel=1e-9, abs=1e-12)
