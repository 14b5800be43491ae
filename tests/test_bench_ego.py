"""benchmarks/bench_ego.py's pooling of draws (issue 33): ``--merge`` of files with the same seeds
and other loop / DiceOptim draws gives the median over all (seed, draw) traces and the seed-by-seed
Wilcoxon comparison. Synthetic traces with known answers; nothing is run but the summary."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def bench():
    sys.path.insert(0, str(ROOT / "benchmarks"))
    try:
        import bench_ego
    finally:
        sys.path.remove(str(ROOT / "benchmarks"))
    return bench_ego


def test_pooled_median_is_over_every_seed_and_draw(bench):
    # 2 seeds x 3 draws x 2 steps: the median of the six values per step, not of the seeds' medians
    r = np.array([[[1.0, 10.0], [2.0, 20.0], [9.0, 30.0]],
                  [[3.0, 40.0], [4.0, 50.0], [8.0, 60.0]]])
    assert bench.pooled_median(r).tolist() == [3.5, 35.0]
    assert np.median(np.median(r, axis=1), axis=0).tolist() != [3.5, 35.0]


def _write(path: Path, seeds: dict, **offsets) -> str:
    path.write_text(json.dumps({**offsets, "traces": {"branin": seeds}}))
    return str(path)


def test_merge_pools_the_draws_and_compares_seed_by_seed(bench, tmp_path, capsys):
    fstar = bench.PROBLEMS["branin"][2]
    y0 = [0.0] * 8  # the same initial design in every file

    def trace(regret: float) -> list:  # a constant trace: its regret at every step
        return [fstar + regret] * 20

    seeds = range(1, 6)
    ours = {s: {"x0": [[0.0, 0.0]] * 8, "y0": y0, "loop": trace(s), "loop_draw_offset": 0,
                "random": trace(100.0), "random_uniform": trace(100.0), "lhs_quadratic": trace(100.0)}
            for s in seeds}
    loop2 = {s: {"x0": [[0.0, 0.0]] * 8, "y0": y0, "loop": trace(s + 2), "loop_draw_offset": 1000} for s in seeds}
    dice = {s: {"x0": [[0.0, 0.0]] * 8, "y0": y0, "diceoptim": trace(s + 1.5), "r_seed_offset": 0} for s in seeds}
    files = [_write(tmp_path / "a.json", ours, loop_draw_offset=0),
             _write(tmp_path / "b.json", loop2, loop_draw_offset=1000),
             _write(tmp_path / "c.json", dice, r_seed_offset=0)]
    out = tmp_path / "merged.json"
    assert bench.main(["--merge", *files, "--json", str(out)]) == 0
    s = json.loads(out.read_text())["summary"]["branin"]
    assert s["draws"] == {"loop": [0, 1000], "diceoptim": [0]}
    # loop: regrets 1..5 (draw 0) and 3..7 (draw 1000): the median of the ten is 4
    assert s["median_regret"]["loop"] == pytest.approx([4.0] * 20, abs=1e-12)
    assert s["median_regret_per_draw"]["loop"]["0"] == pytest.approx([3.0] * 20, abs=1e-12)
    assert s["median_regret_per_draw"]["loop"]["1000"] == pytest.approx([5.0] * 20, abs=1e-12)
    assert s["median_regret"]["diceoptim"] == pytest.approx([4.5] * 20, abs=1e-12)
    # each seed's mean over the loop's draws (s + 1) is 0.5 below DiceOptim's (s + 1.5): five of
    # five seeds ahead, exact two-sided signed-rank p = 2 / 2^5
    cmp = s["loop_vs_diceoptim"]
    assert cmp["loop_ahead"][8:] == [5] * 12 and cmp["diceoptim_ahead"][8:] == [0] * 12
    assert cmp["wilcoxon_p"][8:] == pytest.approx([0.0625] * 12)
    assert s["verdict"]["at_most_diceoptim"] is True and s["verdict"]["below_random"] is True
    printed = capsys.readouterr().out
    assert "loop@1000" in printed
    # the loop is below LHS + quadratic (regret 100) at every step: no step to test is listed
    assert "at the steps where the loop is not below: none" in printed
    assert s["loop_vs_lhs_quadratic"]["mann_whitney_p"][8] < 1e-2


def test_rank_sum_compares_the_seeds_means_unpaired(bench):
    from scipy.stats import mannwhitneyu

    rng = np.random.default_rng(3)
    a = rng.random((20, 4, 3))  # the loop: 4 draws, averaged per seed
    b = rng.random((20, 1, 3)) + np.array([0.0, 0.3, 1.5])  # LHS + quadratic: one draw
    p = bench.rank_sum(a, b)["p"]
    for t in range(3):
        assert p[t] == pytest.approx(mannwhitneyu(a[:, :, t].mean(axis=1), b[:, 0, t]).pvalue, rel=1e-12)
    assert p[2] < 1e-6 < p[0]  # samples a whole unit apart are told apart
    # the mean over draws, not their pooling: seeds whose draws average to b's values tie exactly
    q = rng.integers(0, 1000, (20, 1, 3)) / 8.0  # exact in binary: the means are exact too
    c = np.concatenate([q - 1.0, q + 1.0], axis=1)
    assert bench.rank_sum(c, q)["p"] == pytest.approx([1.0] * 3)
    assert bench.rank_sum(np.zeros((5, 2, 1)), np.zeros((5, 1, 1)))["p"] == [None]
    assert bench.rank_sum(np.zeros((5, 2, 1)), np.full((5, 1, 1), np.nan))["p"] == [None]


def test_merge_refuses_draws_that_differ_between_seeds(bench, tmp_path):
    fstar = bench.PROBLEMS["branin"][2]
    one = {s: {"x0": [[0.0, 0.0]] * 8, "y0": [0.0] * 8, "loop": [fstar + 1.0] * 20, "loop_draw_offset": 0}
           for s in (1, 2)}
    other = {1: {"x0": [[0.0, 0.0]] * 8, "y0": [0.0] * 8, "loop": [fstar + 2.0] * 20, "loop_draw_offset": 1000}}
    files = [_write(tmp_path / "a.json", one), _write(tmp_path / "b.json", other)]
    with pytest.raises(SystemExit, match="seed 2 has draws"):
        bench.main(["--merge", *files])
