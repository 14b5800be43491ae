"""Full factorial designs (3^k by default) against their definition and pyDOE3."""

import itertools

import numpy as np
import pytest
from _design_helpers import multiset
from pyDOE3 import fullfact

from rsm_lrg.design import full_factorial


@pytest.mark.parametrize("k,levels", [(1, 3), (2, 3), (3, 3), (4, 3), (2, 2), (3, 5)])
def test_every_combination_once(k, levels):
    d = full_factorial({f"x{i}": (0.0, 4.0) for i in range(k)}, levels=levels, randomize=False)
    grid = np.linspace(-1, 1, levels)
    expected = np.array(list(itertools.product(grid, repeat=k)))
    assert d.n_runs == levels ** k
    assert multiset(d.coded_runs) == multiset(expected)
    # standard order = pyDOE3 fullfact order (first factor fastest)
    np.testing.assert_allclose(d.coded_runs, 2 * fullfact([levels] * k) / (levels - 1) - 1)


def test_two_levels_by_default_as_design_expert_and_jmp():
    d = full_factorial({"v": (0.4, 0.6), "a": (20, 40), "s": (1, 2)}, randomize=False)
    assert d.n_runs == 8 and sorted(set(d.actual["v"])) == [0.4, 0.6]


def test_three_levels_are_low_centre_high():
    d = full_factorial({"v": (0.4, 0.6), "a": (20, 40)}, levels=3, randomize=False)
    assert sorted(set(d.actual["v"])) == [0.4, 0.5, 0.6]
    assert sorted(set(d.actual["a"])) == [20.0, 30.0, 40.0]


def test_extra_centre_runs_and_seed():
    d = full_factorial({"v": (0, 1), "a": (0, 1)}, levels=3, center=2, seed=9)
    assert d.n_runs == 11 and d.n_center == 3
    assert d.to_frame().equals(full_factorial({"v": (0, 1), "a": (0, 1)}, levels=3, center=2, seed=9).to_frame())
    assert full_factorial({"v": (0, 1), "a": (0, 1)}, center=2, seed=9).n_center == 2


@pytest.mark.parametrize("bad", [dict(levels=1), dict(levels=2.5), dict(center=-1), dict(levels=True)])
def test_bad_options(bad):
    with pytest.raises((ValueError, TypeError)):
        full_factorial({"v": (0, 1), "a": (0, 1)}, **bad)


def test_too_large_is_refused():
    with pytest.raises(ValueError, match="runs"):
        full_factorial({f"x{i}": (0, 1) for i in range(12)}, levels=5)
