"""Hostile input to the surrogate commands (`simulate`, `calibrate`, `physics`): every case
ends with exit 2 and ONE `error:` line under 300 characters that names the file, column,
row or option at fault -- no traceback, no hang, no output left behind, input unchanged
(issue 10, item 11: calibration files with wrong content, values far outside their physical
range, huge durations, file names with newlines)."""

from __future__ import annotations

import hashlib
import subprocess
import sys
import tomllib

import pandas as pd
import pytest

from rsm_lrg.cli import main

DESIGN = pd.DataFrame({"thickness_m": [3e-4, 5e-4, 3e-4], "stroke_m": [0.05, 0.04, 0.06],
                       "velocity_m_s": [0.5, 0.4, 0.6], "acceleration_m_s2": [30.0, 20.0, 40.0]})


def digest(paths):
    return {p: hashlib.sha256(p.read_bytes()).hexdigest() for p in paths}


def check_refused(capsys, argv, needles, inputs, outputs=()):
    """Run the CLI in-process: exit 2, one short `error:` line naming the culprit, inputs
    unchanged, no output written."""
    before = digest(inputs)
    code = main(argv)
    err = capsys.readouterr().err
    lines = [x for x in err.splitlines() if x.strip()]
    assert code == 2, err
    assert len(lines) == 1, err
    line = lines[0]
    assert line.startswith("error:") and len(line) < 300, line
    assert "Traceback" not in err and "Warning" not in err, err
    for n in needles:
        assert n in line, (n, line)
    assert digest(inputs) == before
    for o in outputs:
        assert not o.exists(), o
    return line


@pytest.fixture
def design(tmp_path):
    p = tmp_path / "design.csv"
    DESIGN.to_csv(p, index=False)
    return p


# ---- calibration files with wrong content ------------------------------------------------
BAD_CALIBRATIONS = [
    ('[calibration]\nrespons = "tcr_c_per_min"\n[parameters.heat_partition]\nvalue = 0.5\n',
     ["[calibration]", "'respons'", "did you mean 'response'"]),
    ('[parameters.heat_partition]\nvalu = 0.5\n', ["[parameters.heat_partition]", "'valu'"]),
    ('[parameters.heat_partition]\nvalue = "half"\n', ["[parameters.heat_partition]", "value", "number"]),
    ('[parameters.heat_partition]\nvalue = true\n', ["[parameters.heat_partition]", "value", "number"]),
    ('[parameters.heat_partition]\nunit = "1"\n', ["[parameters.heat_partition]", "no value"]),
    ('[parameters]\nheat_partition = 0.5\n', ["[parameters.heat_partition]", "table"]),
    ('[calibration]\nresponse = 3\n[parameters.heat_partition]\nvalue = 0.5\n', ["[calibration]", "response"]),
    ('[calibration]\nn = -4\n[parameters.heat_partition]\nvalue = 0.5\n', ["[calibration]", "n"]),
    ('[calibration]\nresponse = "kappa"\n[parameters.heat_partition]\nvalue = 0.5\n', ["'kappa'"]),
    ('[parameters.offset]\nvalue = 1.0\n', ["unknown parameter 'offset'"]),
    ('[parameters.heat_partition]\nvalue = 0.5\n[runs]\nobserved = ["a"]\n', ["[runs]", "observed"]),
    ('[parameters.heat_partition]\nvalue = 0.5\n[extra]\nx = 1\n', ["'extra'"]),
    ('[calibration]\n', ["no [parameters.NAME] tables"]),
    ('[parameters.heat_partition]\nvalue = 0.5\nlower = 0.9\nupper = 0.1\n', ["lower", "upper"]),
    # values far outside the documented range: the file's own bounds cannot widen it
    ('[parameters.heat_partition]\nvalue = 50.0\n', ["[parameters.heat_partition]", "50", "bounds [0.01, 1]"]),
    ('[parameters.heat_partition]\nvalue = 50.0\nlower = -1e9\nupper = 1e9\n', ["50", "bounds [0.01, 1]"]),
    ('[parameters.hinge_damping_ratio]\nvalue = 1e6\n', ["hinge_damping_ratio", "bounds [0.01, 3]"]),
    ('[parameters.viscous_friction_n_s_m]\nvalue = -2.0\n', ["viscous_friction_n_s_m", "bounds [0, 30]"]),
    ('[parameters.preload_n]\nvalue = 1e300\n', ["preload_n", "physical range"]),
    ('[parameters.mu_k]\nvalue = nan\n', ["mu_k"]),
    ('[parameters.mu_k]\nvalue = inf\n', ["mu_k"]),
    ("not toml [", ["not valid TOML"]),
]


@pytest.mark.parametrize("text,needles", BAD_CALIBRATIONS, ids=range(len(BAD_CALIBRATIONS)))
def test_simulate_refuses_a_bad_calibration_file(design, tmp_path, capsys, text, needles):
    cal = tmp_path / "cal.toml"
    cal.write_text(text)
    out = tmp_path / "runs.csv"
    check_refused(capsys, ["simulate", str(design), "--calibration", str(cal), "-o", str(out)],
                  ["cal.toml", *needles], [design, cal], [out])


def test_shipped_and_written_calibrations_still_load(design, tmp_path, capsys):
    from rsm_lrg.datasets import data_path

    out = tmp_path / "runs.csv"
    assert main(["simulate", str(design), "--calibration", str(data_path("calibration.toml")), "--seed", "1",
                 "-o", str(out)]) == 0
    assert len(pd.read_csv(out)) == 3


# ---- values far outside their physical range, non-numbers, huge durations ----------------
BAD_OPTIONS = [
    (["--param", "preload_n=1e308"], ["--param", "preload_n", "physical range"]),
    (["--param", "stage_mass_kg=1e300"], ["--param", "stage_mass_kg"]),
    (["--param", "hinge_count=1e300"], ["--param", "hinge_count"]),
    (["--param", "mu_k=inf"], ["--param", "mu_k", "finite"]),
    (["--param", "mu_k=nan"], ["--param", "mu_k", "finite"]),
    (["--param", "mu_k=abc"], ["--param", "mu_k", "number"]),
    (["--param", "stroke_m=" + "9" * 400], ["--param", "stroke_m"]),
    (["--param", "dwell_s=1e12"], ["--param", "dwell_s"]),
    (["--param", "rail_length_m=20"], ["--param", "rail_length_m"]),
    (["--param", "ambient_c=1e300"], ["--param", "ambient_c"]),
    (["--param", "nonsense=1"], ["--param", "nonsense"]),
    (["--param", "mu_k"], ["--param", "NAME=VALUE"]),
    (["--param", "test_duration_min=60"], ["--param test_duration_min", "--duration-min"]),
    (["--param", "carriage_mass_kg=12"], ["--param", "carriage_mass_kg", "12 kg"]),
    (["--duration-min", "1e12"], ["--duration-min"]),
    (["--duration-min", "1e300"], ["--duration-min"]),
    (["--duration-min", "inf"], ["--duration-min"]),
    (["--duration-min", "0.5"], ["--duration-min"]),
    (["--duration-min", "-3"], ["--duration-min"]),
    (["--noise-sd", "1e308"], ["--noise-sd"]),
    (["--noise-sd", "nan"], ["--noise-sd"]),
]


@pytest.mark.parametrize("extra,needles", BAD_OPTIONS, ids=range(len(BAD_OPTIONS)))
def test_simulate_refuses_bad_options(design, tmp_path, capsys, extra, needles):
    out = tmp_path / "runs.csv"
    check_refused(capsys, ["simulate", str(design), *extra, "-o", str(out)], needles, [design], [out])


BAD_COLUMNS = [
    ("test_duration_min", [50, 1e12, 50], "row 2"),
    ("test_duration_min", [50, -5, 50], "row 2"),
    ("test_duration_min", [50, 0.2, 50], "row 2"),
    ("stroke_m", [0.05, "abc", 0.06], "row 2"),
    ("stroke_m", [0.05, "x" * 5000, 0.06], "row 2"),
    ("velocity_m_s", [0.5, 1e200, 0.6], "row 2"),
    ("acceleration_m_s2", [30, 1e-300, 40], "row 2"),
    ("preload_n", [171, 1e300, 171], "row 2"),
    ("mu_k", [0.02, 1e300, 0.02], "row 2"),
    ("heat_partition", [0.5, 7, 0.5], "row 2"),
    ("hinge_damping_ratio", [0.02, 1e6, 0.02], "row 2"),
    ("thickness_m", [3e-4, "", 3e-4], "row 2"),
    ("carriage_mass_kg", [0.19, 12.0, 0.19], "row 2"),
]


@pytest.mark.parametrize("column,values,row", BAD_COLUMNS, ids=range(len(BAD_COLUMNS)))
def test_simulate_refuses_bad_design_cells(tmp_path, capsys, column, values, row):
    p = tmp_path / "bad.csv"
    DESIGN.assign(**{column: values}).to_csv(p, index=False)
    out = tmp_path / "runs.csv"
    check_refused(capsys, ["simulate", str(p), "-o", str(out)], ["bad.csv", column, row], [p], [out])


def test_calibrate_refuses_bad_options(tmp_path, capsys):
    from rsm_lrg.datasets import data_path

    data = tmp_path / "t4.csv"
    data.write_bytes(data_path("table4.csv").read_bytes())
    out = tmp_path / "cal.toml"
    base = ["calibrate", str(data), "--response", "tcr_c_per_min", "-o", str(out)]
    for extra, needles in [(["--duration-min", "1e12"], ["--duration-min"]),
                           (["--duration-min", "inf"], ["--duration-min"]),
                           (["--parameter", "offset"], ["offset"]),
                           (["--parameter", "heat_partition"] * 2, ["twice"]),
                           (["--select", "v5,nope"], ["--select", "'nope'"]),
                           (["--select", "v5,v5"], ["--select", "different"]),
                           (["--select", "v5,v5-nodrive", "--parameter", "mu_k"], ["--select", "--parameter"])]:
        check_refused(capsys, base + extra, needles, [data], [out])


@pytest.mark.parametrize("text,needles", [
    ("[mu_k]\nvalue = 0.01\nvalu = 3\n", ["[mu_k]", "'valu'"]),
    ('mu_k = "abc"\n', ["mu_k", "number"]),
    ('[mu_k]\nunit = "1"\n', ["[mu_k]", "no value"]),
    ("preload_n = 1e300\n", ["preload_n", "physical range"]),
    ("mu_kk = 0.1\n", ["'mu_kk'", "did you mean 'mu_k'"]),
    ("hinge_count = 2.5\n", ["hinge_count", "whole number"]),
    ("heat_in_calories = 3\n", ["heat_in_calories"]),
    ("rail_length_m = 50.0\n", ["rail_length_m"]),
])
def test_physics_refuses_a_bad_params_file(tmp_path, capsys, text, needles):
    p = tmp_path / "params.toml"
    p.write_text(text)
    check_refused(capsys, ["physics", "--params-file", str(p), "--no-thermal"], ["params.toml", *needles], [p])


@pytest.mark.slow
def test_physics_handles_the_ends_of_the_ranges(capsys):
    # a stiff hinge needs too many integration steps (19.9 mm leaf, 20 mm long: 213 257 steps
    # per cycle, above the 200 000 limit): the chain falls back to the quasi-static limit
    # instead of failing; a leaf thicker than its length is refused, as simulate refuses it;
    # a long test stretches the thermal horizon
    assert main(["physics", "--param", "hinge_thickness_m=0.0199", "--no-thermal"]) == 0
    assert main(["physics", "--param", "hinge_thickness_m=0.05", "--no-thermal"]) == 2
    assert main(["physics", "--param", "test_duration_min=100000"]) == 0
    capsys.readouterr()


# ---- a file name with a newline (and quotes) round-trips through calibrate's TOML --------
@pytest.mark.slow
def test_calibrate_writes_valid_toml_for_a_hostile_file_name(tmp_path):
    from rsm_lrg.datasets import data_path

    name = 'we\nird "name"\\ \t#x.csv'
    data = tmp_path / name
    data.write_bytes(data_path("table4.csv").read_bytes())
    out = tmp_path / "cal.toml"
    r = subprocess.run([sys.executable, "-m", "rsm_lrg", "calibrate", str(data), "--response", "tcr_c_per_min",
                        "--model", "v4", "--parameter", "heat_partition", "--no-loo", "-o", str(out)],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]
    assert "calibration fits" in r.stderr  # the progress bar (tqdm) on stderr
    doc = tomllib.loads(out.read_text(encoding="utf-8"))
    assert doc["calibration"]["data"] == name
    # and simulate reads it back
    runs = tmp_path / "runs.csv"
    design = tmp_path / "design.csv"
    DESIGN.to_csv(design, index=False)
    r = subprocess.run([sys.executable, "-m", "rsm_lrg", "simulate", str(design), "--calibration", str(out),
                        "--seed", "1", "-o", str(runs)], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]


def test_calibration_toml_comment_escapes_control_characters():
    from rsm_lrg.surrogate.calibrate import calibration_toml, resolve_calibration

    cal = resolve_calibration({"heat_partition": 0.5})
    text = calibration_toml(cal, "rsm-lrg calibrate 'a\nb\rc\x00d\x7f.csv'")
    assert tomllib.loads(text)["parameters"]["heat_partition"]["value"] == 0.5
    assert "a\\nb\\rc\\u0000d\\u007f.csv" in text


def test_a_real_subprocess_gives_one_line_and_no_traceback(tmp_path):
    cal = tmp_path / "cal.toml"
    cal.write_text('[parameters.heat_partition]\nvalue = 50.0\n')
    design = tmp_path / "design.csv"
    DESIGN.to_csv(design, index=False)
    r = subprocess.run([sys.executable, "-m", "rsm_lrg", "simulate", str(design), "--calibration", str(cal),
                        "-o", str(tmp_path / "o.csv")], capture_output=True, text=True, timeout=120)
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error:") and "cal.toml" in lines[0] and len(lines[0]) < 300
    assert not (tmp_path / "o.csv").exists()


def test_a_row_the_integrator_cannot_afford_is_refused_by_its_motion(tmp_path, capsys):
    # 10 um stroke on the thickest hinge: the quasi-static limit does not hold and the
    # hinge period is 1e5 times shorter than the cycle
    p = tmp_path / "corner.csv"
    DESIGN.assign(thickness_m=0.0199, stroke_m=1e-5, velocity_m_s=1e-4, acceleration_m_s2=1e4).to_csv(p, index=False)
    out = tmp_path / "runs.csv"
    check_refused(capsys, ["simulate", str(p), "-o", str(out)], ["corner.csv", "steps per cycle", "stroke 1e-05 m"],
                  [p], [out])
