"""``rsm-lrg design augment --method optimal --new-block``: the D-optimal added runs account for
the block effect (the same runs as the library call), the original rows are kept, and a
too-small new block is a ``--runs`` error."""

import numpy as np
import pandas as pd

from rsm_lrg.cli import main
from rsm_lrg.design import read_design
from rsm_lrg.design.augment import augment


def _square(tmp_path):
    base = tmp_path / "ff.csv"
    assert main(["design", "full-factorial", "--factor", "a=0:1", "--factor", "b=0:1", "--levels", "2",
                 "--center", "1", "--no-randomize", "-o", str(base)]) == 0
    return base


def test_new_block_optimal_augment_through_the_cli(tmp_path, capsys):
    base = _square(tmp_path)
    out = tmp_path / "aug.csv"
    assert main(["design", "augment", str(base), "--method", "optimal", "--criterion", "D", "--runs", "3",
                 "--new-block", "--seed", "1", "--starts", "3", "-o", str(out)]) == 0
    aug = pd.read_csv(out)
    df = pd.read_csv(base)
    assert aug["block"].tolist() == [1] * 5 + [2] * 3
    pd.testing.assert_frame_equal(aug.iloc[:5].drop(columns="block"), df, check_dtype=False)
    d = read_design(out)
    lib = augment(read_design(base), "optimal", model="quadratic", criterion="D", runs=3, new_block=True,
                  seed=1, starts=3)
    got = sorted(map(tuple, np.round(d.coded_runs[5:], 6).tolist()))
    want = sorted(map(tuple, np.round(lib.coded_runs[5:], 6).tolist()))
    assert got == want and lib.options["block_aware"] is True


def test_a_new_block_too_small_for_the_model_is_a_runs_error(tmp_path, capsys):
    base = _square(tmp_path)
    out = tmp_path / "aug.csv"
    # 5 runs + 1 added: the quadratic's 6 terms would fit, but not with the block effect (7)
    assert main(["design", "augment", str(base), "--method", "optimal", "--runs", "1", "--new-block",
                 "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: --runs: ") and "block effect" in err[0]
    assert not out.exists()
