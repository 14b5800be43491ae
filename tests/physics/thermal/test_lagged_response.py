"""ThermalNetwork.lagged_response: the carriage's rise when its heat arrives through a
first-order lag (the drive heat behind the working stage's heat capacity, issue 15)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rsm_lrg.physics.heat import stage_time_constant
from rsm_lrg.physics.thermal.geometry import GuideGeometry
from rsm_lrg.physics.thermal.network import ThermalNetwork


@pytest.fixture(scope="module")
def net():
    return ThermalNetwork(GuideGeometry(), 8.82, 22.45)  # the paper's h (Eqs. 11-12)


@pytest.mark.slow
@settings(max_examples=15, deadline=None)
@given(st.floats(60.0, 5000.0), st.floats(60.0, 6000.0))
def test_equals_the_convolution_of_the_step_response(tau, t_end):
    # independent route: Duhamel's integral r(t) = int_0^t h(t - u) q'(u) du with the step
    # response h and q(u) = 1 - exp(-u/tau), by the trapezoidal rule on 200k intervals
    # (error ~1e-9 relative for these tau); tolerance 1e-6 relative
    net = ThermalNetwork(GuideGeometry(), 8.82, 22.45)
    u = np.linspace(0.0, t_end, 200_001)
    ref = np.trapezoid(net.response(t_end - u) * np.exp(-u / tau) / tau, u)
    assert float(net.lagged_response(t_end, tau)) == pytest.approx(ref, rel=1e-6)


def test_limits(net):
    t = np.array([0.0, 60.0, 600.0, 3000.0])
    # tau = 0: the step response itself, exactly
    np.testing.assert_array_equal(net.lagged_response(t, 0.0), net.response(t))
    # no rise at t = 0, below the step response after it, the same steady rise
    lag = net.lagged_response(t, 1200.0)
    assert lag[0] == 0.0 and np.all(lag[1:] < net.response(t[1:]))
    # (the modal sum against the direct steady solve: 1e-9 relative)
    assert float(net.lagged_response(1e9, 1200.0)) == pytest.approx(net.steady_rise_per_w, rel=1e-9)
    # a time constant equal to a mode's: the limit branch joins the general one continuously
    tau = float(net.time_constants_s[0])
    assert float(net.lagged_response(3000.0, tau)) == pytest.approx(
        float(net.lagged_response(3000.0, tau * (1 + 1e-6))), rel=1e-5)
    with pytest.raises(ValueError, match="tau_s"):
        net.lagged_response(60.0, -1.0)


def test_stage_time_constant():
    # tau = m c / (G_c + G_s): 0.135 kg of 6061-T6 (c = 896 J/(kg K), paper Table 2) on four
    # 0.3 mm leaves (G_c = 4 * 48 * 0.010 * 0.0003 / 0.020 W/K) and G_s = 0.08 W/K; exact algebra
    g = 4 * 48.0 * 0.010 * 0.0003 / 0.020
    assert float(stage_time_constant(0.135 * 896, g, 0.08)) == pytest.approx(0.135 * 896 / (g + 0.08), rel=1e-15)
    assert float(stage_time_constant(0.135 * 896, np.inf, 0.08)) == 0.0
