"""Help and messages that say what the program does (issue 37, "Help that does not match
behaviour"): each test below failed on the text of the version before it."""

import re
from pathlib import Path

import pandas as pd
import pytest
from _cli_errors import error_line

import rsm_lrg
from rsm_lrg.cli import main
from rsm_lrg.datasets import data_path

TABLE4 = str(data_path("table4.csv"))
README = Path(__file__).resolve().parents[2] / "README.md"


def _help(capsys, *command) -> str:
    assert main([*command, "--help"]) == 0
    return " ".join(capsys.readouterr().out.split())


def test_reproduce_help_says_not_yet_rows_leave_exit_0(capsys):
    # reproduce exits 0 with 'not yet' rows outside their tolerance (rsm_lrg.paper.Reproduction.ok)
    text = _help(capsys, "reproduce")
    assert "only when no checked row is outside its tolerance" not in text
    assert "'not yet' row" in text and "does not change the exit status" in text


def test_fit_help_lists_every_model_family(capsys):
    text = _help(capsys, "fit")
    assert "linear, 2FI or quadratic model" not in text
    for word in ("cubic", "mixture-quadratic", "special-cubic", "--terms", "REML"):
        assert word in text.split("options:")[0], word


def test_bound_error_names_no_option_that_does_not_exist(capsys):
    line = error_line(capsys, main(["optimize", TABLE4, "--response", "tcr_c_per_min",
                                    "--bound", "velocity_m_s=0.3:0.5"]))
    assert "outside the design range" in line
    assert "(or allow extrapolation)" not in line
    assert "give a bound inside the design range" in line


@pytest.mark.slow
def test_simulate_yield_warning_says_what_it_means(tmp_path, capsys):
    # the 0.1 mm leaf at v = 0.6 m/s, a = 40 m/s² yields (README, 'Leaf stress')
    design = tmp_path / "d.csv"
    pd.DataFrame({"thickness_m": [1e-4], "stroke_m": [0.05], "velocity_m_s": [0.6],
                  "acceleration_m_s2": [40.0]}).to_csv(design, index=False)
    assert main(["simulate", str(design), "--seed", "1", "-o", str(tmp_path / "r.csv")]) == 0
    err = capsys.readouterr().err
    warning = next(line for line in err.splitlines() if "would yield" in line)
    assert "outside its validity" in warning and "0.1 mm leaf" in warning
    assert warning.count("(") == warning.count(")")


def test_simulate_help_explains_yielding_rows(capsys):
    text = _help(capsys, "simulate")
    assert "would yield" in text and "outside its validity" in text


def test_mixture_data_caption_says_0_to_1():
    from rsm_lrg.report.fit_report import data_table

    fit = rsm_lrg.fit(rsm_lrg.load_mixture_etch(), "erate", components=["x1", "x2", "x3"], model="mixture-quadratic")
    caption = data_table(fit, "runs")["caption"]
    assert "−1 low" not in caption and "L-pseudo" in caption
    coded = [row[-3:] for row in data_table(fit, "runs")["rows"]]
    assert min(min(r) for r in coded) >= 0.0 and max(max(r) for r in coded) <= 1.0


def test_mixture_with_process_factor_caption_names_both():
    from rsm_lrg.report.fit_report import data_table

    df = rsm_lrg.load_mixture_etch()
    df["power"] = [100, 200] * 7
    fit = rsm_lrg.fit(df, "erate", components=["x1", "x2", "x3"], factors=["power"], model="mixture-linear")
    caption = data_table(fit, "runs")["caption"]
    assert "L-pseudo" in caption and "process factors coded (−1 low" in caption


def test_readme_figures_that_go_stale_are_dated():
    # test counts and run times in the README are stated as of a version (they change with every issue)
    text = README.read_text(encoding="utf-8")
    for m in re.finditer(r"\(\d[\d,]* tests\b[^)]*\)", text):
        around = text[max(0, m.start() - 400):m.end() + 200]
        assert re.search(r"as of\s+(version\s+)?\d+\.\d+", around), m.group()


def test_mixture_design_fitted_without_component_says_to_give_them(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    design = Path("mix.csv")
    assert main(["design", "simplex-centroid", "--component", "a", "--component", "b", "--component", "c",
                 "-o", str(design)]) == 0
    df = pd.read_csv(design)
    df["y"] = [10.0, 12.0, 9.0, 14.0, 11.0, 13.0, 12.5][:len(df)]
    df.to_csv(design, index=False)
    capsys.readouterr()
    line = error_line(capsys, main(["fit", str(design), "--response", "y"]))
    assert "--component a --component b --component c" in line and "mixture --model" in line


def test_ordinary_factors_get_no_mixture_hint(capsys):
    line = error_line(capsys, main(["fit", TABLE4, "--response", "tcr_c_per_min", "--model", "cubic"]))
    assert "--component" not in line and "--factor NAME" in line
