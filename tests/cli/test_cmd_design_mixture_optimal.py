"""``rsm-lrg design optimal --component ...`` and the crossed mixture-process designs
(``--factor`` on simplex-lattice/simplex-centroid/extreme-vertices), then ``fit`` on the
written files with their bookkeeping columns; issue 22's errors (item 5) from the command
line: exit 2, one ``error:`` line naming the row, component or constraint, no file left."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest
from _cli_errors import error_line

from rsm_lrg.cli import main
from rsm_lrg.design.mixture import candidate_blends

COMPS = ["--component", "a=0.1:0.8", "--component", "b=0.1:0.8", "--component", "c=0:0.5"]
CONS = ["--constraint", "a + b <= 0.85"]


def _respond(path, out, rng, process=None):
    d = pd.read_csv(path)
    y = 10 * d["a"] + 12 * d["b"] + 8 * d["c"] + 5 * d["a"] * d["b"]
    if process:
        y = y + 0.05 * (d[process] - d[process].mean()) * d["a"]
    d["y"] = y + rng.normal(0, 0.05, len(d))
    d.to_csv(out, index=False)
    return d


def test_optimal_mixture_then_fit(tmp_path, capsys):
    p = tmp_path / "opt.csv"
    argv = ["design", "optimal", *COMPS, *CONS, "--model", "mixture-quadratic", "--criterion", "D", "--runs", "14",
            "--lack-of-fit", "3", "--replicates", "2", "--seed", "5", "-o", str(p)]
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "optimal design: 3 components, 14 runs" in out and "D-optimal for the mixture-quadratic" in out
    d = pd.read_csv(p)
    assert list(d.columns) == ["std_order", "run_order", "coded_A", "coded_B", "coded_C", "a", "b", "c"]
    x = d[["a", "b", "c"]].to_numpy()
    assert np.all(np.abs(x.sum(axis=1) - 1) <= 1e-12)
    assert candidate_blends({"a": (0.1, 0.8), "b": (0.1, 0.8), "c": (0, 0.5)}, ["a + b <= 0.85"]).inside(x).all()
    assert len(d.drop_duplicates(["a", "b", "c"])) < 14  # the replicates
    data = tmp_path / "data.csv"
    _respond(p, data, np.random.default_rng(1))
    js = tmp_path / "fit.json"
    assert main(["fit", str(data), "--response", "y", *COMPS, "--model", "mixture-quadratic", "--json", str(js)]) == 0
    fit = json.loads(js.read_text())
    assert list(fit["coefficients"]["coded"]) == ["A", "B", "C", "AB", "AC", "BC"]
    assert fit["coefficients"]["actual"]["AB"] == pytest.approx(5.0, abs=1.0)


def test_optimal_mixture_process_then_fit(tmp_path, capsys):
    p = tmp_path / "opt.csv"
    argv = ["design", "optimal", *COMPS, "--factor", "t=20:40", "--criterion", "I", "--runs", "18", "--seed", "2",
            "-o", str(p)]
    assert main(argv) == 0
    assert "3 components and 1 process factor, 18 runs" in capsys.readouterr().out
    d = pd.read_csv(p)
    assert list(d.columns)[-4:] == ["a", "b", "c", "t"] and set(d["t"]) <= {20.0, 30.0, 40.0}
    data = tmp_path / "data.csv"
    _respond(p, data, np.random.default_rng(2), process="t")
    js = tmp_path / "fit.json"
    assert main(["fit", str(data), "--response", "y", *COMPS, "--factor", "t=20:40", "--model", "mixture-quadratic",
                 "--json", str(js)]) == 0
    assert len(json.loads(js.read_text())["coefficients"]["coded"]) == 12  # quadratic x linear process


@pytest.mark.parametrize("kind, extra, runs", [
    ("simplex-centroid", [], 7),
    ("simplex-lattice", ["--degree", "2"], 6),
    ("extreme-vertices", ["--centroids"], None),
])
def test_crossed_designs(tmp_path, capsys, kind, extra, runs):
    comps = COMPS if kind == "extreme-vertices" else ["--component", "a", "--component", "b", "--component", "c"]
    p = tmp_path / "x.csv"
    assert main(["design", kind, *comps, *extra, "--factor", "t=20:40", "--factor", "s=1:2", "--seed", "1",
                 "-o", str(p)]) == 0
    out = capsys.readouterr().out
    assert "crossed mixture-process design" in out and "2^2 factorial in t, s" in out
    d = pd.read_csv(p)
    blends = d[["a", "b", "c"]].drop_duplicates()
    if runs is not None:
        assert len(blends) == runs
    assert len(d) == 4 * len(blends)
    assert (d.groupby(["a", "b", "c"]).size() == 4).all()
    assert set(map(tuple, d[["t", "s"]].to_numpy())) == {(20.0, 1.0), (40.0, 1.0), (20.0, 2.0), (40.0, 2.0)}
    data = tmp_path / "data.csv"
    _respond(p, data, np.random.default_rng(3), process="t")
    js = tmp_path / "fit.json"
    comps_fit = COMPS if kind == "extreme-vertices" else ["--component", "a", "--component", "b", "--component", "c"]
    assert main(["fit", str(data), "--response", "y", *comps_fit, "--factor", "t=20:40", "--factor", "s=1:2",
                 "--model", "mixture-linear", "--json", str(js)]) == 0


def test_errors(tmp_path, capsys):
    out = tmp_path / "o.csv"
    # an empty region and one without interior: the constraint is named
    rc = main(["design", "optimal", *COMPS, "--constraint", "a + b <= 0.1", "-o", str(out)])
    line = error_line(capsys, rc)
    assert line.startswith("error: --constraint:") and "a + b <= 0.1" in line and "empty" in line
    rc = main(["design", "extreme-vertices", "--component", "a=0.5:0.8", "--component", "b=0.5:0.8",
               "--component", "c=0:0.5", "-o", str(out)])
    line = error_line(capsys, rc)
    assert line.startswith("error: --constraint:") and "no interior" in line and "a >= 0.5; b >= 0.5" in line
    rc = main(["design", "optimal", *COMPS, "--runs", "4", "-o", str(out)])
    assert error_line(capsys, rc).startswith("error: --runs:")
    rc = main(["design", "optimal", *COMPS, "--model", "quadratic", "-o", str(out)])
    assert error_line(capsys, rc).startswith("error: --model:")
    rc = main(["design", "simplex-centroid", "--component", "a", "--component", "b", "--factor", "a=0:1",
               "-o", str(out)])
    assert error_line(capsys, rc).startswith("error: --factor:")
    assert not out.exists()
    # fitting a design file: a row off the total, a component outside its bounds, too few blends
    p = tmp_path / "ev.csv"
    assert main(["design", "extreme-vertices", *COMPS, *CONS, "--centroids", "--seed", "1", "-o", str(p)]) == 0
    capsys.readouterr()
    good = _respond(p, tmp_path / "good.csv", np.random.default_rng(4))
    js = tmp_path / "fit.json"
    bad = good.copy()
    bad.loc[3, "a"] += 0.01
    bad.to_csv(tmp_path / "bad.csv", index=False)
    rc = main(["fit", str(tmp_path / "bad.csv"), "--response", "y", *COMPS, "--model", "mixture-linear",
               "--json", str(js)])
    assert "row 4: the components sum to 1.01" in error_line(capsys, rc)
    rc = main(["fit", str(tmp_path / "good.csv"), "--response", "y", "--component", "a=0.2:0.8", "--component",
               "b=0.1:0.8", "--component", "c=0:0.5", "--model", "mixture-linear", "--json", str(js)])
    line = error_line(capsys, rc)
    assert "component 'a'" in line and "outside its bounds 0.2..0.8" in line and line.startswith("error: ")
    few = good[good["a"].round(12).isin(good["a"].round(12).unique()[:3])]
    few.to_csv(tmp_path / "few.csv", index=False)
    rc = main(["fit", str(tmp_path / "few.csv"), "--response", "y", *COMPS, "--model", "mixture-cubic",
               "--json", str(js)])
    assert "distinct blends cannot fit 10 terms" in error_line(capsys, rc)
    assert not js.exists()
