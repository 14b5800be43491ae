"""A reader that closes standard output early (``rsm-lrg ... | head -2``) does not stop the
command: its output files are written whole and it exits 0 (rsm_lrg.cli._PipeGuard)."""

import os
import subprocess
import sys

import pandas as pd
import pytest


def _run_into_closed_pipe(args, cwd):
    """Run ``rsm-lrg ARGS`` with standard output a pipe whose reading end is already closed
    (every write fails with EPIPE, as after ``head`` has exited)."""
    r, w = os.pipe()
    os.close(r)
    try:
        proc = subprocess.run([sys.executable, "-m", "rsm_lrg", *args], stdout=w, stderr=subprocess.PIPE,
                              cwd=cwd, timeout=300, text=True)
    finally:
        os.close(w)
    return proc


def test_design_into_a_closed_pipe_still_writes_its_file(tmp_path):
    factors = [f"--factor={n}=0:1" for n in "abcde"]
    proc = _run_into_closed_pipe(["design", "definitive-screening", *factors, "--seed", "1", "-o", "ds.csv"], tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == ""
    assert len(pd.read_csv(tmp_path / "ds.csv")) == 13  # 2m + 1 runs for m = 6 (five factors, conference order 6)


@pytest.mark.slow
def test_fit_json_into_a_closed_pipe_still_writes_its_report(tmp_path):
    from rsm_lrg.datasets import data_path

    proc = _run_into_closed_pipe(["fit", str(data_path("table4.csv")), "--response", "tcr_c_per_min",
                                  "--json", "-", "--report", "r.html"], tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "r.html").read_text(encoding="utf-8").rstrip().endswith("</html>")
