"""``rsm-lrg simulate``: input columns whose names the surrogate writes."""

import pandas as pd
import pytest

from rsm_lrg.cli import main
from rsm_lrg.surrogate import simulate
from rsm_lrg.surrogate.design_input import EXTRA_OUTPUT_COLUMNS, OUTPUT_COLUMNS

ROW = {"thickness_m": [3e-4], "stroke_m": [0.05], "velocity_m_s": [0.5], "acceleration_m_s2": [30.0]}


def test_output_columns_are_the_declared_ones():
    out = simulate(pd.DataFrame(dict(ROW, note=["x"])), noise_sd=0)
    assert list(out.columns) == [*ROW, "note", *OUTPUT_COLUMNS, *EXTRA_OUTPUT_COLUMNS]


def test_a_written_name_is_kept_as_input_and_said(tmp_path, capsys):
    p, out = tmp_path / "d.csv", tmp_path / "o.csv"
    pd.DataFrame(dict(ROW, tcr_c_per_min=[0.03], hinge_yields=["no"])).to_csv(p, index=False)
    assert main(["simulate", str(p), "--seed", "1", "-o", str(out)]) == 0
    err = capsys.readouterr().err
    assert "tcr_c_per_min, hinge_yields are kept as tcr_c_per_min_input, hinge_yields_input" in err
    df = pd.read_csv(out)
    assert df.tcr_c_per_min_input[0] == 0.03 and df.hinge_yields_input[0] == "no"
    assert df.columns.is_unique


@pytest.mark.parametrize("col", ["tcr_c_per_min", "hinge_peak_stress_pa"])
def test_no_duplicate_column_names(tmp_path, capsys, col):
    # a design with both X and X_input used to give a CSV with two X_input columns
    p, out = tmp_path / "d.csv", tmp_path / "o.csv"
    pd.DataFrame(dict(ROW, **{col: [1.0], f"{col}_input": [2.0]})).to_csv(p, index=False)
    assert main(["simulate", str(p), "--seed", "1", "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error:") and f"'{col}_input'" in err[0] and "d.csv" in err[0]
    assert not out.exists()
