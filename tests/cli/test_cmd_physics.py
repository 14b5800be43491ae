"""``rsm-lrg physics`` from outside: exit codes, one-line errors, the JSON keys."""

import json
import subprocess
import sys

import pytest


def run(*args, **kw):
    return subprocess.run([sys.executable, "-m", "rsm_lrg", "physics", *args], capture_output=True, text=True, **kw)


@pytest.mark.slow
def test_table_and_json_to_stdout():
    out = run("--no-thermal", "--json", "-")
    assert out.returncode == 0, out.stderr
    d = json.loads(out.stdout)
    assert list(d) == ["normal_load_n", "f_mu_max_n", "heat_w", "heat_source_w_m3", "reynolds", "prandtl",
                       "h_side_w_m2k", "h_front_w_m2k", "hinge", "thermal", "wear", "leaf_yield", "leaf_fatigue", "rig"]
    assert list(d["thermal"]) == ["steady_rise_k_fv", "steady_rise_k_network", "time_to_95_percent_h", "tcr_c_per_min"]
    assert list(d["wear"]) == ["rfcms_over_rms"]
    assert abs(d["normal_load_n"] - 173.65) < 0.005   # paper Section 2.1
    assert "normal_load_n" in out.stderr               # the table goes to stderr when JSON is on stdout


@pytest.mark.slow
def test_json_file_force_and_params(tmp_path):
    dest = tmp_path / "p.json"
    out = run("--no-thermal", "--param", "mu_k=0.01", "--json", str(dest))
    assert out.returncode == 0, out.stderr
    assert "heat_w" in out.stdout
    assert json.loads(dest.read_text())["heat_w"] == pytest.approx(0.4150 / 2, rel=5e-4)   # Eq. 8 linear in mu_k
    again = run("--no-thermal", "--json", str(dest))
    assert again.returncode == 2 and again.stderr.startswith("error:") and "--force" in again.stderr
    assert run("--no-thermal", "--json", str(dest), "--force").returncode == 0
    toml = tmp_path / "o.toml"
    toml.write_text("mu_s = 0.06\n")
    d = json.loads(run("--no-thermal", "--params-file", str(toml), "--json", "-").stdout)
    assert d["f_mu_max_n"] == pytest.approx(2 * 5.2094, rel=1e-4)


@pytest.mark.parametrize("args,words", [
    (["--param", "no_such=1"], "no_such"),
    (["--param", "mu_s=2"], "mu_s"),
    (["--param", "stroke_m=-0.1"], "stroke_m"),
    (["--param", "mu_k=abc"], "mu_k"),
    (["--param", "mu_k"], "NAME=VALUE"),
    (["--params-file", "/no/such/file.toml"], "file.toml"),
])
def test_bad_parameters_exit_2_with_one_line(args, words):
    out = run("--no-thermal", *args)
    assert out.returncode == 2
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error:") and words in lines[0]


@pytest.mark.slow
def test_with_thermal_model():
    out = run("--json", "-")
    assert out.returncode == 0, out.stderr
    d = json.loads(out.stdout)
    assert all(isinstance(d["thermal"][k], float) for k in d["thermal"])


def test_list_params():
    out = run("--list-params")
    assert out.returncode == 0 and "hinge_width_m" in out.stdout and "ASSUMPTION" in out.stdout
    # an assumed parameter says so once, with its rationale (it printed "ASSUMPTION  [ASSUMPTION]")
    line = next(ln for ln in out.stdout.splitlines() if ln.startswith("hinge_width_m = "))
    assert line.count("ASSUMPTION") == 1 and "ASSUMPTION: Not given in the paper" in line
    assert "hinge_modulus_pa = 2.11e+11 [Pa] in [1e+06, 1.2e+12]" in out.stdout  # one number format


@pytest.mark.slow
def test_no_thermal_says_it_was_skipped():
    # it used to say 'rsm_lrg.physics.thermal.thermal_summary is not available'
    out = run("--no-thermal")
    assert out.returncode == 0, out.stderr
    assert "not computed" in out.stdout and "not available" not in out.stdout


@pytest.mark.slow
def test_no_static_friction_has_no_thickness_for_the_paper_ratio():
    # mu_s = 0: f_mu_max = 0, Eq. 2 gives no deflection at any thickness; the inverse gave 0 m
    from rsm_lrg.physics.chain import physics_chain

    r = physics_chain(thermal=False, mu_s=0.0)
    assert r.f_mu_max_n == 0.0 and r.details["thickness_for_paper_ratio_m"] is None
    assert "thickness_for_paper_ratio_m" in r.to_text() and "n/a" in r.to_text()
    # default: the inverse of Eqs. 1-2, y = (f l^3 / (n dd E w))^(1/3) with dd = 0.075 (1 - 0.5893) m
    # (Eq. 14), f = 5.2094 N, l = 0.02 m, w = 0.01 m, E = 211 GPa, n = 4: 5.4323e-5 m (hand, rel 1e-4)
    d = physics_chain(thermal=False).details
    assert d["thickness_for_paper_ratio_m"] == pytest.approx(5.4323e-5, rel=1e-4)


@pytest.mark.slow
def test_physics_refuses_geometry_that_simulate_refuses(capsys):
    # the same checks as simulate's (surrogate.design_input): the carriage stays on the rail
    # (stroke <= 0.4 m rail - 0.0644 m block = 0.3356 m, data/lrg_shs15v.toml), a leaf is
    # thinner than its 20 mm length
    from rsm_lrg.cli import main

    assert main(["physics", "--no-thermal", "--param", "stroke_m=0.3356"]) == 0
    capsys.readouterr()
    assert main(["physics", "--no-thermal", "--param", "stroke_m=0.34"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: stroke_m = 0.34 m: the carriage must stay on the rail") and "\n" not in err
    assert main(["physics", "--no-thermal", "--param", "hinge_thickness_m=0.02"]) == 2
    assert "a leaf hinge must be thinner than its length" in capsys.readouterr().err
