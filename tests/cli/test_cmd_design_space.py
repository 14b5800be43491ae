"""``rsm-lrg design-space``: text, JSON and the page; bad options exit 2 naming the option."""

import json
from pathlib import Path

import pytest
from _cli_errors import error_line

from rsm_lrg.cli import main

T4 = str(Path(__file__).parents[2] / "data" / "table4.csv")
BASE = ["design-space", T4, "--response", "tcr_c_per_min", "--spec", "tcr_c_per_min=:0.035"]


def test_json_and_text_agree_with_the_library(capsys):
    import rsm_lrg
    from rsm_lrg.optimize.design_space import design_space

    assert main(BASE + ["--grid", "5", "--json", "-"]) == 0
    out = json.loads(capsys.readouterr().out)
    fit = rsm_lrg.fit(rsm_lrg.load_table4(), "tcr_c_per_min")
    ds = design_space({"tcr_c_per_min": fit}, {"tcr_c_per_min": (None, 0.035)}, grid=5)
    assert out["window"] == {k: {"low": lo, "high": hi} for k, (lo, hi) in ds.window.items()}
    assert out["window_min_probability"] == pytest.approx(ds.window_min_probability, rel=1e-12)
    assert out["probability"] == 0.9 and out["grid"] == 5 and len(out["maps"]) == 6
    assert main(BASE + ["--grid", "5"]) == 0
    text = capsys.readouterr().out
    assert "Largest operating window found" in text and "thickness_m:" in text


def test_page_is_written_atomically_and_not_over_a_file(tmp_path, capsys):
    page = tmp_path / "ds.html"
    assert main(BASE + ["--grid", "5", "-o", str(page)]) == 0
    html = page.read_text()
    assert "Operating window" in html and html.count("<img") == 6 and "<script" not in html
    assert main(BASE + ["--grid", "5", "-o", str(page)]) == 2  # exists, no --force
    assert "exists" in capsys.readouterr().err


@pytest.mark.parametrize("extra, option", [
    (["--probability", "1.5"], "--probability"), (["--grid", "2"], "--grid"),
    (["--spec", "nope=:1"], "--spec"), (["--spec", "tcr_c_per_min=2:1"], "--spec"),
    (["--factor-sd", "stroke_m"], "--factor-sd"), (["--factor-sd", "zzz=1"], "--factor-sd"),
    (["--draws", "0"], "--draws"),
])
def test_bad_options_name_the_option(capsys, extra, option):
    line = error_line(capsys, main(BASE + extra))
    assert option in line
