"""Factor choice (rsm_lrg.factors.choose_factors): a design's factors found from its coded
columns, the numeric-column rule, notes on every column left out, reserved names, messages
that quote user data."""

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rsm_lrg.design import box_behnken, central_composite
from rsm_lrg.factors import Factor, FactorSpace, _numeric, choose_factors, parse_factor_spec

PAPER = {"thickness_m": (0.0001, 0.0005), "stroke_m": (0.04, 0.06), "velocity_m_s": (0.4, 0.6),
         "acceleration_m_s2": (20.0, 40.0)}


def _runs(design, seed=0):
    """A design frame with the extra numeric output columns a simulate run adds."""
    f = design.to_frame()
    rng = np.random.default_rng(seed)
    f["tcr_c_per_min"] = rng.normal(0.03, 0.005, len(f))
    f["temperature_rise_k"] = rng.normal(2.0, 0.1, len(f))
    f["heat_w"] = rng.normal(0.3, 0.01, len(f))
    return f


def test_design_factors_found_from_coded_columns():
    f = _runs(box_behnken(PAPER, center=3, seed=1))
    ch = choose_factors(f, exclude=["tcr_c_per_min"])
    assert ch.how == "design"
    assert ch.space.names == list(PAPER)
    assert ch.coded_columns == ("coded_A", "coded_B", "coded_C", "coded_D")
    # the design's levels exactly (they are the values at coded -1 and +1)
    assert [(fa.low, fa.high) for fa in ch.space] == list(PAPER.values())
    assert ch.unused == ("temperature_rise_k", "heat_w")
    assert any("coded_A" in n and "A thickness_m" in n for n in ch.notes)
    assert any("temperature_rise_k, heat_w" in n for n in ch.notes)
    # FactorSpace.from_data uses the same rule
    assert FactorSpace.from_data(f, exclude=["tcr_c_per_min"]).names == list(PAPER)


def test_ccd_axial_points_keep_the_design_coding():
    # a rotatable CCD in 2 factors has axial points at +-sqrt(2) (Montgomery, Design and
    # Analysis of Experiments, 8th ed., Sec. 11.4.2): the observed min/max are the axial
    # levels, but the coding must be the design's -1/+1 levels
    d = central_composite({"x": (10.0, 20.0), "y": (1.0, 3.0)}, alpha="rotatable", seed=3)
    f = d.to_frame()
    f["resp"] = np.arange(len(f), dtype=float)
    ch = choose_factors(f, exclude=["resp"])
    assert [(fa.low, fa.high) for fa in ch.space] == [(10.0, 20.0), (1.0, 3.0)]
    coded = ch.space.encode(f)
    np.testing.assert_allclose(coded.to_numpy(), f[["coded_A", "coded_B"]].to_numpy(), rtol=0, atol=1e-9)
    assert np.isclose(coded["A"].abs().max(), np.sqrt(2.0), rtol=0, atol=1e-9)  # exact alpha, 1e-9


def test_pairing_is_by_values_not_position():
    # the actual columns moved to the end, in another order, with extra columns between
    f = _runs(box_behnken(PAPER, center=3, seed=2))
    order = ["std_order", "run_order", "coded_A", "coded_B", "coded_C", "coded_D", "tcr_c_per_min",
             "heat_w", "acceleration_m_s2", "velocity_m_s", "temperature_rise_k", "stroke_m", "thickness_m"]
    ch = choose_factors(f[order], exclude=["tcr_c_per_min"])
    assert ch.space.names == list(PAPER)  # letters follow coded_A, coded_B, ...


def test_simulate_written_values_pair():
    # simulate writes with 10 significant digits: still the same factors and levels
    f = _runs(central_composite(PAPER, seed=4))
    g = pd.read_csv(__import__("io").StringIO(f.to_csv(index=False, float_format="%.10g")))
    ch = choose_factors(g, exclude=["tcr_c_per_min"])
    assert ch.space.names == list(PAPER)
    for fa, (lo, hi) in zip(ch.space, PAPER.values()):
        assert fa.low == pytest.approx(lo, rel=1e-12) and fa.high == pytest.approx(hi, rel=1e-12)


def test_coded_column_without_its_actual_column_is_an_error():
    f = _runs(box_behnken(PAPER, center=3, seed=1)).drop(columns=["stroke_m"])
    with pytest.raises(ValueError, match=r"'coded_B' matches no factor column.*--factor"):
        choose_factors(f, exclude=["tcr_c_per_min"])


def test_numeric_rule_and_notes_without_a_design():
    df = pd.DataFrame({"run": [1, 2, 3, 4], "x1": [0, 1, 0, 1], "x2": [0, 0, 1, 1],
                       "who": ["ann", "bob", "ann", "bob"], "block": [1, 1, 2, 2], "y": [1.0, 2, 3, 4]})
    ch = choose_factors(df, exclude=["y"])
    assert ch.how == "numeric" and ch.space.names == ["x1", "x2"]
    assert ch.unused == ("who", "block") and ch.text_columns == ("who",)
    text = " ".join(ch.notes)
    assert "A x1, B x2" in text and "Text column left out" in text and "who" in text
    assert "--block block" in text
    # given factors: no inference note, the rest still listed
    ch = choose_factors(df, ["x1"], exclude=["y"])
    assert not ch.inferred and ch.hint() == ""
    assert ch.unused == ("x2", "who", "block")


def test_reserved_factor_names_are_refused():
    for name in ["std_order", "Run_Order", "block", "coded_A", "CODED_b", "run", "order", "std"]:
        with pytest.raises(ValueError, match="reserved"):
            Factor(name, 0.0, 1.0, "A")
    with pytest.raises(ValueError, match="reserved"):
        box_behnken({"std_order": (0, 1), "b": (0, 1), "c": (0, 1)})
    with pytest.raises(ValueError, match="reserved"):
        FactorSpace.from_specs(["coded_A=0:1"])
    assert parse_factor_spec("runner=0:1") == ("runner", 0.0, 1.0)  # only the exact names


def test_comma_numbers_are_refused_naming_column_and_row():
    df = pd.DataFrame({"x": [1.0, 2.0, 3.0], "n": ["1,234", "2,345", "3,456"], "y": [1.0, 2.0, 4.0]})
    with pytest.raises(ValueError, match=r"column 'n', row 1: holds '1,234', a number with a comma"):
        choose_factors(df, exclude=["y"])
    with pytest.raises(ValueError, match=r"column 'n', row 1: holds '1,234', a number with a comma"):
        _numeric(df, "n")
    df = pd.DataFrame({"x": [1.0, 2.0], "y": ["0,5", "1.5"]})
    with pytest.raises(ValueError, match=r"column 'y', row 1: holds '0,5'"):
        _numeric(df, "y")


def test_quoted_cells_are_cut():
    big = "x" * 10_000_000
    df = pd.DataFrame({"a": [1.0, big, 2.0]})
    with pytest.raises(ValueError) as e:
        _numeric(df, "a")
    assert "row 2" in str(e.value) and len(str(e.value)) < 200
    digits = "9" * 400  # overflows a float: not a finite number
    df = pd.DataFrame({"a": [1.0, digits]})
    with pytest.raises(ValueError) as e:
        _numeric(df, "a")
    assert "row 2" in str(e.value) and len(str(e.value)) < 200
    with pytest.raises(ValueError) as e:
        parse_factor_spec("x=" + "1" * 5000 + ":2")
    assert len(str(e.value)) < 200


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.floats(-1e6, 1e6), st.floats(1e-3, 1e6)), min_size=3, max_size=5),
       st.integers(0, 2**31 - 1))
def test_inferred_levels_are_the_design_levels(ranges, seed):
    # property: for any levels, the coded/actual pairing gives back the design's levels
    # (to 1e-9 relative: the actual columns are the design's own floats)
    spec = {f"f{i}": (lo, lo + w) for i, (lo, w) in enumerate(ranges)}
    f = _runs(box_behnken(spec, center=2, seed=seed), seed=seed)
    ch = choose_factors(f, exclude=["tcr_c_per_min"])
    assert ch.space.names == list(spec)
    for fa, (lo, hi) in zip(ch.space, spec.values()):
        assert fa.low == pytest.approx(lo, rel=1e-9, abs=1e-9 * (hi - lo))
        assert fa.high == pytest.approx(hi, rel=1e-9, abs=1e-9 * (hi - lo))


def test_empty_factor_cell_in_design_data_names_the_row():
    f = _runs(box_behnken(PAPER, center=3, seed=1))
    f.loc[6, "velocity_m_s"] = np.nan  # pairing skips it; the fit's check names row 7
    ch = choose_factors(f, exclude=["tcr_c_per_min"])
    assert ch.space.names == list(PAPER)
    with pytest.raises(ValueError, match=r"column 'velocity_m_s', row 7: is empty"):
        __import__("rsm_lrg").fit(f, "tcr_c_per_min")


def test_read_design_pairs_moved_columns_like_fit(tmp_path):
    from rsm_lrg.design import Design

    f = _runs(box_behnken(PAPER, center=3, seed=2))
    order = ["std_order", "run_order", "coded_A", "coded_B", "coded_C", "coded_D", "tcr_c_per_min",
             "heat_w", "acceleration_m_s2", "velocity_m_s", "temperature_rise_k", "stroke_m", "thickness_m"]
    d = Design.from_frame(f[order])
    assert d.factors.names == list(PAPER)
    assert [(fa.low, fa.high) for fa in d.factors] == list(PAPER.values())


@pytest.mark.parametrize("bad", [("x", 0), 5, None])
def test_a_bad_factor_item_gets_one_message_for_designs_and_data(bad):
    """as_factor_space and choose_factors convert factor items with one routine
    (factors._given_items), so a malformed item gets the same sentence from both."""
    from rsm_lrg.design import as_factor_space

    df = pd.DataFrame({"x": [0.0, 1.0, 2.0]})
    msg = "expected 'NAME=LOW:HIGH' or \\(name, low, high\\)"
    with pytest.raises(ValueError, match=msg):
        as_factor_space([bad])
    with pytest.raises(ValueError, match=msg):
        choose_factors(df, [bad])


def test_design_and_data_factor_items_agree():
    """The same levelled items give the same space through both entry points."""
    from rsm_lrg.design import as_factor_space

    df = pd.DataFrame({"v": [0.4, 0.5, 0.6], "stage": ["rms", "rfcms", "rms"]})
    items = ["stage=cat:rfcms,rms", "v=0.4:0.6"]
    assert as_factor_space(items) == choose_factors(df, items).space == FactorSpace.from_specs(items)
    assert as_factor_space({"v": (0.4, 0.6)}) == FactorSpace.from_ranges({"v": (0.4, 0.6)})


def test_an_inferred_constant_numeric_column_is_left_out_with_a_note():
    # issue 36: a Table 4 file with one more numeric column holding 7 on every row was refused
    # ("factor column 'stroke_m.1' is constant"); inferred, it is left out and said; named, refused
    import pandas as pd

    from rsm_lrg.datasets import data_path
    from rsm_lrg.factors import choose_factors

    d = pd.read_csv(data_path("table4.csv"))
    d["stroke_m.1"] = 7.0
    choice = choose_factors(d, exclude=["tcr_c_per_min"])
    assert list(choice.space.names) == ["thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2"]
    assert any("Constant numeric column" in str(n) and "'stroke_m.1' (7 on every row)" in str(n) for n in choice.notes)
    with pytest.raises(ValueError, match="'stroke_m.1' is constant"):
        choose_factors(d, ["thickness_m", "stroke_m.1"], exclude=["tcr_c_per_min"])
    only = pd.DataFrame({"a": [1.0, 1.0, 1.0], "y": [1.0, 2.0, 3.0]})
    with pytest.raises(ValueError, match="every numeric column is constant: 'a'"):
        choose_factors(only, exclude=["y"])
