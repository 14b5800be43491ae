"""A REML fit does not depend on the unit of the response (issue 36): the cake split-plot
(Lawson 2015 ch. 10, daewr ``cakeb``, tests/model/r/mixed_cakeb.csv) with its response
multiplied by 1e-95 … 1e80 gives the same Kenward–Roger F, p and den df, the same variance
ratio, coefficients and standard errors times the factor and variance components times its
square; ``optimize`` finds the same setting. Before, these ended in ZeroDivisionError,
"SVD did not converge" or "a number is too large"."""

import json
from pathlib import Path

import pandas as pd
import pytest

from rsm_lrg.cli import main

CAKE = Path(__file__).parents[1] / "model" / "r" / "mixed_cakeb.csv"
BASE = ["--response", "y", "--factor", "x1", "--factor", "x2", "--whole-plot", "Ovenrun"]
SCALES = [1e-95, 1e-80, 1e-60, 1e-12, 1e12, 1e80]


def _scaled(tmp_path, s: float) -> str:
    d = pd.read_csv(CAKE)
    d["y"] = d["y"] * s
    path = tmp_path / f"cake_{s:g}.csv"
    d.to_csv(path, index=False, float_format="%.17g")
    return str(path)


def _json(capsys, argv) -> dict:
    assert main(argv) == 0, capsys.readouterr().err
    return json.loads(capsys.readouterr().out)


def _rel(a: float, b: float) -> float:
    return abs(a - b) / max(abs(b), 1e-300)


@pytest.fixture(scope="module")
def base_fit(tmp_path_factory):
    import contextlib
    import io

    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        assert main(["fit", str(CAKE), *BASE, "--json", "-"]) == 0
    return json.loads(buf.getvalue())


@pytest.mark.parametrize("s", SCALES)
def test_reml_fit_is_free_of_the_response_unit(tmp_path, capsys, base_fit, s):
    js = _json(capsys, ["fit", _scaled(tmp_path, s), *BASE, "--json", "-"])
    b0 = base_fit
    assert js["method"] == "REML"
    assert js["variance_ratio"] == pytest.approx(b0["variance_ratio"], rel=1e-9)
    for key in ("coefficients", "std_errors"):
        for units in ("coded", "actual"):
            for name, v in b0[key][units].items():
                assert _rel(js[key][units][name], v * s) < 1e-9, (key, units, name, js[key][units][name], v * s)
    for name, comp in b0["variance_components"].items():
        for key, v in comp.items():  # variance and its Wald interval times s², std_dev times s
            f = s if key == "std_dev" else s * s
            assert _rel(js["variance_components"][name][key], v * f) < 1e-9, (name, key)
    tests0 = {t["term"]: t for t in b0["tests"]}
    assert [t["term"] for t in js["tests"]] == list(tests0)
    for t in js["tests"]:
        for key in ("f", "p", "den_df", "num_df"):
            assert _rel(t[key], tests0[t["term"]][key]) < 1e-9, (t["term"], key)


@pytest.mark.parametrize("s", [1e-95, 1e-80, 1e80])
def test_optimize_on_a_scaled_reml_fit(tmp_path, capsys, s):
    args = [*BASE, "--goal", "maximize", "--json", "-"]
    one = _json(capsys, ["optimize", str(CAKE), *args])
    other = _json(capsys, ["optimize", _scaled(tmp_path, s), *args])

    def leaves(o, path=""):
        if isinstance(o, dict):
            for k, v in o.items():
                yield from leaves(v, f"{path}/{k}")
        elif isinstance(o, list):
            for i, v in enumerate(o):
                yield from leaves(v, f"{path}[{i}]")
        else:
            yield path, o

    a, b = dict(leaves(one)), dict(leaves(other))
    assert a.keys() == b.keys()
    for k, v in a.items():
        w = b[k]
        if isinstance(v, float) and isinstance(w, float) and v != 0.0:
            # settings, desirability, df and p alike; predictions and intervals times s
            assert min(_rel(w, v), _rel(w, v * s), _rel(w, v * s * s)) < 1e-9, (k, v, w)
        elif not isinstance(v, float):
            assert v == w or isinstance(v, (int, str)) and k.endswith(("response",)), (k, v, w)
