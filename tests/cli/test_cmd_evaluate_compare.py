"""``rsm-lrg evaluate A.csv B.csv``: designs compared side by side (criteria table, FDS curves on
one plot), the efficiencies and alias map of one design; bad input exits 2 with one line."""

import json

import pytest

from rsm_lrg.cli import main

F3 = ["--factor", "a=0:1", "--factor", "b=0:1", "--factor", "c=0:1"]


@pytest.fixture(scope="module")
def designs(tmp_path_factory):
    d = tmp_path_factory.mktemp("cmp")
    bbd, fcd, ff2 = d / "bbd.csv", d / "fcd.csv", d / "ff2.csv"
    assert main(["design", "box-behnken", *F3, "--center", "3", "--seed", "1", "-o", str(bbd)]) == 0
    assert main(["design", "central-composite", *F3, "--center", "1", "--alpha", "face", "--seed", "1",
                 "-o", str(fcd)]) == 0
    assert main(["design", "full-factorial", "--factor", "a=0:1", "--factor", "b=0:1", "--levels", "3",
                 "-o", str(ff2)]) == 0
    return str(bbd), str(fcd), str(ff2)


def test_compare_two_designs_table_json_and_plot(designs, tmp_path, capsys):
    bbd, fcd, _ = designs
    capsys.readouterr()
    png, js = tmp_path / "fds.png", tmp_path / "cmp.json"
    assert main(["evaluate", bbd, fcd, "--plot", str(png), "--json", str(js)]) == 0
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    d = json.loads(js.read_text())
    assert d["designs"] == [bbd, fcd] and [r["design"] for r in d["criteria"]] == [bbd, fcd]
    assert {"d_efficiency", "a_efficiency", "g_efficiency", "i_average", "rel_i"} <= set(d["criteria"][0])
    assert max(r["rel_d"] for r in d["criteria"]) == pytest.approx(1.0)
    assert main(["evaluate", bbd, fcd, "--plot", str(tmp_path / "fds.svg")]) == 0
    out = capsys.readouterr().out
    assert "Design comparison for a quadratic model" in out and "rel D" in out
    assert (tmp_path / "fds.svg").read_text().lstrip().startswith("<?xml")


def test_single_design_reports_efficiencies_and_alias_map(designs, capsys):
    bbd = designs[0]
    capsys.readouterr()
    assert main(["evaluate", bbd, "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert list(d)[:4] == ["model", "n", "p", "df"]  # the single-design JSON as before, keys added
    assert 0 < d["d_efficiency"] < 1 and 0 < d["a_efficiency"] < 1 and d["potential"] == "cubic"
    assert d["alias_matrix"]["A"]["A^3"] == pytest.approx(1.0)  # A = A^3 at +-1 and 0
    assert main(["evaluate", bbd, "--potential", "none"]) == 0
    out = capsys.readouterr().out
    assert "Efficiencies: D" in out and "Alias matrix" not in out


@pytest.mark.parametrize("extra, needle", [
    (["ff2"], "has 2 factors"),
    (["bbd"], "given once"),
    (["--plot", "fds.pdf"], "--plot"),
    (["--model", "cubic"], "not estimable"),
])
def test_compare_errors_exit_2(designs, tmp_path, capsys, extra, needle):
    bbd, fcd, ff2 = designs
    args = [{"ff2": ff2, "bbd": bbd}.get(a, a) for a in extra]
    if "--plot" in args:
        args[args.index("--plot") + 1] = str(tmp_path / "fds.pdf")
    capsys.readouterr()
    assert main(["evaluate", bbd, fcd, *args]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error:") and needle in err[0]
    assert not (tmp_path / "fds.pdf").exists()
