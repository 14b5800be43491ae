"""The design space of a mixture: the window is bounds per component on the constrained
simplex (the total kept). Checked here from outside the search: the lattice of blends is
enumerated and the probability at each computed from the fit's ``predict`` (the standard error
of the mean and the residual mean square, Student t with the residual df), then the window's
smallest probability is at least the target and no bound can be relaxed by one grid step
without taking in a blend below the target (or taking in no blend at all)."""

from __future__ import annotations

import itertools

import numpy as np
import pandas as pd
import pytest
from scipy import stats

import rsm_lrg
from rsm_lrg.errors import ParameterError
from rsm_lrg.optimize.design_space import design_space

BOUNDS = {"A": (0.1, 0.6), "B": (0.2, 0.7), "C": (0.1, 0.5)}  # a constrained region (total 1)


def _constrained():
    """Blends of a 0.1 lattice inside BOUNDS, the centroid-ish ones run twice; y a known
    Scheffé quadratic plus seeded normal noise (SD 3)."""
    rows = []
    for a, b in itertools.product(np.arange(0.1, 0.61, 0.1), np.arange(0.2, 0.71, 0.1)):
        c = 1.0 - a - b
        if 0.1 - 1e-9 <= c <= 0.5 + 1e-9:
            rows.append((round(a, 10), round(b, 10), round(c, 10)))
    rows += rows[3:7]
    x = np.array(rows)
    rng = np.random.default_rng(32)
    y = 100 * x[:, 0] + 80 * x[:, 1] + 60 * x[:, 2] + 150 * x[:, 0] * x[:, 1] - 50 * x[:, 0] * x[:, 2]
    d = pd.DataFrame(x, columns=list("ABC"))
    d["y"] = y + 3 * rng.standard_normal(len(d))
    return d


def _independent_p(f, blends, lo, hi):
    pr = f.predict(pd.DataFrame(blends, columns=f.factors))
    res = next(r for r in f.to_dict()["anova"] if r["source"] == "Residual")
    s = np.sqrt(pr["se_fit"].to_numpy() ** 2 + res["mean_sq"])
    yhat = pr["predicted"].to_numpy()
    up = stats.t.cdf((hi - yhat) / s, res["df"]) if hi is not None else 1.0
    down = stats.t.cdf((lo - yhat) / s, res["df"]) if lo is not None else 0.0
    return up - down


def _lattice(lower, upper, m):
    r = 1.0 - sum(lower)
    ks = [k for k in itertools.product(range(m + 1), repeat=3) if sum(k) == m]
    x = np.array([[lo + r * ki / m for lo, ki in zip(lower, k)] for k in ks])
    keep = np.all(x <= np.array(upper) + 1e-9, axis=1)
    return x[keep], r / m


CASES = {
    "constrained": (lambda: (_constrained(), [f"{n}={lo}:{hi}" for n, (lo, hi) in BOUNDS.items()], "y"),
                    (None, 108.0), 0.9, 21),
    "etch": (lambda: (rsm_lrg.load_mixture_etch(), ["x1", "x2", "x3"], "erate"), (450.0, None), 0.9, 21),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_window_meets_the_target_and_no_bound_can_be_relaxed(case):
    make, (lo, hi), target, grid = CASES[case]
    data, comps, y = make()
    f = rsm_lrg.fit(data, y, components=comps, model="mixture-quadratic")
    ds = design_space({y: f}, {y: (lo, hi)}, probability=target, grid=grid)
    assert ds.region == "simplex" and ds.window is not None
    lower = [c.lower for c in f.space.factors]
    upper = [c.upper for c in f.space.factors]
    x, step = _lattice(lower, upper, grid - 1)
    p = _independent_p(f, x, lo, hi)
    assert len(x) == len(ds.grid_probability)
    assert np.sort(ds.grid_probability) == pytest.approx(np.sort(p), abs=1e-10)
    names = list(f.space.names)
    bounds = np.array([ds.window[n] for n in names])
    tol = 1e-9

    def inside(b):
        return np.all((x >= b[:, 0] - tol) & (x <= b[:, 1] + tol), axis=1)

    win = inside(bounds)
    assert win.sum() == ds.window_nodes > 1
    assert p[win].min() >= target and p[win].min() == pytest.approx(ds.window_min_probability, abs=1e-10)
    for j in range(3):  # every bound is reached by a blend of the window
        assert x[win, j].min() == pytest.approx(bounds[j, 0], abs=1e-9)
        assert x[win, j].max() == pytest.approx(bounds[j, 1], abs=1e-9)
    blocked = 0
    for j, side in itertools.product(range(3), (0, 1)):
        b = bounds.copy()
        b[j, side] += -step if side == 0 else step
        new = inside(b) & ~win
        if new.any():  # relaxing it takes in a blend below the target
            assert p[new].min() < target, (names[j], side)
            blocked += 1
    assert blocked >= 1  # the check is not vacuous
    # the window's blends keep the total
    assert np.allclose(x[win].sum(axis=1), 1.0)


def test_mixture_window_refuses_factor_noise_and_shows_the_outline(tmp_path):
    d = rsm_lrg.load_mixture_etch()
    f = rsm_lrg.fit(d, "erate", components=["x1", "x2", "x3"], model="mixture-quadratic")
    with pytest.raises(ParameterError) as e:
        design_space({"erate": f}, {"erate": (450.0, None)}, factor_sd={"x1": 0.01})
    assert e.value.parameter == "factor_sd"
    ds = design_space({"erate": f}, {"erate": (450.0, None)}, grid=11)
    assert len(ds.maps) == 3 and all(m["in_window"].any() for m in ds.maps)
    m = ds.maps[0]  # blends outside the simplex are blank (NaN), the corner x1 = x2 = 1 among them
    assert np.isnan(m["p"][-1, -1]) and np.isfinite(m["p"][0, 0])
    assert ds.to_dict()["region"] == "simplex"
