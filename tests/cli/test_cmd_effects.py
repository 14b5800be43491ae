"""``rsm-lrg effects``: Montgomery's Example 6.2 end to end, the plot, JSON and bad input."""

import json

import pytest

from rsm_lrg.cli import main

# Montgomery (2013), Design and Analysis of Experiments 8th ed., Example 6.2 (unreplicated 2^4)
FILTRATION = {"(1)": 45, "a": 71, "b": 48, "ab": 65, "c": 68, "ac": 60, "bc": 80, "abc": 65,
              "d": 43, "ad": 100, "bd": 45, "abd": 104, "cd": 75, "acd": 86, "bcd": 70, "abcd": 96}


@pytest.fixture
def runs(tmp_path):
    lines = ["temperature,pressure,concentration,stirring,rate"]
    for label, y in FILTRATION.items():
        lines.append(",".join(str(1 if ch in label and label != "(1)" else -1) for ch in "abcd") + f",{y}")
    p = tmp_path / "filtration.csv"
    p.write_text("\n".join(lines) + "\n")
    return p


def test_saturated_effects_plot_and_json(runs, tmp_path, capsys):
    png, js = tmp_path / "hn.png", tmp_path / "e.json"
    assert main(["effects", str(runs), "--response", "rate", "--plot", str(png), "--json", str(js)]) == 0
    out = capsys.readouterr().out
    assert "PSE 2.625" in out and "Active beyond SME: A, D, AC, AD" in out
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    d = json.loads(js.read_text())
    assert d["m"] == 15 and d["pse"] == pytest.approx(2.625, rel=1e-12) and set(d["active"]) == {"A", "C", "D", "AC", "AD"}
    assert main(["effects", str(runs), "--response", "rate", "--model", "linear", "--plot", str(tmp_path / "hn.svg"),
                 "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["m"] == 4 and (tmp_path / "hn.svg").read_text().lstrip().startswith("<?xml")


def test_terms_option(runs, capsys):
    assert main(["effects", str(runs), "--response", "rate", "--term", "A", "--term", "C", "--term", "D",
                 "--term", "AC", "--term", "AD", "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert sorted(r["term"] for r in d["effects"]) == ["A", "AC", "AD", "C", "D"]
    assert any("residual degrees of freedom" in n for n in d["notes"])


def test_bad_input_leaves_nothing(runs, tmp_path, capsys):
    before = runs.read_bytes()
    for extra in (["--plot", str(tmp_path / "hn.txt")], ["--plot", str(runs), "--force"], ["--alpha", "2"],
                  ["--term", "Q"]):
        assert main(["effects", str(runs), "--response", "rate", "--json", str(tmp_path / "x.json"), *extra]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and err[0].startswith("error:"), (extra, err)
        assert not (tmp_path / "x.json").exists() and not (tmp_path / "hn.txt").exists()
    assert runs.read_bytes() == before
    assert main(["effects", str(runs), "--response", "nope"]) == 2
    assert "nope" in capsys.readouterr().err
