"""``rsm-lrg evaluate DESIGN.csv --power`` (issue 35, item 4): Monte Carlo power on the command
line — JSON and the text table equal the library's simulation, and bad input exits 2 with one
line naming the option."""

import itertools
import json
import subprocess
import sys

import numpy as np
import pandas as pd
import pytest
from _cli_errors import error_line
from _cli_process import cli_env

from rsm_lrg.cli import main
from rsm_lrg.model.power import simulate_power


def _csv(path, rows, plots=None):
    rows = np.asarray(rows, dtype=float)
    df = pd.DataFrame({"std_order": np.arange(1, len(rows) + 1), "run_order": np.arange(1, len(rows) + 1)})
    if plots is not None:
        df["whole_plot"] = plots
    for j, L in enumerate("ABC"):
        df[f"coded_{L}"] = rows[:, j]
    for j, L in enumerate("ABC"):
        df[L] = 10.0 + 5.0 * rows[:, j]
    df.to_csv(path, index=False)
    return path


@pytest.fixture(scope="module")
def factorial(tmp_path_factory):
    rows = list(itertools.product([-1, 1], repeat=3)) * 2
    return _csv(tmp_path_factory.mktemp("pw") / "ff.csv", rows)


@pytest.fixture(scope="module")
def split_plot(tmp_path_factory):
    rows, plots = [], []
    for w, a in enumerate([-1, 1] * 3):
        for b, c in itertools.product([-1, 1], repeat=2):
            rows.append((a, b, c))
            plots.append(w + 1)
    return _csv(tmp_path_factory.mktemp("pw") / "sp.csv", rows, plots)


def _json(capsys, argv):
    capsys.readouterr()
    assert main(argv + ["--json", "-"]) == 0
    return json.loads(capsys.readouterr().out)["power_simulation"]


def test_json_equals_the_library_and_the_table_shows_both_powers(factorial, capsys):
    out = _json(capsys, ["evaluate", str(factorial), "--model", "linear", "--power", "--effect-size", "1.5",
                         "--draws", "3000", "--seed", "4"])
    rows = np.array(list(itertools.product([-1.0, 1.0], repeat=3)) * 2)
    lib = simulate_power(rows, "linear", effect_sd=1.5, draws=3000, seed=4).to_dict()["power_simulation"]
    assert out == lib
    assert out["family"] == "gaussian" and out["draws"] == 3000 and set(out["terms"]) == {"A", "B", "C"}
    assert all(abs(t["power"] - t["parametric"]) < 4 * t["mc_se"] + 1e-9 for t in out["terms"].values())
    capsys.readouterr()
    assert main(["evaluate", str(factorial), "--model", "linear", "--power", "--effect", "1.5",
                 "--draws", "3000", "--seed", "4"]) == 0
    text = capsys.readouterr().out
    assert "Power (simulated)" in text and "Power (exact, noncentral F)" in text
    assert f"{100 * out['terms']['A']['power']:.1f} %" in text


def test_split_plot_and_binomial_on_the_command_line(split_plot, factorial, capsys):
    sp = _json(capsys, ["evaluate", str(split_plot), "--model", "linear", "--power", "--draws", "30", "--seed", "2",
                        "--variance-ratio", "0.5"])
    assert sp["whole_plots"] == 6 and sp["variance_ratio"] == 0.5 and "Kenward" in sp["analysis"]
    assert all(t["parametric"] is None for t in sp["terms"].values())
    bi = _json(capsys, ["evaluate", str(factorial), "--model", "linear", "--power", "--family", "binomial",
                        "--baseline", "0.4", "--effect-size", "3", "--draws", "30", "--seed", "2"])
    assert bi["baseline"] == 0.4 and bi["family"] == "binomial" and "likelihood-ratio" in bi["analysis"]
    assert bi["separated"] + bi["failed"] <= 30


@pytest.mark.parametrize("extra, option", [
    (["--power", "--draws", "0"], "--draws"),
    (["--power", "--family", "binomial", "--baseline", "1.5"], "--baseline"),
    (["--power", "--baseline", "0.3"], "--baseline"),
    (["--draws", "100"], "--draws"),
    (["--family", "binomial"], "--family"),
    (["--power", "--seed", "-1"], "--seed"),
    (["--power", "--workers", "0"], "--workers"),
    (["--power", "--region", "sphere"], "--region"),
    (["--power", "--variance-ratio", "2"], "--variance-ratio"),
])
def test_bad_input_is_one_line_naming_the_option(factorial, capsys, extra, option):
    line = error_line(capsys, main(["evaluate", str(factorial), "--model", "linear", *extra]))
    assert option in line


def test_binomial_with_whole_plots_is_refused(split_plot, capsys):
    line = error_line(capsys, main(["evaluate", str(split_plot), "--model", "linear", "--power", "--family",
                                    "binomial"]))
    assert "--family" in line and "whole plots" in line


def test_power_takes_one_design(factorial, capsys):
    line = error_line(capsys, main(["evaluate", str(factorial), str(factorial), "--power"]))
    assert "--power" in line or "once" in line


def test_a_dask_scheduler_gives_the_numbers_of_one_process(split_plot, capsys):
    """``--scheduler``: the blocks of draws run on a real local Dask cluster (two worker
    processes) and give the same JSON as one process."""
    distributed = pytest.importorskip("distributed")
    argv = ["evaluate", str(split_plot), "--model", "linear", "--power", "--draws", "40", "--seed", "3"]
    one = _json(capsys, argv)
    with distributed.LocalCluster(processes=True, n_workers=2, threads_per_worker=1, host="127.0.0.1",
                                  dashboard_address=None) as cluster:
        # as a process: an event loop left running in this one (a browser test's) would stop the client
        done = subprocess.run([sys.executable, "-m", "rsm_lrg", *argv, "--scheduler", cluster.scheduler_address,
                               "--json", "-"], capture_output=True, text=True, env=cli_env(), timeout=600)
    assert done.returncode == 0, done.stderr
    dask = json.loads(done.stdout)["power_simulation"]
    assert {k: v for k, v in dask.items() if k != "seconds"} == {k: v for k, v in one.items() if k != "seconds"}


@pytest.mark.parametrize("extra, option", [
    (["--scheduler", "tcp://127.0.0.1:9"], "--scheduler"),  # without --power
    (["--power", "--workers", "2", "--scheduler", "tcp://127.0.0.1:9"], "--scheduler"),
])
def test_scheduler_options_are_checked(factorial, capsys, extra, option):
    line = error_line(capsys, main(["evaluate", str(factorial), "--model", "linear", *extra]))
    assert option in line
