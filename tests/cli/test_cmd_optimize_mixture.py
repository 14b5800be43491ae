"""``optimize``, ``report`` and ``confirm`` with ``--component``: the command line of the mixture
optimum and report (Myers & Montgomery's plasma-etch blends on the L-simplex x1 >= 0.1,
x2 >= 0.2, x3 >= 0.05, ``tests/model/r/mixture_etch_l.csv``; Cornell's fish-patty
mixture-process data ``mixture_fishp.csv``)."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.cli import main

R = Path(__file__).parents[1] / "model" / "r"
DATA = R / "mixture_etch_l.csv"
SPECS = ["x1=0.1:1", "x2=0.2:1", "x3=0.05:1"]
COMPS = [a for s in SPECS for a in ("--component", s)]


def _fit(model="mixture-quadratic"):
    return rsm_lrg.fit(pd.read_csv(DATA), "erate", components=SPECS, model=model)


@pytest.mark.parametrize("model", ["mixture-quadratic", "special-cubic"])
def test_optimize_json_is_the_python_optimum(tmp_path, capsys, model):
    out = tmp_path / "o.json"
    assert main(["optimize", str(DATA), "--response", "erate", *COMPS, "--model", model, "--goal", "maximize",
                 "--constraint", "x1 + x2 <= 0.8", "--json", str(out)]) == 0
    d = json.loads(out.read_text())
    want = rsm_lrg.optimize(_fit(model), goal="maximize", constraints="x1 + x2 <= 0.8")
    assert d["actual"] == pytest.approx(want.actual, abs=1e-12)
    assert d["predicted"] == pytest.approx(want.predicted, rel=1e-12)
    assert abs(sum(d["actual"].values()) - 1.0) <= 1e-12 and d["total"] == pytest.approx(1.0, abs=1e-12)
    assert d["actual"]["x1"] + d["actual"]["x2"] <= 0.8 + 1e-12
    assert d["ci"][0] < d["predicted"] < d["ci"][1] and d["pi"][0] < d["ci"][0]
    text = capsys.readouterr().out
    assert "L-pseudo" in text and "the blend sums to the total 1" in text


def test_optimize_bound_on_a_component(capsys):
    assert main(["optimize", str(DATA), "--response", "erate", *COMPS, "--model", "mixture-quadratic",
                 "--goal", "maximize", "--bound", "x3=0.3:0.5", "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert 0.3 - 1e-12 <= d["actual"]["x3"] <= 0.5 + 1e-12
    assert d["bounds"]["x3"] == pytest.approx([0.3, 0.5])


@pytest.mark.parametrize("args, message", [
    (["--constraint", "x1 + x2 >= 1.5"], "error: --constraint: constraints and bounds leave no blend"),
    (["--constraint", "x1*x2 <= 0.1"], "error: --constraint: constraint 'x1*x2 <= 0.1' is not linear"),
    (["--bound", "x9=0.1:0.2"], "error: --bound: bound for 'x9': no such component"),
    (["--bound", "x1=0.8:0.9", "--bound", "x2=0.5:0.6"], "error: --bound: the region is empty"),
])
def test_optimize_bad_region_exits_2(tmp_path, capsys, args, message):
    out = tmp_path / "o.json"
    assert main(["optimize", str(DATA), "--response", "erate", *COMPS, "--model", "mixture-quadratic",
                 "--goal", "maximize", *args, "--json", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(message) and err.count("\n") == 1, err
    assert not out.exists()


def test_desirability_over_the_simplex(tmp_path, capsys):
    d = pd.read_csv(DATA)
    d["cost"] = 12 * d["x1"] + 3 * d["x2"] + 5 * d["x3"] + 0.05 * (pd.Series(range(len(d))) % 3)
    p = tmp_path / "two.csv"
    d.to_csv(p, index=False)
    assert main(["optimize", str(p), *COMPS, "--response", "erate", "--model", "mixture-quadratic", "--goal",
                 "maximize", "--response", "cost", "--model", "mixture-linear", "--goal", "minimize",
                 "--json", "-"]) == 0
    got = json.loads(capsys.readouterr().out)
    blend = got["actual"]
    assert abs(sum(blend.values()) - 1.0) <= 1e-12
    assert blend["x1"] >= 0.1 - 1e-12 and blend["x2"] >= 0.2 - 1e-12 and blend["x3"] >= 0.05 - 1e-12
    # no blend of a fine lattice of the region is more desirable
    from rsm_lrg.optimize.desirability import ResponseGoal, individual_desirability, overall_desirability

    fits = {"erate": rsm_lrg.fit(d, "erate", components=SPECS, model="mixture-quadratic"),
            "cost": rsm_lrg.fit(d, "cost", components=SPECS, model="mixture-linear")}
    goals = [ResponseGoal("erate", "maximize").with_limits(d["erate"].min(), d["erate"].max()),
             ResponseGoal("cost", "minimize").with_limits(d["cost"].min(), d["cost"].max())]
    n = 120
    rows = [(0.1 + 0.65 * i / n, 0.2 + 0.65 * j / n) for i in range(n + 1) for j in range(n + 1 - i)]
    grid = pd.DataFrame(rows, columns=["x1", "x2"]).assign(x3=lambda g: 1.0 - g.x1 - g.x2)
    ds = [individual_desirability(fits[g.response].predict(grid)["predicted"].to_numpy(), g) for g in goals]
    best_grid = float(overall_desirability(ds, goals).max())
    assert got["desirability"] >= best_grid - 1e-9


def test_report_of_a_mixture(tmp_path, capsys):
    out = tmp_path / "mix.html"
    assert main(["report", str(DATA), "--response", "erate", *COMPS, "--model", "special-cubic", "--goal",
                 "maximize", "-o", str(out)]) == 0
    html = out.read_text()
    for div in ("ternary-plot", "ternary-surface", "ternary-overlay", "trace-plot", "mixture-effects"):
        assert f'id="{div}"' in html
    data = json.loads(re.search(r'<script type="application/json" id="rsm-data">(.*?)</script>', html, re.S).group(1))
    mix = data["mixture"]
    assert [c["name"] for c in mix["components"]] == ["x1", "x2", "x3"] and mix["total"] == pytest.approx(1.0)
    assert sum(mix["reference"]) == pytest.approx(1.0, abs=1e-12)
    assert all(c["component"] for c in data["controls"])
    static = tmp_path / "static.html"
    assert main(["report", str(DATA), "--response", "erate", *COMPS, "--model", "special-cubic", "--static",
                 "-o", str(static)]) == 0
    s = static.read_text()
    assert 'id="fig-ternary"' in s and 'id="fig-trace"' in s and "<script" not in s.split("</head>")[1]


def test_report_of_a_mixture_process_fit(tmp_path):
    out = tmp_path / "fish.html"
    assert main(["report", str(R / "mixture_fishp.csv"), "--response", "y", "--component", "x1", "--component",
                 "x2", "--component", "x3", "--factor", "z1", "--factor", "z2", "--model", "mixture-linear",
                 "--goal", "maximize", "-o", str(out)]) == 0
    html = out.read_text()
    assert 'data-factor="z1"' in html and 'id="ternary-plot"' in html
    assert 'id="overlay-plot"' in html  # the two process factors keep their own overlay


def test_confirm_blend_off_the_total_names_the_tolerance(capsys):
    assert main(["confirm", str(DATA), "--response", "erate", *COMPS, "--model", "mixture-quadratic", "--at",
                 "x1=0.5", "x2=0.3", "x3=0.3", "--observed", "700"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: --at: prediction point 1: the components sum to 1.1, not the total 1 (tolerance")
    assert err.count("\n") == 1
