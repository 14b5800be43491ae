"""``rsm-lrg optimize``: the paper's optimum (Sec. 4.3 / DIGEST) and bad input."""

import hashlib
import json
from pathlib import Path

import pytest

from rsm_lrg.cli import main
from rsm_lrg.datasets import data_path

TABLE4 = str(data_path("table4.csv"))


def test_optimize_minimize_json(capsys):
    before = hashlib.sha256(Path(TABLE4).read_bytes()).hexdigest()
    assert main(["optimize", TABLE4, "--response", "tcr_c_per_min", "--goal", "minimize", "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    # DIGEST: thickness 0.0001, stroke 0.04, velocity 0.4, acceleration 20, kappa 0.02283;
    # the confirmation run 0.024 inside the 95 % PI (0.0159-0.0298).
    assert d["actual"] == {"thickness_m": 0.0001, "stroke_m": 0.04, "velocity_m_s": 0.4, "acceleration_m_s2": 20.0}
    assert round(d["predicted"], 5) == 0.02283
    assert d["confidence"] == 0.95 and d["pi"][0] < 0.024 < d["pi"][1]
    assert list(d)[:8] == ["response", "goal", "coded", "actual", "predicted", "confidence", "ci", "pi"]
    assert hashlib.sha256(Path(TABLE4).read_bytes()).hexdigest() == before


def test_optimize_text_and_bounds(capsys):
    assert main(["optimize", TABLE4, "--response", "tcr_c_per_min", "--goal", "maximize",
                 "--bound", "velocity_m_s=0.45:0.55"]) == 0
    out = capsys.readouterr().out
    assert "velocity_m_s = 0.55   (coded" in out and "95 % PI" in out


@pytest.mark.parametrize("extra, needle", [
    (["--goal", "fastest"], "goal must be"),
    (["--goal", "target=abc"], "not a number"),
    (["--bound", "speed=0.4:0.5"], "no such factor"),
    (["--bound", "velocity_m_s=0.3:0.5"], "outside the design range"),
    (["--bound", "velocity_m_s=0.5:0.45"], "LOW must be below HIGH"),
])
def test_optimize_bad_input(extra, needle, capsys):
    assert main(["optimize", TABLE4, "--response", "tcr_c_per_min", *extra]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error:") and needle in err[0], err


# --- per-response model options (issue 10, item 13) -------------------------------------------

def _montgomery_three_responses():
    """Montgomery, DAE (8th ed.), Sec. 11.3.4: the CCD of Example 11.2 with three responses,
    yield y (quadratic), viscosity visc (quadratic) and molecular weight mn (linear), the
    models Design-Expert selects there; printed fits: visc = 70.00 - 0.16 x1 - 0.95 x2
    - 1.25 x1x2 - 0.69 x1² - 6.69 x2², mn = 3386.2 + 205.1 x1 + 177.4 x2."""
    from tests.model._published import MONTGOMERY_11_2

    d = MONTGOMERY_11_2.copy()
    d["visc"] = [62, 60, 66, 59, 72, 69, 68, 70, 71, 68, 71, 58, 57]
    d["mn"] = [2940, 3470, 3680, 3890, 3480, 3200, 3410, 3290, 3500, 3360, 3020, 3630, 3150]
    return d


FAC = ["--factor", "x1=-1:1", "--factor", "x2=-1:1"]
GOALS = {"y": ["--goal", "maximize", "--limits", "78.5:80"], "visc": ["--goal", "target=65", "--limits", "62:68"],
         "mn": ["--goal", "range", "--limits", "3200:3400"]}


@pytest.mark.slow
def test_each_response_gets_its_own_model(capsys, tmp_path):
    import rsm_lrg
    from rsm_lrg.optimize.desirability import optimize_desirability, parse_response_goal

    d = _montgomery_three_responses()
    path = tmp_path / "m11.csv"
    d.to_csv(path, index=False)
    argv = ["optimize", str(path), *FAC, "--response", "y", *GOALS["y"], "--model", "quadratic",
            "--response", "visc", *GOALS["visc"], "--response", "mn", *GOALS["mn"], "--model", "linear",
            "--json", "-"]
    assert main(argv) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["models"] == {"y": "quadratic", "visc": "quadratic", "mn": "linear"}
    # the library with the same three models gives the same optimum (1e-9)
    f = ["x1=-1:1", "x2=-1:1"]
    fits = {"y": rsm_lrg.fit(d, "y", factors=f), "visc": rsm_lrg.fit(d, "visc", factors=f),
            "mn": rsm_lrg.fit(d, "mn", factors=f, model="linear")}
    specs = [parse_response_goal("y", "maximize", limits="78.5:80"),
             parse_response_goal("visc", "target=65", limits="62:68"),
             parse_response_goal("mn", "range", limits="3200:3400")]
    lib = optimize_desirability(fits, specs)
    assert out["desirability"] == pytest.approx(lib.desirability, abs=1e-9)
    for r in ("y", "visc", "mn"):
        assert out["predicted"][r] == pytest.approx(lib.predicted[r], rel=1e-9)
    # Montgomery's printed linear mn model at the optimum (coefficients to 0.1: 0.05 (1+|x1|+|x2|))
    x1, x2 = out["coded"]["A"], out["coded"]["B"]
    assert out["predicted"]["mn"] == pytest.approx(3386.2 + 205.1 * x1 + 177.4 * x2, abs=0.05 * (1 + abs(x1) + abs(x2)))
    assert 3200 <= out["predicted"]["mn"] <= 3400 and out["desirability"] > 0
    # one --model before the first --response applies to every response (the old behaviour)
    assert main(["optimize", str(path), *FAC, "--model", "linear", "--response", "y", *GOALS["y"],
                 "--response", "mn", *GOALS["mn"], "--json", "-"]) == 0
    assert json.loads(capsys.readouterr().out)["models"] == {"y": "linear", "mn": "linear"}
    # text output names the models
    assert main(argv[:-2]) == 0
    assert "Models: y quadratic; visc quadratic; mn linear" in capsys.readouterr().out


def test_per_response_transform_and_reduce(capsys, tmp_path):
    import numpy as np

    import rsm_lrg

    d = _montgomery_three_responses()
    path = tmp_path / "m11.csv"
    d.to_csv(path, index=False)
    assert main(["optimize", str(path), *FAC, "--response", "y", *GOALS["y"], "--reduce",
                 "--response", "visc", *GOALS["visc"], "--transform", "log", "--json", "-"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["models"]["y"].startswith("quadratic, reduced (removed AB")
    assert out["models"]["visc"] == "quadratic, log transform"
    # visc is predicted by exp of the log-scale model at the optimum (1e-9)
    tf = rsm_lrg.fit_transformed(d, "visc", "log", factors=["x1=-1:1", "x2=-1:1"])
    x = np.array([[out["coded"]["A"], out["coded"]["B"]]])
    assert out["predicted"]["visc"] == pytest.approx(float(tf.predict(x, coded=True)["predicted"].iloc[0]), rel=1e-9)
    # an option given twice for the same response is an error naming it
    assert main(["optimize", str(path), *FAC, "--response", "y", "--model", "linear", "--model", "2fi",
                 "--response", "mn"]) == 2
    assert "--model" in capsys.readouterr().err


def test_single_response_with_a_decreasing_transform(capsys, tmp_path):
    # maximise y under an inverse-transformed model: the optimiser works on 1/y (minimum there)
    # and reports y; the result is the largest back-transformed prediction on a 201^2 grid.
    import numpy as np

    import rsm_lrg

    d = _montgomery_three_responses()
    path = tmp_path / "m11.csv"
    d.to_csv(path, index=False)
    assert main(["optimize", str(path), *FAC, "--response", "y", "--goal", "maximize",
                 "--transform", "inverse", "--json", "-"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["goal"] == "maximize"
    tf = rsm_lrg.fit_transformed(d[["x1", "x2", "y"]], "y", "inverse", factors=["x1=-1:1", "x2=-1:1"])
    g = np.linspace(-1, 1, 201)
    P = np.array(np.meshgrid(g, g)).reshape(2, -1).T
    grid_max = tf.predict(P, coded=True)["predicted"].max()
    assert out["predicted"] >= grid_max - 1e-9 and out["predicted"] <= grid_max + 1e-3
    assert out["pi"][0] < out["predicted"] < out["pi"][1]


@pytest.mark.slow
def test_goal_and_limits_belong_to_the_response_they_follow(capsys, tmp_path):
    # Documented in --help ("what to do with the response before it"): a --goal or --limits
    # right after the second --response is that response's, even when the first has none.
    # Reference: the same run with every response's options written out (exact equality).
    d = _montgomery_three_responses()
    path = tmp_path / "m11.csv"
    d.to_csv(path, index=False)

    def run(*argv):
        assert main(["optimize", str(path), *FAC, *argv, "--json", "-"]) == 0
        return json.loads(capsys.readouterr().out)

    short = run("--response", "y", "--response", "visc", *GOALS["visc"])
    full = run("--response", "y", "--goal", "minimize", "--response", "visc", *GOALS["visc"])
    assert [g["goal"] for g in short["goals"]] == ["minimize", "target"]
    assert short == full
    # several listed together after the last --response: in --response order (as before)
    listed = run("--response", "y", "--response", "visc", "--goal", "minimize", "--goal", "target=65",
                 "--limits", "74:81", "--limits", "62:68")
    assert listed == run("--response", "y", "--goal", "minimize", "--limits", "74:81",
                         "--response", "visc", *GOALS["visc"])
    # too many is an error naming the option
    assert main(["optimize", str(path), *FAC, "--response", "y", "--goal", "maximize", "--goal", "minimize"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == ["error: --goal: more values (2) than --response options (1)"]


def test_negative_limits_and_constraints_are_values(capsys, tmp_path):
    # '--limits -3:12' and '--constraint "-x1+x2<=0.5"' are values, not unknown options
    # (argparse 3.11 answered "expected one argument"). Reference: the '--opt=value' spelling,
    # which argparse always reads as a value (identical JSON).
    d = _montgomery_three_responses()
    d["y"] = d["y"] - 80.0  # a response with negative values, limits -4.5:0.5
    path = tmp_path / "m11.csv"
    d.to_csv(path, index=False)
    base = ["optimize", str(path), *FAC, "--response", "y", "--goal", "maximize", "--json", "-"]
    assert main(base + ["--limits", "-4.5:0.5", "--constraint", "-x1+x2<=0.5"]) == 0
    got = json.loads(capsys.readouterr().out)
    assert main(base + ["--limits=-4.5:0.5", "--constraint=-x1+x2<=0.5"]) == 0
    assert got == json.loads(capsys.readouterr().out)
    assert got["goals"][0]["low"] == -4.5 and -got["actual"]["x1"] + got["actual"]["x2"] <= 0.5 + 1e-9


def test_a_failing_fit_among_several_names_its_response(capsys, tmp_path):
    # Montgomery Example 11.2 CCD + a 2^2 corner-only response column: with the quadratic
    # default, the response measured only at the corners cannot be fitted; the one error line
    # must say which response (the other is fine).
    d = _montgomery_three_responses()
    d["corners"] = [1.0, 2.0, 3.0, 4.5] + [None] * (len(d) - 4)  # the 4 factorial runs only
    path = tmp_path / "m11.csv"
    d.to_csv(path, index=False)
    assert main(["optimize", str(path), *FAC, "--response", "y", "--response", "corners"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"error: {path}: response 'corners': "), err
