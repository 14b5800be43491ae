"""``rsm-lrg calibrate``: writes a calibration TOML that ``simulate --calibration`` uses."""

import subprocess
import sys
import tomllib

import numpy as np
import pandas as pd
import pytest

from rsm_lrg.cli import main
from rsm_lrg.surrogate import simulate

HEAT = ["--model", "v4", "--parameter", "heat_partition", "--parameter", "viscous_friction_n_s_m"]


@pytest.fixture()
def measured(tmp_path):
    # "measured" runs made by the surrogate with known parameters (an exact solution)
    rng = np.random.default_rng(4)
    n = 10
    d = pd.DataFrame({"run": np.arange(1, n + 1), "thickness_m": rng.choice([3e-4, 5e-4], n),
                      "stroke_m": rng.uniform(0.04, 0.06, n), "velocity_m_s": rng.uniform(0.4, 0.6, n),
                      "acceleration_m_s2": rng.uniform(20, 40, n)})
    d["kappa"] = simulate(d, noise_sd=0, calibration={"heat_partition": 0.3, "viscous_friction_n_s_m": 8.0}).tcr_c_per_min
    p = tmp_path / "measured.csv"
    d.to_csv(p, index=False)
    return p, d


@pytest.mark.slow
def test_calibrate_then_simulate_reproduces_the_data(measured, tmp_path, capsys):
    p, d = measured
    d.rename(columns={"kappa": "tcr_c_per_min"}).to_csv(p, index=False)
    toml = tmp_path / "cal.toml"
    assert main(["calibrate", str(p), "--response", "tcr_c_per_min", *HEAT, "-o", str(toml)]) == 0
    out = capsys.readouterr().out
    assert "heat_partition" in out and "leave-one-out R2" in out
    raw = tomllib.loads(toml.read_text())
    assert raw["calibration"]["data"] == "measured.csv" and len(raw["calibration"]["data_sha256"]) == 64
    assert raw["parameters"]["heat_partition"]["value"] == pytest.approx(0.3, rel=1e-5)
    assert raw["calibration"]["r2"] == pytest.approx(1.0, abs=1e-9)
    runs = tmp_path / "runs.csv"
    assert main(["simulate", str(p), "--noise-sd", "0", "--calibration", str(toml), "-o", str(runs)]) == 0
    got = pd.read_csv(runs)
    np.testing.assert_allclose(got.tcr_c_per_min, got.tcr_c_per_min_input, rtol=1e-6)


def test_json_and_force(measured, tmp_path, capsys):
    p, d = measured
    toml = tmp_path / "cal.toml"
    toml.write_text("old")
    args = ["calibrate", str(p), "--response", "kappa", *HEAT, "--no-loo", "-o", str(toml)]
    assert main(args) == 2
    assert "--force" in capsys.readouterr().err and toml.read_text() == "old"
    # kappa is not a surrogate output column: a clear error
    assert main(args + ["--force"]) == 2
    assert "does not produce 'kappa'" in capsys.readouterr().err


@pytest.mark.slow
@pytest.mark.parametrize("extra,needle", [
    (["--parameter", "offset"], "unknown calibration parameter"),
    (["--parameter", "heat_partition", "--parameter", "viscous_friction_n_s_m", "--parameter", "hinge_length_m",
      "--parameter", "hinge_width_m"], "at most three"),
    # the repeated name is named (it was 'a calibration parameter is given twice')
    (["--parameter", "heat_partition", "--parameter", "heat_partition"], "heat_partition is given twice"),
])
def test_bad_parameters_are_one_error_line(measured, extra, needle):
    p, d = measured
    d.rename(columns={"kappa": "tcr_c_per_min"}).to_csv(p, index=False)
    r = subprocess.run([sys.executable, "-m", "rsm_lrg", "calibrate", str(p), "--response", "tcr_c_per_min", "--model",
                        "v4", *extra],
                       capture_output=True, text=True)
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error:") and needle in lines[0]


def test_missing_response_column(measured, capsys):
    p, _ = measured
    assert main(["calibrate", str(p), "--response", "nope"]) == 2
    err = capsys.readouterr().err
    assert "measured.csv" in err and "'nope'" in err
