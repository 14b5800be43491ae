"""Batches and executors: the same seed gives the same rows on one process, local
processes and a Dask cluster (rsm_lrg.surrogate.execute)."""

from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

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


@pytest.mark.slow
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


@pytest.mark.slow
def test_seed_controls_the_noise(design, reference):
    again = simulate(design, seed=42, noise_sd=0.03, batch_rows=5)
    pd.testing.assert_frame_equal(again, reference, check_exact=True)
    other = simulate(design, seed=43, noise_sd=0.03, batch_rows=5)
    assert not np.array_equal(other.tcr_c_per_min, reference.tcr_c_per_min)
    gen = simulate(design, seed=np.random.default_rng(1), noise_sd=0.03, batch_rows=5)
    gen2 = simulate(design, seed=np.random.default_rng(1), noise_sd=0.03, batch_rows=5)
    pd.testing.assert_frame_equal(gen, gen2)


@pytest.mark.slow
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


@pytest.mark.slow
def test_a_row_alone_agrees_with_the_row_in_its_batch():
    # deterministic part: the stick-slip integrator gives every row its own step count, so a
    # row alone equals the row among others (thin and thick hinges mixed; 1e-12 relative
    # leaves room only for last-bit differences of vectorised floating point)
    d = grid(12, seed=3).assign(thickness_m=lambda x: np.where(np.arange(12) % 2, 1e-4, 3e-4))
    whole = simulate(d, noise_sd=0).tcr_c_per_min.to_numpy()
    alone = np.array([simulate(d.iloc[[i]], noise_sd=0).tcr_c_per_min.iloc[0] for i in range(len(d))])
    np.testing.assert_allclose(alone, whole, rtol=1e-12)


# ----------------------------------------------------------------------------------------
# bit-identity wherever a row runs (issue 10 item 1). Root cause of the old 1.7e-15 Dask
# difference: LAPACK's eigh/solve in the thermal network give last-bit differences with a
# different number of BLAS threads (a Dask worker starts with one); the network now uses
# rsm_lrg.physics.thermal.fixed_order (no BLAS/LAPACK).
# ----------------------------------------------------------------------------------------
def mixed(n=16):
    """Rows with different durations (each batch then asks the thermal model for a
    different number of minutes), thin and thick hinges and both stages."""
    d = grid(n, seed=5)
    d["thickness_m"] = np.where(np.arange(n) % 3 == 0, 1e-4, d["thickness_m"])
    d["test_duration_min"] = np.where(np.arange(n) % 2, 50.0, 37.5 + np.arange(n))
    return d


@pytest.mark.slow
def test_rows_do_not_depend_on_their_batch_or_neighbours():
    d = mixed()
    whole = simulate(d, noise_sd=0)
    for batch in (1, 3, 7):
        pd.testing.assert_frame_equal(simulate(d, noise_sd=0, batch_rows=batch), whole, check_exact=True)
    # the same rows in another order and with other neighbours: each row is the same
    perm = np.random.default_rng(0).permutation(len(d))
    shuffled = simulate(d.iloc[perm].reset_index(drop=True), noise_sd=0, batch_rows=5)
    for c in OUT + ["heat_w", "cycle_time_s"]:
        np.testing.assert_array_equal(shuffled[c].to_numpy(), whole[c].to_numpy()[perm], err_msg=c)
    alone = pd.concat([simulate(d.iloc[[i]], noise_sd=0) for i in (0, 5, 11)])
    np.testing.assert_array_equal(alone[OUT].to_numpy(), whole.iloc[[0, 5, 11]][OUT].to_numpy())


_DIGEST = """
import hashlib, sys
import numpy as np
sys.path.insert(0, {tests!r})
from test_surrogate_execute import mixed
from rsm_lrg.surrogate import simulate
from rsm_lrg.physics.thermal.network import ThermalNetwork
from rsm_lrg.physics.thermal.geometry import GuideGeometry
out = simulate(mixed(), seed=3, noise_sd=0.03, batch_rows=int(sys.argv[1]))
net = ThermalNetwork(GuideGeometry(), 8.82, 22.45)
h = hashlib.sha256(out.select_dtypes("number").to_numpy().tobytes())
h.update(np.asarray(net.response(np.arange(400) * 60.0)).tobytes())
h.update(np.float64(net.steady_rise_per_w).tobytes())
print(h.hexdigest())
"""


@pytest.mark.slow
def test_rows_do_not_depend_on_the_number_of_blas_threads():
    # threadpoolctl is not a dependency: set the thread counts of every BLAS NumPy may use
    # before it starts, in fresh interpreters (1 thread, as on a Dask worker, against 4)
    import os
    import subprocess
    import sys
    from pathlib import Path

    code = _DIGEST.format(tests=str(Path(__file__).parent))
    digests = set()
    for threads, batch in (("1", "16"), ("4", "16"), ("4", "5"), (None, "3")):
        env = dict(os.environ)
        for k in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
            env.pop(k, None)
            if threads is not None:
                env[k] = threads
        r = subprocess.run([sys.executable, "-c", code, batch], env=env, capture_output=True, text=True,
                           timeout=300)
        assert r.returncode == 0, r.stderr[-2000:]
        digests.add(r.stdout.strip())
    assert len(digests) == 1, digests


@pytest.mark.slow
@settings(max_examples=12, deadline=None)
@given(st.integers(0, 2**32 - 1))
def test_rows_anywhere_in_the_physical_ranges_are_finite_or_refused(seed):
    # the whole documented range of the four factors and of two parameters (log-uniform):
    # either every output is finite or a ValueError says why -- never NaN or inf in the rows
    from rsm_lrg.physics.params import PHYSICAL_RANGES

    rng = np.random.default_rng(seed)

    def draw(name, lo=None, hi=None):
        a, b = PHYSICAL_RANGES[name]
        a, b = max(a, lo or a), min(b, hi or b)
        return float(np.exp(rng.uniform(np.log(a), np.log(b))))

    row = pd.DataFrame({"thickness_m": [draw("hinge_thickness_m", hi=0.019)],
                        "stroke_m": [draw("stroke_m", hi=0.3)], "velocity_m_s": [draw("velocity_m_s")],
                        "acceleration_m_s2": [draw("acceleration_m_s2")],
                        "preload_n": [draw("preload_n", lo=1.0)], "mu_k": [draw("mu_k", lo=1e-4)]})
    try:
        out = simulate(row, noise_sd=0)
    except ValueError as exc:
        assert "steps per cycle" in str(exc) or "row 1" in str(exc) or "leaf model" in str(exc), exc
        return
    assert np.isfinite(out[OUT].to_numpy()).all()


def test_a_column_table_design_gives_the_dataframe_design_runs():
    # a plain CSV file read without pandas (rsm_lrg.table): the same runs, columns and names
    from rsm_lrg.surrogate.execute import simulate_columns
    from rsm_lrg.table import ColumnTable

    df = pd.DataFrame({"run": [1, 2, 3], "thickness_m": [3e-4, 5e-4, 1e-4], "stroke_m": [0.05, 0.04, 0.06],
                       "velocity_m_s": [0.5, 0.4, 0.6], "acceleration_m_s2": [30, 20, 40], "heat_w": [1.0, 2.0, 3.0]})
    table = ColumnTable({c: df[c].to_numpy() for c in df.columns})
    a = simulate(df, seed=5)
    b = simulate(table, seed=5)
    pd.testing.assert_frame_equal(a, b)
    names, added = simulate_columns(table, seed=5)
    assert names == list(a.columns) and "heat_w_input" in names
    for k, v in added.items():
        assert np.array_equal(v, a[k].to_numpy(), equal_nan=True)
