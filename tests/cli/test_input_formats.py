"""Every command reads CSV in any common dialect, .xlsx, a single .parquet file and standard
input (``-``): ``fit`` gives the same numbers as from the comma CSV, states what it read,
and each bad variant is exit 2 with one ``error:`` line naming the file (issue 25)."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

from rsm_lrg.cli import main
from rsm_lrg.datasets import data_path

TABLE4 = str(data_path("table4.csv"))
ROOT = Path(__file__).resolve().parents[2]


def _fit_json(capsys, *argv):
    assert main(["fit", *argv, "--response", "tcr_c_per_min", "--json", "-"]) == 0
    cap = capsys.readouterr()
    return json.loads(cap.out), cap.err


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("formats")
    df = pd.read_csv(TABLE4)
    df.to_csv(d / "semi.csv", sep=";", decimal=",", index=False)
    df.to_csv(d / "semi_point.csv", sep=";", index=False)
    df.to_csv(d / "tab.tsv", sep="\t", index=False)
    with pd.ExcelWriter(d / "book.xlsx") as w:
        df.to_excel(w, sheet_name="Runs", index=False)
        pd.DataFrame({"remark": ["rig 2"]}).to_excel(w, sheet_name="Notes", index=False)
    df.to_excel(d / "one.xlsx", sheet_name="Runs", index=False)
    df.to_parquet(d / "runs.parquet")
    return d


def test_every_format_fits_to_the_same_numbers(files, capsys):
    ref, err = _fit_json(capsys, TABLE4)
    assert "note: read" not in err  # the plain comma CSV is not remarked upon
    cases = [
        ([str(files / "semi.csv"), "--decimal", ","], "CSV, separator ';' (detected), decimal ','"),
        ([str(files / "semi.csv"), "--sep", ";", "--decimal", ","], "CSV, separator ';', decimal ','"),
        ([str(files / "semi_point.csv")], "CSV, separator ';' (detected), decimal '.'"),
        ([str(files / "tab.tsv"), "--sep", "tab"], "CSV, separator tab, decimal '.'"),
        ([str(files / "book.xlsx"), "--sheet", "Runs"], "sheet 'Runs' of an Excel workbook"),
        ([str(files / "one.xlsx")], "sheet 'Runs' of an Excel workbook"),
        ([str(files / "runs.parquet")], "a Parquet file"),
    ]
    for argv, said in cases:
        got, err = _fit_json(capsys, *argv)
        assert f"note: read {argv[0]}: {said}" in err, (argv, err)
        assert got["coefficients"] == ref["coefficients"], argv
        assert got["anova"] == ref["anova"], argv


def test_standard_input(files):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    out = subprocess.run([sys.executable, "-m", "rsm_lrg", "fit", "-", "--response", "tcr_c_per_min",
                          "--decimal", ",", "--json", "-"], input=(files / "semi.csv").read_bytes(),
                         capture_output=True, env=env, timeout=120)
    assert out.returncode == 0, out.stderr
    assert b"note: read <stdin>: CSV, separator ';' (detected), decimal ','" in out.stderr
    ref = subprocess.run([sys.executable, "-m", "rsm_lrg", "fit", TABLE4, "--response", "tcr_c_per_min",
                          "--json", "-"], capture_output=True, env=env, timeout=120)
    assert json.loads(out.stdout)["coefficients"] == json.loads(ref.stdout)["coefficients"]


def test_bad_variants_one_error_line(files, tmp_path, capsys):
    x = (files / "one.xlsx").read_bytes()
    q = (files / "runs.parquet").read_bytes()
    bad_cell = pd.read_csv(TABLE4).astype(object)
    bad_cell.loc[4, "velocity_m_s"] = "fast"
    bad_cell.to_excel(tmp_path / "cell.xlsx", index=False, sheet_name="Runs")
    bad_cell.astype({c: str for c in bad_cell.columns}).to_parquet(tmp_path / "cell.parquet")  # text columns
    (tmp_path / "cut.xlsx").write_bytes(x[: len(x) // 3])
    (tmp_path / "cut.parquet").write_bytes(q[: len(q) // 3])
    cases = [
        ([str(files / "semi.csv")], r"semi.csv: column 'thickness_m' row 1: '0,0003' is written with a decimal comma"),
        ([str(files / "semi_point.csv"), "--decimal", ","], "semi_point.csv: column 'thickness_m' row 1"),
        ([str(files / "book.xlsx")], "book.xlsx: the workbook has 2 sheets ('Runs', 'Notes'); choose one with --sheet"),
        ([str(files / "book.xlsx"), "--sheet", "Run"], "book.xlsx: no sheet 'Run' in the workbook"),
        ([str(tmp_path / "cell.xlsx")], "cell.xlsx: column 'velocity_m_s', row 5"),
        ([str(tmp_path / "cell.parquet")], "cell.parquet: column 'velocity_m_s', row 5"),
        ([str(tmp_path / "cut.xlsx")], "cut.xlsx: is not a readable Excel workbook"),
        ([str(tmp_path / "cut.parquet")], "cut.parquet: is not a readable Parquet file"),
        ([str(files / "runs.parquet"), "--sheet", "Runs"], "runs.parquet: --sheet 'Runs' is for an Excel workbook"),
    ]
    for argv, said in cases:
        assert main(["fit", *argv, "--response", "tcr_c_per_min"]) == 2, argv
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and err[0].startswith("error: "), (argv, err)
        assert said in err[0], (argv, err)
    assert main(["fit", TABLE4, "--response", "tcr_c_per_min", "--sep", ":"]) == 2
    assert "--sep: ':' is not a separator read" in capsys.readouterr().err


@pytest.mark.parametrize("command", [
    ["fit-summary"], ["ridge"], ["effects", "--model", "linear"], ["optimize"],
    ["confirm", "--at", "thickness_m=0.0004", "stroke_m=0.05", "velocity_m_s=0.5", "acceleration_m_s2=40",
     "--observed", "0.03"],
])
def test_analysis_commands_read_the_same_way(files, capsys, command):
    name, *rest = command
    assert main([name, str(files / "semi.csv"), "--decimal", ",", "--response", "tcr_c_per_min", *rest]) == 0
    a = capsys.readouterr()
    assert main([name, TABLE4, "--response", "tcr_c_per_min", *rest]) == 0
    b = capsys.readouterr()
    assert a.out.replace(str(files / "semi.csv"), "X") == b.out.replace(TABLE4, "X")
    assert "note: read" in a.err


def test_design_commands_read_workbooks(files, tmp_path, capsys):
    design = tmp_path / "bbd.csv"
    assert main(["design", "box-behnken", "--factor", "a=0:1", "--factor", "b=0:2", "--factor", "c=1:3",
                 "--seed", "1", "-o", str(design)]) == 0
    pd.read_csv(design).to_excel(tmp_path / "bbd.xlsx", index=False)
    capsys.readouterr()
    assert main(["evaluate", str(design)]) == 0
    a = capsys.readouterr().out
    assert main(["evaluate", str(tmp_path / "bbd.xlsx")]) == 0
    b = capsys.readouterr().out
    assert a.replace(str(design), "X") == b.replace(str(tmp_path / "bbd.xlsx"), "X")


def test_design_as_a_workbook_to_fill_in(tmp_path, capsys):
    import openpyxl

    book = tmp_path / "bbd.xlsx"
    argv = ["design", "box-behnken", "--factor", "a=0:1", "--factor", "b=0:2", "--factor", "c=1:3", "--seed", "4"]
    assert main([*argv, "-o", str(tmp_path / "bbd.csv")]) == 0
    assert main([*argv, "-o", str(book), "--response", "y1", "--response", "y2"]) == 0
    ws = openpyxl.load_workbook(book).active
    header = [c.value for c in ws[1]]
    assert header[-2:] == ["y1", "y2"] and ws.max_row == 16
    assert all(ws.cell(row=r, column=len(header)).value is None for r in range(2, 17))  # empty to fill in
    same = pd.read_excel(book).drop(columns=["y1", "y2"])
    pd.testing.assert_frame_equal(same, pd.read_csv(tmp_path / "bbd.csv"), check_dtype=False, check_exact=True)  # exact
    # filled in, the workbook is analysed as it is
    wb = openpyxl.load_workbook(book)
    ws = wb.active
    for r in range(2, 17):
        a, b, c = (ws.cell(row=r, column=header.index(n) + 1).value for n in "abc")
        ws.cell(row=r, column=len(header) - 1, value=1 + a + 0.5 * b * c + 0.1 * r % 3)
    wb.save(book)
    capsys.readouterr()
    assert main(["fit", str(book), "--response", "y1", "--model", "linear"]) == 0
    cap = capsys.readouterr()
    assert "runs: 15" in cap.out and "note: read" in cap.err
    # the default response column, --format, and a name that does not fit
    assert main([*argv, "-o", str(tmp_path / "d.xlsx")]) == 0
    assert openpyxl.load_workbook(tmp_path / "d.xlsx").active.cell(row=1, column=len(header) - 1).value == "response"
    assert main([*argv, "--format", "xlsx", "-o", str(tmp_path / "d.csv")]) == 2
    assert "--format xlsx: name the output .xlsx" in capsys.readouterr().err
    assert not (tmp_path / "d.csv").exists()
