"""rsm_lrg.physics.thermal.two_carriage.two_carriage_rows: many rows of the two-carriage rig in one
compiled loop, against each row's own dense network (two_carriage_network), row by row."""

from __future__ import annotations

import numpy as np
import pytest

from rsm_lrg.physics import motion
from rsm_lrg.physics.params import LRGParams
from rsm_lrg.physics.thermal.fixed_order import RowError, patched_rows
from rsm_lrg.physics.thermal.two_carriage import STAGES, CarriageSetting, two_carriage_network, two_carriage_rows


def _box(n, seed):
    """n random rows of the Table 3 box (thickness, stroke, <v²> of velocity and acceleration), a
    third of them observing the RMS's carriage, durations anywhere in 1..120 min."""
    rng = np.random.default_rng(seed)
    y, s = rng.uniform(1e-4, 5e-4, n), rng.uniform(0.04, 0.06, n)
    msq = motion.mean_square_speed(s, rng.uniform(0.4, 0.6, n), rng.uniform(20.0, 40.0, n))
    dur = rng.uniform(1.0, 120.0, n)
    times = np.stack([np.floor(dur), np.ceil(dur), dur, np.full(n, 50.0)], axis=1) * 60.0
    return y, s, np.asarray(msq, float), rng.random(n) < 1 / 3, times


@pytest.mark.parametrize("over", [{}, {"ball_contact_conductance_w_k": 1.0512, "carriage_spacing_m": 0.16},
                                  {"ball_contact_conductance_w_k": 0.1168, "air_velocity_m_s": 0.05}])
def test_every_row_equals_its_own_dense_network(over):
    # both stages' heat (the other stage running or not reads one column or both) at four times and in the
    # steady state, on random rows of the box: the dense decomposition of the row's own network is the reference
    v = LRGParams().with_overrides(**over).to_dict()
    y, s, msq, obs, times = _box(40, seed=len(over))
    resp, steady = two_carriage_rows(v, y, s, msq, obs, times)
    worst = 0.0
    for i in range(len(y)):
        run = CarriageSetting(float(y[i]), float(s[i]), float(msq[i]))
        net = two_carriage_network(v, run, run)
        node = "rms.carriage" if obs[i] else "rfcms.carriage"
        for c, src in enumerate(STAGES):
            want = net.response(times[i], node, src)
            worst = max(worst, float(np.max(np.abs(resp[i, c] / want - 1.0))))
            worst = max(worst, abs(steady[i, c] / net.steady_rise(src)[net.node(node)] - 1.0))
    assert worst < 1e-11


def test_a_row_is_bit_identical_alone_among_others_and_in_any_order():
    v = LRGParams().to_dict()
    y, s, msq, obs, times = _box(30, seed=7)
    resp, steady = two_carriage_rows(v, y, s, msq, obs, times)
    perm = np.random.default_rng(1).permutation(30)
    r_p, s_p = two_carriage_rows(v, y[perm], s[perm], msq[perm], obs[perm], times[perm])
    assert np.array_equal(r_p, resp[perm]) and np.array_equal(s_p, steady[perm])
    for i in (0, 13, 29):
        r1, s1 = two_carriage_rows(v, y[i:i + 1], s[i:i + 1], msq[i:i + 1], obs[i:i + 1], times[i:i + 1, :2])
        assert np.array_equal(r1[0], resp[i, :, :2]) and np.array_equal(s1[0], steady[i])


def test_the_steady_state_closes_the_heat_balance_of_each_row():
    # at t -> infinity the modal sum reaches the steady rise solved from K (two routes: the modes' rounding,
    # eps times the ratio of the fastest to the slowest rate, about 1e-11), and the steady rise of each row's
    # network, which the rows equal, closes its heat balance to 1e-12 (every watt leaves to the air or the room)
    v = LRGParams().to_dict()
    y, s, msq, obs, _ = _box(6, seed=3)
    resp, steady = two_carriage_rows(v, y, s, msq, obs, np.full((6, 1), 1e9))
    np.testing.assert_allclose(resp[:, :, 0], steady, rtol=1e-10)
    for i in range(6):
        run = CarriageSetting(float(y[i]), float(s[i]), float(msq[i]))
        net = two_carriage_network(v, run, run)
        for src in STAGES:
            assert abs(net.heat_balance(src) - 1.0) < 1e-12


def test_the_first_refused_row_is_named_with_the_network_s_reason():
    v = LRGParams().to_dict()
    y, s, msq, obs, times = _box(5, seed=2)
    s = np.full(5, 0.05)
    s[3], s[4] = 0.058, -1.0  # centres 0.12 m apart: blocks of 64.4 mm with a 58 mm stroke collide
    with pytest.raises(RowError, match="collide") as exc:
        two_carriage_rows(dict(v, carriage_spacing_m=0.12), y, s, msq, obs, times)
    assert exc.value.row == 3
    run = CarriageSetting(float(y[3]), 0.058, float(msq[3]))
    with pytest.raises(ValueError, match="collide"):
        two_carriage_network(dict(v, carriage_spacing_m=0.12), run, run)
    with pytest.raises(RowError, match="off the rail") as exc:
        two_carriage_rows(v, y, np.array([0.05, 0.05, 0.05, 0.3, 0.05]), msq, obs, times)
    assert exc.value.row == 3
    with pytest.raises(RowError, match="CarriageSetting.stroke_m") as exc:
        two_carriage_rows(v, y, s, msq, obs, times)
    assert exc.value.row == 4
    with pytest.raises(RowError, match="Re = ") as exc:
        two_carriage_rows(v, y[:2], s[:2], np.array([0.2, 1e12]), obs[:2], times[:2])
    assert exc.value.row == 1
    with pytest.raises(RowError, match="stroke_m") as exc:  # the very first row: nothing is solved
        two_carriage_rows(v, y[:2], np.array([-1.0, 0.05]), msq[:2], obs[:2], times[:2])
    assert exc.value.row == 0
    with pytest.raises(ValueError, match="ball_contact_conductance_w_k"):
        two_carriage_rows(dict(v, ball_contact_conductance_w_k=0.0), y, s, msq, obs, times)


def test_patched_rows_against_lapack_on_random_networks():
    # a small network with random patches: each row's response equals an independent eigh of its own matrix
    rng = np.random.default_rng(4)
    n, rows = 7, 5
    a = rng.uniform(0.1, 1.0, (n, n))
    k = -(a + a.T)
    np.fill_diagonal(k, 0.0)
    np.fill_diagonal(k, -k.sum(axis=1) + rng.uniform(0.05, 0.2, n))
    c = rng.uniform(1.0, 5.0, n)
    src = rng.uniform(0.0, 1.0, (n, 2))
    k_pos = np.array([[0, 0], [1, 1], [0, 1], [1, 1]])
    k_add = np.column_stack([rng.uniform(0.1, 0.5, rows)] * 2 + [-np.full(rows, 0.05), np.full(rows, 0.05)])
    c_add = rng.uniform(0.0, 2.0, (rows, 1))
    s_add = rng.uniform(0.0, 0.5, (rows, 1))
    node = rng.integers(0, n, rows)
    t = rng.uniform(0.0, 50.0, (rows, 3))
    resp, steady = patched_rows(k, c, src, k_pos, k_add, [2], c_add, [[4, 1]], s_add, node, t)
    for r in range(rows):
        kr = k.copy()
        kr[0, 0] += k_add[r, 0]
        kr[1, 1] += k_add[r, 1] + k_add[r, 3]
        kr[0, 1] += k_add[r, 2]
        kr[1, 0] += k_add[r, 2]
        cr = c.copy()
        cr[2] += c_add[r, 0]
        sr = src.copy()
        sr[4, 1] += s_add[r, 0]
        sc = 1 / np.sqrt(cr)
        mu, vec = np.linalg.eigh(sc[:, None] * kr * sc[None, :])
        for col in range(2):
            th = np.linalg.solve(kr, sr[:, col])
            assert steady[r, col] == pytest.approx(th[node[r]], rel=1e-12)
            coef = sc[node[r]] * vec[node[r]] * (vec.T @ (sc * sr[:, col])) / mu
            want = -np.expm1(-np.multiply.outer(t[r], mu)) @ coef
            np.testing.assert_allclose(resp[r, col], want, rtol=1e-11)
    with pytest.raises(RowError, match="heat capacity") as exc:
        patched_rows(k, c, src, k_pos, k_add, [2], -np.array([[0.0], [0.0], [9.0], [0.0], [0.0]]), [[4, 1]],
                     s_add, node, t)
    assert exc.value.row == 2
