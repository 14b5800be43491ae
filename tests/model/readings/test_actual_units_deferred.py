"""The actual-units solve in two steps (issue 37, item 6): what a summary needs (the residual
sum of squares) first, the change of basis and the inverse when asked."""

from __future__ import annotations

import pickle

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.model.readings.actual_units import solve_actual, solve_actual_deferred
from rsm_lrg.terms import parse_term


@pytest.fixture(scope="module")
def t4() -> pd.DataFrame:
    return rsm_lrg.load_table4()


def _same(a, b) -> bool:
    return all(getattr(a, f) == getattr(b, f) for f in a.__dataclass_fields__ if f != "sigma") and (
        a.sigma == b.sigma or (np.isnan(a.sigma) and np.isnan(b.sigma)))


def test_deferred_solution_is_the_whole_solve_on_table4(t4):
    r = rsm_lrg.fit(t4, "tcr_c_per_min")
    x = np.column_stack([t4[f.name].to_numpy(dtype=float) for f in r.space.factors])
    kw = dict(centre=[f.center for f in r.space.factors], scale=[f.half_range for f in r.space.factors])
    d = solve_actual_deferred(x, r.y, r.terms, **kw)
    whole = solve_actual(x, r.y, r.terms, **kw)
    assert (d.rss, d.sigma, d.n, d.df_resid, d.iterations) == (whole.rss, whole.sigma, whole.n, whole.df_resid,
                                                                 whole.iterations)
    assert _same(d.solution(), whole)
    assert d.solution() is d.solution()  # computed once


def test_deferred_solution_on_an_ill_conditioned_basis():
    # no intercept, factors at 1e5 +- 1e-3 (kappa^2 u > 1; test_nist_strd's
    # test_ill_conditioned_basis_uses_the_double_double_factor): the double-precision Cholesky
    # factor does not converge, the double-double one refines coefficients and inverse up front
    rng = np.random.default_rng(3)
    x = 1e5 + 1e-3 * rng.uniform(-1, 1, (12, 2))
    y = 3 * (x[:, 0] - 1e5) / 1e-3 - 2 * (x[:, 1] - 1e5) / 1e-3 + rng.normal(0, 0.1, 12)
    ts = [parse_term(t, "AB") for t in ("A", "B", "AB")]
    d = solve_actual_deferred(x, y, ts, intercept=False, decimal_inputs=False)
    whole = solve_actual(x, y, ts, intercept=False, decimal_inputs=False)
    assert d.rss == whole.rss
    assert _same(d.solution(), whole)


def test_a_summary_does_not_solve_the_change_of_basis_and_a_fit_still_pickles(t4):
    r = rsm_lrg.fit(t4, "tcr_c_per_min")
    text = str(r.summary())
    assert "actual_deferred" in r.__dict__ and "actual_solution" not in r.__dict__
    r2 = pickle.loads(pickle.dumps(r))  # the deferred part is finished for the trip (a worker process)
    assert str(r2.summary()) == text
    assert r2.actual_coefficients == r.actual_coefficients
    assert r2.actual_std_errors == r.actual_std_errors


def test_coefficient_columns_are_the_coefficient_table(t4):
    r = rsm_lrg.fit(t4, "tcr_c_per_min")
    cols = r.coefficient_columns
    co = r.coefficients
    assert cols["term"] == co.index.tolist()
    for c in ("coded", "std_error", "t", "p", "ci_low", "ci_high", "vif"):
        np.testing.assert_array_equal(cols[c], co[c].to_numpy())
