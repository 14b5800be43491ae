"""Central composite designs: alpha against NIST/SEMATECH and Myers-Montgomery, the design
properties each alpha promises (checked numerically), and pyDOE3 where it agrees."""

from itertools import combinations

import numpy as np
import pytest
from _design_helpers import block_orthogonality, multiset
from pyDOE3 import ccdesign

from rsm_lrg.design import ccd_alpha, central_composite


def space(k):
    return {f"x{i + 1}": (10.0, 20.0) for i in range(k)}


# NIST/SEMATECH e-Handbook 5.3.3.6.1, table "Determining alpha for rotatability":
# F = 2^k cube runs, alpha = F^(1/4): 1.414, 1.682, 2.000, 2.378 (3 decimals as printed).
@pytest.mark.parametrize("k,published", [(2, 1.414), (3, 1.682), (4, 2.000), (5, 2.378)])
def test_rotatable_alpha_matches_nist(k, published):
    assert ccd_alpha(k, "rotatable") == pytest.approx(published, abs=5e-4)
    d = central_composite(space(k), center=(2, 2), randomize=False)
    assert d.options["alpha"] == pytest.approx(published, abs=5e-4)


@pytest.mark.parametrize("k", [2, 3, 4, 5])
def test_rotatable_design_has_rotatable_moments(k):
    # Rotatability (Box & Hunter 1957): sum x_i^4 = 3 sum x_i^2 x_j^2 (relative 1e-9;
    # coded values are stored to 12 decimals).
    X = central_composite(space(k), alpha="rotatable", center=(3, 1), randomize=False).coded_runs
    for i, j in combinations(range(k), 2):
        assert np.sum(X[:, i] ** 4) == pytest.approx(3 * np.sum(X[:, i] ** 2 * X[:, j] ** 2), rel=1e-9)


def test_practical_alpha_is_fourth_root_of_k():
    # Design-Expert "practical" alpha = k^(1/4); k = 4 -> sqrt(2) exactly, k = 6 -> 1.565.
    assert ccd_alpha(4, "practical") == pytest.approx(2 ** 0.5, rel=1e-15)
    assert ccd_alpha(6, "practical") == pytest.approx(1.565, abs=5e-4)


# Myers, Montgomery & Anderson-Cook (2009), Eq. 7.13: orthogonal alpha
# (Q F / 4)^(1/4), Q = (sqrt(F + T) - sqrt(F))^2. k = 2 with one centre run gives the 3^2
# factorial (alpha = 1 exactly); k = 3 with one centre run gives 1.215 (3 decimals, the
# rule evaluated by hand: Q = (sqrt(15) - sqrt(8))^2 = 1.0911, (2 Q)^(1/4) = 1.2154).
# The property the rule promises is checked independently in the next test.
def test_orthogonal_alpha_textbook_values():
    assert ccd_alpha(2, "orthogonal", (1, 0)) == pytest.approx(1.0, abs=1e-12)
    assert ccd_alpha(3, "orthogonal", (1, 0)) == pytest.approx(1.215, abs=5e-4)


@pytest.mark.parametrize("k,center", [(2, (1, 0)), (2, (4, 4)), (3, (2, 3)), (4, (5, 0)), (5, (2, 2))])
def test_orthogonal_alpha_makes_quadratic_columns_orthogonal(k, center):
    X = central_composite(space(k), alpha="orthogonal", center=center, randomize=False).coded_runs
    Q = X ** 2 - (X ** 2).mean(axis=0)
    off = Q.T @ Q - np.diag(np.diag(Q.T @ Q))
    assert np.max(np.abs(off)) < 1e-9 * X.shape[0]


@pytest.mark.parametrize("k,center", [(2, (3, 3)), (3, (4, 2)), (4, (2, 2)), (5, (6, 1))])
def test_orthogonal_blocking_cube_and_star(k, center):
    d = central_composite(space(k), alpha="orthogonal", center=center, blocks=2, seed=3)
    assert d.n_blocks == 2
    assert block_orthogonality(d.coded_runs, d.blocks) < 1e-9
    # agrees with pyDOE3, whose "orthogonal" alpha is the orthogonal-blocking one
    ref = ccdesign(k, center=center, alpha="orthogonal", face="ccc")
    assert multiset(d.coded_runs) == multiset(np.round(ref, 12))


def test_montgomery_two_blocks_k2_is_rotatable_and_orthogonal():
    # Montgomery, Design and Analysis of Experiments (sec. "Blocking in response surface
    # designs"): k = 2, 3 centre runs per block -> alpha = 1.414 blocks orthogonally and is
    # rotatable (sqrt(2), exact).
    assert ccd_alpha(2, "orthogonal", (3, 3), blocked=True) == pytest.approx(2 ** 0.5, rel=1e-15)


@pytest.mark.parametrize("face,code", [("circumscribed", "ccc"), ("inscribed", "cci"), ("faced", "ccf")])
@pytest.mark.parametrize("k", [2, 3, 4])
def test_rotatable_runs_agree_with_pydoe3(face, code, k):
    d = central_composite(space(k), alpha="rotatable" if face != "faced" else None, face=face,
                          center=(2, 3), randomize=False)
    ref = ccdesign(k, center=(2, 3), alpha="rotatable", face=code)
    assert multiset(d.coded_runs) == multiset(ref)


def test_inscribed_puts_star_points_at_the_given_levels():
    d = central_composite({"t": (100.0, 200.0), "p": (1.0, 3.0)}, face="inscribed", center=(1, 0),
                          randomize=False)
    a = d.actual
    assert a["t"].min() == 100.0 and a["t"].max() == 200.0
    assert a["p"].min() == 1.0 and a["p"].max() == 3.0
    cube = d.coded_runs[:4]
    np.testing.assert_allclose(np.abs(cube), 1 / 2 ** 0.5, rtol=1e-11)


def test_circumscribed_star_points_go_beyond_the_levels():
    d = central_composite({"t": (100.0, 200.0), "p": (1.0, 3.0)}, center=(1, 0), randomize=False)
    assert d.actual["t"].min() == pytest.approx(150 - 50 * 2 ** 0.5, rel=1e-12)


def test_face_alpha_and_faced_agree():
    a = central_composite(space(3), alpha="face", center=(2, 0), randomize=False).coded_runs
    b = central_composite(space(3), face="faced", center=(2, 0), randomize=False).coded_runs
    np.testing.assert_array_equal(a, b)
    assert set(np.unique(a).tolist()) == {-1.0, 0.0, 1.0}


def test_numeric_alpha():
    d = central_composite(space(2), alpha=1.5, center=(0, 0), randomize=False)
    assert d.n_runs == 8 and np.max(np.abs(d.coded_runs)) == 1.5


def test_run_count_and_layout():
    d = central_composite(space(3), center=(4, 2), randomize=False)
    assert d.n_runs == 8 + 4 + 6 + 2
    assert d.n_center == 6
    # one number, unblocked: all centre runs together
    assert central_composite(space(3), center=5).n_runs == 8 + 6 + 5
    # one number, blocked: that many per block
    assert central_composite(space(3), center=2, blocks=2).n_runs == 8 + 6 + 4


@pytest.mark.parametrize("bad", [
    dict(alpha="steep"), dict(alpha=-1.0), dict(alpha=0), dict(face="round"),
    dict(blocks=3), dict(center=-1), dict(center=(1, -2)), dict(center=(1, 2, 3)),
    dict(face="faced", alpha=2.0),
])
def test_bad_options(bad):
    with pytest.raises(ValueError):
        central_composite(space(3), **bad)


def test_factor_count_limits():
    with pytest.raises(ValueError, match="2 to"):
        central_composite(space(1))
