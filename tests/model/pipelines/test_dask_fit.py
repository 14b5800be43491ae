"""rsm_lrg.fit of a Dask DataFrame (partition by partition, never collected) equals the
pandas fit of the same rows: coefficients, ANOVA (with lack of fit / pure error) and fit
statistics (with PRESS) to 1e-10 relative (the same algebra; only the order of the
rounding differs), on a real ``distributed.LocalCluster``.
"""

import numpy as np
import pandas as pd
import pytest

import rsm_lrg

dd = pytest.importorskip("dask.dataframe")  # needs pyarrow (dask[dataframe])


def _data(n: int, k: int, seed: int = 0) -> pd.DataFrame:
    # three levels per factor (replicated settings: pure error) and a tenth anywhere in the box,
    # a response on an offset of 1e6 with unit noise; one run without a response
    rng = np.random.default_rng(seed)
    x = rng.integers(-1, 2, size=(n, k)).astype(float)
    x[: n // 10] = rng.uniform(-1, 1, (n // 10, k))
    df = pd.DataFrame(2.0 + 3.0 * x, columns=[f"x{i}" for i in range(k)])
    df["y"] = 1e6 + x.sum(axis=1) + 0.5 * (x ** 2).sum(axis=1) + x[:, 0] * x[:, 1] + rng.normal(size=n)
    df.loc[7, "y"] = np.nan
    return df


def _close(a, b, rtol=1e-10):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    np.testing.assert_allclose(a, b, rtol=rtol, atol=rtol * np.nanmax(np.abs(b)), equal_nan=True)


def _same_fit(got, ref):
    for c in ("coded", "std_error", "t", "vif", "actual"):
        _close(got.coefficients[c], ref.coefficients[c])
    assert list(got.anova["source"]) == list(ref.anova["source"])
    assert list(got.anova["df"]) == list(ref.anova["df"])
    for c in ("sum_sq", "mean_sq", "f"):
        _close(got.anova[c], ref.anova[c])
    for key, v in ref.statistics.to_dict().items():
        assert got.statistics[key] == pytest.approx(v, rel=1e-10), key
    assert got.n == ref.n and got.df_resid == ref.df_resid
    assert got.pure_error.df == ref.pure_error.df
    assert got.pure_error.ss == pytest.approx(ref.pure_error.ss, rel=1e-10)


@pytest.mark.cluster
@pytest.mark.slow
def test_dask_fit_on_a_local_cluster_equals_the_pandas_fit():
    distributed = pytest.importorskip("distributed")
    df = _data(6000, 3)
    ref = rsm_lrg.fit(df, "y")
    with distributed.LocalCluster(processes=False, n_workers=2, threads_per_worker=1,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        assert len(client.scheduler_info()["workers"]) == 2
        got = rsm_lrg.fit(dd.from_pandas(df, npartitions=5), "y", chunk_rows=500)
        given = rsm_lrg.fit(dd.from_pandas(df, npartitions=3), "y", factors=["x0", "x1=0:4", "x2"], model="2fi")
    _same_fit(got, ref)
    _same_fit(given, rsm_lrg.fit(df, "y", factors=["x0", "x1=0:4", "x2"], model="2fi"))
    assert got.y is None and got.hat is None  # nothing per run was collected
    assert "1 run without a response" in got.notes[-1]
    assert "Lack of Fit" in got.summary()


def test_dask_fit_refuses_constant_factors_and_names_bad_blocks():
    df = _data(300, 2).assign(const=1.0, blk=lambda d: np.where(np.arange(len(d)) == 9, None, "b1"))
    ddf = dd.from_pandas(df, npartitions=2)
    with pytest.raises(ValueError, match="'const' is constant"):
        rsm_lrg.fit(ddf, "y", factors=["x0", "const"])
    with pytest.raises(ValueError, match="block column 'blk' has an empty cell"):
        rsm_lrg.fit(ddf, "y", factors=["x0", "x1"], block="blk")
    with pytest.raises(ValueError, match="block column 'nope' not found"):
        rsm_lrg.fit(ddf, "y", factors=["x0", "x1"], block="nope")
    # a text cell in a factor column: named by column (a partition's row is no row of the data)
    text = df.assign(x0=df["x0"].astype(object)).astype({"x0": object})
    text.loc[3, "x0"] = "abc"
    with pytest.raises(ValueError, match=r"^column 'x0': holds 'abc', not a finite number$"):
        rsm_lrg.fit(dd.from_pandas(text, npartitions=2), "y", factors=["x0", "x1"])
    # numbers stored as text (object dtype): refused, the range would come from distinct values only
    with pytest.raises(ValueError, match="'x0' is stored as text in the Dask DataFrame"):
        rsm_lrg.fit(dd.from_pandas(df.astype({"x0": object}), npartitions=2), "y", factors=["x0", "x1"])


def _blocked_categoric(n: int, seed: int = 1) -> pd.DataFrame:
    # two numeric factors on three levels, a three-level text factor, three numeric block
    # labels given out of order (every setting in several blocks: block effects and pure
    # error share the runs), a text column that is no factor, one run without a response
    rng = np.random.default_rng(seed)
    x = rng.integers(-1, 2, size=(n, 2)).astype(float)
    stage = rng.choice(["rms", "rfcms", "mix"], size=n)
    blk = rng.choice([3, 1, 2], size=n)
    df = pd.DataFrame({"v": 0.5 + 0.1 * x[:, 0], "a": 30 + 10 * x[:, 1], "stage": stage, "blk": blk})
    df["y"] = (1e3 + x[:, 0] + 0.5 * x[:, 1] ** 2 + np.where(stage == "rms", 0.3, 0.0) + 0.2 * blk
               + 0.1 * rng.normal(size=n))
    df["operator"] = rng.choice(["ann", "bob"], size=n)
    df.loc[5, "y"] = np.nan
    return df


def _same_blocked_fit(got, ref):
    assert list(got.coefficients.index) == list(ref.coefficients.index)
    _same_fit(got, ref)
    assert got.pure_error.block_df == ref.pure_error.block_df
    assert got.block_levels == ref.block_levels
    assert (got.block_effects is None) == (ref.block_effects is None)
    if ref.block_effects is not None:
        assert list(got.block_effects) == list(ref.block_effects)
        _close(list(got.block_effects.values()), list(ref.block_effects.values()))
    assert got.space == ref.space  # the same factors, levels and letters
    assert [str(v) for v in got.notes[:-1]] == [str(v) for v in ref.notes[:-1]]  # the last names the row


@pytest.mark.cluster
@pytest.mark.parametrize("kw", [
    dict(factors=["v", "a", "stage"]),  # a text column named as a factor is categoric (levels as they appear)
    dict(factors=["v", "a", "stage"], block="blk"),
    dict(factors=["v", "a=20:40", "stage=cat:rms,rfcms,mix"], block="blk", model="2fi"),
    dict(factors=["v", "a", "blk=cat"]),  # a numeric column named as categoric keeps every level
])
def test_dask_fit_with_blocks_and_categoric_factors_equals_the_pandas_fit(kw):
    # the same coefficients, block effects, ANOVA (Block row, multi-df categoric rows, lack of
    # fit / pure error with the block df absorbed), statistics and notes as the pandas fit
    # (rsm_lrg.fit, itself checked against R lm/rsm in tests/model/r/), to 1e-10 relative
    distributed = pytest.importorskip("distributed")
    df = _blocked_categoric(600)
    ref = rsm_lrg.fit(df, "y", **kw)
    with distributed.LocalCluster(processes=False, n_workers=2, threads_per_worker=1,
                                  dashboard_address=None) as cluster, distributed.Client(cluster):
        got = rsm_lrg.fit(dd.from_pandas(df, npartitions=4), "y", chunk_rows=97, **kw)
    _same_blocked_fit(got, ref)
    if "block" in kw:
        assert got.pure_error.block_df == 2 and "Block" in list(got.anova["source"])


def test_dask_pure_error_with_blocks_matches_the_pandas_routine_on_a_blocked_ccd():
    # a CCD in two blocks (factorial + 3 centre runs, axial + 3 centre runs): the centre
    # setting spans both blocks, so one block df is absorbed (R rsm: y ~ Block + PE(x1, x2))
    # and the pure error is the centre runs' variation within each block, by hand
    # (Σy² − (Σy)²/3 per block: 0.26/3 + 0.62/3 = 22/75 on 2 + 2 df); the setting sums of
    # three partitions, merged, give it and rsm_lrg.model.readings.anova.pure_error's SS (1e-12)
    from rsm_lrg.model.pipelines.dask_fit import _merge, _pure_error_sums, _setting_sums
    from rsm_lrg.model.readings.anova import pure_error

    r = np.sqrt(2.0)
    x = np.array([[-1, -1], [1, -1], [-1, 1], [1, 1], [0, 0], [0, 0], [0, 0],
                  [-r, 0], [r, 0], [0, -r], [0, r], [0, 0], [0, 0], [0, 0]])
    b = np.array([0] * 7 + [1] * 7)
    y = np.array([76.5, 77.0, 78.0, 79.5, 79.9, 80.3, 80.0, 75.6, 78.4, 77.0, 78.5, 79.7, 79.8, 80.3])
    yc = y - y.mean()
    merged = (_Acc(), _setting_sums(x[:5], yc[:5], b[:5], 2))
    for s in (slice(5, 11), slice(11, 14)):
        merged = _merge(merged, (_Acc(), _setting_sums(x[s], yc[s], b[s], 2)), 2)
    g, ss, bdf = _pure_error_sums(merged[1], 2)
    ref = pure_error(x, yc, b)
    assert (g, bdf) == (ref.n_groups, ref.block_df) == (9, 1)
    assert y.size - g - bdf == ref.df == 4
    assert ss == pytest.approx(22 / 75, rel=1e-12)
    assert ss == pytest.approx(ref.ss, rel=1e-12)
    # without the block codes the two blocks' centre runs pool: SS of six runs on 5 df
    g1, ss1, bdf1 = _pure_error_sums(_setting_sums(x, yc), 1)
    centre = y[[4, 5, 6, 11, 12, 13]]
    assert (g1, bdf1) == (9, 0) and ss1 == pytest.approx(np.sum((centre - centre.mean()) ** 2), rel=1e-12)


class _Acc:
    """A stand-in factor for :func:`_merge` (only the setting sums are under test here)."""

    def merge(self, other):
        return self


def test_fit_command_reads_a_directory_or_glob_of_csv_files(tmp_path, capsys):
    # `rsm-lrg fit DIR` and `rsm-lrg fit 'DIR/*.csv'` fit the files as one Dask DataFrame:
    # the same coefficients as the one-file fit (1e-10 relative)
    import json

    from rsm_lrg.cli import main

    df = _data(1500, 2)
    for i in range(3):
        df.iloc[500 * i:500 * (i + 1)].to_csv(tmp_path / f"part{i}.csv", index=False)
    df.to_csv(tmp_path / "all.txt", index=False)  # not a .csv: not picked up from the directory
    outs = []
    for src in (str(tmp_path / "all.txt"), str(tmp_path), str(tmp_path / "part*.csv")):
        assert main(["fit", src, "--response", "y", "--json", "-"]) == 0
        outs.append(json.loads(capsys.readouterr().out))
    ref = outs[0]["coefficients"]["coded"]
    for out in outs[1:]:
        assert out["n"] == 1499
        for k, v in ref.items():
            assert out["coefficients"]["coded"][k] == pytest.approx(v, rel=1e-10, abs=1e-10 * abs(ref["Intercept"]))
    assert main(["fit", str(tmp_path), "--response", "y", "--reduce"]) == 2
    assert "--reduce is not available when fitting several files" in capsys.readouterr().err


@pytest.mark.cluster
@pytest.mark.slow
def test_dask_fit_of_parquet_files_on_worker_processes(tmp_path):
    # worker processes (everything a partition needs is pickled to them), bounded memory per
    # worker, partitions read from Parquet files (pyarrow) on the workers: equals the pandas fit
    distributed = pytest.importorskip("distributed")
    pytest.importorskip("pyarrow")
    df = _data(4000, 3, seed=3)
    for i in range(4):
        df.iloc[1000 * i:1000 * (i + 1)].to_parquet(tmp_path / f"part{i}.parquet", index=False)
    ref = rsm_lrg.fit(df, "y")
    with distributed.LocalCluster(processes=True, n_workers=2, threads_per_worker=1, memory_limit="600MB",
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        assert len(client.scheduler_info()["workers"]) == 2
        ddf = dd.read_parquet(sorted(str(p) for p in tmp_path.glob("*.parquet")))
        assert ddf.npartitions == 4
        got = rsm_lrg.fit(ddf, "y", chunk_rows=300)
    _same_fit(got, ref)
    assert got.n == 3999 and got.hat is None


def test_fit_command_reads_a_directory_of_parquet_files(tmp_path, capsys):
    import json

    from rsm_lrg.cli import main

    pytest.importorskip("pyarrow")
    df = _data(900, 2, seed=5)
    for i in range(3):
        df.iloc[300 * i:300 * (i + 1)].to_parquet(tmp_path / f"part{i}.parquet", index=False)
    one = tmp_path / "one.csv"
    df.to_csv(one, index=False)
    assert main(["fit", str(one), "--response", "y", "--json", "-"]) == 0
    ref = json.loads(capsys.readouterr().out)
    assert main(["fit", str(tmp_path / "*.parquet"), "--response", "y", "--json", "-"]) == 0
    got = json.loads(capsys.readouterr().out)
    assert got["n"] == ref["n"] == 899
    for k, v in ref["coefficients"]["coded"].items():
        assert got["coefficients"]["coded"][k] == pytest.approx(v, rel=1e-10, abs=1e-10 * abs(ref["coefficients"]["coded"]["Intercept"]))
    assert main(["fit", str(tmp_path), "--response", "y"]) == 2  # CSV and Parquet files together: refused
    assert "holds both CSV and Parquet files" in capsys.readouterr().err


def test_setting_sums_key_settings_by_their_bits_and_detect_shared_keys():
    # the pure-error sums of a Dask fit group the runs by a 64-bit hash of their setting
    # (rsm_lrg.model.pipelines.dask_fit): equal settings (0.0 and -0.0 alike) share a key, different
    # ones (even by one ulp) do not, and a second hash exposes two settings sharing a key
    from rsm_lrg.model.pipelines import dask_fit

    x = np.array([[0.0, 1.0], [-0.0, 1.0], [0.0, np.nextafter(1.0, 2.0)], [1.0, 0.0], [0.0, 1.0]])
    for which in (0, 1):
        h = dask_fit._row_hash(x, which)
        assert h[0] == h[1] == h[4] and len({h[0], h[2], h[3]}) == 3
    agg = dask_fit._setting_sums(x, np.array([1.0, 2.0, 5.0, 7.0, 3.0]))
    n_groups, ss, block_df = dask_fit._pure_error_sums(agg)
    assert block_df == 0
    assert n_groups == 3 and ss == pytest.approx(2.0, rel=1e-15)  # settings (0, 1) x 3: y 1, 2, 3
    bad = agg.copy()
    bad.iloc[0, bad.columns.get_loc("_hi")] += np.uint64(1)
    with pytest.raises(ValueError, match="share a 64-bit hash"):
        dask_fit._pure_error_sums(bad)


def test_fit_command_fits_blocked_categoric_csv_files_as_the_one_file_fit(tmp_path, capsys):
    # `rsm-lrg fit DIR --block ... --factor stage` (three CSV files, one Dask partition each)
    # prints the one-file fit: the same text but the data path and the row the note names
    from rsm_lrg.cli import main

    df = _blocked_categoric(600, seed=4)
    for i in range(3):
        df.iloc[200 * i:200 * (i + 1)].to_csv(tmp_path / f"part{i}.csv", index=False)
    one = tmp_path / "one.txt"
    df.to_csv(one, index=False)
    args = ["--response", "y", "--factor", "v", "--factor", "a", "--factor", "stage", "--block", "blk"]
    texts = []
    for src in (str(one), str(tmp_path)):
        assert main(["fit", src, *args]) == 0
        texts.append(capsys.readouterr().out.replace(src, "DATA").replace(": row 6.", "."))
    assert texts[0] == texts[1]
    assert "C: stage  categoric, levels" in texts[1] and "Block  " in texts[1]
    assert "Text column left out (not a factor, response or block): operator." in texts[1]


@pytest.mark.parametrize("keyword", ["whole_plot", "random_block", "hard_to_change"])
def test_dask_frame_with_a_random_effect_is_never_fitted_by_ols(keyword):
    """A REML fit needs one in-memory table: a Dask frame with a whole plot (or random block,
    or hard-to-change factors) is refused by a ParameterError naming the argument, never
    fitted by OLS with the column left out."""
    from rsm_lrg.errors import ParameterError

    df = _data(64, 2)
    df["wp"] = np.repeat(np.arange(16), 4)
    ddf = dd.from_pandas(df, npartitions=2)
    kwargs = {"whole_plot": "wp", "random_block": "wp", "hard_to_change": ["x0"]}
    extra = {"whole_plot": "wp"} if keyword == "hard_to_change" else {}
    with pytest.raises(ParameterError, match="in-memory") as info:
        rsm_lrg.fit(ddf, "y", factors=["x0", "x1"], **{keyword: kwargs[keyword]}, **extra)
    assert info.value.parameter in (keyword, "whole_plot")
