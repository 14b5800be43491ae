"""Confirmation runs: the paper's confirmation (Sec. 4.3, DIGEST) and the interval algebra."""

import numpy as np
import pytest

import rsm_lrg
from rsm_lrg.optimize.confirm import confirm

AT = {"thickness_m": 0.0001, "stroke_m": 0.04, "velocity_m_s": 0.4, "acceleration_m_s2": 20}


@pytest.fixture(scope="module")
def paper():
    return rsm_lrg.fit(rsm_lrg.load_table4(), "tcr_c_per_min")


def test_paper_confirmation(paper):
    c = confirm(paper, AT, [0.024], reference=0.023)
    # DIGEST (checked): predicted 0.022833; inside the 95 % PI 0.0159–0.0298 (4 digits -> 5e-5)
    assert c.predicted == pytest.approx(0.0228333333, abs=1e-9)
    assert c.pi[0] == pytest.approx(0.0159, abs=5e-5) and c.pi[1] == pytest.approx(0.0298, abs=5e-5)
    assert c.inside
    # paper: 4.35 % relative to the rounded 0.023 (printed to 0.01 %), exact (0.024/0.022833 - 1) = 5.109 %
    assert c.relative_error_vs_reference_percent == pytest.approx(4.35, abs=5e-3)
    assert c.relative_error_percent == pytest.approx(100 * (0.024 / 0.02283333333 - 1), rel=1e-8)
    assert c.relative_error_percent == pytest.approx(5.11, abs=5e-3)
    d = c.to_dict()
    assert d["inside"] is True and d["n"] == 1 and len(d["pi"]) == 2


def test_single_run_interval_is_the_prediction_interval(paper):
    # independent route: for n = 1 the interval is FitResult.predict(interval="prediction")
    c = confirm(paper, AT, 0.03)
    p = paper.predict({k: [v] for k, v in AT.items()}, interval="prediction").iloc[0]
    assert c.pi == pytest.approx((p.pi_low, p.pi_high), rel=1e-12)
    assert not c.inside  # 0.03 lies above 0.0298


def test_mean_of_n_runs_shrinks_towards_the_confidence_interval(paper):
    widths = [np.diff(confirm(paper, AT, [0.024] * n).pi)[0] for n in (1, 2, 4, 1000)]
    assert widths == sorted(widths, reverse=True)
    p = paper.predict({k: [v] for k, v in AT.items()}, interval="confidence").iloc[0]
    assert widths[-1] == pytest.approx(p.ci_high - p.ci_low, rel=2e-3)
    c = confirm(paper, AT, [0.022, 0.026])
    assert c.mean == pytest.approx(0.024) and c.n == 2


def test_errors(paper):
    with pytest.raises(ValueError, match="no setting"):
        confirm(paper, {"thickness_m": 0.0001}, [0.024])
    with pytest.raises(ValueError, match="no such factor"):
        confirm(paper, dict(AT, speed=1), [0.024])
    with pytest.raises(ValueError, match="observed"):
        confirm(paper, AT, [])
    c = confirm(paper, ["A=0.0001", "B=0.04", "C=0.4", "D=50"], [0.03])
    assert c.extrapolation and c.warnings


# --- reduced and transformed models (issue 10, item 13) --------------------------------------

def _montgomery_11_2():
    from tests.model._published import MONTGOMERY_11_2

    return MONTGOMERY_11_2.copy()


def _hand_pi_log(df, point, obs, terms=None, conf=0.95):
    """Hand computation of the log-scale PI for the mean of len(obs) runs (numpy only)."""
    from scipy import stats

    x1, x2 = df["x1"].to_numpy(float), df["x2"].to_numpy(float)
    cols = {"Intercept": np.ones_like(x1), "A": x1, "B": x2, "AB": x1 * x2, "A^2": x1 ** 2, "B^2": x2 ** 2}
    names = list(cols) if terms is None else ["Intercept", *terms]
    X = np.column_stack([cols[c] for c in names])
    z = np.log(df["y"].to_numpy(float))
    beta, *_ = np.linalg.lstsq(X, z, rcond=None)
    nu = len(z) - X.shape[1]
    s2 = float(np.sum((z - X @ beta) ** 2) / nu)
    a, b = point
    x0 = np.array([{"Intercept": 1.0, "A": a, "B": b, "AB": a * b, "A^2": a * a, "B^2": b * b}[c] for c in names])
    zhat = float(x0 @ beta)
    se = np.sqrt(s2 * (1 / len(obs) + x0 @ np.linalg.inv(X.T @ X) @ x0))
    t = stats.t.ppf(1 - (1 - conf) / 2, nu)
    return zhat, (zhat - t * se, zhat + t * se), se


def test_log_transformed_confirmation_equals_a_hand_computation():
    # Montgomery, DAE (8th ed.), Example 11.2 (CCD, yield), fitted to ln(y) (quadratic).
    # Hand computation: OLS on ln y, s² on 13 - 6 = 7 df, PI for the mean of 2 runs on the
    # log scale, ends exponentiated; the runs are judged by the mean of their logs (1e-12).
    df = _montgomery_11_2()
    obs = [79.0, 80.2]
    r = rsm_lrg.fit_transformed(df, "y", "log", factors=["x1=-1:1", "x2=-1:1"])
    c = confirm(r, {"x1": 0.5, "x2": 0.5}, obs)
    zhat, (zlo, zhi), se = _hand_pi_log(df, (0.5, 0.5), obs)
    assert c.transform == "log"
    assert c.predicted_transformed == pytest.approx(zhat, rel=1e-12)
    assert c.predicted == pytest.approx(np.exp(zhat), rel=1e-12)
    assert c.pi_transformed == pytest.approx((zlo, zhi), rel=1e-12)
    assert c.pi == pytest.approx((np.exp(zlo), np.exp(zhi)), rel=1e-12)
    assert c.se_mean == pytest.approx(se, rel=1e-12)
    assert c.mean == pytest.approx(79.6, rel=1e-15)
    assert c.mean_back_transformed == pytest.approx(np.sqrt(79.0 * 80.2), rel=1e-12)  # geometric mean
    assert c.inside == bool(zlo <= np.mean(np.log(obs)) <= zhi)
    # the back-transformed interval is not symmetric about the prediction
    assert c.pi[1] - c.predicted > c.predicted - c.pi[0]
    assert "transformed" in c.summary() and c.to_dict()["pi_transformed"] == pytest.approx([zlo, zhi])


def test_inverse_transform_swaps_the_interval_ends():
    # a decreasing transform (1/y): the back-transformed ends swap; hand: 1/(ẑ ± t·se)
    df = _montgomery_11_2()
    r = rsm_lrg.fit_transformed(df, "y", "inverse", factors=["x1=-1:1", "x2=-1:1"])
    c = confirm(r, {"x1": 0.0, "x2": 0.0}, [80.0])
    zlo, zhi = c.pi_transformed
    assert c.pi == pytest.approx((1 / zhi, 1 / zlo), rel=1e-12) and c.pi[0] < c.predicted < c.pi[1]


def test_reduced_model_confirmation_equals_the_refit_on_kept_terms():
    # the reduced model (backward elimination) is the same as fitting its kept terms by hand
    df = _montgomery_11_2()
    from rsm_lrg.model.choice.reduce import reduce_terms

    red = reduce_terms(df, "y", factors=["x1=-1:1", "x2=-1:1"], alpha_out=0.1)
    assert "AB" in red.removed  # Montgomery Example 11.2: the interaction is not significant
    r = rsm_lrg.fit(df, "y", factors=["x1=-1:1", "x2=-1:1"], terms=list(red.kept[1:]))
    c = confirm(r, {"x1": 0.5, "x2": 0.5}, [79.0])
    from scipy import stats

    X = np.column_stack([np.ones(13), df.x1, df.x2, df.x1 ** 2, df.x2 ** 2])
    y = df.y.to_numpy()
    beta = np.linalg.lstsq(X, y, rcond=None)[0]
    s2 = np.sum((y - X @ beta) ** 2) / 8
    x0 = np.array([1, 0.5, 0.5, 0.25, 0.25])
    se = np.sqrt(s2 * (1 + x0 @ np.linalg.inv(X.T @ X) @ x0))
    t = stats.t.ppf(0.975, 8)
    assert c.pi == pytest.approx((x0 @ beta - t * se, x0 @ beta + t * se), rel=1e-12)
