"""``rsm-lrg datasets``: lists the shipped tables and writes them, so a pip user can follow
the README (``data/table4.csv``) without the repository."""

from pathlib import Path

import pytest
from _cli_errors import error_line

from rsm_lrg.cli import main
from rsm_lrg.datasets import DATASETS, data_path

REPO_DATA = Path(__file__).resolve().parents[2] / "data"


def test_list_names_every_shipped_table(capsys):
    assert main(["datasets"]) == 0
    out = capsys.readouterr().out
    for d in DATASETS:
        assert d.name in out and d.file in out
    # Table 4: 27 runs of 6 columns (the paper, Table 4)
    assert any(line.split()[:4] == ["table4", "27", "x", "6"] for line in out.splitlines())


def test_the_four_tables_the_issue_names_are_shipped():
    names = {d.name for d in DATASETS}
    assert {"table4", "table3", "mixture-etch", "cake-split-plot"} <= names


def test_name_prints_the_csv(capsys):
    assert main(["datasets", "table4"]) == 0
    assert capsys.readouterr().out == (REPO_DATA / "table4.csv").read_text(encoding="utf-8")


@pytest.mark.parametrize("name", ["table4.csv", "mixture_etch"])
def test_file_name_and_underscore_spelling_are_accepted(capsys, name):
    assert main(["datasets", name]) == 0
    assert capsys.readouterr().out.count("\n") > 5


def test_output_file_and_directory(tmp_path, capsys):
    assert main(["datasets", "cake-split-plot", "-o", str(tmp_path / "cake.csv")]) == 0
    assert (tmp_path / "cake.csv").read_bytes() == data_path("cake_split_plot.csv").read_bytes()
    assert main(["datasets", "table3", "-o", str(tmp_path)]) == 0
    assert (tmp_path / "table3_levels.csv").read_bytes() == (REPO_DATA / "table3_levels.csv").read_bytes()


def test_every_table_into_a_new_directory_then_refuses_to_overwrite(tmp_path, capsys):
    target = tmp_path / "data"
    assert main(["datasets", "-o", str(target)]) == 0
    assert sorted(p.name for p in target.iterdir()) == sorted(d.file for d in DATASETS)
    capsys.readouterr()
    line = error_line(capsys, main(["datasets", "-o", str(target)]))
    assert "-o/--output" in line and "--force" in line
    assert main(["datasets", "-o", str(target), "--force"]) == 0


def test_unknown_name_is_one_error_line(capsys):
    line = error_line(capsys, main(["datasets", "table9"]))
    assert "NAME" in line and "'table9'" in line and "table4" in line


def test_without_name_o_must_be_a_directory(tmp_path, capsys):
    f = tmp_path / "x.csv"
    f.write_text("a\n1\n")
    line = error_line(capsys, main(["datasets", "-o", str(f)]))
    assert "-o/--output" in line and "directory" in line
    assert f.read_text() == "a\n1\n"
