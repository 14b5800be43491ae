"""``rsm-lrg optimize``: the paper's optimum (Sec. 4.3 / DIGEST) and bad input."""

import hashlib
import json
from pathlib import Path

import pytest

from rsm_lrg.cli import main
from rsm_lrg.datasets import data_path

TABLE4 = str(data_path("table4.csv"))


def test_optimize_minimize_json(capsys):
    before = hashlib.sha256(Path(TABLE4).read_bytes()).hexdigest()
    assert main(["optimize", TABLE4, "--response", "tcr_c_per_min", "--goal", "minimize", "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    # DIGEST: thickness 0.0001, stroke 0.04, velocity 0.4, acceleration 20, kappa 0.02283;
    # the confirmation run 0.024 inside the 95 % PI (0.0159-0.0298).
    assert d["actual"] == {"thickness_m": 0.0001, "stroke_m": 0.04, "velocity_m_s": 0.4, "acceleration_m_s2": 20.0}
    assert round(d["predicted"], 5) == 0.02283
    assert d["confidence"] == 0.95 and d["pi"][0] < 0.024 < d["pi"][1]
    assert list(d)[:8] == ["response", "goal", "coded", "actual", "predicted", "confidence", "ci", "pi"]
    assert hashlib.sha256(Path(TABLE4).read_bytes()).hexdigest() == before


def test_optimize_text_and_bounds(capsys):
    assert main(["optimize", TABLE4, "--response", "tcr_c_per_min", "--goal", "maximize",
                 "--bound", "velocity_m_s=0.45:0.55"]) == 0
    out = capsys.readouterr().out
    assert "velocity_m_s = 0.550000" in out and "95 % PI" in out


@pytest.mark.parametrize("extra, needle", [
    (["--goal", "fastest"], "goal must be"),
    (["--goal", "target=abc"], "not a number"),
    (["--bound", "speed=0.4:0.5"], "no such factor"),
    (["--bound", "velocity_m_s=0.3:0.5"], "outside the design range"),
    (["--bound", "velocity_m_s=0.5:0.45"], "LOW must be below HIGH"),
])
def test_optimize_bad_input(extra, needle, capsys):
    assert main(["optimize", TABLE4, "--response", "tcr_c_per_min", *extra]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error:") and needle in err[0], err
