"""``rsm-lrg optimize --dispersion``: hit the mean's target while minimising the modelled spread
s = exp(ln s); the optimum's desirability is checked against a grid search computed here from
the two fitted equations and Derringer-Suich's formulas written out."""

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from _cli_errors import error_line

from rsm_lrg.cli import main

DATA = str(Path(__file__).parents[1] / "model" / "r" / "dispersion_cure.csv")
BASE = ["optimize", DATA, "--response", "yield_pct", "--factor", "temp_c", "--factor", "time_min"]


def test_target_the_mean_minimise_the_spread(capsys):
    import rsm_lrg

    assert main(BASE + ["--goal", "target=50", "--dispersion", "--json", "-"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["responses"] == ["yield_pct", "s(yield_pct)"]
    d = pd.read_csv(DATA)
    mean = rsm_lrg.fit(d, "yield_pct", factors=["temp_c", "time_min"])
    b = rsm_lrg.fit_dispersion(d, "yield_pct", factors=mean.space).result.coefficients["coded"]
    # the grid, with the desirabilities written out (limits: the observed ranges of y and of s)
    a, c = np.meshgrid(np.linspace(-1, 1, 201), np.linspace(-1, 1, 201))
    X = pd.DataFrame({"temp_c": 170 + 20 * a.ravel(), "time_min": 20 + 10 * c.ravel()})
    y = mean.predict(X)["predicted"].to_numpy()
    s = np.exp(b["Intercept"] + b["A"] * a.ravel() + b["B"] * c.ravel())
    lo, hi = d.yield_pct.min(), d.yield_pct.max()
    g = d.groupby(["temp_c", "time_min"]).yield_pct
    sd = g.std()[g.size() >= 2]
    d1 = np.where(y <= 50, (y - lo) / (50 - lo), (hi - y) / (hi - 50)).clip(0, 1)
    d2 = ((sd.max() - s) / (sd.max() - sd.min())).clip(0, 1)
    D = np.sqrt(d1 * d2)
    assert out["goals"][1]["low"] == pytest.approx(sd.min(), rel=1e-12)
    assert out["desirability"] >= D.max() - 1e-9  # nothing on the grid beats the optimum
    assert out["desirability"] - D.max() < 5e-3  # and the grid comes close to it
    A = (out["actual"]["temp_c"] - 170) / 20
    B = (out["actual"]["time_min"] - 20) / 10
    assert out["predicted"]["s(yield_pct)"] == pytest.approx(np.exp(b["Intercept"] + b["A"] * A + b["B"] * B), rel=1e-9)
    assert out["predicted"]["yield_pct"] == pytest.approx(50, abs=1e-4)
    # the spread moved the optimum: the mean alone is on target along a whole curve, the spread picks
    # its low-s end (temp low, time high: ln s falls with B and rises with A)
    assert out["actual"]["time_min"] == pytest.approx(30, abs=1e-6)
    assert out["models"]["s(yield_pct)"].startswith("ln s linear (8 replicated settings)")


def test_dispersion_with_interval_is_refused(capsys):
    line = error_line(capsys, main(BASE + ["--dispersion", "--interval", "pi"]))
    assert line.startswith("error: --dispersion:")
