"""Design evaluation: SPV at the centre against exact results (Box–Behnken intercept = centre
mean; Box & Hunter's closed form for rotatable CCDs), rotatability, VIF against statsmodels,
power by the noncentral F against a Monte-Carlo simulation and the orthogonal closed form."""

import numpy as np
import pytest
import statsmodels.api as sm
from scipy import stats
from statsmodels.stats.outliers_influence import variance_inflation_factor

import rsm_lrg
from rsm_lrg.design import read_design
from rsm_lrg.model.build.terms import design_matrix, model_terms
from rsm_lrg.model.evaluate import evaluate_design


def test_paper_bbd_spv_at_centre_is_n_over_n0():
    # In a Box–Behnken design b0 is the mean of the n0 centre runs (the paper's intercept
    # 0.03367 is the mean of 0.033, 0.034, 0.034), so SPV(0) = n / n0 = 27 / 3 = 9 exactly.
    e = evaluate_design(read_design("designs/paper-bbd4.csv"))
    assert e.spv_center == pytest.approx(9.0, rel=1e-12)
    assert e.df == {"model": 14, "residual": 12, "lack_of_fit": 10, "pure_error": 2, "blocks": 0}
    bbd3 = rsm_lrg.box_behnken({"a": (0, 1), "b": (0, 1), "c": (0, 1)}, center=3, randomize=False)
    assert evaluate_design(bbd3).spv_center == pytest.approx(15 / 3, rel=1e-12)
    # leverages sum to p (trace of the hat matrix)
    assert e.leverage.sum() == pytest.approx(15.0, rel=1e-12)
    # FDS curve is nondecreasing and brackets the region's SPV
    assert np.all(np.diff(e.fds.variance) >= 0)
    assert e.fds.spv.iloc[0] == pytest.approx(e.spv_region["min"]) and e.fds.spv.iloc[-1] == pytest.approx(e.spv_region["max"])


@pytest.mark.parametrize("k,n0", [(2, 5), (3, 6), (4, 7)])
def test_rotatable_ccd_spv_centre_closed_form_and_rotatability(k, n0):
    # Box & Hunter (1957) / Myers, Montgomery & Anderson-Cook Sec. 8.2: for a rotatable design
    # with moments λ2 = Σx²/N, λ4 = Σx_i²x_j²/N, SPV(0) = (k+2)λ4 / ((k+2)λ4 - kλ2²).
    # k = 2, n0 = 5 gives 2.6 (Var(b0) = 0.2σ², Montgomery Example 11.2).
    d = rsm_lrg.central_composite({f"x{i}": (-1, 1) for i in range(k)}, center=(n0, 0), randomize=False)
    X = d.coded_runs
    N = len(X)
    lam2 = np.sum(X[:, 0] ** 2) / N
    lam4 = np.sum(X[:, 0] ** 2 * X[:, 1] ** 2) / N
    ref = (k + 2) * lam4 / ((k + 2) * lam4 - k * lam2 ** 2)
    e = evaluate_design(d)
    assert e.spv_center == pytest.approx(ref, rel=1e-10)
    if k == 2:
        assert e.spv_center == pytest.approx(2.6, rel=1e-10)
    # rotatable: equal SPV on a sphere (1e-9)
    u = np.random.default_rng(0).normal(size=(50, k))
    u = 0.8 * u / np.linalg.norm(u, axis=1, keepdims=True)
    Z = design_matrix(u, model_terms(d.factors.letters, "quadratic"))
    Xm = design_matrix(X, model_terms(d.factors.letters, "quadratic"))
    v = N * np.einsum("ij,jk,ik->i", Z, np.linalg.inv(Xm.T @ Xm), Z)
    assert np.ptp(v) < 1e-9 * v.max()


def test_vif_matches_statsmodels():
    e = evaluate_design(read_design("designs/paper-bbd4.csv"))
    d = read_design("designs/paper-bbd4.csv")
    X = design_matrix(d.coded_runs, model_terms("ABCD", "quadratic"))
    for j, name in enumerate(e.terms.index):
        if j == 0:
            continue
        assert e.terms.loc[name, "vif"] == pytest.approx(variance_inflation_factor(X, j), rel=1e-9), name
    assert e.terms.loc["A^2", "vif"] == pytest.approx(1.25, rel=1e-12)


def test_power_noncentral_f_against_orthogonal_closed_form_and_simulation():
    d = rsm_lrg.full_factorial({"a": (-1, 1), "b": (-1, 1), "c": (-1, 1)}, levels=2, center=4, randomize=False)
    e = evaluate_design(d, "linear")
    # orthogonal 2^3 + 4 centres: C_jj = 1/8, λ = (2/2)² · 8 = 8, ν = 12 - 4 = 8
    ref = stats.ncf.sf(stats.f.ppf(0.95, 1, 8), 1, 8, 8.0)
    assert e.terms.loc["A", "power"] == pytest.approx(ref, rel=1e-12)
    # Monte-Carlo: effect of 2σ over -1..+1 (coefficient σ), 4000 data sets; 4 standard errors
    rng = np.random.default_rng(5)
    X = design_matrix(d.coded_runs, model_terms("ABC", "linear"))
    reps = 4000
    Y = X[:, [1]] * 1.0 + rng.normal(size=(len(X), reps))  # every column one data set
    beta, *_ = np.linalg.lstsq(X, Y, rcond=None)
    s2 = np.sum((Y - X @ beta) ** 2, axis=0) / (len(X) - 4)
    C11 = np.linalg.inv(X.T @ X)[1, 1]
    pvals = 2 * stats.t.sf(np.abs(beta[1] / np.sqrt(s2 * C11)), len(X) - 4)
    hits = int(np.sum(pvals < 0.05))
    # statsmodels on the first data set agrees with the vectorised t test
    assert sm.OLS(Y[:, 0], X).fit().pvalues[1] == pytest.approx(pvals[0], rel=1e-9)
    se = np.sqrt(ref * (1 - ref) / reps)
    assert hits / reps == pytest.approx(ref, abs=4 * se)


def test_aliased_model_is_reported():
    e = evaluate_design(read_design("designs/paper-bbd4.csv"), "cubic")
    assert e.aliased
    assert "Aliased" in e.summary()
    with pytest.raises(ValueError, match="region"):
        evaluate_design(read_design("designs/paper-bbd4.csv"), region="ball")


# --- maximum SPV over the region: exact boundary search (issue 10, item 13) -------------------

def _exact_spv(runs, terms):
    """x -> N f(x)'(X'X)^-1 f(x) in exact rational arithmetic (fractions.Fraction; (X'X)^-1 by
    Gauss-Jordan once)."""
    from fractions import Fraction as Fr

    def row(x):
        out = []
        for t in terms:
            v = Fr(1)
            for xi, pw in zip(x, t.powers):
                v *= Fr(xi) ** pw
            out.append(v)
        return out

    X = [row([Fr(v).limit_denominator(10**6) for v in r]) for r in runs]
    p = len(terms)
    A = [[sum(X[r][i] * X[r][j] for r in range(len(X))) for j in range(p)] + [Fr(int(i == j)) for j in range(p)]
         for i in range(p)]
    for c in range(p):
        piv = next(r for r in range(c, p) if A[r][c] != 0)
        A[c], A[piv] = A[piv], A[c]
        d = A[c][c]
        A[c] = [v / d for v in A[c]]
        for r in range(p):
            if r != c and A[r][c] != 0:
                f = A[r][c]
                A[r] = [a - f * b for a, b in zip(A[r], A[c])]
    Cinv = [r[p:] for r in A]
    N = len(runs)

    def spv(point):
        f = row(point)
        return N * sum(f[i] * sum(Cinv[i][j] * f[j] for j in range(p)) for i in range(p))

    return spv


def test_spv_max_2x2_plus_centre_linear_closed_form():
    # 2^2 + 1 centre, first-order model: X'X = diag(5, 4, 4), so SPV(x) = 5 (1/5 + (x1² + x2²)/4),
    # largest at the vertices: 5 (1/5 + 1/2) = 3.5 exactly (closed form). The interior Sobol
    # sample gave 3.4898 before the boundary search.
    X = np.array([[-1, -1], [1, -1], [-1, 1], [1, 1], [0, 0]], float)
    e = evaluate_design(X, "linear")
    assert e.spv_region["max"] == pytest.approx(3.5, rel=1e-12)
    assert [abs(v) for v in e.spv_max_at.values()] == [1.0, 1.0]
    assert e.fds.spv.iloc[-1] == pytest.approx(3.5, rel=1e-12)  # the FDS curve ends at the maximum
    assert e.g_efficiency == pytest.approx(3 / 3.5, rel=1e-12)   # p / max SPV (Myers et al. Sec. 8.2.1)


@pytest.mark.parametrize("name", ["fcd2", "bbd3"])
def test_spv_max_equals_exact_rational_boundary_grid(name):
    # Independent route: (X'X)^-1 in exact fractions and the SPV on a rational grid over every
    # face of the cube (step 1/10 in 3-D, 1/20 in 2-D; vertices and edge midpoints included).
    # 3^2 factorial (the face-centred CCD in 2 factors with one centre run), quadratic: max 29/4;
    # Box-Behnken, 3 factors, 3 centre runs: max 335/16 = 20.9375, at the vertices it never visits.
    import itertools
    from fractions import Fraction as Fr

    if name == "fcd2":
        runs = np.array(list(itertools.product([-1, 0, 1], repeat=2)), float)
        letters, step = "AB", 20
    else:
        runs = rsm_lrg.box_behnken({"a": (0, 1), "b": (0, 1), "c": (0, 1)}, center=3, randomize=False).coded_runs
        letters, step = "ABC", 10
    k = len(letters)
    terms = model_terms(letters, "quadratic")
    grid = [Fr(i, step) for i in range(-step, step + 1)]
    spv = _exact_spv(runs, terms)
    best = Fr(0)
    for axis in range(k):  # the faces x_axis = ±1 cover the whole boundary
        for s in (-1, 1):
            for rest in itertools.product(grid, repeat=k - 1):
                pt = list(rest[:axis]) + [Fr(s)] + list(rest[axis:])
                best = max(best, spv(pt))
    e = evaluate_design(runs, "quadratic")
    assert float(best) == pytest.approx({"fcd2": 29 / 4, "bbd3": 335 / 16}[name], rel=1e-15)
    assert e.spv_region["max"] == pytest.approx(float(best), rel=1e-12)
    at = [e.spv_max_at[L] for L in letters]
    assert float(spv([Fr(v).limit_denominator(10**6) for v in at])) == pytest.approx(
        e.spv_region["max"], rel=1e-12)


@pytest.mark.parametrize("seed", range(4))
def test_spv_max_is_never_below_a_dense_grid_for_random_designs(seed):
    # Random (irregular) designs put the maximum anywhere on the boundary, also inside an edge
    # or a face. A dense grid (201^2 in 2-D, 41^3 in 3-D, float) can only under-estimate the
    # maximum: the search must reach it (1e-12) and exceed it by no more than the grid
    # resolution allows (1e-2 relative).
    rng = np.random.default_rng(seed)
    k = 2 + seed % 2
    letters = "ABC"[:k]
    runs = rng.uniform(-1, 1, size=(12, k))
    terms = model_terms(letters, "quadratic")
    X = design_matrix(runs, terms)
    C = np.linalg.inv(X.T @ X)
    g = np.linspace(-1, 1, 201 if k == 2 else 41)
    P = np.array(np.meshgrid(*[g] * k)).reshape(k, -1).T
    Z = design_matrix(P, terms)
    grid_max = len(runs) * np.max(np.einsum("ij,jk,ik->i", Z, C, Z))
    e = evaluate_design(runs, "quadratic")
    assert e.spv_region["max"] >= grid_max * (1 - 1e-12)
    assert e.spv_region["max"] <= grid_max * (1 + 1e-2)
    x = np.array([e.spv_max_at[L] for L in letters])
    z = design_matrix(x[None, :], terms)[0]
    assert len(runs) * z @ C @ z == pytest.approx(e.spv_region["max"], rel=1e-12)


def test_replicated_2cubed_cubic_is_refused_naming_every_aliased_term():
    # Replicated 2^3 (16 runs, 8 distinct settings) cannot estimate the 20-term cubic model:
    # on ±1 levels x² = 1 and x³ = x, so the 12 terms A^2 .. C^3 are aliased (rank 8).
    import itertools

    runs = np.array(list(itertools.product([-1, 1], repeat=3)) * 2, float)
    e = evaluate_design(runs, "cubic")
    assert not e.estimable and e.rank == 8 and e.n_distinct == 8
    assert set(e.aliased) == {"A^2", "B^2", "C^2", "A^2B", "A^2C", "AB^2", "AC^2", "B^2C", "BC^2", "A^3", "B^3", "C^3"}
    assert "A^3 = A" in e.alias_relations and "A^2 = Intercept" in e.alias_relations
    assert all(v is None or v >= 0 for v in e.df.values())
    assert "-4" not in e.summary() and "A^3 = A" in e.summary()
    assert "A^3" in e.not_estimable_message()


def test_spv_max_over_the_ball_of_a_rotatable_ccd_equals_a_radial_search():
    # A rotatable CCD has SPV depending on the radius only (Box & Hunter 1957), so the maximum
    # over the ball |x| <= r (r = α = √2, the design's radius) is the maximum of SPV along one
    # axis on [0, r]: an independent 1-D dense search (20001 points, 1e-9 relative).
    d = rsm_lrg.central_composite({"a": (-1, 1), "b": (-1, 1)}, center=(5, 0), randomize=False)
    e = evaluate_design(d, region="sphere")
    terms = model_terms("AB", "quadratic")
    X = design_matrix(d.coded_runs, terms)
    C = np.linalg.inv(X.T @ X)
    r = np.max(np.linalg.norm(d.coded_runs, axis=1))
    rho = np.linspace(0, r, 20001)
    Z = design_matrix(np.column_stack([rho, np.zeros_like(rho)]), terms)
    ref = len(X) * np.max(np.einsum("ij,jk,ik->i", Z, C, Z))
    assert e.spv_region["max"] == pytest.approx(ref, rel=1e-9)
    assert np.hypot(*e.spv_max_at.values()) == pytest.approx(r, rel=1e-6)
