"""``rsm-lrg design-space --surrogate``: the surrogate's map, window and attribution in text and
JSON (equal to the library's for the seed); options that belong to the fitted path are refused
naming the option."""

import json

import pytest
from _cli_errors import error_line

from rsm_lrg.cli import main

BASE = ["design-space", "--surrogate", "--factor", "velocity_m_s=0.4:0.6", "--spec", "tcr_c_per_min=:0.045",
        "--grid", "2", "--draws", "6", "--seed", "3"]


def test_json_equals_the_library_and_the_text_names_the_draws(capsys, tmp_path):
    from rsm_lrg.paper.surrogate_space import surrogate_design_space

    assert main(BASE + ["--param-sd", "thickness_m=5e-6", "--json", "-"]) == 0
    out = json.loads(capsys.readouterr().out)
    lib = surrogate_design_space({"velocity_m_s": (0.4, 0.6)}, {"tcr_c_per_min": (None, 0.045)}, grid=2, draws=6,
                                 seed=3, param_sd={"thickness_m": 5e-6}).to_dict()
    for d in (out, lib):
        d["surrogate"].pop("seconds")
    assert out == lib
    node = out["surrogate"]["nodes"][0]
    assert set(node["attribution"]["tcr_c_per_min"]) == {"variance", "parameters", "tolerances", "noise",
                                                          "interaction", "dominant"}
    kinds = {p["name"]: p["distribution"] for p in out["surrogate"]["parameters"]}
    assert kinds["ball_contact_conductance_w_k"] == "uniform" and kinds["thickness_m"] == "deviation"
    page = tmp_path / "s.html"
    assert main(BASE + ["--no-attribution", "-o", str(page)]) == 0
    text = capsys.readouterr().out
    assert "known only by a bound" in text and "6 draws per setting, seed 3, 12 runs" in text
    assert page.exists() and "the calibrated surrogate" in page.read_text()


@pytest.mark.parametrize("extra, option", [
    (["--response", "tcr_c_per_min"], "--response"),
    (["--factor-sd", "velocity_m_s=0.01"], "--factor-sd"),
    (["--param-sd", "nonsense=1"], "--param-sd"),
    (["--factor", "leaf=1:2"], "--factor"),
    (["--factor", "velocity_m_s"], "--factor"),
    (["--spec", "kappa=:1"], "--spec"),
    (["--calibration", "/nonexistent/cal.toml"], "--calibration"),
])
def test_bad_surrogate_options_name_the_option(capsys, extra, option):
    assert error_line(capsys, main(BASE + extra)).startswith(f"error: {option}")


def test_surrogate_only_options_are_refused_on_data(capsys):
    from pathlib import Path

    t4 = str(Path(__file__).parents[2] / "data" / "table4.csv")
    line = error_line(capsys, main(["design-space", t4, "--response", "tcr_c_per_min", "--spec",
                                    "tcr_c_per_min=:0.035", "--param-sd", "thickness_m=1e-6"]))
    assert line.startswith("error: --param-sd: only with --surrogate")
    line = error_line(capsys, main(["design-space", "--spec", "tcr_c_per_min=:0.035"]))
    assert line.startswith("error: DATA.csv")


def test_the_table3_box_gives_the_same_json_on_one_and_two_workers(capsys):
    """All three of the paper's varied factors (leaf thickness, velocity, acceleration; stroke at
    Table 3's centre), a tiny grid: the same seed gives the same JSON on one worker and two."""
    argv = ["design-space", "--surrogate", "--factor", "thickness_m=1e-4:5e-4", "--factor", "velocity_m_s=0.4:0.6",
            "--factor", "acceleration_m_s2=20:40", "--spec", "tcr_c_per_min=:0.035", "--grid", "2", "--draws", "4",
            "--seed", "7", "--param-sd", "thickness_m=5e-6", "--json", "-"]
    outs = []
    for workers in ("1", "2"):
        assert main(argv + ["--workers", workers]) == 0
        d = json.loads(capsys.readouterr().out)
        assert d["surrogate"].pop("workers") == int(workers)
        d["surrogate"].pop("seconds")
        outs.append(d)
    assert outs[0] == outs[1]
    nodes = outs[0]["surrogate"]["nodes"]
    assert len(nodes) == 8 and outs[0]["surrogate"]["runs"] == 8 * 4 * 5
    assert outs[0]["surrogate"]["held"] == {"stroke_m": 0.05}
    assert all(set(nd["attribution"]["tcr_c_per_min"]) >= {"parameters", "tolerances", "noise"} for nd in nodes)
