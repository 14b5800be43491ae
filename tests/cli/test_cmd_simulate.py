"""``rsm-lrg simulate``: through a real subprocess and through rsm_lrg.cli.main."""

import subprocess
import sys

import numpy as np
import pandas as pd
import pytest

from rsm_lrg.cli import main
from rsm_lrg.surrogate import simulate


def run(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "rsm_lrg", *args], capture_output=True, text=True, cwd=cwd)


@pytest.fixture()
def design_csv(tmp_path):
    p = tmp_path / "design.csv"
    pd.DataFrame({
        "run": [1, 2, 3, 4],
        "thickness_m": [3e-4, 5e-4, 3e-4, None],
        "stroke_m": [0.05, 0.04, 0.06, 0.05],
        "velocity_m_s": [0.5, 0.4, 0.6, 0.5],
        "acceleration_m_s2": [30, 20, 40, 30],
        "stage": ["rfcms", "rfcms", "rfcms", "rms"],
        "operator": ["a", "b", "c", "d"],
    }).to_csv(p, index=False)
    return p


def test_subprocess_writes_runs_with_every_input_column(design_csv, tmp_path):
    out = tmp_path / "runs.csv"
    r = run("simulate", str(design_csv), "--seed", "3", "-o", str(out))
    assert r.returncode == 0, r.stderr
    df = pd.read_csv(out)
    inp = pd.read_csv(design_csv)
    assert list(df.columns[: inp.shape[1]]) == list(inp.columns)
    for c in ("tcr_c_per_min", "temperature_rise_k", "steady_rise_k", "wear_volume_m3_per_h",
              "sliding_distance_m_per_cycle"):
        assert np.isfinite(df[c]).all()
    # the same as the library with the same seed and the default noise (10 significant digits in the CSV)
    lib = simulate(inp, seed=3)
    np.testing.assert_allclose(df.tcr_c_per_min, lib.tcr_c_per_min, rtol=1e-9)


def test_workers_and_seed_give_identical_files(design_csv, tmp_path):
    a, b = tmp_path / "a.csv", tmp_path / "b.csv"
    assert main(["simulate", str(design_csv), "--seed", "5", "-o", str(a)]) == 0
    assert main(["simulate", str(design_csv), "--seed", "5", "--workers", "2", "-o", str(b)]) == 0
    assert a.read_bytes() == b.read_bytes()


def test_noise_free_and_uncalibrated(design_csv, tmp_path):
    a, b = tmp_path / "a.csv", tmp_path / "b.csv"
    assert main(["simulate", str(design_csv), "--noise-sd", "0", "--uncalibrated", "-o", str(a)]) == 0
    lib = simulate(pd.read_csv(design_csv), noise_sd=0, calibration=None)
    np.testing.assert_allclose(pd.read_csv(a).tcr_c_per_min, lib.tcr_c_per_min, rtol=1e-9)
    assert main(["simulate", str(design_csv), "--noise-sd", "0", "--param", "mu_k=0.04", "--uncalibrated",
                 "-o", str(b)]) == 0
    # Eq. 8: heat proportional to mu_k (RMS row: sliding does not depend on friction)
    assert pd.read_csv(b).heat_w[3] == pytest.approx(2 * pd.read_csv(a).heat_w[3], rel=1e-8)


def test_seed_is_printed_when_not_given(design_csv, tmp_path, capsys):
    assert main(["simulate", str(design_csv), "-o", str(tmp_path / "r.csv")]) == 0
    assert "--seed" in capsys.readouterr().err


@pytest.mark.parametrize("content,needle", [
    ("thickness_m,stroke_m,velocity_m_s\n3e-4,0.05,0.5\n", "acceleration_m_s2"),
    ("thickness_m,stroke_m,velocity_m_s,acceleration_m_s2\n3e-4,0.05,0.5,30\n3e-4,-0.05,0.5,30\n",
     "column 'stroke_m', row 2"),
    ("thickness_m,stroke_m,velocity_m_s,acceleration_m_s2,stage\n3e-4,0.05,0.5,30,rigid\n", "column 'stage', row 1"),
    ("thickness_m,stroke_m,velocity_m_s,acceleration_m_s2\n3e-4,0.05,,30\n", "column 'velocity_m_s', row 1"),
])
def test_bad_design_is_one_error_line(tmp_path, content, needle):
    p = tmp_path / "bad.csv"
    p.write_text(content)
    r = run("simulate", str(p), "-o", str(tmp_path / "out.csv"))
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error:") and needle in lines[0] and "bad.csv" in lines[0]
    assert not (tmp_path / "out.csv").exists()


def test_existing_output_needs_force(design_csv, tmp_path, capsys):
    out = tmp_path / "runs.csv"
    out.write_text("keep me")
    assert main(["simulate", str(design_csv), "--seed", "1", "-o", str(out)]) == 2
    assert "--force" in capsys.readouterr().err and out.read_text() == "keep me"
    assert main(["simulate", str(design_csv), "--seed", "1", "-o", str(out), "--force"]) == 0
    assert "tcr_c_per_min" in out.read_text()


def test_bad_options(design_csv, tmp_path, capsys):
    o = str(tmp_path / "o.csv")
    for args in (["--noise-sd", "-1"], ["--workers", "0"], ["--duration-min", "0.5"],
                 ["--workers", "2", "--scheduler", "tcp://127.0.0.1:1"], ["--param", "nope=1"],
                 ["--calibration", str(tmp_path / "missing.toml")]):
        assert main(["simulate", str(design_csv), *args, "-o", o]) == 2, args
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and err[0].startswith("error:"), (args, err)


@pytest.mark.slow
def test_unreachable_scheduler_is_a_clear_error(design_csv, tmp_path, capsys):
    pytest.importorskip("distributed")
    assert main(["simulate", str(design_csv), "--scheduler", "tcp://127.0.0.1:9", "-o",
                 str(tmp_path / "o.csv")]) == 2
    err = capsys.readouterr().err
    assert "tcp://127.0.0.1:9" in err and "nothing listens there (connection refused)" in err


@pytest.mark.cluster
@pytest.mark.slow
def test_scheduler_gives_the_same_file_as_one_process(design_csv, tmp_path):
    distributed = pytest.importorskip("distributed")
    one, dask = tmp_path / "one.csv", tmp_path / "dask.csv"
    assert main(["simulate", str(design_csv), "--seed", "8", "-o", str(one)]) == 0
    with distributed.LocalCluster(processes=True, n_workers=2, threads_per_worker=1, host="127.0.0.1",
                                  dashboard_address=None) as cluster:
        r = run("simulate", str(design_csv), "--seed", "8", "--scheduler", cluster.scheduler_address, "-o", str(dask))
    assert r.returncode == 0, r.stderr
    assert one.read_bytes() == dask.read_bytes()


def _plain_and_quoted(tmp_path):
    """Table 4 as it is (plain: read without pandas) and with one header name quoted (not plain:
    read by pandas), the same table."""
    from pathlib import Path

    text = (Path(__file__).resolve().parents[2] / "data" / "table4.csv").read_text()
    plain, quoted = tmp_path / "plain.csv", tmp_path / "quoted.csv"
    plain.write_text(text)
    quoted.write_text(text.replace("order", '"order"', 1))
    return plain, quoted


def test_a_plain_design_runs_without_pandas_and_writes_the_same_file(tmp_path):
    plain, quoted = _plain_and_quoted(tmp_path)
    code = ("import sys, io, contextlib\nfrom rsm_lrg.cli import main\n"
            "with contextlib.redirect_stderr(io.StringIO()):\n"
            f"    rc = main(['simulate', {str(plain)!r}, '--seed', '3', '-o', {str(tmp_path / 'a.csv')!r}])\n"
            "print(rc, 'pandas' in sys.modules, 'pyarrow' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["0", "False", "False"]
    r = run("simulate", str(quoted), "--seed", "3", "-o", str(tmp_path / "b.csv"))
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "a.csv").read_bytes() == (tmp_path / "b.csv").read_bytes()
    a = run("simulate", str(plain), "--seed", "3", "-o", str(tmp_path / "c.csv"))
    assert a.stderr.replace("c.csv", "b.csv").replace(str(plain), str(quoted)) == r.stderr  # the same notes
    assert (tmp_path / "c.csv").read_bytes() == (tmp_path / "b.csv").read_bytes()


def test_a_plain_design_with_a_stage_of_numbers_is_refused_in_the_same_words(tmp_path):
    plain, quoted = _plain_and_quoted(tmp_path)
    for p in (plain, quoted):
        p.write_text(p.read_text().replace("tcr_c_per_min", "stage", 1))
    a = run("simulate", str(plain), "--seed", "3", "-o", str(tmp_path / "a.csv"))
    b = run("simulate", str(quoted), "--seed", "3", "-o", str(tmp_path / "b.csv"))
    assert a.returncode == b.returncode == 2
    assert a.stderr.replace(str(plain), "D") == b.stderr.replace(str(quoted), "D")
    assert "column 'stage', row 1" in a.stderr
    assert not (tmp_path / "a.csv").exists()
