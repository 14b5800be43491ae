"""``rsm-lrg design split-plot-ccd``: through rsm_lrg.cli.main; the CSV read back is the
equivalent-estimation design; bad input exits 2 with one line naming the option and writes nothing."""

import numpy as np
import pytest

from rsm_lrg.cli import main
from rsm_lrg.design import read_design

FACTORS = ["--factor", "thickness_m=0.0001:0.0005", "--factor", "stroke_m=0.04:0.06",
           "--factor", "velocity_m_s=0.4:0.6"]


def test_writes_the_design_with_whole_plots(tmp_path, capsys):
    out = tmp_path / "d.csv"
    assert main(["design", "split-plot-ccd", *FACTORS, "--hard-to-change", "thickness_m", "--center-whole-plots", "2",
                 "--seed", "4", "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "star distance 1.73205 whole plot, 1.73205 sub-plot" in text and "6 whole plots (5 runs each)" in text
    d = read_design(out)
    assert d.n_runs == 30 and d.whole_plots is not None
    thick = d.coded_runs[:, 0]
    for b in np.unique(d.whole_plots):
        assert np.ptp(thick[d.whole_plots == b]) == 0.0


@pytest.mark.parametrize("args, needle", [
    (["--hard-to-change", "thickness_m", "--alpha", "0.9"], "--alpha: the whole-plot star distance must exceed"),
    (["--hard-to-change", "thick"], "--hard-to-change: 'thick' is not among the factors"),
    (["--hard-to-change", "thickness_m", "--hard-to-change", "stroke_m", "--hard-to-change", "velocity_m_s"],
     "--hard-to-change: a split-plot central composite design needs 1 to 5 hard-to-change and 1 to 5 other"),
])
def test_bad_input_exits_2_and_writes_nothing(tmp_path, capsys, args, needle):
    out = tmp_path / "d.csv"
    assert main(["design", "split-plot-ccd", *FACTORS, *args, "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: ") and needle in err[0], err
    assert not out.exists()
