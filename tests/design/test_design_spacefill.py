"""Latin hypercube and Sobol' designs, on a box and on a constrained region."""

import numpy as np
import pytest

from rsm_lrg.design.constraints import Constraints
from rsm_lrg.design.spacefill import latin_hypercube, sobol
from rsm_lrg.factors import FactorSpace

SP = FactorSpace.from_ranges([("v", 0.2, 1.0), ("a", 5.0, 20.0), ("s", 0.02, 0.1)])


def test_latin_property_on_the_box():
    for crit in ("discrepancy", "maximin"):
        d = latin_hypercube(SP, 12, criterion=crit, seed=3)
        u = (d.coded_runs + 1) / 2  # each column: one run in each of the 12 equal bins
        for j in range(3):
            assert sorted(np.floor(u[:, j] * 12).astype(int).tolist()) == list(range(12))
    a, b = latin_hypercube(SP, 12, seed=3), latin_hypercube(SP, 12, seed=3)
    np.testing.assert_array_equal(a.coded_runs, b.coded_runs)


def test_constrained_runs_are_feasible():
    cons = Constraints.parse("v**2/a <= s", SP)
    for d in (latin_hypercube(SP, 20, constraints=cons, seed=1), sobol(SP, 16, constraints=cons, seed=1)):
        assert d.n_runs in (16, 20)
        assert cons.feasible(d.actual).all()


def test_sobol_balance_and_categoric_levels():
    d = sobol(["x=0:1", "y=0:1", "g=cat:p,q"], 16, seed=2)
    u = (d.coded_runs[:, :2] + 1) / 2
    for j in range(2):  # a power of 2: each half of each axis holds half the points
        assert (u[:, j] < 0.5).sum() == 8
    assert sorted(d.to_frame()["g"].value_counts().tolist()) == [8, 8]
    with pytest.raises(ValueError, match="runs"):
        sobol(SP, 1)
