"""Inputs under attack (issue 26 item 2): a path that exists is read as that file, glob
characters and all; categoric levels are the text in the file (``01`` is not ``1``); the
many-file path (a directory or a glob) keeps the one-file contract file by file: every error
names its file, columns are checked per file, lock and hidden files are skipped with a note,
the size limit applies per file, an unreadable file is exit 2.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from _cli_process import one_error_line, run_cli

from rsm_lrg.cli import main
from rsm_lrg.cli.file_sets import expand_data_path, skipped_reason
from rsm_lrg.datasets import data_path
from rsm_lrg.io import read_table

TABLE4 = Path(data_path("table4.csv"))
RESPONSE = "tcr_c_per_min"
ROOT = hasattr(os, "geteuid") and os.geteuid() == 0


def _one_error(capsys, *words) -> str:
    err = capsys.readouterr().err
    lines = [ln for ln in err.splitlines() if not ln.startswith("note:")]
    assert len(lines) == 1 and lines[0].startswith("error:"), err[-800:]
    assert "Traceback" not in err
    for w in words:
        assert w in lines[0], (w, lines[0])
    return lines[0]


def _fit_json(capsys, src, *extra):
    assert main(["fit", str(src), "--response", RESPONSE, "--json", "-", *extra]) == 0, capsys.readouterr().err
    cap = capsys.readouterr()
    return json.loads(cap.out), cap.err


def test_an_existing_path_with_glob_characters_is_that_file(tmp_path, capsys):
    # `fit 'run[1].csv'` once read the glob, i.e. the neighbouring run1.csv
    shutil.copy(TABLE4, tmp_path / "run[1].csv")
    other = pd.read_csv(TABLE4)
    other[RESPONSE] = other[RESPONSE] * 3.3
    other.to_csv(tmp_path / "run1.csv", index=False)
    got, _ = _fit_json(capsys, tmp_path / "run[1].csv")
    ref, _ = _fit_json(capsys, TABLE4)
    assert got["coefficients"]["coded"]["Intercept"] == pytest.approx(0.0336666667, rel=1e-8)
    assert got["coefficients"]["coded"] == ref["coefficients"]["coded"]
    assert expand_data_path(str(tmp_path / "run[1].csv")) is None
    assert expand_data_path(str(tmp_path / "run[1-9].csv")) == [str(tmp_path / "run1.csv")]


def _lots(tmp_path, codes=("01", "1", "02", "2")) -> Path:
    # four lots whose codes differ only in their text; each lot shifts y by its own amount
    rng = np.random.default_rng(7)
    shift = dict(zip(codes, (0.0, 1.0, 2.0, 3.0)))
    rows = [f"{x},{c},{1 + 0.5 * x + shift[c] + 0.01 * rng.standard_normal():.5f}"
            for x in (-1, 0, 1) for c in codes for _ in range(2)]
    p = tmp_path / "lots.csv"
    p.write_text("x,lot,y\n" + "\n".join(rows) + "\n")
    return p


def test_categoric_levels_are_the_text_in_the_file(tmp_path, capsys):
    lots = _lots(tmp_path)
    df = read_table(lots)
    assert sorted(set(df["lot"])) == ["01", "02", "1", "2"]  # not merged into 1, 2
    for spec in ("lot=cat", "lot=cat:01,1,02,2"):
        assert main(["fit", str(lots), "--response", "y", "--factor", "x", "--factor", spec, "--model", "linear",
                     "--json", "-"]) == 0
        out = json.loads(capsys.readouterr().out)
        (lot,) = [f for f in out["factors"] if f["name"] == "lot"]
        assert lot["levels"] == ["01", "1", "02", "2"]
        # four lots, each its own shift: the fit explains them (R^2 near 1; merged lots could not)
        assert out["statistics"]["r2"] > 0.999
    # used as a numeric factor, the same column still reads as numbers
    assert main(["fit", str(lots), "--response", "y", "--factor", "x", "--factor", "lot", "--model", "linear",
                 "--json", "-"]) == 0
    out = json.loads(capsys.readouterr().out)
    (lot,) = [f for f in out["factors"] if f["name"] == "lot"]
    assert (lot["low"], lot["high"]) == (1.0, 2.0)


def test_a_numeric_column_made_categoric_says_how_its_levels_are_written(tmp_path, capsys):
    p = tmp_path / "num.csv"
    p.write_text("x,lot,y\n" + "\n".join(f"{x},{lv},{x + i * 0.1:.3f}" for i, (x, lv) in
                                          enumerate([(-1, "1.0"), (1, "1"), (-1, "2"), (1, "2.0"), (0, "1"), (0, "2")]))
                 + "\n")
    assert main(["fit", str(p), "--response", "y", "--factor", "x", "--factor", "lot=cat", "--model", "linear"]) == 0
    out = capsys.readouterr().out
    assert "levels 1, 2" in out
    assert "Categoric factor 'lot' is read from a column of numbers" in out and "written 1, 2" in out


def _parts(tmp_path, n=3) -> Path:
    d = tmp_path / "parts"
    d.mkdir()
    df = pd.read_csv(TABLE4)
    for i in range(n):
        df.to_csv(d / f"p{i}.csv", index=False)
    return d


def test_lock_hidden_and_other_files_are_skipped_with_a_note(tmp_path, capsys):
    d = _parts(tmp_path)
    ref, _ = _fit_json(capsys, d)
    shutil.copy(TABLE4, d / "~$p0.csv")  # an Excel lock file (here a copy: it would be read twice)
    (d / ".~lock.p1.csv#").write_text("lock")
    (d / ".hidden.csv").write_bytes(b"\0" * 100)  # NUL-filled
    (d / "notes.txt").write_text("not data")
    (d / "p2.csv~").write_text("backup")
    got, err = _fit_json(capsys, d)
    assert got["n"] == ref["n"] == 81 and got["coefficients"] == ref["coefficients"]
    for name in ("~$p0.csv", ".~lock.p1.csv#", ".hidden.csv", "notes.txt", "p2.csv~"):
        assert name in err
    assert [skipped_reason(n) for n in ("~$a.csv", ".a.csv", "a.csv~", "a.txt", "a.csv")] == \
        ["lock", "hidden", "backup", "kind", None]


def _bad_other_columns(d):
    pd.read_csv(TABLE4).drop(columns=[RESPONSE]).to_csv(d / "p1.csv", index=False)
    return "p1.csv", "missing 'tcr_c_per_min'"


def _bad_nul(d):
    (d / "p1.csv").write_bytes(b"\0" * 50)
    return "p1.csv", "NUL"


def _bad_nul_deep(d):
    text = TABLE4.read_bytes()
    (d / "p1.csv").write_bytes(text[:200] + b"\0" + text[200:])
    row = text[:200].count(b"\n")  # the data row, as every other reader error counts (issue 36)
    return "p1.csv", f"NUL bytes, row {row})"


def _bad_text_cell(d):
    df = pd.read_csv(TABLE4, dtype=str)
    df.loc[4, "stroke_m"] = "abc"
    df.to_csv(d / "p2.csv", index=False)
    return "p2.csv", "row 5"


def _bad_empty_factor_cell(d):
    df = pd.read_csv(TABLE4)
    df.loc[3, "stroke_m"] = None
    df.to_csv(d / "p1.csv", index=False)
    return "p1.csv", "row 4"


def _bad_empty_file(d):
    (d / "p2.csv").write_text("")
    return "p2.csv", "empty"


def _bad_too_large(d):
    with open(d / "p1.csv", "r+b") as fh:  # a sparse file of 500 MB: refused before it is read
        fh.truncate(500 * 1024 * 1024)
    return "p1.csv", "limit"


BAD_PARTS = {"other-columns": _bad_other_columns, "nul-filled": _bad_nul, "nul-deep": _bad_nul_deep,
             "text-cell": _bad_text_cell, "empty-factor-cell": _bad_empty_factor_cell, "empty-file": _bad_empty_file,
             "too-large": _bad_too_large}


@pytest.mark.parametrize("how", ["directory", "glob"])
@pytest.mark.parametrize("kind", sorted(BAD_PARTS))
def test_a_bad_file_among_many_is_named(kind, how, tmp_path, capsys):
    d = _parts(tmp_path)
    name, word = BAD_PARTS[kind](d)
    before = {p.name: p.stat().st_size for p in d.iterdir()}
    src = d if how == "directory" else d / "p*.csv"
    assert main(["fit", str(src), "--response", RESPONSE, "--json", str(tmp_path / "out.json")]) == 2
    _one_error(capsys, name, word)
    assert {p.name: p.stat().st_size for p in d.iterdir()} == before
    assert not (tmp_path / "out.json").exists()


@pytest.mark.skipif(not ROOT or shutil.which("setpriv") is None, reason="needs root and setpriv (drop capabilities)")
def test_an_unreadable_file_among_many_is_exit_2(tmp_path):
    d = _parts(tmp_path)
    os.chmod(d / "p1.csv", 0)
    env = dict(os.environ, PYTHONPATH=str(Path(__file__).resolve().parents[2]))
    drop = "-dac_override,-dac_read_search"
    proc = subprocess.run(["setpriv", f"--inh-caps={drop}", f"--bounding-set={drop}", sys.executable, "-m",
                           "rsm_lrg", "fit", str(d), "--response", RESPONSE], env=env, text=True,
                          capture_output=True, timeout=300)
    assert proc.returncode == 2, proc.stderr
    lines = proc.stderr.splitlines()
    assert len(lines) == 1 and "p1.csv" in lines[0] and "Permission denied" in lines[0], proc.stderr


def test_parquet_schema_mismatch_is_a_clean_error(tmp_path, capsys):
    pytest.importorskip("pyarrow")
    df = pd.read_csv(TABLE4)
    df.to_parquet(tmp_path / "a.parquet", index=False)
    text = df.copy()
    text["stroke_m"] = text["stroke_m"].astype(str)
    text.to_parquet(tmp_path / "b.parquet", index=False)
    assert main(["fit", str(tmp_path / "[ab].parquet"), "--response", RESPONSE]) == 2
    _one_error(capsys, "b.parquet", "stroke_m", "text")
    df.drop(columns=["order"]).to_parquet(tmp_path / "c.parquet", index=False)
    assert main(["fit", str(tmp_path / "[ac].parquet"), "--response", RESPONSE]) == 2
    _one_error(capsys, "c.parquet", "missing 'order'")
    (tmp_path / "d.parquet").write_text("not parquet")
    assert main(["fit", str(tmp_path / "[ad].parquet"), "--response", RESPONSE]) == 2
    _one_error(capsys, "d.parquet", "not a readable Parquet file")
    # the good case: the same file twice fits as the one-file fit of the doubled table
    df.to_parquet(tmp_path / "e.parquet", index=False)
    got, _ = _fit_json(capsys, tmp_path / "[ae].parquet")
    assert got["n"] == 54


def test_parquet_limits_apply_to_what_the_file_unpacks_to(tmp_path, capsys, monkeypatch):
    # a small Parquet file may hold far more rows or bytes than its size says: the limits of
    # one table are checked on its metadata, before it is read
    pytest.importorskip("pyarrow")
    from rsm_lrg.cli import file_sets
    from rsm_lrg.io import MAX_ROWS

    df = pd.read_csv(TABLE4)
    df.to_parquet(tmp_path / "a.parquet", index=False)
    big = pd.DataFrame({c: np.zeros(MAX_ROWS + 1, dtype=np.int8) for c in df.columns})
    big.to_parquet(tmp_path / "b.parquet", index=False)
    assert (tmp_path / "b.parquet").stat().st_size < 2**20  # under a megabyte on disk
    assert main(["fit", str(tmp_path / "[ab].parquet"), "--response", RESPONSE]) == 2
    _one_error(capsys, "b.parquet", f"{MAX_ROWS + 1} rows")
    wide = pd.DataFrame({c: np.zeros(200_000) for c in df.columns})  # 9.6 MB of zeros unpacked
    wide.to_parquet(tmp_path / "c.parquet", index=False)
    monkeypatch.setattr(file_sets, "MAX_PARQUET_UNPACKED", 4 * 2**20)
    assert main(["fit", str(tmp_path / "[ac].parquet"), "--response", RESPONSE]) == 2
    _one_error(capsys, "c.parquet", "decompressed")


def test_codes_written_differently_across_files_are_not_merged(tmp_path, capsys):
    # the first file writes lot 1, 2; the second 01, 02: merging them as numbers would join
    # lots that the second file tells apart, so the file is named instead
    d = tmp_path / "parts"
    d.mkdir()
    lots = _lots(tmp_path)
    df = pd.read_csv(lots, dtype=str)
    df[df["lot"].isin(["1", "2"])].to_csv(d / "a.csv", index=False)
    df[df["lot"].isin(["01", "02"])].to_csv(d / "b.csv", index=False)
    assert main(["fit", str(d), "--response", "y", "--factor", "x", "--factor", "lot=cat", "--model", "linear"]) == 2
    _one_error(capsys, "b.csv", "leading zero", "'lot'")


def test_a_sub_directory_is_skipped_with_a_note(tmp_path, capsys):
    d = _parts(tmp_path, 2)
    (d / "more.csv").mkdir()
    shutil.copy(TABLE4, d / "more.csv" / "p9.csv")
    got, err = _fit_json(capsys, d)
    assert got["n"] == 54 and "sub-directory" in err and "more.csv" in err


def test_errors_on_standard_input_name_it_as_stdin(tmp_path):
    # issue 36: an error in what came on standard input named '-'; the others name the file
    proc = run_cli(["fit", "-", "--response", "b"], tmp_path, input="a,b\n1,x\n2,y\n", capture_output=True)
    assert proc.returncode == 2
    one_error_line(proc.stderr, "<stdin>: column 'b', row 1")


def test_a_nul_byte_is_named_by_its_data_row(tmp_path):
    # issue 36: the NUL-byte error said "line 21" where every other reader error says "row 20"
    lines = TABLE4.read_text().splitlines()
    lines[20] += "\0"
    (tmp_path / "nul.csv").write_text("\n".join(lines) + "\n")
    proc = run_cli(["fit", "nul.csv", "--response", RESPONSE], tmp_path, capture_output=True)
    assert proc.returncode == 2
    one_error_line(proc.stderr, "nul.csv", "NUL bytes, row 20)")
