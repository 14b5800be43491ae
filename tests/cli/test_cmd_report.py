"""``rsm-lrg report``: writes one self-contained HTML file; bad input is one error line, exit 2."""

from __future__ import annotations

import re
import subprocess
import sys
from html import unescape

import pytest

from rsm_lrg.cli import main
from rsm_lrg.datasets import data_path


def test_report_of_table4(tmp_path, capsys):
    out = tmp_path / "r.html"
    rc = main(["report", str(data_path("table4.csv")), "--response", "tcr_c_per_min", "-o", str(out)])
    assert rc == 0
    assert capsys.readouterr().out.strip() == f"wrote {out}"
    html = out.read_text(encoding="utf-8")
    assert html.startswith("<!DOCTYPE html>")
    assert "221.92" in html and "26.03" in html  # Table 5: F of C and of the model
    # the page loads nothing from the network: no src/href to a URL, and a policy that forbids it
    # (the inlined plotly.js carries URL text, e.g. http://get.webgl.org, that it never requests)
    markup = re.sub(r"<script\b[^>]*>.*?</script>", "", html, flags=re.S | re.I)  # the page outside its scripts
    assert "https://" not in markup and "http://" not in markup.replace("http://www.w3.org", "")
    assert "default-src 'none'" in unescape(html)
    # refuses to overwrite, and says so on one line
    rc = main(["report", str(data_path("table4.csv")), "--response", "tcr_c_per_min", "-o", str(out)])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1 and err[0].startswith("error:") and "--force" in err[0]


def test_gp_report_puts_its_leave_one_out_beside_the_polynomials(tmp_path, capsys):
    # issue 33, item 4: the page shows fit-summary --gp's comparison, the same numbers
    import json
    from pathlib import Path

    from rsm_lrg.report.html import fmt_num

    branin = str(Path(__file__).parents[1] / "model" / "r" / "gp_branin.csv")
    factors = ["--factor", "x1=-5:10", "--factor", "x2=0:15"]
    assert main(["fit-summary", branin, "--response", "y", *factors, "--gp", "--json", "-"]) == 0
    want = json.loads(capsys.readouterr().out)["loo_comparison"]
    out = tmp_path / "gp.html"
    assert main(["report", branin, "--response", "y", *factors, "--model", "gp", "-o", str(out)]) == 0
    page = unescape(out.read_text(encoding="utf-8"))
    table = re.search(r'<table class="data loo-comparison">(.*?)</table>', page, re.S).group(1)
    rows = [[re.sub(r"<[^>]+>", "", c).strip() for c in re.findall(r"<td[^>]*>(.*?)</td>", tr, re.S)]
            for tr in re.findall(r"<tr>(.*?)</tr>", table, re.S) if "<td" in tr]
    assert [r[0] for r in rows] == [m["model"] for m in want["models"]]
    for r, m in zip(rows, want["models"]):
        assert r[1:4] == [fmt_num(m["press"]), fmt_num(m["pred_r2"]), fmt_num(m["rmse"])]
        assert (r[4] == "Smallest PRESS") == (m["model"] == want["best"])


def test_bad_column_is_one_error_line(tmp_path):
    out = subprocess.run(
        [sys.executable, "-m", "rsm_lrg", "report", str(data_path("table4.csv")), "--response", "nope",
         "-o", str(tmp_path / "r.html")], capture_output=True, text=True)
    assert out.returncode == 2
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error:") and "table4.csv" in lines[0] and "'nope'" in lines[0]
    assert not (tmp_path / "r.html").exists()


@pytest.mark.parametrize("args, needle", [
    (["--hold", "middle"], "invalid choice"),
    (["--model", "quartic"], "invalid choice"),
])
def test_bad_options(tmp_path, capsys, args, needle):
    rc = main(["report", str(data_path("table4.csv")), "--response", "tcr_c_per_min", "-o",
               str(tmp_path / "r.html"), *args])
    assert rc == 2 and needle in capsys.readouterr().err


def test_missing_output_dir(tmp_path, capsys):
    rc = main(["report", str(data_path("table4.csv")), "--response", "tcr_c_per_min", "--goal", "maximize",
               "-o", str(tmp_path / "no" / "r.html")])
    err = capsys.readouterr().err
    assert rc == 2 and "does not exist" in err
