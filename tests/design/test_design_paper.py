"""The paper's design (Su, Zhang & Yang 2023, Tables 3 and 4) is the published 4-factor
Box-Behnken design with 3 centre runs, and designs/paper-bbd4.csv holds it."""

from pathlib import Path

import numpy as np
import pandas as pd
from _design_helpers import multiset

from rsm_lrg.datasets import load_table4
from rsm_lrg.design import box_behnken, paper_design, read_design
from rsm_lrg.design.paper import PAPER_LEVELS

ROOT = Path(__file__).resolve().parents[2]
FACTORS = list(PAPER_LEVELS)


def test_table4_equals_bbd4_with_3_centres_as_a_multiset():
    # Table 4: 27 runs; Table 3: the levels. Exact equality of coded settings.
    t4 = load_table4()
    d = box_behnken(PAPER_LEVELS, center=3, randomize=False)
    coded_t4 = d.factors.encode(t4[FACTORS]).to_numpy()
    assert len(t4) == d.n_runs == 27
    assert multiset(coded_t4) == multiset(d.coded_runs)


def test_paper_design_keeps_the_papers_run_order():
    d = paper_design()
    t4 = load_table4()
    f = d.to_frame()
    assert f["run_order"].tolist() == t4["order"].tolist()
    pd.testing.assert_frame_equal(f[FACTORS], t4[FACTORS], check_exact=True, check_dtype=False)
    assert sorted(f["std_order"]) == list(range(1, 28))
    # each std_order points at the generator's run with the same settings
    gen = box_behnken(PAPER_LEVELS, center=3, randomize=False).standard_order().set_index("std_order")
    coded = [c for c in f.columns if c.startswith("coded_")]
    np.testing.assert_array_equal(gen.loc[f["std_order"], coded].to_numpy(), f[coded].to_numpy())


def test_designs_paper_bbd4_csv_is_regenerated_exactly():
    path = ROOT / "designs" / "paper-bbd4.csv"
    on_disk = path.read_text()
    assert on_disk == paper_design().to_frame().to_csv(index=False, lineterminator="\n")
    assert "tcr" not in on_disk.splitlines()[0]  # no response column
    r = read_design(path)
    assert r.factors.names == FACTORS
    assert [(f.low, f.high) for f in r.factors] == list(PAPER_LEVELS.values())


def test_a_run_that_is_not_in_the_design_is_named():
    import pytest

    t4 = load_table4().copy()
    t4.loc[6, "stroke_m"] = 0.04  # row 7 becomes (+1, -1, +1, 0): not a BBD run
    d = box_behnken(PAPER_LEVELS, center=3, randomize=False)
    with pytest.raises(ValueError, match="row 7"):
        d.with_runs_of(t4, run_order="order")
