"""``simulate`` runs a design of any size piece by piece (issue 25): a CSV or Parquet design of
more than ``--chunk-rows`` rows is read, run and written a piece at a time, the rows equal to
the design run whole, errors name the row of the whole design, and the peak memory is bounded
by the piece, not the design (the 2,000,000-row check is slow)."""

import os
import resource
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from rsm_lrg.cli import main

ROOT = Path(__file__).resolve().parents[2]


def _design(n: int, seed: int = 0, flexible: float = 0.01) -> pd.DataFrame:
    """``n`` random runs in Table 3's box; a share ``flexible`` on the flexure stage (rfcms,
    whose stick-slip integrator costs far more per batch than the rigid stage's rows)."""
    rng = np.random.default_rng(seed)
    return pd.DataFrame({
        "run": np.arange(1, n + 1),
        "thickness_m": rng.uniform(1e-4, 5e-4, n).round(7),
        "stroke_m": rng.uniform(0.04, 0.06, n).round(5),
        "velocity_m_s": rng.uniform(0.4, 0.6, n).round(4),
        "acceleration_m_s2": rng.uniform(20, 40, n).round(3),
        "stage": np.where(rng.random(n) < flexible, "rfcms", "rms"),
    })


def _grid_design(n: int, seed: int = 0) -> pd.DataFrame:
    """``n`` runs of the rigid stage drawn from the 81 settings of Table 3's 3-level grid (a
    replicated design: each setting's network is solved once, so the rows cost I/O, not physics)."""
    rng = np.random.default_rng(seed)
    return pd.DataFrame({
        "run": np.arange(1, n + 1),
        "thickness_m": rng.choice([1e-4, 3e-4, 5e-4], n),
        "stroke_m": rng.choice([0.04, 0.05, 0.06], n),
        "velocity_m_s": rng.choice([0.4, 0.5, 0.6], n),
        "acceleration_m_s2": rng.choice([20.0, 30.0, 40.0], n),
        "stage": "rms",
    })


@pytest.fixture(scope="module")
def design(tmp_path_factory):
    d = tmp_path_factory.mktemp("stream")
    df = _design(2500)
    df.to_csv(d / "design.csv", index=False)
    df.to_csv(d / "semi.csv", sep=";", decimal=",", index=False)
    df.to_parquet(d / "design.parquet")
    return d


def test_pieces_give_the_rows_of_the_whole_design(design, tmp_path, capsys):
    whole = tmp_path / "whole.csv"
    assert main(["simulate", str(design / "design.csv"), "--seed", "5", "-o", str(whole)]) == 0
    assert "rows at a time" not in capsys.readouterr().err
    for src, extra in ((design / "design.csv", []), (design / "semi.csv", ["--decimal", ","]),
                       (design / "design.parquet", [])):
        out = tmp_path / f"piece_{src.name}.csv"
        assert main(["simulate", str(src), *extra, "--seed", "5", "--chunk-rows", "1000", "-o", str(out)]) == 0
        err = capsys.readouterr().err
        assert "1,000 rows at a time" in err and "2500 runs" in err, err
        if src.suffix == ".csv" and not extra:
            assert out.read_bytes() == whole.read_bytes()  # byte for byte
        else:
            pd.testing.assert_frame_equal(pd.read_csv(out), pd.read_csv(whole), check_exact=True)
    # Parquet out, piece by piece, the same numbers
    pq_out = tmp_path / "runs.parquet"
    assert main(["simulate", str(design / "design.parquet"), "--seed", "5", "--chunk-rows", "1000",
                 "-o", str(pq_out)]) == 0
    got = pd.read_parquet(pq_out)
    ref = pd.read_csv(whole)
    assert len(got) == 2500
    for col in ("tcr_c_per_min", "wear_volume_m3_per_h", "temperature_rise_k"):
        np.testing.assert_allclose(got[col].to_numpy(), ref[col].to_numpy(), rtol=1e-9)  # CSV keeps 10 digits


def test_an_error_in_a_later_piece_names_the_row_of_the_whole_design(design, tmp_path, capsys):
    df = _design(2500).astype({"velocity_m_s": object})
    df.loc[2200, "velocity_m_s"] = "fast"
    bad = tmp_path / "bad.csv"
    df.to_csv(bad, index=False)
    out = tmp_path / "out.csv"
    assert main(["simulate", str(bad), "--seed", "1", "--chunk-rows", "1000", "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "column 'velocity_m_s', row 2201: holds 'fast'" in err[0], err
    assert not out.exists() and not [p for p in tmp_path.iterdir() if p.name.startswith(".out")]  # nothing left


def _peak_rss_mib(rows: int, tmp_path: Path, chunk: int) -> float:
    """Peak resident memory [MiB] of ``rsm-lrg simulate`` on a design of ``rows`` rows, run in
    its own process (the design file is written piece by piece too)."""
    src = tmp_path / f"d{rows}.csv"
    with open(src, "w") as fh:
        for start in range(0, rows, 200_000):
            part = _grid_design(min(200_000, rows - start), seed=start)
            part.to_csv(fh, index=False, header=start == 0)
    code = ("import resource, sys; from rsm_lrg.cli import main; rc = main(sys.argv[1:]); "
            "print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss); sys.exit(rc)")
    env = dict(os.environ, PYTHONPATH=str(ROOT), OPENBLAS_NUM_THREADS="1")
    out = subprocess.run([sys.executable, "-c", code, "simulate", str(src), "--seed", "2", "--noise-sd", "0",
                          "--chunk-rows", str(chunk), "--no-progress", "-o", str(tmp_path / f"r{rows}.parquet")],
                         capture_output=True, text=True, env=env, timeout=1500)
    assert out.returncode == 0, out.stderr[-2000:]
    assert pd.read_parquet(tmp_path / f"r{rows}.parquet", columns=["tcr_c_per_min"]).shape[0] == rows
    return int(out.stdout.strip().splitlines()[-1]) / 1024.0


@pytest.mark.slow
def test_two_million_rows_in_memory_bounded_by_the_piece(tmp_path):
    # the same piece size: 10x the rows may not cost 10x the memory (the whole design as a
    # DataFrame alone, with its outputs, would take over 600 MiB). The rows repeat the 81
    # settings of a 3-level grid on the rigid stage: this checks the streaming, not the physics.
    small = _peak_rss_mib(200_000, tmp_path, chunk=50_000)
    big = _peak_rss_mib(2_000_000, tmp_path, chunk=50_000)
    print(f"peak RSS: 200,000 rows {small:.0f} MiB, 2,000,000 rows {big:.0f} MiB")
    assert big < 1.25 * small + 20, (small, big)
    assert resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0 < 2000  # this process held no design


# -- a line longer than any design row (issue 36) ---------------------------------------------
@pytest.mark.parametrize("extra", [2 * 1024 * 1024, 9 * 1024 * 1024])  # within one block; across three
def test_a_huge_line_is_refused_before_it_is_read(tmp_path, capsys, extra):
    """A 2 GB line was buffered by the streaming reader until memory ran out; every line is now
    measured in the counting pass (blocks of bounded size) and one over
    ``readers.MAX_STREAM_LINE_BYTES`` is refused naming its row, before any parsing."""
    from rsm_lrg import readers
    from rsm_lrg.cli import main
    from rsm_lrg.datasets import data_path

    d = pd.read_csv(data_path("table4.csv"))[["thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2"]]
    lines = pd.concat([d] * 50, ignore_index=True).to_csv(index=False).splitlines()  # 1350 rows
    lines[1201] += "," + "9" * extra
    p = tmp_path / "long.csv"
    p.write_text("\n".join(lines) + "\n")
    out = tmp_path / "o.csv"
    assert main(["simulate", str(p), "--chunk-rows", "1000", "--no-progress", "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "row 1201 is longer than the limit" in err[0] and str(p.name) in err[0], err
    assert not out.exists()
    # the bound is a parameter of the counting pass; the rows count as before under it
    with open(p, "rb") as fh:
        with pytest.raises(readers.TableError, match="row 1201"):
            readers.count_rows(fh, "csv")
        assert readers.count_rows(fh, "csv", max_line_bytes=extra + 100) == 1350
        with pytest.raises(readers.TableError, match="in the header"):
            readers.count_rows(fh, "csv", max_line_bytes=10)
