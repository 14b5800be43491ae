"""``rsm-lrg reproduce``: prints the side-by-side table, writes DIR/paper-reproduction.html,
exits 0 when no checked row fails, shows progress on stderr, never overwrites without --force."""

from __future__ import annotations

import json

import pytest

from rsm_lrg.cli import main

pytestmark = pytest.mark.slow


def test_reproduce_writes_the_page_and_exits_0(tmp_path, capsys):
    out = tmp_path / "reports"
    rc = main(["reproduce", "-o", str(out)])
    cap = capsys.readouterr()
    assert rc == 0, cap.out[-2000:]
    assert cap.out.splitlines()[0].split()[:3] == ["quantity", "paper", "toolkit"]
    assert "0 FAIL" in cap.out
    assert "reproduce: [1/5]" in cap.err and "reproduce: [5/5]" in cap.err
    page = out / "paper-reproduction.html"
    html = page.read_text(encoding="utf-8")
    assert html.startswith("<!DOCTYPE html>") and 'id="comparison-table"' in html
    for sid in ("fig5", "fig9", "fig10", "fig11", "surrogate"):
        assert f'id="{sid}"' in html
    # again without --force: refused before the long run, one error line
    rc = main(["reproduce", "-o", str(out)])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1 and err[0].startswith("error:") and "--force" in err[0]


def test_reproduce_json_only(tmp_path, capsys):
    rc = main(["reproduce", "--no-html", "--json", "-"])
    cap = capsys.readouterr()
    doc = json.loads(cap.out)
    assert rc == 0 and doc["ok"] is True and doc["counts"]["FAIL"] == 0
    assert any(r["quantity"].startswith("Eq. 19 coefficient") for r in doc["rows"])


def test_output_must_be_a_directory(tmp_path, capsys):
    f = tmp_path / "file"
    f.write_text("x")
    rc = main(["reproduce", "-o", str(f)])
    assert rc == 2 and "is not a directory" in capsys.readouterr().err
