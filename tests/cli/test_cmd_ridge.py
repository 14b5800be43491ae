"""``rsm-lrg ridge``: the INTERFACE JSON shape, radii, errors."""

import json
import math

from rsm_lrg.cli import main


def test_json_shape(capsys):
    assert main(["ridge", "data/table4.csv", "--response", "tcr_c_per_min", "--goal", "minimize",
                 "--radius", "1", "--step", "0.25", "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert list(d) == ["response", "goal", "kind", "path"]
    assert d["kind"] == "ridge" and d["goal"] == "minimize"
    assert [p["radius"] for p in d["path"]] == [0.0, 0.25, 0.5, 0.75, 1.0]
    for p in d["path"]:
        assert list(p) == ["radius", "coded", "actual", "predicted"]
        assert math.hypot(*p["coded"].values()) == __import__("pytest").approx(p["radius"], abs=1e-9)


def test_linear_model_is_steepest_and_errors(capsys, tmp_path):
    assert main(["ridge", "data/table4.csv", "--response", "tcr_c_per_min", "--model", "linear", "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["kind"] == "steepest" and d["path"][0]["radius"] == 0.0
    assert main(["ridge", "data/table4.csv", "--response", "tcr_c_per_min", "--step", "0"]) == 2
    assert capsys.readouterr().err.startswith("error:")
    bad = tmp_path / "bad.csv"
    bad.write_text("a,b,y\n1,2,3\n2,x,4\n3,1,5\n")
    assert main(["ridge", str(bad), "--response", "y"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "bad.csv" in err[0] and "'b'" in err[0] and "row 2" in err[0]
