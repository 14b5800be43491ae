"""``rsm-lrg design optimal --component ... --blocks N [--block-size ...]`` (issue 35, item 3):
the blocked D-optimal mixture design written with its ``block`` column, then ``fit --block``
on it; bad blocking options give exit 2 and one ``error:`` line naming the option."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from _cli_errors import error_line

from rsm_lrg.cli import main

COMPS = ["--component", "a=0.1:0.8", "--component", "b=0.1:0.8", "--component", "c=0:0.5"]
CONS = ["--constraint", "a + b <= 0.85"]


def test_blocked_mixture_process_design_then_fit(tmp_path, capsys):
    p = tmp_path / "blocked.csv"
    argv = ["design", "optimal", *COMPS, *CONS, "--factor", "temp=20:40", "--model", "mixture-linear",
            "--blocks", "3", "--block-size", "6,6,5", "--seed", "2", "--starts", "3", "-o", str(p)]
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "17 runs" in out and "3 blocks" in out and "beside 2 block contrasts" in out
    d = pd.read_csv(p)
    assert list(d.columns[:3]) == ["std_order", "run_order", "block"]
    assert d.groupby("block").size().tolist() == [6, 6, 5]
    assert d.block.is_monotonic_increasing and sorted(d.run_order) == list(range(1, 18))
    rng = np.random.default_rng(1)
    d["y"] = 5 * d.a + 7 * d.b + 3 * d.c + 0.01 * d.temp * d.a + d.block + rng.normal(0, 0.05, len(d))
    data = tmp_path / "data.csv"
    d.to_csv(data, index=False)
    assert main(["fit", str(data), "--response", "y", "--component", "a", "--component", "b", "--component", "c",
                 "--factor", "temp", "--model", "mixture-linear", "--block", "block"]) == 0
    text = capsys.readouterr().out
    assert "blocks: block (3)" in text and "Block effects (sum to zero)" in text


def test_default_criterion_with_blocks_is_d_and_runs_default(tmp_path, capsys):
    p = tmp_path / "b.csv"
    assert main(["design", "optimal", *COMPS, *CONS, "--blocks", "2", "--seed", "1", "--starts", "2", "-o",
                 str(p)]) == 0
    assert "D-optimal for the mixture-quadratic model" in capsys.readouterr().out
    assert len(pd.read_csv(p)) == 6 + 1 + 10


@pytest.mark.parametrize("extra, message", [
    (["--blocks", "2", "--criterion", "I"], "error: --criterion: a blocked mixture design is D-optimal"),
    (["--blocks", "2", "--runs", "14", "--block-size", "7,6"], "error: --block-size: the block sizes sum to 13"),
    (["--block-size", "7"], "error: --block-size: give the number of blocks too"),
    (["--blocks", "2", "--block-size", "7,x"], "error: --block-size: expected a whole number"),
    (["--blocks", "2", "--runs", "6"], "error: --runs: 6 runs cannot support"),
    (["--blocks", "2", "--lack-of-fit", "2"], "error: --lof-points: lack-of-fit points are not set apart"),
    (["--blocks", "1"], "--blocks: expected a whole number >= 2"),
])
def test_bad_blocking_options(tmp_path, capsys, extra, message):
    p = tmp_path / "x.csv"
    try:
        rc = main(["design", "optimal", *COMPS, *extra, "--seed", "1", "-o", str(p)])
    except SystemExit as exc:  # argparse's own check of --blocks
        rc = exc.code
    assert message in error_line(capsys, rc)
    assert not p.exists()


def test_blocks_need_components(tmp_path, capsys):
    rc = main(["design", "optimal", "--factor", "x=0:1", "--factor", "y=0:1", "--blocks", "2", "-o",
               str(tmp_path / "x.csv")])
    assert "error: --blocks: blocks in an optimal design are available for mixtures" in error_line(capsys, rc)
