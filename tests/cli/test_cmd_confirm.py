"""``rsm-lrg confirm``: the paper's confirmation run (Sec. 4.3) from the command line."""

import json

import pytest

from rsm_lrg.cli import main

AT = ["--at", "thickness_m=0.0001", "--at", "stroke_m=0.04", "--at", "velocity_m_s=0.4", "--at", "acceleration_m_s2=20"]


def test_paper_confirmation_json(capsys):
    assert main(["confirm", "data/table4.csv", "--response", "tcr_c_per_min", *AT, "--observed", "0.024",
                 "--reference", "0.023", "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["inside"] is True
    assert d["pi"] == pytest.approx([0.0159, 0.0298], abs=5e-5)  # DIGEST, 95 % PI
    assert d["relative_error_vs_reference_percent"] == pytest.approx(4.35, abs=5e-3)  # paper
    assert d["relative_error_percent"] == pytest.approx(5.11, abs=5e-3)  # vs exact 0.022833


def test_missing_setting_is_an_error(capsys):
    assert main(["confirm", "data/table4.csv", "--response", "tcr_c_per_min", "--at", "thickness_m=0.0001",
                 "--observed", "0.024"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: --at:") and "stroke_m" in err  # an option error names the option
