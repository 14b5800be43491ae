"""Batches and executors: the same seed gives the same rows on one process, local
processes and a Dask cluster (rsm_lrg.surrogate.execute)."""

from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pandas as pd
import pytest

from rsm_lrg.surrogate import simulate

OUT = ["tcr_c_per_min", "temperature_rise_k", "steady_rise_k", "wear_volume_m3_per_h",
       "sliding_distance_m_per_cycle"]


def grid(n=24, seed=0):
    rng = np.random.default_rng(seed)
    return pd.DataFrame({
        "run": np.arange(1, n + 1),
        "thickness_m": rng.choice([3e-4, 5e-4], n),   # stiff hinges: quick dynamics
        "stroke_m": rng.uniform(0.04, 0.06, n),
        "velocity_m_s": rng.uniform(0.4, 0.6, n),
        "acceleration_m_s2": rng.uniform(20, 40, n),
        "stage": rng.choice(["rfcms", "rms"], n),
        "label": [f"r{i}" for i in range(n)],
    })


@pytest.fixture(scope="module")
def design():
    return grid()


@pytest.fixture(scope="module")
def reference(design):
    return simulate(design, seed=42, noise_sd=0.03, batch_rows=5)


def test_keeps_input_columns_and_adds_outputs(design, reference):
    assert list(reference.columns[: design.shape[1]]) == list(design.columns)
    pd.testing.assert_frame_equal(reference[design.columns], design)
    for c in OUT:
        assert c in reference and np.isfinite(reference[c]).all()


def test_in_process_batches_do_not_change_the_noise(design, reference):
    # the noise of a row depends only on (seed, row index): noisy minus noise-free is the
    # same whatever the batch size
    other = simulate(design, seed=42, noise_sd=0.03, batch_rows=7)
    clean5 = simulate(design, noise_sd=0, batch_rows=5)
    clean7 = simulate(design, noise_sd=0, batch_rows=7)
    np.testing.assert_array_equal(reference.temperature_rise_k - clean5.temperature_rise_k,
                                  other.temperature_rise_k - clean7.temperature_rise_k)


def test_process_pool_gives_identical_rows(design, reference):
    with ProcessPoolExecutor(max_workers=2) as ex:
        got = simulate(design, seed=42, noise_sd=0.03, batch_rows=5, executor=ex)
    pd.testing.assert_frame_equal(got, reference, check_exact=True)


@pytest.mark.cluster
@pytest.mark.slow
def test_dask_local_cluster_gives_identical_rows(design, reference):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(processes=True, n_workers=2, threads_per_worker=1, host="127.0.0.1",
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        got = simulate(design, seed=42, noise_sd=0.03, batch_rows=5, executor=client.get_executor())
        workers = set(client.run(lambda: 1))
    assert len(workers) == 2
    pd.testing.assert_frame_equal(got, reference, check_exact=True)


def test_seed_controls_the_noise(design, reference):
    again = simulate(design, seed=42, noise_sd=0.03, batch_rows=5)
    pd.testing.assert_frame_equal(again, reference, check_exact=True)
    other = simulate(design, seed=43, noise_sd=0.03, batch_rows=5)
    assert not np.array_equal(other.tcr_c_per_min, reference.tcr_c_per_min)
    gen = simulate(design, seed=np.random.default_rng(1), noise_sd=0.03, batch_rows=5)
    gen2 = simulate(design, seed=np.random.default_rng(1), noise_sd=0.03, batch_rows=5)
    pd.testing.assert_frame_equal(gen, gen2)


def test_zero_noise_is_deterministic_and_ignores_the_seed(design):
    a = simulate(design, seed=1, noise_sd=0)
    b = simulate(design, seed=2, noise_sd=0)
    pd.testing.assert_frame_equal(a, b, check_exact=True)


def test_progress_bar_on_stderr(design, capsys):
    simulate(design.iloc[:4], noise_sd=0, progress=True, batch_rows=2)
    err = capsys.readouterr().err
    assert "virtual runs" in err and "4/4" in err


def test_bad_arguments():
    d = grid(3)
    with pytest.raises(ValueError, match="noise_sd"):
        simulate(d, noise_sd=-1)
    with pytest.raises(ValueError, match="duration_min"):
        simulate(d, duration_min=0.5)
    with pytest.raises(TypeError, match="executor"):
        simulate(d, executor=object())
    with pytest.raises(ValueError, match="batch_rows"):
        simulate(d, batch_rows=0)
    with pytest.raises(TypeError, match="params"):
        simulate(d, params={"mu_k": 0.1})


def test_output_column_in_the_input_is_kept_as_input():
    d = grid(3).assign(tcr_c_per_min=[1.0, 2.0, 3.0])
    out = simulate(d, noise_sd=0)
    assert out["tcr_c_per_min_input"].tolist() == [1.0, 2.0, 3.0]
    assert (out["tcr_c_per_min"] < 1).all()


def test_a_row_alone_agrees_with_the_row_in_its_batch():
    # deterministic part: the stick-slip integrator gives every row its own step count, so a
    # row alone equals the row among others (thin and thick hinges mixed; 1e-12 relative
    # leaves room only for last-bit differences of vectorised floating point)
    d = grid(12, seed=3).assign(thickness_m=lambda x: np.where(np.arange(12) % 2, 1e-4, 3e-4))
    whole = simulate(d, noise_sd=0).tcr_c_per_min.to_numpy()
    alone = np.array([simulate(d.iloc[[i]], noise_sd=0).tcr_c_per_min.iloc[0] for i in range(len(d))])
    np.testing.assert_allclose(alone, whole, rtol=1e-12)
