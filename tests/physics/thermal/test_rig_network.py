"""One heat balance in watts: the guide's network with the rig's bodies (issue 24 item 1)."""

import numpy as np
import pytest
import scipy.linalg

from rsm_lrg.physics.params import LRGParams
from rsm_lrg.physics.thermal.geometry import GuideGeometry
from rsm_lrg.physics.thermal.network import RigBodies, ThermalNetwork, rig_bodies, rig_network

V = LRGParams().to_dict()
G = GuideGeometry.from_params(V)


def _net(y=3e-4, rigid=False, dx=1e-2, **over):
    return rig_network(G, 8.82, 22.45, rig_bodies(dict(V, **over), y, rigid=rigid), dx_m=dx)


@pytest.mark.parametrize("rigid", [False, True])
@pytest.mark.parametrize("source", ["balls", "stage"])
def test_every_watt_leaves_to_the_air_somewhere(rigid, source):
    # energy balance of the steady state: the shares given to the air by all bodies sum to 1
    hp = _net(rigid=rigid).heat_paths(source)
    assert sum(hp.to_ambient.values()) == pytest.approx(1.0, abs=1e-12)
    assert all(v >= -1e-15 for v in hp.to_ambient.values())
    assert set(hp.to_ambient) == {"carriage", "balls", "rail", "frame", "stage", "base"} | (
        set() if rigid else {"leaves"})
    if source == "balls":  # the friction heat leaves the contacts into the carriage or into the rail
        assert hp.into_carriage + hp.into_rail == pytest.approx(1.0, abs=1e-12)
        assert 0 < hp.into_carriage < 1


def test_transient_against_the_matrix_exponential():
    # independent route: theta(t) = int_0^t exp(-C^-1 K s) ds C^-1 b, from the augmented matrix
    # exponential (Van Loan 1978), no eigen-decomposition
    net = _net(y=1e-4)
    n = len(net.C)
    A = -net.K / net.C[:, None]
    for source in ("balls", "stage"):
        f = net.sources[source] / net.C
        M = np.zeros((n + 1, n + 1))
        M[:n, :n] = A
        M[:n, n] = f
        for t in (60.0, 600.0, 3000.0):
            theta = scipy.linalg.expm(M * t)[:n, n]
            assert net.response([t], source=source)[0] == pytest.approx(theta[0], rel=1e-9)
        assert net.steady_rise(source)[0] == pytest.approx(np.linalg.solve(net.K, net.sources[source])[0], rel=1e-10)


def test_the_leaves_set_how_much_stage_heat_reaches_the_carriage():
    # a watt entering the working stage reaches the carriage through the leaves (n lambda w y / l,
    # Eq. 3): more through thicker leaves, most through the RMS's bolted joint
    r = [_net(y=y).response([3000.0], source="stage")[0] for y in (1e-4, 3e-4, 5e-4)]
    rms = _net(rigid=True).response([3000.0], source="stage")[0]
    assert 0 < r[0] < r[1] < r[2] < rms
    # the friction heat escapes a little more through thicker leaves (a fin): slightly cooler carriage
    f = [_net(y=y).response([3000.0], source="balls")[0] for y in (1e-4, 5e-4)]
    assert f[1] < f[0]


def test_share_into_the_carriage_follows_the_ball_contacts():
    # no free heat share: what enters the carriage is set by the conductances. Better contacts tie
    # the carriage to the rail bolted on the base: a lower carriage rise per watt
    lo = _net(ball_contact_conductance_w_k=0.1).heat_paths("balls")
    hi = _net(ball_contact_conductance_w_k=10.0).heat_paths("balls")
    assert hi.carriage_rise_per_w < lo.carriage_rise_per_w
    assert 0 < lo.into_carriage < 1 and 0 < hi.into_carriage < 1


def test_rail_cells_converge():
    # 10 mm rail cells (the surrogate's) against 1 mm: within 0.3 % at 50 min
    fine = _net(y=1e-4, dx=1e-3).response([3000.0], source="balls")[0]
    used = _net(y=1e-4, dx=1e-2).response([3000.0], source="balls")[0]
    assert used == pytest.approx(fine, rel=3e-3)


def test_without_the_rig_the_guide_network_is_unchanged():
    # the paper's guide-only network (adiabatic base, perfect ball contacts) keeps its numbers
    plain = ThermalNetwork(G, 8.82, 22.45)
    assert plain.response([1e7])[0] * 0.415 == pytest.approx(2.795, abs=5e-4)
    assert list(plain.sources) == ["balls"]
    with pytest.raises(ValueError, match="source"):
        plain.response([1.0], source="stage")


def test_bodies_are_checked():
    good = rig_bodies(V, 3e-4)
    with pytest.raises(ValueError, match="ball_contact_w_k"):
        RigBodies(**dict(good.__dict__, ball_contact_w_k=0.0))
    with pytest.raises(ValueError, match="base_capacity_j_k"):
        RigBodies(**dict(good.__dict__, base_capacity_j_k=float("nan")))
    assert good.leaf_w_k == pytest.approx(4 * 48.0 * 0.010 * 3e-4 / 0.020, rel=1e-12)


def test_many_rows_in_one_loop_are_each_rows_own_network():
    # rig_responses (the core reduced once, a QL per row) against rig_network (one dense
    # decomposition per thickness): two routes to the same numbers, equal to rounding;
    # thicknesses drawn at random and repeated, two times per row; the RMS too
    from rsm_lrg.physics.thermal.network import leaf_terms, rig_responses

    rng = np.random.default_rng(7)
    y = np.concatenate([rng.uniform(1e-4, 5e-4, 9), [2e-4, 2e-4]])
    t = np.stack([rng.uniform(0, 3600, y.size), rng.uniform(0, 9000, y.size)], axis=1).round()
    for rigid in (False, True):
        rig = rig_bodies(V, 3e-4, rigid=rigid)
        g, c = leaf_terms(V, y)
        resp, steady = rig_responses(G, 8.82, 22.45, rig, g, c, t)
        for r in range(y.size):
            net = _net(y=y[r], rigid=rigid)
            for k, source in enumerate(("balls", "stage")):
                np.testing.assert_allclose(resp[r, k], net.response(t[r], source=source), rtol=1e-11, atol=0)
                assert steady[r, k] == pytest.approx(net.steady_rise(source)[0], rel=1e-12)
        # a row's values do not depend on the other rows asked for with it
        r1, s1 = rig_responses(G, 8.82, 22.45, rig, g[3:4], c[3:4], t[3:4])
        assert np.array_equal(r1[0], resp[3]) and np.array_equal(s1[0], steady[3])


def test_many_rows_against_the_matrix_exponential():
    # independent route (no eigen-decomposition): the augmented matrix exponential of each
    # row's own network, assembled by ThermalNetwork
    from rsm_lrg.physics.thermal.network import leaf_terms, rig_responses

    y = np.array([1e-4, 2.7e-4, 5e-4])
    g, c = leaf_terms(V, y)
    resp, _ = rig_responses(G, 8.82, 22.45, rig_bodies(V, 1e-4), g, c, np.full((3, 1), 1800.0))
    for r in range(3):
        net = _net(y=y[r])
        n = len(net.C)
        for k, source in enumerate(("balls", "stage")):
            M = np.zeros((n + 1, n + 1))
            M[:n, :n] = -net.K / net.C[:, None]
            M[:n, n] = net.sources[source] / net.C
            assert resp[r, k, 0] == pytest.approx(scipy.linalg.expm(M * 1800.0)[0, n], rel=1e-9)


def test_a_failing_row_is_named():
    from rsm_lrg.physics.thermal.fixed_order import RowError
    from rsm_lrg.physics.thermal.network import leaf_terms, rig_responses

    g, c = leaf_terms(V, np.array([1e-4, 2e-4, 3e-4]))
    with pytest.raises(RowError, match="row 1:") as e:
        rig_responses(G, 8.82, 22.45, rig_bodies(V, 1e-4), g, np.array([c[0], -c[1], c[2]]), np.zeros((3, 1)))
    assert e.value.row == 1
