"""The two-stage analysis of a definitive screening design (issue 35, item 5; Jones & Nachtsheim
2017): stage 1 recomputed in exact arithmetic from the fold-over pairs, stage 2 against a
brute-force search over full-data least-squares fits, recovery of known active effects in
simulated DSDs, and the refusals."""

import itertools
from fractions import Fraction

import numpy as np
import pytest

from rsm_lrg.design import definitive_screening
from rsm_lrg.model.choice.dsd import fold_over_pairs, two_stage

TRUTH = ("Intercept", "A", "C", "D", "AC", "D^2")


def _dsd(columns=8, used=6, center=3):
    """A DSD for ``columns`` factors (standard order: C, -C, centre runs) of which the first
    ``used`` are real; the others are fake factors."""
    d = definitive_screening([f"x{i}=-1:1" for i in range(columns)], center=center, randomize=False)
    return d.coded_runs[:, :used], [chr(ord("A") + i) for i in range(used)], d.options["conference_order"]


def _respond(X, seed, sd=1.0):
    rng = np.random.default_rng(seed)
    return (50 + 4 * X[:, 0] - 3 * X[:, 2] + 2.5 * X[:, 3] + 3 * X[:, 0] * X[:, 2] + 4 * X[:, 3] ** 2
            + rng.normal(0, sd, len(X)))


def test_stage1_equals_exact_arithmetic():
    X, letters, nc = _dsd()
    y = np.round(_respond(X, 7), 3)
    r = two_stage(X, y, letters, alpha=0.05)
    P, c = nc, len(X) - 2 * nc
    F = [Fraction(str(v)) for v in y.tolist()]
    xs = [[Fraction(int(v)) for v in row] for row in X.tolist()]
    diff = [F[i] - F[i + P] for i in range(P)]  # row i and row i + P are mirror runs by construction
    # C'C = (n - 1) I for the columns of a conference matrix: b_j = sum_i x_ij (y_i - y_i') / (2 (n - 1))
    b = [sum(xs[i][j] * diff[i] for i in range(P)) / (2 * (nc - 1)) for j in range(len(letters))]
    assert [row["estimate"] for row in r.stage1] == pytest.approx([float(v) for v in b], rel=1e-12, abs=1e-12)
    yc = F[2 * P:]
    ss_pe = sum((v - sum(yc) / c) ** 2 for v in yc)
    active = [j for j, row in enumerate(r.stage1) if row["active"]]
    assert [letters[j] for j in active] == ["A", "C", "D"]
    rss_odd = sum(d * d for d in diff) / 2 - sum(b[j] * sum(xs[i][j] * diff[i] for i in range(P)) for j in active)
    sigma2 = (rss_odd + ss_pe) / (P - len(active) + c - 1)
    assert r.stage1_df == P - len(active) + c - 1 == 7
    assert r.stage1_rmse ** 2 == pytest.approx(float(sigma2), rel=1e-12)
    assert (r.fake_df, r.pure_error_df, r.pairs, r.centre_runs) == (2, 2, 8, 3)


def test_stage2_equals_brute_force_full_data_fits():
    X, letters, nc = _dsd()
    y = _respond(X, 11)
    r = two_stage(X, y, letters, alpha=0.05)
    assert r.kept == TRUTH
    n, m = X.shape
    cand = {"AC": X[:, 0] * X[:, 2], "AD": X[:, 0] * X[:, 3], "CD": X[:, 2] * X[:, 3], "A^2": X[:, 0] ** 2,
            "C^2": X[:, 2] ** 2, "D^2": X[:, 3] ** 2}

    def rss(cols):
        Z = np.column_stack([np.ones(n), X, *cols])
        res = y - Z @ np.linalg.lstsq(Z, y, rcond=None)[0]
        return float(res @ res)

    base = rss([])  # every main effect in: the odd residual plus the even residual of the intercept
    yc = y[2 * nc:]
    ss_pe = float(np.sum((yc - yc.mean()) ** 2))
    for step in r.stage2:  # the best subset of each size, and its even-space RSS
        k = step["size"]
        best = min(rss([cand[t] for t in sub]) for sub in itertools.combinations(cand, k))
        got = sorted(step["terms"].split())
        assert rss([cand[t] for t in got]) == pytest.approx(best, rel=1e-10)
        assert step["rss"] + (base - _even_intercept_rss(y, nc)) == pytest.approx(rss([cand[t] for t in got]),
                                                                                 rel=1e-9)
    assert [s["size"] for s in r.stage2] == [0, 1, 2]
    assert r.stage2[-1]["p"] >= 0.05 and all(s["p"] < 0.05 for s in r.stage2[:-1])
    assert ss_pe > 0


def _even_intercept_rss(y, P):
    """Even-space residual of the intercept-only model, pure error left out: the pair sums and the
    centre mean about their weighted mean."""
    w = np.r_[(y[:P] + y[P:2 * P]) / np.sqrt(2), np.sqrt(len(y) - 2 * P) * y[2 * P:].mean()]
    s = np.r_[np.full(P, np.sqrt(2)), np.sqrt(len(y) - 2 * P)]
    a = (s @ w) / (s @ s)
    return float(np.sum((w - a * s) ** 2))


@pytest.mark.parametrize("columns, used, center, sd, stage1_rate, model_rate", [
    (8, 6, 3, 1.0, 0.75, 0.70),   # 2 fake factors + 2 pure-error df (Jones & Nachtsheim's advice): 81 %, 76 %
    (8, 8, 1, 1.0, 0.85, 0.55),   # no error df: Lenth's PSE in stage 1: 93 %, 64 %
    (8, 6, 3, 0.3, 0.75, 0.75),   # strong signal: 81 %, 79 % (the misses are alpha's false positives)
])
def test_recovers_known_active_effects(columns, used, center, sd, stage1_rate, model_rate):
    """100 simulated responses (4A - 3C + 2.5D + 3AC + 4D^2, sd ``sd``) at alpha 0.05: the share
    whose stage 1 is exactly A C D and whose model is exactly the truth; with a strong signal the
    true terms are never missed."""
    X, letters, _ = _dsd(columns, used, center)
    found1 = found = covered = 0
    for seed in range(100):
        r = two_stage(X, _respond(X, seed, sd), letters, alpha=0.05)
        found1 += [row["term"] for row in r.stage1 if row["active"]] == ["A", "C", "D"]
        found += r.kept == TRUTH
        covered += set(TRUTH) <= set(r.kept)
    assert found1 / 100 >= stage1_rate and found / 100 >= model_rate
    if sd < 1:
        assert covered == 100


def test_fold_over_pairs_and_refusals():
    X, letters, nc = _dsd()
    pairs, centres = fold_over_pairs(X[::-1])
    assert len(pairs) == 8 and len(centres) == 3
    with pytest.raises(ValueError, match="run 2 has no mirror run"):
        two_stage(np.delete(X, 8 + 1, axis=0)[::1], np.zeros(len(X) - 1), letters)
    with pytest.raises(ValueError, match="no active main effect"):
        two_stage(X, np.random.default_rng(0).normal(0, 1, len(X)) * 1e-3 + np.r_[np.zeros(len(X) - 1), 0.0],
                  letters, alpha=1e-9)
