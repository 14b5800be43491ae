"""``rsm-lrg optimize --model gp``: the optimum of a Gaussian-process fit (as the library's
``optimize(fit(..., model="gp"))``), and the options a GP does not take as one error line."""

import json
from pathlib import Path

import pandas as pd
import pytest
from _cli_errors import error_line

import rsm_lrg
from rsm_lrg.cli import main
from rsm_lrg.optimize import optimize

BRANIN = str(Path(__file__).parents[1] / "model" / "r" / "gp_branin.csv")
FACTORS = ["--factor", "x1=-5:10", "--factor", "x2=0:15"]


def test_optimum_is_the_librarys(capsys):
    assert main(["optimize", BRANIN, "--response", "y", *FACTORS, "--model", "gp", "--goal", "target=30",
                 "--constraint", "x1 + x2 <= 10", "--json", "-"]) == 0
    got = json.loads(capsys.readouterr().out)
    gp = rsm_lrg.fit(pd.read_csv(BRANIN), "y", factors=["x1=-5:10", "x2=0:15"], model="gp")
    want = optimize(gp, "target=30", constraints=["x1 + x2 <= 10"])
    assert got["actual"] == pytest.approx(want.actual, abs=1e-12)
    assert got["predicted"] == pytest.approx(30.0, abs=1e-4)
    assert got["pi"] == pytest.approx(list(want.pi), rel=1e-12)


@pytest.mark.parametrize("extra, option", [
    (["--reduce"], "--reduce"),
    (["--transform", "log"], "--transform"),
    (["--goal", "poe"], "--goal poe"),
])
def test_options_a_gp_does_not_take(extra, option, capsys):
    line = error_line(capsys, main(["optimize", BRANIN, "--response", "y", *FACTORS, "--model", "gp", *extra]))
    assert option in line


def test_desirability_with_a_gp_and_a_quadratic(tmp_path, capsys):
    d = pd.read_csv(BRANIN)
    d["y2"] = 0.5 * d.x1 + d.x2 + 0.1 * d.x1 * d.x2
    src = tmp_path / "two.csv"
    d.to_csv(src, index=False)
    assert main(["optimize", str(src), "--response", "y", "--model", "gp", "--goal", "minimize", "--response", "y2",
                 "--goal", "maximize", *FACTORS, "--json", "-"]) == 0
    got = json.loads(capsys.readouterr().out)
    gp = rsm_lrg.fit(d, "y", factors=["x1=-5:10", "x2=0:15"], model="gp")
    at = pd.DataFrame([got["actual"]])
    assert got["predicted"]["y"] == pytest.approx(float(gp.predict(at)["predicted"].iloc[0]), rel=1e-9)
    assert 0.5 < got["desirability"] <= 1.0


def test_report_pages_of_a_gp(tmp_path, capsys):
    page = tmp_path / "gp.html"
    assert main(["report", BRANIN, "--response", "y", *FACTORS, "--model", "gp", "-o", str(page)]) == 0
    text = page.read_text()
    assert '"kriging"' in text and "a Gaussian process has none" in text
    static = tmp_path / "gp_static.html"
    assert main(["report", BRANIN, "--response", "y", *FACTORS, "--model", "gp", "--static", "-o", str(static)]) == 0
    assert "<script" not in static.read_text()
    capsys.readouterr()
    line = error_line(capsys, main(["report", BRANIN, "--response", "y", *FACTORS, "--model", "gp", "--transform",
                                    "log", "-o", str(tmp_path / "x.html")]))
    assert "--transform" in line
