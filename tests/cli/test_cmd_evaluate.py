"""``rsm-lrg evaluate``: the paper's design before any data."""

import json

import pytest

from rsm_lrg.cli import main


def test_paper_design(capsys):
    assert main(["evaluate", "designs/paper-bbd4.csv", "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["n"] == 27 and d["p"] == 15
    assert d["spv_center"] == pytest.approx(9.0, rel=1e-12)  # n / n0 for a Box-Behnken design
    assert set(d["terms"]["A"]) == {"std_error", "vif", "power"}
    assert len(d["fds"]) == 11 and len(d["leverage"]) == 27
    assert main(["evaluate", "designs/paper-bbd4.csv", "--model", "linear"]) == 0
    assert "Power" in capsys.readouterr().out


def test_data_csv_and_errors(capsys, tmp_path):
    assert main(["evaluate", "data/table4.csv", "--exclude", "tcr_c_per_min", "--json", "-"]) == 0
    assert json.loads(capsys.readouterr().out)["n"] == 27
    assert main(["evaluate", str(tmp_path / "none.csv")]) == 2
    assert capsys.readouterr().err.startswith("error:")


def test_cubic_on_replicated_2cubed_exits_2_naming_aliased_terms(capsys, tmp_path):
    # Issue 10 item 13: was a negative residual df and no table; now a clear refusal.
    import itertools

    rows = ["a,b,c"] + [f"{a},{b},{c}" for a, b, c in itertools.product([10, 20], [1, 2], [5, 7])] * 2
    path = tmp_path / "rep2cubed.csv"
    path.write_text("\n".join(rows) + "\n")
    assert main(["evaluate", str(path), "--model", "cubic"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error:") and "not estimable" in err and "A^3" in err and "residual" not in err
    assert len(err.strip().splitlines()) == 1 and len(err) < 300
    assert main(["evaluate", str(path), "--model", "2fi"]) == 0
    out = capsys.readouterr().out
    assert "maximum by exact search" in out
