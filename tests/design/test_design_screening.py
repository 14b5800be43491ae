"""Definitive screening designs (every m from 4 to 24), conference matrices, fractional
factorials with their aliases, Plackett-Burman."""

import itertools

import numpy as np
import pytest

from rsm_lrg.design.screening import (
    alias_groups,
    alias_matrix,
    conference_matrix,
    conference_order,
    definitive_screening,
    fractional_factorial,
    plackett_burman,
)

# Orders with a conference matrix among 4..24: every even order but 22 (Belevitch 1950:
# order n = 2 mod 4 needs n - 1 to be a sum of two squares; 21 is not).
EXACT = {4, 6, 8, 10, 12, 14, 16, 18, 20, 24}


@pytest.mark.parametrize("n", sorted(EXACT))
def test_conference_matrices_are_exact(n):
    C = conference_matrix(n)
    assert np.all(np.diag(C) == 0)
    assert np.array_equal(C.T @ C, (n - 1) * np.eye(n, dtype=int))  # exact integers


def test_no_order_22():
    with pytest.raises(ValueError, match="22"):
        conference_matrix(22)


@pytest.mark.parametrize("m", range(4, 25))
def test_definitive_screening_properties(m):
    # Jones & Nachtsheim (2011), JQT 43(1): three levels, orthogonal main effects, mains
    # orthogonal to 2FIs and squares, 2m + 1 runs when a conference matrix of order m exists
    d = definitive_screening([f"x{i}=0:1" for i in range(m)], randomize=False)
    X = d.coded_runs
    n_conf = conference_order(m)
    assert d.n_runs == 2 * n_conf + 1
    if m in EXACT:
        assert d.n_runs == 2 * m + 1
    else:  # odd m (next even order) or m = 22 (order 24): columns dropped
        assert n_conf == (m + 1 if m + 1 in EXACT else 24)
    for j in range(m):
        assert set(X[:, j].tolist()) == {-1.0, 0.0, 1.0}
    XtX = X.T @ X
    assert np.array_equal(XtX, np.diag(np.diag(XtX)))  # main effects mutually orthogonal (exact)
    for j in range(m):  # each main effect against every 2FI and every pure square: exactly 0
        others = [X[:, a] * X[:, b] for a, b in itertools.combinations(range(m), 2)]
        others += [X[:, a] ** 2 for a in range(m)]
        assert all(float(X[:, j] @ o) == 0.0 for o in others)


def test_fractional_factorial_aliases_and_resolution():
    # 2^(4-1) with D = ABC: resolution IV, 2FIs aliased in pairs (Montgomery, Design and
    # Analysis of Experiments, 8th ed., section 8.2)
    d = fractional_factorial(["a=0:1", "b=0:1", "c=0:1", "d=0:1"], generators="A B C ABC", randomize=False)
    assert d.n_runs == 8 and d.options["resolution"] == 4
    groups = [g for g in d.options["aliases"] if len(g) > 1]
    assert sorted(map(sorted, groups)) == [["AB", "CD"], ["AC", "BD"], ["AD", "BC"]]
    r3 = fractional_factorial([f"x{i}=0:1" for i in range(5)], resolution=3, randomize=False)
    assert r3.n_runs == 8 and r3.options["resolution"] == 3
    with pytest.raises(ValueError, match="not a factor letter"):
        fractional_factorial(["a=0:1", "b=0:1", "c=0:1"], generators="A B Z")


def test_alias_matrix_matches_alias_groups():
    d = fractional_factorial(["a=0:1", "b=0:1", "c=0:1"], generators="A B AB", randomize=False)
    A, fitted, potential = alias_matrix(d.coded_runs, "ABC", "linear", "2fi")
    # C = AB: the estimate of C is biased by all of AB; A by BC; B by AC
    assert A[fitted.index("C"), potential.index("AB")] == pytest.approx(1.0)
    assert A[fitted.index("A"), potential.index("BC")] == pytest.approx(1.0)
    assert ["C", "AB"] in alias_groups(d.coded_runs, "ABC")


def test_plackett_burman_orthogonal():
    d = plackett_burman([f"x{i}=0:1" for i in range(11)], randomize=False)
    X = d.coded_runs
    assert d.n_runs == 12 and np.array_equal(X.T @ X, 12 * np.eye(11))


def test_definitive_screening_with_two_level_categoric_factors():
    # Jones & Nachtsheim (2013), JQT 45(2): numeric mains still orthogonal to each other and
    # every main effect (categoric as -1/+1) orthogonal to 2FIs and numeric squares
    d = definitive_screening([f"x{i}=0:1" for i in range(6)] + ["g=cat:p,q", "h=cat:u,v"], randomize=False)
    assert d.n_runs == 2 * 8 + 2
    X = d.coded_runs.copy()
    X[:, 6:] = 2 * X[:, 6:] - 1
    assert set(X[:, 6].tolist()) == {-1.0, 1.0}
    num = X[:, :6]
    G = num.T @ num
    assert np.array_equal(G, np.diag(np.diag(G)))
    for j in range(8):
        others = [X[:, a] * X[:, b] for a, b in itertools.combinations(range(8), 2)]
        others += [X[:, a] ** 2 for a in range(6)]
        assert all(float(X[:, j] @ o) == 0.0 for o in others)
    assert sorted(d.to_frame()["g"].value_counts().tolist()) == [9, 9]


@pytest.mark.parametrize("k", list(range(2, 48)) + [51, 59, 67, 71, 75, 83, 87, 99])
def test_plackett_burman_every_size(k):
    # N = the smallest multiple of 4 above k (Plackett & Burman 1946 give N = 4..100 but 92);
    # pyDOE3 built only N = 2^e, 12 * 2^e and 20 * 2^e and refused 24 to 27 factors (N = 28).
    # Exact integers: X'X = N I, every column balanced.
    d = plackett_burman([f"x{i}=0:1" for i in range(k)], randomize=False)
    X = d.coded_runs
    n = 4 * (k // 4 + 1)
    assert d.n_runs == n and np.array_equal(X.T @ X, n * np.eye(k)) and not X.sum(axis=0).any()


def test_plackett_burman_published_rows():
    # the first rows of Plackett & Burman (1946), Table 1, as printed by Montgomery (2013),
    # Table 8.22, then the cyclic shifts and a row of minus signs
    rows = {11: "++-+++---+-", 19: "++--++++-+-+----++-", 23: "+++++-+-++--++--+-+----"}
    for k, first in rows.items():
        X = plackett_burman([f"x{i}=0:1" for i in range(k)], randomize=False).coded_runs
        g = np.array([1.0 if c == "+" else -1.0 for c in first])
        assert np.array_equal(X[0], g) and np.array_equal(X[1], np.roll(g, 1))
        assert np.array_equal(X[-1], -np.ones(k))


def test_hadamard_orders_and_the_gap():
    from rsm_lrg.design.screening import hadamard_matrix

    for n in [1, 2] + list(range(4, 101, 4)):
        if n == 92:
            continue
        H = hadamard_matrix(n)
        assert np.array_equal(H @ H.T, n * np.eye(n, dtype=int)) and set(np.unique(H)) <= {-1, 1}
    with pytest.raises(ValueError, match="order 92"):
        hadamard_matrix(92)
    with pytest.raises(ValueError, match="92 runs"):
        plackett_burman([f"x{i}=0:1" for i in range(90)])
