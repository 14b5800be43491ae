"""The physics prior beside the polynomials (issue 34, item 4): every LOO R² equals 27 explicit
refits of its own (each run left out, the model refitted by least squares, the run predicted)."""

import numpy as np
import pytest

import rsm_lrg
from rsm_lrg.paper.hybrid import PRIOR_CALIBRATION, hybrid_comparison, physics_prior


@pytest.fixture(scope="module")
def t4():
    return rsm_lrg.load_table4()


@pytest.fixture(scope="module")
def prior(t4):
    return physics_prior(t4)


def _loo_r2(X, y, ss):
    err = []
    for i in range(len(y)):
        keep = np.arange(len(y)) != i
        beta, *_ = np.linalg.lstsq(X[keep], y[keep], rcond=None)
        err.append(y[i] - X[i] @ beta)
    return 1.0 - float(np.sum(np.square(err))) / ss


def test_every_loo_r2_equals_explicit_refits(t4, prior):
    h = hybrid_comparison(t4, prior)
    y = t4["tcr_c_per_min"].to_numpy(float)
    ss = float(np.sum((y - y.mean()) ** 2))
    x = np.column_stack([(t4[c].to_numpy(float) - m) / r for c, m, r in
                         (("thickness_m", 3e-4, 2e-4), ("stroke_m", 0.05, 0.01), ("velocity_m_s", 0.5, 0.1),
                          ("acceleration_m_s2", 30.0, 10.0))])
    one = np.ones((len(y), 1))
    lin = np.hstack([one, x])
    c2 = np.hstack([lin, x[:, [2]] ** 2])
    quad = np.hstack([lin] + [x[:, [i]] * x[:, [j]] for i in range(4) for j in range(i + 1, 4)] + [x ** 2])
    p = prior[:, None]
    want = {
        "physics alone (a + b·prior)": _loo_r2(np.hstack([one, p]), y, ss),
        "quadratic (Eq. 19)": _loo_r2(quad, y, ss),
        "linear + C²": _loo_r2(c2, y, ss),
        "prior offset + linear discrepancy": _loo_r2(lin, y - prior, ss),
        "linear + prior covariate": _loo_r2(np.hstack([lin, p]), y, ss),
        "linear + C² + prior covariate": _loo_r2(np.hstack([c2, p]), y, ss),
    }
    assert [n for n, _, _ in h.rows] == list(want)
    for name, r2 in want.items():
        assert h.r2(name) == pytest.approx(r2, abs=1e-10), name
    assert h.r2("quadratic (Eq. 19)") == pytest.approx(0.818, abs=5e-4)  # the paper's PRESS R² (Table 5)
    assert h.r2("linear + C²") == pytest.approx(0.894, abs=5e-4)


def test_the_prior_takes_nothing_from_table4(t4, prior):
    # the prior depends on the settings only: the same runs with another response give the same κ
    other = t4.assign(tcr_c_per_min=t4["tcr_c_per_min"].to_numpy()[::-1])
    assert np.array_equal(physics_prior(other), prior)
    assert PRIOR_CALIBRATION["viscous_friction_n_s_m"] == 0.0 and PRIOR_CALIBRATION["two_carriage"] is True
    assert np.all(np.isfinite(prior)) and np.all(prior > 0)
