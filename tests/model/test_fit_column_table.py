"""A least-squares fit of a ColumnTable (a plain CSV file read without pandas, issue 37 item 6)
is the fit of the same table as a DataFrame: the same JSON and the same text, bit for bit,
over factor counts, term lists, blocks, categoric factors held as numbers, transforms,
models without an intercept, replicates and designs with coded columns; and it imports no
pandas."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import rsm_lrg
from rsm_lrg.table import ColumnTable

ROOT = Path(__file__).resolve().parents[2]


def _table(df: pd.DataFrame) -> ColumnTable:
    return ColumnTable({c: df[c].to_numpy() for c in df.columns})


def _same(df: pd.DataFrame, response: str, **kw) -> None:
    a = rsm_lrg.fit(df, response, **kw)
    b = rsm_lrg.fit(_table(df), response, **kw)
    assert json.dumps(b.to_dict(), sort_keys=True) == json.dumps(a.to_dict(), sort_keys=True)
    assert b.summary() == a.summary()
    assert type(b.data).__name__ == "ColumnTable"


def _random_frame(rng: np.random.Generator, k: int, n: int, *, ints: bool) -> pd.DataFrame:
    x = rng.integers(-1, 2, size=(n, k)) if ints else np.round(rng.uniform(-3, 7, size=(n, k)), 3)
    cols = {f"x{j}": x[:, j] for j in range(k)}
    y = 5 + x @ rng.normal(size=k) + 0.3 * (x[:, 0] ** 2) + rng.normal(scale=0.2, size=n)
    return pd.DataFrame({**cols, "y": np.round(y, 4)})


def test_table4_the_same_both_ways():
    df = pd.read_csv(ROOT / "data" / "table4.csv")
    _same(df, "tcr_c_per_min")
    _same(df, "tcr_c_per_min", model="linear")
    _same(df, "tcr_c_per_min", terms="A B C AB A^2", intercept=True)
    _same(df, "tcr_c_per_min", transform="log")


@pytest.mark.parametrize("seed", range(8))
def test_random_tables_the_same_both_ways(seed):
    rng = np.random.default_rng(seed)
    k = int(rng.integers(2, 5))
    df = _random_frame(rng, k, int(rng.integers(3 * k + 8, 40)), ints=bool(seed % 2))
    model = ["linear", "2fi", "quadratic"][seed % 3]
    _same(df, "y", model=model)
    if seed % 4 == 0:  # no intercept, a term list
        _same(df, "y", terms=" ".join(f"{chr(65 + j)}" for j in range(k)), intercept=False)


def test_blocks_and_a_categoric_factor_held_as_numbers():
    rng = np.random.default_rng(3)
    df = _random_frame(rng, 3, 24, ints=True)
    df["block"] = np.repeat([1, 2, 3], 8)
    _same(df, "y", block="block", model="2fi")
    df2 = df.drop(columns="block").assign(kind=np.tile([10, 20, 30], 8))
    _same(df2, "y", factors=["x0", "x1", "kind=cat"], model="2fi")


def test_a_design_file_with_coded_columns():
    design = pd.read_csv(ROOT / "data" / "table4.csv")
    coded = {f"coded_{L}": np.round((design[c] - design[c].min()) / (design[c].max() - design[c].min()) * 2 - 1, 6)
             for L, c in zip("ABCD", ["thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2"])}
    df = pd.concat([pd.DataFrame(coded), design], axis=1)
    _same(df, "tcr_c_per_min")


def test_the_other_engines_read_it_as_a_dataframe():
    df = pd.read_csv(ROOT / "data" / "table4.csv")
    t = _table(df)
    gp = rsm_lrg.fit(t, "tcr_c_per_min", model="gp", seed=1)
    assert gp.to_dict() == rsm_lrg.fit(df, "tcr_c_per_min", model="gp", seed=1).to_dict()
    red = rsm_lrg.fit(t, "tcr_c_per_min", reduce="backward")
    assert red.to_dict() == rsm_lrg.fit(df, "tcr_c_per_min", reduce="backward").to_dict()


def test_errors_name_the_same_column_and_row():
    df = pd.read_csv(ROOT / "data" / "table4.csv")
    t = _table(df)
    for kw in ({"factors": ["nope"]}, {"block": "nope"}):
        with pytest.raises(ValueError) as a:
            rsm_lrg.fit(df, "tcr_c_per_min", **kw)
        with pytest.raises(ValueError) as b:
            rsm_lrg.fit(t, "tcr_c_per_min", **kw)
        assert str(a.value) == str(b.value)
    const = df.assign(thickness_m=0.0003)
    with pytest.raises(ValueError) as a:
        rsm_lrg.fit(const, "tcr_c_per_min", factors=["thickness_m", "stroke_m"])
    with pytest.raises(ValueError) as b:
        rsm_lrg.fit(_table(const), "tcr_c_per_min", factors=["thickness_m", "stroke_m"])
    assert str(a.value) == str(b.value)


def test_a_fit_of_a_column_table_imports_no_pandas():
    code = (
        "import sys; sys.modules['pandas'] = None\n"
        "import numpy as np\n"
        "from rsm_lrg.table import ColumnTable\n"
        "from rsm_lrg.model import fit\n"
        "import csv\n"
        f"rows = list(csv.reader(open({str(ROOT / 'data' / 'table4.csv')!r})))\n"
        "cols = {h: np.array([float(r[j]) for r in rows[1:]]) for j, h in enumerate(rows[0])}\n"
        "r = fit(ColumnTable(cols), 'tcr_c_per_min')\n"
        "assert r.to_dict()['statistics']['r2'] > 0.9 and 'Cor Total' in r.summary()\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)
    assert out.returncode == 0, out.stderr


def test_anything_else_is_refused_as_before():
    with pytest.raises(TypeError, match="^data must be a pandas DataFrame$"):
        rsm_lrg.fit({"x": [1, 2, 3], "y": [1.0, 2.0, 4.0]}, "y")
