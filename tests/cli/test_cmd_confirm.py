"""``rsm-lrg confirm``: the paper's confirmation run (Sec. 4.3) from the command line."""

import json

import pytest

from rsm_lrg.cli import main

AT = ["--at", "thickness_m=0.0001", "--at", "stroke_m=0.04", "--at", "velocity_m_s=0.4", "--at", "acceleration_m_s2=20"]


def test_paper_confirmation_json(capsys):
    assert main(["confirm", "data/table4.csv", "--response", "tcr_c_per_min", *AT, "--observed", "0.024",
                 "--reference", "0.023", "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["inside"] is True
    assert d["pi"] == pytest.approx([0.0159, 0.0298], abs=5e-5)  # DIGEST, 95 % PI
    assert d["relative_error_vs_reference_percent"] == pytest.approx(4.35, abs=5e-3)  # paper
    assert d["relative_error_percent"] == pytest.approx(5.11, abs=5e-3)  # vs exact 0.022833


def test_missing_setting_is_an_error(capsys):
    assert main(["confirm", "data/table4.csv", "--response", "tcr_c_per_min", "--at", "thickness_m=0.0001",
                 "--observed", "0.024"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: --at:") and "stroke_m" in err  # an option error names the option


def test_reduced_and_transformed_models(capsys, tmp_path):
    # Montgomery, DAE (8th ed.), Example 11.2 (CCD): confirm takes fit's model options; the
    # CLI equals the library on the same model (1e-12), the log interval is back-transformed.
    import rsm_lrg
    from rsm_lrg.optimize.confirm import confirm
    from tests.model._published import MONTGOMERY_11_2

    path = tmp_path / "m11_2.csv"
    MONTGOMERY_11_2.to_csv(path, index=False)
    base = ["confirm", str(path), "--response", "y", "--factor", "x1=-1:1", "--factor", "x2=-1:1",
            "--at", "x1=0.5", "x2=0.5", "--observed", "79.0", "80.2", "--json", "-"]
    assert main(base + ["--transform", "log"]) == 0
    d = json.loads(capsys.readouterr().out)
    lib = confirm(rsm_lrg.fit_transformed(MONTGOMERY_11_2, "y", "log", factors=["x1=-1:1", "x2=-1:1"]),
                  {"x1": 0.5, "x2": 0.5}, [79.0, 80.2])
    assert d["transform"] == "log" and d["pi"] == pytest.approx(list(lib.pi), rel=1e-12)
    assert d["model"] == "quadratic, log transform"
    assert main(base + ["--reduce", "--alpha-out", "0.1"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["reduction"]["removed"] == ["AB"] and d["transform"] is None
    r = rsm_lrg.fit(MONTGOMERY_11_2, "y", factors=["x1=-1:1", "x2=-1:1"], terms=["A", "B", "A^2", "B^2"])
    assert d["pi"] == pytest.approx(list(confirm(r, {"x1": 0.5, "x2": 0.5}, [79.0, 80.2]).pi), rel=1e-12)
    assert main(base[:-2] + ["--reduce", "--transform", "sqrt"]) == 0
    out = capsys.readouterr().out
    assert "Model: quadratic, reduced" in out and "sqrt transform" in out and "back-transformed" in out
    assert main(base + ["--transform", "cube"]) == 2
    assert capsys.readouterr().err.startswith("error: --transform")


def test_negative_values_in_any_number_form(capsys, tmp_path):
    # argparse (3.11) reads '-2.5e-1' as an unknown option ("expected at least one argument");
    # reference: the same values written so that argparse cannot misread them (the result is
    # identical, exact equality). Shifted Montgomery Example 11.2 response: y - 80 < 0.
    from tests.model._published import MONTGOMERY_11_2

    d = MONTGOMERY_11_2.copy()
    d["y"] = d["y"] - 80.0
    path = tmp_path / "shifted.csv"
    d.to_csv(path, index=False)
    base = ["confirm", str(path), "--response", "y", "--factor", "x1=-1:1", "--factor", "x2=-1:1",
            "--at", "x1=0.5", "x2=0.5", "--json", "-"]
    assert main(base + ["--observed", "-2.5e-1", "-1E-1", "--reference", "-1e-1"]) == 0
    got = json.loads(capsys.readouterr().out)
    assert main(base + ["--reference=-0.1", "--observed", "-0.25", "-0.1"]) == 0
    assert got == json.loads(capsys.readouterr().out)
    assert got["observed"] == [-0.25, -0.1] and got["reference"] == -0.1


def test_confirm_refuses_a_blend_outside_the_simplex(capsys):
    # issue 36: `--at x1=2 x2=-1 x3=0` (a negative share, one above the total) was accepted
    from rsm_lrg.datasets import data_path

    argv = ["confirm", str(data_path("mixture_etch.csv")), "--response", "erate", "--component", "x1", "--component",
            "x2", "--component", "x3", "--model", "mixture-quadratic", "--observed", "500", "--at"]
    assert main(argv + ["x1=2", "x2=-1", "x3=0"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--at" in err[0] and "'x1' is above the total" in err[0], err
    assert main(argv + ["x1=0.5", "x2=0.5", "x3=0"]) == 0
