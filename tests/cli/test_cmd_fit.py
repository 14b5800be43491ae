"""``rsm-lrg fit``: the acceptance case on the command line, JSON, and bad input (exit 2)."""

import hashlib
import json
import subprocess
import sys
from pathlib import Path

from rsm_lrg.cli import main
from rsm_lrg.datasets import data_path

TABLE4 = str(data_path("table4.csv"))


def _sha(p):
    return hashlib.sha256(Path(p).read_bytes()).hexdigest()


def test_fit_prints_table5_layout(capsys):
    before = _sha(TABLE4)
    assert main(["fit", TABLE4, "--response", "tcr_c_per_min"]) == 0
    out = capsys.readouterr().out
    for needle in ["Sum of Squares", "Lack of Fit", "10.75", "0.0880", "26.03", "0.9681", "18.46", "4.978",
                   "terms of coded factors", "terms of actual factors", "Canonical analysis"]:
        assert needle in out, needle
    assert _sha(TABLE4) == before  # the input is never written


def test_fit_json_matches_interface(tmp_path, capsys):
    dest = tmp_path / "fit.json"
    assert main(["fit", TABLE4, "--response", "tcr_c_per_min", "--json", str(dest)]) == 0
    d = json.loads(dest.read_text())
    # Eq. 19 (within 6e-6) and Table 5 Lack of Fit F 10.75 in the JSON, as checked from outside
    assert abs(d["coefficients"]["coded"]["C"] - 0.0075) < 6e-6
    lof = [r for r in d["anova"] if r["source"] == "Lack of Fit"][0]
    assert round(lof["f"], 2) == 10.75
    assert d["anova"][-1]["mean_sq"] is None
    # an existing output needs --force
    capsys.readouterr()
    assert main(["fit", TABLE4, "--response", "tcr_c_per_min", "--json", str(dest)]) == 2
    assert "already exists" in capsys.readouterr().err
    assert main(["fit", TABLE4, "--response", "tcr_c_per_min", "--json", str(dest), "--force"]) == 0


def test_fit_json_to_stdout(capsys):
    assert main(["fit", TABLE4, "--response", "tcr_c_per_min", "--json", "-", "--model", "linear"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["model"] == "linear" and d["stationary_point"]["kind"] is None


def _write(tmp_path, name, text):
    p = tmp_path / name
    p.write_text(text)
    return str(p)


def _bad_cases(tmp_path):
    t4 = Path(TABLE4).read_text().splitlines()
    assert t4[5].split(",")[3] == "0.4"  # run 5, velocity
    text_row = t4[:5] + [t4[5].replace(",0.4,", ",fast,", 1)] + t4[6:]
    inf_row = t4[:3] + [t4[3].rsplit(",", 1)[0] + ",inf"] + t4[4:]
    const = "\n".join([t4[0] + ",const"] + [ln + ",1" for ln in t4[1:]])
    return [
        (["fit", str(tmp_path / "missing.csv"), "--response", "y"], "no such file"),
        (["fit", _write(tmp_path, "empty.csv", ""), "--response", "y"], "empty"),
        (["fit", _write(tmp_path, "bin.csv", "\x00\x01\x02"), "--response", "y"], "not a CSV"),
        (["fit", TABLE4, "--response", "nope"], "'nope'"),
        (["fit", TABLE4, "--response", "tcr_c_per_min", "--factor", "nope"], "'nope'"),
        (["fit", _write(tmp_path, "text.csv", "\n".join(text_row)), "--response", "tcr_c_per_min"], "'velocity_m_s', row 5"),
        (["fit", _write(tmp_path, "inf.csv", "\n".join(inf_row)), "--response", "tcr_c_per_min"], "row 3"),
        (["fit", _write(tmp_path, "const.csv", const), "--response", "tcr_c_per_min"], "constant"),
        (["fit", _write(tmp_path, "few.csv", "\n".join(t4[:11])), "--response", "tcr_c_per_min"], "10 runs cannot fit 15 terms"),
        (["fit", TABLE4, "--response", "tcr_c_per_min", "--factor", "stroke_m=0.06:0.04"], "LOW must be below HIGH"),
    ]


def test_bad_input_is_one_error_line(tmp_path, capsys):
    for argv, needle in _bad_cases(tmp_path):
        capsys.readouterr()
        assert main(argv) == 2, argv
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and err[0].startswith("error:"), (argv, err)
        assert needle in err[0], (argv, err[0])


def test_fit_as_a_real_process():
    out = subprocess.run([sys.executable, "-m", "rsm_lrg", "fit", TABLE4, "--response", "tcr_c_per_min", "--json", "-"],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    d = json.loads(out.stdout)
    assert d["n"] == 27 and round(d["statistics"]["adeq_precision"], 2) == 18.46
