"""``rsm-lrg fit --model gp``: the Gaussian process on the command line (text, ``--json``,
and bad input as one ``error:`` line with exit status 2)."""

import json
from pathlib import Path

import pytest
from _cli_errors import error_line

from rsm_lrg.cli import main

DATA = Path(__file__).parents[1] / "model" / "r"
BRANIN = str(DATA / "gp_branin.csv")
HART = str(DATA / "gp_hartmann3.csv")


def test_text_output(capsys):
    assert main(["fit", BRANIN, "--response", "y", "--model", "gp", "--factor", "x1=-5:10", "--factor", "x2=0:15",
                 "--kernel", "matern32", "--trend", "linear"]) == 0
    out = capsys.readouterr().out
    assert "Gaussian process (kriging): y, 20 runs, 2 factors" in out
    assert "Kernel: matern32" in out and "trend: linear" in out and "Leave-one-out" in out


def test_json_output(capsys):
    assert main(["fit", HART, "--response", "y", "--model", "gp", "--nugget", "estimate", "--seed", "4",
                 "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["model"] == "gp" and d["gp"]["kernel"] == "matern52" and d["gp"]["trend"]["type"] == "constant"
    assert d["gp"]["estimated"]["nugget"] and d["gp"]["nugget"] > 0 and d["gp"]["seed"] == 4
    assert set(d["gp"]["length_scales"]["coded"]) == {"x1", "x2", "x3"}
    assert -1.0 < d["loo"]["q2"] <= 1.0


def test_length_scale_bounds(capsys):
    # km's bounds (2 x the range): theta_x2 stops at km's bound, 3.88566 (tests/model/r/gp.R); the
    # default bounds (10 x the range) let it rise to a higher likelihood
    out = {}
    for given in ([], ["--length-scale-bounds", "0.001:2"]):
        assert main(["fit", BRANIN, "--response", "y", "--model", "gp", "--factor", "x1=-5:10", "--factor", "x2=0:15",
                     "--kernel", "gauss", "--trend", "quadratic", *given, "--json", "-"]) == 0
        out[bool(given)] = json.loads(capsys.readouterr().out)["gp"]
    assert out[True]["search"]["length_scale_bounds"] == [0.001, 2.0]
    assert out[False]["search"]["length_scale_bounds"] == [0.001, 10.0]
    assert out[True]["length_scales"]["coded"]["x2"] == pytest.approx(3.8856585726669608, rel=1e-9)
    assert out[False]["length_scales"]["coded"]["x2"] > 4.5
    assert out[False]["log_likelihood"] > out[True]["log_likelihood"] + 0.4


def test_fixed_nugget_value(capsys):
    assert main(["fit", HART, "--response", "y", "--model", "gp", "--nugget", "0.01", "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["gp"]["nugget"] == 0.01 and not d["gp"]["estimated"]["nugget"]


@pytest.mark.parametrize("args, option", [
    (["--model", "gp", "--nugget", "-1"], "--nugget"),
    (["--model", "gp", "--nugget", "some"], "--nugget"),
    (["--model", "gp", "--kernel", "exp"], "--kernel"),
    (["--model", "gp", "--trend", "cubic"], "--trend"),
    (["--model", "gp", "--seed", "-2"], "--seed"),
    (["--model", "gp", "--length-scale-bounds", "2:1"], "--length-scale-bounds"),
    (["--model", "gp", "--length-scale-bounds", "0:1"], "--length-scale-bounds"),
    (["--model", "gp", "--length-scale-bounds", "0.1"], "--length-scale-bounds"),
    (["--model", "gp", "--length-scale-bounds", "0.1:inf"], "--length-scale-bounds"),
    (["--model", "quadratic", "--length-scale-bounds", "0.1:2"], "--length-scale-bounds"),
    (["--kernel", "gauss"], "--kernel"),
    (["--model", "quadratic", "--nugget", "estimate"], "--nugget"),
    (["--model", "gp", "--block", "x1"], "--block"),
    (["--model", "gp", "--transform", "log"], "--transform"),
    (["--model", "gp", "--reduce"], "--reduce"),
    (["--model", "gp", "--diagnostics"], "--diagnostics"),
    (["--model", "gp", "--trend", "quadratic", "--factor", "x1", "--factor", "x2", "--factor", "x3",
      "--nugget", "estimate", "--response", "y"], None),
])
def test_bad_input_is_one_error_line(args, option, capsys, tmp_path):
    data = HART
    if option is None:  # 10 coefficients need 11 runs: give 8
        small = tmp_path / "small.csv"
        small.write_text("\n".join(Path(HART).read_text().splitlines()[:9]) + "\n")
        data = str(small)
        args = args[:-2]
    line = error_line(capsys, main(["fit", data, "--response", "y", *args]))
    assert (option or "--trend") in line
