"""Reading and checking a design for virtual runs (rsm_lrg.surrogate.design_input)."""

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rsm_lrg.surrogate.design_input import FACTOR_COLUMNS, read_design_arrays


def design(**over):
    d = {"thickness_m": [3e-4, 1e-4, 5e-4], "stroke_m": [0.05, 0.04, 0.06],
         "velocity_m_s": [0.5, 0.4, 0.6], "acceleration_m_s2": [30.0, 20.0, 40.0]}
    d.update(over)
    return pd.DataFrame(d)


def test_reads_the_four_factors():
    a = read_design_arrays(design(note=["x", "y", "z"]))
    assert a.n == 3 and not a.rigid.any() and a.param_columns == ()
    assert np.allclose(a.columns["stroke_m"], [0.05, 0.04, 0.06])


@pytest.mark.parametrize("col", FACTOR_COLUMNS)
def test_missing_column_is_named(col):
    with pytest.raises(ValueError, match=col):
        read_design_arrays(design().drop(columns=[col]))


def test_empty_and_text_values_name_column_and_row():
    with pytest.raises(ValueError, match=r"column 'stroke_m', row 2: is empty"):
        read_design_arrays(design(stroke_m=[0.05, None, 0.06]))
    with pytest.raises(ValueError, match=r"column 'velocity_m_s', row 3: holds 'fast'"):
        read_design_arrays(design(velocity_m_s=[0.5, 0.4, "fast"]))


@pytest.mark.parametrize("col,bad,row", [("stroke_m", -0.05, 2), ("velocity_m_s", 0.0, 1),
                                         ("acceleration_m_s2", -1.0, 3), ("thickness_m", 0.0, 2)])
def test_out_of_range_names_column_and_row(col, bad, row):
    vals = list(design()[col])
    vals[row - 1] = bad
    with pytest.raises(ValueError, match=rf"column '{col}', row {row}: .* out of range"):
        read_design_arrays(design(**{col: vals}))


def test_stroke_must_fit_on_the_rail():
    # default rail 0.4 m, block 0.0644 m (data/lrg_shs15v.toml)
    with pytest.raises(ValueError, match=r"column 'stroke_m', row 1: .*rail"):
        read_design_arrays(design(stroke_m=[0.5, 0.04, 0.06]))


def test_stage_column():
    a = read_design_arrays(design(stage=["RFCMS", "rms", " rms "], thickness_m=[3e-4, None, None]))
    assert a.rigid.tolist() == [False, True, True]
    assert np.isnan(a.columns["thickness_m"][1])
    with pytest.raises(ValueError, match=r"column 'stage', row 2: holds 'rigid'"):
        read_design_arrays(design(stage=["rfcms", "rigid", "rms"]))
    with pytest.raises(ValueError, match=r"column 'thickness_m', row 1: is empty"):
        read_design_arrays(design(stage=["rfcms", "rms", "rms"], thickness_m=[None, None, None]))


def test_parameter_columns_are_validated_by_the_physics_rules():
    a = read_design_arrays(design(mu_k=[0.01, 0.02, 0.03], preload_n=[100.0, 171.0, 300.0]))
    assert a.param_columns == ("mu_k", "preload_n")
    with pytest.raises(ValueError, match=r"column 'mu_k', row 3: .*\[0, 1\]"):
        read_design_arrays(design(mu_k=[0.01, 0.02, 1.5]))
    with pytest.raises(ValueError, match="test_duration_min"):
        read_design_arrays(design(test_duration_min=[50, 0.5, 50]))
    with pytest.raises(ValueError, match="thickness_m"):
        read_design_arrays(design(hinge_thickness_m=[1e-4] * 3))


def test_not_a_dataframe_or_empty():
    with pytest.raises(TypeError):
        read_design_arrays({"stroke_m": [0.05]})
    with pytest.raises(ValueError, match="no rows"):
        read_design_arrays(design().iloc[:0])


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.floats(1e-5, 1e-3), st.floats(1e-3, 0.3), st.floats(0.01, 2.0),
                          st.floats(0.1, 100.0)), min_size=1, max_size=30))
def test_any_valid_design_is_accepted_in_order(rows):
    df = pd.DataFrame(rows, columns=list(FACTOR_COLUMNS))
    a = read_design_arrays(df)
    assert a.n == len(rows)
    for c in FACTOR_COLUMNS:
        assert np.array_equal(a.columns[c], df[c].to_numpy())


def test_surrogate_parameters_may_vary_by_row():
    a = read_design_arrays(design(heat_partition=[0.2, 0.5, 1.0]))
    assert a.param_columns == ("heat_partition",)
    with pytest.raises(ValueError, match=r"column 'heat_partition', row 2: .*\(0, 1\]"):
        read_design_arrays(design(heat_partition=[0.2, 1.5, 1.0]))
    with pytest.raises(ValueError, match=r"column 'viscous_friction_n_s_m', row 1"):
        read_design_arrays(design(viscous_friction_n_s_m=[-1.0, 0.0, 1.0]))


@pytest.mark.parametrize("name,reads", [("Stage", "stage"), ("Mu_K", "mu_k"), ("HEAT_PARTITION", "heat_partition"),
                                        ("Stroke_M", "stroke_m")])
def test_a_known_name_in_other_case_is_refused(name, reads):
    # a 'Stage' column of rms rows used to pass through unused: the rows ran as RFCMS
    d = design(**{name: ["rms", "rms", "rms"] if reads == "stage" else [0.5, 0.5, 0.5]})
    if reads == "stroke_m":
        d = d.drop(columns=["stroke_m"])
    with pytest.raises(ValueError, match=f"column '{name}': the surrogate reads '{reads}'"):
        read_design_arrays(d)
    # with the exact name present too, the other one is just another column
    if reads != "stroke_m":
        read_design_arrays(d.assign(**{reads: ["rms"] * 3 if reads == "stage" else [0.5] * 3}))


@pytest.mark.parametrize("switch", ["hinge_membrane", "heat_in_calories"])
def test_a_physics_switch_column_is_refused_by_name(switch):
    # hinge_membrane used to fail with NumPy's 'truth value of an array ... is ambiguous'
    with pytest.raises(ValueError, match=f"column '{switch}' cannot vary row by row"):
        read_design_arrays(design(**{switch: [True, False, True]}))


@pytest.mark.parametrize("values", [[True, True, True], [0.5, True, 0.6]])
def test_booleans_are_not_numbers(values):
    # pandas turns True into 1.0: a velocity of True ran at 1 m/s
    with pytest.raises(ValueError, match="column 'velocity_m_s', row [12]: holds True"):
        read_design_arrays(design(velocity_m_s=values))
