"""Pure error's groups (rsm_lrg.model.readings.anova): the distinct settings numbered in order
of first appearance, as ``pandas.factorize`` numbers them (the reference here; the module
itself does it with NumPy so that a fit needs no pandas), 0.0 and -0.0 one setting."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
from hypothesis import given, settings
from hypothesis import strategies as st

from rsm_lrg.model.readings.anova import anova_rows, anova_table, pure_error

LEVELS = [-1.0, -0.0, 0.0, 0.5, 1.0, 1.682, -1.682, 1e-300]


def _reference_groups(keys: np.ndarray) -> np.ndarray:
    groups = np.zeros(keys.shape[0], dtype=np.int64)
    for j in range(keys.shape[1]):
        codes, uniq = pd.factorize(keys[:, j])
        groups = pd.factorize(groups * len(uniq) + codes)[0]
    return groups


@settings(max_examples=200, deadline=None)
@given(st.integers(1, 30), st.integers(1, 4), st.data())
def test_groups_are_pandas_factorize_numbering(n, m, data):
    keys = np.array(data.draw(st.lists(st.lists(st.sampled_from(LEVELS), min_size=m, max_size=m),
                                       min_size=n, max_size=n)))
    y = np.arange(n, dtype=float) ** 1.5
    pe = pure_error(keys, y)
    ref = _reference_groups(keys)
    assert np.array_equal(pe.groups, ref)
    assert pe.n_groups == int(ref.max()) + 1
    # the within-group sum of squares, from the reference groups
    means = pd.Series(y).groupby(ref).transform("mean").to_numpy()
    assert abs(pe.ss - float(np.sum((y - means) ** 2))) <= 1e-9 * max(1.0, float(np.sum(y ** 2)))


def test_anova_table_is_the_rows_as_a_frame():
    kw = dict(term_names=["A", "B"], term_ss=[4.0, 1e-40], ss_model=4.0, df_model=2, ss_block=0.0, df_block=0,
              ss_res=2.0, df_res=5, ss_total=6.0, df_total=7, pe=None, clean=True)
    rows = anova_rows(**kw)
    frame = anova_table(rows)
    assert json.dumps(frame.to_dict(orient="records")) == json.dumps(rows)  # NaN where F and p do not apply
    assert [r["source"] for r in rows] == ["Model", "A", "B", "Residual", "Cor Total"]
    assert rows[2]["sum_sq"] == 0.0 and rows[2]["p"] == 1.0  # round-off cleaned as every face shows it
