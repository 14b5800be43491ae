"""``rsm-lrg simulate --param``: no value given on the command line is silently replaced.

Before, ``--param stroke_m=...`` (a design factor), ``--param mu_k=...`` with a ``mu_k``
design column, and ``--param viscous_friction_n_s_m=...`` (a calibrated parameter) all ran
without the value, and a name given twice kept the last one silently.
"""

import pandas as pd
import pytest

from rsm_lrg.cli import main
from rsm_lrg.physics.params import LRGParams
from rsm_lrg.surrogate import simulate
from rsm_lrg.surrogate.calibrate import resolve_calibration

ROW = {"thickness_m": [3e-4], "stroke_m": [0.05], "velocity_m_s": [0.5], "acceleration_m_s2": [30.0]}


@pytest.fixture()
def design_csv(tmp_path):
    p = tmp_path / "design.csv"
    pd.DataFrame(ROW).to_csv(p, index=False)
    return p


def _one_error(capsys, *needles):
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error:"), err
    for n in needles:
        assert n in err[0], (n, err[0])


@pytest.mark.parametrize("item,column", [("stroke_m=0.01", "stroke_m"), ("velocity_m_s=0.1", "velocity_m_s"),
                                         ("acceleration_m_s2=5", "acceleration_m_s2"),
                                         ("hinge_thickness_m=0.001", "thickness_m")])
def test_a_design_factor_is_refused(design_csv, tmp_path, capsys, item, column):
    out = tmp_path / "o.csv"
    assert main(["simulate", str(design_csv), "--param", item, "-o", str(out)]) == 2
    _one_error(capsys, "--param " + item.split("=")[0], repr(column))
    assert not out.exists()


def test_a_design_column_of_the_same_name_is_refused(tmp_path, capsys):
    p = tmp_path / "d.csv"
    pd.DataFrame(dict(ROW, mu_k=[0.02])).to_csv(p, index=False)
    out = tmp_path / "o.csv"
    assert main(["simulate", str(p), "--param", "mu_k=0.05", "-o", str(out)]) == 2
    _one_error(capsys, "--param mu_k", "d.csv", "'mu_k'")
    assert not out.exists()


@pytest.mark.parametrize("a,b", [("mu_k=0.05", "mu_k=0.01"), ("heat_partition=0.5", "heat_partition=0.6")])
def test_a_name_given_twice_is_refused(design_csv, tmp_path, capsys, a, b):
    assert main(["simulate", str(design_csv), "--param", a, "--param", b, "-o", str(tmp_path / "o.csv")]) == 2
    _one_error(capsys, "more than once")


def test_param_replaces_the_calibrated_value_and_says_so(design_csv, tmp_path, capsys):
    out = tmp_path / "o.csv"
    assert main(["simulate", str(design_csv), "--noise-sd", "0", "--param", "viscous_friction_n_s_m=20",
                 "-o", str(out)]) == 0
    assert "replaces the calibrated" in capsys.readouterr().err
    # reference: the library with the shipped calibration, its viscous friction set to 20 N s/m
    # (the other calibrated values kept); the CSV holds 10 significant digits: rtol 1e-9
    cal = resolve_calibration("default").parameter_values()
    assert cal["viscous_friction_n_s_m"] != 20.0
    lib = simulate(pd.DataFrame(ROW), noise_sd=0, calibration=dict(cal, viscous_friction_n_s_m=20.0))
    got = pd.read_csv(out)
    for c in ("tcr_c_per_min", "heat_w", "sliding_distance_m_per_cycle"):
        assert got[c][0] == pytest.approx(lib[c][0], rel=1e-9), c
    default = simulate(pd.DataFrame(ROW), noise_sd=0)
    assert got.heat_w[0] > 1.1 * default.heat_w[0]  # the block's viscous heat grows with c_v (runs.py step 3)


def test_surrogate_parameter_by_param(design_csv, tmp_path):
    a, b = tmp_path / "a.csv", tmp_path / "b.csv"
    assert main(["simulate", str(design_csv), "--noise-sd", "0", "--uncalibrated", "-o", str(a)]) == 0
    assert main(["simulate", str(design_csv), "--noise-sd", "0", "--uncalibrated", "--param",
                 "heat_partition=0.5", "-o", str(b)]) == 0
    # the share of the friction heat entering the guide multiplies it (Eq. 8 times heat_partition;
    # no drive heat in the raw physics): exactly half, within the CSV's 10 digits (rtol 1e-9)
    ha, hb = pd.read_csv(a).heat_w[0], pd.read_csv(b).heat_w[0]
    assert hb == pytest.approx(0.5 * ha, rel=1e-9)


@pytest.mark.parametrize("item", ["heat_partition=0", "heat_partition=abc", "drive_friction_n=-1"])
def test_bad_surrogate_parameter(design_csv, tmp_path, capsys, item):
    assert main(["simulate", str(design_csv), "--param", item, "-o", str(tmp_path / "o.csv")]) == 2
    _one_error(capsys, "--param", item.split("=")[0])


def test_api_params_in_conflict_with_the_calibration():
    params = LRGParams().with_overrides(viscous_friction_n_s_m=20.0)
    with pytest.raises(ValueError, match="viscous_friction_n_s_m = 20.0 but the calibration"):
        simulate(pd.DataFrame(ROW), noise_sd=0, params=params)
    # without the calibration, or with the default value, it runs
    simulate(pd.DataFrame(ROW), noise_sd=0, params=params, calibration=None)
    simulate(pd.DataFrame(ROW), noise_sd=0, params=LRGParams())
