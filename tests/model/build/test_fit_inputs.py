"""fit()'s inputs: factors inferred from a design, columns and runs left out with notes,
runs without a response left out (issue 10, items 2, 3 and 5)."""

import numpy as np
import pytest

import rsm_lrg
from rsm_lrg.design import box_behnken

PAPER = {"thickness_m": (0.0001, 0.0005), "stroke_m": (0.04, 0.06), "velocity_m_s": (0.4, 0.6),
         "acceleration_m_s2": (20.0, 40.0)}
Y = "tcr_c_per_min"


def _table4():
    return rsm_lrg.load_table4()


def _virtual_runs():
    """The paper's BBD written as a design, with a response and extra numeric outputs (as simulate adds)."""
    f = box_behnken(PAPER, center=3, seed=1).to_frame()
    x = f[["coded_A", "coded_B", "coded_C", "coded_D"]].to_numpy()
    rng = np.random.default_rng(7)
    f[Y] = 0.035 + 0.003 * x[:, 0] + 0.008 * x[:, 2] + 0.002 * x[:, 0] ** 2 + rng.normal(0, 5e-4, len(f))
    f["temperature_rise_k"] = 60 * f[Y]
    f["steady_rise_k"] = 70 * f[Y] + 0.1
    f["heat_w"] = rng.normal(0.3, 0.01, len(f))
    return f


def test_design_derived_data_fit_on_the_design_factors():
    f = _virtual_runs()
    r = rsm_lrg.fit(f, Y)
    assert r.factors == list(PAPER)
    given = rsm_lrg.fit(f, Y, factors=[f"{k}={lo}:{hi}" for k, (lo, hi) in PAPER.items()])
    # the same model as with the factors named (same coding): coefficients equal to 1e-12
    np.testing.assert_allclose(r.coefficients["coded"], given.coefficients["coded"], rtol=1e-12, atol=1e-15)
    text = " ".join(r.input_notes)
    assert "A thickness_m (coded_A)" in text
    assert "temperature_rise_k, steady_rise_k, heat_w" in text
    assert r.notes[:len(r.input_notes)] == r.input_notes
    assert "Factors taken from the design's coded columns" in r.summary()


def test_too_few_runs_names_the_inferred_factors():
    df = _table4().iloc[:10]
    with pytest.raises(ValueError, match=r"10 runs cannot fit 15 terms.*A thickness_m, B stroke_m.*--factor"):
        rsm_lrg.fit(df, Y)
    with pytest.raises(ValueError) as e:  # given factors: no hint
        rsm_lrg.fit(df, Y, factors=list(PAPER))
    assert "--factor" not in str(e.value)


def test_text_column_is_noted_not_dropped_silently():
    df = _table4()
    df["operator"] = ["ann", "bob", "cy"] * 9
    r = rsm_lrg.fit(df, Y)
    assert r.factors == list(PAPER)
    assert any("Text column left out" in n and "operator" in n for n in r.input_notes)
    assert any("operator" in n for n in r.notes)


def test_runs_without_a_response_are_left_out():
    full = _table4()
    df = full.copy()
    df[Y] = df[Y].astype(object)
    df.loc[[3, 10], Y] = [None, "  "]  # rows 4 and 11: not run (empty, blank)
    r = rsm_lrg.fit(df, Y)
    ref = rsm_lrg.fit(full.drop(index=[3, 10]).reset_index(drop=True), Y)
    # independent route: the fit of the 25 runs given alone, coefficients to 1e-12
    np.testing.assert_allclose(r.coefficients["coded"], ref.coefficients["coded"], rtol=1e-12, atol=1e-15)
    assert r.n == 25 and r.omitted_rows == (4, 11)
    assert list(r.omitted_data.index) == [3, 10]
    assert r.run_rows == [i for i in range(1, 28) if i not in (4, 11)]
    d = r.to_dict()
    assert d["n"] == 25 and d["omitted_rows"] == [4, 11] and d["notes"] == list(r.notes)
    assert len(r.data) == 25 and np.array_equal(r.y, ref.y)
    assert any("2 runs without a response left out of the fit (not run): rows 4, 11." == n for n in r.notes)
    # the coding is still the one of every run (factor levels of the runs left out count)
    assert [(f.low, f.high) for f in r.space] == [(f.low, f.high) for f in rsm_lrg.fit(full, Y).space]


def test_bad_response_and_factor_cells_still_name_the_row():
    df = _table4().astype({Y: object})
    df.loc[6, Y] = "n/a"
    with pytest.raises(ValueError, match=r"column 'tcr_c_per_min', row 7: holds 'n/a'"):
        rsm_lrg.fit(df, Y)
    df = _table4()
    df.loc[4, Y] = np.nan  # row 5 not run ...
    df.loc[4, "stroke_m"] = np.nan  # ... but an empty factor cell is still an error, with its row
    with pytest.raises(ValueError, match=r"column 'stroke_m', row 5: is empty"):
        rsm_lrg.fit(df, Y)
    df = _table4()
    df[Y] = np.nan
    with pytest.raises(ValueError, match="empty on every row"):
        rsm_lrg.fit(df, Y)


def test_block_cell_empty_names_the_input_row():
    df = _table4()
    df["day"] = [1.0] * 14 + [2.0] * 13
    df.loc[2, Y] = np.nan  # a run left out before the bad block cell: the row is still the input row
    df.loc[20, "day"] = np.nan
    with pytest.raises(ValueError, match=r"'day', row 21: is empty"):
        rsm_lrg.fit(df, Y, block="day")


def test_long_cells_are_cut_in_messages():
    df = _table4().astype({"velocity_m_s": object})
    df.loc[4, "velocity_m_s"] = "z" * 1_000_000
    with pytest.raises(ValueError) as e:
        rsm_lrg.fit(df, Y, factors=list(PAPER))
    assert "'velocity_m_s', row 5" in str(e.value) and len(str(e.value)) < 200


@pytest.mark.parametrize("column", [Y, "stroke_m"])
def test_an_infinite_cell_is_named_as_the_number(column):
    # a CSV cell 'inf' is read as a numpy float: the error shows 'inf' as written, not numpy's
    # repr np.float64(inf) (exact text; row 3 is the 1-based data row)
    d = _table4()
    d.loc[2, column] = np.inf
    with pytest.raises(ValueError) as err:
        rsm_lrg.fit(d, Y)
    assert f"column '{column}', row 3: holds inf, not a finite number" in str(err.value)
    assert "np." not in str(err.value)
