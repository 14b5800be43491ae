"""What ``rsm-lrg fit`` loads at start-up (issue 11, item 3: the CLI imports only what a
command needs). Times are measured by benchmarks/bench_cli.py, never asserted here."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
# a plain CSV file of numbers is read into a ColumnTable without pandas (nor pyarrow, which
# pandas imports whenever it is installed): issue 37, item 6
HEAVY = ("pandas", "pyarrow", "scipy", "statsmodels", "matplotlib", "dask", "jinja2", "charset_normalizer",
         "rsm_lrg.optimize", "rsm_lrg.report")
THREADS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "BLIS_NUM_THREADS")


def _run_fit(args, env_extra=None):
    code = ("import sys, os, json, io, contextlib\nfrom rsm_lrg.cli import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n"
            f"    rc = main({list(args)!r})\n"
            f"heavy = sorted(m for m in sys.modules if m.split('.')[0] in {HEAVY!r} or m in {HEAVY!r})\n"
            "print(json.dumps([rc, heavy, os.environ.get('OPENBLAS_NUM_THREADS')]))")
    env = {k: v for k, v in os.environ.items() if k not in THREADS} | (env_extra or {})
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, env=env, timeout=120)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout.strip().splitlines()[-1])


FIT = ["fit", "data/table4.csv", "--response", "tcr_c_per_min"]


@pytest.mark.slow
@pytest.mark.parametrize("extra", [[], ["--json", "-"]])
def test_fit_loads_no_pandas_scipy_statsmodels_matplotlib(extra):
    # the regression core uses numpy's LAPACK and its own t/F tails (model.statistics);
    # statsmodels (result.ols), scipy and matplotlib are for other commands and options; a
    # plain file is read and fitted without pandas (rsm_lrg.table)
    rc, heavy, _ = _run_fit(FIT + extra)
    assert rc == 0
    assert heavy == []


def test_a_file_that_is_not_plain_is_read_by_pandas_and_fitted_alike(tmp_path):
    # a quoted header name is no plain CSV: the same fit through pandas, the same output
    text = (ROOT / "data" / "table4.csv").read_text()
    quoted = tmp_path / "quoted.csv"
    quoted.write_text(text.replace("thickness_m", '"thickness_m"', 1))
    rc, heavy, _ = _run_fit(["fit", str(quoted), "--response", "tcr_c_per_min", "--json", "-"])
    assert rc == 0 and "pandas" in heavy
    outs = []
    for path in (str(ROOT / "data" / "table4.csv"), str(quoted)):
        out = subprocess.run([sys.executable, "-m", "rsm_lrg", "fit", path, "--response", "tcr_c_per_min", "--json",
                              "-"], capture_output=True, text=True, cwd=ROOT, timeout=120)
        assert out.returncode == 0, out.stderr
        outs.append(out.stdout)
    assert outs[0] == outs[1]


@pytest.mark.slow
def test_small_input_uses_one_blas_thread_unless_the_user_chose():
    # a 27-run file: one OpenBLAS thread (threads cost start-up CPU and gain nothing here)
    assert _run_fit(FIT)[2] == "1"
    # a thread count the user set is left alone
    assert _run_fit(FIT, {"OMP_NUM_THREADS": "2"})[2] is None
    assert _run_fit(FIT, {"OPENBLAS_NUM_THREADS": "2"})[2] == "2"


def test_other_commands_use_one_blas_thread_unless_the_user_chose():
    rc, _, threads = _run_fit(["datasets"])
    assert (rc, threads) == (0, "1")
    assert _run_fit(["datasets"], {"MKL_NUM_THREADS": "2"})[2] is None


def test_large_input_keeps_blas_threads(tmp_path):
    from rsm_lrg.cli.cmd_fit import SMALL_INPUT_BYTES

    big = tmp_path / "big.csv"
    with open(big, "wb") as fh:  # only its size is looked at before NumPy is loaded
        fh.truncate(SMALL_INPUT_BYTES + 1)
    code = ("import os\nfrom rsm_lrg.cli.cmd_fit import one_blas_thread_if_small\n"
            f"one_blas_thread_if_small({str(big)!r})\nprint(os.environ.get('OPENBLAS_NUM_THREADS'))")
    env = {k: v for k, v in os.environ.items() if k not in THREADS}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, env=env, timeout=60)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "None"
