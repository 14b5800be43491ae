"""``rsm-lrg design-space`` on a mixture: the window is bounds per component (JSON ``region``
``"simplex"``), equal to the library's; the page draws the maps; factor noise is refused naming
the option."""

import json
from pathlib import Path

from _cli_errors import error_line

from rsm_lrg.cli import main

ETCH = str(Path(__file__).parents[2] / "rsm_lrg" / "data" / "mixture_etch.csv")
BASE = ["design-space", ETCH, "--response", "erate", "--component", "x1", "--component", "x2", "--component", "x3",
        "--model", "mixture-quadratic", "--spec", "erate=450:", "--grid", "11"]


def test_json_equals_the_library_and_the_page_has_the_maps(capsys, tmp_path):
    import rsm_lrg
    from rsm_lrg.optimize.design_space import design_space

    page = tmp_path / "ds.html"
    assert main(BASE + ["--json", "-", "-o", str(page)]) == 0
    out = json.loads(capsys.readouterr().out)
    f = rsm_lrg.fit(rsm_lrg.load_mixture_etch(), "erate", components=["x1", "x2", "x3"], model="mixture-quadratic")
    ds = design_space({"erate": f}, {"erate": (450.0, None)}, grid=11)
    assert out["region"] == "simplex" and out["factors"] == ["x1", "x2", "x3"]
    assert out["window"] == {k: {"low": lo, "high": hi} for k, (lo, hi) in ds.window.items()}
    assert out["window_min_probability"] >= 0.9
    assert all(v is None or 0 <= v <= 1 for m in out["maps"] for row in m["p"] for v in row)
    html = page.read_text()
    assert html.count("<img") == 3 and "simplex lattice" in html


def test_factor_noise_on_a_mixture_names_the_option(capsys):
    line = error_line(capsys, main(BASE + ["--factor-sd", "x1=0.01"]))
    assert line.startswith("error: --factor-sd")
