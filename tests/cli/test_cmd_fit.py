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
        (["fit", _write(tmp_path, "const.csv", const), "--response", "tcr_c_per_min", "--factor", "thickness_m",
          "--factor", "const"], "'const' is constant"),  # named: an error (inferred, it is left out with a note)
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


def _one_error(argv, capsys):
    capsys.readouterr()
    assert main(argv) == 2, argv
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error:") and len(err[0]) < 300, err
    return err[0]


def test_columns_and_runs_left_out_are_said(tmp_path, capsys):
    t4 = Path(TABLE4).read_text().splitlines()
    lines = [t4[0] + ",operator"] + [ln + f",op{i % 3}" for i, ln in enumerate(t4[1:])]
    lines[5] = lines[5].replace(lines[5].split(",")[5], "", 1)  # row 5: no response (not run)
    path = _write(tmp_path, "ops.csv", "\n".join(lines) + "\n")
    capsys.readouterr()
    assert main(["fit", path, "--response", "tcr_c_per_min"]) == 0
    out = capsys.readouterr().out
    assert "Text column left out" in out and "operator" in out
    assert "1 run without a response left out of the fit (not run): row 5." in out
    assert "runs: 26" in out
    # with JSON on stdout the notes go to stderr, and the JSON stays clean
    assert main(["fit", path, "--response", "tcr_c_per_min", "--json", "-"]) == 0
    cap = capsys.readouterr()
    assert json.loads(cap.out)["n"] == 26
    notes = cap.err.strip().splitlines()
    assert notes and all(n.startswith("note: ") for n in notes)
    assert any("operator" in n for n in notes) and any("row 5" in n for n in notes)


def test_column_names_and_comma_numbers(tmp_path, capsys):
    # valid distinct columns stroke_m and stroke_m.1
    t4 = Path(TABLE4).read_text().splitlines()
    two = [t4[0].replace("velocity_m_s", "stroke_m.1")] + t4[1:]
    path = _write(tmp_path, "two.csv", "\n".join(two) + "\n")
    assert main(["fit", path, "--response", "tcr_c_per_min"]) == 0
    assert "B: stroke_m " in capsys.readouterr().out
    # a true duplicate in the header line
    dup = [t4[0].replace("velocity_m_s", "stroke_m")] + t4[1:]
    err = _one_error(["fit", _write(tmp_path, "dup.csv", "\n".join(dup)), "--response", "tcr_c_per_min"], capsys)
    assert "'stroke_m' appears more than once" in err
    # a quoted thousands separator in a column that would be a factor
    com = [t4[0]] + [t4[1].replace(",30,", ',"1,030",', 1)] + t4[2:]
    err = _one_error(["fit", _write(tmp_path, "com.csv", "\n".join(com)), "--response", "tcr_c_per_min"], capsys)
    assert "'acceleration_m_s2', row 1" in err and "comma" in err
    # unquoted 1,234 on every row: one field too many
    unq = ["a,b,y", "1,234,5,6", "2,345,6,7", "3,456,7,8"]
    err = _one_error(["fit", _write(tmp_path, "unq.csv", "\n".join(unq)), "--response", "y"], capsys)
    assert "more fields than the header" in err


def test_huge_cell_is_cut_in_the_error(tmp_path, capsys):
    t4 = Path(TABLE4).read_text().splitlines()
    big = [t4[0]] + [t4[1].replace(",0.4,", "," + "7" * 300 + "x,", 1)] + t4[2:]
    err = _one_error(["fit", _write(tmp_path, "big.csv", "\n".join(big)), "--response", "tcr_c_per_min"], capsys)
    assert "'velocity_m_s', row 1" in err


def test_design_refuses_a_bookkeeping_factor_name(tmp_path, capsys):
    for name in ["std_order", "coded_A", "block", "Run_Order"]:
        out = tmp_path / f"{name}.csv"
        err = _one_error(["design", "box-behnken", "--factor", f"{name}=0:1", "--factor", "b=0:1",
                          "--factor", "c=0:1", "-o", str(out)], capsys)
        assert "reserved" in err and name in err
        assert not out.exists()


def test_other_commands_print_the_notes_to_stderr(tmp_path, capsys):
    t4 = Path(TABLE4).read_text().splitlines()
    lines = [t4[0] + ",operator"] + [ln + ",ann" for ln in t4[1:]]
    path = _write(tmp_path, "ops.csv", "\n".join(lines) + "\n")
    for argv in (["ridge", path, "--response", "tcr_c_per_min", "--json", "-"],
                 ["fit-summary", path, "--response", "tcr_c_per_min", "--json", "-"]):
        capsys.readouterr()
        assert main(argv) == 0, argv
        cap = capsys.readouterr()
        json.loads(cap.out)
        assert "note: Text column left out (not a factor, response or block): operator." in cap.err, argv


def test_fit_diagnostics_takes_the_boxcox_rule(capsys):
    assert main(["fit", TABLE4, "--response", "tcr_c_per_min", "--diagnostics", "--boxcox-rule", "design-expert"]) == 0
    assert "Design-Expert's rule" in capsys.readouterr().out
    assert main(["fit", TABLE4, "--response", "tcr_c_per_min", "--diagnostics"]) == 0
    assert "maximum likelihood" in capsys.readouterr().out


def test_optimize_names_its_inferred_factors_and_runs_left_out(tmp_path, capsys):
    import pandas as pd

    d = pd.read_csv(TABLE4)
    d["wear"] = d["tcr_c_per_min"] * 2
    d["operator"] = "ann"
    d.loc[3, "tcr_c_per_min"] = float("nan")
    d.loc[5, "wear"] = float("nan")
    src = tmp_path / "t.csv"
    d.to_csv(src, index=False)
    assert main(["optimize", str(src), "--response", "tcr_c_per_min", "--factor", "thickness_m",
                 "--factor", "stroke_m", "--factor", "velocity_m_s", "--factor", "acceleration_m_s2",
                 "--json", "-"]) == 0
    err = capsys.readouterr().err
    assert "row 4" in err and "wear" in err and "operator" in err  # the run and the columns left out
    assert main(["optimize", str(src), "--response", "tcr_c_per_min", "--goal", "minimize",
                 "--response", "wear", "--goal", "minimize", "--json", "-"]) == 0
    err = capsys.readouterr().err
    assert "tcr_c_per_min: 1 run without a response left out of the fit (not run): row 4" in err
    assert "wear: 1 run without a response left out of the fit (not run): row 6" in err
    assert "operator" in err


def _table4_with_stage(tmp_path):
    import pandas as pd

    d = pd.read_csv(TABLE4)
    d["stage"] = ["rfcms" if i % 2 else "rms" for i in range(len(d))]
    p = tmp_path / "t4s.csv"
    d.to_csv(p, index=False)
    return str(p)


def test_messages_name_the_option_or_the_level_at_fault(tmp_path, capsys):
    # issue 36: each of these named the wrong thing (the response, aliasing, --alpha-out)
    cake = str(data_path("cake_split_plot.csv"))
    cases = [
        (["fit", TABLE4, "--response", "tcr_c_per_min", "--reduce", "--alpha-out", "1e-300"],
         ["--alpha-out", "removed every term"]),
        (["fit", TABLE4, "--response", "tcr_c_per_min", "--transform", "power=1e-320"],
         ["--transform", "maps every value"]),
        (["fit", cake, "--response", "y", "--whole-plot", "Ovenrun", "--reduce", "--criterion", "aicc"],
         ["--criterion", "Kenward-Roger"]),
        (["fit", _table4_with_stage(tmp_path), "--response", "tcr_c_per_min", "--factor", "thickness_m", "--factor",
          "stroke_m", "--factor", "stage=cat:rfcms,rms,zzz", "--terms", "A B C"], ["'stage'", "'zzz'", "no row"]),
    ]
    for argv, words in cases:
        assert main(argv) == 2, argv
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and err[0].startswith("error:"), err
        for w in words:
            assert w in err[0], (w, err[0])
