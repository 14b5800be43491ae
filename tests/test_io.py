"""rsm_lrg.io: TOML reading and writing shared by the parameter and calibration files."""

import math
import tomllib

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from rsm_lrg.io import InputError, read_toml, toml_value, write_output


def test_read_toml_errors_name_the_file(tmp_path):
    with pytest.raises(InputError, match=r"nope\.toml: no such calibration file"):
        read_toml(tmp_path / "nope.toml", "calibration file")
    with pytest.raises(InputError, match="is a directory"):
        read_toml(tmp_path)
    bad = tmp_path / "bad.toml"
    bad.write_text("a = = 1\n")
    with pytest.raises(InputError, match=r"bad\.toml: not valid TOML \(.*line 1"):
        read_toml(bad)
    latin = tmp_path / "latin.toml"
    latin.write_bytes(b'a = "\xe9"\n')
    with pytest.raises(InputError, match="not valid TOML"):
        read_toml(latin)


def test_read_toml_leaves_the_file_alone(tmp_path):
    f = tmp_path / "ok.toml"
    f.write_text('x = 1.5\n[t]\nname = "a"\n')
    before = f.read_bytes(), f.stat().st_mtime_ns
    assert read_toml(f) == {"x": 1.5, "t": {"name": "a"}}
    assert (f.read_bytes(), f.stat().st_mtime_ns) == before


def test_toml_value_numpy_scalars_and_non_finite():
    assert toml_value(np.float64(0.1)) == "0.1"
    assert toml_value(np.int32(7)) == "7"
    assert toml_value(np.bool_(True)) == "true"
    assert toml_value(float("inf")) == "nan"
    assert toml_value(None) == "nan"


_values = st.one_of(
    st.booleans(),
    st.integers(min_value=-(2 ** 63), max_value=2 ** 63 - 1),
    st.floats(allow_nan=False, allow_infinity=False),
    st.text(),
)


@given(st.lists(_values, max_size=6), _values)
def test_toml_value_round_trips_through_tomllib(items, scalar):
    # independent route: Python's own TOML parser reads back exactly what was written
    doc = f"x = {toml_value(scalar)}\ny = {toml_value(items)}\n"
    back = tomllib.loads(doc)
    assert back["x"] == scalar and type(back["x"]) is type(scalar)
    assert back["y"] == items


def test_calibration_file_round_trips(tmp_path):
    from rsm_lrg.surrogate.calibrate import calibration_toml, load_calibration, resolve_calibration

    cal = resolve_calibration("default")
    out = write_output(tmp_path / "c.toml", calibration_toml(cal))
    again = load_calibration(out)
    assert again.parameters == cal.parameters
    assert list(again.predicted) == list(cal.predicted)
    assert math.isclose(again.r2, cal.r2, rel_tol=0, abs_tol=0)
