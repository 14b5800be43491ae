"""Component effects along the Cox and Piepel directions (rsm_lrg.model.readings.mixture_trace) and the
region of a mixture fit (rsm_lrg.model.build.mixture_region), against constructions written out here:
the Cox blend ``x_i = s_i + Δ, x_j = s_j (T - s_i - Δ) / (T - s_i)``, the closed-form slope of a
linear blending model along it, the ends of the range where a bound becomes active, and the
extreme vertices of the design module (McLean & Anderson).

Data: Myers & Montgomery's plasma-etch blends (``r/mixture_etch.csv``) and the same blends on
the L-simplex x1 >= 0.1, x2 >= 0.2, x3 >= 0.05 (``r/mixture_etch_l.csv``).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.model.build.mixture_region import mixture_region
from rsm_lrg.model.readings.mixture_trace import mixture_trace, ternary_slice

R = Path(__file__).parents[1] / "r"
NAMES = ["x1", "x2", "x3"]


@pytest.fixture(scope="module")
def fits():
    etch = pd.read_csv(R / "mixture_etch.csv")
    etch_l = pd.read_csv(R / "mixture_etch_l.csv")
    return {
        "quadratic": rsm_lrg.fit(etch, "erate", components=NAMES, model="mixture-quadratic"),
        "cubic-L": rsm_lrg.fit(etch_l, "erate", components=["x1=0.1:1", "x2=0.2:1", "x3=0.05:1"],
                               model="special-cubic"),
        "linear": rsm_lrg.fit(etch, "erate", components=NAMES, model="mixture-linear"),
    }


def _cox_blend(s: dict, i: str, delta: float) -> dict:
    T = sum(s.values())
    return {k: (v + delta if k == i else v * (T - s[i] - delta) / (T - s[i])) for k, v in s.items()}


@pytest.mark.parametrize("which, bounds", [("quadratic", {}), ("cubic-L", {}), ("cubic-L", {"x2": (0.2, 0.7)})])
def test_cox_trace_is_the_cox_blend(fits, which, bounds):
    fit = fits[which]
    tr = mixture_trace(fit, n=21, bounds=bounds or None)
    s = tr.reference
    assert sum(s.values()) == pytest.approx(1.0, abs=1e-12)
    for name in NAMES:
        dev = tr.deviation[name]
        assert dev[0] < 0 < dev[-1] and len(dev) == 21
        blends = pd.DataFrame([_cox_blend(s, name, d) for d in dev])
        np.testing.assert_allclose(tr.blends[name], blends[NAMES].to_numpy(), rtol=0, atol=1e-12)
        want = fit.predict(blends)["predicted"].to_numpy()
        # (coded settings are rounded to 12 decimals, from the blend or from the pseudo components: 1e-10)
        np.testing.assert_allclose(tr.predicted[name], want, rtol=1e-10)
        assert tr.effects[name] == pytest.approx(want[-1] - want[0], rel=1e-10, abs=1e-8)
        # each end is where a bound becomes active, and no bound is broken on the way
        for end in (0, -1):
            x = blends.iloc[end]
            gaps = []
            for f in fit.space.factors:
                lo, hi = f.lower, min(f.upper, f.total)
                if f.name in bounds:
                    lo, hi = max(lo, bounds[f.name][0]), min(hi, bounds[f.name][1])
                assert lo - 1e-12 <= x[f.name] <= hi + 1e-12
                gaps += [x[f.name] - lo, hi - x[f.name]]
            assert min(gaps) <= 1e-12
        # the slope at the reference: a central difference along the Cox blend
        # (Richardson: exact for a cubic along a line up to round-off; coded values carry 12 decimals)
        def diff(h, name=name):
            yy = fit.predict(pd.DataFrame([_cox_blend(s, name, -h), _cox_blend(s, name, h)]))["predicted"].to_numpy()
            return (yy[1] - yy[0]) / (2 * h)

        assert tr.gradients[name] == pytest.approx((4 * diff(5e-4) - diff(1e-3)) / 3, rel=1e-7)


def test_linear_blending_slope_closed_form(fits):
    """ŷ = Σ b_i x_i: along the Cox direction dŷ/dΔ = b_i - Σ_{j≠i} b_j s_j / (1 - s_i)."""
    fit = fits["linear"]
    b = fit.actual_coefficients
    ref = {"x1": 0.5, "x2": 0.3, "x3": 0.2}
    tr = mixture_trace(fit, reference=ref)
    letters = dict(zip(NAMES, "ABC"))
    for i in NAMES:
        want = b[letters[i]] - sum(b[letters[j]] * ref[j] for j in NAMES if j != i) / (1 - ref[i])
        assert tr.gradients[i] == pytest.approx(want, rel=1e-10)
        # a straight line: the total effect is the slope times the range
        assert tr.effects[i] == pytest.approx(want * (tr.high[i] - tr.low[i]), rel=1e-10)
        assert tr.low[i] == pytest.approx(-ref[i], abs=1e-12) and tr.high[i] == pytest.approx(1 - ref[i], abs=1e-12)


def test_piepel_direction_keeps_pseudo_ratios(fits):
    fit = fits["cubic-L"]
    tr = mixture_trace(fit, direction="piepel", n=11)
    L = np.array([0.1, 0.2, 0.05])
    Rng = 1 - L.sum()
    ref = np.array([tr.reference[n] for n in NAMES])
    zr = (ref - L) / Rng
    for i, name in enumerate(NAMES):
        Z = (tr.blends[name] - L) / Rng
        np.testing.assert_allclose(Z[:, i] - zr[i], tr.deviation[name], atol=1e-12)
        others = [j for j in range(3) if j != i]
        live = np.min(Z[:, others], axis=1) > 1e-6  # at the far end both others are 0: no ratio
        assert live.sum() >= 9
        ratio = Z[live, others[0]] / Z[live, others[1]]
        np.testing.assert_allclose(ratio, zr[others[0]] / zr[others[1]], rtol=1e-9)


def test_reference_blend_is_checked(fits):
    fit = fits["quadratic"]
    with pytest.raises(ValueError, match="sums to 1.1"):
        mixture_trace(fit, reference={"x1": 0.5, "x2": 0.3, "x3": 0.3})
    with pytest.raises(ValueError, match="direction"):
        mixture_trace(fit, direction="sideways")
    with pytest.raises(ValueError, match="outside the region"):
        mixture_trace(fits["cubic-L"], reference={"x1": 0.05, "x2": 0.5, "x3": 0.45})


def test_region_vertices_are_the_extreme_vertices(fits):
    fit = fits["cubic-L"]
    region = mixture_region(fit.space, bounds={"x2": (0.2, 0.7)}, constraints=["x1 + x2 <= 0.8"])
    V = np.array([list(region.to_actual(v).values()) for v in region.vertices()])
    bounds = {"x1": (0.1, 1.0), "x2": (0.2, 0.7), "x3": (0.05, 1.0)}
    want = rsm_lrg.extreme_vertices(bounds, constraints=["x1 + x2 <= 0.8"]).to_frame()[NAMES].to_numpy()
    assert len(V) == len(want)
    for w in want:
        assert np.min(np.max(np.abs(V - w), axis=1)) <= 1e-12
    # the centroid is the vertex average
    np.testing.assert_allclose(list(region.to_actual(region.centroid()).values()), V.mean(axis=0), atol=1e-12)


def test_ternary_slice_predicts_inside_the_region_only(fits):
    fit = fits["cubic-L"]
    sl = ternary_slice(fit, n=30)
    X = sl["settings"]
    assert np.allclose(X.sum(axis=1), 1.0, atol=1e-12)
    inside = (X[:, 0] >= 0.1 - 1e-12) & (X[:, 1] >= 0.2 - 1e-12) & (X[:, 2] >= 0.05 - 1e-12)
    assert 0 < inside.sum() < len(X)
    np.testing.assert_array_equal(sl["inside"], inside)
    want = fit.predict(pd.DataFrame(X[inside], columns=NAMES))["predicted"].to_numpy()
    np.testing.assert_allclose(sl["predicted"][inside], want, rtol=1e-10)
    assert np.isnan(sl["predicted"][~inside]).all()
