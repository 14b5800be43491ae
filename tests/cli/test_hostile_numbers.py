"""Parsers and numbers under attack (issue 26 item 5): TOML inputs bounded in depth and number
size with the file named; every error line names the option or file that caused it (not the
data file for an option's fault); no design command writes a non-finite or overflowed
number (the option that would cause it is refused).
"""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from rsm_lrg.cli import main
from rsm_lrg.datasets import data_path
from rsm_lrg.io import InputError, check_nesting, read_toml

TABLE4 = Path(data_path("table4.csv"))
RESPONSE = "tcr_c_per_min"
AT = ["--at", "thickness_m=0.0001", "--at", "stroke_m=0.04", "--at", "velocity_m_s=0.4"]


def _one_error(capsys, *words) -> str:
    err = capsys.readouterr().err
    lines = err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error:"), err[-800:]
    assert len(lines[0]) < 300
    for w in words:
        assert w in lines[0], (w, lines[0])
    return lines[0]


TOMLS = {
    "deep-array": ("a = " + "[" * 5000 + "]" * 5000 + "\n", "nested too deeply"),
    "deep-inline-tables": ("a = " + "{b = " * 3000 + "1" + "}" * 3000 + "\n", "nested too deeply"),
    "deep-dotted-key": ("x." * 3000 + "y = 1\n", "nested more than 32 levels"),
    "deep-tables": ("[" + ".".join(["t"] * 200) + "]\nv = 1\n", "nested more than 32 levels"),
    "integer-5000-digits": ("thickness_m = " + "9" * 5000 + "\n", "thousands of digits"),
    "integer-100-digits": ("thickness_m = " + "9" * 100 + "\n", "64-bit"),
    "float-beyond-range": ("thickness_m = 1e400\n", "beyond the range of a float"),
}


@pytest.mark.parametrize("kind", sorted(TOMLS))
@pytest.mark.parametrize("option", ["physics --params-file", "simulate --calibration"])
def test_hostile_toml_is_refused_naming_the_file(option, kind, tmp_path, capsys):
    text, word = TOMLS[kind]
    f = tmp_path / f"{kind}.toml"
    f.write_text(text)
    cmd, opt = option.split()
    if cmd == "physics":
        argv = ["physics", opt, str(f)]
    else:
        design = tmp_path / "design.csv"
        pd.read_csv(TABLE4).iloc[:, 1:5].to_csv(design, index=False)
        argv = ["simulate", str(design), opt, str(f), "-o", str(tmp_path / "o.csv"), "--seed", "1"]
    before = f.read_bytes()
    assert main(argv) == 2
    _one_error(capsys, f.name, word)
    assert f.read_bytes() == before
    assert not (tmp_path / "o.csv").exists()


def test_read_toml_keeps_the_words_inf_and_nan(tmp_path):
    f = tmp_path / "ok.toml"
    f.write_text("a = inf\nb = -inf\nc = nan\nd = 1.5e300\ne = 9223372036854775807\n")
    got = read_toml(f)
    assert got["a"] == np.inf and got["b"] == -np.inf and np.isnan(got["c"]) and got["d"] == 1.5e300
    assert got["e"] == 2**63 - 1
    with pytest.raises(InputError, match="64-bit"):
        check_nesting({"e": 2**63}, f)


OPTION_FAULTS = [
    # the option's fault, once blamed on the data file
    (["design", "optimal", "--factor", "a=0:1", "--factor", "b=0:1", "--runs", "8", "--constraint",
      "a+b<=" + "9" * 400], "--constraint", "400 digits"),
    (["optimize", "{T}", "--response", RESPONSE, "--constraint", "thickness_m+stroke_m<=" + "9" * 400],
     "--constraint", "too large"),
    (["confirm", "{T}", "--response", RESPONSE, *AT, "--at", "acceleration_m_s2=1e308", "--observed", "0.03"],
     "--at", "acceleration_m_s2"),
    (["confirm", "{T}", "--response", RESPONSE, *AT, "--at", "acceleration_m_s2=-1e300", "--observed", "0.03"],
     "--at", "too far outside"),
    (["predict", "{T}", "--response", RESPONSE, *AT, "--at", "acceleration_m_s2=1e308"], "--at", "acceleration_m_s2"),
    (["predict", "{T}", "--response", RESPONSE, *AT, "--at", "acceleration_m_s2=20", "--factor-sd",
      "velocity_m_s=1e308"], "--factor-sd", "half range"),
    (["predict", "{T}", "--response", RESPONSE, *AT, "--at", "acceleration_m_s2=20", "--draws", "1e308"], "--draws",
     "at most"),
    (["effects", "{T}", "--response", RESPONSE, "--term", ""], "--term", "empty term"),
    (["effects", "{T}", "--response", RESPONSE, "--term", "A", "--term", "Q"], "--term", "'Q'"),
    (["fit", "{T}", "--response", RESPONSE, "--transform", "power=-1e300"], "--transform", "overflows"),
    (["fit", "{T}", "--response", RESPONSE, "--transform", "power=400"], "--transform", "0.028"),
    (["confirm", "{T}", "--response", RESPONSE, *AT, "--at", "acceleration_m_s2=30", "--observed", "0.03",
      "--transform", "power=-1e300"], "--transform", "overflows"),
]


@pytest.mark.parametrize("argv,option,word", OPTION_FAULTS, ids=[f"{a[0]}-{o}-{i}" for i, (a, o, _) in
                                                                  enumerate(OPTION_FAULTS)])
def test_an_option_at_fault_is_named_not_the_file(argv, option, word, tmp_path, capsys):
    t = tmp_path / "t4.csv"
    shutil.copy(TABLE4, t)
    argv = [str(t) if a == "{T}" else a for a in argv]
    out = tmp_path / "out.csv"
    if argv[0] == "design":
        argv += ["-o", str(out)]
    assert main(argv) == 2
    line = _one_error(capsys, option, word)
    assert "t4.csv" not in line  # the data file is not blamed
    assert t.read_bytes() == TABLE4.read_bytes() and not out.exists()


DESIGN_FAULTS = [
    (["central-composite", "--factor", "a=-1e308:1e308", "--factor", "b=0:1"], "--factor", "too wide"),
    (["box-behnken", "--factor", "a=-1e308:1e308", "--factor", "b=0:1", "--factor", "c=0:1"], "--factor", "too wide"),
    (["full-factorial", "--factor", "a=-1e308:1e308", "--factor", "b=0:1"], "--factor", "too wide"),
    (["plackett-burman", "--factor", "a=-1e308:1e308", "--factor", "b=0:1", "--factor", "c=0:1"], "--factor",
     "too wide"),
    (["optimal", "--factor", "a=-1e308:1e308", "--factor", "b=0:1", "--runs", "6"], "--factor", "too wide"),
    (["latin-hypercube", "--factor", "a=-1.7e308:0", "--factor", "b=0:1", "--runs", "6"], "--factor", "too wide"),
    (["central-composite", "--factor", "a=0:1", "--factor", "b=0:1", "--alpha", "1e300"], "--alpha", "1000"),
    (["central-composite", "--factor", "a=0:1", "--factor", "b=0:1", "--alpha", "1001"], "--alpha", "1000"),
]


@pytest.mark.parametrize("argv,option,word", DESIGN_FAULTS, ids=[f"{a[0]}-{i}" for i, (a, _, _) in
                                                                  enumerate(DESIGN_FAULTS)])
def test_no_design_command_writes_an_overflowed_number(argv, option, word, tmp_path, capsys):
    out = tmp_path / "d.csv"
    assert main(["design", *argv, "-o", str(out)]) == 2
    _one_error(capsys, option, word)
    assert not out.exists()


def test_widest_allowed_range_and_alpha_give_finite_designs(tmp_path, capsys):
    # at the limits (1e300 wide, alpha 1000) every number written is finite and exact
    out = tmp_path / "d.csv"
    assert main(["design", "central-composite", "--factor", "a=-5e299:5e299", "--factor", "b=0:1", "--alpha", "1000",
                 "--seed", "1", "-o", str(out)]) == 0
    capsys.readouterr()
    d = pd.read_csv(out)
    num = d.select_dtypes("number").to_numpy(dtype=float)
    assert np.isfinite(num).all()
    assert d["a"].abs().max() == pytest.approx(5e302) and d["coded_A"].abs().max() == 1000


def test_a_design_built_through_the_api_with_an_overflowing_range_is_not_written(tmp_path):
    # the library's last guard: a Factor made directly (not through a --factor spec) with a
    # range whose width overflows gives a design that refuses to be written
    from rsm_lrg.design import central_composite
    from rsm_lrg.factors import FactorSpace

    space = FactorSpace.from_items([("numeric", "a", -1e308, 1e308), ("numeric", "b", 0.0, 1.0)])
    with np.errstate(all="ignore"):
        design = central_composite(space, seed=1)
    with pytest.raises(ValueError, match=r"overflowed number for factor 'a' in run \d+"):
        design.to_csv(tmp_path / "d.csv")
    assert list(tmp_path.iterdir()) == []
