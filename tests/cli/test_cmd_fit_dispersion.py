"""``rsm-lrg fit --dispersion``: the ln s model in the text and the JSON ``dispersion`` block,
equal to the library's; bad uses exit 2 naming the option."""

import json
from pathlib import Path

import pytest
from _cli_errors import error_line

from rsm_lrg.cli import main

DATA = str(Path(__file__).parents[1] / "model" / "r" / "dispersion_cure.csv")
BASE = ["fit", DATA, "--response", "yield_pct", "--factor", "temp_c", "--factor", "time_min"]


def test_json_block_equals_the_library_and_names_what_was_left_out(capsys):
    import pandas as pd

    from rsm_lrg.model.dispersion import fit_dispersion

    assert main(BASE + ["--dispersion", "--dispersion-model", "2fi", "--json", "-"]) == 0
    out = json.loads(capsys.readouterr().out)
    disp = out["dispersion"]
    lib = fit_dispersion(pd.read_csv(DATA), "yield_pct", factors=["temp_c", "time_min"], model="2fi")
    assert disp["terms"] == ["A", "B", "AB"] and disp["scale"] == "ln s"
    assert disp["coefficients"]["coded"] == pytest.approx(dict(lib.result.coefficients["coded"]), rel=1e-12)
    assert disp["r2"] == pytest.approx(0.922747250017846, rel=1e-10)  # R lm, tests/model/r/dispersion.R
    assert disp["settings_used"] == 8 and len(disp["settings_left_out"]) == 2
    assert {r["source"] for r in disp["anova"]} >= {"Model", "A", "B", "AB", "Residual"}
    assert "coefficients" in out and out["response"] == "yield_pct"  # the mean's fit is unchanged
    assert main(BASE + ["--dispersion"]) == 0
    text = capsys.readouterr().out
    assert "Dispersion model: ln s of yield_pct at 8 replicated settings" in text
    assert "Left out: 2 unreplicated setting(s): temp_c=165, time_min=25; temp_c=190, time_min=30" in text


@pytest.mark.parametrize("extra, option", [
    (["--dispersion", "--dispersion-model", "cubic"], "--dispersion-model"),
    (["--dispersion", "--model", "gp"], "--dispersion"),
])
def test_bad_uses_name_the_option(capsys, extra, option):
    assert error_line(capsys, main(BASE + extra)).startswith(f"error: {option}")


def test_unreplicated_data_names_dispersion(tmp_path, capsys):
    import pandas as pd

    p = tmp_path / "once.csv"
    pd.read_csv(DATA).drop_duplicates(["temp_c", "time_min"]).to_csv(p, index=False)
    line = error_line(capsys, main(["fit", str(p), "--response", "yield_pct", "--dispersion"]))
    assert line.startswith("error: --dispersion:") and "0 replicated setting(s)" in line
