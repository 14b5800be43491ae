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
