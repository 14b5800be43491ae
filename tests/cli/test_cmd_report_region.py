"""``report --constraint/--bound``: bad input is one error line naming the option; the page
carries the region and optima found inside it (the browser side: tests/browser/test_report_region.py)."""

import json

import pytest
from _cli_errors import error_line

from rsm_lrg.cli import main
from rsm_lrg.datasets import data_path

TABLE4 = str(data_path("table4.csv"))


@pytest.mark.parametrize("args, option", [
    (["--constraint", "speed <= 1"], "--constraint"),
    (["--constraint", "velocity_m_s >= 0.7"], "--constraint"),          # empty region (velocity 0.4 .. 0.6)
    (["--bound", "velocity_m_s=0.5:0.45"], "--bound"),
    (["--bound", "speed=0.4:0.5"], "--bound"),
])
def test_bad_region_is_one_error_line(tmp_path, capsys, args, option):
    out = tmp_path / "r.html"
    line = error_line(capsys, main(["report", TABLE4, "--response", "tcr_c_per_min", *args, "-o", str(out)]))
    assert line.startswith(f"error: {option}"), line
    assert not out.exists()


def _data(path):
    html = path.read_text(encoding="utf-8")
    start = html.index('id="rsm-data"')
    return json.loads(html[html.index(">", start) + 1:html.index("</script>", start)])


def test_optimum_and_region_in_the_page(tmp_path, capsys):
    out = tmp_path / "r.html"
    assert main(["report", TABLE4, "--response", "tcr_c_per_min", "--goal", "maximize",
                 "--constraint", "velocity_m_s + 0.01*acceleration_m_s2 <= 0.85",
                 "--bound", "thickness_m=0.0001:0.0003", "-o", str(out)]) == 0
    data = _data(out)
    texts = [c["text"] for c in data["region"]["constraints"]]
    assert texts == ["velocity_m_s + 0.01*acceleration_m_s2 <= 0.85", "thickness_m >= 0.0001", "thickness_m <= 0.0003"]
    s = data["optima"]["tcr_c_per_min"]["setting"]
    # unconstrained, κ is largest at v = 0.6, a = 40 (0.6 + 0.4 = 1.0 > 0.85) and the thickest leaf
    assert s["velocity_m_s"] + 0.01 * s["acceleration_m_s2"] <= 0.85 + 1e-9
    assert s["thickness_m"] <= 0.0003 + 1e-12
