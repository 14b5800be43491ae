"""Response-surface designs crossed with categoric factors (issue 12, item 2) and the CSV
round trip (read_design and the fit's factor inference)."""

import numpy as np
import pandas as pd
import pytest

from rsm_lrg.design import box_behnken, central_composite, full_factorial, read_design
from rsm_lrg.factors import choose_factors

NUM3 = ["a=0:1", "b=10:20", "c=-1:1"]


@pytest.mark.parametrize("make, n_numeric", [
    (lambda f: box_behnken(f, center=3, seed=1), 15),
    (lambda f: central_composite(f, center=(2, 2), seed=1), 8 + 2 + 6 + 2),
    (lambda f: full_factorial(f, levels=3, seed=1), 27),
])
def test_every_combination_runs_the_whole_numeric_design(make, n_numeric):
    d = make(NUM3 + ["stage=cat:rfcms,rms", "oil=cat:x,y,z"])
    # Design-Expert's layout: the numeric design at each of the 2 x 3 level combinations
    assert d.n_runs == 6 * n_numeric
    num = make(NUM3)
    ref = sorted(map(tuple, num.coded_runs))
    for s in range(2):
        for o in range(3):
            rows = d.coded_runs[(d.coded_runs[:, 3] == s) & (d.coded_runs[:, 4] == o)][:, :3]
            assert sorted(map(tuple, rows)) == ref
    # centre points per combination
    assert d.n_center == 6 * num.n_center


def test_csv_carries_levels_as_text_and_round_trips(tmp_path):
    d = box_behnken(NUM3 + ["stage=cat:rms,rfcms"], center=2, seed=4)
    p = tmp_path / "d.csv"
    d.to_csv(p)
    df = pd.read_csv(p)
    assert list(df.columns)[-1] == "stage" and "coded_D" in df.columns
    assert (df["coded_D"] == df["stage"]).all() and set(df["stage"]) == {"rms", "rfcms"}
    back = read_design(p)
    f = back.factors["stage"]
    assert f.kind == "categoric" and f.levels == ("rms", "rfcms")  # order of the design (std_order)
    np.testing.assert_array_equal(back.coded_runs, d.coded_runs)
    assert back.std_order.tolist() == d.std_order.tolist()
    # the fit's inference finds the same factors from the coded columns
    ch = choose_factors(df.assign(y=np.arange(len(df), dtype=float)), exclude={"y"})
    assert ch.how == "design"
    assert [g.kind for g in ch.space] == ["numeric"] * 3 + ["categoric"]
    assert ch.space["stage"].levels == ("rms", "rfcms")
    assert [(g.low, g.high) for g in ch.space.numeric] == [(0, 1), (10, 20), (-1, 1)]


def test_blocks_are_kept_across_combinations():
    d = box_behnken(["a=0:1", "b=0:1", "c=0:1", "d=0:1", "s=cat:p,q"], blocks=3, center=1, seed=2)
    assert d.n_blocks == 3 and d.n_runs == 2 * (24 + 3)
    # run order: blocks in order, each block holds both levels
    assert np.all(np.diff(d.blocks) >= 0)
    for b in (1, 2, 3):
        assert set(d.coded_runs[d.blocks == b, 4]) == {0.0, 1.0}


def test_mismatched_level_columns_are_refused(tmp_path):
    d = box_behnken(NUM3 + ["stage=cat:rfcms,rms"], center=1, seed=1)
    df = d.to_frame()
    df.loc[3, "stage"] = "rms" if df.loc[3, "stage"] == "rfcms" else "rfcms"
    p = tmp_path / "bad.csv"
    df.to_csv(p, index=False)
    with pytest.raises(ValueError, match="row 4"):
        read_design(p)
