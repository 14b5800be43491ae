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
