"""The drive-friction thickness mechanism of calibration model v4 (issue 15): the heat of the
drive element's Coulomb friction, F_d <|v|>, enters the working stage and reaches the carriage
through the leaves (conductance ~ y) behind the stage's heat capacity; the RMS's rigid joint
passes all of it at once."""

import numpy as np
import pandas as pd
import pytest

from rsm_lrg.physics import convection, motion
from rsm_lrg.physics.params import LRGParams
from rsm_lrg.physics.thermal.geometry import GuideGeometry
from rsm_lrg.physics.thermal.network import ThermalNetwork
from rsm_lrg.surrogate import simulate

ROWS = pd.DataFrame({"thickness_m": [1e-4, 3e-4, 5e-4, 3e-4], "stroke_m": [0.05, 0.05, 0.05, 0.05],
                     "velocity_m_s": [0.5, 0.5, 0.5, 0.5], "acceleration_m_s2": [30.0, 30.0, 30.0, 30.0],
                     "stage": ["rfcms", "rfcms", "rfcms", "rms"]})


def _runs(fd, name="drive_friction_n"):
    return simulate(ROWS, noise_sd=0, calibration={"heat_partition": 0.3, "viscous_friction_n_s_m": 8.0,
                                                   name: fd})


@pytest.mark.parametrize("name", ["drive_friction_n", "drive_viscous_n_s_m"])
def test_drive_friction_heat_by_hand(name):
    # Hand route: P = F_d * 2 s / T (T the trapezoidal cycle of Eqs. 15-16; Coulomb friction of
    # the drive) or c_d * <v^2> (its viscous friction; per stroke v_p s - v_p^3/(3 a), exact
    # for the trapezoid, computed here from the closed form), the carriage's share
    # G/(G + G_s) with G = n lambda w y / l (Fourier; 65Mn lambda = 48 W/(m K), paper Table 2),
    # reached through tau = m_ws c / (G + G_s) (6061-T6 c = 896 J/(kg K), Table 2); the rise at
    # 50 min from the exact lagged modal response. Tolerance 1e-9 relative (same algebra,
    # different code path; the dynamics do not depend on F_d).
    p = LRGParams()
    base, with_fd = _runs(0.0, name), _runs(2.0, name)
    T = float(motion.cycle_time(0.05, 0.5, 30.0))
    if name == "drive_friction_n":
        power = 2.0 * 2 * 0.05 / T
    else:  # trapezoid: v_p = 0.5 m/s (0.5^2/30 < 0.05 m)
        power = 2.0 * 2 * (0.5 * 0.05 - 0.5 ** 3 / (3 * 30.0)) / T
    hs, hf = convection.coefficients(p.to_dict())
    net = ThermalNetwork(GuideGeometry.from_params(p.to_dict()), hs, hf)
    cap = (1 - p.frame_mass_fraction) * p.stage_mass_kg * p.stage_specific_heat_j_kgk
    for i, y in enumerate([1e-4, 3e-4, 5e-4]):
        g = p.hinge_count * p.hinge_conductivity_w_mk * p.hinge_width_m * y / p.hinge_length_m
        q = power * g / (g + p.stage_loss_conductance_w_k)
        tau = cap / (g + p.stage_loss_conductance_w_k)
        rise = q * float(net.lagged_response(50 * 60.0, tau))
        assert with_fd.temperature_rise_k[i] - base.temperature_rise_k[i] == pytest.approx(rise, rel=1e-9)
        assert with_fd.heat_w[i] - base.heat_w[i] == pytest.approx(q, rel=1e-12)
    # the RMS: all of it, as a step
    assert with_fd.heat_w[3] - base.heat_w[3] == pytest.approx(power, rel=1e-12)
    assert with_fd.temperature_rise_k[3] - base.temperature_rise_k[3] == pytest.approx(
        power * float(net.response([50 * 60.0])[0]), rel=1e-9)


def test_drive_friction_raises_kappa_with_thickness_and_leaves_the_dynamics_alone():
    base, with_fd = _runs(0.0), _runs(1.0)
    extra = (with_fd.tcr_c_per_min - base.tcr_c_per_min).to_numpy()
    assert 0 < extra[0] < extra[1] < extra[2] < extra[3]
    np.testing.assert_array_equal(with_fd.sliding_distance_m_per_cycle, base.sliding_distance_m_per_cycle)


def test_bad_drive_friction_column_names_the_row():
    d = ROWS.assign(drive_friction_n=[0.0, -1.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="drive_friction_n"):
        simulate(d, noise_sd=0)
