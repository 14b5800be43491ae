"""Mixture designs (issue 22, item 1): simplex lattice, simplex centroid, extreme vertices.

Checked against an independent enumeration in exact arithmetic (fractions.Fraction), against
R mixexp (SLD, SCD, Xvert; tests/design/data/mixexp_xvert.R and the CSVs it writes) and
against the published flare example of McLean & Anderson (1966), *Technometrics* 8, 447-454.
"""

import itertools
import math
from fractions import Fraction
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import rsm_lrg
from rsm_lrg.design import MixtureDesign, extreme_vertices, read_design, simplex_centroid, simplex_lattice
from rsm_lrg.design.mixture import lattice_size
from rsm_lrg.errors import ParameterError

DATA = Path(__file__).parent / "data"
FLARE = {"magnesium": (0.40, 0.60), "sodium_nitrate": (0.10, 0.50), "strontium_nitrate": (0.10, 0.50),
         "binder": (0.03, 0.08)}


def _rows(points) -> list[tuple]:
    return sorted(tuple(float(v) for v in r) for r in np.asarray(points, dtype=float))


def _same_sets(a, b, tol):
    """Two point sets (multisets) equal within ``tol`` (max norm), matched greedily after sorting."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    assert a.shape == b.shape, (a.shape, b.shape)
    left = list(range(len(b)))
    for p in a:
        d = [np.max(np.abs(b[j] - p)) for j in left]
        k = int(np.argmin(d))
        assert d[k] <= tol, (p, b[left[k]], d[k])
        left.pop(k)


def _exact_lattice(q: int, m: int, total: Fraction) -> list[tuple]:
    """All blends with proportions in {0, 1/m, ..., 1} summing to 1 (exact), scaled to the total."""
    pts = [tuple(total * Fraction(i, m) for i in c)
           for c in itertools.product(range(m + 1), repeat=q) if sum(c) == m]
    return sorted(tuple(float(v) for v in p) for p in pts)


@pytest.mark.parametrize("q,m", [(2, 1), (2, 4), (3, 1), (3, 2), (3, 3), (4, 2), (4, 3), (5, 4), (6, 2)])
@pytest.mark.parametrize("total", ["1", "100", "0.7"])
def test_lattice_equals_exact_enumeration(q, m, total):
    T = Fraction(float(total))  # the exact value of the float total the design is given
    d = simplex_lattice([f"x{i}" for i in range(q)], m, total=float(T), randomize=False)
    assert d.n_runs == lattice_size(q, m) == math.comb(q + m - 1, m)
    assert _rows(d.proportions) == _exact_lattice(q, m, T)  # each value T*i/m correctly rounded
    for row in d.proportions:
        assert abs(math.fsum(row) - float(T)) <= 1e-12 * float(T)
    # the coded columns are the L-pseudo components x / T (held to 12 decimals)
    assert np.allclose(d.coded_runs, d.proportions / float(T), atol=5e-13, rtol=0)


@pytest.mark.parametrize("q", [2, 3, 4, 5])
def test_lattice_center_and_axial_blends(q):
    names = [f"c{i}" for i in range(q)]
    plain = simplex_lattice(names, 2, randomize=False)
    d = simplex_lattice(names, 2, center=True, axial=True, total=2.0, randomize=False)
    assert d.n_runs == plain.n_runs + q + 1
    std = d.proportions[np.argsort(d.std_order)]
    extra = std[plain.n_runs:]
    for i in range(q):  # axial check blend i: (q+1)/2q of component i, 1/2q of the others
        want = [float(Fraction(2) * (Fraction(q + 1, 2 * q) if j == i else Fraction(1, 2 * q))) for j in range(q)]
        assert extra[i].tolist() == want
    assert extra[q].tolist() == [float(Fraction(2, q))] * q
    # the {q, 2} lattice holds the centroid itself when q divides 2; --center adds one more
    assert d.n_center == 1 + (2 % q == 0)
    assert {"axial", "centroid", "vertex"} <= set(d.point_types)
    for row in d.proportions:
        assert abs(math.fsum(row) - 2.0) <= 2e-12


@pytest.mark.parametrize("q", [2, 3, 4, 6])
def test_simplex_centroid_equals_subsets(q):
    d = simplex_centroid([f"x{i}" for i in range(q)], randomize=False)
    assert d.n_runs == 2 ** q - 1
    want = sorted(tuple(float(Fraction(1, len(S))) if j in S else 0.0 for j in range(q))
                  for r in range(1, q + 1) for S in itertools.combinations(range(q), r))
    assert _rows(d.proportions) == want
    assert d.n_center == 1
    ax = simplex_centroid([f"x{i}" for i in range(q)], axial=True, center=True, randomize=False)
    assert ax.n_runs == 2 ** q - 1 + q + 1 and ax.n_center == 2


def test_lattice_and_centroid_equal_r_mixexp():
    """R mixexp SLD(4, 3) and SCD(4), written by data/mixexp_xvert.R (15 significant digits)."""
    sld = pd.read_csv(DATA / "mixexp_sld.csv").to_numpy()
    scd = pd.read_csv(DATA / "mixexp_scd.csv").to_numpy()
    _same_sets(simplex_lattice(list("abcd"), 3, randomize=False).proportions, sld, 1e-14)
    _same_sets(simplex_centroid(list("abcd"), randomize=False).proportions, scd, 1e-14)


# McLean & Anderson (1966), Table 1: the eight vertices of the flare region (x1 magnesium,
# x2 sodium nitrate, x3 strontium nitrate, x4 binder)
PUBLISHED = [("0.40", "0.10", "0.47", "0.03"), ("0.40", "0.10", "0.42", "0.08"),
             ("0.60", "0.10", "0.27", "0.03"), ("0.60", "0.10", "0.22", "0.08"),
             ("0.40", "0.47", "0.10", "0.03"), ("0.40", "0.42", "0.10", "0.08"),
             ("0.60", "0.27", "0.10", "0.03"), ("0.60", "0.22", "0.10", "0.08")]


def test_flare_vertices_published_and_r():
    d = extreme_vertices(FLARE, randomize=False)
    assert d.n_runs == 8 and set(d.point_types) == {"vertex"}
    # the published vertices (to the float resolution of the decimal bounds), and exactly
    # the McLean-Anderson rule worked in rational arithmetic on the float bounds
    _same_sets(d.proportions, [[float(Fraction(v)) for v in r] for r in PUBLISHED], 1e-15)
    exact = _exact_vertices([Fraction(lo) for lo, _ in FLARE.values()], [Fraction(hi) for _, hi in FLARE.values()],
                            Fraction(1))
    assert _rows(d.proportions) == exact
    for row in d.proportions:
        assert abs(math.fsum(row) - 1.0) <= 1e-12
    # R mixexp's Xvert works in single precision: agreement to 1e-7
    xv = pd.read_csv(DATA / "mixexp_xvert.csv")
    _same_sets(d.proportions, xv[xv["dimen"] == 0][["x1", "x2", "x3", "x4"]].to_numpy(), 1e-7)
    assert "implied bounds" in d.summary() and "sodium_nitrate 0.1..0.47" in d.summary()
    # L-pseudo coding on the implied lower bounds (here the given ones): (x - L) / (1 - 0.63)
    L = np.array([0.40, 0.10, 0.10, 0.03])
    assert np.allclose(d.coded_runs, (d.proportions - L) / 0.37, atol=1e-12, rtol=0)


def test_flare_in_percent_is_exact():
    """The same region in percent (total 100): every vertex is a whole number, exactly."""
    pct = {k: (round(100 * a), round(100 * b)) for k, (a, b) in FLARE.items()}
    d = extreme_vertices(pct, total=100, randomize=False)
    assert _rows(d.proportions) == sorted(tuple(float(Fraction(v) * 100) for v in r) for r in PUBLISHED)
    assert all(math.fsum(r) == 100.0 for r in d.proportions)


def test_flare_centroids_equal_r_mixexp():
    """Vertices + 12 edge centroids + 6 constraint-plane centroids + overall centroid, as Xvert
    with ndm = 2 (for q = 4 the constraint planes are the 2-dimensional faces)."""
    d = extreme_vertices(FLARE, centroids=True, randomize=False)
    xv = pd.read_csv(DATA / "mixexp_xvert_centroids.csv")
    assert d.n_runs == len(xv) == 27
    kinds = {"vertex": 0, "edge": 1, "plane": 2, "centroid": 3}
    for kind, dim in kinds.items():
        mine = d.proportions[[t == kind for t in d.point_types]]
        _same_sets(mine, xv[xv["dimen"] == dim][["x1", "x2", "x3", "x4"]].to_numpy(), 1e-7)
    # every centroid is the exact average of the vertices on its face: the overall centroid
    V = [[Fraction(v) for v in r] for r in PUBLISHED]
    centre = [float(sum(col, Fraction(0)) / 8) for col in zip(*V)]
    assert d.proportions[[t == "centroid" for t in d.point_types]][0].tolist() == centre
    assert d.n_center == 1


def test_three_components_centroids_not_repeated():
    """q = 3: the constraint planes are the edges, so plane centroids are edge centroids and
    are not repeated."""
    d = extreme_vertices({"a": (0.1, 0.6), "b": (0.2, 0.7), "c": (0.0, 0.5)}, centroids=True, randomize=False)
    nv = d.options["n_vertices"]
    assert d.n_runs == 2 * nv + 1 and "plane" not in d.point_types
    assert len(set(map(tuple, d.proportions.tolist()))) == d.n_runs


def _exact_vertices(L, U, T):
    """McLean & Anderson's rule in exact arithmetic: every component but one at a bound, the
    remaining one taking the rest of the total when that lies within its bounds."""
    q = len(L)
    out = set()
    for j in range(q):
        others = [i for i in range(q) if i != j]
        for choice in itertools.product((0, 1), repeat=q - 1):
            x = [None] * q
            for i, c in zip(others, choice):
                x[i] = (L[i], U[i])[c]
            x[j] = T - sum(x[i] for i in others)
            if L[j] <= x[j] <= U[j]:
                out.add(tuple(x))
    return sorted(tuple(float(v) for v in p) for p in out)


frac = st.integers(0, 100).map(lambda k: Fraction(k, 100))


@st.composite
def bounded_regions(draw, max_q=5):
    q = draw(st.integers(3, max_q))
    L, U = [], []
    for _ in range(q):
        a, b = sorted(draw(st.lists(frac, min_size=2, max_size=2, unique=True)))
        L.append(a)
        U.append(b)
    T = Fraction(1)
    if sum(L) >= T or sum(U) <= T:
        from hypothesis import reject
        reject()
    return L, U


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(bounded_regions())
def test_bounds_only_vertices_equal_exact_rule(region):
    L, U = region
    q = len(L)
    bounds = {f"x{i}": (float(a), float(b)) for i, (a, b) in enumerate(zip(L, U))}
    want = np.array(_exact_vertices(L, U, Fraction(1)))
    rank = np.linalg.matrix_rank(want[1:] - want[0], tol=1e-9) if len(want) > 1 else 0
    if rank < q - 1:  # a region without interior is refused
        with pytest.raises(ValueError, match="no interior"):
            extreme_vertices(bounds, randomize=False)
        return
    d = extreme_vertices(bounds, randomize=False)
    _same_sets(d.proportions, want, 1e-12)
    for row in d.proportions:
        assert abs(math.fsum(row) - 1.0) <= 1e-12


@st.composite
def constrained_regions(draw):
    L, U = draw(bounded_regions(max_q=4))
    q = len(L)
    coef = draw(st.lists(st.integers(-3, 3), min_size=q, max_size=q).filter(any))
    rhs = draw(st.integers(-2, 4)) / 4
    return L, U, coef, rhs


@settings(max_examples=50, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(constrained_regions(), st.integers(0, 2 ** 16))
def test_vertices_feasible_active_and_hull(region, seed):
    """Every vertex is feasible with q - 1 independent active planes (besides the sum), and
    every feasible random blend is a convex combination of the vertices."""
    from scipy.optimize import linprog

    L, U, coef, rhs = region
    q = len(L)
    names = [f"x{i}" for i in range(q)]
    expr = " + ".join(f"{c}*{n}" for c, n in zip(coef, names)) + f" <= {rhs}"
    bounds = {n: (float(a), float(b)) for n, a, b in zip(names, L, U)}
    try:
        d = extreme_vertices(bounds, constraints=[expr], randomize=False)
    except ValueError as exc:
        assert "empty" in str(exc) or "no interior" in str(exc)
        return
    Lf, Uf = np.array([float(v) for v in L]), np.array([float(v) for v in U])
    G = np.vstack([-np.eye(q), np.eye(q), np.array(coef, dtype=float)[None, :]])
    h = np.concatenate([-Lf, Uf, [rhs]])
    V = d.proportions
    for v in V:
        assert abs(math.fsum(v) - 1.0) <= 1e-12
        slack = h - G @ v
        assert np.all(slack >= -1e-9)
        active = np.abs(slack) <= 1e-9
        assert np.linalg.matrix_rank(np.vstack([np.ones(q), G[active]])) == q
    rng = np.random.default_rng(seed)
    pts = rng.dirichlet(np.ones(q), size=400)
    pts = pts[np.all(pts @ G.T <= h - 1e-9, axis=1)]
    for p in pts[:10]:
        res = linprog(np.zeros(len(V)), A_eq=np.vstack([V.T, np.ones(len(V))]), b_eq=np.append(p, 1.0),
                      bounds=[(0, None)] * len(V), method="highs")
        assert res.status == 0, p
        assert np.all(p >= V.min(axis=0) - 1e-9) and np.all(p <= V.max(axis=0) + 1e-9)


def test_linear_constraint_vertices_exact():
    """Three components, 0.1 <= a, b, c <= 0.7 and a + b <= 0.6: a hexagon cut to a
    pentagon; vertices worked by hand."""
    d = extreme_vertices({"a": (0.1, 0.7), "b": (0.1, 0.7), "c": (0.1, 0.7)}, constraints=["a + b <= 0.6"],
                         randomize=False)
    want = [(0.1, 0.1, 0.8), (0.1, 0.2, 0.7), (0.2, 0.1, 0.7), (0.1, 0.5, 0.4), (0.5, 0.1, 0.4)]
    want = [w for w in want if w[2] <= 0.7]  # (0.1, 0.1, 0.8) breaks c <= 0.7
    _same_sets(d.proportions, want, 1e-15)
    assert "constraints: a + b <= 0.6" in d.summary()


def test_errors_name_the_component():
    with pytest.raises(ValueError, match="'b': LOW 0.5 is above HIGH 0.2"):
        extreme_vertices({"a": (0, 1), "b": (0.5, 0.2)})
    with pytest.raises(ValueError, match="lower bounds sum to 1.1"):
        extreme_vertices({"a": (0.6, 0.9), "b": (0.5, 0.9)})
    with pytest.raises(ValueError, match="upper bounds sum to 0.7"):
        extreme_vertices({"a": (0.0, 0.3), "b": (0.0, 0.4)})
    with pytest.raises(ValueError, match="'a': LOW -0.1 is negative"):
        extreme_vertices({"a": (-0.1, 0.5), "b": (0, 1)})
    with pytest.raises(ValueError, match="no interior"):
        extreme_vertices({"a": (0.5, 0.9), "b": (0.5, 0.9), "c": (0.0, 0.5)})
    with pytest.raises(ValueError, match="not linear"):
        extreme_vertices({"a": (0, 1), "b": (0, 1)}, constraints=["a*b <= 0.1"])
    with pytest.raises(ValueError, match="given twice"):
        simplex_lattice(["a", "a"], 2)
    with pytest.raises(ValueError, match="at least 2 components"):
        simplex_centroid(["a"])
    with pytest.raises(ValueError, match="degree must be at least 1"):
        simplex_lattice(["a", "b"], 0)
    with pytest.raises(ParameterError, match="lattice has 92378 points") as info:
        simplex_lattice([f"x{i}" for i in range(10)], 10)
    assert info.value.parameter == "runs"


def test_run_order_seed_and_csv(tmp_path):
    a = simplex_lattice(["a", "b", "c"], 3, seed=7)
    b = simplex_lattice(["a", "b", "c"], 3, seed=7)
    assert a.csv_text() == b.csv_text() and a.options["seed"] == 7
    assert sorted(a.std_order.tolist()) == list(range(1, 11)) and a.run_order.tolist() == list(range(1, 11))
    s = simplex_lattice(["a", "b", "c"], 3, randomize=False)
    assert s.std_order.tolist() == list(range(1, 11)) and "standard order" in s.summary()
    p = tmp_path / "lat.csv"
    a.to_csv(p)
    df = pd.read_csv(p)
    assert list(df.columns) == ["std_order", "run_order", "coded_A", "coded_B", "coded_C", "a", "b", "c"]
    assert np.array_equal(df[["a", "b", "c"]].to_numpy(), a.proportions)  # full precision
    back = read_design(p)
    assert back.n_runs == 10 and back.factors.names == ["a", "b", "c"]
    assert np.allclose(back.actual.to_numpy(), a.proportions, atol=1e-12, rtol=0)


def test_facade_names():
    assert rsm_lrg.simplex_lattice is simplex_lattice
    assert rsm_lrg.simplex_centroid is simplex_centroid
    assert rsm_lrg.extreme_vertices is extreme_vertices
    assert isinstance(rsm_lrg.extreme_vertices(FLARE, randomize=False), MixtureDesign)
