"""``fit --whole-plot COL`` / ``--random-block COL``: REML with Kenward–Roger tests on the
command line, and ``optimize``, ``confirm``, ``report`` on a REML fit; bad input exits 2 with
one line naming the column, row or whole plot."""

import json
from pathlib import Path

import pytest

from rsm_lrg.cli import main

R = Path(__file__).parents[1] / "model" / "r"
CAKE = str(R / "mixed_cakeb.csv")  # Lawson (2015) ch. 10, daewr cakeb: 4 oven runs (whole plots)
SP = str(R / "mixed_sp_bal.csv")
BASE = ["--response", "y", "--factor", "x1", "--factor", "x2", "--whole-plot", "Ovenrun"]


def _err(capsys) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error:"), err
    return err[0]


def test_fit_whole_plot_json(capsys):
    assert main(["fit", CAKE, *BASE, "--json", "-"]) == 0
    js = json.loads(capsys.readouterr().out)
    assert js["whole_plot"] == "Ovenrun" and js["method"] == "REML"
    assert [(r["source"], r["df"], r["f"], r["sum_sq"]) for r in js["anova"]] == [(t["term"], t["num_df"], t["f"], None) for t in js["tests"]]
    assert set(js["variance_components"]) == {"whole_plot", "residual"}
    tests = {t["term"]: t for t in js["tests"]}
    assert list(tests) == ["A", "B", "AB", "A^2", "B^2"]
    # pbkrtest (tests/model/r/mixed_kr_expected.csv): x1 is tested on 0.98 den df (not clamped to 1)
    assert tests["A"]["den_df"] == pytest.approx(0.98393566, rel=1e-6)
    assert tests["B"]["den_df"] == pytest.approx(4.0, rel=1e-6)


def test_fit_whole_plot_text(capsys):
    assert main(["fit", CAKE, *BASE]) == 0
    out = capsys.readouterr().out
    for needle in ("REML variance components", "whole_plot", "Kenward-Roger F tests", "den df",
                   "Coefficients in terms of coded factors", "terms of actual factors"):
        assert needle in out, needle
    assert "Lack of Fit" not in out and "Sum of Squares" not in out


def test_random_block_and_reduce(capsys):
    assert main(["fit", str(R / "mixed_pastry.csv"), "--response", "y", "--factor", "x1", "--factor", "x2",
                 "--factor", "x3", "--random-block", "Block", "--reduce", "--json", "-"]) == 0
    js = json.loads(capsys.readouterr().out)
    assert js["random_block"] == "Block" and set(js["variance_components"]) == {"block", "residual"}
    assert js["reduction"]["criterion"] == "p" and js["reduction"]["removed"]


def test_optimize_and_confirm_on_a_reml_fit(capsys):
    assert main(["optimize", CAKE, *BASE, "--goal", "maximize", "--json", "-"]) == 0
    opt = json.loads(capsys.readouterr().out)
    assert opt["actual"]["x2"] == pytest.approx(-1.0)
    assert main(["confirm", CAKE, *BASE, "--at", "x1=0", "x2=0", "--observed", "2.9", "--json", "-"]) == 0
    c = json.loads(capsys.readouterr().out)
    assert c["inside"] is True and c["pi"][0] < 2.9 < c["pi"][1]


@pytest.mark.slow
def test_report_on_a_reml_fit(tmp_path, capsys):
    out = tmp_path / "r.html"
    assert main(["report", CAKE, *BASE, "--static", "-o", str(out)]) == 0
    html = out.read_text()
    assert "Kenward" in html or "REML" in html


@pytest.mark.parametrize("args, needle", [
    (["--whole-plot", "Oven"], "whole-plot column 'Oven' not found"),
    (["--whole-plot", "Ovenrun", "--block", "Ovenrun"], "fixed blocks together"),
])
def test_bad_whole_plot_options_exit_2(args, needle, capsys):
    assert main(["fit", CAKE, "--response", "y", "--factor", "x1", "--factor", "x2", *args]) == 2
    assert needle in _err(capsys)


def test_empty_whole_plot_cell_exits_2(tmp_path, capsys):
    src = Path(SP).read_text().splitlines()
    src[3] = "," + src[3].split(",", 1)[1]
    bad = tmp_path / "sp.csv"
    bad.write_text("\n".join(src) + "\n")
    assert main(["fit", str(bad), "--response", "wear_um", "--whole-plot", "whole_plot"]) == 2
    assert "whole-plot column 'whole_plot', row 3: is empty" in _err(capsys)


def test_too_few_whole_plots_exit_2(tmp_path, capsys):
    lines = [ln for ln in Path(SP).read_text().splitlines() if not ln.startswith(("W7,", "W8,"))]
    bad = tmp_path / "sp6.csv"
    bad.write_text("\n".join(lines) + "\n")
    assert main(["fit", str(bad), "--response", "wear_um", "--whole-plot", "whole_plot"]) == 2
    assert "6 whole plots cannot estimate the 6 whole-plot terms" in _err(capsys)


def test_whole_plot_over_several_files_exits_2(tmp_path, capsys):
    for name in ("a.csv", "b.csv"):
        (tmp_path / name).write_text(Path(SP).read_text())
    assert main(["fit", str(tmp_path), "--response", "wear_um", "--whole-plot", "whole_plot"]) == 2
    assert "--whole-plot is not available when fitting several files" in _err(capsys)


def test_hard_to_change_factor_varying_inside_a_whole_plot_exits_2(capsys):
    # x2 is the sub-plot factor of the cake data: it varies inside oven run 1 (rows 1-3)
    assert main(["fit", CAKE, *BASE, "--hard-to-change", "x2"]) == 2
    assert _err(capsys).endswith("hard-to-change factor 'x2' varies inside whole plot 1 (rows 1-3)")


@pytest.mark.parametrize("cmd", ["fit", "optimize"])
def test_hard_to_change_checked_and_noted(cmd, capsys):
    extra = ["--goal", "maximize"] if cmd == "optimize" else []
    assert main([cmd, CAKE, *BASE, "--hard-to-change", "x1", *extra, "--json", "-"]) == 0
    out = capsys.readouterr()
    assert "Hard-to-change factors (checked constant within every whole plot): x1." in out.out + out.err


def test_whole_plot_factors_listed_without_hard_to_change(capsys):
    assert main(["fit", SP, "--response", "wear_um", "--whole-plot", "whole_plot", "--json", "-"]) == 0
    js = json.loads(capsys.readouterr().out)
    assert "Factors constant within every whole plot (whole-plot factors): temp_c, preload_kn." in js["notes"]


@pytest.mark.parametrize("args, needle", [
    (["--hard-to-change", "x1"], "--hard-to-change: give --whole-plot COL too"),
    (["--whole-plot", "Ovenrun", "--hard-to-change", "x9"], "hard-to-change factor 'x9' is not a column"),
    (["--whole-plot", "Ovenrun", "--hard-to-change", "x1", "--hard-to-change", "x1"], "'x1' is given twice"),
])
def test_bad_hard_to_change_exits_2(args, needle, capsys):
    assert main(["fit", CAKE, "--response", "y", "--factor", "x1", "--factor", "x2", *args]) == 2
    assert needle in _err(capsys)
