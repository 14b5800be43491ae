"""``rsm-lrg predict``: intervals (CI, PI, TI), propagation of error and the simulator from the
command line; the JSON equals the library, bad input is one ``error:`` line naming the option."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.cli import main
from rsm_lrg.optimize.poe import propagation_of_error
from tests.cli._cli_errors import error_line

R = Path(__file__).parents[1] / "model" / "r"
HELI = str(R / "heli.csv")
FACTORS = ["--factor", "A", "--factor", "R", "--factor", "W", "--factor", "L"]
AT = ["--at", "A=12.4", "R=2.5", "W=1.1", "L=1.6"]


def _json(capsys, argv):
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


def test_intervals_equal_the_library(capsys):
    d = _json(capsys, ["predict", HELI, "--response", "ave", *FACTORS, *AT, "--tolerance", "0.99",
                       "--confidence", "0.9", "--json", "-"])
    fit = rsm_lrg.fit(pd.read_csv(HELI), "ave", factors=["A", "R", "W", "L"])
    exp = fit.predict({"A": 12.4, "R": 2.5, "W": 1.1, "L": 1.6}, interval="both", alpha=0.1, tolerance=0.99).iloc[0]
    got = d["predictions"]["ave"][0]
    for key in ("predicted", "ci_low", "ci_high", "pi_low", "pi_high", "ti_low", "ti_high",
                "ti_one_sided_low", "ti_one_sided_high"):
        assert got[key] == pytest.approx(float(exp[key]), rel=1e-14), key
    assert d["points"] == [{"A": 12.4, "R": 2.5, "W": 1.1, "L": 1.6}]
    assert d["confidence"] == 0.9 and d["tolerance"] == 0.99
    assert "poe" not in got and "simulation" not in d


def test_points_file_several_responses_and_poe(capsys, tmp_path):
    data = pd.read_csv(HELI)
    pts = tmp_path / "pts.csv"
    pd.DataFrame({"L": [1.6, 1.4], "A": [12.4, 11.0], "R": [2.5, 2.0], "W": [1.1, 0.9]}).to_csv(pts, index=False)
    d = _json(capsys, ["predict", HELI, "--response", "ave", "--response", "logSD", "--model", "linear",
                       "--transform", "log", *FACTORS, "--points", str(pts), "--factor-sd", "A=0.2",
                       "--factor-sd", "W=0.03", "--json", "-"])
    assert set(d["predictions"]) == {"ave", "logSD"} and len(d["points"]) == 2
    assert d["models"]["logSD"].startswith("linear")
    fit = rsm_lrg.fit(data, "logSD", factors=["A", "R", "W", "L"], model="linear", transform="log")
    frame = pd.read_csv(pts)[["A", "R", "W", "L"]]
    poe = propagation_of_error(fit, frame, {"A": 0.2, "W": 0.03})
    assert [p["poe"] for p in d["predictions"]["logSD"]] == pytest.approx(list(poe), rel=1e-14)
    assert "ti_low" not in d["predictions"]["ave"][0]


def test_text_output(capsys):
    assert main(["predict", HELI, "--response", "ave", *FACTORS, *AT, "--tolerance", "0.95",
                 "--factor-sd", "A=0.1"]) == 0
    out = capsys.readouterr().out
    assert "TI for 95 % of runs" in out and "POE" in out and "PI high" in out


def test_simulator_is_seeded(capsys):
    argv = ["predict", HELI, "--response", "ave", *FACTORS, *AT, "--draws", "2e4", "--seed", "5",
            "--factor-sd", "A=0.3", "--spec", "ave=365:385", "--json", "-"]
    a = _json(capsys, argv)
    b = _json(capsys, argv)
    assert a == b
    sim = a["simulation"][0]
    assert a["seed"] == 5 and sim["draws"] == 20000 and sim["seed"] == 5
    r = sim["responses"]["ave"]
    assert set(r["quantiles"]) == {"0.1%", "2.5%", "50%", "97.5%", "99.9%"}
    assert 0 < r["ppm"] < 1e6 and r["cpk"] is not None
    assert sim["ppm_outside_any_spec"] == r["ppm"]
    c = _json(capsys, [("6" if v == "5" else v) for v in argv])
    assert c["simulation"][0]["responses"]["ave"]["mean"] != r["mean"]


def test_no_non_finite_number_in_the_json(capsys, tmp_path):
    """A model without residual df: the intervals are null, never NaN."""
    data = pd.read_csv(HELI).iloc[:5]
    path = tmp_path / "few.csv"
    data.to_csv(path, index=False)
    out = tmp_path / "out.json"
    assert main(["predict", str(path), "--response", "ave", "--factor", "A", "--factor", "R", "--model", "linear",
                 "--at", "A=12", "R=2.3", "--tolerance", "0.9", "--json", str(out)]) == 0
    text = out.read_text()
    assert "NaN" not in text and "Infinity" not in text
    d = json.loads(text)
    assert np.isfinite(d["predictions"]["ave"][0]["predicted"])


@pytest.mark.parametrize("extra, option", [
    (["--draws", "1e12", "--seed", "1"], "--draws"),
    (["--draws", "0"], "--draws"),
    (["--draws", "2.5"], "--draws"),
    (["--tolerance", "1.5"], "--tolerance"),
    (["--confidence", "0"], "--confidence"),
    (["--factor-sd", "A=-1"], "--factor-sd"),
    (["--factor-sd", "nope=1"], "--factor-sd"),
    (["--draws", "10", "--spec", "zz=1:2"], "--spec"),
    (["--draws", "10", "--spec", "ave=3:1"], "--spec"),
    (["--spec", "ave=1:2"], "--spec"),
    (["--seed", "3"], "--seed"),
])
def test_bad_options_name_the_option(capsys, extra, option):
    rc = main(["predict", HELI, "--response", "ave", *FACTORS, *AT, *extra])
    line = error_line(capsys, rc)
    assert option in line


def test_bad_settings(capsys, tmp_path):
    line = error_line(capsys, main(["predict", HELI, "--response", "ave", *FACTORS, "--at", "A=12", "R=2"]))
    assert "--at" in line
    pts = tmp_path / "p.csv"
    pd.DataFrame({"A": [12.0], "R": [2.5], "W": [1.0]}).to_csv(pts, index=False)
    line = error_line(capsys, main(["predict", HELI, "--response", "ave", *FACTORS, "--points", str(pts)]))
    assert "--points" in line and "p.csv" in line and "'L'" in line
    line = error_line(capsys, main(["predict", HELI, "--response", "ave", *FACTORS]))
    assert "--at" in line or "--points" in line
    line = error_line(capsys, main(["predict", HELI, "--response", "ave", *FACTORS, *AT, "--points", str(pts)]))
    assert "--points" in line


def test_mixture_blend_must_keep_the_total(capsys):
    comps = ["--component", "x1", "--component", "x2", "--component", "x3", "--model", "mixture-quadratic"]
    etch = str(R / "mixture_etch.csv")
    d = _json(capsys, ["predict", etch, "--response", "erate", *comps, "--at", "x1=0.2", "x2=0.3", "x3=0.5",
                       "--factor-sd", "x1=0.02", "--tolerance", "0.9", "--json", "-"])
    assert d["predictions"]["erate"][0]["poe"] > 0
    line = error_line(capsys, main(["predict", etch, "--response", "erate", *comps, "--at", "x1=0.2", "x2=0.3",
                                    "x3=0.6"]))
    assert line.startswith("error: --at:")


def test_reml_and_categoric_from_the_command_line(capsys):
    """A split-plot REML fit (daewr cakeb): the TI uses the KR df and both variance components
    (equal to the library); a categoric factor at a level in --points."""
    cake = str(R / "mixed_cakeb.csv")
    base = ["--response", "y", "--factor", "x1", "--factor", "x2", "--whole-plot", "Ovenrun"]
    d = _json(capsys, ["predict", cake, *base, "--at", "x1=0.5", "x2=-0.5", "--tolerance", "0.9",
                       "--factor-sd", "x1=0.1", "--json", "-"])
    fit = rsm_lrg.fit(pd.read_csv(cake), "y", factors=["x1", "x2"], whole_plot="Ovenrun")
    exp = fit.predict({"x1": 0.5, "x2": -0.5}, interval="both", tolerance=0.9).iloc[0]
    got = d["predictions"]["y"][0]
    assert got["ti_low"] == pytest.approx(float(exp.ti_low), rel=1e-13)
    assert got["pi_high"] == pytest.approx(float(exp.pi_high), rel=1e-13)
    assert got["poe"] == pytest.approx(float(propagation_of_error(fit, {"x1": 0.5, "x2": -0.5}, {"x1": 0.1})[0]),
                                       rel=1e-13)
    cat = str(R / "cat_bbd3x2.csv")
    d = _json(capsys, ["predict", cat, "--response", "yield_pct", "--factor", "temp_c", "--factor", "time_min",
                       "--factor", "conc_pct", "--factor", "supplier=cat", "--at", "temp_c=150", "time_min=30",
                       "conc_pct=5", "supplier=south", "--tolerance", "0.95", "--draws", "1000", "--seed", "2",
                       "--json", "-"])
    assert d["points"][0]["supplier"] == "south"
    assert d["simulation"][0]["responses"]["yield_pct"]["mean"] is not None


def test_one_and_two_workers_give_the_same_numbers(capsys):
    argv = ["predict", HELI, "--response", "ave", *FACTORS, *AT, "--draws", "140000", "--seed", "3",
            "--factor-sd", "A=0.3", "--spec", "ave=365:385", "--json", "-"]
    one = _json(capsys, argv)
    two = _json(capsys, argv + ["--workers", "2"])
    assert one == two
    line = error_line(capsys, main(["predict", HELI, "--response", "ave", *FACTORS, *AT, "--workers", "2"]))
    assert "--workers" in line


@pytest.mark.slow
def test_a_dask_scheduler_gives_the_numbers_of_one_process(capsys):
    """``--scheduler ADDRESS``: the simulator's blocks drawn on a real local Dask cluster of two
    workers give the JSON of one process."""
    distributed = pytest.importorskip("distributed")
    argv = ["predict", HELI, "--response", "ave", *FACTORS, *AT, "--draws", "140000", "--seed", "3",
            "--factor-sd", "A=0.3", "--spec", "ave=365:385", "--json", "-"]
    one = _json(capsys, argv)
    with distributed.LocalCluster(processes=True, n_workers=2, threads_per_worker=1, host="127.0.0.1",
                                  dashboard_address=None) as cluster:
        dask = _json(capsys, argv + ["--scheduler", cluster.scheduler_address, "--progress"])
    assert dask == one


@pytest.mark.parametrize("extra", [["--scheduler", "tcp://127.0.0.1:1"], ["--progress"]])
def test_simulator_options_need_draws(capsys, extra):
    line = error_line(capsys, main(["predict", HELI, "--response", "ave", *FACTORS, *AT, *extra]))
    assert line.startswith("error: --seed, --workers, --scheduler") and "--draws" in line


def test_workers_and_scheduler_are_exclusive(capsys):
    line = error_line(capsys, main(["predict", HELI, "--response", "ave", *FACTORS, *AT, "--draws", "10",
                                    "--workers", "2", "--scheduler", "tcp://127.0.0.1:1"]))
    assert "--scheduler" in line and "not allowed with" in line


def test_an_unreachable_scheduler_is_one_line(capsys):
    line = error_line(capsys, main(["predict", HELI, "--response", "ave", *FACTORS, *AT, "--draws", "10", "--seed", "1",
                                    "--scheduler", "tcp://127.0.0.1:1", "--scheduler-timeout", "2"]))
    assert line.startswith("error: --scheduler")
