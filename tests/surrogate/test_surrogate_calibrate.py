"""Calibration (rsm_lrg.surrogate.calibrate): recovery of known parameters, file round trip,
the shipped calibration against Table 4."""

import math

import numpy as np
import pandas as pd
import pytest

from rsm_lrg.surrogate import simulate
from rsm_lrg.surrogate.calibrate import (
    ParameterSpec,
    calibrate,
    calibration_toml,
    load_calibration,
    resolve_calibration,
)


def synthetic(truth, n=12, seed=0, thickness=(3e-4, 5e-4)):
    rng = np.random.default_rng(seed)
    d = pd.DataFrame({"thickness_m": rng.choice(thickness, n), "stroke_m": rng.uniform(0.04, 0.06, n),
                      "velocity_m_s": rng.uniform(0.4, 0.6, n), "acceleration_m_s2": rng.uniform(20, 40, n)})
    d["tcr_c_per_min"] = simulate(d, noise_sd=0, calibration=truth).tcr_c_per_min
    return d


@pytest.mark.slow
def test_recovers_known_heat_parameters_exactly():
    # exact solution: data made by the surrogate itself with known parameters, no noise
    truth = {"heat_partition": 0.4, "viscous_friction_n_s_m": 5.0}
    d = synthetic(truth)
    cal = calibrate(d, parameters=["heat_partition", "viscous_friction_n_s_m"], source="synthetic", model="v4")
    got = cal.parameter_values()
    assert got["heat_partition"] == pytest.approx(0.4, rel=1e-5)
    assert got["viscous_friction_n_s_m"] == pytest.approx(5.0, rel=1e-4)
    assert cal.r2 == pytest.approx(1.0, abs=1e-9) and cal.loo_r2 == pytest.approx(1.0, abs=1e-8)
    assert cal.n == 12 and len(cal.loo_predicted) == 12


@pytest.mark.slow
def test_recovers_a_stage_parameter_through_the_profile_grid():
    # the small-deflection hinge of model v2, where the frame mass moves the stick-slip of the
    # thin leaf (with held ends the leaves are stiff enough that it hardly matters)
    truth = {"heat_partition": 0.5, "frame_mass_fraction": 0.3, "hinge_membrane": False}
    d = synthetic(truth, n=8, thickness=(1e-4, 3e-4))
    cal = calibrate(d, parameters=["heat_partition", "frame_mass_fraction"], loo=False, grid_points=7, model="v2")
    assert cal.r2 > 0.999
    assert cal.parameter_values()["heat_partition"] == pytest.approx(0.5, rel=1e-2)


@pytest.mark.slow
def test_noise_gives_finite_standard_errors_that_cover_the_truth():
    truth = {"heat_partition": 0.4, "viscous_friction_n_s_m": 5.0}
    d = synthetic(truth, n=20)
    d["tcr_c_per_min"] += np.random.default_rng(1).normal(0, 5e-4, len(d))
    cal = calibrate(d, parameters=["heat_partition", "viscous_friction_n_s_m"], loo=False, model="v4")
    for p in cal.parameters:
        assert math.isfinite(p.std_error) and p.std_error > 0
        assert abs(p.value - truth[p.name]) < 4 * p.std_error


@pytest.mark.slow
def test_toml_round_trip(tmp_path):
    d = synthetic({"heat_partition": 0.4, "viscous_friction_n_s_m": 5.0}, n=6)
    cal = calibrate(d, parameters=["heat_partition", "viscous_friction_n_s_m"], source="x.csv", model="v4",
                    data_sha256="ab" * 32)
    path = tmp_path / "cal.toml"
    path.write_text(calibration_toml(cal))
    back = load_calibration(path)
    assert back.parameter_values() == cal.parameter_values()
    assert back.r2 == cal.r2 and back.loo_r2 == cal.loo_r2 and back.data == "x.csv"
    assert back.observed == cal.observed and back.predicted == cal.predicted
    assert resolve_calibration(str(path)).parameter_values() == cal.parameter_values()


def test_bad_requests():
    d = synthetic({"heat_partition": 0.4}, n=6)
    with pytest.raises(ValueError, match="at most three"):
        calibrate(d, parameters=["heat_partition", "viscous_friction_n_s_m", "hinge_length_m", "hinge_width_m"])
    with pytest.raises(ValueError, match="unknown calibration parameter"):
        calibrate(d, parameters=["offset"])
    with pytest.raises(ValueError, match="not found"):
        calibrate(d, response="kappa")
    with pytest.raises(ValueError, match="start within the bounds"):
        calibrate(d, parameters=[ParameterSpec("heat_partition", 0.5, 1.0, 0.1, "1", "")])
    with pytest.raises(ValueError, match="too few"):
        calibrate(d.iloc[:2], parameters=["heat_partition"], model="v4")
    with pytest.raises(ValueError, match="heat_partition is not a parameter of model v5"):
        calibrate(d, parameters=["heat_partition"])


def test_bad_files(tmp_path):
    p = tmp_path / "c.toml"
    p.write_text("[parameters.offset]\nvalue = 1.0\n")
    with pytest.raises(ValueError, match="unknown parameter 'offset'"):
        load_calibration(p)
    p.write_text("[parameters.heat_partition]\nvalue = 2.0\nlower = 0.01\nupper = 1.0\n")
    with pytest.raises(ValueError, match="outside its bounds"):
        load_calibration(p)
    p.write_text("not toml [")
    with pytest.raises(ValueError, match="not valid TOML"):
        load_calibration(p)


@pytest.mark.parametrize("value", ["3", "false", "0.5"])
@pytest.mark.parametrize("switch", ["hinge_membrane", "heat_in_calories", "heat_balance"])
def test_a_switch_is_not_a_calibrated_number(tmp_path, switch, value):
    # value = 3 used to be 'outside its bounds [0, 1] (a share of the heat)'; false: 'must be a number'
    p = tmp_path / "c.toml"
    p.write_text(f"[parameters.{switch}]\nvalue = {value}\n")
    with pytest.raises(ValueError, match=rf"\[parameters\.{switch}\]: {switch} is a switch of the physics"):
        load_calibration(p)


def test_aicc_charges_each_parameter():
    # Hurvich & Tsai (1989): n ln(SSR/n) + 2k + 2k(k+1)/(n-k-1), by hand for n = 26
    import math

    from rsm_lrg.surrogate.calibrate import aicc

    assert aicc(0.5, 26, 3) == pytest.approx(26 * math.log(0.5 / 26) + 6 + 24 / 22, rel=1e-14)
    assert aicc(0.5, 26, 3) > aicc(0.5, 26, 2)
    with pytest.raises(ValueError, match="n > k"):
        aicc(1.0, 4, 3)


def test_selection_is_checked_and_recorded_in_the_file(tmp_path):
    d = synthetic({"heat_partition": 0.4}, n=6)
    with pytest.raises(ValueError, match="unknown calibration model"):
        calibrate(d, select=["v5", "nope"])
    with pytest.raises(ValueError, match="different"):
        calibrate(d, select=["v5", "v5"])
    p = tmp_path / "c.toml"
    p.write_text('[calibration]\nselected_from = "v5,v5-nodrive"\n[parameters.viscous_friction_n_s_m]\nvalue = 1.0\n'
                 "[runs]\nloo_model_index = [0, 1, 2]\n")
    with pytest.raises(ValueError, match="loo_model_index"):
        load_calibration(p)
    p.write_text('[calibration]\nselected_from = "v5,v9"\n[parameters.viscous_friction_n_s_m]\nvalue = 1.0\n')
    with pytest.raises(ValueError, match="selected_from"):
        load_calibration(p)
    p.write_text('[calibration]\nselected_from = "v5,v5-nodrive"\n[parameters.viscous_friction_n_s_m]\nvalue = 1.0\n'
                 "[runs]\nloo_model_index = [0, 1, 1]\n")
    c = load_calibration(p)
    assert c.selected_from == ("v5", "v5-nodrive") and c.loo_models == (0, 1, 1)
    assert c.to_dict()["loo_models"] == ["v5", "v5-nodrive", "v5-nodrive"]


def test_profile_interval_needs_a_parameter_of_the_calibration():
    from rsm_lrg.datasets import load_table4
    from rsm_lrg.surrogate.calibrate import profile_interval

    cal = resolve_calibration("default")
    with pytest.raises(ValueError, match="'mu_k' is not a parameter of this calibration"):
        profile_interval(load_table4(), cal, "mu_k")
    with pytest.raises(ValueError, match="names no model"):
        profile_interval(load_table4(), resolve_calibration({"heat_partition": 0.5}), "heat_partition")
