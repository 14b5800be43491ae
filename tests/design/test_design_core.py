"""The Design object: CSV layout, coding round trips (hypothesis), reading back."""

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rsm_lrg.design import Design, box_behnken, central_composite, read_design
from rsm_lrg.factors import FactorSpace
from rsm_lrg.io import InputError

PAPER = {"thickness_m": (0.0001, 0.0005), "stroke_m": (0.04, 0.06),
         "velocity_m_s": (0.4, 0.6), "acceleration_m_s2": (20.0, 40.0)}


def test_csv_layout_columns():
    f = box_behnken(PAPER, center=3, seed=1).to_frame()
    assert list(f.columns) == ["std_order", "run_order", "coded_A", "coded_B", "coded_C", "coded_D",
                               "thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2"]
    assert f["run_order"].tolist() == list(range(1, 28))
    fb = box_behnken(PAPER, center=1, blocks=3, seed=1).to_frame()
    assert list(fb.columns[:3]) == ["std_order", "run_order", "block"]


def test_centre_levels_are_written_without_float_noise():
    # (0.0001 + 0.0005) / 2 is 0.00030000000000000003 in binary; the CSV says 0.0003.
    d = box_behnken(PAPER, center=1, randomize=False)
    centre = d.actual.iloc[-1]
    assert centre["thickness_m"] == 0.0003 and centre["velocity_m_s"] == 0.5


def test_coded_and_actual_views():
    d = box_behnken(PAPER, center=3, seed=2)
    assert list(d.coded.columns) == ["A", "B", "C", "D"]
    assert list(d.actual.columns) == list(PAPER)
    back = d.factors.encode(d.actual)
    np.testing.assert_array_equal(back.to_numpy(), d.coded.to_numpy())


def test_to_csv_atomic_and_refuses_overwrite(tmp_path):
    d = box_behnken(PAPER, center=3, seed=2)
    p = tmp_path / "d.csv"
    d.to_csv(p)
    with pytest.raises(InputError, match="already exists"):
        d.to_csv(p)
    box_behnken(PAPER, center=3, seed=3).to_csv(p, force=True)
    assert not d.to_frame().equals(pd.read_csv(p))


@pytest.mark.parametrize("make", [
    lambda: box_behnken(PAPER, center=3, seed=2),
    lambda: box_behnken(PAPER, center=2, blocks=3, seed=2),
    lambda: central_composite({"a": (-3, 7), "b": (0.1, 0.2), "c": (5, 6)}, center=(2, 2), blocks=2, seed=4),
    lambda: central_composite({"a": (-3, 7), "b": (0.1, 0.2)}, face="inscribed", center=(1, 1), seed=4),
])
def test_csv_round_trip(tmp_path, make):
    d = make()
    p = tmp_path / "d.csv"
    d.to_csv(p)
    r = read_design(p)
    assert r.factors == d.factors
    np.testing.assert_allclose(r.coded_runs, d.coded_runs, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(r.std_order, d.std_order)
    np.testing.assert_array_equal(r.run_order, d.run_order)
    if d.blocks is None:
        assert r.blocks is None
    else:
        np.testing.assert_array_equal(r.blocks, d.blocks)
    pd.testing.assert_frame_equal(r.to_frame(), pd.read_csv(p), check_dtype=False)


def test_read_design_ignores_extra_response_columns(tmp_path):
    d = box_behnken(PAPER, center=3, seed=2)
    f = d.to_frame()
    f["tcr_c_per_min"] = 0.03
    p = tmp_path / "sim.csv"
    f.to_csv(p, index=False)
    assert read_design(p).factors.names == list(PAPER)


def test_read_design_errors_name_file_and_row(tmp_path):
    f = box_behnken(PAPER, center=3, randomize=False).to_frame()
    f.loc[4, "stroke_m"] = 0.07  # inconsistent with its coded value
    p = tmp_path / "bad.csv"
    f.to_csv(p, index=False)
    with pytest.raises(InputError, match=r"bad\.csv: row 5: stroke_m"):
        read_design(p)
    g = f.drop(columns=["coded_A", "coded_B", "coded_C", "coded_D"])
    g.to_csv(p, index=False)
    with pytest.raises(InputError, match="no coded columns"):
        read_design(p)


def test_from_data_skips_coded_columns_by_default():
    # factors.FactorSpace.from_data excludes columns starting with "coded_" (any case).
    f = box_behnken(PAPER, center=3, seed=2).to_frame()
    f["CODED_extra"] = 1.0
    f["y"] = np.arange(len(f), dtype=float)
    space = FactorSpace.from_data(f, exclude=["y"])
    assert space.names == list(PAPER)


def test_design_validates_its_tables():
    fs = FactorSpace.from_ranges({"a": (0, 1), "b": (0, 1)})
    with pytest.raises(ValueError, match="std_order"):
        Design(fs, "custom", np.zeros((3, 2)), [1, 1, 2], [1, 2, 3])
    with pytest.raises(ValueError, match=r"\(n, 2\)"):
        Design(fs, "custom", np.zeros((3, 3)), [1, 2, 3], [1, 2, 3])


def test_to_dict_is_json_safe():
    import json

    d = central_composite({"a": (0, 1), "b": (0, 1)}, seed=1)
    out = json.loads(json.dumps(d.to_dict()))
    assert out["n_runs"] == d.n_runs and out["kind"] == "central-composite"


finite = st.floats(min_value=-1e6, max_value=1e6, allow_nan=False, allow_infinity=False)


@st.composite
def ranges(draw, k):
    out = {}
    for i in range(k):
        low = draw(finite)
        width = draw(st.floats(min_value=1e-3, max_value=1e6))
        high = low + width
        if not high > low:
            high = np.nextafter(low, np.inf) * 2 if low > 0 else low + 1.0
        out[f"f{i}"] = (low, high)
    return out


@pytest.mark.slow
@settings(max_examples=60, deadline=None)
@given(st.integers(3, 7).flatmap(ranges), st.integers(0, 4), st.integers(0, 2**32 - 1))
def test_low_high_map_to_pm1_exactly_and_round_trip(rng_map, center, seed):
    d = box_behnken(rng_map, center=center, seed=seed)
    coded, actual = d.coded_runs, d.actual
    for i, (name, (low, high)) in enumerate(rng_map.items()):
        col = actual[name].to_numpy()
        assert np.all(col[coded[:, i] == -1.0] == low)
        assert np.all(col[coded[:, i] == 1.0] == high)
    # coded -> actual -> coded: exact to float resolution, i.e. within
    # 4 eps max(|low|, |high|) / half-range coded units (exact for most ranges, since coded
    # values are kept to 12 decimals; a range like 128..128.001 cannot do better).
    back = d.factors.encode(actual).to_numpy()
    tol = np.array([4 * np.finfo(float).eps * max(abs(f.low), abs(f.high)) / f.half_range
                    for f in d.factors])
    assert np.all(np.abs(back - coded) <= tol + 1e-12)
    # the frame reads back to the same factors and runs
    r = Design.from_frame(d.to_frame())
    assert r.factors == d.factors
    np.testing.assert_array_equal(r.coded_runs, coded)


@settings(max_examples=40, deadline=None)
@given(st.integers(2, 5).flatmap(ranges), st.sampled_from(["rotatable", "orthogonal", "practical"]),
       st.sampled_from(["circumscribed", "inscribed"]))
def test_ccd_actual_round_trip(rng_map, alpha, face):
    d = central_composite(rng_map, alpha=alpha, face=face, center=(1, 1), seed=0)
    back = d.factors.encode(d.actual).to_numpy()
    # float resolution of the actual values, in coded units (alpha <= 2 multiplies it)
    tol = np.array([8 * np.finfo(float).eps * (max(abs(f.low), abs(f.high)) + 2 * f.half_range)
                    / f.half_range for f in d.factors])
    assert np.all(np.abs(back - d.coded_runs) <= tol + 1e-12)


def test_star_points_written_with_the_shortest_decimal_that_codes_back():
    # x = 0.5 + 0.5 * coded on 0..1 and y = 5 * coded on -5..5; coded +-1.414213562373 (12
    # decimals) decodes exactly (decimal arithmetic) to -0.2071067811865 / 1.2071067811865 and
    # -+7.071067811865. Binary floating point gives -0.20710678118650006 and -7.071067811864999;
    # the CSV says the 13-digit decimals, which code back to the same coded values (tol 0).
    from decimal import Decimal
    from io import StringIO

    from rsm_lrg.design.core import as_factor_space

    a = 1.414213562373
    space = as_factor_space(["x=0:1", "y=-5:5"])
    d = Design.from_standard(space, "test", np.array([[-a, 0.0], [a, 0.0], [0.0, -a], [0.0, a]]), randomize=False)
    text = d.to_frame().to_csv(index=False)
    exact = {str(Decimal("0.5") - Decimal("0.5") * Decimal(str(a))), str(Decimal("0.5") + Decimal("0.5") * Decimal(str(a))),
             str(-Decimal(5) * Decimal(str(a))), str(Decimal(5) * Decimal(str(a)))}
    assert exact == {"-0.2071067811865", "1.2071067811865", "-7.071067811865", "7.071067811865"}
    for value in exact:
        assert value in text
    assert "0.20710678118650006" not in text and "7.071067811864999" not in text
    back = pd.read_csv(StringIO(text))
    assert np.array_equal(space.factors[0].encode(back["x"].to_numpy()), d.coded_runs[:, 0])
    assert np.array_equal(space.factors[1].encode(back["y"].to_numpy()), d.coded_runs[:, 1])


def test_csv_text_is_the_pandas_csv_byte_for_byte():
    # `rsm-lrg design` writes the CSV without loading pandas; the bytes are pandas' own
    from rsm_lrg.design import (
        box_behnken,
        central_composite,
        definitive_screening,
        full_factorial,
        latin_hypercube,
        optimal,
        plackett_burman,
    )

    designs = [
        box_behnken({"thickness_m": (1e-4, 5e-4), "stroke_m": (0.04, 0.06), "v": (0.4, 0.6), "a": (20, 40)}, seed=1),
        box_behnken(["a=0:1", "b=0:2", "c=1:3", "s=cat:rfcms,rms"], seed=2),
        box_behnken({"a": (0, 1), "b": (0, 1), "c": (0, 1), "d": (0, 1)}, blocks=3, seed=3),
        central_composite({"a": (0.1, 0.7), "b": (-3, 5), "c": (1e-9, 3e-9)}, blocks=2, seed=4),
        full_factorial({"a": (0, 1), "b": (2, 3)}, levels=3, seed=5),
        optimal(["x=0:1", "y=0:7", "z=cat:p,q,r"], model="quadratic", criterion="D", runs=14, seed=1),
        plackett_burman({L: (-1.5, 2.5) for L in "abcdefgh"}, seed=1),
        definitive_screening({L: (0, 10) for L in "abcdef"}, seed=1),
        latin_hypercube({"a": (0, 1), "b": (1e3, 1e6)}, 20, seed=1),
    ]
    for d in designs:
        assert d.csv_text() == d.to_frame().to_csv(index=False, lineterminator="\n"), d.kind
